"""Production worksheet against hand-computed numbers."""
import json
import math

import pytest
from mpmath import mp, mpf

from h3_plans import hand_plan
from embroact.export.report.worksheet import (
    LAY_TUBE_S, STOP_RESTART_S, TAIL_MM, TRIM_TIME_S, over_tube_extra_mm, worksheet)
from embroact.patterns.base.errors import ParameterError
from embroact.patterns.params import FABRIC_THICKNESS_MM
from embroact.patterns.base.findings import RULES


def _taut_extra(a, r):
    """Thread over a cylinder by explicit tangent points (independent of the closed form)."""
    mp.dps = 50
    a, r = mpf(a), mpf(r)
    # circle centre (0, r) touching the fabric at the axis; P = (a, 0).
    # tangent point T = (r sin t, r - r cos t) ... solve (T - P).(T - C) = 0 for the upper tangent
    def f(t):
        return (r * mp.sin(t) - a) * (r * mp.sin(t)) + (r - r * mp.cos(t)) * (-r * mp.cos(t))

    t = mp.findroot(f, mpf(2))  # angle from the bottom contact point, upper side
    tx, ty = r * mp.sin(t), r - r * mp.cos(t)
    tangent = mp.sqrt((tx - a) ** 2 + ty**2)
    arc = r * (2 * mp.pi - 2 * t)  # between the two symmetric tangent points over the top
    return float(2 * tangent + arc - 2 * a)


@pytest.mark.parametrize("a,r", [(3.5, 1.5), (2.5, 1.5), (6.0, 1.0)])
def test_over_tube_extra_matches_tangent_construction(a, r):
    assert float(over_tube_extra_mm(a, r)) == pytest.approx(_taut_extra(a, r), abs=1e-12)


def test_counts_sizes_and_tube_lengths():
    plan = hand_plan(3, length=40.0, gap=20.0)
    ws = worksheet(plan)
    # per actuator: 3 tie-in + 40 legs + 2 tie-off = 45 stitches
    assert ws.stitch_count == 135 and ws.stop_count == 3 and ws.trim_count == 3 and ws.jump_count == 2
    assert ws.size_mm == pytest.approx((40.0, 2 * 20.0 + 7.0))
    for a in ws.actuators:
        assert a.path_length_mm == pytest.approx(40.0)
        assert a.tube_cut_mm == pytest.approx(40.0 + 2 * 30.0)
        assert a.legs_over_tube == 40
    assert ws.stops[0].startswith("stop 1: lay tube for actuator A1 (100 mm cut): its axis runs from (5.0, -3.0) "
                                  "to (45.0, -3.0) mm, leaving the start at 0 deg; from the needle at (5.0, 0.5) mm "
                                  "its start is 3.5 mm down")
    assert [s.split(":")[0] for s in ws.stops] == ["stop 1", "stop 2", "stop 3"]


def test_thread_estimate_by_hand():
    plan = hand_plan(1, width=7.0, interval=1.0, length=40.0)
    a = worksheet(plan).actuators[0]
    leg = math.hypot(1.0, 7.0)
    ties = 0.7 * 4  # tie-in 0.7 out and back, tie-off 0.7 and back
    straight = 40 * leg + ties
    extra = 40 * _taut_extra(leg / 2, 1.5)
    assert a.bobbin_thread_mm == pytest.approx(straight + 45 * FABRIC_THICKNESS_MM)
    assert a.top_thread_mm == pytest.approx(straight + extra + 45 * FABRIC_THICKNESS_MM + 2 * TAIL_MM)


def test_sewing_time_by_hand():
    plan = hand_plan(3)
    ws = worksheet(plan, speed_spm=400)
    assert ws.sewing_time_s == pytest.approx(60 * (135 + 2) / 400 + 3 * TRIM_TIME_S + 3 * STOP_RESTART_S)
    assert ws.handling_time_s == 3 * LAY_TUBE_S


