"""Segmented actuators: one tube, one actuator, the pattern changing along the path.

An actuator may hold consecutive segments ``k = 1..n`` along its path, each with its own
pattern kind, parameters and length (docs/model.md, segmented actuators: segments in
series decouple, each bends with its own uniform curvature). The machine sews them in one
run: one cord-in STOP, one set of lock stitches at each end, one TRIM.

Construction. Segment ``k`` covers ``[S_k, S_k + L_k]`` of the path (``S_k`` the sum of the
lengths before it). Its needle stations are those its own generator puts on a straight
path of length ``L_k`` (legs centred in the segment, as for a single actuator), placed on
the real path at arc length ``S_k + x`` and offset ``y``. A segment is mirrored (every
offset negated, the same pattern started on the other rail) when its first needle point
would lie on the other rail than the one the segment before ended on, so that every
*transition* is a run along one rail, never a stitch across the tube::

    segment k (w_k)            transition          segment k+1 (w_k+1)
    o---o---o---o                                   o------o------o
     \\ / \\ / \\ / \\ last leg  o....o....o (EDGE, <= 3 mm,   / \\    / \\
    ==============================================================  tube
                          rail offset w_k/2 -> w_k+1/2)

The thread runs from the last needle point of segment ``k`` to the first of segment
``k + 1`` in EDGE stitches of at most ``MAX_TRANSITION_STITCH_MM`` along the path, the rail
offset changing linearly from ``w_k/2`` to ``w_(k+1)/2`` (:attr:`SegmentPlan.join_run_mm`:
a zigzag ends at its far end, so the run is short; a cross pattern with an even number of
passes ends near its start, so the run goes back along its rail). The *transition* is the
path between the last leg of segment ``k`` and the first leg of ``k + 1``
(:attr:`SegmentPlan.transition_mm`, well under a stitch interval or two): the model treats
it as part of no segment (it bends by zero). Each segment's realised parameters are
measured on its own needle points on the real path.

Examples
--------
>>> from embroact.patterns.centerline import Centerline
>>> from embroact.patterns.params import CrossParams, ZigzagParams
>>> from embroact.patterns.plan import Command
>>> from embroact.patterns.segments import SegmentSpec, segmented
>>> segs = (SegmentSpec(ZigzagParams(7.0, 1.0), 40.0), SegmentSpec(CrossParams(7.0, 1.4, 45.0), 60.0))
>>> plan = segmented(Centerline.straight(100.0), segs, name="S")
>>> plan.count(Command.STOP), plan.count(Command.TRIM), len(plan.actuators)
(1, 1, 1)
>>> [(s.pattern, round(s.realised.length_mm, 3)) for s in plan.actuators[0].segments]
[('zigzag', 40.0), ('cross', 58.8)]
>>> round(plan.actuators[0].segments[0].transition_mm, 3)
0.6
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .assemble import check_pattern_inputs, frame_records
from .base.errors import EmbroactError, ParameterError
from .centerline import Centerline, as_centerline
from .kinds import PATTERN_KINDS, KindFields, KindOf, pattern_kind
from .limits import on_grid
from .measure import measure
from .params import PatternParams, StitchOptions, Tube
from .plan import ActuatorPlan, Realised, Role, StitchPlan

__all__ = ["SegmentSpec", "SegmentPlan", "segmented", "check_segments", "segment_stations", "pattern_parts",
           "MAX_TRANSITION_STITCH_MM", "LENGTH_MATCH_MM"]

#: Longest stitch of a transition between segments, along the path [mm].
MAX_TRANSITION_STITCH_MM = 3.0
#: The segments' lengths must add up to the path's length within this [mm].
LENGTH_MATCH_MM = 0.05
_STATION_ROLES = (Role.LEG, Role.EDGE)


@dataclass(frozen=True, slots=True)
class SegmentSpec(KindFields):
    """One segment of a segmented actuator, as asked for.

    Parameters
    ----------
    params : PatternParams
    length_mm : float
        Length of the path the segment covers [mm], > 0.
    adjust : str
        Cross only: what may change to close the pattern (``"auto"``, ``"interval"``, ``"angle"``).
    """

    params: PatternParams
    length_mm: float
    adjust: str = "auto"

    def __post_init__(self) -> None:
        PATTERN_KINDS.for_params(self.params)
        if isinstance(self.length_mm, bool) or not isinstance(self.length_mm, (int, float)) \
                or not 0.0 < self.length_mm < 1e6:
            raise ParameterError(f"length_mm must be in (0, 1e6) mm, got {self.length_mm!r}")
        object.__setattr__(self, "length_mm", float(self.length_mm))


@dataclass(frozen=True, slots=True)
class SegmentPlan(KindOf):
    """One generated segment.

    Attributes
    ----------
    params : PatternParams
        The request.
    start_mm, length_mm : float
        Where the segment's share of the path starts and how long it is [mm].
    realised : Realised
        Measured on the segment's needle points (``length_mm`` there: first to last leg).
    first_leg_mm : float
        Arc length where the segment's legs start [mm]; they end at
        ``first_leg_mm + realised.length_mm`` (the part of the path that bends).
    transition_mm : float
        Path length from the end of this segment's legs to the start of the next
        segment's [mm] (bends by zero); 0 for the last segment.
    join_run_mm : float
        Path length the thread runs along a rail from this segment's last needle point to
        the next segment's first [mm]; 0 for the last segment.
    adjustments : tuple of str
        What the generator changed (cross closing).
    mirrored : bool
        True when the segment starts on the right rail (see the module docstring).
    """

    params: PatternParams
    start_mm: float
    length_mm: float
    realised: Realised
    first_leg_mm: float
    transition_mm: float
    join_run_mm: float
    adjustments: tuple[str, ...] = ()
    mirrored: bool = False


def pattern_parts(act: ActuatorPlan) -> tuple[tuple[str, PatternParams, Realised], ...]:
    """``(label, requested parameters, realised)`` of an actuator's patterns: one per segment of a segmented one.

    Rules comparing the request with what was sewn loop over these; ``label`` is ``""`` for a
    single-pattern actuator and ``"segment k: "`` for a segment (a message prefix).

    >>> from embroact.patterns.params import ZigzagParams
    >>> segs = (SegmentSpec(ZigzagParams(7.0, 1.0), 30.0), SegmentSpec(ZigzagParams(9.0, 1.0), 30.0))
    >>> act = segmented(Centerline.straight(60.0), segs).actuators[0]
    >>> [(label, p.width_mm, round(r.width_mm, 6)) for label, p, r in pattern_parts(act)]
    [('segment 0: ', 7.0, 7.0), ('segment 1: ', 9.0, 9.0)]
    """
    if act.segments:
        return tuple((f"segment {k}: ", seg.params, seg.realised) for k, seg in enumerate(act.segments))
    return (("", act.params, act.realised),)


def check_segments(cl: Centerline, segments) -> tuple[SegmentSpec, ...]:
    """``segments`` as a tuple if it is a non-empty sequence of :class:`SegmentSpec` whose lengths
    add up to the path's within ``LENGTH_MATCH_MM``; :class:`ParameterError` otherwise.

    >>> from embroact.patterns.params import ZigzagParams
    >>> check_segments(Centerline.straight(60.0), [SegmentSpec(ZigzagParams(7.0, 1.0), 50.0)])
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.ParameterError: segment length_mm values must add up to the path length 60 mm (within 0.05 mm), got 50
    """
    segs = tuple(segments)
    if not segs or not all(isinstance(s, SegmentSpec) for s in segs):
        raise ParameterError("segments must be a non-empty sequence of SegmentSpec")
    total = sum(s.length_mm for s in segs)
    if abs(total - cl.length_mm) > LENGTH_MATCH_MM:
        raise ParameterError(f"segment length_mm values must add up to the path length {cl.length_mm:.6g} mm "
                             f"(within {LENGTH_MATCH_MM:g} mm), got {total:.6g}")
    return segs


def segment_stations(segments, tube: Tube = Tube(), options: StitchOptions = StitchOptions()) -> int:
    """Upper bound of the needle stations of all segments (no allocation).

    >>> from embroact.patterns.params import ZigzagParams
    >>> segment_stations([SegmentSpec(ZigzagParams(7.0, 1.0), 50.0)] * 2)   # 2 x (51 + transition bound)
    152
    """
    total = 0.0
    for seg in segments:
        kind = pattern_kind(seg.pattern)
        total += kind.stations(seg.length_mm, seg.params, **seg.kind_options)
        total += seg.length_mm / MAX_TRANSITION_STITCH_MM + 8
    return int(math.ceil(total))


def _stations(seg: SegmentSpec, tube: Tube, options: StitchOptions, name: str):
    """(x, y, role) of a segment's needle stations as its generator puts them on a straight path."""
    plan = pattern_kind(seg.pattern).generate(Centerline.straight(seg.length_mm), seg.params, tube=tube,
                                              options=options, name=name, **seg.kind_options)
    roles = plan.roles
    keep = np.isin(roles, _STATION_ROLES)
    first = int(np.argmax(keep)) - 1  # the last tie-in stitch ends on the first station
    keep[first] = True
    return plan.xy_mm[keep], roles[keep], plan.actuators[0].adjustments


