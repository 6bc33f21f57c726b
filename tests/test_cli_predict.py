"""``embroact predict``: quick parameters, design files, JSON and table output, errors."""
import json

import numpy as np
import pytest

from embroact.export.cli.main import main
from embroact.export.cli.cmd_predict import parse_pressures
from embroact.patterns.base.errors import ParameterError
from embroact.patterns.params import Tube
from embroact.predict.curve import ActuatorModel, curve
from embroact.predict.derived import derive_from_values


def run_json(capsys, *argv):
    code = main(["predict", *argv, "--json"])
    out = capsys.readouterr()
    assert code == 0, out.err
    return json.loads(out.out)


def quick_json(capsys, *argv):
    """The one actuator of quick parameters, in the design files' schema (design name "quick")."""
    d = run_json(capsys, *argv)
    assert d["design"] == "quick" and len(d["actuators"]) == 1
    return d["actuators"][0]


def test_quick_zigzag_json_matches_the_api(capsys):
    d = quick_json(capsys, "zigzag", "--width-mm", "7", "--g-mpa", "2.7", "--p0-kpa", "85",
                 "--pressure-kpa", "0:300:10")
    p = np.arange(0.0, 301.0, 10.0)
    assert d["pressure_kpa"] == p.tolist()
    dg = derive_from_values("zigzag", width_mm=7, interval_mm=1, angle_deg=0, length_mm=100, tube=Tube())
    ref = curve(ActuatorModel.from_derived(dg, g_mpa=2.7, p0_kpa=85.0), p)
    np.testing.assert_allclose(d["theta_deg"], ref.theta_deg, rtol=1e-12, atol=1e-12)
    assert d["status"][:9] == ["INFLATION"] * 9 and d["status"][9] == "BENDING"
    assert len(d["radius_mm"]) == len(d["length_mm"]) == len(d["beta_deg"]) == len(d["inner_radius_mm"]) == 31
    assert d["method"] == "stable-analytic-trace"
    assert d["calibration"] == "given"
    assert d["model"]["g_source"] == d["model"]["p0_source"] == "given"
    assert {k: d["model"][k] for k in ("g_mpa", "p0_kpa", "tube_law")} == {"g_mpa": 2.7, "p0_kpa": 85.0,
                                                                        "tube_law": "paper"}
    assert d["model"]["tube"] == {"outer_radius_mm": 1.5, "inner_radius_mm": 1.0, "g_e_mpa": 0.13}
    assert d["derived"]["r0_mm"] == pytest.approx(2.5814206750769157, rel=1e-12)
    # the zigzag's branch ends at a fold of the formula, far inside the coiled region
    assert d["branch_end"]["kind"] == "fold" and d["branch_end"]["status"] == "COILED"
    assert d["branch_end"]["theta_deg"] == pytest.approx(1888.7643, abs=1e-3)
    assert d["limits"][:10] == [[]] * 10


def test_quick_cross_uses_the_calibration_set(capsys):
    d = quick_json(capsys, "cross", "--width-mm", "7", "--interval-mm", "1.4", "--angle-deg", "45",
                 "--pressure-kpa", "100,200,300")
    assert d["model"]["g_mpa"] == 1.3 and d["model"]["p0_kpa"] == 170.0  # paper's fit, docs/model.md section 7
    assert d["calibration"].startswith("calibration paper-2025")
    assert d["model"]["p0_source"] == d["model"]["g_source"] == "calibration paper-2025 (cross, angle_deg=45)"
    assert d["status"] == ["INFLATION", "BENDING", "BENDING"]
    assert d["theta_deg"][1] < 0 and d["theta_deg"][2] < d["theta_deg"][1]  # alpha0 = 45 bends negative
    assert d["branch_end"]["kind"] == "lock-up" and d["branch_end"]["pressure_kpa"] is None  # a pole


