"""The bent shape as a chain of arcs (predict/shape.py) against hand-derived arcs, and both views against it."""
import math

import numpy as np
import pytest

from embroact.export.pictures.mesh import BentPath, PlanarPath, actuator_mesh
from embroact.export.pictures.sideview import SidePanel, shape_line_mm
from embroact.patterns.base.errors import ParameterError
from embroact.predict.shape import BentShape


def hand_tip(lengths, thetas_deg):
    """Tip (x, y) and heading of a chain of arcs, by complex numbers: each arc ends at L (e^{i t} - 1) / (i t)."""
    z, phi = 0j, 0.0
    for length, t_deg in zip(lengths, thetas_deg):
        t = math.radians(t_deg)
        chord = length * (np.exp(1j * t) - 1.0) / (1j * t) if t else complex(length)
        z += np.exp(1j * phi) * chord
        phi += t
    return z.real, z.imag, math.degrees(phi)


@pytest.mark.parametrize("theta", [1e-9, 5.0, 90.0, 180.0, 300.0, -45.0, -170.0])
def test_uniform_bend_ends_on_the_hand_arc(theta):
    t = math.radians(theta)
    tip = BentShape.chain([100.0], [theta]).profile_mm([100.0])[0]
    # 1 - cos t written as 2 sin^2(t/2), which keeps its digits for tiny t
    assert tip == pytest.approx([100.0 * math.sin(t) / t, 200.0 * math.sin(t / 2.0) ** 2 / t], abs=1e-10)


def test_points_along_an_arc_lie_on_its_circle():
    shape = BentShape.chain([80.0], [135.0])
    r = 80.0 / math.radians(135.0)
    xy = shape.profile_mm(np.linspace(0.0, 80.0, 33))
    assert np.hypot(xy[:, 0], xy[:, 1] - r) == pytest.approx(np.full(33, r), abs=1e-10)


@pytest.mark.parametrize("seed", range(5))
def test_random_chains_match_the_hand_sum(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 7))
    lengths, thetas = rng.uniform(10.0, 40.0, n), rng.uniform(-120.0, 120.0, n)
    shape = BentShape.chain(lengths, thetas)
    x, y, heading = hand_tip(lengths, thetas)
    assert shape.profile_mm([lengths.sum()])[0] == pytest.approx([x, y], abs=1e-9)
    assert shape.turning_deg == pytest.approx(heading, abs=1e-9)
    wrapped = (heading + 180.0) % 360.0 - 180.0
    assert shape.tip_angle_deg == pytest.approx(wrapped, abs=1e-9)
    # the frames stay orthonormal and the line has unit speed
    _, r = shape.frames(np.linspace(0.0, lengths.sum(), 50))
    assert np.einsum("nji,njk->nik", r, r) == pytest.approx(np.broadcast_to(np.eye(3), (50, 3, 3)), abs=1e-12)


def test_curved_path_unbent_stays_in_the_plan_on_its_circle():
    radius, length = 40.0, 60.0
    shape = BentShape.chain([length], [0.0], path_lengths_mm=[length], path_kappa_per_mm=[1.0 / radius])
    tip = shape.tip_mm
    a = length / radius
    assert tip == pytest.approx([radius * math.sin(a), radius * (1.0 - math.cos(a)), 0.0], abs=1e-10)


