"""Every machine format: read back with pyembroidery's readers and compared with the plan."""
import numpy as np
import pytest

from h3_plans import generated_plans, hand_plan, needle_points
from embroact.export.machine.formats import FORMATS, encode, machine_format, write
from embroact.export.machine.encode import THREAD_COLORS
from embroact.patterns.base.errors import ParameterError
from embroact.patterns.limits import FORMAT_LIMITS
from embroact.patterns.plan import Command as C

pe = pytest.importorskip("pyembroidery")
GRID_HALF_MM = 0.05 + 1e-9
ALL = sorted(FORMATS)


def _read(tmp_path, plan, fmt):
    path = tmp_path / f"design.{fmt}"
    write(plan, path)
    return pe.read(str(path))


def _dedup(a):
    """Drop consecutive repeats (PEC writes a zero-length stitch after a jump)."""
    keep = np.ones(len(a), bool)
    keep[1:] = np.any(np.diff(a, axis=0) != 0, axis=1)
    return a[keep]


def _count(pattern, command):
    return sum(1 for s in pattern.stitches if s[2] & pe.COMMAND_MASK == command)


def test_registry_covers_every_limit_and_writer():
    assert set(FORMATS) == set(FORMAT_LIMITS) == {"dst", "tbf", "pes", "pec", "jef", "exp", "vp3", "xxx", "u01"}
    written = {f["extension"] for f in pe.supported_formats() if f.get("writer") and f["category"] == "embroidery"}
    assert set(FORMATS) <= written


def test_suffix_override_and_unknown_suffix():
    assert machine_format("x.Jef").name == "jef"
    assert machine_format("x.dst", fmt="PES").name == "pes"
    with pytest.raises(ParameterError, match=r"\.dst, \.tbf, \.pes.*got '\.svg'"):
        machine_format("x.svg")
    with pytest.raises(ParameterError, match="format must be one of"):
        machine_format("x.dst", fmt="gcode")


@pytest.mark.parametrize("fmt", ALL)
@pytest.mark.parametrize("n", [1, 3])
def test_round_trip_needle_points(tmp_path, fmt, n):
    plan = hand_plan(n)
    back = _read(tmp_path, plan, fmt)
    got = np.array([(x, -y) for x, y, c in back.stitches if c & pe.COMMAND_MASK == pe.STITCH]) / 10.0
    want = needle_points(plan)
    got, want = _dedup(got), _dedup(want)
    assert got.shape == want.shape
    assert np.abs(got - want).max() <= GRID_HALF_MM


@pytest.mark.parametrize("fmt", ALL)
def test_round_trip_commands(tmp_path, fmt):
    plan = hand_plan(3)
    back = _read(tmp_path, plan, fmt)
    stops, trims = plan.count(C.STOP), plan.count(C.TRIM)
    style = FORMATS[fmt].stop_style
    if style == "stop":  # DST, EXP: every stop is the shared stop/colour-change code
        assert _count(back, pe.COLOR_CHANGE) == stops
        assert _count(back, pe.TRIM) == trims
    elif style == "needle_stop":  # TBF, U01: separate stop, needle set per actuator
        assert _count(back, pe.STOP) == stops and _count(back, pe.NEEDLE_SET) == stops
        assert _count(back, pe.TRIM) == trims
    else:  # colour-table formats: one colour (thread) per actuator
        assert _count(back, pe.COLOR_CHANGE) == stops - 1
        assert len(back.threadlist) == len(plan.actuators)
        # every actuator but the last is trimmed before the next colour
        assert _count(back, pe.TRIM) >= trims - 1
    assert _count(back, pe.END) == 1


@pytest.mark.parametrize("fmt", ["pes", "vp3"])
def test_thread_table_names_each_actuator(tmp_path, fmt):
    back = _read(tmp_path, hand_plan(3), fmt)
    assert [t.description for t in back.threadlist] == ["A1", "A2", "A3"]
    assert [t.color & 0xFFFFFF for t in back.threadlist] == list(THREAD_COLORS[:3])


@pytest.mark.parametrize("fmt", ALL)
def test_deterministic_bytes(fmt):
    plan = hand_plan(3)
    assert encode(plan, fmt)[0] == encode(plan, fmt)[0]


@pytest.mark.parametrize("fmt", ["pes", "vp3", "jef", "tbf"])
@pytest.mark.parametrize("label,plan", generated_plans(), ids=lambda v: v if isinstance(v, str) else "")
def test_generated_round_trip(tmp_path, fmt, label, plan):
    back = _read(tmp_path, plan, fmt)
    got = np.array([(x, -y) for x, y, c in back.stitches if c & pe.COMMAND_MASK == pe.STITCH]) / 10.0
    got, want = _dedup(got), _dedup(needle_points(plan))
    assert got.shape == want.shape and np.abs(got - want).max() <= GRID_HALF_MM


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
