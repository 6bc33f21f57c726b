"""Geometric and file-level design rules: one case that triggers each rule, one that does not.

Expected numbers are derived by hand in the comments (not captured from the code).
"""
import math

import numpy as np
import pytest

from embroact.patterns.centerline import Centerline
from embroact.patterns.base.findings import RULES, Finding, Severity, count_by_severity, rules_table_markdown
from embroact.patterns.params import CrossParams, Tube, ZigzagParams
from embroact.patterns.plan import ActuatorPlan, Command, Realised, Role, StitchPlan
from embroact.patterns.rules import Layout, RuleSettings, TubeLayout, check_geometry, check_layout, needle_density
from embroact.predict import sleeve_rules
from embroact.patterns.zigzag import zigzag

S, J, T, P = Command.STITCH, Command.JUMP, Command.TRIM, Command.STOP


def _tube(points=((0.0, 0.0), (100.0, 0.0)), name="A", half_width_mm=3.5, end_margin_mm=0.0):
    return TubeLayout.from_path(name, points, outer_radius_mm=1.5, clearance_mm=0.3,
                                end_margin_mm=end_margin_mm, half_width_mm=half_width_mm)


def _zig(n=10, s=1.0, w=7.0, x0=10.0):
    """Needle points of a zigzag along y = 0: x = x0 + i s, y = +-w/2 alternately."""
    return [(x0 + i * s, (w / 2) * (1 if i % 2 == 0 else -1)) for i in range(n)]


def _layout(xy, commands=None, owner=None, tubes=None):
    n = len(xy)
    tubes = (_tube(),) if tubes is None else tubes
    owner = [0 if tubes else -1] * n if owner is None else owner
    return Layout.from_points(xy, [S] * n if commands is None else commands, owner, tubes=tubes)


def _hits(findings, code):
    return [f for f in findings if f.code == code]


def _check(layout, **settings):
    return check_layout(layout, RuleSettings(**settings))


# --------------------------------------------------------------------- findings and registry
def test_registry_codes_unique_and_documented():
    codes = [r.code for r in RULES]
    assert len(codes) == len(set(codes)) == len(RULES)
    assert codes == sorted(codes)
    table = rules_table_markdown()
    assert table.count("\n") == len(RULES) + 2
    for row in table.splitlines():
        assert row.replace("\\|", "").count("|") == 6  # five cells: pipes inside cells are escaped
    for r in RULES:
        assert f"| {r.code} | {r.severity.value} |" in table
        assert r.description and r.fix and r.title


def test_finding_value_and_dict():
    f = RULES.finding("EA103", "stitch 13 mm", actuator="A1", stitch_index=np.int64(5), xy_mm=np.array([1.5, -2.0]))
    assert isinstance(f, Finding) and f.severity is Severity.ERROR and f.is_error
    assert f.stitch_index == 5 and type(f.stitch_index) is int
    assert f.as_dict() == {"code": "EA103", "severity": "error", "title": "stitch over machine maximum",
                           "message": "stitch 13 mm", "actuator": "A1", "stitch_index": 5,
                           "xy_mm": [1.5, -2.0], "fix": RULES["EA103"].fix, "count": 1,
                           "place": "A1, stitch 5 at (1.50, -2.00) mm"}
    assert "A1, stitch 5 at (1.50, -2.00) mm" == f.place()
    assert count_by_severity([f, f]) == {"error": 2, "warning": 0, "info": 0}
    # the closing finding of a capped rule stands for the ones it does not list
    more = RULES.finding("EA103", "7 more findings of this rule, from stitch 9 on", count=7)
    assert more.as_dict()["count"] == 7 and count_by_severity([f, more]) == {"error": 8, "warning": 0, "info": 0}


def test_unknown_code_lists_valid():
    with pytest.raises(ValueError, match="rule code must be one of EA101, "):
        RULES["EA999"]


def test_settings_validated():
    with pytest.raises(ValueError, match="format must be one of"):
        RuleSettings(format="xyz")
    with pytest.raises(ValueError, match="density_error_count must be an integer"):
        RuleSettings(density_error_count=0)