def test_curved_path_bends_about_the_in_fabric_normal():
    # a bent curved path: at every point the tangent turns by -kappa_b B + kappa_p N; the tangent stays unit
    # and its out-of-plane component after a pure bend of theta on an arc path is -sin(theta)
    shape = BentShape.chain([30.0, 30.0], [40.0, 50.0], path_lengths_mm=[60.0], path_kappa_per_mm=[1.0 / 50.0])
    s = np.linspace(0.0, 60.0, 61)
    s = s[np.abs(s - 30.0) > 0.1]  # the tangent's derivative jumps where the segments meet
    _, r = shape.frames(s)
    # B . T = 0 and N stays in the plane spanned with T (no twist): N . e_z relation checked through d/ds
    assert np.abs(np.einsum("ni,ni->n", r[:, :, 0], r[:, :, 2])).max() < 1e-12
    eps = 1e-6
    _, ra = shape.frames(s[1:-1] - eps)
    _, rb = shape.frames(s[1:-1] + eps)
    dt = (rb[:, :, 0] - ra[:, :, 0]) / (2 * eps)
    kb = np.where(s[1:-1] < 30.0, math.radians(40.0) / 30.0, math.radians(50.0) / 30.0)
    expected = (1.0 / 50.0) * r[1:-1, :, 1] - kb[:, None] * r[1:-1, :, 2]
    assert dt == pytest.approx(expected, abs=1e-6)


def test_bad_input_is_named():
    with pytest.raises(ParameterError, match="theta_deg must have one value per segment length"):
        BentShape.chain([10.0, 20.0], [5.0])
    with pytest.raises(ParameterError, match=r"segment_lengths_mm\[1\]"):
        BentShape.chain([10.0, -1.0], [5.0, 5.0])
    with pytest.raises(ParameterError, match="path_lengths_mm must add up"):
        BentShape.chain([10.0], [5.0], path_lengths_mm=[9.0], path_kappa_per_mm=[0.0])


def test_side_view_draws_the_chain():
    lengths, thetas = [30.0, 40.0, 30.0], [60.0, -30.0, 90.0]
    x, y, _ = hand_tip(lengths, thetas)
    line = shape_line_mm(BentShape.chain(lengths, thetas), 0.0, tolerance_mm=1e-3)
    # side view: x across (= -y of the profile), z up (= -x of the profile)
    assert line[-1] == pytest.approx([-y, -x], abs=1e-9)
    panel = SidePanel("seg", 100.0, 2.58, [0.0, 200.0], [0.0, sum(thetas)], segment_lengths_mm=lengths,
                      segment_theta_deg=[[0.0, 0.0, 0.0], thetas])
    assert panel.shape(1).profile_mm([100.0])[0] == pytest.approx([x, y], abs=1e-9)
    with pytest.raises(ParameterError, match="segment_theta_deg"):
        SidePanel("bad", 100.0, 2.58, [0.0], [0.0], segment_lengths_mm=lengths, segment_theta_deg=[[0.0, 0.0, 0.0]] * 2)


def test_mesh_follows_the_chain():
    lengths, thetas = [50.0, 50.0], [120.0, -60.0]
    x, y, _ = hand_tip(lengths, thetas)
    bent = BentPath.from_segments(PlanarPath.straight(100.0), lengths, thetas)
    pos, _ = bent.frames([100.0])
    assert pos[0] == pytest.approx([x, 0.0, -y], abs=1e-9)
    mesh = actuator_mesh(PlanarPath.straight(100.0), 60.0, width_mm=7.0, r0_mm=2.58, segment_lengths_mm=lengths,
                         segment_theta_deg=thetas)
    assert mesh.max_deviation_mm <= mesh.tolerance_mm
    fabric = next(b for b in mesh.bodies if b.name == "fabric")
    # the fabric's last ring is centred (fabric line at v = -t/2) near the chain's tip
    last = fabric.vertices[-fabric.ring_size:].mean(axis=0)
    assert last[[0, 2]] == pytest.approx([x, -y], abs=0.5)
    again = mesh.remeshed(0.2)
    assert again.bent.segment_theta_deg == tuple(thetas)


@pytest.mark.parametrize("seed", range(3))
def test_planar_fast_path_is_the_same_line(seed):
    from embroact.predict.shape import planar_chain_mm

    rng = np.random.default_rng(seed)
    lengths, thetas = rng.uniform(5.0, 40.0, 5), rng.uniform(-200.0, 200.0, 5)
    s = np.linspace(0.0, lengths.sum(), 77)
    assert planar_chain_mm(lengths, thetas, s) == pytest.approx(BentShape.chain(lengths, thetas).profile_mm(s),
                                                                 abs=1e-9)
