"""DST files checked with an independent decoder (tests/dst_decoder.py), not pyembroidery's reader."""
import os
import subprocess
import sys

import numpy as np
import pytest

import dst_decoder
from h3_plans import generated_plans, hand_plan, needle_points
from embroact.export.machine.formats import encode, write
from embroact.export.machine.encode import LongLegError
from embroact.patterns.base.errors import ExportError, PatternError
from embroact.patterns.plan import Command as C, Role as R, StitchPlan

GRID_HALF_MM = 0.05 + 1e-9  # a 0.1 mm grid puts every point within half a step of the plan


def _plans():
    return [("hand-1", hand_plan(1)), ("hand-3", hand_plan(3))] + generated_plans()


def expected_events(plan):
    """What the DST body must say, derived from the plan record by record."""
    out = []

    def travel(x, y):
        pos = out[-1] if out and out[-1][0] in ("stitch", "travel") else None
        if pos is None or pos[1:3] != (x, y):
            if out and out[-1][0] == "travel":
                out.pop()
            out.append(("travel", x, y))

    pos = (0, 0)
    for (xm, ym), cmd in zip(plan.xy_mm, plan.commands):
        x, y = int(round(xm * 10)), int(round(ym * 10))
        if cmd == C.STITCH:
            out.append(("stitch", x, y))
        elif cmd in (C.JUMP, C.STOP, C.TRIM):
            if (x, y) != pos:
                travel(x, y)
            if cmd == C.STOP:
                out.append(("stop",))
            elif cmd == C.TRIM:
                out.append(("trim",))
        elif cmd == C.END:
            out.append(("end",))
        pos = (x, y)
    return out


def test_decoder_reads_the_published_examples():
    # achatina.de: "A8 12 23 -> y+64 x-12", "A8 12 A3 jump stitch", "00 00 C3 color change"
    head = b"LA:x\r\x1a".ljust(512, b" ")
    dst = dst_decoder.decode(head + bytes.fromhex("A81223A812A30000C30000F3"))
    assert [(r.kind, r.dx, r.dy) for r in dst.records] == [
        ("stitch", -12, 64), ("jump", -12, 64), ("stop", 0, 0), ("end", 0, 0)]


@pytest.mark.parametrize("label,plan", _plans(), ids=lambda v: v if isinstance(v, str) else "")
def test_dst_body_matches_plan(label, plan):
    data, _ = encode(plan, "dst")
    dst = dst_decoder.decode(data)
    # needle points within half a grid step of the plan, in order
    got = np.array([(r.x, r.y) for r in dst.records if r.kind == "stitch"]) / 10.0
    want = needle_points(plan)
    assert got.shape == want.shape
    assert np.abs(got - want).max() <= GRID_HALF_MM
    # every command in order; travel only as jump runs of <= 121 per axis
    ev = [e[:3] if e[0] == "travel" else e for e in dst_decoder.events(dst.records)]
    assert ev == expected_events(plan)
    assert all(abs(r.dx) <= 121 and abs(r.dy) <= 121 for r in dst.records)
    assert dst.records[-1].kind == "end" and dst.trailing == b"\x1a"


@pytest.mark.parametrize("label,plan", _plans(), ids=lambda v: v if isinstance(v, str) else "")
def test_dst_header_fields(label, plan):
    data, _ = encode(plan, "dst")
    dst = dst_decoder.decode(data)
    h = dst.header
    xs = [0] + [r.x for r in dst.records]
    ys = [0] + [r.y for r in dst.records]
    assert h["LA"].rstrip() == plan.name[:16] and len(h["LA"]) == 16
    assert int(h["ST"]) == len(dst.records)
    assert int(h["CO"]) == plan.count(C.STOP) == sum(r.kind == "stop" for r in dst.records)
    assert (int(h["+X"]), int(h["-X"]), int(h["+Y"]), int(h["-Y"])) == (max(xs), -min(xs), max(ys), -min(ys))
    assert int(h["AX"].replace(" ", "")) == dst.records[-1].x
    assert int(h["AY"].replace(" ", "")) == dst.records[-1].y
    assert h["MX"].replace(" ", "") == "+0" and h["MY"].replace(" ", "") == "+0"
    assert h["PD"] == "******"


