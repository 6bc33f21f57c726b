"""What a machine file holds, counted from its bytes: the numbers embroact reports for it.

Every count and position that a summary line, ``--json``, the worksheet or the report
gives for a machine file comes from here, read back from the encoded bytes, so what is
reported is what the file holds.  DST is decoded by :func:`embroact.export.machine.dst.decode_moves`;
every other format by pystitch's reader for it, with no trims inserted and nothing
clipped (the file's own records, in order).

How records are counted
-----------------------
The same words mean different records in different formats; docs/machine.md section 5
tabulates them per format.  In short:

stitches
    Needle records (penetrations).
jumps
    Frame-move records without the needle that are not part of a trim: DST's travel
    jumps after a trim's 3; every jump record of EXP, JEF, TBF, U01 and XXX; the jump
    records of PEC/PES without the trim flag.  Not counted: the move that begins a VP3
    colour block (the block's start position, a header field, not a record) and the
    lead-in of a PEC stitch block (pystitch writes a move from the design's corner to the
    start point there and its reader skips it).
trims
    Thread cuts: a DST run of 3 jumps netting to zero; a run of trim records (JEF writes a
    trim as 3 zero-length jumps, read as 3 trims: one cut); a PEC/PES trim-flagged jump (one
    record that cuts and moves, so it is not also counted as a jump); the trim codes of EXP,
    TBF, U01, VP3 and XXX.
stops
    Stop records (DST/EXP: the shared stop / colour-change code; TBF/U01: their own stop
    code); two in a row (``cord_stop = "double"``) count as two records but one pause.
color_changes
    Colour changes of colour formats (PES, PEC, JEF, VP3, XXX: for VP3 each colour block
    after the first) and needle-set records of TBF/U01.
pauses_mm
    Where the machine waits for the operator, in order: each run of stop records
    (stop-code formats) or each colour change (colour formats; VP3: the new block's start,
    where its first stitch is), in the file frame (mm, y up, origin at the file's start point).
pause_stops
    Stop records at each pause (2: a double stop, ``cord_stop = "double"``; 0: a colour change).
trims_mm
    Where each trim cuts the thread, in order, in the same frame.

Examples
--------
>>> body = bytes([0x01, 0x00, 0x03, 0x00, 0x00, 0xC3, 0x00, 0x00, 0xC3, 0x02, 0x00, 0x03, 0x00, 0x00, 0xF3])
>>> c = census(bytes(512) + body, "dst")
>>> c.stitches, c.stops, c.pauses_mm, c.pause_stops, c.needle_points_mm.tolist()
(2, 2, ((0.1, 0.0),), (2,), [[0.1, 0.0], [0.0, 0.0]])
"""
from __future__ import annotations

import io
from dataclasses import dataclass

import numpy as np

from ...patterns.base.arrays import frozen_array
from .dst import COLOR_BYTE, END_BYTE, HEADER_SIZE, decode_moves

__all__ = ["Census", "census", "raw_reader", "RAW_READ", "STOP_CODE_FORMATS", "COLOR_FORMATS", "NAMED_FORMATS",
           "TRIM_FLAG_FORMATS", "BLOCK_START_FORMATS"]

#: Formats with a stop record (DST and EXP share it with the colour change; TBF and U01 have their own).
STOP_CODE_FORMATS = frozenset({"dst", "exp", "tbf", "u01"})
#: Formats without a stop code: the machine pauses at each colour change.
COLOR_FORMATS = frozenset({"pes", "pec", "jef", "vp3", "xxx"})
#: Formats whose files carry thread names (the actuator names).
NAMED_FORMATS = frozenset({"pes", "vp3"})
#: Formats whose trim is a flag on a jump record (the reader gives a trim, then the same record's move).
TRIM_FLAG_FORMATS = frozenset({"pes", "pec"})
#: Formats without jump records: a colour block starts at a position its header gives (the reader's move).
BLOCK_START_FORMATS = frozenset({"vp3"})
_JUMP_BIT = 0x80
#: Reader settings that keep the file's own records (no trims made from jump runs, nothing clipped).
RAW_READ = {"trim_at": None, "trim_distance": None, "clipping": False}


@dataclass(frozen=True, slots=True, eq=False)
class Census:
    """The records of one machine file (see the module docstring for how each is counted).

    Attributes
    ----------
    format : str
        The format's suffix.
    stitches, jumps, trims, stops, color_changes : int
        Record counts.
    needle_points_mm : ndarray (n, 2)
        Needle points in order [mm], file frame (y up, origin at the start point); read-only.
    pauses_mm : tuple of (float, float)
        Where the machine waits for the operator, in order [mm], file frame.
    thread_names : tuple of str
        Thread names the file carries (empty for formats without names).
    pause_stops : tuple of int
        Stop records at each pause (2: a double stop; 0: a colour change).
    trims_mm : tuple of (float, float)
        Where each trim cuts [mm], file frame.

    Examples
    --------
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> from embroact.export.machine.formats import encode
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (1, 1, Command.STITCH, Role.LEG),
    ...                                 (1, 1, Command.END, Role.CONTROL, -1)])
    >>> data, _ = encode(plan, "dst")
    >>> c = census(data, "dst")
    >>> c.stitches, c.jumps, c.needle_points_mm.tolist()
    (2, 0, [[0.0, 0.0], [1.0, 1.0]])
    """

    format: str
    stitches: int
    jumps: int
    trims: int
    stops: int
    color_changes: int
    needle_points_mm: np.ndarray
    pauses_mm: tuple[tuple[float, float], ...]
    thread_names: tuple[str, ...]
    pause_stops: tuple[int, ...] = ()
    trims_mm: tuple[tuple[float, float], ...] = ()


