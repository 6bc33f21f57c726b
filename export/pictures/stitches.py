"""Stitch preview: the plan drawn to scale in millimetres (SVG, :mod:`.svgdoc`).

The drawing's user unit is the millimetre (``viewBox`` in mm, ``width``/``height``
with ``mm`` units), so it prints at 1:1 and measures true in Inkscape.  The plan
frame has y up; SVG's y points down, so y is negated when drawing.

Layers (``<g id=...>``, bottom to top): ``fabric`` outline, ``corridor`` (tube
corridor, no needle may land there), ``tube``, ``centerline``, ``rails``,
``travel`` (jumps, dashed), ``placement`` (placement-line stitches along a tube axis,
sewn before the tube is laid, in one colour of their own), ``legs`` (thread legs coloured
by sewing order, from :data:`RAMP` start colour to end colour), ``needle-points``, ``ties``
(tie-in triangles, tie-off squares), ``stops`` and ``trims`` (labelled marks),
``scale-bar`` and ``params`` (realised parameters as text).

Examples
--------
>>> from embroact.patterns.plan import Command, Role, StitchPlan
>>> plan = StitchPlan.from_records([
...     (0, 3.5, Command.STOP, Role.CONTROL), (0, 3.5, Command.STITCH, Role.TIE_IN),
...     (1, -3.5, Command.STITCH, Role.LEG), (2, 3.5, Command.STITCH, Role.TIE_OFF),
...     (2, 3.5, Command.TRIM, Role.CONTROL), (2, 3.5, Command.END, Role.CONTROL, -1)])
>>> import xml.etree.ElementTree as ET
>>> root = ET.fromstring(plan_svg(plan))
>>> root.get("width"), root.get("viewBox")
('55.5mm', '-8 -11.5 55.5 54.8')
"""
from __future__ import annotations

import numpy as np

from ...patterns.base.errors import check_range
from ...patterns.kinds import pattern_kind
from ...patterns.plan import Command, Role, StitchPlan
from ..machine.census import COLOR_FORMATS
from .labels import Box, Placer
from .titles import text_width_px

__all__ = ["RAMP", "PLACEMENT_COLOUR", "plan_svg"]

RAMP = ((0x31, 0x36, 0x95), (0x2C, 0x7F, 0xB8), (0x41, 0xB6, 0xC4), (0xFD, 0xAE, 0x61), (0xD7, 0x30, 0x27))
"""Sewing-order colour ramp, first leg to last (blue -> red)."""

_RAMP_BINS = 24
#: Colour of placement-line stitches (outside the sewing-order ramp, which runs blue to red).
PLACEMENT_COLOUR = "#7b3294"
_FONT_MM = 2.5
_TEXT_ROW_MM = 3.6
_SCALE_CANDIDATES_MM = (1, 2, 5, 10, 20, 50, 100, 200, 500)
_CHAR_EM = 0.55  # mean glyph advance of a sans-serif font, in font sizes (to size the text area)
_FONT = "font-family:Helvetica,Arial,sans-serif"
_MARK_FONT_MM = 2.0
# stop and trim labels: beside the mark, above or below it, before the diagonals
_MARK_DIRECTIONS = ((1, -1), (1, 1), (-1, -1), (-1, 1), (0, -1), (0, 1), (1, 0), (-1, 0))
_PLACEMENT_DASH = "0.6,0.3"
STOP_COLOUR, TRIM_COLOUR, TIE_IN_COLOUR, TIE_OFF_COLOUR = "#c51b7d", "#542788", "#1a9850", "#d73027"
TRAVEL_COLOUR, CORRIDOR_COLOUR, TUBE_COLOUR, RAIL_COLOUR = "#888888", "#d9d9d9", "#b0b0b0", "#2a9d8f"
_LEGEND_FONT_MM = 2.0
_LEGEND_ROW_MM = 3.4
_LEGEND_KEY_MM = 4.0  # width of a legend entry's symbol


def _f(v: float) -> str:
    s = f"{v:.3f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _pts(xy) -> str:
    """SVG points/path coordinates, y negated, 3 decimals."""
    return " ".join(f"{_f(x)},{_f(-y)}" for x, y in np.asarray(xy, dtype=np.float64).reshape(-1, 2))


