"""Printable marker sheets of a calibration coupon: the fins for each actuator, the reference board.

Both are SVG documents in millimetres, to print at 100 % (each carries a 50 mm scale bar
to check the print with a ruler), on sheets of :data:`~embroact.export.pictures.pages.SHEET_MM`
(210 x 279.4 mm: it fits A4 and Letter alike) with everything drawn at least
:data:`~embroact.export.pictures.pages.MARGIN_MM` inside the edges, where printers print;
text lines are wrapped to the page, measured a little wider than the font's advances
(:data:`TEXT_SLACK`: DejaVu Sans, what librsvg picks first, is wider than Helvetica):

* :func:`fins_svgs`: one row per actuator (its label, its fin side), as many rows a sheet as
  fit, on as many sheets as the coupon needs (``fins-1.svg``, ``fins-2.svg``, ...); each fin is a card
  with a glue tab below a dashed fold line and its marker ``fin_offset_mm`` above the
  fold, at the position the layout gives; glue the fold line along the strip at the
  fin's mark (the first at the clamped end), marker facing the camera, "up" away from
  the fabric;
* :func:`board_svg`: the reference board, markers at :class:`~embroact.predict.photomarkers.ReferenceBoard`'s
  positions, with the window the strip bends in.

Markers are ArUco 4x4 markers of the 250-id dictionary (:mod:`embroact.export.photo.arucobits`)
with a white quiet zone of one cell around the black border.

Examples
--------
>>> from embroact.predict.coupon import plan_coupon
>>> sheets = fins_svgs(plan_coupon(patterns=("zigzag",), width_count=2))
>>> len(sheets), sheets[0].count('class="marker"'), 'height="279.4mm"' in sheets[0] and 'width="210mm"' in sheets[0]
(1, 22, True)
"""
from __future__ import annotations

import math

from ...patterns.base.errors import ParameterError
from ...predict.photomarkers import PhotoLayout, ReferenceBoard
from ..pictures.pages import MARGIN_MM, SHEET_MM
from ..pictures.svgdoc import Drawing
from ..pictures.titles import fit_title
from .arucobits import marker_cells

__all__ = ["TEXT_SLACK", "board_svg", "fins_svgs"]

#: Text is wrapped as if this much wider than its Helvetica-Bold advances (DejaVu Sans runs up to ~12 % wider).
TEXT_SLACK = 1.15
_TAB_MM = 3.0  # glue tab below the fold line
_ROW_GAP_MM = 6.0
_FONT = "DejaVu Sans, Arial, sans-serif"


def _marker(dwg, group, marker_id: int, centre, size: float) -> None:
    """ArUco marker ``marker_id``: black square, white inner cells, white quiet zone of one cell."""
    cell = size / 6.0
    x0, y0 = centre[0] - size / 2.0, centre[1] - size / 2.0
    g = group.add(dwg.g(class_="marker", id=f"marker-{marker_id}", shape_rendering="crispEdges"))
    g.add(dwg.rect((round(x0 - cell, 4), round(y0 - cell, 4)), (round(size + 2 * cell, 4),) * 2, fill="white"))
    g.add(dwg.rect((round(x0, 4), round(y0, 4)), (round(size, 4),) * 2, fill="black"))
    for r, row in enumerate(marker_cells(marker_id)):
        for c, bit in enumerate(row):
            if bit:
                g.add(dwg.rect((round(x0 + (c + 1) * cell, 4), round(y0 + (r + 1) * cell, 4)),
                               (round(cell, 4),) * 2, fill="white"))


def _text(dwg, text: str, x: float, y: float, width_mm: float, font_mm: float) -> float:
    """``text`` wrapped into ``width_mm`` from baseline ``y`` on; returns the baseline below its last line."""
    for line in fit_title(text, width_mm / TEXT_SLACK, font_px=font_mm, small_px=font_mm, max_lines=50).lines:
        dwg.add(dwg.text(line, insert=(round(x, 4), round(y, 4)), font_size=font_mm, font_family=_FONT))
        y += 1.3 * font_mm
    return y


def _scale_bar(dwg, x: float, y: float, width_mm: float) -> float:
    """The 50 mm bar with its baseline at ``y``, its note beside it; returns the baseline below the note."""
    g = dwg.add(dwg.g(id="scale-bar", stroke="black", stroke_width=0.3))
    g.add(dwg.line((x, y), (x + 50.0, y)))
    for k in range(6):
        g.add(dwg.line((x + 10.0 * k, y), (x + 10.0 * k, y - (3.0 if k % 5 == 0 else 1.5))))
    return max(y + 4.0, _text(dwg, "50 mm: print at 100 % and check with a ruler", x + 53.0, y, width_mm - 53.0, 3.2))


