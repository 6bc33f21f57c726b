"""Validity limits of the model (predict/validity.py): criteria against hand and 50-digit values."""
import math

import mpmath as mp
import numpy as np
import pytest

import mpref
from embroact.patterns.base.errors import ParameterError
from embroact.patterns.params import Tube
from embroact.predict import curve as C
from embroact.predict.curve import ActuatorModel, curve, pressure_at
from embroact.predict.derived import derive_from_values
from embroact.predict.status import Status
from embroact.predict.branch import EndKind, branch_end, first_limit
from embroact.predict.validity import STRETCH_LIMIT, apply_limits, coil_angle_deg, limit_flags, valid_mask

L0 = 100.0


def zigzag(w=7.0, g=2.7, p0=85.0, l0=100.0):
    d = derive_from_values("zigzag", width_mm=w, interval_mm=1.0, angle_deg=0.0, length_mm=l0, tube=Tube())
    return ActuatorModel.from_derived(d, g_mpa=g, p0_kpa=p0)


def cross(angle, g, p0):
    d = derive_from_values("cross", width_mm=7.0, interval_mm=1.4, angle_deg=angle, length_mm=100.0, tube=Tube())
    return ActuatorModel.from_derived(d, g_mpa=g, p0_kpa=p0)


def test_negative_coil_angle_is_where_the_tip_lands_on_the_tube():
    """Tip phi = 2 pi - |theta| short of a full turn, at height R (1 - cos phi) above the base line:
    it reaches the tube's top 2 r.  Hand value for l0 = 100 mm, r = 2.58 mm: 315.7 deg."""
    r = 2.58
    with mp.workdps(30):
        root = mp.findroot(lambda t: (L0 / t) * (1 - mp.cos(2 * mp.pi - t)) - 2 * r, 5.5)
    assert coil_angle_deg(L0, r, negative=True) == pytest.approx(float(mp.degrees(root)), abs=1e-9)
    assert coil_angle_deg(L0, r, negative=True) == pytest.approx(315.7, abs=0.05)
    a = math.radians(float(mp.degrees(root)))
    f = limit_flags([-(a - 1e-9), -(a + 1e-9), a + 1e-9], L0, r, L0)
    assert f.coiled.tolist() == [False, True, False]  # a positive bend reaches the supply tube later


def test_positive_coil_angle_is_where_the_tips_tube_corner_enters_the_supply_tube():
    """Tube outside the bend, centre (0, R): the tip section's tube-side corner (0, R) + (R + 2 r)(sin, -cos)
    reaches the supply tube's band (y <= 0) at cos(theta) = R / (R + 2 r), R = l0 / theta."""
    r = 2.58
    with mp.workdps(30):
        root = mp.findroot(lambda t: mp.cos(t) - (L0 / t) / (L0 / t + 2 * r), 5.6)
    assert coil_angle_deg(L0, r, negative=False) == pytest.approx(float(mp.degrees(root)), abs=1e-9)
    assert coil_angle_deg(L0, r, negative=False) == pytest.approx(320.9, abs=0.05)


def test_full_turn_and_kink_and_stretch_thresholds():
    r = 2.0
    th = np.radians([300.0, 360.0, -360.0])  # a positive bend's tip reaches the supply tube at 324.6 deg
    assert limit_flags(th, L0, r, L0).coiled.tolist() == [False, True, True]
    kink = L0 / (2 * r)  # radius l0/theta = 2 r
    assert limit_flags([kink * (1 - 1e-12), kink * (1 + 1e-12)], L0, r, L0).kinked.tolist() == [False, True]
    assert limit_flags([0.1, 0.1], [STRETCH_LIMIT * L0 * (1 - 1e-12), STRETCH_LIMIT * L0], r, L0) \
        .overstretched.tolist() == [False, True]
    assert STRETCH_LIMIT == 2.0


def test_short_strip_kinks_where_its_tube_reaches_the_clamp():
    """l0 = 20 mm, r = 2.58 mm: kinked at l0/(2 r) = 222.1 deg, long before a turn; there the tube's band
    (2 r thick, inside a radius of 2 r) fills the circle to its centre, where the clamp's section ends too."""
    kink = math.degrees(20.0 / (2 * 2.58))
    f = limit_flags(np.radians([-(kink - 0.01), -(kink + 0.01)]), 20.0, 2.58, 20.0)
    assert f.kinked.tolist() == [False, True] and f.coiled.tolist() == [False, True]
    assert coil_angle_deg(20.0, 2.58, negative=True) == pytest.approx(kink, abs=1e-6)
    with pytest.raises(ParameterError, match="l0_mm must be in"):
        coil_angle_deg(-1.0, 2.0, negative=True)


