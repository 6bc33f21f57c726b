"""Rich display (Jupyter) and summary reprs of the value classes; the import direction they keep."""
import json
import math
import subprocess
import sys
import xml.etree.ElementTree as ET
from html.parser import HTMLParser
from pathlib import Path

import pytest

import embroact
from embroact.export.files.designfile import load_design
from embroact.export.pictures.stitches import plan_svg
from embroact.patterns.base import display
from embroact.patterns.base.errors import ParameterError, PatternError
from embroact.patterns.plan import Command as C, Role as R, StitchPlan
from embroact.predict.curve import ActuatorModel, curve
from embroact.predict.shape import BentShape

ROOT = Path(__file__).resolve().parents[1]
SVG = "{http://www.w3.org/2000/svg}"


class _Cells(HTMLParser):
    """Text of every <td>, and how many <svg> elements the fragment holds."""

    def __init__(self):
        super().__init__()
        self.cells, self.svgs, self._in = [], 0, False

    def handle_starttag(self, tag, attrs):
        self._in = tag == "td"
        if tag == "td":
            self.cells.append("")
        self.svgs += tag == "svg"

    def handle_endtag(self, tag):
        self._in = False if tag == "td" else self._in

    def handle_data(self, data):
        if self._in:
            self.cells[-1] += data


def _cells(html):
    p = _Cells()
    p.feed(html)
    return p


def _model(*, p0_kpa):
    return ActuatorModel(pattern="zigzag", length_mm=100.0, r0_mm=2.58, beta0_deg=0.0, outer_radius_mm=1.5,
                         inner_radius_mm=1.0, g_e_mpa=1.0, g_mpa=2.7, p0_kpa=p0_kpa)


@pytest.fixture(scope="module")
def analysis():
    return embroact.analyse(embroact.default_design())


def test_plan_repr_summarises_instead_of_dumping_arrays():
    plan = StitchPlan.from_records([(0.0, 0.0, C.STITCH, R.TIE_IN), (2.0, 3.5, C.STITCH, R.LEG),
                                    (2.0, 3.5, C.END, R.CONTROL)], name="demo")
    assert repr(plan) == "StitchPlan('demo': 3 records, 2 stitches, 0 actuators, extent 2.0 x 3.5 mm)"


def test_default_plan_repr_names_its_actuator_and_extent(analysis):
    # the paper's actuator: 100 mm long, 7 mm wide; one line, no array dump
    text = repr(analysis.plan)
    assert text.startswith("StitchPlan('paper-zigzag': ") and "1 actuator (A1)" in text
    assert "extent 100.0 x 7.0 mm" in text and "\n" not in text and "array" not in text


def test_curve_repr_counts_pressures_range_method_and_statuses():
    c = curve(_model(p0_kpa=25.0), [0.0, 10.0, 200.0], method="stable-analytic-trace")
    # below P0 = 25 kPa the tube only inflates; 200 kPa bends
    assert repr(c) == ("Curve(3 pressures, 0-200 kPa, method stable-analytic-trace, calibration 'given'; "
                       "INFLATION 2, BENDING 1)")


def test_analysis_and_shape_reprs(analysis):
    act = analysis.actuators[0]
    assert repr(act) == f"ActuatorAnalysis('A1': zigzag, w 7 mm, l0 100 mm, r0 {act.derived.r0_mm:.4g} mm; " \
                        f"G 2.7 MPa, P0 {act.model.p0_kpa:.4g} kPa)"
    assert repr(analysis) == f"DesignAnalysis('paper-zigzag': {repr(act)[len('ActuatorAnalysis('):-1]})"
    assert repr(BentShape.chain([50.0, 50.0], [30.0, 60.0])) == "BentShape(2 pieces, 100 mm, turning 90 deg)"


def test_design_and_plan_show_the_stitch_preview(analysis):
    design = embroact.default_design()
    assert design._repr_svg_() == plan_svg(embroact.build_plan(design)) == analysis.plan._repr_svg_()
    assert ET.fromstring(design._repr_svg_()).tag == SVG + "svg"