def _page(width_mm: float, height_mm: float) -> Drawing:
    return Drawing(size=(f"{width_mm:g}mm", f"{height_mm:g}mm"), viewBox=f"0 0 {width_mm:g} {height_mm:g}")


def _fin_row(dwg, lay: PhotoLayout, act, y: float, per_line: int, pitch: float, fin_w: float, fin_h: float) -> None:
    """Actuator ``act``'s label and fins, ``per_line`` to a line, from ``y`` (top of its label) down."""
    size, off = lay.marker_size_mm, lay.fin_offset_mm
    ids = lay.ids(act.block)
    _text(dwg, f"{act.label}: fins on the {act.fin_side.value} side (ids {ids[0]}-{ids[-1]})", MARGIN_MM, y + 3.5,
          SHEET_MM[0] - 2 * MARGIN_MM, 3.0)
    row = dwg.add(dwg.g(id=f"fins-{act.order:02d}"))
    for j, marker_id in enumerate(ids):
        line, col = divmod(j, per_line)
        x = MARGIN_MM + fin_w / 2.0 + col * pitch
        base = y + 6.0 + fin_h - _TAB_MM + line * (fin_h + 2.0)  # the fold line
        row.add(dwg.rect((round(x - fin_w / 2.0, 4), round(base - fin_h + _TAB_MM, 4)),
                         (round(fin_w, 4), round(fin_h, 4)), fill="none", stroke="#999999", stroke_width=0.2))
        row.add(dwg.line((round(x - fin_w / 2.0, 4), round(base, 4)), (round(x + fin_w / 2.0, 4), round(base, 4)),
                         stroke="#999999", stroke_width=0.2, stroke_dasharray="1,0.7"))
        _marker(dwg, row, marker_id, (x, base - off), size)
        row.add(dwg.text(str(j), insert=(round(x - 0.8, 4), round(base + 2.3, 4)), font_size=2.0, font_family=_FONT))


def _fins_header(dwg, lay: PhotoLayout, sheet: int, sheets: int) -> float:
    """Title, instructions and scale bar of fin sheet ``sheet`` of ``sheets``; returns where the rows start."""
    room = SHEET_MM[0] - 2 * MARGIN_MM
    n, size, off = lay.markers.markers_per_side, lay.marker_size_mm, lay.fin_offset_mm
    y = _text(dwg, f"embroact calibration coupon, marker fins (sheet {sheet} of {sheets}): {n} per actuator "
                   f"{lay.markers.spacing_mm:g} mm apart along the strip; marker {size:g} mm, centre {off:g} mm "
                   "off the fabric", MARGIN_MM, MARGIN_MM + 3.2, room, 3.2)
    y = _text(dwg, "Cut along the grey outline, fold the tab on the dashed line, glue the tab across the strip "
                   "at the fin's place (fin 0 at the clamped end): marker facing the camera, up away from the fabric.",
              MARGIN_MM, y + 0.6, room, 2.8)
    return _scale_bar(dwg, MARGIN_MM, y + 4.0, room) + 2.0


