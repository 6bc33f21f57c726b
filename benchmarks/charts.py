"""SVG charts of the benchmark (svgwrite): the speed/accuracy Pareto chart and the stability map.

Both return the SVG text; :mod:`run` writes it. Log axes throughout; an error of 0
is drawn at ``ERROR_FLOOR`` and a method that failed (infinite error) on the
"failed" line above the plot.

Examples
--------
>>> from charts import pareto_front, pareto_svg
>>> pareto_front([(1.0, 1e-3), (2.0, 1e-6), (3.0, 1e-4), (0.5, 1.0)])
[3, 0, 1]
>>> svg = pareto_svg([{"label": "a", "time_ms": 1.0, "error_deg": 1e-9, "kind": "method"}])
>>> svg.startswith("<?xml") and "Pareto" in svg
True
"""
from __future__ import annotations

import math

import svgwrite

__all__ = ["ERROR_FLOOR", "pareto_front", "pareto_svg", "stability_svg", "CLASS_COLOURS"]

#: Smallest error drawn on the log axis [deg].
ERROR_FLOOR = 1e-16
#: Colour per stability class (see :data:`stability.CLASSES`).
CLASS_COLOURS = ("#1a9850", "#a6d96a", "#fdae61", "#d73027", "#000000", "#d9d9d9")
_KIND_COLOURS = {"method": "#2c7bb6", "auto": "#1a9850", "baseline": "#d7191c"}
_FONT = "font-family:sans-serif;font-size:11px"


