"""Bent-shape side view (SVG): strip and tube at several pressures, as the paper photographs them.

The top end is clamped, the strip hangs down, the lower end is free.  The model bends
the fabric side (length ``l0``) into a circular arc of total angle ``theta``, curvature
``kappa = theta / l0`` (uniform along the strip).  Seen from the side, the thread side
(tube side) faces +x at the clamp; positive ``theta`` bends toward the back of the
fabric, i.e. toward -x, with the tube on the outside of the bend::

      ##  clamp
      |o
      |o      theta > 0: curls to the left (toward the fabric's back)
       \\o
         `--o

With the clamp at the origin, x across, z up, arc length s along the fabric line:

    x(s) = (cos(kappa s) - 1) / kappa,    z(s) = -sin(kappa s) / kappa

and a line at distance ``o`` on the thread side is ``(x, z) + o * (cos(kappa s), -sin(kappa s))``.
The lines come from :class:`embroact.predict.shape.BentShape` (the one bent-shape
kinematics, shared with the 3D mesh): every panel is a chain of arcs
(``SidePanel.segment_lengths_mm`` / ``segment_theta_deg``), each piece bending by its own angle;
an actuator's pieces are its unbent lead-in, each segment's legs with the transitions between
them, and its tail, for a chain of one segment as for five.

Examples
--------
>>> from embroact.export.pictures.sideview import SidePanel, bent_line_mm, side_view_svg
>>> pts = bent_line_mm(100.0, 180.0, 0.0)
>>> [round(float(v), 3) for v in pts[-1]]   # half a turn: back up beside the clamp
[-63.662, 0.0]
>>> panel = SidePanel("w = 7 mm", length_mm=100.0, r0_mm=2.58,
...                   pressure_kpa=[0.0, 150.0], theta_deg=[0.0, 40.0])
>>> side_view_svg([panel]).startswith('<svg')
True
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ...patterns.base.errors import ParameterError, check_range
from ...patterns.base.tolerances import DEFAULT_TOLERANCES
from ...patterns.params import FABRIC_THICKNESS_MM
from ...predict.shape import BentShape
from .chart import PALETTE
from .labels import Box, Placer, text_box

__all__ = ["SidePanel", "bent_line_mm", "shape_line_mm", "side_view_svg", "PX_PER_MM", "SIDE_VIEW_MAX_PANELS"]

#: Scale of the drawings in mm (side views, shape overlays) [px per mm].
PX_PER_MM = 3.0
#: Most actuators a side view draws, side by side (a wider drawing shows nothing more on a screen, and its
#: size and time grew with the design: 1000 panels were 13 MB and a fifth of the build); :func:`side_view_svg`
#: draws the first ones and says so in its title, for every caller (build, report, preview, studio). The
#: report keeps every actuator's side-view states.
SIDE_VIEW_MAX_PANELS = 24
_PANEL_GAP_MM = 24.0
_MARGIN_MM = 8.0
_LEGEND_ROW_MM = 6.0
_LEGEND_WIDTH_MM = 50.0
_FONT = "font-family:Helvetica,Arial,sans-serif"
_PANEL_FONT_MM = 4.5
_LEGEND_FONT_MM = 3.6
_TIP_FONT_MM = 3.5
_SIDE_FONT_MM = 3.0
_SIDE_GAP_MM = 0.8  # between the clamp and a face name
_NOTE_FONT_MM = 3.2
_FRAME_INSET_MM = 1.5  # labels keep this far from the picture's edges
_SAME_TIP_MM = 1.5  # tips closer than this get one label ("1,2")


@dataclass(frozen=True, slots=True)
class SidePanel:
    """One actuator's bent shapes at several pressures.

    Parameters
    ----------
    label : str
        Panel title.
    length_mm : float
        Fabric-side length l0 [mm], > 0.
    r0_mm : float
        Sleeve radius r0 [mm] (the tube is drawn with diameter 2 r0 on the thread side), > 0.
    pressure_kpa, theta_deg : array-like
        Pressures [kPa] and the predicted bend angles there [deg]; NaN angles are skipped, a
        NaN pressure (a shape not tied to one) is left out of the legend.
    segment_lengths_mm : array-like, optional
        The fabric line as pieces from the clamp, each bent uniformly [mm] (adding up to
        ``length_mm``): an actuator's :meth:`~embroact.predict.analysis.ActuatorAnalysis.bend_pieces`,
        whatever its chain's length. Empty (default): one piece over ``length_mm``; the panel then
        holds that one piece (``segment_lengths_mm == (length_mm,)``).
    segment_theta_deg : array-like, optional
        With ``segment_lengths_mm``: one row per pressure, the bend of each piece [deg]
        (``theta_deg`` is then their sum, the total bend); without it, ``theta_deg`` itself.
    marks_mm : array-like, optional
        Arc lengths along the fabric line [mm] marked (open circles on the tube) in every
        state, e.g. where one segment of a segmented actuator gives way to the next.
    note : str, optional
        One line written under the legend (``class="not-drawn"``), e.g. the states left out and why
        (:func:`~embroact.export.pictures.previews.not_drawn_note`); "" (default): none.

    Examples
    --------
    >>> panel = SidePanel("A1", 100.0, 2.58, [100.0, 300.0], [11.5, 90.0])
    >>> panel.label, panel.shape(1).profile_mm([100.0]).round(3).tolist()
    ('A1', [[63.662, 63.662]])
    """

    label: str
    length_mm: float
    r0_mm: float
    pressure_kpa: tuple[float, ...]
    theta_deg: tuple[float, ...]
    segment_lengths_mm: tuple[float, ...] = ()
    segment_theta_deg: tuple[tuple[float, ...], ...] = ()
    marks_mm: tuple[float, ...] = ()
    note: str = ""

    def __post_init__(self) -> None:
        check_range("length_mm", self.length_mm, low=0.0)
        check_range("r0_mm", self.r0_mm, low=0.0)
        p = tuple(float(v) for v in np.asarray(self.pressure_kpa, dtype=np.float64).reshape(-1))
        t = tuple(float(v) for v in np.asarray(self.theta_deg, dtype=np.float64).reshape(-1))
        if len(p) != len(t):
            raise ParameterError(f"theta_deg must have one value per pressure ({len(p)}), got {len(t)}")
        lengths = tuple(float(v) for v in np.asarray(self.segment_lengths_mm, dtype=np.float64).reshape(-1))
        rows = np.asarray(self.segment_theta_deg, dtype=np.float64).reshape(-1, max(len(lengths), 1))
        if not lengths:  # no pieces given: one piece over the whole length, bent by the whole angle
            lengths, rows = (float(self.length_mm),), np.reshape(t, (-1, 1))
        if rows.shape != (len(p), len(lengths)) or abs(sum(lengths) - self.length_mm) > 1e-6:
            raise ParameterError(f"segment_theta_deg must have one row of {len(lengths)} angles per pressure "
                                 f"({len(p)}) and segment_lengths_mm must add up to length_mm {self.length_mm:g}")
        marks = tuple(float(v) for v in np.asarray(self.marks_mm, dtype=np.float64).reshape(-1))
        if not all(0.0 <= m <= self.length_mm for m in marks):
            raise ParameterError(f"marks_mm must lie in [0, length_mm {self.length_mm:g}], got {marks}")
        object.__setattr__(self, "pressure_kpa", p)
        object.__setattr__(self, "theta_deg", t)
        object.__setattr__(self, "marks_mm", marks)
        object.__setattr__(self, "segment_lengths_mm", lengths)
        object.__setattr__(self, "segment_theta_deg", tuple(tuple(float(v) for v in r) for r in rows))

    def shape(self, k: int) -> BentShape:
        """The bent line of state ``k``: the chain of arcs of its pieces, each bent by its own angle.

        Parameters
        ----------
        k : int
            The state's index (its pressure's).

        Returns
        -------
        BentShape

        Examples
        --------
        >>> hook = SidePanel("hook", 100.0, 2.58, [300.0], [60.0], segment_lengths_mm=[50.0, 50.0],
        ...                  segment_theta_deg=[[90.0, -30.0]])
        >>> [round(p[2] * p[1], 6) for p in hook.shape(0).pieces()]  # each segment's turn [rad]
        [1.570796, -0.523599]
        """
        return BentShape.chain(self.segment_lengths_mm, self.segment_theta_deg[k])


def shape_line_mm(shape: BentShape, offset_mm: float, *,
                  tolerance_mm: float = DEFAULT_TOLERANCES.curve_flatness_mm) -> np.ndarray:
    """Side-view points (x, z) [mm] of a line at ``offset_mm`` on the thread side of a bent straight strip.

    Parameters
    ----------
    shape : BentShape
        The bent fabric line (straight path, clamped at the origin).
    offset_mm : float
        Distance from the fabric line toward the thread side [mm] (negative: into the fabric).
    tolerance_mm : float
        Maximum chordal error of the polyline [mm].

    Returns
    -------
    ndarray, shape (n, 2)
        From the clamp to the free end; x = the shape's thread-side axis, z = minus its length axis.

    Examples
    --------
    >>> from embroact.predict.shape import BentShape
    >>> line = shape_line_mm(BentShape.chain([100.0], [90.0]), 0.0)
    >>> line[-1].round(3).tolist(), len(line)
    ([-63.662, -63.662], 64)
    """
    p = shape.points(shape.samples_mm(tolerance_mm, offset_mm), [(0.0, offset_mm)])[:, 0, :]
    return np.column_stack([p[:, 2], -p[:, 0]])


def bent_line_mm(length_mm: float, theta_deg: float, offset_mm: float, *,
                 tolerance_mm: float = DEFAULT_TOLERANCES.curve_flatness_mm) -> np.ndarray:
    """Side-view points (x, z) [mm] of a line at ``offset_mm`` on the thread side of the uniformly bent strip.

    Parameters
    ----------
    length_mm : float
        Fabric-side length l0 [mm].
    theta_deg : float
        Bend angle [deg]; positive curls toward -x (the fabric's back).
    offset_mm : float
        Distance from the fabric line toward the thread side [mm] (negative: into the fabric).
    tolerance_mm : float
        Maximum chordal error of the polyline [mm].

    Returns
    -------
    ndarray, shape (n, 2)
        From the clamp (s = 0) to the free end (s = l0).

    Examples
    --------
    >>> (bent_line_mm(100.0, 0.0, 2.0) + 0.0).tolist()  # straight: two points, 2 mm on the thread side
    [[2.0, 0.0], [2.0, -100.0]]
    """
    l0 = check_range("length_mm", length_mm, low=0.0)
    return shape_line_mm(BentShape.chain([l0], [check_range("theta_deg", theta_deg)]), offset_mm,
                         tolerance_mm=tolerance_mm)


def _band(lines: dict[float, np.ndarray], lo_mm: float, hi_mm: float) -> np.ndarray:
    """Closed outline of the region between two offsets (of a state's :func:`_state_lines`)."""
    return np.vstack([lines[lo_mm], lines[hi_mm][::-1]])


def _states(panel: SidePanel) -> list[tuple[float, float, BentShape]]:
    return [(p, t, panel.shape(k)) for k, (p, t) in enumerate(zip(panel.pressure_kpa, panel.theta_deg))
            if math.isfinite(t) and all(map(math.isfinite, panel.segment_theta_deg[k]))]


def _state_lines(panel: SidePanel) -> list[tuple[float, float, BentShape, dict[float, np.ndarray]]]:
    """Each drawn state with its lines at the offsets the panel draws (fabric back and line, tube axis
    and top), each computed once for the panel's extent and its drawing."""
    offsets = (-FABRIC_THICKNESS_MM, 0.0, panel.r0_mm, 2.0 * panel.r0_mm)
    return [(p, t, shape, {o: shape_line_mm(shape, o) for o in offsets}) for p, t, shape in _states(panel)]


def _side_names(panel: SidePanel) -> tuple[tuple[str, float, int], ...]:
    """The face names at the clamp: (text, x of the clamp's edge it sits beside [mm], direction)."""
    return (("fabric", -3.0, -1), ("tube", 2.0 * panel.r0_mm + 3.0, 1))


def _panel_bounds(panel: SidePanel, states) -> tuple[float, float, float, float]:
    """The panel's extent (x0, z0, x1, z1) [mm]: the clamp with room for its face names beside it, and every state."""
    room = [x + d * (_SIDE_GAP_MM + text_box(text, 0.0, 0.0, _SIDE_FONT_MM).x1) for text, x, d in _side_names(panel)]
    pts = [np.array([[room[0], 4.0], [room[1], 0.0]])]
    pts += [_band(lines, -FABRIC_THICKNESS_MM, 2.0 * panel.r0_mm) for *_, lines in states]
    allp = np.vstack(pts)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])


