"""``embroact design``: target bends checked by ``embroact predict`` on the written file, target shapes, errors."""
import json
import sys
from pathlib import Path

import numpy as np
import pytest

from embroact.export.cli.main import main

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from inverse_targets import PRESSURE_KPA, target_shape  # noqa: E402


def _json(capsys, argv):
    capsys.readouterr()
    assert main(argv + ["--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("bend, pressure, pattern", [(84.5, 150.0, "zigzag"), (-40.0, 250.0, "cross"),
                                                     (30.0, 220.0, "cross")])
def test_target_bend_met_as_predict_reads_the_file(tmp_path, capsys, bend, pressure, pattern):
    out = tmp_path / "d.toml"
    res = _json(capsys, ["design", "--bend-deg", str(bend), "--at-kpa", str(pressure), "--pattern", pattern,
                         "-o", str(out)])
    assert res["reached"] and res["best"]["pattern"] == pattern
    pred = _json(capsys, ["predict", str(out), "--pressure-kpa", str(pressure)])
    theta = pred["actuators"][0]["theta_deg"][0]
    assert abs(theta - bend) <= 0.5
    assert pred["actuators"][0]["status"] == ["BENDING"]
    first = out.read_bytes()
    assert main(["design", "--bend-deg", str(bend), "--at-kpa", str(pressure), "--pattern", pattern, "-o",
                 str(out)]) == 0
    assert out.read_bytes() == first  # deterministic, byte for byte


def test_target_shape_from_csv(tmp_path, capsys):
    _, xy = target_shape(6, step_mm=0.5)
    csv = tmp_path / "shape.csv"
    csv.write_text("x_mm,y_mm\n" + "".join(f"{x:.5f},{y:.5f}\n" for x, y in xy))
    out = tmp_path / "s.toml"
    res = _json(capsys, ["design", "--target-shape", str(csv), "--at-kpa", str(PRESSURE_KPA), "-o", str(out)])
    assert res["reached"] and res["rmse_mm"] < 0.5
    svg = Path(res["svg"]).read_text()
    assert 'class="target"' in svg and 'class="predicted"' in svg
    assert svg.count('class="boundary"') == len(res["segments"]) - 1
    from embroact.export.files.designfile import load_design
    design = load_design(out)
    assert len(design.actuators[0].segments) == len(res["segments"])
    assert design.actuators[0].centerline.length_mm == pytest.approx(np.hypot(*np.diff(xy, axis=0).T).sum(), abs=0.01)


@pytest.mark.parametrize("argv, needle", [
    (["--bend-deg", "90", "--at-kpa", "-5"], "--at-kpa must be in (0, 10000), got -5"),
    (["--bend-deg", "90", "--at-kpa", "150", "--length-mm", "5"], "length_mm must be in"),
    (["--bend-deg", "90", "--at-kpa", "150", "--pattern", "satin"], "invalid choice"),
])
def test_bad_input_is_one_line(tmp_path, capsys, argv, needle):
    assert main(["design", *argv, "-o", str(tmp_path / "x.toml")]) == 2
    err = capsys.readouterr().err.strip()
    assert needle in err and "\n" not in err
    assert not (tmp_path / "x.toml").exists()


def test_bad_shape_file(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text("x,y\n0,0\n")
    assert main(["design", "--target-shape", str(bad), "--at-kpa", "200", "-o", str(tmp_path / "x.toml")]) == 2
    assert "header x_mm,y_mm" in capsys.readouterr().err
    bad.write_text("x_mm,y_mm\n0,0\n1,oops\n")
    assert main(["design", "--target-shape", str(bad), "--at-kpa", "200", "-o", str(tmp_path / "x.toml")]) == 2
    assert "row 3" in capsys.readouterr().err


def test_target_shape_from_an_svg_path(tmp_path, capsys):
    """An SVG drawing's path in real units is a target (y flipped to y up, like every SVG path)."""
    from embroact.predict.shape import BentShape

    xy = BentShape.chain([40.0, 50.0], [40.0, -30.0]).profile_mm(np.linspace(0.0, 90.0, 181))
    d = "M " + " L ".join(f"{x:.4f} {-y:.4f}" for x, y in xy)
    svg = tmp_path / "t.svg"
    svg.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="200mm" height="200mm" viewBox="0 0 200 200">'
                   f'<path id="target" d="{d}" fill="none" stroke="black"/></svg>')
    res = _json(capsys, ["design", "--target-shape", f"{svg}#target", "--at-kpa", "250", "-o",
                         str(tmp_path / "s.toml")])
    assert res["reached"] and res["rmse_mm"] < 0.5
    assert [s["pattern"] for s in res["segments"]] == ["zigzag", "cross"]


def test_a_limit_far_past_the_target_is_reported_as_none(tmp_path, capsys):
    """cross -40 deg at 250 kPa: its first limit lay at 82 MPa ('COILED at 82253.5 kPa'), a state of no sewn actuator;
    past ten times the target pressure the limit line says none up to there."""
    import re

    from embroact.export.cli.main import main

    assert main(["design", "--bend-deg", "-40", "--at-kpa", "250", "--pattern", "cross",
                 "-o", str(tmp_path / "c.toml")]) == 0
    limits = [ln for ln in capsys.readouterr().out.splitlines() if ln.strip().startswith("limit:")]
    assert limits and limits[0].strip() == "limit: none up to 2500 kPa (10 x the target pressure)", limits
    for ln in limits:
        assert all(float(v) <= 2500.0 for v in re.findall(r"([\d.]+) kPa", ln)), ln
