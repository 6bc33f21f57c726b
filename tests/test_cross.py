"""Cross generator: exact paper case, adjustments, every leg at +-alpha0, rails, curves, errors."""
import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from embroact.patterns.centerline import Centerline
from embroact.patterns.limits import GRID_ROUNDING_MM
from embroact.patterns.cross import MAX_EDGE_STITCH_MM, closing, cross
from embroact.patterns.base.errors import ParameterError, PatternError
from embroact.patterns.params import CrossParams, ZigzagParams
from embroact.patterns.plan import Command, Role
from embroact.predict.derived import derive

from h1_checks import (
    PATHS,
    arc,
    assert_outside_corridor,
    assert_record_convention,
    assert_valid_plan,
    legs,
    rail_distance_error,
)

PAPER = CrossParams(width_mm=7.0, interval_mm=1.4, angle_deg=45.0)


def _leg_frame(plan, path):
    """Per leg: ds, doffset and the arc length where it crosses the centerline."""
    (sa, oa), (sb, ob) = path.project(legs(plan)[0]), path.project(legs(plan)[1])
    ds, do = sb - sa, ob - oa
    return ds, do, sa - oa * ds / do


@pytest.fixture(scope="module")
def paper_plan():
    return cross(Centerline.straight(100.0), PAPER)


def test_paper_case_is_exact(paper_plan):
    a = paper_plan.actuators[0]
    assert a.adjustments == ()
    assert a.realised.passes == 10  # 2 * 7 * tan(45 deg) / 1.4
    assert a.realised.angle_deg == pytest.approx(45.0, abs=1e-9)
    assert a.realised.interval_mm == pytest.approx(1.4, rel=1e-9)
    assert a.realised.width_mm == pytest.approx(7.0, abs=1e-12)
    assert_record_convention(paper_plan)
    assert_outside_corridor(paper_plan)
    assert paper_plan.count(Command.JUMP) == 0  # sewn continuously


def test_paper_every_leg_at_45_and_every_point_on_a_rail(paper_plan):
    start, end = legs(paper_plan)
    d = end - start
    ang = np.degrees(np.arctan2(np.abs(d[:, 0]), np.abs(d[:, 1])))  # from the perpendicular (y axis)
    np.testing.assert_allclose(ang, 45.0, atol=1e-9)
    stitches = paper_plan.xy_mm[paper_plan.commands == Command.STITCH]
    np.testing.assert_allclose(np.abs(stitches[:, 1]), 3.5, atol=1e-12)
    # both families present in equal numbers (within one leg at the turns)
    plus = np.sign(d[:, 0] * d[:, 1])
    assert abs(int(np.sum(plus > 0)) - int(np.sum(plus < 0))) <= 2


def test_paper_parallel_legs_every_interval_in_the_interior(paper_plan):
    start, end = legs(paper_plan)
    d = end - start
    cross_x = start[:, 0] - start[:, 1] * d[:, 0] / d[:, 1]  # where the leg crosses y = 0
    family = np.sign(d[:, 0] * d[:, 1])
    lo, hi = cross_x.min() + 14.0, cross_x.max() - 14.0  # 2 w tan(alpha0) from either end
    for f in (-1, 1):
        x = np.sort(cross_x[(family == f) & (cross_x > lo) & (cross_x < hi)])
        np.testing.assert_allclose(np.diff(x), 1.4, atol=1e-9)  # no leg missing inside


def test_paper_edges_run_along_a_rail(paper_plan):
    e = np.flatnonzero(paper_plan.roles == Role.EDGE)
    assert len(e) == 9  # one between each pair of the 10 passes
    a, b = paper_plan.xy_mm[e - 1], paper_plan.xy_mm[e]
    np.testing.assert_array_equal(np.sign(a[:, 1]), np.sign(b[:, 1]))
    assert np.all(np.hypot(*(b - a).T) <= MAX_EDGE_STITCH_MM)


def test_passes_alternate_direction(paper_plan):
    start, end = legs(paper_plan)
    direction = np.sign(end[:, 0] - start[:, 0])
    runs = 1 + np.count_nonzero(np.diff(direction))
    assert runs == 10 and direction[0] == 1


