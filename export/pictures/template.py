"""Layout template: a printable 1:1 drawing of where each tube goes on the hooped fabric (SVG).

The operator prints it at actual size (100 %, no "fit to page"), lays it on the hooped
fabric (or tapes it under a thin one) and lays each tube along its drawing.  The user unit
is the millimetre: ``viewBox`` in mm and ``width``/``height`` in ``mm``, so one unit prints
as one millimetre; the 10 mm scale bar checks the print.  Plan frame (y up), drawn with y
negated, so the template shows the fabric as the machine sees it from above.

Layers (``<g id=...>``): ``hoop`` (the sewing field, machine.hoop_width_mm x
hoop_height_mm, centred on the design as the hoop rule EA306 centres it, with ``centre``
marks: a cross at its centre and ticks at the middle of each side), ``start`` (the machine's
start point), ``tubes`` (per actuator a group with its ``axis``, the embroidered stretch
outlined at the tube's diameter, the ``free-end`` margins of ``end_margin_mm`` along the end
tangents dashed, the ``connector`` end marked, the far end marked sealed, the sewing order and name),
``scale-bar`` and ``notes``.

Examples
--------
>>> import xml.etree.ElementTree as ET
>>> from embroact.patterns.centerline import Centerline
>>> from embroact.patterns.params import ZigzagParams
>>> from embroact.patterns.zigzag import zigzag
>>> svg = template_svg(zigzag(Centerline.straight(100.0), ZigzagParams(7.0, 1.0), name="A1"))
>>> root = ET.fromstring(svg)
>>> root.get("width"), root.get("height"), root.get("viewBox")   # the 200 x 200 mm hoop and its border
('210mm', '237.6mm', '-55 -105 210 237.6')
>>> [e.get("points") for e in root.iter("{http://www.w3.org/2000/svg}polyline") if e.get("class") == "axis"]
['0,0 100,0']
"""
from __future__ import annotations

import numpy as np

from ...patterns.plan import StitchPlan
from ...patterns.rules.tubes import hoop_centre_mm
from .labels import Box, Placer
from .stitches import _f, _pts_list

__all__ = ["template_svg", "start_from_centre", "SCALE_BAR_MM"]

SCALE_BAR_MM = 10.0
"""Length of the scale bar that checks the print [mm]."""
_BORDER_MM = 5.0
_FONT_MM = 3.0
_ROW_MM = 4.4
_TICK_MM = 6.0
_FONT = "font-family:Helvetica,Arial,sans-serif"
_INK = "#000000"
_TUBE = "#1f4e9a"
_DEFAULT_HOOP_MM = (200.0, 200.0)


def _unit(v: np.ndarray) -> np.ndarray:
    return v / float(np.hypot(v[0], v[1]))


def _laid(act) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The tube's path and its two free ends (start margin, end margin) as point arrays [mm]."""
    pts = act.centerline.points_mm
    m = act.tube.end_margin_mm
    head = pts[0] + m * _unit(pts[0] - pts[1])
    tail = pts[-1] + m * _unit(pts[-1] - pts[-2])
    return pts, np.vstack([head, pts[0]]), np.vstack([pts[-1], tail])


def start_from_centre(plan: StitchPlan) -> str:
    """Where the machine's start point lies from the hoop centre (the hoop centred on the records and the start point).

    Parameters
    ----------
    plan : StitchPlan
        A plan in the machine's frame (the start point at (0, 0)).

    Returns
    -------
    str
        ``"<x> mm right|left, <y> mm up|down"``.

    Examples
    --------
    >>> import dataclasses
    >>> from embroact.patterns.design import build_plan, default_design
    >>> start_from_centre(build_plan(default_design()))  # the default origin: the design's centre
    '0.0 mm right, 0.0 mm up'
    >>> d = default_design()
    >>> start_from_centre(build_plan(dataclasses.replace(d, machine=dataclasses.replace(d.machine, origin="first-stitch"))))
    '50.0 mm left, 3.5 mm up'
    """
    dx, dy = -hoop_centre_mm(plan.xy_mm, plan.commands) + 0.0
    return f"{abs(dx):.1f} mm {'right' if dx >= 0 else 'left'}, {abs(dy):.1f} mm {'up' if dy >= 0 else 'down'}"


