"""Physics of the deformation model against docs/model.md, hand derivations and mpmath (50 digits)."""
import math

import mpmath as mp
import numpy as np
import pytest

import mpref
from embroact.patterns.base.errors import ModelDomainError, ParameterError
from embroact.patterns.params import Tube
from embroact.predict.sleeve import neutral_angle_deg, thread_angle_deg
from embroact.predict import model as M
from embroact.predict.curve import ActuatorModel, curve
from embroact.predict.derived import derive_from_values
from embroact.predict.tubelaws import pressure_kpa, radius_mm, thick_wall_limit_kpa, transition_pressure_kpa

# Paper's fitted parameters, docs/model.md section 7
ZIGZAG = [(5.0, 0.8, 50.0), (7.0, 2.7, 85.0), (9.0, 3.4, 180.0)]
CROSS = [(15.0, 2.9, 150.0), (30.0, 12.0, 160.0), (45.0, 1.3, 170.0), (60.0, 2.9, 200.0)]


def geometry(ref: mpref.Ref) -> M.Geometry:
    return M.Geometry.from_values(beta0_rad=float(ref.beta0), l0_mm=float(ref.l0), r0_mm=float(ref.r0),
                                  c_mm2=float(ref.c), g_mpa=float(ref.g), p0_mpa=float(ref.p0))


def refs():
    out = [mpref.Ref.zigzag(width_mm=w, g_mpa=g, p0_kpa=p0) for w, g, p0 in ZIGZAG]
    out += [mpref.Ref.cross(width_mm=7, angle_deg=a, g_mpa=g, p0_kpa=p0) for a, g, p0 in CROSS]
    # other tubes and lengths
    out.append(mpref.Ref.cross(width_mm=11, angle_deg=20, g_mpa=1.0, p0_kpa=60, rf=2.0, df=1.2, l0=60))
    out.append(mpref.Ref.zigzag(width_mm=4, g_mpa=5.0, p0_kpa=10, rf=1.0, df=0.3, l0=250))
    return out


REFS = refs()


def lock(ref):
    s0 = mp.sin(ref.beta0)
    return float(ref.lock_theta(1 if s0 < 1 / mp.sqrt(5) else -1)) if s0 > 0 else math.inf


# -- identities stated in docs/model.md sections 2-4 ---------------------------------------
@pytest.mark.parametrize("l, r", [(100, 2.5), (37.5, 1.9), (160.25, 4.0), (100.000001, 2.58)])
def test_a2_minus_b2r2_is_l_over_l0_at_50_digits(l, r):
    with mp.workdps(60):
        l, r, l0 = mp.mpf(l), mp.mpf(r), mp.mpf(100)
        A, B = (l + l0) / (2 * l0), (l - l0) / (2 * r * l0)
        assert abs(A**2 - B**2 * r**2 - l / l0) < mp.mpf(10) ** -55


@pytest.mark.parametrize("ref", REFS, ids=lambda r: f"{r.pattern}-{float(mp.degrees(r.beta0)):.1f}")
def test_constraint_matches_reference_and_l_is_l0_plus_2r_theta(ref):
    geo = geometry(ref)
    th = np.array([[-0.3, -1e-9, 0.0, 1e-9, 0.2, 0.7]])
    l, r, sinb, cosb = M.constraint(th, geo)
    for k, t in enumerate(th[0]):
        lr = ref.l_r(t)
        assert l[0, k] == pytest.approx(float(lr[0]), rel=1e-14)
        assert r[0, k] == pytest.approx(float(lr[1]), rel=1e-14)
    np.testing.assert_allclose(l, geo.l0 + 2.0 * r * th, rtol=1e-14)
    np.testing.assert_allclose(sinb, l / geo.l0 * geo.s0, rtol=1e-14, atol=0)


