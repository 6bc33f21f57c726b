"""Placement lines: a running stitch along the tube axis, sewn before the cord-in stop.

Expected numbers are derived by hand in the comments; file checks read the written bytes back.
"""
import math
from dataclasses import replace

import numpy as np
import pytest
import shapely

from embroact.export.cli.main import main
from embroact.patterns.base.errors import DesignFileError, ParameterError
from embroact.patterns.centerline import Centerline
from embroact.patterns.design import MachineSettings, build_plan, default_design, design_from_dict, design_to_dict
from embroact.patterns.limits import GRID_ROUNDING_MM
from embroact.patterns.params import ZigzagParams
from embroact.patterns.placement import placement_records, with_placement
from embroact.patterns.plan import Command, Role
from embroact.patterns.rules import Layout, RuleSettings, TubeLayout, check_layout
from embroact.patterns.zigzag import zigzag

S, P = Command.STITCH, Command.STOP


def _placed(design):
    return replace(design, machine=replace(design.machine, placement_line=True))


def _codes(findings):
    return sorted({f.code for f in findings})


# --------------------------------------------------------------------- the line itself
def test_straight_line_by_hand():
    """100 mm zigzag, w 7, 3 lock stitches of 0.7 mm, stitch 2.5 mm: locks at x = 100/99.3, then
    ceil(99.3 / 2.5) = 40 stitches of 99.3 / 40 = 2.4825 mm to x = 0, then ceil(|(0.7, 3.5)| / 2.5) =
    ceil(3.569 / 2.5) = 2 stitches out to the stop point (0.7, 3.5): 4 + 40 + 2 = 46 records."""
    plan = with_placement(zigzag(Centerline.straight(100.0), ZigzagParams(7.0, 1.0)), 2.5)
    line = np.flatnonzero(plan.roles == Role.PLACEMENT)
    assert line.tolist() == list(range(46))  # first in the plan, before anything else
    assert np.all(plan.commands[line] == S) and plan.commands[46] == P
    xy = plan.xy_mm[line]
    assert xy[:4, 0].round(9).tolist() == [100.0, 99.3, 100.0, 99.3] and np.all(xy[:44, 1] == 0.0)
    # the 40 stitches of 2.4825 mm, each needle point on the 0.1 mm machine grid
    assert xy[3:44, 0].tolist() == pytest.approx(np.rint((99.3 - np.arange(41) * 99.3 / 40) * 10) / 10, abs=1e-12)
    assert xy[-1] == pytest.approx(plan.xy_mm[46]) and xy[-1] == pytest.approx([0.7, 3.5])
    assert len(line) <= placement_records(100.0, 2.5, 3, 3.5)


def test_curved_line_stays_on_the_axis():
    """On an arc every axis needle point lies on the path; chords never exceed the stitch length."""
    cl = Centerline.from_svg_path("M 0 0 A 40 40 0 0 1 60 30")
    plan = with_placement(zigzag(cl, ZigzagParams(7.0, 1.0)), 3.0)
    xy = plan.xy_mm[plan.roles == Role.PLACEMENT]
    axis = cl.as_linestring()
    on_axis = shapely.distance(axis, shapely.points(xy[:-2]))  # the last two go out to the rail
    assert on_axis.max() <= GRID_ROUNDING_MM + 1e-9  # on the axis, to the machine grid
    steps = np.hypot(*np.diff(xy, axis=0).T)
    assert steps.max() <= 3.0 + 2 * GRID_ROUNDING_MM and steps[3:].min() > 0.3  # the machine grid may add 0.14 mm
    s, _ = cl.project(xy[3:-2])
    assert s[0] == pytest.approx(cl.length_mm - 0.7, abs=0.01) and s[-1] == pytest.approx(0.0, abs=1e-9)


def test_joined_plan_is_refused():
    two = build_plan(design_from_dict({"actuator": [
        {"name": "A", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 20},
        {"name": "B", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 20, "origin_mm": [0, 20]}]}))
    with pytest.raises(ParameterError, match=r"one actuator's plan with one STOP, got 2 actuator\(s\) and 2 STOP"):
        with_placement(two, 2.5)


