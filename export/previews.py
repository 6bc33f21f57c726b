"""What a build attaches to its machine files: bend chart, side view, 3D shape, report.

:func:`write_previews` is the one call ``embroact build`` makes after it has the plan,
the derived geometry, the predicted curves and the findings.  It writes, atomically,
into an existing directory:

============== ===========================================================
``bend.svg``   pressure-bend chart of every actuator (:mod:`.chart`)
``shape.svg``  side views at a few pressures (:mod:`.sideview`)
``shape.glb``  3D shape at the shape pressure (:mod:`.mesh`; suffix selectable)
``shape3d.svg`` flat-shaded picture of the 3D shape (:mod:`.meshview`)
``report.json`` everything above as data, plus worksheet and findings
``report.html`` the same, self-contained, with the stitch preview
============== ===========================================================

Examples
--------
>>> from embroact.export.previews import side_pressures
>>> side_pressures([0.0, 50.0, 100.0, 150.0, 200.0, 250.0, 300.0], [0, 0, 5, 20, 40, 60, 80], count=4)
(0.0, 100.0, 200.0, 300.0)
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np

from ..patterns.errors import ParameterError
from ..predict.status import status_names
from .atomic import write_text_atomic
from .chart import Series, bend_chart_svg
from .report import report_data, report_html, report_json
from .sideview import SidePanel, side_view_svg

__all__ = ["OUTPUT_NAMES", "PreviewResult", "side_pressures", "shape_theta_deg", "write_previews"]

#: Output kind -> file name (the mesh's suffix follows ``mesh_suffix``).
OUTPUT_NAMES = {
    "bend": "bend.svg",
    "side": "shape.svg",
    "mesh": "shape",
    "shape3d": "shape3d.svg",
    "json": "report.json",
    "html": "report.html",
}
DEFAULT_SIDE_STATES = 5


@dataclass(frozen=True, slots=True)
class PreviewResult:
    """What :func:`write_previews` wrote.

    Attributes
    ----------
    paths : dict
        Output kind (keys of ``OUTPUT_NAMES``) -> Path written.
    mesh : dict or None
        3D facts: file, pressure_kpa, per-actuator theta_deg, triangle_count,
        tolerance_mm, max_deviation_mm.
    """

    paths: dict
    mesh: dict | None


def side_pressures(pressure_kpa, theta_deg, *, count: int = DEFAULT_SIDE_STATES) -> tuple[float, ...]:
    """Up to ``count`` sampled pressures, evenly spread over the range, with a finite angle.

    The nearest sample to each of ``count`` evenly spaced targets is taken (no repeats).
    """
    p = np.asarray(pressure_kpa, dtype=np.float64)
    ok = np.isfinite(np.asarray(theta_deg, dtype=np.float64))
    p = p[ok]
    if len(p) == 0:
        return ()
    targets = np.linspace(p.min(), p.max(), max(1, int(count)))
    picks = sorted({float(p[np.argmin(np.abs(p - t))]) for t in targets})
    return tuple(picks)


def shape_theta_deg(curve, pressure_kpa: float | None) -> tuple[float, float]:
    """(pressure, theta) for the 3D shape: the highest sampled pressure with a finite angle,
    or the curve interpolated at ``pressure_kpa``."""
    p = np.asarray(curve.pressure_kpa, dtype=np.float64)
    t = np.asarray(curve.theta_deg, dtype=np.float64)
    ok = np.isfinite(t)
    if not ok.any():
        raise ParameterError("the curve has no finite angle to draw a 3D shape from")
    p, t = p[ok], t[ok]
    order = np.argsort(p, kind="stable")
    p, t = p[order], t[order]
    if pressure_kpa is None:
        return float(p[-1]), float(t[-1])
    if not p[0] <= pressure_kpa <= p[-1]:
        raise ParameterError(f"shape_pressure_kpa must be in [{p[0]:g}, {p[-1]:g}] (the predicted range), "
                             f"got {pressure_kpa:g}")
    return float(pressure_kpa), float(np.interp(pressure_kpa, p, t))


def _curve_dict(curve) -> dict:
    return {"pressure_kpa": np.asarray(curve.pressure_kpa).tolist(),
            "theta_deg": np.asarray(curve.theta_deg).tolist(),
            "status": [n.lower() for n in status_names(curve.status)],
            "method": getattr(curve, "method", None)}


def _dict(obj):
    return obj.as_dict() if hasattr(obj, "as_dict") else obj


def write_previews(
    out_dir,
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
) -> PreviewResult:
    """Write the previews and the report of one build into ``out_dir``.

    Parameters
    ----------
    out_dir : path
        Existing, writable directory.
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
        ``".glb"`` (default), ``".stl"``, ``".obj"``, ``".ply"``; None writes no 3D (trimesh is
        then not imported).
    tolerance_mm : float, optional
        Chordal tolerance of the mesh [mm]; default ``mesh.DEFAULT_CHORD_TOLERANCE_MM``.
    """
    acts = tuple(plan.actuators)
    if not (len(acts) == len(derived) == len(curves)) or not acts:
        raise ParameterError(f"need one derived geometry and one curve per actuator ({len(acts)}), "
                             f"got {len(derived)} and {len(curves)}")
    if isinstance(side_states, bool) or not isinstance(side_states, int) or not 1 <= side_states <= 12:
        raise ParameterError(f"side_states must be an integer in [1, 12], got {side_states!r}")
    out = Path(out_dir)
    measured = dict(measured or {})
    series, panels, entries = [], [], []
    for act, geo, curve in zip(acts, derived, curves):
        series.append(Series.from_curve(curve, label=f"{act.name} ({geo.pattern}, w {geo.width_mm:.1f} mm)",
                                        p0_kpa=geo.p0_kpa, measured=measured.get(act.name)))
        picks = side_pressures(curve.pressure_kpa, curve.theta_deg, count=side_states)
        thetas = [shape_theta_deg(curve, p)[1] for p in picks]
        panels.append(SidePanel(act.name, length_mm=geo.length_mm, r0_mm=geo.r0_mm, pressure_kpa=picks,
                                theta_deg=thetas))
        entries.append({"name": act.name, "derived": geo.as_dict(), "curve": _curve_dict(curve),
                        "side_view": [{"pressure_kpa": p, "theta_deg": t} for p, t in zip(picks, thetas)]})
    title = getattr(plan, "name", "embroact")
    figures = {"bend": bend_chart_svg(series, title=f"{title}: predicted bend angle"),
               "side": side_view_svg(panels)}
    paths = {"bend": out / OUTPUT_NAMES["bend"], "side": out / OUTPUT_NAMES["side"]}
    write_text_atomic(paths["bend"], figures["bend"])
    write_text_atomic(paths["side"], figures["side"])
    mesh_info = None
    if mesh_suffix is not None:
        mesh_info, figures["shape3d"] = _write_shape(out, acts, derived, curves, shape_pressure_kpa, mesh_suffix,
                                                     tolerance_mm, paths)
    figures["stitches"] = stitch_svg if stitch_svg is not None else _plan_svg(plan)
    data = report_data(title=title, actuators=entries, findings=findings, worksheet=_dict(worksheet), mesh=mesh_info)
    paths["json"], paths["html"] = out / OUTPUT_NAMES["json"], out / OUTPUT_NAMES["html"]
    write_text_atomic(paths["json"], report_json(data))
    write_text_atomic(paths["html"], report_html(data, figures=figures))
    return PreviewResult(paths, mesh_info)


def _plan_svg(plan) -> str:
    from .preview import plan_svg

    return plan_svg(plan)


def _write_shape(out: Path, acts, derived, curves, pressure_kpa, suffix, tolerance_mm, paths):
    from .mesh import DEFAULT_CHORD_TOLERANCE_MM, MESH_FORMATS, PlanarPath, actuator_mesh, write_mesh
    from .meshview import mesh_svg

    if suffix not in MESH_FORMATS:
        from ..patterns.errors import ExportError

        raise ExportError(f"mesh suffix must be one of {', '.join(MESH_FORMATS)}, got {suffix!r}")
    tol = DEFAULT_CHORD_TOLERANCE_MM if tolerance_mm is None else tolerance_mm
    shapes, thetas, pressures = [], {}, {}
    for act, geo, curve in zip(acts, derived, curves):
        p, theta = shape_theta_deg(curve, pressure_kpa)
        shapes.append(actuator_mesh(PlanarPath.from_centerline(act.centerline), theta, width_mm=geo.width_mm,
                                    r0_mm=geo.r0_mm, tolerance_mm=tol, name=act.name))
        thetas[act.name], pressures[act.name] = theta, p
    paths["mesh"] = write_mesh(shapes, out / (OUTPUT_NAMES["mesh"] + suffix))
    paths["shape3d"] = out / OUTPUT_NAMES["shape3d"]
    picture = mesh_svg(shapes, title="3D shape at " + ", ".join(f"{n}: {p:g} kPa" for n, p in pressures.items()))
    write_text_atomic(paths["shape3d"], picture)
    info = {"file": paths["mesh"].name, "pressure_kpa": pressures, "theta_deg": thetas,
            "triangle_count": sum(s.triangle_count for s in shapes), "tolerance_mm": tol,
            "max_deviation_mm": max(s.max_deviation_mm for s in shapes)}
    return info, picture
