"""The 1:1 layout template tiled on paper: one printable HTML file of A4 or Letter sheets.

A hoop is often larger than a sheet (a 200 mm hoop nearly fills A4, a 400 mm one needs
several), and printers cannot print the outer few millimetres of a sheet. :func:`tile_template`
cuts the template (:func:`~embroact.export.pictures.template.template_svg`) into tiles that lie
inside a :data:`MARGIN_MM` margin on every side, each tile overlapping its neighbours by
:data:`OVERLAP_MM`, in the orientation that needs fewer sheets. Every sheet carries:

- its tile of the template at 1:1 (the template's own geometry, copied, clipped to the tile);
- the overlap with each neighbour shaded, its inner edge dashed, and registration crosses at
  the template positions that both neighbours show, to lay one sheet on the next;
- a footer with the sheet's place (row, column, of how many), the paper, "print at 100 %" and
  a 10 mm check square to measure after printing.

:func:`template_pages_html` writes the sheets as one HTML file (one inline SVG per sheet, CSS
``@page`` of the paper's size, no margin, a page break after each sheet): print it from a
browser at 100 % (actual size).

Examples
--------
>>> from embroact.patterns.centerline import Centerline
>>> from embroact.patterns.params import ZigzagParams
>>> from embroact.patterns.zigzag import zigzag
>>> from embroact.export.pictures.template import template_svg
>>> sheets = tile_template(template_svg(zigzag(Centerline.straight(100.0), ZigzagParams(7.0, 1.0))), "a4")
>>> len(sheets), sheets[0].paper, (sheets[0].width_mm, sheets[0].height_mm)
(2, 'A4', (210.0, 297.0))
"""
from __future__ import annotations

import copy
import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass

from ...patterns.base.errors import ParameterError

__all__ = ["PAPERS", "SHEET_MM", "MARGIN_MM", "OVERLAP_MM", "CHECK_SQUARE_MM", "Sheet", "tile_template", "template_pages_html"]

#: Paper name -> (width, height) in portrait [mm].
PAPERS = {"a4": ("A4", 210.0, 297.0), "letter": ("Letter", 215.9, 279.4)}
#: A sheet that fits every paper of :data:`PAPERS` (the narrowest width, the shortest height) [mm]: what one
#: printed page made for any of them (the coupon's marker sheets) is drawn on, portrait.
SHEET_MM = (min(w for _, w, _ in PAPERS.values()), min(h for _, _, h in PAPERS.values()))
#: Clear border on every side of a sheet [mm]: wider than most printers' unprintable margin (4-6.35 mm).
MARGIN_MM = 10.0
#: Most sheets a template is tiled on (100 A4 sheets hold about 2.5 x 1.8 m); a larger one gets a page saying so.
MAX_SHEETS = 100
#: Width of the strip two neighbouring sheets both print [mm].
OVERLAP_MM = 10.0
#: Side of the square on every sheet that checks the print scale [mm].
CHECK_SQUARE_MM = 10.0
_FOOTER_MM = 14.0
_FONT = "font-family:Helvetica,Arial,sans-serif"
_SVG_NS = "http://www.w3.org/2000/svg"
_CROSS_MM = 3.0


@dataclass(frozen=True, slots=True)
class Sheet:
    """One printed sheet.

    Attributes
    ----------
    paper : str
        ``"A4"`` or ``"Letter"``.
    width_mm, height_mm : float
        Sheet size as printed (landscape when wider than high).
    row, column, rows, columns : int
        Its place in the grid of sheets (from 1) and the grid's size.
    tile_mm : (float, float, float, float)
        The template area it shows: x, y, width, height in the template's coordinates [mm].
    svg : str
        The sheet as an SVG document (``width``/``height`` in mm).

    Examples
    --------
    >>> drawing = '<svg xmlns="http://www.w3.org/2000/svg" width="400mm" height="100mm" viewBox="0 0 400 100"/>'
    >>> sheets = tile_template(drawing, "a4")
    >>> s = sheets[1]
    >>> s.paper, (s.width_mm, s.height_mm), (s.row, s.column, s.rows, s.columns), s.tile_mm
    ('A4', (297.0, 210.0), (1, 2, 1, 2), (267.0, 0.0, 277.0, 176.0))
    """

    paper: str
    width_mm: float
    height_mm: float
    row: int
    column: int
    rows: int
    columns: int
    tile_mm: tuple[float, float, float, float]
    svg: str


def _f(v: float) -> str:
    s = f"{v:.3f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _grid(width: float, height: float, tile_w: float, tile_h: float) -> tuple[int, int]:
    """(columns, rows) of tiles overlapping by OVERLAP_MM that cover width x height."""
    cols = max(1, math.ceil((width - OVERLAP_MM) / (tile_w - OVERLAP_MM) - 1e-9))
    rows = max(1, math.ceil((height - OVERLAP_MM) / (tile_h - OVERLAP_MM) - 1e-9))
    return cols, rows


