"""embroact.predict: the deformation model of docs/model.md, its numerical methods and calibration.

No file I/O; scipy is imported only by the functions that need it (root finding,
fitting). The names below load their module on first use (lazy_loader), so
importing one small module (``embroact.predict.derived``) does not load the model.
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
import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach(__name__, submod_attrs={
    "curve": ["ActuatorModel", "Curve", "pressure_at", "lockup", "sweep", "METHODS"],
    "status": ["Status"],
    "derived": ["DerivedGeometry", "derive", "derive_from_values"],
    "calibration": ["lookup", "model_for"],
    "analysis": ["analyse", "DesignAnalysis", "ActuatorAnalysis"],
})
