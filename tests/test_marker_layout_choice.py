"""The layout a calibration set records is the default layout of the readings made with it.

A calibration file written by ``embroact fit`` with a non-default layout (one row of 5 markers
12 mm apart, the first 5 mm from the clamped end) gives ``embroact predict --measurement
markers`` that layout when no layout flag is given; each given flag sets its own field; without
a recorded layout the paper's is used; the output says which. The expected readings are the
hand formula ``(n - 2) h theta / l0`` (every marker on the 100 mm bend).
"""
import json

import numpy as np
import pytest

from embroact.export.cli.main import main
from embroact.predict.layoutchoice import layout_for
from embroact.predict.markers import MarkerLayout

ZIGZAG = ["zigzag", "--width-mm", "7"]
LAB = ["--markers-per-side", "5", "--marker-spacing-mm", "12", "--marker-offset-mm", "5", "--sides", "1"]
LAB_LAYOUT = {"markers_per_side": 5, "spacing_mm": 12.0, "offset_mm": 5.0, "rows": 1, "side": "fabric"}
GRID = "100,150,200,250"


def _json(capsys, *argv):
    assert main(list(argv)) == 0, capsys.readouterr().err
    doc = json.loads(capsys.readouterr().out)
    if argv[0] == "predict" and doc.get("design") == "quick":  # quick parameters: one actuator of the design schema
        (doc,) = doc["actuators"]
    return doc


@pytest.fixture()
def lab(capsys, tmp_path):
    """lab.toml: G and P0 fitted to marker sums of the lab layout (made from the model at 2.7 MPa, 85 kPa)."""
    pressures = list(range(0, 301, 20))
    theta = _json(capsys, "predict", *ZIGZAG, "--g-mpa", "2.7", "--p0-kpa", "85", "--pressure-kpa",
                  ",".join(map(str, pressures)), "--json")["theta_deg"]
    data = tmp_path / "sums.csv"
    data.write_text("pressure_kpa,angle_deg\n" + "".join(f"{p},{0.36 * t!r}\n" for p, t in zip(pressures, theta)))
    cal = tmp_path / "lab.toml"
    doc = _json(capsys, "fit", str(data), "--pattern", "zigzag", "--width-mm", "7", "--branch", "loading",
                "--measurement", "markers", *LAB, "-o", str(cal), "--json")
    assert doc["calibration"]["marker_layout"] == LAB_LAYOUT
    assert doc["calibration"]["marker_layout_source"] == ("given markers_per_side, spacing_mm, offset_mm, rows; "
                                                          "the rest the paper's")
    return cal


def _predict(capsys, cal, *flags):
    return _json(capsys, "predict", *ZIGZAG, "--calibration", str(cal), "--pressure-kpa", GRID,
                 "--measurement", "markers", *flags, "--json")


def test_predict_defaults_to_the_layout_the_calibration_records(capsys, lab):
    doc = _predict(capsys, lab)
    assert doc["measurement"] == LAB_LAYOUT
    assert doc["measurement_source"] == "recorded by calibration set 'lab'"
    theta = np.array(doc["theta_deg"])
    assert np.allclose(doc["reading_deg"], 3 * 12.0 / 100.0 * theta, rtol=1e-9)  # (5 - 2) * 12 mm of 100 mm
    # the band's reading is the same layout's: its half-width scales by the same factor
    band = doc["band"]
    assert np.allclose(band["reading_sd_deg"], 0.36 * np.array(band["theta_sd_deg"]), rtol=1e-6)
    # the text table says which layout and where it came from
    assert main(["predict", *ZIGZAG, "--calibration", str(lab), "--pressure-kpa", GRID,
                 "--measurement", "markers"]) == 0
    out = capsys.readouterr().out
    assert ("reading_deg: what the marker sum reads (markers: 1 rows of 5, 12 mm apart, first 5 mm from the "
            "clamped end, fabric side; layout: recorded by calibration set 'lab')") in out


