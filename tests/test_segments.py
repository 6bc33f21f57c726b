"""Segmented actuators (patterns/segments.py): one continuous run over several patterns along one tube."""
import math

import numpy as np
import pytest
import shapely

from embroact.patterns.base.errors import DesignFileError, ParameterError
from embroact.patterns.centerline import Centerline
from embroact.patterns.design import ActuatorSpec, Design, MachineSettings, OperationSettings, build_plan, \
    design_from_dict, design_to_dict
from embroact.patterns.params import CrossParams, Tube, ZigzagParams
from embroact.patterns.plan import Command, Role
from embroact.patterns.segments import SegmentSpec, segmented
from embroact.predict.curve import curve

MIXED = (SegmentSpec(ZigzagParams(7.0, 1.0), 40.0), SegmentSpec(CrossParams(7.0, 1.4, 45.0), 60.0),
         SegmentSpec(ZigzagParams(9.0, 1.0), 30.0))


def test_one_run_one_stop_one_trim():
    plan = segmented(Centerline.straight(130.0), MIXED, name="S")
    assert plan.count(Command.STOP) == 1 and plan.count(Command.TRIM) == 1
    assert (plan.commands == Command.JUMP).sum() == 0
    act = plan.actuators[0]
    assert [s.pattern for s in act.segments] == ["zigzag", "cross", "zigzag"]
    assert [s.start_mm for s in act.segments] == [0.0, 40.0, 100.0]


def test_realised_per_segment_matches_the_request():
    act = segmented(Centerline.straight(130.0), MIXED).actuators[0]
    z1, c, z2 = act.segments
    assert (z1.realised.width_mm, z1.realised.interval_mm, z1.realised.length_mm) == pytest.approx((7.0, 1.0, 40.0))
    assert (c.realised.width_mm, c.realised.interval_mm, c.realised.angle_deg) == pytest.approx((7.0, 1.4, 45.0))
    assert c.realised.passes == 10
    # a 60 mm cross segment at s = 1.4 mm: 42 intervals = 58.8 mm span, centred (0.6 mm each side)
    assert c.realised.length_mm == pytest.approx(58.8)
    assert c.first_leg_mm == pytest.approx(40.6)
    assert z2.realised.width_mm == pytest.approx(9.0)


def test_transitions_run_along_a_rail_and_are_reported():
    plan = segmented(Centerline.straight(130.0), MIXED)
    act = plan.actuators[0]
    s, o = act.centerline.project(plan.xy_mm[plan.commands == Command.STITCH])
    roles = plan.roles[plan.commands == Command.STITCH]
    # zigzag 1 ends at 40.0; the cross starts at 40.6 (0.6 mm); the cross span ends at 99.4, zigzag 2 starts at 100
    assert act.segments[0].transition_mm == pytest.approx(0.6)
    assert act.segments[1].transition_mm == pytest.approx(0.6)
    assert act.segments[2].transition_mm == 0.0
    # the 10-pass cross ends near its start (46.2 mm): the thread runs back along the rail to 100 mm
    assert act.segments[0].join_run_mm == pytest.approx(0.6)
    assert act.segments[1].join_run_mm == pytest.approx(100.0 - 46.2)
    # no needle point of the transitions lies nearer the tube than the narrower rail
    edge = roles == Role.EDGE
    assert np.all(np.abs(o[edge]) >= 3.5 - 1e-9)
    # every stitch arriving at an EDGE point advances at most 3 mm along the path
    assert np.abs(np.diff(s))[edge[1:]].max() <= 3.0 + 1e-9


def test_a_segment_is_mirrored_to_start_on_the_rail_the_last_ended_on():
    segs = (SegmentSpec(ZigzagParams(7.0, 1.0), 41.0), SegmentSpec(ZigzagParams(7.0, 1.0), 40.0))
    plan = segmented(Centerline.straight(81.0), segs)
    a, b = plan.actuators[0].segments
    # 41 legs end on the right rail (odd count): the next zigzag starts there, mirrored
    assert b.mirrored and not a.mirrored
    cl = plan.actuators[0].centerline
    s, o = cl.project(plan.xy_mm[plan.commands == Command.STITCH])
    at = np.flatnonzero(np.isclose(s, 41.0))
    assert np.all(o[at] < 0)


