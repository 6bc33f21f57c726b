"""Needle stations to records: what every actuator needs around its pattern's stations.

A pattern kind's *layout* (:class:`Layout`, e.g. :func:`embroact.patterns.zigzag.zigzag_layout`)
decides *where* the needle goes on its stretch of the path: stations given by arc length
``s`` along the centerline, rail side (+1 left, -1 right) and the role of the stitch
arriving there (LEG or EDGE). The chain generator (:func:`embroact.patterns.segments.segmented`)
puts the segments' stations in a row and :func:`frame_records` adds, in this fixed record
convention:

1. ``STOP`` (CONTROL) where the lock stitches start, a needle point on the first
   station's rail: cord in, the operator lays the tube;
2. ``tie_count`` TIE_IN lock stitches of ``tie_stitch_mm`` back and forth along that
   rail (towards the inside of the path), ending on the first station (so the STOP sits
   ``tie_stitch_mm`` from it when ``tie_count`` is odd, on it when even); the length is
   the straight stitch between two points of the rail, so on a curve the second point
   lies about ``tie_stitch_mm / (1 - kappa * offset)`` along the centerline, farther on an
   inner rail (:func:`tie_step_mm`);
3. the stations' LEG / EDGE stitches;
4. ``tie_count`` TIE_OFF lock stitches along the last station's rail;
5. ``TRIM`` (CONTROL) at the last point; 6. ``END`` (CONTROL, actuator -1).

It then checks the corridor invariant with shapely (every STITCH at distance
>= r_f + clearance from the centerline).

Examples
--------
>>> import numpy as np
>>> from embroact.patterns.assemble import frame_records, inward
>>> from embroact.patterns.centerline import Centerline
>>> from embroact.patterns.params import StitchOptions, Tube
>>> from embroact.patterns.plan import Role
>>> cl = Centerline.straight(4.0)
>>> xy, commands, roles, owner = frame_records(cl, np.array([0.0, 1.0, 2.0, 3.0]), np.array([3.5, -3.5, 3.5, -3.5]),
...                                            np.full(4, Role.LEG), inward(cl, 0.0, 3.0), tube=Tube(),
...                                            options=StitchOptions())
>>> len(xy)   # STOP, 3 tie-in (the last on station 0), 3 more stations, 3 tie-off, TRIM, END
12
>>> xy[:5].round(9).tolist()   # STOP, 3 tie-in stitches ending on station 0, station 1
[[0.7, 3.5], [0.0, 3.5], [0.7, 3.5], [0.0, 3.5], [1.0, -3.5]]
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from .centerline import Centerline
from .base.errors import ParameterError, PatternError, PathError
from .limits import GRID_ROUNDING_MM, on_grid
from .params import PatternParams, StitchOptions, Tube
from .plan import Command, Role
from .base.tolerances import DEFAULT_TOLERANCES
from .spatial import corridor_hits

__all__ = ["Layout", "frame_records", "inward", "check_pattern_inputs", "check_record_count", "rail_positions", "tie_step_mm",
           "MAX_RECORDS", "MIN_TIE_GRID_STEPS"]

#: Hard cap on records in one plan; generators refuse before allocating.
MAX_RECORDS = 5_000_000
#: Shortest lock stitch in machine grid steps: two points 2 steps apart stay distinct after rounding
#: each to the grid (found by the H8 round-trip property: 0.1 mm ties at x.x5 mm rounded to one point).
MIN_TIE_GRID_STEPS = 2
#: A lock stitch's far point is searched within this many tie_stitch_mm of centerline (the inner rail
#: covers at least 1/16 of the centerline's length there), on this many samples, then bisected.
_TIE_SEARCH_SPAN = 16.0
_TIE_SEARCH_SAMPLES = 129
_BISECT_STEPS = 40
#: Records an actuator adds besides its stations and 2 * tie_count lock stitches (STOP, TRIM, END,
#: less the first station, which is the last tie-in stitch).
_EXTRA_RECORDS = 2


def check_pattern_inputs(cl: Centerline, params: PatternParams, tube: Tube, options: StitchOptions) -> None:
    """Checks shared by the generators: types, width vs tube corridor, interval, path bends.

    Parameters
    ----------
    cl : Centerline
        The path.
    params : PatternParams
        The requested pattern.
    tube : Tube
        The tube the pattern holds.
    options : StitchOptions
        Lock stitches and the like.

    Raises
    ------
    ParameterError
        One line naming the parameter, the rule and the value.

    Examples
    --------
    >>> from embroact.patterns.params import ZigzagParams
    >>> try:
    ...     check_pattern_inputs(Centerline.straight(50.0), ZigzagParams(3.0, 1.0), Tube(), StitchOptions())
    ... except ValueError as exc:
    ...     print(exc)
    width_mm must be > 2*(r_f + clearance) = 3.6, got 3
    """
    if not isinstance(tube, Tube):
        raise ParameterError(f"tube must be a Tube, got {type(tube).__name__}")
    if not isinstance(options, StitchOptions):
        raise ParameterError(f"options must be a StitchOptions, got {type(options).__name__}")
    corridor = tube.corridor_radius_mm
    if params.width_mm / 2.0 <= corridor:
        raise ParameterError(
            f"width_mm must be > 2*(r_f + clearance) = {2.0 * corridor:g}, got {params.width_mm:g}"
        )
    grid = DEFAULT_TOLERANCES.machine_grid_mm
    if params.interval_mm < grid:
        raise ParameterError(
            f"interval_mm must be >= {grid:g} (needle points closer than the machine grid merge), "
            f"got {params.interval_mm:g}"
        )
    if options.tie_stitch_mm < MIN_TIE_GRID_STEPS * grid:  # shorter lock stitches can round to zero length
        raise ParameterError(f"tie_stitch_mm must be >= {MIN_TIE_GRID_STEPS * grid:g} (two machine grid steps), "
                             f"got {options.tie_stitch_mm:g}")
    cl.check_radius(params.width_mm / 2.0, "width_mm/2")


def rail_positions(cl: Centerline, s_from: float, s_to: float, offset_mm: float, max_step_mm: float) -> np.ndarray:
    """Centerline positions after ``s_from`` up to ``s_to`` (included) that split the rail at
    ``offset_mm`` (> 0 left) between them into the fewest equal pieces of at most ``max_step_mm``
    measured along that rail, whose arc length is ``(1 - kappa * offset) ds``.

    Parameters
    ----------
    cl : Centerline
        The path.
    s_from, s_to : float
        Arc lengths along the path [mm].
    offset_mm : float
        The rail's offset from the path [mm], > 0 left.
    max_step_mm : float
        Longest piece along the rail [mm].

    Returns
    -------
    numpy.ndarray
        Arc lengths [mm], ending at ``s_to``.

    Examples
    --------
    >>> from embroact.patterns.centerline import Centerline
    >>> rail_positions(Centerline.straight(10.0), 1.0, 7.0, 2.0, 2.5).tolist()
    [3.0, 5.0, 7.0]
    """
    s_v = cl.vertex_s_mm
    factor = np.maximum(1.0 - cl.segment_curvature() * offset_mm, 0.0)
    sigma_v = np.concatenate([[0.0], np.cumsum(np.diff(s_v) * factor)])
    a, b = np.interp([s_from, s_to], s_v, sigma_v)
    count = max(1, math.ceil(abs(b - a) / max_step_mm))
    out = np.interp(a + (b - a) * np.arange(1, count + 1) / count, sigma_v, s_v)
    out[-1] = s_to
    return out


def tie_step_mm(cl: Centerline, s_mm, offset_mm, direction, tie_mm: float) -> np.ndarray:
    """Centerline distance from each ``s_mm`` (towards ``direction``, +-1) to the point of the rail at
    ``offset_mm`` that is ``tie_mm`` (straight) from the rail point at ``s_mm``; 1-D arrays.

    Where the path ends before that point (a path shorter than about ``tie_mm`` on that rail:
    an inner rail shrinks by 1 - w/(2R) on a bend of radius R), the longest stitch the rail
    holds there (its other needle points are as close); :class:`PatternError` if the rail
    holds none.

    Parameters
    ----------
    cl : Centerline
        The path.
    s_mm, offset_mm, direction : array_like (n,)
        Arc length [mm], rail offset [mm] and direction (+1 or -1) of each lock stitch.
    tie_mm : float
        Lock stitch length, straight [mm].

    Returns
    -------
    numpy.ndarray, shape (n,)
        Arc-length steps [mm], >= 0.

    Examples
    --------
    >>> from embroact.patterns.centerline import Centerline
    >>> tie_step_mm(Centerline.straight(10.0), [1.0, 9.0], [2.0, -2.0], [1, -1], 0.5).round(12).tolist()
    [0.5, 0.5]
    """
    s = np.asarray(s_mm, dtype=np.float64)[:, None]
    off = np.asarray(offset_mm, dtype=np.float64)[:, None]
    d = np.asarray(direction, dtype=np.float64)[:, None]
    room = np.where(d > 0.0, cl.length_mm - s, s)
    u = np.minimum(room, _TIE_SEARCH_SPAN * tie_mm) * np.linspace(0.0, 1.0, _TIE_SEARCH_SAMPLES)
    x0, y0 = cl.offset_xy_at(s, off)

    def chord(step):
        x, y = cl.offset_xy_at(s + d * step, off)
        return np.hypot(x - x0, y - y0)

    c = chord(u)
    reach = c >= tie_mm
    rows = np.arange(u.shape[0])
    first = np.argmax(reach, axis=1)
    lo, hi = u[rows, first - 1][:, None], u[rows, first][:, None]
    for _ in range(_BISECT_STEPS):
        mid = 0.5 * (lo + hi)
        short = chord(mid) < tie_mm
        lo, hi = np.where(short, mid, lo), np.where(short, hi, mid)
    # a rail too short for the whole stitch: the longest one it holds (not a point)
    short_path = ~reach.any(axis=1)
    no_room = short_path & (c.max(axis=1) <= DEFAULT_TOLERANCES.length_mm)
    if np.any(no_room):
        x, y = x0[int(np.argmax(no_room)), 0], y0[int(np.argmax(no_room)), 0]
        raise PatternError(f"the rail at ({x:.2f}, {y:.2f}) mm has no room for a lock stitch (tie_stitch_mm="
                           f"{tie_mm:g}): the path is too short or bends at radius width_mm/2; use a longer or "
                           f"gentler path")
    return np.where(short_path, u[rows, np.argmax(c, axis=1)], hi[:, 0])


def check_record_count(n_stations: float, options: StitchOptions) -> int:
    """Records a plan with ``n_stations`` stations needs; :class:`PatternError` above the cap.

    Parameters
    ----------
    n_stations : float
        Needle stations (an upper bound will do).
    options : StitchOptions
        Its ``tie_count`` adds lock stitches at both ends.

    Returns
    -------
    int

    Examples
    --------
    >>> check_record_count(101, StitchOptions()) > 101
    True
    >>> try:
    ...     check_record_count(1e9, StitchOptions())
    ... except ValueError as exc:
    ...     print(exc)  # doctest: +ELLIPSIS
    pattern would need about 1e+09 records, more than the limit ...; use a larger interval_mm or a shorter path
    """
    n = float(n_stations) + 2 * options.tie_count + _EXTRA_RECORDS
    if n > MAX_RECORDS:
        raise PatternError(
            f"pattern would need about {n:.3g} records, more than the limit {MAX_RECORDS:,}; "
            "use a larger interval_mm or a shorter path"
        )
    return int(n)


@dataclass(frozen=True, slots=True)
class Layout:
    """A pattern's needle stations on its stretch of the path, in the path frame.

    Attributes
    ----------
    s_mm : ndarray (m,)
        Arc length of each station along the actuator's centerline [mm].
    side : ndarray (m,)
        Rail of each station: +1 left, -1 right (the offset is ``side * width_mm / 2``).
    roles : ndarray (m,)
        :class:`~embroact.patterns.plan.Role` of the stitch arriving at each station (the first
        station's is unused: the tie-in ends there).
    adjustments : tuple of str
        What the layout changed in the request (the cross closing its pattern).

    Examples
    --------
    >>> import numpy as np
    >>> lay = Layout(np.array([0.0, 1.0]), np.array([1, -1]), np.full(2, Role.LEG))
    >>> lay.s_mm.tolist(), lay.adjustments
    ([0.0, 1.0], ())
    """

    s_mm: np.ndarray
    side: np.ndarray
    roles: np.ndarray
    adjustments: tuple[str, ...] = ()


def inward(cl: Centerline, s_first_mm: float, s_last_mm: float) -> np.ndarray:
    """Directions (+-1) along the path of the tie-in and the tie-off lock stitches: towards the inside.

    Parameters
    ----------
    cl : Centerline
    s_first_mm, s_last_mm : float
        Arc length of the first and the last station [mm].

    Returns
    -------
    ndarray (2,)

    Examples
    --------
    >>> from embroact.patterns.centerline import Centerline
    >>> inward(Centerline.straight(10.0), 0.5, 9.5).tolist()
    [1.0, -1.0]
    """
    return np.array([1.0 if s <= cl.length_mm / 2.0 else -1.0 for s in (s_first_mm, s_last_mm)])


def frame_records(cl: Centerline, station_s: np.ndarray, station_offset_mm: np.ndarray, station_role: np.ndarray,
                  inward: np.ndarray, *, tube: Tube, options: StitchOptions):
    """Records 1-6 of the module docstring around stations given by arc length and rail offset [mm].

    Checks the corridor invariant.

    Parameters
    ----------
    cl : Centerline
        The path.
    station_s, station_offset_mm, station_role : numpy.ndarray (m,)
        Arc length [mm], rail offset [mm] and role of the stitch arriving at each station.
    inward : numpy.ndarray (2,)
        Direction along the path (+1 or -1) of the tie-in and the tie-off lock stitches.
    tube, options : Tube, StitchOptions
        The tube and the lock stitches.

    Returns
    -------
    xy, commands, roles, actuator : numpy.ndarray
        The records: positions on the machine grid [mm], :class:`Command`, :class:`Role` and
        actuator index (-1 for the END record).

    Examples
    --------
    >>> s = np.array([0.0, 1.0, 2.0])
    >>> xy, cmds, roles, act = frame_records(Centerline.straight(5.0), s, np.array([3.5, -3.5, 3.5]),
    ...                                      np.full(3, Role.LEG), np.array([1.0, -1.0]), tube=Tube(),
    ...                                      options=StitchOptions(tie_count=2))
    >>> [Command(c).name for c in cmds[[0, -2, -1]]], len(xy), int(act[-1])
    (['STOP', 'TRIM', 'END'], 9, -1)
    """
    k = options.tie_count
    s0, sn = float(station_s[0]), float(station_s[-1])
    o0, on = float(station_offset_mm[0]), float(station_offset_mm[-1])
    step = inward * tie_step_mm(cl, [s0, sn], np.array([o0, on]), inward, options.tie_stitch_mm)
    j = np.arange(k + 1)
    tie_in = s0 + step[0] * ((k - j) % 2)  # [STOP, k stitches ending on s0]
    tie_off = sn + step[1] * (j[1:] % 2)  # k stitches from sn
    s_all = np.concatenate([tie_in, station_s[1:], tie_off])
    o_all = np.concatenate([np.full(k + 1, o0), station_offset_mm[1:], np.full(k, on)])
    xy = on_grid(cl.offset_point_at(s_all, o_all))  # the points the machine file will hold
    xy = np.vstack([xy, xy[-1], xy[-1]])  # TRIM, END
    n = len(xy)
    commands = np.full(n, Command.STITCH, dtype=np.int8)
    commands[[0, -2, -1]] = (Command.STOP, Command.TRIM, Command.END)
    roles = np.concatenate(
        [[Role.CONTROL], np.full(k, Role.TIE_IN), station_role[1:], np.full(k, Role.TIE_OFF), [Role.CONTROL] * 2]
    ).astype(np.int8)
    actuator = np.zeros(n, dtype=np.int16)
    actuator[-1] = -1
    _check_corridor(cl, xy[commands == Command.STITCH], tube)
    return xy, commands, roles, actuator


def _check_corridor(cl: Centerline, xy: np.ndarray, tube: Tube) -> None:
    # the points are on the machine grid: a rail at the corridor's edge may round into it by up to GRID_ROUNDING_MM
    bad = corridor_hits(cl.segment_index(), xy, tube.corridor_radius_mm - GRID_ROUNDING_MM - DEFAULT_TOLERANCES.length_mm)
    if bad.size:
        x, y = xy[bad[0]]
        d = float(shapely.distance(cl.as_linestring(), shapely.Point(x, y)))
        raise PathError(
            f"needle point ({x:.2f}, {y:.2f}) mm is {d:.3g} mm from the path, inside the tube corridor "
            f"r_f + clearance = {tube.corridor_radius_mm:g} mm: the path comes too close to itself"
        )
