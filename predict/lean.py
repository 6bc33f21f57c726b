"""The lean solve: theta(P) of one model from its closed form, a bracket and one stencil per pressure.

A curve of one model (what the studio, inverse design and every command ask for) solves
``R = F' - t V' = 0`` for each target ``t = P - P0`` on the rising part of the branch, in the
stretch ``m = (l - l0)/(2 l0)`` (:class:`~embroact.predict.model.StretchRates`: P as a ratio of
rates in ``m`` needs no derivative of the constraint, about half the operations of the rates in
theta), and gives theta at the root. The branch's *nodes* are fixed fractions of its served span: nested
grids, level ``k`` spanning ``[0, span / 2^k]`` with :data:`LEVEL_POINTS` points
(:data:`LEVELS` halvings), the whole finest level and the upper half of each coarser
one, so every interval is at most 1/32 of the angles it serves. Per target:

1. bracket: the nodes with ``P_i <= t < P_(i+1)`` (a search over the nodes);
2. start: the secant of the residuals at the two nodes (R has no pole at lock-up, P has);
3. polish: R at four points around the start (:data:`STENCIL`, spaced 1/64 of the
   interval), the root of the cubic through them by two Newton steps on that cubic.

The answer is *settled* when the root lies inside the stencil and inside the bracket,
and the error the cubic leaves (its next term, estimated from its third difference) is
within ``rtol |theta| + atol``. A target that is not settled (so small that its residual
is round-off, or where the cubic does not hold) is the caller's to solve by the full
trace inverse (:func:`embroact.predict.solvers.trace_inverse`, which also knows P's
round-off floor); so is every target at or above the last node's pressure.

Which nodes a target uses depends on the model and the target only, so an answer is the
same whatever else the call or earlier calls asked. Many pressures evaluate every node at
once on numpy arrays (:func:`solve_lean`, one closed-form evaluation over the nodes, one over
the stencils); a handful evaluate only the few nodes their search visits, on Python floats
(:func:`solve_lean_scalar`, :data:`embroact.predict.floats.SCALAR`; :func:`_bracket`: nearly always the
two around its guess from a table shared by all designs): the same operations in the same order, so both
give the same bits, and neither builds a table of the design first.

The served span: the branch up to its lock-up (where P has a pole) or up to the stretch
``m = RISE_M``, whichever comes first; beyond it P may fold. A zigzag's P depends on ``m`` and
``c/r0^2`` alone and first folds at ``m`` 0.828-0.954 over ``0 <= c/r0^2 < 1``; a cross design
of a small thread angle folds as a zigzag does (its lock-up lies far beyond), one of a larger
angle locks up first (tests/test_lean.py holds the rise up to the span over the designs'
parameter space). The array path checks the rise on
its nodes and leaves every target to the trace inverse where it does not hold.

Examples
--------
>>> import numpy as np
>>> from embroact.predict.model import Geometry, lock_theta, pressure_mpa
>>> from embroact.predict.lean import lean_table, solve_lean, solve_lean_scalar
>>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
>>> tab = lean_table(geo, theta_end=float(lock_theta(geo)[0, 0]), pole_at_end=True, rtol=1e-10, atol=1e-22)
>>> t = pressure_mpa(np.array([-0.003, -0.3, -4.0]), geo)[0] - 0.17
>>> m, settled = solve_lean(tab, t)
>>> theta = tab.rates.theta(m)
>>> bool(np.all(np.abs(theta / [-0.003, -0.3, -4.0] - 1.0) < 1e-10)), settled.tolist()
(True, [True, True, True])
>>> solve_lean_scalar(tab, float(t[1])) == float(m[1])
True
"""
from __future__ import annotations

import math
from bisect import bisect_right
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..patterns.base.arrays import array_max, array_min
from ..patterns.base.records import quick_init
from . import model as _m
from . import solvers
from .floats import SCALAR

__all__ = ["LeanTable", "lean_table", "solve_lean", "solve_lean_scalar", "solve_rows", "solve_to_fold", "LEVELS",
           "LEVEL_POINTS", "STENCIL", "RISE_M", "FOLD_BEFORE_M", "FOLD_NODES"]

#: Halvings of the served span below the full one (the finest level spans 1/1024 of it).
LEVELS = 10
#: Grid points per level: 2^k + 1, so each node is an exact binary fraction of the span.
LEVEL_POINTS = 65
#: Where the polish evaluates R around the start, in units of its spacing (1/64 of the interval).
STENCIL = (-1.5, -0.5, 0.5, 1.5)
_SPACING = 1.0 / 64.0
#: The nodes reach at most the stretch m = this (a zigzag's P rises up to m = 0.828 at least).
RISE_M = 0.8
#: A design of s0 = 0 folds before this stretch (at m 0.828-0.954: :func:`solve_to_fold`).
FOLD_BEFORE_M = 0.96
#: Nodes of the rise from RISE_M up to such a design's fold (:func:`solve_to_fold`).
FOLD_NODES = 17

