"""Pressure-bend chart: tick rules and data-to-SVG coordinates checked against hand-computed positions."""
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from embroact.export.pictures.chart import Scale, Series, bend_chart_svg, chart_scale, nice_ticks
from embroact.patterns.base.errors import ParameterError

SVG = "{http://www.w3.org/2000/svg}"


def _parse(svg: str):
    return ET.fromstring(svg)


def _points(el):
    return np.array([[float(v) for v in pair.split(",")] for pair in el.get("points").split()])


def _simple():
    return Series("A", [0, 100, 200, 300], [0.0, 0.0, 50.0, 100.0],
                  status=("inflation", "inflation", "bending", "locked"), p0_kpa=150.0,
                  measured_pressure_kpa=[120.0, 240.0], measured_theta_deg=[10.0, 80.0])


# ----------------------------------------------------------------------------- ticks
@pytest.mark.parametrize("low, high, expected", [
    (0.0, 290.0, (0, 50, 100, 150, 200, 250, 300)),          # 290/7 = 41 -> 50
    (0.0, 100.0, (0, 20, 40, 60, 80, 100)),                  # 100/7 = 14.3 -> 20
    (-48.0, 0.0, (-50, -40, -30, -20, -10, 0)),              # 48/7 = 6.9 -> 10
    (0.0, 0.7, (0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7)),     # 0.1, 8 ticks fit
    (-45.6, 160.0, (-50, 0, 50, 100, 150, 200)),             # 205.6/7 = 29 -> 50
])
def test_nice_ticks_hand_values(low, high, expected):
    assert nice_ticks(low, high) == pytest.approx(expected, abs=1e-12)


@settings(max_examples=200, deadline=None)
@given(st.floats(-1e4, 1e4, allow_subnormal=False), st.floats(1e-3, 1e4))  # subnormal lows underflow in low/step
def test_nice_ticks_cover_range_with_125_step(low, span):
    ticks = nice_ticks(low, low + span)
    assert 2 <= len(ticks) <= 8
    assert ticks[0] <= low and ticks[-1] >= low + span
    step = ticks[1] - ticks[0]
    mantissa = step / 10 ** math.floor(math.log10(step) + 1e-12)
    assert min(abs(mantissa - m) for m in (1, 2, 5, 10)) < 1e-6
    assert np.allclose(np.diff(ticks), step, rtol=1e-9, atol=1e-12 * max(abs(t) for t in ticks))


def test_nice_ticks_rejects_reversed_range():
    with pytest.raises(ParameterError, match="low <= high"):
        nice_ticks(2.0, 1.0)


# ----------------------------------------------------------------------------- mapping
def test_scale_maps_corners_and_midpoints():
    sc = Scale(0.0, 300.0, -50.0, 150.0, left_px=64.0, top_px=46.0, width_px=640.0, height_px=342.0)
    assert sc.x_px(0.0) == 64.0 and sc.x_px(300.0) == 64.0 + 640.0
    assert sc.x_px(150.0) == pytest.approx(64.0 + 320.0)
    assert sc.y_px(150.0) == 46.0 and sc.y_px(-50.0) == 46.0 + 342.0
    assert sc.y_px(0.0) == pytest.approx(46.0 + 342.0 * 150.0 / 200.0)


def test_chart_scale_for_default_size():
    # ticks: x 0..300 (step 50), y 0..100 (step 20); plot box 720 - 64 - 16 wide (legend below), 440 - 46 - 52 high
    sc = chart_scale([_simple()])
    assert (sc.x_min_kpa, sc.x_max_kpa, sc.y_min_deg, sc.y_max_deg) == (0.0, 300.0, 0.0, 100.0)
    assert (sc.left_px, sc.top_px, sc.width_px, sc.height_px) == (64.0, 46.0, 640.0, 342.0)


def test_polyline_points_land_on_hand_computed_coordinates():
    root = _parse(bend_chart_svg([_simple()]))
    (line,) = [e for e in root.iter(SVG + "polyline") if e.get("class") == "curve"]
    expected = [(64.0, 388.0), (64.0 + 640.0 / 3, 388.0), (64.0 + 2 * 640.0 / 3, 46.0 + 171.0), (704.0, 46.0)]
    assert np.abs(_points(line) - np.array(expected)).max() <= 0.006  # coordinates are written to 0.01


