"""`check` on embroidery files embroact did not write: by hand (a DST encoder written here from the
format's description) and by pystitch's writers. Each fault gives one finding."""
import json

import numpy as np
import pystitch as pe

import dst_decoder
from embroact.export.cli.main import main
from embroact.export.machine.filecheck import check_file, tube_layout

_WEIGHTS = (81, 27, 9, 3, 1)
#: (byte, bit) of +w and -w per axis and weight, from the record layout (docs/machine.md section 4).
_X = {1: ((0, 0), (0, 1)), 9: ((0, 2), (0, 3)), 3: ((1, 0), (1, 1)), 27: ((1, 2), (1, 3)), 81: ((2, 2), (2, 3))}
_Y = {1: ((0, 7), (0, 6)), 9: ((0, 5), (0, 4)), 3: ((1, 7), (1, 6)), 27: ((1, 5), (1, 4)), 81: ((2, 5), (2, 4))}


def _ternary(v: int) -> dict:
    """Balanced-ternary digits of v (|v| <= 121) by weight."""
    out = {}
    for w in _WEIGHTS:
        d = int(np.clip(round(v / w), -1, 1)) if abs(v) > (w - 1) // 2 else 0
        out[w] = d
        v -= d * w
    assert v == 0
    return out


def _record(dx: int, dy: int, kind: str = "stitch") -> bytes:
    b = [0, 0, 0x03]
    for table, v in ((_X, dx), (_Y, dy)):
        for w, d in _ternary(v).items():
            if d:
                byte, bit = table[w][0 if d > 0 else 1]
                b[byte] |= 1 << bit
    if kind == "jump":
        b[2] |= 0x80
    elif kind == "stop":
        b = [0, 0, 0xC3]
    elif kind == "end":
        b = [0, 0, 0xF3]
    return bytes(b)


def _hand_dst(moves, *, st=None, co=None, plus_x=None):
    """A DST file from (dx, dy, kind) moves [0.1 mm, y up], header written from them (or the given fields)."""
    body = b"".join(_record(*m) for m in moves) + _record(0, 0, "end")
    xs, ys = np.cumsum([0] + [m[0] for m in moves]), np.cumsum([0] + [m[1] for m in moves])
    fields = [("LA", "hand made".ljust(16)), ("ST", f"{len(moves) + 1 if st is None else st:7d}"),
              ("CO", f"{sum(m[2] == 'stop' for m in moves) if co is None else co:3d}"),
              ("+X", f"{xs.max() if plus_x is None else plus_x:5d}"), ("-X", f"{-xs.min():5d}"),
              ("+Y", f"{ys.max():5d}"), ("-Y", f"{-ys.min():5d}"), ("AX", f"+{xs[-1]:5d}"), ("AY", f"+{ys[-1]:5d}"),
              ("MX", "+    0"), ("MY", "+    0"), ("PD", "******")]
    head = "".join(f"{k}:{v}\r" for k, v in fields).encode("ascii") + b"\x1a"
    return head.ljust(512, b" ") + body + b"\x1a"


