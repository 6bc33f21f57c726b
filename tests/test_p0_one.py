"""One tube-law P0: a thick-wall design reports the same tube-law P0 in every output, the thick-wall law's at r0.

The expected value is the thick-walled Neo-Hookean tube of docs/model.md section 3 evaluated
with 50-digit mpmath (tests/mpref.py) at the sleeve radius of docs/model.md section 2; the
paper law's P0 at the same r0 (84.455 kPa for w = 7 mm) must appear nowhere.
"""
import json
import re

import pytest

import mpref
from embroact.export.cli.main import main
from embroact.export.files.designfile import load_design

DESIGN = """name = "thick"
[[actuator]]
name = "T1"
pattern = "zigzag"
width_mm = 7.0
interval_mm = 1.0
length_mm = 100.0
[actuator.model]
tube_law = "thick-wall"
"""
R0 = float(mpref.sleeve_radius(7.0, 1.5))
THICK_KPA = float(mpref.thick_wall_law(R0, 1.5, 1.0, 0.13)) * 1000.0  # 49.148 kPa
PAPER_KPA = float(mpref.paper_law(R0, 1.5, 0.13)) * 1000.0  # 84.455 kPa


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    d = tmp_path_factory.mktemp("thick")
    (d / "thick.toml").write_text(DESIGN, encoding="utf-8")
    (d / "out").mkdir()
    assert main(["build", str(d / "thick.toml"), "--out", str(d / "out")]) == 0
    return d


def test_the_two_laws_differ_here():
    assert THICK_KPA == pytest.approx(49.148, abs=1e-3) and PAPER_KPA == pytest.approx(84.455, abs=1e-3)


def _tube_law_p0s(doc) -> list[float]:
    """Every tube_law_p0_kpa anywhere in a JSON document."""
    found = []

    def walk(v):
        if isinstance(v, dict):
            for k, x in v.items():
                if k == "tube_law_p0_kpa":
                    found.append(x)
                walk(x)
        elif isinstance(v, list):
            for x in v:
                walk(x)

    walk(doc)
    return found


def test_json_outputs_carry_the_thick_wall_p0_once_per_actuator(built, capsys):
    for name in ("report.json", "worksheet.json"):
        doc = json.loads((built / "out" / name).read_text(encoding="utf-8"))
        found = _tube_law_p0s(doc)  # the report repeats the worksheet's actuator: the same value
        assert found and all(x == pytest.approx(THICK_KPA, rel=1e-12) for x in found), name
        assert "p0_kpa" not in json.dumps(doc.get("actuators", [{}])[0].get("derived", {}))  # geometry has no P0
    assert main(["predict", str(built / "thick.toml"), "--pressure-kpa", "100", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    found = _tube_law_p0s(doc)  # the actuator's model and its one segment's: the same value
    assert found and all(x == pytest.approx(THICK_KPA, rel=1e-12) for x in found)
    assert doc["actuators"][0]["model"]["tube_law"] == "thick-wall"


def test_worksheet_and_report_show_the_thick_wall_p0_and_never_the_paper_one(built):
    text = (built / "out" / "worksheet.txt").read_text(encoding="utf-8")
    (line,) = [ln for ln in text.splitlines() if "tube-law P0" in ln]
    assert float(re.search(r"([0-9.]+) kPa", line).group(1)) == pytest.approx(THICK_KPA, rel=1e-5)
    assert "thick-wall" in line
    html = (built / "out" / "report.html").read_text(encoding="utf-8")
    html = re.sub(r"<svg.*?</svg>", "", html, flags=re.S)  # the pictures' coordinates are no P0
    assert f"{THICK_KPA:.6g}" in html
    for doc in (text, html):
        assert f"{PAPER_KPA:.4g}" not in doc and f"{PAPER_KPA:.3g}" not in doc


def test_studio_shows_the_same_p0(built, tmp_path):
    from embroact.export.studio.session import Studio

    v = Studio(load_design(built / "thick.toml"), tmp_path).views(200.0)
    found = _tube_law_p0s(v["actuators"])
    assert found and all(x == pytest.approx(THICK_KPA, rel=1e-12) for x in found)
    assert f"{PAPER_KPA:.4g}" not in json.dumps({k: x for k, x in v.items() if not k.endswith("_svg")})


def test_geometry_source_uses_the_same_value(tmp_path, capsys):
    p = tmp_path / "geo.toml"
    p.write_text(DESIGN + 'p0_source = "geometry"\n', encoding="utf-8")
    assert main(["predict", str(p), "--pressure-kpa", "100", "--json"]) == 0
    model = json.loads(capsys.readouterr().out)["actuators"][0]["model"]
    assert model["p0_kpa"] == model["tube_law_p0_kpa"] == pytest.approx(THICK_KPA, rel=1e-12)