def test_header_corrects_the_library():
    """A design entirely below the start (y < 0): pystitch still swaps +Y/-Y and ends without 0x1A.

    (pyembroidery 1.5.1 also left stops out of ``CO``; pystitch counts them: that correction is no
    longer needed, the rewritten header agrees.)
    """
    import io

    import pystitch
    from embroact.export.machine.formats import machine_format
    from embroact.export.machine.encode import to_pattern

    plan = hand_plan(3)  # A1 at y = -3 +- 3.5 mm, then 20 mm lower each
    mp = to_pattern(plan, machine_format("a.dst"))
    raw = io.BytesIO()
    pystitch.write_dst(mp.pattern, raw, {"encode": False})
    raw_h = dst_decoder.parse_header(raw.getvalue()[:512])
    fixed = dst_decoder.decode(encode(plan, "dst")[0])
    lowest = min(r.y for r in fixed.records)  # machine frame, y up
    assert int(fixed.header["-Y"]) == -lowest == 2 * 200 + 30 + 35  # two 20 mm gaps, origin at -3 mm, half width
    assert int(raw_h["+Y"]) == -lowest  # the library puts the downward extent under +Y
    assert int(raw_h["CO"]) == int(fixed.header["CO"]) == 3
    assert not raw.getvalue().endswith(b"\xf3\x1a")


def test_three_actuators_stop_exactly_three_times():
    dst = dst_decoder.decode(encode(hand_plan(3), "dst")[0])
    ev = dst_decoder.events(dst.records)
    kinds = [e[0] for e in ev if e[0] != "stitch"]
    assert kinds == ["travel", "stop", "trim", "travel", "stop", "trim", "travel", "stop", "trim", "end"]


def _long_leg_plan():
    # one 13 mm leg across the tube of A1 (corridor radius 1.8 mm around y = 0)
    plan = hand_plan(1, width=13.0, length=4.0)
    return plan


def test_long_leg_refused_with_its_name():
    with pytest.raises(LongLegError) as exc:
        encode(_long_leg_plan(), "dst")
    msg = str(exc.value)
    assert "stitch index 3 of actuator 'A1'" in msg and "13.0 mm" in msg and "12.1 mm" in msg
    assert len(exc.value.legs) == 4  # four legs of 4 mm x 13 mm (tie stitches are short)
    # PES allows 204.7 mm: no error
    encode(_long_leg_plan(), "pes")


def test_split_long_keeps_needles_out_of_the_corridor():
    plan = _long_leg_plan()
    data, res = encode(plan, "dst", split_long=True)
    assert res.split_legs == 4
    dst = dst_decoder.decode(data)
    pts = np.array([(r.x, r.y) for r in dst.records if r.kind == "stitch"]) / 10.0
    assert len(pts) == len(needle_points(plan)) + 4  # one extra needle point per leg
    corridor = plan.actuators[0].tube.corridor_radius_mm
    axis_y = plan.actuators[0].centerline.points_mm[0, 1]
    assert np.all(np.abs(pts[:, 1] - axis_y) >= corridor)
    assert all(abs(r.dy) <= 121 for r in dst.records)


@pytest.mark.parametrize("jumps", [[40.0], [12.0, 24.0, 36.0]])
def test_unintended_trim_is_refused(jumps):
    """Three jump records in a row after a stitch would cut the thread: refused, one long or several short."""
    recs = [(0, 0, C.STITCH, R.LEG), (1, 0, C.STITCH, R.LEG)] + [(x, 0, C.JUMP, R.TRAVEL) for x in jumps]
    recs.append((jumps[-1] + 1, 0, C.STITCH, R.LEG))
    with pytest.raises(PatternError, match="read 3 or more jumps as a trim"):
        encode(StitchPlan.from_records(recs), "dst")
    encode(StitchPlan.from_records(recs[:2] + [(1, 0, C.TRIM, R.CONTROL)] + recs[2:]), "dst")  # after a trim: fine


def test_same_bytes_in_two_processes(tmp_path):
    code = ("import sys; sys.path.insert(0, 'tests'); from h3_plans import hand_plan; "
            "from embroact.export.machine.formats import write; write(hand_plan(3), sys.argv[1])")
    outs = []
    for i in range(2):
        p = tmp_path / f"{i}.dst"
        subprocess.run([sys.executable, "-c", code, str(p)], check=True, cwd=os.path.dirname(os.path.dirname(__file__)))
        outs.append(p.read_bytes())
    assert outs[0] == outs[1] == encode(hand_plan(3), "dst")[0]


def test_failed_write_leaves_existing_file_and_no_partial(tmp_path, monkeypatch):
    target = tmp_path / "act.dst"
    target.write_bytes(b"old")
    with pytest.raises(LongLegError):
        write(_long_leg_plan(), target)
    assert target.read_bytes() == b"old"

    def boom(*a, **k):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "replace", boom)
    with pytest.raises(ExportError, match="No space left"):
        write(hand_plan(1), target)
    assert target.read_bytes() == b"old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["act.dst"]


def test_missing_directory_is_an_export_error(tmp_path):
    with pytest.raises(ExportError, match="does not exist"):
        write(hand_plan(1), tmp_path / "nope" / "act.dst")
