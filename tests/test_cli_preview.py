"""``embroact preview``: every kind, pressure parsing, one-line errors, lazy trimesh."""
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from embroact.export.cli.main import main
from embroact.export.cli.args import parse_pressures
from embroact.patterns.base.errors import ParameterError

SVG = "{http://www.w3.org/2000/svg}"

DESIGN = """
name = "two"
[[actuator]]
name = "Z5"
pattern = "zigzag"
width_mm = 5.0
interval_mm = 1.0
length_mm = 60.0
[[actuator]]
name = "Z9"
pattern = "zigzag"
width_mm = 9.0
interval_mm = 1.0
length_mm = 60.0
origin_mm = [0.0, 30.0]
"""


@pytest.mark.parametrize("text, match", [
    ("0:300:0", "step must be > 0"),
    ("300:0:10", "stop must be >= start"),
    ("a,b", "is not a number"),
    ("-5", "must be finite and >= 0 kPa"),
    ("2e5", "must be <= 100000 kPa"),
    ("0:1e5:1e-3", "at most 100000 pressures"),
    (",", "must list 1 to 100000 pressures"),
])
def test_parse_pressures_errors(text, match):
    with pytest.raises(ParameterError, match=match):
        parse_pressures(text)


def test_bend_chart_has_one_point_per_pressure(tmp_path, capsys):
    out = tmp_path / "bend.svg"
    assert main(["preview", "bend", "-o", str(out), "--pressure-kpa", "0:300:25"]) == 0
    assert "13 pressures" in capsys.readouterr().out
    lines = [e for e in ET.parse(out).getroot().iter(SVG + "polyline") if e.get("class") == "curve"]
    # the 13 pressures and the curve's breakpoint, P0 = 85 kPa (the inflation part ends there)
    assert sum(len(e.get("points").split()) for e in lines) == 14


def test_design_file_with_two_actuators(tmp_path):
    design = tmp_path / "two.toml"
    design.write_text(DESIGN)
    bend, side, stl = tmp_path / "b.svg", tmp_path / "s.svg", tmp_path / "m.stl"
    assert main(["preview", "bend", str(design), "-o", str(bend), "--pressure-kpa", "0:200:20"]) == 0
    root = ET.parse(bend).getroot()
    assert {e.get("data-series") for e in root.iter(SVG + "polyline") if e.get("class") == "curve"} == {"0", "1"}
    assert main(["preview", "shape", str(design), "-o", str(side), "--states", "3"]) == 0
    groups = [g for g in ET.parse(side).getroot().iter(SVG + "g") if g.get("class") == "state"]
    assert len(groups) == 6  # 3 pressures x 2 actuators
    assert main(["preview", "mesh", str(design), "-o", str(stl), "--tolerance-mm", "0.2"]) == 0
    import trimesh

    mesh = trimesh.load(stl, force="mesh")
    assert len(mesh.faces) > 0 and mesh.bounds[1][1] - mesh.bounds[0][1] > 30.0  # the actuators lie 30 mm apart


def test_stitches_and_mesh_picture(tmp_path, capsys):
    st, pic = tmp_path / "st.svg", tmp_path / "pic.svg"
    assert main(["preview", "stitches", "-o", str(st)]) == 0
    assert main(["preview", "mesh", "-o", str(pic), "--shape-pressure-kpa", "150"]) == 0
    out = capsys.readouterr().out
    assert "106 stitches" in out and "at 150 kPa" in out and "max deviation" in out
    polys = list(ET.parse(pic).getroot().iter(SVG + "polygon"))
    assert len(polys) > 100


@pytest.mark.parametrize("argv, code, message", [
    (["preview", "bend", "-o", "{tmp}/x.png"], 2, "must end in .svg"),
    (["preview", "mesh", "-o", "{tmp}/x.fbx"], 2, ".glb, .stl, .obj, .ply, .svg"),
    (["preview", "bend", "-o", "{tmp}/x.svg", "--pressure-kpa", "5:1:1"], 2, "--pressure-kpa"),
    (["preview", "mesh", "-o", "{tmp}/x.glb", "--tolerance-mm", "-1"], 2, "tolerance_mm must be in"),
    (["preview", "mesh", "-o", "{tmp}/x.glb", "--shape-pressure-kpa", "900"], 2, "shape_pressure_kpa"),
    (["preview", "shape", "-o", "{tmp}/x.svg", "--states", "0"], 2, "states must be"),
    (["preview", "bend", "-o", "{tmp}/missing/x.svg"], 3, "does not exist"),
    (["preview", "bend", "{tmp}/none.toml", "-o", "{tmp}/x.svg"], 2, "none.toml"),
])
def test_errors_are_one_line_and_write_nothing(tmp_path, capsys, argv, code, message):
    argv = [a.format(tmp=tmp_path) for a in argv]
    assert main(argv) == code
    err = capsys.readouterr().err.strip()
    assert err.startswith("embroact: error:") and message in err and "\n" not in err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("kind, suffix, loads", [("bend", ".svg", False), ("shape", ".svg", False),
                                                 ("mesh", ".glb", False), ("mesh", ".stl", True)])
