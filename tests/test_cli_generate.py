"""``embroact zigzag`` / ``embroact cross`` through ``main([...])``."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import dst_decoder
from embroact.export.cli.main import main
from embroact.export.cli.target import GATE_ERRORS_PER_CODE
from embroact.patterns.centerline import Centerline
from embroact.patterns.params import ZigzagParams
from embroact.patterns.zigzag import zigzag

ZZ = ["zigzag", "--width-mm", "7", "--interval-mm", "1", "--length-mm", "100"]


def _has_cross():
    import importlib.util

    return importlib.util.find_spec("embroact.patterns.cross") is not None


def test_zigzag_writes_the_paper_actuator(tmp_path, capsys):
    out = tmp_path / "act.dst"
    assert main(ZZ + ["-o", str(out)]) == 0
    assert "106 stitches, 1 stop, 1 trim" in capsys.readouterr().out
    dst = dst_decoder.decode(out.read_bytes())
    pts = np.array([(r.x, r.y) for r in dst.records if r.kind == "stitch"]) / 10.0
    plan = zigzag(Centerline.straight(100.0), ZigzagParams(7.0, 1.0), name="A1")
    centre = (plan.xy_mm.min(axis=0) + plan.xy_mm.max(axis=0)) / 2.0  # the file starts at the design's centre
    assert np.abs(pts - (plan.xy_mm[plan.commands == 0] - centre)).max() <= 0.05 + 1e-9
    assert dst.header["CO"].strip() == "1"


def test_json_output_has_units_and_derived(tmp_path, capsys):
    out = tmp_path / "act.pes"
    assert main(ZZ + ["-o", str(out), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["file"] == str(out) and doc["format"] == "pes" and doc["stitch_count"] == 106
    assert doc["realised"]["width_mm"] == pytest.approx(7.0)
    assert doc["derived"]["r0_mm"] == pytest.approx(2.5814, abs=1e-4)
    assert doc["model"]["tube_law_p0_kpa"] == pytest.approx(84.5, abs=0.1)
    assert out.read_bytes()[:4] == b"#PES"


def test_format_overrides_suffix(tmp_path):
    out = tmp_path / "act.dst"
    assert main(ZZ + ["-o", str(out), "--format", "jef"]) == 0
    assert out.read_bytes()[:4] != b"LA:A"  # not a DST header


def test_worksheet_and_preview(tmp_path, capsys):
    out = tmp_path / "act.dst"
    svg = tmp_path / "act.svg"
    assert main(ZZ + ["-o", str(out), "--worksheet", "--preview", str(svg)]) == 0
    ws = json.loads((tmp_path / "act.worksheet.json").read_text())
    assert ws["actuators"][0]["tube_cut_mm"] == 160.0
    text = (tmp_path / "act.worksheet.txt").read_text()
    assert "stop 1: lay tube for actuator A1 (160 mm cut): its axis runs from (-50.0, 0.0) to (50.0, 0.0) mm" in text
    assert ws["machine_format"] == "dst" and ws["stop_count"] == 1
    assert svg.read_text().startswith("<svg")


def test_curved_path(tmp_path):
    out = tmp_path / "curve.dst"
    assert main(ZZ + ["-o", str(out), "--path", "M 0 0 C 30 -25 60 25 90 0"]) == 0
    plan = zigzag(Centerline.from_svg_path("M 0 0 C 30 -25 60 25 90 0"), ZigzagParams(7.0, 1.0))
    dst = dst_decoder.decode(out.read_bytes())
    assert sum(r.kind == "stitch" for r in dst.records) == plan.stitch_count


@pytest.mark.skipif(not _has_cross(), reason="cross generator not yet merged")
def test_cross(tmp_path, capsys):
    out = tmp_path / "cross.dst"
    assert main(["cross", "--width-mm", "7", "--interval-mm", "1.4", "--angle-deg", "45", "-o", str(out), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["derived"]["pattern"] == "cross"
    assert doc["derived"]["beta0_deg"] == pytest.approx(37.208, abs=0.5)


@pytest.mark.parametrize("argv,needle", [
    (["--width-mm", "-1", "--interval-mm", "1"], "width_mm must be in (0, 200), got -1"),
    (["--width-mm", "nan", "--interval-mm", "1"], "width_mm"),
    (["--width-mm", "7", "--interval-mm", "0"], "interval_mm"),
    (["--width-mm", "3", "--interval-mm", "1"], "width"),  # no room for the tube
    (["--width-mm", "7", "--interval-mm", "1", "--length-mm", "0.5"], "length_mm"),
    (["--width-mm", "7", "--interval-mm", "1", "--tube-radius-mm", "-2"], "outer_radius_mm"),
])
def test_bad_parameters_exit_2_and_write_nothing(tmp_path, capsys, argv, needle):
    out = tmp_path / "x.dst"
    assert main(["zigzag"] + argv + ["-o", str(out), "--preview", str(tmp_path / "p.svg"), "--worksheet"]) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1 and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []


def test_unknown_suffix_lists_formats(tmp_path, capsys):
    assert main(ZZ + ["-o", str(tmp_path / "x.svg")]) == 2
    assert ".dst, .tbf, .pes, .pec, .jef, .exp, .vp3, .xxx, .u01" in capsys.readouterr().err


def test_long_legs_refused_then_split(tmp_path, capsys):
    out = tmp_path / "wide.dst"
    argv = ["zigzag", "--width-mm", "14", "--interval-mm", "1", "--length-mm", "20", "-o", str(out)]
    assert main(argv) == 1  # refused by the rule gate: EA102, legs over the DST record limit
    err = capsys.readouterr().err
    assert "EA102 (A1)" in err.splitlines()[0] and "12.1 mm per axis" in err and "--force" in err
    assert not out.exists()
    assert main(argv + ["--split-long", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["split_legs"] == 20


def test_missing_or_readonly_directory_exit_3(tmp_path, capsys, monkeypatch):
    assert main(ZZ + ["-o", str(tmp_path / "nope" / "x.dst")]) == 3
    assert "does not exist" in capsys.readouterr().err
    ro = tmp_path / "ro"
    ro.mkdir()
    real_access = os.access
    monkeypatch.setattr(os, "access", lambda p, mode: False if str(p) == str(ro) else real_access(p, mode))
    assert main(ZZ + ["-o", str(ro / "x.dst"), "--worksheet"]) == 3
    assert "is not writable" in capsys.readouterr().err
    assert list(ro.iterdir()) == []


def test_same_bytes_twice(tmp_path):
    a, b = tmp_path / "a.vp3", tmp_path / "b.vp3"
    assert main(ZZ + ["-o", str(a)]) == 0 and main(ZZ + ["-o", str(b)]) == 0
    assert a.read_bytes() == b.read_bytes()


# ----------------------------------------------------------------------------- the rule gate
GATED = [
    # outside the 200 x 200 mm hoop
    (["zigzag", "--width-mm", "7", "--interval-mm", "1", "--length-mm", "300"], "EA306"),
    # w = 14 mm: legs of 14 mm, over the DST record limit and the machine's longest stitch
    (["zigzag", "--width-mm", "14", "--interval-mm", "1"], "EA102"),
    # alpha0 = 0.785 deg (radians by mistake): the interval shrinks to 0.19 mm, the fabric tears
    (["cross", "--width-mm", "7", "--interval-mm", "1.4", "--angle-deg", "0.785"], "EA106"),
]


@pytest.mark.parametrize("argv, code", GATED, ids=["outside-hoop", "wide", "radians"])
def test_rule_errors_refuse_and_force_writes(tmp_path, capsys, argv, code):
    out = tmp_path / "x.dst"
    assert main(argv + ["-o", str(out), "--worksheet"]) == 1
    err = capsys.readouterr().err
    summary = err.splitlines()[0]
    assert summary.startswith("design rules: ") and f"{code} (A1)" in summary
    assert f"error: {code} " in err and "nothing written" in err
    assert list(tmp_path.iterdir()) == []
    assert main(argv + ["-o", str(out), "--worksheet", "--force", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert out.exists() and doc["written"] and code in {f["code"] for f in doc["findings"]}
    sheet = json.loads((tmp_path / "x.worksheet.json").read_text())
    assert sheet["findings"] == doc["findings"]


def test_gate_prints_a_few_errors_per_rule_and_counts_the_rest(tmp_path, capsys):
    """w = 14 mm, s = 1 mm, l0 = 100 mm: 100 legs of 14 mm, each an EA102 and an EA103 error."""
    argv = ["zigzag", "--width-mm", "14", "--interval-mm", "1", "-o", str(tmp_path / "x.dst")]
    assert main(argv) == 1
    lines = capsys.readouterr().err.splitlines()
    assert "demonstration data" in lines.pop()  # the paper-2025 note comes last, once
    assert lines[0].startswith("design rules: 200 errors, ") and lines[-1].endswith("nothing written "
                                                                                     "(use --force to write anyway)")
    assert len(lines) == 1 + 2 * (GATE_ERRORS_PER_CODE + 1) + 1
    assert main(argv + ["--force", "--json"]) == 0
    counts = {}
    for f in json.loads(capsys.readouterr().out)["findings"]:
        counts[f["code"]] = counts.get(f["code"], 0) + f["count"]
    for code in ("EA102", "EA103"):
        mine = [line for line in lines if line.startswith(f"error: {code} ")]
        assert len(mine) == GATE_ERRORS_PER_CODE + 1 and counts[code] == 100
        assert mine[-1] == (f"error: {code} ... and {100 - GATE_ERRORS_PER_CODE} more "
                            "(see the worksheet / embroact check --json)")


def test_warnings_are_one_line_and_json_has_the_model(tmp_path, capsys):
    """The paper's zigzag bends past 180 deg at 300 kPa (EA403): written, with one summary line on stderr."""
    assert main(ZZ + ["-o", str(tmp_path / "a.dst"), "--json"]) == 0
    captured = capsys.readouterr()
    err = captured.err.splitlines()  # no paper-2025 note with --json
    assert err == [line for line in err if line.startswith("design rules: 0 errors")]
    assert len(err) == 1 and "EA403 (A1)" in captured.err
    doc = json.loads(captured.out)
    assert (doc["model"]["g_mpa"], doc["model"]["p0_kpa"]) == (2.7, 85.0)
    assert doc["model"]["p0_source"] == "calibration paper-2025 (zigzag, width_mm=7)"


def test_only_the_program_freezes_the_collector_before_its_exit(tmp_path):
    # run as the program (argv None) main ends with gc.freeze() (a quick exit); a call from Python does not
    code = ("import gc, sys\nfrom embroact.export.cli.main import main\n"
            f"args = {ZZ!r}\n"
            f"assert main(args + ['-o', {str(tmp_path / 'a.dst')!r}]) == 0 and gc.get_freeze_count() == 0\n"
            f"sys.argv = ['embroact', *args, '-o', {str(tmp_path / 'b.dst')!r}]\n"
            "assert main() == 0 and gc.get_freeze_count() > 0\n"
            "print('ok')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.stdout.split()[-1:] == ["ok"], out.stderr
    assert (tmp_path / "a.dst").read_bytes() == (tmp_path / "b.dst").read_bytes()
