"""Marker bend angles (MODEL.md section 8) against hand-computed geometry.

Markers on a circular arc: the chord from marker k to k+1 points along the arc's
tangent at the chord's mid-angle, so consecutive chords differ by the angular step
and the five joint angles of seven markers sum to 5/6 of the arc angle (the chord sum).
"""
import numpy as np
import pytest

from embroact.patterns.base.errors import ParameterError
from embroact.predict.markers import bend_angle_deg, marker_angles


def _arc(total_deg, radius_mm=40.0, n=7):
    """n markers on a circle: base at the origin, tangent +x, bending toward +y (straight if 0)."""
    if total_deg == 0.0:
        return np.stack([np.arange(n) * 10.0, np.zeros(n), np.zeros(n)], axis=1)
    t = np.radians(np.linspace(0.0, total_deg, n))
    return np.stack([radius_mm * np.sin(t), radius_mm * (1 - np.cos(t)), np.zeros(n)], axis=1)


def _rotation(seed):
    q, _ = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    return q * np.sign(np.linalg.det(q))  # proper rotation


@pytest.mark.parametrize("total", [6.0, 60.0, 120.0, 180.0, 300.0])
def test_circular_arc_gives_chord_sum(total):
    side = _arc(total)
    both = np.concatenate([side, side + [0.0, 0.0, 12.0]])
    r = marker_angles(both)
    assert float(r.theta_deg) == pytest.approx(total * 5 / 6, abs=1e-9)
    np.testing.assert_allclose(r.joint_deg, total / 6, atol=1e-9)
    np.testing.assert_allclose(r.side_deg, total * 5 / 6, atol=1e-9)


def test_invariant_under_rotation_translation_and_scale():
    side = _arc(90.0, radius_mm=25.0)
    both = np.concatenate([side, side + [0.0, 0.0, 10.0]])
    R = _rotation(3)
    moved = 2.5 * both @ R.T + [100.0, -40.0, 7.0]
    assert bend_angle_deg(moved) == pytest.approx(75.0, abs=1e-9)
    # signed: normal +y at rest bends positive; it moves with the body
    assert bend_angle_deg(moved, normal=R @ [0.0, 1.0, 0.0]) == pytest.approx(75.0, abs=1e-9)
    assert bend_angle_deg(moved, normal=R @ [0.0, -1.0, 0.0]) == pytest.approx(-75.0, abs=1e-9)


def test_straight_line_is_zero():
    x = np.arange(7) * 10.0
    side = np.stack([x, 2.0 * x, -x], axis=1)
    both = np.concatenate([side, side + 5.0])
    assert bend_angle_deg(both) == pytest.approx(0.0, abs=1e-6)
    assert bend_angle_deg(both, normal=(0, 0, 1)) == pytest.approx(0.0, abs=1e-6)


def test_right_angle_l():
    pts = np.array([[0, 0], [10, 0], [20, 0], [30, 0], [30, 10], [30, 20], [30, 30]], float)
    assert bend_angle_deg(pts, sides=1) == pytest.approx(90.0, abs=1e-12)
    assert bend_angle_deg(pts, sides=1, normal=(0, 1)) == pytest.approx(90.0, abs=1e-12)
    assert bend_angle_deg(pts, sides=1, normal=(0, -1)) == pytest.approx(-90.0, abs=1e-12)


def test_sign_holds_beyond_90_degrees_and_two_sides_average():
    # 7 markers, 40 deg per joint: 200 deg in total, the tip has turned past the normal
    a = _arc(240.0, radius_mm=20.0)
    b = _arc(120.0, radius_mm=40.0) + [0.0, 0.0, 10.0]
    r = marker_angles(np.concatenate([a, b]), normal=(0.0, 1.0, 0.0))
    assert r.signed
    np.testing.assert_allclose(r.side_deg, [200.0, 100.0], atol=1e-9)
    assert float(r.theta_deg) == pytest.approx(150.0, abs=1e-9)
    mirrored = np.concatenate([a, b]) * [1.0, -1.0, 1.0]
    assert bend_angle_deg(mirrored, normal=(0.0, 1.0, 0.0)) == pytest.approx(-150.0, abs=1e-9)


def test_frames_are_vectorised():
    totals = np.array([0.0, 30.0, 90.0, 150.0])
    frames = np.stack([np.concatenate([_arc(t), _arc(t) + [0, 0, 8.0]]) for t in totals])
    theta = bend_angle_deg(frames, normal=(0, 1, 0))
    assert theta.shape == (4,) and not theta.flags.writeable
    np.testing.assert_allclose(theta, totals * 5 / 6, atol=1e-9)
    r = marker_angles(frames.reshape(2, 2, 14, 3))
    assert r.theta_deg.shape == (2, 2) and r.joint_deg.shape == (2, 2, 2, 5)


def test_fold_back_joint_is_accurate():
    # a hairpin: the fourth segment comes straight back (179.999 deg joint)
    eps = np.radians(0.001)
    pts = np.array([[0, 0, 0], [10, 0, 0], [20, 0, 0], [20 - 10 * np.cos(eps), 10 * np.sin(eps), 0]])
    assert bend_angle_deg(pts, markers_per_side=4, sides=1) == pytest.approx(179.999, abs=1e-9)


@pytest.mark.parametrize(
    "markers, kwargs, match",
    [
        (np.zeros((13, 3)), {}, r"shape \(\.\.\., 14, 2 or 3\)"),
        (np.zeros((14, 4)), {}, "2 or 3"),
        (np.full((14, 3), np.nan), {}, "finite"),
        (np.zeros((14, 3)), {}, "coincide"),
        (_arc(30.0, n=14), {"normal": (0, 0, 0)}, "non-zero vector"),
        (_arc(30.0, n=14), {"markers_per_side": 2, "sides": 7}, "markers_per_side must be an integer >= 3"),
        (_arc(30.0, n=14), {"sides": 0}, "sides must be an integer >= 1"),
    ],
)
def test_bad_input(markers, kwargs, match):
    with pytest.raises(ParameterError, match=match):
        marker_angles(markers, **kwargs)
