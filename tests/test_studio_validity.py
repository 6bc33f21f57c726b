"""States past a validity limit: the studio, ``preview shape`` and ``preview mesh`` leave them undrawn, say why
in one line, and agree on the range the model describes.

The expected range is read off the analysis's statuses directly (the highest sampled pressure whose
status is an equilibrium or a branch end), not from the views' own helpers.
"""
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from embroact.export.cli.main import main
from embroact.export.files.designfile import load_design
from embroact.predict.analysis import analyse
from embroact.predict.status import Status

EXAMPLE = str(Path(__file__).resolve().parents[1] / "examples" / "three_actuators.toml")
SVG = "{http://www.w3.org/2000/svg}"
DESCRIBED = {Status.INFLATION, Status.BENDING, Status.LOCKED, Status.UNSTABLE}


def highest_described_kpa(analysis, k: int) -> float:
    c = analysis.curves()[k]
    return max(p for p, s in zip(c.pressure_kpa, c.status) if Status(int(s)) in DESCRIBED)


@pytest.fixture(scope="module")
def analysis():
    return analyse(load_design(EXAMPLE))


def test_the_narrow_zigzag_coils_at_167_kpa(analysis):  # the premise of the tests below
    c = analysis.curves([167.0])[0]
    assert Status(int(c.status[0])) is Status.COILED and c.theta_deg[0] > 270.0
    assert highest_described_kpa(analysis, 0) == 150.0


@pytest.fixture
def client(tmp_path):
    pytest.importorskip("starlette")
    pytest.importorskip("httpx2")
    from starlette.testclient import TestClient

    from embroact.export.studio.app import create_app
    from embroact.export.studio.session import Studio

    app = create_app(Studio(load_design(EXAMPLE), tmp_path), token="t", port=8123)
    return TestClient(app, base_url="http://127.0.0.1:8123")


def panels(svg: str) -> list:
    return ET.fromstring(svg).findall(f".//{SVG}g[@class='panel']")


def states(panel) -> list[str]:
    return [g.get("data-pressure-kpa") for g in panel.iter(f"{SVG}g") if g.get("class") == "state"]


def note(panel) -> str | None:
    found = [t.text for t in panel.iter(f"{SVG}text") if t.get("class") == "not-drawn"]
    return found[0] if found else None


def test_the_studio_reports_and_does_not_draw_a_coiled_state(client, analysis):
    v = client.get("/api/views?pressure_kpa=167&token=t").json()
    narrow, wide, cross = v["actuators"]
    hi = highest_described_kpa(analysis, 0)
    assert narrow["status"] == "COILED" and narrow["drawn"] is False
    assert narrow["described_kpa"] == [0.0, hi]
    assert narrow["note"] == f"not drawn at 167 kPa: COILED; the model describes 0-{hi:g} kPa"
    assert wide["drawn"] and cross["drawn"] and wide["note"] is None
    side = panels(v["side_svg"])
    assert states(side[0]) == ["0"] and note(side[0]) == narrow["note"]  # only the unbent reference
    assert states(side[1]) == ["0", "167"] and note(side[1]) is None
    assert 'class="pressure-dot"' in v["chart_svg"]  # the drawn ones keep their dots
    shape = client.get("/api/shape3d?pressure_kpa=167&token=t").json()["svg"]
    names = [t.text for t in ET.fromstring(shape).iter(f"{SVG}text")]
    assert "narrow zigzag" not in names and "wide zigzag" in names
    assert "narrow zigzag not drawn at 167 kPa: COILED" in " ".join(n or "" for n in names)


def test_at_the_limit_the_studio_draws_it(client, analysis):
    hi = highest_described_kpa(analysis, 0)
    v = client.get(f"/api/views?pressure_kpa={hi:g}&token=t").json()
    assert v["actuators"][0]["drawn"] and v["actuators"][0]["note"] is None
    assert states(panels(v["side_svg"])[0]) == ["0", f"{hi:g}"]


def test_the_cli_and_the_studio_agree_on_the_range(client, analysis, tmp_path, capsys):
    hi = highest_described_kpa(analysis, 0)
    out = tmp_path / "m.svg"
    assert main(["preview", "mesh", EXAMPLE, "--shape-pressure-kpa", "167", "-o", str(out)]) == 2
    assert f"must be in [0, {hi:g}]" in capsys.readouterr().err and not out.exists()
    assert main(["preview", "mesh", EXAMPLE, "--shape-pressure-kpa", f"{hi:g}", "-o", str(out)]) == 0
    v = client.get("/api/views?pressure_kpa=167&token=t").json()
    assert v["actuators"][0]["described_kpa"] == [0.0, hi]


def test_preview_shape_says_why_a_panel_is_empty(tmp_path, analysis):
    out = tmp_path / "s.svg"
    assert main(["preview", "shape", EXAMPLE, "--pressure-kpa", "167", "-o", str(out)]) == 0
    narrow, wide, _ = panels(out.read_text())
    hi = highest_described_kpa(analysis, 0)
    assert states(narrow) == [] and note(narrow) == f"not drawn at 167 kPa: COILED; the model describes 0-{hi:g} kPa"
    assert states(wide) == ["167"] and note(wide) is None


def test_preview_shape_over_the_default_pressures_notes_the_states_left_out(tmp_path, analysis):
    out = tmp_path / "s.svg"
    assert main(["preview", "shape", EXAMPLE, "-o", str(out)]) == 0
    narrow = panels(out.read_text())[0]
    hi = highest_described_kpa(analysis, 0)
    assert max(float(p) for p in states(narrow)) == hi
    assert note(narrow) == f"not drawn at {hi + 10:g}-250 kPa: COILED; the model describes 0-{hi:g} kPa"
