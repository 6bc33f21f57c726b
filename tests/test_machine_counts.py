"""Every count embroact reports for a machine file, held against two readers it did not write.

Every example x every format x {with, without placement line} x {sequence, double cord stop}:
the file is read by pystitch and by pyembroidery, its records grouped by the format's own
conventions (``machine_readers``, docs/machine.md section 5), and every count, needle point
and needle number compared with what ``encode`` reports; every record is held to the
format's per-record limits.
"""
import glob
import os
from dataclasses import replace

import machine_readers as mr
import numpy as np
import pytest
from embroact.export.machine.formats import FORMATS, encode
from h3_plans import needle_points

pytest.importorskip("pyembroidery")
EXAMPLES = sorted(glob.glob(os.path.join(os.path.dirname(__file__), "..", "examples", "*.toml")))


def _designs():
    from embroact.export.files.designfile import load_design
    from embroact.patterns.design import build_plan

    out = []
    for path in EXAMPLES:
        d = load_design(path)
        for placed in (False, True):
            label = os.path.basename(path) + ("+placement" if placed else "")
            out.append((label, build_plan(replace(d, machine=replace(d.machine, placement_line=placed)))))
    return out


DESIGNS = _designs()
CASES = [(label, fmt, mode) for label, _ in DESIGNS for fmt in sorted(FORMATS) for mode in ("sequence", "double")]
PLANS = dict(DESIGNS)


@pytest.mark.parametrize("label,fmt,mode", CASES, ids=["-".join(c) for c in CASES])
def test_every_count_is_what_two_readers_find(label, fmt, mode):
    plan = PLANS[label]
    data, res = encode(plan, fmt, cord_stop=mode, split_long=True)
    reported = {k: getattr(res, k) for k in ("stitches", "jumps", "trims", "stops", "color_changes")}
    lim = FORMATS[fmt].limit
    points = []
    for library in mr.LIBRARIES:
        records = mr.file_records(data, fmt, library)
        assert mr.counts(records, fmt) == reported, library
        assert mr.over_limit(records, round(lim.max_record_mm * 10), round(lim.max_jump_mm * 10)) == [], library
        assert [r.needle for r in records if r.kind == "needle"] == [1] * sum(r.kind == "needle" for r in records)
        assert [r.kind for r in records].count("end") == 1
        points.append(np.array([(r.x, -r.y) for r in records if r.kind == "stitch"], dtype=float) / 10.0)
    # the same needle points for both readers, and the plan's (0.1 mm grid, file origin added back)
    assert np.array_equal(points[0], points[1])
    want = np.rint(needle_points(plan) * 10) / 10
    assert np.abs(points[0] + np.array(res.origin_mm) - want).max() < 1e-6
    # the chosen stop mode changes only the stop-code formats' bytes
    if fmt not in ("dst", "exp"):
        assert encode(plan, fmt, cord_stop="sequence", split_long=True)[0] == data


def test_jumps_of_three_actuators_by_hand():
    """The issue's case: 4 jumps to the first needle point and 7 after each of 2 trims (DST: after the trim's 3)."""
    plan = PLANS["three_actuators.toml"]
    jumps = {fmt: encode(plan, fmt)[1].jumps for fmt in FORMATS}
    assert {f: j for f, j in jumps.items() if f in ("dst", "exp", "jef", "tbf", "u01", "xxx")} == dict.fromkeys(
        ("dst", "exp", "jef", "tbf", "u01", "xxx"), 4 + 7 + 7)
    assert jumps["vp3"] == 0  # VP3 holds no jump record: its colour blocks start at header positions
    assert jumps["pes"] == jumps["pec"] == 1  # one move to the first point; later travel is on the trim-flagged jump


def test_vp3_placement_travel_begins_a_block():
    """VP3 has no jump: the travel to a later placement line is a colour block's start, not a 42.5 mm stitch."""
    plan = PLANS["three_actuators.toml+placement"]
    data, res = encode(plan, "vp3")
    records = mr.file_records(data, "vp3", "pystitch")
    assert max(max(abs(r.dx), abs(r.dy)) for r in records if r.kind == "stitch") <= 255
    assert res.thread_names == ("narrow zigzag placement", "narrow zigzag", "wide zigzag placement", "wide zigzag",
                                "cross 45deg placement", "cross 45deg")
    assert res.color_changes == 5 and res.pauses == 5


def test_vp3_worksheet_says_press_start_at_the_block_before_a_placement_line():
    from embroact.export.report.worksheet import worksheet

    plan = PLANS["three_actuators.toml+placement"]
    sheet = worksheet(plan, machine=encode(plan, "vp3")[1])
    assert len(sheet.stops) == 5
    assert ["lay tube" in line for line in sheet.stops] == [True, False, True, False, True]
    assert sheet.stops[1].startswith("stop 2: a colour change before the placement line")
    assert "3 after the placement lines" in sheet.setup[0] and "2 before the placement lines" in sheet.setup[0]