def test_a_design_naming_the_calibration_file_gets_the_same_layout(capsys, lab, tmp_path):
    design = tmp_path / "d.toml"
    design.write_text('[[actuator]]\nname = "A1"\npattern = "zigzag"\nwidth_mm = 7.0\ninterval_mm = 1.0\n'
                      'length_mm = 100.0\n[actuator.model]\ncalibration = "lab.toml"\n')
    (act,) = _json(capsys, "predict", str(design), "--pressure-kpa", GRID, "--measurement", "markers",
                   "--json")["actuators"]
    via_flag = _predict(capsys, lab)
    assert act["measurement"] == LAB_LAYOUT and act["measurement_source"] == via_flag["measurement_source"]
    assert act["reading_deg"] == via_flag["reading_deg"]


def test_given_flags_win_field_by_field(capsys, lab):
    doc = _predict(capsys, lab, "--marker-spacing-mm", "10")
    assert doc["measurement"] == {**LAB_LAYOUT, "spacing_mm": 10.0}
    assert doc["measurement_source"] == "given spacing_mm; the rest recorded by calibration set 'lab'"
    assert np.allclose(doc["reading_deg"], 3 * 10.0 / 100.0 * np.array(doc["theta_deg"]), rtol=1e-9)
    # given the paper's values explicitly: they win although they are the old parser defaults
    doc = _predict(capsys, lab, "--markers-per-side", "7", "--marker-spacing-mm", "10", "--marker-offset-mm", "0",
                   "--sides", "2", "--marker-side", "fabric")
    assert doc["measurement"] == MarkerLayout().as_dict() and doc["measurement_source"] == "given"
    assert np.allclose(doc["reading_deg"], 0.5 * np.array(doc["theta_deg"]), rtol=1e-9)


def test_without_a_recorded_layout_the_paper_layout(capsys, lab):
    # the built-in set records none
    doc = _json(capsys, "predict", *ZIGZAG, "--pressure-kpa", GRID, "--measurement", "markers", "--json")
    assert doc["measurement"] == MarkerLayout().as_dict()
    assert doc["measurement_source"] == "the paper's (calibration set 'paper-2025' records none)"
    # G and P0 both given: no calibration set is used, so none lends its layout
    doc = _predict(capsys, lab, "--g-mpa", "2.7", "--p0-kpa", "85")
    assert doc["measurement"] == MarkerLayout().as_dict() and doc["measurement_source"] == "the paper's"


def test_fit_append_defaults_to_the_layout_of_the_merged_set(capsys, lab, tmp_path):
    data = tmp_path / "w8.csv"
    data.write_text("pressure_kpa,angle_deg\n0,0\n100,2\n150,8\n200,20\n250,40\n300,60\n")
    doc = _json(capsys, "fit", str(data), "--pattern", "zigzag", "--width-mm", "8", "--branch", "loading",
                "--measurement", "markers", "-o", str(lab), "--append", "--json")
    assert doc["calibration"]["marker_layout"] == LAB_LAYOUT and doc["calibration"]["points"] == 2
    assert doc["calibration"]["marker_layout_source"] == "recorded by calibration set 'lab'"
    # a flag that contradicts the set is refused in one line, the file untouched
    before = lab.read_bytes()
    assert main(["fit", str(data), "--pattern", "zigzag", "--width-mm", "8", "--branch", "loading",
                 "--measurement", "markers", "--marker-spacing-mm", "10", "-o", str(lab), "--append"]) == 2
    err = capsys.readouterr().err
    assert "differs from the set's (markers: 1 rows of 5, 12 mm apart" in err and err.count("\n") == 1
    assert lab.read_bytes() == before


def test_help_says_where_the_default_comes_from(capsys):
    assert main(["predict", "--help"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "markers in each row (default: the layout the actuator's calibration set records, if any, else 7)" in out


def test_layout_for_refuses_unknown_and_bad_fields():
    from embroact.patterns.base.errors import ParameterError

    with pytest.raises(ParameterError, match="marker layout field must be one of markers_per_side, spacing_mm"):
        layout_for(given={"spacing": 3.0})
    with pytest.raises(ParameterError, match="markers_per_side must be an integer >= 3, got 2"):
        layout_for(given={"markers_per_side": 2})