def test_corridor_and_stitch_lengths_hold_on_a_curved_path():
    path = Centerline.from_svg_path("M 0 0 A 60 60 0 0 1 60 60")
    half = path.length_mm / 2
    segs = (SegmentSpec(ZigzagParams(7.0, 1.0), half), SegmentSpec(CrossParams(8.0, 1.4, 45.0, ), half))
    plan = segmented(path, segs, tube=Tube())
    xy = plan.xy_mm[plan.commands == Command.STITCH]
    d = shapely.distance(path.as_linestring(), shapely.points(xy))
    assert d.min() >= Tube().corridor_radius_mm - 1e-6
    assert np.hypot(*np.diff(xy, axis=0).T).max() <= 12.1


def test_lengths_must_add_up():
    with pytest.raises(ParameterError, match="must add up to the path length 100 mm"):
        segmented(Centerline.straight(100.0), MIXED[:2] + (SegmentSpec(ZigzagParams(7.0, 1.0), 5.0),))


def test_design_file_segments_round_trip_and_errors():
    d = {"name": "seg", "actuator": [{"name": "S", "segment": [
        {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 40},
        {"pattern": "cross", "width_mm": 7, "interval_mm": 1.4, "angle_deg": 45, "length_mm": 60}]}]}
    design = design_from_dict(d)
    spec = design.actuators[0]
    assert spec.centerline.length_mm == pytest.approx(100.0) and len(spec.segments) == 2
    assert design_from_dict(design_to_dict(design)) == design
    plan = build_plan(design)
    assert plan.count(Command.STOP) == 1
    bad = {"actuator": [{**d["actuator"][0], "pattern": "zigzag"}]}
    with pytest.raises(DesignFileError, match=r"actuator\[0\].pattern: a segmented actuator sets pattern per"):
        design_from_dict(bad)
    bad = {"actuator": [{**d["actuator"][0], "length_mm": 90}]}
    with pytest.raises(DesignFileError, match=r"actuator\[0\]: segment length_mm values must add up"):
        design_from_dict(bad)
    bad = {"actuator": [{"name": "S", "segment": [{"pattern": "zigzag", "width_mm": 7, "interval_mm": 1}]}]}
    with pytest.raises(DesignFileError, match=r"actuator\[0\].segment\[0\].length_mm: missing key"):
        design_from_dict(bad)


def test_a_single_pattern_actuator_is_a_chain_of_one():
    spec = ActuatorSpec("A", ZigzagParams(7.0, 1.0), Centerline.straight(100.0))
    assert spec.segments == (SegmentSpec(ZigzagParams(7.0, 1.0), 100.0),)
    plan = build_plan(Design("d", Tube(), MachineSettings(), OperationSettings(), (spec,)))
    (seg,) = plan.actuators[0].segments
    # 101 stations 1 mm apart over the whole 100 mm path, 2 x 3 lock stitches, the first station shared
    assert (seg.start_mm, seg.length_mm, seg.first_leg_mm, seg.transition_mm, seg.join_run_mm) == (0, 100, 0, 0, 0)
    assert plan.stitch_count == 106 and seg.realised.width_mm == 7.0 and seg.realised.length_mm == 100.0


