r"""Cross pattern: two families of straight legs at +alpha0 and -alpha0 from the perpendicular.

Construction. One *pass* is a zigzag whose legs lean by +-alpha0: each leg runs
from one rail to the other while advancing ``d = w tan(alpha0)`` along the path, so
within a pass each family has a leg every ``2 d``::

    L rail  o---------------o---------------o          o  needle point (always on a rail)
             \             / \             /           d = w tan(alpha0)
              \ +alpha0   /   \ -alpha0   /
    tube   ====\=========/=====\=========/=====        leg families:
                \       /       \       /                \  L -> R   (+alpha0)
    R rail       \     /         \     /                 /  R -> L   (-alpha0)
                  o---'           o---'
            |<--- d --->|<--- d --->|
            |<-------- 2 d -------->|   pitch of one family in one pass

``n = 2 d / s`` passes, pass ``j`` shifted by ``j * s`` along the path, give each
family a leg every ``s``. The machine sews them continuously: even passes forward,
odd passes backward, each joined to the next by a short EDGE stitch along a rail::

    pass 0  ----------------------------->  (forward)
                                          |  edge along a rail, ~s
    pass 1  <-----------------------------   (backward, shifted by s)
            |
    pass 2  ----------------------------->  (forward, shifted by 2 s) ...

    rail points of n = 3 passes (digit = pass):  L  0 1 2 0 1 2 0 1 2 0 ...  every s

Exact when ``n`` is an integer (the paper's w = 7 mm, s = 1.4 mm, alpha0 = 45 deg
gives n = 10). Otherwise ``n`` is rounded to the neighbouring integer (>= 1) that
needs the smaller relative change, and either the interval (``s' = 2 w tan(alpha0) / n``)
or the angle (``alpha0' = atan(n s / (2 w))``) is changed: ``adjust="interval"``,
``"angle"``, or ``"auto"`` (default: whichever relative change is smaller; the interval
on a tie). The change is reported in ``ActuatorPlan.adjustments`` and in the realised
values.

Ends. Legs are clipped to the embroidered span (the largest multiple of ``s`` that
fits the path, centred on it): a pass keeps exactly the legs whose two needle points
lie in the span. Where a pass would end on the other rail than the one the next pass
starts on, one leg at that turn is left out (the one that leaves the shorter edge
stitch; it always lies within ``2 w tan(alpha0)`` of the span end). :func:`cross_layout` places
the stations on a stretch of the path (the whole path, or one segment's share of it); lock
stitches and STOP/TRIM/END follow :mod:`embroact.patterns.assemble`.

Examples
--------
>>> from embroact.patterns.cross import cross
>>> from embroact.patterns.centerline import Centerline
>>> from embroact.patterns.params import CrossParams
>>> plan = cross(Centerline.straight(100.0), CrossParams(width_mm=7.0, interval_mm=1.4, angle_deg=45.0))
>>> a = plan.actuators[0]
>>> a.realised.passes, round(a.realised.interval_mm, 9), round(a.realised.angle_deg, 9), a.adjustments
(10, 1.4, 45.0, ())
>>> p30 = CrossParams(width_mm=7.0, interval_mm=1.4, angle_deg=30.0)   # 2 w tan(30 deg) / s = 5.77
>>> cross(Centerline.straight(100.0), p30).actuators[0].adjustments
('angle_deg 30 -> 30.96 (6 passes)',)
>>> cross(Centerline.straight(100.0), p30, adjust="interval").actuators[0].adjustments
('interval_mm 1.4 -> 1.347 (6 passes)',)
"""
from __future__ import annotations

import math

import numpy as np

from .assemble import Layout, check_record_count, rail_positions
from .centerline import Centerline
from .base.errors import ParameterError, PatternError
from .params import ADJUST_METHODS, CrossParams, StitchOptions, Tube, whole_intervals
from .plan import Role, StitchPlan
from .segments import chain_of_one
from .base.tolerances import DEFAULT_TOLERANCES

__all__ = ["cross", "cross_layout", "cross_stations", "cross_realised_params", "cross_min_length_mm", "closing", "ADJUST_METHODS", "MAX_EDGE_STITCH_MM"]

#: Longest single EDGE stitch between passes, measured along its rail [mm]; longer edges are split.
MAX_EDGE_STITCH_MM = 3.0
#: Passes closer to an integer than this (relative) count as exact.
_EXACT_REL = 1e-9


