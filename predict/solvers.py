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
:func:`trace_inverse` is a parametric trace in theta: it tabulates the rates
``E'(theta)``, ``V'(theta)`` on a grid along the branch (and again on the part the
targets need when they sit in its first quarter), finds the first fold of
``P = P0 + E'/V'`` on the grid, brackets each target between grid points, starts
from the root of a cubic through the four tabulated residuals
``R = E' - (P - P0) V'`` around the bracket (R has no pole at lock-up, P has) and
finishes with Newton steps on the true residual, stopping when the predicted error
left after a step is below the tolerance or the residual is within the round-off
floor of P(theta) the caller gives (``ptol``); entries a Newton step would take out of
the bracket finish by Illinois regula falsi (bracketing, superlinear). It follows the
branch from theta = 0 only, so it cannot jump to another branch; a fold narrower than
the grid spacing is missed. :func:`root_each` runs scipy's ``brentq`` per target on
the whole branch: it returns *a* root in the bracket, which may belong to an
unstable or later branch, or finds none when P(theta) dips below the target and
ends below it (a missed branch).

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

from ..patterns.base.errors import ParameterError, SolverError

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
#: Machine epsilon of float64.
EPS = float(np.finfo(np.float64).eps)
#: Central-difference step relative to the function's length scale: cbrt(machine epsilon).
CENTRAL_STEP = float(np.cbrt(EPS))
#: Complex step relative to the length scale (any tiny value works; no cancellation).
COMPLEX_STEP = 1e-30
#: Iteration caps of the vectorised bracketing methods (float64 halves 1 to 0 in ~1075 steps).
BISECT_ITERATIONS = 64
ILLINOIS_MAX_ITERATIONS = 100
#: Newton steps on the interpolating cubic (no model evaluations) and on the model.
CUBIC_NEWTON_STEPS = 2
NEWTON_STEPS = 6
#: A branch is tabulated again up to its highest target when that lies within the first 1/ZOOM.
ZOOM = 4
#: Relative tolerance of a located fold at most (the root of the slope: Illinois converges superlinearly, so a
#: few more steps put it at round-off, where the answers past it are, whatever grid bracketed it).
FOLD_RTOL = 16 * EPS


def derivative(f, x, *, scale, method: str):
    """Derivative of the vectorised function ``f`` at ``x`` by ``method`` ("central" or "complex").

    Parameters
    ----------
    f : callable
        ``f(x) -> array``, vectorised; complex arguments for ``"complex"``.
    x : numpy.ndarray
        Where.
    scale : float
        The length over which ``f`` changes appreciably (sets the step).
    method : {"central", "complex"}
        Central difference or complex step.

    Returns
    -------
    numpy.ndarray
        df/dx at ``x``.

    Examples
    --------
    >>> derivative(np.sin, np.array([0.0, 1.0]), scale=1.0, method="complex").round(12).tolist()
    [1.0, 0.540302305868]
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

    Parameters
    ----------
    inside : callable
        ``inside(x) -> bool array``, vectorised.
    lo, hi : array_like
        Brackets: ``inside(lo)`` true, ``inside(hi)`` false.
    iterations : int, optional
        Halvings.

    Returns
    -------
    numpy.ndarray
        The last point found inside (a lower bracket of the boundary).

    Examples
    --------
    >>> bisect(lambda x: x * x < 2.0, 0.0, 2.0).round(12).tolist()
    1.414213562373
    """
    lo, hi = np.array(lo, dtype=np.float64), np.array(hi, dtype=np.float64)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        ok = inside(mid)
        lo, hi = np.where(ok, mid, lo), np.where(ok, hi, mid)
    return lo


