"""A simulated calibration round: measurements generated from a known profile (G and P0 varying along
width and angle, 2 deg reading noise as in the band tests) -> ``embroact fit --sheet`` of the whole sheet
-> the profile recovers the true G and P0 within its standard errors, reports leave-one-out errors,
flags a coupon that disagrees, and works as a calibration for predict and design.

The measurements come from neither the fit nor the model code: the bend is the 50-digit reference of
docs/model.md (tests/mpref.py, ``Ref.bend_deg``) and the layout's reading the turning between the first
and last marker chord on that bend, by hand (tests/markerdata.py).
"""
import csv
import functools
import json
import math

import mpref
import numpy as np
import pytest

from markerdata import chord_turning_deg
from embroact.export.cli.main import main
from embroact.export.files.designfile import load_design
from embroact.predict.analysis import analyse

SIGMA_DEG = 2.0
MARKERS_MM = 10.0 * np.arange(11)  # the coupon's layout, by hand: 11 markers 10 mm apart from the clamp


def true_g_p0(pattern, width_mm, angle_deg):
    """The known profile: smooth in the width (zigzag) and in the angle (cross)."""
    if pattern == "zigzag":
        return 3.0 + 0.4 * (width_mm - 7.0), 40.0 + 25.0 * (width_mm - 5.0)
    return 2.0 + 0.03 * abs(angle_deg - 33.4), 90.0 + 1.0 * angle_deg


@functools.lru_cache(maxsize=None)
def true_bend_deg(pattern, width_mm, angle_deg, length_mm, pressures_kpa, g_factor=1.0):
    """The reference theta [deg] at each pressure of the design with the known profile's G (times ``g_factor``)."""
    g, p0 = true_g_p0(pattern, width_mm, angle_deg)
    kw = dict(width_mm=width_mm, g_mpa=g * g_factor, p0_kpa=p0, l0=length_mm)
    ref = mpref.Ref.zigzag(**kw) if pattern == "zigzag" else mpref.Ref.cross(angle_deg=angle_deg, **kw)
    return np.array(ref.bend_deg(pressures_kpa))


def true_reading_deg(d, pressures_kpa, g_factor=1.0):
    """What the coupon's marker layout reads on the reference bend of the sewn design ``d``."""
    theta = true_bend_deg(d.pattern, d.requested_width_mm, d.requested_angle_deg if d.pattern == "cross" else 0.0,
                          d.length_mm, tuple(pressures_kpa), g_factor)
    return np.array([chord_turning_deg(t, MARKERS_MM, d.length_mm) for t in theta])


@pytest.fixture(scope="module")
def coupon(tmp_path_factory):
    out = tmp_path_factory.mktemp("coupon")
    assert main(["calibrate", "coupon", "--out", str(out)]) == 0
    return out


@functools.lru_cache(maxsize=None)
def _sewn(design_path):
    """Each actuator's derived values in a coupon's design file, by name (the files of a coupon never change,
    so the 100 rounds of the band test analyse them once)."""
    return {a.name: a.derived for a in analyse(load_design(design_path)).actuators}