# --------------------------------------------------------------------- design settings
def test_design_setting_round_trip_and_errors():
    d = design_from_dict({"machine": {"placement_line": True, "placement_stitch_mm": 3.0},
                          "actuator": [{"name": "A", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1,
                                        "length_mm": 50}]})
    assert d.machine.placement_line and d.machine.placement_stitch_mm == 3.0
    assert design_from_dict(design_to_dict(d)) == d
    with pytest.raises(DesignFileError, match=r"^machine.placement_line: must be true or false, got 'yes'$"):
        design_from_dict({"machine": {"placement_line": "yes"}, "actuator": design_to_dict(d)["actuator"]})
    with pytest.raises(ParameterError, match=r"placement_stitch_mm must be in \[0.3, 12.1\], got 20"):
        MachineSettings(placement_line=True, placement_stitch_mm=20.0)
    MachineSettings(placement_stitch_mm=20.0)  # unused without the line: only its own range


def test_plan_with_and_without_the_line():
    """The setting adds exactly the placement records before each actuator's STOP, nothing else changes."""
    base = build_plan(default_design())
    placed = build_plan(_placed(default_design()))
    keep = placed.roles != Role.PLACEMENT
    assert np.array_equal(placed.xy_mm[keep], base.xy_mm) and np.array_equal(placed.commands[keep], base.commands)
    assert int(np.count_nonzero(~keep)) == 46  # the hand count of test_straight_line_by_hand


# --------------------------------------------------------------------- rules
def test_design_rules_see_no_tube_under_a_placement_line():
    """EA101 (corridor), EA307 (couching), EA502/EA503 (stops) judge the placed design as the plain one."""
    from embroact.predict.analysis import analyse
    from embroact.predict.rules import check_design
    from embroact.export.files.designfile import load_design

    for design in (default_design(), load_design("examples/three_actuators.toml"), load_design("examples/curved.toml")):
        assert _codes(check_design(analyse(_placed(design)))) == _codes(check_design(analyse(design)))


def _tube(points=((0.0, 0.0), (100.0, 0.0)), name="A"):
    return TubeLayout.from_path(name, points, outer_radius_mm=1.5, clearance_mm=0.3, end_margin_mm=0.0,
                                half_width_mm=3.5)


def test_corridor_rule_skips_only_the_own_tube():
    """A needle point on tube A's axis: sewn before A is laid it pierces nothing; the same point on tube B's
    axis, sewn before A is laid, still pierces B."""
    a, b = _tube(name="A"), _tube(((50.0, -20.0), (50.0, 20.0)), name="B")
    xy = [(20.0, 0.0), (50.0, 10.0)]
    early = Layout.from_points(xy, [S, S], [0, 0], tubes=(a, b), before_tube=[True, True])
    hits = [f for f in check_layout(early, RuleSettings()) if f.code == "EA101"]
    assert [(f.actuator, f.stitch_index) for f in hits] == [("A", 1)]  # the point on B's axis, not A's
    plain = Layout.from_points(xy, [S, S], [0, 0], tubes=(a, b))
    assert len([f for f in check_layout(plain, RuleSettings()) if f.code == "EA101"]) == 2


def test_placement_legs_hold_no_tube():
    """Legs that cross the tube, flagged as sewn before it: the tube is not held (EA307 error)."""
    xy = [(10.0 + i, 3.5 * (-1) ** i) for i in range(80)]
    tube = _tube(((10.0, 0.0), (89.0, 0.0)))
    held = Layout.from_points(xy, [S] * 80, [0] * 80, tubes=(tube,))
    assert "EA307" not in _codes(check_layout(held, RuleSettings()))
    early = Layout.from_points(xy, [S] * 80, [0] * 80, tubes=(tube,), before_tube=[True] * 80)
    msg = [f.message for f in check_layout(early, RuleSettings()) if f.code == "EA307"]
    assert len(msg) == 1 and msg[0].startswith("no leg crosses the tube of A")


