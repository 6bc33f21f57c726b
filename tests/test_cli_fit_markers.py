"""``embroact fit --markers`` end to end: marker frames made by hand, fitted, then predicted with.

The frames are the paper's layout (2 rows of 7 markers 10 mm apart, tests/markerdata.py) on
the paper's zigzag (w = 7 mm) bent uniformly by the model's theta at known G and P0, asked
of ``embroact predict`` with those values. The marker sum of such a frame reads the bend
between the first and last chord middles (half of theta here), so a fit that compares the
data with the layout's reading must give G and P0 back within the uncertainty it reports;
the old comparison with theta overestimated G by 77 % or more. The written calibration
file then gives ``embroact predict`` a 1-sigma band, checked against a finite-difference
propagation of the file's covariance through ``predict`` at shifted parameters.
"""
import json
import math
import tomllib

import numpy as np
import pytest

from markerdata import chord_turning_deg, paper_frame
from embroact.export.cli.main import main

ZIGZAG = ["zigzag", "--width-mm", "7"]
CROSS45 = ["cross", "--width-mm", "7", "--angle-deg", "45", "--interval-mm", "1.4"]
G_MPA, P0_KPA = 2.7, 85.0
UP = [float(p) for p in range(0, 301, 10)]


def _json(capsys, *argv):
    assert main(list(argv)) == 0, capsys.readouterr().err
    doc = json.loads(capsys.readouterr().out)
    if argv[0] == "predict" and doc.get("design") == "quick":  # quick parameters: one actuator of the design schema
        (doc,) = doc["actuators"]
    return doc


def _predicted(capsys, design, g_mpa, p0_kpa, pressures):
    """(theta [deg], l0 [mm]) of the generated design, as ``embroact predict`` gives them."""
    grid = ",".join(f"{p:g}" for p in pressures)
    doc = _json(capsys, "predict", *design, "--g-mpa", repr(g_mpa), "--p0-kpa", repr(p0_kpa),
                "--pressure-kpa", grid, "--json")
    return np.array(doc["theta_deg"]), doc["derived"]["length_mm"]


def _theta(capsys, design, g_mpa, p0_kpa, pressures):
    return _predicted(capsys, design, g_mpa, p0_kpa, pressures)[0]


def _marker_csv(path, pressures, frames):
    cols = ",".join(f"m{i}_{a}" for i in range(1, 15) for a in "xyz")
    rows = [f"{p:g}," + ",".join(repr(float(v)) for v in f.ravel()) for p, f in zip(pressures, frames)]
    path.write_text(f"pressure_kpa,{cols}\n" + "\n".join(rows) + "\n")
    return str(path)


def _frames(theta, sigma_mm=0.0, seed=0, offset=0.0, rot=np.eye(3), l0=100.0):
    frames = np.stack([paper_frame(t, offset=offset, rot=rot, l0=l0) for t in theta])
    return frames + np.random.default_rng(seed).normal(0.0, sigma_mm, frames.shape)


def _fit(capsys, data, design, *flags):
    return _json(capsys, "fit", data, "--pattern", design[0], *design[1:], "--branch", "loading", *flags, "--json")


