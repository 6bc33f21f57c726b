"""What a build attaches to its machine files: bend chart, side view, 3D shape, report.

:func:`previews_stage` gives the build stage (see :mod:`embroact.export.report.build`) that
predicts every actuator's curve and renders, in memory:

================ =========================================================
``bend.svg``     pressure-bend chart of every actuator (:mod:`.chart`)
``shape.svg``    side views at a few pressures (:mod:`.sideview`)
``shape.glb``    3D shape at the shape pressure (:mod:`.mesh`; suffix selectable)
``shape3d.svg``  flat-shaded picture of the 3D shape (:mod:`.meshview`)
``report.json``  all of it as data, with the worksheet and the findings
``report.html``  the same, self-contained, with the stitch preview
================ =========================================================

:func:`render_previews` does the rendering for given curves; :func:`predict_curves`
makes the curves (each actuator's ``ModelSettings``: G from the calibration set unless given).

Examples
--------
>>> from embroact.export.pictures.previews import side_pressures
>>> side_pressures([0.0, 50.0, 100.0, 150.0, 200.0, 250.0, 300.0], [0, 0, 5, 20, 40, 60, 80], count=4)
(0.0, 100.0, 200.0, 300.0)
>>> pressures_for()[:3], pressures_for()[-1]
((0.0, 10.0, 20.0), 300.0)
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from ...patterns.base.errors import ExportError, ParameterError
from .chart import Series, bend_chart_svg
from ..report.report import report_data, report_html, report_json
from .sideview import SidePanel, side_view_svg

__all__ = [
    "OUTPUT_NAMES",
    "DEFAULT_PRESSURES_KPA",
    "Previews",
    "side_pressures",
    "shape_theta_deg",
    "pressures_for",
    "predict_curves",
    "bend_series",
    "side_panels",
    "shape_meshes",
    "shape3d_title",
    "check_side_states",
    "render_previews",
    "previews_stage",
]

#: Output kind -> file name (the mesh's suffix follows ``mesh_suffix``).
OUTPUT_NAMES = {
    "bend": "bend.svg",
    "side": "shape.svg",
    "mesh": "shape",
    "shape3d": "shape3d.svg",
    "json": "report.json",
    "html": "report.html",
}
#: Pressures of the predicted curves unless told otherwise: 0, 10, ..., 300 kPa.
DEFAULT_PRESSURES_KPA = tuple(float(p) for p in range(0, 301, 10))
PRESSURE_STEP_KPA = 10.0
DEFAULT_SIDE_STATES = 5
MAX_SIDE_STATES = 12


@dataclass(frozen=True, slots=True)
class Previews:
    """Rendered previews, not yet written.

    Attributes
    ----------
    files : dict
        File name -> contents (str for text, bytes for the mesh), in writing order.
    mesh : dict or None
        3D facts: file, pressure_kpa and theta_deg per actuator, triangle_count,
        tolerance_mm, max_deviation_mm.
    """

    files: dict
    mesh: dict | None


def side_pressures(pressure_kpa, theta_deg, *, count: int = DEFAULT_SIDE_STATES) -> tuple[float, ...]:
    """Up to ``count`` sampled pressures, evenly spread over the range, with a finite angle.

    The nearest sample to each of ``count`` evenly spaced targets is taken (no repeats).
    """
    p = np.asarray(pressure_kpa, dtype=np.float64)[np.isfinite(np.asarray(theta_deg, dtype=np.float64))]
    if len(p) == 0:
        return ()
    targets = np.linspace(p.min(), p.max(), max(1, int(count)))
    return tuple(sorted({float(p[np.argmin(np.abs(p - t))]) for t in targets}))


def shape_theta_deg(curve, pressure_kpa: float | None) -> tuple[float, float]:
    """(pressure, theta) for a drawn shape: the highest sampled pressure with a finite angle,
    or the curve interpolated linearly at ``pressure_kpa`` (which must lie in its range)."""
    p = np.asarray(curve.pressure_kpa, dtype=np.float64)
    t = np.asarray(curve.theta_deg, dtype=np.float64)
    ok = np.isfinite(t)
    if not ok.any():
        raise ParameterError("the curve has no finite angle to draw a shape from")
    order = np.argsort(p[ok], kind="stable")
    p, t = p[ok][order], t[ok][order]
    if pressure_kpa is None:
        return float(p[-1]), float(t[-1])
    if not p[0] <= pressure_kpa <= p[-1]:
        raise ParameterError(f"shape_pressure_kpa must be in [{p[0]:g}, {p[-1]:g}] (the predicted range), "
                             f"got {pressure_kpa:g}")
    return float(pressure_kpa), float(np.interp(pressure_kpa, p, t))


def pressures_for(design=None, *, step_kpa: float = PRESSURE_STEP_KPA) -> tuple[float, ...]:
    """0 to the design's ``operation.max_pressure_kpa`` in ``step_kpa`` steps (default 0..300 kPa)."""
    top = float(design.operation.max_pressure_kpa) if design is not None else DEFAULT_PRESSURES_KPA[-1]
    n = int(np.floor(top / step_kpa + 0.5))
    return tuple(float(v) for v in np.linspace(0.0, n * step_kpa, n + 1)) + (() if n * step_kpa >= top else (top,))