def fins_svgs(coupon) -> list[str]:
    """The fin sheets of ``coupon`` (module docstring): as many rows a sheet as fit, as many sheets as it needs.

    Parameters
    ----------
    coupon : Coupon
        The coupon (:func:`~embroact.predict.coupon.plan_coupon`).

    Returns
    -------
    list of str
        One SVG per sheet, each ``SHEET_MM`` in size.

    Examples
    --------
    >>> from embroact.predict.coupon import plan_coupon
    >>> sheets = fins_svgs(plan_coupon(("zigzag", "cross")))  # 11 actuators, 11 fins each
    >>> len(sheets), sum(s.count('class="marker"') for s in sheets)
    (2, 121)
    """
    lay: PhotoLayout = coupon.layout
    size, off = lay.marker_size_mm, lay.fin_offset_mm
    fin_w = size + 2.0 * size / 6.0 + 1.0
    fin_h = _TAB_MM + off + size / 2.0 + size / 6.0 + 0.5
    pitch = max(fin_w + 1.5, 8.0)
    n = lay.markers.markers_per_side
    per_line = max(1, min(n, math.floor((SHEET_MM[0] - 2 * MARGIN_MM - fin_w) / pitch) + 1))
    row_h = 6.0 + math.ceil(n / per_line) * (fin_h + 2.0) - 2.0 + _ROW_GAP_MM
    top = _fins_header(_page(*SHEET_MM), lay, 1, 1)  # the header's height, the same on every sheet
    per_sheet = max(1, math.floor((SHEET_MM[1] - MARGIN_MM - top + _ROW_GAP_MM) / row_h))
    if top + row_h - _ROW_GAP_MM > SHEET_MM[1] - MARGIN_MM:
        raise ParameterError(f"marker_size_mm and fin_offset_mm: {size:g} and {off:g} mm make a fin row "
                             f"{row_h - _ROW_GAP_MM:.0f} mm tall, more than a {SHEET_MM[0]:g} x {SHEET_MM[1]:g} mm "
                             "sheet holds")
    acts = list(coupon.actuators)
    chunks = [acts[k:k + per_sheet] for k in range(0, len(acts), per_sheet)] or [[]]
    out = []
    for k, chunk in enumerate(chunks):
        dwg = _page(*SHEET_MM)
        y = _fins_header(dwg, lay, k + 1, len(chunks))
        for act in chunk:
            _fin_row(dwg, lay, act, y, per_line, pitch, fin_w, fin_h)
            y += row_h
        out.append(dwg.tostring())
    return out


def board_svg(board: ReferenceBoard) -> str:
    """The reference board (module docstring): its markers, the strip's window and a scale bar.

    Parameters
    ----------
    board : ReferenceBoard
        The board.

    Returns
    -------
    str
        SVG, 1:1 in mm, one ``SHEET_MM`` sheet (portrait, or landscape for a board too wide for it).

    Examples
    --------
    >>> from embroact.predict.photomarkers import DEFAULT_BOARD
    >>> svg = board_svg(DEFAULT_BOARD)
    >>> svg.count('class="marker"'), 'height="279.4mm"' in svg and 'width="210mm"' in svg
    (8, True)
    """
    xs = [c[0] for c in board.centres_mm]
    ys = [c[1] for c in board.centres_mm]
    ink = board.size_mm / 2.0 + board.size_mm / 6.0  # a marker's reach from its centre, quiet zone included
    ink_w, ink_h = max(xs) - min(xs) + 2 * ink, max(ys) - min(ys) + 2 * ink
    fits = [(w, h) for w, h in (SHEET_MM, SHEET_MM[::-1]) if ink_w <= w - 2 * MARGIN_MM and ink_h + 30.0 <= h - 2 * MARGIN_MM]
    if not fits:
        raise ParameterError(f"board centres_mm and size_mm: the board's markers span {ink_w:.0f} x {ink_h:.0f} mm, "
                             f"more than a {SHEET_MM[0]:g} x {SHEET_MM[1]:g} mm sheet holds inside its "
                             f"{MARGIN_MM:g} mm margins")
    w, h = fits[0]
    dwg = _page(w, h)
    top = _text(dwg, "reference board: flat, facing the camera, in the plane of the marker fins; "
                     "the strip bends inside the dashed window", MARGIN_MM, MARGIN_MM + 2.8, w - 2 * MARGIN_MM, 2.8)
    x0, y1 = min(xs) - ink - (w - ink_w) / 2.0, max(ys) + ink + top + 2.0  # board frame of the page's (0, 0)

    def page(x: float, y: float) -> tuple[float, float]:  # board frame (y up) to page (y down)
        return round(x - x0, 4), round(y1 - y, 4)

    markers = dwg.add(dwg.g(id="board"))
    for i, marker_id in enumerate(board.ids):
        _marker(dwg, markers, marker_id, page(*board.centres_mm[i]), board.size_mm)
    inner = board.size_mm / 2.0 + 4.0
    (wx0, wy0), (wx1, wy1) = page(min(xs) + inner, max(ys) - inner), page(max(xs) - inner, min(ys) + inner)
    dwg.add(dwg.rect((wx0, wy0), (round(wx1 - wx0, 4), round(wy1 - wy0, 4)), fill="none", stroke="#bbbbbb",
                     stroke_width=0.3, stroke_dasharray="2,1.5"))
    _scale_bar(dwg, MARGIN_MM, page(0.0, min(ys) - ink)[1] + 10.0, w - 2 * MARGIN_MM)
    return dwg.tostring()
