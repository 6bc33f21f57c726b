"""Every picture of every example and of 50 seeded random designs: no two labels overlap, none leaves its canvas.

The text boxes are read back from the SVG geometry (tests/svg_text_boxes.py: font size, string,
anchor and transforms), independent of the placement code; every example's pictures are also drawn
by two real renderers, librsvg (``rsvg-convert``) and Chromium, and Chromium's own text boxes
(``getBBox`` mapped to the document) are checked the same way. The bend chart's curves are read
from the path data: each leaves zero at its P0 to within a chart pixel.
"""
from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from embroact.export.files.designfile import load_design
from embroact.export.pictures import previews as pv
from embroact.export.report.stage import render_previews
from embroact.export.pictures.chart import chart_scale
from embroact.export.pictures.stitches import plan_svg
from embroact.export.pictures.template import template_svg
from embroact.patterns.design import default_design, design_from_dict
from embroact.predict.analysis import analyse
from svg_text_boxes import label_problems

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))
SEEDS = range(50)


def pictures(design) -> dict[str, str]:
    """Every SVG picture a build writes for ``design`` (stitch preview, template, bend chart, side view, 3D)."""
    analysis = analyse(design)
    out = {"preview.svg": plan_svg(analysis.plan), "template.svg": template_svg(analysis.plan, design.machine)}
    rendered = render_previews(analysis, mesh_suffix=".glb").files
    out.update({name: body for name, body in rendered.items() if name.endswith(".svg")})
    return out


def random_design(seed: int):
    """1-12 actuators, straight, curved (an arc path) or segmented, zigzag or cross, stacked down the hoop."""
    rng = np.random.default_rng(seed)
    actuators, y = [], 0.0
    for k in range(int(rng.integers(1, 13))):
        kind = ("straight", "curved", "segmented")[int(rng.integers(3))]

        def pattern():
            w = float(np.round(rng.uniform(4.0, 10.0), 2))
            if rng.random() < 0.5:
                return {"pattern": "zigzag", "width_mm": w, "interval_mm": 1.0}
            return {"pattern": "cross", "width_mm": w, "interval_mm": 1.4, "angle_deg": float(rng.integers(35, 50))}

        a = {"name": f"A{k + 1}" if rng.random() < 0.5 else f"actuator {k + 1}", "origin_mm": [-60.0, -y]}
        if kind == "straight":
            a.update(pattern(), length_mm=float(rng.integers(50, 120)))
            y += 22.0
        elif kind == "curved":
            r = float(rng.integers(40, 70))
            a.update(pattern(), path=f"M 0 0 A {r:g} {r:g} 0 0 1 {r:g} {r:g}")
            y += r + 22.0
        else:
            segs = [pattern() for _ in range(int(rng.integers(2, 4)))]
            # a cross segment needs four widths times tan(angle) of length
            a["segment"] = [{**seg, "length_mm": float(rng.integers(25, 50)) + 5.0 * seg["width_mm"]} for seg in segs]
            y += 22.0
        actuators.append(a)
    return design_from_dict({"name": f"random-{seed}", "machine": {"hoop_width_mm": 400.0, "hoop_height_mm": 400.0},
                             "actuator": actuators})


@pytest.fixture(scope="module")
def example_pictures():
    designs = {"default": default_design(), **{p.stem: load_design(p) for p in EXAMPLES}}
    return {(name, pic): svg for name, d in designs.items() for pic, svg in pictures(d).items()}


def test_every_example_picture_has_no_overlapping_or_clipped_label(example_pictures):
    assert len(example_pictures) >= 6 * 5
    bad = {key: p for key, svg in example_pictures.items() if (p := label_problems(svg))}
    assert not bad, bad


@pytest.mark.parametrize("seed", SEEDS)
def test_random_design_pictures_have_no_overlapping_or_clipped_label(seed):
    bad = {name: p for name, svg in pictures(random_design(seed)).items() if (p := label_problems(svg))}
    assert not bad, bad


@pytest.mark.skipif(shutil.which("rsvg-convert") is None, reason="rsvg-convert not installed")
def test_librsvg_draws_every_example_picture(example_pictures, tmp_path):
    for (name, pic), svg in example_pictures.items():
        src = tmp_path / f"{name}-{pic}"
        src.write_text(svg, encoding="utf-8")
        png = src.with_suffix(".png")
        run = subprocess.run(["rsvg-convert", "-w", "600", "-o", str(png), str(src)], capture_output=True, text=True)
        assert run.returncode == 0 and not run.stderr, (name, pic, run.stderr)
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 2000


_CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
_BOXES_JS = """
const out = [];
document.querySelectorAll('div.pic').forEach(div => {
  const svg = div.querySelector('svg'), vb = svg.viewBox.baseVal, rs = [];
  svg.querySelectorAll('text').forEach(t => {
    if (!t.textContent.trim()) return;
    const b = t.getBBox(), m = t.getCTM(), root = svg.getCTM().inverse().multiply(m);
    const ps = [[b.x, b.y], [b.x + b.width, b.y], [b.x, b.y + b.height], [b.x + b.width, b.y + b.height]]
      .map(([x, y]) => new DOMPoint(x, y).matrixTransform(root));
    rs.push([t.textContent, Math.min(...ps.map(p => p.x)), Math.min(...ps.map(p => p.y)),
             Math.max(...ps.map(p => p.x)), Math.max(...ps.map(p => p.y))]);
  });
  out.push({name: div.id, canvas: [vb.x, vb.y, vb.x + vb.width, vb.y + vb.height], boxes: rs});
});
document.body.setAttribute('data-boxes', JSON.stringify(out));
"""


@pytest.mark.skipif(_CHROMIUM is None, reason="chromium not installed")
def test_chromium_text_boxes_of_every_example_picture_are_apart_and_inside(example_pictures, tmp_path):
    divs = "".join(f'<div class="pic" id="{name}/{pic}">{svg}</div>' for (name, pic), svg in example_pictures.items())
    page = tmp_path / "pictures.html"
    page.write_text(f"<!doctype html><html><body>{divs}<script>{_BOXES_JS}</script></body></html>", encoding="utf-8")
    run = subprocess.run([_CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--dump-dom", page.as_uri()],
                         capture_output=True, text=True, timeout=180)
    found = re.search(r'data-boxes="([^"]*)"', run.stdout)
    assert found, run.stderr[-2000:]
    import html

    results = json.loads(html.unescape(found.group(1)))
    assert len(results) == len(example_pictures)
    bad = []
    for r in results:
        x0, y0, x1, y1 = r["canvas"]
        eps = 1e-3 * max(x1 - x0, y1 - y0)
        boxes = r["boxes"]
        for i, (text, a0, b0, a1, b1) in enumerate(boxes):
            if a0 < x0 - eps or b0 < y0 - eps or a1 > x1 + eps or b1 > y1 + eps:
                bad.append((r["name"], text, "leaves the canvas"))
            for other, c0, d0, c1, d1 in boxes[i + 1:]:
                # glyph boxes include the line's full ascent and descent: a sliver of 10 % is two lines touching
                tol = 0.1 * min(b1 - b0, d1 - d0)
                if min(a1, c1) - max(a0, c0) > tol and min(b1, d1) - max(b0, d0) > tol:
                    bad.append((r["name"], text, other))
    assert not bad, bad


def _curve_vertices(svg: str, series: int) -> np.ndarray:
    """The vertices of the first drawn curve polyline of ``series`` (SVG px)."""
    m = re.search(rf'<polyline class="curve" data-series="{series}"[^>]* points="([^"]+)"', svg)
    return np.array([[float(v) for v in p.split(",")] for p in m.group(1).split()])


@pytest.mark.parametrize("name", ["default", "three_actuators", "paper_cross", "designed_hook"])
def test_chart_curves_leave_zero_at_their_p0_within_a_pixel(name):
    design = default_design() if name == "default" else load_design(ROOT / "examples" / f"{name}.toml")
    analysis = analyse(design)
    curves = analysis.curves()
    svg = pv.bend_chart(analysis, curves)
    series = pv.bend_series(analysis, pv.chart_curves(analysis, curves))
    sc = chart_scale(series, width_px=pv.bend_chart_width_px(series))
    checked = 0
    for k, s in enumerate(series):
        if s.p0_kpa is None:
            continue
        xy = _curve_vertices(svg, k)
        zero = float(sc.y_px(0.0))
        off = np.flatnonzero(np.abs(xy[:, 1] - zero) > 0.5)
        assert len(off), f"series {k} never leaves zero"
        i = int(off[0])
        # the curve runs flat up to vertex i - 1 and rises after it: that vertex is P0
        assert np.all(np.abs(xy[:i, 1] - zero) <= 0.5)
        assert xy[i - 1, 0] == pytest.approx(float(sc.x_px(s.p0_kpa)), abs=1.0), (k, s.label)
        checked += 1
    assert checked >= 1