def _ramp(t: float) -> str:
    t = min(max(t, 0.0), 1.0) * (len(RAMP) - 1)
    i = min(int(t), len(RAMP) - 2)
    a, b = np.array(RAMP[i]), np.array(RAMP[i + 1])
    r, g, bl = np.rint(a + (b - a) * (t - i)).astype(int)
    return f"#{r:02x}{g:02x}{bl:02x}"


def _geom_xy(g) -> list[np.ndarray]:
    """Coordinate arrays of a shapely (multi)polygon's rings or (multi)line's parts."""
    parts = getattr(g, "geoms", [g])
    out = []
    for p in parts:
        if p.is_empty:
            continue
        if p.geom_type == "Polygon":
            out += [np.asarray(p.exterior.coords)] + [np.asarray(r.coords) for r in p.interiors]
        else:
            out.append(np.asarray(p.coords))
    return out


def _ring_path(rings: list[np.ndarray]) -> str:
    return " ".join(f"M {_pts(r)} Z" for r in rings)


def _param_lines(plan: StitchPlan, machine=None) -> list[str]:
    """The counts (a machine file's, as its writer reports them, when given; else the plan's) and the
    parameters of every segment."""
    if machine is not None:
        counts = machine.counts_text()
    else:
        n_stop, n_trim = plan.count(Command.STOP), plan.count(Command.TRIM)
        counts = (f"{plan.stitch_count} stitches, {n_stop} stop{'s' * (n_stop != 1)}, "
                  f"{n_trim} trim{'s' * (n_trim != 1)}")
    lines = [f"{plan.name}: {counts}"]
    parts = []
    for a in plan.actuators:  # one line per segment of the chain
        for name, pattern, r in [(a.segments.part_name(a.name, k), s.pattern, s.realised)
                                 for k, s in enumerate(a.segments)]:
            angle = f", alpha0 {r.angle_deg:.2f} deg" if pattern_kind(pattern).has_angle else ""
            parts.append((name, f"{pattern}: w {r.width_mm:.2f} mm, s {r.interval_mm:.3f} mm{angle}, "
                                f"l0 {r.length_mm:.1f} mm, passes {r.passes}; tube r {a.tube.outer_radius_mm:g} mm"))
    return lines + _summarised_lines(parts)


#: Segment lines the preview's text holds at most: past it, segments with the same parameters share a line
#: ("A0 (and 999 alike) zigzag: ..."), and past that the first ones are listed with a count of the rest.
PREVIEW_MAX_LINES = 20


def _summarised_lines(parts: list[tuple[str, str]]) -> list[str]:
    """``name text`` per (name, text), or past :data:`PREVIEW_MAX_LINES` one line per distinct text.

    Examples
    --------
    >>> _summarised_lines([("A1", "zigzag"), ("A2", "cross")])
    ['A1 zigzag', 'A2 cross']
    >>> _summarised_lines([(f"A{k}", "zigzag" if k % 3 else "cross") for k in range(30)])
    ['A0 (and 9 alike) cross', 'A1 (and 19 alike) zigzag']
    """
    if len(parts) <= PREVIEW_MAX_LINES:
        return [f"{name} {text}" for name, text in parts]
    groups: dict[str, list[str]] = {}
    for name, text in parts:
        groups.setdefault(text, []).append(name)
    lines = [f"{names[0]} (and {len(names) - 1} alike) {text}" if len(names) > 1 else f"{names[0]} {text}"
             for text, names in groups.items()]
    if len(lines) > PREVIEW_MAX_LINES:
        rest = sum(len(names) for names in list(groups.values())[PREVIEW_MAX_LINES:])
        lines = lines[:PREVIEW_MAX_LINES] + [f"... and {rest} more segments (worksheet.txt lists every one)"]
    return lines