def illinois(residual, a, b, fa, fb, *, rtol, atol, max_iterations: int = ILLINOIS_MAX_ITERATIONS):
    """Illinois regula falsi on 1-D brackets ``[a, b]`` with ``sign(fa) != sign(fb)``.

    ``residual(x, idx)`` evaluates the function of entries ``idx`` at ``x`` (both
    1-D); only unconverged entries are evaluated. An entry stops when its step or
    its bracket falls below ``rtol * |x| + atol``, or its residual is 0 (callers
    floor a residual at its round-off level to 0).

    Parameters
    ----------
    residual : callable
        ``residual(x, idx) -> array`` of the entries ``idx`` at ``x`` (both 1-D).
    a, b, fa, fb : array_like (n,)
        Brackets and the residual at them.
    rtol, atol : float
        Step or bracket tolerance.
    max_iterations : int, optional
        Iterations before giving up.

    Returns
    -------
    numpy.ndarray (n,)
        The roots.

    Raises
    ------
    SolverError
        An entry has not converged after ``max_iterations``.

    Examples
    --------
    >>> targets = np.array([2.0, 3.0])
    >>> x = illinois(lambda x, i: x * x - targets[i], [0.0, 0.0], [2.0, 2.0], [-2.0, -3.0], [2.0, 1.0],
    ...              rtol=1e-14, atol=0.0)
    >>> x.round(12).tolist()
    [1.414213562373, 1.732050807569]
    """
    a, b, fa, fb = (np.array(v, dtype=np.float64) for v in (a, b, fa, fb))
    x = a.copy()
    side = np.zeros(a.shape, dtype=np.int8)  # end kept by the last step: -1 a, +1 b
    idx = np.arange(a.size)
    for _ in range(max_iterations):
        if idx.size == 0:
            return x
        ai, bi, fai, fbi = a[idx], b[idx], fa[idx], fb[idx]
        with np.errstate(invalid="ignore", divide="ignore"):
            xn = bi - fbi * (bi - ai) / (fbi - fai)
        inside = np.isfinite(xn) & (xn > np.minimum(ai, bi)) & (xn < np.maximum(ai, bi))
        xn = np.where(inside, xn, 0.5 * (ai + bi))
        step = np.abs(xn - x[idx])
        x[idx] = xn
        fx = residual(xn, idx)
        low = np.sign(fx) == np.sign(fai)  # xn replaces a; if b is kept twice, halve fb
        kept = side[idx]
        fbi = np.where(low & (kept == 1), 0.5 * fbi, fbi)
        fai = np.where(~low & (kept == -1), 0.5 * fai, fai)
        a[idx], fa[idx] = np.where(low, xn, ai), np.where(low, fx, fai)
        b[idx], fb[idx] = np.where(low, bi, xn), np.where(low, fbi, fx)
        side[idx] = np.where(low, 1, -1)
        tol = rtol * np.abs(xn) + atol
        idx = idx[~((step <= tol) | (np.abs(b[idx] - a[idx]) <= tol) | (fx == 0.0))]
    if idx.size == 0:  # the last iteration converged
        return x
    raise SolverError(
        f"regula falsi did not converge in {max_iterations} iterations on {idx.size} point(s); "
        f"bracket width up to {float(np.max(np.abs(b - a)[idx])):.3g}"
    )


