"""How a pattern kind's realised interval is read off its legs (:class:`embroact.patterns.kinds.Interval`).

Each function takes the legs' start and end points in the path frame (arc length ``sa``,
``sb`` and signed offset ``oa``, ``ob``, arrays [mm]; see :mod:`embroact.patterns.measure`)
and returns the realised interval [mm].

Examples
--------
>>> import numpy as np
>>> needle_interval_mm(np.array([0.0, 1.0]), np.zeros(2), np.array([1.0, 2.0]), np.zeros(2))
1.0
"""
from __future__ import annotations

import numpy as np

from .base.arrays import median
from .base.errors import PatternError
from .base.tolerances import DEFAULT_TOLERANCES

__all__ = ["needle_interval_mm", "family_interval_mm"]


def needle_interval_mm(sa, oa, sb, ob) -> float:
    """Mean axial advance of the legs [mm]: the spacing of consecutive needle points (zigzag).

    Parameters
    ----------
    sa, oa, sb, ob : ndarray
        Arc length and signed offset of each leg's start and end [mm].

    Returns
    -------
    float

    Examples
    --------
    >>> needle_interval_mm(np.array([0.0, 1.0]), np.zeros(2), np.array([1.0, 2.0]), np.zeros(2))
    1.0
    """
    return float(np.abs(sb - sa).mean())


def family_interval_mm(sa, oa, sb, ob) -> float:
    """Median spacing along the path of neighbouring parallel legs of one family [mm] (cross).

    A leg's position is where it crosses the centerline (``o = 0``); a family is the sign of
    its lean.

    Parameters
    ----------
    sa, oa, sb, ob : ndarray
        Arc length and signed offset of each leg's start and end [mm].

    Returns
    -------
    float

    Raises
    ------
    PatternError
        Fewer than two parallel legs in each family.

    Examples
    --------
    >>> sa, oa = np.array([0.0, 1.0, 7.0, 8.0]), np.array([3.5, 3.5, -3.5, -3.5])
    >>> family_interval_mm(sa, oa, sa + 7.0, -oa)
    1.0
    """
    ds, do = sb - sa, ob - oa
    crossing = sa - oa * ds / np.where(do != 0.0, do, 1.0)
    return _family_spacing(crossing, np.sign(ds * do))


def _family_spacing(pos: np.ndarray, family: np.ndarray) -> float:
    """Median spacing of neighbouring distinct leg positions within each family.

    The median, not the mean: a leg left out where two passes turn (see
    :mod:`embroact.patterns.cross`) must not bias the typical spacing.
    """
    gaps = []
    for f in (-1.0, 1.0):
        p = np.sort(pos[family == f])
        d = np.diff(p)
        gaps.append(d[d > DEFAULT_TOLERANCES.machine_grid_mm / 2.0])
    g = np.concatenate(gaps)
    if g.size == 0:
        raise PatternError("cannot measure the interval: fewer than two parallel legs in each family")
    return median(g)