# --------------------------------------------------------------------- EA1xx
def test_ea101_needle_in_corridor():
    xy = _zig()
    xy[4] = (14.0, 1.0)  # 1.0 mm from the axis, corridor 1.5 + 0.3 = 1.8 mm
    hits = _hits(_check(_layout(xy)), "EA101")
    assert [(f.stitch_index, f.xy_mm) for f in hits] == [(4, (14.0, 1.0))]
    assert "1.00 mm" in hits[0].message and "1.80 mm corridor" in hits[0].message
    xy[4] = (14.0, 1.81)
    assert not _hits(_check(_layout(xy)), "EA101")


def test_ea101_counts_the_end_margin_tube():
    xy = [(-5.0, 3.0), (-5.0, -3.0), (-3.0, 0.5)]  # beyond the path start, 0.5 mm from the extended axis
    assert not _hits(_check(_layout(xy, tubes=(_tube(end_margin_mm=0.0),))), "EA101")
    hits = _hits(_check(_layout(xy, tubes=(_tube(end_margin_mm=10.0),))), "EA101")
    assert [f.stitch_index for f in hits] == [2]


def test_ea102_record_over_format_limit():
    xy = [(0.0, 5.0), (12.2, 5.0), (12.2, -7.0)]  # dx 12.2 > 12.1 (DST); second record dy 12.0 fine
    hits = _hits(_check(_layout(xy, tubes=())), "EA102")
    assert [f.stitch_index for f in hits] == [1]
    assert not _hits(_check(_layout([(0.0, 5.0), (12.1, 5.0)], tubes=())), "EA102")
    assert not _hits(_check(_layout(xy, tubes=()), format="jef"), "EA102")  # 12.7 mm


def test_ea103_stitch_over_machine_max():
    xy = [(0.0, 0.0), (8.0, 7.0), (14.0, 0.0)]  # lengths hypot(8,7)=10.63, hypot(6,7)=9.22
    hits = _hits(_check(_layout(xy, tubes=()), max_stitch_mm=10.0), "EA103")
    assert [f.stitch_index for f in hits] == [1] and "10.63 mm" in hits[0].message


def test_ea104_too_short_only_between_stitches():
    xy = [(0.0, 0.0), (0.0, 0.0), (0.2, 0.0), (0.2, 3.0), (0.2, 3.0)]
    cmds = [P, S, S, J, S]  # stop->stitch and jump->stitch at 0 mm are first penetrations
    hits = _hits(_check(_layout(xy, cmds, tubes=()), min_stitch_mm=0.3), "EA104")
    assert [f.stitch_index for f in hits] == [2] and "0.20 mm" in hits[0].message


def test_density_hand_counted():
    # points on a line; within 0.5 mm (inclusive), the point itself counted:
    # 0: {0, .25, .5} = 3; .25: {0, .25, .5, .75} = 4; .5: 4; .75: {.25, .5, .75} = 3;
    # 2.0: {2.0, 2.5} = 2; 2.5: 2; 5.0: 1
    x = [0.0, 0.25, 0.5, 0.75, 2.0, 2.5, 5.0]
    assert needle_density([(v, 0.0) for v in x]).tolist() == [3, 4, 4, 3, 2, 2, 1]
    assert needle_density([(0.0, 0.0), (0.3, 0.4)], 0.5).tolist() == [2, 2]  # distance exactly 0.5
    assert needle_density([(0.0, 0.0), (0.3, 0.41)], 0.5).tolist() == [1, 1]


