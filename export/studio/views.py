"""What the studio page shows for an analysed design at the slider's pressure, rendered by the CLI's own code.

Every picture comes from :mod:`embroact.export.pictures` and every number from the
analysis (:func:`embroact.predict.analysis.analyse`), its memoised curves and the rules
(:func:`embroact.predict.rules.check_design`), the same calls ``embroact build``,
``predict`` and ``check`` make. This module only adds what a live view needs on top:
the findings marked on the stitch preview (one ``<circle class="finding">`` per
finding with a place, ``data-finding`` = its index in the list), the slider's pressure
marked on the bend chart, and one-pressure side and 3D views.

Examples
--------
>>> from embroact.patterns.design import default_design
>>> from embroact.predict.analysis import analyse
>>> a = analyse(default_design())
>>> [round(x["theta_deg"], 3) for x in bend_at(a, 200.0)]
[102.93]
>>> bend_at(a, 200.0)[0]["status"]
'BENDING'
"""
from __future__ import annotations

import re
from xml.sax.saxutils import escape

import numpy as np

from ...patterns.base.errors import EmbroactError

__all__ = ["bend_at", "stitches_svg", "chart_svg", "side_svg", "shape3d_svg", "message_svg", "worksheet_figures",
           "SHAPE3D_WIDTH_PX", "SHAPE3D_TOLERANCE_MM"]

#: Width of the live 3D picture [px] and the mesh's chordal tolerance [mm] (the picture remeshes
#: at a fraction of a pixel anyway; the deviation is not measured: no file is written).
SHAPE3D_WIDTH_PX = 420.0
SHAPE3D_TOLERANCE_MM = 0.2
_VIEWBOX = re.compile(r'viewBox="([-\d.e]+) ([-\d.e]+) ([-\d.e]+) ([-\d.e]+)"')


def message_svg(text: str, *, width_px: int = 480, chars_per_line: int = 70) -> str:
    """A small SVG that says ``text``, wrapped (where a view cannot be drawn, e.g. no model).

    Parameters
    ----------
    text : str
        The message (cut to 600 characters).
    width_px : int, optional
        The picture's width [px].
    chars_per_line : int, optional
        Where it wraps.

    Returns
    -------
    str
        SVG.

    Examples
    --------
    >>> svg = message_svg("no side view: A1 has no model")
    >>> svg.startswith('<svg xmlns="http://www.w3.org/2000/svg" width="480"'), "no side view" in svg
    (True, True)
    """
    import textwrap

    lines = textwrap.wrap(text[:600], chars_per_line) or [""]
    height = 16 * len(lines) + 20
    rows = "".join(f'<tspan x="10" dy="{16 if k else 0}">{escape(line)}</tspan>' for k, line in enumerate(lines))
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width_px}" height="{height}" class="message">'
            f'<rect width="100%" height="100%" fill="#fff7e6" stroke="#d9a441"/>'
            f'<text x="10" y="22" font-size="13" font-family="Helvetica,Arial,sans-serif">{rows}</text></svg>')


def bend_at(analysis, pressure_kpa: float) -> list[dict]:
    """Per actuator: bend [deg] and status at ``pressure_kpa`` (per segment too), or why there is none.

    A segmented actuator's bend and status are its whole strip's
    (:func:`~embroact.predict.analysis.strip_curve`), as ``embroact predict`` gives them.

    Parameters
    ----------
    analysis : DesignAnalysis
        The analysed design.
    pressure_kpa : float
        The pressure [kPa].

    Returns
    -------
    list of dict
        ``name``, ``theta_deg``, ``status``, ``segment_theta_deg`` and ``model_error`` per actuator;
        ``drawn`` (whether the views draw this state as a shape: one the model describes, in
        ``described_kpa``, the range ``embroact preview mesh`` takes a shape pressure in), and
        ``note``, the line the views write where it is not drawn (None where it is).

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> bends = bend_at(analysis, 150.0)
    >>> b, = bends
    >>> b["name"], round(b["theta_deg"], 2), b["status"], b["model_error"]
    ('A1', 53.71, 'BENDING', None)
    """
    from ...predict.status import Status

    p = float(pressure_kpa)
    try:
        whole, described = analysis.curves((p,)), analysis.curves()
    except EmbroactError as exc:
        return [{"name": a.name, "theta_deg": None, "status": None, "segment_theta_deg": [],
                 "model_error": a.model_error or str(exc), "drawn": False, "described_kpa": None,
                 "note": None} for a in analysis.actuators]
    return [{"name": a.name, "theta_deg": float(c.theta_deg[0]), "status": Status(int(c.status[0])).name,
             "segment_theta_deg": [float(sc.theta_deg[0]) for sc in c.segments],
             "model_error": None, **_drawn(c, d, p)} for a, c, d in zip(analysis.actuators, whole, described)]


