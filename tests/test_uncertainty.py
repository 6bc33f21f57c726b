"""Uncertainty bands (predict/uncertainty.py): derivatives against brute-force refits of the curve,
and coverage of a fitted set's 1-sigma band by simulation."""
import dataclasses

import numpy as np
import pytest

from embroact.patterns.base.errors import ParameterError
from embroact.patterns.params import Tube
from embroact.predict.curve import ActuatorModel, curve
from embroact.predict.derived import derive_from_values
from embroact.predict.fit import fit_design
from embroact.predict.markers import PAPER_LAYOUT, reading_deg
from embroact.predict.status import Status
from embroact.predict.tubelaws import transition_pressure_kpa
from embroact.predict.uncertainty import fit_band, theta_band

DESIGN = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
TRUE = ActuatorModel.from_derived(DESIGN, g_mpa=2.7, p0_kpa=85.0)


def _theta(model, p, **change):
    return np.asarray(curve(dataclasses.replace(model, **change), p).theta_deg)


@pytest.mark.parametrize("m", [TRUE, ActuatorModel.from_derived(
    derive_from_values("cross", width_mm=7.0, interval_mm=1.4, angle_deg=45.0, length_mm=100.0, tube=Tube()),
    g_mpa=1.3, p0_kpa=170.0)])
def test_band_is_the_linear_propagation_of_brute_force_sensitivities(m):
    """J from central differences of whole curves at perturbed G and P0 (not the slope formula)."""
    p = np.array([m.p0_kpa + 20.0, m.p0_kpa + 80.0, m.p0_kpa + 150.0])
    hg, hp = 1e-5 * m.g_mpa, 1e-4
    dg = (_theta(m, p, g_mpa=m.g_mpa + hg) - _theta(m, p, g_mpa=m.g_mpa - hg)) / (2 * hg)
    dp = (_theta(m, p, p0_kpa=m.p0_kpa + hp) - _theta(m, p, p0_kpa=m.p0_kpa - hp)) / (2 * hp)
    cov = np.array([[0.04, -0.5], [-0.5, 9.0]])
    want = np.sqrt(dg**2 * cov[0, 0] + 2 * dg * dp * cov[0, 1] + dp**2 * cov[1, 1])
    b = theta_band(m, p, ("g_mpa", "p0_kpa"), cov)
    np.testing.assert_allclose(b.theta_sd_deg, want, rtol=1e-5)
    np.testing.assert_allclose(b.theta_high_deg - b.theta_low_deg, 2 * want, rtol=1e-5)
    # the order of the parameters follows the names
    b2 = theta_band(m, p, ("p0_kpa", "g_mpa"), cov[::-1, ::-1])
    np.testing.assert_allclose(b2.theta_sd_deg, b.theta_sd_deg, rtol=1e-12)


def test_g_e_band_acts_through_p0_from_the_tube_law():
    p = np.array([120.0, 200.0])
    m = ActuatorModel.from_derived(DESIGN, g_mpa=2.7)  # P0 from the paper law at r0 (84.45 kPa)
    h = 1e-6
    ge = m.g_e_mpa
    p0 = lambda g: float(transition_pressure_kpa(DESIGN.r0_mm, DESIGN.tube, "paper")) * g / ge  # noqa: E731  (P0 proportional to G_e)
    d = (_theta(m, p, g_e_mpa=ge + h, p0_kpa=p0(ge + h)) - _theta(m, p, g_e_mpa=ge - h, p0_kpa=p0(ge - h))) / (2 * h)
    b = theta_band(m, p, ("g_e_mpa",), [[1e-4]])
    np.testing.assert_allclose(b.theta_sd_deg, np.abs(d) * 1e-2, rtol=1e-5)