def test_ea105_ea106_density():
    x = [0.0, 0.25, 0.5, 0.75, 2.0, 2.5, 5.0]
    found = _check(_layout([(v, 10.0) for v in x], tubes=()), min_stitch_mm=0.0)
    assert [f.stitch_index for f in _hits(found, "EA105")] == [0, 1, 2, 3]
    assert not _hits(found, "EA106")
    # a centre and six points at 0.2 mm around it: each has all 7 within 0.4 mm -> error
    ring = [(10 + 0.2 * math.cos(k * math.pi / 3), 10 + 0.2 * math.sin(k * math.pi / 3)) for k in range(6)]
    found = _check(_layout([(10.0, 10.0)] + ring, tubes=()), min_stitch_mm=0.0)
    assert len(_hits(found, "EA106")) == 7 and not _hits(found, "EA105")
    assert "7 needle points within 0.5 mm" in _hits(found, "EA106")[0].message
    assert not _hits(_check(_layout(_zig(), tubes=())), "EA105")


# --------------------------------------------------------------------- EA2xx
def _check_sleeve(layout, **settings):
    return sleeve_rules.check_layout(layout, RuleSettings(**settings))


def test_ea201_ea202_sleeve():
    # r0 <= r_f iff w <= (pi^2 - 4)/pi * r_f = 2.8025 mm for r_f = 1.5
    no_sleeve = _check_sleeve(_layout(_zig(), tubes=(_tube(half_width_mm=1.3),)))
    assert len(_hits(no_sleeve, "EA201")) == 1 and "needs w > 2.80 mm" in _hits(no_sleeve, "EA201")[0].message
    # w = 3.0: r0 = (3 + 2 sqrt(2.25 + 9)) / (2 pi) = 1.54510, gap 0.045 < 0.1
    r0 = (3.0 + 2 * math.sqrt(2.25 + 9.0)) / (2 * math.pi)
    tight = _check_sleeve(_layout(_zig(), tubes=(_tube(half_width_mm=1.5),)))
    assert len(_hits(tight, "EA202")) == 1 and f"{r0:.3f}" in _hits(tight, "EA202")[0].message
    assert not _hits(tight, "EA201")
    fine = _check_sleeve(_layout(_zig()))
    assert not _hits(fine, "EA201") and not _hits(fine, "EA202")
    assert not _hits(_check(_layout(_zig(), tubes=(_tube(half_width_mm=1.3),))), "EA201")  # physics: predict's


def test_ea203_interval_over_diameter():
    # legs cross the axis at the leg midpoints: spacing = s; 3.5 mm > 2 r_f = 3 mm
    hits = _hits(_check(_layout(_zig(s=3.5))), "EA203")
    assert [f.stitch_index for f in hits] == list(range(2, 10))
    assert "3.50 mm apart" in hits[0].message
    assert not _hits(_check(_layout(_zig(s=2.9))), "EA203")


def _actuator_plan(params, realised, w_real=7.0):
    cl = Centerline.straight(20.0)
    act = ActuatorPlan("A1", params, Tube(), cl, realised)
    recs = [(x, y, S, Role.LEG) for x, y in _zig(n=6, w=w_real, x0=2.0)]
    return StitchPlan.from_records(recs, actuators=(act,))


def test_ea204_angle_off_request():
    def run(angle):
        plan = _actuator_plan(CrossParams(7.0, 1.4, 60.0), Realised(7.0, 1.4, angle, 20.0))
        return _hits(check_geometry(plan), "EA204")

    hits = run(60.5)  # 0.5 deg off > 0.1 deg tolerance
    assert len(hits) == 1 and hits[0].actuator == "A1" and hits[0].stitch_index == 0
    assert not run(60.05)


def test_ea205_spacing_off_request():
    def run(interval):
        return _hits(check_geometry(_actuator_plan(ZigzagParams(7.0, 1.4), Realised(7.0, interval, 11.3, 20.0))), "EA205")

    # allowed: 1 % of 1.4 mm plus half the 0.1 mm machine grid = 0.064 mm
    assert len(run(1.47)) == 1 and len(run(1.33)) == 1  # 0.07 mm off
    assert not run(1.46) and not run(1.41)  # 0.06 mm, 0.01 mm


