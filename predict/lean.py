"""The lean solve: theta(P) of one model on its branch table, in one model evaluation per pressure.

A curve of one model (what the studio, inverse design and every command ask for) solves
``R(theta) = E'(theta) - t V'(theta) = 0`` for each target ``t = P - P0`` on the rising
part of the branch. :func:`lean_table` tabulates the rates once per model on nested
grids: level ``k`` spans ``[0, theta_end / 2^k]`` with :data:`LEVEL_POINTS` points
(:data:`LEVELS` halvings), and the table keeps, from the finest level up, the upper half
of each level, so every interval is at most 1/64 of the angles it serves (the whole
finest level serves the smallest angles). Per interval it holds the cubics of ``E'``
and ``V'`` through the four grid points of its level around it, in the interval's own
coordinate ``w = (theta - theta_i)/h_i`` in [0, 1], and the tabulated rates at both ends.
The table stops at the first fold of P (or holds the whole branch up to a lock-up,
where P has a pole and R has none). :func:`solve_lean` then does, per target and with no
Python loop over targets:

1. bracket: the interval with ``P_i <= t < P_(i+1)`` (a binary search in the table);
2. start: the root of the cubic ``R`` from the secant of the tabulated residuals, by
   :data:`CUBIC_STEPS` Newton step(s) on the cubic (no model evaluation);
3. polish: one Newton step on the model's residual with the cubic's slope.

A target is *settled* when the step stays in its interval and the error the step
leaves is within the tolerance: ``min(step, left) <= rtol |theta| + atol``, where
``left = step (27 |c3| + |R_ww| step/|h|)/|R_w|`` bounds the slope error of the cubic
(its cubic term) times the step plus Newton's quadratic term (``R_ww`` the cubic's own
second derivative), as the trace inverse estimates it. A target that is not settled (near a fold, near the lock-up pole, or so
small that its residual is round-off) is the caller's to solve by the full trace inverse
(:func:`embroact.predict.solvers.trace_inverse`, which also knows P's round-off floor);
so is every target above the table's top (beyond a fold, or past the branch end).

The table depends on the model only, never on the pressures asked for, so a settled
answer is the same whatever else the call or earlier calls asked. The same text runs on numpy
arrays (many pressures) and on Python floats (:data:`embroact.predict.floats.SCALAR`, a
handful of pressures): the same operations in the same order, so both give the same bits.

Examples
--------
>>> import numpy as np
>>> from embroact.predict.model import Geometry, lock_theta, pressure_mpa
>>> from embroact.predict.lean import lean_table, solve_lean, solve_lean_scalar
>>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
>>> tab = lean_table(geo, theta_end=float(lock_theta(geo)[0, 0]), pole_at_end=True, rtol=1e-10, atol=1e-22)
>>> t = pressure_mpa(np.array([-0.003, -0.3, -4.0]), geo)[0] - 0.17
>>> theta, settled = solve_lean(tab, t)
>>> bool(np.all(np.abs(theta / [-0.003, -0.3, -4.0] - 1.0) < 1e-10)), settled.tolist()
(True, [True, True, True])
>>> solve_lean_scalar(tab, float(t[1])) == float(theta[1])
True
"""
from __future__ import annotations

from bisect import bisect_right
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from . import model as _m
from .floats import SCALAR

__all__ = ["LeanTable", "lean_table", "solve_lean", "solve_lean_scalar", "LEVELS", "LEVEL_POINTS", "CUBIC_STEPS"]

#: Halvings of the branch below the full one (the finest level spans 1/1024 of it).
LEVELS = 10
#: Grid points per level: an odd count, so the midpoint of a level is the end of the next.
LEVEL_POINTS = 129
#: Newton steps on the interpolating cubic for the start (no model evaluations).
CUBIC_STEPS = 1
#: Power-basis coefficients of the cubic through the grid points j..j+3, in the coordinate of
#: the interval starting at j + s (s = 0, 1, 2: the first, inner and last intervals' windows).
_WINDOW = tuple(np.linalg.inv(np.vander(np.arange(4.0) - s, 4, increasing=True)) for s in range(3))


