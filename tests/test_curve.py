"""Public API of the model: values, statuses of every region, sweeps, validation, never NaN."""
import json
import math
import os
import subprocess
import sys

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mpref
from embroact.patterns.base.errors import ParameterError
from embroact.patterns.params import Tube
from embroact.predict import curve as C
from embroact.predict.curve import ActuatorModel, curve, lockup, pressure_at, sweep
from embroact.predict.derived import derive_from_values
from embroact.predict.status import Status

NEUTRAL_BETA0_DEG = math.degrees(math.atan(0.5))


def derived(pattern="zigzag", w=7.0, angle=0.0, tube=Tube()):
    return derive_from_values(pattern, width_mm=w, interval_mm=1.0, angle_deg=angle, length_mm=100.0, tube=tube)


def model(pattern="zigzag", w=7.0, angle=0.0, g=2.7, p0=85.0, **kw):
    return ActuatorModel.from_derived(derived(pattern, w, angle), g_mpa=g, p0_kpa=p0, **kw)


def raw(pattern="cross", *, r0=2.5814206750769157, beta0=30.0, g=2.0, p0=150.0, rf=1.5, df=1.0, l0=100.0, **kw):
    return ActuatorModel(pattern, length_mm=l0, r0_mm=r0, beta0_deg=beta0 if pattern == "cross" else 0.0,
                         outer_radius_mm=rf, inner_radius_mm=df, g_e_mpa=0.13, g_mpa=g, p0_kpa=p0, **kw)


ZIGZAG7 = mpref.Ref.zigzag(width_mm=7, g_mpa=2.7, p0_kpa=85)