def test_precedence_and_fill_values_kept():
    st = np.array([Status.BENDING, Status.UNSTABLE, Status.LOCKED, Status.OUT_OF_DOMAIN, Status.FAILED,
                   Status.BENDING, Status.BENDING], dtype=np.int8)
    th = np.radians([400.0, 400.0, 400.0, 400.0, 400.0, 100.0, 10.0])
    l = np.array([250.0, 250.0, 250.0, 250.0, 250.0, 250.0, 101.0])
    out = apply_limits(st, th, l, 2.5, L0)
    assert [Status(v).name for v in out] == ["COILED", "COILED", "COILED", "OUT_OF_DOMAIN", "FAILED",
                                             "OVERSTRETCHED", "BENDING"]
    f = limit_flags(th, l, 2.5, L0)
    assert f.names()[0] == ["COILED", "OVERSTRETCHED"] and f.names()[6] == []


def test_paper_w5_zigzag_is_coiled_and_overstretched_as_issue_reports():
    """Built-in set: G = 0.8 MPa, P0 = 50 kPa: 2032 deg at 250 kPa, stretch 2.45, radius 2.8 mm < 2 r0."""
    m = zigzag(5.0, 0.8, 50.0)
    c = curve(m, np.arange(100.0, 301.0, 50.0))
    assert [Status(s).name for s in c.status] == ["BENDING", "BENDING", "COILED", "COILED", "COILED"]
    assert c.theta_deg[3] == pytest.approx(2032.35, abs=0.01)
    f = limit_flags(np.radians(c.theta_deg), c.length_mm, c.radius_mm, m.length_mm)
    assert f.names()[3] == ["COILED", "KINKED", "OVERSTRETCHED"]
    assert c.length_mm[3] / m.length_mm == pytest.approx(2.446, abs=1e-3)
    assert valid_mask(c).tolist() == [True, True, False, False, False]
    # the formula alone: bending, then unstable past the fold
    raw = curve(m, np.arange(100.0, 301.0, 50.0), limits=False)
    assert [Status(s).name for s in raw.status] == ["BENDING"] * 4 + ["UNSTABLE"]
    np.testing.assert_array_equal(raw.theta_deg, c.theta_deg)


def test_zigzag_kink_and_stretch_coincide_at_l0_over_2r0():
    m = zigzag(9.0, 3.4, 180.0, l0=30.0)  # short: kink before the full turn
    t = math.degrees(m.length_mm / (2 * m.r0_mm))
    c = pressure_at(m, [t * (1 - 1e-9), t * (1 + 1e-9)])
    assert [Status(s).name for s in c.status] == ["BENDING", "KINKED"]
    f = limit_flags(np.radians(c.theta_deg), c.length_mm, c.radius_mm, m.length_mm)
    assert f.overstretched.tolist() == [False, True]


def test_branch_end_names_the_zigzag_fold_and_the_cross_lock():
    e = branch_end(zigzag())
    assert e.kind is EndKind.FOLD and e.status is Status.COILED
    assert e.theta_deg == pytest.approx(1888.7643, abs=1e-3) and e.pressure_kpa == pytest.approx(509.3, abs=0.1)
    x = branch_end(cross(45.0, 1.3, 170.0))
    ref = mpref.Ref.cross(width_mm=7, angle_deg=45, g_mpa=1.3, p0_kpa=170)
    assert x.kind is EndKind.LOCK_UP and x.pressure_kpa is None and x.status is Status.LOCKED
    assert x.theta_deg == pytest.approx(float(mp.degrees(ref.lock_theta(-1))), rel=1e-12)
    assert x.as_dict() == {"kind": "lock-up", "theta_deg": x.theta_deg, "pressure_kpa": None, "status": "LOCKED"}
    neutral = ActuatorModel("cross", length_mm=100, r0_mm=2.58, beta0_deg=math.degrees(math.atan(0.5)),
                            outer_radius_mm=1.5, inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.0, p0_kpa=150)
    assert branch_end(neutral).kind is EndKind.NONE