def _pts(xz: np.ndarray, dx: float, dy: float) -> list[tuple[float, float]]:
    """Model (x, z) [mm] to SVG user units (mm, y down), shifted, rounded to 1 um."""
    return [(round(x + dx, 3), round(dy - z, 3)) for x, z in xz.tolist()]  # floats: rows of an array are slow


def _draw_panel(dwg, parent, panel: SidePanel, states, dx: float, dy: float, left: float, legend_y: float,
                placer: Placer, title_y: float) -> list[tuple[tuple[float, float], list[int]]]:
    """Draw the panel's title, states, legend and clamp; return its tips (SVG point, state numbers there)."""
    r0 = panel.r0_mm
    g = dwg.g(**{"class": "panel"})
    parent.add(g)
    g.add(dwg.text(panel.label, insert=(left, round(title_y, 3)), font_size=_PANEL_FONT_MM, font_weight="bold",
                   **{"class": "panel-title"}))
    tips: list[tuple[tuple[float, float], list[int]]] = []
    for k, (p, t, shape, lines) in enumerate(states):
        colour = PALETTE[k % len(PALETTE)]
        sg = dwg.g(**{"class": "state", "data-pressure-kpa": f"{p:g}", "data-theta-deg": f"{t:.6g}"})
        g.add(sg)
        tube = _pts(_band(lines, 0.0, 2.0 * r0), dx, dy)
        sg.add(dwg.polygon(tube, fill=colour, fill_opacity=0.25, stroke=colour, stroke_width=0.25,
                           **{"class": "tube"}))
        sg.add(dwg.polygon(_pts(_band(lines, -FABRIC_THICKNESS_MM, 0.0), dx, dy), fill=colour,
                           stroke=colour, stroke_width=0.3, **{"class": "fabric"}))
        placer.block_polyline(tube + tube[:1])
        if panel.marks_mm:
            on_tube = shape.points(list(panel.marks_mm), [(0.0, r0)])[:, 0, :]
            for x, y in _pts(np.column_stack([on_tube[:, 2], -on_tube[:, 0]]), dx, dy):
                sg.add(dwg.circle((x, y), 0.9, fill="#fff", stroke=colour, stroke_width=0.35, **{"class": "mark"}))
        tip = _pts(lines[r0][-1:], dx, dy)[0]
        sg.add(dwg.circle(tip, 1.0, fill=colour))
        placer.block_box(Box(tip[0] - 1.0, tip[1] - 1.0, tip[0] + 1.0, tip[1] + 1.0))
        same = [n for n, (q, _) in enumerate(tips) if math.dist(q, tip) < _SAME_TIP_MM]
        if same:  # a state ending where an earlier one ends: one label for both
            tips[same[0]][1].append(k)
        else:
            tips.append((tip, [k]))
        y = legend_y + k * _LEGEND_ROW_MM
        sg.add(dwg.rect((left, y - 3.0), (4.0, 4.0), fill=colour))
        legend = f"{k + 1}: {p:g} kPa, {t:.1f} deg" if math.isfinite(p) else f"{k + 1}: {t:.1f} deg"
        sg.add(dwg.text(legend, insert=(left + 5.5, y + 0.6), font_size=_LEGEND_FONT_MM))
        placer.block_box(text_box(legend, left + 5.5, y + 0.6, _LEGEND_FONT_MM).union(Box(left, y - 3.0, left, y)))
    if panel.note:
        y = legend_y + len(states) * _LEGEND_ROW_MM
        g.add(dwg.text(panel.note, insert=(left, y + 0.6), font_size=_NOTE_FONT_MM, fill="#a33",
                       **{"class": "not-drawn"}))
        placer.block_box(text_box(panel.note, left, y + 0.6, _NOTE_FONT_MM))
    clamp = (dx - 3.0, dy - 4.0, 2.0 * r0 + 6.0, 4.0)
    g.add(dwg.rect(clamp[:2], clamp[2:], fill="#444", **{"class": "clamp"}))
    placer.block_box(Box(clamp[0], clamp[1], clamp[0] + clamp[2], clamp[1] + clamp[3]))
    return tips


