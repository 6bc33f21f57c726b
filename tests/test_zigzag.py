"""Zigzag generator: hand coordinates, record convention, invariants on straight and curved paths."""
import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from embroact.patterns.centerline import Centerline
from embroact.patterns.limits import GRID_ROUNDING_MM
from embroact.patterns.base.errors import ParameterError, PathError, PatternError
from embroact.patterns.params import CrossParams, StitchOptions, Tube, ZigzagParams
from embroact.patterns.plan import Command, Role
from embroact.patterns.zigzag import zigzag
from embroact.predict.derived import derive
from embroact.predict.tubelaws import transition_pressure_kpa

from h1_checks import (
    PATHS,
    arc,
    assert_outside_corridor,
    assert_record_convention,
    assert_valid_plan,
    legs,
    rail_distance_error,
)

S, C, T, E = Command.STITCH, Command.STOP, Command.TRIM, Command.END


def test_tiny_straight_zigzag_by_hand():
    plan = zigzag(Centerline.straight(4.0), ZigzagParams(width_mm=7.0, interval_mm=1.0))
    # stations s = 0..4, left/right alternately; 3 lock stitches of 0.7 mm inward on the rail
    expected = [
        ((0.7, 3.5), C, Role.CONTROL),
        ((0.0, 3.5), S, Role.TIE_IN),
        ((0.7, 3.5), S, Role.TIE_IN),
        ((0.0, 3.5), S, Role.TIE_IN),
        ((1.0, -3.5), S, Role.LEG),
        ((2.0, 3.5), S, Role.LEG),
        ((3.0, -3.5), S, Role.LEG),
        ((4.0, 3.5), S, Role.LEG),
        ((3.3, 3.5), S, Role.TIE_OFF),
        ((4.0, 3.5), S, Role.TIE_OFF),
        ((3.3, 3.5), S, Role.TIE_OFF),
        ((3.3, 3.5), T, Role.CONTROL),
        ((3.3, 3.5), E, Role.CONTROL),
    ]
    np.testing.assert_allclose(plan.xy_mm, [e[0] for e in expected], atol=1e-12)
    assert plan.commands.tolist() == [e[1] for e in expected]
    assert plan.roles.tolist() == [e[2] for e in expected]
    assert plan.actuator.tolist() == [0] * 12 + [-1]


def test_rotated_zigzag_is_the_rotated_hand_plan():
    ref = zigzag(Centerline.straight(4.0), ZigzagParams(7.0, 1.0))
    rot = zigzag(Centerline.straight(4.0, origin_mm=(10.0, 20.0), rotation_deg=90.0), ZigzagParams(7.0, 1.0))
    # rotate +90 deg: (x, y) -> (-y, x), then move by (10, 20)
    np.testing.assert_allclose(rot.xy_mm, np.c_[10.0 - ref.xy_mm[:, 1], 20.0 + ref.xy_mm[:, 0]], atol=1e-12)


def test_legs_centred_on_the_path():
    plan = zigzag(Centerline.straight(10.5), ZigzagParams(7.0, 1.0))
    leg_x = np.concatenate(legs(plan))[:, 0]
    # the legs span 0.25 .. 10.25 mm, on the machine grid (round half to even) 0.2 .. 10.2 mm
    assert leg_x.min() == pytest.approx(0.2, abs=1e-12) and leg_x.max() == pytest.approx(10.2, abs=1e-12)
    assert plan.actuators[0].realised.length_mm == pytest.approx(10.0, abs=1e-12)


def test_tie_options_are_used():
    plan = zigzag(Centerline.straight(20.0), ZigzagParams(7.0, 1.0), options=StitchOptions(tie_stitch_mm=0.5, tie_count=4))
    assert_record_convention(plan, tie_count=4)
    ties = plan.xy_mm[plan.roles == Role.TIE_IN]
    np.testing.assert_allclose(np.hypot(*np.diff(ties, axis=0).T), 0.5, atol=1e-12)
    np.testing.assert_allclose(np.hypot(*(ties[0] - plan.xy_mm[0])), 0.5, atol=1e-12)


