"""The printable layout template: true millimetres, tube paths with their free ends, hoop marks."""
import shutil
import struct
import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from embroact.export.pictures.template import template_svg
from embroact.patterns.centerline import Centerline
from embroact.patterns.design import MachineSettings, build_plan, design_from_dict
from embroact.patterns.params import ZigzagParams
from embroact.patterns.zigzag import zigzag

NS = "{http://www.w3.org/2000/svg}"


def _root(svg):
    return ET.fromstring(svg)  # raises on invalid XML


def _points(el):
    return np.array([[float(v) for v in p.split(",")] for p in el.get("points").split()])


def _length(xy):
    return float(np.hypot(*np.diff(xy, axis=0).T).sum())


def _by_class(root, tag, cls):
    return [e for e in root.iter(NS + tag) if e.get("class") == cls]


def _straight(name="A1"):
    return zigzag(Centerline.straight(100.0), ZigzagParams(7.0, 1.0), name=name)


def test_one_unit_is_one_millimetre_and_a_100_mm_tube_draws_100_mm():
    root = _root(template_svg(_straight()))
    w, h = (float(root.get(k).removesuffix("mm")) for k in ("width", "height"))
    vb = [float(v) for v in root.get("viewBox").split()]
    assert (vb[2], vb[3]) == (w, h)  # viewBox size = physical size in mm: 1 user unit = 1 mm
    axis, = _by_class(root, "polyline", "axis")
    assert _length(_points(axis)) == pytest.approx(100.0, abs=1e-9)
    ends = _by_class(root, "polyline", "free-end")
    assert [_length(_points(e)) for e in ends] == pytest.approx([30.0, 30.0])  # the default tube's end_margin_mm
    assert _points(ends[0]).tolist() == [[-30.0, 0.0], [0.0, 0.0]] and _points(ends[1]).tolist() == [[100.0, 0.0],
                                                                                                       [130.0, 0.0]]
    bar = next(e for e in root.iter(NS + "rect") if e.get("id") == "scale-bar-10mm")
    assert float(bar.get("width")) == 10.0


def test_hoop_field_and_centre_marks():
    """Records span x 0..100, y -3.5..3.5: the 160 x 120 mm field is centred on (50, 0), so in SVG
    coordinates (y down) it spans x -30..130, y -60..60, and the centre cross sits at (50, 0)."""
    root = _root(template_svg(_straight(), MachineSettings(hoop_width_mm=160.0, hoop_height_mm=120.0)))
    field, = _by_class(root, "rect", "hoop-field")
    assert [float(field.get(k)) for k in ("x", "y", "width", "height")] == [-30.0, -60.0, 160.0, 120.0]
    cross, = _by_class(root, "path", "centre-cross")
    assert cross.get("d") == "M 44,0 H 56 M 50,-6 V 6"


def test_curved_path_and_end_tangents():
    cl = Centerline.from_svg_path("M 0 0 A 40 40 0 0 1 60 30")
    root = _root(template_svg(zigzag(cl, ZigzagParams(7.0, 1.0), name="arc")))
    axis, = _by_class(root, "polyline", "axis")
    assert _length(_points(axis)) == pytest.approx(cl.length_mm, abs=0.01)  # 3-decimal coordinates
    head, tail = (_points(e) for e in _by_class(root, "polyline", "free-end"))
    pts = cl.points_mm * [1, -1]  # drawn with y negated
    t0 = (pts[0] - pts[1]) / np.hypot(*(pts[0] - pts[1]))
    assert head[0] == pytest.approx(pts[0] + 30.0 * t0, abs=1e-3) and head[1] == pytest.approx(pts[0], abs=1e-3)
    assert tail[0] == pytest.approx(pts[-1], abs=1e-3) and _length(tail) == pytest.approx(30.0, abs=1e-3)


def test_names_in_sewing_order_and_escaped():
    d = design_from_dict({"name": "t", "actuator": [
        {"name": "first <A> & °", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 40},
        {"name": "second", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 40,
         "origin_mm": [0, 30]}]})
    root = _root(template_svg(build_plan(d), d.machine))
    names = [e.text for e in _by_class(root, "text", "name")]
    assert names == ["1: first <A> & °", "2: second"]
    assert len(_by_class(root, "circle", "connector-end")) == len(_by_class(root, "circle", "sealed-end")) == 2


@pytest.mark.skipif(shutil.which("rsvg-convert") is None, reason="rsvg-convert not installed")
def test_an_independent_renderer_prints_it_at_actual_size(tmp_path):
    """librsvg at 254 dpi (10 px per mm): the PNG is the SVG's size in mm times 10 pixels."""
    svg = tmp_path / "t.svg"
    svg.write_text(template_svg(_straight()))
    png = tmp_path / "t.png"
    subprocess.run(["rsvg-convert", "--dpi-x", "254", "--dpi-y", "254", "-o", str(png), str(svg)], check=True)
    width_px, height_px = struct.unpack(">II", png.read_bytes()[16:24])
    root = _root(svg.read_text())
    for px, key in ((width_px, "width"), (height_px, "height")):  # within the pixel the renderer rounds up to
        assert abs(px - float(root.get(key).removesuffix("mm")) * 10) <= 1.0


def test_build_writes_the_template_with_the_designs_hoop(tmp_path):
    from embroact.export.report.build import build

    d = design_from_dict({"machine": {"hoop_width_mm": 150, "hoop_height_mm": 150}, "actuator": [
        {"name": "A", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 60}]})
    res = build(d, tmp_path)
    assert "template.svg" in res.files
    field, = _by_class(_root((tmp_path / "template.svg").read_text()), "rect", "hoop-field")
    assert (float(field.get("width")), float(field.get("height"))) == (150.0, 150.0)