def test_derived_beta0_matches_model_formula_mpmath(paper_plan):
    a = paper_plan.actuators[0]
    mpmath.mp.dps = 50
    w, al, rf = mpmath.mpf(a.realised.width_mm), mpmath.radians(mpmath.mpf(a.realised.angle_deg)), mpmath.mpf("1.5")
    h = w / 2
    beta0 = mpmath.degrees(mpmath.asin(h * mpmath.tan(al) / mpmath.sqrt((2 * rf) ** 2 + h**2 * (1 + mpmath.tan(al) ** 2))))
    r0 = (w + 2 * mpmath.sqrt(h**2 + (2 * rf) ** 2)) / (2 * mpmath.pi)
    g = derive(a)
    assert g.beta0_deg == pytest.approx(float(beta0), rel=1e-12)
    assert g.r0_mm == pytest.approx(float(r0), rel=1e-12)
    assert g.requested_angle_deg == 45.0


@pytest.mark.parametrize(
    "angle, adjust, passes, interval, angle_out, note",
    [
        # 2 * 7 * tan(15 deg) / 1.4 = 2.68 -> 3 passes; interval 14 tan15 / 3 (10.7 %) beats angle (11.3 %)
        (15.0, "auto", 3, 14 * math.tan(math.radians(15)) / 3, 15.0, "interval_mm 1.4 -> 1.25 (3 passes)"),
        (15.0, "angle", 3, 1.4, math.degrees(math.atan(3 * 1.4 / 14)), "angle_deg 15 -> 16.7 (3 passes)"),
        # 5.77 -> 6 passes: angle atan(0.6) = 30.96 (3.2 %) beats interval 1.347 (3.8 %)
        (30.0, "auto", 6, 1.4, math.degrees(math.atan(0.6)), "angle_deg 30 -> 30.96 (6 passes)"),
        (30.0, "interval", 6, 14 * math.tan(math.radians(30)) / 6, 30.0, "interval_mm 1.4 -> 1.347 (6 passes)"),
        # 17.32 -> 17 passes: angle atan(17 * 1.4 / 14) = 59.53 deg
        (60.0, "auto", 17, 1.4, math.degrees(math.atan(1.7)), "angle_deg 60 -> 59.53 (17 passes)"),
    ],
)
def test_adjustments(angle, adjust, passes, interval, angle_out, note):
    plan = cross(Centerline.straight(100.0), CrossParams(7.0, 1.4, angle), adjust=adjust)
    a = plan.actuators[0]
    assert a.adjustments == (note,)
    assert a.realised.passes == passes
    # measured on the needle points, which sit on the 0.1 mm machine grid
    assert a.realised.interval_mm == pytest.approx(interval, abs=0.005)
    assert a.realised.angle_deg == pytest.approx(angle_out, abs=0.05)
    assert a.params.angle_deg == angle  # the request is kept
    assert closing(CrossParams(7.0, 1.4, angle), adjust)[0] == passes


def test_unknown_adjust_lists_valid_names():
    with pytest.raises(ParameterError, match="adjust must be one of 'auto', 'interval', 'angle', got 'both'"):
        cross(Centerline.straight(100.0), PAPER, adjust="both")


@pytest.mark.parametrize("name", sorted(PATHS))
@pytest.mark.parametrize("angle", [30.0, 45.0, 60.0])
def test_invariants_on_every_path(name, angle):
    path = PATHS[name]()
    plan = cross(path, CrossParams(7.0, 1.4, angle))
    n, s, alpha, _ = closing(plan.actuators[0].params)
    assert_valid_plan(plan, width_mm=7.0, interval_mm=s, angle_deg=alpha, passes=n)
    ds, do, _ = _leg_frame(plan, path)
    leg_angle = np.degrees(np.arctan2(np.abs(ds), np.abs(do)))
    # every leg, in the path frame, within what rounding its two ends to the machine grid can turn it
    grid_turn = np.degrees(2 * GRID_ROUNDING_MM * (np.abs(ds) + np.abs(do)) / (ds**2 + do**2))
    assert np.all(np.abs(leg_angle - alpha) <= 0.1 + grid_turn)
    _, off = path.project(plan.xy_mm[plan.commands == Command.STITCH])
    np.testing.assert_allclose(np.abs(off), 3.5, atol=GRID_ROUNDING_MM + 1e-9)  # every needle point on a rail