def plan_svg(plan: StitchPlan, *, margin_mm: float = 5.0, point_radius_mm: float = 0.15,
             leg_width_mm: float = 0.12, show_points: bool = True, machine=None) -> str:
    """Render ``plan`` as an SVG document (a string) drawn to scale in mm.

    Parameters
    ----------
    plan : StitchPlan
        The records to draw.
    machine : WriteResult, optional
        A machine file written from ``plan`` (or read, :func:`embroact.export.machine.formats.read_result`):
        the counts are that file's, the stop marks are where it makes the machine wait (a colour
        format's colour changes, tubes laid before start named; a double stop one mark), the trim
        marks where it cuts, and the travel starts at its origin.  Default: the plan's STOP and
        TRIM records.
    margin_mm : float
        Fabric margin around the design [mm], in [0, 100].
    point_radius_mm, leg_width_mm : float
        Needle-point dot radius and thread stroke width [mm], in (0, 5].
    show_points : bool
        Draw a dot at every needle point.

    Returns
    -------
    str
        SVG, 1 user unit = 1 mm.

    Examples
    --------
    >>> from embroact.patterns.zigzag import zigzag
    >>> from embroact.patterns.params import ZigzagParams
    >>> svg = plan_svg(zigzag([[0.0, 0.0], [20.0, 0.0]], ZigzagParams(7.0, 1.0)))
    >>> svg.startswith("<svg"), 'height="51.6mm"' in svg
    (True, True)
    """
    from .svgdoc import INKSCAPE, Drawing, svg_id
    from .svgdoc import layer as inkscape_layer

    margin = check_range("margin_mm", margin_mm, low=0.0, high=100.0, low_inclusive=True, high_inclusive=True)
    pr = check_range("point_radius_mm", point_radius_mm, low=0.0, high=5.0, high_inclusive=True)
    lw = check_range("leg_width_mm", leg_width_mm, low=0.0, high=5.0, high_inclusive=True)

    corridors = [a.corridor() for a in plan.actuators]
    xy = plan.xy_mm
    boxes = [np.array(c.bounds).reshape(2, 2) for c in corridors if not c.is_empty]
    if len(xy):
        boxes.append(np.vstack([xy.min(axis=0), xy.max(axis=0)]))
    lo, hi = (np.min([b[0] for b in boxes], axis=0), np.max([b[1] for b in boxes], axis=0)) if boxes else (
        np.zeros(2), np.zeros(2))
    fab_lo, fab_hi = lo - margin, hi + margin
    texts = _param_lines(plan, machine) + _pause_lines(machine)
    pad = 3.0
    text_w = max(len(t) for t in texts) * _CHAR_EM * _FONT_MM
    width = max(fab_hi[0] - fab_lo[0], text_w) + 2 * pad
    stop_marks, trim_points = _stop_marks(plan, machine), _trim_points(plan, machine)
    entries = _legend_entries(plan, bool(stop_marks), bool(len(trim_points)))
    legend_rows = _legend_rows(entries, max(fab_hi[0] - fab_lo[0], text_w))
    text_h = _TEXT_ROW_MM * (len(texts) + 2) + 4.0 + len(legend_rows) * _LEGEND_ROW_MM
    height = (fab_hi[1] - fab_lo[1]) + 2 * pad + text_h
    vx, vy = fab_lo[0] - pad, -fab_hi[1] - pad
    dwg = Drawing(size=(f"{_f(width)}mm", f"{_f(height)}mm"), viewBox=f"{_f(vx)} {_f(vy)} {_f(width)} {_f(height)}",
                  **INKSCAPE)
    dwg.add(dwg.rect((_f(vx), _f(vy)), (_f(width), _f(height)), fill="white", id="background"))
    layer = {name: dwg.add(dwg.g(**inkscape_layer(name))) for name in (
        "fabric", "corridor", "tube", "centerline", "rails", "travel", "placement", "legs", "needle-points", "ties",
        "stops",
        "trims", "scale-bar", "params", "legend")}
    layer["fabric"].add(dwg.rect((_f(fab_lo[0]), _f(-fab_hi[1])), (_f(fab_hi[0] - fab_lo[0]), _f(fab_hi[1] - fab_lo[1])),
                                 fill="#f6f1e7", stroke="#9c8f78", stroke_width="0.3"))
    for a, corr in zip(plan.actuators, corridors):
        layer["corridor"].add(dwg.path(d=_ring_path(_geom_xy(corr)), fill=CORRIDOR_COLOUR, fill_opacity="0.6", stroke="none"))
        tube = a.centerline.as_linestring().buffer(a.tube.outer_radius_mm, cap_style="flat")
        layer["tube"].add(dwg.path(d=_ring_path(_geom_xy(tube)), fill=TUBE_COLOUR, stroke="#707070", stroke_width="0.1"))
        layer["centerline"].add(dwg.polyline(_pts_list(a.centerline.points_mm), fill="none", stroke="#505050",
                                             stroke_width="0.1", stroke_dasharray="1,0.6", id=svg_id(f"tube-{a.name}"),
                                             **{"inkscape:label": f"tube-{a.name}"}))
        for rail in a.rails():
            layer["rails"].add(dwg.polyline(_pts_list(np.asarray(rail.coords)), fill="none", stroke=RAIL_COLOUR,
                                            stroke_width="0.1", stroke_dasharray="0.4,0.4"))
    placer = Placer(Box(fab_lo[0], -fab_hi[1], fab_hi[0], -fab_lo[1]), margin=0.2)
    _draw_records(dwg, layer, plan, pr, lw, show_points, machine, placer)
    _draw_marks(dwg, layer, placer, stop_marks, trim_points)
    y_text = -fab_lo[1] + pad + 2.0
    _draw_scale_and_text(dwg, layer, texts, fab_lo[0], y_text, fab_hi[0] - fab_lo[0])
    _draw_legend(dwg, layer["legend"], entries, fab_lo[0], y_text + 1.0 + (len(texts) + 1) * _TEXT_ROW_MM, width - 2 * pad)
    for g in layer.values():
        _hoist_style(g)
    return dwg.tostring()