def test_ea207_width_off_request():
    def run(width):
        return _hits(check_geometry(_actuator_plan(ZigzagParams(6.1, 1.0), Realised(width, 1.0, 0.0, 20.0))), "EA207")

    # allowed: half the 0.1 mm machine grid
    assert len(run(6.0)) == 1 and len(run(6.2)) == 1
    assert not run(6.1) and not run(6.14) and not run(6.06)


@pytest.mark.parametrize("width", [3.7, 6.1, 6.4, 7.0, 8.3])
def test_the_quick_command_sews_the_width_asked_on_the_grid(tmp_path, width):
    """``embroact zigzag --width-mm W`` lays its straight path so that both rails lie on the machine grid: the
    decoded file's rails (pystitch) are W apart for an odd number of grid units too (3.7 mm was sewn 3.6, a width
    the input check refuses)."""
    import pystitch

    from embroact.export.cli.main import main

    out = tmp_path / "z.dst"
    assert main(["zigzag", "--width-mm", str(width), "--length-mm", "40", "-o", str(out), "--json"]) == 0
    ys = sorted({y for x, y, c in pystitch.read(str(out)).stitches if c == pystitch.STITCH})
    assert (ys[-1] - ys[0]) == round(width * 10), ys  # file units of 0.1 mm


def test_ea206_near_neutral_angle():
    # neutral: tan(alpha0) = sqrt((2 r_f)^2 + (w/2)^2) / w = sqrt(9 + 12.25) / 7 -> 33.37 deg
    neutral = math.degrees(math.atan(math.sqrt(9.0 + 12.25) / 7.0))
    assert abs(neutral - 33.37) < 0.01

    def run(angle):
        return _hits(sleeve_rules.check_without_model(_actuator_plan(CrossParams(7.0, 1.4, angle),
                                                            Realised(7.0, 1.4, angle, 20.0))), "EA206")

    assert len(run(35.0)) == 1 and f"{neutral:.2f}" in run(35.0)[0].message
    assert not run(45.0) and not run(30.0)  # 3.37 deg away, band 3 deg


# --------------------------------------------------------------------- EA3xx
def _arc(radius, n=400):
    t = np.linspace(0.0, math.pi / 2, n)
    return np.column_stack([radius * np.cos(t), radius * np.sin(t)])


def test_ea301_turning_radius():
    # minimum turning radius 3 x 2 r_f = 9 mm
    hits = _hits(_check(_layout([], tubes=(_tube(_arc(5.0)),))), "EA301")
    assert len(hits) == 1 and "radius 5.00 mm" in hits[0].message and "9 mm" in hits[0].message
    assert not _hits(_check(_layout([], tubes=(_tube(_arc(20.0)),))), "EA301")
    corner = _hits(_check(_layout([], tubes=(_tube([(0, 0), (50, 0), (50, 50)]),))), "EA301")
    assert len(corner) == 1 and "corner" in corner[0].message
    assert np.hypot(corner[0].xy_mm[0] - 50.0, corner[0].xy_mm[1]) <= 25.0


def test_ea302_self_intersection():
    hits = _hits(_check(_layout([], tubes=(_tube([(0, 0), (10, 0), (10, 10), (5, 10), (5, -5)]),))), "EA302")
    assert len(hits) == 1 and hits[0].xy_mm == (5.0, 0.0)  # the last segment crosses the first at (5, 0)
    closed = _hits(_check(_layout([], tubes=(_tube([(0, 0), (10, 0), (10, 10), (0, 0)]),))), "EA302")
    assert len(closed) == 1 and "closed" in closed[0].message
    assert not _hits(_check(_layout([], tubes=(_tube([(0, 0), (10, 0), (10, 10)]),))), "EA302")


def _two_tubes(gap_mm):
    return (_tube(name="A"), _tube([(0.0, gap_mm), (100.0, gap_mm)], name="B"))


