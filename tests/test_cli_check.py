"""``embroact check`` through ``main([...])``: designs, embroidery files, exit codes, table and JSON."""
import glob
import json
import os

import numpy as np
import pystitch as pe
import pytest

import dst_decoder
from embroact.export.cli.main import main
from embroact.patterns.centerline import Centerline
from embroact.patterns.params import ZigzagParams
from embroact.patterns.plan import Command, Role
from embroact.patterns.zigzag import zigzag

EXAMPLES = sorted(glob.glob(os.path.join(os.path.dirname(__file__), "..", "examples", "*.toml")))
_PE = {Command.STITCH: pe.STITCH, Command.JUMP: pe.JUMP, Command.TRIM: pe.TRIM, Command.STOP: pe.STOP,
       Command.END: pe.END}


def _dst_with_leg_in_corridor(path, leg_number=55):
    """The paper zigzag with one leg's needle point moved to 0.3 mm from the axis, written by pystitch."""
    plan = zigzag(Centerline.straight(100.0), ZigzagParams(width_mm=7.0, interval_mm=1.0))
    i = int(np.flatnonzero(plan.roles == Role.LEG)[leg_number])
    xy = plan.xy_mm.copy()
    xy[i, 1] = 0.3 * np.sign(xy[i, 1])
    pat = pe.EmbPattern()
    for (x, y), c in zip(xy, plan.commands):
        pat.add_stitch_absolute(_PE[int(c)], round(x * 10), round(-y * 10))
    pe.write_dst(pat, str(path))
    records = dst_decoder.decode(path.read_bytes()).records
    target = (round(xy[i, 0] * 10), round(xy[i, 1] * 10))
    return [k for k, r in enumerate(records) if r.kind == "stitch" and (r.x, r.y) == target]