@pytest.mark.parametrize("name", sorted(PATHS))
@pytest.mark.parametrize("w, s", [(7.0, 1.0), (5.0, 0.8), (9.0, 1.5)])
def test_invariants_on_every_path(name, w, s):
    path = PATHS[name]()
    plan = zigzag(path, ZigzagParams(w, s), name=name)
    assert_valid_plan(plan, width_mm=w, interval_mm=s, angle_deg=math.degrees(math.atan(s / w)), passes=1)
    assert plan.actuators[0].adjustments == ()
    # each leg individually: advances s along the path and crosses from rail to rail
    sa, oa = path.project(legs(plan)[0])
    sb, ob = path.project(legs(plan)[1])
    np.testing.assert_allclose(sb - sa, s, atol=2 * GRID_ROUNDING_MM)  # both ends rounded to the machine grid
    np.testing.assert_allclose(np.abs(ob - oa), w, atol=2 * GRID_ROUNDING_MM)
    # tie stitches on the rails (projection frame) and outside the corridor
    ties = np.isin(plan.roles, [Role.TIE_IN, Role.TIE_OFF])
    _, off = path.project(plan.xy_mm[ties])
    np.testing.assert_allclose(np.abs(off), w / 2, atol=GRID_ROUNDING_MM + 1e-9)


def test_straight_rails_by_shapely_distance():
    plan = zigzag(Centerline.straight(50.0, rotation_deg=17.0), ZigzagParams(7.0, 1.0))
    assert rail_distance_error(plan, plan.commands == Command.STITCH) <= GRID_ROUNDING_MM + 1e-9


def test_legs_follow_the_local_normal_on_an_arc():
    r, w, s = 25.0, 7.0, 1.0
    plan = zigzag(arc(r, 200.0), ZigzagParams(w, s))
    centre = np.array([0.0, r])
    pts = np.concatenate([legs(plan)[0][:1], legs(plan)[1]])
    rad = np.hypot(*(pts - centre).T)
    # left rail at r - w/2 from the arc's centre, right rail at r + w/2, alternately
    np.testing.assert_allclose(rad[0::2], r - w / 2, atol=GRID_ROUNDING_MM + 1e-4)
    np.testing.assert_allclose(rad[1::2], r + w / 2, atol=GRID_ROUNDING_MM + 1e-4)
    # consecutive needle points advance by s / r in polar angle about the centre
    ang = np.unwrap(np.arctan2(pts[:, 1] - r, pts[:, 0]))
    np.testing.assert_allclose(np.diff(ang), s / r, atol=2 * GRID_ROUNDING_MM / (r - w / 2))


@pytest.mark.parametrize("w, p0_paper", [(5.0, 25.0), (7.0, 85.0), (9.0, 180.0)])
def test_p0_within_5_percent_of_paper(w, p0_paper):
    g = derive(zigzag(Centerline.straight(100.0), ZigzagParams(w, 1.0)).actuators[0])
    assert float(transition_pressure_kpa(g.r0_mm, g.tube, "paper")) == pytest.approx(p0_paper, rel=0.05)


@pytest.mark.parametrize("name", ["straight", "s_curve"])
def test_derived_r0_matches_model_formula(name):
    plan = zigzag(PATHS[name](), ZigzagParams(7.0, 1.0))
    a = plan.actuators[0]
    w, rf = a.realised.width_mm, 1.5
    r0 = (w + 2 * math.sqrt((w / 2) ** 2 + (2 * rf) ** 2)) / (2 * math.pi)  # docs/model.md section 2
    g = derive(a)
    assert g.r0_mm == pytest.approx(r0, rel=1e-12)
    x = r0 / rf
    p0 = float(transition_pressure_kpa(g.r0_mm, g.tube, "paper"))
    assert p0 == pytest.approx(0.13 / 2 * (x**2 + 1 / x**2 - 2) * 1000, rel=1e-9)  # docs/model.md section 3
    assert g.beta0_deg == 0.0


def test_realised_is_measured_not_copied():
    # a path of 10.5 mm covers 10 intervals: the realised length is 10, not the path length
    a = zigzag(Centerline.straight(10.5), ZigzagParams(7.0, 1.0)).actuators[0]
    assert a.realised.length_mm == pytest.approx(10.0)
    assert a.params == ZigzagParams(7.0, 1.0) and a.centerline.length_mm == pytest.approx(10.5)


def test_deterministic_and_read_only():
    a = zigzag(PATHS["s_curve"](), ZigzagParams(7.0, 1.0))
    b = zigzag(PATHS["s_curve"](), ZigzagParams(7.0, 1.0))
    assert a == b
    with pytest.raises(ValueError):
        a.xy_mm[0, 0] = 1.0


def _spiral() -> Centerline:
    th = np.linspace(2 * np.pi, 6 * np.pi, 4000)
    rad = 10.0 + 5.0 * th / (2 * np.pi)  # turns 5 mm apart, radius of curvature > 15 mm
    return Centerline(np.c_[rad * np.cos(th), rad * np.sin(th)])