def predict_curves(plan, pressures_kpa=DEFAULT_PRESSURES_KPA, *, design=None, method: str = "auto") -> tuple[tuple, tuple]:
    """(derived geometry, curve) per actuator of ``plan``.

    Each actuator's model follows the ``ModelSettings`` of the design's actuator of the
    same name (defaults when there is no design or no such actuator).
    """
    from ...predict.analysis import analyse

    analysis = analyse(design, plan=plan)
    return tuple(a.derived for a in analysis.actuators), analysis.curves(pressures_kpa, method=method)


def _status_list(status) -> list[str]:
    from ...predict.status import status_names

    return [n.lower() for n in status_names(status)]


def bend_series(plan, derived, curves, measured: Mapping[str, tuple] | None = None) -> list[Series]:
    """Chart series, one per actuator; ``measured`` maps actuator name -> (pressure_kpa, theta_deg)."""
    measured = dict(measured or {})
    return [Series.from_curve(c, label=f"{a.name} ({g.pattern}, w {g.width_mm:.1f} mm)", p0_kpa=g.p0_kpa,
                              measured=measured.get(a.name))
            for a, g, c in zip(plan.actuators, derived, curves)]


def side_panels(plan, derived, curves, *, count: int = DEFAULT_SIDE_STATES) -> list[SidePanel]:
    """Side-view panels, one per actuator, at up to ``count`` of the curve's pressures."""
    panels = []
    for a, g, c in zip(plan.actuators, derived, curves):
        picks = side_pressures(c.pressure_kpa, c.theta_deg, count=count)
        panels.append(SidePanel(a.name, length_mm=g.length_mm, r0_mm=g.r0_mm, pressure_kpa=picks,
                                theta_deg=[shape_theta_deg(c, p)[1] for p in picks]))
    return panels


def shape_meshes(plan, derived, curves, *, pressure_kpa: float | None = None, tolerance_mm: float | None = None):
    """3D shape per actuator at ``pressure_kpa`` (default the highest predicted)."""
    from .mesh import DEFAULT_CHORD_TOLERANCE_MM, PlanarPath, actuator_mesh

    tol = DEFAULT_CHORD_TOLERANCE_MM if tolerance_mm is None else tolerance_mm
    shapes, pressures = [], {}
    for a, g, c in zip(plan.actuators, derived, curves):
        p, theta = shape_theta_deg(c, pressure_kpa)
        shapes.append(actuator_mesh(PlanarPath.from_centerline(a.centerline), theta, width_mm=g.width_mm,
                                    r0_mm=g.r0_mm, tolerance_mm=tol, name=a.name))
        pressures[a.name] = p
    return shapes, pressures


def shape3d_title(pressures: Mapping[str, float]) -> str:
    """Title of the 3D picture: the pressure of each actuator's shape.

    Examples
    --------
    >>> shape3d_title({"A1": 150.0, "A2": 87.5})
    '3D shape at A1: 150 kPa, A2: 87.5 kPa'
    """
    return "3D shape at " + ", ".join(f"{n}: {p:g} kPa" for n, p in pressures.items())


def check_side_states(value, *, name: str = "side_states") -> int:
    """``value`` if it is an integer in [1, :data:`MAX_SIDE_STATES`], else :class:`ParameterError` naming ``name``.

    Examples
    --------
    >>> check_side_states(5)
    5
    """
    if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= MAX_SIDE_STATES:
        raise ParameterError(f"{name} must be an integer in [1, {MAX_SIDE_STATES}], got {value!r}")
    return value


def _check_inputs(plan, derived, curves, side_states) -> None:
    n = len(plan.actuators)
    if not n or not (n == len(derived) == len(curves)):
        raise ParameterError(f"need one derived geometry and one curve per actuator ({n}), "
                             f"got {len(derived)} and {len(curves)}")
    check_side_states(side_states)


