"""The lean solve of one model's curve (predict/lean.py, predict/onecurve.py).

Against the 50-digit reference (tests/mpref.py), against the trace inverse that a
``sweep`` of several models runs, and against itself: the float path and the array path
give the same bits, and a pressure's answer depends neither on the other pressures of the
call nor on what was cached before.
"""
from __future__ import annotations

import dataclasses
import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given

import mpref
from strategies import budget, model_designs, pressures_kpa
from embroact.predict import curve as C
from embroact.predict.curve import ActuatorModel, curve, lockup, sweep
from embroact.predict.derived import derive_from_values
from embroact.predict.lean import LEVEL_POINTS, LEVELS, RISE_M, lean_table, solve_lean
from embroact.predict.model import Geometry, lock_theta, pressure_mpa
from embroact.predict.onecurve import FLOAT_PATH_MAX, one_curve_floats
from embroact.predict.status import Status
from embroact.patterns.params import Tube

FIELDS = ("pressure_kpa", "theta_deg", "status", "length_mm", "radius_mm", "beta_deg", "inner_radius_mm")


def design(pattern, w, angle=0.0, g=2.0, p0=150.0, l0=100.0):
    d = derive_from_values(pattern, width_mm=w, interval_mm=1.0, angle_deg=angle, length_mm=l0, tube=Tube())
    return ActuatorModel.from_derived(d, g_mpa=g, p0_kpa=p0)


def ref_of(m: ActuatorModel) -> mpref.Ref:
    return mpref.Ref(m.pattern, l0=m.length_mm, r0=m.r0_mm, beta0=mp.radians(mp.mpf(m.beta0_deg)),
                     rf=m.outer_radius_mm, df=m.inner_radius_mm, g=m.g_mpa, p0=mp.mpf(m.p0_kpa) / 1000)


def same_bits(a, b):
    for f in FIELDS:
        x, y = getattr(a, f), getattr(b, f)
        assert x.tobytes() == y.tobytes(), f


@pytest.mark.parametrize("m", [design("zigzag", 7.0, g=2.7, p0=85.0), design("cross", 7.0, 20.0, g=1.3, p0=170.0),
                               design("cross", 9.0, 60.0, g=2.9, p0=200.0), design("cross", 5.0, 10.0, g=0.8),
                               design("zigzag", 5.0, g=12.0, p0=0.0, l0=10.0)])
def test_angles_match_the_50_digit_reference_over_the_branch(m):
    """Angles evenly spread over the stable branch (down to 1e-4 of it): P from mpmath, theta back
    from the lean solve within rtol 1e-10 (the documented tolerance; observed ~1e-13)."""
    ref = ref_of(m)
    end, _ = lockup(m)
    cap = math.radians(min(abs(end) * 0.98, 700.0))
    theta = math.copysign(1.0, end) * np.concatenate([cap * np.geomspace(1e-4, 0.1, 12), np.linspace(0.1, 1.0, 40)
                                                       * cap])
    p = np.array([float(ref.pressure(mp.mpf(float(t))) * 1000) for t in theta])
    c = curve(m, p, limits=False)
    assert c.status.tolist() == [Status.BENDING] * p.size
    back = np.radians(c.theta_deg)
    with mp.workdps(60):  # the exact root of each float64 pressure, by one Newton step from theta
        exact = [float(mp.mpf(float(t)) + (mp.mpf(float(pk)) / 1000 - ref.pressure(mp.mpf(float(t))))
                       / mp.diff(ref.pressure, mp.mpf(float(t)))) for t, pk in zip(theta, p)]
    assert np.all(np.abs(back - exact) <= 1e-10 * np.abs(exact))


def arrays_only(m, p):
    """The curve by the array path whatever the number of pressures (curve() takes floats for a handful)."""
    return C._solve([m], p, "auto", C.DEFAULT_TOLERANCES.model_rtol, squeeze=True)


@given(m=model_designs(), p=pressures_kpa(max_size=3 * FLOAT_PATH_MAX))
@budget(0.3)
def test_float_path_and_array_path_give_the_same_bits(m, p):
    many = arrays_only(m, p)
    for k in range(0, len(p), FLOAT_PATH_MAX):  # a handful at a time: the float path where it serves them
        few = curve(m, p[k:k + FLOAT_PATH_MAX])
        for f in FIELDS:
            assert getattr(few, f).tobytes() == getattr(many, f)[k:k + FLOAT_PATH_MAX].tobytes(), f
    one = curve(m, p[-1])
    for f in FIELDS:
        assert getattr(one, f).tobytes() == getattr(many, f)[-1:].tobytes(), f