@pytest.mark.parametrize(
    "path, params, kwargs, error, fragment",
    [
        (Centerline.straight(50.0), ZigzagParams(3.0, 1.0), {}, ParameterError,
         "width_mm must be > 2*(r_f + clearance) = 3.6, got 3"),
        (Centerline.straight(50.0), ZigzagParams(5.0, 1.0), {"tube": Tube(outer_radius_mm=2.0, clearance_mm=0.5)},
         ParameterError, "width_mm must be > 2*(r_f + clearance) = 5, got 5"),
        (Centerline.straight(1.5), ZigzagParams(7.0, 1.0), {}, PatternError,
         "path length_mm must be >= 2 for a zigzag with interval_mm=1 (at least 2 legs), got 1.5"),
        (arc(3.0, 90.0), ZigzagParams(7.0, 1.0), {}, PathError,
         "path curvature radius must be >= width_mm/2 = 3.5 mm, got 3"),
        (Centerline.from_points([[0, 0], [30, 0], [30, 30]]), ZigzagParams(7.0, 1.0), {}, PathError,
         "path has a corner at (30.00, 0.00) mm"),
        (_spiral(), ZigzagParams(7.0, 1.0), {}, PathError, "inside the tube corridor r_f + clearance = 1.8 mm"),
        (Centerline.straight(9e5), ZigzagParams(7.0, 0.1), {}, PatternError,
         "pattern would need about 9e+06 records, more than the limit 5,000,000"),
        (Centerline.straight(50.0), ZigzagParams(7.0, 0.05), {}, ParameterError,
         "interval_mm must be >= 0.1 (needle points closer than the machine grid merge), got 0.05"),
        (Centerline.straight(50.0), CrossParams(7.0, 1.0, 45.0), {}, ParameterError,
         "params must be ZigzagParams, got CrossParams"),
        (Centerline.straight(50.0), ZigzagParams(7.0, 1.0), {"tube": "tube"}, ParameterError,
         "tube must be a Tube, got str"),
    ],
)
def test_bad_input_messages(path, params, kwargs, error, fragment):
    with pytest.raises(error) as exc:
        zigzag(path, params, **kwargs)
    assert fragment in str(exc.value)
    assert "\n" not in str(exc.value)


@pytest.mark.parametrize(
    "kwargs, fragment",
    [({"width_mm": -1.0, "interval_mm": 1.0}, "width_mm must be in (0, 200), got -1"),
     ({"width_mm": 7.0, "interval_mm": math.nan}, "interval_mm must be a finite number"),
     ({"width_mm": math.inf, "interval_mm": 1.0}, "width_mm must be a finite number")],
)
def test_params_reject_bad_numbers(kwargs, fragment):
    with pytest.raises(ParameterError) as exc:
        ZigzagParams(**kwargs)
    assert fragment in str(exc.value)


def test_accepts_svg_string_and_linestring():
    d = "M 0 0 C 22.09 0 40 17.91 40 40"
    a = zigzag(d, ZigzagParams(7.0, 1.0))
    b = zigzag(shapely.LineString(Centerline.from_svg_path(d).points_mm), ZigzagParams(7.0, 1.0))
    assert a.isclose(b)


@settings(max_examples=80, deadline=None)
@given(
    w=st.floats(3.7, 20.0),
    s=st.floats(0.1, 5.0),
    radius_factor=st.floats(0.6, 20.0),  # at exactly w/2 the inner rail collapses to a point
    sweep=st.floats(5.0, 320.0),
    left=st.booleans(),
)
def test_property_any_zigzag_on_an_arc(w, s, radius_factor, sweep, left):
    path = arc(radius_factor * w, sweep, n=3000, left=left)
    if path.length_mm < max(2 * s, StitchOptions().tie_stitch_mm):
        with pytest.raises(PatternError, match="path length_mm must be >="):
            zigzag(path, ZigzagParams(w, s))
        return
    plan = zigzag(path, ZigzagParams(w, s))
    if s * (1.0 - w / (2.0 * radius_factor * w)) < 5 * GRID_ROUNDING_MM:  # needle steps on the inner rail
        assert_record_convention(plan)  # near the machine grid: rounding decides the realised values
        assert_outside_corridor(plan)
        return
    assert_valid_plan(plan, width_mm=w, interval_mm=s, angle_deg=math.degrees(math.atan(s / w)), passes=1)