def _layout(paper: str, width: float, height: float):
    """(sheet width, sheet height, tile width, tile height, columns, rows), fewer sheets first, portrait on ties."""
    name, pw, ph = PAPERS[paper]
    best = None
    for sw, sh in ((pw, ph), (ph, pw)):
        tw, th = sw - 2 * MARGIN_MM, sh - 2 * MARGIN_MM - _FOOTER_MM
        cols, rows = _grid(width, height, tw, th)
        if best is None or cols * rows < best[4] * best[5]:
            best = (sw, sh, tw, th, cols, rows)
    return name, best


def _el(tag: str, text: str | None = None, **attrs) -> ET.Element:
    el = ET.Element(tag, {k.rstrip("_").replace("_", "-"): str(v) for k, v in attrs.items()})
    if text is not None:
        el.text = text
    return el


def _cross(x: float, y: float) -> ET.Element:
    c = _CROSS_MM
    return _el("path", d=f"M {_f(x - c)},{_f(y)} H {_f(x + c)} M {_f(x)},{_f(y - c)} V {_f(y + c)}", stroke="#000",
               stroke_width="0.2", fill="none", class_="registration")


def tile_template(template: str, paper: str = "a4") -> list[Sheet]:
    """The template SVG cut into overlapping tiles on sheets of ``paper`` (``"a4"`` or ``"letter"``).

    Parameters
    ----------
    template : str
        A layout template (:func:`~embroact.export.pictures.template.template_svg`; any SVG drawn in
        mm with a ``viewBox``).
    paper : str
        ``"a4"`` or ``"letter"``.

    Returns
    -------
    list of Sheet
        Row by row, left to right.

    Raises
    ------
    ParameterError
        An unknown paper, a drawing without a ``viewBox``, or one that needs more than :data:`MAX_SHEETS`.

    Examples
    --------
    >>> drawing = '<svg xmlns="http://www.w3.org/2000/svg" width="400mm" height="100mm" viewBox="0 0 400 100"/>'
    >>> sheets = tile_template(drawing, "a4")
    >>> len(sheets), sheets[0].tile_mm  # 400 mm wide: two landscape sheets, 10 mm overlap
    (2, (0.0, 0.0, 277.0, 176.0))
    """
    key = str(paper).lower()
    if key not in PAPERS:
        raise ParameterError(f"paper must be one of {', '.join(PAPERS)}, got {paper!r}")
    root = ET.fromstring(template)
    box = root.get("viewBox")
    if box is None:
        raise ParameterError("template must be an SVG drawing in mm with a viewBox, got one without")
    vx, vy, w, h = (float(v) for v in box.split())
    name, (sw, sh, tw, th, cols, rows) = _layout(key, w, h)
    if rows * cols > MAX_SHEETS:
        raise ParameterError(f"a {_f(w)} x {_f(h)} mm template needs {rows * cols} {name} sheets at 1:1, more than "
                             f"{MAX_SHEETS}: print template.svg on a plotter or tile it in a drawing program")
    # tiles from the template's corner, each sharing OVERLAP_MM with the next; the last may run past the far edge
    step_x, step_y = tw - OVERLAP_MM, th - OVERLAP_MM
    over = (tw - step_x, th - step_y)
    xs = [vx + c * step_x for c in range(cols)]
    ys = [vy + r * step_y for r in range(rows)]
    marks = [(x + step_x + over[0] / 2.0, y) for x in xs[:-1] for y in (vy + h * 0.25, vy + h * 0.75)]
    marks += [(x, y + step_y + over[1] / 2.0) for y in ys[:-1] for x in (vx + w * 0.25, vx + w * 0.75)]
    content = [child for child in root if child.tag != f"{{{_SVG_NS}}}defs"]
    sheets = []
    for r, ty in enumerate(ys):
        for c, tx in enumerate(xs):
            k = r * cols + c + 1
            svg = _el("svg", xmlns=_SVG_NS, width=f"{_f(sw)}mm", height=f"{_f(sh)}mm",
                      viewBox=f"0 0 {_f(sw)} {_f(sh)}", version="1.1", class_="sheet")
            defs = ET.SubElement(svg, "defs")
            clip = ET.SubElement(defs, "clipPath", id=f"tile-{k}")
            clip.append(_el("rect", x=_f(MARGIN_MM), y=_f(MARGIN_MM), width=_f(tw), height=_f(th)))
            svg.append(_el("rect", x="0", y="0", width=_f(sw), height=_f(sh), fill="#fff"))
            tile = ET.SubElement(svg, "g", {"clip-path": f"url(#tile-{k})", "class": "tile"})
            moved = ET.SubElement(tile, "g", transform=f"translate({_f(MARGIN_MM - tx)},{_f(MARGIN_MM - ty)})")
            for child in content:
                part = copy.deepcopy(child)
                for el in part.iter():
                    el.tag = el.tag.rpartition("}")[2]  # the sheet declares the SVG namespace once
                    if el.get("id"):
                        el.set("id", f"s{k}-{el.get('id')}")
                moved.append(part)
            for x, y in marks:
                moved.append(_cross(x, y))
            _overlaps(svg, c, r, cols, rows, tw, th, over)
            svg.append(_el("rect", x=_f(MARGIN_MM), y=_f(MARGIN_MM), width=_f(tw), height=_f(th), fill="none",
                           stroke="#999", stroke_width="0.2", class_="tile-edge"))
            _footer(svg, sh, f"{name}: sheet {k} of {rows * cols} (row {r + 1} of {rows}, column {c + 1} of {cols}); "
                         "print at 100 % (actual size), then check the square")
            text = ET.tostring(svg, encoding="unicode")
            sheets.append(Sheet(name, sw, sh, r + 1, c + 1, rows, cols, (tx, ty, tw, th), text))
    return sheets


