"""Every numerical method against the 50-digit mpmath evaluation of docs/model.md section 4.

Regions: near theta = 0 (B -> 0), mid-range, near the neutral angle (dV/dtheta small),
near lock-up (the pole of P), over several designs and tubes. Each method is held
to the accuracy it documents (``ACCURACY``); the printed form's failure near the
straight state is asserted, since it is documented.
"""
import functools
import math

import mpmath as mp
import numpy as np
import pytest

import mpref
from embroact.patterns.base.errors import ParameterError
from embroact.predict.sleeve import neutral_angle_deg
from embroact.predict import model as M
from embroact.predict import curve as C
from embroact.predict.curve import ACCURACY, METHODS, ActuatorModel, lockup

# these tests study the formula itself, also past the validity limits (predict/validity.py):
# its own statuses, without COILED / KINKED / OVERSTRETCHED
curve = functools.partial(C.curve, limits=False)
pressure_at = functools.partial(C.pressure_at, limits=False)

NEUTRAL = float(neutral_angle_deg(7.0, 1.5))


def designs():
    d = {
        "zigzag-w5": mpref.Ref.zigzag(width_mm=5, g_mpa=0.8, p0_kpa=50),
        "zigzag-w9": mpref.Ref.zigzag(width_mm=9, g_mpa=3.4, p0_kpa=180),
        "zigzag-thin-tube": mpref.Ref.zigzag(width_mm=4, g_mpa=5.0, p0_kpa=10, rf=1.0, df=0.3, l0=250),
        "cross-15": mpref.Ref.cross(width_mm=7, angle_deg=15, g_mpa=2.9, p0_kpa=150),
        "cross-30": mpref.Ref.cross(width_mm=7, angle_deg=30, g_mpa=12.0, p0_kpa=160),
        "cross-45": mpref.Ref.cross(width_mm=7, angle_deg=45, g_mpa=1.3, p0_kpa=170),
        "cross-60": mpref.Ref.cross(width_mm=7, angle_deg=60, g_mpa=2.9, p0_kpa=200),
        "cross-wide-tube": mpref.Ref.cross(width_mm=11, angle_deg=20, g_mpa=1.0, p0_kpa=60, rf=2.0, df=1.2, l0=60),
        "near-neutral-below": mpref.Ref.cross(width_mm=7, angle_deg=NEUTRAL - 0.05, g_mpa=2.9, p0_kpa=150),
        "near-neutral-above": mpref.Ref.cross(width_mm=7, angle_deg=NEUTRAL + 0.05, g_mpa=2.9, p0_kpa=150),
    }
    return d


DESIGNS = designs()


def geometry(ref):
    return M.Geometry.from_values(beta0_rad=float(ref.beta0), l0_mm=float(ref.l0), r0_mm=float(ref.r0),
                                  c_mm2=float(ref.c), g_mpa=float(ref.g), p0_mpa=float(ref.p0))


def model(ref):
    c = float(ref.c)
    return ActuatorModel(ref.pattern, length_mm=float(ref.l0), r0_mm=float(ref.r0),
                         beta0_deg=float(mp.degrees(ref.beta0)), outer_radius_mm=math.sqrt(c + 1.0),
                         inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=float(ref.g), p0_kpa=float(ref.p0 * 1000))


def lock_theta(ref):
    return float(M.lock_theta(geometry(ref))[0, 0])


def thetas(ref):
    """Angles [rad] along the branch: near 0, mid-range, near lock-up (cross)."""
    lock = lock_theta(ref)
    sign = math.copysign(1.0, lock)
    span = min(abs(lock), 1.5)
    near0 = [1e-12, 1e-8, 1e-4]
    mid = [0.2 * span, 0.6 * span]
    near_lock = [abs(lock) * (1 - 1e-3), abs(lock) * (1 - 1e-6)] if math.isfinite(lock) else [3.0, 20.0]
    return sign * np.array(near0 + mid + near_lock)


@pytest.fixture(scope="module")
def reference_pressures():
    """P(theta) [MPa] at 50 digits and its condition number with respect to l.

    The model's generalised coordinate is l; a float l carries a relative rounding
    error eps, which no formula can undo. cond = |l dP/dl / P| = |l P'(theta) / (l'(theta) P)|
    is large only near the pole of P at lock-up (and more so near the neutral angle,
    where lock-up sits at a tiny theta).
    """
    out = {}
    with mp.workdps(60):
        for k, r in DESIGNS.items():
            th = thetas(r)
            p = np.array([float(r.pressure(t)) for t in th])
            cond = np.array([abs(float(r.l_r(t)[0] * mp.diff(r.pressure, t) / mp.diff(lambda x: r.l_r(x)[0], t)))
                             for t in th]) / p
            out[k] = (p, cond)
    return out


