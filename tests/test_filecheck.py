"""Checking embroidery files written by pystitch against their tubes.

Record indices are located with the test suite's own DST decoder (tests/dst_decoder.py),
not with pystitch's reader that embroact.export.machine.filecheck uses.
"""
import numpy as np
import pystitch as pe
import pytest

import dst_decoder
from embroact.export.machine.filecheck import (check_file, load_tube_file, parse_tube_path, read_records,
                                       tube_layout)
from embroact.patterns.centerline import Centerline
from embroact.patterns.base.errors import DesignFileError, ParameterError
from embroact.patterns.params import ZigzagParams
from embroact.patterns.plan import Command, Role
from embroact.patterns.rules import RuleSettings
from embroact.patterns.zigzag import zigzag

_PE = {Command.STITCH: pe.STITCH, Command.JUMP: pe.JUMP, Command.TRIM: pe.TRIM, Command.STOP: pe.STOP,
       Command.END: pe.END}
TUBE = tube_layout([(0.0, 0.0), (100.0, 0.0)], name="T")  # file frame: the plan's y = 0 axis


def _write(path, xy_mm, commands):
    """Plan-frame records (mm, y up) -> pystitch (0.1 mm, y down) -> file."""
    pat = pe.EmbPattern()
    for (x, y), c in zip(xy_mm, commands):
        pat.add_stitch_absolute(_PE[int(c)], round(x * 10), round(-y * 10))
    pe.write(pat, str(path))
    return path


def _plan():
    return zigzag(Centerline.straight(100.0), ZigzagParams(width_mm=7.0, interval_mm=1.0))


def _records(path):
    return dst_decoder.decode(path.read_bytes()).records


def _index_of(records, x_units, y_units_up):
    hits = [i for i, r in enumerate(records) if r.kind == "stitch" and (r.x, r.y) == (x_units, y_units_up)]
    assert len(hits) == 1, hits
    return hits[0]


def test_records_in_the_files_own_order(tmp_path):
    # stitch, trim (3 zero-net jumps in DST), a 40 mm travel, stop, stitch: no record dropped or added
    xy = [(0, 0), (1, 0), (1, 0), (41, 0), (41, 0), (42, 0), (42, 0)]
    cmds = [Command.STITCH, Command.STITCH, Command.TRIM, Command.JUMP, Command.STOP, Command.STITCH, Command.END]
    path = _write(tmp_path / "a.dst", xy, cmds)
    decoded = _records(path)
    rec = read_records(path)
    kinds = {"stitch": Command.STITCH, "jump": Command.JUMP, "stop": Command.STOP, "end": Command.END}
    assert len(rec) == len(decoded)
    assert rec.commands.tolist() == [kinds[r.kind] for r in decoded]
    assert np.array_equal(rec.xy_mm * 10, [[r.x, -r.y] for r in decoded])  # mm, y down


def test_clean_design_file_has_no_findings(tmp_path):
    plan = _plan()
    path = _write(tmp_path / "ok.dst", plan.xy_mm, plan.commands)
    # only pystitch's header, EA505 warnings: ST counts the trim (3 jump records) as one record, and +Y leaves
    # out the trim's first jump (+0.2 mm above the last needle point, 3.5 mm up)
    st = int(dst_decoder.decode(path.read_bytes()).header["ST"])
    found = check_file(path, [TUBE])
    assert {f.code for f in found} == {"EA505"} and not any(f.is_error for f in found)
    assert sorted(f.message for f in found) == [
        "header +Y 35, but the body reaches 37 units above the start point",
        f"header ST {st}, but the body holds {st + 2} records (the end record included)"]


def test_misplaced_leg_found_at_the_files_record_index(tmp_path):
    plan = _plan()
    leg = int(np.flatnonzero(plan.roles == Role.LEG)[40])
    xy = plan.xy_mm.copy()
    xy[leg, 1] = 0.5 * np.sign(xy[leg, 1])  # 0.5 mm from the axis: inside the 1.8 mm corridor
    path = _write(tmp_path / "bad.dst", xy, plan.commands)
    expected = _index_of(_records(path), round(xy[leg, 0] * 10), round(xy[leg, 1] * 10))
    found = check_file(path, [TUBE])
    errors = [f for f in found if f.is_error]
    assert [(f.code, f.stitch_index) for f in errors] == [("EA101", expected)]
    assert errors[0].xy_mm == (round(xy[leg, 0], 1), -xy[leg, 1])  # file frame: y down
    # a tube 2 mm off the axis (file y = +2, i.e. decoder y = -20): the needle points of one rail
    # (1.5 mm away) are too close; 10 are listed, the 11th finding counts the rest
    off = tube_layout([(0.0, 2.0), (100.0, 2.0)])
    hits = [f for f in check_file(path, [off]) if f.code == "EA101"]
    close = [i for i, r in enumerate(_records(path)) if r.kind == "stitch" and abs(r.y + 20) < 18]
    assert [f.stitch_index for f in hits[:10]] == close[:10]
    assert hits[10].message.startswith(f"{len(close) - 10} more findings")