def test_p0_from_geometry_and_thick_wall_law(capsys):
    d = quick_json(capsys, "zigzag", "--width-mm", "7", "--g-mpa", "2.7", "--p0-source", "geometry",
                 "--pressure-kpa", "0,40,60")
    assert d["model"]["p0_kpa"] == pytest.approx(84.455, abs=1e-3)
    t = quick_json(capsys, "zigzag", "--width-mm", "7", "--g-mpa", "2.7", "--p0-source", "geometry",
                 "--tube-law", "thick-wall", "--pressure-kpa", "0,40,60")
    assert t["model"]["p0_kpa"] == pytest.approx(49.148, abs=1e-3) and t["model"]["tube_law"] == "thick-wall"
    assert t["status"] == ["INFLATION", "INFLATION", "BENDING"]


def test_table_output(capsys):
    assert main(["predict", "zigzag", "--width-mm", "5", "--pressure-kpa", "0:100:50"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("A1: zigzag w=5 mm") and "paper-2025" in lines[0]
    assert lines[1].split()[:3] == ["pressure_kpa", "theta_deg", "status"]
    assert [ln.split()[2] for ln in lines[2:]] == ["INFLATION", "INFLATION", "BENDING"]


DESIGN = """
name = "two"
[[actuator]]
name = "Z"
pattern = "zigzag"
width_mm = 7.0
interval_mm = 1.0
length_mm = 100.0
[actuator.model]
g_mpa = 2.7
p0_kpa = 85.0

[[actuator]]
name = "X"
pattern = "cross"
width_mm = 7.0
interval_mm = 1.4
angle_deg = 15.0
length_mm = 80.0
origin_mm = [0.0, 30.0]
[operation]
max_pressure_kpa = 200.0
"""


def test_design_file(tmp_path, capsys):
    path = tmp_path / "two.toml"
    path.write_text(DESIGN)
    d = run_json(capsys, str(path))
    assert d["design"] == "two"
    z, x = d["actuators"]
    assert (z["name"], x["name"]) == ("Z", "X")
    assert z["pressure_kpa"] == np.arange(0.0, 201.0, 10.0).tolist()  # default: 0 to max_pressure_kpa
    assert z["calibration"] == "given" and x["calibration"].startswith("calibration paper-2025")
    assert 72.0 < x["derived"]["length_mm"] <= 80.0  # realised: whole pattern repeats within the path
    assert x["theta_deg"][-1] > 0  # alpha0 = 15 bends positive
    only = run_json(capsys, str(path), "--actuator", "X", "--g-mpa", "5")
    assert [a["name"] for a in only["actuators"]] == ["X"] and only["actuators"][0]["model"]["g_mpa"] == 5.0


@pytest.mark.parametrize("argv, message", [
    (["zigzag", "--width-mm", "7", "--pressure-kpa", "0:300"], "--pressure-kpa must be 'start:stop:step'"),
    (["zigzag", "--width-mm", "7", "--pressure-kpa", "0:abc:10"], "--pressure-kpa: 'abc' is not a number"),
    (["zigzag", "--width-mm", "7", "--pressure-kpa", "300:0:10"], "--pressure-kpa: stop must be >= start"),
    (["zigzag", "--width-mm", "7", "--pressure-kpa=-5,10"], "--pressure-kpa: pressures must be finite and >= 0"),
    (["zigzag", "--width-mm", "7", "--pressure-kpa", "0:1e5:1e-3"], "--pressure-kpa: at most 100000 pressures"),
    (["zigzag", "--pressure-kpa", "10"], "--width-mm is required"),
    (["cross", "--width-mm", "7", "--pressure-kpa", "10"], "--angle-deg is required for the cross pattern"),
    (["zigzag", "--width-mm", "7", "--method", "fast"], "method must be one of auto, stable-analytic-trace"),
    (["zigzag", "--width-mm", "-7"], "width_mm must be in (0, 200), got -7"),
])
def test_errors_are_one_line(capsys, argv, message):
    assert main(["predict", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("embroact: error: ") and message in err and err.count("\n") == 1


def test_missing_design_file(tmp_path, capsys):
    assert main(["predict", str(tmp_path / "nope.toml")]) == 2
    err = capsys.readouterr().err
    assert "nope.toml" in err and err.count("\n") == 1


def test_unknown_actuator(tmp_path, capsys):
    path = tmp_path / "two.toml"
    path.write_text(DESIGN)
    assert main(["predict", str(path), "--actuator", "Q"]) == 2
    assert "--actuator must be one of Z, X, got 'Q'" in capsys.readouterr().err


def test_parse_pressures_inclusive_stop():
    assert parse_pressures("0:1:0.1").tolist() == pytest.approx([0.1 * k for k in range(11)])
    assert parse_pressures("10:10:5").tolist() == [10.0]
    assert parse_pressures("0:0.95:0.1")[-1] == pytest.approx(0.9)
    with pytest.raises(ParameterError, match="--pressure-kpa"):
        parse_pressures("")


def test_paper_w5_zigzag_reports_its_coiled_and_over_stretched_states(capsys):
    """Built-in calibration (G = 0.8 MPa, P0 = 50 kPa): 2032 deg at 250 kPa is not a valid bend; 293 deg at
    150 kPa neither (short of a full turn, but the 30 mm sealed stub beyond the tip reaches the clamp)."""
    d = quick_json(capsys, "zigzag", "--width-mm", "5", "--pressure-kpa", "100:300:50")
    assert d["status"] == ["BENDING", "COILED", "COILED", "COILED", "COILED"]
    assert d["limits"][3] == ["COILED", "KINKED", "OVERSTRETCHED"] and d["limits"][0] == []
    assert d["limits"][1] == ["COILED"] and 253.9 < d["theta_deg"][1] < 360.0
    assert main(["predict", "zigzag", "--width-mm", "5", "--pressure-kpa", "100:300:50"]) == 0
    rows = capsys.readouterr().out.splitlines()[2:]
    assert rows[3].split()[2] == "COILED" and rows[3].endswith("COILED+KINKED+OVERSTRETCHED")
    assert rows[0].split()[2] == "BENDING" and len(rows[0].split()) == 7
    # the table prints no state the model does not describe (2032 deg was printed as a bend): '-' and the status
    for row, status in zip(rows[:5], d["status"]):
        cells = row.split()
        assert (cells[1] == "-") == (status == "COILED") and cells[2] == status, row
        assert status == "BENDING" or cells[3:7] == ["-"] * 4, row
    assert "-: past a validity limit the model describes no state" in rows[5]


SEGMENTED = """name = "seg"
[[actuator]]
name = "S"
[[actuator.segment]]
pattern = "zigzag"
width_mm = 7
interval_mm = 1
length_mm = 50
[[actuator.segment]]
pattern = "cross"
width_mm = 7
interval_mm = 1.4
angle_deg = 45
length_mm = 50
"""


def test_segmented_actuator_predicts_each_segment_and_their_sum(tmp_path, capsys):
    path = tmp_path / "seg.toml"
    path.write_text(SEGMENTED)
    d = run_json(capsys, str(path), "--pressure-kpa", "0:300:50")
    (s,) = d["actuators"]
    zig, crs = s["segment_curves"]
    # a zigzag's curvature does not depend on its length (docs/model.md, segmented actuators): the 50 mm
    # segment bends by its length over 100 mm times what the whole 100 mm paper zigzag bends at each pressure
    whole = quick_json(capsys, "zigzag", "--width-mm", "7", "--pressure-kpa", "0:300:50")
    share = s["segments"][0]["derived"]["length_mm"] / whole["derived"]["length_mm"]
    np.testing.assert_allclose(zig["theta_deg"], np.array(whole["theta_deg"]) * share, rtol=1e-9, atol=1e-9)
    assert crs["theta_deg"][-1] < 0 < zig["theta_deg"][-1]  # alpha0 = 45 deg bends the other way
    np.testing.assert_allclose(s["theta_deg"], np.add(zig["theta_deg"], crs["theta_deg"]), rtol=0, atol=1e-12)
    assert s["status"][0] == "INFLATION" and s["status"][-1] == "BENDING"
    assert main(["predict", str(path), "--pressure-kpa", "100"]) == 0
    assert "whole strip, 2 segments" in capsys.readouterr().out