def trace_inverse(rate, theta_end, targets, *, slope, grid_points: int, rtol, atol, ptol=0.0,
                  pole_at_end=False, memo=None, zoom=True):
    """theta(P) along the branch from 0 to ``theta_end`` by tabulation and polish.

    Parameters
    ----------
    rate : callable
        ``rate(theta, rows=None) -> (dE/dtheta, dV/dtheta)`` for theta of shape
        ``(n, k)`` (one design per row), or at the designs ``rows`` (theta 1-D, one
        value per row, or 2-D, one row each).
    slope : callable
        ``slope(theta, rows)``, a smooth function with the sign of dP/dtheta along the
        branch (zero at a fold), same calling convention.
    theta_end : ndarray, shape (n, 1)
        End of each branch (lock-up, domain end or cap; finite, sign = bending direction).
    targets : ndarray, shape (n, m)
        Pressures minus P0 [MPa], > 0.
    grid_points : int
        Tabulation points along each branch (and again on a zoomed part, see below).
    rtol, atol : float
        Converged when a step is below ``rtol * |theta| + atol`` [rad].
    ptol : float or ndarray (n, 1)
        Round-off floor of P - P0 [MPa]: also converged where the residual is
        within it, ``|E' - (P - P0) V'| <= ptol |V'|`` (theta is resolved as far as
        P(theta) can be; a target below the floor would otherwise chase noise).
    pole_at_end : bool or ndarray (n, 1)
        True where ``theta_end`` is a lock-up (P -> +inf there).
    memo : dict, optional
        One design only (n = 1): keeps the tabulation, the located fold and each zoom
        (by the grid point it reaches) for the next call with the same arguments, which
        then only polishes; the answers are those of a call without it.
    zoom : bool, optional
        Tabulate again the part up to the highest target where it is short (below); False keeps the one
        tabulation, so that each answer depends on its own target only (the fold is located when some
        target lies above the last rising grid point, and locating it changes no other target's bracket).

    Returns
    -------
    theta : ndarray (n, m)
        Equilibrium angle; for targets beyond the traced part, the end point.
    where : ndarray of int8 (n, m)
        0 solved, 1 target above the branch end, 2 target above a fold (unstable).
    theta_stop, p_stop : ndarray (n, 1)
        Where the stable part of the branch stops (fold or end) and P - P0 there. A
        fold is located exactly (root of ``slope``) only when a target lies above the
        last rising grid point, or when ``targets`` is empty (the caller asks for the
        end); otherwise it is the last rising grid point.

    Notes
    -----
    Rows whose targets all lie in the first quarter of the tabulated branch are
    tabulated again on the part up to the highest target (a zoom), so that the cubic
    start of the polish is accurate without a finer grid everywhere.

    Examples
    --------
    P - P0 = sin(theta) with dV/dtheta = 1: a fold at pi/2, where P - P0 = 1.

    >>> rate = lambda theta, rows=None: (np.sin(theta), np.ones_like(theta))
    >>> slope = lambda theta, rows=None: np.cos(theta)
    >>> theta, where, stop, p_stop = trace_inverse(rate, np.array([[3.0]]), np.array([[0.5, 1.5]]), slope=slope,
    ...                                            grid_points=24, rtol=1e-13, atol=0.0)
    >>> theta.round(6).tolist(), where.tolist(), stop.round(6).tolist(), p_stop.round(9).tolist()
    ([[0.523599, 1.570796]], [[0, 2]], [[1.570796]], [[1.0]])
    """
    memo = {} if memo is None else memo
    if "table" not in memo:
        memo["table"] = _tabulate(rate, theta_end, grid_points, pole_at_end)
    grid, de, dv, p, first_fall = memo["table"]
    rows = np.arange(grid.shape[0])
    theta_stop = grid[rows, first_fall]
    p_stop = p[rows, first_fall]
    top = targets.max(axis=1) if targets.shape[1] else np.full(rows.size, np.inf)
    folded = np.flatnonzero((first_fall < grid_points - 1) & (top > p[rows, np.maximum(first_fall - 1, 0)]))
    if folded.size:  # locate the fold: the root of the slope around the last rising point
        key: tuple = ("fold", folded.tobytes())
        if key not in memo:
            memo[key] = _fold(rate, slope, grid, first_fall, folded, rtol, atol)
        sel, t_fold, p_fold = memo[key]
        theta_stop[sel], p_stop[sel] = t_fold, p_fold
    theta_stop, p_stop = theta_stop[:, None], p_stop[:, None]
    # the stable part ends at the last grid point before the fold (the fold may precede grid[ff])
    last = first_fall - (np.abs(grid[rows, first_fall]) > np.abs(theta_stop[:, 0]))
    reach = np.array([np.searchsorted(p[k, :last[k] + 1], top[k]) for k in rows])  # first point >= top
    short = np.flatnonzero((reach + 1) * ZOOM < last) if zoom else rows[:0]
    if short.size:
        key = ("zoom", short.tobytes(), reach[short].tobytes())
        if key not in memo:
            memo[key] = _zoom(rate, grid, de, dv, p, short, reach[short], grid_points)
        grid, de, dv, p = memo[key]
        last[short] = grid_points - 1
    beyond = targets > p_stop
    where = np.where(beyond, np.where(first_fall[:, None] < grid_points - 1, 2, 1), 0).astype(np.int8)
    theta = np.where(beyond, theta_stop, 0.0)
    # between the last rising grid point and a located fold: bracket [grid point, fold]
    floor = np.broadcast_to(ptol, theta_end.shape)[:, 0]
    tail = ~beyond & (targets > p[rows, last][:, None])
    if tail.any():
        r_t, t_t = np.nonzero(tail)[0], targets[tail]
        a, b = grid[r_t, last[r_t]], theta_stop[r_t, 0]
        fa = de[r_t, last[r_t]] - t_t * dv[r_t, last[r_t]]
        e, v = rate(b, r_t)
        theta[tail] = illinois(_residual_fn(rate, r_t, t_t, floor[r_t]), a, b, fa, e - t_t * v, rtol=rtol,
                               atol=atol)
    i = _bracket_index(p, last, np.where(beyond | tail, 0.0, targets))
    solve = np.nonzero(~beyond & ~tail)
    if solve[0].size:
        theta[solve] = _polish(rate, grid, de, dv, i[solve], solve[0], targets[solve], (rtol, atol, floor))
    return theta, where, theta_stop, p_stop


