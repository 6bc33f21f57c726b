"""The pictures a notebook shows for embroact's values (registered by the top-level package).

Each function takes one value and returns SVG or HTML text drawn by the build's own
renderers: a design and a stitch plan show the stitch preview
(:func:`~embroact.export.pictures.stitches.plan_svg`), an analysis its actuator table, stitch
preview, bend chart and side view (:mod:`~embroact.export.pictures.previews`), a curve its
bend chart (:func:`~embroact.export.pictures.chart.bend_chart_svg`) and a bent shape its
side view (:func:`~embroact.export.pictures.sideview.side_view_svg`). ``embroact/__init__.py``
maps each class to its function (:mod:`embroact.patterns.base.display`).

Examples
--------
>>> import embroact
>>> from embroact.export.pictures.display import analysis_html
>>> html = analysis_html(embroact.analyse(embroact.default_design()))
>>> html.startswith('<div class="embroact">'), html.count("<svg")
(True, 3)
>>> embroact.default_design()._repr_svg_().startswith("<svg")
True
"""
from __future__ import annotations

from html import escape
from typing import TYPE_CHECKING

from ...patterns.base.errors import EmbroactError
from ...patterns.kinds import pattern_kind

if TYPE_CHECKING:  # pragma: no cover
    from ...patterns.design import Design
    from ...predict.analysis import ActuatorAnalysis, DesignAnalysis
    from ...predict.curve import Curve
    from ...predict.shape import BentShape

__all__ = ["design_svg", "analysis_html", "actuator_html", "curve_svg", "shape_svg"]

_COLUMNS = ("actuator", "pattern", "w [mm]", "s [mm]", "alpha0 [deg]", "l0 [mm]", "r0 [mm]", "beta0 [deg]",
            "G [MPa]", "P0 [kPa]", "G, P0 from")


def design_svg(design: Design) -> str:
    """The stitch preview of a design (generated now).

    Parameters
    ----------
    design : Design

    Returns
    -------
    str
        SVG text (:func:`~embroact.export.pictures.stitches.plan_svg` of ``build_plan(design)``).

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> 'id="needle-points"' in design_svg(default_design())
    True
    """
    from ...patterns.design import build_plan
    from .stitches import plan_svg

    return plan_svg(build_plan(design))


def _rows(act: ActuatorAnalysis) -> str:
    """One table row per segment of the actuator's chain (``A1 segment 0``...; a chain of one: ``A1``)."""
    return "".join(_row(act.segments.part_name(act.name, k), s) for k, s in enumerate(act.segments))


def _row(name: str, act) -> str:
    d = act.derived
    cells = [name, d.pattern, f"{d.width_mm:.3g}", f"{d.interval_mm:.3g}",
             f"{d.angle_deg:.3g}" if pattern_kind(d.pattern).has_angle else "", f"{d.length_mm:.4g}", f"{d.r0_mm:.4g}",
             f"{d.beta0_deg:.4g}"]
    if act.choice is None:
        cells += ["", "", act.model_error]
    else:
        m, c = act.choice.model, act.choice
        cells += [f"{m.g_mpa:.4g}", f"{m.p0_kpa:.4g}",
                  c.g_source if c.g_source == c.p0_source else f"G: {c.g_source}; P0: {c.p0_source}"]
    return "<tr>" + "".join(f"<td>{escape(v)}</td>" for v in cells) + "</tr>"


def _table(actuators) -> str:
    head = "".join(f"<th>{escape(c)}</th>" for c in _COLUMNS)
    return f"<table><tr>{head}</tr>{''.join(_rows(a) for a in actuators)}</table>"


def _figure(svg: str) -> str:
    return f'<div style="max-width:720px">{svg[svg.index("<svg"):]}</div>'


def _model_figures(analysis: DesignAnalysis) -> list[str]:
    """Bend chart and side view; a note instead when an actuator (or a segment) has no model."""
    from .previews import bend_chart, side_panels
    from .sideview import side_view_svg

    try:
        curves = analysis.curves()
    except EmbroactError as exc:
        return [f"<p>no bend chart: {escape(str(exc))}</p>"]
    return [_figure(bend_chart(analysis, curves)), _figure(side_view_svg(side_panels(analysis, curves)))]


