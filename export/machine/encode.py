"""Stitch plan -> machine records: frame, cord stops, trims, threads, long legs.

The plan frame is millimetres with y up; pyembroidery works in 0.1 mm units with
y down.  Every position is rounded to the 0.1 mm grid once, in absolute terms, so
rounding never accumulates along the design.  The plan origin is the machine's
start point (the first record moves from there).

How plan records become machine records
---------------------------------------
========  ==================================================================
plan      machine
========  ==================================================================
STITCH    one needle record.  A leg longer than the format's per-record limit
          (per axis) is refused with :class:`LongLegError`; with
          ``split_long=True`` it becomes several needle records whose extra
          needle points all lie *outside* the tube corridor.
JUMP      frame move without the needle, split into records of at most the
          format's jump limit.  Machines read a run of 3 or more jump records
          as a trim; travel written here only follows a TRIM (or precedes the
          first stitch), where a trim is wanted anyway.  A longer travel
          anywhere else is refused.
STOP      cord in: the frame first moves to the record's point, then, by the
          format's ``stop_style``:

          * ``"stop"`` (DST, EXP): one stop record per plan STOP.  DST and EXP
            share the stop and colour-change code, so the header's ``CO`` counts
            exactly these.
          * ``"color"`` (PES, PEC, JEF, VP3, XXX): formats with a thread table.
            The first actuator's stop is implicit (the machine waits for start);
            every later STOP is one colour change to that actuator's thread,
            which makes single-needle machines stop, placed at the actuator's
            first needle point (the frame travels there first).  PEC/PES
            writers add a zero-length stitch at a colour change after travel:
            one extra penetration on the first needle point.
          * ``"needle_stop"`` (TBF, U01): a needle-set record selecting the
            actuator's thread (always needle 1) and a separate stop record.
TRIM      one trim (DST: pyembroidery's run of 3 jumps netting to zero).
END       one end record.
========  ==================================================================

The thread list holds one thread per actuator, its description the actuator name.

Examples
--------
>>> from embroact.patterns.plan import Command, Role, StitchPlan
>>> from embroact.export.machine.formats import machine_format
>>> plan = StitchPlan.from_records([
...     (0.0, 3.5, Command.STOP, Role.CONTROL), (0.0, 3.5, Command.STITCH, Role.TIE_IN),
...     (1.0, -3.5, Command.STITCH, Role.LEG), (1.0, -3.5, Command.TRIM, Role.CONTROL),
...     (1.0, -3.5, Command.END, Role.CONTROL, -1)])
>>> mp = to_pattern(plan, machine_format("act.dst"))
>>> import pyembroidery as pe
>>> names = {pe.JUMP: "jump", pe.STOP: "stop", pe.STITCH: "stitch", pe.TRIM: "trim", pe.END: "end"}
>>> [(names[c], x, y) for x, y, c in mp.pattern.stitches]  # 0.1 mm, y down
[('jump', 0, -35), ('stop', 0, -35), ('stitch', 0, -35), ('stitch', 10, 35), ('trim', 10, 35), ('end', 10, 35)]
>>> mp.stops, mp.trims, mp.split_legs
(1, 1, 0)
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ...patterns.base.errors import ExportError, PatternError
from ...patterns.plan import Command, StitchPlan
from ...patterns.base.tolerances import DEFAULT_TOLERANCES

if TYPE_CHECKING:  # pragma: no cover
    from .formats import MachineFormat

__all__ = [
    "UNITS_PER_MM",
    "TRIM_JUMP_RUN",
    "THREAD_COLORS",
    "LongLeg",
    "LongLegError",
    "MachinePattern",
    "to_machine_units",
    "find_long_legs",
    "to_pattern",
]

UNITS_PER_MM = round(1.0 / DEFAULT_TOLERANCES.machine_grid_mm)
"""pyembroidery units per millimetre (0.1 mm grid)."""

TRIM_JUMP_RUN = 3
"""Consecutive jump records a machine (and pyembroidery's DST writer) treat as a trim."""

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
    """

    actuator: str
    stitch_index: int
    record_index: int
    length_mm: float
    dx_mm: float
    dy_mm: float
    limit_mm: float

    def describe(self, fmt: str) -> str:
        """One line naming the leg, its size and the limit."""
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
    """A plan converted for one format, ready for a pyembroidery writer.

    Attributes
    ----------
    pattern : pyembroidery.EmbPattern
        Low-level records (0.1 mm, y down); write with ``encode=False``.
    format : str
    stops : int
        Stop records written (colour changes in ``"color"`` formats).
    trims, jumps : int
        Trim and jump records written (a DST trim adds its own jumps when written).
    split_legs : int
        Legs split into several stitches (only with ``split_long=True``).
    extra_needle_points : int
        Needle points added by splitting.
    """

    pattern: object
    format: str
    stops: int
    trims: int
    jumps: int
    split_legs: int
    extra_needle_points: int


def to_machine_units(xy_mm: np.ndarray) -> np.ndarray:
    """Plan positions [mm, y up] -> integer pyembroidery units (0.1 mm, y down).

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

    Examples
    --------
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (13, 0, Command.STITCH, Role.LEG)])
    >>> leg, = find_long_legs(plan, 12.1)
    >>> leg.stitch_index, leg.length_mm
    (1, 13.0)
    """
    u = to_machine_units(plan.xy_mm)
    lim = round(limit_mm * UNITS_PER_MM)
    d = np.diff(u, axis=0, prepend=np.zeros((1, 2), dtype=np.int64))
    stitch = plan.commands == Command.STITCH
    bad = np.flatnonzero(stitch & (np.abs(d).max(axis=1) > lim))
    legs = []
    for i in bad:
        k = int(plan.actuator[i])
        same = (plan.actuator[:i] == k) & stitch[:i]
        dx, dy = d[i, 0] / UNITS_PER_MM, -d[i, 1] / UNITS_PER_MM
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


class _Builder:
    """Accumulates low-level records and counts them."""

    def __init__(self, fmt: "MachineFormat") -> None:
        import pyembroidery

        self.pe = pyembroidery
        self.fmt = fmt
        self.pattern = pyembroidery.EmbPattern()
        self.pos = np.zeros(2, dtype=np.int64)
        self.jump_ok = True  # at the start or after a trim: a long jump run is harmless
        self.stitched = False  # a needle record has been written
        self.jump_run = 0  # consecutive jump records just written
        self.stops = self.trims = self.jumps = 0
        self.max_jump = round(fmt.limit.max_jump_mm * UNITS_PER_MM)

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
            self.jumps += 1
        if self.jump_run >= TRIM_JUMP_RUN and not self.jump_ok:
            raise PatternError(
                f"travel up to plan record {record} needs {self.jump_run} jump records in a row without a trim "
                f"before them; machines read {TRIM_JUMP_RUN} or more jumps as a trim: add a TRIM before the travel"
            )

    def stop(self, thread: int) -> None:
        pe, style = self.pe, self.fmt.stop_style
        if style == "stop":
            self.add(pe.STOP)
        elif style == "color":
            self.add(pe.COLOR_CHANGE)
        else:  # needle_stop
            self.add(pe.encode_thread_change(pe.NEEDLE_SET, thread, 1))
            self.add(pe.STOP)
        self.stops += 1


def to_pattern(plan: StitchPlan, fmt: "MachineFormat", *, split_long: bool = False) -> MachinePattern:
    """Convert ``plan`` to low-level pyembroidery records for ``fmt``.

    Parameters
    ----------
    plan : StitchPlan
    fmt : MachineFormat
        From :func:`embroact.export.machine.formats.machine_format`.
    split_long : bool
        Split legs above the per-record limit into stitches outside the tube
        corridor instead of refusing them.

    Raises
    ------
    LongLegError
        A leg exceeds the limit and ``split_long`` is false.
    PatternError
        A leg cannot be split, or a travel would read as an unintended trim.
    ExportError
        More records than the format holds.
    """
    legs = find_long_legs(plan, fmt.limit.max_record_mm)
    if legs and not split_long:
        raise LongLegError(legs, fmt.name)
    b = _Builder(fmt)
    pe = b.pe
    lim = round(fmt.limit.max_record_mm * UNITS_PER_MM)
    units = to_machine_units(plan.xy_mm)
    split = extra = 0
    threads: dict[int, int] = {}
    for i, (cmd, p) in enumerate(zip(plan.commands.tolist(), units)):
        k = int(plan.actuator[i])
        if cmd == Command.STITCH:
            if b.jump_ok and b.stops == 0 and not b.stitched:
                b.travel(p, i)  # first needle point of the design when no stop record precedes it
            if int(np.abs(p - b.pos).max()) > lim:
                pts = _split_leg(b.pos, p, lim, _forbidden_t(plan, k, plan.xy_mm[i - 1], plan.xy_mm[i]))
                split, extra = split + 1, extra + len(pts) - 1
            else:
                pts = [p]
            for q in pts:
                b.add(pe.STITCH, q)
            b.jump_ok, b.stitched = False, True
        elif cmd == Command.JUMP:
            b.travel(p, i)
        elif cmd == Command.STOP:
            threads.setdefault(k, len(threads))
            if fmt.stop_style == "color":
                if threads[k] == 0:
                    continue  # implicit first stop: the first stitch travels to its point
                p = units[_next_stitch(plan, i)]  # colour change where the actuator's first stitch is
            b.travel(p, i)
            b.stop(threads[k])
        elif cmd == Command.TRIM:
            b.travel(p, i)
            b.add(pe.TRIM)
            b.trims += 1
            b.jump_ok = True
        elif cmd == Command.END:
            b.add(pe.END)
    if not plan.count(Command.END):
        b.add(pe.END)
    if len(b.pattern.stitches) > fmt.limit.max_records:
        raise ExportError(
            f"design needs {len(b.pattern.stitches)} records; {fmt.name} holds at most {fmt.limit.max_records}"
        )
    for k in sorted(threads, key=threads.get) or [0]:
        t = pe.EmbThread()
        t.set_color(*(THREAD_COLORS[len(b.pattern.threadlist) % len(THREAD_COLORS)].to_bytes(3, "big")))
        t.description = _actuator_name(plan, k)
        t.catalog_number = f"A{len(b.pattern.threadlist) + 1}"
        t.brand = "embroact"
        b.pattern.add_thread(t)
    b.pattern.metadata("name", plan.name)
    return MachinePattern(b.pattern, fmt.name, b.stops, b.trims, b.jumps, split, extra)