def test_ea303_ea304_tube_pairs():
    # corridors 1.8 + 1.8 = 3.6 mm; bands 3.5 + 3.5 + clearance 1 = 8 mm
    over = _check(_layout([], tubes=_two_tubes(3.0)))
    assert len(_hits(over, "EA303")) == 1 and "3.00 mm apart" in _hits(over, "EA303")[0].message
    close = _check(_layout([], tubes=_two_tubes(7.5)))
    assert not _hits(close, "EA303") and len(_hits(close, "EA304")) == 1
    assert "0.50 mm apart" in _hits(close, "EA304")[0].message
    far = _check(_layout([], tubes=_two_tubes(9.0)))
    assert not _hits(far, "EA303") and not _hits(far, "EA304")


def test_ea305_end_margin_outside_hoop():
    # records span x 0..80 -> hoop 100 wide centred at 40: [-10, 90]; margin 30 reaches -30 and 110
    xy = [(0.0, 3.5), (40.0, -3.5), (80.0, 3.5)]
    tubes = (_tube([(0.0, 0.0), (80.0, 0.0)], end_margin_mm=30.0),)
    hits = _hits(_check(_layout(xy, tubes=tubes), hoop_width_mm=100.0, hoop_height_mm=100.0), "EA305")
    assert sorted(f.xy_mm for f in hits) == [(-30.0, 0.0), (110.0, 0.0)]
    tubes = (_tube([(0.0, 0.0), (80.0, 0.0)], end_margin_mm=5.0),)
    assert not _hits(_check(_layout(xy, tubes=tubes), hoop_width_mm=100.0, hoop_height_mm=100.0), "EA305")


def test_ea306_outside_hoop_including_jumps():
    # needle points and the start point span 0..120: a 100 mm hoop centred at 60 -> [10, 110]: x = 0 (a jump)
    # and 120 are out
    xy = [(0.0, 0.0), (15.0, 3.5), (60.0, -3.5), (120.0, 3.5)]
    hits = _hits(_check(_layout(xy, [J, S, S, S], tubes=()), hoop_width_mm=100.0, hoop_height_mm=100.0), "EA306")
    assert [f.stitch_index for f in hits] == [0, 3] and hits[0].message.startswith("jump record")
    assert not _hits(_check(_layout(xy[1:3], tubes=()), hoop_width_mm=100.0, hoop_height_mm=100.0), "EA306")


def test_ea306_a_stray_travel_is_one_finding_and_moves_no_stitch_out():
    """A 300 mm excursion by 25 jumps of 12 mm in the middle of 60 mm of stitching: the hoop stays centred on
    the needle points, the travel's first record is the one finding."""
    stitches = [(1.0 * k, 3.5 * (-1) ** k) for k in range(61)]
    out = [(60.0 + 12.0 * k, 3.5) for k in range(1, 26)]
    back = [(60.0 + 12.0 * k, 3.5) for k in range(24, -1, -1)]
    xy = stitches + out + back + [(59.0, -3.5)]
    cmds = [S] * 61 + [J] * 50 + [S]
    hits = _hits(_check(_layout(xy, cmds, tubes=()), hoop_width_mm=100.0, hoop_height_mm=100.0), "EA306")
    # hoop [-20, 80] x [-50, 50] (needle points and start point 0..60): the first jump outside is to x = 84
    # (record 62); the run goes out and back
    assert [f.stitch_index for f in hits] == [62]
    # farthest: x = 60 + 300 = 360, the hoop centre at x = 30 (needle points 0..60): 330 mm
    assert hits[0].message.startswith("a travel of 47 jump records outside") and "up to 330.0 mm" in hits[0].message