def test_each_segment_bends_as_the_same_pattern_alone():
    """Segments decouple: a segment's curve is that of a single actuator with its pattern and leg length."""
    from embroact.predict.analysis import analyse

    seg = design_from_dict({"actuator": [{"name": "S", "segment": [
        {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 40},
        {"pattern": "cross", "width_mm": 7, "interval_mm": 1.4, "angle_deg": 45, "length_mm": 60}]}]})
    alone = design_from_dict({"actuator": [
        {"name": "Z", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 40},
        {"name": "C", "pattern": "cross", "width_mm": 7, "interval_mm": 1.4, "angle_deg": 45, "length_mm": 58.8,
         "origin_mm": [0, 30]}]})
    p = [0.0, 150.0, 250.0]
    a, b = analyse(seg), analyse(alone)
    z, c = a.segment_curves(p)[0]
    assert z.theta_deg == pytest.approx(b.curves(p)[0].theta_deg, abs=1e-9)
    assert c.theta_deg == pytest.approx(b.curves(p)[1].theta_deg, abs=1e-9)
    act = a.actuators[0]
    assert [s.derived.pattern for s in act.segments] == ["zigzag", "cross"]
    assert act.segments[1].model.g_mpa == b.actuators[1].model.g_mpa == 1.3
    # the whole strip's model: what the segments share (tube, tube law), None where they differ, lengths summed
    assert (act.model.g_mpa, act.model.pattern, act.model.tube_law, act.model.outer_radius_mm) == \
        (None, "zigzag+cross", "paper", 1.5)
    assert act.model.length_mm == pytest.approx(act.segments[0].model.length_mm + act.segments[1].model.length_mm)
    # the shape: zigzag arc, a 0.6 mm straight transition, the cross arc, a 0.6 mm straight tail
    pieces = act.bend_pieces()
    assert [k for _, k in pieces] == [0, -1, 1, -1]
    assert sum(length for length, _ in pieces) == pytest.approx(100.0)
    shape, theta = a.shapes("S", [250.0])[0]
    t0, t1 = float(z.theta_deg[2]), float(c.theta_deg[2])
    assert theta == pytest.approx((t0, 0.0, t1, 0.0))
    assert shape.tip_angle_deg == pytest.approx(t0 + t1)
    lengths = [length for length, _ in pieces]
    zc = 0j
    phi = 0.0
    for length, t_deg in zip(lengths, theta):
        t = math.radians(t_deg)
        zc += np.exp(1j * phi) * (length * (np.exp(1j * t) - 1.0) / (1j * t) if t else length)
        phi += t
    assert shape.profile_mm([100.0])[0] == pytest.approx([zc.real, zc.imag], abs=1e-9)


def test_model_rules_run_per_segment():
    """EA401 names the segment whose P0 is above the working pressure; EA403 reads the total bend."""
    from embroact.predict.analysis import analyse
    from embroact.predict.rules import check_model

    d = design_from_dict({"operation": {"max_pressure_kpa": 160.0, "max_bend_deg": 30.0}, "actuator": [
        {"name": "S", "segment": [
            {"pattern": "zigzag", "width_mm": 6, "interval_mm": 1, "length_mm": 50},
            {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]})
    a = analyse(d)
    found = check_model(a)
    codes = {(f.code, f.message.split(":")[0]) for f in found}
    # the paper's set: w = 9 mm has P0 = 180 kPa > 160 kPa; w = 6 mm bends
    assert ("EA401", "segment 1") in codes
    seg0 = float(curve(a.actuators[0].segments[0].model, [160.0]).theta_deg[0])
    assert seg0 > 30.0
    ea403 = [f for f in found if f.code == "EA403"]
    assert len(ea403) == 1 and f"{seg0:.1f} deg" in ea403[0].message


def test_request_rules_run_per_segment():
    """EA204 (angle off request) and EA206 (near neutral) name the segment they are about."""
    from embroact.predict.analysis import analyse
    from embroact.predict.rules import check_design

    d = design_from_dict({"actuator": [{"name": "S", "segment": [
        {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 40},
        {"pattern": "cross", "width_mm": 7, "interval_mm": 1.4, "angle_deg": 30, "adjust": "angle", "length_mm": 60},
        {"pattern": "cross", "width_mm": 7, "interval_mm": 1.4, "angle_deg": 33.4, "adjust": "interval",
         "length_mm": 60}]}]})
    found = check_design(analyse(d))
    msgs = {f.code: [g.message for g in found if g.code == f.code] for f in found}
    # segment 1: closing the cross at 30 deg moves it to 30.96 deg (> the 0.5 deg tolerance)
    assert any(m.startswith("segment 1: leg angle 30.96 deg realised") for m in msgs["EA204"])
    # segment 2: 33.4 deg (33.41 on the machine grid's needle points) is within the neutral band of 33.37 deg
    assert any(m.startswith("segment 2: angle 33.41 deg") for m in msgs["EA206"])


def test_single_actuator_pieces_cover_the_path():
    """A single cross actuator's legs (58.8 mm on a 60 mm path, centred) with the unbent ends around them."""
    from embroact.predict.analysis import analyse

    d = design_from_dict({"actuator": [{"name": "C", "pattern": "cross", "width_mm": 7, "interval_mm": 1.4,
                                        "angle_deg": 45, "length_mm": 60}]})
    act = analyse(d).actuators[0]
    assert [(round(length, 9), k) for length, k in act.bend_pieces()] == [(0.6, -1), (58.8, 0), (0.6, -1)]
    shape, theta = analyse(d).shapes("C", [250.0])[0]
    assert shape.length_mm == pytest.approx(60.0) and theta[0] == theta[2] == 0.0