def test_branch_end_at_the_tracing_cap(monkeypatch):
    monkeypatch.setattr(C, "MAX_BEND_DEG", 90.0)
    e = branch_end(zigzag())
    assert e.kind is EndKind.TRACING_CAP and e.theta_deg == 90.0 and e.status is Status.OUT_OF_DOMAIN


def test_first_limit_of_a_zigzag_is_the_tip_on_the_supply_tube_at_the_reference_pressure():
    """r = r0 along a zigzag's bend: the tip's tube-side corner enters the supply tube at cos(theta) = R / (R + 2 r0)."""
    m = zigzag()
    f = first_limit(m)
    ref = mpref.Ref.zigzag(width_mm=7, g_mpa=2.7, p0_kpa=85)
    with mp.workdps(30):
        root = mp.findroot(lambda t: mp.cos(t) - (L0 / t) / (L0 / t + 2 * m.r0_mm), 5.6)
        assert f.status is Status.COILED and f.theta_deg == pytest.approx(float(mp.degrees(root)), abs=1e-7)
        assert f.pressure_kpa == pytest.approx(float(ref.pressure(root)) * 1000, rel=1e-7)


def test_first_limit_of_a_negative_cross_bend_is_the_tube_contact():
    """alpha0 = 60 deg: the pantograph changes r along the bend; at the first limit the contact holds
    with the state's own r (from the 50-digit reference), l0 (1 - cos theta) = 2 r |theta|."""
    m = cross(60.0, 2.9, 200.0)
    f = first_limit(m)
    if f is None:  # the lock comes first: nothing to check but that the lock state is valid
        assert branch_end(m).status is Status.LOCKED
        return
    ref = mpref.Ref.cross(width_mm=7, angle_deg=60, g_mpa=2.9, p0_kpa=200)
    th = math.radians(f.theta_deg)
    with mp.workdps(30):
        r = float(ref.l_r(mp.mpf(th))[1])
    if f.status is Status.COILED:
        assert m.length_mm * (1 - math.cos(th)) == pytest.approx(2 * r * abs(th), rel=1e-9)
    else:
        assert f.status is Status.KINKED and 2 * r * abs(th) == pytest.approx(m.length_mm, rel=1e-9)


@pytest.mark.parametrize("model", [zigzag(), zigzag(w=5.2, g=4.0, p0=120.0, l0=37.0), cross(60.0, 2.9, 200.0),
                                   cross(20.0, 4.1, 160.0), cross(52.0, 1.5, 90.0)])
def test_first_limit_bisects_as_one_halving_per_call(model):
    """The batched bisection (several halvings' midpoints per pressure_at call) ends at the angle the plain
    bisection, one pressure_at call per halving, ends at: the same float, status and pressure."""
    from embroact.predict.status import VALIDITY_LIMITS
    from embroact.predict.validity import LIMIT_BISECTIONS

    grid = np.linspace(0.0, branch_end(model).theta_deg, 257)
    hit = np.flatnonzero(np.isin(pressure_at(model, grid).status, [int(s) for s in VALIDITY_LIMITS]))
    if hit.size == 0:
        assert first_limit(model) is None
        return
    lo, hi = float(grid[hit[0] - 1]), float(grid[hit[0]])
    for _ in range(LIMIT_BISECTIONS):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        lo, hi = (lo, mid) if Status(int(pressure_at(model, [mid]).status[0])) in VALIDITY_LIMITS else (mid, hi)
    c = pressure_at(model, [hi])
    f = first_limit(model)
    assert (f.status, f.theta_deg, f.pressure_kpa) == (Status(int(c.status[0])), float(c.theta_deg[0]),
                                                       float(c.pressure_kpa[0]))


def test_cross_45_locks_before_its_coil_contact():
    m = cross(45.0, 1.3, 170.0)
    assert first_limit(m) is None
    c = curve(m, [200.0, 300.0, 1e4])
    assert np.all(c.status == Status.BENDING)


def test_apply_limits_takes_numbers_and_lists_and_returns_a_new_array():
    from embroact.predict.validity import apply_limits

    st = np.array([int(Status.BENDING)] * 2, dtype=np.int8)
    out = apply_limits(st, [0.1, 7.0], [100.0, 130.0], 2.5, 100.0)  # 7 rad: past a full turn
    assert out.tolist() == [Status.BENDING, Status.COILED] and out is not st
    calm = apply_limits(st, [0.1, 0.2], [100.0, 101.0], 2.5, 100.0)
    assert calm.tolist() == st.tolist() and calm is not st and calm.dtype == np.int8
    assert apply_limits(int(Status.BENDING), 0.1, 100.0, 2.5, 100.0).tolist() == int(Status.BENDING)


