"""A machine file embroact writes reads back in the design's frame, whatever the format.

A user checks a file against where the tubes are: the design's tube paths, y negated
(file frame, y down).  VP3 is written with its origin 1 mm beside the first needle point
and records that origin in its notes string; the check shifts the file back.
"""
import os

import pytest

from embroact.export.cli.main import main
from embroact.export.files.designfile import load_design
from embroact.export.machine.formats import FORMATS, write
from embroact.export.machine.vp3note import add_origin_note, read_origin_mm
from embroact.patterns.design import build_plan

pe = pytest.importorskip("pystitch")
THREE = os.path.join(os.path.dirname(__file__), "..", "examples", "three_actuators.toml")


@pytest.fixture(scope="module")
def three(tmp_path_factory):
    design = load_design(THREE)
    plan = build_plan(design)
    out = tmp_path_factory.mktemp("frame")
    results = {f: write(plan, out / f"three.{f}") for f in sorted(FORMATS)}
    # the design's tube paths in the file frame: plan (x, y) -> file (x, -y)
    paths = [" ".join(f"{x:g},{-y:g}" for x, y in a.centerline.points_mm) for a in design.actuators]
    return out, results, paths


@pytest.mark.parametrize("fmt", sorted(FORMATS))
def test_every_format_checks_clean_against_the_designs_tubes(three, fmt, capsys):
    out, _, paths = three
    argv = ["check", str(out / f"three.{fmt}")]
    for p in paths:
        argv += ["--tube-path", p]
    assert main(argv) == 0
    assert "3 tube(s): no findings" in capsys.readouterr().out


def test_vp3_records_its_origin_and_the_plain_reader_sees_the_shift(three):
    out, results, _ = three
    data = (out / "three.vp3").read_bytes()
    origin = read_origin_mm(data)
    assert origin == results["vp3"].origin_mm
    # the design starts at x = -40 mm (first actuator's origin_mm [-40, 40]): the origin lies near it
    assert -43 < origin[0] < -38 and 38 < origin[1] < 43
    # pystitch skips the note and reads positions relative to that origin (0.1 mm, y down)
    plain = pe.read(str(out / "three.vp3"), {"trim_at": None, "trim_distance": None, "clipping": False})
    dst = pe.read(str(out / "three.dst"), {"trim_at": None, "trim_distance": None, "clipping": False})
    first_vp3 = next(s for s in plain.stitches if s[2] == pe.STITCH)
    first_dst = next(s for s in dst.stitches if s[2] == pe.STITCH)
    assert first_vp3[0] + origin[0] * 10 == pytest.approx(first_dst[0], abs=1e-9)
    assert first_vp3[1] - origin[1] * 10 == pytest.approx(first_dst[1], abs=1e-9)


def test_origin_note_bytes_by_hand():
    head = b"%vsm%\0" + b"\0\2" + b"AB" + b"\0\2\0" + (5).to_bytes(4, "big")
    data = add_origin_note(head + b"\0\0" + b"xyz", (-1.0, 2.5))
    note = "embroact origin_mm=-1.0,2.5".encode("utf-16-be")
    assert data == head[:-4] + (5 + len(note)).to_bytes(4, "big") + len(note).to_bytes(2, "big") + note + b"xyz"
    assert read_origin_mm(data) == (-1.0, 2.5)
    assert read_origin_mm(head + b"\0\0") is None  # no note: no shift
    assert read_origin_mm(b"#PES0001") is None


def test_a_file_without_suffix_is_one_line_naming_the_readable_suffixes(capsys):
    assert main(["check", os.devnull]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert f"{os.devnull}: no file suffix to tell its format by; readable: " in err
    assert "'.'" not in err and " dst, " in err and " vp3, " in err