def analysis_html(analysis: DesignAnalysis) -> str:
    """An analysed design: actuator table, stitch preview, bend chart and side view.

    Parameters
    ----------
    analysis : DesignAnalysis

    Returns
    -------
    str
        An HTML fragment (one ``<div class="embroact">``) with the SVG pictures inline.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> "<td>A1</td><td>zigzag</td><td>7</td>" in analysis_html(analyse(default_design()))
    True
    """
    from .stitches import plan_svg

    parts = [f"<h4>{escape(analysis.plan.name)}</h4>", _table(analysis.actuators), _figure(plan_svg(analysis.plan)),
             *_model_figures(analysis)]
    return f'<div class="embroact">{"".join(parts)}</div>'


def actuator_html(act: ActuatorAnalysis) -> str:
    """One analysed actuator: its table row and its bend chart over 0-300 kPa.

    Parameters
    ----------
    act : ActuatorAnalysis

    Returns
    -------
    str
        An HTML fragment; without a model the chart is replaced by the reason.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> actuator_html(analyse(default_design()).actuators[0]).count("<svg")
    1
    """
    from ...patterns.design import OperationSettings
    from ...predict.analysis import pressure_grid_kpa
    from ...predict.curve import curve
    from .chart import bend_chart_svg
    from .previews import actuator_series

    parts = [_table([act])]
    missing = [p.model_error for p in act.segments if p.choice is None]
    if missing:
        parts.append(f"<p>no bend chart: {escape('; '.join(missing))}</p>")
    else:  # the whole strip and each segment
        grid = pressure_grid_kpa(OperationSettings().max_pressure_kpa)
        c = act.strip([curve(s.model, grid) for s in act.segments])
        parts.append(_figure(bend_chart_svg(actuator_series(act, c), title=f"{act.name}: predicted bend angle")))
    return f'<div class="embroact">{"".join(parts)}</div>'


def curve_svg(curve: Curve) -> str:
    """A predicted curve's bend chart (one series per row of a swept curve).

    Parameters
    ----------
    curve : Curve

    Returns
    -------
    str
        SVG text.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> curve_svg(analyse(default_design()).curves([0.0, 100.0, 200.0])[0]).count('class="curve"')
    1
    """
    import numpy as np

    from .chart import Series, bend_chart_svg

    rows = np.atleast_2d(curve.theta_deg)
    p = np.atleast_2d(curve.pressure_kpa)
    status = np.atleast_2d(curve.status)
    series = [Series(f"{curve.method}" + (f" [{k}]" if len(rows) > 1 else ""), p[min(k, len(p) - 1)], row,
                     status=tuple(status[k])) for k, row in enumerate(rows)]
    return bend_chart_svg(series, title=f"Predicted bend angle ({curve.calibration})")


def shape_svg(shape: BentShape) -> str:
    """A bent shape's side view (clamped top); a plan path's curvature is not shown.

    Parameters
    ----------
    shape : BentShape

    Returns
    -------
    str
        SVG text: the fabric line and a 1 mm tube band, drawn to scale in mm.

    Examples
    --------
    >>> from embroact.predict.shape import BentShape
    >>> shape_svg(BentShape.chain([50.0, 50.0], [30.0, 60.0])).startswith("<svg")
    True
    """
    import math

    from .sideview import SidePanel, side_view_svg

    lengths = tuple(float(v) for v in shape.lengths_mm)
    theta = tuple(math.degrees(k * length) for k, length in zip(shape.kappa_b_per_mm.tolist(), lengths))
    panel = SidePanel(f"{len(lengths)} piece{'s' * (len(lengths) > 1)}, {shape.turning_deg:.1f} deg",
                      length_mm=shape.length_mm, r0_mm=0.5, pressure_kpa=(math.nan,), theta_deg=(sum(theta),),
                      segment_lengths_mm=lengths, segment_theta_deg=(theta,))
    return side_view_svg([panel], title="Bent shape (side view, clamped top)")