def test_one_state_on_floats_decides_contact_as_the_arrays_do():
    """The float path's arc contact (one state, numpy's sin and cos on floats) gives arc_contact's answer,
    also at the neighbouring floats of each contact angle."""
    import random

    from embroact.predict.validity import _arc_contact_float, arc_contact, coil_angle_deg

    rng = random.Random(3)
    for _ in range(300):
        r, l0, m = rng.uniform(0.5, 5.0), rng.uniform(10.0, 300.0), rng.choice([0.0, math.nan, rng.uniform(0.0, 50.0)])
        neg = rng.random() < 0.5
        edge = math.radians(coil_angle_deg(l0, r, negative=neg, stub_mm=0.0 if m != m else m)) * (-1 if neg else 1)
        for x in (edge, math.nextafter(edge, math.inf), math.nextafter(edge, -math.inf), rng.uniform(-7.0, 7.0)):
            assert _arc_contact_float(x, r, l0, m) == bool(arc_contact(x, r, l0, m)), (x, r, l0, m)


def test_contact_bound_clears_only_bends_short_of_contact():
    """The bound that spares the contact test of a curve's states far from contact lies below the first contact
    (the closed form of the module docstring for l0 = 100 mm, r = 2.58 mm: 315.70 deg), and an arc of any bend
    below it is apart on a fine grid, with a stub, without, and as a segment of a chain."""
    import random

    from embroact.predict.validity import _contact_free_below, arc_contact

    with mp.workdps(30):
        first = float(mp.degrees(mp.findroot(lambda t: L0 * (1 - mp.cos(t)) - 2 * 2.58 * t, 5.5)))
    assert first == pytest.approx(315.70, abs=0.01)
    assert 280.0 < math.degrees(_contact_free_below(L0, 2 * 2.58, 0.0)) < first
    assert _contact_free_below(L0, 2 * 2.58, math.nan) == 2 * math.pi  # a chain's arc: its full turn only
    rng = random.Random(11)
    for _ in range(200):
        l0, r, m = rng.uniform(5.0, 400.0), rng.uniform(0.3, 9.0), rng.choice([0.0, rng.uniform(0.0, 60.0)])
        free = _contact_free_below(l0, 2 * r, m)
        for neg in (True, False):
            assert free <= math.radians(coil_angle_deg(l0, r, negative=neg, stub_mm=m)) + 1e-12
            grid = np.linspace(0.0, free, 1001)[:-1] * (-1.0 if neg else 1.0)
            assert not arc_contact(grid, r, l0, m).any(), (l0, r, m, free)


def test_contact_bounds_hold_on_both_sides_of_the_first_contact():
    """The closed-form ends that spare a curve's states the contact test: every bend from the free bound up to
    ``below`` is apart and every one in ``[start, end]`` touches, for any band between the narrowest and the
    widest, with a stub and without; without a stub both ends lie within 0.01 deg of the 50-digit first
    contact (l0 = 100 mm, r = 2.58 mm: 315.70 deg negative, 320.9 deg positive, cos t = R/(R + 2 r))."""
    import random

    from embroact.predict.validity import _contact_bounds, _contact_free_below, arc_contact

    with mp.workdps(30):
        neg = float(mp.findroot(lambda t: L0 * (1 - mp.cos(t)) - 2 * 2.58 * t, 5.5))
        pos = float(mp.findroot(lambda t: mp.cos(t) - (L0 / t) / (L0 / t + 2 * 2.58), 5.6))
    w = 2 * 2.58
    for negative, first in ((True, neg), (False, pos)):
        below, start, end = _contact_bounds(L0, w, w, 0.0, negative, _contact_free_below(L0, w, 0.0))
        assert below < first < start and start - below < math.radians(0.01)
        assert end < 2 * math.pi and 2 * math.pi - end < math.radians(0.02)
    rng = random.Random(5)
    for _ in range(200):
        l0, r, m = rng.uniform(5.0, 400.0), rng.uniform(0.3, 9.0), rng.choice([0.0, rng.uniform(0.0, 60.0)])
        w_lo, w_hi = 2 * r * rng.uniform(0.9, 1.0), 2 * r
        free = _contact_free_below(l0, w_hi, m)
        for negative in (True, False):
            below, start, end = _contact_bounds(l0, w_lo, w_hi, m, negative, free)
            sign = -1.0 if negative else 1.0
            band = rng.uniform(w_lo, w_hi) / 2
            if below > free:
                grid = np.linspace(free, below, 401)[:-1]
                assert not arc_contact(sign * grid, band, l0, m).any(), (l0, r, m, negative)
            if start <= end:
                grid = np.linspace(start, end, 401)
                assert arc_contact(sign * grid, band, l0, m).all(), (l0, r, m, negative)