def allowed(energy, deriv, cond):
    """Documented accuracy plus what rounding l costs (8 eps per unit of condition number)."""
    return ACCURACY[(energy, deriv)] + 8 * np.finfo(float).eps * cond


COMBOS = [(e, d) for e, d in ACCURACY]


@pytest.mark.parametrize("energy, deriv", COMBOS, ids=lambda x: x)
@pytest.mark.parametrize("name", DESIGNS)
def test_pressure_meets_documented_accuracy(name, energy, deriv, reference_pressures):
    ref = DESIGNS[name]
    th = thetas(ref)[None, :]
    p = M.pressure_mpa(th, geometry(ref), form=energy, derivative=deriv)[0]
    expected, cond = reference_pressures[name]
    rel = np.abs(p / expected - 1.0)
    assert np.all(rel <= allowed(energy, deriv, cond)), rel


@pytest.mark.parametrize("deriv", ["analytic", "complex", "central"])
@pytest.mark.parametrize("name", ["zigzag-w5", "cross-15", "cross-45"])
def test_printed_form_loses_digits_near_straight_state(name, deriv, reference_pressures):
    """Documented failure: the printed T cancels catastrophically as B -> 0."""
    ref = DESIGNS[name]
    th = thetas(ref)
    p = M.pressure_mpa(th[None, :], geometry(ref), form="printed", derivative=deriv)[0]
    expected = reference_pressures[name][0]
    rel = np.abs(p / expected - 1.0)
    assert rel[1] > 1.0  # |theta| = 1e-8 rad: not a single correct digit
    assert rel[2] > 1e-3  # |theta| = 1e-4 rad: still wrong in the first few digits
    stable = M.pressure_mpa(th[None, :], geometry(ref), form="stable", derivative=deriv)[0]
    assert np.all(np.abs(stable / expected - 1.0)[:3] < 1e-7)  # same angles, stable form fine


def test_printed_form_is_usable_away_from_straight_state():
    ref = DESIGNS["cross-45"]
    th = np.array([[-0.5, -1.0, -2.0]])
    p = M.pressure_mpa(th, geometry(ref), form="printed", derivative="analytic")[0]
    with mp.workdps(60):
        expected = np.array([float(ref.pressure(t)) for t in th[0]])
    assert np.all(np.abs(p / expected - 1) < 1e-6)


def test_energy_forms_agree_with_printed_energy_at_50_digits():
    for ref in DESIGNS.values():
        geo = geometry(ref)
        for t in thetas(ref)[:6]:
            l, r = ref.l_r(t)
            with mp.workdps(60):
                e_ref = float(ref.energy(l, r)) if t != 0 else 0.0
            for form in ("stable", "reference"):
                e = float(M.energy(np.array([[float(l)]]), np.array([[float(r)]]), geo, form)[0, 0])
                # E ~ theta^2 near 0: compare on the scale of G l0 c as well as relatively
                assert abs(e - e_ref) <= 1e-13 * abs(e_ref) + 1e-14 * float(ref.g * ref.l0 * ref.c), (form, t)


# -- theta(P) ---------------------------------------------------------------------------------
def pressures_kpa(ref):
    """Pressures [kPa] whose angles span the branch: just above P0, mid, near lock-up."""
    p0 = float(ref.p0 * 1000)
    lock = lock_theta(ref)
    far = lock * (1 - 1e-4) if math.isfinite(lock) else 5.0
    with mp.workdps(30):
        p_far = float(ref.pressure(far) * 1000)
    return np.array([p0 * (1 + 1e-9), p0 + 1.0, p0 + 50.0, p_far])


@pytest.fixture(scope="module")
def reference_angles():
    """50-digit roots of P(theta) = P: findroot seeded by the stable analytic answer."""
    out = {}
    for name, ref in DESIGNS.items():
        p = pressures_kpa(ref)
        seed = np.radians(curve(model(ref), p, method="stable-analytic-trace").theta_deg)
        with mp.workdps(60):
            out[name] = (p, np.array([float(mp.degrees(ref.theta(mp.mpf(pk) / 1000, s))) for pk, s in zip(p, seed)]))
    return out


