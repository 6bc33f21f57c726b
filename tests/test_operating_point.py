"""A designed file keeps the operation limits and marks its target as the operating point; `design`, `check`,
`build` and the studio give the same findings for it.

Expected values come from the written file itself (read back with ``load_design``), from `check --json`,
`build --json` and the studio's views of that file, never from the design search's own result.
"""
import json
import re

import pytest

from embroact.export.cli.main import main
from embroact.export.files.designfile import load_design
from embroact.patterns.design import OperationSettings

pytest.importorskip("starlette")
from embroact.export.studio.session import Studio  # noqa: E402

import sys  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import inverse_targets  # noqa: E402


def _run_json(capsys, argv):
    capsys.readouterr()
    code = main(argv + ["--json"])
    return code, json.loads(capsys.readouterr().out)


def _texts(found):
    return sorted(f"{f['code']} {f['severity']}: {f['message']}" for f in found)


def _marks(svg):
    """(pressure, bend) of each operating-point diamond of a chart."""
    return [(re.search(r'data-pressure-kpa="([^"]+)"', m).group(1), re.search(r'data-theta-deg="([^"]+)"', m).group(1))
            for m in re.findall(r'<polygon class="operating-point"[^>]*>', svg)]


def _agree(capsys, tmp_path, path, design_findings):
    """check, build and the studio give for ``path`` the findings `design` listed."""
    _, checked = _run_json(capsys, ["check", str(path)])
    out = tmp_path / "build"
    out.mkdir(exist_ok=True)
    _, built = _run_json(capsys, ["build", str(path), "--out", str(out), "--force"])
    studio = Studio(load_design(path), tmp_path / "studio").views()
    assert sorted(design_findings) == _texts(checked["findings"]) == _texts(built["findings"]) \
        == _texts(studio["findings"])
    return built, studio, out


def test_a_bend_design_keeps_the_limits_and_marks_its_target(tmp_path, capsys):
    path = tmp_path / "bend.toml"
    code, res = _run_json(capsys, ["design", "--bend-deg", "84.5", "--at-kpa", "150", "--pattern", "zigzag",
                                   "-o", str(path)])
    assert code == 0
    op = load_design(path).operation
    assert op == OperationSettings(300.0, 180.0, 150.0, 84.5)  # the default limits, not the target pressure
    built, studio, out = _agree(capsys, tmp_path, path, res["best"]["findings"])
    # the limits are the ones the rules judge by: at 300 kPa the 6.2 mm zigzag bends past 180 deg
    assert any(f.startswith("EA403 warning") for f in res["best"]["findings"])
    assert _marks((out / "bend.svg").read_text()) == [("150", "84.5")]
    assert _marks(studio["chart_svg"]) == [("150", "84.5")]
    text = (out / "worksheet.txt").read_text()
    assert "operating point  84.5 deg at 150 kPa (the design's target; the rules judge up to 300 kPa)" in text
    sheet = json.loads((out / "worksheet.json").read_text())
    assert sheet["operating_point"] == {"target_pressure_kpa": 150.0, "target_bend_deg": 84.5,
                                        "max_pressure_kpa": 300.0}
    assert studio["pressure_kpa"] == 150.0  # the studio opens at the operating point


def test_the_users_limits_are_kept_and_widened_only_to_the_target(tmp_path, capsys):
    path = tmp_path / "bend.toml"
    code, res = _run_json(capsys, ["design", "--bend-deg", "84.5", "--at-kpa", "150", "--pattern", "zigzag",
                                   "--max-pressure-kpa", "160", "--max-bend-deg", "120", "-o", str(path)])
    assert code == 0 and load_design(path).operation == OperationSettings(160.0, 120.0, 150.0, 84.5)
    _agree(capsys, tmp_path, path, res["best"]["findings"])
    code, res = _run_json(capsys, ["design", "--bend-deg", "84.5", "--at-kpa", "150", "--pattern", "zigzag",
                                   "--max-pressure-kpa", "100", "--max-bend-deg", "30", "-o", str(path)])
    assert load_design(path).operation == OperationSettings(150.0, 84.5, 150.0, 84.5)
    capsys.readouterr()
    assert main(["design", "--bend-deg", "84.5", "--at-kpa", "150", "--max-pressure-kpa", "-3", "-o", str(path)]) == 2
    assert capsys.readouterr().err.strip().splitlines()[-1] == \
        "embroact: error: --max-pressure-kpa must be in (0, 100000), got -3"


def test_a_shape_design_writes_its_target_as_operating_point_not_as_max_pressure(tmp_path, capsys):
    _, xy = inverse_targets.target_shape(1, step_mm=0.5)
    csv = tmp_path / "shape.csv"
    csv.write_text("x_mm,y_mm\n" + "".join(f"{x:.5f},{y:.5f}\n" for x, y in xy))
    path = tmp_path / "shape.toml"
    code, res = _run_json(capsys, ["design", "--target-shape", str(csv), "--at-kpa", "200", "-o", str(path)])
    assert code == 0
    assert load_design(path).operation == OperationSettings(300.0, 180.0, 200.0, None)
    built, studio, out = _agree(capsys, tmp_path, path, res["findings"])
    marks = _marks((out / "bend.svg").read_text())
    assert len(marks) == 1 and marks[0][0] == "200"  # on the whole strip's curve, at its predicted bend
    _, pred = _run_json(capsys, ["predict", str(path), "--pressure-kpa", "200"])
    assert float(marks[0][1]) == pytest.approx(pred["actuators"][0]["theta_deg"][0], rel=1e-5)


def test_an_operating_point_beyond_the_limits_is_refused_in_the_design_file(tmp_path):
    from embroact.patterns.design import design_from_dict
    from embroact.patterns.base.errors import DesignFileError

    act = {"name": "A", "pattern": "zigzag", "width_mm": 7.0, "interval_mm": 1.0, "length_mm": 100.0}
    with pytest.raises(DesignFileError, match=r"^operation: target_pressure_kpa must be in \(0, 300\], got 400$"):
        design_from_dict({"operation": {"target_pressure_kpa": 400}, "actuator": [act]})
    with pytest.raises(DesignFileError, match="target_bend_deg 90 needs target_pressure_kpa"):
        design_from_dict({"operation": {"target_bend_deg": 90}, "actuator": [act]})


def test_the_studios_target_bend_is_judged_by_the_designs_own_limits(tmp_path, capsys):
    """The studio searched with the default 300 kPa / 180 deg limits whatever the design's [operation] said, so
    its answer listed EA403/EA405 that `design --max-pressure-kpa 150` and `check` of that design do not give."""
    import dataclasses

    from embroact.patterns.design import default_design

    code, cli = _run_json(capsys, ["design", "--bend-deg", "84.5", "--at-kpa", "150", "--pattern", "zigzag",
                                   "--max-pressure-kpa", "150", "-o", str(tmp_path / "d.toml")])
    assert code == 0
    design = dataclasses.replace(default_design(), operation=OperationSettings(150.0, 180.0))
    answer = Studio(design, str(tmp_path)).inverse(84.5, 150.0, pattern="zigzag")
    assert answer["best"]["findings"] == cli["best"]["findings"]
    assert not [f for f in answer["best"]["findings"] if f.startswith(("EA403", "EA405"))]
