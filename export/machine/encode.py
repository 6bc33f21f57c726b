"""Stitch plan -> machine records: frame, cord stops, trims, threads, long legs.

The plan frame is millimetres with y up; pystitch works in 0.1 mm units with
y down.  Every position is rounded to the 0.1 mm grid once, in absolute terms, so
rounding never accumulates along the design.  The plan origin is the machine's
start point (the first record moves from there); VP3, which has no frame move
before its first stitch, is written with its origin 1 mm beside the first needle
point (home machines place a design by its centre, so nothing is lost).

How plan records become machine records
---------------------------------------
========  ==================================================================
plan      machine
========  ==================================================================
STITCH    one needle record.  A leg longer than the format's per-record limit
          (per axis) is refused with :class:`LongLegError`; with
          ``split_long=True`` it becomes several needle records whose extra
          needle points all lie *outside* the tube corridor.  The design's
          first needle point is reached by a frame move, never a stitch.
JUMP      a run of plan JUMPs is one travel to the run's end, split into
          records of at most the format's jump limit.  Machines read a run of
          3 or more jump records as a trim; travel only follows a TRIM (or
          precedes the first stitch), where a trim is wanted anyway.  A
          longer travel anywhere else is refused.
STOP      cord in, by the format's ``stop_style``:

          * ``"stop"`` (DST, EXP): the frame moves to the record's point, then
            one stop record (two with ``cord_stop="double"``, see
            :mod:`embroact.patterns.stops`).  A stop before anything else is
            left out: the machine waits at its start anyway, and readers drop a
            leading stop record.
          * ``"color"`` (PES, PEC, JEF, VP3, XXX): no stop code.  The first
            actuator is laid before start; every later one gets its own colour
            (thread) and the colour change makes the machine pause.  With a
            placement line (:mod:`embroact.patterns.placement`) the first
            actuator's line is a colour block of its own (thread
            ``"<name> placement"``), so the machine pauses for tube 1 too.  JEF, VP3
            and XXX change colour at the actuator's first needle point, after the
            travel (VP3 starts a colour block there: it has no jump record, so
            every other travel, such as the one to a later placement line, begins
            a colour block of its own, thread ``"<name> placement"``); PEC/PES change colour where
            the last actuator ended, before the travel, because their writer adds
            a needle penetration to a colour change that follows a jump.
          * ``"needle_stop"`` (TBF, U01): a needle-set record selecting the
            actuator's thread (always needle 1) and the format's own stop record;
            with a placement line, a needle-set record before its first needle
            point too, so no stitch is sewn before a needle is chosen.
TRIM      one trim (DST: a run of 3 jumps netting to zero; JEF: 3 zero-length
          jumps; PEC/PES have no trim code: the trim flag of the next jump, a
          zero-length one after the last actuator; VP3's end code trims, so the
          last TRIM is that code).
END       one end record.
========  ==================================================================

The thread list holds one thread per actuator, its description the actuator name as
:func:`ascii_label` writes it.  Which of these records a file really holds is read back
from its bytes by :mod:`embroact.export.machine.census`.

Examples
--------
>>> from embroact.patterns.plan import Command, Role, StitchPlan
>>> from embroact.export.machine.formats import machine_format
>>> plan = StitchPlan.from_records([
...     (0.0, 3.5, Command.STOP, Role.CONTROL), (0.0, 3.5, Command.STITCH, Role.TIE_IN),
...     (1.0, -3.5, Command.STITCH, Role.LEG), (1.0, -3.5, Command.TRIM, Role.CONTROL),
...     (1.0, -3.5, Command.END, Role.CONTROL, -1)])
>>> mp = to_pattern(plan, machine_format("act.dst"), cord_stop="double")
>>> import pystitch as pe
>>> names = {pe.JUMP: "jump", pe.STOP: "stop", pe.STITCH: "stitch", pe.TRIM: "trim", pe.END: "end"}
>>> [(names[c], x, y) for x, y, c in mp.pattern.stitches]  # 0.1 mm, y down
[('jump', 0, -35), ('stop', 0, -35), ('stop', 0, -35), ('stitch', 0, -35), ('stitch', 10, 35), ('trim', 10, 35), ('end', 10, 35)]
>>> mp.split_legs
0
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ...patterns.base.errors import ExportError, PatternError
from ...patterns import limits
from ...patterns.limits import framed_first, record_moves_units, records_needed
from ...patterns.plan import Command, StitchPlan
from ...patterns.base.tolerances import DEFAULT_TOLERANCES
from ...patterns.stops import CordStop, cord_stop as check_cord_stop

if TYPE_CHECKING:  # pragma: no cover
    from .formats import MachineFormat

__all__ = [
    "UNITS_PER_MM",
    "TRIM_JUMP_RUN",
    "THREAD_COLORS",
    "PLACEMENT_LABEL",
    "LongLeg",
    "LongLegError",
    "MachinePattern",
    "to_machine_units",
    "find_long_legs",
    "ascii_label",
    "to_pattern",
]

UNITS_PER_MM = limits.UNITS_PER_MM
"""Machine-file units per millimetre (0.1 mm grid)."""

TRIM_JUMP_RUN = limits.TRIM_JUMP_RUN
"""Consecutive jump records a machine (and the DST writer) treat as a trim."""

PLACEMENT_LABEL = " placement"
"""Ending of a thread label whose colour block is a placement line (``"<name> placement"``)."""

THREAD_COLORS = (0x1F77B4, 0xD62728, 0x2CA02C, 0xFF7F0E, 0x9467BD, 0x8C564B, 0xE377C2, 0x17BECF)
"""Thread colours cycled over the actuators (distinct on screen, same thread on the machine)."""


@dataclass(frozen=True, slots=True)
class LongLeg:
    """A stitch longer than a format allows in one record.

    Attributes
    ----------
    actuator : str
        Actuator name.
    stitch_index : int
        Index of the stitch among its actuator's STITCH records (0 = first).
    record_index : int
        Index of the record in the plan.
    length_mm, dx_mm, dy_mm : float
        Leg length and its per-axis components on the 0.1 mm grid [mm].
    limit_mm : float
        The format's per-axis limit [mm].

    Examples
    --------
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (13, 0, Command.STITCH, Role.LEG)])
    >>> leg, = find_long_legs(plan, 12.1)
    >>> leg.actuator, leg.record_index, leg.dx_mm, leg.limit_mm
    ('A1', 1, 13.0, 12.1)
    """

    actuator: str
    stitch_index: int
    record_index: int
    length_mm: float
    dx_mm: float
    dy_mm: float
    limit_mm: float

    def describe(self, fmt: str) -> str:
        """One line naming the leg, its size and the limit.

        Parameters
        ----------
        fmt : str
            The format's name, for the line.

        Returns
        -------
        str

        Examples
        --------
        >>> from embroact.patterns.plan import Command, Role, StitchPlan
        >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (13, 0, Command.STITCH, Role.LEG)])
        >>> leg, = find_long_legs(plan, 12.1)
        >>> print(leg.describe("dst"))
        leg at stitch index 1 of actuator 'A1' (plan record 1) is 13.0 mm long (|dx| 13.0 mm, |dy| 0.0 mm); dst allows 12.1 mm per axis in one record
        """
        return (
            f"leg at stitch index {self.stitch_index} of actuator {self.actuator!r} (plan record {self.record_index}) is "
            f"{self.length_mm:.1f} mm long (|dx| {abs(self.dx_mm):.1f} mm, |dy| {abs(self.dy_mm):.1f} mm); "
            f"{fmt} allows {self.limit_mm:g} mm per axis in one record"
        )


class LongLegError(PatternError):
    """Legs exceed the format's per-record limit; ``legs`` lists them all."""

    def __init__(self, legs: tuple[LongLeg, ...], fmt: str) -> None:
        more = f" (and {len(legs) - 1} more)" if len(legs) > 1 else ""
        super().__init__(
            f"{legs[0].describe(fmt)}{more}; narrow the pattern or pass split_long=True (--split-long) "
            "to split long legs into stitches outside the tube corridor"
        )
        self.legs = legs