def pareto_front(points) -> list[int]:
    """Indices of the non-dominated (time, error) points, by increasing time."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], math.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def _log_map(lo, hi, a, b):
    llo, lhi = math.log10(lo), math.log10(hi)
    return lambda v: a + (math.log10(v) - llo) / (lhi - llo) * (b - a)


def _decade_range(lo, hi):
    a = math.floor(math.log10(lo))
    return 10.0**a, 10.0 ** max(math.ceil(math.log10(hi)), a + 1)


def _decades(lo, hi):
    return [10.0**k for k in range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1)]


def _text(dwg, s, x, y, **kw):
    return dwg.text(s, insert=(x, y), style=_FONT, **kw)


def pareto_svg(points, *, title: str = "Speed against accuracy (Pareto chart)") -> str:
    """Log-log chart: median time per 200-pressure curve [ms] against the max angle error [deg].

    ``points``: dicts with ``label``, ``time_ms``, ``error_deg`` and ``kind``
    ("method", "auto" or "baseline"). The Pareto front (no other point both faster
    and more accurate) is drawn as a step line.
    """
    w, h, left, right, top, bottom = 900, 620, 80, 230, 60, 60
    finite = [p for p in points if p["time_ms"] is not None]
    xs = [p["time_ms"] for p in finite]
    ys = [max(p["error_deg"], ERROR_FLOOR) for p in finite if math.isfinite(p["error_deg"])] or [1.0]
    xlo, xhi = _decade_range(min(xs), max(xs))
    ylo, yhi = _decade_range(min(ys) / 3.0, max(ys) * 3.0)
    fx, fy = _log_map(xlo, xhi, left, w - right), _log_map(ylo, yhi, h - bottom, top)
    dwg = svgwrite.Drawing(size=(f"{w}px", f"{h}px"), profile="full", debug=False)
    dwg.add(dwg.rect((0, 0), (w, h), fill="white"))
    dwg.add(_text(dwg, title, left, 24, font_weight="bold"))
    for v in _decades(xlo, xhi):
        dwg.add(dwg.line((fx(v), top), (fx(v), h - bottom), stroke="#eeeeee"))
        dwg.add(_text(dwg, f"{v:g}", fx(v), h - bottom + 16, text_anchor="middle"))
    for v in _decades(ylo, yhi):
        dwg.add(dwg.line((left, fy(v)), (w - right, fy(v)), stroke="#eeeeee"))
        dwg.add(_text(dwg, f"1e{round(math.log10(v))}", left - 6, fy(v) + 4, text_anchor="end"))
    dwg.add(dwg.rect((left, top), (w - right - left, h - bottom - top), fill="none", stroke="black"))
    dwg.add(_text(dwg, "median time per 200-pressure curve [ms] (log)", (left + w - right) / 2, h - 20,
                  text_anchor="middle"))
    dwg.add(_text(dwg, "max angle error vs 50-digit mpmath [deg] (log)", 18, (top + h - bottom) / 2,
                  text_anchor="middle", transform=f"rotate(-90 18 {(top + h - bottom) / 2})"))
    fail_y = top - 14
    if any(not math.isfinite(p["error_deg"]) for p in finite):
        dwg.add(_text(dwg, "failed (no finite error)", w - right + 6, fail_y + 4))
    coords = [(p["time_ms"], max(p["error_deg"], ERROR_FLOOR)) for p in finite]
    front = [i for i in pareto_front(coords) if math.isfinite(coords[i][1])]
    if front:
        pts, prev = [], None
        for i in front:
            x, y = fx(coords[i][0]), fy(coords[i][1])
            if prev is not None:
                pts.append((x, prev))
            pts.append((x, y))
            prev = y
        pts.append((w - right, prev))
        dwg.add(dwg.polyline(pts, fill="none", stroke="#1a9850", stroke_width=2, stroke_dasharray="6,3"))
    xy = [(fx(p["time_ms"]), fy(max(p["error_deg"], ERROR_FLOOR)) if math.isfinite(p["error_deg"]) else fail_y)
          for p in finite]
    boxes = [(x - 5, y - 5, x + 5, y + 5) for x, y in xy]
    for p, (x, y) in zip(finite, xy):
        colour = _KIND_COLOURS.get(p["kind"], "#444444")
        if math.isfinite(p["error_deg"]):
            dwg.add(dwg.circle((x, y), 5, fill=colour, stroke="black", stroke_width=0.5))
        else:
            dwg.add(dwg.path(f"M{x - 5},{y - 5} L{x + 5},{y + 5} M{x - 5},{y + 5} L{x + 5},{y - 5}",
                             stroke=colour, stroke_width=2))
    for p, (x, y) in zip(finite, xy):
        tx, ty, leader = _place_label(p["label"], x, y, boxes, (left + 2, w - 4))
        if leader:
            dwg.add(dwg.line((x, y), (tx, ty - 4), stroke="#999999", stroke_width=0.5))
        dwg.add(_text(dwg, p["label"], tx, ty))
    ky = top + 10
    for kind, label in (("auto", "auto (default)"), ("method", "embroact method"), ("baseline", "baselines")):
        dwg.add(dwg.circle((w - right + 16, ky + 30), 5, fill=_KIND_COLOURS[kind]))
        dwg.add(_text(dwg, label, w - right + 26, ky + 34))
        ky += 16
    dwg.add(dwg.line((w - right + 10, ky + 30), (w - right + 22, ky + 30), stroke="#1a9850", stroke_width=2,
                     stroke_dasharray="6,3"))
    dwg.add(_text(dwg, "Pareto front", w - right + 26, ky + 34))
    return _xml(dwg)


#: Label offsets tried in turn (right, above, below, left, further out) [px].
_LABEL_OFFSETS = ((8, 4), (8, -7), (8, 15), (-8, 4), (8, -18), (8, 26), (-8, -14), (-8, 22), (8, -30), (8, 38))
_CHAR_PX = 6.2


def _place_label(label: str, x: float, y: float, boxes: list, x_range) -> tuple[float, float, bool]:
    """First label position (text start, baseline) inside ``x_range`` overlapping no earlier box; appends it."""
    width = _CHAR_PX * len(label)
    for k, (dx, dy) in enumerate(_LABEL_OFFSETS):
        tx = x + dx if dx > 0 else x + dx - width
        box = (tx, y + dy - 10, tx + width, y + dy + 2)
        if x_range[0] <= box[0] and box[2] <= x_range[1] and not any(box[0] < b[2] and b[0] < box[2] and box[1] < b[3] and b[1] < box[3] for b in boxes):
            boxes.append(box)
            return tx, y + dy, k >= 3
    dx, dy = _LABEL_OFFSETS[0]
    boxes.append((x + dx, y + dy - 10, x + dx + width, y + dy + 2))
    return x + dx, y + dy, False


def _runs(row):
    """(start, stop, value) of each run of equal values in ``row``."""
    out, start = [], 0
    for i in range(1, len(row) + 1):
        if i == len(row) or row[i] != row[start]:
            out.append((start, i, row[start]))
            start = i
    return out


def _xml(dwg) -> str:
    return '<?xml version="1.0" encoding="utf-8" ?>\n' + dwg.tostring() + "\n"


def stability_svg(panels: dict, theta_abs_deg, row_info: dict, class_labels, *,
                  title: str = "Stability map: relative angle error per method and design") -> str:
    """Heat maps, one row of panels per method (zigzag, cross), coloured by class.

    ``panels[method][pattern]`` is a 2-D array of class indices (rows x thetas);
    ``row_info[pattern]`` is ``(row_label, row_values)``; panels are drawn in the
    order of ``panels`` and ``row_info``.
    """
    patterns = list(row_info)
    cell_w, cell_h, pw_gap, ph_gap = 9, 5, 90, 26
    n_t = len(theta_abs_deg)
    rows = {pt: len(row_info[pt][1]) for pt in patterns}
    pw = n_t * cell_w
    ph = max(rows.values()) * cell_h
    left, top = 190, 110
    w = left + len(patterns) * (pw + pw_gap) + 20
    h = top + len(panels) * (ph + ph_gap) + 60
    dwg = svgwrite.Drawing(size=(f"{w}px", f"{h}px"), profile="full", debug=False)
    dwg.add(dwg.rect((0, 0), (w, h), fill="white"))
    dwg.add(_text(dwg, title, 10, 20, font_weight="bold"))
    lx, ly = 10, 32
    for k, label in enumerate(class_labels):
        step = 16 + _CHAR_PX * len(label) + 14
        if lx + step > w:
            lx, ly = 10, ly + 18
        dwg.add(dwg.rect((lx, ly), (12, 12), fill=CLASS_COLOURS[k], stroke="black", stroke_width=0.3))
        dwg.add(_text(dwg, label, lx + 16, ly + 10))
        lx += step
    t_lo, t_hi = theta_abs_deg[0], theta_abs_deg[-1]
    for j, pt in enumerate(patterns):
        x0 = left + j * (pw + pw_gap)
        label, values = row_info[pt]
        dwg.add(_text(dwg, f"{pt}: rows {label} {values[0]:g} (top) to {values[-1]:g}", x0, top - 30))
        fx = _log_map(t_lo, t_hi, x0, x0 + pw - cell_w)
        for v in _decades(t_lo, t_hi)[::2]:
            if t_lo <= v <= t_hi:
                dwg.add(_text(dwg, f"{v:g}", fx(v) + cell_w / 2, top - 8, text_anchor="middle"))
        dwg.add(_text(dwg, "|theta| [deg] (log) ->", x0 + pw, top - 18, text_anchor="end"))
    for i, (method, by_pattern) in enumerate(panels.items()):
        y0 = top + i * (ph + ph_gap)
        dwg.add(_text(dwg, method, left - 8, y0 + ph / 2 + 4, text_anchor="end"))
        for j, pt in enumerate(patterns):
            x0 = left + j * (pw + pw_gap)
            grid = by_pattern[pt]
            for r, row in enumerate(grid):
                for c0, c1, k in _runs(row):  # one rectangle per run of equal cells keeps the file small
                    dwg.add(dwg.rect((x0 + c0 * cell_w, y0 + r * cell_h), ((c1 - c0) * cell_w, cell_h),
                                     fill=CLASS_COLOURS[int(k)]))
            dwg.add(dwg.rect((x0, y0), (pw, len(grid) * cell_h), fill="none", stroke="black", stroke_width=0.5))
    return _xml(dwg)