# --------------------------------------------------------------------- EA5xx
def test_ea501_jump_run_reads_as_trim():
    # file-like: three 10 mm jumps after a stitch (net 30 mm): the machine trims
    xy = [(0, 0), (10, 0), (20, 0), (30, 0), (31, 0)]
    hits = _hits(_check(_layout(xy, [S, J, J, J, S], tubes=())), "EA501")
    assert [f.stitch_index for f in hits] == [1] and "3 consecutive jump records" in hits[0].message
    # a trim written as jumps netting zero first (pyembroidery's DST trim), then travel: intended
    xy2 = [(0, 0), (0.2, 0.2), (-0.2, -0.2), (0, 0), (10, 0), (11, 0)]
    assert not _hits(_check(_layout(xy2, [S, J, J, J, J, S], tubes=())), "EA501")
    # plan-like: one 30 mm jump needs ceil(30 / 12.1) = 3 DST records; 20 mm needs 2
    assert _hits(_check(_layout([(0, 0), (30, 0), (31, 0)], [S, J, S], tubes=())), "EA501")
    assert not _hits(_check(_layout([(0, 0), (20, 0), (21, 0)], [S, J, S], tubes=())), "EA501")
    assert not _hits(_check(_layout([(0, 0), (0, 0), (30, 0), (31, 0)], [S, T, J, S], tubes=())), "EA501")
    assert not _hits(_check(_layout([(0, 0), (30, 0), (31, 0)], [S, J, S], tubes=()), format="pes"), "EA501")


def test_ea502_ea503_stops():
    a, b = _zig(n=4, x0=10.0), [(x, y + 50.0) for x, y in _zig(n=4, x0=10.0)]
    tubes = (_tube(name="A"), _tube([(0.0, 50.0), (100.0, 50.0)], name="B"))
    owner = [0] * 4 + [1] * 4
    missing = _check(_layout(a + b, [S] * 8, owner, tubes))
    hits = _hits(missing, "EA502")
    assert [(f.stitch_index, f.actuator) for f in hits] == [(4, "B")] and "from A to B" in hits[0].message
    ok = _check(_layout(a + [b[0]] + b, [S] * 4 + [P] + [S] * 4, owner[:4] + [1] + owner[4:], tubes))
    assert not _hits(ok, "EA502") and not _hits(ok, "EA503")
    inside = _check(_layout(a[:2] + [a[1]] + a[2:], [S, S, P, S, S], [0] * 5))
    assert [(f.stitch_index, f.actuator) for f in _hits(inside, "EA503")] == [(2, "A")]
    # a writer's needle-down in place before the colour change (PES): jump, stitch 0 mm, stop, stitch 0 mm
    seq = a + [b[0], b[0], b[0], b[0]] + b[1:]
    cmds = [S] * 4 + [J, S, P, S] + [S] * 3
    found = _check(_layout(seq, cmds, [0] * 4 + [-1, 1, -1, 1] + [1] * 3, tubes))
    assert not _hits(found, "EA502") and not _hits(found, "EA503")


def test_ea504_record_count():
    lay = _layout(_zig(n=12), tubes=())
    assert len(_hits(_check(lay, max_records=11), "EA504")) == 1
    assert not _hits(_check(lay, max_records=12), "EA504")


# --------------------------------------------------------------------- real generated plans
def test_generated_zigzag_is_clean():
    plan = zigzag(Centerline.straight(100.0), ZigzagParams(width_mm=7.0, interval_mm=1.0))
    assert check_geometry(plan, RuleSettings(hoop_width_mm=200.0, hoop_height_mm=200.0)) == ()


def test_generated_plan_with_moved_leg_is_found():
    plan = zigzag(Centerline.straight(100.0), ZigzagParams(width_mm=7.0, interval_mm=1.0))
    i = int(np.flatnonzero(plan.roles == Role.LEG)[40])
    xy = plan.xy_mm.copy()
    xy[i, 1] = 0.5 * np.sign(xy[i, 1])
    bad = StitchPlan(xy, plan.commands, plan.roles, plan.actuator, plan.actuators, plan.name)
    hits = _hits(check_geometry(bad), "EA101")
    assert [f.stitch_index for f in hits] == [i] and hits[0].actuator == plan.actuators[0].name


def test_findings_are_capped_per_rule():
    xy = [(10.0 + i, 0.2) for i in range(30)]
    found = _hits(_check(_layout(xy), max_findings_per_rule=5), "EA101")
    assert len(found) == 6 and found[-1].message.startswith("25 more findings")