def test_the_float_path_serves_a_handful_of_bending_pressures():
    m = design("cross", 7.0, 20.0, g=1.3, p0=170.0)
    br = C._branch(m, C.DEFAULT_TOLERANCES.model_rtol)
    assert one_curve_floats(br, [0.23, 0.26]) is not None  # MPa, above P0 and settled
    assert one_curve_floats(br, [0.1, 0.26]) is None  # an inflation point: the array path's tube law
    same_bits(curve(m, [230.0, 260.0]), arrays_only(m, [230.0, 260.0]))


@given(m=model_designs(), p=pressures_kpa(max_size=20))
@budget(0.3)
def test_an_answer_depends_neither_on_the_other_pressures_nor_on_the_cache(m, p):
    warm = arrays_only(m, p)
    C._cached_branch.cache_clear()
    cold_reversed = arrays_only(m, p[::-1])
    for f in FIELDS:
        assert getattr(cold_reversed, f)[::-1].tobytes() == getattr(warm, f).tobytes(), f
    for k, pk in enumerate(p):  # each pressure alone
        alone = arrays_only(m, [pk])
        for f in FIELDS:
            assert getattr(alone, f).tobytes() == getattr(warm, f)[k:k + 1].tobytes(), f


@pytest.mark.parametrize("m, p, other", [
    # a target the lean step leaves to the trace inverse (round-off-sized), with one far past the fold
    (design("zigzag", 7.0, g=2.7, p0=85.0), 85.000000000001, 1e5),
    (ActuatorModel("cross", length_mm=87.1533556167941, r0_mm=4.697723863285179, beta0_deg=4.2135640896712205,
                   outer_radius_mm=1.270686703640462, inner_radius_mm=0.27055142212689764,
                   g_e_mpa=1.7346866114754718, g_mpa=2.778803484852792, p0_kpa=0.0), 165.3466490033037,
     3684.58633312124)])
def test_an_unsettled_target_is_solved_alone(m, p, other):
    assert arrays_only(m, [p]).theta_deg.tobytes() == arrays_only(m, [p, other]).theta_deg[:1].tobytes()


#: A cross that rises past the lean table's m = 0.8 up to a lock-up near m = 8.6 (no fold): its targets above
#: the table go to one trace call, where a zoom (or a matrix product, which BLAS sums in another order for one
#: row than for two) would make each answer depend on the others.
RISING_CROSS = ActuatorModel("cross", length_mm=10.0, r0_mm=1.5369360885246874, beta0_deg=2.1222898958678784,
                             outer_radius_mm=1.0, inner_radius_mm=0.0, g_e_mpa=1.0, g_mpa=1.0,
                             p0_kpa=392.7558206938526)


@pytest.mark.parametrize("others", [[756.0, 756.0], [1000.0, 756.0, 5000.0], [500.0, 9e4, 756.0]])
def test_targets_above_the_lean_table_do_not_depend_on_each_other(others):
    br = C._branch(RISING_CROSS, C.DEFAULT_TOLERANCES.model_rtol)
    assert br.lean.top < 0.756 - br.scalar.p0 and br.lean.pole is False  # 756 kPa lies above the table
    alone = arrays_only(RISING_CROSS, [756.0])
    many = arrays_only(RISING_CROSS, others)
    for f in FIELDS:
        assert getattr(many, f)[others.index(756.0):][:1].tobytes() == getattr(alone, f).tobytes(), f


@given(m=model_designs(), p=pressures_kpa(max_size=12))
@budget(0.3)
def test_lean_curve_agrees_with_the_trace_inverse_of_sweep(m, p):
    c, s = curve(m, p), sweep([m, m], p)  # two models: sweep's own trace inverse (one model is a curve)
    assert c.status.tolist() == s.status[0].tolist()
    lift = np.maximum(np.asarray(p) - m.p0_kpa, 1e-300)  # the round-off floor of P - P0 (documented)
    floor = 2.0 * C.PRESSURE_FLOOR_PER_G["analytic"] * m.g_mpa * 1000 / lift
    assert np.all(np.abs(c.theta_deg - s.theta_deg[0]) <= (2e-10 + floor) * np.abs(s.theta_deg[0]) + 1e-12)


