"""Zigzag pattern: legs cross the tube alternately from rail to rail.

Needle points sit at arc lengths ``s_i = s0 + i*s`` along the centerline,
alternately on the left and right rail ``c(s_i) +- (w/2) n(s_i)``; the legs are
centred on the path (``s0 = (L - n*s) / 2``, ``n = floor(L / s)``)::

    left rail   o---------o---------o---------o          o  needle point
                 \\       / \\       / \\       /           -- rail (w/2 from the path)
    centerline  ==\\=====/===\\=====/===\\=====/=== tube
                   \\   /     \\   /     \\   /
    right rail      o-/       o-/       o-/
                  |<-s->|
                  s0 + 0 s,  s0 + 1 s, ...

Each leg leans by ``atan(s / w)`` from the local perpendicular (its "angle" in the
realised values). :func:`zigzag_layout` places the stations on a stretch of the path (the
whole path, or one segment's share of it); lock stitches, STOP, TRIM and END follow the
record convention of :mod:`embroact.patterns.assemble`.

Examples
--------
>>> from embroact.patterns.zigzag import zigzag
>>> from embroact.patterns.centerline import Centerline
>>> from embroact.patterns.params import ZigzagParams
>>> plan = zigzag(Centerline.straight(100.0), ZigzagParams(width_mm=7.0, interval_mm=1.0))
>>> r = plan.actuators[0].realised
>>> round(r.width_mm, 9), round(r.interval_mm, 9), round(r.length_mm, 9)
(7.0, 1.0, 100.0)
>>> plan.stitch_count   # 101 needle stations + 2 * 3 lock stitches, first station shared
106
"""
from __future__ import annotations

import numpy as np

from .assemble import Layout, check_record_count
from .centerline import Centerline
from .base.errors import ParameterError, PatternError
from .params import StitchOptions, Tube, ZigzagParams, whole_intervals
from .plan import Role, StitchPlan
from .segments import chain_of_one
from .base.tolerances import DEFAULT_TOLERANCES

__all__ = ["zigzag", "zigzag_layout", "zigzag_stations", "zigzag_realised_params", "MIN_LEGS"]

#: Fewest legs a zigzag actuator may have.
MIN_LEGS = 2


def zigzag_stations(length_mm: float, params: ZigzagParams) -> int:
    """Needle stations a zigzag of ``params`` has on a path of ``length_mm`` (no allocation).

    Parameters
    ----------
    length_mm : float
        Path length [mm].
    params : ZigzagParams
        The pattern.

    Returns
    -------
    int
        One station per whole interval, plus the first.

    Examples
    --------
    >>> zigzag_stations(100.0, ZigzagParams(width_mm=7.0, interval_mm=1.0))
    101
    """
    return whole_intervals(length_mm, params.interval_mm) + 1


def zigzag_realised_params(params: ZigzagParams) -> ZigzagParams:
    """The parameters the generator uses: a zigzag realises its request as given.

    Parameters
    ----------
    params : ZigzagParams
        The requested pattern.

    Returns
    -------
    ZigzagParams
        ``params`` itself.

    Examples
    --------
    >>> zigzag_realised_params(ZigzagParams(7.0, 1.0))
    ZigzagParams(width_mm=7.0, interval_mm=1.0)
    """
    return params


def zigzag_layout(cl: Centerline, params: ZigzagParams, start_mm: float, length_mm: float, *,
                  options: StitchOptions = StitchOptions()) -> Layout:
    """The zigzag's needle stations on ``[start_mm, start_mm + length_mm]`` of ``cl``, legs centred there.

    Parameters
    ----------
    cl : Centerline
        The actuator's path.
    params : ZigzagParams
    start_mm, length_mm : float
        Where the stretch starts along ``cl`` and how long it is [mm].
    options : StitchOptions
        Lock stitches (the stretch holds at least one).

    Returns
    -------
    Layout

    Raises
    ------
    PatternError
        Stretch shorter than ``MIN_LEGS`` legs, or too many records.

    Examples
    --------
    >>> lay = zigzag_layout(Centerline.straight(10.0), ZigzagParams(7.0, 1.0), 2.0, 4.5)
    >>> lay.s_mm.tolist(), lay.side.tolist()
    ([2.25, 3.25, 4.25, 5.25, 6.25], [1, -1, 1, -1, 1])
    """
    s = params.interval_mm
    minimum = max(MIN_LEGS * s, options.tie_stitch_mm)
    if length_mm < minimum - DEFAULT_TOLERANCES.length_mm:
        raise PatternError(
            f"path length_mm must be >= {minimum:g} for a zigzag with interval_mm={s:g} "
            f"(at least {MIN_LEGS} legs), got {length_mm:g}"
        )
    n = zigzag_stations(length_mm, params) - 1
    check_record_count(n + 1, options)
    i = np.arange(n + 1)
    return Layout(start_mm + (0.5 * max(length_mm - n * s, 0.0) + i * s), np.where(i % 2 == 0, 1, -1),
                  np.full(n + 1, Role.LEG))


def zigzag(
    centerline,
    params: ZigzagParams,
    *,
    tube: Tube = Tube(),
    options: StitchOptions = StitchOptions(),
    name: str = "actuator",
) -> StitchPlan:
    """One zigzag actuator along ``centerline``, as a complete plan (a chain of one segment).

    Parameters
    ----------
    centerline : Centerline, shapely LineString, (n, 2) points or SVG path string
        The tube path [mm]; the legs cover its length.
    params : ZigzagParams
        Rail spacing ``width_mm`` (w/2 > r_f + clearance) and interval ``interval_mm``.
    tube : Tube
    options : StitchOptions
        Lock stitches.
    name : str
        Actuator name.

    Raises
    ------
    ParameterError
        Width leaves no room for the tube, interval below the machine grid.
    PathError
        Path bends tighter than w/2, crosses itself, or comes back into the corridor.
    PatternError
        Path shorter than ``MIN_LEGS`` legs, or too many records.

    Returns
    -------
    StitchPlan
        Tie-in, legs, tie-off, then the STOP/TRIM/END records; one :class:`ActuatorPlan`.

    Examples
    --------
    >>> from embroact.patterns.centerline import Centerline
    >>> plan = zigzag(Centerline.straight(50.0), ZigzagParams(width_mm=7.0, interval_mm=1.0), name="Z1")
    >>> plan.actuators[0].name, plan.stitch_count, round(plan.actuators[0].realised.length_mm, 6)
    ('Z1', 56, 50.0)
    """
    if not isinstance(params, ZigzagParams):
        raise ParameterError(f"params must be ZigzagParams, got {type(params).__name__}")
    return chain_of_one(centerline, params, tube=tube, options=options, name=name)
