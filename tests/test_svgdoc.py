"""The pictures' SVG documents (export/pictures/svgdoc.py) against svgwrite, which they were first drawn with.

svgwrite is no longer imported by the package (its import is about 40 ms of every build), but the
test environment has it (the benchmark charts draw with it): every picture of a build, drawn once
with svgdoc and once with svgwrite's ``Drawing(profile="full", debug=False)`` in its place, must be
the same text, byte for byte.
"""
import functools
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import embroact
from embroact.export.pictures import svgdoc
from embroact.export.report.stage import previews_stage
from embroact.export.pictures.shapefit import shape_overlay_svg

svgwrite = pytest.importorskip("svgwrite")
ROOT = Path(__file__).resolve().parents[1]
SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture
def with_svgwrite(monkeypatch):
    """Draw with svgwrite instead of svgdoc while the fixture is active."""
    def use():
        monkeypatch.setattr(svgdoc, "Drawing", functools.partial(svgwrite.Drawing, profile="full", debug=False))
    return use


def _pictures(out: Path) -> dict[str, str]:
    return {p.name: p.read_text(encoding="utf-8") for p in sorted(out.iterdir()) if p.suffix in (".svg", ".html")}


@pytest.mark.parametrize("design", ["default", "examples/three_actuators.toml", "examples/designed_hook.toml"])
def test_build_pictures_are_svgwrites_bytes(design, tmp_path, with_svgwrite):
    d = embroact.default_design() if design == "default" else embroact.load_design(ROOT / design)
    ours, theirs = tmp_path / "ours", tmp_path / "theirs"
    ours.mkdir()
    theirs.mkdir()
    analysis, stages = embroact.analyse(d), (previews_stage(),)
    embroact.build(d, ours, analysis=analysis, stages=stages)
    with_svgwrite()
    embroact.build(d, theirs, analysis=analysis, stages=stages)
    got, want = _pictures(ours), _pictures(theirs)
    assert set(got) == set(want) and {"preview.svg", "template.svg", "bend.svg", "shape.svg", "shape3d.svg"} <= set(got)
    for name in want:
        assert got[name] == want[name], name


def test_shape_overlay_is_svgwrites_bytes(with_svgwrite):
    s = np.linspace(0.0, 1.0, 21)[:, None]
    args = (np.hstack([100 * s, 0 * s]), np.hstack([100 * s, 3 * s ** 2]), [50.0])
    kwargs = {"title": "a <hook> & more", "caption": ["RMSE 0.1 mm", "max 0.2 mm"]}
    ours = shape_overlay_svg(*args, **kwargs)
    with_svgwrite()
    assert ours == shape_overlay_svg(*args, **kwargs)


def test_document_reads_back_with_every_shape():
    """Independently of svgwrite: each factory's attributes as SVG names them, read back by a parser."""
    dwg = svgdoc.Drawing(size=("40mm", "20mm"), viewBox="0 0 40 20")
    clip = dwg.defs.add(dwg.clipPath(id="box"))
    clip.add(dwg.rect((1, 2), (3, 4)))
    g = dwg.add(dwg.g(class_="layer", stroke_width=0.5, fill=None, stroke=""))
    g.set_desc("tip: <here>")
    g.add(dwg.circle((5.5, 6), 1.25))
    g.add(dwg.line((0, 1), (2, 3), stroke_dasharray="1,2"))
    g.add(dwg.polyline([(0, 0), (1.5, 2)]))
    g.add(dwg.polygon([("0", "1"), ("2", "3"), ("4", "5")], **{"data-kpa": "100"}))
    g.add(dwg.path(d="M 0,0 L 1,1"))
    g.add(dwg.text("x < y & z", insert=(7, 8), font_size=3))
    root = ET.fromstring(dwg.tostring())
    assert root.tag == SVG + "svg"
    assert (root.get("width"), root.get("height"), root.get("viewBox")) == ("40mm", "20mm", "0 0 40 20")
    assert [c.tag for c in root] == [SVG + "defs", SVG + "g"]
    assert root[0][0][0].attrib == {"x": "1", "y": "2", "width": "3", "height": "4"}
    layer = root[1]
    assert layer.attrib == {"class": "layer", "stroke-width": "0.5"}  # None and "" left out
    kids = list(layer)
    assert [k.tag[len(SVG):] for k in kids] == ["title", "circle", "line", "polyline", "polygon", "path", "text"]
    assert kids[0].text == "tip: <here>"
    assert kids[1].attrib == {"cx": "5.5", "cy": "6", "r": "1.25"}
    assert kids[2].attrib == {"x1": "0", "y1": "1", "x2": "2", "y2": "3", "stroke-dasharray": "1,2"}
    assert kids[3].get("points") == "0,0 1.5,2" and kids[4].get("points") == "0,1 2,3 4,5"
    assert kids[4].get("data-kpa") == "100" and kids[5].get("d") == "M 0,0 L 1,1"
    assert (kids[6].text, kids[6].get("x"), kids[6].get("y"), kids[6].get("font-size")) == ("x < y & z", "7", "8", "3")