@pytest.mark.parametrize("m", [design("zigzag", 7.0, g=2.7, p0=85.0), design("zigzag", 5.0, g=12.0, p0=0.0, l0=10.0)])
def test_sweep_solves_a_zigzag_above_its_nodes_up_to_the_fold(m):
    """Past the nodes' end (m = RISE_M) a sweep solves a zigzag's targets on its rise to the fold
    (lean.solve_to_fold), and higher ones are UNSTABLE at the fold: angles from the 50-digit reference's P, and
    the fold where the reference's P peaks (the old central-difference slope put it up to 4e-10 of its angle
    off)."""
    ref = ref_of(m)
    br = C._branch(m, C.DEFAULT_TOLERANCES.model_rtol)
    fold_deg, _ = lockup(m)
    start = math.degrees(br.lean.rates.theta(RISE_M))
    theta = np.radians(start + (fold_deg - start) * np.array([0.05, 0.3, 0.6, 0.8]))
    p = np.array([float(ref.pressure(mp.mpf(float(t))) * 1000) for t in theta])
    fold = mp.radians(mp.mpf(fold_deg))
    p_fold = ref.pressure(fold)
    p = np.append(p, [float(p_fold * 1000) * 1.001, 1e5])
    s, c = sweep([m, m], p, limits=False), curve(m, p, limits=False)
    assert s.status[1].tolist() == c.status.tolist() == [Status.BENDING] * 4 + [Status.UNSTABLE] * 2
    np.testing.assert_allclose(np.radians(s.theta_deg[1, :4]), theta, rtol=1e-10)  # observed 5e-14
    np.testing.assert_allclose(s.theta_deg[1], c.theta_deg, rtol=2e-10)  # curve's trace inverse: 2e-11
    assert s.theta_deg[1, 4] == s.theta_deg[1, 5] == pytest.approx(fold_deg, rel=1e-14)
    d = fold * mp.mpf("1e-7")  # P(fold +- d) = P(fold) - a d^2 +- P' d: P' d is < 1e-3 of a d^2
    lo, hi = ref.pressure(fold - d), ref.pressure(fold + d)
    assert lo < p_fold and hi < p_fold and abs(hi - lo) < 1e-3 * (p_fold - (lo + hi) / 2)


def test_nodes_cover_each_scale_and_stop_short_of_the_zigzags_fold():
    m = design("zigzag", 7.0, g=2.7, p0=85.0)
    br = C._branch(m, 1e-10)
    tab = br.lean
    nodes, rises = tab.arrays()
    stretch, p = nodes[0], nodes[3]
    h = np.diff(stretch)
    # every interval but the finest level's is at most 1/32 of the stretches it serves
    assert np.all(h[LEVEL_POINTS - 1:] <= stretch[LEVEL_POINTS - 1:-1] / 31.99)
    assert np.isclose(h[0], tab.span / 2 ** LEVELS / (LEVEL_POINTS - 1), rtol=1e-15)
    # P rises over the nodes; the zigzag's nodes end at m = RISE_M, short of the fold of P
    assert rises and np.all(np.diff(p) > 0.0)
    assert tab.span == RISE_M
    theta_fold, p_fold = lockup(m)
    assert tab.rates.theta(stretch[-1]) < math.radians(theta_fold)
    beyond = curve(m, [p_fold * 1.01], limits=False)
    assert beyond.status[0] == Status.UNSTABLE and beyond.theta_deg[0] == pytest.approx(theta_fold, rel=1e-9)


@pytest.mark.parametrize("s", [1e-6, 1e-3, 0.05, 0.2, 0.5, 0.8, 0.95, 0.999, 1 - 1e-9])
def test_a_zigzags_pressure_rises_up_to_the_nodes_end(s):
    """A zigzag's P - P0 is G c/(2 r0^2) times a function of m = (r0/l0) theta and s = c/r0^2 alone: its
    first fold lies at m = 0.828 (s -> 0) to 0.954 (s -> 1), beyond RISE_M, where the lean
    nodes end (the float path binary-searches them on that rise)."""
    geo = Geometry.from_values(beta0_rad=0.0, l0_mm=1.0, r0_mm=1.0, c_mm2=s, g_mpa=1.0, p0_mpa=0.0)
    m = np.linspace(0.0, RISE_M, 200_001)[None, 1:]
    p = pressure_mpa(m, geo)[0]
    assert np.all(np.diff(p) > 0.0)
    fold = np.linspace(RISE_M, 0.96, 2001)[None, :]
    assert np.any(np.diff(pressure_mpa(fold, geo)[0]) <= 0.0)  # the fold follows (the bound is not loose)