# -- the model value ---------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs, match", [
    ({"pattern": "spiral"}, "pattern must be one of zigzag, .*, got 'spiral'"),
    ({"r0": -1.0}, r"r0_mm must be in \(0, 1000\), got -1"),
    ({"beta0": 90.0}, r"beta0_deg must be in \(0, 90\), got 90"),
    ({"df": 1.5}, r"inner_radius_mm must be in \[0, 1.5\), got 1.5"),
    ({"p0": -5.0}, r"p0_kpa must be in \[0, 1e\+06\), got -5"),
    ({"g": 0.0}, r"g_mpa must be in \(0, 100000\), got 0"),
    ({"tube_law": "thin"}, "tube_law must be one of paper, thick-wall, got 'thin'"),
    ({"tube_law": "thick-wall", "df": 0.0}, "inner_radius_mm must be > 0 with tube_law 'thick-wall'"),
])
def test_model_validation_one_line(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        raw(**kwargs)


def test_zigzag_beta0_must_be_zero():
    with pytest.raises(ParameterError, match="beta0_deg must be 0 for the zigzag"):
        ActuatorModel("zigzag", length_mm=100, r0_mm=2.5, beta0_deg=10.0, outer_radius_mm=1.5,
                      inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=1.0, p0_kpa=10.0)


def test_from_derived_takes_geometry_and_p0():
    d = derived("cross", 7.0, 45.0)
    m = ActuatorModel.from_derived(d, g_mpa=1.3, calibration="mine")
    x = d.r0_mm / 1.5  # the paper's tube law at r0 (docs/model.md section 3), G_e = 0.13 MPa
    assert (m.pattern, m.r0_mm, m.beta0_deg, m.calibration) == ("cross", d.r0_mm, d.beta0_deg, "mine")
    assert m.p0_kpa == pytest.approx(65.0 * (x - 1.0 / x) ** 2, rel=1e-12)
    assert ActuatorModel.from_derived(d, g_mpa=1.3, p0_kpa=170.0).p0_kpa == 170.0
    c = curve(m, [100.0, 300.0])
    assert c.calibration == "mine" and c.method == "stable-analytic-trace"


# -- the curve value ----------------------------------------------------------------------------
def test_curve_arrays_are_read_only_float64_and_json_safe():
    c = curve(model(), np.arange(0.0, 701.0, 50.0))
    arrays = [c.pressure_kpa, c.theta_deg, c.length_mm, c.radius_mm, c.beta_deg, c.inner_radius_mm]
    assert all(a.dtype == np.float64 and a.shape == (15,) and not a.flags.writeable for a in arrays)
    assert c.status.dtype == np.int8 and not c.status.flags.writeable
    d = c.as_dict()
    assert set(d) == {"pressure_kpa", "theta_deg", "status", "length_mm", "radius_mm", "beta_deg",
                      "inner_radius_mm", "method", "calibration"}
    # 700 kPa is past the fold (1888.8 deg), which lies far inside the coiled region
    assert d["status"][:3] == ["INFLATION", "INFLATION", "BENDING"] and d["status"][-1] == "COILED"
    json.dumps(d, allow_nan=False)


def test_inflation_phase_follows_the_tube_law():
    m = model(p0=85.0)
    p = np.array([0.0, 10.0, 50.0, 84.4])
    c = curve(m, p)
    assert np.all(c.status == Status.INFLATION) and np.all(c.theta_deg == 0.0)
    for pk, r in zip(p, c.radius_mm):  # the paper law at r gives back the pressure
        assert float(mpref.paper_law(r, 1.5, 0.13)) * 1000 == pytest.approx(pk, rel=1e-10, abs=1e-12)
    np.testing.assert_allclose(c.inner_radius_mm, np.sqrt(c.radius_mm**2 - 1.25), rtol=1e-14)
    assert np.all(c.length_mm == 100.0)


def test_inflation_radius_capped_by_the_sleeve_when_p0_is_given_higher():
    c = curve(model(p0=200.0), [150.0, 199.0])
    assert np.all(c.status == Status.INFLATION)
    np.testing.assert_allclose(c.radius_mm, derived().r0_mm, rtol=1e-15)


def test_bending_states_match_reference():
    c = curve(model(), [120.0, 250.0])
    assert np.all(c.status == Status.BENDING)
    with mp.workdps(60):
        for t, l, r, p in zip(c.theta_deg, c.length_mm, c.radius_mm, c.pressure_kpa):
            lr = ZIGZAG7.l_r(mp.radians(t))
            assert l == pytest.approx(float(lr[0]), rel=1e-14) and r == pytest.approx(float(lr[1]), rel=1e-14)
            assert float(ZIGZAG7.pressure(mp.radians(t))) * 1000 == pytest.approx(p, rel=1e-11)


def test_beyond_the_fold_is_unstable_at_the_fold_angle():
    """Zigzag w = 7 mm: P(theta) peaks (509.3 kPa at 1888.76 deg); higher pressures snap through.
    The formula's statuses (limits=False); with the validity limits all these states are coiled."""
    assert curve(model(), [505.0, 600.0, 1e4]).status.tolist() == [Status.COILED] * 3
    c = curve(model(), [505.0, 600.0, 1e4], limits=False)
    assert c.status.tolist() == [Status.BENDING, Status.UNSTABLE, Status.UNSTABLE]
    theta_fold, p_fold = lockup(model())
    assert c.theta_deg[1] == c.theta_deg[2] == pytest.approx(theta_fold, abs=1e-6)
    with mp.workdps(30):
        ref = mp.findroot(lambda x: mp.diff(ZIGZAG7.pressure, x), mp.radians(theta_fold))
        assert theta_fold == pytest.approx(float(mp.degrees(ref)), abs=1e-6)
        assert p_fold == pytest.approx(float(ZIGZAG7.pressure(ref)) * 1000, rel=1e-12)
        assert float(ZIGZAG7.pressure(mp.radians(c.theta_deg[0]))) * 1000 == pytest.approx(505.0, rel=1e-11)
    # just below the fold (between the last rising grid point and the fold): still answered
    near = curve(model(), [p_fold - 1e-3, p_fold * (1 - 1e-12)], limits=False)
    assert np.all(near.status == Status.BENDING) and np.all(near.theta_deg < theta_fold)
    with mp.workdps(30):
        for t, p in zip(near.theta_deg, near.pressure_kpa):
            assert float(ZIGZAG7.pressure(mp.radians(t))) * 1000 == pytest.approx(p, rel=1e-12)
    # P(theta) past the fold: real pressures, reported unstable
    back = pressure_at(model(), [1000.0, 2000.0, 2500.0], limits=False)
    assert back.status.tolist() == [Status.BENDING, Status.UNSTABLE, Status.UNSTABLE]
    with mp.workdps(30):
        assert back.pressure_kpa[2] == pytest.approx(float(ZIGZAG7.pressure(mp.radians(2500))) * 1000, rel=1e-11)


def test_root_finder_misses_the_branch_where_tracing_does_not():
    """Documented failure of per-pressure root finding on a non-monotone P(theta):
    505 kPa is reached twice before the cap (rising, then falling past the fold) and
    P(cap) < 505 kPa, so the bracket [0, cap] has no sign change."""
    trace = curve(model(), [505.0], method="stable-analytic-trace", limits=False)
    root = curve(model(), [505.0], method="stable-analytic-root", limits=False)
    assert trace.status[0] == Status.BENDING
    assert root.status[0] == Status.OUT_OF_DOMAIN and root.theta_deg[0] == C.MAX_BEND_DEG


def test_root_and_trace_agree_on_monotone_curves():
    m = model("cross", 7.0, 45.0, 1.3, 170.0)
    p = np.linspace(150, 400, 11)
    a = curve(m, p, method="stable-analytic-root")
    b = curve(m, p, method="stable-analytic-trace")
    np.testing.assert_allclose(a.theta_deg, b.theta_deg, rtol=1e-9, atol=1e-9)
    assert a.status.tolist() == b.status.tolist()


def test_exact_neutral_angle_is_locked_straight():
    m = raw(beta0=NEUTRAL_BETA0_DEG)
    c = curve(m, [100.0, 150.0, 151.0, 1e4])
    assert c.status.tolist() == [Status.INFLATION, Status.INFLATION, Status.LOCKED, Status.LOCKED]
    assert np.all(c.theta_deg == 0.0)
    assert lockup(m) == (0.0, math.inf)
    p = pressure_at(m, [0.0, 1.0, -1.0])
    assert p.status.tolist() == [Status.INFLATION, Status.LOCKED, Status.LOCKED]
    assert np.all(p.pressure_kpa == 150.0)


def test_cross_lock_up_angle_and_pole():
    m = model("cross", 7.0, 45.0, 1.3, 170.0)
    ref = mpref.Ref.cross(width_mm=7, angle_deg=45, g_mpa=1.3, p0_kpa=170)
    theta, p = lockup(m)
    assert p == math.inf
    assert theta == pytest.approx(float(mp.degrees(ref.lock_theta(-1))), rel=1e-12)
    # huge pressures approach the lock from the bending side, never beyond
    c = curve(m, [1e3, 1e5, 1e7], limits=False)
    assert np.all(c.status == Status.BENDING) and np.all(np.diff(c.theta_deg) < 0)
    gap = c.theta_deg - theta
    assert np.all(gap > 0)
    assert gap[1] / gap[2] == pytest.approx(100.0, rel=0.01)  # simple pole: P - P0 ~ 1/(theta - theta_lock)
    back = pressure_at(m, [theta + 1.0, theta, theta - 1.0, 10.0], limits=False)
    assert back.status.tolist() == [Status.BENDING, Status.LOCKED, Status.LOCKED, Status.OUT_OF_DOMAIN]
    assert np.all(back.pressure_kpa[1:] == 170.0)


def test_sleeve_too_narrow_is_refused():
    """r0 <= r_f: no sleeve, no inflation phase; the model refuses it instead of predicting a bend."""
    with pytest.raises(ValueError, match="r0_mm must be > outer_radius_mm=1.5 \\(no sleeve"):
        raw("zigzag", r0=1.0, p0=0.0)


def test_tracing_cap_gives_out_of_domain(monkeypatch):
    monkeypatch.setattr(C, "MAX_BEND_DEG", 90.0)
    m = model()
    p90 = float(ZIGZAG7.pressure(mp.radians(90))) * 1000
    c = curve(m, [p90 - 1.0, p90 + 1.0])
    assert c.status.tolist() == [Status.BENDING, Status.OUT_OF_DOMAIN]
    assert c.theta_deg[1] == 90.0
    assert lockup(m) == (90.0, pytest.approx(p90, rel=1e-12))
    assert pressure_at(m, [95.0]).status[0] == Status.OUT_OF_DOMAIN


def test_pressure_at_wrong_direction_and_zero():
    p = pressure_at(model(), [-5.0, 0.0, 5.0])
    assert p.status.tolist() == [Status.OUT_OF_DOMAIN, Status.INFLATION, Status.BENDING]
    assert p.pressure_kpa[0] == p.pressure_kpa[1] == 85.0
    assert p.pressure_kpa[2] > 85.0


# -- sweeps -----------------------------------------------------------------------------------
def test_sweep_matches_single_curves():
    models = [model(), model("cross", 7.0, 15.0, 2.9, 150.0), model("cross", 7.0, 60.0, 2.9, 200.0),
              raw(beta0=NEUTRAL_BETA0_DEG), model(w=5.0, g=0.8, p0=50.0)]
    p = np.linspace(0.0, 600.0, 31)
    s = sweep(models, p)
    assert s.theta_deg.shape == s.status.shape == (5, 31)
    for k, m in enumerate(models):
        c = curve(m, p)
        np.testing.assert_allclose(s.theta_deg[k], c.theta_deg, rtol=1e-12, atol=1e-12)
        assert s.status[k].tolist() == c.status.tolist()
        np.testing.assert_allclose(s.radius_mm[k], c.radius_mm, rtol=1e-12)  # two solves, each within rtol
    assert s.calibration == "given"
    d = s.as_dict()
    assert len(d["status"]) == 5 and len(d["status"][0]) == 31
    json.dumps(d, allow_nan=False)


def test_sweep_mixed_tube_laws():
    models = [model(), model(tube_law="thick-wall", p0=None)]
    s = sweep(models, [20.0, 40.0])
    assert np.all(s.status == Status.INFLATION)
    for k, p in enumerate((20.0, 40.0)):
        assert float(mpref.paper_law(s.radius_mm[0, k], 1.5, 0.13)) * 1000 == pytest.approx(p, rel=1e-10)
        assert float(mpref.thick_wall_law(s.radius_mm[1, k], 1.5, 1.0, 0.13)) * 1000 == pytest.approx(p, rel=1e-10)


# -- input validation -------------------------------------------------------------------------
@pytest.mark.parametrize("pressures, match", [
    ([-1.0], r"pressure_kpa must be finite numbers in \[0, inf\], got -1"),
    ([float("nan")], "pressure_kpa must be finite numbers"),
    ([[1.0, 2.0]], "pressure_kpa must be a number or a 1-D sequence"),
])
def test_pressure_validation(pressures, match):
    with pytest.raises(ParameterError, match=match):
        curve(model(), pressures)


def test_other_validation():
    with pytest.raises(ParameterError, match="models must be a non-empty sequence of ActuatorModel"):
        sweep([], [1.0])
    with pytest.raises(ParameterError, match="theta_deg must be finite numbers"):
        pressure_at(model(), [float("inf")])
    with pytest.raises(ParameterError, match=r"theta_deg must be finite numbers in \[-1e\+06, 1e\+06\], got 2e\+06"):
        pressure_at(model(), [2e6])
    with pytest.raises(ParameterError, match=r"rtol must be in \(0, 1\)"):
        curve(model(), [1.0], rtol=0.0)


def test_import_does_not_load_scipy():
    code = ("import sys, embroact.predict.curve, embroact.predict.tubelaws; "
            "from embroact.predict.curve import ActuatorModel, curve; "
            "m = ActuatorModel('zigzag', length_mm=100, r0_mm=2.58, beta0_deg=0, outer_radius_mm=1.5, "
            "inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85); curve(m, [0, 100, 200]); "
            "assert 'scipy' not in sys.modules, 'scipy imported'")
    subprocess.run([sys.executable, "-c", code], check=True)


# -- never NaN ----------------------------------------------------------------------------------
designs = st.builds(  # r0 > r_f: a model needs a sleeve (ActuatorModel refuses r0 <= r_f)
    lambda pattern, ratio, beta0, g, p0, rf, wall, l0, law: raw(
        pattern, r0=rf * ratio, beta0=beta0, g=g, p0=p0, rf=rf, df=rf * (1 - wall), l0=l0, tube_law=law),
    pattern=st.sampled_from(["zigzag", "cross"]),
    ratio=st.floats(1.001, 5.0), beta0=st.floats(0.5, 89.0), g=st.floats(0.05, 50.0),
    p0=st.floats(0.0, 400.0, allow_subnormal=False),  # a subnormal P0 is refused (check_range)
    rf=st.floats(0.5, 3.0), wall=st.floats(0.05, 0.95), l0=st.floats(10.0, 500.0),
    law=st.sampled_from(["paper", "thick-wall"]),
)


@settings(max_examples=40, deadline=None)
@given(m=designs, pressures=st.lists(st.floats(0.0, 5000.0), min_size=1, max_size=8),
       angles=st.lists(st.floats(-1e6, 1e6), min_size=1, max_size=8))
def test_never_nan(m, pressures, angles):
    c = curve(m, pressures)
    p = pressure_at(m, angles)
    for res in (c, p):
        for k in ("pressure_kpa", "theta_deg", "length_mm", "radius_mm", "beta_deg", "inner_radius_mm"):
            assert np.all(np.isfinite(getattr(res, k))), (k, res)
        assert set(res.status.tolist()) <= {int(s) for s in Status}
    bent = c.status == Status.BENDING
    if bent.any():  # every answered angle holds its pressure
        back = pressure_at(m, c.theta_deg[bent])
        np.testing.assert_allclose(back.pressure_kpa, c.pressure_kpa[bent], rtol=1e-9, atol=1e-9)


def test_the_float_paths_method_check_is_what_auto_resolves_to():
    """The float path serves "auto" from the fast method's accuracy up (ACCURACY's first entry, so "auto"
    resolves to it there) and the fast method by name; curve() gives the same bits either way."""
    assert next(iter(C.ACCURACY)) == C._FAST[:2]
    for rtol in (C._FAST_RTOL, 1e-10, 1e-3, 0.5):
        assert C._resolve("auto", rtol) == C._FAST
    m = ActuatorModel("cross", length_mm=100, r0_mm=2.6, beta0_deg=20.0, outer_radius_mm=1.5, inner_radius_mm=1.0,
                      g_e_mpa=0.13, g_mpa=1.3, p0_kpa=170)
    one = curve(m, [230.0], rtol=1e-9)
    named = curve(m, [230.0], method=C._FAST_NAME, rtol=1e-9)
    arrays = curve(m, np.array([0.0, 230.0, 240.0]), rtol=1e-9)
    assert one.theta_deg[0] == named.theta_deg[0] == arrays.theta_deg[1]
    with pytest.raises(ParameterError, match="rtol"):
        curve(m, [230.0], rtol=1.5)
    with pytest.raises(ParameterError, match="rtol"):
        curve(m, [230.0], rtol=1e-13)


def test_a_models_kept_hash_is_its_fields_hash_and_pickles_as_its_fields(tmp_path):
    """The model's hash, computed once, is the hash of its fields (equal models, also 100 and 100.0 or -0.0 and
    0.0, hash alike); unpickled in a process that hashes strings differently, it hashes as that process's own."""
    import dataclasses
    import pickle

    m = ActuatorModel("cross", length_mm=100, r0_mm=2.6, beta0_deg=20.0, outer_radius_mm=1.5, inner_radius_mm=1.0,
                      g_e_mpa=0.13, g_mpa=1.3, p0_kpa=170)
    same = dataclasses.replace(m, length_mm=100.0, p0_kpa=170.0)
    assert same == m and hash(same) == hash(m) and {m: 1}[same] == 1
    assert hash(dataclasses.replace(m, calibration="fit")) != hash(m)
    zero = dataclasses.replace(m, pattern="zigzag", beta0_deg=-0.0)
    assert hash(zero) == hash(dataclasses.replace(m, pattern="zigzag", beta0_deg=0.0))
    path = tmp_path / "m.pickle"
    path.write_bytes(pickle.dumps(m))
    code = ("import pickle, sys; from embroact.predict.curve import ActuatorModel; "
            f"m = pickle.loads(open({str(path)!r}, 'rb').read()); "
            "f = ActuatorModel('cross', length_mm=100, r0_mm=2.6, beta0_deg=20.0, outer_radius_mm=1.5, "
            "inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=1.3, p0_kpa=170); "
            "sys.exit(0 if m == f and hash(m) == hash(f) and {f: 1}[m] == 1 else 1)")
    for seed in ("1", "2"):
        run = subprocess.run([sys.executable, "-c", code], env={**os.environ, "PYTHONHASHSEED": seed},
                             capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
