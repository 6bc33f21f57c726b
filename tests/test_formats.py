"""Every machine format: written, read back with pystitch's readers (and, for DST, the suite's own
decoder), and compared record by record with the plan and with what embroact reports."""
import glob
import importlib
import io
import os

import numpy as np
import pytest

import dst_decoder
from h3_plans import generated_plans, hand_plan, needle_points
from embroact.export.machine.encode import THREAD_COLORS, ascii_label
from embroact.export.machine.formats import FORMATS, encode, machine_format, write
from embroact.patterns.base.errors import ParameterError
from embroact.patterns.limits import FORMAT_LIMITS
from embroact.patterns.plan import Command as C

pe = pytest.importorskip("pystitch")
ALL = sorted(FORMATS)
EXAMPLES = sorted(glob.glob(os.path.join(os.path.dirname(__file__), "..", "examples", "*.toml")))
RAW = {"trim_at": None, "trim_distance": None, "clipping": False}
STOP_CODE = {"dst", "exp", "tbf", "u01"}
COLOUR = {"pes", "pec", "jef", "vp3", "xxx"}


def _read_back(data, fmt):
    """pystitch's reader on the bytes, keeping the file's own records."""
    reader = importlib.import_module(f"pystitch.{fmt.capitalize()}Reader")
    return pe.EmbPattern.read_embroidery(reader, io.BytesIO(data), dict(RAW))


def _kinds(pattern):
    names = {pe.STITCH: "stitch", pe.JUMP: "jump", pe.TRIM: "trim", pe.STOP: "stop", pe.COLOR_CHANGE: "color",
             pe.NEEDLE_SET: "needle", pe.END: "end"}
    return [(names.get(c & pe.COMMAND_MASK, "other"), x / 10.0, -y / 10.0) for x, y, c in pattern.stitches]


def _runs(kinds, kind):
    """Number of runs of consecutive records of ``kind``."""
    return sum(1 for i, k in enumerate(kinds) if k == kind and (i == 0 or kinds[i - 1] != kind))


def _leading_stop(plan):
    """The plan's first record is a STOP at the origin: the file leaves it out (the machine waits at its start)."""
    return plan.commands[0] == C.STOP and not np.any(np.rint(plan.xy_mm[0] * 10))


def _expected(plan, fmt, cord_stop="sequence"):
    """Counts the file must hold, by the format's documented conventions, from the plan alone."""
    stops = plan.count(C.STOP) - int(_leading_stop(plan))
    exp = {"stitches": plan.stitch_count, "trims": plan.count(C.TRIM)}
    if fmt in ("dst", "exp"):
        exp.update(stops=stops * (2 if cord_stop == "double" else 1), color_changes=0)
    elif fmt in ("tbf", "u01"):  # a needle set at each stop, and before a placement line sewn before the first
        sewn_first = np.any(plan.commands[:int(np.argmax(plan.commands == C.STOP))] == C.STITCH)
        exp.update(stops=stops, color_changes=plan.count(C.STOP) + int(sewn_first))
    else:  # a colour change wherever a tube is laid after something was sewn (later actuators, placement lines)
        sewn = np.cumsum(plan.commands == C.STITCH)
        changes = int(np.count_nonzero((plan.commands == C.STOP) & (sewn > 0)))
        if fmt == "vp3":  # no jump record: the travel to a placement line sewn after something begins a block
            from embroact.patterns.plan import Role

            line = plan.roles == Role.PLACEMENT
            starts = line & ~np.concatenate([[False], line[:-1]])
            changes += int(np.count_nonzero(starts & (sewn > 1)))
        exp.update(stops=0, color_changes=changes)
    return exp


def _plans():
    from dataclasses import replace

    from embroact.export.files.designfile import load_design
    from embroact.patterns.design import build_plan

    designs = [(os.path.basename(p), load_design(p)) for p in EXAMPLES]
    placed = [(f"{label}+placement", replace(d, machine=replace(d.machine, placement_line=True)))
              for label, d in designs if label in ("three_actuators.toml", "curved.toml")]
    return [(label, build_plan(d)) for label, d in designs + placed] + [("hand-3", hand_plan(3))]


PLANS = _plans()


def test_registry_covers_every_limit_and_writer():
    assert set(FORMATS) == set(FORMAT_LIMITS) == {"dst", "tbf", "pes", "pec", "jef", "exp", "vp3", "xxx", "u01"}
    written = {f["extension"] for f in pe.supported_formats() if f.get("writer") and f["category"] == "embroidery"}
    assert set(FORMATS) <= written


@pytest.mark.parametrize("fmt", ALL)
def test_limits_pinned_to_writer_constants(fmt):
    """patterns/limits.py must say what pystitch's writer does (0.1 mm units per axis)."""
    writer = importlib.import_module(f"pystitch.{FORMATS[fmt].writer}")
    lim = FORMAT_LIMITS[fmt]
    # XXX writes a stitch of 124 units or more per axis as a long move (read as a jump): one unit less
    stitch_units = writer.MAX_STITCH_DISTANCE - (1 if fmt == "xxx" else 0)
    assert round(lim.max_record_mm * 10) == stitch_units
    assert round(lim.max_jump_mm * 10) == writer.MAX_JUMP_DISTANCE