def test_curve_shows_its_bend_chart():
    root = ET.fromstring(curve(_model(p0_kpa=25.0), [0.0, 50.0, 100.0, 200.0])._repr_svg_())
    lines = [e for e in root.iter(SVG + "polyline") if e.get("class") == "curve"]
    assert len(lines) == 1 and len(lines[0].get("points").split()) == 4


def test_bent_shape_shows_its_side_view():
    # two pieces bent 30 + 60 deg: one state drawn, at the total bend, without a pressure
    root = ET.fromstring(BentShape.chain([50.0, 50.0], [30.0, 60.0])._repr_svg_())
    states = [g for g in root.iter(SVG + "g") if g.get("class") == "state"]
    assert len(states) == 1 and math.isclose(float(states[0].get("data-theta-deg")), 90.0)
    assert "1: 90.0 deg" in [t.text for t in root.iter(SVG + "text")]


def test_analysis_html_tables_and_pictures(analysis):
    act = analysis.actuators[0]
    parsed = _cells(analysis._repr_html_())
    assert parsed.cells[:5] == ["A1", "zigzag", "7", "1", ""]     # w 7 mm, s 1 mm, no cross angle
    assert parsed.cells[8] == "2.7"                                # the paper's G
    assert parsed.svgs == 3                                        # stitches, bend chart, side view
    one = _cells(act._repr_html_())
    assert one.cells == parsed.cells and one.svgs == 1


def test_segmented_design_shows_a_row_per_segment_and_its_chart_and_side_view():
    analysis = embroact.analyse(load_design(ROOT / "examples" / "designed_hook.toml"))
    html = analysis._repr_html_()
    parsed = _cells(html)
    assert parsed.svgs == 3 and "no bend chart" not in html  # stitches, bend chart, side view
    names = [c for c in parsed.cells if c.startswith("A1")]
    n = len(analysis.actuators[0].segments)
    assert n >= 2 and names == [f"A1 segment {k}" for k in range(n)]
    for seg in analysis.actuators[0].segments:  # each segment's own G from its calibration
        assert f"{seg.model.g_mpa:.4g}" in parsed.cells
    one = analysis.actuators[0]._repr_html_()
    assert _cells(one).svgs == 1 and f"whole strip: sum of its {n} segments" in one


def test_a_renderer_that_cannot_draw_falls_back_to_the_text_repr():
    class Broken:
        _repr_svg_ = display.repr_svg

    display.register(Broken, "image/svg+xml", f"{__name__}:_refuse")
    assert Broken()._repr_svg_() is None


def _refuse(obj):
    raise PatternError("cannot draw this")


def test_register_refuses_unknown_mime_and_bad_targets():
    with pytest.raises(ParameterError, match="mime must be one of image/svg"):
        display.register("x.Y", "image/png", "m:f")
    with pytest.raises(ParameterError, match="target must be 'module:function'"):
        display.register("x.Y", "text/html", "m.f")


def test_every_value_class_finds_a_renderer():
    from embroact.predict.analysis import ActuatorAnalysis, DesignAnalysis

    for cls, mime in ((embroact.Design, "image/svg+xml"), (StitchPlan, "image/svg+xml"),
                      (DesignAnalysis, "text/html"), (ActuatorAnalysis, "text/html"),
                      (embroact.Curve, "image/svg+xml"), (BentShape, "image/svg+xml")):
        assert callable(display.renderer(cls, mime)), cls


def test_export_is_imported_only_when_a_picture_is_asked_for():
    code = ("import json, sys\nfrom embroact.predict.analysis import analyse\nfrom embroact.patterns.design import "
            "default_design\na = analyse(default_design()); repr(a); repr(a.curves()[0])\n"
            "before = 'embroact.export.pictures.display' in sys.modules\na._repr_html_()\n"
            "print(json.dumps([before, 'embroact.export.pictures.display' in sys.modules]))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == [False, True]