def _zigzag(length_units=600, half_units=35, step=10):
    """Moves of a zigzag along +x from the start point: the first needle point 3.5 mm above the axis."""
    moves = [(0, half_units, "jump")]
    for k in range(length_units // step):
        moves.append((step, -2 * half_units if k % 2 == 0 else 2 * half_units, "stitch"))
    return moves


def _check(path, *tube_paths, extra=()):
    return check_file(path, [tube_layout(_file_points(p)) for p in tube_paths], *extra)


def _file_points(text):
    from embroact.export.machine.filecheck import parse_tube_path

    return parse_tube_path(text)


def test_hand_made_dst_is_clean_and_decodes_with_the_suites_decoder(tmp_path):
    path = tmp_path / "hand.dst"
    path.write_bytes(_hand_dst(_zigzag()))
    dst = dst_decoder.decode(path.read_bytes())
    assert int(dst.header["ST"]) == len(dst.records) == 62 and dst.records[-1].x == 600
    assert [f.code for f in _check(path, "0,0 60,0")] == []


def test_dst_header_fields_are_held_against_the_body(tmp_path):
    """The issue's file: ST 99, CO 0 and +X 1 over a body of 62 records with one stop: one finding per field."""
    moves = _zigzag()
    moves.insert(1, (0, 0, "stop"))
    path = tmp_path / "header.dst"
    path.write_bytes(_hand_dst(moves, st=99, co=0, plus_x=1))
    found = _check(path, "0,0 60,0")
    assert sorted((f.code, f.message) for f in found) == [
        ("EA505", "header +X 1, but the body reaches 600 units right of the start point"),
        ("EA505", "header CO 0, but the body holds 1 colour-change (stop) records"),
        ("EA505", "header ST 99, but the body holds 63 records (the end record included)")]
    assert all(f.severity.value == "warning" for f in found)
    assert all(f.fix.startswith("save the file again") for f in found)


def _pystitch_file(path, stitches_mm, *, encode=True):
    """Needle points [mm, file frame y down] written by pystitch's own writer (its encoder on)."""
    pat = pe.EmbPattern()
    for x, y in stitches_mm:
        pat.add_stitch_absolute(pe.STITCH, x * 10, y * 10)
    pat.add_command(pe.END)
    pe.write(pat, str(path), {"encode": encode})
    return path


def test_a_long_stitch_split_by_pystitch_is_named_as_a_long_stitch(tmp_path):
    """A satin of 12.6 mm legs (12.64 mm long): pystitch's DST encoder splits each into jump + stitch."""
    pts = [(1.0 * k, 6.3 * (-1) ** k) for k in range(41)]
    path = _pystitch_file(tmp_path / "satin.dst", pts)
    kinds = [r.kind for r in dst_decoder.decode(path.read_bytes()).records]
    assert kinds.count("jump") >= 39  # every leg but the first move: jump + stitch
    found = _check(path, "0,0 40,0")
    assert {f.code for f in found} == {"EA103"}
    assert sum(f.count for f in found) == 40  # one per long leg (the first needle point is reached by travel)
    f = found[0]
    assert "written as 1 jump record(s) + 1 stitch" in f.message and "12.64 mm long" in f.message
    assert f.fix.startswith("split this leg")
    assert f.needle_point is not None and f.at_needle and f"needle point {f.needle_point} (record" in f.place()


def test_one_stray_travel_outside_the_hoop_is_one_finding_on_the_jump(tmp_path):
    pat = pe.EmbPattern()
    for k in range(61):
        pat.add_stitch_absolute(pe.STITCH, 10 * k, 35 * (-1) ** k)
    pat.add_stitch_absolute(pe.JUMP, 3600, 35)  # 300 mm right of the stitching, and back
    pat.add_stitch_absolute(pe.JUMP, 600, -35)
    for k in range(61, 80):
        pat.add_stitch_absolute(pe.STITCH, 10 * k, 35 * (-1) ** k)
    pat.add_command(pe.END)
    path = tmp_path / "stray.dst"
    pe.write(pat, str(path))
    found = _check(path, "0,0 79,0")
    hoop = [f for f in found if f.code == "EA306"]
    assert len(hoop) == 1 and not hoop[0].at_needle and "jump records outside" in hoop[0].message
    assert hoop[0].place().startswith("record ") and "after needle point 60" in hoop[0].place()


def test_a_tube_shorter_than_the_embroidery_is_found(tmp_path):
    path = tmp_path / "long.dst"
    path.write_bytes(_hand_dst(_zigzag(length_units=1000)))
    found = _check(path, "0,0 50,0")
    assert [f.code for f in found] == ["EA308"]
    # legs of 1 mm along x up to 100 mm; those that miss the tube (r 1.5 mm, ending at x = 50) start at x >= 52
    assert found[0].message.startswith("48 legs from here (48.0 mm of embroidery) beyond the end of every tube")


def test_a_tube_end_not_covered_is_found(tmp_path):
    path = tmp_path / "short.dst"
    path.write_bytes(_hand_dst(_zigzag()))
    found = _check(path, "-30,0 60,0")  # 30 mm of tube before the first leg
    assert [f.code for f in found] == ["EA307"]


def test_places_are_needle_points_the_same_in_every_format(tmp_path):
    """Two tubes, a trim and a colour change between them, one needle point of the second on its axis
    (EA101): each format writes the trim with its own records, the needle point named is the same."""
    places = {}
    for fmt in ("dst", "jef", "tbf", "xxx", "u01", "exp"):
        pat = pe.EmbPattern()
        for k in range(31):
            pat.add_stitch_absolute(pe.STITCH, 10 * k, 35 * (-1) ** k)
        pat.add_command(pe.TRIM)
        pat.add_command(pe.COLOR_CHANGE)
        for k in range(31):
            pat.add_stitch_absolute(pe.STITCH, 10 * k, 300 + (0 if k == 10 else 35 * (-1) ** k))
        pat.add_command(pe.END)
        path = tmp_path / f"two.{fmt}"
        pe.write(pat, str(path))
        found = [f for f in _check(path, "0,0 30,0", "0,30 30,30") if f.code == "EA101"]
        assert len(found) == 1, fmt
        places[fmt] = (found[0].needle_point, found[0].stitch_index)
    assert {p[0] for p in places.values()} == {41}  # needle point 10 of the second tube (counted from 0)
    assert len({p[1] for p in places.values()}) > 1  # the record numbers differ between the formats


def test_tube_path_takes_svg_path_data_and_names_the_frame(tmp_path, capsys):
    path = tmp_path / "hand.dst"
    path.write_bytes(_hand_dst([(0, -100, "jump"), (0, -65, "jump")] + _zigzag()[1:]))  # axis 20 mm below the start
    # file frame is y down: the tube lies at y = +20
    assert main(["check", str(path), "--tube-path", "M 0 20 H 60", "--json"]) == 0
    svg = json.loads(capsys.readouterr().out)
    assert main(["check", str(path), "--tube-path", "0,20 60,20", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["findings"] == svg["findings"]
    assert main(["check", str(path), "--tube-path", "M 0 -20 H 60", "--json"]) == 1  # pasted y up
    doc = json.loads(capsys.readouterr().out)
    assert [f["code"] for f in doc["findings"]] == ["EA307"]
    assert "with y negated the tube path lies on the stitches" in doc["findings"][0]["message"]


def test_tbf_header_extents_are_held_against_the_records(tmp_path):
    """pystitch writes TBF's +Y/-Y from the y-down bounds (swapped): needle points 10..60 mm right of the
    start and 20..30 mm below it (file frame, y down), the start point included, claim +Y 300 and -Y 0
    (0.1 mm); the records reach 0 above and 300 below. +X 600 and -X 0 are right."""
    pat = pe.EmbPattern()
    for k in range(51):
        pat.add_stitch_absolute(pe.STITCH, 100 + 10 * k, 250 + 50 * (-1) ** k)
    pat.add_command(pe.END)
    path = tmp_path / "a.tbf"
    pe.write(pat, str(path))
    found = [f for f in _check(path, "10,25 60,25") if f.code == "EA505"]
    assert sorted(f.message for f in found) == [
        "header +Y 300, but the body reaches 0 units above the start point",
        "header -Y 0, but the body reaches 300 units below the start point"]


def test_embroacts_own_tbf_and_dst_headers_agree_with_their_records(tmp_path):
    from embroact.export.machine.formats import write
    from embroact.patterns.design import build_plan, default_design

    for fmt in ("dst", "tbf"):
        path = tmp_path / f"a.{fmt}"
        write(build_plan(default_design()), str(path))
        assert [f for f in _check(path, "0,0 100,0") if f.code == "EA505"] == []


def test_a_bare_machine_file_gets_no_ea203_at_the_transitions_the_generator_made(tmp_path, capsys):
    """`check file.dst` of a segmented actuator warned EA203 at each transition between segments (a 4.45 mm gap
    in the README's hook) which `check design.toml` leaves out: the file has no plan to name its segments, so a
    gap across which the legs' extents change (7 mm zigzag to 7 mm cross: along the tube 1 mm against 2 x 7 tan 45)
    is read as a transition; a segment whose own interval is too wide still gets EA203 inside it (3.5 mm gaps)."""
    from embroact.export.machine.formats import encode
    from embroact.patterns.centerline import Centerline
    from embroact.patterns.design import ActuatorSpec, Design, MachineSettings, OperationSettings, build_plan
    from embroact.patterns.origin import origin_point_mm
    from embroact.patterns.rules import check_geometry
    from embroact.patterns.params import CrossParams, Tube, ZigzagParams
    from embroact.patterns.segments import SegmentSpec

    for interval_mm, inside in ((1.0, 0), (3.5, 8)):
        segs = (SegmentSpec(ZigzagParams(7.0, interval_mm), 40.0), SegmentSpec(CrossParams(7.0, 1.4, 45.0), 30.0),
                SegmentSpec(ZigzagParams(8.0, 1.0), 30.0))
        design = Design("s", Tube(), MachineSettings(), OperationSettings(),
                        (ActuatorSpec.segmented("S", segs, Centerline.straight(100.0)),))
        plan = build_plan(design)
        path = tmp_path / "s.dst"
        path.write_bytes(encode(plan, "dst")[0])
        tube = " ".join(f"{x:g},{y:g}" for x, y in plan.actuators[0].centerline.points_mm)  # the path as placed
        origin = ",".join(f"{v:g}" for v in origin_point_mm(plan, design.machine.origin))
        capsys.readouterr()
        main(["check", str(path), "--tube-path", tube, "--origin-mm", origin, "--json"])
        found = json.loads(capsys.readouterr().out)["findings"]
        assert not [f for f in found if f["severity"] == "error"], found  # the file is read on its tube
        gaps = [f["message"] for f in found if f["code"] == "EA203"]
        design_gaps = [f.message.replace("S ", "tube 1 ") for f in check_geometry(plan) if f.code == "EA203"]
        assert gaps == design_gaps and len(gaps) >= inside and all("3.50 mm apart" in m for m in gaps)