def test_suffix_override_and_unknown_suffix():
    assert machine_format("x.Jef").name == "jef"
    assert machine_format("x.dst", fmt="PES").name == "pes"
    with pytest.raises(ParameterError, match=r"\.dst, \.tbf, \.pes.*got '\.svg'"):
        machine_format("x.svg")
    with pytest.raises(ParameterError, match="format must be one of"):
        machine_format("x.dst", fmt="gcode")


@pytest.mark.parametrize("fmt", ALL)
@pytest.mark.parametrize("label,plan", PLANS, ids=[p[0] for p in PLANS])
def test_reported_is_written(fmt, label, plan):
    """Every reported count and needle point is what the bytes hold, read by a reader embroact did not write."""
    data, res = encode(plan, fmt)
    back = _kinds(_read_back(data, fmt))
    kinds = [k for k, *_ in back]
    # needle points: every one, in order, no extra penetration, within the 0.1 mm grid of the plan
    got = np.array([(x, y) for k, x, y in back if k == "stitch"]) + np.array(res.origin_mm)
    want = np.rint(needle_points(plan) * 10) / 10
    assert got.shape == want.shape
    assert np.abs(got - want).max() < 1e-6
    # counts the plan says the file must hold, and the reader finds there, and embroact reports
    exp = _expected(plan, fmt)
    assert {k: getattr(res, k) for k in exp} == exp
    assert kinds.count("stitch") == res.stitches
    if fmt in STOP_CODE - {"dst"}:
        assert kinds.count("stop") + kinds.count("color") * (fmt == "exp") == res.stops
    if fmt in ("tbf", "u01"):
        assert kinds.count("needle") == res.color_changes
    if fmt in COLOUR:
        assert kinds.count("color") == res.color_changes and kinds.count("stop") == 0
    if fmt != "dst":
        assert _runs(kinds, "trim") == res.trims
    assert kinds[-1] == "end" and kinds.count("end") == 1
    # where the machine pauses: one place per stop run or colour change, after something was done
    assert res.pauses == (plan.count(C.STOP) - int(_leading_stop(plan)) if fmt in STOP_CODE else exp["color_changes"])


@pytest.mark.parametrize("label,plan", PLANS, ids=[p[0] for p in PLANS])
@pytest.mark.parametrize("mode", ["sequence", "double"])
def test_dst_reported_is_what_the_independent_decoder_reads(label, plan, mode):
    data, res = encode(plan, "dst", cord_stop=mode)
    dst = dst_decoder.decode(data)
    ev = dst_decoder.events(dst.records)
    assert sum(e[0] == "stitch" for e in ev) == res.stitches
    assert sum(e[0] == "trim" for e in ev) == res.trims == plan.count(C.TRIM)
    assert sum(e[0] == "stop" for e in ev) == res.stops == int(dst.header["CO"])
    assert sum(e[3] for e in ev if e[0] == "travel") == res.jumps
    # the chosen stop mode is visible in the records: one or two consecutive C3 per cord-in
    kinds = [r.kind for r in dst.records]
    pairs = sum(1 for i in range(1, len(kinds)) if kinds[i] == kinds[i - 1] == "stop")
    assert pairs == (res.pauses if mode == "double" else 0)
    assert res.cord_stop == mode
    assert dst.records[0].kind != "stop"  # never a bare leading stop


def test_stop_at_the_origin_is_not_a_leading_record():
    """A design whose stop point is the origin: no stop record first (readers drop it); lay tube 1 before start."""
    from embroact.patterns.plan import Role as R, StitchPlan

    plan = StitchPlan.from_records([(0, 0, C.STOP, R.CONTROL), (0, 0, C.STITCH, R.TIE_IN), (1, 3, C.STITCH, R.LEG),
                                    (1, 3, C.TRIM, R.CONTROL), (1, 3, C.END, R.CONTROL, -1)])
    data, res = encode(plan, "dst")
    assert [r.kind for r in dst_decoder.decode(data).records][:2] == ["stitch", "stitch"]
    assert res.stops == 0 and res.pauses_mm == ()


NAMES = ("cross 45°", "Ümlaut ø", "A1")


def _named_plan():
    from dataclasses import replace

    plan = hand_plan(3, name="Übung °")
    acts = tuple(replace(a, name=n) for a, n in zip(plan.actuators, NAMES))
    return replace(plan, actuators=acts)


