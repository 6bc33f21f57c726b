"""Machine-format facts the generators, rules and writers share: the grid, per-record limits, trims.

A machine file stores every record as a move on the 0.1 mm grid from the previous
record. The writer rounds each *absolute* position to the grid once
(:func:`grid_units`), so a record's move is the difference of two rounded
positions (:func:`record_moves_units`), and a move fits one record when neither
axis exceeds the format's limit on that grid (:func:`records_needed`). The design
rule EA102 and the machine writer both judge a stitch with these functions, so a
leg the writer encodes in one record never trips the rule.

Limits are pystitch's writers' (those of pyembroidery 1.5.1, which it forks; docs/machine.md),
in mm per axis (not Euclidean). XXX: the writer encodes a stitch of 124 units (12.4 mm) or more per axis
with the long-move code 0x7D, which every reader takes as a jump, so its stitch
limit is 12.3 mm (frame moves of 12.4 mm are fine).

Examples
--------
>>> from embroact.patterns.limits import format_limit, record_moves_units, records_needed
>>> format_limit("dst").max_record_mm
12.1
>>> moves = record_moves_units([(-0.049, 0.0), (12.149, 0.0)])  # rounds to 0.0 and 12.1 mm
>>> moves.tolist(), records_needed(moves, 12.1).tolist()
([[0, 0], [121, 0]], [1, 1])
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .base.errors import ParameterError
from .base.tolerances import DEFAULT_TOLERANCES
from .plan import Command

__all__ = [
    "MAX_STITCH_MM",
    "MIN_STITCH_MM",
    "UNITS_PER_MM",
    "TRIM_JUMP_RUN",
    "FormatLimit",
    "FORMAT_LIMITS",
    "format_limit",
    "grid_units",
    "on_grid",
    "GRID_ROUNDING_MM",
    "record_moves_units",
    "records_needed",
    "framed_first",
    "rail_offset_mm",
    "grid_origin_mm",
]

UNITS_PER_MM = round(1.0 / DEFAULT_TOLERANCES.machine_grid_mm)
"""Machine-file units per millimetre (the 0.1 mm grid of every supported format)."""

GRID_ROUNDING_MM = 0.5 * math.sqrt(2.0) * DEFAULT_TOLERANCES.machine_grid_mm
"""The farthest :func:`on_grid` moves a point [mm]: half a grid step on each axis."""

TRIM_JUMP_RUN = 3
"""Consecutive jump records a machine (and pystitch's DST writer) treat as a trim."""


@dataclass(frozen=True, slots=True)
class FormatLimit:
    """Limits of one machine-file format.

    Attributes
    ----------
    name : str
        Lower-case suffix without the dot.
    max_record_mm : float
        Largest stitch per axis in one record [mm].
    max_jump_mm : float
        Largest jump per axis in one record [mm].
    max_records : int
        Largest number of records the format (or its header field) can hold.
    trim_as_jumps : bool
        True when the writer encodes a trim as a run of :data:`TRIM_JUMP_RUN` jumps (DST).
    description : str
        The format's name for listings (``"Tajima DST (default)"``).
    unit_mm : float
        The format's position unit [mm]: every record is a whole number of them. The stitch
        plan's needle points are made on this grid (:func:`on_grid`), so a format with another
        unit must declare it here.

    Examples
    --------
    >>> f = FORMAT_LIMITS["vp3"]
    >>> f.max_record_mm, f.max_jump_mm, f.unit_mm
    (25.5, 320.0, 0.1)
    """

    name: str
    max_record_mm: float
    max_jump_mm: float
    max_records: int
    trim_as_jumps: bool
    description: str
    unit_mm: float = DEFAULT_TOLERANCES.machine_grid_mm


FORMAT_LIMITS: dict[str, FormatLimit] = {
    f.name: f
    for f in (
        FormatLimit("dst", 12.1, 12.1, 9_999_999, True, "Tajima DST (default)"),
        FormatLimit("tbf", 12.7, 12.7, 9_999_999, False, "Tajima TBF, separate stop and trim codes"),
        FormatLimit("exp", 12.7, 12.7, 9_999_999, False, "Melco / Bernina EXP"),
        FormatLimit("jef", 12.7, 12.7, 9_999_999, False, "Janome JEF"),
        FormatLimit("u01", 12.7, 12.7, 9_999_999, False, "Barudan U01"),
        FormatLimit("xxx", 12.3, 12.4, 9_999_999, False, "Singer XXX"),
        FormatLimit("pes", 204.7, 204.7, 9_999_999, False, "Brother PES"),
        FormatLimit("pec", 204.7, 204.7, 9_999_999, False, "Brother PEC"),
        FormatLimit("vp3", 25.5, 320.0, 9_999_999, False, "Pfaff / Husqvarna VP3"),
    )
}


#: The default machine's longest stitch [mm]: DST's per-record limit (DST is the default format).
MAX_STITCH_MM = FORMAT_LIMITS["dst"].max_record_mm
#: The default machine's shortest stitch [mm] (shorter ones pile needle holes up, EA104).
MIN_STITCH_MM = 0.3


def format_limit(name: str) -> FormatLimit:
    """Limits for a format name or suffix (``"dst"``, ``".DST"``); unknown names list the valid ones.

    Parameters
    ----------
    name : str
        Format name or file suffix, any case.

    Returns
    -------
    FormatLimit

    Examples
    --------
    >>> format_limit(".DST").max_record_mm
    12.1
    >>> try:
    ...     format_limit("svg")
    ... except ValueError as exc:
    ...     print(exc)  # doctest: +ELLIPSIS
    format must be one of dst, tbf, exp, ..., got 'svg'
    """
    key = name.lower().lstrip(".")
    if key not in FORMAT_LIMITS:
        raise ParameterError(f"format must be one of {', '.join(FORMAT_LIMITS)}, got {name!r}")
    return FORMAT_LIMITS[key]


def grid_units(xy_mm) -> np.ndarray:
    """Positions [mm] rounded to the machine grid, as int64 units (same frame and axes).

    Parameters
    ----------
    xy_mm : array_like (n, 2)
        Positions [mm].

    Returns
    -------
    numpy.ndarray of int64, shape (n, 2)
        Whole machine units (no negative zeros).

    Examples
    --------
    >>> grid_units([(1.0, 2.0), (-0.04, 12.149)]).tolist()
    [[10, 20], [0, 121]]
    """
    u = np.rint(np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2) * UNITS_PER_MM).astype(np.int64)
    u[u == 0] = 0  # no negative zeros
    return u


