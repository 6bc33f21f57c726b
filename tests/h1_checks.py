"""Shared checks and paths for the pattern-generator tests (H1).

The checks use shapely and plain geometry, independent of the generator's own
projection: distances to the centerline LineString, hand-written record order.
"""
from __future__ import annotations

import math

import numpy as np
import shapely

from embroact.patterns.centerline import Centerline
from embroact.patterns.limits import GRID_ROUNDING_MM
from embroact.patterns.plan import Command, Role


def arc(radius_mm: float, angle_deg: float, *, n: int = 2000, left: bool = True) -> Centerline:
    """Circular arc starting at (0, 0) heading +x, turning left (or right)."""
    t = np.linspace(0.0, math.radians(angle_deg), n)
    sign = 1.0 if left else -1.0
    return Centerline(np.c_[radius_mm * np.sin(t), sign * radius_mm * (1.0 - np.cos(t))])


def s_curve() -> Centerline:
    """Two quarter circles of radius 40 mm (SVG cubic approximations), opposite turns."""
    return Centerline.from_svg_path("M 0 0 C 22.09 0 40 17.91 40 40 S 57.91 80 80 80")


def sine(length_mm: float = 150.0, amplitude_mm: float = 8.0, wavelength_mm: float = 100.0) -> Centerline:
    """Densely sampled sine wave (a smooth polyline given as points)."""
    x = np.linspace(0.0, length_mm, 3001)
    return Centerline(np.c_[x, amplitude_mm * np.sin(2 * np.pi * x / wavelength_mm)])


def gentle_polyline() -> Centerline:
    """A coarse polyline whose vertices turn by 5 deg or less (treated as smooth)."""
    ang = np.radians(np.cumsum([0.0, 5.0, 5.0, 4.0, -3.0, -5.0]))
    steps = 20.0 * np.c_[np.cos(ang), np.sin(ang)]
    return Centerline(np.vstack([[0.0, 0.0], np.cumsum(steps, axis=0)]))


PATHS = {
    "straight": lambda: Centerline.straight(100.0, origin_mm=(5.0, -3.0), rotation_deg=30.0),
    "arc_left": lambda: arc(25.0, 200.0),
    "arc_right": lambda: arc(10.0, 300.0, left=False),
    "s_curve": s_curve,
    "sine": sine,
    "polyline": gentle_polyline,
}


def assert_record_convention(plan, tie_count: int = 3) -> None:
    """STOP, TIE_IN..., LEG/EDGE..., TIE_OFF..., TRIM, END; actuator 0 except END (-1)."""
    c, r = plan.commands, plan.roles
    assert c[0] == Command.STOP and r[0] == Role.CONTROL
    assert np.all(c[1 : 1 + tie_count] == Command.STITCH) and np.all(r[1 : 1 + tie_count] == Role.TIE_IN)
    body = slice(1 + tie_count, len(plan) - 2 - tie_count)
    assert np.all(c[body] == Command.STITCH)
    assert set(np.unique(r[body]).tolist()) <= {Role.LEG, Role.EDGE}
    assert np.all(r[len(plan) - 2 - tie_count : -2] == Role.TIE_OFF)
    assert c[-2] == Command.TRIM and r[-2] == Role.CONTROL
    assert c[-1] == Command.END and r[-1] == Role.CONTROL
    assert np.all(plan.actuator[:-1] == 0) and plan.actuator[-1] == -1
    np.testing.assert_array_equal(plan.xy_mm[-1], plan.xy_mm[-2])
    np.testing.assert_array_equal(plan.xy_mm[-2], plan.xy_mm[-3])
    assert np.all(np.isfinite(plan.xy_mm))


def assert_outside_corridor(plan) -> None:
    """Every STITCH point at distance >= r_f + clearance from the centerline (shapely), less the rounding of a
    rail point to the machine grid."""
    for k, a in enumerate(plan.actuators):
        pts = plan.xy_mm[(plan.commands == Command.STITCH) & (plan.actuator == k)]
        d = shapely.distance(a.centerline.as_linestring(), shapely.points(pts))
        assert d.min() >= a.tube.corridor_radius_mm - GRID_ROUNDING_MM - 1e-9, (a.name, float(d.min()))


def rail_distance_error(plan, mask) -> float:
    """Largest |distance to centerline - w/2| over the masked points (shapely distance)."""
    a = plan.actuators[0]
    d = shapely.distance(a.centerline.as_linestring(), shapely.points(plan.xy_mm[mask]))
    return float(np.max(np.abs(d - a.params.width_mm / 2.0)))


def legs(plan):
    """(start, end) xy arrays of the LEG stitches."""
    ends = np.flatnonzero(plan.roles == Role.LEG)
    return plan.xy_mm[ends - 1], plan.xy_mm[ends]


def assert_valid_plan(plan, *, width_mm: float, interval_mm: float, angle_deg: float, passes: int) -> None:
    """Record convention, corridor invariant, and the realised values within the generators' tolerances
    (angle 0.1 deg, interval and width 1 %) and what rounding the needle points to the machine grid can add
    (each point moves by at most GRID_ROUNDING_MM: a leg end-to-end twice that, a leg of length >= w turns by
    at most 2 GRID_ROUNDING_MM sqrt(2) / w rad)."""
    assert_record_convention(plan)
    assert_outside_corridor(plan)
    r = plan.actuators[0].realised
    assert abs(r.angle_deg - angle_deg) <= 0.1 + math.degrees(2 * GRID_ROUNDING_MM * math.sqrt(2) / width_mm)
    assert abs(r.interval_mm - interval_mm) <= 0.01 * interval_mm + 2 * GRID_ROUNDING_MM
    assert abs(r.width_mm - width_mm) <= 0.01 * width_mm + 2 * GRID_ROUNDING_MM
    assert r.passes == passes
