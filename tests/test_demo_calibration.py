"""The built-in paper-2025 set is demonstration data: every command using it says so once, in one
line on stderr; the paper-prototype example marks states past a validity limit as predict does."""
import json
import os
import subprocess
import sys

from embroact.export.cli.main import main
from embroact.export.cli.target import DEMO_NOTE

EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "examples")


def _note_lines(err: str) -> list[str]:
    return [line for line in err.splitlines() if "demonstration data" in line]


def test_predict_with_the_demo_set_says_so_once(capsys):
    design = os.path.join(EXAMPLES, "three_actuators.toml")  # three actuators, all on paper-2025
    assert main(["predict", design, "--pressure-kpa", "100"]) == 0
    err = capsys.readouterr().err
    assert _note_lines(err) == [f"embroact: {DEMO_NOTE}"]
    assert "embroact calibrate coupon" in DEMO_NOTE
    # once per command run: the next run says it again, once
    assert main(["check", design]) in (0, 1)
    assert len(_note_lines(capsys.readouterr().err)) == 1


def test_no_note_without_the_demo_set(capsys, tmp_path):
    assert main(["predict", "zigzag", "--width-mm", "7", "--g-mpa", "2.7", "--p0-kpa", "85",
                 "--pressure-kpa", "100"]) == 0
    assert _note_lines(capsys.readouterr().err) == []
    cal = tmp_path / "mine.toml"
    cal.write_text('name = "mine"\n[[points]]\npattern = "zigzag"\nwidth_mm = 7.0\ng_mpa = 2.0\np0_kpa = 80.0\n')
    assert main(["predict", "zigzag", "--width-mm", "7", "--calibration", str(cal), "--pressure-kpa", "100"]) == 0
    assert _note_lines(capsys.readouterr().err) == []


def test_design_and_build_say_so(capsys, tmp_path):
    assert main(["build", "--out", str(tmp_path), "--no-previews"]) == 0
    assert len(_note_lines(capsys.readouterr().err)) == 1
    main(["design", "--bend-deg", "90", "--at-kpa", "150", "--pattern", "zigzag", "-o", str(tmp_path / "d.toml")])
    assert len(_note_lines(capsys.readouterr().err)) == 1
    # machine-readable runs keep stderr for errors: no note with --json
    main(["design", "--bend-deg", "90", "--at-kpa", "150", "--pattern", "zigzag", "--json", "-o", str(tmp_path / "e.toml")])
    out = capsys.readouterr()
    assert _note_lines(out.err) == [] and "demonstration" not in out.out


def test_paper_prototypes_mark_coiled_states_as_predict_does(capsys):
    proc = subprocess.run([sys.executable, os.path.join(EXAMPLES, "paper_prototypes.py")], capture_output=True,
                          text=True, check=True)
    row = next(line for line in proc.stdout.splitlines() if line.startswith("zigzag w5"))
    for value in ("596.74C", "2032.35C", "2430.40C"):
        assert value in row
    assert main(["predict", "zigzag", "--width-mm", "5", "--pressure-kpa", "200,250,300", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    statuses = json.dumps(doc)
    assert statuses.count('"COILED"') >= 3
