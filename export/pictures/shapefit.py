"""Predicted shape over a target shape (SVG): how well an inverse design matches the curve asked for.

Both curves are in the profile frame of a target shape (docs/model.md, segmented
actuators): the clamped end at the origin heading +x, +y toward positive bends. Drawn in
millimetres (1 user unit = 1 mm, y up on the page as in the frame), with the segment
boundaries of the design marked on the predicted line and a 10 mm scale bar.

Examples
--------
>>> import numpy as np
>>> from embroact.export.pictures.shapefit import shape_overlay_svg
>>> s = np.linspace(0.0, 1.0, 11)[:, None]
>>> svg = shape_overlay_svg(np.hstack([100 * s, 0 * s]), np.hstack([100 * s, 0.1 * s]), [50.0],
...                         title="flat")
>>> svg.startswith("<svg") and 'class="target"' in svg and 'class="boundary"' in svg
True
"""
from __future__ import annotations

from typing import Sequence

import numpy as np

from ...patterns.base.errors import ParameterError
from ...patterns.kinds import params_text
from .sideview import PX_PER_MM

__all__ = ["shape_overlay_svg", "design_shape_svg"]

_MARGIN_MM = 10.0
_HEADER_MM = 16.0
_TARGET, _PREDICTED = "#888888", "#d62728"
_FONT = "font-family:Helvetica,Arial,sans-serif"


def _points(xy: np.ndarray, x0: float, y1: float) -> list[tuple[float, float]]:
    return [(round(float(x) - x0, 3), round(y1 - float(y), 3)) for x, y in xy]


def shape_overlay_svg(target_xy_mm, predicted_xy_mm, boundaries_mm: Sequence[float] = (), *,
                      title: str = "Predicted shape over the target", caption: Sequence[str] = ()) -> str:
    """SVG document: the target (grey, wide) and the predicted line (red) with segment boundaries.

    Parameters
    ----------
    target_xy_mm, predicted_xy_mm : array (n, 2)
        The curves [mm], profile frame; the predicted one sampled at the same arc lengths.
    boundaries_mm : sequence of float
        Arc lengths of the segment boundaries along the predicted line [mm] (ticks).
    title : str
        The picture's title.
    caption : sequence of str
        Lines printed under the drawing (errors, the design).

    Returns
    -------
    str
        SVG.

    Raises
    ------
    ParameterError
        A curve of fewer than 2 points.

    Examples
    --------
    >>> target = np.column_stack([np.linspace(0.0, 100.0, 11), np.zeros(11)])
    >>> svg = shape_overlay_svg(target, target + [0.0, 1.0], [50.0], caption=["RMSE 1 mm"])
    >>> svg.startswith("<svg"), "RMSE 1 mm" in svg
    (True, True)
    """
    from .svgdoc import Drawing

    target = np.asarray(target_xy_mm, dtype=np.float64).reshape(-1, 2)
    pred = np.asarray(predicted_xy_mm, dtype=np.float64).reshape(-1, 2)
    if len(target) < 2 or len(pred) < 2:
        raise ParameterError("target_xy_mm and predicted_xy_mm must hold at least 2 points each")
    both = np.vstack([target, pred])
    lo, hi = both.min(axis=0) - _MARGIN_MM, both.max(axis=0) + _MARGIN_MM
    text_mm = max([0.55 * 5.0 * len(title) + 8.0, 90.0] + [0.5 * 3.6 * len(line) + 8.0 for line in caption])
    width = max(float(hi[0] - lo[0]), text_mm)  # room for the title and the caption (Helvetica ~0.5 em/char)
    body = float(hi[1] - lo[1])
    height = _HEADER_MM + body + 6.0 * (len(caption) + 1) + _MARGIN_MM
    top = _HEADER_MM + float(hi[1])  # page y = top - plan y (y up on the page)
    dwg = Drawing(size=(f"{width * PX_PER_MM:.0f}", f"{height * PX_PER_MM:.0f}"),
                  viewBox=f"0 0 {width:.3f} {height:.3f}")
    dwg.add(dwg.rect((0, 0), (round(width, 3), round(height, 3)), fill="#fff"))
    root = dwg.g(style=_FONT)
    dwg.add(root)
    root.add(dwg.text(title, insert=(4.0, 7.0), font_size=5, font_weight="bold"))
    x0 = float(lo[0])
    root.add(dwg.polyline(_points(target, x0, top), fill="none", stroke=_TARGET, stroke_width=1.6,
                          stroke_linecap="round", stroke_linejoin="round", **{"class": "target"}))
    root.add(dwg.polyline(_points(pred, x0, top), fill="none", stroke=_PREDICTED, stroke_width=0.5,
                          stroke_linejoin="round", **{"class": "predicted"}))
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pred, axis=0).T))])
    for b in boundaries_mm:
        x, y = float(np.interp(b, s, pred[:, 0])), float(np.interp(b, s, pred[:, 1]))
        root.add(dwg.circle(_points(np.array([[x, y]]), x0, top)[0], 1.2, fill="#fff", stroke=_PREDICTED, stroke_width=0.4,
                            **{"class": "boundary", "data-s-mm": f"{b:g}"}))
    root.add(dwg.circle(_points(pred[:1], x0, top)[0], 1.5, fill="#444", **{"class": "clamp"}))
    legend_y = 12.0
    for k, (colour, text, w) in enumerate(((_TARGET, "target", 1.6), (_PREDICTED, "predicted", 0.5))):
        x = 4.0 + 32.0 * k
        root.add(dwg.line((x, legend_y), (x + 8.0, legend_y), stroke=colour, stroke_width=w))
        root.add(dwg.text(text, insert=(x + 10.0, legend_y + 1.2), font_size=3.6))
    y = _HEADER_MM + body + 6.0
    for line in caption:
        root.add(dwg.text(line, insert=(4.0, y), font_size=3.6))
        y += 6.0
    bar_x, bar_y = width - _MARGIN_MM - 10.0, legend_y
    root.add(dwg.line((bar_x, bar_y), (bar_x + 10.0, bar_y), stroke="#000", stroke_width=0.6))
    root.add(dwg.text("10 mm", insert=(bar_x + 5.0, bar_y - 1.5), font_size=3.5, text_anchor="middle"))
    return dwg.tostring()


