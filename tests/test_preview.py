"""Stitch preview SVG: valid XML, drawn to scale in mm, every layer present, deterministic."""
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from h3_plans import generated_plans, hand_plan
from embroact.export.pictures.stitches import plan_svg
from embroact.patterns.base.errors import ParameterError
from embroact.patterns.plan import Command as C, Role as R

NS = {"s": "http://www.w3.org/2000/svg"}
LAYERS = ["fabric", "corridor", "tube", "centerline", "rails", "travel", "legs", "needle-points", "ties", "stops",
          "trims", "scale-bar", "params"]


def _segments_in(d):
    """Straight segments a path's data draws: per subpath (``M`` ...) one fewer than its points."""
    return sum(len(re.findall(r"-?[\d.]+,-?[\d.]+", sub)) - 1 for sub in d.split("M")[1:])


def _layer(root, name):
    g = root.find(f".//s:g[@id='{name}']", NS)
    assert g is not None, name
    return g


def test_layers_and_counts():
    plan = hand_plan(3)
    root = ET.fromstring(plan_svg(plan))
    for name in LAYERS:
        _layer(root, name)
    assert len(_layer(root, "needle-points").findall("s:circle", NS)) == plan.stitch_count
    assert len(_layer(root, "stops").findall("s:g", NS)) == 3
    assert len(_layer(root, "trims").findall("s:g", NS)) == 3
    ties = _layer(root, "ties")
    assert len(ties.findall("s:polygon", NS)) == int(np.sum(plan.roles == R.TIE_IN))
    assert len(ties.findall("s:rect", NS)) == int(np.sum((plan.roles == R.TIE_OFF) & (plan.commands == C.STITCH)))
    assert len(_layer(root, "corridor").findall("s:path", NS)) == 3
    assert len(_layer(root, "rails").findall("s:polyline", NS)) == 6
    # one line segment per leg, in sewing order, spread over several ramp colours
    legs = _layer(root, "legs").findall("s:path", NS)
    n_seg = sum(_segments_in(p.get("d")) for p in legs)
    assert n_seg == 3 * (45 - 1)
    assert len({p.get("stroke") for p in legs}) > 10
    text = " ".join(t.text for t in root.iter("{http://www.w3.org/2000/svg}text"))
    assert "A2 zigzag: w 7.00 mm, s 1.000 mm" in text and "STOP 3: lay tube A3" in text and "20 mm" in text


def test_drawn_to_scale_in_mm():
    plan = hand_plan(1, length=40.0)
    root = ET.fromstring(plan_svg(plan, margin_mm=5.0))
    w, h = root.get("width"), root.get("height")
    vb = [float(v) for v in root.get("viewBox").split()]
    assert w.endswith("mm") and h.endswith("mm")
    assert float(w[:-2]) == pytest.approx(vb[2]) and float(h[:-2]) == pytest.approx(vb[3])  # 1 user unit = 1 mm
    fabric = _layer(root, "fabric").find("s:rect", NS)
    # fabric = corridor/needle bounds + 5 mm: x from 0 (needles start at 5, margin 5) to 45 + 5
    assert float(fabric.get("x")) == pytest.approx(0.0)
    assert float(fabric.get("width")) == pytest.approx(40.0 + 10.0)
    # y negated: the top needle row at y = +0.5 mm is drawn at -0.5
    first = _layer(root, "needle-points").find("s:circle", NS)
    assert (float(first.get("cx")), float(first.get("cy"))) == (5.0, -0.5)
    bar = _layer(root, "scale-bar").find("s:rect", NS)
    label = _layer(root, "scale-bar").find("s:text", NS).text
    assert float(bar.get("width")) == float(re.match(r"(\d+) mm", label).group(1))


def test_deterministic_and_jupyter_hook():
    plan = hand_plan(2)
    assert plan_svg(plan) == plan_svg(plan) == plan._repr_svg_()


@pytest.mark.parametrize("label,plan", generated_plans(), ids=lambda v: v if isinstance(v, str) else "")
def test_generated_plans_render(label, plan):
    root = ET.fromstring(plan_svg(plan))
    assert len(_layer(root, "needle-points").findall("s:circle", NS)) == plan.stitch_count


def test_bad_options():
    with pytest.raises(ParameterError, match="margin_mm"):
        plan_svg(hand_plan(1), margin_mm=-1)


def test_placement_line_is_a_layer_of_its_own():
    """The placement line's stitches are drawn in the ``placement`` layer, one colour, and not among the legs
    (read with the standard library's XML parser)."""
    from dataclasses import replace as _replace

    from embroact.export.pictures.stitches import PLACEMENT_COLOUR
    from embroact.patterns.design import build_plan, default_design

    d = default_design()
    plan = build_plan(_replace(d, machine=_replace(d.machine, placement_line=True)))
    ns = {"s": "http://www.w3.org/2000/svg"}
    root = ET.fromstring(plan_svg(plan))
    paths = root.findall(".//s:g[@id='placement']/s:path", ns)
    assert len(paths) == 1 and paths[0].get("stroke") == PLACEMENT_COLOUR
    segments = _segments_in(paths[0].get("d"))
    stitch = plan.commands == C.STITCH
    placed = stitch[1:] & stitch[:-1] & (plan.roles[1:] == R.PLACEMENT)
    assert segments == int(placed.sum()) > 10
    legs = sum(_segments_in(p.get("d")) for p in root.findall(".//s:g[@id='legs']/s:path", ns))
    assert legs == int((stitch[1:] & stitch[:-1]).sum()) - segments
    plain = ET.fromstring(plan_svg(build_plan(d)))
    assert plain.findall(".//s:g[@id='placement']/s:path", ns) == []