#: Inherited presentation attributes a layer of many elements carries once for them all (see _hoist_style).
_INHERITED = ("fill", "fill-opacity", "stroke", "stroke-width", "stroke-dasharray", "stroke-linecap")
#: Children a layer needs before their shared style moves to it (a few marks keep theirs, as drawn).
_HOIST_MIN = 20


def _hoist_style(group) -> None:
    """Move each inherited attribute every child of ``group`` sets to the same value onto ``group`` (where it has
    at least ``_HOIST_MIN`` children): the drawing is the same (SVG inherits these), the file holds it once.

    Examples
    --------
    >>> from .svgdoc import Drawing
    >>> dwg = Drawing(size=("10mm", "10mm"))
    >>> g = dwg.g()
    >>> for k in range(_HOIST_MIN):
    ...     _ = g.add(dwg.circle((k, 0), 1, fill="red", stroke="blue" if k else "black"))
    >>> _hoist_style(g)
    >>> g.attribs.get("fill"), g.elements[0].attribs.get("fill"), g.elements[0].attribs.get("stroke"), g.attribs.get("stroke")
    ('red', None, 'black', None)
    """
    children = group.elements  # svgdoc's and svgwrite's names (tests/test_svgdoc.py draws with both)
    if len(children) < _HOIST_MIN:
        return
    for name in _INHERITED:
        value = children[0].attribs.get(name)
        if value is None or name in group.attribs or any(c.attribs.get(name) != value for c in children):
            continue
        group.update({name: value})
        for c in children:
            del c.attribs[name]


def _pts_list(xy) -> list[tuple[str, str]]:
    return [(_f(x), _f(-y)) for x, y in np.asarray(xy, dtype=np.float64).reshape(-1, 2)]


def _segments_d(xy, starts) -> str:
    """Path data of the segments from each record in ``starts`` (ascending) to the next one; a segment starting
    where the one before ends continues its line (``M a L b c``: an implied line-to per further point).

    Examples
    --------
    >>> _segments_d(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [5.0, 5.0], [6.0, 5.0]]), [0, 1, 3])
    'M 0,0 L 1,0 1,-1 M 5,-5 L 6,-5'
    """
    out: list[str] = []
    last = None
    for i in (int(k) for k in starts):
        out.append(f" {_pts(xy[i + 1])}" if i - 1 == last else f"{' ' if out else ''}M {_pts(xy[i])} L {_pts(xy[i + 1])}")
        last = i
    return "".join(out)


def _pause_lines(machine) -> list[str]:
    if machine is None:
        return []
    kind = "colour changes: no stop code" if machine.format in COLOR_FORMATS else "stop codes"
    return [f"stops: where the {machine.format.upper()} file makes the machine wait ({kind})"]


def _trim_points(plan: StitchPlan, machine) -> np.ndarray:
    """Where each trim cuts (plan frame, mm): the machine file's trims, or the plan's TRIM records."""
    if machine is None:
        return plan.xy_mm[plan.commands == Command.TRIM]
    return np.array(machine.trims_mm, dtype=np.float64).reshape(-1, 2)