def test_derived_geometry_and_json():
    plan = hand_plan(1)
    ws = worksheet(plan, findings=[RULES.finding("EA101", "needle point 0.4 mm from the tube axis", stitch_index=7)])
    d = json.loads(json.dumps(ws.as_dict()))
    act = d["actuators"][0]
    assert act["derived"]["width_mm"] == 7.0 and act["derived"]["r0_mm"] == pytest.approx(2.5814, abs=1e-4)
    assert act["tube_cut_mm"] == 100.0
    assert d["findings"][0]["code"] == "EA101"
    assert {"top_thread_m", "bobbin_thread_m", "sewing_time_s", "speed_spm", "size_mm"} <= set(d)
    text = ws.as_text()
    assert "tube cut length  100 mm = 40.0 mm path + 2 x 30 mm end margin" in text
    assert "EA101" in text


@pytest.mark.parametrize("spm", [0, -5, float("nan"), 5000])
def test_bad_speed(spm):
    with pytest.raises(ParameterError, match="speed_spm"):
        worksheet(hand_plan(1), speed_spm=spm)


def _three_dst(mode):
    import dst_decoder
    from embroact.export.files.designfile import load_design
    from embroact.export.machine.formats import encode
    from embroact.patterns.design import build_plan

    design = load_design("examples/three_actuators.toml")
    plan = build_plan(design)
    data, res = encode(plan, "dst", cord_stop=mode)
    return design, plan, res, dst_decoder.decode(data)


@pytest.mark.parametrize("mode,entries", [("sequence", 4), ("double", 7)])
def test_three_actuator_dst_tells_a_multi_needle_operator_what_to_set(mode, entries):
    design, plan, res, dst = _three_dst(mode)
    ws = worksheet(plan, design, machine=res)
    kinds = [r.kind for r in dst.records]
    stop_codes = kinds.count("stop")
    assert stop_codes == {"sequence": 3, "double": 6}[mode] == ws.stop_count == entries - 1
    # pauses where the decoded records stop, in the plan frame: one per actuator
    waits = []
    for r, prev in zip(dst.records, [None] + dst.records[:-1]):
        if r.kind == "stop" and (prev is None or prev.kind != "stop"):
            waits.append((r.x / 10, r.y / 10))
    assert [line.split(":")[0] for line in ws.stops] == ["stop 1", "stop 2", "stop 3"]
    for line, (wx, wy) in zip(ws.stops, waits):
        assert f"from the needle at ({wx:.1f}, {wy:.1f}) mm" in line
    text = ws.as_text()
    multi = next(s for s in ws.setup if s.startswith("multi-needle"))
    assert f"set all {entries} entries of the needle sequence to needle 1" in multi
    assert ("manual needle mode" in multi) == (mode == "sequence")
    assert "connector on the start end" in text and "fabric to hoop   280 x 280 mm" in text
    assert ws.jump_count == res.jumps == sum(e[3] for e in dst_decoder_events(dst) if e[0] == "travel")


def dst_decoder_events(dst):
    import dst_decoder

    return dst_decoder.events(dst.records)


@pytest.mark.parametrize("fmt", ["pes", "vp3", "jef"])
def test_colour_format_worksheet_lays_tube_one_before_start(fmt):
    from embroact.export.files.designfile import load_design
    from embroact.export.machine.formats import encode
    from embroact.patterns.design import build_plan

    design = load_design("examples/three_actuators.toml")
    plan = build_plan(design)
    _, res = encode(plan, fmt)
    ws = worksheet(plan, design, machine=res)
    assert ws.stop_count == 0 and ws.color_change_count == 2
    assert ws.stops[0].startswith("before start: lay tube for actuator narrow zigzag")
    assert [s.split(":")[0] for s in ws.stops[1:]] == ["stop 1", "stop 2"]
    assert any("lay tube 1 before pressing start" in s for s in ws.setup)
    assert any("no stop code" in n for n in ws.notes)
    assert (ws.stitch_count, ws.trim_count, ws.jump_count) == (res.stitches, res.trims, res.jumps)