_HALF = (LEVEL_POINTS - 1) // 2
#: The nodes as fractions of the span, rising: the finest level, then the upper half of each coarser one.
_FRACTIONS = np.concatenate(
    [np.arange(LEVEL_POINTS) / (LEVEL_POINTS - 1) * 0.5 ** LEVELS]
    + [np.arange(_HALF + 1, LEVEL_POINTS) / (LEVEL_POINTS - 1) * 0.5 ** (LEVELS - k) for k in range(1, LEVELS + 1)])
_FRACTION_LIST = _FRACTIONS.tolist()
#: The stencil spacing of each node's interval to the next, as a fraction of the span (the last node's: its
#: level's step).
_KW = _SPACING * np.append(np.diff(_FRACTIONS), _FRACTIONS[-1] - _FRACTIONS[-2])
_KW_LIST = _KW.tolist()
_LAST = _FRACTIONS.size - 1
_Z = np.array(STENCIL)[:, None]
_Z0, _Z1, _Z2, _Z3 = STENCIL
_FOLD_FRACTIONS = np.linspace(0.0, 1.0, FOLD_NODES)


@quick_init
@dataclass(frozen=True, slots=True, eq=False)
class LeanTable:
    """One branch's served span and what has been evaluated on it (made by :func:`lean_table`).

    Attributes
    ----------
    rates : StretchRates
        The model's rates in the stretch ``m`` (:class:`~embroact.predict.model.StretchRates`); its
        ``scale`` turns their ratio into P - P0 [MPa].
    span : float
        The served span in ``m``, signed as the branch (the nodes are fractions of it).
    pole : bool
        The span ends at a lock-up (P -> inf at the last node).
    rtol, atol : float
        Settling tolerances in ``m`` (module docstring).
    floor : float
        Targets at or below it (in units of ``rates.scale`` MPa) are round-off sized: left to the trace inverse.
    nodes : dict
        Node index -> (m, F', V', P - P0 over the scale) evaluated on floats so far (:func:`solve_lean_scalar`).
    lazy : dict
        The arrays of every node, made on first use (:meth:`arrays`), and their pressures as floats (the float
        path's binary search).

    Examples
    --------
    >>> from embroact.predict.model import Geometry, lock_theta
    >>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
    >>> tab = lean_table(geo, theta_end=float(lock_theta(geo)[0, 0]), pole_at_end=True, rtol=1e-10, atol=1e-22)
    >>> tab.pole, tab.top  # up to a lock-up: every target is served
    (True, inf)
    """

    rates: _m.StretchRates
    span: float
    pole: bool
    rtol: float
    atol: float
    floor: float
    nodes: dict
    lazy: dict

    def arrays(self):
        """The arrays of every node, made once.

        Returns
        -------
        nodes : numpy.ndarray (5, n)
            Per node: m, F', V', P - P0 over the scale and the stencil spacing of the interval it starts.
        rises : bool
            P rises over the nodes.

        Examples
        --------
        >>> from embroact.predict.model import Geometry, lock_theta
        >>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
        >>> tab = lean_table(geo, theta_end=float(lock_theta(geo)[0, 0]), pole_at_end=True, rtol=1e-10, atol=1e-22)
        >>> nodes, rises = tab.arrays()
        >>> nodes.shape, rises
        ((5, 385), True)
        """
        if "arrays" not in self.lazy:
            m = self.span * _FRACTIONS
            f, v = self.rates(m, np)
            nodes = np.empty((5, m.size))
            nodes[0], nodes[1], nodes[2] = m, f, v
            with np.errstate(divide="ignore", invalid="ignore"):
                np.divide(f, nodes[2], out=nodes[3])
            nodes[3, 0] = 0.0
            if self.pole:
                nodes[3, -1] = np.inf
            np.multiply(_KW, abs(self.span), out=nodes[4])
            p = nodes[3]
            self.lazy["arrays"] = nodes, bool(np.logical_and.reduce(p[1:] > p[:-1]))
        return self.lazy["arrays"]

    @property
    def top(self) -> float:
        """The lowest target the table does not serve: P - P0 at its last node [MPa] (inf at a lock-up)."""
        return float(self.arrays()[0][3, -1]) * self.rates.scale

    def node(self, j: int):
        """(m, F', V', P - P0 over the scale) at node ``j`` on Python floats (kept in :attr:`nodes`).

        Parameters
        ----------
        j : int
            Node index, 0 (the straight state) to the last.

        Returns
        -------
        tuple of float

        Examples
        --------
        >>> from embroact.predict.model import Geometry, lock_theta
        >>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
        >>> tab = lean_table(geo, theta_end=float(lock_theta(geo)[0, 0]), pole_at_end=True, rtol=1e-10, atol=1e-22)
        >>> tab.node(100)[0] == float(tab.arrays()[0][0, 100]), tab.node(100)[3] == float(tab.arrays()[0][3, 100])
        (True, True)
        """
        got = self.nodes.get(j)
        if got is None:
            made = self.lazy.get("arrays")
            if made is not None:  # the same bits
                got = tuple(made[0][:4, j].tolist())
            else:
                m = self.span * _FRACTION_LIST[j]
                f, v = self.rates(m, SCALAR)
                got = (m, f, v, 0.0 if j == 0 else (np.inf if j == _LAST and self.pole else f / v))
            self.nodes[j] = got
        return got