def test_band_statuses_and_marker_reading():
    b = theta_band(TRUE, [0.0, 50.0, 200.0, 700.0], ("g_mpa", "p0_kpa"), np.diag([0.01, 4.0]),
                   measurement=PAPER_LAYOUT, noise_sd_deg=1.5)
    assert b.theta_sd_deg[0] == b.theta_sd_deg[1] == 0.0  # inflation: theta = 0 does not move
    assert b.status[3] == Status.COILED and b.theta_sd_deg[3] == 0.0  # past the fold: the fold angle, a fill
    np.testing.assert_allclose(b.reading_deg, reading_deg(b.theta_deg, 100.0), rtol=1e-12)
    np.testing.assert_allclose(b.reading_sd_deg[2], 0.5 * b.theta_sd_deg[2], rtol=1e-6)  # all markers on the arc
    assert b.prediction_sd_deg()[2] == pytest.approx(np.hypot(b.reading_sd_deg[2], 1.5), rel=1e-12)
    d = b.as_dict()
    assert d["status"][0] == "INFLATION" and d["parameters"] == ["g_mpa", "p0_kpa"] and len(d["reading_sd_deg"]) == 4


def test_band_input_is_validated():
    for params, cov, match in [(("g_mpa", "q"), np.eye(2), "parameters must be distinct names"),
                               (("p0_kpa", "g_e_mpa"), np.eye(2), "cannot hold both"),
                               (("g_mpa",), np.eye(2), "symmetric 1 x 1"),
                               (("g_mpa", "p0_kpa"), [[1.0, 2.0], [2.0, 1.0]], "positive semi-definite")]:
        with pytest.raises(ParameterError, match=match):
            theta_band(TRUE, [100.0], params, cov)
    with pytest.raises(ParameterError, match="noise_sd_deg must be"):
        theta_band(TRUE, [100.0], ("g_mpa",), [[0.01]], noise_sd_deg=-1.0)


# ----------------------------------------------------------------------------- coverage by simulation
FIT_P = np.arange(0.0, 301.0, 20.0)
HELD_P = np.arange(110.0, 300.0, 20.0)  # between the fitted pressures, in the bending phase
SIGMA_DEG = 2.0


def _coverage(seeds, measurement=None):
    truth = _theta(TRUE, HELD_P)
    seen_fit = _theta(TRUE, FIT_P)
    seen_held = truth
    if measurement is not None:
        seen_fit, seen_held = reading_deg(seen_fit, 100.0, measurement), reading_deg(truth, 100.0, measurement)
    inside = inside_new = 0
    for seed in seeds:
        rng = np.random.default_rng(seed)
        data = seen_fit + rng.normal(0.0, SIGMA_DEG, FIT_P.size)
        (r,) = fit_design(DESIGN, FIT_P, data, branch="loading", measurement=measurement)
        b = fit_band(DESIGN, r, HELD_P, prediction=True)
        centre, sd = (b.theta_deg, b.theta_sd_deg) if measurement is None else (b.reading_deg, b.reading_sd_deg)
        inside += int(np.count_nonzero(np.abs(seen_held - centre) <= sd))
        new = seen_held + rng.normal(0.0, SIGMA_DEG, HELD_P.size)
        inside_new += int(np.count_nonzero(np.abs(new - centre) <= b.prediction_sd_deg()))
    n = len(seeds) * HELD_P.size
    return inside / n, inside_new / n


def test_one_sigma_band_covers_about_68_percent_of_held_out_points_over_50_seeds():
    """A fitted set's band against the true curve at held-out pressures, and its prediction band
    against new noisy measurements there (2 deg noise, G and P0 fitted on 16 points)."""
    curve_cover, new_cover = _coverage(range(50))
    assert 0.60 <= curve_cover <= 0.76, curve_cover
    assert 0.60 <= new_cover <= 0.76, new_cover


def test_marker_reading_band_covers_the_true_reading():
    curve_cover, new_cover = _coverage(range(100, 130), measurement=PAPER_LAYOUT)  # 30 seeds: wider bounds
    assert 0.55 <= curve_cover <= 0.81 and 0.55 <= new_cover <= 0.81, (curve_cover, new_cover)