def test_a_branchs_limits_equal_the_limits_of_every_state():
    """apply_limits on states of one bending direction through the contact (the bounds' fast path, a few states
    tested on floats or many on arrays) equals limit_flags state by state, also at the floats next to each
    contact angle and just short of the full turn."""
    import random

    rng = random.Random(13)
    for _ in range(300):
        l0, r0, stub = rng.uniform(10.0, 300.0), rng.uniform(0.5, 8.0), rng.choice([0.0, 30.0, None])
        neg = rng.random() < 0.5
        sign = -1.0 if neg else 1.0
        edge = math.radians(coil_angle_deg(l0, r0, negative=neg, stub_mm=0.0 if stub is None else stub))
        th = sign * np.concatenate([np.linspace(0.0, 2 * math.pi, rng.choice([5, 60, 400])),
                                    [edge, math.nextafter(edge, 0.0), math.nextafter(edge, 7.0),
                                     math.nextafter(2 * math.pi, 0.0), 2 * math.pi - 1e-9, 2 * math.pi + 0.1]])
        r = r0 * np.array([rng.choice([1.0, rng.uniform(0.97, 1.0)]) for _ in th])
        length = l0 * (1.0 + 0.05 * np.abs(th))
        st = np.full(th.size, int(Status.BENDING), dtype=np.int8)
        got = apply_limits(st, th, length, r, l0, stub_mm=stub)
        f = limit_flags(th, length, r, l0, stub_mm=math.nan if stub is None else stub)
        want = np.where(f.coiled, Status.COILED, np.where(f.kinked, Status.KINKED,
                                                           np.where(f.overstretched, Status.OVERSTRETCHED, st)))
        assert got.tolist() == want.tolist(), (l0, r0, stub, neg)


def test_one_models_limits_equal_the_limits_of_every_state():
    """apply_limits on one model's states (the bound, the contact test only where it cannot clear) gives the
    statuses limit_flags gives state by state, also at the floats next to each contact angle."""
    import random

    rng = random.Random(12)
    for _ in range(300):
        l0, r0, stub = rng.uniform(10.0, 300.0), rng.uniform(0.5, 8.0), rng.choice([0.0, 30.0, None])
        m = math.nan if stub is None else stub
        edges = [math.radians(coil_angle_deg(l0, r0, negative=n, stub_mm=0.0 if stub is None else stub))
                 * (-1.0 if n else 1.0) for n in (True, False)]
        th = np.array([rng.uniform(-7.0, 7.0) for _ in range(rng.choice([2, 40]))]
                      + [f(e, g) for e in edges for f, g in ((math.nextafter, math.inf), (math.nextafter, -math.inf),
                                                            (lambda e, _: e, None))])
        r = r0 * np.array([rng.uniform(0.95, 1.0) for _ in th])
        length = l0 * (1.0 + 0.05 * np.abs(th))
        st = np.full(th.size, int(Status.BENDING), dtype=np.int8)
        got = apply_limits(st, th, length, r, l0, stub_mm=stub)
        f = limit_flags(th, length, r, l0, stub_mm=m)
        want = np.where(f.coiled, Status.COILED, np.where(f.kinked, Status.KINKED,
                                                           np.where(f.overstretched, Status.OVERSTRETCHED, st)))
        assert got.tolist() == want.tolist(), (l0, r0, stub)