def on_grid(xy_mm) -> np.ndarray:
    """Positions [mm] moved to the nearest point of the machine grid, as float mm.

    The generators put every needle point through this once, where the plan is made, so the
    plan holds the points the machine file will hold (a whole number of units each) and
    everything measured on the plan (realised width, angle, length, the derived geometry,
    every prediction) is measured on what the machine sews.

    Parameters
    ----------
    xy_mm : array_like (n, 2)
        Positions [mm].

    Returns
    -------
    numpy.ndarray, shape (n, 2)
        The grid points [mm].

    Examples
    --------
    >>> on_grid([(3.0764, -3.0764), (0.04, 12.15)]).tolist()
    [[3.1, -3.1], [0.0, 12.2]]
    """
    return grid_units(xy_mm) / float(UNITS_PER_MM)


def record_moves_units(xy_mm) -> np.ndarray:
    """Each record's move on the grid [units] from the previous record; the first moves from the origin.

    Parameters
    ----------
    xy_mm : array_like (n, 2)
        Record positions [mm].

    Returns
    -------
    numpy.ndarray of int64, shape (n, 2)
        The moves [machine units].

    Examples
    --------
    >>> record_moves_units([(1.0, 0.0), (1.5, -0.2)]).tolist()
    [[10, 0], [5, -2]]
    """
    u = grid_units(xy_mm)
    return np.diff(u, axis=0, prepend=np.zeros((1, 2), dtype=np.int64))