@dataclass(frozen=True, slots=True)
class MachinePattern:
    """A plan converted for one format, ready for a pystitch writer.

    Attributes
    ----------
    pattern : pystitch.EmbPattern
        Low-level records (0.1 mm, y down); write with ``encode=False``.
    format : str
        The format's name.
    split_legs : int
        Legs split into several stitches (only with ``split_long=True``).
    origin_mm : tuple of float
        Plan position of the file's origin [mm, y up]: (0, 0) except for formats
        written from their first needle point (VP3).
    lead_block : bool
        Colour formats: the first actuator's placement line is a colour block of its own
        (the machine pauses for tube 1 too).

    Examples
    --------
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> from embroact.export.machine.formats import machine_format
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (1, 1, Command.STITCH, Role.LEG),
    ...                                 (1, 1, Command.END, Role.CONTROL, -1)])
    >>> mp = to_pattern(plan, machine_format("a.dst"))
    >>> mp.format, mp.split_legs, mp.lead_block, len(mp.pattern.stitches)
    ('dst', 0, False, 3)
    """

    pattern: Any
    format: str
    split_legs: int
    origin_mm: tuple[float, float] = (0.0, 0.0)
    lead_block: bool = False


def to_machine_units(xy_mm: np.ndarray) -> np.ndarray:
    """Plan positions [mm, y up] -> integer machine-file units (0.1 mm, y down).

    Parameters
    ----------
    xy_mm : numpy.ndarray (n, 2)
        Plan positions [mm].

    Returns
    -------
    numpy.ndarray of int64 (n, 2)

    Examples
    --------
    >>> to_machine_units(np.array([[1.0, 2.0], [-0.04, -0.06]])).tolist()
    [[10, -20], [0, 1]]
    """
    xy = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
    u = np.rint(xy * UNITS_PER_MM).astype(np.int64)
    u[:, 1] = -u[:, 1]
    u[u == 0] = 0  # no negative zeros
    return u