def _drawn(at, curve, pressure_kpa: float) -> dict:
    """Whether the state ``at`` (a curve at ``pressure_kpa`` alone) is drawn as a shape: a state the model
    describes, in the range ``embroact preview mesh`` draws in (:func:`~embroact.export.pictures.previews.described_kpa`
    of ``curve``, the actuator's curve over the analysis's pressures); else the note the views write."""
    from ...predict.status import is_model_state, status_names
    from ..pictures.previews import described_kpa, not_drawn_note

    rng = described_kpa(curve)
    state = bool(np.isfinite(at.theta_deg[0]) and is_model_state(at.status)[0])
    if state and rng is not None and rng[0] <= pressure_kpa <= rng[1]:
        return {"drawn": True, "described_kpa": list(rng), "note": None}
    if state:  # in a gap of the sampled range: the nearest sample left out says why
        out = ~is_model_state(curve.status)
        p = np.asarray(curve.pressure_kpa, dtype=np.float64)
        names = status_names(np.asarray(curve.status)[out][np.argsort(np.abs(p[out] - pressure_kpa))[:1]])
    else:
        names = status_names(at.status)
    return {"drawn": False, "described_kpa": None if rng is None else list(rng),
            "note": not_drawn_note([pressure_kpa], names, rng)}


def stitches_svg(plan, findings) -> str:
    """The stitch preview (:func:`~embroact.export.pictures.stitches.plan_svg`) with every placed finding circled.

    Parameters
    ----------
    plan : StitchPlan
        The design's plan.
    findings : sequence of Finding
        Its design-rule findings.

    Returns
    -------
    str
        SVG; each finding with a place is a ``<circle class="finding ...">``.

    Examples
    --------
    >>> import embroact.patterns.rules  # declares the rules
    >>> from embroact.patterns.base.findings import RULES
    >>> from embroact.patterns.design import build_plan, default_design
    >>> svg = stitches_svg(build_plan(default_design()), [RULES.finding("EA105", "dense", xy_mm=(0.0, 3.5))])
    >>> svg.count('class="finding warning"')
    1
    """
    from ..pictures.stitches import plan_svg

    svg = plan_svg(plan)
    box = _VIEWBOX.search(svg)
    if box is None or not findings:
        return svg
    size = max(float(box.group(3)), float(box.group(4)))
    r = max(1.0, 0.015 * size)
    marks = []
    for k, f in enumerate(findings):
        if f.xy_mm is None:
            continue
        x, y = f.xy_mm
        marks.append(f'<circle class="finding {f.severity.value}" data-finding="{k}" cx="{x:.3f}" cy="{-y:.3f}" '
                     f'r="{r:.3f}" fill="none" stroke-width="{r / 4:.3f}"><title>{escape(f.code)} '
                     f"{escape(f.message)}</title></circle>")
    layer = '<g id="studio-findings">' + "".join(marks) + "</g>"
    return svg[: svg.rfind("</svg>")] + layer + "</svg>"


def chart_svg(analysis, bends: list[dict], pressure_kpa: float) -> str:
    """The build's bend chart (:func:`~embroact.export.pictures.previews.bend_chart`) with the slider's
    pressure as a vertical line and each actuator's bend there as a dot; a segmented actuator has
    the build's curve (and dot) for its whole strip and for each segment.

    Parameters
    ----------
    analysis : DesignAnalysis
        The studio's analysed design.
    bends : list of dict
        :func:`bend_at` at ``pressure_kpa``.
    pressure_kpa : float
        The slider's pressure [kPa].

    Returns
    -------
    str
        SVG (a message when it cannot be drawn).

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> bends = bend_at(analysis, 150.0)
    >>> svg = chart_svg(analysis, bends, 150.0)
    >>> 'class="pressure-dot" cx="384.00"' in svg  # the bend at 150 kPa, on the curve
    True
    """
    from ..pictures import previews as pv
    from ..pictures.chart import chart_scale

    try:
        curves = analysis.curves()
        series, svg = pv.bend_series(analysis, pv.chart_curves(analysis, curves)), pv.bend_chart(analysis, curves)
        thetas = [t if b["drawn"] else None  # the series drawn: whole strip, then listed segments
                  for a, b in zip(analysis.actuators, bends)
                  for t in [b["theta_deg"], *a.segments.one_or_all((), b["segment_theta_deg"])]]
    except EmbroactError as exc:
        return message_svg(f"no bend chart: {exc}")
    sc = chart_scale(series, width_px=pv.bend_chart_width_px(series))  # the chart's own (a long legend widens it)
    if not sc.x_min_kpa <= pressure_kpa <= sc.x_max_kpa:
        return svg
    x = sc.x_px(pressure_kpa)
    parts = [f'<line x1="{x:.2f}" x2="{x:.2f}" y1="{sc.top_px:.2f}" y2="{sc.top_px + sc.height_px:.2f}" '
             f'stroke="#c0392b" stroke-width="1.2" stroke-dasharray="4,3"/>']
    for t in thetas:
        if t is not None and np.isfinite(t) and sc.y_min_deg <= t <= sc.y_max_deg:
            parts.append(f'<circle class="pressure-dot" cx="{x:.2f}" cy="{sc.y_px(t):.2f}" r="4.5" fill="#c0392b"/>')
    layer = f'<g id="pressure-marker" data-pressure-kpa="{pressure_kpa:g}">' + "".join(parts) + "</g>"
    return svg[: svg.rfind("</svg>")] + layer + "</svg>"