def segmented(centerline, segments, *, tube: Tube = Tube(), options: StitchOptions = StitchOptions(),
              name: str = "actuator") -> StitchPlan:
    """One segmented actuator along ``centerline``, as a complete plan (see the module docstring).

    Parameters
    ----------
    centerline : Centerline or anything :func:`as_centerline` takes
    segments : sequence of SegmentSpec
        In order from the path's start; lengths adding up to the path's (within ``LENGTH_MATCH_MM``).
    tube, options, name
        As for the single-pattern generators.

    Returns
    -------
    StitchPlan
        One actuator whose :attr:`ActuatorPlan.segments` holds a :class:`SegmentPlan` per
        segment; its ``params`` and ``realised`` are the first segment's.

    Raises
    ------
    ParameterError, PathError, PatternError
        As the generators, the message prefixed with ``segment[k]``.
    """
    cl = as_centerline(centerline)
    segs = check_segments(cl, segments)
    s_all: list[np.ndarray] = []
    o_all: list[np.ndarray] = []
    role_all: list[np.ndarray] = []
    parts = []
    start = 0.0
    for k, seg in enumerate(segs):
        try:
            check_pattern_inputs(cl, pattern_kind(seg.pattern).realised_params(seg.params, **seg.kind_options),
                                 tube, options)
            x, roles, notes = _stations(seg, tube, options, name)
        except EmbroactError as exc:
            raise type(exc)(f"segment[{k}]: {exc}") from None
        s, o = start + x[:, 0], x[:, 1].copy()
        mirrored = bool(o_all) and bool(np.sign(o[0]) != np.sign(o_all[-1][-1]))
        if mirrored:
            o = -o
        if o_all:
            s_prev, o_prev = s_all[-1][-1], o_all[-1][-1]
            count = max(1, math.ceil(abs(s[0] - s_prev) / MAX_TRANSITION_STITCH_MM))
            f = np.arange(1, count) / count
            s_all.append(s_prev + f * (s[0] - s_prev))
            o_all.append(o_prev + f * (o[0] - o_prev))
            role_all.append(np.full(count - 1, Role.EDGE))
            roles = roles.copy()
            roles[0] = Role.EDGE
        s_all.append(s)
        o_all.append(o)
        role_all.append(roles)
        parts.append((seg, start, s, o, roles, tuple(notes), mirrored))
        start += seg.length_mm
    plans = []
    for k, (seg, s0, s, o, roles, notes, mirrored) in enumerate(parts):
        xy = on_grid(cl.offset_point_at(s, o))  # as frame_records puts them in the plan
        r = roles.copy()
        r[0] = Role.TIE_IN  # the segment's first point starts its first leg
        realised = measure(xy, r, cl, seg.pattern)
        last = k + 1 == len(parts)
        gap = 0.0 if last else float(parts[k + 1][2].min() - s.max())
        run = 0.0 if last else float(abs(parts[k + 1][2][0] - s[-1]))
        plans.append(SegmentPlan(seg.params, s0, seg.length_mm, realised, float(s.min()), gap, run, notes, mirrored))
    return _wrap(cl, np.concatenate(s_all), np.concatenate(o_all), np.concatenate(role_all), tuple(plans),
                 tube=tube, options=options, name=name)


def _wrap(cl: Centerline, station_s, station_o, station_role, segs: tuple[SegmentPlan, ...], *, tube: Tube,
          options: StitchOptions, name: str) -> StitchPlan:
    """STOP, lock stitches, the stations, lock stitches, TRIM, END (the record convention of assemble)."""
    xy, commands, roles, actuator = frame_records(cl, station_s, station_o, station_role, np.array([1.0, -1.0]),
                                                  tube=tube, options=options)
    first = segs[0]
    act = ActuatorPlan(name, first.params, tube, cl, first.realised,
                       tuple(f"segment[{i}]: {note}" for i, s in enumerate(segs) for note in s.adjustments), options,
                       segs)
    return StitchPlan(xy, commands, roles, actuator, (act,), name)
