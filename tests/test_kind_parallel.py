"""A third pattern kind from one module (tests/kind_parallel.py): it builds, checks, predicts, shows in the studio.

The steps are exactly the README's "Adding a pattern kind": one module defines the parameter
class and the generator, registers the kind and one model row. Expected values are derived
by hand from the pattern's construction (legs straight across every ``interval_mm``) and
the model's fixed-radius constraint, not read from embroact's output.
"""
import json
import math
from pathlib import Path

import pytest

import kind_parallel
from embroact.export.cli.main import main
from embroact.patterns.base.errors import ParameterError
from embroact.patterns.kinds import PATTERN_KINDS, pattern_kind
from embroact.predict.inverse import design_bend
from embroact.predict.kinds import MODEL_KINDS, Constraint

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

DESIGN = """name = "par"
[[actuator]]
name = "P1"
pattern = "parallel"
width_mm = 7.0
interval_mm = 2.0
length_mm = 100.0
[actuator.model]
g_mpa = 2.7
p0_kpa = 85.0
"""


@pytest.fixture(scope="module", autouse=True)
def parallel_registered():
    mine = kind_parallel.register_parallel()
    yield
    if mine:  # with EMBROACT_TEST_KINDS=1 the whole session keeps it
        kind_parallel.unregister_parallel()


@pytest.fixture
def design_file(tmp_path):
    p = tmp_path / "par.toml"
    p.write_text(DESIGN, encoding="utf-8")
    return p


def test_registered_once_from_one_module():
    assert pattern_kind("parallel") is kind_parallel.KIND
    assert MODEL_KINDS["parallel"].constraint is Constraint.FIXED_RADIUS
    with pytest.raises(ParameterError, match="already registered"):
        PATTERN_KINDS.add(kind_parallel.KIND)


