"""embroact.patterns: tube paths, stitch-pattern generators, plans and design values.

Pure geometry: imports numpy and shapely only (no scipy, no trimesh). Every name below
loads its module on first use (lazy_loader), so importing one small module
(``embroact.patterns.base.errors``) loads neither numpy nor shapely, and a command that
never reads a design file does not load one. The generators ``zigzag``, ``cross`` and
``measure`` share their modules' names; the package attribute is the function even after
the module was imported.

Examples
--------
>>> from embroact.patterns import Centerline, ZigzagParams, zigzag
>>> plan = zigzag(Centerline.straight(20.0), ZigzagParams(width_mm=7.0, interval_mm=1.0))
>>> plan.actuators[0].realised.passes
1
"""
import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach(__name__, submod_attrs={
    "zigzag": ["zigzag"],
    "cross": ["cross"],
    "measure": ["measure"],
    "centerline": ["Centerline", "as_centerline"],
    "design": ["ActuatorSpec", "Design", "MachineSettings", "ModelSettings", "OperationSettings", "build_plan",
               "default_design", "design_from_dict", "design_to_dict", "generate_actuator", "join_plans"],
    "base.errors": ["DesignFileError", "EmbroactError", "ParameterError", "PathError", "PatternError"],
    "params": ["CrossParams", "StitchOptions", "Tube", "ZigzagParams"],
    "plan": ["ActuatorPlan", "Command", "Realised", "Role", "StitchPlan"],
})
