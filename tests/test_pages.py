"""The layout template tiled on A4 and Letter: inside the printable margin, overlapping, covering it all, 1:1.

Expected values are the papers' own sizes (ISO 216 A4 210 x 297 mm; US Letter 8.5 x 11 in), the
margin and overlap asked for, and the pages Chromium prints from the HTML file (their count and
PDF media boxes in points, 72 per inch), none of which the tiling code computes.
"""
from __future__ import annotations

import re
import shutil
import subprocess
import xml.etree.ElementTree as ET

import pytest

from embroact.export.pictures.pages import MARGIN_MM, OVERLAP_MM, template_pages_html, tile_template
from embroact.export.pictures.template import template_svg
from embroact.patterns.base.errors import ParameterError
from embroact.patterns.design import build_plan, default_design, design_from_dict

SVG = "{http://www.w3.org/2000/svg}"
PAPER_MM = {"a4": (210.0, 297.0), "letter": (8.5 * 25.4, 11.0 * 25.4)}


def _template(hoop_mm: float) -> str:
    d = design_from_dict({"machine": {"hoop_width_mm": hoop_mm, "hoop_height_mm": hoop_mm}, "actuator": [
        {"name": "A1", "pattern": "zigzag", "width_mm": 7.0, "interval_mm": 1.0, "length_mm": 100.0}]})
    return template_svg(build_plan(d), d.machine)


def _canvas(svg: str) -> tuple[float, float, float, float]:
    x, y, w, h = (float(v) for v in ET.fromstring(svg).get("viewBox").split())
    return x, y, w, h


@pytest.mark.parametrize("paper", ["a4", "letter"])
@pytest.mark.parametrize("hoop_mm", [100.0, 200.0, 400.0])
def test_tiles_cover_the_template_overlap_and_stay_inside_the_margin(paper, hoop_mm):
    template = _template(hoop_mm)
    x, y, w, h = _canvas(template)
    sheets = tile_template(template, paper)
    short, long_ = PAPER_MM[paper]
    for s in sheets:
        assert sorted((s.width_mm, s.height_mm)) == pytest.approx([short, long_], abs=1e-9)
        root = ET.fromstring(s.svg)
        assert root.get("width") == f"{s.width_mm:g}mm" and root.get("viewBox") == f"0 0 {s.width_mm:g} {s.height_mm:g}"
        # the tile's clip and every mark lie at least the margin inside the sheet
        (clip,) = root.iter(SVG + "clipPath")
        r = clip[0]
        cx, cy, cw, ch = (float(r.get(k)) for k in ("x", "y", "width", "height"))
        assert cx >= MARGIN_MM and cy >= MARGIN_MM
        assert cx + cw <= s.width_mm - MARGIN_MM + 1e-9 and cy + ch <= s.height_mm - MARGIN_MM + 1e-9
        (square,) = [e for e in root.iter(SVG + "rect") if e.get("class") == "check-square"]
        assert (float(square.get("width")), float(square.get("height"))) == (10.0, 10.0)  # user unit = 1 mm
        assert float(square.get("x")) >= MARGIN_MM
        assert float(square.get("y")) + 10.0 <= s.height_mm - MARGIN_MM + 1e-9
        assert (cw, ch) == pytest.approx(s.tile_mm[2:], abs=1e-9)
    # the tiles cover the whole template, and neighbours share at least the overlap
    cols, rows = sheets[0].columns, sheets[0].rows
    assert len(sheets) == cols * rows
    xs = sorted({s.tile_mm[0] for s in sheets})
    ys = sorted({s.tile_mm[1] for s in sheets})
    tw, th = sheets[0].tile_mm[2:]
    assert xs[0] == pytest.approx(x) and ys[0] == pytest.approx(y)
    assert xs[-1] + tw >= x + w - 1e-9 and ys[-1] + th >= y + h - 1e-9
    assert all(b - a <= tw - OVERLAP_MM + 1e-9 for a, b in zip(xs, xs[1:]))
    assert all(b - a <= th - OVERLAP_MM + 1e-9 for a, b in zip(ys, ys[1:]))


def test_a_400_mm_hoop_needs_several_sheets_and_a_100_mm_one_a_single_sheet():
    assert len(tile_template(_template(400.0), "a4")) > 1
    assert len(tile_template(_template(100.0), "a4")) == 1


def test_sheets_carry_their_place_and_overlap_edges():
    sheets = tile_template(_template(400.0), "letter")
    for s in sheets:
        assert f"sheet {(s.row - 1) * s.columns + s.column} of {len(sheets)}" in s.svg and "print at 100 %" in s.svg
        edges = s.svg.count('class="overlap-edge"')
        assert edges == (s.column > 1) + (s.column < s.columns) + (s.row > 1) + (s.row < s.rows)


def test_unknown_paper_is_refused_in_one_line():
    with pytest.raises(ParameterError, match=r"^paper must be one of a4, letter, got 'a3'$"):
        tile_template(_template(200.0), "a3")


_CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.mark.skipif(_CHROMIUM is None, reason="chromium not installed")
@pytest.mark.parametrize("paper, points", [("a4", (595.28, 841.89)), ("letter", (612.0, 792.0))])
def test_chromium_prints_one_page_per_sheet_at_the_papers_size(tmp_path, paper, points):
    template = template_svg(build_plan(default_design()), default_design().machine)
    sheets = tile_template(template, paper)
    page = tmp_path / "t.html"
    page.write_text(template_pages_html(template, paper), encoding="utf-8")
    pdf = tmp_path / "t.pdf"
    subprocess.run([_CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--no-pdf-header-footer",
                    f"--print-to-pdf={pdf}", page.as_uri()], capture_output=True, timeout=180, check=False)
    data = pdf.read_bytes()
    boxes = [tuple(float(v) for v in b.split()) for b in re.findall(rb"/MediaBox\s*\[([^\]]*)\]", data)]
    assert len(boxes) == len(sheets)
    want = points if sheets[0].width_mm < sheets[0].height_mm else points[::-1]
    for box in boxes:
        assert (box[2] - box[0], box[3] - box[1]) == pytest.approx(want, abs=1.0)