def test_trimesh_only_for_mesh(tmp_path, kind, suffix, loads):
    """trimesh only for the mesh formats it writes (STL, OBJ, PLY); GLB is written without it."""
    out = tmp_path / f"x{suffix}"
    code = ("import sys; from embroact.export.cli.main import main; "
            f"rc = main(['preview', '{kind}', '-o', r'{out}', '--pressure-kpa', '0:300:100']); "
            "print(rc, 'trimesh' in sys.modules)")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert res.stdout.split()[-2:] == ["0", str(loads)]


def test_same_bytes_twice(tmp_path):
    a, b = tmp_path / "a.glb", tmp_path / "b.glb"
    assert main(["preview", "mesh", "-o", str(a), "--tolerance-mm", "0.5"]) == 0
    assert main(["preview", "mesh", "-o", str(b), "--tolerance-mm", "0.5"]) == 0
    assert a.read_bytes() == b.read_bytes()
    assert np.frombuffer(a.read_bytes()[:4], dtype=np.uint8).tobytes() == b"glTF"


def test_measured_points_overlay_at_their_coordinates(tmp_path):
    from embroact.export.pictures.chart import chart_scale

    csv = tmp_path / "loop.csv"
    csv.write_text("pressure_kpa,angle_deg\n0,0\n150,40\n300,120\n150,60\n")
    out = tmp_path / "b.svg"
    assert main(["preview", "bend", "-o", str(out), "--pressure-kpa", "0:300:50", "--measured", f"A1={csv}"]) == 0
    circles = [e for e in ET.parse(out).getroot().iter(SVG + "circle") if e.get("class") == "measured"]
    got = np.array([[float(c.get("cx")), float(c.get("cy"))] for c in circles])
    # the same chart scale, rebuilt from the series the command drew
    from embroact.export.pictures import previews as pv
    from embroact.patterns.design import default_design
    from embroact.predict.analysis import analyse

    analysis = analyse(default_design())
    curves = analysis.curves(parse_pressures("0:300:50"))
    sc = chart_scale(pv.bend_series(analysis, curves, {"A1": ([0, 150, 300, 150], [0, 40, 120, 60])}))
    want = np.column_stack([sc.x_px([0, 150, 300, 150]), sc.y_px([0, 40, 120, 60])])
    assert np.abs(got - want).max() <= 0.006
    assert sc.y_max_deg >= 120.0


def test_json_output_names_file_kind_and_counts(tmp_path, capsys):
    import json

    out = tmp_path / "bend.svg"
    assert main(["preview", "bend", "-o", str(out), "--pressure-kpa", "0:300:100", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["file"] == str(out) and doc["kind"] == "bend"
    assert doc["pressure_kpa"] == [0.0, 100.0, 200.0, 300.0] and [a["name"] for a in doc["actuators"]] == ["A1"]
    (act,) = doc["actuators"]
    assert (act["model"]["g_mpa"], act["model"]["p0_kpa"]) == (2.7, 85.0)  # paper-2025, zigzag w = 7 mm
    assert act["model"]["p0_source"] == "calibration paper-2025 (zigzag, width_mm=7)"
    assert act["curve"]["status"][0] == "INFLATION" and act["curve"]["pressure_kpa"] == doc["pressure_kpa"]
    assert out.exists()


def test_stitches_of_a_machine_file_are_its_records_to_scale(tmp_path, capsys):
    """preview stitches x.dst: one needle-point dot per stitch pystitch reads, at its place (y flipped)."""
    import xml.etree.ElementTree as ET

    import pystitch

    dst, svg = tmp_path / "three.dst", tmp_path / "three.svg"
    examples = Path(__file__).resolve().parent.parent / "examples"
    assert main(["build", str(examples / "three_actuators.toml"), "--out", str(tmp_path), "--no-previews"]) == 0
    shutil.move(tmp_path / "three-actuators.dst", dst)
    capsys.readouterr()
    assert main(["preview", "stitches", str(dst), "-o", str(svg)]) == 0
    assert capsys.readouterr().out.startswith(f"wrote {svg}: stitches of three.dst, ")
    stitches = [(x / 10.0, y / 10.0) for x, y, c in pystitch.read(str(dst)).stitches if c == pystitch.STITCH]
    ns = {"svg": "http://www.w3.org/2000/svg"}
    dots = ET.parse(svg).getroot().findall(".//svg:g[@id='needle-points']/svg:circle", ns)
    assert len(dots) == len(stitches) == 292
    drawn = sorted((float(d.get("cx")), float(d.get("cy"))) for d in dots)  # SVG y down: the file's own y
    np.testing.assert_allclose(drawn, sorted(stitches), atol=1e-3)
    assert main(["preview", "bend", str(dst), "-o", str(tmp_path / "b.svg")]) == 2
    assert "previews the stitches only" in capsys.readouterr().err