def _tabulate(rate, theta_end, grid_points, pole_at_end):
    """(grid, E', V', P - P0, first fall) of each branch on ``grid_points`` points; P is 0 at the start, inf at a pole."""
    grid = theta_end * np.linspace(0.0, 1.0, grid_points)
    de, dv = rate(grid)
    with np.errstate(divide="ignore", invalid="ignore"):
        p = de / dv
    p[:, 0] = 0.0
    p[:, -1] = np.where(np.ravel(np.broadcast_to(pole_at_end, theta_end.shape)) | ~np.isfinite(p[:, -1]),
                        np.inf, p[:, -1])
    rising = p[:, 1:] > p[:, :-1]
    first_fall = np.where(rising.all(axis=1), grid_points - 1, np.argmin(rising, axis=1))
    return grid, de, dv, p, first_fall


def _fold(rate, slope, grid, first_fall, folded, rtol, atol):
    """(rows located, fold angle, P - P0 there): the root of the slope around each row's last rising point
    (to :data:`FOLD_RTOL` at least)."""
    lo = grid[folded, np.maximum(first_fall[folded] - 1, 0)]
    hi = grid[folded, first_fall[folded] + 1]
    s_lo, s_hi = slope(lo, folded), slope(hi, folded)
    ok = np.sign(s_lo) != np.sign(s_hi)
    sel = folded[ok]
    t_fold = illinois(lambda x, k: slope(x, sel[k]), lo[ok], hi[ok], s_lo[ok], s_hi[ok], rtol=min(rtol, FOLD_RTOL),
                      atol=atol)
    e, v = rate(t_fold, sel)
    return sel, t_fold, e / v


def _zoom(rate, grid, de, dv, p, zoom, reach, grid_points):
    """Copies of the tables with the rows ``zoom`` tabulated again from 0 to their grid point ``reach + 1``."""
    grid, de, dv, p = grid.copy(), de.copy(), dv.copy(), p.copy()
    grid[zoom] = grid[zoom, reach + 1][:, None] * np.linspace(0.0, 1.0, grid_points)
    de[zoom], dv[zoom] = rate(grid[zoom], zoom)
    with np.errstate(divide="ignore", invalid="ignore"):
        p[zoom] = de[zoom] / dv[zoom]
    p[zoom, 0] = 0.0
    return grid, de, dv, p


def _floored(e, v, t, ptol):
    """Residual ``e - t v``, zero where it is within the round-off floor ``ptol |v|``."""
    r = e - t * v
    return np.where(np.abs(r) <= ptol * np.abs(v), 0.0, r)