def test_straight_rails_by_shapely_distance():
    plan = cross(Centerline.straight(60.0, rotation_deg=-40.0), PAPER)
    assert rail_distance_error(plan, plan.commands == Command.STITCH) <= GRID_ROUNDING_MM + 1e-9


@pytest.mark.parametrize("name", ["arc_left", "s_curve"])
def test_parallel_spacing_on_curves(name):
    path = PATHS[name]()
    plan = cross(path, PAPER)
    ds, do, where = _leg_frame(plan, path)
    family = np.sign(ds * do)
    lo, hi = where.min() + 14.0, where.max() - 14.0
    for f in (-1, 1):
        x = np.sort(where[(family == f) & (where > lo) & (where < hi)])
        np.testing.assert_allclose(np.diff(x), 1.4, atol=2 * GRID_ROUNDING_MM)  # leg ends on the machine grid


@pytest.mark.parametrize(
    "path, params, error, fragment",
    [
        (Centerline.straight(20.0), PAPER, PatternError,
         "path length_mm must be >= 28 for a cross pattern with width_mm=7, angle_deg=45 "
         "(4*w*tan(angle), two leg pitches, and >= tie_stitch_mm), got 20"),
        (Centerline.straight(100.0), CrossParams(3.0, 1.4, 45.0), ParameterError,
         "width_mm must be > 2*(r_f + clearance) = 3.6, got 3"),
        (Centerline.straight(9e5), CrossParams(7.0, 0.1, 45.0), PatternError,
         "more than the limit 5,000,000; use a larger interval_mm or a shorter path"),
        (Centerline.straight(100.0), ZigzagParams(7.0, 1.0), ParameterError, "params must be CrossParams"),
    ],
)
def test_bad_input_messages(path, params, error, fragment):
    with pytest.raises(error) as exc:
        cross(path, params)
    assert fragment in str(exc.value)


@pytest.mark.parametrize("angle", [0.0, 90.0, -5.0, math.nan])
def test_angle_must_be_inside_0_90(angle):
    with pytest.raises(ParameterError, match="angle_deg must be"):
        CrossParams(7.0, 1.4, angle)


def test_single_pass_when_legs_are_dense():
    # 2 * 7 * tan(5.71 deg) / 1.4 = 1: one +-alpha0 zigzag is the whole pattern
    alpha = math.degrees(math.atan(0.1))
    plan = cross(Centerline.straight(30.0), CrossParams(7.0, 1.4, alpha))
    assert plan.actuators[0].realised.passes == 1 and plan.count(Command.STITCH) > 0
    assert plan.actuators[0].adjustments == ()
    assert not np.any(plan.roles == Role.EDGE)


@settings(max_examples=80, deadline=None)
@given(
    w=st.floats(3.7, 20.0),
    s=st.floats(0.3, 3.0),
    angle=st.floats(3.0, 75.0),
    radius_factor=st.floats(0.6, 20.0),
    extra=st.floats(0.0, 60.0),
    left=st.booleans(),
)
def test_property_any_cross_on_an_arc(w, s, angle, radius_factor, extra, left):
    params = CrossParams(w, s, angle)
    n, s_real, alpha, _ = closing(params)
    radius = radius_factor * w  # >= w/2
    length = 4.0 * n * s_real / 2.0 + extra + 1.0
    sweep = min(math.degrees(length / radius), 300.0)
    path = arc(radius, sweep, n=3000, left=left)
    if path.length_mm < 4.0 * n * s_real / 2.0:
        with pytest.raises(PatternError, match="path length_mm must be >="):
            cross(path, params)
        return
    plan = cross(path, params)
    if s_real * (1.0 - w / (2.0 * radius)) < 5 * GRID_ROUNDING_MM:  # leg spacing on the inner rail
        assert_record_convention(plan)  # near the machine grid: rounding decides the realised values
        assert_outside_corridor(plan)
        return
    assert_valid_plan(plan, width_mm=w, interval_mm=s_real, angle_deg=alpha, passes=n)