NAMES = ["A", "x" * 16, "abcdefghijklmnopq", "n" * 60, "Ümlaut ø 45° – a name of more than sixteen"]
#: The label each format's reader gives back, by the format's field (None: the format holds no name).
FIELD = {"dst": ("name", 16), "tbf": ("name", 16), "pec": ("Name", 16), "pes": ("name", None), "vp3": (None, None),
         "jef": (None, None), "exp": (None, None), "xxx": (None, None), "u01": (None, None)}


@pytest.mark.parametrize("fmt", sorted(FORMATS))
@pytest.mark.parametrize("name", NAMES, ids=[f"{len(n)}-chars" for n in NAMES])
def test_names_of_any_length_keep_the_header_in_place(fmt, name):
    """A name cut to its fixed field after transliteration: nothing after the field moves, every
    count stays, and TBF/U01 read needle 1 for every actuator."""
    import re

    from embroact.export.machine.encode import ascii_label
    from embroact.patterns.design import build_plan, design_from_dict

    design = {"name": name, "actuator": [{"name": f"T{k}", "pattern": "zigzag", "width_mm": 5.0, "interval_mm": 1.0,
                                          "length_mm": 20.0, "origin_mm": [0.0, 15.0 * k]} for k in range(3)]}
    plan = build_plan(design_from_dict(design))
    data, res = encode(plan, fmt)
    reference = encode(replace(plan, name="A"), fmt)[1]
    key, width = FIELD[fmt]
    label = ascii_label(name)
    if fmt == "pec":  # PEC keeps letters and digits only (pystitch's writer: others upset machines)
        label = re.sub(r"[^A-Za-z0-9]+", "", label)
    for library in mr.LIBRARIES:
        _, pattern = mr.read(data, fmt, library)
        if key is not None:
            assert pattern.get_metadata(key, None) == label[:width]
        records = mr.file_records(data, fmt, library)
        assert mr.counts(records, fmt) == {k: getattr(reference, k) for k in mr.counts(records, fmt)}
        needles = [r.needle for r in records if r.kind == "needle"]
        assert needles == ([1] * 3 if fmt in ("tbf", "u01") else [])
    if fmt == "tbf":  # the needle table stays at 0x10A: one byte per needle set, needle 1
        assert data[0x107:0x10A] == b"DO:" and data[0x10A:0x10D] == bytes([1, 1, 1]) and data[0x10D] == 0
    if fmt == "dst":
        assert data[:20] == b"LA:" + label[:16].ljust(16).encode("ascii") + b"\r"


def test_cord_stop_is_reported_where_it_changes_the_bytes():
    plan = PLANS["three_actuators.toml"]
    for fmt in FORMATS:
        seq, res = encode(plan, fmt, cord_stop="sequence")
        dbl, res2 = encode(plan, fmt, cord_stop="double")
        assert (seq != dbl) == (fmt in ("dst", "exp"))
        assert (res.cord_stop, res2.cord_stop) == (("sequence", "double") if seq != dbl else (None, None))


def _stop_marks(svg):
    import xml.etree.ElementTree as ET

    ns = {"s": "http://www.w3.org/2000/svg"}
    root = ET.fromstring(svg)
    out = []
    for g in root.find(".//s:g[@id='stops']", ns):
        c, t = g.find("s:circle", ns), g.find("s:text", ns)
        out.append((g.get("class"), round(float(c.get("cx")), 1), round(-float(c.get("cy")), 1), t.text))
    return root, ns, out


@pytest.mark.parametrize("fmt", ["dst", "pes", "vp3"])
def test_stitch_preview_shows_the_formats_pauses_and_the_travel_from_the_origin(fmt):
    """The stop marks of a build's preview are where that format's file makes the machine wait, as
    pyembroidery reads the file (DST: the stop codes; PES: its colour changes, tube 1 before start)."""
    from embroact.export.pictures.stitches import plan_svg

    plan = PLANS["three_actuators.toml"]
    data, res = encode(plan, fmt)
    root, ns, marks = _stop_marks(plan_svg(plan, machine=res))
    records = mr.file_records(data, fmt, "pyembroidery")
    wait = "color"  # pyembroidery reads DST's stop code as the colour change it shares
    where = []
    for n, r in enumerate(records):  # VP3: the new block's start, the move after the colour change
        if r.kind == wait and (n == 0 or records[n - 1].kind != wait):
            q = records[n + 1] if fmt == "vp3" else r
            where.append((round(q.x / 10 + res.origin_mm[0], 1), round(-q.y / 10 + res.origin_mm[1], 1)))
    shown = [(x, y) for cls, x, y, _ in marks if cls == "stop"]
    assert shown == where and len(where) == (3 if fmt == "dst" else 2)
    before = [text for cls, *_, text in marks if cls == "before-start"]
    assert before == ([] if fmt == "dst" else ["before start: lay tube narrow zigzag"])
    # the frame's first move, from the machine's start point (the file origin) to the first record
    travel = root.find(".//s:g[@id='travel']/s:path", ns).get("d")
    ox, oy = res.origin_mm
    assert travel.startswith(f"M {ox:g},{-oy:g} L ".replace("-0,", "0,"))