def design_shape_svg(result) -> str:
    """The answer of :func:`embroact.predict.inverse.design_shape` drawn over its target, captioned with the
    statement, the tip error and each segment (what ``embroact design --target-shape --svg`` writes and the
    studio shows).

    Parameters
    ----------
    result : ShapeResult
        A target shape's answer.

    Returns
    -------
    str
        SVG.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> from embroact.patterns.params import ZigzagParams
    >>> from embroact.predict.inverse import ShapeSegment
    >>> xy = np.column_stack([np.linspace(0.0, 100.0, 11), np.zeros(11)])
    >>> result = SimpleNamespace(segments=(ShapeSegment(ZigzagParams(6.2, 1.0), 100.0, 60.0, 0.0105),),
    ...                          statement="met with 1 segment(s)", pressure_kpa=150.0, tip_error_mm=0.2,
    ...                          target_xy_mm=xy, predicted_xy_mm=xy)  # the fields of a ShapeResult it reads
    >>> svg = design_shape_svg(result)
    >>> "segment 0: zigzag width_mm=6.2 interval_mm=1 length_mm=100 (+60.0 deg)" in svg
    True
    """
    bounds = np.cumsum([s.length_mm for s in result.segments])[:-1]
    caption = [f"{result.statement} at {result.pressure_kpa:g} kPa; tip {result.tip_error_mm:.2f} mm off"]
    caption += [f"segment {i}: {s.pattern} {params_text(s.params)} length_mm={s.length_mm:g} ({s.theta_deg:+.1f} deg)"
                for i, s in enumerate(result.segments)]
    return shape_overlay_svg(result.target_xy_mm, result.predicted_xy_mm, bounds.tolist(), caption=caption,
                             title=f"Predicted shape over the target at {result.pressure_kpa:g} kPa")