def test_rows_of_designs_are_coiled_where_the_contact_test_says():
    """limit_flags on rows of designs (arrays broadcast as sweep passes them: the contact test only at or past the
    free bound) flags coiled exactly where arc_contact flags each state alone, at every angle, with a stub, without and inside a chain, also at the floats next to each contact angle,
    and for short arcs where the bound has no closed form."""
    import random

    from embroact.predict.validity import arc_contact

    rng = random.Random(17)
    rows = [(rng.uniform(5.0, 300.0), rng.uniform(0.5, 8.0), rng.choice([0.0, 30.0, math.nan])) for _ in range(120)]
    l0, r0, stub = (np.array([[row[k]] for row in rows]) for k in range(3))
    th = np.empty((len(rows), 64))
    for k, (length, radius, m) in enumerate(rows):
        neg = rng.random() < 0.5
        edge = math.radians(coil_angle_deg(length, radius, negative=neg, stub_mm=0.0 if m != m else m))
        th[k] = (-1.0 if neg else 1.0) * np.concatenate([np.linspace(0.0, 2 * math.pi + 0.1, 58), [
            edge, math.nextafter(edge, 0.0), math.nextafter(edge, 7.0), math.nextafter(2 * math.pi, 0.0),
            2 * math.pi, rng.uniform(0.0, 7.0)]])
    r = r0 * np.array([[rng.uniform(0.95, 1.0) for _ in range(th.shape[1])] for _ in rows])
    f = limit_flags(th, l0 * (1.0 + 0.01 * np.abs(th)), r, l0, stub_mm=stub)
    alone = np.array([[bool(arc_contact(th[k, j], r[k, j], l0[k, 0], stub[k, 0])) for j in range(th.shape[1])]
                      for k in range(len(rows))])
    assert alone.any() and not alone.all()
    assert f.coiled.tolist() == alone.tolist()


def test_a_short_arc_with_a_long_stub_is_coiled_before_a_quarter_turn_on_every_path():
    """l0 10.7 mm, r 6.1 mm, a 30 mm stub, bending negative (towards the tube): the stub's rectangle meets the fixed
    band from about -51 deg, short of a quarter turn, where the kink limit (2 r theta > l0 from 50.3 deg) also holds; COILED takes precedence. The
    contact test alone, rows of designs (limit_flags), one model's states (apply_limits on arrays) and one state
    on floats give the same status at every angle, and coil_angle_deg finds that first contact."""
    from embroact.predict.floats import SCALAR
    from embroact.predict.validity import arc_contact

    l0, r, stub = 10.7, 6.1, 30.0
    th = -np.radians(np.linspace(1.0, 89.0, 89))
    touch = arc_contact(th, r, l0, stub)
    assert touch.any() and not touch.all()
    first = -float(np.degrees(th[touch][0]))
    assert 45.0 < first < 60.0
    assert abs(coil_angle_deg(l0, r, negative=True, stub_mm=stub) - first) <= 1.0
    length = l0 + 2.0 * r * th  # a zigzag's thread side (shorter)
    rows = limit_flags(th[None, :], length[None, :], r, l0, stub_mm=stub).coiled[0]
    states = apply_limits(np.ones(th.size, dtype=np.int8), th, length, np.full(th.size, r), l0, stub_mm=stub)
    floats = [apply_limits(1, float(a), float(b), r, l0, SCALAR, stub) for a, b in zip(th, length)]
    assert rows.tolist() == touch.tolist()
    assert (states == Status.COILED).tolist() == touch.tolist() == [c == Status.COILED for c in floats]


def test_a_models_contact_bound_spares_the_test_and_changes_no_status():
    """One state on floats with the model's bound (contact_free_below_rad at its largest radius) gets the status it
    gets without it, over bends up to past a full turn, radii up to that largest, with and without a stub and
    inside a chain; the bound lies below the contact angle coil_angle_deg finds."""
    from embroact.predict.floats import SCALAR
    from embroact.predict.validity import contact_free_below_rad

    for l0, r_max, stub in ((100.0, 2.58, 0.0), (100.0, 2.58, 30.0), (40.0, 3.0, None), (10.7, 6.1, 30.0)):
        free = contact_free_below_rad(l0, r_max, stub)
        if stub is not None:
            for negative in (True, False):
                assert math.degrees(free) <= coil_angle_deg(l0, r_max, negative=negative, stub_mm=stub) + 1e-9
        for deg in np.linspace(-370.0, 370.0, 371):
            for r in (0.5 * r_max, r_max):
                th, length = math.radians(deg), l0 * (1.0 + 0.001 * abs(deg))
                plain = apply_limits(int(Status.BENDING), th, length, r, l0, SCALAR, stub)
                assert apply_limits(int(Status.BENDING), th, length, r, l0, SCALAR, stub, free) == plain, (l0, deg)