def test_pes_file_is_checked_too(tmp_path):
    plan = _plan()
    leg = int(np.flatnonzero(plan.roles == Role.LEG)[10])
    xy = plan.xy_mm.copy()
    xy[leg, 1] = 0.0
    # pystitch's PES writer starts with a needle record at the origin, on this tube's axis:
    # start the tube 5 mm in so that only the moved leg is in its corridor
    tube = tube_layout([(5.0, 0.0), (100.0, 0.0)])
    found = check_file(_write(tmp_path / "bad.pes", xy, plan.commands), [tube])
    hits = [f for f in found if f.code == "EA101"]
    assert len(hits) == 1 and hits[0].xy_mm == (round(xy[leg, 0], 1), 0.0)


def test_missing_stop_between_tubes(tmp_path):
    a = _plan()
    shift = np.array([0.0, -30.0])  # second actuator 30 mm lower (plan frame)
    body = lambda p: [(xy, c) for xy, c in zip(p.xy_mm, p.commands) if c == Command.STITCH]  # noqa: E731
    tubes = [TUBE, tube_layout([(0.0, 30.0), (100.0, 30.0)], name="U")]  # file frame: y = +30
    second = [(xy + shift, c) for xy, c in body(a)]
    no_stop = body(a) + [(second[0][0], Command.JUMP)] + second + [(second[-1][0], Command.END)]
    path = _write(tmp_path / "two.dst", [r[0] for r in no_stop], [r[1] for r in no_stop])
    # the first needle record of U that moves (the jump's landing stitch of 0 mm lays no thread)
    expected = next(k for k, r in enumerate(_records(path))
                    if r.kind == "stitch" and r.y < -200 and (r.dx, r.dy) != (0, 0))
    hits = [f for f in check_file(path, tubes) if f.code == "EA502"]
    assert [(f.stitch_index, f.actuator) for f in hits] == [(expected, "U")]
    with_stop = body(a) + [(second[0][0], Command.JUMP), (second[0][0], Command.STOP)] + second
    path = _write(tmp_path / "two_ok.dst", [r[0] for r in with_stop] + [second[-1][0]],
                  [r[1] for r in with_stop] + [Command.END])
    found = check_file(path, tubes)
    assert not [f for f in found if f.code in ("EA502", "EA503") or f.is_error]


def test_long_travel_reads_as_trim(tmp_path):
    xy = [(0, 0), (1, 0), (41, 0), (42, 0), (42, 0)]
    path = _write(tmp_path / "j.dst", xy, [Command.STITCH, Command.STITCH, Command.JUMP, Command.STITCH, Command.END])
    kinds = [r.kind for r in _records(path)]
    first_jump = kinds.index("jump")
    hits = [f for f in check_file(path, []) if f.code == "EA501"]
    assert [f.stitch_index for f in hits] == [first_jump]
    assert f"{kinds.count('jump')} consecutive jump records" in hits[0].message


def test_measured_width_gives_sleeve_rules(tmp_path):
    narrow = zigzag(Centerline.straight(50.0), ZigzagParams(width_mm=7.0, interval_mm=1.0))
    xy = narrow.xy_mm * np.array([1.0, 2.6 / 7.0])  # squeeze to w = 2.6 mm < 2.80 mm
    found = check_file(_write(tmp_path / "n.dst", xy, narrow.commands), [tube_layout([(0, 0), (50, 0)])])
    assert [f.code for f in found if f.code == "EA201"] == ["EA201"]


