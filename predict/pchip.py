"""Monotone piecewise-cubic interpolation (PCHIP) through calibrated points.

A calibration holds G and P0 at a few design coordinates (zigzag widths, cross angles);
between them the lookup needs a value that

* is the calibrated one at a calibrated point,
* varies continuously, with a continuous slope, along the coordinate (a predicted bend
  must not jump when a width moves by a micrometre), and
* is monotone between two points where the data are (no overshoot above the larger of
  two neighbouring values, no invented extremum between them).

The Fritsch-Carlson construction does this: a cubic Hermite piece per interval whose end
slopes are the weighted harmonic mean of the neighbouring secants where those have one
sign, and zero where the data turn (a local extremum sits on a calibrated point). The end
slopes use the non-centred three-point formula, limited the same way. Two points give the
straight line through them.

Examples
--------
>>> from embroact.predict.pchip import pchip
>>> xs, ys = [5.0, 7.0, 9.0], [0.8, 2.7, 3.4]
>>> [round(pchip(xs, ys, x), 6) for x in (5.0, 7.0, 9.0)]
[0.8, 2.7, 3.4]
>>> 0.8 < pchip(xs, ys, 6.0) < 2.7 < pchip(xs, ys, 8.0) < 3.4
True
>>> pchip([1.0, 2.0], [10.0, 20.0], 1.25)
12.5
"""
from __future__ import annotations

import math
from bisect import bisect_right
from typing import Sequence

__all__ = ["pchip", "pchip_slopes"]


def _end_slope(h0: float, h1: float, d0: float, d1: float) -> float:
    """Three-point end slope, limited so the end piece stays monotone (Fritsch-Carlson)."""
    m = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1)
    if math.copysign(1.0, m) != math.copysign(1.0, d0) or d0 == 0.0:
        return 0.0
    if math.copysign(1.0, d0) != math.copysign(1.0, d1) and abs(m) > abs(3.0 * d0):
        return 3.0 * d0
    return m


def pchip_slopes(xs: Sequence[float], ys: Sequence[float]) -> list[float]:
    """Slope of the interpolant at each point.

    Parameters
    ----------
    xs : sequence of float
        Strictly increasing coordinates, at least two.
    ys : sequence of float
        Values at ``xs``.

    Returns
    -------
    list of float

    Examples
    --------
    >>> pchip_slopes([0.0, 1.0, 2.0], [0.0, 1.0, 0.0])   # a turn: flat at the middle point
    [2.0, 0.0, -2.0]
    """
    h = [b - a for a, b in zip(xs, xs[1:])]
    d = [(y1 - y0) / hk for y0, y1, hk in zip(ys, ys[1:], h)]
    if len(d) == 1:
        return [d[0], d[0]]
    m = [0.0] * len(xs)
    for k in range(1, len(xs) - 1):
        a, b = d[k - 1], d[k]
        if a * b > 0.0:
            w1, w2 = 2.0 * h[k] + h[k - 1], h[k] + 2.0 * h[k - 1]
            m[k] = (w1 + w2) / (w1 / a + w2 / b)
    m[0] = _end_slope(h[0], h[1], d[0], d[1])
    m[-1] = _end_slope(h[-1], h[-2], d[-1], d[-2])
    return m


def pchip(xs: Sequence[float], ys: Sequence[float], x: float, *, slopes: Sequence[float] | None = None) -> float:
    """The interpolant through ``(xs, ys)`` at ``x`` (``xs[0] <= x <= xs[-1]``; ends extend as cubics).

    Parameters
    ----------
    xs : sequence of float
        Strictly increasing coordinates, at least one.
    ys : sequence of float
        Values at ``xs``.
    x : float
        Where to evaluate.
    slopes : sequence of float or None, optional
        :func:`pchip_slopes` of ``(xs, ys)``, when the caller keeps them (many values through the same
        points); None: computed here.

    Returns
    -------
    float
        Exactly ``ys[k]`` at ``x == xs[k]``.

    Examples
    --------
    >>> pchip([0.0, 1.0, 2.0], [0.0, 1.0, 0.0], 0.5), pchip([0.0, 1.0, 2.0], [0.0, 1.0, 4.0], 1.0)
    (0.75, 1.0)
    >>> pchip([0.0, 1.0, 2.0], [0.0, 1.0, 0.0], 0.5, slopes=pchip_slopes([0.0, 1.0, 2.0], [0.0, 1.0, 0.0]))
    0.75
    """
    if len(xs) == 1:
        return float(ys[0])
    m = pchip_slopes(xs, ys) if slopes is None else slopes
    k = min(max(bisect_right(xs, x) - 1, 0), len(xs) - 2)
    h = xs[k + 1] - xs[k]
    t = (x - xs[k]) / h
    if t == 0.0:
        return float(ys[k])
    if t == 1.0:
        return float(ys[k + 1])
    t2, t3 = t * t, t * t * t
    return float((2.0 * t3 - 3.0 * t2 + 1.0) * ys[k] + (t3 - 2.0 * t2 + t) * h * m[k]
                 + (-2.0 * t3 + 3.0 * t2) * ys[k + 1] + (t3 - t2) * h * m[k + 1])