@dataclass(frozen=True, slots=True, eq=False)
class LeanTable:
    """One branch's rising part, a row per interval (built once per model by :func:`lean_table`).

    Attributes
    ----------
    geo : Geometry
        The model's constants as Python floats (:meth:`~embroact.predict.model.Geometry.scalar`).
    rate : callable
        ``rate(theta, geo, xp)``: the fused analytic rates (:func:`~embroact.predict.model.fast_rate_of`).
    p : ndarray
        P - P0 at the intervals' ends [MPa], rising, ``(k + 1,)``.
    columns : ndarray
        ``(13, k)``, a column per interval: its start theta [rad], its width h and ``|h|`` [rad] (h signed
        as the branch), the cubics of E' and V' (4 coefficients each) and E', V' at its end.
    rtol, atol : float
        Settling tolerances (module docstring).
    p_list : list
        ``p`` as Python floats, for :func:`solve_lean_scalar`.

    Examples
    --------
    >>> from embroact.predict.model import Geometry, lock_theta
    >>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
    >>> tab = lean_table(geo, theta_end=float(lock_theta(geo)[0, 0]), pole_at_end=True, rtol=1e-10, atol=1e-22)
    >>> tab.columns.shape[0], tab.top  # up to a lock-up: every target is served
    (13, inf)
    """

    geo: _m.Geometry
    rate: Callable
    p: np.ndarray
    columns: np.ndarray
    rtol: float
    atol: float
    p_list: list

    @property
    def top(self) -> float:
        """The highest target the table serves (P - P0 at its last rising grid point) [MPa]."""
        return self.p_list[-1]


def lean_table(geo: _m.Geometry, *, theta_end: float, pole_at_end: bool, rtol: float,
               atol: float) -> LeanTable | None:
    """The table of one design's branch from 0 to ``theta_end`` [rad] (module docstring).

    Parameters
    ----------
    geo : Geometry
        One design, as arrays of one row or as Python floats (:meth:`~embroact.predict.model.Geometry.scalar`).
    theta_end : float
        The branch's end [rad], signed as it bends.
    pole_at_end : bool
        ``theta_end`` is a lock-up (P -> inf there).
    rtol, atol : float
        Settling tolerances.

    Returns
    -------
    LeanTable or None
        None when no interval rises, or when the last interval before the pole is not finite
        (nothing the table could serve).

    Examples
    --------
    >>> from embroact.predict.model import Geometry, lock_theta
    >>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
    >>> tab = lean_table(geo, theta_end=float(lock_theta(geo)[0, 0]), pole_at_end=True, rtol=1e-10, atol=1e-22)
    >>> len(tab.p_list) == tab.columns.shape[1] + 1
    True
    """
    n = LEVEL_POINTS
    g = geo if isinstance(geo.l0, float) else geo.scalar()
    grid = (theta_end * _HALVINGS)[:, None] * _UNIT  # finest level first; halvings: exact
    rate = _m.fast_rate_of(g)
    de, dv = rate(grid, g, np)
    with np.errstate(divide="ignore", invalid="ignore"):
        p = de / dv
    p[:, 0] = 0.0
    if pole_at_end or not np.isfinite(p[-1, -1]):
        p[-1, -1] = np.inf
    rising = p[:, 1:] > p[:, :-1]
    tops = np.where(rising.all(axis=1), n - 1, np.argmin(rising, axis=1))
    # finest level first: all of it, then the upper half of each coarser level, up to the first fold
    # (P falls beyond it: the coarser levels add nothing)
    folded = np.flatnonzero(tops < n - 1)
    keep = _KEEP & (_INTERVAL < tops[:, None])
    if folded.size:
        keep[folded[0] + 1:] = False
    kept = np.flatnonzero(keep.ravel())  # level * (n - 1) + interval, finest level first
    if not kept.size:
        return None
    level, i = np.divmod(kept, n - 1)
    at = level * n + i  # the interval's start in the flat grid
    p_ends = np.append(p.ravel()[at], p.ravel()[at[-1] + 1])
    if not np.isfinite(p_ends[-2]):
        return None
    return LeanTable(g, rate, p_ends, _columns(grid.ravel(), de.ravel(), dv.ravel(), at, i), float(rtol),
                     float(atol), p_ends.tolist())


