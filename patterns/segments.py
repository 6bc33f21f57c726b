"""Segmented actuators: one tube, one actuator, the pattern changing along the path.

An actuator may hold consecutive segments ``k = 1..n`` along its path, each with its own
pattern kind, parameters and length (docs/model.md, segmented actuators: segments in
series decouple, each bends with its own uniform curvature). The machine sews them in one
run: one cord-in STOP, one set of lock stitches at each end, one TRIM.

Construction. Segment ``k`` covers ``[S_k, S_k + L_k]`` of the path (``S_k`` the sum of the
lengths before it). Its kind's layout (:class:`~embroact.patterns.assemble.Layout`) puts its
needle stations on that stretch of the real path (legs centred in it, as for a single
actuator, which is a chain of one segment over the whole path) at arc length ``s`` and offset
``side * w_k / 2``; every needle point goes onto the machine grid once. A segment is mirrored
(every offset negated, the same pattern started on the other rail) when its first needle point
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
measured on its own needle points in the plan.

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
from dataclasses import dataclass, replace

import numpy as np

from .assemble import check_pattern_inputs, check_record_count, frame_records, inward
from .base.errors import EmbroactError, ParameterError
from .centerline import Centerline, as_centerline
from .chain import Chain
from .kinds import PATTERN_KINDS, KindFields, pattern_kind
from .measure import measure
from .params import PatternParams, StitchOptions, Tube
from .plan import ActuatorPlan, Realised, Role, SegmentPlan, StitchPlan

__all__ = ["SegmentSpec", "SegmentPlan", "segmented", "chain_of_one", "check_segments", "chain_records", "pattern_parts",
           "MAX_TRANSITION_STITCH_MM", "LENGTH_MATCH_MM"]

#: Longest stitch of a transition between segments, along the path [mm].
MAX_TRANSITION_STITCH_MM = 3.0
#: The segments' lengths must add up to the path's length within this [mm].
LENGTH_MATCH_MM = 0.05


@dataclass(frozen=True, slots=True)
class SegmentSpec(KindFields):
    """One segment of an actuator's chain, as asked for (a single-pattern actuator: one over its whole path).

    Parameters
    ----------
    params : PatternParams
        Its pattern.
    length_mm : float
        Length of the path the segment covers [mm], > 0.
    adjust : str
        Cross only: what may change to close the pattern (``"auto"``, ``"interval"``, ``"angle"``).

    Examples
    --------
    >>> from embroact.patterns.params import ZigzagParams
    >>> SegmentSpec(ZigzagParams(7.0, 1.0), 30.0)
    SegmentSpec(params=ZigzagParams(width_mm=7.0, interval_mm=1.0), length_mm=30.0, adjust='auto')
    """

    params: PatternParams
    length_mm: float
    adjust: str = "auto"

    def __post_init__(self) -> None:
        PATTERN_KINDS.for_params(self.params)
        if isinstance(self.length_mm, bool) or not isinstance(self.length_mm, (int, float)) \
                or not 0.0 < self.length_mm < math.inf:
            raise ParameterError(f"length_mm must be a finite number > 0 mm, got {self.length_mm!r}")
        object.__setattr__(self, "length_mm", float(self.length_mm))


def pattern_parts(act: ActuatorPlan) -> tuple[tuple[str, PatternParams, Realised], ...]:
    """``(label, requested parameters, realised)`` of each segment of an actuator's chain.

    Rules comparing the request with what was sewn loop over these; ``label`` is the chain's
    message prefix (:meth:`~embroact.patterns.chain.Chain.label`: ``""`` in a chain of one).

    Parameters
    ----------
    act : ActuatorPlan
        A generated actuator.

    Returns
    -------
    tuple of (str, PatternParams, Realised)

    Examples
    --------
    >>> from embroact.patterns.params import ZigzagParams
    >>> segs = (SegmentSpec(ZigzagParams(7.0, 1.0), 30.0), SegmentSpec(ZigzagParams(9.0, 1.0), 30.0))
    >>> act = segmented(Centerline.straight(60.0), segs).actuators[0]
    >>> [(label, p.width_mm, round(r.width_mm, 6)) for label, p, r in pattern_parts(act)]
    [('segment 0: ', 7.0, 7.0), ('segment 1: ', 9.0, 9.0)]
    >>> one = segmented(Centerline.straight(60.0), [SegmentSpec(ZigzagParams(7.0, 1.0), 60.0)]).actuators[0]
    >>> [label for label, _, _ in pattern_parts(one)]
    ['']
    """
    return tuple((act.segments.label(k), seg.params, seg.realised) for k, seg in enumerate(act.segments))


def check_segments(cl: Centerline, segments) -> tuple[SegmentSpec, ...]:
    """``segments`` as a tuple if it is a non-empty sequence of :class:`SegmentSpec` whose lengths
    add up to the path's within ``LENGTH_MATCH_MM``; :class:`ParameterError` otherwise.

    Parameters
    ----------
    cl : Centerline
        The path.
    segments : sequence of SegmentSpec
        The chain.

    Returns
    -------
    tuple of SegmentSpec

    Examples
    --------
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