def _residual_fn(rate, rows, t, ptol):
    """residual(x, k) of entries k (1-D) of the targets ``t`` on ``rows``, floored (illinois' convention)."""
    def residual(x, k):
        e, v = rate(x, rows[k])
        return _floored(e, v, t[k], ptol[k])

    return residual


def _power_cubic(f):
    """Power-basis coefficients (k, 4) of the cubic through (u, f[:, u]), u = 0..3, from its differences:
    elementwise operations, so each row's coefficients are the same bits however many rows there are (a
    matrix product's are not: BLAS sums a single row in another order)."""
    f0, f1, f2, f3 = f[:, 0], f[:, 1], f[:, 2], f[:, 3]
    d1, d2 = f1 - f0, (f2 - f1) - (f1 - f0)
    d3 = ((f3 - f2) - (f2 - f1)) - d2
    return np.stack([f0, d1 - 0.5 * d2 + d3 / 3.0, 0.5 * (d2 - d3), d3 / 6.0], axis=1)


def _cubics(de, dv, rows, i):
    """Power-basis cubics of E' and V' through the four grid points around interval i of each entry.

    Returns ``(ce, cv, j)``: coefficients (k, 4) in ``u = (theta - grid_j)/h`` and the window's first point j.
    """
    j = np.clip(i - 1, 0, de.shape[1] - 4)
    window = (rows[:, None], j[:, None] + np.arange(4))
    return _power_cubic(de[window]), _power_cubic(dv[window]), j


def _polish(rate, grid, de, dv, i, rows, t, tols):
    """Roots of R = dE - t dV between grid points i and i + 1 of each entry's row (1-D), see :func:`_newton`."""
    ce, cv, j = _cubics(de, dv, rows, i)
    return _newton(rate, (grid[rows, i], grid[rows, i + 1], grid[rows, j], grid[rows, 1] - grid[rows, 0], i - j),
                   (de[rows, i], dv[rows, i], de[rows, i + 1], dv[rows, i + 1]), ce, cv, rows, t, tols)


def _newton(rate, interval, ends, ce, cv, rows, t, tols):
    """Root of R = E' - t V' in each entry's bracket: a cubic's root to start, Newton on the model to finish.

    ``interval`` is (theta_a, theta_b, base, h, u_a): the bracket, the cubic window's first grid
    point and spacing and the bracket's start in ``u = (theta - base)/h``; ``ends`` the
    tabulated (E', V') at both ends; ``ce``, ``cv`` the cubics of E' and V' (:func:`_cubics`).
    The cubic ``ce - t cv`` through the four tabulated residuals gives the start (its root)
    and the slope; Newton steps on the true residual finish. Entries whose step leaves the
    bracket, or that still move after ``NEWTON_STEPS``, go to Illinois.
    """
    rtol, atol, floor = tols
    ta, tb, base, h, u_a = interval
    ra, rb = ends[0] - t * ends[1], ends[2] - t * ends[3]
    x = np.where(ra == 0.0, ta, tb)  # exact grid hits, and no sign change (target at the end)
    todo = np.flatnonzero((np.sign(ra) != np.sign(rb)) & (ra != 0.0))
    if todo.size == 0:
        return x
    if todo.size < x.size:
        ta, tb, base, h, u_a, ra, rb, ce, cv, rows, t = (a[todo] for a in (ta, tb, base, h, u_a, ra, rb, ce, cv,
                                                                           rows, t))
    coef = ce - t[:, None] * cv
    c0, c1, c2, c3 = coef[:, 0], coef[:, 1], coef[:, 2], coef[:, 3]
    d2, d3 = 2.0 * c2, 3.0 * c3
    u_lo = u_a.astype(np.float64)
    with np.errstate(divide="ignore", invalid="ignore"):
        u = u_lo + ra / (ra - rb)
        for _ in range(CUBIC_NEWTON_STEPS):  # root of the cubic in [u_lo, u_lo + 1]
            u = u - (c0 + u * (c1 + u * (c2 + u * c3))) / (c1 + u * (d2 + u * d3))
            u = np.minimum(np.maximum(u, u_lo), u_lo + 1.0)  # nan (flat cubic) goes on to Illinois
    lo, hi = np.minimum(ta, tb), np.maximum(ta, tb)
    xt = base + h * u
    # Newton on the model's residual; the working arrays shrink to the unconverged entries
    work = [np.arange(xt.size), xt.copy(), rows, t, base, h, c1, d2, d3, lo, hi, floor[rows]]
    stuck = []
    for _ in range(NEWTON_STEPS):
        idx, xw, rw, tw, bw, hw, c1w, d2w, d3w, low, hiw, fw = work
        e, v = rate(xw, rw)
        fx = _floored(e, v, tw, fw)
        uu = (xw - bw) / hw
        r_u = c1w + uu * (d2w + uu * d3w)  # dR/du of the cubic
        with np.errstate(divide="ignore", invalid="ignore"):
            xn = xw - fx * hw / r_u
            # error left after the step: the cubic's slope error (bounded by its cubic term)
            # times the step, plus Newton's quadratic term
            step = np.abs(xn - xw)
            left = step * (9.0 * np.abs(d3w) + np.abs(d2w + 2.0 * d3w * uu) * step / hw) / np.abs(r_u)  # R_uu
        ok = (xn >= low) & (xn <= hiw)
        done = ok & ((np.minimum(step, left) <= rtol * np.abs(xn) + atol) | (fx == 0.0))
        if done.all():
            xt[idx] = xn
            act = idx[:0]
            break
        xt[idx] = np.where(ok, xn, xw)
        stuck.append(idx[~ok])
        keep = ok & ~done
        if not keep.any():
            act = idx[:0]
            break
        work = [a[keep] for a in work]
        work[1] = xn[keep]
    else:
        act = work[0]  # still moving after NEWTON_STEPS
    stuck = np.concatenate(stuck + [act]) if stuck else act
    if stuck.size:
        r_s = rows[stuck]
        xt[stuck] = illinois(_residual_fn(rate, r_s, t[stuck], floor[r_s]), ta[stuck], tb[stuck],
                             ra[stuck], rb[stuck], rtol=rtol, atol=atol)
    x[todo] = xt
    return x