#: The nested grids' constants: the halvings (finest level first), one level's points in [0, 1], each
#: level's interval indices, the intervals a level serves (all of the finest, the upper half of the others).
_HALVINGS = 0.5 ** np.arange(LEVELS, -1.0, -1.0)
_UNIT = np.linspace(0.0, 1.0, LEVEL_POINTS)
_INTERVAL = np.arange(LEVEL_POINTS - 1)
_KEEP = np.broadcast_to(_INTERVAL >= (LEVEL_POINTS - 1) // 2, (LEVELS + 1, LEVEL_POINTS - 1)).copy()
_KEEP[0] = True
#: Per interval of a level: the offset of its four-point window from its start, and the window's matrix.
_WINDOW_START = np.clip(_INTERVAL - 1, 0, LEVEL_POINTS - 4) - _INTERVAL
_WINDOW_OF = np.stack(_WINDOW)[-_WINDOW_START]


def _columns(grid, de, dv, at, i):
    """The ``(13, k)`` columns (:class:`LeanTable`) of the intervals starting at the flat grid indices ``at``
    (interval ``i`` of its level)."""
    window = (at + _WINDOW_START[i])[:, None] + np.arange(4)
    mats = _WINDOW_OF[i]
    out = np.empty((13, at.size))
    out[0] = grid[at]
    out[1] = grid[at - i + 1] - grid[at - i]  # the level's step: its second point less its first
    out[2] = abs(out[1])
    out[3:7] = np.einsum("kw,kcw->ck", de[window], mats)
    out[7:11] = np.einsum("kw,kcw->ck", dv[window], mats)
    out[3], out[7] = de[at], dv[at]  # the cubic meets the table at w = 0 exactly
    out[11], out[12] = de[at + 1], dv[at + 1]
    return out


def _settle(tab: LeanTable, t, row, xp):
    """(theta, settled) of targets ``t`` in the intervals ``row`` (steps 2-3 of the module docstring)."""
    x_i, h, habs, e0, e1, e2, e3, v0, v1, v2, v3, e_b, v_b = row
    c0, c1, c2, c3 = e0 - t * v0, e1 - t * v1, e2 - t * v2, e3 - t * v3
    q2, q3 = 2.0 * c2, 3.0 * c3
    u = c0 / (c0 - (e_b - t * v_b))  # the secant of the tabulated residuals: R(0) <= 0 < R(1)
    for _ in range(CUBIC_STEPS):
        u = xp.minimum(xp.maximum(u - (c0 + u * (c1 + u * (c2 + u * c3))) / (c1 + u * (q2 + u * q3)), 0.0), 1.0)
    e, v = tab.rate(x_i + h * u, tab.geo, xp)
    slope = c1 + u * (q2 + u * q3)
    dw = (e - t * v) / slope
    w = u - dw
    theta = x_i + h * w
    step = abs(dw) * habs
    left = step * (27.0 * abs(c3) + abs(q2 + 2.0 * q3 * u) * step / habs) / abs(slope)
    settled = (w >= 0.0) & (w <= 1.0) & (xp.minimum(step, left) <= tab.rtol * abs(theta) + tab.atol)
    return theta, settled


def solve_lean(tab: LeanTable, t):
    """(theta [rad], settled) for targets ``t = P - P0`` [MPa], 1-D, ``0 < t <= tab.top``.

    Entries not settled (module docstring) hold no answer: solve them by the trace inverse.

    Parameters
    ----------
    tab : LeanTable
        The branch's table.
    t : numpy.ndarray (n,)
        Targets P - P0 [MPa].

    Returns
    -------
    theta : numpy.ndarray (n,)
        Bend angle [rad].
    settled : numpy.ndarray of bool (n,)

    Examples
    --------
    >>> from embroact.predict.model import Geometry, lock_theta
    >>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
    >>> tab = lean_table(geo, theta_end=float(lock_theta(geo)[0, 0]), pole_at_end=True, rtol=1e-10, atol=1e-22)
    >>> theta, settled = solve_lean(tab, np.array([0.01, 0.1]))
    >>> theta.round(6).tolist(), settled.tolist()
    ([-0.234103, -1.500631], [True, True])
    """
    i = np.searchsorted(tab.p, t, side="right") - 1  # >= 0: t > 0 = p[0]
    np.minimum(i, tab.columns.shape[1] - 1, out=i)  # t = top itself: the last interval
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        theta, settled = _settle(tab, t, tab.columns[:, i], np)
        return theta, settled & np.isfinite(theta)


def solve_lean_scalar(tab: LeanTable, t: float) -> float | None:
    """theta [rad] for one target ``0 < t <= tab.top`` [MPa] in Python floats, or None if not settled.

    The same answer, bit for bit, as :func:`solve_lean` gives for ``t`` among any others.

    Parameters
    ----------
    tab : LeanTable
        The branch's table.
    t : float
        Target P - P0 [MPa].

    Returns
    -------
    float or None
        Bend angle [rad].

    Examples
    --------
    >>> from embroact.predict.model import Geometry, lock_theta
    >>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
    >>> tab = lean_table(geo, theta_end=float(lock_theta(geo)[0, 0]), pole_at_end=True, rtol=1e-10, atol=1e-22)
    >>> solve_lean_scalar(tab, 0.1) == float(solve_lean(tab, np.array([0.01, 0.1]))[0][1])
    True
    """
    i = min(bisect_right(tab.p_list, t) - 1, tab.columns.shape[1] - 1)  # >= 0: t > 0 = p[0]
    try:
        theta, settled = _settle(tab, t, tab.columns[:, i].tolist(), SCALAR)
    except (ZeroDivisionError, ValueError, OverflowError):  # a flat cubic: the trace inverse's case
        return None
    return theta if settled and theta == theta else None
