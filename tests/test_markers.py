"""Marker bend angles (docs/model.md section 11) against hand-computed geometry, and the model's reading of a layout.

Markers on a circular arc: the chord from marker k to k+1 points along the arc's
tangent at the chord's mid-angle, so consecutive chords differ by the angular step
and the five joint angles of seven markers sum to 5/6 of the arc angle (the chord sum).
"""
import math

import numpy as np
import pytest

from markerdata import paper_frame, strip_points

from embroact.patterns.base.errors import ParameterError
from embroact.predict.markers import (PAPER_LAYOUT, MarkerLayout, bend_angle_deg, marker_angles, marker_positions_mm,
                                      reading_deg)


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


# ----------------------------------------------------------------------------- layout and model reading
@pytest.mark.parametrize("theta", [-300.0, -45.0, 0.0, 30.0, 155.0, 300.0])
def test_reading_on_the_bent_part_is_n_minus_2_spacings_of_curvature(theta):
    assert reading_deg(theta, 100.0) == pytest.approx(theta * 50.0 / 100.0, abs=1e-9)
    lay = MarkerLayout(markers_per_side=5, spacing_mm=8.0, offset_mm=30.0)
    assert reading_deg(theta, 80.0, lay) == pytest.approx(theta * 3 * 8.0 / 80.0, abs=1e-9)


def test_reading_with_markers_past_the_bent_length():
    # markers at 90, 100, 110 mm on a 100 mm bend of 90 deg: chord 1 on the arc points at kappa * 95 mm,
    # chord 2 lies on the straight continuation (90 deg): 90 - 85.5 = 4.5 deg
    lay = MarkerLayout(markers_per_side=3, spacing_mm=10.0, offset_mm=90.0, rows=1)
    assert reading_deg(90.0, 100.0, lay) == pytest.approx(4.5, abs=1e-12)
    # all markers on the straight part read nothing
    assert reading_deg(90.0, 100.0, MarkerLayout(offset_mm=100.0)) == pytest.approx(0.0, abs=1e-12)
    # a chord straddling the end of the bend (markers at 95, 105, 115): from the hand-built points
    p = strip_points(90.0, [95.0, 105.0, 115.0])
    d1, d2 = p[1] - p[0], p[2] - p[1]
    want = math.degrees(math.atan2(d1[0] * d2[1] - d1[1] * d2[0], d1 @ d2))
    got = reading_deg(90.0, 100.0, MarkerLayout(markers_per_side=3, offset_mm=95.0, rows=1))
    assert got == pytest.approx(want, abs=1e-12) and 0.0 < got < 2.25  # less than the midpoint integral
    np.testing.assert_allclose(marker_positions_mm(90.0, 100.0, lay), strip_points(90.0, [90.0, 100.0, 110.0]),
                               atol=1e-12)


def test_reading_is_vectorised_and_layout_is_validated():
    r = reading_deg(np.array([[0.0, 100.0], [-100.0, 200.0]]), 100.0)
    np.testing.assert_allclose(r, [[0.0, 50.0], [-50.0, 100.0]], atol=1e-9)
    assert PAPER_LAYOUT.as_dict() == {"markers_per_side": 7, "spacing_mm": 10.0, "offset_mm": 0.0, "rows": 2,
                                      "side": "fabric"}
    for kwargs, match in [({"markers_per_side": 2}, "markers_per_side must be an integer >= 3"),
                          ({"spacing_mm": 0.0}, r"spacing_mm must be in \(0"),
                          ({"offset_mm": -1.0}, r"offset_mm must be in \[0"),
                          ({"side": "top"}, "side must be one of 'fabric', 'thread', got 'top'")]:
        with pytest.raises(ParameterError, match=match):
            MarkerLayout(**kwargs)


# ----------------------------------------------------------------------------- sign and noise
def test_300_degree_bend_reads_with_the_right_sign():
    R = _rotation(11)
    normal = R @ [0.0, 1.0, 0.0]
    for theta in (300.0, -300.0):
        frame = paper_frame(theta, rot=R)
        assert bend_angle_deg(frame, normal=normal) == pytest.approx(theta / 2, abs=1e-9)
    # markers 40 mm from the clamp: the first chord has turned 135 deg; a rest frame fixes the tangent
    frames = np.stack([paper_frame(0.0, 40.0, R), paper_frame(300.0, 40.0, R), paper_frame(-300.0, 40.0, R)])
    got = bend_angle_deg(frames, normal=normal)
    np.testing.assert_allclose(got, [0.0, 150.0, -150.0], atol=1e-9)
    # or the tangent is given
    assert bend_angle_deg(frames[1], normal=normal, tangent=R @ [1.0, 0.0, 0.0]) == pytest.approx(150.0, abs=1e-9)


def test_signed_angles_are_unbiased_under_coordinate_noise_and_report_their_floor():
    rng = np.random.default_rng(7)
    sigma, n = 0.2, 4000
    for theta in (0.0, 150.0):
        clean = paper_frame(theta)
        frames = clean + rng.normal(0.0, sigma, size=(n,) + clean.shape)
        r = marker_angles(frames, normal=(0.0, 1.0, 0.0), tangent=(1.0, 0.0, 0.0))
        sd = float(np.std(r.theta_deg))
        assert abs(float(np.mean(r.theta_deg)) - theta / 2) < 4 * sd / math.sqrt(n)  # no bias
        assert r.noise_mm == pytest.approx(sigma, rel=0.03)
        assert float(np.mean(r.theta_se_deg)) == pytest.approx(sd, rel=0.1)  # the reported floor is the scatter
        # hand value: sqrt(2) sigma / 10 mm per chord, two chords per row, two rows
        assert sd == pytest.approx(math.degrees(math.sqrt(2 * 2 * 2 * sigma**2 / 100.0) / 2), rel=0.1)


def test_unsigned_series_has_no_noise_bias_at_zero_bend():
    """The old unsigned mode read +18 deg at zero bend for 0.2 mm noise; the series axis keeps signs."""
    rng = np.random.default_rng(3)
    frames = np.stack([paper_frame(0.0)] * 500 + [paper_frame(150.0)])
    frames = frames + rng.normal(0.0, 0.2, size=frames.shape)
    r = marker_angles(frames)
    assert not r.signed and float(r.theta_deg[-1]) == pytest.approx(75.0, abs=3.0)
    straight = np.asarray(r.theta_deg[:-1])
    assert abs(float(np.mean(straight))) < 4 * float(np.std(straight)) / math.sqrt(straight.size)