def test_p0_line_and_measured_points():
    root = _parse(bend_chart_svg([_simple()]))
    (p0,) = [e for e in root.iter(SVG + "line") if e.get("class") == "p0"]
    assert float(p0.get("x1")) == pytest.approx(64.0 + 640.0 / 2, abs=0.006)
    assert float(p0.get("y1")) == 46.0 and float(p0.get("y2")) == 388.0
    circles = [e for e in root.iter(SVG + "circle") if e.get("class") == "measured"]
    got = [(float(c.get("cx")), float(c.get("cy"))) for c in circles]
    want = [(64 + 640 * 120 / 300, 46 + 342 * 0.9), (64 + 640 * 240 / 300, 46 + 342 * 0.2)]
    assert np.abs(np.array(got) - np.array(want)).max() <= 0.006


def test_status_bands_split_halfway_between_samples():
    root = _parse(bend_chart_svg([_simple()]))
    rects = [e for e in root.iter(SVG + "rect") if (e.get("class") or "").startswith("status")]
    spans = [(e.get("class").split()[1], float(e.get("x")), float(e.get("x")) + float(e.get("width"))) for e in rects]
    x = lambda p: 64 + 640 * p / 300  # noqa: E731
    assert [s[0] for s in spans] == ["inflation", "bending", "locked"]
    assert spans[0][1:] == pytest.approx((x(0), x(150)), abs=0.011)
    assert spans[1][1:] == pytest.approx((x(150), x(250)), abs=0.011)
    assert spans[2][1:] == pytest.approx((x(250), x(300)), abs=0.011)
    # single design: bands fill the plot height
    assert all(float(e.get("height")) == 342.0 for e in rects)


def test_several_series_get_ribbons_and_negative_angles():
    a = _simple()
    b = Series("B", [0, 100, 200, 300], [0.0, -10.0, -30.0, -48.0], status=["inflation", "bending", "bending",
                                                                            "unstable"])
    svg = bend_chart_svg([a, b])
    root = _parse(svg)
    sc = chart_scale([a, b])
    assert sc.y_min_deg == -50.0 and sc.y_max_deg == 100.0  # 148/7 = 21: steps 10, 20 need > 8 ticks; 50 fits
    lines = [e for e in root.iter(SVG + "polyline") if e.get("class") == "curve"]
    assert [e.get("data-series") for e in lines] == ["0", "1"]
    last = _points(lines[1])[-1]
    assert np.abs(last - [sc.x_px(300.0), sc.y_px(-48.0)]).max() <= 0.006
    ribbons = [e for e in root.iter(SVG + "rect") if (e.get("class") or "").startswith("status")]
    assert {float(e.get("height")) for e in ribbons} == {8.0}  # 9 px rows, 1 px apart
    assert "lock-up" in svg and "unstable" in svg and ">B<" in svg


def test_nan_angles_break_the_line():
    s = Series("gap", [0, 10, 20, 30, 40], [0.0, 1.0, float("nan"), 3.0, 4.0])
    lines = [e for e in _parse(bend_chart_svg([s])).iter(SVG + "polyline") if e.get("class") == "curve"]
    assert [len(_points(e)) for e in lines] == [2, 2]


def test_status_codes_from_the_model_enum():
    from embroact.predict.status import Status

    s = Series("codes", [0, 100], [0.0, 5.0], status=np.array([Status.INFLATION, Status.BENDING], dtype=np.int8))
    assert s.status == ("inflation", "bending")


def test_same_input_same_bytes():
    assert bend_chart_svg([_simple()]) == bend_chart_svg([_simple()])