def render_previews(
    *,
    plan,
    derived: Sequence,
    curves: Sequence,
    findings=(),
    worksheet=None,
    measured: Mapping[str, tuple] | None = None,
    stitch_svg: str | None = None,
    side_states: int = DEFAULT_SIDE_STATES,
    shape_pressure_kpa: float | None = None,
    mesh_suffix: str | None = ".glb",
    tolerance_mm: float | None = None,
) -> Previews:
    """Render the previews and the report of one build, in memory.

    Parameters
    ----------
    plan : StitchPlan
        The generated plan; ``plan.actuators[k]`` gives actuator k's name and centerline.
    derived : sequence of DerivedGeometry
        One per actuator, same order.
    curves : sequence of Curve
        Predicted curve per actuator (``pressure_kpa``, ``theta_deg``, ``status``, ``method``).
    findings : iterable
        Design-rule findings (``Finding`` or dicts).
    worksheet : Worksheet or dict, optional
    measured : mapping, optional
        Actuator name -> (pressure_kpa, theta_deg) arrays of measured points to overlay.
    stitch_svg : str, optional
        Stitch preview SVG; default ``export.preview.plan_svg(plan)``.
    side_states : int
        Number of pressures drawn in the side view, in [1, 12].
    shape_pressure_kpa : float, optional
        Pressure of the 3D shape [kPa]; default the highest predicted pressure.
    mesh_suffix : str or None
        ``".glb"`` (default; written without trimesh), ``".stl"``, ``".obj"``, ``".ply"`` (these import
        trimesh); None: no 3D.
    tolerance_mm : float, optional
        Chordal tolerance of the mesh [mm]; default ``mesh.DEFAULT_CHORD_TOLERANCE_MM``.
    """
    _check_inputs(plan, derived, curves, side_states)
    title = getattr(plan, "name", "embroact")
    panels = side_panels(plan, derived, curves, count=side_states)
    figures = {"bend": bend_chart_svg(bend_series(plan, derived, curves, measured),
                                      title=f"{title}: predicted bend angle"),
               "side": side_view_svg(panels)}
    files: dict = {OUTPUT_NAMES["bend"]: figures["bend"], OUTPUT_NAMES["side"]: figures["side"]}
    mesh_info = None
    if mesh_suffix is not None:
        from .mesh import MESH_FORMATS, mesh_bytes
        from .meshview import mesh_svg

        if str(mesh_suffix).lower() not in MESH_FORMATS:
            raise ExportError(f"mesh suffix must be one of {', '.join(MESH_FORMATS)}, got {mesh_suffix!r}")
        shapes, pressures = shape_meshes(plan, derived, curves, pressure_kpa=shape_pressure_kpa,
                                         tolerance_mm=tolerance_mm)
        name = OUTPUT_NAMES["mesh"] + str(mesh_suffix).lower()
        files[name] = mesh_bytes(shapes, mesh_suffix)
        figures["shape3d"] = mesh_svg(shapes, title=shape3d_title(pressures))
        files[OUTPUT_NAMES["shape3d"]] = figures["shape3d"]
        mesh_info = {"file": name, "pressure_kpa": pressures, "theta_deg": {s.name: s.theta_deg for s in shapes},
                     "triangle_count": sum(s.triangle_count for s in shapes), "tolerance_mm": shapes[0].tolerance_mm,
                     "max_deviation_mm": max(s.max_deviation_mm for s in shapes)}
    if stitch_svg is None:
        from .stitches import plan_svg

        stitch_svg = plan_svg(plan)
    figures["stitches"] = stitch_svg
    entries = [{"name": a.name, "derived": g.as_dict(),
                "curve": {"pressure_kpa": c.pressure_kpa, "theta_deg": c.theta_deg, "status": _status_list(c.status),
                          "method": getattr(c, "method", None), "calibration": getattr(c, "calibration", None)},
                "side_view": [{"pressure_kpa": p, "theta_deg": t} for p, t in zip(s.pressure_kpa, s.theta_deg)]}
               for a, g, c, s in zip(plan.actuators, derived, curves, panels)]
    ws = worksheet.as_dict() if hasattr(worksheet, "as_dict") else worksheet
    data = report_data(title=title, actuators=entries, findings=findings, worksheet=ws, mesh=mesh_info)
    files[OUTPUT_NAMES["json"]] = report_json(data)
    files[OUTPUT_NAMES["html"]] = report_html(data, figures=figures)
    return Previews(files, mesh_info)


def previews_stage(
    *,
    pressures_kpa=None,
    measured: Mapping[str, tuple] | None = None,
    side_states: int = DEFAULT_SIDE_STATES,
    shape_pressure_kpa: float | None = None,
    mesh_suffix: str | None = ".glb",
    tolerance_mm: float | None = None,
):
    """The build stage: ``stage(context) -> {file name: contents}`` (see :mod:`embroact.export.report.build`).

    It predicts the curves at ``pressures_kpa`` (default :func:`pressures_for` the
    design) with each actuator's model settings (:func:`predict_curves`), takes the
    stitch preview from ``context.outputs["preview.svg"]`` when present, the worksheet
    and findings from the context, and returns :attr:`Previews.files`.
    """
    def stage(context) -> dict:
        pressures = pressures_for(context.design) if pressures_kpa is None else pressures_kpa
        derived, curves = predict_curves(context.plan, pressures, design=context.design)
        svg = context.outputs.get("preview.svg")
        return render_previews(
            plan=context.plan, derived=derived, curves=curves, findings=context.findings,
            worksheet=context.worksheet, measured=measured,
            stitch_svg=svg.decode("utf-8") if isinstance(svg, bytes) else svg, side_states=side_states,
            shape_pressure_kpa=shape_pressure_kpa, mesh_suffix=mesh_suffix, tolerance_mm=tolerance_mm).files

    return stage