def test_corridor_query_matches_brute_force_distance():
    import shapely

    from embroact.patterns.spatial import TubeIndex

    t = np.linspace(0.0, 3 * math.pi, 300)
    path = shapely.LineString(np.column_stack([10 * t, 8 * np.sin(t)]))
    other = shapely.LineString([(0.0, 6.0), (90.0, -6.0)])  # crosses the sine: points near both count twice
    pts = np.random.default_rng(7).uniform([-5, -12], [100, 12], size=(2000, 2))
    point, tube, dist = TubeIndex([path, other]).within(pts, [2.0, 1.0])
    for k, (line, radius) in enumerate(((path, 2.0), (other, 1.0))):
        brute = shapely.distance(line, shapely.points(pts))
        assert point[tube == k].tolist() == np.flatnonzero(brute < radius).tolist()
        assert np.allclose(dist[tube == k], brute[point[tube == k]], atol=1e-12)


def test_density_matches_brute_force_counts():
    pts = np.random.default_rng(3).uniform(0.0, 4.0, size=(400, 2))
    pts[10] = pts[11]  # a repeated hole counts twice
    d = np.hypot(*(pts[:, None, :] - pts[None, :, :]).transpose(2, 0, 1))
    assert needle_density(pts, 0.5).tolist() == (d <= 0.5).sum(axis=1).tolist()


def test_bad_tube_paths_and_owners():
    with pytest.raises(ValueError, match="tube path of A must have a length > 0"):
        _tube([(1.0, 1.0), (1.0, 1.0)])
    with pytest.raises(ValueError, match="at least 2"):
        _tube([(1.0, 1.0)])
    with pytest.raises(ValueError, match="owner must be in"):
        Layout.from_points([(0, 0)], [S], [1], tubes=(_tube(),))


def _leg_crossings_mm(plan):
    """Where the plan's legs cross y = 0 (a straight path along +x), by linear interpolation, sorted; as arc
    length from the path's start."""
    xy, roles = plan.xy_mm - plan.actuators[0].centerline.points_mm[0], plan.roles
    out = []
    for i in np.flatnonzero(roles == Role.LEG):
        (x0, y0), (x1, y1) = xy[i - 1], xy[i]
        if i > 0 and y0 * y1 < 0.0:
            out.append(x0 + (x1 - x0) * y0 / (y0 - y1))
    return np.sort(np.array(out))


def test_ea203_leaves_out_the_transitions_the_generator_makes_between_segments():
    """Between two segments the generator leaves an unbent transition wider than 2 r_f (the model counts it as
    unbent tube): no EA203 there; a segment whose own interval is too wide still gets it, inside that segment."""
    from embroact.patterns.design import ActuatorSpec, Design, MachineSettings, OperationSettings, build_plan
    from embroact.patterns.segments import SegmentSpec

    def design(interval_mm):
        segs = (SegmentSpec(ZigzagParams(7.0, interval_mm), 40.0), SegmentSpec(CrossParams(7.0, 1.4, 45.0), 60.0))
        spec = ActuatorSpec.segmented("S", segs, Centerline.straight(100.0))
        return Design("s", Tube(), MachineSettings(), OperationSettings(), (spec,))

    plan = build_plan(design(1.0))
    x = _leg_crossings_mm(plan)
    gaps = np.diff(x)
    wider = np.flatnonzero(gaps > 3.0)  # one gap wider than 2 r_f: the one across the transition at 40-40.6 mm
    assert len(wider) == 1 and x[wider[0]] < 40.0 and x[wider[0] + 1] > 40.6 and gaps[wider[0]] > 4.0
    assert not _hits(check_geometry(plan), "EA203")
    plan = build_plan(design(3.5))
    hits = _hits(check_geometry(plan), "EA203")
    assert hits and all("3.50 mm apart" in f.message for f in hits)
    start = plan.actuators[0].centerline.points_mm[0][0]
    assert all(plan.xy_mm[f.stitch_index][0] - start < 40.0 for f in hits)  # inside segment 0, not at the transition
