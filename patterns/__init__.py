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
from .errors import DesignFileError, EmbroactError, ParameterError, PathError, PatternError
from .measure import measure
from .params import CrossParams, StitchOptions, Tube, ZigzagParams
from .plan import ActuatorPlan, Command, Realised, Role, StitchPlan
from .zigzag import zigzag

__all__ = [
    "Centerline",
    "as_centerline",
    "zigzag",
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