def closing(params: CrossParams, adjust: str = "auto") -> tuple[int, float, float, str]:
    """Number of passes and the (possibly adjusted) interval and angle that close the pattern.

    Parameters
    ----------
    params : CrossParams
        The requested pattern.
    adjust : {"auto", "interval", "angle"}, optional
        What may change to close it: the interval, the angle, or whichever changes less ("auto").

    Returns
    -------
    passes, interval_mm, angle_deg, note
        ``note`` is ``""`` when nothing changed, else e.g. ``"interval_mm 1.4 -> 1.25 (3 passes)"``.

    Examples
    --------
    >>> from embroact.patterns.params import CrossParams
    >>> closing(CrossParams(7.0, 1.4, 45.0))
    (10, 1.4, 45.0, '')
    >>> n, s, a, note = closing(CrossParams(7.0, 1.4, 30.0), adjust="angle")
    >>> n, round(a, 4), note
    (6, 30.9638, 'angle_deg 30 -> 30.96 (6 passes)')
    """
    if adjust not in ADJUST_METHODS:
        raise ParameterError(f"adjust must be one of {', '.join(map(repr, ADJUST_METHODS))}, got {adjust!r}")
    w, s, a = params.width_mm, params.interval_mm, params.angle_deg
    ratio = 2.0 * w * math.tan(math.radians(a)) / s
    if not math.isfinite(ratio):  # a subnormal interval: no number of passes exists
        raise ParameterError(f"interval_mm is too small to close the cross pattern (2*w*tan(angle)/interval_mm "
                             f"overflows), got {s:g}")
    if abs(ratio - round(ratio)) <= _EXACT_REL * ratio and round(ratio) >= 1:
        return round(ratio), s, a, ""
    options = []
    for n in {max(1, math.floor(ratio)), max(1, math.ceil(ratio))}:
        s_new = 2.0 * w * math.tan(math.radians(a)) / n
        a_new = math.degrees(math.atan(n * s / (2.0 * w)))
        options.append((abs(s_new - s) / s, 0, n, s_new, a, f"interval_mm {s:g} -> {s_new:.4g} ({n} passes)"))
        options.append((abs(a_new - a) / a, 1, n, s, a_new, f"angle_deg {a:g} -> {a_new:.4g} ({n} passes)"))
    kind = {"auto": (0, 1), "interval": (0,), "angle": (1,)}[adjust]
    _, _, n, s_new, a_new, note = min(o for o in options if o[1] in kind)
    return n, s_new, a_new, note


def _trim_turn(prev: tuple, nxt: tuple) -> tuple[tuple, tuple]:
    """Make ``prev`` end on the rail ``nxt`` starts on by leaving out one leg at the turn."""
    (pp, ps), (np_, ns) = prev, nxt
    if ps[-1] == ns[0]:
        return prev, nxt
    drop_prev = abs(pp[-2] - np_[0]) if len(pp) > 2 else math.inf
    drop_next = abs(pp[-1] - np_[1]) if len(np_) > 2 else math.inf
    if drop_prev <= drop_next:
        return (pp[:-1], ps[:-1]), nxt
    return prev, (np_[1:], ns[1:])


def cross_stations(length_mm: float, params: CrossParams, adjust: str = "auto") -> float:
    """Upper bound of the needle stations (legs and edge stitches) of a cross pattern (no allocation).

    Parameters
    ----------
    length_mm : float
        Path length [mm].
    params : CrossParams
        The requested pattern.
    adjust : {"auto", "interval", "angle"}, optional
        How the pattern is closed (:func:`closing`).

    Returns
    -------
    float
        The bound (not rounded).

    Examples
    --------
    >>> round(cross_stations(100.0, CrossParams(7.0, 1.4, 45.0)))
    171
    """
    n, s, _, _ = closing(params, adjust)
    span = whole_intervals(length_mm, s) * s
    return 2.0 * span / s + n * (2.0 + 2.0 * s / MAX_EDGE_STITCH_MM)  # an outer rail is at most 2x as long


def cross_min_length_mm(params: CrossParams) -> float:
    """Shortest legs span of a cross of ``params`` as given (closed): two leg pitches, ``4 w tan(alpha0)`` [mm].

    Parameters
    ----------
    params : CrossParams
        The pattern, as the generator sews it.

    Returns
    -------
    float
        The span [mm].

    Examples
    --------
    >>> round(cross_min_length_mm(CrossParams(7.0, 1.4, 45.0)), 9)
    28.0
    """
    return 4.0 * params.width_mm * math.tan(math.radians(params.angle_deg))


def cross_realised_params(params: CrossParams, adjust: str = "auto") -> CrossParams:
    """The parameters the generator uses: interval or angle adjusted so the pattern closes (:func:`closing`).

    Parameters
    ----------
    params : CrossParams
        The requested pattern.
    adjust : {"auto", "interval", "angle"}, optional
        What may change (:func:`closing`).

    Returns
    -------
    CrossParams
        The closed pattern's parameters.

    Examples
    --------
    >>> round(cross_realised_params(CrossParams(7.0, 1.4, 30.0), adjust="angle").angle_deg, 4)
    30.9638
    """
    _, s, alpha, _ = closing(params, adjust)
    return CrossParams(params.width_mm, s, alpha)


