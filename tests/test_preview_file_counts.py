"""``embroact preview stitches FILE``: its counts and marks are what the file holds, for every format.

Each file is written with the CLI and decoded here with pystitch's own reader (default settings:
a DST run of 3 jumps is read as a trim); a run of trim records is one cut (JEF writes one as 3).
"""
import re
import xml.etree.ElementTree as ET

import pystitch
import pytest

from embroact.export.cli.main import main
from embroact.export.machine.formats import FORMATS

SVG = "{http://www.w3.org/2000/svg}"
#: Formats whose colour-change record is the stop (the others' colour change is a pause, not a stop).
STOP_IS_COLOR_CHANGE = {"dst", "exp"}
COUNTS = re.compile(r"(\d+) stitches, (\d+) stops?, (\d+) trims?")


def decoded(path, fmt):
    """(stitches, stops, trims) as pystitch reads ``path``."""
    cmds = [s[2] & pystitch.COMMAND_MASK for s in pystitch.read(str(path)).stitches]
    trims = sum(c == pystitch.TRIM and (k == 0 or cmds[k - 1] != pystitch.TRIM) for k, c in enumerate(cmds))
    stops = cmds.count(pystitch.STOP) + (cmds.count(pystitch.COLOR_CHANGE) if fmt in STOP_IS_COLOR_CHANGE else 0)
    return cmds.count(pystitch.STITCH), stops, trims


def counts(line):
    return tuple(int(v) for v in COUNTS.search(line).groups())


def preview(path, out, capsys):
    assert main(["preview", "stitches", str(path), "-o", str(out)]) == 0
    printed = counts(capsys.readouterr().out)
    root = ET.parse(out).getroot()
    texts = [t.text or "" for t in root.iter(f"{SVG}text")]
    drawn = counts(next(t for t in texts if COUNTS.search(t)))
    marks = {c: sum(1 for g in root.iter(f"{SVG}g") if g.get("class") == c) for c in ("trim", "stop")}
    return printed, drawn, marks, texts


@pytest.mark.parametrize("fmt", sorted(FORMATS))
@pytest.mark.parametrize("args", [["zigzag", "--width-mm", "7"], ["cross", "--width-mm", "7", "--angle-deg", "45"]],
                         ids=["zigzag", "cross"])
def test_preview_counts_are_the_files(tmp_path, capsys, fmt, args):
    path = tmp_path / f"a.{fmt}"
    assert main(args + ["--length-mm", "40", "-o", str(path)]) == 0
    written = counts(capsys.readouterr().out)
    printed, drawn, marks, _ = preview(path, tmp_path / "p.svg", capsys)
    assert printed == drawn == written == decoded(path, fmt)
    assert marks["trim"] == decoded(path, fmt)[2] == 1


@pytest.mark.parametrize("fmt", sorted(FORMATS))
def test_three_actuators_preview_counts(tmp_path, capsys, fmt):
    from pathlib import Path

    design = Path(__file__).resolve().parents[1] / "examples" / "three_actuators.toml"
    assert main(["build", str(design), "--out", str(tmp_path), "--format", fmt, "--no-previews"]) == 0
    capsys.readouterr()
    path = tmp_path / f"three-actuators.{fmt}"
    sheet = (tmp_path / "worksheet.txt").read_text()
    sheet_trims = int(re.search(r"trims (\d+)", sheet).group(1))
    printed, drawn, marks, _ = preview(path, tmp_path / "p.svg", capsys)
    assert printed == drawn == decoded(path, fmt)
    assert printed[2] == sheet_trims == marks["trim"] == 3


@pytest.mark.parametrize("fmt", ["dst", "exp"])
def test_double_stop_is_one_labelled_stop(tmp_path, capsys, fmt):
    path = tmp_path / f"pl.{fmt}"
    assert main(["zigzag", "--width-mm", "7", "--length-mm", "40", "--placement-line", "--cord-stop", "double",
                 "-o", str(path)]) == 0
    written = counts(capsys.readouterr().out)
    printed, drawn, marks, texts = preview(path, tmp_path / "p.svg", capsys)
    assert printed == drawn == written == decoded(path, fmt)
    assert printed[1] == 2  # two stop records ...
    labels = [t for t in texts if t.startswith("STOP")]
    assert marks["stop"] == 1 and len(labels) == 1  # ... one stop, one tube
    assert "lay tube A1" in labels[0] and "double stop" in labels[0] and "A2" not in labels[0]
