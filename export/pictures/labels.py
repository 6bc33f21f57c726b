"""Label placement: text boxes that keep off each other, the marks, the curves and the frame.

Every picture places its free labels (stop and trim marks, P0 marks, tip numbers, actuator
names) through one :class:`Placer`. A label's box is estimated from its font size and its
string (:func:`~embroact.export.pictures.titles.text_width_px`, the bold Helvetica advances, a
little wider than the regular text drawn; ascent 0.75 em, descent 0.22 em). The placer tries
positions around the label's anchor point, nearest first (right, above, below, left and the
diagonals, then the same at two and four times the distance), and keeps the first whose box
stays inside the frame and touches no box or polyline placed or blocked before; when none is
free it keeps the cheapest (crossing marks before covering a label, anything before leaving
the frame). Placed labels become obstacles for the next.

Examples
--------
>>> from embroact.export.pictures.labels import Box, Placer
>>> p = Placer(Box(0.0, 0.0, 100.0, 50.0))
>>> p.block_box(Box(40.0, 10.0, 60.0, 30.0))      # a mark
>>> a = p.place("first", (50.0, 20.0), 10.0, gap=2.0)
>>> a.box.overlaps(Box(40.0, 10.0, 60.0, 30.0))
False
>>> b = p.place("second", (50.0, 20.0), 10.0, gap=2.0)
>>> a.box.overlaps(b.box), p.frame.contains(b.box)
(False, True)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .titles import text_width_px

__all__ = ["ASCENT_EM", "DESCENT_EM", "Box", "Label", "text_box", "Placer"]

#: Height of a text line above and below its baseline, in font sizes.
ASCENT_EM, DESCENT_EM = 0.75, 0.22

# Directions tried around an anchor (dx, dy in units of the gap; y down), nearest first.
_DIRECTIONS = ((1, 0), (0, -1), (0, 1), (-1, 0), (1, -1), (1, 1), (-1, -1), (-1, 1))
_RINGS = (1.0, 2.0, 4.0, 7.0, 11.0, 16.0)
# A collision with another label or a step outside the frame costs more than any number of marks crossed.
_LABEL_WEIGHT, _FRAME_WEIGHT = 10_000, 100_000_000
# The obstacle index: the frame's longer side in this many cells; an obstacle spanning more cells than
# _WIDE_CELLS is checked by every query instead; a polyline is indexed in runs of _RUN segments.
_GRID_CELLS, _WIDE_CELLS, _RUN = 64, 64, 16


@dataclass(frozen=True, slots=True)
class Box:
    """An axis-aligned box (x0 <= x1, y0 <= y1; SVG user units, y down).

    Attributes
    ----------
    x0, y0, x1, y1 : float
        Left, top, right and bottom edge.

    Examples
    --------
    >>> a, b = Box(0, 0, 10, 5), Box(10, 0, 20, 5)
    >>> a.overlaps(b), a.union(b), a.grown(1.0)
    (False, Box(x0=0, y0=0, x1=20, y1=5), Box(x0=-1.0, y0=-1.0, x1=11.0, y1=6.0))
    """

    x0: float
    y0: float
    x1: float
    y1: float

    def overlaps(self, other: "Box") -> bool:
        """True when the two boxes share an area (touching edges do not count).

        Parameters
        ----------
        other : Box
            Another box.

        Returns
        -------
        bool

        Examples
        --------
        >>> Box(0, 0, 10, 5).overlaps(Box(5, 2, 20, 9)), Box(0, 0, 10, 5).overlaps(Box(10, 0, 20, 5))
        (True, False)
        """
        return min(self.x1, other.x1) > max(self.x0, other.x0) and min(self.y1, other.y1) > max(self.y0, other.y0)

    def contains(self, other: "Box") -> bool:
        """True when ``other`` lies inside this box (edges included).

        Parameters
        ----------
        other : Box
            Another box.

        Returns
        -------
        bool

        Examples
        --------
        >>> Box(0, 0, 10, 5).contains(Box(0, 0, 10, 5)), Box(0, 0, 10, 5).contains(Box(5, 2, 20, 9))
        (True, False)
        """
        return self.x0 <= other.x0 and self.y0 <= other.y0 and other.x1 <= self.x1 and other.y1 <= self.y1

    def grown(self, d: float) -> "Box":
        """The box grown by ``d`` on every side.

        Parameters
        ----------
        d : float
            The margin (negative: shrunk).

        Returns
        -------
        Box

        Examples
        --------
        >>> Box(0, 0, 10, 5).grown(0.5)
        Box(x0=-0.5, y0=-0.5, x1=10.5, y1=5.5)
        """
        return Box(self.x0 - d, self.y0 - d, self.x1 + d, self.y1 + d)

    def union(self, other: "Box") -> "Box":
        """The least box holding both.

        Parameters
        ----------
        other : Box
            Another box.

        Returns
        -------
        Box

        Examples
        --------
        >>> Box(0, 0, 10, 5).union(Box(5, 2, 20, 9))
        Box(x0=0, y0=0, x1=20, y1=9)
        """
        return Box(min(self.x0, other.x0), min(self.y0, other.y0), max(self.x1, other.x1), max(self.y1, other.y1))


@dataclass(frozen=True, slots=True)
class Label:
    """A placed label: write ``text`` at baseline point (``x``, ``y``) with ``text-anchor`` ``anchor``.

    Attributes
    ----------
    text : str
        The label.
    x, y : float
        Its baseline point.
    anchor : str
        ``"start"``, ``"middle"`` or ``"end"``.
    box : Box
        The box it covers.
    collisions : int
        The cost of its place (:meth:`Placer.collisions`; 0: clear of everything).

    Examples
    --------
    >>> lab = Placer(Box(0, 0, 100, 50)).place("P0", (50, 25), 10.0, gap=2.0)
    >>> lab.anchor, lab.collisions
    ('start', 0)
    """

    text: str
    x: float
    y: float
    anchor: str
    box: Box
    collisions: int


def text_box(text: str, x: float, y: float, font_size: float, anchor: str = "start") -> Box:
    """The box of one line of ``text`` written at baseline point (``x``, ``y``).

    Parameters
    ----------
    text : str
        One line.
    x, y : float
        Its baseline point.
    font_size : float
        Font size (same units).
    anchor : {"start", "middle", "end"}, optional
        Its ``text-anchor``.

    Returns
    -------
    Box

    Examples
    --------
    >>> text_box("MM", 10.0, 20.0, 10.0, "middle")
    Box(x0=1.67, y0=12.5, x1=18.33, y1=22.2)
    """
    w = text_width_px(text, font_size)
    left = x - {"start": 0.0, "middle": w / 2.0, "end": w}[anchor]
    return Box(round(left, 6), round(y - ASCENT_EM * font_size, 6), round(left + w, 6),
               round(y + DESCENT_EM * font_size, 6))


def _segments_hit(segs: np.ndarray, box: Box) -> int:
    """How many of the segments (n x 4: x0, y0, x1, y1) cross or lie in ``box`` (Liang-Barsky clipping)."""
    if len(segs) == 0:
        return 0
    x0, y0, x1, y1 = segs.T
    near = (np.maximum(x0, x1) >= box.x0) & (np.minimum(x0, x1) <= box.x1) \
        & (np.maximum(y0, y1) >= box.y0) & (np.minimum(y0, y1) <= box.y1)
    if not near.any():
        return 0
    x0, y0, x1, y1 = x0[near], y0[near], x1[near], y1[near]
    dx, dy = x1 - x0, y1 - y0
    lo, hi = np.zeros(len(x0)), np.ones(len(x0))
    ok = np.ones(len(x0), dtype=bool)
    for p, q in ((-dx, x0 - box.x0), (dx, box.x1 - x0), (-dy, y0 - box.y0), (dy, box.y1 - y0)):
        parallel = p == 0
        ok &= ~(parallel & (q < 0))
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(parallel, 0.0, q / np.where(parallel, 1.0, p))
        lo = np.where(~parallel & (p < 0), np.maximum(lo, t), lo)
        hi = np.where(~parallel & (p > 0), np.minimum(hi, t), hi)
    return int(np.count_nonzero(ok & (lo <= hi)))


class _Grid:
    """Obstacles bucketed by the square cells their bounding boxes touch, so a query reads only its neighbours.

    Cells are closed on both sides (a box ending on a cell edge is in both cells), so every obstacle whose
    bounding box touches a query box (edges included) is returned: a query's answer is a superset of the
    obstacles that can overlap it, and the callers' counts are those of a full scan.
    """

    def __init__(self, frame: Box) -> None:
        self._cell = max(frame.x1 - frame.x0, frame.y1 - frame.y0) / _GRID_CELLS or 1.0
        self._buckets: dict[tuple[int, int], list[int]] = {}
        self._wide: list[int] = []
        self.items: list = []

    def _span(self, x0: float, y0: float, x1: float, y1: float) -> tuple[int, int, int, int] | None:
        """The cell range of a bounding box, or None when it is too wide (or not finite) to bucket."""
        if not all(map(math.isfinite, (x0, y0, x1, y1))):
            return None
        c = self._cell
        i0, j0, i1, j1 = math.floor(x0 / c), math.floor(y0 / c), math.floor(x1 / c), math.floor(y1 / c)
        return None if (i1 - i0 + 1) * (j1 - j0 + 1) > _WIDE_CELLS else (i0, j0, i1, j1)

    def add(self, bbox: tuple[float, float, float, float], item) -> None:
        """Keep ``item`` under its bounding box (x0, y0, x1, y1)."""
        k = len(self.items)
        self.items.append(item)
        span = self._span(*bbox)
        if span is None:
            self._wide.append(k)
            return
        i0, j0, i1, j1 = span
        for i in range(i0, i1 + 1):
            for j in range(j0, j1 + 1):
                self._buckets.setdefault((i, j), []).append(k)

    def near(self, box: Box) -> list:
        """Every item whose bounding box may touch ``box`` (each once)."""
        span = self._span(box.x0, box.y0, box.x1, box.y1)
        if span is None:
            return self.items
        i0, j0, i1, j1 = span
        found = set(self._wide)
        for i in range(i0, i1 + 1):
            for j in range(j0, j1 + 1):
                found.update(self._buckets.get((i, j), ()))
        return [self.items[k] for k in sorted(found)]


class Placer:
    """Places labels one after another inside ``frame``, each clear of what came before.

    Parameters
    ----------
    frame : Box
        The room labels must stay in (the canvas or the plot box).
    margin : float
        Clearance kept around every obstacle box (same units).

    Examples
    --------
    >>> placer = Placer(Box(0, 0, 100, 50), margin=1.0)
    >>> placer.block_box(Box(40, 20, 60, 30))  # a mark
    >>> lab = placer.place("P0", (50, 25), 10.0, gap=2.0)
    >>> lab.box.overlaps(Box(40, 20, 60, 30)), lab.collisions, len(placer.labels)
    (False, 0, 1)
    """

    def __init__(self, frame: Box, *, margin: float = 0.0) -> None:
        self.frame = frame
        self.margin = margin
        self._boxes = _Grid(frame)
        self._label_boxes = _Grid(frame)
        self._segments = _Grid(frame)
        self.labels: list[Label] = []

    def _keep_box(self, grid: _Grid, box: Box) -> None:
        grid.add((box.x0, box.y0, box.x1, box.y1), box)

    def _keep_segments(self, segs: np.ndarray) -> None:
        """Index ``segs`` (n x 4) in runs of consecutive segments, each under its bounding box."""
        xs, ys = segs[:, 0::2], segs[:, 1::2]
        starts = np.arange(0, len(segs), _RUN)
        lo_x, hi_x = np.minimum.reduceat(xs.min(axis=1), starts), np.maximum.reduceat(xs.max(axis=1), starts)
        lo_y, hi_y = np.minimum.reduceat(ys.min(axis=1), starts), np.maximum.reduceat(ys.max(axis=1), starts)
        for k, start in enumerate(starts.tolist()):
            self._segments.add((float(lo_x[k]), float(lo_y[k]), float(hi_x[k]), float(hi_y[k])),
                               segs[start:start + _RUN])

    def block_box(self, box: Box) -> None:
        """Keep labels off ``box`` (a mark, a legend, a title).

        Parameters
        ----------
        box : Box
            The obstacle (grown by the margin).

        Examples
        --------
        >>> placer = Placer(Box(0, 0, 100, 50), margin=1.0)
        >>> placer.block_box(Box(40, 20, 60, 30))
        >>> placer.collisions(Box(45, 22, 47, 24))
        1
        """
        self._keep_box(self._boxes, box.grown(self.margin))

    def block_polyline(self, points) -> None:
        """Keep labels off the polyline through ``points`` (n x 2, the picture's units).

        Parameters
        ----------
        points : array_like (n, 2)
            The polyline (one point: a dot).

        Examples
        --------
        >>> placer = Placer(Box(0, 0, 100, 50), margin=1.0)
        >>> placer.block_polyline([(0, 10), (100, 10)])
        >>> placer.collisions(Box(5, 8, 15, 12)), placer.collisions(Box(5, 20, 15, 25))
        (1, 0)
        """
        pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        if len(pts) == 1:
            pts = np.vstack([pts, pts])
        if len(pts) >= 2:
            self._keep_segments(np.hstack([pts[:-1], pts[1:]]))

    def block_segments(self, segments) -> None:
        """Keep labels off the segments (n x 4: x0, y0, x1, y1).

        Parameters
        ----------
        segments : array_like (n, 4)
            Straight segments.

        Examples
        --------
        >>> placer = Placer(Box(0, 0, 100, 50), margin=1.0)
        >>> placer.block_segments([(0, 40, 100, 40), (50, 0, 50, 50)])
        >>> placer.collisions(Box(45, 35, 55, 45))
        2
        """
        segs = np.asarray(segments, dtype=np.float64).reshape(-1, 4)
        if len(segs):
            self._keep_segments(segs)

    def collisions(self, box: Box) -> int:
        """A cost of ``box``: obstacles it touches (boxes, segments), far more for a label or leaving the frame.

        Parameters
        ----------
        box : Box
            A candidate place.

        Returns
        -------
        int
            0: clear of everything and inside the frame.

        Examples
        --------
        >>> placer = Placer(Box(0, 0, 100, 50), margin=1.0)
        >>> placer.collisions(Box(0, 0, 5, 5)), placer.collisions(Box(-5, 0, 1, 1)) > 1000
        (0, True)
        """
        n = sum(box.overlaps(b) for b in self._boxes.near(box))
        n += _LABEL_WEIGHT * sum(box.overlaps(b) for b in self._label_boxes.near(box))
        grown = box.grown(self.margin)
        runs = self._segments.near(grown)
        n += _segments_hit(np.concatenate(runs), grown) if runs else 0
        return n + (0 if self.frame.contains(box) else _FRAME_WEIGHT)

    def _keep_label(self, label: Label) -> Label:
        self.labels.append(label)
        self._keep_box(self._label_boxes, label.box.grown(self.margin))
        return label

    def _candidates(self, text, anchor_xy, font_size, gap, directions, rings=_RINGS):
        ax, ay = anchor_xy
        w = text_width_px(text, font_size)
        h_up, h_down = ASCENT_EM * font_size, DESCENT_EM * font_size
        for ring in rings:
            d = gap * ring
            for dx, dy in directions:
                anchor = "start" if dx > 0 else "end" if dx < 0 else "middle"
                x = ax + dx * d
                # vertically: centred on the anchor, or wholly above or below it
                y = ay + (h_up - h_down) / 2.0 if dy == 0 else ay - d - h_down if dy < 0 else ay + d + h_up
                yield x, y, anchor
        if len(rings) == 1:
            return
        # last resort: slide along the frame's inside
        x = min(max(ax, self.frame.x0 + w / 2.0), self.frame.x1 - w / 2.0)
        y = min(max(ay, self.frame.y0 + h_up), self.frame.y1 - h_down)
        yield x, y, "middle"

    def place_along(self, text: str, points, font_size: float, *, gap: float, directions=((1, 0), (-1, 0))) -> Label:
        """Place ``text`` beside the first of ``points`` (in order) where it is free, else as :meth:`place` at the first.

        For a label that may sit anywhere along a mark (a P0 line): ``points`` are the spots
        along it, best first, each tried in ``directions`` at distance ``gap``.

        Parameters
        ----------
        text : str
            The label.
        points : sequence of (float, float)
            Spots along the mark, best first.
        font_size : float
            Font size.
        gap : float
            Distance between the spot and the label.
        directions : sequence of (int, int), optional
            Directions to try at each spot (y down).

        Returns
        -------
        Label

        Examples
        --------
        >>> placer = Placer(Box(0, 0, 100, 50), margin=1.0)
        >>> placer.block_box(Box(0, 20, 40, 40))  # the first spot's sides are taken
        >>> lab = placer.place_along("A1", [(10, 30), (80, 30)], 8.0, gap=2.0)
        >>> lab.x > 80, lab.collisions
        (True, 0)
        """
        for anchor_xy in points:
            for x, y, anchor in self._candidates(text, anchor_xy, font_size, gap, directions, rings=(1.0,)):
                box = text_box(text, x, y, font_size, anchor)
                if self.collisions(box) == 0:
                    return self._keep_label(Label(text, x, y, anchor, box, 0))
        return self.place(text, points[0], font_size, gap=gap)

    def place(self, text: str, anchor_xy, font_size: float, *, gap: float, directions=_DIRECTIONS) -> Label:
        """Place ``text`` near ``anchor_xy`` and keep its box as an obstacle for later labels.

        Parameters
        ----------
        text : str
            The label.
        anchor_xy : (float, float)
            The point labelled.
        font_size : float
            Font size.
        gap : float
            Distance between the point and the nearest edge of the label.
        directions : sequence of (int, int)
            Directions to try (dx, dy in {-1, 0, 1}, y down), best first.

        Returns
        -------
        Label
            The best place found (its ``collisions`` > 0 when none is clear).

        Examples
        --------
        >>> placer = Placer(Box(0, 0, 100, 50), margin=1.0)
        >>> lab = placer.place("tip", (95, 25), 10.0, gap=2.0)  # no room on the right: left of the point
        >>> lab.anchor, placer.frame.contains(lab.box)
        ('end', True)
        """
        best: Label | None = None
        for x, y, anchor in self._candidates(text, anchor_xy, font_size, gap, directions):
            box = text_box(text, x, y, font_size, anchor)
            n = self.collisions(box)
            if best is None or n < best.collisions:
                best = Label(text, x, y, anchor, box, n)
                if n == 0:
                    break
        assert best is not None  # there is always a candidate
        return self._keep_label(best)
