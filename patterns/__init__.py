"""embroact.patterns: tube paths, stitch-pattern generators, plans and design values.

Pure geometry: imports numpy and shapely only (no scipy, no trimesh).

Examples
--------
>>> from embroact.patterns import Centerline, ZigzagParams, zigzag
>>> plan = zigzag(Centerline.straight(20.0), ZigzagParams(width_mm=7.0, interval_mm=1.0))
>>> plan.actuators[0].realised.passes
1
"""
from .centerline import Centerline, as_centerline
from .cross import cross
from .design import (
    ActuatorSpec,
    Design,
    MachineSettings,
    ModelSettings,
    OperationSettings,
    build_plan,
    default_design,
    design_from_dict,
    design_to_dict,
    generate_actuator,
    join_plans,
)
from .errors import DesignFileError, EmbroactError, ParameterError, PathError, PatternError
from .measure import measure
from .params import CrossParams, StitchOptions, Tube, ZigzagParams
from .plan import ActuatorPlan, Command, Realised, Role, StitchPlan
from .zigzag import zigzag

__all__ = [
    "Centerline",
    "as_centerline",
    "zigzag",
    "cross",
    "Design",
    "ActuatorSpec",
    "MachineSettings",
    "OperationSettings",
    "ModelSettings",
    "design_from_dict",
    "design_to_dict",
    "default_design",
    "build_plan",
    "generate_actuator",
    "join_plans",
    "measure",
    "Tube",
    "StitchOptions",
    "ZigzagParams",
    "CrossParams",
    "Command",
    "Role",
    "Realised",
    "ActuatorPlan",
    "StitchPlan",
    "EmbroactError",
    "ParameterError",
    "PatternError",
    "PathError",
    "DesignFileError",
]