def test_table_reaches_the_lock_up_of_a_cross():
    m = design("cross", 7.0, 20.0, g=1.3, p0=170.0)
    tab = C._branch(m, 1e-10).lean
    assert tab.top == math.inf
    near = curve(m, [1e4, 1e6], limits=False)  # P -> inf at the lock: the angle creeps towards it
    lock, _ = lockup(m)
    assert np.all(np.abs(near.theta_deg) < abs(lock)) and abs(near.theta_deg[1]) > abs(near.theta_deg[0])


def test_unsettled_targets_go_to_the_trace_inverse():
    """A target whose residual is round-off (far below the finest level's first grid point) is not settled
    by the lean step; the trace inverse solves it, within the pressure floor."""
    m = design("zigzag", 7.0, g=2.7, p0=85.0)
    br = C._branch(m, 1e-10)
    t = np.array([1e-15, 1e-3])  # MPa above P0
    theta, settled = solve_lean(br.lean, t)
    assert settled.tolist() == [False, True]
    c = curve(m, 85.0 + t * 1000, limits=False)
    assert c.status.tolist() == [Status.BENDING] * 2
    # near the straight state P - P0 is linear in theta: the slope from the reference at a small angle
    ref, small = ref_of(m), mp.mpf("1e-6")
    slope = (ref.pressure(small) - mp.mpf(85) / 1000) / small
    expected = math.degrees(float(mp.mpf(t[0]) / slope))
    floor = C.PRESSURE_FLOOR_PER_G["analytic"] * m.g_mpa / t[0]  # relative round-off floor of P - P0
    assert c.theta_deg[0] == pytest.approx(expected, rel=2 * floor)


def test_no_rising_interval_gives_no_table():
    m = design("cross", 7.0, 20.0, g=1.3, p0=170.0)
    geo = C._geometry([m])
    assert lean_table(geo, theta_end=0.0, pole_at_end=False, rtol=1e-10, atol=1e-22) is None
    assert lean_table(geo, theta_end=float(lock_theta(geo)[0, 0]), pole_at_end=True, rtol=1e-10,
                      atol=1e-22) is not None


@pytest.mark.parametrize("bad", [[-1.0], [float("nan")], [float("inf")], [[1.0, 2.0]]])
def test_bad_pressures_are_refused_as_on_the_array_path(bad):
    m = design("zigzag", 7.0)
    with pytest.raises(Exception) as one:
        curve(m, bad)
    with pytest.raises(Exception) as many:
        curve(m, np.array(bad * 20 if np.ndim(bad) == 1 else bad))
    assert type(one.value) is type(many.value) and "pressure_kpa" in str(one.value)


def test_numpy_scalars_arrays_and_tuples_give_the_answers_of_floats_and_lists():
    m = design("cross", 7.0, 20.0, g=1.3, p0=170.0)
    same_bits(curve(m, [np.float64(230.0)]), curve(m, [230.0]))
    same_bits(curve(m, np.array([230.0, 240.0])), curve(m, (230.0, 240.0)))
    same_bits(curve(m, 230), curve(m, [230.0]))
    assert curve(m, [True]).pressure_kpa.tolist() == [1.0]  # a bool is the number numpy makes of it


def test_sweep_past_the_tracing_cap_of_a_cross_is_out_of_domain_as_a_curve():
    """A cross whose lock-up lies beyond MAX_BEND_DEG: its nodes end at the cap, a pressure past it is not
    bracketed by the last node (a pole only at a lock-up), so the trace inverse answers, as for curve()."""
    m = ActuatorModel("cross", length_mm=262.0, r0_mm=3.073872177049375, beta0_deg=9.99858527677441,
                      outer_radius_mm=2.0, inner_radius_mm=0.0, g_e_mpa=1.0, g_mpa=1.0, p0_kpa=10.0)
    assert abs(lockup(m)[0]) == C.MAX_BEND_DEG
    c, s = curve(m, [1e4]), sweep([m, m], [1e4])
    assert c.status[0] == s.status[1, 0] == Status.OUT_OF_DOMAIN
    assert c.theta_deg[0] == s.theta_deg[1, 0] == C.MAX_BEND_DEG


@given(m=model_designs())
@budget(0.3)
def test_pressure_rises_over_the_served_span(m):
    """The float path binary-searches the nodes on the rise of P the array path checks: it holds up to the
    served span (the lock-up or m = RISE_M) over the designs' parameter space, on a grid finer than the nodes."""
    br = C._branch(m, C.DEFAULT_TOLERANCES.model_rtol)
    if br.lean is None:
        return
    tab = br.lean
    assert abs(tab.span) <= RISE_M and tab.arrays()[1]
    f, v = tab.rates(tab.span * np.linspace(0.0, 1.0, 4001)[1:-1])
    assert np.all(np.diff(f / v) > 0.0)


