"""``build()`` and ``embroact build``: outputs, plug-in points, errors."""
import json
from pathlib import Path
import os

import numpy as np
import pytest

import dst_decoder
from h3_plans import hand_plan
from embroact.export.report.build import BuildContext, DesignRuleError, build, build_plan_outputs
from embroact.export.cli.main import main
from embroact.patterns.design import build_plan, default_design, design_from_dict
from embroact.patterns.base.errors import ExportError, ParameterError
from embroact.patterns.base.findings import RULES
from embroact.patterns.plan import Command as C

THREE = {"name": "three", "actuator": [
    {"name": f"A{k + 1}", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 60,
     "origin_mm": [0, 25 * k]} for k in range(3)]}


def test_default_design_outputs(tmp_path):
    res = build(default_design(), tmp_path)  # what `embroact build` writes: the previews and the report too
    assert res.files == ("paper-zigzag.dst", "worksheet.json", "worksheet.txt", "preview.svg", "template.svg",
                         "template-a4.html", "template-letter.html", "bend.svg", "shape.svg", "shape.glb",
                         "shape3d.svg", "report.json", "report.html")
    assert build(default_design(), tmp_path, stages=()).files[-1] == "template-letter.html"  # stages=(): no previews
    assert sorted(os.listdir(tmp_path)) == sorted(res.files)
    dst = dst_decoder.decode((tmp_path / "paper-zigzag.dst").read_bytes())
    assert sum(r.kind == "stitch" for r in dst.records) == 106
    ws = json.loads((tmp_path / "worksheet.json").read_text())
    assert ws["actuators"][0]["tube_cut_mm"] == 160.0 and ws["speed_spm"] == 600.0


def test_three_actuator_design_in_three_formats(tmp_path):
    design = design_from_dict(THREE)
    res = build(design, tmp_path, formats=("dst", "pes", "tbf"))
    assert {m.format for m in res.machine_files} == {"dst", "pes", "tbf"}
    dst = dst_decoder.decode((tmp_path / "three.dst").read_bytes())
    assert int(dst.header["CO"]) == 3
    plan = build_plan(design)
    got = np.array([(r.x, r.y) for r in dst.records if r.kind == "stitch"]) / 10.0
    assert np.abs(got - plan.xy_mm[plan.commands == C.STITCH]).max() <= 0.05 + 1e-9
    assert len(res.worksheet.stops) == 3