def lean_table(geo: _m.Geometry, *, theta_end: float, pole_at_end: bool, rtol: float, atol: float,
               floor: float = 0.0) -> LeanTable | None:
    """The lean table of one design's branch from 0 to ``theta_end`` [rad] (module docstring); nothing is
    evaluated until a solve asks.

    Parameters
    ----------
    geo : Geometry
        One design, as arrays of one row or as Python floats (:meth:`~embroact.predict.model.Geometry.scalar`).
    theta_end : float
        The branch's end [rad], signed as it bends.
    pole_at_end : bool
        ``theta_end`` is a lock-up (P -> inf there).
    rtol, atol : float
        The tolerance of theta [rad].
    floor : float, optional
        Targets at or below it [MPa] are left to the trace inverse.

    Returns
    -------
    LeanTable or None
        None when the branch is empty.

    Examples
    --------
    >>> from embroact.predict.model import Geometry, lock_theta
    >>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
    >>> tab = lean_table(geo, theta_end=float(lock_theta(geo)[0, 0]), pole_at_end=True, rtol=1e-10, atol=1e-22)
    >>> bool(abs(tab.rates.theta(tab.span) / float(lock_theta(geo)[0, 0]) - 1.0) < 1e-12)
    True
    """
    if theta_end == 0.0:
        return None
    g = geo if isinstance(geo.l0, float) else geo.scalar()
    rates = _m.StretchRates.of(g)
    span, pole = rates.m_of(float(theta_end)), bool(pole_at_end)
    if abs(span) > RISE_M:  # up to RISE_M, short of a fold
        span, pole = (RISE_M if span > 0.0 else -RISE_M), False
    return LeanTable(rates, span, pole, float(rtol), float(atol) / rates.theta_per_m, float(floor) / rates.scale,
                     {}, {})


def _start(ma, mb, fa, va, fb, vb, t, zigzag):
    """The start: the secant of the residuals at the bracket's nodes (R(ma) <= 0 < R(mb)); a zigzag's V' is 1."""
    ra, rb = (fa - t, fb - t) if zigzag else (fa - t * va, fb - t * vb)
    return ma + (mb - ma) * (ra / (ra - rb))


def _polish(x0, d, r0, r1, r2, r3, rtol, atol):
    """(m, settled) from the residuals ``r0..r3`` at ``x0 + d * STENCIL`` (step 3 of the module docstring),
    settled within ``rtol |m| + atol``."""
    f0, f1 = r1 - r0, r2 - r1
    df = f1 - f0
    k2 = 0.5 * df
    k3 = ((r3 - r2 - f1) - df) / 6.0
    y = 1.0 + r1 / (r1 - r2)  # y = z + 1.5 in [0, 3]: the secant of the two middle points
    # one Newton step on the cubic p(y) = r0 + y (f0 + (y - 1)(k2 + (y - 2) k3)) through them
    y1 = y - 1.0
    q = k2 + (y - 2.0) * k3
    s = f0 + y1 * q
    slope = s + y * (q + y1 * k3)
    z = (y - (r0 + y * s) / slope) - 1.5
    m = x0 + d * z
    # the cubic's error: its next difference (at most its third times the spacing ratio) times
    # |y (y - 1)(y - 2)(y - 3)| <= 1 on [0, 3], over the slope; the root then lies in the bracket
    # within the tolerance (its residuals change sign there)
    left = abs(k3 / slope) * (d * _SPACING)
    return m, (abs(z) <= 1.5) & (left <= rtol * abs(m) + atol)  # NaN: False


