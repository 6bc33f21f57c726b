"""embroact.predict: the deformation model of MODEL.md, its numerical methods and calibration.

No file I/O; scipy is imported only by the functions that need it (root finding, fitting).
The function ``curve`` lives in (and is not re-exported over) the module
:mod:`embroact.predict.curve`: ``from embroact.predict.curve import curve``.

Examples
--------
>>> from embroact.patterns import Tube
>>> from embroact.predict import ActuatorModel, derive_from_values
>>> from embroact.predict.curve import curve
>>> g = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0,
...                        length_mm=100.0, tube=Tube())
>>> c = curve(ActuatorModel.from_derived(g, g_mpa=2.7, p0_kpa=85.0), [50.0, 200.0])
>>> c.as_dict()["status"], c.method
(['INFLATION', 'BENDING'], 'stable-analytic-trace')
"""
from .calibration import calibrated_model, lookup
from .curve import METHODS, ActuatorModel, Curve, lockup, pressure_at, sweep
from .derived import DerivedGeometry, derive, derive_from_values
from .status import Status

__all__ = [
    "ActuatorModel",
    "Curve",
    "pressure_at",
    "lockup",
    "sweep",
    "METHODS",
    "Status",
    "DerivedGeometry",
    "derive",
    "derive_from_values",
    "lookup",
    "calibrated_model",
]
