"""Side view: the bent strip is a circular arc of length l0 and angle theta, hanging from the clamp."""
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from embroact.export.pictures.sideview import SidePanel, bent_line_mm, side_view_svg
from embroact.patterns.params import FABRIC_THICKNESS_MM
from embroact.patterns.base.errors import ParameterError

SVG = "{http://www.w3.org/2000/svg}"


def test_quarter_turn_end_point_by_hand():
    # theta = 90 deg, l0 = 100: R = 200/pi; the end is R to the back (-x) and R down.
    r = 200.0 / math.pi
    end = bent_line_mm(100.0, 90.0, 0.0)[-1]
    assert end == pytest.approx([-r, -r], abs=1e-12)
    # a line 3 mm on the thread side ends 3 mm further down (its normal there points -z)
    assert bent_line_mm(100.0, 90.0, 3.0)[-1] == pytest.approx([-r, -r - 3.0], abs=1e-12)


@pytest.mark.parametrize("theta", [5.0, 60.0, 155.0, 300.0])
@pytest.mark.parametrize("offset", [0.0, 2.58, -FABRIC_THICKNESS_MM])
def test_points_on_the_offset_circle_within_tolerance(theta, offset):
    tol = 0.005
    pts = bent_line_mm(100.0, theta, offset, tolerance_mm=tol)
    kappa = math.radians(theta) / 100.0
    centre = np.array([-1.0 / kappa, 0.0])
    radius = 1.0 / kappa + offset
    assert np.hypot(*(pts - centre).T) == pytest.approx(radius, abs=1e-9)
    mids = (pts[1:] + pts[:-1]) / 2.0
    sagitta = radius - np.hypot(*(mids - centre).T)
    assert sagitta.max() <= tol
    # polyline length of the fabric line approaches l0
    if offset == 0.0:
        assert np.hypot(*np.diff(pts, axis=0).T).sum() == pytest.approx(100.0, rel=1e-4)


def test_straight_and_mirror():
    pts = bent_line_mm(80.0, 0.0, 1.0)
    assert pts.tolist() == [[1.0, 0.0], [1.0, -80.0]]
    pos, neg = bent_line_mm(100.0, 40.0, 0.0), bent_line_mm(100.0, -40.0, 0.0)
    assert neg[:, 0] == pytest.approx(-pos[:, 0]) and neg[:, 1] == pytest.approx(pos[:, 1])


def test_tiny_angle_matches_straight_limit():
    # no cancellation: sinc forms hold near theta = 0
    end = bent_line_mm(100.0, 1e-9, 0.0)[-1]
    assert end[1] == pytest.approx(-100.0, rel=1e-12)
    assert end[0] == pytest.approx(-100.0 * math.radians(1e-9) / 2.0 * 100.0 / 100.0, rel=1e-6)


def test_svg_has_one_group_per_finite_state():
    panel = SidePanel("A1", length_mm=100.0, r0_mm=2.58, pressure_kpa=[0, 100, 200, 250],
                      theta_deg=[0.0, 30.0, float("nan"), -20.0])
    root = ET.fromstring(side_view_svg([panel]))
    states = [g for g in root.iter(SVG + "g") if g.get("class") == "state"]
    assert [(g.get("data-pressure-kpa"), g.get("data-theta-deg")) for g in states] == [
        ("0", "0"), ("100", "30"), ("250", "-20")]
    for g in states:
        classes = [e.get("class") for e in g]
        assert "tube" in classes and "fabric" in classes


def test_svg_tube_outline_is_the_offset_band():
    panel = SidePanel("A1", length_mm=100.0, r0_mm=2.5, pressure_kpa=[150], theta_deg=[90.0])
    root = ET.fromstring(side_view_svg([panel]))
    tube = next(e for e in root.iter(SVG + "polygon") if e.get("class") == "tube")
    pts = np.array([[float(v) for v in p.split(",")] for p in tube.get("points").split()])
    # the clamp is drawn at some (dx, dy); positions relative to the first point (clamp, offset 0)
    rel = pts - pts[0]
    r = 200.0 / math.pi
    model = bent_line_mm(100.0, 90.0, 0.0)
    n = len(model)
    # first half of the outline is the fabric-side line, SVG y = -z
    assert rel[n - 1] == pytest.approx([-r, r], abs=2e-3)
    # the outline closes through the thread-side line at 2 r0, which starts 5 mm right of the clamp
    assert rel[-1] == pytest.approx([5.0, 0.0], abs=2e-3)


def test_deterministic_and_validated():
    panel = SidePanel("A1", length_mm=100.0, r0_mm=2.58, pressure_kpa=[0, 200], theta_deg=[0.0, 80.0])
    assert side_view_svg([panel]) == side_view_svg([panel])
    with pytest.raises(ParameterError, match="length_mm must be in"):
        SidePanel("x", length_mm=-1.0, r0_mm=2.0, pressure_kpa=[0], theta_deg=[0])
    with pytest.raises(ParameterError, match="one value per pressure"):
        SidePanel("x", length_mm=10.0, r0_mm=2.0, pressure_kpa=[0, 1], theta_deg=[0])
    with pytest.raises(ParameterError, match="at least one"):
        side_view_svg([])


def _text_boxes(svg: str):
    """(text, box, class) of every text in a side view, boxes estimated as the placer estimates them."""
    import xml.etree.ElementTree as ET

    from embroact.export.pictures.labels import text_box

    ns = "{http://www.w3.org/2000/svg}"
    root = ET.fromstring(svg)
    for t in root.iter(f"{ns}text"):
        if t.text:
            yield t.text, text_box(t.text, float(t.get("x")), float(t.get("y")), float(t.get("font-size")),
                                   t.get("text-anchor", "start")), t.get("class")


@pytest.mark.parametrize("theta", [[0.0, 0.0, 0.0, -10.4, -23.2], [0.0, 0.0, 0.0, -68.0, -126.0]])
def test_a_strip_bending_right_keeps_its_labels_off_the_clamp_and_the_edge(theta):
    # the coupon's first hoop-2 panels: states 1-3 unbent end at one tip ("1,2,3"), 4-5 bend to the right
    import xml.etree.ElementTree as ET

    from embroact.export.pictures.labels import Box

    panel = SidePanel("09 cross", 100.0, 2.58, [0.0, 70.0, 150.0, 220.0, 300.0], theta)
    svg = side_view_svg([panel])
    root = ET.fromstring(svg)
    ns = "{http://www.w3.org/2000/svg}"
    width, height = (float(v) for v in root.get("viewBox").split()[2:])
    rect = next(r for r in root.iter(f"{ns}rect") if r.get("class") == "clamp")
    x, y, w, h = (float(rect.get(k)) for k in ("x", "y", "width", "height"))
    clamp = Box(x, y, x + w, y + h)
    boxes = list(_text_boxes(svg))
    fabric = next(b for t, b, _ in boxes if t == "fabric")
    assert not fabric.overlaps(clamp) and fabric.x1 <= clamp.x0
    assert {t for t, _, c in boxes if c == "tip"} >= {"1,2,3"}
    for t, b, _ in boxes:
        assert 1.0 <= b.x0 and b.x1 <= width - 1.0 and 0.0 <= b.y0 and b.y1 <= height, t