def _actuator_name(plan: StitchPlan, index: int) -> str:
    return plan.actuators[index].name if 0 <= index < len(plan.actuators) else f"A{index + 1}"


def find_long_legs(plan: StitchPlan, limit_mm: float) -> tuple[LongLeg, ...]:
    """Needle records whose move from the previous record exceeds ``limit_mm`` per axis.

    The check runs on the 0.1 mm grid, as the machine sees it.

    Parameters
    ----------
    plan : StitchPlan
        The records.
    limit_mm : float
        The format's per-axis limit [mm].

    Returns
    -------
    tuple of LongLeg

    Examples
    --------
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (13, 0, Command.STITCH, Role.LEG)])
    >>> leg, = find_long_legs(plan, 12.1)
    >>> leg.stitch_index, leg.length_mm
    (1, 13.0)
    """
    d = record_moves_units(plan.xy_mm)  # plan frame (y up), as the design rule EA102 judges it
    stitch = plan.commands == Command.STITCH
    bad = np.flatnonzero(stitch & ~framed_first(plan.commands) & (records_needed(d, limit_mm) > 1))
    legs = []
    for i in bad:
        k = int(plan.actuator[i])
        same = (plan.actuator[:i] == k) & stitch[:i]
        dx, dy = d[i, 0] / UNITS_PER_MM, d[i, 1] / UNITS_PER_MM
        legs.append(LongLeg(_actuator_name(plan, k), int(np.count_nonzero(same)), int(i),
                            float(math.hypot(dx, dy)), float(dx), float(dy), float(limit_mm)))
    return tuple(legs)


def _steps(p0: np.ndarray, p1: np.ndarray, lim: int) -> list[np.ndarray]:
    """Integer points after ``p0`` up to ``p1`` with no per-axis step above ``lim``."""
    d = p1 - p0
    n = max(1, math.ceil(int(np.abs(d).max()) / lim))
    return [p0 + np.rint(d * (k / n)).astype(np.int64) for k in range(1, n + 1)]


#: Growth of the tube corridor when placing split points [mm]: covers the rounding of the leg ends and
#: of the split point to the machine grid (found by the H8 round-trip property: 0.011 mm inside before).
_SPLIT_MARGIN_MM = 2.0 * DEFAULT_TOLERANCES.machine_grid_mm


def _forbidden_t(plan: StitchPlan, index: int, a_mm: np.ndarray, b_mm: np.ndarray) -> list[tuple[float, float]]:
    """Parameter ranges of segment a->b inside actuator ``index``'s corridor, grown by the rounding margin.

    A split point is taken on the segment between the *rounded* leg ends and then rounded itself:
    each rounding moves it by up to half a grid step per axis (sqrt(2)/2 grid), so the corridor
    is grown by :data:`_SPLIT_MARGIN_MM` = 2 grid steps (> sqrt(2) grid).
    """
    if not 0 <= index < len(plan.actuators):
        return []
    from shapely.geometry import LineString

    seg = LineString([a_mm, b_mm])
    inside = seg.intersection(plan.actuators[index].corridor().buffer(_SPLIT_MARGIN_MM))
    parts = getattr(inside, "geoms", [inside])
    out = []
    for g in parts:
        if g.is_empty or g.length == 0.0:
            continue
        ts = [seg.project(pt, normalized=True) for pt in g.boundary.geoms]
        out.append((min(ts), max(ts)))
    return sorted(out)