def test_build_writes_the_legs_the_construction_gives(design_file, tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    assert main(["build", str(design_file), "--out", str(out)]) == 0
    report = json.loads((out / "report.json").read_text(encoding="utf-8"))
    (act,) = report["actuators"]
    # 100 mm at 2 mm: 50 intervals, 51 legs straight across, each 7 mm wide
    assert act["pattern"] == "parallel"
    derived = act["derived"]
    assert derived["width_mm"] == pytest.approx(7.0, abs=1e-9)
    assert derived["interval_mm"] == pytest.approx(2.0, abs=1e-9)
    assert derived["length_mm"] == pytest.approx(100.0, abs=1e-9)
    assert derived["beta0_deg"] == 0.0  # fixed radius: threads around the tube
    # the DST read back by pystitch (not embroact's writer): 51 legs of 2 needle points, 3 + 3 ties
    import pystitch

    pattern = pystitch.read(str(out / "par.dst"))
    stitches = [s for s in pattern.stitches if (s[2] & pystitch.COMMAND_MASK) == pystitch.STITCH]
    assert len(stitches) == 2 * 51 + 2 * 3 - 1  # the last tie-in stitch is the first leg's start


def test_check_and_predict(design_file, capsys):
    assert main(["check", str(design_file), "--json"]) in (0, 1)
    checked = json.loads(capsys.readouterr().out)
    assert not [f for f in checked["findings"] if f["severity"] == "error"]
    assert main(["predict", str(design_file), "--pressure-kpa", "200", "--json"]) == 0
    pred = json.loads(capsys.readouterr().out)
    (act,) = pred["actuators"]
    # fixed radius: r = r0 and l = l0 + 2 r0 theta (docs/model.md); the bend is positive above P0
    theta = math.radians(act["theta_deg"][0])
    r0 = act["derived"]["r0_mm"]
    assert act["status"] == ["BENDING"] and theta > 0.0
    assert act["radius_mm"][0] == pytest.approx(r0, rel=1e-12)
    assert act["length_mm"][0] == pytest.approx(act["derived"]["length_mm"] + 2.0 * r0 * theta, rel=1e-9)


def test_quick_command_for_the_new_kind(tmp_path, capsys):
    out = tmp_path / "p.dst"
    assert main(["parallel", "--width-mm", "7", "--interval-mm", "2", "--g-mpa", "2.7", "--p0-kpa", "85",
                 "-o", str(out)]) == 0
    assert "wrote" in capsys.readouterr().out and out.stat().st_size > 0


def test_design_skips_the_kind_no_calibration_covers_with_a_note(tmp_path, capsys):
    out = tmp_path / "d.toml"
    # 84.533 deg: what the sewable 6.2 mm zigzag bends at 150 kPa (predict zigzag --width-mm 6.2)
    assert main(["design", "--bend-deg", "84.5", "--at-kpa", "150", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "best: zigzag width_mm=6.2 interval_mm=1 -> 84.533 deg sewn" in text  # as without the kind
    assert "note: parallel skipped: calibration 'paper-2025' has no parallel points" in text
    shape = tmp_path / "hook.toml"
    assert main(["design", "--target-shape", str(EXAMPLES / "data" / "target_hook.csv"), "--at-kpa", "250",
                 "-o", str(shape), "--json", "--write-nearest"]) in (0, 5)  # 5: met only within a wider RMSE
    result = json.loads(capsys.readouterr().out)
    assert {s["pattern"] for s in result["segments"]} <= {"zigzag", "cross"}
    assert [n for n in result["notes"] if n.startswith("parallel skipped")]
    with pytest.raises(ParameterError, match="no parallel points"):
        design_bend(90.0, 150.0, pattern="parallel")


def test_shows_in_the_studio(design_file, tmp_path):
    from embroact.export.files.designfile import load_design
    from embroact.export.studio.session import Studio

    s = Studio(load_design(design_file), tmp_path)
    v = s.views(200.0)
    pattern_field = next(f for f in v["fields"] if f["key"] == "actuator[0].pattern")
    assert "parallel" in pattern_field["choices"] and pattern_field["value"] == "parallel"
    assert "<svg" in v["stitches_svg"] and v["actuators"][0]["theta_deg"] > 0.0
    assert v["inverse_patterns"][0] == "any" and "parallel" in v["inverse_patterns"]  # the page lists what it may search
    with pytest.raises(ParameterError, match="no parallel points"):
        s.inverse(90.0, 150.0, pattern="parallel")
    v = s.edit({"actuator[0].interval_mm": 2.5}, pressure_kpa=200.0)
    assert v["actuators"][0]["derived"]["interval_mm"] == pytest.approx(2.5, abs=1e-9)


def test_the_readme_lists_the_steps_this_module_takes():
    """The README's "Adding a pattern kind" names every function the module defines for the kind, every
    keyword its PatternKind and ModelKind are made with, and the two register calls, and nothing else."""
    import ast
    import re

    readme = (EXAMPLES.parent / "README.md").read_text(encoding="utf-8")
    section = readme.split("### Adding a pattern kind", 1)[1].split("\n## ", 1)[0]
    tree = ast.parse(Path(kind_parallel.__file__).read_text(encoding="utf-8"))
    passed = {"parallel_interval_mm", "parallel_design"}  # handed over as interval= and design_params=
    functions = {n.name.replace(kind_parallel.NAME, "<name>", 1) for n in tree.body if isinstance(n, ast.FunctionDef)
                 and n.name.startswith(kind_parallel.NAME + "_") and n.name not in passed}
    promised = set(re.findall(r"`(<name>_[a-z0-9_]+)", section))
    assert functions == promised - {"<name>_min_length_mm"}  # the optional one this kind leaves out
    calls = {n.func.id: n for n in ast.walk(tree) if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)}
    for kw in calls["PatternKind"].keywords:
        assert f"{kw.arg}=" in section or f"`{kw.arg}`" in section, kw.arg
    assert "register(PatternKind(" in section and "register_model(ModelKind(" in section
    assert {"register", "register_model"} <= set(calls)


def test_the_calibration_coupon_samples_the_new_kind(tmp_path, capsys):
    """Every registered kind gets coupon strips along its calibration axis (the width, for parallel couching),
    and a refused pattern's message lists the registered kinds."""
    from embroact.predict.coupon import coupon_kinds, plan_coupon

    assert "parallel" in coupon_kinds()
    c = plan_coupon(width_count=3, angle_count=2)
    par = [a for a in c.actuators if a.pattern == "parallel"]
    # 3 widths over 10/3 to 6 tube radii of the 1.5 mm tube (5 and 9 mm) on the 0.2 mm grid, at the kind's interval
    assert [a.width_mm for a in par] == [5.0, 7.0, 9.0] and {a.interval_mm for a in par} == {1.0}
    assert [a.coordinate for a in par] == [5.0, 7.0, 9.0]
    assert all(a.fin_side.value == "thread" for a in par)  # fixed radius: bends toward the back
    assert par[0].design_table() == {"name": par[0].label, "pattern": "parallel", "width_mm": 5.0, "interval_mm": 1.0,
                                      "length_mm": 100.0, "origin_mm": list(par[0].origin_mm)}
    with pytest.raises(ParameterError, match="parallel, got 'satin'"):
        plan_coupon(("satin",))
    out = tmp_path / "coupon"
    out.mkdir()
    assert main(["calibrate", "coupon", "--patterns", "parallel", "--width-count", "2", "--out", str(out), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert [(a["pattern"], a["width_mm"]) for a in doc["actuators"]] == [("parallel", 5.0), ("parallel", 9.0)]
    assert (out / "hoop1" / "coupon-hoop1.dst").exists() and (out / "hoop1" / "worksheet.txt").exists()
    # no calibration holds parallel points yet (the coupon is there to make them): no bend previews, said once
    assert doc["notes"] == ["hoop 1: no bend previews (calibration set 'paper-2025' has no parallel points for the "
                            "loading branch)"]
    assert not (out / "hoop1" / "bend.svg").exists()
