"""measure(): realised parameters from hand-built needle points."""
import math

import numpy as np
import pytest

from embroact.patterns.centerline import Centerline
from embroact.patterns.base.errors import ParameterError, PatternError
from embroact.patterns.measure import measure
from embroact.patterns.plan import Role

from h1_checks import arc

L_, G = Role.LEG, Role.EDGE

# Two hand-built cross passes on a straight path, w = 4, d = 2, s = 2 (n = 2d/s = 2):
# pass 0 forward L0 R2 L4 R6, edge R6 -> R8, pass 1 backward R8 L6 R4 L2.
CROSS_XY = [[0, 2], [2, -2], [4, 2], [6, -2], [8, -2], [6, 2], [4, -2], [2, 2]]
CROSS_ROLES = [Role.TIE_IN, L_, L_, L_, G, L_, L_, L_]


def test_zigzag_by_hand():
    xy = [[0, 3.5], [1, -3.5], [2, 3.5], [3, -3.5], [4, 3.5]]
    r = measure(xy, [Role.TIE_IN] + [L_] * 4, Centerline.straight(5.0), "zigzag")
    assert (r.width_mm, r.interval_mm, r.length_mm, r.passes) == (7.0, 1.0, 4.0, 1)
    assert r.angle_deg == pytest.approx(math.degrees(math.atan(1 / 7)), abs=1e-12)


def test_cross_by_hand():
    r = measure(CROSS_XY, CROSS_ROLES, Centerline.straight(10.0), "cross")
    # family -1 crosses y=0 at 1, 3, 5, 7; family +1 at 3, 5: spacing 2 in both
    assert r.interval_mm == pytest.approx(2.0, abs=1e-12)
    assert r.angle_deg == pytest.approx(math.degrees(math.atan(2 / 4)), abs=1e-12)
    assert (r.width_mm, r.length_mm, r.passes) == (4.0, 8.0, 2)


def test_cross_interval_is_robust_to_one_missing_leg():
    # drop the last leg of pass 1 (R4 -> L2): one family loses a leg at the end
    r = measure(CROSS_XY[:-1], CROSS_ROLES[:-1], Centerline.straight(10.0), "cross")
    assert r.interval_mm == pytest.approx(2.0, abs=1e-12)


def test_edges_are_not_legs():
    roles = [Role.TIE_IN, L_, G, L_]
    r = measure([[0, 3.5], [1, -3.5], [1.5, -3.5], [2.5, 3.5]], roles, Centerline.straight(5.0), "zigzag")
    assert r.interval_mm == pytest.approx(1.0)  # the 0.5 mm edge is ignored


def test_zigzag_on_an_arc_by_hand():
    rad, w, s = 30.0, 7.0, 1.2
    phi = np.arange(1, 61) * s / rad  # away from the path's end, whose tangent is its first chord's
    side = np.where(np.arange(60) % 2 == 0, 1.0, -1.0)  # left rail is nearer the centre
    rr = rad - side * w / 2
    xy = np.c_[rr * np.sin(phi), rad - rr * np.cos(phi)]
    r = measure(xy, [Role.TIE_IN] + [L_] * 59, arc(rad, 180.0, n=4000), "zigzag")
    assert r.interval_mm == pytest.approx(s, rel=1e-6)
    assert r.width_mm == pytest.approx(w, rel=1e-5)
    assert r.length_mm == pytest.approx(59 * s, rel=1e-5)
    assert r.angle_deg == pytest.approx(math.degrees(math.atan(s / w)), abs=1e-3)


def test_errors():
    with pytest.raises(ParameterError, match="pattern must be one of 'zigzag', 'cross'(, '[a-z]+')*, got 'satin'"):
        measure(CROSS_XY, CROSS_ROLES, Centerline.straight(10.0), "satin")
    with pytest.raises(PatternError, match="without legs"):
        measure([[0, 1], [1, 1]], [Role.TIE_IN, Role.EDGE], Centerline.straight(10.0), "zigzag")
    with pytest.raises(PatternError, match="fewer than two parallel legs"):
        measure(CROSS_XY[:3], CROSS_ROLES[:3], Centerline.straight(10.0), "cross")