def _bracket_index(values, last, targets):
    """Per row, the index i < last[row] with values[i] <= target < values[i+1].

    ``values[:, :last+1]`` must be increasing; targets outside give the nearest end
    interval (the first one when ``last`` is 0). One ``searchsorted`` per row.
    """
    out = np.empty(targets.shape, dtype=np.intp)
    for k, (row, end) in enumerate(zip(values, last)):
        out[k] = np.searchsorted(row[:end + 1], targets[k], side="right") - 1
    return np.clip(out, 0, np.maximum(last - 1, 0)[:, None])


def root_each(residual, lo, hi, *, rtol, atol):
    """Per-target scalar bracketing root finding (scipy ``brentq``) on [lo, hi].

    ``residual(x, k)`` is the scalar residual of target ``k``; ``lo``, ``hi`` are
    1-D arrays. Entries whose bracket has no sign change return ``hi``; entries
    where the residual is not finite (a failing method) or where ``brentq`` does not
    converge (a noisy residual) return nan, which the caller reports as FAILED.

    Parameters
    ----------
    residual : callable
        ``residual(x, k) -> float``, target ``k``'s residual at the scalar ``x``.
    lo, hi : array_like (n,)
        Brackets.
    rtol, atol : float
        ``brentq``'s tolerances.

    Returns
    -------
    numpy.ndarray (n,)
        The roots (``hi`` without a sign change, nan on failure).

    Examples
    --------
    >>> targets = [2.0, 3.0, -1.0]
    >>> root_each(lambda x, k: x * x - targets[k], np.zeros(3), np.full(3, 2.0), rtol=1e-14, atol=1e-14).round(12).tolist()
    [1.414213562373, 1.732050807569, 2.0]
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
                out[k] = brentq(residual, a, b, args=(k,), xtol=atol, rtol=max(rtol, 4 * EPS))
            except (ValueError, RuntimeError):  # a nan inside the bracket, or no convergence
                out[k] = np.nan
    return out