def _hoop_box(plan: StitchPlan, hoop_mm: tuple[float, float]) -> tuple[np.ndarray, np.ndarray]:
    """The hoop's sewing field centred on the records' bounding box (as EA306 places it)."""
    centre = hoop_centre_mm(plan.xy_mm, plan.commands)
    half = np.array(hoop_mm, dtype=np.float64) / 2.0
    return centre - half, centre + half


def template_svg(plan: StitchPlan, machine=None) -> str:
    """Render the 1:1 layout template of ``plan`` (see the module docstring) as an SVG string.

    Parameters
    ----------
    plan : StitchPlan
        The design's plan, in the machine's frame.
    machine : MachineSettings, optional
        Its ``hoop_width_mm`` x ``hoop_height_mm`` is the hoop drawn (default 200 x 200 mm).

    Returns
    -------
    str
        SVG in mm, 1:1, in Inkscape layers (tube axes ``tube-NAME``).

    Examples
    --------
    >>> from embroact.patterns.design import build_plan, default_design
    >>> svg = template_svg(build_plan(default_design()))
    >>> 'id="tube-A1"' in svg, 'inkscape:label="hoop"' in svg
    (True, True)
    """
    from .svgdoc import INKSCAPE, Drawing
    from .svgdoc import layer as inkscape_layer

    hoop = (getattr(machine, "hoop_width_mm", _DEFAULT_HOOP_MM[0]), getattr(machine, "hoop_height_mm",
                                                                          _DEFAULT_HOOP_MM[1]))
    h_lo, h_hi = _hoop_box(plan, hoop)
    laid = [_laid(a) for a in plan.actuators]
    every = np.vstack([h_lo, h_hi, np.zeros(2)] + [np.vstack(parts) for parts in laid])
    lo, hi = every.min(axis=0) - _BORDER_MM, every.max(axis=0) + _BORDER_MM
    notes = [f"{plan.name}: layout template, print at actual size (100 %, no scaling)",
             f"hoop field {hoop[0]:g} x {hoop[1]:g} mm; the bar above must measure {SCALE_BAR_MM:g} mm",
             "outlined: the embroidered stretch of each tube (numbered in sewing order); shaded: its free ends"]
    text_h = _ROW_MM * (len(notes) + 1) + 2 * _BORDER_MM
    width, height = hi[0] - lo[0], hi[1] - lo[1] + text_h
    vx, vy = lo[0], -hi[1]
    dwg = Drawing(size=(f"{_f(width)}mm", f"{_f(height)}mm"),
                  viewBox=f"{_f(vx)} {_f(vy)} {_f(width)} {_f(height)}", **INKSCAPE)
    dwg.add(dwg.rect((_f(vx), _f(vy)), (_f(width), _f(height)), fill="white", id="background"))
    layer = {name: dwg.add(dwg.g(**inkscape_layer(name))) for name in ("hoop", "start", "tubes", "scale-bar", "notes")}
    _draw_hoop(dwg, layer["hoop"], h_lo, h_hi)
    placer = Placer(Box(vx, vy, vx + width, vy + height - text_h), margin=0.3)
    for a, parts in zip(plan.actuators, laid):  # every tube and its free ends first: no label is written over one
        for part in parts:  # the axis and the two free ends
            placer.block_polyline(np.column_stack([part[:, 0], -part[:, 1]]))
    _cross(dwg, layer["start"], np.zeros(2), 3.0, "#c51b7d", f"start: {start_from_centre(plan)} of the hoop centre", placer)
    for k, (a, parts) in enumerate(zip(plan.actuators, laid)):
        _draw_tube(dwg, layer["tubes"], a, parts, k, placer)
    x0, y0 = lo[0] + _BORDER_MM, -lo[1] + _BORDER_MM
    g = layer["scale-bar"]
    g.add(dwg.rect((_f(x0), _f(y0)), (_f(SCALE_BAR_MM), "1"), fill=_INK, id="scale-bar-10mm"))
    g.add(dwg.text(f"{SCALE_BAR_MM:g} mm", insert=(_f(x0 + SCALE_BAR_MM + 1.5), _f(y0 + 1.1)),
                   font_size=_f(_FONT_MM), style=_FONT))
    for n, line in enumerate(notes, start=1):
        layer["notes"].add(dwg.text(line, insert=(_f(x0), _f(y0 + 1.0 + n * _ROW_MM)), font_size=_f(_FONT_MM),
                                    style=_FONT))
    return dwg.tostring()


