"""The worksheet (text and JSON) and report.html name every finding's place, as ``embroact check`` does."""
import html
import json
import re
import tomllib
from pathlib import Path

from embroact.export.cli.main import main
from embroact.export.files.designfile import load_design
from embroact.patterns.design import build_plan

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "three_actuators.toml"
_LINE = re.compile(r"^  (error|warning|info) (EA\d{3}): (.*) \[(.*)\]$")


def _finding_lines(worksheet: str) -> list[str]:
    return worksheet.split("DESIGN-RULE FINDINGS\n", 1)[1].splitlines()


def _build(design: Path, out: Path, *extra: str) -> None:
    out.mkdir()
    assert main(["build", str(design), "--out", str(out), *extra]) == 0


def test_three_actuators_worksheet_names_each_findings_actuator(tmp_path, capsys):
    names = [a["name"] for a in tomllib.loads(EXAMPLE.read_text(encoding="utf-8"))["actuator"]]
    _build(EXAMPLE, tmp_path / "out")
    lines = _finding_lines((tmp_path / "out" / "worksheet.txt").read_text(encoding="utf-8"))
    assert len(lines) >= 3 and len(set(lines)) == len(lines), lines  # three EA406, one per actuator, tell apart
    places = []
    for line in lines:
        m = _LINE.match(line)
        assert m, line
        assert m.group(4).split(",")[0] in names, line
        places.append(m.group(4))
    assert {p for p, line in zip(places, lines) if " EA406: " in line} == set(names)
    doc = json.loads((tmp_path / "out" / "worksheet.json").read_text(encoding="utf-8"))
    assert [f["place"] for f in doc["findings"]] == places
    assert [f["actuator"] for f in doc["findings"]] == [p.split(",")[0] for p in places]
    report = html.unescape((tmp_path / "out" / "report.html").read_text(encoding="utf-8"))
    for place in places:
        assert f"<td>{place}</td>" in report


def test_overlapping_tubes_findings_name_stitch_and_coordinates(tmp_path, capsys):
    """Two tubes 1.5 mm apart, built with --force: each EA101 line names its actuator, stitch and the stitch's
    coordinates in the plan (read from the plan, not from the finding)."""
    text = EXAMPLE.read_text(encoding="utf-8").replace("origin_mm = [-40.0, 0.0]", "origin_mm = [-40.0, 38.5]")
    assert "38.5" in text
    design = tmp_path / "overlap.toml"
    design.write_text(text, encoding="utf-8")
    _build(design, tmp_path / "out", "--force", "--no-previews")
    lines = _finding_lines((tmp_path / "out" / "worksheet.txt").read_text(encoding="utf-8"))
    ea101 = [line for line in lines if " EA101: " in line]
    assert len(ea101) >= 5 and len(set(lines)) == len(lines)
    plan = build_plan(load_design(design))
    names = [a.name for a in plan.actuators]
    for line in ea101:
        m = re.search(r"\[(.+), stitch (\d+) at \((-?[\d.]+), (-?[\d.]+)\) mm\]$", line)
        assert m, line
        k = int(m.group(2))
        assert m.group(1) == names[plan.actuator[k]], line
        assert abs(plan.xy_mm[k, 0] - float(m.group(3))) < 0.006 and abs(plan.xy_mm[k, 1] - float(m.group(4))) < 0.006