def solve_lean(tab: LeanTable, t):
    """(m, settled) for targets ``t = P - P0`` [MPa], 1-D, ``t > 0``: the stretches
    (:meth:`~embroact.predict.model.StretchRates.state` gives theta and the state there).

    Entries not settled (module docstring) hold no answer: solve them by the trace inverse.

    Parameters
    ----------
    tab : LeanTable
        The branch's table.
    t : numpy.ndarray (n,)
        Targets P - P0 [MPa].

    Returns
    -------
    m : numpy.ndarray (n,)
        The stretch at each root.
    settled : numpy.ndarray of bool (n,)

    Examples
    --------
    >>> from embroact.predict.model import Geometry, lock_theta
    >>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
    >>> tab = lean_table(geo, theta_end=float(lock_theta(geo)[0, 0]), pole_at_end=True, rtol=1e-10, atol=1e-22)
    >>> m, settled = solve_lean(tab, np.array([0.01, 0.1]))
    >>> tab.rates.theta(m).round(6).tolist(), settled.tolist()
    ([-0.234103, -1.500631], [True, True])
    """
    nodes, rises = tab.arrays()
    t = t / tab.rates.scale
    lo = nodes[3, 1:_LAST].searchsorted(t, side="right")  # t > 0 = p[0]: the bracket [lo, lo + 1]
    (ma, fa, va, _, kh), (mb, fb, vb, _, _) = nodes.take(lo, axis=1), nodes[:, 1:].take(lo, axis=1)
    zigzag = tab.rates.zigzag
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        x0 = _start(ma, mb, fa, va, fb, vb, t, zigzag)
        d = np.minimum(kh, _SPACING * np.abs(x0))
        fs, vs = tab.rates(x0 + d * _Z, np)
        r = fs - t if zigzag else fs - t * vs
        m, settled = _polish(x0, d, r[0], r[1], r[2], r[3], tab.rtol, tab.atol)
    if not rises:
        settled[:] = False
    elif not (float(array_min(t, axis=None)) > tab.floor and float(array_max(t, axis=None)) < float(nodes[3, _LAST])):
        settled &= (t < nodes[3, _LAST]) & (t > tab.floor)  # at or above the last node: not served
    return m, settled