def test_same_bytes_twice(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir(), b.mkdir()
    build(design_from_dict(THREE), a, formats=("dst", "vp3"))
    build(design_from_dict(THREE), b, formats=("dst", "vp3"))
    for name in os.listdir(a):
        assert (a / name).read_bytes() == (b / name).read_bytes(), name


def test_rule_gate_and_force(tmp_path):
    bad = RULES.finding("EA101", "needle point 0.4 mm from the tube axis", stitch_index=7)
    check = lambda analysis: [bad]  # noqa: E731
    with pytest.raises(DesignRuleError, match="EA101.*--force"):
        build(default_design(), tmp_path, check=check)
    assert os.listdir(tmp_path) == []
    res = build(default_design(), tmp_path, check=check, force=True)
    assert json.loads((tmp_path / "worksheet.json").read_text())["findings"][0]["code"] == "EA101"
    assert res.findings == (bad,)


def test_stage_plugs_in_and_sees_outputs(tmp_path):
    seen = {}

    def stage(ctx: BuildContext):
        seen.update(ctx.outputs)
        return {"report.html": f"<p>{ctx.worksheet.stitch_count}</p>", "blob.bin": b"\x00\x01"}

    res = build_plan_outputs(hand_plan(1), tmp_path, stages=[stage])
    assert "preview.svg" in seen and "hand.dst" in seen
    assert res.files[-2:] == ("report.html", "blob.bin")
    assert (tmp_path / "report.html").read_text() == "<p>45</p>"


def test_failing_stage_writes_nothing(tmp_path):
    def stage(ctx):
        raise ParameterError("pressures_kpa must be >= 0, got -1")

    with pytest.raises(ParameterError):
        build_plan_outputs(hand_plan(1), tmp_path, stages=[stage])
    assert os.listdir(tmp_path) == []


def test_missing_dir_and_bad_format(tmp_path):
    with pytest.raises(ExportError, match="does not exist"):
        build(default_design(), tmp_path / "nope")
    with pytest.raises(ParameterError, match="format must be one of"):
        build(default_design(), tmp_path, formats=("dst", "svg"))
    assert os.listdir(tmp_path) == []


def test_cli_build_default_and_json(tmp_path, capsys):
    assert main(["build", "--out", str(tmp_path), "--format", "dst,pes", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["files"] == ["paper-zigzag.dst", "paper-zigzag.pes", "worksheet.json", "worksheet.txt", "preview.svg",
                            "template.svg", "template-a4.html", "template-letter.html", "bend.svg", "shape.svg", "shape.glb", "shape3d.svg", "report.json", "report.html"]
    assert sorted(os.listdir(tmp_path)) == sorted(doc["files"])
    assert doc["actuators"][0]["model"]["tube_law_p0_kpa"] == pytest.approx(84.5, abs=0.1)


def test_cli_build_design_file(tmp_path, capsys):
    from embroact.export.files.designfile import save_design

    path = tmp_path / "three.toml"
    save_design(design_from_dict(THREE), path)
    out = tmp_path / "out"
    out.mkdir()
    assert main(["build", str(path), "--out", str(out)]) == 0
    assert "three.dst" in capsys.readouterr().out
    assert (out / "three.dst").exists()


@pytest.mark.parametrize("argv,code,needle", [
    (["--out", "NOPE"], 3, "does not exist"),
    (["--out", "OUT", "--format", "svg"], 2, "format must be one of"),
    (["MISSING.toml", "--out", "OUT"], 2, "MISSING.toml"),
])
def test_cli_build_errors(tmp_path, capsys, argv, code, needle):
    (tmp_path / "OUT").mkdir()
    argv = [str(tmp_path / a) if a in ("NOPE", "OUT", "MISSING.toml") else a for a in argv]
    assert main(["build"] + argv) == code
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1
    assert os.listdir(tmp_path / "OUT") == []


def test_cli_build_rule_errors_exit_1(tmp_path, capsys):
    """A design that leaves the hoop: refused with codes (not enum reprs), written with --force."""
    design = tmp_path / "long.toml"
    design.write_text('[[actuator]]\nname = "L"\npattern = "zigzag"\nwidth_mm = 7.0\ninterval_mm = 1.0\n'
                      'length_mm = 300.0\n', encoding="utf-8")
    out = tmp_path / "out"
    out.mkdir()
    assert main(["build", str(design), "--out", str(out), "--no-previews"]) == 1
    err = capsys.readouterr().err
    assert err.startswith("design rules: ") and "EA306 (L)" in err.splitlines()[0]
    assert "error: EA306 " in err and "Severity" not in err and os.listdir(out) == []
    assert main(["build", str(design), "--out", str(out), "--no-previews", "--force"]) == 0
    assert "EA306" in capsys.readouterr().err and "EA306" in (out / "worksheet.txt").read_text()


def test_cli_build_prints_its_warnings_in_one_line(tmp_path, capsys):
    """examples/three_actuators.toml: the warnings the rules find are summarised with codes and actuators."""
    from embroact.predict.analysis import analyse
    from embroact.predict.rules import check_design
    from embroact.export.files.designfile import load_design
    from embroact.patterns.base.findings import summary_line

    example = Path(__file__).resolve().parent.parent / "examples" / "three_actuators.toml"
    assert main(["build", str(example), "--out", str(tmp_path), "--no-previews"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert "demonstration data" in err.pop()  # the paper-2025 note comes last, once
    findings = check_design(analyse(load_design(example)))
    warned = sorted({f.code for f in findings if f.severity.value == "warning"})
    assert warned and err == [f"design rules: {summary_line(findings)}"]
    assert all(code in err[0] for code in warned)


def test_cli_build_real_gate_refuses_misplaced_design(tmp_path, capsys):
    """A design whose P0 exceeds the working pressure is refused by the real checks (EA401)."""
    design = tmp_path / "hot.toml"
    design.write_text('name = "hot"\n[operation]\nmax_pressure_kpa = 50.0\n'
                      '[[actuator]]\nname = "A"\npattern = "zigzag"\nwidth_mm = 9.0\n'
                      'interval_mm = 1.0\nlength_mm = 60.0\n', encoding="utf-8")
    out = tmp_path / "out"
    out.mkdir()
    assert main(["build", str(design), "--out", str(out)]) == 1
    assert "EA401" in capsys.readouterr().err and os.listdir(out) == []
