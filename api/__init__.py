"""embroact: CAD tool and stitch generator for embroidery actuators.

The main entry points, loaded on first use (``import embroact`` itself loads no numpy):

==========================  =====================================================
load and make a design      :func:`load_design`, :func:`save_design`,
                            :func:`default_design`, :func:`design_from_dict`,
                            :class:`Design`, :class:`ActuatorSpec`, :func:`svg_centerline`
generate stitches           :func:`build_plan`, :func:`zigzag`, :func:`cross`,
                            :class:`Centerline`, :class:`ZigzagParams`, :class:`CrossParams`,
                            :class:`Tube`, :class:`StitchPlan`
analyse and predict         :func:`analyse` (-> :class:`DesignAnalysis`), :func:`curve`,
                            :class:`ActuatorModel`, :class:`Curve`
check                       :func:`check_design` (design rules; findings with code and fix)
write                       :func:`write` (one machine file), :func:`build` (every output)
errors                      :class:`EmbroactError` and its subclasses
==========================  =====================================================

Subpackages: :mod:`embroact.patterns` (geometry), :mod:`embroact.predict` (model),
:mod:`embroact.export` (files, pictures, reports, the command line). Units are mm, kPa,
MPa and degrees at every boundary; every name carries its unit. ``__version__`` is read
from the installed package's metadata. In Jupyter a design or stitch plan shows its stitch
preview, an analysis its actuator table and pictures, a curve its bend chart and a bent
shape its side view (drawn by :mod:`embroact.export.pictures.display` when first shown).

Examples
--------
>>> import embroact
>>> analysis = embroact.analyse(embroact.default_design())
>>> act = analysis.actuators[0]
>>> act.name, round(act.derived.r0_mm, 3), act.model.g_mpa
('A1', 2.581, 2.7)
>>> [round(float(t), 1) for t in analysis.curves([100.0, 200.0])[0].theta_deg]
[11.5, 102.9]
>>> embroact.__version__ == __import__("importlib.metadata").metadata.version("embroact")
True
"""
import lazy_loader

# Rich display in Jupyter: which export function draws each value class (imported when first shown).
from .patterns.base.display import register as _register  # noqa: E402  (light: no numpy)

for _cls, _mime, _target in (
    ("embroact.patterns.design.Design", "image/svg+xml", "embroact.export.pictures.display:design_svg"),
    ("embroact.patterns.plan.StitchPlan", "image/svg+xml", "embroact.export.pictures.stitches:plan_svg"),
    ("embroact.predict.analysis.DesignAnalysis", "text/html", "embroact.export.pictures.display:analysis_html"),
    ("embroact.predict.analysis.ActuatorAnalysis", "text/html", "embroact.export.pictures.display:actuator_html"),
    ("embroact.predict.curve.Curve", "image/svg+xml", "embroact.export.pictures.display:curve_svg"),
    ("embroact.predict.shape.BentShape", "image/svg+xml", "embroact.export.pictures.display:shape_svg"),
):
    _register(_cls, _mime, _target)
del _cls, _mime, _target, _register


_stub: tuple | None = None


def _attached() -> tuple:
    """lazy_loader's ``(__getattr__, __dir__, __all__)`` for the public names and the modules they live in:
    __init__.pyi (which type checkers read too), parsed when a name is first asked for (parsing takes
    ``ast``: 3 ms of ``embroact --help``, which asks for none)."""
    global _stub
    if _stub is None:
        _stub = lazy_loader.attach_stub(__name__, __file__)
    return _stub


def __getattr__(name: str):
    if name == "__version__":
        from importlib.metadata import version

        globals()["__version__"] = v = version(__name__)
        return v
    if name == "__all__":
        globals()["__all__"] = names = [*_attached()[2], "__version__"]
        return names
    return _attached()[0](name)


def __dir__() -> list[str]:
    return _attached()[1]()