def _bracket(tab: LeanTable, t: float) -> int | None:
    """The node ``lo`` with ``P_lo <= t < P_(lo+1)`` (what ``searchsorted`` finds among all nodes: P rises over
    them), or None if ``t`` is at or above P at the last node.

    Once the node arrays are made (:meth:`LeanTable.arrays`), a binary search of their pressures. Before, it
    evaluates few nodes: first the two :func:`_guess` names (nearly always the bracket). Otherwise the search
    follows the residual ``R = F' - t V'`` signed as ``P - t`` (no pole at a lock-up, where P has one) in the
    span's fraction ``x``. The first probe is the node nearest the root of the quadratic with R's value and
    slope at the straight state (:attr:`~embroact.predict.model.StretchRates.rise`; F' is 0 there) and its
    value at the last node; each further probe is the node nearest the root of the quadratic through the bracket's ends and the end the last
    probe replaced, and a bisection when four probes did not halve the bracket: about four evaluations a target,
    the last node's among them, where the guess missed.
    """
    keys = tab.lazy.get("keys")
    if keys is None and "arrays" in tab.lazy:
        keys = tab.lazy["keys"] = tab.lazy["arrays"][0][3, 1:].tolist()  # the last: the top
    if keys is not None:
        return bisect_right(keys, t, 0, _LAST - 1) if t < keys[-1] else None
    lo = _guess(tab, t)
    if lo is not None and tab.node(lo)[3] <= t < tab.node(lo + 1)[3]:
        return lo
    _, f, v, p = tab.node(_LAST)
    if not t < p:
        return None
    rates = tab.rates
    v0 = 1.0 - 5.0 * rates.s0sq  # V' at the straight state
    sign = 1.0 if v0 > 0.0 else -1.0
    lo, hi, r_lo, r_hi = 0, _LAST, -t * abs(v0), sign * (f - t * v)
    slope = sign * (rates.rise + 16.0 * t * rates.s0sq) * tab.span  # dR/dx at x = 0 (V'' = -16 s0^2 there)
    x = _quadratic_root(r_hi - r_lo - slope, slope, r_lo, 0.0, 1.0)
    x = r_lo / (r_lo - r_hi) if x is None else x
    widths = [2 * _LAST] * 4
    while True:
        j = bisect_right(_FRACTION_LIST, x, lo, hi) - 1  # the nodes j, j + 1 around x: the one nearer, inside
        j = j + 1 if j + 1 < hi and (j == lo or _FRACTION_LIST[j + 1] - x < x - _FRACTION_LIST[j]) else j
        widths.append(hi - lo)
        _, f, v, p = tab.node(j)
        if p <= t:
            third, lo, r_lo = (lo, r_lo), j, sign * (f - t * v)
        else:
            third, hi, r_hi = (hi, r_hi), j, sign * (f - t * v)
        if hi - lo == 1:
            return lo
        x_lo, x_hi = _FRACTION_LIST[lo], _FRACTION_LIST[hi]
        if hi - lo > widths[-4] // 2 or not r_lo < r_hi:  # no progress, or R's round-off: bisect
            x = _FRACTION_LIST[(lo + hi) // 2]
            continue
        x = _quadratic_through(x_lo, r_lo, x_hi, r_hi, _FRACTION_LIST[third[0]], third[1])
        x = x_lo + (x_hi - x_lo) * (r_lo / (r_lo - r_hi)) if x is None else x


#: The guess table's grid (:func:`_guess_nodes`): ``s0 = sin(beta0)`` at ``0, 1/64, ..., 63/64`` and
#: ``sigma = c cos^2(beta0)/r0^2`` at ``1/64, ..., 63/64``.
GUESS_GRID = 64
#: Rows of the guess table kept (each made on first use, 12 KB): a zigzag reads two, another design four.
GUESS_ROWS = 512
#: Cells of four rows kept (:func:`_guess_cell`; all dropped when full): at most four times as many rows held.
GUESS_CELLS = 256
_CELLS: dict = {}
_NO_CELL = object()
#: A zigzag row's branch end [rad] (its lock-up is at infinity; any angle past the span RISE_M will do).
_FAR_RAD = 1e3


@lru_cache(maxsize=GUESS_ROWS)
def _guess_nodes(i: int, k: int):
    """P - P0 over the scale (``F'/V'``) at every node of the design of ``s0 = i / GUESS_GRID`` and
    ``sigma = k / GUESS_GRID`` on the span :func:`lean_table` gives it (up to its lock-up or :data:`RISE_M`),
    or None where it has no branch (``sigma >= cos^2(beta0)``: the wall does not fit).

    Such a design's rates depend on ``s0`` and ``sigma`` alone, and so does its span in ``m`` (the lock-up's
    stretch): its nodes' pressures over the scale are the same for every length, radius and modulus.
    """
    s0 = i / GUESS_GRID
    c_mm2 = k / GUESS_GRID / (1.0 - s0 * s0)  # with r0 = 1 mm
    if not c_mm2 < 1.0:
        return None
    geo = _m.Geometry.of_floats(beta0_rad=math.asin(s0), l0_mm=1.0, r0_mm=1.0, c_mm2=c_mm2, g_mpa=1.0, p0_mpa=0.0)
    lock = _m.lock_theta(geo, SCALAR)
    tab = lean_table(geo, theta_end=min(lock, _FAR_RAD), pole_at_end=lock < _FAR_RAD, rtol=0.0, atol=0.0)
    return None if tab is None else tab.arrays()[0][3].tolist()


def _guess_cell(key: int, i: int, k: int, across: bool):
    """The rows of :func:`_guess_nodes` at the corners of the grid's cell ``[i, i + 1] x [k, k + 1]`` (those of
    ``i`` twice unless ``across``), or None if one has no row; kept in :data:`_CELLS` under ``key``."""
    a, b = _guess_nodes(i, k), _guess_nodes(i, k + 1)
    c, d = (_guess_nodes(i + 1, k), _guess_nodes(i + 1, k + 1)) if across else (a, b)
    cell = None if a is None or b is None or c is None or d is None else (a, b, c, d)
    if len(_CELLS) >= GUESS_CELLS:
        _CELLS.clear()
    _CELLS[key] = cell
    return cell


def _guess(tab: LeanTable, t: float) -> int | None:
    """The bracket of target ``t`` (over the scale) the design most likely has: its nodes' pressures interpolated
    between the rows of :func:`_guess_nodes` around its ``s0`` and ``sigma`` (linearly in ``sigma`` for a zigzag
    on the span :data:`RISE_M`, bilinearly otherwise); None outside the grid (the caller checks the guess on the
    design's own nodes: a design whose span its rows do not share, one capped by the tracing cap, is only
    guessed wrong)."""
    rates = tab.rates
    x = rates.sigma * GUESS_GRID
    if not 1.0 <= x < GUESS_GRID - 1:  # sigma = 0: no scale to divide by (no wall)
        return None
    k = int(x)
    wk = x - k
    if rates.zigzag:
        if tab.span != RISE_M:
            return None
        i, wi = 0, 0.0
    else:
        y = math.sqrt(rates.s0sq) * GUESS_GRID
        if not y < GUESS_GRID - 1:
            return None
        i = int(y)
        wi = y - i
    across = wi != 0.0
    key = (i * GUESS_GRID + k) * 2 + across
    cell = _CELLS.get(key, _NO_CELL)  # a dict read: the cheapest cache to ask
    if cell is _NO_CELL:
        cell = _guess_cell(key, i, k, across)
    if cell is None:
        return None
    a, b, c, d = cell
    wa, wb, wc, wd = (1.0 - wi) * (1.0 - wk), (1.0 - wi) * wk, wi * (1.0 - wk), wi * wk
    # from the bracket in the first row, to the last node whose interpolated pressure is at or below t
    j = bisect_right(a, t, 1, _LAST) - 1
    while j > 0 and a[j] * wa + b[j] * wb + c[j] * wc + d[j] * wd > t:
        j -= 1
    while j < _LAST - 1 and not a[j + 1] * wa + b[j + 1] * wb + c[j + 1] * wc + d[j + 1] * wd > t:
        j += 1
    return j


def _quadratic_through(x0: float, y0: float, x1: float, y1: float, x2: float, y2: float) -> float | None:
    """The root in ``(x0, x1)`` of the quadratic through three points (distinct ``x``), or None."""
    d01, d12 = (y1 - y0) / (x1 - x0), (y2 - y1) / (x2 - x1)
    a = (d12 - d01) / (x2 - x0)
    b = d01 - a * (x0 + x1)
    return _quadratic_root(a, b, y0 - x0 * (a * x0 + b), x0, x1)


def _quadratic_root(a: float, b: float, c: float, lo: float, hi: float) -> float | None:
    """A root in ``(lo, hi)`` of ``a x^2 + b x + c`` (the cancellation-free pair of formulas), or None."""
    disc = b * b - 4.0 * a * c
    if not disc >= 0.0:  # also NaN
        return None
    q = -0.5 * (b + math.copysign(math.sqrt(disc), b))
    for root in (q / a if a != 0.0 else math.nan, c / q if q != 0.0 else math.nan):
        if lo < root < hi:
            return root
    return None


def solve_lean_scalar(tab: LeanTable, t: float) -> float | None:
    """m for one target ``t > 0`` [MPa] in Python floats, or None if not settled.

    The same answer, bit for bit, as :func:`solve_lean` gives for ``t`` among any others; it evaluates
    only the nodes its search visits (:func:`_bracket`) and the four stencil points.

    Parameters
    ----------
    tab : LeanTable
        The branch's table.
    t : float
        Target P - P0 [MPa].

    Returns
    -------
    float or None
        The stretch at the root.

    Examples
    --------
    >>> from embroact.predict.model import Geometry, lock_theta
    >>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
    >>> tab = lean_table(geo, theta_end=float(lock_theta(geo)[0, 0]), pole_at_end=True, rtol=1e-10, atol=1e-22)
    >>> solve_lean_scalar(tab, 0.1) == float(solve_lean(tab, np.array([0.01, 0.1]))[0][1])
    True
    >>> len(tab.nodes) < 12  # of 385 nodes
    True
    """
    t = t / tab.rates.scale
    lo = _bracket(tab, t)
    if lo is None:
        return None
    hi = lo + 1
    ma, fa, va, _ = tab.node(lo)
    mb, fb, vb, _ = tab.node(hi)
    zigzag = tab.rates.zigzag
    try:
        x0 = _start(ma, mb, fa, va, fb, vb, t, zigzag)
        d = SCALAR.minimum(_KW_LIST[lo] * abs(tab.span), _SPACING * abs(x0))
        rates = tab.rates  # the four stencil points one by one (no list: a first curve's cost)
        (f0, v0), (f1, v1), (f2, v2), (f3, v3) = (rates(x0 + d * _Z0, SCALAR), rates(x0 + d * _Z1, SCALAR),
                                                  rates(x0 + d * _Z2, SCALAR), rates(x0 + d * _Z3, SCALAR))
        if zigzag:
            m, settled = _polish(x0, d, f0 - t, f1 - t, f2 - t, f3 - t, tab.rtol, tab.atol)
        else:
            m, settled = _polish(x0, d, f0 - t * v0, f1 - t * v1, f2 - t * v2, f3 - t * v3, tab.rtol, tab.atol)
    except (ZeroDivisionError, ValueError, OverflowError):  # a flat cubic or a stencil out of the domain
        return None
    return m if settled and t > tab.floor else None


def solve_rows(geo: _m.Geometry, t, theta_end, pole_at_end, *, rtol: float, atol: float, floor):
    """The lean solve of many designs at once (what ``sweep`` runs): ``(theta [rad], settled)``, (n, k).

    ``geo``: the designs as ``(n, 1)`` arrays; ``t``: targets P - P0 [MPa] (n, k), those <= 0 ignored (settled,
    theta 0); ``theta_end``, ``pole_at_end``: each branch's end (n, 1), non-zero; ``floor``: per design (n, 1).
    Each design has the nodes of :func:`lean_table` (its served span); one ``searchsorted`` brackets every
    target, in keys ``row + P/(1 + P)`` that rise through the rows. Designs whose P does not rise over their
    nodes leave every target unsettled, as entries not settled do: the caller's trace inverse solves them.

    Parameters
    ----------
    geo : Geometry
        The designs, ``(n, 1)`` columns.
    t : numpy.ndarray (n, k)
        Targets P - P0 [MPa]; those <= 0 are ignored.
    theta_end : numpy.ndarray (n, 1)
        Each branch's end [rad], non-zero.
    pole_at_end : numpy.ndarray of bool (n, 1)
        The end is a lock-up.
    rtol, atol : float
        The tolerance of theta [rad].
    floor : numpy.ndarray (n, 1)
        Targets at or below it [MPa] are left unsettled.

    Returns
    -------
    theta : numpy.ndarray (n, k)
        Bend angle [rad] (0 where ignored).
    settled : numpy.ndarray of bool (n, k)

    Examples
    --------
    >>> from embroact.predict.model import Geometry, lock_theta
    >>> geo = Geometry.from_values(beta0_rad=[0.6, 0.0], l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3,
    ...                            p0_mpa=0.17)
    >>> end = np.where(geo.s0 > 0.0, lock_theta(geo), 20.0)
    >>> theta, settled = solve_rows(geo, np.array([[0.0, 0.1], [0.05, 0.1]]), end, geo.s0 > 0.0, rtol=1e-10,
    ...                             atol=1e-22, floor=np.zeros((2, 1)))
    >>> theta.round(6).tolist(), settled.tolist()
    ([[0.0, -1.500631], [1.606927, 3.936154]], [[True, True], [True, True]])
    """
    rates = _m.StretchRates.of(geo)
    n = t.shape[0]
    span = rates.m_of(theta_end)
    capped = np.abs(span) > RISE_M
    span = np.where(capped, np.copysign(RISE_M, span), span)
    m = span * _FRACTIONS
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        f, v = rates(m, np)
        v = np.broadcast_to(v, m.shape)
        p = f / v
        p[:, 0] = 0.0
        p[:, -1] = np.where(np.ravel(pole_at_end & ~capped), np.inf, p[:, -1])
        rises = np.all(p[:, 1:] > p[:, :-1], axis=1)
        p = np.where(rises[:, None], p, _FRACTIONS)  # keys that rise whatever the row's P does
        # the targets > 0 only (flat indices), as (entries, 1) columns with their designs' rates
        flat = np.flatnonzero(t > 0.0)
        row = flat // t.shape[1]
        at_row = row[:, None]
        tt = (t.take(flat) / rates.scale.take(row))[:, None]
        keys = (np.arange(n)[:, None] + np.where(p < np.inf, p / (1.0 + p), 1.0)).ravel()  # P = inf at a pole
        i = np.searchsorted(keys, at_row + tt / (1.0 + tt), side="right") - 1 - at_row * (_LAST + 1)
        served = (i >= 0) & (i < _LAST) & rises[at_row] & (tt > (floor.take(row) / rates.scale.take(row))[:, None])
        node = np.clip(i, 0, _LAST - 1)
        at = at_row * (_LAST + 1) + node
        ma, mb = m.take(at), m.take(at + 1)
        fa, fb, va, vb = f.take(at), f.take(at + 1), v.take(at), v.take(at + 1)
        x0 = _start(ma, mb, fa, va, fb, vb, tt, False)
        kh = np.abs(span.take(at_row)) * _KW.take(node)
        d = np.minimum(kh, _SPACING * np.abs(x0))
        mine = _m.StretchRates.of(geo.take(row))
        r = []
        for z in STENCIL:  # one point at a time: each array of the rates then stays in cache
            fs, vs = mine(x0 + d * z, np)
            r.append(fs - tt * vs)
        ms, settled = _polish(x0, d, r[0], r[1], r[2], r[3], float(rtol), atol / mine.theta_per_m)
        theta = np.zeros(t.shape)
        theta.reshape(-1)[flat] = mine.theta(ms, np)[:, 0]  # a view of the new array (.flat's writes are slower)
    ok = np.ones(t.shape, dtype=bool)  # targets <= 0: ignored
    ok.reshape(-1)[flat] = (settled & served)[:, 0]
    return theta, ok


def solve_to_fold(geo: _m.Geometry, t, m_end, *, rtol: float, atol: float):
    """The targets of designs with ``s0 = 0`` above their nodes (``m = RISE_M``), up to the fold of P (what
    ``sweep`` runs before the trace inverse): ``(theta [rad], settled, unstable)``, (n, k).

    Such a design's P depends on ``m`` and ``c/r0^2`` alone and first folds at ``m`` 0.828-0.954
    (:data:`RISE_M`), so the fold is the root of the slope (:meth:`~embroact.predict.model.StretchRates.slope`,
    exact to round-off) in ``[RISE_M, min(FOLD_BEFORE_M, m_end)]``, by Illinois regula falsi to round-off;
    the rise up to it has :data:`FOLD_NODES` nodes, evenly spaced (each interval about 1/100 of the
    stretches it serves), where a target is bracketed and polished as on the nodes below (:func:`solve_rows`),
    from the secant in ``w = sqrt(P(fold) - P)`` (m is smooth in w through the fold, not in P). A target at or above P at the fold is *unstable*: theta is the fold's. Which
    targets are solved depends on their own value only: targets below the nodes' first pressure (the last of
    :func:`solve_rows`' nodes), those not settled and the designs without a sign change of the slope there
    (a branch that ends first) are neither settled nor unstable: the caller's trace inverse solves them.

    Parameters
    ----------
    geo : Geometry
        The designs, ``(n, 1)`` columns, ``s0 = 0``.
    t : numpy.ndarray (n, k)
        Targets P - P0 [MPa]; those <= 0 are ignored.
    m_end : numpy.ndarray (n, 1)
        The stretch at each branch's end.
    rtol, atol : float
        The tolerance of theta [rad].

    Returns
    -------
    theta : numpy.ndarray (n, k)
        Bend angle [rad] where settled or unstable (0 elsewhere).
    settled, unstable : numpy.ndarray of bool (n, k)

    Examples
    --------
    >>> from embroact.predict.model import Geometry, StretchRates
    >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
    >>> rates = StretchRates.of(geo)
    >>> p = rates.scale * rates(np.array([[0.81, 0.84]]))[0]  # P - P0 at m 0.81 and 0.84 (the fold: 0.8506)
    >>> theta, settled, unstable = solve_to_fold(geo, np.append(p, 1.0)[None, :], np.array([[2.0]]),
    ...                                          rtol=1e-10, atol=1e-22)
    >>> bool(np.all(np.abs(rates.m_of(theta[:, :2]) / [0.81, 0.84] - 1.0) < 1e-12)), settled.tolist(), unstable.tolist()
    (True, [[True, True, False]], [[False, False, True]])
    """
    n = t.shape[0]
    theta = np.zeros(t.shape)
    settled, unstable = np.zeros(t.shape, dtype=bool), np.zeros(t.shape, dtype=bool)
    rates = _m.StretchRates.of(geo)
    lo, hi = np.full((n, 1), RISE_M), np.minimum(m_end, FOLD_BEFORE_M)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        s_lo, s_hi = rates.slope(lo)[:, 0], rates.slope(hi)[:, 0]
        rows = np.flatnonzero((s_lo > 0.0) & (s_hi < 0.0))
        if rows.size == 0:
            return theta, settled, unstable
        geo = geo.take(rows)
        rates, t, scale = _m.StretchRates.of(geo), t[rows], rates.scale[rows]

        def slope(x, k):
            return _m.StretchRates.of(geo.take(k)).slope(x[:, None])[:, 0]

        fold = solvers.illinois(slope, lo[rows, 0], hi[rows, 0], s_lo[rows], s_hi[rows], rtol=solvers.FOLD_RTOL,
                                atol=0.0)[:, None]
        m = RISE_M + (fold - RISE_M) * _FOLD_FRACTIONS
        f, v = rates(m)
        p = f / v
        tt = t / scale
        top = (tt >= p[:, :1]) & (t > 0.0)  # above the nodes below: this table's
        over = top & (tt >= p[:, -1:])
        rises = np.all(p[:, 1:] > p[:, :-1], axis=1)[:, None]
        r_e, c_e = np.nonzero(top & ~over & rises)
        te = tt[r_e, c_e][:, None]  # the entries as (entries, 1) columns, as their designs' rates are
        i = np.minimum(np.sum(p[r_e] <= te, axis=1) - 1, FOLD_NODES - 2)
        # the start: the secant in w = sqrt(P(fold) - P), in which m runs straight through the fold
        w = np.sqrt(p[:, -1:] - p)
        (ma, wa), (mb, wb) = ([a[r_e, j][:, None] for a in (m, w)] for j in (i, i + 1))
        x0 = ma + (mb - ma) * ((wa - np.sqrt(p[r_e, -1:] - te)) / (wa - wb))
        d = np.minimum(_SPACING * (mb - ma), _SPACING * np.abs(x0))
        ke = _m.StretchRates.of(geo.take(r_e))
        r = []
        for z in STENCIL:
            fs, vs = ke(x0 + d * z)
            r.append(fs - te * vs)
        ms, ok = _polish(x0, d, r[0], r[1], r[2], r[3], float(rtol), atol / ke.theta_per_m)
        out = np.zeros(t.shape)
        out[r_e, c_e] = ke.theta(ms)[:, 0]
        done = np.zeros(t.shape, dtype=bool)
        done[r_e, c_e] = ok[:, 0]
        fold_theta = rates.theta(fold)
        over &= rises
    theta[rows] = np.where(over, fold_theta, np.where(done, out, 0.0))
    settled[rows], unstable[rows] = done, over
    return theta, settled, unstable