def _draw_sides(dwg, parent, panel: SidePanel, dx: float, dy: float, placer: Placer) -> None:
    """Name the two faces at the clamp: the fabric to its left (-x), the tube on the thread side to its right."""
    for text, x, d in _side_names(panel):
        lab = placer.place(text, (dx + x, dy - 2.0), _SIDE_FONT_MM, gap=_SIDE_GAP_MM, directions=((d, 0), (d, -1)))
        parent.add(dwg.text(text, insert=(round(lab.x, 3), round(lab.y, 3)), font_size=_SIDE_FONT_MM,
                            text_anchor=lab.anchor, fill="#555", **{"class": "side-name"}))


def _draw_segment_names(dwg, parent, panel: SidePanel, states, dx: float, dy: float, placer: Placer) -> None:
    """A segmented actuator's segments (between its ``marks_mm``) numbered beside the middle of each, on the
    first state drawn."""
    if not panel.marks_mm or not states:
        return
    shape = states[0][2]
    ends = np.array([0.0, *sorted(panel.marks_mm), panel.length_mm])
    middles = ((ends[:-1] + ends[1:]) / 2.0).tolist()
    on_tube = shape.points(middles, [(0.0, 2.0 * panel.r0_mm)])[:, 0, :]
    for k, (x, y) in enumerate(_pts(np.column_stack([on_tube[:, 2], -on_tube[:, 0]]), dx, dy)):
        text = f"segment {k}"
        lab = placer.place(text, (x, y), _SIDE_FONT_MM, gap=1.0, directions=((1, 0), (-1, 0), (1, -1), (1, 1)))
        parent.add(dwg.text(text, insert=(round(lab.x, 3), round(lab.y, 3)), font_size=_SIDE_FONT_MM,
                            text_anchor=lab.anchor, fill="#555", **{"class": "segment-name"}))