# --------------------------------------------------------------------- machine files and the worksheet
def test_file_check_and_stop_in_the_records(tmp_path, capsys):
    """The DST holds the line before its stop code; check finds it clean on the right tube and the
    couching error 10 mm beside it."""
    import dst_decoder

    out = tmp_path / "a.dst"
    assert main(["zigzag", "--width-mm", "7", "--length-mm", "100", "-o", str(out), "--placement-line",
                 "--origin", "0,0"]) == 0  # the file's frame is the path's
    assert "152 stitches" in capsys.readouterr().out  # 106 of the plain actuator + 46
    kinds = [r.kind for r in dst_decoder.decode(out.read_bytes()).records]
    assert kinds.index("stop") > 46 and kinds.count("stop") == 1
    assert kinds[:kinds.index("stop")].count("stitch") == 46  # the whole line is sewn before the stop
    assert main(["check", str(out), "--tube-path", "0,0 100,0"]) == 0
    capsys.readouterr()
    assert main(["check", str(out), "--tube-path", "0,10 100,10"]) == 1
    assert "EA307" in capsys.readouterr().out


@pytest.mark.parametrize("fmt", ["dst", "pes", "jef", "tbf"])
def test_worksheet_lays_every_tube_after_its_line(fmt):
    """Three actuators with lines: the machine waits three times, once after each line, in every kind of
    format (a colour format's first actuator gets a colour block for its line)."""
    from embroact.export.files.designfile import load_design
    from embroact.export.machine.formats import encode
    from embroact.export.report.worksheet import worksheet

    plan = build_plan(_placed(load_design("examples/three_actuators.toml")))
    _, res = encode(plan, fmt)
    assert res.pauses == 3
    ws = worksheet(plan, machine=res)
    assert [s.split(":")[0] for s in ws.stops] == ["stop 1", "stop 2", "stop 3"]
    assert all("sews the placement line of" in s and "and stops; lay the tube over that line" in s for s in ws.stops)
    assert any("placement line is sewn first" in s for s in ws.setup)
    assert not any("before pressing start" in s for s in ws.setup)
    if fmt == "pes":
        assert res.thread_names[0] == "narrow zigzag placement" and len(res.thread_names) == 4


def test_build_flag_equals_design_setting(tmp_path):
    """--placement-line on build and machine.placement_line = true write the same bytes."""
    design = tmp_path / "d.toml"
    design.write_text('[machine]\nplacement_line = true\n[[actuator]]\nname = "A1"\npattern = "zigzag"\n'
                      'width_mm = 7.0\ninterval_mm = 1.0\nlength_mm = 60.0\n')
    plain = tmp_path / "plain.toml"
    plain.write_text(design.read_text().replace("placement_line = true", ""))
    (tmp_path / "a").mkdir(), (tmp_path / "b").mkdir()
    assert main(["build", str(design), "--out", str(tmp_path / "a"), "--no-previews"]) == 0
    assert main(["build", str(plain), "--out", str(tmp_path / "b"), "--no-previews", "--placement-line"]) == 0
    a, b = (tmp_path / "a" / "design.dst").read_bytes(), (tmp_path / "b" / "design.dst").read_bytes()
    assert a == b and len(a) > 512 + 3 * math.ceil(60 / 2.5)


@pytest.mark.parametrize("fmt", ["tbf", "u01"])
def test_needle_formats_choose_the_needle_before_the_placement_line(fmt, tmp_path):
    """TBF and U01 select the needle with a record of their own: the placement line, sewn before the first
    cord-in stop, comes after one (read back by pystitch's reader, not embroact's)."""
    import pystitch

    from embroact.export.files.designfile import load_design
    from embroact.export.machine.formats import encode

    data, res = encode(build_plan(_placed(load_design("examples/three_actuators.toml"))), fmt)
    (tmp_path / f"x.{fmt}").write_bytes(data)
    cmds = [c[2] & pystitch.COMMAND_MASK for c in pystitch.read(str(tmp_path / f"x.{fmt}")).stitches]
    first_stitch, first_needle = cmds.index(pystitch.STITCH), cmds.index(pystitch.NEEDLE_SET)
    assert first_needle < first_stitch < cmds.index(pystitch.STOP)
    assert cmds.count(pystitch.NEEDLE_SET) == res.color_changes == 4  # the start, and each of 3 cord-in stops
