"""Measure the pattern parameters a set of needle points actually realises.

Works in the path frame of :meth:`Centerline.project`: arc length ``s`` along the
centerline and signed offset ``o`` (left > 0). A *leg* is the stitch arriving at a
record whose role is LEG, from the record before it.

- width: rail spacing, ``2 * mean |o|`` over leg end points;
- angle: mean ``atan(|ds| / |do|)`` of the legs, i.e. the angle from the local
  perpendicular (zigzag: its small lean ``atan(s / w)``; cross: alpha0);
- interval: zigzag, mean ``|ds|`` of the legs (axial spacing of consecutive needle
  points); cross, median spacing along the path between neighbouring parallel legs
  of one family (a leg's position is where it crosses the centerline, ``o = 0``);
- length: axial extent of all leg end points; passes: runs of legs advancing the
  same way along the path.

Examples
--------
>>> import numpy as np
>>> from embroact.patterns.centerline import Centerline
>>> from embroact.patterns.measure import measure
>>> from embroact.patterns.plan import Role
>>> xy = [[0.0, 3.5], [1.0, -3.5], [2.0, 3.5], [3.0, -3.5]]
>>> r = measure(xy, [Role.TIE_IN, Role.LEG, Role.LEG, Role.LEG], Centerline.straight(4.0), "zigzag")
>>> r.width_mm, r.interval_mm, round(r.angle_deg, 4), r.length_mm, r.passes
(7.0, 1.0, 8.1301, 3.0, 1)
"""
from __future__ import annotations

import numpy as np

from .centerline import as_centerline
from .base.errors import PatternError
from .kinds import pattern_kind
from .limits import GRID_ROUNDING_MM
from .plan import Realised, Role

__all__ = ["measure"]


def measure(xy_mm, roles, centerline, pattern: str) -> Realised:
    """Realised width, interval, angle, length and passes of the LEG stitches.

    Parameters
    ----------
    xy_mm : array (n, 2)
        Needle points in sewing order [mm].
    roles : array (n,)
        :class:`Role` per point; legs arrive at ``Role.LEG`` points.
    centerline : Centerline or anything :func:`as_centerline` takes
        The path the legs were sewn along.
    pattern : str
        A registered pattern kind (its :attr:`~embroact.patterns.kinds.PatternKind.interval`
        measures the interval).

    Returns
    -------
    Realised
        Width, interval, angle and length [mm, deg], passes and where the legs start [mm].

    Raises
    ------
    PatternError
        No record is a leg.

    Examples
    --------
    >>> from embroact.patterns.plan import Role
    >>> xy = [[0.0, 3.5], [1.0, -3.5], [2.0, 3.5]]
    >>> r = measure(xy, [Role.TIE_IN, Role.LEG, Role.LEG], [[0.0, 0.0], [2.0, 0.0]], "zigzag")
    >>> r.width_mm, r.interval_mm, r.length_mm, r.passes
    (7.0, 1.0, 2.0, 1)
    """
    pattern_kind(pattern)  # a registered kind, else one line naming them
    cl = as_centerline(centerline)
    xy = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
    ends = np.flatnonzero(np.asarray(roles) == Role.LEG)
    ends = ends[ends > 0]
    if ends.size == 0:
        raise PatternError("cannot measure a pattern without legs")
    s, o = cl.project(xy)
    sa, oa, sb, ob = s[ends - 1], o[ends - 1], s[ends], o[ends]
    ds, do = sb - sa, ob - oa
    pts = np.zeros(len(xy), dtype=bool)  # both ends of every leg (a mask: np.union1d would load numpy.ma)
    pts[ends - 1] = pts[ends] = True
    angle = float(np.degrees(np.arctan2(np.abs(ds), np.abs(do))).mean())
    direction = np.sign(ds[np.abs(ds) > 2.0 * GRID_ROUNDING_MM])  # a shorter step may be the grid's, not the leg's
    passes = 1 + int(np.count_nonzero(np.diff(direction)))
    interval = float(pattern_kind(pattern).interval(sa, oa, sb, ob))
    return Realised(
        width_mm=float(2.0 * np.abs(o[pts]).mean()),
        interval_mm=interval,
        angle_deg=angle,
        length_mm=float(s[pts].max() - s[pts].min()),
        passes=passes,
        start_mm=float(s[pts].min()),
    )