def _draw_tips(dwg, parent, tips, placer: Placer) -> None:
    """Each tip numbered by its state(s), placed clear of the other labels and the drawing."""
    for tip, ks in tips:
        text = ",".join(str(k + 1) for k in ks)
        lab = placer.place(text, tip, _TIP_FONT_MM, gap=1.4)
        parent.add(dwg.text(text, insert=(round(lab.x, 3), round(lab.y, 3)), font_size=_TIP_FONT_MM,
                            text_anchor=lab.anchor, fill=PALETTE[ks[0] % len(PALETTE)], **{"class": "tip"}))


def side_view_svg(panels: Sequence[SidePanel], *, title: str = "Bent shape (side view, clamped top)") -> str:
    """Side views of one or more actuators, left to right, as an SVG document string.

    Units in the drawing are millimetres (1 user unit = 1 mm, shown at 3 px/mm); a
    10 mm scale bar is drawn.  Each state is a ``<g class="state">`` carrying
    ``data-pressure-kpa`` and ``data-theta-deg``. Past :data:`SIDE_VIEW_MAX_PANELS` panels
    the first ones are drawn and the title says how many of how many.

    Parameters
    ----------
    panels : sequence of SidePanel
        One per actuator, at least one.
    title : str, optional
        The picture's title.

    Returns
    -------
    str
        SVG.

    Examples
    --------
    >>> panel = SidePanel("A1", 100.0, 2.58, [100.0, 300.0], [11.5, 90.0])
    >>> side_view_svg([panel]).count('class="state"')
    2
    """
    from .svgdoc import Drawing

    if not panels:
        raise ParameterError("panels must hold at least one side view")
    if len(panels) > SIDE_VIEW_MAX_PANELS:
        title = f"{title}: the first {SIDE_VIEW_MAX_PANELS} of {len(panels)} actuators"
        panels = panels[:SIDE_VIEW_MAX_PANELS]
    states = [_state_lines(p) for p in panels]
    bounds = [_panel_bounds(p, s) for p, s in zip(panels, states)]
    top = max(b[3] for b in bounds) + 24.0
    bottom = min(b[1] for b in bounds)
    legend_y = top - bottom + 6.0
    rows = max(len(s) + bool(p.note) for p, s in zip(panels, states))
    x, lefts = _MARGIN_MM, []
    for p, b in zip(panels, bounds):
        lefts.append(x)
        x += max(b[2] - b[0], _LEGEND_WIDTH_MM, text_box(p.note, 0.0, 0.0, _NOTE_FONT_MM).x1) + _PANEL_GAP_MM
    width = max(x - _PANEL_GAP_MM + _MARGIN_MM + 20.0, text_box(title, 0.0, 0.0, 5.0).x1 + 2 * _MARGIN_MM)
    height = legend_y + rows * _LEGEND_ROW_MM + _MARGIN_MM
    dwg = Drawing(size=(f"{width * PX_PER_MM:.0f}", f"{height * PX_PER_MM:.0f}"),
                  viewBox=f"0 0 {width:.3f} {height:.3f}")
    dwg.add(dwg.rect((0, 0), (round(width, 3), round(height, 3)), fill="#fff"))
    root = dwg.g(style=_FONT)
    dwg.add(root)
    placer = Placer(Box(0.0, 0.0, width, height).grown(-_FRAME_INSET_MM), margin=0.3)
    root.add(dwg.text(title, insert=(_MARGIN_MM, 7.0), font_size=5, font_weight="bold"))
    placer.block_box(text_box(title, _MARGIN_MM, 7.0, 5.0))
    bar_x, bar_y = width - _MARGIN_MM - 10.0, height - _MARGIN_MM
    root.add(dwg.line((bar_x, bar_y), (bar_x + 10.0, bar_y), stroke="#000", stroke_width=0.6))
    root.add(dwg.text("10 mm", insert=(bar_x + 5.0, bar_y - 1.5), font_size=3.5, text_anchor="middle"))
    placer.block_box(text_box("10 mm", bar_x + 5.0, bar_y - 1.5, 3.5, "middle").union(Box(bar_x, bar_y, bar_x + 10, bar_y)))
    title_y = top - max(b[3] for b in bounds) - 3.0  # above the highest drawing: a coil never runs through it
    for panel, left in zip(panels, lefts):
        placer.block_box(text_box(panel.label, left, title_y, _PANEL_FONT_MM))
    tips = [_draw_panel(dwg, root, panel, s, left - b[0], top, left, legend_y, placer, title_y)
            for panel, s, b, left in zip(panels, states, bounds, lefts)]
    for panel, s_, b, left in zip(panels, states, bounds, lefts):
        _draw_sides(dwg, root, panel, left - b[0], top, placer)
        _draw_segment_names(dwg, root, panel, s_, left - b[0], top, placer)
    for panel_tips in tips:
        _draw_tips(dwg, root, panel_tips, placer)
    return dwg.tostring()