def _split_leg(p0: np.ndarray, p1: np.ndarray, lim: int, forbidden: list[tuple[float, float]]) -> list[np.ndarray]:
    """Needle points from p0 (excluded) to p1 (included), steps <= lim, extra points outside ``forbidden``."""
    even = _steps(p0, p1, lim)
    n = len(even)
    if not any(a < k / n < b for k in range(1, n) for a, b in forbidden):
        return even
    d = (p1 - p0).astype(np.float64)
    # half a unit below the limit: rounding the new point moves it by at most half a unit more
    dt = (lim - 0.5) / float(np.abs(d).max())
    pts, t, prev = [], 0.0, p0
    while int(np.abs(p1 - prev).max()) > lim:
        t_next = t + dt
        for a, b in forbidden:
            if a < t_next < b:
                t_next = a
        if t_next <= t:
            raise PatternError(
                f"a leg cannot be split: its crossing of the tube corridor is longer than {lim / UNITS_PER_MM:g} mm per axis"
            )
        prev = p0 + np.rint(d * t_next).astype(np.int64)
        pts.append(prev)
        t = t_next
    return pts + [p1]


def _next_stitch(plan: StitchPlan, i: int) -> int:
    """Index of the first STITCH record after ``i`` (``i`` itself if there is none)."""
    after = np.flatnonzero(plan.commands[i:] == Command.STITCH)
    return i + int(after[0]) if len(after) else i


#: Characters NFKD does not reduce to ASCII, spelled out (everything else unknown becomes "_").
_SPELLED = {
    "°": "deg", "ø": "o", "Ø": "O", "ß": "ss", "æ": "ae", "Æ": "AE", "œ": "oe", "Œ": "OE",
    "ł": "l", "Ł": "L", "đ": "d", "Đ": "D", "þ": "th", "Þ": "Th", "µ": "u", "×": "x",
}
#: Longest label any format's length byte holds.
MAX_LABEL_CHARS = 255


def ascii_label(text: str, *, max_chars: int = MAX_LABEL_CHARS) -> str:
    """The label written into machine files: printable ASCII, one byte per character.

    Formats count label lengths in bytes (PES, VP3) or hold fixed ASCII fields (DST, TBF),
    so every name is transliterated once, the same way for every format: accents are
    dropped (Unicode NFKD, combining marks removed), a few letters and signs are spelled
    out (``°`` -> ``deg``, ``ø`` -> ``o``, ``ß`` -> ``ss``, ...), anything else outside
    printable ASCII becomes ``_``.

    Parameters
    ----------
    text : str
        A design or actuator name.
    max_chars : int, optional
        Longest label [characters].

    Returns
    -------
    str

    Examples
    --------
    >>> ascii_label("cross 45°"), ascii_label("Ümlaut ø"), ascii_label("tube\\tA")
    ('cross 45deg', 'Umlaut o', 'tube_A')
    """
    import unicodedata

    out = []
    for ch in str(text):
        if ch in _SPELLED:
            out.append(_SPELLED[ch])
            continue
        base = "".join(c for c in unicodedata.normalize("NFKD", ch) if not unicodedata.combining(c))
        out.append(base if base and all(32 <= ord(c) < 127 for c in base) else "_")
    return "".join(out)[:max_chars]


#: Offsets [0.1 mm] tried for the first needle point from a file origin set near it (VP3).
_ORIGIN_OFFSETS = ((10, 10), (13, 17), (17, 13), (19, 23), (23, 19), (29, 31))


def _file_origin(plan: StitchPlan, units: np.ndarray) -> np.ndarray:
    """Origin for a format that cannot move the frame before its first stitch (VP3).

    The first needle point then lies 1 mm (or a little more) from the origin per axis: the
    first record is a short stitch, not a long move that readers take for a trim.  Readers
    skip a colour block's start move when one of its coordinates is zero, so the offset is
    the first one leaving every later actuator's first needle point off both axes.
    """
    stitch = np.flatnonzero(plan.commands == Command.STITCH)
    if not len(stitch):
        return np.zeros(2, dtype=np.int64)
    # a colour block starts at the first needle point after each stop or travel that follows sewing
    stops = [int(i) for i in np.flatnonzero(np.isin(plan.commands, (Command.STOP, Command.JUMP))) if i > stitch[0]]
    starts = units[stops + [_next_stitch(plan, i) for i in stops]].reshape(-1, 2)
    for off in _ORIGIN_OFFSETS:
        origin = units[stitch[0]] - np.array(off) * np.array([1, -1])
        if not np.any(starts - origin == 0):
            return origin
    return origin


