"""A fitted calibration's 1-sigma band in the build's views: bend chart, report.json, report.html.

The band comes from the calibration file's covariance (``embroact fit -o``); the build must
quote the same band ``embroact predict --json`` gives at the same pressures, shade it in the
bend chart, and claim none for the built-in paper set, which carries no covariance.
"""
import json
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from embroact.export.cli.main import main

SVG = "{http://www.w3.org/2000/svg}"
#: Six scattered points of a w = 7 mm zigzag: a fit with a band wide enough to see (G +- 5 %).
POOR_DATA = "pressure_kpa,angle_deg\n0,0\n100,14\n140,40\n180,95\n220,125\n260,195\n"
DESIGN = ('name = "banded"\n[[actuator]]\nname = "Z7"\npattern = "zigzag"\nwidth_mm = 7.0\ninterval_mm = 1.0\n'
          'length_mm = 100.0\n[actuator.model]\ncalibration = "{cal}"\n')


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """A design whose actuator uses a fitted calibration file, built; and the same design on the paper set."""
    root = tmp_path_factory.mktemp("band")
    (root / "poor.csv").write_text(POOR_DATA)
    assert main(["fit", str(root / "poor.csv"), "--pattern", "zigzag", "--width-mm", "7", "-o",
                 str(root / "lab.toml")]) == 0
    out = {}
    for name, cal in (("fitted", "lab.toml"), ("paper", "paper-2025")):
        (root / f"{name}.toml").write_text(DESIGN.format(cal=cal))
        (root / name).mkdir()
        assert main(["build", str(root / f"{name}.toml"), "--out", str(root / name), "--mesh-format", "none"]) in (0, 1)
        out[name] = root / name
    out["design"] = root / "fitted.toml"
    return out


def test_report_json_quotes_the_band_predict_gives(built, capsys):
    capsys.readouterr()
    (act,) = json.loads((built["fitted"] / "report.json").read_text())["actuators"]
    band, curve = act["band"], act["curve"]
    assert band["parameters"] == ["g_mpa", "p0_kpa"] and len(band["theta_sd_deg"]) == len(curve["pressure_kpa"])
    grid = ",".join(f"{p:g}" for p in curve["pressure_kpa"])
    assert main(["predict", str(built["design"]), "--pressure-kpa", grid, "--json"]) == 0
    (pred,) = json.loads(capsys.readouterr().out)["actuators"]
    for key in ("theta_sd_deg", "theta_low_deg", "theta_high_deg", "covariance"):
        assert np.allclose(band[key], pred["band"][key], rtol=1e-12, atol=0.0), key
    sd, theta = np.array(band["theta_sd_deg"]), np.array(curve["theta_deg"])
    assert np.all(sd[theta == 0.0] == 0.0) and 1.0 < sd.max() < 20.0
    # the edge toward zero stays at zero (a later P0 keeps the strip straight, it never bends it back)
    assert np.all(np.array(band["theta_low_deg"]) >= 0.0)
    bent = (theta - sd) > 0.0
    assert np.allclose(np.array(band["theta_low_deg"])[bent], (theta - sd)[bent], rtol=1e-12)


def test_bend_chart_shades_the_band_and_the_paper_set_has_none(built):
    root = ET.parse(built["fitted"] / "bend.svg").getroot()
    polygons = [e for e in root.iter(SVG + "polygon") if e.get("class") == "band"]
    assert len(polygons) == 1 and "1-sigma band" in [t.text for t in root.iter(SVG + "text")]
    paper = ET.parse(built["paper"] / "bend.svg").getroot()
    assert not [e for e in paper.iter(SVG + "polygon") if e.get("class") == "band"]
    (act,) = json.loads((built["paper"] / "report.json").read_text())["actuators"]
    assert act.get("band") is None


def test_report_html_quotes_theta_with_its_band(built):
    html = (built["fitted"] / "report.html").read_text()
    (act,) = json.loads((built["fitted"] / "report.json").read_text())["actuators"]
    i = act["curve"]["pressure_kpa"].index(200.0)
    theta, sd = act["curve"]["theta_deg"][i], act["band"]["theta_sd_deg"][i]
    assert f'<td class="num">{theta:.6g} +- {sd:.3g}</td>' in html
    assert "1-sigma band of the fitted calibration's covariance" in html
    assert " +- " not in (built["paper"] / "report.html").read_text().split("Predicted curve")[1]