def _cross(dwg, group, p: np.ndarray, size: float, colour: str, label: str, placer: Placer) -> None:
    x, y = p
    g = group.add(dwg.g(**{"class": "mark"}))
    g.add(dwg.path(d=f"M {_f(x - size)},{_f(-y - size)} L {_f(x + size)},{_f(-y + size)} "
                     f"M {_f(x - size)},{_f(-y + size)} L {_f(x + size)},{_f(-y - size)}",
                   stroke=colour, stroke_width="0.3", fill="none"))
    placer.block_box(Box(x - size, -y - size, x + size, -y + size))
    _text(dwg, g, placer, label, (x, -y), size + 0.8, _FONT_MM * 0.8, fill=colour)


def _text(dwg, g, placer: Placer, text: str, at, gap: float, font_mm: float, **extra) -> None:
    """``text`` placed near SVG point ``at``, clear of the tubes and the labels placed before."""
    lab = placer.place(text, at, font_mm, gap=gap)
    g.add(dwg.text(text, insert=(_f(lab.x), _f(lab.y)), font_size=_f(font_mm), style=_FONT, text_anchor=lab.anchor,
                   **extra))


def _draw_hoop(dwg, group, lo: np.ndarray, hi: np.ndarray) -> None:
    size = hi - lo
    group.add(dwg.rect((_f(lo[0]), _f(-hi[1])), (_f(size[0]), _f(size[1])), fill="none", stroke="#555555",
                       stroke_width="0.4", stroke_dasharray="4,2", **{"class": "hoop-field"}))
    c = (lo + hi) / 2.0
    marks = group.add(dwg.g(id="centre", stroke=_INK, stroke_width="0.3", fill="none"))
    marks.add(dwg.path(d=f"M {_f(c[0] - _TICK_MM)},{_f(-c[1])} H {_f(c[0] + _TICK_MM)} "
                         f"M {_f(c[0])},{_f(-c[1] - _TICK_MM)} V {_f(-c[1] + _TICK_MM)}", **{"class": "centre-cross"}))
    t = _TICK_MM
    ticks = (f"M {_f(c[0])},{_f(-hi[1])} v {_f(t)} M {_f(c[0])},{_f(-lo[1])} v {_f(-t)} "
             f"M {_f(lo[0])},{_f(-c[1])} h {_f(t)} M {_f(hi[0])},{_f(-c[1])} h {_f(-t)}")
    marks.add(dwg.path(d=ticks, **{"class": "centre-ticks"}))


def _draw_tube(dwg, group, act, parts, k: int, placer: Placer) -> None:
    from .svgdoc import svg_id

    pts, head, tail = parts
    r = act.tube.outer_radius_mm
    g = group.add(dwg.g(id=f"tube-{k + 1}", **{"class": "tube"}))
    g.set_desc(title=f"tube of {act.name}")
    outline = act.centerline.as_linestring().buffer(r, cap_style="flat")
    ring = np.asarray(outline.exterior.coords) if outline.geom_type == "Polygon" else None
    if ring is not None:
        g.add(dwg.polygon(_pts_list(ring), fill="none", stroke=_TUBE, stroke_width="0.35", **{"class": "tube-outline"}))
    g.add(dwg.polyline(_pts_list(pts), fill="none", stroke=_TUBE, stroke_width="0.25", id=svg_id(f"tube-{act.name}"),
                       **{"class": "axis", "inkscape:label": f"tube-{act.name}"}))  # template.svg#tube-NAME reads it back
    for end in (head, tail):
        g.add(dwg.polyline(_pts_list(end), fill="none", stroke=_TUBE, stroke_width=_f(2 * r), stroke_opacity="0.25",
                           stroke_dasharray="3,1.5", **{"class": "free-end"}))
    for label, p in (("connector", head[0]), ("sealed", tail[1])):
        g.add(dwg.circle((_f(p[0]), _f(-p[1])), _f(r), fill="none", stroke=_INK, stroke_width="0.3",
                         **{"class": f"{label}-end"}))
        placer.block_box(Box(p[0] - r, -p[1] - r, p[0] + r, -p[1] + r))
        _text(dwg, g, placer, label, (p[0], -p[1]), r + 1.0, _FONT_MM * 0.8)
    _text(dwg, g, placer, f"{k + 1}: {act.name}", (pts[0][0], -pts[0][1]), r + 2.0, _FONT_MM * 1.2, fill=_TUBE,
          **{"class": "name"})