FAST_METHODS = [m for m in METHODS if m != "auto" and not m.startswith("printed") and not m.startswith("reference")]
REFERENCE_METHODS = ["reference-complex-trace", "reference-central-trace", "reference-complex-root"]


@pytest.mark.parametrize("method", FAST_METHODS + ["auto"])
@pytest.mark.parametrize("name", DESIGNS)
def test_theta_of_pressure_against_reference(name, method, reference_angles):
    ref = DESIGNS[name]
    p, expected = reference_angles[name]
    c = curve(model(ref), p, method=method)
    assert np.all(c.status == 1)
    if "central" in method:
        # central differences resolve P to ~3e-7 relative (ACCURACY): P0 (1 + 1e-9) is below that
        c, p, expected = c.theta_deg[1:], p[1:], expected[1:]
        np.testing.assert_allclose(c, expected, rtol=0, atol=1e-5)
        return
    np.testing.assert_allclose(c.theta_deg, expected, rtol=0, atol=1e-6)
    if "central" not in method:  # relative too, except just above P0 where P - P0 itself has ~1e-7 round-off
        np.testing.assert_allclose(c.theta_deg[1:], expected[1:], rtol=1e-9)


@pytest.mark.parametrize("method", REFERENCE_METHODS)
@pytest.mark.parametrize("name", ["zigzag-w5", "cross-45", "near-neutral-below"])
def test_reference_energy_methods_theta(name, method, reference_angles):
    ref = DESIGNS[name]
    p, expected = reference_angles[name]
    c = curve(model(ref), p, method=method)
    assert c.method == method
    np.testing.assert_allclose(c.theta_deg, expected, rtol=0, atol=1e-5)


@pytest.mark.parametrize("name", DESIGNS)
def test_round_trip_pressure_of_theta_of_pressure(name):
    ref = DESIGNS[name]
    m = model(ref)
    p = np.linspace(m.p0_kpa * 1.001, min(m.p0_kpa + 300, 0.999 * lockup(m)[1]), 25)
    c = curve(m, p)
    back = pressure_at(m, c.theta_deg)
    assert np.all(back.status == 1)
    np.testing.assert_allclose(back.pressure_kpa, p, rtol=1e-11)
    # states agree both ways
    for k in ("length_mm", "radius_mm", "beta_deg", "inner_radius_mm"):
        np.testing.assert_allclose(getattr(back, k), getattr(c, k), rtol=1e-12)


def test_auto_reports_its_choice_and_rejects_impossible_tolerance():
    m = model(DESIGNS["cross-45"])
    assert curve(m, [200.0]).method == "stable-analytic-trace"
    assert curve(m, [200.0], rtol=1e-6).method == "stable-analytic-trace"
    with pytest.raises(ParameterError, match="rtol must be >= 1e-12"):
        curve(m, [200.0], rtol=1e-14)
    with pytest.raises(ParameterError, match="method must be one of auto, stable-analytic-trace"):
        curve(m, [200.0], method="newton")


def test_method_names_cover_every_combination():
    assert "auto" in METHODS
    assert {"stable-analytic-trace", "printed-central-root", "reference-central-root"} <= set(METHODS)
    assert len(METHODS) == 1 + 2 * (3 + 3 + 2)
    assert not any(m.startswith("reference-analytic") for m in METHODS)


@pytest.mark.parametrize("method", [m for m in METHODS if m.startswith("printed")])
def test_printed_methods_never_return_nan(method):
    m = model(DESIGNS["zigzag-w5"])
    c = curve(m, [0.0, 50.0, 50.000001, 60.0, 120.0], method=method)
    for k in ("theta_deg", "length_mm", "radius_mm", "beta_deg", "inner_radius_mm"):
        assert np.all(np.isfinite(getattr(c, k)))
    assert c.method == method


# -- the solvers on functions with known answers -------------------------------------------
def _rate_of(f):
    """Solver calling convention for P(theta) = f(theta) with dV/dtheta = 1."""
    def rate(theta, rows=None):
        return f(theta), np.ones_like(theta)
    return rate


def _central_slope(f):
    def slope(theta, rows=None):
        h = 1e-6
        return (f(theta + h) - f(theta - h)) / (2 * h)
    return slope


