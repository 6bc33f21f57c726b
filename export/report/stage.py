"""The build stage of the previews and the report: render every picture and the report of an analysis.

:func:`previews_stage` gives the stage :func:`embroact.export.report.build.build` runs after the
machine files; :func:`render_previews` renders an analysed design
(:func:`embroact.predict.analysis.analyse`) with its memoised curves, in memory, with the
pictures of :mod:`embroact.export.pictures.previews` and the report of :mod:`.report`.

Examples
--------
>>> from embroact.patterns.design import default_design
>>> from embroact.predict.analysis import analyse
>>> out = render_previews(analyse(default_design()), stitch_svg="<svg/>", mesh_suffix=None)
>>> sorted(out.files)
['bend.svg', 'report.html', 'report.json', 'shape.svg']
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

from ...patterns.base.errors import ExportError, ParameterError
from ..pictures.previews import (DEFAULT_SIDE_STATES, OUTPUT_NAMES, bend_chart, check_side_states,
                                 curve_bands, shape3d_title, shape_meshes, shape_state, side_panels)
from ..pictures.sideview import side_view_svg
from .report import report_data, report_html, report_json

__all__ = ["Previews", "actuator_entry", "render_previews", "previews_stage"]


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

    Examples
    --------
    >>> from embroact.predict.analysis import analyse
    >>> from embroact.patterns.design import default_design
    >>> analysis = analyse(default_design())
    >>> previews = render_previews(analysis, mesh_suffix=None)
    >>> list(previews.files), previews.mesh
    (['bend.svg', 'shape.svg', 'report.json', 'report.html'], None)
    """

    files: dict
    mesh: dict | None


def _check_inputs(analysis, curves, side_states) -> None:
    n = len(analysis.actuators)
    if not n or n != len(curves):
        raise ParameterError(f"need one curve per actuator ({n}), got {len(curves)}")
    for a, c in zip(analysis.actuators, curves):
        a.segments.check_parts(c.segments, f"actuator {a.name!r}",
                               f"its curve must be its whole strip (DesignAnalysis.curves), got {type(c).__name__}")
    check_side_states(side_states)


def actuator_entry(act, curve, band=None) -> dict:
    """One actuator of the report: :meth:`ActuatorAnalysis.as_dict` (derived geometry, G, P0, tube,
    tube law and their sources, and per segment) and the curve as ``Curve.as_dict``
    gives it (status names as in ``embroact predict --json``): the whole strip's, followed by each
    segment's (``segment_curves``; one for a single-pattern actuator).

    Parameters
    ----------
    act : ActuatorAnalysis
        The actuator.
    curve : StripCurve
        Its predicted curve.
    band : Band or None, optional
        The 1-sigma band of the calibration's covariance per point (its
        :meth:`~embroact.predict.uncertainty.Band.summary`); None without one.

    Returns
    -------
    dict

    Examples
    --------
    >>> from embroact.predict.analysis import analyse
    >>> from embroact.patterns.design import default_design
    >>> analysis = analyse(default_design())
    >>> entry = actuator_entry(analysis.actuators[0], analysis.curves()[0])
    >>> entry["name"], entry["band"], len(entry["segment_curves"])
    ('A1', None, 1)
    """
    return {**act.as_dict(), "curve": curve.as_dict(), "band": None if band is None else band.summary(),
            "segment_curves": [c.as_dict() for c in curve.segments]}


def _side_states(act, curve, panel) -> list[dict]:
    """The report's side-view states: pressure, the whole strip's bend and each segment's."""
    return [{"pressure_kpa": p, "theta_deg": t, "segment_theta_deg": list(shape_state(curve, p)[2])}
            for p, t in zip(panel.pressure_kpa, panel.theta_deg)]


