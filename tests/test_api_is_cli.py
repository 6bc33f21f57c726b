"""The API is the CLI: ``embroact.load_design`` / ``analyse`` / ``build`` read a design as the commands do.

A design naming a calibration file next to it (and an SVG drawing) is read from another
working directory through the API and through ``embroact predict`` / ``embroact build``;
the numbers and the written files must agree. The calibration's G and P0 are chosen here
(2.0 MPa, 90 kPa), so a reader that fell back to the built-in set shows at once.
"""
import json
import os
from pathlib import Path

import pytest

import embroact
from embroact.export.cli.main import main
from embroact.export.files.calibfile import write_calibration
from embroact.predict.calibration import CalibrationPoint, CalibrationSet

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@pytest.fixture
def design_dir(tmp_path, monkeypatch):
    d = tmp_path / "designs"
    d.mkdir()
    write_calibration(d / "calA.toml", CalibrationSet("calA", (CalibrationPoint("zigzag", 7.0, 2.0, 90.0),)))
    (d / "lab.toml").write_text('name = "lab"\n[[actuator]]\nname = "A1"\npattern = "zigzag"\nwidth_mm = 7.0\n'
                                'interval_mm = 1.0\nlength_mm = 100.0\n[actuator.model]\ncalibration = "calA.toml"\n',
                                encoding="utf-8")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)  # relative references resolve against the design file, not the cwd
    return d


def test_analyse_reads_the_calibration_file_the_design_names(design_dir, capsys):
    a = embroact.analyse(embroact.load_design(design_dir / "lab.toml"))
    m = a.actuators[0].model
    assert (m.g_mpa, m.p0_kpa) == (2.0, 90.0)
    assert main(["predict", str(design_dir / "lab.toml"), "--pressure-kpa", "150,250", "--json"]) == 0
    (cli,) = json.loads(capsys.readouterr().out)["actuators"]
    assert cli["model"]["g_mpa"] == 2.0 and cli["model"]["p0_kpa"] == 90.0
    assert [float(t) for t in a.curves([150.0, 250.0])[0].theta_deg] == cli["theta_deg"]


def test_build_writes_what_the_command_writes(design_dir, tmp_path, capsys):
    api_out, cli_out = tmp_path / "api", tmp_path / "cli"
    api_out.mkdir()
    cli_out.mkdir()
    res = embroact.build(embroact.load_design(design_dir / "lab.toml"), api_out)
    assert main(["build", str(design_dir / "lab.toml"), "--out", str(cli_out)]) == 0
    assert sorted(os.listdir(api_out)) == sorted(os.listdir(cli_out)) == sorted(res.files)
    assert "report.json" in res.files
    for name in res.files:
        assert (api_out / name).read_bytes() == (cli_out / name).read_bytes(), name
    report = json.loads((api_out / "report.json").read_text(encoding="utf-8"))
    assert report["actuators"][0]["model"]["g_mpa"] == 2.0


def test_svg_references_resolve_as_on_the_command_line(monkeypatch, tmp_path, capsys):
    monkeypatch.chdir(tmp_path)
    a = embroact.analyse(embroact.load_design(EXAMPLES / "inkscape_tubes.toml"))
    assert main(["predict", str(EXAMPLES / "inkscape_tubes.toml"), "--pressure-kpa", "100", "--json"]) == 0
    cli = json.loads(capsys.readouterr().out)["actuators"]
    assert [x.derived.length_mm for x in a.actuators] == [c["derived"]["length_mm"] for c in cli]
    # and the same bend and model: the paths the drawing gives decide both
    assert [[float(t) for t in c.theta_deg] for c in a.curves([100.0])] == [c["theta_deg"] for c in cli]
    assert [x.as_dict()["model"] for x in a.actuators] == [c["model"] for c in cli]


def test_predict_json_has_one_schema_for_quick_parameters_and_design_files(tmp_path, capsys):
    path = tmp_path / "z.toml"
    path.write_text('name = "quick"\n[[actuator]]\nname = "A1"\npattern = "zigzag"\nwidth_mm = 7.0\n'
                    'interval_mm = 1.0\nlength_mm = 100.0\n', encoding="utf-8")
    assert main(["predict", "zigzag", "--width-mm", "7", "--pressure-kpa", "150", "--json"]) == 0
    quick = json.loads(capsys.readouterr().out)
    assert main(["predict", str(path), "--pressure-kpa", "150", "--json"]) == 0
    design = json.loads(capsys.readouterr().out)
    assert quick == design  # the same actuator: the same document, key for key