def test_trace_inverse_on_a_cubic():
    """P = theta^3 + theta: theta(P) by Cardano, to the last digits."""
    from embroact.predict import solvers

    f = lambda t: t**3 + t  # noqa: E731
    targets = np.array([[1e-9, 0.5, 2.0, 9.9]])
    theta, where, stop, p_stop = solvers.trace_inverse(_rate_of(f), np.array([[2.0]]), targets,
                                                       slope=_central_slope(f), grid_points=16, rtol=1e-14, atol=0)
    exact = 2 / np.sqrt(3) * np.sinh(np.arcsinh(1.5 * np.sqrt(3) * targets) / 3)  # real root, no cancellation
    np.testing.assert_allclose(theta, exact, rtol=1e-13)
    assert where.tolist() == [[0, 0, 0, 0]] and stop[0, 0] == 2.0 and p_stop[0, 0] == 10.0
    beyond = solvers.trace_inverse(_rate_of(f), np.array([[2.0]]), np.array([[10.5]]), slope=_central_slope(f),
                                   grid_points=16, rtol=1e-14, atol=0)
    assert beyond[1].tolist() == [[1]] and beyond[0][0, 0] == 2.0


@pytest.mark.parametrize("end", [3.0, (np.pi / 2 + 0.01) * 23 / 12], ids=["fold-after-grid-point",
                                                                         "fold-before-grid-point"])
def test_trace_inverse_finds_the_fold_and_stops_there(end):
    """P = sin(theta): the fold is at pi/2 with P = 1; higher targets are past it. With the
    second end a grid point sits just past the fold and still looks rising."""
    from embroact.predict import solvers

    targets = np.array([[0.5, 0.99999, 0.999999, 1.5]])
    theta, where, stop, p_stop = solvers.trace_inverse(_rate_of(np.sin), np.array([[end]]), targets,
                                                       slope=_central_slope(np.sin), grid_points=24, rtol=1e-13, atol=0)
    assert where.tolist() == [[0, 0, 0, 2]]
    assert stop[0, 0] == pytest.approx(np.pi / 2, abs=1e-9) and p_stop[0, 0] == pytest.approx(1.0, abs=1e-15)
    np.testing.assert_allclose(theta[0, :3], np.arcsin(targets[0, :3]), rtol=1e-10)  # the rising side
    assert theta[0, 3] == stop[0, 0]


def test_polish_falls_back_to_illinois_when_newton_cannot_finish(monkeypatch):
    """With no Newton step allowed, every entry is finished by the bracketing method."""
    from embroact.predict import solvers

    monkeypatch.setattr(solvers, "NEWTON_STEPS", 0)
    f = lambda t: np.exp(t) - 1  # noqa: E731
    targets = np.array([[0.1, 1.0, 5.0]])
    theta = solvers.trace_inverse(_rate_of(f), np.array([[2.0]]), targets, slope=_central_slope(f),
                                  grid_points=8, rtol=1e-14, atol=0)[0]
    np.testing.assert_allclose(theta, np.log1p(targets), rtol=1e-13)


def test_illinois_reports_non_convergence():
    from embroact.patterns.base.errors import SolverError
    from embroact.predict import solvers

    with pytest.raises(SolverError, match="did not converge in 3 iterations on 1 point"):
        solvers.illinois(lambda x, k: x**3 - 2.0, np.array([0.0]), np.array([2.0]), np.array([-2.0]),
                         np.array([6.0]), rtol=1e-15, atol=0.0, max_iterations=3)


def test_printed_form_failure_is_reported_not_nan():
    """At |theta| = 1e-20 deg B^2 r^2 is below A^2's last bit: the printed analytic
    derivative divides 0 by 0 (FAILED, fill P0); the printed complex step returns a
    number that is wrong by an order of magnitude (the documented cancellation)."""
    from embroact.predict.status import Status

    m = model(DESIGNS["zigzag-w5"])
    failed = pressure_at(m, [1e-20], method="printed-analytic-trace")
    assert failed.status[0] == Status.FAILED and failed.pressure_kpa[0] == m.p0_kpa and failed.theta_deg[0] == 0
    wrong = pressure_at(m, [1e-20], method="printed-complex-trace")
    assert wrong.status[0] == Status.BENDING and wrong.pressure_kpa[0] > 2 * m.p0_kpa
    right = pressure_at(m, [1e-20])
    assert right.pressure_kpa[0] == pytest.approx(m.p0_kpa, rel=1e-15)