@pytest.mark.parametrize("example", EXAMPLES, ids=os.path.basename)
def test_every_example_design_has_no_errors(example, capsys):
    assert main(["check", example, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["counts"]["error"] == 0 and doc["kind"] == "design"
    assert all(f["severity"] != "error" for f in doc["findings"])


def test_examples_exist():
    assert len(EXAMPLES) >= 3


def test_misplaced_leg_in_a_dst_is_found_at_its_record(tmp_path, capsys):
    path = tmp_path / "bad.dst"
    index = _dst_with_leg_in_corridor(path)
    assert len(index) == 1
    assert main(["check", str(path), "--tube-path", "0,0 100,0", "--json"]) == 1
    doc = json.loads(capsys.readouterr().out)
    errors = [f for f in doc["findings"] if f["severity"] == "error"]
    assert [(f["code"], f["stitch_index"]) for f in errors] == [("EA101", index[0])]
    # the warnings: pystitch's header (EA505: ST counts a trim as one record, +Y leaves out the trim's jump)
    assert doc["counts"] == {"error": 1, "warning": 2, "info": 0} and doc["format"] == "dst"
    # the needle point's number: the stitch records before it, as the suite's own decoder reads the file
    before = sum(r.kind == "stitch" for r in dst_decoder.decode(path.read_bytes()).records[:index[0]])
    assert errors[0]["needle_point"] == before and errors[0]["at_needle"]
    assert "0.30 mm" in errors[0]["message"]


def test_table_grouped_by_severity(tmp_path, capsys):
    path = tmp_path / "bad.dst"
    index = _dst_with_leg_in_corridor(path)
    assert main(["check", str(path), "--tube-path", "0,0 100,0"]) == 1
    out = capsys.readouterr().out
    lines = out.splitlines()
    assert lines[0] == f"{path}: embroidery file, format dst, 1 tube(s): 1 error, 2 warnings, 0 info"
    assert lines[2] == "ERRORS"
    before = sum(r.kind == "stitch" for r in dst_decoder.decode(path.read_bytes()).records[:index[0]])
    assert lines[3].startswith(f"  EA101  needle in tube corridor  [tube 1, needle point {before} (record {index[0]}) at (")
    assert lines[5].strip().startswith("fix: ")


def test_clean_file_and_tube_toml(tmp_path, capsys):
    plan = zigzag(Centerline.straight(100.0), ZigzagParams(width_mm=7.0, interval_mm=1.0))
    pat = pe.EmbPattern()
    for (x, y), c in zip(plan.xy_mm, plan.commands):
        pat.add_stitch_absolute(_PE[int(c)], round(x * 10), round(-y * 10))
    path = tmp_path / "ok.dst"
    pe.write_dst(pat, str(path))
    tubes = tmp_path / "t.toml"
    tubes.write_text('[[tube]]\nname = "A1"\npath_mm = [[0, 0], [100, 0]]\n[machine]\nhoop_width_mm = 50.0\n'
                     'hoop_height_mm = 50.0\n')
    assert main(["check", str(path), "--tube-path", "0,0 100,0"]) == 0
    # only pystitch's header (EA505: ST counts the trim as one record, +Y leaves out its jump): warnings
    assert "1 tube(s): 0 errors, 2 warnings, 0 info" in capsys.readouterr().out
    # the hoop from the tube file is too small for the 100 mm design
    assert main(["check", str(path), "--tube", str(tubes), "--json"]) == 1
    codes = {f["code"] for f in json.loads(capsys.readouterr().out)["findings"]}
    assert codes == {"EA306", "EA505"}
    assert main(["check", str(path)]) == 0
    assert "no tube given (tube rules skipped)" in capsys.readouterr().out


def test_design_with_errors_exits_1(tmp_path, capsys):
    design = tmp_path / "d.toml"
    design.write_text('name = "wide"\n[machine]\nmax_stitch_mm = 13.0\n[operation]\nmax_pressure_kpa = 450.0\n'
                      '[[actuator]]\nname = "W"\npattern = "zigzag"\nwidth_mm = 12.5\n'
                      'interval_mm = 1.0\nlength_mm = 60.0\n')
    assert main(["check", str(design), "--json"]) == 1  # legs |dy| 12.5 mm > DST's 12.1 mm
    doc = json.loads(capsys.readouterr().out)
    assert "EA102" in {f["code"] for f in doc["findings"] if f["severity"] == "error"}
    assert main(["check", str(design), "--format", "jef", "--json"]) == 0  # 12.7 mm per record
    assert json.loads(capsys.readouterr().out)["format"] == "jef"


@pytest.mark.parametrize("data", [b"", b"LA:junk", b"LA:" + b" " * 509 + b"\x01\x02"])
def test_unusable_file_exits_2_with_one_line(tmp_path, capsys, data):
    path = tmp_path / "x.dst"
    path.write_bytes(data)
    assert main(["check", str(path), "--tube-path", "0,0 100,0"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("embroact: error: ") and err.count("\n") == 1


@pytest.mark.parametrize("argv,message", [
    (["check", "missing.dst"], "cannot read"),
    (["check", "x.dst", "--tube-path", "0,0"], "tube_path must be"),
    (["check", "x.dst", "--tube-path", "0,0 1,0", "--tube-radius-mm", "-1"], "outer_radius_mm must be in"),
])
def test_bad_arguments_exit_2(tmp_path, capsys, argv, message):
    plan = zigzag(Centerline.straight(20.0), ZigzagParams(width_mm=7.0, interval_mm=1.0))
    pat = pe.EmbPattern()
    for (x, y), c in zip(plan.xy_mm, plan.commands):
        pat.add_stitch_absolute(_PE[int(c)], round(x * 10), round(-y * 10))
    pe.write_dst(pat, str(tmp_path / "x.dst"))
    argv = [str(tmp_path / a) if a.endswith(".dst") else a for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1


def test_tube_options_rejected_for_designs(capsys):
    assert main(["check", EXAMPLES[0], "--tube-path", "0,0 1,0"]) == 2
    assert "a design file carries its tubes" in capsys.readouterr().err


def test_rules_table_and_missing_input(capsys):
    from embroact.patterns.base.findings import RULES

    assert main(["check", "--rules"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("| code | severity | rule |") and out.count("\n") == len(RULES) + 2
    assert main(["check"]) == 2
    assert "check needs an input" in capsys.readouterr().err


def test_summary_counts_every_finding_shown_or_not(tmp_path, capsys):
    """alpha0 = 0.785 deg (radians by mistake): more findings than any rule lists; the counts take them all."""
    design = tmp_path / "radians.toml"
    design.write_text('[[actuator]]\nname = "C"\npattern = "cross"\nwidth_mm = 7.0\ninterval_mm = 1.4\n'
                      'angle_deg = 0.785\nlength_mm = 100.0\n', encoding="utf-8")
    assert main(["check", str(design), "--json"]) == 1
    doc = json.loads(capsys.readouterr().out)
    capped = [f for f in doc["findings"] if f["count"] > 1]
    assert capped and all("more findings of this rule" in f["message"] for f in capped)
    for severity in ("error", "warning", "info"):
        assert doc["counts"][severity] == sum(f["count"] for f in doc["findings"] if f["severity"] == severity)
    assert sum(doc["counts"].values()) > len(doc["findings"])
    assert main(["check", str(design)]) == 1
    head = capsys.readouterr().out.splitlines()[0]
    assert f"{doc['counts']['error']} errors, {doc['counts']['warning']} warnings" in head


def test_model_flags_reach_the_model_rules(tmp_path, capsys):
    """check takes the model flags predict and build take: the same P0 in the rules as in the prediction."""
    design = os.path.join(os.path.dirname(__file__), "..", "examples", "paper_zigzag.toml")
    assert main(["check", design, "--json"]) == 0
    assert "EA401" not in {f["code"] for f in json.loads(capsys.readouterr().out)["findings"]}
    assert main(["check", design, "--p0-kpa", "400", "--json"]) == 1
    (hit,) = [f for f in json.loads(capsys.readouterr().out)["findings"] if f["code"] == "EA401"]
    assert hit["message"].startswith("P0 400.0 kPa above the working pressure 300 kPa")
    assert main(["predict", design, "--p0-kpa", "400", "--pressure-kpa", "300", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["actuators"][0]["model"]["p0_kpa"] == 400.0
    assert main(["check", str(tmp_path / "x.dst"), "--g-mpa", "2"]) == 2
    assert "--g-mpa applies to design files" in capsys.readouterr().err
