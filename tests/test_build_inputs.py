"""No output of ``embroact build`` replaces an input of the run; ``design --svg`` is refused for a bend target.

Every input kind build reads is put where build writes one of its fixed outputs (the design
file as ``report.json``, a drawing as ``preview.svg``, a calibration file as ``worksheet.json``
or ``template.svg``): each run must exit 2 with one stderr line naming ``--out``, the output
and the input, and leave the directory byte for byte as it was.
"""
from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from embroact.export.cli.main import main

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
DESIGN_WITH_CALIBRATION = ('name = "cal"\n[[actuator]]\nname = "A1"\npattern = "zigzag"\nwidth_mm = 7\n'
                           'interval_mm = 1\nlength_mm = 100\n[actuator.model]\ncalibration = "./{name}"\n')


@pytest.fixture(scope="module")
def calibration(tmp_path_factory) -> bytes:
    """A calibration file's bytes, written by ``embroact fit`` as the README makes one."""
    path = tmp_path_factory.mktemp("cal") / "mycal.toml"
    assert main(["fit", str(EXAMPLES / "data" / "zigzag_w7_loop.csv"), "--pattern", "zigzag", "--width-mm", "7",
                 "-o", str(path)]) == 0
    return path.read_bytes()


def _snapshot(d: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(d.iterdir())}


def _refused(capsys, argv: list[str], d: Path, needle: str) -> None:
    """``argv`` exits 2 with one line holding ``needle`` and changes nothing in ``d``."""
    before = _snapshot(d)
    capsys.readouterr()
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    assert err.startswith("embroact: error: ") and needle in err, err
    assert _snapshot(d) == before  # the inputs byte-identical, no output added (no hidden staging file either)


def test_build_refuses_to_replace_its_design_file(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "o").mkdir()
    shutil.copy(EXAMPLES / "paper_zigzag.toml", tmp_path / "o" / "report.json")
    needle = ("--out 'o/report.json' would replace the input design file 'o/report.json': "
              "write the output to another file")
    _refused(capsys, ["build", "o/report.json", "--out", "o"], tmp_path / "o", needle)
    # another spelling of the directory, and a hard link to the design: the same file
    _refused(capsys, ["build", "o/report.json", "--out", "./o/../o"], tmp_path / "o", "design file 'o/report.json'")
    (tmp_path / "o" / "report.json").rename(tmp_path / "d.toml")
    (tmp_path / "o" / "worksheet.txt").hardlink_to(tmp_path / "d.toml")
    _refused(capsys, ["build", "d.toml", "--out", "o"], tmp_path / "o",
             "--out 'o/worksheet.txt' would replace the input design file 'd.toml'")


def test_build_refuses_to_replace_a_drawing_the_design_reads(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "o").mkdir()
    shutil.copy(EXAMPLES / "inkscape_tubes.svg", tmp_path / "o" / "preview.svg")
    text = (EXAMPLES / "inkscape_tubes.toml").read_text(encoding="utf-8")
    (tmp_path / "o" / "d.toml").write_text(text.replace("inkscape_tubes.svg", "preview.svg"), encoding="utf-8")
    _refused(capsys, ["build", "o/d.toml", "--out", "o"], tmp_path / "o",
             "--out 'o/preview.svg' would replace the input drawing of o/d.toml actuator[0].path 'o/preview.svg'")
    assert (tmp_path / "o" / "preview.svg").read_bytes() == (EXAMPLES / "inkscape_tubes.svg").read_bytes()


def test_build_refuses_to_replace_the_calibration_option_file(tmp_path, capsys, monkeypatch, calibration):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "o").mkdir()
    (tmp_path / "o" / "worksheet.json").write_bytes(calibration)
    _refused(capsys, ["build", "--calibration", "o/worksheet.json", "--out", "o", "--no-previews"], tmp_path / "o",
             "--out 'o/worksheet.json' would replace the input calibration file 'o/worksheet.json'")
    assert (tmp_path / "o" / "worksheet.json").read_bytes() == calibration


def test_build_refuses_to_replace_a_calibration_file_the_design_names(tmp_path, capsys, monkeypatch, calibration):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "o").mkdir()
    (tmp_path / "o" / "template.svg").write_bytes(calibration)
    (tmp_path / "o" / "d.toml").write_text(DESIGN_WITH_CALIBRATION.format(name="template.svg"), encoding="utf-8")
    _refused(capsys, ["build", "o/d.toml", "--out", "o"], tmp_path / "o",
             "--out 'o/template.svg' would replace the input calibration file of o/d.toml "
             "actuator[0].model.calibration 'o/template.svg'")
    assert (tmp_path / "o" / "template.svg").read_bytes() == calibration


def test_build_still_writes_beside_its_inputs(tmp_path, capsys, monkeypatch, calibration):
    """Inputs in the output directory under names build does not write are read, kept, and built."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "o").mkdir()
    (tmp_path / "o" / "lab.toml").write_bytes(calibration)
    (tmp_path / "o" / "d.toml").write_text(DESIGN_WITH_CALIBRATION.format(name="lab.toml"), encoding="utf-8")
    before = _snapshot(tmp_path / "o")
    assert main(["build", "o/d.toml", "--out", "o", "--no-previews"]) == 0
    after = _snapshot(tmp_path / "o")
    assert {k: after[k] for k in before} == before and "cal.dst" in after


def test_design_refuses_svg_for_a_bend_target(tmp_path, capsys, monkeypatch):
    """``--svg`` has no overlay to take with ``--bend-deg``: refused before the search, nothing written."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "keep.svg").write_bytes(b"<svg/>")
    for out, svg in (("d.svg", "d.svg"), ("d.toml", "keep.svg")):
        _refused(capsys, ["design", "--bend-deg", "84.5", "--at-kpa", "150", "-o", out, "--svg", svg], tmp_path,
                 f"embroact: error: --svg '{svg}': only a --target-shape target writes an overlay; --bend-deg "
                 "writes the design file alone (drop --svg)")
    assert _snapshot(tmp_path) == {"keep.svg": b"<svg/>"}


def test_preview_refuses_to_replace_a_drawing_the_design_reads(tmp_path, capsys, monkeypatch):
    """The same check in ``preview``: the drawing a design names is an input of the run too."""
    monkeypatch.chdir(tmp_path)
    shutil.copy(EXAMPLES / "inkscape_tubes.svg", tmp_path / "x.svg")
    text = (EXAMPLES / "inkscape_tubes.toml").read_text(encoding="utf-8")
    (tmp_path / "d.toml").write_text(text.replace("inkscape_tubes.svg", "x.svg"), encoding="utf-8")
    _refused(capsys, ["preview", "stitches", "d.toml", "-o", "./x.svg"], tmp_path,
             "--output './x.svg' would replace the input drawing of d.toml actuator[0].path 'x.svg'")