class _Builder:
    """Accumulates low-level records in the format's own conventions."""

    def __init__(self, fmt: "MachineFormat") -> None:
        import pystitch

        self.pe = pystitch
        self.fmt = fmt
        self.pattern = pystitch.EmbPattern()
        self.pos = np.zeros(2, dtype=np.int64)
        self.jump_ok = True  # at the start or after a trim: a long jump run is harmless
        self.stitched = False  # a needle record has been written
        self.jump_run = 0  # consecutive jump records just written
        self.waited = False  # a cord-in stop was handled: the first stitch starts where the machine waited
        self.selected = False  # needle-stop formats: a needle-set record was written
        self.max_jump = round(fmt.limit.max_jump_mm * UNITS_PER_MM)
        self.blocks: list[str] = []  # colour formats: the label of each colour block begun by a colour change

    def change_colour(self, label: str) -> None:
        """A colour change at the current position, beginning a block for ``label``."""
        self.add(self.pe.COLOR_CHANGE)
        self.blocks.append(label)

    def add(self, cmd: int, p: np.ndarray | None = None) -> None:
        p = self.pos if p is None else p
        self.pattern.stitches.append([int(p[0]), int(p[1]), cmd])
        self.pos = np.array(p, dtype=np.int64)
        self.jump_run = self.jump_run + 1 if cmd == self.pe.JUMP else 0

    def travel(self, target: np.ndarray, record: int) -> None:
        if np.array_equal(target, self.pos):
            return
        for p in _steps(self.pos, target, self.max_jump):
            self.add(self.pe.JUMP, p)
        if self.jump_run >= TRIM_JUMP_RUN and not self.jump_ok:
            raise PatternError(
                f"travel up to plan record {record} needs {self.jump_run} jump records in a row without a trim "
                f"before them; machines read {TRIM_JUMP_RUN} or more jumps as a trim: add a TRIM before the travel"
            )

    def select(self, thread: int) -> None:
        """A needle-set record choosing ``thread`` (always needle 1)."""
        self.add(self.pe.encode_thread_change(self.pe.NEEDLE_SET, thread, 1))
        self.selected = True

    def stop(self, thread: int, cord: CordStop) -> None:
        """A cord-in stop at the current position in the format's stop style."""
        pe, style = self.pe, self.fmt.stop_style
        if style == "needle_stop":
            self.select(thread)
        if not self.pattern.stitches or (style == "needle_stop" and len(self.pattern.stitches) == 1):
            return  # nothing before it: the machine waits at the start anyway (a leading stop is dropped by readers)
        for _ in range(cord.records_per_stop if style == "stop" else 1):
            self.add(pe.STOP)