def test_a_cross_of_a_small_thread_angle_folds_as_a_zigzag_and_the_float_path_leaves_it():
    """beta0 = 1.6 deg: P folds at m = 1.1 (274.8 deg), long before the lock-up (2948 deg); past the fold the
    answer is the fold (UNSTABLE) on both paths, never an equilibrium found beyond it."""
    m = ActuatorModel("cross", length_mm=10.0, r0_mm=2.2972394456619596, beta0_deg=1.5910423532081408,
                      outer_radius_mm=2.0, inner_radius_mm=1.5, g_e_mpa=1.0, g_mpa=1.0, p0_kpa=38.644658675636244)
    theta_fold, p_fold = lockup(m)
    one = curve(m, [2.0 * p_fold], limits=False)
    many = C._solve([m], [2.0 * p_fold] * 20, "auto", C.DEFAULT_TOLERANCES.model_rtol, squeeze=True, limits=False)
    assert one.status[0] == many.status[0] == Status.UNSTABLE
    assert one.theta_deg[0] == pytest.approx(theta_fold, rel=1e-9)


@pytest.mark.parametrize("pattern, angles", [("zigzag", [0.0]), ("cross", [5.0, 20.0, 45.0, 75.0])])
def test_the_float_paths_bracket_is_the_search_of_every_node_in_few_evaluations(pattern, angles):
    """The float path's bracket of a target (evaluating few nodes: a first guess from the table over s0 and
    sigma = c cos^2(beta0)/r0^2, checked on two of its own nodes; quadratic guesses where it misses) is the node
    searchsorted finds among all of them, over widths whose sigma falls on, between and next to the table's grid,
    and targets from round-off size to the last node; a zigzag evaluates two nodes, others fewer than three on
    average and at most a dozen (of 385)."""
    from embroact.predict import lean as L

    counts = []
    for w in (4.0, 5.5, 7.0, 9.0, 12.0):
        for angle in angles:
            br = C._branch(design(pattern, w, angle), 1e-10)
            tab = br.lean
            nodes, _ = tab.arrays()
            top = float(nodes[3, -1]) if math.isfinite(nodes[3, -1]) else 50.0 * float(nodes[3, -2])
            for t in [1e-12, 1e-6] + list(np.linspace(0.0005, 0.9995, 41) ** 2 * top):
                want = int(np.searchsorted(nodes[3, 1:L._LAST], t, side="right"))
                probe = L.LeanTable(tab.rates, tab.span, tab.pole, tab.rtol, tab.atol, tab.floor, {}, {})
                got = L._bracket(probe, t)
                assert got == (want if want < L._LAST else None)
                assert L._bracket(tab, t) == got  # by the nodes' arrays
                counts.append(len(probe.nodes))
    if pattern == "zigzag":
        assert set(counts) == {2}
    assert max(counts) <= 12 and np.mean(counts) < 3.0


def test_the_guess_table_is_the_closed_form_at_its_grid_for_any_length_and_radius():
    """Each row of the guess table is P - P0 over the scale of the closed form (StretchRates) at the nodes of a
    design of that s0 and sigma, whatever its length and radius: on the span up to its lock-up (a cross design)
    or RISE_M (a zigzag; a cross whose lock-up lies beyond), evaluated on floats one node at a time; no row
    where the wall does not fit the sleeve."""
    from embroact.predict import lean as L
    from embroact.predict.floats import SCALAR
    from embroact.predict.model import StretchRates, lock_theta

    for i, k, l0, r0 in ((0, 1, 50.0, 2.0), (0, 17, 120.0, 3.1), (0, L.GUESS_GRID - 1, 80.0, 2.5),
                         (3, 20, 60.0, 2.2), (24, 9, 200.0, 4.0), (40, 30, 90.0, 2.6), (60, 2, 100.0, 3.0)):
        row = L._guess_nodes(i, k)
        assert len(row) == L._LAST + 1
        s0 = i / L.GUESS_GRID
        geo = Geometry.of_floats(beta0_rad=math.asin(s0), l0_mm=l0, r0_mm=r0,
                                 c_mm2=k / L.GUESS_GRID * r0 * r0 / (1.0 - s0 * s0), g_mpa=2.0, p0_mpa=0.1)
        rates = StretchRates.of(geo)
        span = rates.m_of(float(lock_theta(geo, SCALAR))) if i else math.inf
        pole = abs(span) <= L.RISE_M
        span = span if pole else math.copysign(L.RISE_M, span)
        for j in (1, 100, 300, L._LAST - 1) + (() if pole else (L._LAST,)):
            f, v = rates(span * L._FRACTION_LIST[j], SCALAR)
            assert row[j] == pytest.approx(f / v, rel=1e-9)
        assert row[L._LAST] == math.inf if pole else math.isfinite(row[L._LAST])
    assert L._guess_nodes(62, 10) is None  # s0 = 0.97: sigma 10/64 > cos^2(beta0) = 0.06