def chain_records(cl: Centerline, segments, tube: Tube = Tube(), options: StitchOptions = StitchOptions()) -> int:
    """Records an actuator of this chain will need, from its parameters alone (no allocation).

    Each segment's own input checks run first (a degenerate interval or width is reported as
    such, prefixed as :func:`segmented` prefixes it); then the upper bound of every segment's
    stations and of the transition runs between segments is held against the record cap.

    Parameters
    ----------
    cl : Centerline
    segments : sequence of SegmentSpec
    tube : Tube
    options : StitchOptions

    Returns
    -------
    int
        The bound (:func:`~embroact.patterns.assemble.check_record_count`).

    Raises
    ------
    ParameterError, PathError, PatternError
        A segment's inputs refused, or more records than the cap.

    Examples
    --------
    >>> from embroact.patterns.params import ZigzagParams
    >>> seg = SegmentSpec(ZigzagParams(7.0, 1.0), 50.0)
    >>> chain_records(Centerline.straight(50.0), [seg]), chain_records(Centerline.straight(100.0), [seg] * 2)
    (59, 135)
    """
    segs = Chain(segments)
    total = 0.0
    for k, seg in enumerate(segs):
        kind = pattern_kind(seg.pattern)
        try:
            check_pattern_inputs(cl, kind.realised_params(seg.params, **seg.kind_options), tube, options)
        except EmbroactError as exc:
            raise type(exc)(f"{segs.where(k)}{exc}") from None
        total += kind.stations(seg.length_mm, seg.params, **seg.kind_options)
    total += sum(seg.length_mm / MAX_TRANSITION_STITCH_MM + 8 for seg in segs[:-1])  # the transition runs
    return check_record_count(math.ceil(total), options)