def to_pattern(plan: StitchPlan, fmt: "MachineFormat", *, split_long: bool = False,
               cord_stop: CordStop | str = CordStop.SEQUENCE) -> MachinePattern:
    """Convert ``plan`` to low-level pystitch records for ``fmt`` (see the module docstring).

    Parameters
    ----------
    plan : StitchPlan
        The records.
    fmt : MachineFormat
        From :func:`embroact.export.machine.formats.machine_format`.
    split_long : bool
        Split legs above the per-record limit into stitches outside the tube
        corridor instead of refusing them.
    cord_stop : CordStop or str
        How a stop-code format (DST, EXP) writes a cord-in stop.

    Returns
    -------
    MachinePattern

    Raises
    ------
    LongLegError
        A leg exceeds the limit and ``split_long`` is false.
    PatternError
        A leg cannot be split, or a travel would read as an unintended trim.
    ExportError
        More records than the format holds.

    Examples
    --------
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> from embroact.export.machine.formats import machine_format
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (13, 0, Command.STITCH, Role.LEG),
    ...                                 (13, 0, Command.END, Role.CONTROL, -1)])
    >>> to_pattern(plan, machine_format("a.dst"), split_long=True).split_legs
    1
    """
    cord = check_cord_stop(cord_stop)
    legs = find_long_legs(plan, fmt.limit.max_record_mm)
    if legs and not split_long:
        raise LongLegError(legs, fmt.name)
    b = _Builder(fmt)
    pe = b.pe
    lim = round(fmt.limit.max_record_mm * UNITS_PER_MM)
    units = to_machine_units(plan.xy_mm)
    origin = _file_origin(plan, units) if fmt.first_at_origin else np.zeros(2, np.int64)
    units = units - origin
    commands = plan.commands.tolist()
    split = 0
    threads: dict[int, int] = {}
    lead_block = False  # colour formats: the first actuator's placement line is a colour block of its own
    pending: np.ndarray | None = None  # travel target of a run of plan JUMPs, written as one move
    for i, (cmd, p) in enumerate(zip(commands, units)):
        k = int(plan.actuator[i])
        if cmd == Command.JUMP:
            pending = p
            continue
        if cmd == Command.STOP:
            first = k not in threads
            threads.setdefault(k, len(threads))
            if fmt.stop_style == "color":
                pause = b.stitched  # a later actuator, or after a placement line (the first gets its own colour)
                lead_block = lead_block or (pause and threads[k] == 0)
                if pause and not fmt.color_after_travel:
                    b.change_colour(_actuator_name(plan, k))  # where the last actuator (or the placement line) ended, before the travel
                if not np.array_equal(b.pos, p):  # a placement line ends at the stop: the tie-in stitches from there
                    b.travel(units[_next_stitch(plan, i)], i)  # else colour formats wait at the first needle point
                pending = None
                if pause and fmt.color_after_travel:
                    b.change_colour(_actuator_name(plan, k))
                b.waited = True
                continue
            if pending is not None:
                b.travel(pending, i)
                pending = None
            b.travel(p, i)
            if first:
                b.stop(threads[k], cord)
            b.waited = True
            continue
        if pending is not None:
            b.travel(pending, i)
            pending = None
            if fmt.no_jumps and b.stitched:  # no jump record: the travel is the start of a colour block
                b.change_colour(_actuator_name(plan, k) + PLACEMENT_LABEL)
        if cmd == Command.STITCH:
            if fmt.stop_style == "needle_stop" and not b.selected:  # a placement line sewn before the first stop
                b.select(threads.get(k, len(threads)))
            if not b.stitched and b.jump_ok and not b.waited:
                b.travel(p, i)  # first needle point: a frame move, never a stitch from the origin
            if int(np.abs(p - b.pos).max()) > lim:
                pts = _split_leg(b.pos, p, lim, _forbidden_t(plan, k, plan.xy_mm[i - 1], plan.xy_mm[i]))
                split += 1
            else:
                pts = [p]
            for q in pts:
                b.add(pe.STITCH, q)
            b.jump_ok, b.stitched = False, True
        elif cmd == Command.TRIM:
            b.travel(p, i)
            last = i + 1 >= len(commands) or commands[i + 1] == Command.END
            if not (last and fmt.end_trims):  # VP3 writes a trim with its end code
                b.add(pe.TRIM)
                if last and fmt.trim_is_jump:  # PEC/PES trim only at a trim-flagged jump: one of zero length
                    b.add(pe.JUMP)
            b.jump_ok = True
        elif cmd == Command.END:
            b.add(pe.END)
    if not plan.count(Command.END):
        b.add(pe.END)
    if len(b.pattern.stitches) > fmt.limit.max_records:
        raise ExportError(
            f"design needs {len(b.pattern.stitches)} records; {fmt.name} holds at most {fmt.limit.max_records}"
        )
    labels = [_actuator_name(plan, k) for k in sorted(threads, key=lambda k: threads[k]) or [0]]
    if fmt.stop_style == "color":  # one thread per colour block
        labels = [labels[0] + PLACEMENT_LABEL if lead_block else labels[0]] + b.blocks
    for label in labels:
        t = pe.EmbThread()
        t.set_color(*(THREAD_COLORS[len(b.pattern.threadlist) % len(THREAD_COLORS)].to_bytes(3, "big")))
        t.description = ascii_label(label)
        t.catalog_number = f"A{len(b.pattern.threadlist) + 1}"
        t.brand = "embroact"
        b.pattern.add_thread(t)
    b.pattern.metadata("name", ascii_label(plan.name, max_chars=fmt.label_chars or MAX_LABEL_CHARS))
    return MachinePattern(b.pattern, fmt.name, split,
                          (float(origin[0]) / UNITS_PER_MM, -float(origin[1]) / UNITS_PER_MM), lead_block)
