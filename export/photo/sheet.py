"""Printable marker sheets of a calibration coupon: the fins for each actuator, the reference board.

Both are SVG documents in millimetres, to print at 100 % (each carries a 50 mm scale bar
to check the print with a ruler):

* :func:`fins_svg`: one row per actuator (its label, its fin side); each fin is a card
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
>>> svg = fins_svg(plan_coupon(patterns=("zigzag",), width_count=2))
>>> svg.count('class="marker"'), 'width="210mm"' in svg
(22, True)
"""
from __future__ import annotations

from ...predict.photomarkers import PhotoLayout, ReferenceBoard
from ..pictures.svgdoc import Drawing
from .arucobits import marker_cells

__all__ = ["board_svg", "fins_svg"]

_PAGE_W_MM = 210.0
_MARGIN_MM = 12.0
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


def _scale_bar(dwg, x: float, y: float) -> None:
    g = dwg.add(dwg.g(id="scale-bar", stroke="black", stroke_width=0.3))
    g.add(dwg.line((x, y), (x + 50.0, y)))
    for k in range(6):
        g.add(dwg.line((x + 10.0 * k, y), (x + 10.0 * k, y - (3.0 if k % 5 == 0 else 1.5))))
    dwg.add(dwg.text("50 mm: print at 100 % and check with a ruler", insert=(x + 53.0, y), font_size=3.2,
                     font_family=_FONT))


def fins_svg(coupon) -> str:
    """The fin sheet of ``coupon`` (module docstring): A4 wide, as tall as its rows need.

    Parameters
    ----------
    coupon : Coupon
        The coupon (:func:`~embroact.predict.coupon.plan_coupon`).

    Returns
    -------
    str
        SVG.

    Examples
    --------
    >>> from embroact.predict.coupon import plan_coupon
    >>> fins_svg(plan_coupon(("zigzag",), width_count=2)).count('class="marker"')  # 11 fins each
    22
    """
    lay: PhotoLayout = coupon.layout
    size, off = lay.marker_size_mm, lay.fin_offset_mm
    quiet = size / 6.0
    fin_w = size + 2.0 * quiet + 1.0
    fin_h = _TAB_MM + off + size / 2.0 + quiet + 0.5
    pitch = max(fin_w + 1.5, 8.0)
    row_h = 6.0 + fin_h + _ROW_GAP_MM
    n = lay.markers.markers_per_side
    height = 2 * _MARGIN_MM + 22.0 + row_h * len(coupon.actuators)
    dwg = Drawing(size=(f"{_PAGE_W_MM:g}mm", f"{height:g}mm"), viewBox=f"0 0 {_PAGE_W_MM:g} {height:g}")
    dwg.add(dwg.text(f"embroact calibration coupon: marker fins, {n} per actuator {lay.markers.spacing_mm:g} mm apart "
                     f"along the strip; marker {size:g} mm, centre {off:g} mm off the fabric",
                     insert=(_MARGIN_MM, _MARGIN_MM), font_size=3.2, font_family=_FONT))
    for k, line in enumerate(("Cut along the grey outline, fold the tab on the dashed line, glue the tab across the strip",
                              "at the fin's place (fin 0 at the clamped end): marker facing the camera, up away from the fabric.")):
        dwg.add(dwg.text(line, insert=(_MARGIN_MM, _MARGIN_MM + 5.0 + 3.6 * k), font_size=2.8, font_family=_FONT))
    _scale_bar(dwg, _MARGIN_MM, _MARGIN_MM + 16.0)
    y = _MARGIN_MM + 22.0
    for act in coupon.actuators:
        ids = lay.ids(act.block)
        dwg.add(dwg.text(f"{act.label}: fins on the {act.fin_side.value} side (ids {ids[0]}-{ids[-1]})",
                         insert=(_MARGIN_MM, y + 3.5), font_size=3.0, font_family=_FONT))
        base = y + 6.0 + fin_h - _TAB_MM  # the fold line
        row = dwg.add(dwg.g(id=f"fins-{act.order:02d}"))
        for j, marker_id in enumerate(ids):
            x = _MARGIN_MM + fin_w / 2.0 + j * pitch
            row.add(dwg.rect((round(x - fin_w / 2.0, 4), round(base - fin_h + _TAB_MM, 4)),
                             (round(fin_w, 4), round(fin_h, 4)), fill="none", stroke="#999999", stroke_width=0.2))
            row.add(dwg.line((round(x - fin_w / 2.0, 4), round(base, 4)), (round(x + fin_w / 2.0, 4), round(base, 4)),
                             stroke="#999999", stroke_width=0.2, stroke_dasharray="1,0.7"))
            _marker(dwg, row, marker_id, (x, base - off), size)
            row.add(dwg.text(str(j), insert=(round(x - 0.8, 4), round(base + 2.3, 4)), font_size=2.0,
                             font_family=_FONT))
        y += row_h
    return dwg.tostring()


def board_svg(board: ReferenceBoard) -> str:
    """The reference board (module docstring): its markers, the strip's window and a scale bar.

    Parameters
    ----------
    board : ReferenceBoard
        The board.

    Returns
    -------
    str
        SVG, 1:1 in mm.

    Examples
    --------
    >>> from embroact.predict.photomarkers import DEFAULT_BOARD
    >>> board_svg(DEFAULT_BOARD).count('class="marker"')
    8
    """
    xs = [c[0] for c in board.centres_mm]
    ys = [c[1] for c in board.centres_mm]
    pad = board.size_mm / 2.0 + 12.0
    x0, x1, y0, y1 = min(xs) - pad, max(xs) + pad, min(ys) - pad, max(ys) + pad + 10.0
    w, h = x1 - x0, y1 - y0
    dwg = Drawing(size=(f"{w:g}mm", f"{h:g}mm"), viewBox=f"0 0 {w:g} {h:g}")

    def page(x: float, y: float) -> tuple[float, float]:  # board frame (y up) to page (y down)
        return round(x - x0, 4), round(y1 - y, 4)

    markers = dwg.add(dwg.g(id="board"))
    for i, marker_id in enumerate(board.ids):
        _marker(dwg, markers, marker_id, page(*board.centres_mm[i]), board.size_mm)
    inner = board.size_mm / 2.0 + 4.0
    (wx0, wy0), (wx1, wy1) = page(min(xs) + inner, max(ys) - inner), page(max(xs) - inner, min(ys) + inner)
    dwg.add(dwg.rect((wx0, wy0), (round(wx1 - wx0, 4), round(wy1 - wy0, 4)), fill="none", stroke="#bbbbbb",
                     stroke_width=0.3, stroke_dasharray="2,1.5"))
    dwg.add(dwg.text("reference board: flat, facing the camera, in the plane of the marker fins; "
                     "the strip bends inside the dashed window", insert=(6.0, 6.0), font_size=2.8, font_family=_FONT))
    _scale_bar(dwg, 6.0, h - 4.0)
    return dwg.tostring()