def test_clean_markers_recover_g_and_p0_and_the_old_comparison_was_biased(capsys, tmp_path):
    theta = _theta(capsys, ZIGZAG, G_MPA, P0_KPA, UP)
    data = _marker_csv(tmp_path / "m.csv", UP, _frames(theta))
    doc = _fit(capsys, data, ZIGZAG, "--markers", "--normal", "0,1,0")
    (f,) = doc["fits"]
    assert f["measurement"] == {"markers_per_side": 7, "spacing_mm": 10.0, "offset_mm": 0.0, "rows": 2,
                                "side": "fabric"}
    # clean data: the fit is exact to the model's solver tolerance, and says so
    assert abs(f["g_mpa"] - G_MPA) <= 3 * f["g_mpa_se"] + 1e-7 and f["g_mpa_se"] < 1e-5
    assert abs(f["p0_kpa"] - P0_KPA) <= 3 * f["p0_kpa_se"] + 1e-5 and f["p0_kpa_se"] < 1e-3
    # the marker sums read half of theta: every marker lies on the bent 100 mm, 50 mm between chord middles
    assert np.allclose(f["angle_deg"], 0.5 * theta, atol=1e-9)

    # the same marker sums as an angle CSV: --measurement markers agrees with --markers ...
    angles = tmp_path / "a.csv"
    angles.write_text("pressure_kpa,angle_deg\n" + "".join(f"{p:g},{a!r}\n" for p, a in zip(UP, f["angle_deg"])))
    (same,) = _fit(capsys, str(angles), ZIGZAG, "--measurement", "markers")["fits"]
    assert same["g_mpa"] == pytest.approx(f["g_mpa"], rel=1e-9) and same["p0_kpa"] == pytest.approx(f["p0_kpa"], rel=1e-9)
    # ... and taken for whole-strip angles they give the old, biased answer
    (naive,) = _fit(capsys, str(angles), ZIGZAG)["fits"]
    assert naive["g_mpa"] > 1.5 * G_MPA and naive["measurement"] == "whole-strip"


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_noisy_markers_recover_g_and_p0_within_three_standard_errors(capsys, tmp_path, seed):
    """0.2 mm noise on every coordinate, the rig turned at random (the fit's frame is the markers')."""
    q, _ = np.linalg.qr(np.random.default_rng(50 + seed).normal(size=(3, 3)))
    rot = q * np.sign(np.linalg.det(q))
    theta = _theta(capsys, ZIGZAG, G_MPA, P0_KPA, UP)
    data = _marker_csv(tmp_path / "m.csv", UP, _frames(theta, 0.2, seed, rot=rot))
    normal = ",".join(repr(float(v)) for v in rot @ [0.0, 1.0, 0.0])
    doc = _fit(capsys, data, ZIGZAG, "--markers", f"--normal={normal}")
    (f,) = doc["fits"]
    assert abs(f["g_mpa"] - G_MPA) < 3 * f["g_mpa_se"] and abs(f["p0_kpa"] - P0_KPA) < 3 * f["p0_kpa_se"], f
    assert f["g_mpa_se"] < 0.05 * G_MPA  # the uncertainty is small: no bias hidden in it
    assert "coordinate noise 0.2 mm" in doc["note"]  # the noise the markers show, estimated from their scatter


@pytest.mark.parametrize("design, g_mpa, p0_kpa, top_kpa", [(ZIGZAG, 1.2, 85.0, 200.0), (CROSS45, 0.25, 170.0, 300.0)])
def test_large_bends_read_with_the_right_sign(capsys, tmp_path, design, g_mpa, p0_kpa, top_kpa):
    """The zigzag bends 314 deg, the cross -231 deg; markers from 35 to 95 mm, so the first chord
    turns past 90 deg (the zigzag's by 126 deg) and the last one past 180 deg. The cross as
    generated is 99.4 mm long: its marker sum reads 50/99.4 of theta."""
    pressures = [float(p) for p in np.arange(0.0, top_kpa + 1.0, 10.0)]
    theta, l0 = _predicted(capsys, design, g_mpa, p0_kpa, pressures)
    assert abs(theta[-1]) > 230.0 and np.sign(theta[-1]) == (1 if design is ZIGZAG else -1)
    data = _marker_csv(tmp_path / "m.csv", pressures, _frames(theta, offset=35.0, l0=l0))
    (f,) = _fit(capsys, data, design, "--markers", "--marker-offset-mm", "35", "--normal", "0,1,0",
                "--tangent", "1,0,0")["fits"]
    assert np.all(np.sign(f["angle_deg"]) * np.sign(theta[-1]) >= 0.0)  # every frame on the bend's side
    assert np.allclose(f["angle_deg"], 50.0 / l0 * theta, atol=1e-9)  # all markers on the bent length
    assert f["g_mpa"] == pytest.approx(g_mpa, rel=1e-6) and f["p0_kpa"] == pytest.approx(p0_kpa, rel=1e-6)