def render_previews(
    analysis,
    curves: Sequence | None = None,
    *,
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
    analysis : DesignAnalysis
        The analysed design (:func:`embroact.predict.analysis.analyse`): plan, derived
        geometry and model of every actuator.
    curves : sequence of Curve, optional
        Predicted curve per actuator (a segmented one: its whole strip,
        :class:`~embroact.predict.analysis.StripCurve`); default ``analysis.curves()`` (the standard grid).
    findings : iterable
        Design-rule findings (``Finding`` or dicts).
    worksheet : Worksheet or dict, optional
        The worksheet the report shows.
    measured : mapping, optional
        Actuator name -> (pressure_kpa, theta_deg) arrays of measured points to overlay.
    stitch_svg : str, optional
        Stitch preview SVG, the build's ``preview.svg`` (the report links that file when the picture is too large
        to inline); default ``plan_svg(analysis.plan)``.
    side_states : int
        Number of pressures drawn in the side view, in [1, 12].
    shape_pressure_kpa : float, optional
        Pressure of the 3D shape [kPa]; default the highest predicted pressure.
    mesh_suffix : str or None
        ``".glb"`` (default; written without trimesh), ``".stl"``, ``".obj"``, ``".ply"`` (these import
        trimesh); None: no 3D.
    tolerance_mm : float, optional
        Chordal tolerance of the mesh [mm]; default ``mesh.DEFAULT_CHORD_TOLERANCE_MM``.

    Returns
    -------
    Previews

    Examples
    --------
    >>> from embroact.predict.analysis import analyse
    >>> from embroact.patterns.design import default_design
    >>> analysis = analyse(default_design())
    >>> previews = render_previews(analysis, mesh_suffix=None)
    >>> previews.files["bend.svg"].startswith("<svg"), "report.html" in previews.files
    (True, True)
    """
    curves = analysis.curves() if curves is None else tuple(curves)
    _check_inputs(analysis, curves, side_states)
    plan = analysis.plan
    panels = side_panels(analysis, curves, count=side_states)
    bands = curve_bands(analysis, curves)
    figures = {"bend": bend_chart(analysis, curves, measured, bands), "side": side_view_svg(panels)}
    files: dict = {OUTPUT_NAMES["bend"]: figures["bend"], OUTPUT_NAMES["side"]: figures["side"]}
    mesh_info = None
    if mesh_suffix is not None:
        from ..pictures.mesh import MESH_FORMATS, mesh_bytes
        from ..pictures.meshview import mesh_svg

        if str(mesh_suffix).lower() not in MESH_FORMATS:
            raise ExportError(f"mesh suffix must be one of {', '.join(MESH_FORMATS)}, got {mesh_suffix!r}")
        shapes, pressures = shape_meshes(analysis, curves, pressure_kpa=shape_pressure_kpa, tolerance_mm=tolerance_mm)
        name = OUTPUT_NAMES["mesh"] + str(mesh_suffix).lower()
        files[name] = mesh_bytes(shapes, mesh_suffix)
        figures["shape3d"] = mesh_svg(shapes, title=shape3d_title(pressures))
        files[OUTPUT_NAMES["shape3d"]] = figures["shape3d"]
        mesh_info = {"file": name, "pressure_kpa": pressures, "theta_deg": {s.name: s.theta_deg for s in shapes},
                     "triangle_count": sum(s.triangle_count for s in shapes), "tolerance_mm": shapes[0].tolerance_mm,
                     "max_deviation_mm": max(s.max_deviation_mm for s in shapes)}
        mesh_info["segment_theta_deg"] = {  # each segment's bend in the 3D shape
            a.name: list(shape_state(c, shape_pressure_kpa)[2]) for a, c in zip(analysis.actuators, curves)}
    # the files written beside report.html (a figure too large to inline is linked there): these previews, and
    # the stitch preview when it is the build's preview.svg
    figure_files = {k: OUTPUT_NAMES[k] for k in ("bend", "side", "shape3d")}
    if stitch_svg is None:
        from ..pictures.stitches import plan_svg

        stitch_svg = plan_svg(plan)
    else:
        figure_files["stitches"] = "preview.svg"
    figures["stitches"] = stitch_svg
    entries = [{**actuator_entry(a, c, b), "side_view": _side_states(a, c, s)}
               for a, c, s, b in zip(analysis.actuators, curves, panels, bands)]
    ws = worksheet.as_dict() if hasattr(worksheet, "as_dict") else worksheet
    data = report_data(title=plan.name, actuators=entries, findings=findings, worksheet=ws, mesh=mesh_info)
    files[OUTPUT_NAMES["json"]] = report_json(data)
    files[OUTPUT_NAMES["html"]] = report_html(data, figures=figures, figure_files=figure_files)
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

    It renders the build's own analysis (``context.analysis``) with its memoised curves at
    ``pressures_kpa`` (default the design's standard grid, the one the model rules use), takes the
    stitch preview from ``context.outputs["preview.svg"]`` when present, the worksheet
    and findings from the context, and returns :attr:`Previews.files`.

    Parameters
    ----------
    pressures_kpa : array_like, optional
        The bend chart's pressures [kPa].
    measured, side_states, shape_pressure_kpa, mesh_suffix, tolerance_mm
        As for :func:`render_previews`.

    Returns
    -------
    callable

    Examples
    --------
    >>> import tempfile
    >>> from embroact.export.report.build import build_plan_outputs
    >>> from embroact.predict.analysis import analyse
    >>> from embroact.patterns.design import default_design
    >>> analysis = analyse(default_design())
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     result = build_plan_outputs(analysis.plan, tmp, analysis=analysis, stages=[previews_stage(mesh_suffix=None)])
    >>> result.files[-4:]
    ('bend.svg', 'shape.svg', 'report.json', 'report.html')
    """
    def stage(context) -> dict:
        curves = context.analysis.curves(pressures_kpa)
        svg = context.outputs.get("preview.svg")
        return render_previews(
            context.analysis, curves, findings=context.findings, worksheet=context.worksheet, measured=measured,
            stitch_svg=svg.decode("utf-8") if isinstance(svg, bytes) else svg, side_states=side_states,
            shape_pressure_kpa=shape_pressure_kpa, mesh_suffix=mesh_suffix, tolerance_mm=tolerance_mm).files

    return stage