@pytest.mark.parametrize("m", [design("zigzag", 7.0, g=2.7, p0=85.0), design("zigzag", 5.0, g=1.4, p0=50.0, l0=40.0),
                               design("cross", 7.0, 15.0, g=2.9, p0=150.0), design("cross", 7.0, 60.0, g=2.9, p0=200.0),
                               dataclasses.replace(design("zigzag", 9.0, g=2.0, p0=60.0), stub_mm=30.0),
                               dataclasses.replace(design("cross", 6.0, 20.0, g=1.3, p0=120.0), stub_mm=8.0)])
def test_the_float_paths_contact_range_gives_the_contact_tests_statuses(m):
    """One pressure at a time through the contact and past it (the float path makes its contact range at the
    second state that may touch, then decides states by it): the statuses of the array path over all of them, and
    COILED exactly where the closed-form contact test (arc_contact on the curve's own states) or a full turn says
    the strip touches."""
    from embroact.predict.validity import ContactRange, arc_contact

    theta_end, _ = lockup(m)
    top = float(curve(m, [1e5], limits=False).pressure_kpa[0])
    ref = C._solve([m], np.linspace(m.p0_kpa, 4.0 * m.p0_kpa + 400.0, 400)[1:], "auto",
                   C.DEFAULT_TOLERANCES.model_rtol, squeeze=True, limits=False)
    near = ref.pressure_kpa[np.abs(ref.theta_deg) >= 240.0]
    assert near.size > 20, (top, theta_end)  # the sweep reaches the contact
    C._cached_branch.cache_clear()
    ones = [curve(m, [float(p)]) for p in near]
    served = [c for c in ones if c.method == C._FAST_NAME]
    assert len(served) > 20
    many = arrays_only(m, near)
    for k, c in enumerate(ones):
        assert c.status.tobytes() == many.status[k:k + 1].tobytes()
    for c in served:
        th = math.radians(float(c.theta_deg[0]))
        touches = bool(arc_contact(th, float(c.radius_mm[0]), m.length_mm, m.stub_mm)[()])
        assert (int(c.status[0]) == Status.COILED) == touches or int(c.status[0]) in (Status.KINKED,
                                                                                     Status.OVERSTRETCHED)
    assert isinstance(C._branch(m, C.DEFAULT_TOLERANCES.model_rtol).lazy["contact"], ContactRange)  # made


def test_a_models_branch_is_kept_from_its_second_curve_on(monkeypatch):
    """A model's first curve keeps no branch (a model asked once evicts none), its second keeps one, and the three
    curves give the same bits, for one pressure (the float path) and for many (the arrays); the models asked are
    forgotten at ASKED_MAX (then a model's second curve makes its branch once more, kept from its third)."""
    C._cached_branch.cache_clear()
    for k, p in enumerate(([230.0], np.linspace(0.0, 400.0, 50).tolist())):
        m = dataclasses.replace(design("cross", 7.0, 15.0, g=2.9, p0=150.0), calibration=f"asked once {k}")
        first, held = curve(m, p), C._cached_branch.cache_info().currsize
        assert held == k  # the first curve kept nothing
        second = curve(m, p)
        assert C._cached_branch.cache_info().currsize == held + 1
        third = curve(m, p)
        assert C._cached_branch.cache_info().currsize == held + 1 and C._cached_branch.cache_info().hits >= 1
        for name in FIELDS:
            assert getattr(first, name).tobytes() == getattr(second, name).tobytes() == getattr(third, name).tobytes()
    monkeypatch.setattr(C, "ASKED_MAX", 3)
    for k in range(5):
        curve(dataclasses.replace(RISING_CROSS, calibration=f"forgotten {k}"), [230.0])
        assert len(C._ASKED) <= 3