def _point(x: int, y: int) -> tuple[float, float]:
    return (round(x / 10.0, 1) + 0.0, round(y / 10.0, 1) + 0.0)


def _dst(data: bytes) -> Census:
    x = y = 0
    pts, pauses, pause_stops, cuts = [], [], [], []
    stitches = jumps = stops = 0
    run: list[tuple[int, int]] = []  # the jump run being read

    def close_run() -> None:
        nonlocal jumps
        if len(run) >= 3 and sum(d[0] for d in run[:3]) == 0 and sum(d[1] for d in run[:3]) == 0:
            cuts.append(_point(x - sum(d[0] for d in run), y - sum(d[1] for d in run)))  # where the run began
            jumps += len(run) - 3
        else:
            jumps += len(run)
        run.clear()

    previous = None
    for dx, dy, b3 in decode_moves(data[HEADER_SIZE:]):
        kind = "end" if b3 == END_BYTE else "stop" if b3 == COLOR_BYTE else "jump" if b3 & _JUMP_BIT else "stitch"
        if kind != "jump":
            close_run()
        x, y = x + dx, y + dy
        if kind == "jump":
            run.append((dx, dy))
        elif kind == "stitch":
            stitches += 1
            pts.append(_point(x, y))
        elif kind == "stop":
            stops += 1
            if previous != "stop":
                pauses.append(_point(x, y))
                pause_stops.append(0)
            pause_stops[-1] += 1
        previous = kind
    close_run()
    return Census("dst", stitches, jumps, len(cuts), stops, 0, _array(pts), tuple(pauses), (), tuple(pause_stops),
                  tuple(cuts))


def _array(pts) -> np.ndarray:
    return frozen_array(np.array(pts, dtype=np.float64).reshape(-1, 2))


def raw_reader(fmt: str):
    """pystitch's reader module for format ``fmt`` (read it with :data:`RAW_READ`).

    Parameters
    ----------
    fmt : str
        A format's suffix.

    Returns
    -------
    module

    Examples
    --------
    >>> raw_reader("pes").__name__
    'pystitch.PesReader'
    """
    import pystitch

    return next(f["reader"] for f in pystitch.supported_formats() if f["extension"] == fmt)


def _read(data: bytes, fmt: str):
    import pystitch as pe

    return pe, pe.EmbPattern.read_embroidery(raw_reader(fmt), io.BytesIO(data), dict(RAW_READ))


def _block_start(records, n: int, pe) -> tuple[float, float]:
    """Where the colour block begun by the colour change ``records[n]`` starts (the move after it)."""
    for x, y, c in records[n + 1:]:
        if c & pe.COMMAND_MASK != pe.COLOR_CHANGE:
            return _point(int(round(x)), -int(round(y)))
    x, y, _ = records[n]
    return _point(int(round(x)), -int(round(y)))


def census(data: bytes, fmt: str) -> Census:
    """Count the records of ``data``, a file of format ``fmt`` (see the module docstring).

    Parameters
    ----------
    data : bytes
        The file's bytes.
    fmt : str
        Its format's suffix.

    Returns
    -------
    Census

    Examples
    --------
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> from embroact.export.machine.formats import encode
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (1, 1, Command.STITCH, Role.LEG),
    ...                                 (1, 1, Command.END, Role.CONTROL, -1)])
    >>> data, _ = encode(plan, "dst")
    >>> pes, _ = encode(plan, "pes")
    >>> census(data, "dst").stitches, census(pes, "pes").stitches
    (2, 2)
    """
    if fmt == "dst":
        return _dst(data)
    pe, pattern = _read(data, fmt)
    pts, pauses, pause_stops, cuts = [], [], [], []
    stitches = jumps = stops = colors = 0
    previous = None
    records = pattern.stitches
    for n, (x, y, c) in enumerate(records):
        cmd = c & pe.COMMAND_MASK
        here = _point(int(round(x)), -int(round(y)))
        if cmd == pe.STITCH:
            stitches += 1
            pts.append(here)
        elif cmd == pe.JUMP:
            if not (previous == pe.TRIM and fmt in TRIM_FLAG_FORMATS) and not (
                    previous == pe.COLOR_CHANGE and fmt in BLOCK_START_FORMATS):
                jumps += 1  # else the trim-flagged jump's own move, or a colour block's start
        elif cmd == pe.TRIM:
            if previous != pe.TRIM:
                cuts.append(here)
        elif cmd == pe.STOP or (cmd == pe.COLOR_CHANGE and fmt in STOP_CODE_FORMATS):
            stops += 1
            if previous not in (pe.STOP, pe.COLOR_CHANGE):
                pauses.append(here)
                pause_stops.append(0)
            pause_stops[-1] += 1
        elif cmd in (pe.COLOR_CHANGE, pe.NEEDLE_SET):
            colors += 1
            if fmt in COLOR_FORMATS:
                pauses.append(_block_start(records, n, pe) if fmt in BLOCK_START_FORMATS else here)
                pause_stops.append(0)
        previous = cmd
    names = tuple(t.description or "" for t in pattern.threadlist) if fmt in NAMED_FORMATS else ()
    return Census(fmt, stitches, jumps, len(cuts), stops, colors, _array(pts), tuple(pauses), names,
                  tuple(pause_stops), tuple(cuts))