def test_written_calibration_gives_predict_a_band_matching_finite_differences(capsys, tmp_path):
    theta = _theta(capsys, ZIGZAG, G_MPA, P0_KPA, UP)
    data = _marker_csv(tmp_path / "m.csv", UP, _frames(theta, 0.2, 7))
    cal = tmp_path / "lab.toml"
    assert main(["fit", data, "--pattern", "zigzag", "--width-mm", "7", "--branch", "loading", "--markers",
                 "--normal", "0,1,0", "-o", str(cal)]) == 0
    capsys.readouterr()
    raw = tomllib.loads(cal.read_text())  # the file as written, read without embroact
    assert raw["marker_layout"] == {"markers_per_side": 7, "spacing_mm": 10.0, "offset_mm": 0.0, "rows": 2,
                                    "side": "fabric"}
    assert raw["tube_law"] == "paper" and raw["measurement"].startswith("markers: 2 rows of 7, 10 mm apart")
    (point,) = raw["points"]
    assert point["fitted"] == ["g_mpa", "p0_kpa"] and point["tube_law_parameters"] == {
        "outer_radius_mm": 1.5, "g_e_mpa": 0.13}
    cov = np.array(point["covariance"])
    assert cov.shape == (2, 2) and math.sqrt(cov[0, 0]) == pytest.approx(point["g_mpa_se"], rel=1e-12)

    pressures = [100.0, 150.0, 200.0, 250.0]
    grid = ",".join(f"{p:g}" for p in pressures)
    doc = _json(capsys, "predict", *ZIGZAG, "--calibration", str(cal), "--pressure-kpa", grid, "--json")
    band = doc["band"]
    assert band["parameters"] == ["g_mpa", "p0_kpa"] and np.allclose(band["covariance"], cov, rtol=1e-12)
    # independent propagation: central differences of predict's theta at shifted G and P0
    g, p0 = point["g_mpa"], point["p0_kpa"]
    jac = []
    for k, (name, value) in enumerate((("g", g), ("p0", p0))):
        h = 1e-4 * value
        shifted = [(g + s * h, p0) if k == 0 else (g, p0 + s * h) for s in (1, -1)]
        hi, lo = (_theta(capsys, ZIGZAG, gg, pp, pressures) for gg, pp in shifted)
        jac.append((hi - lo) / (2 * h))
    jac = np.array(jac).T  # (pressures, 2)
    sd = np.sqrt(np.einsum("pi,ij,pj->p", jac, cov, jac))
    assert np.allclose(band["theta_sd_deg"], sd, rtol=1e-4), (band["theta_sd_deg"], sd)
    assert np.allclose(np.subtract(band["theta_high_deg"], band["theta_low_deg"]), 2 * sd, rtol=1e-4)
    assert 0.1 < min(sd) and max(sd) < 3.0  # a band worth drawing: tenths of a degree to a few degrees
    # the table says it too
    assert main(["predict", *ZIGZAG, "--calibration", str(cal), "--pressure-kpa", grid]) == 0
    line = capsys.readouterr().out.splitlines()[1]
    assert line.startswith("1-sigma band of theta from the calibration's covariance: 100 kPa +-")


def test_thick_wall_fit_records_mu(capsys, tmp_path):
    """--tube-law thick-wall fits mu (as g_e) with P0 from that law; the file records the law and mu."""
    theta = _theta(capsys, ZIGZAG, G_MPA, P0_KPA, UP)
    angles = tmp_path / "a.csv"
    angles.write_text("pressure_kpa,angle_deg\n" + "".join(f"{p:g},{float(t)!r}\n" for p, t in zip(UP, theta)))
    cal = tmp_path / "thick.toml"
    assert main(["fit", str(angles), "--pattern", "zigzag", "--width-mm", "7", "--branch", "loading",
                 "--tube-law", "thick-wall", "--fit", "g,mu", "-o", str(cal)]) == 0
    out = capsys.readouterr().out
    assert "mu = " in out and "(tube law thick-wall)" in out
    raw = tomllib.loads(cal.read_text())
    (point,) = raw["points"]
    assert raw["tube_law"] == "thick-wall" and point["fitted"] == ["g_mpa", "g_e_mpa"]
    law = point["tube_law_parameters"]
    assert set(law) == {"outer_radius_mm", "inner_radius_mm", "mu_mpa"} and law["mu_mpa"] == point["g_e_mpa"]
    assert point["p0_kpa"] == pytest.approx(P0_KPA, rel=1e-5)  # the law's P0 at the fitted mu meets the onset
    # appending whole-strip data fitted with the other law to this set is refused in one line
    assert main(["fit", str(angles), "--pattern", "zigzag", "--width-mm", "7", "-o", str(cal), "--append"]) == 2
    assert "--tube-law paper differs from the set's 'thick-wall'" in capsys.readouterr().err
    # ... and so are marker sums appended to a set of whole-strip angles
    assert main(["fit", str(angles), "--pattern", "zigzag", "--width-mm", "7", "-o", str(cal), "--append",
                 "--tube-law", "thick-wall", "--fit", "g,mu", "--measurement", "markers"]) == 2
    err = capsys.readouterr().err
    assert "the measurement (markers: 2 rows of 7, 10 mm apart" in err and "differs from the set's (whole-strip)" in err