@pytest.mark.parametrize("name,data,message", [
    ("short.dst", b"LA:x", "shorter than the 512-byte header"),
    ("nohead.dst", b"\0" * 600, "does not start with 'LA:'"),
    ("empty.pes", b"", "empty file"),
    ("junk.pes", b"#PES0001" + b"\xff" * 40, "unreadable PES file"),
])
def test_unusable_files_give_one_line(tmp_path, name, data, message):
    path = tmp_path / name
    path.write_bytes(data)
    with pytest.raises(DesignFileError, match=message) as err:
        read_records(path)
    assert "\n" not in str(err.value)


def test_truncated_dst(tmp_path):
    plan = _plan()
    data = _write(tmp_path / "ok.dst", plan.xy_mm, plan.commands).read_bytes()
    (tmp_path / "cut.dst").write_bytes(data[:512 + 3 * 40])
    with pytest.raises(DesignFileError, match="truncated DST file: no end record among 40 records"):
        read_records(tmp_path / "cut.dst")


def test_missing_and_unknown_files(tmp_path):
    with pytest.raises(DesignFileError, match="cannot read"):
        read_records(tmp_path / "none.dst")
    (tmp_path / "a.xyz").write_bytes(b"x")
    with pytest.raises(DesignFileError, match=r"cannot read '\.xyz' embroidery files; readable: .*dst"):
        read_records(tmp_path / "a.xyz")


def test_tube_path_text():
    assert parse_tube_path("1,2  3.5,-4\n5,6").tolist() == [[1, 2], [3.5, -4], [5, 6]]
    for bad in ("1,2", "1,2 3", "1,2 a,b", "1,2,3 4,5,6", "1,2 nan,3"):
        with pytest.raises(ParameterError, match="tube_path"):
            parse_tube_path(bad)
    with pytest.raises(ParameterError, match="outer_radius_mm must be in"):
        tube_layout([(0, 0), (1, 0)], outer_radius_mm=-1.0)


def test_tube_toml(tmp_path):
    path = tmp_path / "tubes.toml"
    path.write_text('[[tube]]\nname = "A"\npath_mm = "0,0 100,0"\n\n'
                    '[[tube]]\npath_mm = [[0, 30], [100, 30]]\nouter_radius_mm = 2.0\nend_margin_mm = 30\n\n'
                    '[machine]\nhoop_width_mm = 150.0\nhoop_height_mm = 100.0\n')
    tubes, machine = load_tube_file(path)
    assert [t.name for t in tubes] == ["A", "tube 2"]
    assert tubes[1].outer_radius_mm == 2.0 and tubes[1].end_margin_mm == 30.0
    assert list(tubes[1].path.coords) == [(0.0, 30.0), (100.0, 30.0)]
    assert RuleSettings(**machine).hoop_width_mm == 150.0
    for text, message in [
        ('[[tube]]\npath_mm = "0,0 1,0"\nradius = 2\n', "unknown key 'radius' in \\[\\[tube\\]\\] 1"),
        ('[[tube]]\nname = "A"\n', "has no path_mm"),
        ('[[tube]]\npath_mm = [[0, 0]]\n', "at least 2 finite points"),
        ('[machine]\nhoop_width_mm = 1\n', "needs at least one \\[\\[tube\\]\\]"),
        ('[[tube]\n', "TOML syntax error"),
    ]:
        path.write_text(text)
        with pytest.raises(DesignFileError, match=message):
            load_tube_file(path)


@pytest.mark.parametrize("fmt", ["dst", "tbf", "u01", "jef", "exp", "pes", "xxx"])
def test_three_actuator_machine_files_check_clean(tmp_path, fmt):
    """embroact's own writer output, checked with the tubes in the file frame (plan y negated)."""
    import os

    from embroact.export.files.designfile import load_design
    from embroact.export.machine.formats import write
    from embroact.patterns.design import build_plan

    here = os.path.dirname(__file__)
    plan = build_plan(load_design(os.path.join(here, "..", "examples", "three_actuators.toml")))
    path = tmp_path / f"three.{fmt}"
    write(plan, str(path))
    tubes = [tube_layout(a.centerline.points_mm * np.array([1.0, -1.0]), name=a.name) for a in plan.actuators]
    found = check_file(path, tubes)
    assert not [f for f in found if f.is_error or f.code in ("EA502", "EA503")]
    # checked against only the first two tubes, the third actuator's needle points belong to no tube
    assert not [f for f in check_file(path, tubes[:2]) if f.is_error]
