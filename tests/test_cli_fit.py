"""``embroact fit``: the demo data give back the parameters they were made with.

The demo CSVs (``examples/make_demo_data.py``, fixed seed) were generated with known
parameters: zigzag w = 7 mm loading G = 2.7 MPa, P0 = 85 kPa, unloading 2.3 / 70;
cross alpha0 = 45 deg loading 1.3 / 170, unloading 1.1 / 150; noise 1 deg.
"""
import json
import math
import runpy
from pathlib import Path

import pytest

from embroact.export.files.calibfile import read_bend_csv, read_calibration, read_marker_csv
from embroact.export.cli.main import main
from embroact.predict.calibration import lookup

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
DATA = EXAMPLES / "data"
ZIGZAG = ["--pattern", "zigzag", "--width-mm", "7"]
CROSS45 = ["--pattern", "cross", "--width-mm", "7", "--angle-deg", "45"]
TRUTH = {
    "zigzag": {"loading": (2.7, 85.0), "unloading": (2.3, 70.0)},
    "cross": {"loading": (1.3, 170.0), "unloading": (1.1, 150.0)},
}


def _fit_json(capsys, *argv):
    assert main(["fit", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def _assert_truth(doc, pattern):
    assert [f["branch"] for f in doc["fits"]] == ["loading", "unloading"]
    for f in doc["fits"]:
        g, p0 = TRUTH[pattern][f["branch"]]
        assert abs(f["g_mpa"] - g) < 3 * f["g_mpa_se"]
        assert abs(f["p0_kpa"] - p0) < 3 * f["p0_kpa_se"]
        assert 0.7 < f["rmse_deg"] < 1.4  # the demo noise is 1 deg


def test_demo_data_are_reproducible(tmp_path):
    runpy.run_path(str(EXAMPLES / "make_demo_data.py"), run_name="not_main")["main"](str(tmp_path))
    for name in ("zigzag_w7_loop.csv", "cross_a45_loop.csv", "zigzag_w7_markers.csv"):
        assert (tmp_path / name).read_bytes() == (DATA / name).read_bytes()


def test_fit_zigzag_demo_json(capsys):
    doc = _fit_json(capsys, str(DATA / "zigzag_w7_loop.csv"), *ZIGZAG)
    _assert_truth(doc, "zigzag")
    assert doc["design"]["r0_mm"] == pytest.approx(2.581421, abs=1e-6)
    assert doc["fits"][0]["method"] == "stable-analytic-trace" and doc["calibration"] is None


def test_fit_cross_demo_writes_calibration(capsys, tmp_path):
    out = tmp_path / "lab.toml"
    rc = main(["fit", str(DATA / "cross_a45_loop.csv"), *CROSS45, "-o", str(out), "--material", "tube=latex"])
    text = capsys.readouterr().out
    assert rc == 0 and "wrote calibration set 'lab' (2 point(s))" in text
    assert text.splitlines()[1].split()[:2] == ["branch", "n"]
    cset = read_calibration(out)
    assert cset.name == "lab" and dict(cset.materials) == {"tube": "latex"}
    c = lookup("cross", width_mm=7.0, angle_deg=45.0, name="lab", sets=[cset])
    assert abs(c.g_mpa - 1.3) < 0.05 and abs(c.p0_kpa - 170.0) < 2.0

    # append the zigzag fit to the same set
    assert main(["fit", str(DATA / "zigzag_w7_loop.csv"), *ZIGZAG, "-o", str(out), "--append"]) == 0
    merged = read_calibration(out)
    assert len(merged.points) == 4 and merged.name == "lab"
    assert abs(lookup("zigzag", width_mm=7.0, name="lab", sets=[merged]).g_mpa - 2.7) < 0.05
    assert main(["fit", str(DATA / "zigzag_w7_loop.csv"), *ZIGZAG, "-o", str(out), "--append", "--name", "x"]) == 2
    assert "differs from the set 'lab'" in capsys.readouterr().err


def test_fit_markers_signed(capsys):
    doc = _fit_json(capsys, str(DATA / "zigzag_w7_markers.csv"), "--markers", "--normal", "1,0,0", *ZIGZAG)
    for f in doc["fits"]:
        g, p0 = TRUTH["zigzag"][f["branch"]]
        # marker noise adds about 1 deg of angle noise on top of the 1 deg in the data
        assert abs(f["g_mpa"] - g) < 3 * f["g_mpa_se"] and abs(f["p0_kpa"] - p0) < 3 * f["p0_kpa_se"]
    assert "markers" in doc["note"]


def test_fit_options(capsys):
    doc = _fit_json(capsys, str(DATA / "zigzag_w7_loop.csv"), *ZIGZAG, "--fit", "g", "--p0-kpa", "85",
                    "--branch", "loading")
    (f,) = doc["fits"]
    assert f["fitted"] == ["g_mpa"] and f["p0_kpa"] == 85.0 and f["p0_source"] == "given"
    doc = _fit_json(capsys, str(DATA / "zigzag_w7_loop.csv"), *ZIGZAG, "--fit", "g,g_e", "--branch", "pooled")
    (f,) = doc["fits"]
    assert f["p0_source"] == "geometry" and f["g_e_mpa"] > 0 and f["n_points"] == 51
    assert main(["fit", str(DATA / "zigzag_w7_loop.csv"), *ZIGZAG, "--fit", "g,g_e"]) == 0
    assert "G_e = " in capsys.readouterr().out


def _write(tmp_path, text, name="d.csv"):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


@pytest.mark.parametrize(
    "text, message",
    [
        ("pressure_kpa,angle\n0,0\n", "missing column 'angle_deg' (header has: pressure_kpa, angle)"),
        ("pressure_kpa,angle_deg\n0,0\n10,abc\n", "line 3: angle_deg must be a finite number, got 'abc'"),
        ("# comment\npressure_kpa,angle_deg\n0,0\n10,nan\n", "line 4: angle_deg must be a finite number, got 'nan'"),
        ("pressure_kpa,angle_deg\n0,\n", "line 2: column 'angle_deg' is empty"),
        ("", "is empty: expected a header line"),
        ("pressure_kpa,angle_deg\n", "has a header but no data rows"),
        ("pressure_kpa,angle_deg,angle_deg\n0,0,0\n", "column 'angle_deg' appears more than once"),
        ("pressure_kpa,angle_deg,branch\n0,0,up\n", "line 2: branch must be 'loading' or 'unloading', got 'up'"),
        ("pressure_kpa,angle_deg\n" + "".join(f"{p},0.1\n" for p in range(0, 300, 10)), "no deformation phase"),
        ("pressure_kpa,angle_deg\n0,0\n-5,10\n10,20\n", "line 3: pressure_kpa must be >= 0 (gauge pressure), got -5"),
    ],
)
def test_bad_csv_is_one_line_exit_2(capsys, tmp_path, text, message):
    assert main(["fit", _write(tmp_path, text), *ZIGZAG, "-o", str(tmp_path / "cal.toml")]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and err.startswith("embroact: error: ")
    assert not (tmp_path / "cal.toml").exists()


@pytest.mark.parametrize(
    "argv, message",
    [
        (["--pattern", "zigzag"], "give the design: --pattern and --width-mm"),
        (["--pattern", "cross", "--width-mm", "7"], "--angle-deg is required"),
        ([*ZIGZAG, "--fit", "g,k"], "--fit must list parameters from g, p0, g_e"),
        ([*ZIGZAG, "--fit", "p0,g_e", "--g-mpa", "2"], "both 'p0_kpa' and 'g_e_mpa'"),
        ([*ZIGZAG, "--width-mm", "-7"], "width_mm must be in"),
        ([*CROSS45], "data bend positive but this cross design bends negative"),
        ([*ZIGZAG, "--markers"], "missing column 'm1_x'"),
        ([*ZIGZAG, "--material", "tube", "-o", "x.toml"], "--material must be KEY=VALUE"),
    ],
)
def test_bad_arguments_exit_2(capsys, argv, message, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["fit", str(DATA / "zigzag_w7_loop.csv"), *argv]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1
    assert not (tmp_path / "x.toml").exists()


def test_missing_file_and_unwritable_output(capsys, tmp_path):
    assert main(["fit", str(tmp_path / "none.csv"), *ZIGZAG]) == 2
    assert "cannot read" in capsys.readouterr().err
    out = tmp_path / "no-such-dir" / "cal.toml"
    assert main(["fit", str(DATA / "zigzag_w7_loop.csv"), *ZIGZAG, "-o", str(out)]) == 3
    assert "does not exist" in capsys.readouterr().err and not out.parent.exists()


def test_csv_readers(tmp_path):
    d = read_bend_csv(_write(tmp_path, "Angle_Deg , pressure_kpa,time_s\n1.5,10,0\n\n# note\n2.5,20,1\n"))
    assert d.pressure_kpa.tolist() == [10.0, 20.0] and d.angle_deg.tolist() == [1.5, 2.5] and d.branch is None
    header = "pressure_kpa," + ",".join(f"m{i}_{a}" for i in range(1, 4) for a in "xy")
    m = read_marker_csv(_write(tmp_path, header + "\n5,0,0,10,0,20,0\n"), n_markers=3)
    assert m.markers_mm.shape == (1, 3, 2) and m.markers_mm[0, 2].tolist() == [20.0, 0.0]


def test_fit_with_design_file(capsys, tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(
        'name = "lab"\n[[actuator]]\nname = "A1"\npattern = "zigzag"\nwidth_mm = 5.0\ninterval_mm = 1.0\n'
        'length_mm = 100.0\n[[actuator]]\nname = "Z7"\npattern = "zigzag"\nwidth_mm = 7.0\ninterval_mm = 1.0\n'
        "length_mm = 100.0\norigin_mm = [0.0, 30.0]\n"
    )
    doc = _fit_json(capsys, str(DATA / "zigzag_w7_loop.csv"), "--design", str(design), "--actuator", "Z7")
    _assert_truth(doc, "zigzag")
    assert doc["design"]["name"] == "Z7" and doc["design"]["width_mm"] == pytest.approx(7.0, abs=1e-9)
    assert main(["fit", str(DATA / "zigzag_w7_loop.csv"), "--design", str(design), "--actuator", "Q"]) == 2
    assert "--actuator must be one of 'A1', 'Z7', got 'Q'" in capsys.readouterr().err


def test_unsigned_markers_take_the_design_direction(capsys, tmp_path):
    """Without --normal the paper's unsigned angle sum is given the design's sign (cross 45: negative).

    The markers sit on the uniformly bent strip (tests/markerdata.py), turned over so that the
    bend looks positive: only the design can tell the sign."""
    import numpy as np
    from markerdata import strip_points

    bend = read_bend_csv(DATA / "cross_a45_loop.csv")
    side = np.stack([strip_points(abs(t), 10.0 * np.arange(7)) for t in bend.angle_deg])
    both = np.concatenate([side, side], axis=1)  # 2-D: both rows project onto one line
    cols = ",".join(f"m{i}_{a}" for i in range(1, 15) for a in "xy")
    rows = [f"{p:g},{b}," + ",".join(f"{v:.6f}" for v in m.ravel())
            for p, b, m in zip(bend.pressure_kpa, bend.branch, both)]
    path = _write(tmp_path, f"pressure_kpa,branch,{cols}\n" + "\n".join(rows) + "\n", "markers.csv")
    doc = _fit_json(capsys, path, "--markers", *CROSS45, "--branch", "loading")
    (f,) = doc["fits"]
    assert "negative bending direction" in doc["note"]
    assert all(a <= 0 for a in f["angle_deg"]) and f["g_mpa"] == pytest.approx(1.3, rel=0.05)


# ----------------------------------------------------------------------------- calibration round trip
def _cross30_truth(g_mpa, p0_kpa, pressures, noise_deg=0.0, seed=0):
    """Angles of the cross alpha0 = 30 deg design as the generator sews it.

    For w = 7 mm, s = 1.4 mm the generator cannot meet 30 deg with whole passes and sews
    tan(alpha0) = 3 s / w = 0.6 (30.964 deg); the data are made with that angle, derived by
    hand, and the plan's length.
    """
    import math

    import numpy as np

    from embroact.patterns.params import Tube
    from embroact.predict.curve import ActuatorModel, curve
    from embroact.predict.derived import derive_from_values
    from embroact.predict.analysis import analyse
    from embroact.patterns.design import design_from_dict

    alpha = math.degrees(math.atan(0.6))
    plan_act = analyse(design_from_dict({"actuator": [{"name": "A1", "pattern": "cross", "width_mm": 7,
                                                       "interval_mm": 1.4, "angle_deg": 30,
                                                       "length_mm": 100}]})).actuators[0]
    assert plan_act.derived.angle_deg == pytest.approx(alpha, abs=1e-9)  # the generator adjusted it
    d = derive_from_values("cross", width_mm=7.0, interval_mm=1.4, angle_deg=alpha,
                           length_mm=plan_act.derived.length_mm, tube=Tube())
    theta = np.asarray(curve(ActuatorModel.from_derived(d, g_mpa=g_mpa, p0_kpa=p0_kpa), pressures).theta_deg)
    return theta + np.random.default_rng(seed).normal(0.0, noise_deg, theta.shape)


CROSS30 = ["--pattern", "cross", "--width-mm", "7", "--interval-mm", "1.4", "--angle-deg", "30"]


def _csv(tmp_path, pressures, theta, name):
    path = tmp_path / name
    path.write_text("pressure_kpa,angle_deg\n" + "".join(f"{p:g},{float(t)!r}\n" for p, t in zip(pressures, theta)))
    return str(path)


def test_fit_of_an_adjusted_cross_recovers_g_and_p0_within_their_errors(capsys, tmp_path):
    pressures = [float(p) for p in range(0, 301, 10)]
    data = _csv(tmp_path, pressures, _cross30_truth(2.0, 120.0, pressures, noise_deg=0.5, seed=3), "noisy.csv")
    (fit,) = _fit_json(capsys, data, *CROSS30)["fits"]
    assert abs(fit["g_mpa"] - 2.0) < 3 * fit["g_mpa_se"] and fit["g_mpa_se"] < 0.05
    assert abs(fit["p0_kpa"] - 120.0) < 3 * fit["p0_kpa_se"] and fit["p0_kpa_se"] < 3.0
    # the point is keyed by the angle the legs are sewn at, tan(alpha0) = 0.6, not the requested 30 deg
    assert fit["design"]["angle_deg"] == pytest.approx(math.degrees(math.atan(0.6)), abs=1e-9)


def test_fit_file_round_trips_through_predict_and_a_design(capsys, tmp_path):
    pressures = [float(p) for p in range(0, 301, 10)]
    truth = _cross30_truth(2.0, 120.0, pressures)
    cal = tmp_path / "lab.toml"
    assert main(["fit", _csv(tmp_path, pressures, truth, "clean.csv"), *CROSS30, "-o", str(cal)]) == 0
    capsys.readouterr()
    cset = read_calibration(cal)
    assert cset.tube is not None and (cset.tube.outer_radius_mm, cset.tube.inner_radius_mm, cset.tube.g_e_mpa) == (
        1.5, 1.0, 0.13)
    assert cset.tube_law == "paper" and cset.measurement == "whole-strip"
    sewn = math.degrees(math.atan(0.6))
    assert cset.coverage()["cross"] == (pytest.approx(sewn, abs=1e-9), pytest.approx(sewn, abs=1e-9))
    grid = ",".join(f"{p:g}" for p in pressures)
    assert main(["predict", "cross", "--width-mm", "7", "--interval-mm", "1.4", "--angle-deg", "30",
                 "--calibration", str(cal), "--pressure-kpa", grid, "--json"]) == 0
    (doc,) = json.loads(capsys.readouterr().out)["actuators"]
    assert doc["model"]["g_source"] == f"calibration lab (cross, angle_deg={sewn:g}, requested 30)"  # on the point
    assert max(abs(a - b) for a, b in zip(doc["theta_deg"], truth)) < 1e-6
    # the same file named by a design, relative to the design file
    sub = tmp_path / "designs"
    sub.mkdir()
    (sub / "d.toml").write_text('[[actuator]]\nname = "C"\npattern = "cross"\nwidth_mm = 7.0\ninterval_mm = 1.4\n'
                                'angle_deg = 30.0\nlength_mm = 100.0\n[actuator.model]\ncalibration = "../lab.toml"\n')
    assert main(["predict", str(sub / "d.toml"), "--pressure-kpa", grid, "--json"]) == 0
    (act,) = json.loads(capsys.readouterr().out)["actuators"]
    assert max(abs(a - b) for a, b in zip(act["theta_deg"], truth)) < 1e-6
    assert main(["check", str(sub / "d.toml"), "--json"]) in (0, 1)
    assert "calibration must be one of" not in capsys.readouterr().err
    # and the API: the design's calibration file resolved relative to the design, as the commands do
    from embroact.export.files.calibfile import resolve_calibration_files
    from embroact.export.files.designfile import load_design
    from embroact.predict.analysis import analyse

    design, sets = resolve_calibration_files(load_design(sub / "d.toml"), sub)
    assert sets == (cset,) and design.actuators[0].model.calibration == sets[0].source  # the file, by path
    (c,) = analyse(design, calibration_sets=sets).curves(pressures)
    assert max(abs(a - b) for a, b in zip(c.theta_deg, truth)) < 1e-6
    # a resolved design saved elsewhere (as the studio saves into its output folder) still finds the file
    from embroact.export.files.designfile import save_design

    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    save_design(design, elsewhere / "saved.toml")
    assert main(["predict", str(elsewhere / "saved.toml"), "--pressure-kpa", grid, "--json"]) == 0
    (act,) = json.loads(capsys.readouterr().out)["actuators"]
    assert max(abs(a - b) for a, b in zip(act["theta_deg"], truth)) < 1e-6


def test_fit_prints_no_demonstration_note(capsys):
    """A fit estimates G and P0 from the measurements and takes no calibration's: the note that the paper's
    demonstration set is in use (every command that predicts with it prints one) is not printed."""
    csv = Path(__file__).resolve().parents[1] / "examples" / "data" / "zigzag_w7_loop.csv"
    assert main(["fit", str(csv), "--pattern", "zigzag", "--width-mm", "7"]) == 0
    assert "paper-2025" not in capsys.readouterr().err