@pytest.mark.parametrize("fmt", ALL)
def test_non_ascii_names_round_trip(fmt):
    """Labels are written byte-exact; formats with a thread table give back the transliterated names."""
    plan = _named_plan()
    data, res = encode(plan, fmt)
    back = _read_back(data, fmt)  # a corrupt thread table fails here (it did for VP3)
    assert sum(1 for *_, c in back.stitches if c & pe.COMMAND_MASK == pe.STITCH) == plan.stitch_count
    if fmt in ("pes", "vp3"):
        assert [t.description for t in back.threadlist] == ["cross 45deg", "Umlaut o", "A1"] == list(res.thread_names)
        assert [t.color & 0xFFFFFF for t in back.threadlist] == list(THREAD_COLORS[:3])
    else:
        assert res.thread_names == () and any("no thread names" in n for n in res.notes)
    if fmt == "dst":
        assert dst_decoder.decode(data).header["LA"] == f"{'Ubung deg':<16}"


def test_ascii_label_by_hand():
    assert ascii_label("Çà et là — 5 µm") == "Ca et la _ 5 um"
    assert ascii_label("x" * 300) == "x" * 255


@pytest.mark.parametrize("fmt", ALL)
def test_deterministic_bytes(fmt):
    plan = hand_plan(3)
    assert encode(plan, fmt)[0] == encode(plan, fmt)[0]


@pytest.mark.parametrize("fmt", ALL)
@pytest.mark.parametrize("label,plan", generated_plans(), ids=lambda v: v if isinstance(v, str) else "")
def test_generated_round_trip(tmp_path, fmt, label, plan):
    """A generated plan holds the machine's points: the file, read by pystitch, holds exactly the plan's needle
    points (no rounding left for the writer), and each is a whole number of the format's unit."""
    path = tmp_path / f"design.{fmt}"
    res = write(plan, path)
    back = pe.read(str(path), dict(RAW))
    got = np.array([(x, -y) for x, y, c in back.stitches if c & pe.COMMAND_MASK == pe.STITCH]) / 10.0
    got = got + np.array(res.origin_mm)
    want = needle_points(plan)
    unit = FORMAT_LIMITS[fmt].unit_mm
    assert got.shape == want.shape and np.abs(got - want).max() < 1e-9
    assert np.abs(plan.xy_mm / unit - np.rint(plan.xy_mm / unit)).max() < 1e-9


def test_every_format_declares_the_plan_grid():
    """The plan is made on one grid; every format written today stores positions in that unit (0.1 mm)."""
    from embroact.patterns.base.tolerances import DEFAULT_TOLERANCES

    assert {f.unit_mm for f in FORMAT_LIMITS.values()} == {DEFAULT_TOLERANCES.machine_grid_mm} == {0.1}


def test_exp_trim_moves_nothing():
    """EXP trims are 80 80 00 00: no reader (nor a Bernina) shifts the design by the old 0.7 mm offset."""
    data, res = encode(hand_plan(3), "exp")
    recs, i = [], 0
    while i < len(data):
        if data[i] == 0x80:
            recs.append(data[i:i + 4])
            i += 4
        else:
            i += 2
    trims = [r for r in recs if r[1] == 0x80]
    assert len(trims) == res.trims == 3 and all(r == b"\x80\x80\x00\x00" for r in trims)


def test_tbf_header_extents():
    """TBF header +X/-X/+Y/-Y are the excursions from the start (machine frame, y up): hand_plan lies below it."""
    plan = hand_plan(3)  # x from 5 to 45 mm, y from 0.5 down to -46.5 mm
    data, _ = encode(plan, "tbf")
    head = data[:0x376].decode("ascii", "replace")
    fields = {k: int(head.split(k + ":")[1][:5]) for k in ("+X", "-X", "+Y", "-Y")}
    assert fields == {"+X": 450, "-X": 0, "+Y": 5, "-Y": 465}


@pytest.mark.parametrize("fmt", ["exp", "jef", "u01", "tbf", "xxx"])
def test_long_leg_limit_per_format(fmt):
    """A leg just over the format's limit is refused, one just under is written."""
    from embroact.export.machine.encode import LongLegError
    from embroact.patterns.plan import Role as R, StitchPlan

    lim = FORMAT_LIMITS[fmt].max_record_mm

    def plan(d):
        return StitchPlan.from_records([(0, 0, C.STITCH, R.LEG), (d, 0, C.STITCH, R.LEG), (d, 0, C.END, R.CONTROL, -1)])

    encode(plan(lim), fmt)
    with pytest.raises(LongLegError, match=f"{fmt} allows {lim:g} mm"):
        encode(plan(lim + 0.1), fmt)


def test_record_limit_is_an_export_error():
    from dataclasses import replace

    from embroact.patterns.base.errors import ExportError

    small = replace(FORMATS["dst"], limit=replace(FORMATS["dst"].limit, max_records=40))
    with pytest.raises(ExportError, match=r"design needs \d+ records; dst holds at most 40"):
        encode(hand_plan(1), small)


def test_bad_cord_stop_is_named():
    with pytest.raises(ParameterError, match=r"cord_stop must be one of 'sequence', 'double', got 'twice'"):
        encode(hand_plan(1), "dst", cord_stop="twice")