def cross_layout(cl: Centerline, params: CrossParams, start_mm: float, length_mm: float, *,
                 options: StitchOptions = StitchOptions(), adjust: str = "auto") -> Layout:
    """The cross pattern's needle stations on ``[start_mm, start_mm + length_mm]`` of ``cl`` (module docstring).

    Parameters
    ----------
    cl : Centerline
        The actuator's path (the edge stitches follow its rails).
    params : CrossParams
    start_mm, length_mm : float
        Where the stretch starts along ``cl`` and how long it is [mm].
    options : StitchOptions
        Lock stitches (the stretch holds at least one).
    adjust : {"auto", "interval", "angle"}
        What may change to close the pattern (:func:`closing`).

    Returns
    -------
    Layout
        Its ``adjustments`` name the change :func:`closing` made, if any.

    Raises
    ------
    PatternError
        Stretch shorter than ``4 w tan(alpha0)`` or ``tie_stitch_mm``, or too many records.

    Examples
    --------
    >>> lay = cross_layout(Centerline.straight(100.0), CrossParams(7.0, 1.4, 30.0), 0.0, 100.0)
    >>> len(lay.s_mm), lay.adjustments
    (143, ('angle_deg 30 -> 30.96 (6 passes)',))
    """
    n, s, alpha, note = closing(params, adjust)
    d = n * s / 2.0  # = w tan(alpha), exactly closing
    minimum = max(4.0 * d, options.tie_stitch_mm)
    tol = DEFAULT_TOLERANCES.length_mm
    if length_mm < minimum - tol:
        raise PatternError(
            f"path length_mm must be >= {minimum:.4g} for a cross pattern with width_mm={params.width_mm:g}, "
            f"angle_deg={alpha:.4g} (4*w*tan(angle), two leg pitches, and >= tie_stitch_mm), got {length_mm:g}"
        )
    span = whole_intervals(length_mm, s) * s
    check_record_count(cross_stations(length_mm, params, adjust), options)
    start = start_mm + 0.5 * (length_mm - span)
    passes = []
    for j in range(n):
        k = np.arange(math.ceil(-j * s / d - tol / d), math.floor((span - j * s) / d + tol / d) + 1)
        pos, side = start + j * s + k * d, np.where(k % 2 == 0, 1, -1)
        passes.append((pos[::-1], side[::-1]) if j % 2 else (pos, side))
    for j in range(n - 1):
        passes[j], passes[j + 1] = _trim_turn(passes[j], passes[j + 1])
    station_s, station_side, station_role = [passes[0][0]], [passes[0][1]], [np.full(len(passes[0][0]), Role.LEG)]
    for (pp, _), (pos, side) in zip(passes[:-1], passes[1:]):
        run = rail_positions(cl, pp[-1], pos[0], side[0] * params.width_mm / 2.0, MAX_EDGE_STITCH_MM)
        station_s += [run[:-1], pos]
        station_side += [np.full(len(run) - 1, side[0]), side]
        station_role += [np.full(len(run), Role.EDGE), np.full(len(pos) - 1, Role.LEG)]
    return Layout(np.concatenate(station_s), np.concatenate(station_side), np.concatenate(station_role),
                  (note,) if note else ())


def cross(
    centerline,
    params: CrossParams,
    *,
    tube: Tube = Tube(),
    options: StitchOptions = StitchOptions(),
    name: str = "actuator",
    adjust: str = "auto",
) -> StitchPlan:
    """One cross-pattern actuator along ``centerline``, as a complete plan (a chain of one segment).

    Parameters
    ----------
    centerline : Centerline, shapely LineString, (n, 2) points or SVG path string
    params : CrossParams
        Width w (w/2 > r_f + clearance), interval s between parallel legs, angle alpha0.
    tube : Tube
    options : StitchOptions
    name : str
    adjust : {"auto", "interval", "angle"}
        What may change when ``2 w tan(alpha0) / s`` is not an integer (see the module docstring).

    Raises
    ------
    ParameterError, PathError, PatternError
        As for :func:`embroact.patterns.zigzag.zigzag`; the minimum path length is
        ``4 w tan(alpha0)`` (two leg pitches of each family) and at least ``tie_stitch_mm``.

    Returns
    -------
    StitchPlan
        One :class:`ActuatorPlan`; its ``realised`` parameters say what the pattern closed with.

    Examples
    --------
    >>> from embroact.patterns.centerline import Centerline
    >>> plan = cross(Centerline.straight(100.0), CrossParams(width_mm=7.0, interval_mm=1.4, angle_deg=45.0))
    >>> r = plan.actuators[0].realised
    >>> plan.stitch_count, round(r.interval_mm, 3), round(r.angle_deg, 3)
    (148, 1.4, 45.0)
    """
    if not isinstance(params, CrossParams):
        raise ParameterError(f"params must be CrossParams, got {type(params).__name__}")
    return chain_of_one(centerline, params, tube=tube, options=options, name=name, adjust=adjust)