def _stop_marks(plan: StitchPlan, machine) -> list[tuple[np.ndarray, str]]:
    """(where, label) of every stop mark: the plan's STOP records, or the machine file's pauses."""
    names = {k: a.name for k, a in enumerate(plan.actuators)}
    stops = np.flatnonzero(plan.commands == Command.STOP)
    if machine is None:
        return [(plan.xy_mm[i], f"STOP {n}: lay tube {names.get(int(plan.actuator[i]), f'A{int(plan.actuator[i]) + 1}')}")
                for n, i in enumerate(stops, start=1)]
    ids = sorted({int(a) for a in plan.actuator.tolist() if a >= 0})
    tube = machine.tube_pauses()
    before = len(ids) - sum(tube)
    word = "PAUSE" if machine.format in COLOR_FORMATS else "STOP"
    first = {int(plan.actuator[i]): plan.xy_mm[i]  # a tube's first stop, else its first stitch (a file's)
             for i in np.flatnonzero(plan.commands == Command.STITCH)[::-1]}
    first.update({int(plan.actuator[i]): plan.xy_mm[i] for i in stops[::-1]})
    marks = [(first.get(k, plan.xy_mm[0]), f"before start: lay tube {names.get(k, f'A{k + 1}')}")
             for k in ids[:before]]
    later = iter(ids[before:])
    records = tuple(machine.pause_stops) + (1,) * (len(machine.pauses_mm) - len(machine.pause_stops))
    for n, (p, is_tube, k_stops) in enumerate(zip(machine.pauses_mm, tube, records), start=1):
        what = f"lay tube {names.get(k, f'A{k + 1}')}" if is_tube and (k := next(later, None)) is not None \
            else "press start"
        double = f" ({k_stops} stop records: one double stop)" if k_stops > 1 else ""
        marks.append((np.asarray(p, dtype=np.float64), f"{word} {n}: {what}{double}"))
    return marks