def segmented(centerline, segments, *, tube: Tube = Tube(), options: StitchOptions = StitchOptions(),
              name: str = "actuator") -> StitchPlan:
    """One actuator along ``centerline`` from its chain of segments, as a complete plan (see the module docstring).

    The one generator of every actuator: a single-pattern one is a chain of one segment over
    the whole path (:func:`chain_of_one`).

    Parameters
    ----------
    centerline : Centerline or anything :func:`as_centerline` takes
        The path.
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
        As the layouts, the message prefixed with ``segment[k]: `` in a chain of more than one.

    Examples
    --------
    >>> from embroact.patterns.params import ZigzagParams
    >>> segs = [SegmentSpec(ZigzagParams(7.0, 1.0), 30.0), SegmentSpec(ZigzagParams(9.0, 1.0), 30.0)]
    >>> act = segmented(Centerline.straight(60.0), segs, name="S").actuators[0]
    >>> [round(s.realised.width_mm, 3) for s in act.segments]
    [7.0, 9.0]
    """
    cl = as_centerline(centerline)
    segs = Chain(check_segments(cl, segments))
    s_all: list[np.ndarray] = []
    o_all: list[np.ndarray] = []
    role_all: list[np.ndarray] = []
    parts = []
    start = 0.0
    for k, seg in enumerate(segs):
        kind = pattern_kind(seg.pattern)
        try:
            check_pattern_inputs(cl, kind.realised_params(seg.params, **seg.kind_options), tube, options)
            lay = kind.layout(cl, seg.params, start, seg.length_mm, options=options, **seg.kind_options)
        except EmbroactError as exc:
            raise type(exc)(f"{segs.where(k)}{exc}") from None
        s, o, roles = lay.s_mm, lay.side * (seg.params.width_mm / 2.0), lay.roles
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
        parts.append((seg, start, s, sum(map(len, s_all)), lay.adjustments, mirrored))
        s_all.append(s)
        o_all.append(o)
        role_all.append(roles)
        start += seg.length_mm
    station_s, station_role = np.concatenate(s_all), np.concatenate(role_all)
    xy, commands, roles, actuator = frame_records(cl, station_s, np.concatenate(o_all), station_role,
                                                  inward(cl, float(station_s[0]), float(station_s[-1])), tube=tube,
                                                  options=options)
    at = [(options.tie_count + first, options.tie_count + first + len(s)) for _, _, s, first, _, _ in parts]
    plans = [_segment_plan(cl, xy[i:j], station_role[i - options.tie_count:j - options.tie_count], seg, s0, notes,
                           mirrored) for (i, j), (seg, s0, _, _, notes, mirrored) in zip(at, parts)]
    ends, _ = cl.project(xy[[k for i, j in at for k in (i, j - 1)]])  # each segment's first and last needle point
    plans = [replace(p, transition_mm=b.first_leg_mm - (p.first_leg_mm + p.realised.length_mm),
                     join_run_mm=float(abs(ends[2 * k + 2] - ends[2 * k + 1])))
             for k, (p, b) in enumerate(zip(plans, plans[1:]))] + plans[-1:]
    chain = Chain(plans)
    # a chain of one is the actuator's own values over its whole path, made again when the path moves
    # (embroact.patterns.origin.to_machine_frame): the plan holds it as ActuatorPlan makes it
    act = ActuatorPlan(name, chain[0].params, tube, cl, chain[0].realised,
                       tuple(f"{chain.where(i)}{note}" for i, p in enumerate(chain) for note in p.adjustments), options,
                       chain.one_or_all((), chain))
    return StitchPlan(xy, commands, roles, actuator, (act,), name)


def chain_of_one(centerline, params: PatternParams, *, tube: Tube = Tube(), options: StitchOptions = StitchOptions(),
                 name: str = "actuator", **kind_options) -> StitchPlan:
    """One single-pattern actuator along ``centerline``: a chain of one segment over the whole path.

    Parameters
    ----------
    centerline : Centerline or anything :func:`as_centerline` takes
    params : PatternParams
        Any registered kind's parameters.
    tube, options, name
        As for :func:`segmented`.
    **kind_options
        The kind's generator options (``adjust`` for the cross pattern).

    Returns
    -------
    StitchPlan
        One actuator (:func:`segmented`).

    Examples
    --------
    >>> from embroact.patterns.params import ZigzagParams
    >>> plan = chain_of_one([(0, 0), (50, 0)], ZigzagParams(7.0, 1.0), name="Z")
    >>> plan.actuators[0].name, plan.stitch_count, len(plan.actuators[0].segments)
    ('Z', 56, 1)
    """
    cl = as_centerline(centerline)
    return segmented(cl, (SegmentSpec(params, cl.length_mm, **kind_options),), tube=tube, options=options, name=name)


def _segment_plan(cl: Centerline, xy, station_roles, seg: SegmentSpec, start_mm: float, notes: tuple[str, ...],
                  mirrored: bool) -> SegmentPlan:
    """A segment as generated, measured on its needle points in the plan (:func:`segmented` then sets the
    transition to the next segment and the thread's run there)."""
    r = np.array(station_roles)
    r[0] = Role.TIE_IN  # the segment's first point starts its first leg
    realised = measure(xy, r, cl, seg.pattern)
    return SegmentPlan(seg.params, start_mm, seg.length_mm, realised, 0.0, 0.0, notes, mirrored)