@pytest.mark.parametrize("kwargs, match", [
    (dict(pressure_kpa=[0, 1], theta_deg=[0.0]), "theta_deg must have one value per pressure"),
    (dict(pressure_kpa=[0, 1], theta_deg=[0, 1], status=["bending", "flying"]), "status must be one of"),
    (dict(pressure_kpa=[0, float("nan")], theta_deg=[0, 1]), "pressure_kpa must be finite"),
    (dict(pressure_kpa=[0], theta_deg=[0], measured_pressure_kpa=[1.0]), "must be given together"),
])
def test_bad_series_are_one_line_errors(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        Series("bad", **kwargs)


def test_empty_chart_rejected():
    with pytest.raises(ParameterError, match="at least one"):
        bend_chart_svg([])


# ----------------------------------------------------------------------------- validity and bands
def _coiling():
    """Bends to 100 deg, then the formula's 2000 deg past a validity limit, then a fill value."""
    return Series("Z", [0, 100, 200, 250, 300], [0.0, 40.0, 100.0, 2000.0, 3600.0],
                  status=("inflation", "bending", "bending", "coiled", "out_of_domain"))


def test_invalid_states_do_not_scale_the_angle_axis():
    sc = chart_scale([_coiling()])
    assert (sc.y_min_deg, sc.y_max_deg) == (0.0, 100.0)  # ticks 0..100: the 2000 and 3600 deg are not states


def test_beyond_validity_is_dashed_clipped_and_shaded_fill_values_not_drawn():
    root = _parse(bend_chart_svg([_coiling()]))
    polys = [e for e in root.iter(SVG + "polyline")]
    (curve,) = [e for e in polys if e.get("class") == "curve"]
    (beyond,) = [e for e in polys if e.get("class") == "beyond"]
    x = lambda p: 64 + 640 * p / 300  # noqa: E731
    assert _points(curve)[:, 0] == pytest.approx([x(0), x(100), x(200)], abs=0.006)
    # from the last valid point (200 kPa, 100 deg: the top of the box) to 250 kPa, clipped to the box
    assert _points(beyond)[0] == pytest.approx([x(200), 46.0], abs=0.006)
    assert _points(beyond)[:, 0] == pytest.approx([x(200), x(250)], abs=0.006)
    assert beyond.get("clip-path") == "url(#plot-box)" and beyond.get("stroke-dasharray") == "2,3"
    (clip,) = [e for e in root.iter(SVG + "clipPath")]
    assert clip.get("id") == "plot-box"
    names = [e.get("class").split()[1] for e in root.iter(SVG + "rect") if (e.get("class") or "").startswith("status")]
    assert names == ["inflation", "bending", "coiled", "out_of_domain"]
    texts = [t.text for t in root.iter(SVG + "text")]
    assert "beyond validity: coiled" in texts and "formula past validity" in texts


def test_band_polygon_follows_low_then_high_edge_over_drawn_points():
    s = Series("B", [0, 100, 200, 300], [0.0, 40.0, 80.0, 2000.0], status=("inflation", "bending", "bending", "kinked"),
               theta_low_deg=[0.0, 30.0, 60.0, 1500.0], theta_high_deg=[0.0, 50.0, 100.0, 2500.0])
    sc = chart_scale([s])
    assert (sc.y_min_deg, sc.y_max_deg) == (0.0, 100.0)  # the band's high edge at 200 kPa, not 2500
    root = _parse(bend_chart_svg([s]))
    (band,) = [e for e in root.iter(SVG + "polygon") if e.get("class") == "band"]
    x = lambda p: 64 + 640 * p / 300  # noqa: E731
    y = lambda a: 46 + 342 * (100 - a) / 100  # noqa: E731
    want = [(x(0), y(0)), (x(100), y(30)), (x(200), y(60)), (x(200), y(100)), (x(100), y(50)), (x(0), y(0))]
    assert np.abs(_points(band) - np.array(want)).max() <= 0.006
    assert "1-sigma band" in [t.text for t in root.iter(SVG + "text")]


def test_band_needs_both_edges_of_the_right_length():
    with pytest.raises(ParameterError, match="theta_low_deg and theta_high_deg must be given together"):
        Series("B", [0, 1], [0, 1], theta_low_deg=[0, 1])
    with pytest.raises(ParameterError, match="one value per pressure"):
        Series("B", [0, 1], [0, 1], theta_low_deg=[0], theta_high_deg=[0])


def test_chart_of_a_model_curve_with_validity_statuses():
    """The paper's w = 5 mm zigzag with the built-in G: the axis stops at the last valid state (< 360 deg)."""
    from embroact.patterns.params import Tube
    from embroact.predict.curve import ActuatorModel, curve
    from embroact.predict.derived import derive_from_values

    d = derive_from_values("zigzag", width_mm=5.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
    c = curve(ActuatorModel.from_derived(d, g_mpa=0.8, p0_kpa=50.0), np.arange(0.0, 301.0, 10.0))
    sc = chart_scale([Series.from_curve(c, label="w5")])
    assert sc.y_max_deg <= 400.0 and float(np.max(c.theta_deg)) > 2000.0


def test_status_bands_change_at_p0_when_a_sample_sits_there():
    # a breakpoint sample at P0 (the views sample there): inflation shaded up to P0 itself, not halfway on
    s = Series("A", [0, 50, 84.5, 90, 100], [0.0, 0.0, 0.0, 3.0, 8.0],
               status=["inflation"] * 3 + ["bending"] * 2, p0_kpa=84.5)
    root = _parse(bend_chart_svg([s]))
    rects = [e for e in root.iter(SVG + "rect") if (e.get("class") or "").startswith("status")]
    x = lambda p: 64 + 640 * p / 100  # noqa: E731  (ticks 0..100 kPa, plot 640 px wide)
    spans = [(e.get("class").split()[1], float(e.get("x")), float(e.get("x")) + float(e.get("width"))) for e in rects]
    assert spans == [("inflation", pytest.approx(x(0)), pytest.approx(x(84.5))),
                     ("bending", pytest.approx(x(84.5)), pytest.approx(x(100)))]