def _simulate(coupon, seed, spoil=None):
    with open(coupon / "measurements.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    derived = {}
    for r in rows:
        key = (r["design"], r["actuator"])
        if key not in derived:
            derived[key] = _sewn(coupon / r["design"])[r["actuator"]]
    rng = np.random.default_rng(seed)
    truth = {}
    for key, d in derived.items():
        g, p0 = true_g_p0(d.pattern, d.requested_width_mm, d.requested_angle_deg)
        factor = 1.8 if key[1] == spoil else 1.0
        truth[key[1]] = (g * factor, p0)
        mine = [r for r in rows if (r["design"], r["actuator"]) == key]
        p = [float(r["pressure_kpa"]) for r in mine]
        bend = true_reading_deg(d, p, factor) + rng.normal(0.0, SIGMA_DEG, len(p))
        for r, b in zip(mine, bend):
            r["bend_deg"] = f"{b:.4f}"
    path = coupon / f"filled-{seed}-{spoil}.csv"
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    return path, truth


def test_round_recovers_the_known_profile(coupon, tmp_path, capsys):
    sheet, truth = _simulate(coupon, seed=7)
    prof = tmp_path / "mine.toml"
    assert main(["fit", "--sheet", str(sheet), "-o", str(prof), "--material", "tube=silicone 3x2", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    z = []
    for c in doc["coupons"]:
        g, p0 = truth[c["name"]]
        assert [f["branch"] for f in c["fits"]] == ["loading", "unloading"]
        for f in c["fits"]:
            z += [(f["g_mpa"] - g) / f["g_mpa_se"], (f["p0_kpa"] - p0) / f["p0_kpa_se"]]
    z = np.abs(np.array(z))
    assert len(doc["coupons"]) == len(truth) and len(z) == len(truth) * 2 * 2  # every strip sewn, both branches fitted
    # standard errors that mean what they say: ~95 % within 2 se, none beyond 3.5
    assert np.mean(z <= 2.0) >= 0.85 and z.max() < 3.5, np.round(z, 2)
    loo = [c["leave_one_out_rmse_deg"] for c in doc["coupons"]]
    assert all(v is not None and v > 0 for v in loo)
    assert not any(c["flagged"] for c in doc["coupons"])
    # the profile is a calibration: predict takes it, without the demonstration note
    assert main(["predict", "zigzag", "--width-mm", "6", "--calibration", str(prof), "--pressure-kpa", "200",
                 "--json"]) == 0
    out = capsys.readouterr()
    assert "demonstration" not in out.err
    p = json.loads(out.out)
    text = prof.read_text()
    assert 'tube = "silicone 3x2"' in text and "marker_layout" in text and "covariance" in text
    g6, _ = true_g_p0("zigzag", 6.0, 0.0)
    assert json.dumps(p).count("calibration mine") >= 1 or "mine" in json.dumps(p)
    assert math.isfinite(g6)


@pytest.mark.parametrize("spoil", ["03 zigzag w7.0", "01 zigzag w5.0", "02 zigzag w6.0", "08 cross a26.6 w7.0",
                                   "09 cross a38.7 w7.0", "10 cross a45.0 w7.0", "11 cross a52.4 w7.0"])
def test_a_disagreeing_coupon_is_flagged(coupon, capsys, spoil):
    """One coupon's G 1.8 times the profile's: it is the one flagged, not its neighbour, whether it is
    interior, next to an end (whose extrapolation through it reads twice its error), at an end, or next
    to the cross pattern's neutral angle (33.4 deg, where the known profile has a kink)."""
    sheet, _ = _simulate(coupon, seed=8, spoil=spoil)
    assert main(["fit", "--sheet", str(sheet)]) == 0
    out = capsys.readouterr().out
    flagged = [line for line in out.splitlines() if line.startswith("disagrees:")]
    assert len(flagged) == 1 and spoil in flagged[0], out
    assert "unresolved:" not in out


def test_three_coupons_cannot_tell_which_one_disagrees(tmp_path, capsys):
    """A trend through two of three coupons predicts the third as badly whichever is off: the pattern is
    reported as disagreeing, no coupon is blamed."""
    assert main(["calibrate", "coupon", "--patterns", "zigzag", "--width-count", "3", "--out", str(tmp_path)]) == 0
    capsys.readouterr()
    sheet, truth = _simulate(tmp_path, seed=3, spoil="02 zigzag w7.0")
    assert main(["fit", "--sheet", str(sheet), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert not any(c["flagged"] for c in doc["coupons"]) and [u["pattern"] for u in doc["unexplained"]] == ["zigzag"]
    assert main(["fit", "--sheet", str(sheet)]) == 0
    (line,) = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("unresolved:")]
    assert "zigzag" in line and "at least 4" in line


#: Seeds of the band-coverage round, and the probability that a normal deviate lies within 1 sigma.
ROUNDS = 100
ONE_SIGMA = math.erf(1.0 / math.sqrt(2.0))


@pytest.mark.slow
def test_design_with_a_profile_meets_targets_inside_its_band_about_68_percent(tmp_path_factory, capsys):
    """ROUNDS seeded calibration rounds of the zigzag coupon (both branches measured, 2 deg noise) ->
    ``fit --sheet`` -> ``design`` for a target the true profile reaches (a width drawn inside the
    coupon's range, away from its ends, at a pressure drawn in 150-220 kPa); the reference bend of the
    designed width with the true profile lies within the reported 1-sigma band in ONE_SIGMA of the
    rounds. Each round is an independent Bernoulli trial, so the count is Binomial(ROUNDS, 0.6827):
    the test accepts its central 99 % (56-80 of 100), which an under-covering band (the 48-56 %
    seen while the lookup snapped a design within 1 % of a coupon's width to that coupon) fails."""
    from scipy.stats import binom

    out = tmp_path_factory.mktemp("zig")
    assert main(["calibrate", "coupon", "--patterns", "zigzag", "--out", str(out)]) == 0
    capsys.readouterr()
    inside, zs = 0, []
    for seed in range(ROUNDS):
        sheet, _ = _simulate(out, seed=100 + seed)
        cal = out / "prof.toml"
        assert main(["fit", "--sheet", str(sheet), "-o", str(cal)]) == 0
        rng = np.random.default_rng(1000 + seed)
        width, at = round(float(rng.uniform(5.4, 8.6)), 3), round(float(rng.uniform(150.0, 220.0)), 3)
        (target,) = true_bend_deg("zigzag", width, 0.0, 100.0, (at,))
        design = out / f"d{seed}.toml"
        capsys.readouterr()
        assert main(["design", "--bend-deg", f"{target:.3f}", "--at-kpa", f"{at}", "--pattern", "zigzag",
                     "--tolerance-deg", "3", "--calibration", str(cal), "-o", str(design), "--json"]) == 0
        best = json.loads(capsys.readouterr().out)["best"]
        assert best["theta_sd_deg"] is not None and best["theta_sd_deg"] > 0
        (a,) = analyse(load_design(design)).actuators
        (true,) = true_bend_deg("zigzag", a.derived.requested_width_mm, 0.0, a.derived.length_mm, (at,))
        zs.append((true - best["theta_deg"]) / best["theta_sd_deg"])
        inside += abs(zs[-1]) <= 1.0
    low, high = binom.ppf([0.005, 0.995], ROUNDS, ONE_SIGMA)
    print(f"true bend inside the reported 1-sigma band: {inside} of {ROUNDS} (accepted {low:.0f}-{high:.0f}); "
          f"sd of (true - predicted) / band: {np.std(zs):.2f}")
    assert low <= inside <= high, (inside, np.round(zs, 2))