def records_needed(moves_units, limit_mm: float) -> np.ndarray:
    """Records a move needs when no record may exceed ``limit_mm`` per axis (at least 1 per move).

    Parameters
    ----------
    moves_units : array_like (n, 2)
        Moves [machine units] (:func:`record_moves_units`).
    limit_mm : float
        Largest move per axis in one record [mm].

    Returns
    -------
    numpy.ndarray of int64, shape (n,)

    Examples
    --------
    >>> records_needed([[121, 0], [122, 0], [0, -363], [0, 0]], 12.1).tolist()
    [1, 2, 3, 1]
    """
    lim = round(limit_mm * UNITS_PER_MM)
    reach = np.abs(np.asarray(moves_units, dtype=np.int64).reshape(-1, 2)).max(axis=1)
    return np.maximum(1, -(-reach // lim))


def framed_first(commands) -> np.ndarray:
    """Mask of the record the writer reaches by a frame move although it is a needle record: the
    first STITCH when only JUMP records come before it (a placement line starts a design that
    way); its move from the start point is travel, not a stitch.

    Parameters
    ----------
    commands : array_like (n,)
        :class:`Command` per record.

    Returns
    -------
    numpy.ndarray of bool, shape (n,)
        True at most once.

    Examples
    --------
    >>> framed_first([1, 1, 0, 0]).tolist(), framed_first([3, 0, 0]).tolist()
    ([False, False, True, False], [False, False, False])
    """
    cmds = np.asarray(commands).reshape(-1)
    out = np.zeros(len(cmds), dtype=bool)
    other = np.flatnonzero(cmds != Command.JUMP)
    if len(other) and cmds[other[0]] == Command.STITCH:
        out[other[0]] = True
    return out


def rail_offset_mm(width_mm: float) -> float:
    """The sideways shift of a straight path along a grid line that puts both rails (+-w/2) of a width on the
    machine grid: 0 for a width of an even number of grid units, half a unit for an odd one.

    A 6.1 mm zigzag on the path y = 0 would round its rails at +-3.05 mm to +-3.1 (a 6.2 mm zigzag is
    sewn); on the path y = 0.05 mm they lie at 3.1 and -3.0 mm, exactly 6.1 mm apart. The tube lies on
    the path, so it stays centred between the rails.

    Parameters
    ----------
    width_mm : float
        The zigzag's width [mm], on the machine grid.

    Returns
    -------
    float
        The shift [mm].

    Examples
    --------
    >>> rail_offset_mm(6.1), rail_offset_mm(6.2), rail_offset_mm(7.0)
    (0.05, 0.0, 0.0)
    """
    grid = DEFAULT_TOLERANCES.machine_grid_mm
    return 0.5 * grid if round(width_mm / grid) % 2 else 0.0


def grid_origin_mm(width_mm: float, origin_mm=(0.0, 0.0), rotation_deg: float = 0.0) -> tuple[float, float]:
    """Where a straight actuator starts so that both rails of ``width_mm`` lie on the machine grid.

    A path along a grid axis (``rotation_deg`` a multiple of 90) starts on the nearest grid point along
    itself (so its legs round as on a path from the origin) and is moved across itself to the grid
    line at or below its start, then by :func:`rail_offset_mm` (so moving it back and forth between
    an odd and an even width does not creep); a path at another angle (its needle points round one
    by one) keeps its start.

    Parameters
    ----------
    width_mm : float
        The width [mm], on the machine grid.
    origin_mm : (float, float)
        The path's start [mm].
    rotation_deg : float
        The path's direction [deg, counter-clockwise from +x].

    Returns
    -------
    tuple of float
        The start [mm].

    Examples
    --------
    >>> grid_origin_mm(6.1), grid_origin_mm(6.2, (0.0, 0.05)), grid_origin_mm(6.1, (10.0, 20.03), 90.0)
    ((0.0, 0.05), (0.0, 0.0), (10.05, 20.0))
    """
    quarter = rotation_deg / 90.0
    x, y = (float(v) for v in origin_mm)
    if abs(quarter - round(quarter)) > 1e-9:
        return x, y
    grid = DEFAULT_TOLERANCES.machine_grid_mm

    def across(c: float) -> float:
        return round(math.floor(c / grid + 1e-6) * grid + rail_offset_mm(width_mm), 10)

    def along(c: float) -> float:
        return round(round(c / grid) * grid, 10)

    return (along(x), across(y)) if round(quarter) % 2 == 0 else (across(x), along(y))