def side_svg(analysis, bends: list[dict], pressure_kpa: float) -> str:
    """Side view (:func:`~embroact.export.pictures.sideview.side_view_svg`) unbent and at the slider's pressure,
    each actuator's panel made as the build makes it (:func:`~embroact.export.pictures.previews.side_panel`).

    Parameters
    ----------
    analysis : DesignAnalysis
        The studio's analysed design.
    bends : list of dict
        :func:`bend_at` at ``pressure_kpa``.
    pressure_kpa : float
        The slider's pressure [kPa].

    Returns
    -------
    str
        SVG (a message when it cannot be drawn).

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> bends = bend_at(analysis, 150.0)
    >>> side_svg(analysis, bends, 150.0).count('class="state"')
    2
    """
    from ..pictures import previews as pv
    from ..pictures.sideview import side_view_svg

    if any(b["theta_deg"] is None or not np.isfinite(b["theta_deg"]) for b in bends):
        return message_svg("no side view: " + "; ".join(b["model_error"] or f"{b['name']}: no finite bend"
                                                        for b in bends if b["theta_deg"] is None))
    panels = []
    for a, b in zip(analysis.actuators, bends):
        unbent = (0.0, 0.0, (0.0,) * len(b["segment_theta_deg"]))
        at = (pressure_kpa, b["theta_deg"], b["segment_theta_deg"])
        panels.append(pv.side_panel(a, [unbent, at] if pressure_kpa > 0 and b["drawn"] else [unbent],
                                    note=b["note"] or ""))
    return side_view_svg(panels, title=f"Side view at {pressure_kpa:g} kPa")


def shape3d_svg(analysis, bends: list[dict], pressure_kpa: float) -> str:
    """The 3D picture (:func:`~embroact.export.pictures.meshview.mesh_svg`) of every actuator at the slider's pressure.

    Parameters
    ----------
    analysis : DesignAnalysis
        The studio's analysed design.
    bends : list of dict
        :func:`bend_at` at ``pressure_kpa``.
    pressure_kpa : float
        The slider's pressure [kPa].

    Returns
    -------
    str
        SVG (a message when it cannot be drawn).

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> bends = bend_at(analysis, 150.0)
    >>> "3D shape at 150 kPa" in shape3d_svg(analysis, bends, 150.0)
    True
    """
    from ..pictures.meshview import mesh_svg
    from ..pictures.previews import actuator_shape, shape3d_title

    if any(b["theta_deg"] is None or not np.isfinite(b["theta_deg"]) for b in bends):
        return message_svg("no 3D view: the model gives no finite bend here")
    notes = "; ".join(f"{b['name']} {b['note']}" for b in bends if not b["drawn"])
    drawn = [(a, b) for a, b in zip(analysis.actuators, bends) if b["drawn"]]
    if not drawn:
        return message_svg(f"no 3D view at {pressure_kpa:g} kPa: {notes}")
    shapes = [actuator_shape(a, b["theta_deg"], b["segment_theta_deg"], tolerance_mm=SHAPE3D_TOLERANCE_MM, measure=False)
              for a, b in drawn]
    title = shape3d_title({a.name: pressure_kpa for a, _ in drawn})
    return mesh_svg(shapes, width_px=SHAPE3D_WIDTH_PX, title=f"{title}; {notes}" if notes else title)


def worksheet_figures(ws) -> dict:
    """The worksheet's production figures (counts, thread, time, fabric, tube to cut per actuator).

    Parameters
    ----------
    ws : Worksheet
        The design's worksheet.

    Returns
    -------
    dict
        The figures ``worksheet.json`` holds, by the same keys.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> from embroact.export.report.worksheet import worksheet
    >>> analysis = analyse(default_design())
    >>> figures = worksheet_figures(worksheet(analysis.plan, analysis.design, analysis=analysis))
    >>> figures["stitch_count"], figures["actuators"]
    (106, [{'name': 'A1', 'tube_cut_mm': 160.0, 'stitches': 106, 'legs_over_tube': 100}])
    """
    d = ws.as_dict()
    keep = ("stitch_count", "jump_count", "trim_count", "stop_count", "top_thread_m", "bobbin_thread_m",
            "sewing_time_s", "handling_time_s", "size_mm", "fabric_mm", "operating_point")
    out = {k: d[k] for k in keep if k in d}
    out["actuators"] = [{"name": a.name, "tube_cut_mm": a.tube_cut_mm, "stitches": a.stitches,
                         "legs_over_tube": a.legs_over_tube} for a in ws.actuators]
    return out