def _draw_records(dwg, layer, plan: StitchPlan, pr: float, lw: float, show_points: bool, machine,
                  placer: Placer) -> None:
    """Placement lines, legs, travel, needle points and ties; the legs' segments blocked for the labels."""
    cmds, xy = plan.commands, plan.xy_mm
    stitch = cmds == Command.STITCH
    # legs: consecutive STITCH records, binned by sewing order into one path per colour; the stitches of a
    # placement line (sewn along the tube axis before the tube is laid) are drawn apart, in their own colour
    joined = stitch[1:] & stitch[:-1]
    placed = joined & (plan.roles[1:] == Role.PLACEMENT)
    if placed.any():
        d = _segments_d(xy, np.flatnonzero(placed))
        layer["placement"].add(dwg.path(d=d, fill="none", stroke=PLACEMENT_COLOUR, stroke_width=_f(2.5 * lw),
                                        stroke_dasharray=_PLACEMENT_DASH, stroke_linecap="butt"))
    legs = np.flatnonzero(joined & ~placed)
    if len(legs):
        bins = np.minimum((np.arange(len(legs)) * _RAMP_BINS) // len(legs), _RAMP_BINS - 1)
        for b in range(_RAMP_BINS):
            sel = legs[bins == b]
            if len(sel) == 0:
                continue
            d = _segments_d(xy, sel)
            layer["legs"].add(dwg.path(d=d, fill="none", stroke=_ramp(b / max(_RAMP_BINS - 1, 1)),
                                       stroke_width=_f(lw), stroke_linecap="round"))
    # travel: from the previous record to every JUMP/STOP that moves
    moves = 1 + np.flatnonzero(np.isin(cmds[1:], (Command.JUMP, Command.STOP)) & np.any(xy[1:] != xy[:-1], axis=1))
    origin = np.asarray(getattr(machine, "origin_mm", (0.0, 0.0)), dtype=np.float64)
    lead = f"M {_pts(origin)} L {_pts(xy[0])} " if len(xy) and np.any(np.abs(xy[0] - origin) > 0.05) else ""
    if len(moves) or lead:  # the frame's move from the machine's start point (the origin) to the first record too
        d = lead + _segments_d(xy, moves - 1)
        layer["travel"].add(dwg.path(d=d, fill="none", stroke=TRAVEL_COLOUR, stroke_width="0.15",
                                     stroke_dasharray="0.8,0.5"))
    if show_points:  # the dots' fill set once, on their layer
        layer["needle-points"].update({"fill": "#111111"})
        for x, y in xy[stitch]:
            layer["needle-points"].add(dwg.circle((_f(x), _f(-y)), _f(pr)))
    s = 0.5
    for i in np.flatnonzero(stitch & (plan.roles == Role.TIE_IN)):
        x, y = xy[i]
        layer["ties"].add(dwg.polygon([(_f(x), _f(-y - s)), (_f(x - s), _f(-y + s)), (_f(x + s), _f(-y + s))],
                                      fill="none", stroke=TIE_IN_COLOUR, stroke_width="0.12", **{"class": "tie-in"}))
    for i in np.flatnonzero(stitch & (plan.roles == Role.TIE_OFF)):
        x, y = xy[i]
        layer["ties"].add(dwg.rect((_f(x - s / 2), _f(-y - s / 2)), (_f(s), _f(s)), fill="none", stroke=TIE_OFF_COLOUR,
                                   stroke_width="0.12", **{"class": "tie-off"}))
    pts = np.column_stack([xy[:, 0], -xy[:, 1]])
    placer.block_segments(np.hstack([pts[legs], pts[legs + 1]]))


def _draw_marks(dwg, layer, placer: Placer, stop_marks, trim_points: np.ndarray) -> None:
    """Stop circles and trim crosses, each labelled clear of the stitches, the marks and the other labels."""
    stops = [(float(p[0]), -float(p[1]), label) for p, label in stop_marks]
    trims = np.column_stack([trim_points[:, 0], -trim_points[:, 1]]) if len(trim_points) else np.zeros((0, 2))
    for x, y, _ in stops:
        placer.block_box(Box(x - 1.2, y - 1.2, x + 1.2, y + 1.2))
    for x, y in trims:
        placer.block_box(Box(x - 0.8, y - 0.8, x + 0.8, y + 0.8))
    for x, y, label in stops:
        g = layer["stops"].add(dwg.g(**{"class": "before-start" if label.startswith("before") else "stop"}))
        g.add(dwg.circle((_f(x), _f(y)), "1.2", fill="none", stroke=STOP_COLOUR, stroke_width="0.25"))
        _label(dwg, g, placer, label, (x, y), 1.6, STOP_COLOUR)
    for n, (x, y) in enumerate(trims, start=1):
        g = layer["trims"].add(dwg.g(**{"class": "trim"}))
        g.add(dwg.path(d=_cross_d(x, y, 0.8), stroke=TRIM_COLOUR, stroke_width="0.25", fill="none"))
        _label(dwg, g, placer, f"TRIM {n}", (x, y), 1.2, TRIM_COLOUR)


def _cross_d(x: float, y: float, c: float) -> str:
    """Path data of an x-shaped cross of half size ``c`` at SVG point (x, y)."""
    return f"M {_f(x - c)},{_f(y - c)} L {_f(x + c)},{_f(y + c)} M {_f(x - c)},{_f(y + c)} L {_f(x + c)},{_f(y - c)}"


def _label(dwg, g, placer: Placer, text: str, at, gap: float, colour: str) -> None:
    lab = placer.place(text, at, _MARK_FONT_MM, gap=gap, directions=_MARK_DIRECTIONS)
    g.add(dwg.text(text, insert=(_f(lab.x), _f(lab.y)), font_size=_f(_MARK_FONT_MM), fill=colour, style=_FONT,
                   text_anchor=lab.anchor))


def _draw_scale_and_text(dwg, layer, texts: list[str], x0: float, y0: float, avail: float) -> None:
    bar = max([c for c in _SCALE_CANDIDATES_MM if c <= max(avail * 0.4, 1)] or [1])
    g = layer["scale-bar"]
    g.add(dwg.rect((_f(x0), _f(y0)), (_f(bar), "0.8"), fill="#000000"))
    g.add(dwg.text(f"{bar} mm", insert=(_f(x0 + bar + 1.0), _f(y0 + 0.9)), font_size=_f(_FONT_MM), style=_FONT))
    for n, line in enumerate(texts, start=1):
        layer["params"].add(dwg.text(line, insert=(_f(x0), _f(y0 + 1.0 + n * _TEXT_ROW_MM)), font_size=_f(_FONT_MM),
                                     style=_FONT))


def _legend_entries(plan: StitchPlan, stops: bool, trims: bool) -> list[str]:
    """The legend's entries: every kind of mark this preview draws (``stops``, ``trims``: any stop, trim mark)."""
    cmds, roles = plan.commands, plan.roles
    stitch = cmds == Command.STITCH
    out = ["ramp", "corridor", "tube", "rails"]
    if (stitch & (roles == Role.PLACEMENT)).any():
        out.append("placement")
    out += [name for name, present in (
        ("tie-in", (stitch & (roles == Role.TIE_IN)).any()), ("tie-off", (stitch & (roles == Role.TIE_OFF)).any()),
        ("travel", bool(np.isin(cmds, (Command.JUMP, Command.STOP)).any())), ("stop", stops),
        ("trim", trims)) if present]
    return out


_LEGEND_TEXT = {
    "ramp": "legs in sewing order: first to last", "corridor": "tube corridor (no needle)", "tube": "tube",
    "rails": "rails (leg ends)", "placement": "placement line (sewn before the tube)", "tie-in": "tie-in",
    "tie-off": "tie-off", "travel": "travel (jump)", "stop": "stop: lay the tube", "trim": "trim",
}


def _entry_mm(name: str) -> float:
    return _LEGEND_KEY_MM + 1.0 + text_width_px(_LEGEND_TEXT[name], _LEGEND_FONT_MM) + 3.0


def _legend_rows(entries: list[str], width_mm: float) -> list[list[str]]:
    """Entries flowed into rows no wider than ``width_mm``."""
    rows: list[list[str]] = [[]]
    used = 0.0
    for name in entries:
        w = _entry_mm(name)
        if rows[-1] and used + w > width_mm:
            rows.append([])
            used = 0.0
        rows[-1].append(name)
        used += w
    return rows


def _draw_key(dwg, g, name: str, x: float, y: float) -> None:
    """The symbol of legend entry ``name``, ``_LEGEND_KEY_MM`` wide, centred on height ``y``."""
    k = _LEGEND_KEY_MM
    if name == "ramp":
        for j in range(len(RAMP)):
            g.add(dwg.rect((_f(x + j * k / len(RAMP)), _f(y - 0.5)), (_f(k / len(RAMP)), "1"), fill=_ramp(j / (len(RAMP) - 1))))
    elif name in ("corridor", "tube"):
        g.add(dwg.rect((_f(x), _f(y - 0.9)), (_f(k), "1.8"), fill=CORRIDOR_COLOUR if name == "corridor" else TUBE_COLOUR,
                       stroke="#707070" if name == "tube" else "none", stroke_width="0.1"))
    elif name in ("rails", "travel", "placement"):
        style = {"rails": (RAIL_COLOUR, "0.1", "0.4,0.4"), "travel": (TRAVEL_COLOUR, "0.15", "0.8,0.5"),
                 "placement": (PLACEMENT_COLOUR, "0.3", _PLACEMENT_DASH)}[name]
        g.add(dwg.line((_f(x), _f(y)), (_f(x + k), _f(y)), stroke=style[0], stroke_width=style[1],
                       stroke_dasharray=style[2]))
    elif name == "tie-in":
        g.add(dwg.polygon([(_f(x + k / 2), _f(y - 0.5)), (_f(x + k / 2 - 0.5), _f(y + 0.5)), (_f(x + k / 2 + 0.5), _f(y + 0.5))],
                          fill="none", stroke=TIE_IN_COLOUR, stroke_width="0.12"))
    elif name == "tie-off":
        g.add(dwg.rect((_f(x + k / 2 - 0.25), _f(y - 0.25)), ("0.5", "0.5"), fill="none", stroke=TIE_OFF_COLOUR,
                       stroke_width="0.12"))
    elif name == "stop":
        g.add(dwg.circle((_f(x + k / 2), _f(y)), "1", fill="none", stroke=STOP_COLOUR, stroke_width="0.25"))
    else:  # trim
        g.add(dwg.path(d=_cross_d(x + k / 2, y, 0.7), stroke=TRIM_COLOUR, stroke_width="0.25", fill="none"))


def _draw_legend(dwg, g, entries: list[str], x0: float, y0: float, width_mm: float) -> None:
    """The legend rows from ``y0`` (the first row's baseline) down."""
    for r, row in enumerate(_legend_rows(entries, width_mm)):
        x, y = x0, y0 + r * _LEGEND_ROW_MM
        for name in row:
            _draw_key(dwg, g, name, x, y - 0.6)
            g.add(dwg.text(_LEGEND_TEXT[name], insert=(_f(x + _LEGEND_KEY_MM + 1.0), _f(y)),
                           font_size=_f(_LEGEND_FONT_MM), style=_FONT))
            x += _entry_mm(name)
