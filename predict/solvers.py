"""Numerical machinery of the model: derivatives, quadrature, bracketing and tracing.

Generic over callables; the physics is in :mod:`embroact.predict.model`. All
routines are vectorised over numpy arrays (one design per row); the only Python
loops are fixed-length iterations of vectorised updates, and the per-pressure
scalar root finder of the ``"root"`` inverse (which is the point of that method).

Derivatives (``method=``)
-------------------------
``"central"``
    ``(f(x+h) - f(x-h))/(2h)`` with ``h = eps^(1/3) * scale``: error ~ ``eps^(2/3)``
    relative to the size of ``f`` (truncation h^2 against round-off eps/h), so a
    derivative that is small compared with ``f`` (``dE/dtheta`` near the straight
    state) keeps only ~1e-10 absolute accuracy in units of ``f/scale``.
``"complex"``
    ``Im f(x + i h)/h`` with ``h = 1e-30 * scale``: no subtraction, exact to round-off,
    but ``f`` must be analytic and written with complex-safe operations; it
    inherits any cancellation already inside ``f`` (the printed ``T``).

Inverses
--------
:func:`trace_inverse` tabulates the equilibrium residual on a grid along the branch
(a parametric trace in theta), finds each target's bracket from the tabulated
pressures, interpolates linearly and polishes with the Illinois variant of regula
falsi (superlinear, never leaves the bracket). It follows the branch from theta = 0
only, so it cannot jump to another branch; a fold narrower than the grid spacing is
missed. :func:`root_each` runs scipy's ``brentq`` per target on the whole branch: it
returns *a* root in the bracket, which may belong to an unstable or later branch
when P(theta) is not monotone.

Examples
--------
>>> import numpy as np
>>> from embroact.predict.solvers import derivative, gauss_legendre
>>> bool(abs(derivative(np.sin, np.array(0.5), scale=1.0, method="complex") - np.cos(0.5)) < 1e-15)
True
>>> x, w = gauss_legendre(4)
>>> round(float(w @ x**6), 12) == round(2 / 7, 12)
True
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..patterns.errors import ParameterError, SolverError

__all__ = [
    "DERIVATIVE_METHODS",
    "derivative",
    "gauss_legendre",
    "bisect",
    "illinois",
    "trace_inverse",
    "root_each",
]

DERIVATIVE_METHODS = ("central", "complex")
#: Central-difference step relative to the function's length scale: cbrt(machine epsilon).
CENTRAL_STEP = float(np.cbrt(np.finfo(np.float64).eps))
#: Complex step relative to the length scale (any tiny value works; no cancellation).
COMPLEX_STEP = 1e-30
#: Iteration caps of the vectorised bracketing methods (float64 halves 1 to 0 in ~1075 steps).
BISECT_ITERATIONS = 64
ILLINOIS_MAX_ITERATIONS = 100
#: Newton steps on the interpolating cubic (no model evaluations) and on the model.
CUBIC_NEWTON_STEPS = 4
NEWTON_STEPS = 6
#: Largest (rows x targets x grid) boolean block when bracketing targets in a table.
BRACKET_BLOCK = 1 << 22


def derivative(f, x, *, scale, method: str):
    """Derivative of the vectorised function ``f`` at ``x`` by ``method`` ("central" or "complex").

    ``scale`` is the length over which ``f`` changes appreciably (sets the step).
    """
    if method == "central":
        h = CENTRAL_STEP * scale
        return (f(x + h) - f(x - h)) / (2.0 * h)
    if method == "complex":
        h = COMPLEX_STEP * scale
        return np.imag(f(x + 1j * h)) / h
    raise ParameterError(f"derivative method must be one of {DERIVATIVE_METHODS}, got {method!r}")


@lru_cache(maxsize=None)
def gauss_legendre(n: int):
    """Nodes and weights of the ``n``-point Gauss-Legendre rule on [-1, 1] (read-only)."""
    x, w = np.polynomial.legendre.leggauss(n)
    x.flags.writeable = False
    w.flags.writeable = False
    return x, w


def bisect(inside, lo, hi, iterations: int = BISECT_ITERATIONS):
    """Vectorised bisection of a boolean predicate: ``inside(lo)`` true, ``inside(hi)`` false.

    Returns the last point found inside (a lower bracket of the boundary).
    """
    lo, hi = np.array(lo, dtype=np.float64), np.array(hi, dtype=np.float64)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        ok = inside(mid)
        lo, hi = np.where(ok, mid, lo), np.where(ok, hi, mid)
    return lo


def illinois(residual, a, b, fa, fb, *, rtol, atol, active=None, max_iterations: int = ILLINOIS_MAX_ITERATIONS):
    """Vectorised Illinois regula falsi on brackets ``fa < 0 < fb`` (or the reverse).

    ``residual(x, active)`` evaluates the function at the entries selected by the
    boolean mask ``active`` (x has the full shape); entries not in the initial
    ``active`` mask (default: all) are returned as ``a``. Stops entrywise when the step
    or the bracket falls below ``rtol * |x| + atol``. Raises :class:`SolverError` if any entry
    has not converged after ``max_iterations``.
    """
    a, b, fa, fb = (np.array(v, dtype=np.float64) for v in (a, b, fa, fb))
    x = a.copy()
    active = np.ones(a.shape, dtype=bool) if active is None else np.array(active, dtype=bool)
    side = np.zeros(a.shape, dtype=np.int8)  # which end was kept last: -1 a, +1 b
    for _ in range(max_iterations):
        with np.errstate(invalid="ignore", divide="ignore"):
            xn = b - fb * (b - a) / (fb - fa)
        xn = np.where(np.isfinite(xn) & (xn > np.minimum(a, b)) & (xn < np.maximum(a, b)), xn, 0.5 * (a + b))
        step = np.abs(xn - x)
        x = np.where(active, xn, x)
        fx = residual(x, active)
        same_as_a = np.sign(fx) == np.sign(fa)
        # replace the end with the same sign; halve the kept end's value if kept twice
        fb_half = np.where(same_as_a & (side == 1), 0.5 * fb, fb)
        fa_half = np.where(~same_as_a & (side == -1), 0.5 * fa, fa)
        a, fa = np.where(active & same_as_a, x, a), np.where(active & same_as_a, fx, np.where(active, fa_half, fa))
        b, fb = np.where(active & ~same_as_a, x, b), np.where(active & ~same_as_a, fx, np.where(active, fb_half, fb))
        side = np.where(active, np.where(same_as_a, 1, -1), side).astype(np.int8)
        tol = rtol * np.abs(x) + atol
        done = (step <= tol) | (np.abs(b - a) <= tol) | (fx == 0.0)
        active &= ~done
        if not active.any():
            return x
    raise SolverError(
        f"regula falsi did not converge in {max_iterations} iterations on {int(active.sum())} point(s); "
        f"bracket width up to {float(np.max(np.abs(b - a)[active])):.3g}"
    )


def trace_inverse(rate, theta_end, targets, *, slope, grid_points: int, rtol, atol, pole_at_end=False):
    """theta(P) along the branch from 0 to ``theta_end`` by tabulation and polish.

    Parameters
    ----------
    rate : callable
        ``rate(theta) -> (dE/dtheta, dV/dtheta)`` for an ``(n, k)`` array, one design per row.
    slope : callable
        ``slope(theta)``, a smooth function with the sign of dP/dtheta along the branch
        (zero at a fold), for ``(n, 1)`` arrays.
    theta_end : ndarray, shape (n, 1)
        End of each branch (lock-up, domain end or cap; finite, sign = bending direction).
    targets : ndarray, shape (n, m)
        Pressures minus P0 [MPa], > 0.
    grid_points : int
        Tabulation points along each branch.
    rtol, atol : float
        Converged when a step is below ``rtol * |theta| + atol`` [rad].
    pole_at_end : bool or ndarray (n, 1)
        True where ``theta_end`` is a lock-up (P -> +inf there).

    Returns
    -------
    theta : ndarray (n, m)
        Equilibrium angle; for targets beyond the traced part, the end point.
    where : ndarray of int8 (n, m)
        0 solved, 1 target above the branch end, 2 target above a fold (unstable).
    theta_stop, p_stop : ndarray (n, 1)
        Where the stable part of the branch stops (fold or end) and P - P0 there.
    """
    s = np.linspace(0.0, 1.0, grid_points)
    grid = theta_end * s
    de, dv = rate(grid)
    with np.errstate(divide="ignore", invalid="ignore"):
        p = de / dv
    p[:, 0] = 0.0
    p[:, -1] = np.where(np.ravel(np.broadcast_to(pole_at_end, theta_end.shape)) | ~np.isfinite(p[:, -1]),
                        np.inf, p[:, -1])
    rising = np.diff(p, axis=1) > 0.0
    first_fall = np.where(rising.all(axis=1), grid_points - 1, np.argmin(rising, axis=1))
    folded = first_fall < grid_points - 1
    rows = np.arange(grid.shape[0])
    theta_stop = grid[rows, first_fall][:, None]
    p_stop = p[rows, first_fall][:, None]
    if folded.any():  # refine the fold: the root of the slope between the last rising point's neighbours
        lo = grid[rows, np.maximum(first_fall - 1, 0)][:, None]
        hi = grid[rows, np.minimum(first_fall + 1, grid_points - 1)][:, None]
        s_lo, s_hi = slope(lo), slope(hi)
        change = folded[:, None] & (np.sign(s_lo) != np.sign(s_hi))
        if change.any():
            t_fold = illinois(lambda t, act: np.where(act, slope(t), 0.0), lo, hi, s_lo, s_hi,
                              rtol=rtol, atol=atol, active=change)
            e, v = rate(t_fold)
            with np.errstate(divide="ignore", invalid="ignore"):
                theta_stop = np.where(change, t_fold, theta_stop)
                p_stop = np.where(change, e / v, p_stop)
    beyond = targets > p_stop
    i = _bracket_index(p, np.maximum(first_fall, 1), np.where(beyond, 0.0, targets))
    where = np.where(beyond, np.where(folded[:, None], 2, 1), 0).astype(np.int8)
    r2 = rows[:, None]
    ta, tb = grid[r2, i], grid[r2, i + 1]
    with np.errstate(invalid="ignore"):
        ra, rb = de[r2, i] - targets * dv[r2, i], de[r2, i + 1] - targets * dv[r2, i + 1]
    solve = ~beyond & (np.sign(ra) != np.sign(rb))
    theta = np.where(ra == 0.0, ta, tb)
    if np.any(solve):
        theta = np.where(solve, _polish(rate, grid, de, dv, i, targets, (ta, tb, ra, rb), solve, (rtol, atol)), theta)
    theta = np.where(beyond, theta_stop, theta)
    return theta, where, theta_stop, p_stop


#: Power-basis coefficients of the cubic through (0, f0), (1, f1), (2, f2), (3, f3).
_CUBIC = np.linalg.inv(np.vander(np.arange(4.0), 4, increasing=True))


def _polish(rate, grid, de, dv, i, targets, bracket, solve, tols):
    """Roots of R = dE - t dV in each bracket ``(ta, tb, R(ta), R(tb))``.

    A cubic through the four tabulated residuals around the bracket gives the start
    (its root) and the slope; Newton steps on the true residual finish. Steps that
    leave the bracket, or entries still moving after ``NEWTON_STEPS``, go to Illinois.
    """
    ta, tb, ra, rb = bracket
    rtol, atol = tols
    h = grid[:, 1:2] - grid[:, 0:1]
    j = np.clip(i - 1, 0, grid.shape[1] - 4)
    r2 = np.arange(grid.shape[0])[:, None]
    window = j[..., None] + np.arange(4)
    coef = (de[r2[..., None], window] - targets[..., None] * dv[r2[..., None], window]) @ _CUBIC.T
    c0, c1, c2, c3 = coef[..., 0], coef[..., 1], 2.0 * coef[..., 2], 3.0 * coef[..., 3]
    u_lo = (i - j).astype(np.float64)
    with np.errstate(divide="ignore", invalid="ignore"):
        u = u_lo + ra / (ra - rb)
        for _ in range(CUBIC_NEWTON_STEPS):  # root of the cubic in [u_lo, u_lo + 1] (u = (x - grid_j)/h)
            u = u - (c0 + u * (c1 + u * (coef[..., 2] + u * coef[..., 3]))) / (c1 + u * (c2 + u * c3))
            u = np.clip(np.where(u == u, u, u_lo + 0.5), u_lo, u_lo + 1.0)
    base = grid[r2, j]
    lo, hi = np.minimum(ta, tb), np.maximum(ta, tb)
    x = base + h * u
    active = solve.copy()
    for _ in range(NEWTON_STEPS):
        e, v = rate(x)
        fx = e - targets * v
        uu = (x - base) / h
        with np.errstate(divide="ignore", invalid="ignore"):
            xn = x - fx * h / (c1 + uu * (c2 + uu * c3))
        ok = (xn >= lo) & (xn <= hi)
        done = ok & ((np.abs(xn - x) <= rtol * np.abs(x) + atol) | (fx == 0.0))
        x = np.where(active & ok, xn, x)
        active &= ok & ~done
        if not active.any():
            break
    stuck = solve & ~((x >= lo) & (x <= hi)) | active
    if stuck.any():
        def residual(t, act):
            e, v = rate(t)
            return np.where(act, e - targets * v, 0.0)

        x = np.where(stuck, illinois(residual, ta, tb, ra, rb, rtol=rtol, atol=atol, active=stuck), x)
    return x


def _bracket_index(values, last, targets):
    """Per row, the index i < last[row] with values[i] <= target < values[i+1].

    ``values[:, :last+1]`` must be increasing; targets outside give the nearest end
    interval. Counts in blocks of rows to bound the (rows, targets, grid) temporary.
    """
    n, k = values.shape
    usable = np.arange(k) <= last[:, None]
    out = np.empty(targets.shape, dtype=np.intp)
    step = max(1, BRACKET_BLOCK // max(1, targets.shape[1] * k))
    for lo in range(0, n, step):
        v, t = values[lo:lo + step], targets[lo:lo + step]
        out[lo:lo + step] = ((v[:, None, :] <= t[:, :, None]) & usable[lo:lo + step, None, :]).sum(axis=2)
    return np.clip(out - 1, 0, np.minimum(last, k - 1)[:, None] - 1)


def root_each(residual, lo, hi, *, rtol, atol):
    """Per-target scalar bracketing root finding (scipy ``brentq``) on [lo, hi].

    ``residual(x, k)`` is the scalar residual of target ``k``; ``lo``, ``hi`` are
    1-D arrays. Entries whose bracket has no sign change return ``hi``; entries
    where the residual is not finite (a failing method) return nan.
    """
    from scipy.optimize import brentq

    out = np.array(hi, dtype=np.float64)
    for k, (a, b) in enumerate(zip(lo, hi)):
        fa, fb = residual(a, k), residual(b, k)
        if not (np.isfinite(fa) and np.isfinite(fb)):
            out[k] = np.nan
        elif fa == 0.0:
            out[k] = a
        elif np.sign(fa) != np.sign(fb):
            try:
                out[k] = brentq(residual, a, b, args=(k,), xtol=atol, rtol=max(rtol, 4 * np.finfo(float).eps))
            except ValueError:  # brentq met a nan inside the bracket
                out[k] = np.nan
    return out