@pytest.mark.parametrize("ref", REFS, ids=lambda r: f"{r.pattern}-{float(mp.degrees(r.beta0)):.1f}")
def test_constraint_rates_match_mpmath_derivatives(ref):
    geo = geometry(ref)
    th = np.array([[0.0, 0.05, -0.05, 0.4]])
    l, r, sinb, cosb = M.constraint(th, geo)
    l_t, r_t = M.constraint_rates(th, l, r, sinb, cosb, geo)
    for k, t in enumerate(th[0]):
        assert l_t[0, k] == pytest.approx(float(mp.diff(lambda x: ref.l_r(x)[0], t)), rel=1e-12)
        assert r_t[0, k] == pytest.approx(float(mp.diff(lambda x: ref.l_r(x)[1], t)), rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("ref", REFS, ids=lambda r: f"{r.pattern}-{float(mp.degrees(r.beta0)):.1f}")
def test_energy_is_stationary_at_straight_state(ref):
    """dE_s/dl = 0 at theta = 0 (so P(0) = P0): mpmath and the analytic rate agree."""
    with mp.workdps(60):
        assert abs(mp.diff(ref.energy_theta, 0)) < mp.mpf(10) ** -40
    de, _ = M.energy_rate(np.zeros((1, 1)), geometry(ref))
    assert abs(de[0, 0]) < 1e-13 * float(ref.g * ref.l0 * ref.c)  # E_s(0) = 0; scale of dE/dtheta


@pytest.mark.parametrize("ref", REFS, ids=lambda r: f"{r.pattern}-{float(mp.degrees(r.beta0)):.1f}")
def test_volume_rate_at_straight_state(ref):
    """dV/dl = (pi r0^2/2)(1 - 4 tan^2 beta0) at theta = 0 (zigzag: pi r0^2/2)."""
    geo = geometry(ref)
    z = np.zeros((1, 1))
    l, r, sinb, cosb = M.constraint(z, geo)
    l_t, r_t = M.constraint_rates(z, l, r, sinb, cosb, geo)
    v_l, v_r = M.volume_gradient(l, r, geo)
    dv_dl = (v_l * l_t + v_r * r_t) / l_t
    with mp.workdps(60):
        expected = mp.pi * ref.r0**2 / 2 * (1 - 4 * mp.tan(ref.beta0) ** 2)
        mp_rate = mp.diff(lambda t: ref.volume(*ref.l_r(t)), 0) / mp.diff(lambda t: ref.l_r(t)[0], 0)
        assert abs(mp_rate - expected) < mp.mpf(10) ** -40
    assert dv_dl[0, 0] == pytest.approx(float(expected), rel=1e-13, abs=1e-13)


@pytest.mark.parametrize("ref", [r for r in REFS if r.pattern == "cross"],
                         ids=lambda r: f"{float(mp.degrees(r.beta0)):.1f}")
def test_lock_angle_closed_form_matches_root_of_dv(ref):
    theta_lock = float(M.lock_theta(geometry(ref))[0, 0])
    assert theta_lock == pytest.approx(lock(ref), rel=1e-12)
    # bending direction = sign of dV/dtheta at 0 = side of the lock
    assert math.copysign(1, theta_lock) == math.copysign(1, float(ref.dvolume(0)))


def test_zigzag_never_locks():
    assert np.isinf(M.lock_theta(geometry(REFS[0]))).all()


def test_neutral_angle_tan_half():
    """tan(beta0) = 1/2 at the neutral angle: dV/dl = 0 at theta = 0 and the lock is at 0."""
    w, rf = 7.0, 1.5
    alpha = float(neutral_angle_deg(w, rf))
    assert alpha == pytest.approx(33.37, abs=0.005)
    beta0 = math.radians(float(thread_angle_deg(w, alpha, rf)))
    assert math.tan(beta0) == pytest.approx(0.5, rel=1e-14)
    with mp.workdps(60):
        ref = mpref.Ref("cross", l0=100, r0=mpref.sleeve_radius(w, rf), beta0=mp.atan(mp.mpf(1) / 2), rf=rf,
                        df=1.0, g=1.0, p0=0.1)
        assert abs(ref.dvolume(0)) < mp.mpf(10) ** -40
    geo = geometry(ref)
    assert abs(M.lock_theta(geo)[0, 0]) < 1e-14
    # either side of the neutral angle the bending direction flips
    for da, sign in ((-0.5, 1), (0.5, -1)):
        m = model_for("cross", 7.0, alpha + da, 2.0, 150.0)
        assert np.sign(curve(m, [400.0]).theta_deg[0]) == sign


# -- the paper's facts (docs/model.md section 7) ---------------------------------------------
def model_for(pattern, w, angle, g, p0, interval=1.0, **kw):
    d = derive_from_values(pattern, width_mm=w, interval_mm=interval, angle_deg=angle, length_mm=100.0,
                           tube=Tube())
    return ActuatorModel.from_derived(d, g_mpa=g, p0_kpa=p0, **kw)


@pytest.mark.parametrize("w, paper", [(5.0, 25.0), (7.0, 85.0), (9.0, 180.0)])
def test_zigzag_p0_within_5_percent_of_paper(w, paper):
    d = derive_from_values("zigzag", width_mm=w, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
    p0 = float(transition_pressure_kpa(d.r0_mm, Tube(), "paper"))
    assert abs(p0 / paper - 1) < 0.05
    mp_p0 = mpref.paper_law(mpref.sleeve_radius(w, 1.5), 1.5, 0.13) * 1000
    assert p0 == pytest.approx(float(mp_p0), rel=1e-13)
    assert ActuatorModel.from_derived(d, g_mpa=1.0).p0_kpa == p0


@pytest.mark.parametrize("alpha, g, p0", CROSS)
def test_cross_bending_direction_with_paper_parameters(alpha, g, p0):
    m = model_for("cross", 7.0, alpha, g, p0, interval=1.4)
    c = curve(m, np.arange(0.0, 301.0, 10.0))
    bent = c.theta_deg[c.pressure_kpa > p0]
    assert bent.size and np.all(c.status[c.pressure_kpa > p0] == 1)
    expected = 1 if alpha <= 30 else -1
    assert np.all(np.sign(bent) == expected)
    assert np.all(np.diff(np.abs(bent)) > 0)  # monotone loading curve


@pytest.mark.parametrize("w, g, p0", ZIGZAG)
def test_zigzag_bends_positive(w, g, p0):
    c = curve(model_for("zigzag", w, 0.0, g, p0), [p0 + 1.0, p0 + 100.0])
    assert np.all(c.theta_deg > 0)


# -- tube laws --------------------------------------------------------------------------------
@pytest.mark.parametrize("tube", [Tube(), Tube(outer_radius_mm=2.0, inner_radius_mm=0.5, g_e_mpa=0.4),
                                  Tube(outer_radius_mm=1.0, inner_radius_mm=0.9, g_e_mpa=1.1)])
@pytest.mark.parametrize("stretch", [1.0 + 1e-6, 1.2, 1.7, 3.0, 10.0])
def test_thick_wall_law_against_integrated_equilibrium(tube, stretch):
    r = tube.outer_radius_mm * stretch
    quad = mpref.thick_wall_quad(r, tube.outer_radius_mm, tube.inner_radius_mm, tube.g_e_mpa) * 1000
    assert float(pressure_kpa(r, tube, "thick-wall")) == pytest.approx(float(quad), rel=1e-12)
    assert float(radius_mm(float(quad), tube, "thick-wall")) == pytest.approx(r, rel=1e-10)


def test_thick_wall_limit_and_errors():
    t = Tube()
    limit = float(thick_wall_limit_kpa(t))
    assert limit == pytest.approx(130.0 * math.log(1.5), rel=1e-14)
    assert 0.999 * limit < float(pressure_kpa(1e3, t, "thick-wall")) < limit
    with pytest.raises(ModelDomainError, match="limit"):
        radius_mm(limit, t, "thick-wall")
    with pytest.raises(ModelDomainError, match="inner_radius_mm"):
        pressure_kpa(2.0, Tube(inner_radius_mm=0.0), "thick-wall")
    with pytest.raises(ParameterError, match="tube_law must be one of paper, thick-wall"):
        pressure_kpa(2.0, t, "thin")


def test_paper_law_round_trip_and_mpmath():
    t = Tube()
    for r in (1.5, 1.9, 2.58, 4.0):
        p = float(pressure_kpa(r, t, "paper"))
        assert p == pytest.approx(float(mpref.paper_law(r, 1.5, 0.13) * 1000), rel=1e-13, abs=1e-13)
        assert float(radius_mm(p, t, "paper")) == pytest.approx(r, rel=1e-12)


def test_thick_wall_p0_from_geometry():
    m = model_for("zigzag", 7.0, 0.0, 2.7, None, tube_law="thick-wall")
    r0 = mpref.sleeve_radius(7.0, 1.5)
    assert m.p0_kpa == pytest.approx(float(mpref.thick_wall_law(r0, 1.5, 1.0, 0.13) * 1000), rel=1e-12)
    c = curve(m, [0.0, m.p0_kpa / 2, m.p0_kpa])
    assert c.status.tolist() == [0, 0, 0]
    # below P0 the tube follows the thick-wall law; at P0 it fills the sleeve
    assert c.radius_mm[1] == pytest.approx(float(radius_mm(m.p0_kpa / 2, Tube(), "thick-wall")), rel=1e-12)
    assert c.radius_mm[2] == pytest.approx(float(r0), rel=1e-10)
    assert c.radius_mm[0] == pytest.approx(1.5, rel=1e-15)


@pytest.mark.parametrize("beta0_deg", [10.0, 60.0, 89.0, 89.99])
def test_radius_stays_accurate_as_beta_approaches_90(beta0_deg):
    """cos(beta) from the rationalised form: no cancellation as sin(beta) -> 1."""
    with mp.workdps(60):
        ref = mpref.Ref("cross", l0=100, r0=2.5, beta0=mp.radians(beta0_deg), rf=1.5, df=1.0, g=1.0, p0=0.1)
    geo = geometry(ref)
    th = np.array([[-100.0, -3.0, 3.0, 100.0, 1e4]])
    l, r, sinb, cosb = M.constraint(th, geo)
    for k, t in enumerate(th[0]):
        with mp.workdps(60):
            lr = ref.l_r(t)
        assert l[0, k] == pytest.approx(float(lr[0]), rel=1e-13)
        assert r[0, k] == pytest.approx(float(lr[1]), rel=1e-12)  # 1 - sin^2 would lose all digits at 89 deg


def test_unknown_energy_form_is_refused_not_computed():
    from embroact.patterns.base.errors import ParameterError

    # the name is checked before any arithmetic, so no geometry is needed to see the refusal
    with pytest.raises(ParameterError, match="form must be one of 'stable', 'printed', 'reference', got 'bogus'"):
        M.energy(np.array([100.0]), np.array([2.58]), None, form="bogus")
