"""embroact.patterns: tube paths, stitch-pattern generators, plans and design values.

Pure geometry: imports numpy and shapely only (no scipy, no trimesh). The generators are
imported here (their names equal their modules' names, which a lazy name cannot shadow);
every other name loads its module on first use (:mod:`embroact.patterns.base.lazy`), so a
command that never reads a design file does not load one.

Examples
--------
>>> from embroact.patterns import Centerline, ZigzagParams, zigzag
>>> plan = zigzag(Centerline.straight(20.0), ZigzagParams(width_mm=7.0, interval_mm=1.0))
>>> plan.actuators[0].realised.passes
1
"""
from .cross import cross
from .base.lazy import lazy_exports
from .measure import measure
from .zigzag import zigzag

_EXPORTS = {
    "Centerline": "centerline",
    "as_centerline": "centerline",
    "ActuatorSpec": "design",
    "Design": "design",
    "MachineSettings": "design",
    "ModelSettings": "design",
    "OperationSettings": "design",
    "build_plan": "design",
    "default_design": "design",
    "design_from_dict": "design",
    "design_to_dict": "design",
    "generate_actuator": "design",
    "join_plans": "design",
    "DesignFileError": "base.errors",
    "EmbroactError": "base.errors",
    "ParameterError": "base.errors",
    "PathError": "base.errors",
    "PatternError": "base.errors",
    "CrossParams": "params",
    "StitchOptions": "params",
    "Tube": "params",
    "ZigzagParams": "params",
    "ActuatorPlan": "plan",
    "Command": "plan",
    "Realised": "plan",
    "Role": "plan",
    "StitchPlan": "plan",
}

__all__ = ["zigzag", "cross", "measure", *_EXPORTS]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