@pytest.mark.parametrize("flags, message", [
    (["--marker-spacing-mm", "0"], "marker_spacing_mm must be in (0, 10000), got 0"),
    (["--marker-offset-mm", "-1"], "marker_offset_mm must be in [0, 100000), got -1"),
    (["--marker-spacing-mm", "nan"], "marker_spacing_mm must be"),
    (["--markers", "--tangent", "1,0,0"], "--tangent needs --normal"),
    (["--markers", "--normal", "0,1,0", "--tangent", "1,x"], "--tangent must be 2 or 3 comma-separated numbers"),
    (["--normal", "0,1,0"], "--normal and --tangent orient marker coordinates: they need --markers"),
    (["--measurement", "markers", "--marker-offset-mm", "100"],
     "marker offset_mm must be below the bent length l0 = 100 mm (markers beyond it lie on the straight end"),
])
def test_bad_layout_flags_are_one_line(capsys, tmp_path, flags, message):
    data = tmp_path / "a.csv"
    data.write_text("pressure_kpa,angle_deg\n0,0\n100,10\n200,50\n")
    assert main(["fit", str(data), "--pattern", "zigzag", "--width-mm", "7", *flags, "-o", str(tmp_path / "c.toml")]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1, err
    assert not (tmp_path / "c.toml").exists()


# ----------------------------------------------------------------------------- predict's marker reading
def test_predict_gives_the_marker_reading_next_to_theta(capsys):
    """--measurement markers: reading_deg is the turning of the layout's chords on the predicted bend,
    also with markers past the bent length (offset 60 mm: the last two on the straight continuation)."""
    grid = "0,100,150,200,250"
    for offset, per_side in (("0", "7"), ("60", "5")):
        doc = _json(capsys, "predict", *ZIGZAG, "--g-mpa", "2.7", "--p0-kpa", "85", "--pressure-kpa", grid,
                    "--measurement", "markers", "--marker-offset-mm", offset, "--markers-per-side", per_side, "--json")
        s = float(offset) + 10.0 * np.arange(int(per_side))
        want = [chord_turning_deg(t, s, doc["derived"]["length_mm"]) for t in doc["theta_deg"]]
        assert np.allclose(doc["reading_deg"], want, rtol=1e-9, atol=1e-9)
        assert doc["measurement"]["offset_mm"] == float(offset) and doc["band"] is None
    # the paper's layout on 100 mm: exactly half of theta; the text table shows the same column
    doc = _json(capsys, "predict", *ZIGZAG, "--g-mpa", "2.7", "--p0-kpa", "85", "--pressure-kpa", grid,
                "--measurement", "markers", "--json")
    assert np.allclose(doc["reading_deg"], 0.5 * np.array(doc["theta_deg"]), rtol=1e-12)
    assert main(["predict", *ZIGZAG, "--g-mpa", "2.7", "--p0-kpa", "85", "--pressure-kpa", grid,
                 "--measurement", "markers"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[2].split()[:3] == ["pressure_kpa", "theta_deg", "reading_deg"]
    assert [float(ln.split()[2]) for ln in lines[3:]] == pytest.approx(doc["reading_deg"], abs=5e-4)
    # whole-strip (default): no reading column or key
    assert "reading_deg" not in _json(capsys, "predict", *ZIGZAG, "--pressure-kpa", grid, "--json")


def test_predict_reading_at_the_fitted_parameters_is_what_fit_matched(capsys, tmp_path):
    """fit --markers and predict --measurement markers answer the same question: at the fitted G and P0
    predict's reading is the marker sums fit computed from the coordinates; the band carries a reading band."""
    theta = _theta(capsys, ZIGZAG, G_MPA, P0_KPA, UP)
    data = _marker_csv(tmp_path / "m.csv", UP, _frames(theta, 0.2, 11))
    cal = tmp_path / "lab.toml"
    doc = _fit(capsys, data, ZIGZAG, "--markers", "--normal", "0,1,0", "-o", str(cal))
    (f,) = doc["fits"]
    grid = ",".join(f"{p:g}" for p in f["pressure_kpa"])
    pred = _json(capsys, "predict", *ZIGZAG, "--calibration", str(cal), "--pressure-kpa", grid,
                 "--measurement", "markers", "--json")
    assert np.allclose(np.array(pred["reading_deg"]) - f["angle_deg"], f["residuals_deg"], atol=1e-6)
    sd, rsd = np.array(pred["band"]["theta_sd_deg"]), np.array(pred["band"]["reading_sd_deg"])
    assert np.allclose(rsd, 0.5 * sd, rtol=1e-6)  # the reading is half of theta here, so is its band


def test_readme_marker_example_numbers(capsys):
    """The README's marker example quotes what these commands print."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    readme = (root / "README.md").read_text(encoding="utf-8")
    (load, _) = _json(capsys, "fit", str(root / "examples/data/zigzag_w7_markers.csv"), "--markers", "--normal",
                      "1,0,0", "--pattern", "zigzag", "--width-mm", "7", "--json")["fits"]
    assert (f"loading {load['n_points']} points: G {load['g_mpa']:.4g} +- {load['g_mpa_se']:.2g} MPa, "
            f"P0 {load['p0_kpa']:.4g} +- {load['p0_kpa_se']:.2g} kPa") in readme
    # ... and the truth they were made with (examples/make_demo_data.py) lies within 3 SE
    assert abs(load["g_mpa"] - 2.7) < 3 * load["g_mpa_se"] and abs(load["p0_kpa"] - 85.0) < 3 * load["p0_kpa_se"]


# ----------------------------------------------------------------------------- the calibration file's new fields
def _cal_text(extra_set="", extra_point=""):
    return ('name = "lab"\n' + extra_set + '[[points]]\npattern = "zigzag"\nwidth_mm = 7.0\ng_mpa = 2.7\n'
            'p0_kpa = 85.0\n' + extra_point)


@pytest.mark.parametrize("extra_set, extra_point, message", [
    ("", 'fitted = "g_mpa"\n', "points[0]: fitted must be a list of parameter names, got 'g_mpa'"),
    ("", 'fitted = ["g_mpa", "p0_kpa"]\ncovariance = [[1.0, 0.0]]\n', "covariance must be 2 x 2"),
    ("", 'fitted = ["g_mpa"]\ncovariance = [["a"]]\n', "covariance must be a list of rows of numbers"),
    ("", 'fitted = ["g_mpa"]\ncovariance = [[-1.0]]\n', "non-negative diagonal"),
    ("", 'tube_law_parameters = 3\n', "tube_law_parameters must be a table of numbers, got 3"),
    ("", '[points.tube_law_parameters]\nk_mpa = 1.0\n', "tube_law_parameters must name distinct keys of"),
    ("", '[points.tube_law_parameters]\nmu_mpa = -1.0\n', "tube_law_parameters.mu_mpa must be in (0, "),
    ('marker_layout = 7\n', "", "[marker_layout] must be a table of markers_per_side"),
    ('[marker_layout]\nspacing_mm = 0\n', "", "[marker_layout]: spacing_mm must be in (0, 10000), got 0"),
    ('[marker_layout]\nrow = 2\n', "", "unknown key 'row' in [marker_layout]"),
    ('[marker_layout]\nside = "inside"\n', "", "side must be one of 'fabric', 'thread', got 'inside'"),
])
def test_bad_new_calibration_fields_are_one_line(capsys, tmp_path, extra_set, extra_point, message):
    cal = tmp_path / "bad.toml"
    cal.write_text(_cal_text(extra_set, extra_point))
    assert main(["predict", *ZIGZAG, "--calibration", str(cal), "--pressure-kpa", "100"]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1, err


def test_old_and_new_files_read(tmp_path):
    """A file without the new fields reads as before (no layout, no covariance); a full one round-trips."""
    import dataclasses

    from embroact.export.files.calibfile import read_calibration, write_calibration
    from embroact.predict.markers import MarkerLayout

    old = tmp_path / "old.toml"
    old.write_text(_cal_text())
    cset = read_calibration(old)
    assert cset.marker_layout is None and cset.measurement == "whole-strip"
    (p,) = cset.points
    assert p.fitted == () and p.covariance == () and p.tube_law_parameters == ()
    full = dataclasses.replace(cset, marker_layout=MarkerLayout(markers_per_side=5, spacing_mm=12.5, offset_mm=3.0,
                                                                rows=1, side="thread"),
                               measurement="whole-strip",  # replaced by the layout's label
                               points=(dataclasses.replace(p, fitted=("g_mpa", "g_e_mpa"),
                                                           covariance=((1e-4, 2e-6), (2e-6, 3e-7)),
                                                           tube_law_parameters=(("outer_radius_mm", 1.5),
                                                                                ("inner_radius_mm", 1.0),
                                                                                ("mu_mpa", 0.2))),))
    assert full.measurement == "markers: 1 rows of 5, 12.5 mm apart, first 3 mm from the clamped end, thread side"
    write_calibration(tmp_path / "new.toml", full)
    assert read_calibration(tmp_path / "new.toml") == full


def test_thick_wall_calibration_band_acts_through_p0_at_the_fitted_mu(capsys, tmp_path):
    """A (G, mu) fit's band: mu moves P0 in proportion (P0 = law(r0; mu)), checked by finite differences
    of predict at shifted G and P0 = P0 (1 + dmu/mu); the design's G_e (0.13) plays no part."""
    theta = _theta(capsys, ZIGZAG, G_MPA, P0_KPA, UP)
    noisy = theta + np.random.default_rng(5).normal(0.0, 1.0, theta.shape) * (theta > 0)
    angles = tmp_path / "a.csv"
    angles.write_text("pressure_kpa,angle_deg\n" + "".join(f"{p:g},{float(t)!r}\n" for p, t in zip(UP, noisy)))
    cal = tmp_path / "thick.toml"
    assert main(["fit", str(angles), "--pattern", "zigzag", "--width-mm", "7", "--branch", "loading",
                 "--tube-law", "thick-wall", "--fit", "g,mu", "-o", str(cal)]) == 0
    capsys.readouterr()
    (point,) = tomllib.loads(cal.read_text())["points"]
    pressures = [120.0, 200.0, 280.0]
    grid = ",".join(f"{p:g}" for p in pressures)
    doc = _json(capsys, "predict", *ZIGZAG, "--calibration", str(cal), "--tube-law", "thick-wall",
                "--pressure-kpa", grid, "--json")
    assert doc["band"]["parameters"] == ["g_mpa", "g_e_mpa"]
    g, p0, mu = point["g_mpa"], point["p0_kpa"], point["g_e_mpa"]
    assert doc["model"]["p0_kpa"] == pytest.approx(p0, rel=1e-12)
    hg, hmu = 1e-4 * g, 1e-4 * mu
    d_g = (_theta(capsys, ZIGZAG, g + hg, p0, pressures) - _theta(capsys, ZIGZAG, g - hg, p0, pressures)) / (2 * hg)
    d_mu = (_theta(capsys, ZIGZAG, g, p0 * (1 + hmu / mu), pressures)
            - _theta(capsys, ZIGZAG, g, p0 * (1 - hmu / mu), pressures)) / (2 * hmu)
    jac = np.stack([d_g, d_mu], axis=1)
    sd = np.sqrt(np.einsum("pi,ij,pj->p", jac, np.array(point["covariance"]), jac))
    assert np.allclose(doc["band"]["theta_sd_deg"], sd, rtol=1e-4) and sd.min() > 0.05