def _overlaps(svg: ET.Element, c: int, r: int, cols: int, rows: int, tw: float, th: float, over) -> None:
    """Shade the strips this sheet shares with its neighbours (``over``: their widths across and down [mm]) and
    dash their inner edges, where the neighbouring sheet's tile ends."""
    x0, y0, x1, y1 = MARGIN_MM, MARGIN_MM, MARGIN_MM + tw, MARGIN_MM + th
    ox, oy = over
    bands = []
    if c > 0:
        bands.append((x0, y0, ox, th, f"M {_f(x0 + ox)},{_f(y0)} V {_f(y1)}"))
    if c < cols - 1:
        bands.append((x1 - ox, y0, ox, th, f"M {_f(x1 - ox)},{_f(y0)} V {_f(y1)}"))
    if r > 0:
        bands.append((x0, y0, tw, oy, f"M {_f(x0)},{_f(y0 + oy)} H {_f(x1)}"))
    if r < rows - 1:
        bands.append((x0, y1 - oy, tw, oy, f"M {_f(x0)},{_f(y1 - oy)} H {_f(x1)}"))
    for x, y, bw, bh, edge in bands:
        svg.append(_el("rect", x=_f(x), y=_f(y), width=_f(bw), height=_f(bh), fill="#4477aa", fill_opacity="0.08",
                       class_="overlap"))
        svg.append(_el("path", d=edge, stroke="#4477aa", stroke_width="0.25", stroke_dasharray="2,1.5", fill="none",
                       class_="overlap-edge"))


def _footer(svg: ET.Element, sh: float, text: str) -> None:
    """The sheet's caption and its 10 mm check square, inside the printable margin under the tile."""
    y = sh - MARGIN_MM - CHECK_SQUARE_MM
    svg.append(_el("rect", x=_f(MARGIN_MM), y=_f(y), width=_f(CHECK_SQUARE_MM), height=_f(CHECK_SQUARE_MM),
                   fill="none", stroke="#000", stroke_width="0.2", class_="check-square"))
    svg.append(_el("text", "10 mm", x=_f(MARGIN_MM + CHECK_SQUARE_MM / 2), y=_f(y + CHECK_SQUARE_MM / 2 + 0.9),
                   font_size="2.5", text_anchor="middle", style=_FONT))
    svg.append(_el("text", text, x=_f(MARGIN_MM + CHECK_SQUARE_MM + 3.0), y=_f(y + CHECK_SQUARE_MM / 2 + 0.9),
                   font_size="2.8", style=_FONT, class_="sheet-caption"))


def template_pages_html(template: str, paper: str = "a4", *, title: str = "layout template") -> str:
    """One printable HTML file of the template's sheets (:func:`tile_template`), one sheet per page.

    Parameters
    ----------
    template : str
        The template SVG.
    paper : str, optional
        ``"a4"`` or ``"letter"``.
    title : str, optional
        The page's title.

    Returns
    -------
    str
        HTML.

    Examples
    --------
    >>> drawing = '<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="50mm" viewBox="0 0 100 50"/>'
    >>> html = template_pages_html(drawing, "letter")
    >>> html.count('class="sheet"'), "@page{size:215.9mm 279.4mm;margin:0}" in html
    (1, True)
    """
    from html import escape

    try:
        sheets = tile_template(template, paper)
    except ParameterError as exc:
        if "sheets at 1:1" not in str(exc):
            raise
        return (f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>{escape(title)}</title></head>'
                f"<body><p>{escape(str(exc))}.</p></body></html>\n")  # beyond what a printer and a table can use
    size = f"{_f(sheets[0].width_mm)}mm {_f(sheets[0].height_mm)}mm"
    style = (f"@page{{size:{size};margin:0}}body{{margin:0}}svg.sheet{{display:block;break-after:page}}"
             "svg.sheet:last-child{break-after:auto}")
    body = "".join(s.svg for s in sheets)
    return (f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>{escape(title)}: '
            f"{sheets[0].paper}, {len(sheets)} sheet(s)</title><style>{style}</style></head><body>{body}</body></html>\n")
