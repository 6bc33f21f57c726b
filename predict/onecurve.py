"""The curve of one model on its cached branch: what ``curve(model, ...)`` runs with ``method="auto"``.

:func:`one_curve` answers any pressures on numpy arrays: the lean solve
(:mod:`embroact.predict.lean`) for targets on the branch's rising part, the trace inverse
for the rest (fold, branch end, targets the lean solve does not settle), the tube law
below P0, then the states and the validity limits. :func:`one_curve_floats` answers a
handful of pressures on Python floats, where numpy's fixed cost per operation would be
most of the time; it serves only bending points the lean solve settles and returns None
otherwise (the caller then asks :func:`one_curve`). Both compute each state with the
same operations (:meth:`~embroact.predict.model.StretchRates.state`), so a pressure gets
the same bits whichever path, and
whatever other pressures the call holds (the targets the trace inverse solves are solved
one at a time for that, except those beyond the lean table: one call that keeps one tabulation, where
they do not depend on each other).

Examples
--------
>>> from embroact.predict.curve import ActuatorModel, curve
>>> m = ActuatorModel("cross", length_mm=100, r0_mm=2.6, beta0_deg=20.0, outer_radius_mm=1.5,
...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=1.3, p0_kpa=170)
>>> one, many = curve(m, [230.0]), curve(m, [0.0, 230.0, 260.0])
>>> bool(one.theta_deg[0] == many.theta_deg[1]), bool(one.beta_deg[0] == many.beta_deg[1])
(True, True)
"""
from __future__ import annotations

import math

import numpy as np

from . import model as _m
from .floats import SCALAR
from .inflation import KPA_PER_MPA
from .lean import solve_lean, solve_lean_scalar
from .solvers import trace_inverse
from .status import Status
from .tubelaws import radius_mm
from .validity import FULL_TURN_RAD, apply_limits, contact_free_below_rad, contact_range_rad

__all__ = ["state", "free_tube_radius", "tube_radius_of", "trace_outcome", "one_curve", "one_curve_floats",
           "FLOAT_PATH_MAX"]

#: Largest number of pressures :func:`one_curve_floats` takes (above it numpy's arrays are cheaper).
FLOAT_PATH_MAX = 8
_DEG_PER_RAD = 180.0 / math.pi  # numpy's degrees() multiplies by this same double
_INFLATION, _BENDING, _UNSTABLE, _FAILED, _COILED = (int(s) for s in (Status.INFLATION, Status.BENDING,
                                                                        Status.UNSTABLE, Status.FAILED, Status.COILED))


def state(theta, g: _m.Geometry):
    """(l, r, beta [deg], d^2) on the constraint at bend angles ``theta`` [rad] of the scalar geometry ``g``
    (the trace inverse's answers, the straight state; the lean solve's come from its stretch).

    Parameters
    ----------
    theta : numpy.ndarray
        Bend angles [rad].
    g : Geometry
        One design, its fields floats (:meth:`~embroact.predict.model.Geometry.scalar`).

    Returns
    -------
    l, r, beta, d2
        Thread-side length [mm], sleeve radius [mm], thread angle [deg], inner radius squared [mm^2].

    Examples
    --------
    >>> from embroact.predict.model import Geometry
    >>> g = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.5, c_mm2=1.25, g_mpa=1.0, p0_mpa=0.1).scalar()
    >>> [round(float(v[0]), 6) for v in state(np.array([0.5]), g)]  # l = l0 + 2 r0 theta, d^2 = r0^2 - c 2 l0/(l + l0)
    [102.5, 2.5, 0.0, 5.015432]
    """
    u, cos2, _, _, _ = _m.pantograph(theta, g)
    l = g.l0 * u
    r = g.r_c0 * np.sqrt(cos2)
    beta = np.arcsin(np.minimum(np.maximum(u * g.s0, -1.0), 1.0)) * _DEG_PER_RAD
    return l, r, beta, _m.inner_radius_sq(l, r, g)


def free_tube_radius(p, law, tube, r0, p_sleeve, sleeve_r0_mm):
    """Outer radius [mm] of the tube below P0 at pressures ``p`` [MPa]: its law (``tube`` as
    :func:`~embroact.predict.tubelaws.radius_mm` takes it) until it meets the sleeve (r0, reached at
    ``p_sleeve`` [kPa]); a P0 above the law's pressure at r0 leaves it at r0 in between; never more
    than the sleeve's ``sleeve_r0_mm`` (a sleeve narrower than the tube squeezes it).

    Parameters
    ----------
    p : numpy.ndarray
        Pressures [MPa].
    law : str
        The tube law.
    tube : tuple of arrays
        The tube as :func:`~embroact.predict.tubelaws.radius_mm` takes it.
    r0 : array_like
        Where the tube meets the sleeve [mm].
    p_sleeve : array_like
        The law's pressure at ``r0`` [kPa].
    sleeve_r0_mm : float
        The sleeve's radius [mm].

    Returns
    -------
    numpy.ndarray
        Outer radius [mm].

    Examples
    --------
    >>> from embroact.predict.curve import ActuatorModel, _geometry, _tube_laws
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0, outer_radius_mm=1.5,
    ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
    >>> (_, law, tube, r0, p_sleeve), = _tube_laws(_geometry([m]), [m])  # as sweep takes them
    >>> free_tube_radius(np.array([0.0, 0.05, 0.09]), law, tube, r0, p_sleeve, m.r0_mm).round(4).tolist()
    [[1.5, 2.2957, 2.5814]]
    """
    pk = np.minimum(p * KPA_PER_MPA, p_sleeve)
    return np.minimum(np.where(pk >= p_sleeve, r0, radius_mm(pk, tube, law)), sleeve_r0_mm)


def tube_radius_of(law, tube, r0, p_sleeve, sleeve_r0_mm):
    """``radius(p)``: :func:`free_tube_radius` of one model at pressures ``p`` [MPa] (1-D), its constants bound
    (``tube`` and the rest as numbers); the paper's law in closed form, ``r_f (q + sqrt(q^2 + 4))/2`` with
    ``q = sqrt(2 P/G_e)`` up to the sleeve (the same values to rounding), the thick-wall law by its inverse.

    Parameters
    ----------
    law : str
        ``"paper"`` or ``"thick-wall"``.
    tube : tuple of float
        ``(r_f, d_f, G_e)`` [mm, mm, MPa].
    r0 : float
        Radius where the tube meets the sleeve [mm].
    p_sleeve : float
        The law's pressure at ``r0`` [kPa].
    sleeve_r0_mm : float
        The sleeve's radius [mm] (the tube never exceeds it).

    Returns
    -------
    callable
        ``radius(p)`` [mm] at pressures ``p`` [MPa].

    Examples
    --------
    >>> r = tube_radius_of("paper", (1.5, 1.0, 0.13), 2.5814, 84.45, 2.5814)
    >>> [round(float(v), 4) for v in r(np.array([0.0, 0.08445, 0.2]))]
    [1.5, 2.5814, 2.5814]
    """
    if law != "paper":
        return lambda p: free_tube_radius(p, law, tube, r0, p_sleeve, sleeve_r0_mm)
    rf, _, g_e = (float(v) for v in tube)
    cap, top, k = min(float(r0), float(sleeve_r0_mm)), float(p_sleeve) / KPA_PER_MPA, 2.0 / g_e

    def radius(p):
        q = np.sqrt(np.minimum(p, top) * k)
        return np.minimum((0.5 * rf) * (q + np.sqrt(q * q + 4.0)), cap)

    return radius


def trace_outcome(theta, where, full, kind):
    """(theta, status) of the trace inverse's answers (:func:`~embroact.predict.solvers.trace_inverse`):
    ``where`` 1, past the branch end: the end and its status ``kind``; 2, past a fold: UNSTABLE at the
    fold; a non-finite angle: FAILED with theta 0; the rest BENDING.

    Parameters
    ----------
    theta : numpy.ndarray
        The trace inverse's angles [rad].
    where : numpy.ndarray of int8
        Its outcome per angle (0 solved, 1 beyond the end, 2 beyond a fold).
    full : float or numpy.ndarray
        The branch end [rad].
    kind : int
        The status at the branch end.

    Returns
    -------
    theta : numpy.ndarray
        [rad].
    status : numpy.ndarray of int8

    Examples
    --------
    >>> theta, status = trace_outcome(np.array([0.1, 0.2, np.nan, 0.3]), np.array([0, 1, 0, 2]), 0.5, 2)
    >>> theta.tolist(), [Status(s).name for s in status]
    ([0.1, 0.5, 0.0, 0.3], ['BENDING', 'LOCKED', 'FAILED', 'UNSTABLE'])
    """
    theta = np.where(where == 1, full, theta)
    status = np.where(where == 2, _UNSTABLE, np.where(where == 1, kind, _BENDING))
    bad = ~np.isfinite(theta)
    return np.where(bad, 0.0, theta), np.where(bad, _FAILED, status).astype(np.int8)


def _trace_groups(br, t, settled):
    """The entries of ``t`` the trace inverse solves, in calls, and whether the call may zoom: those at or
    above the lean table's last node (near a fold or past it) in one call without a zoom, whose answers then
    depend each on its own target only (:func:`~embroact.predict.solvers.trace_inverse`); then each other
    target the lean solve did not settle, one call each with the zoom (it follows the largest target of a
    call, so an answer would otherwise depend on the others)."""
    above = t >= br.lean.top
    return ([(np.flatnonzero(above), False)] if above.any() else []) + [([k], True)
                                                                          for k in np.flatnonzero(~settled & ~above)]


def one_curve(br, p, *, limits: bool = True):
    """Arrays (P [kPa], theta [deg], status, l, r, beta, d) of one model at pressures ``p`` [MPa] (1-D).

    Bending targets: the lean solve's stretch m and the state there
    (:meth:`~embroact.predict.model.StretchRates.state`), the trace inverse's theta and its state for
    the targets the lean solve leaves (:func:`_trace_groups`); inflation points: the straight state with
    the tube law's radius.

    Parameters
    ----------
    br : branch
        The model's cached branch (kept by :mod:`embroact.predict.curve`).
    p : numpy.ndarray (n,)
        Pressures [MPa], >= 0.
    limits : bool, optional
        Apply the validity limits.

    Returns
    -------
    tuple of numpy.ndarray
        P [kPa], theta [deg], status, l [mm], r [mm], beta [deg], d [mm].

    Examples
    --------
    >>> from embroact.predict.curve import ActuatorModel, _branch
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0, outer_radius_mm=1.5,
    ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
    >>> br = _branch(m, 1e-10)  # the branch curve(m, ...) keeps
    >>> p_kpa, theta_deg, status, *_ = one_curve(br, np.array([0.05, 0.2]))
    >>> p_kpa.tolist(), theta_deg.round(3).tolist(), status.tolist()
    ([50.0, 200.0], [0.0, 102.93], [0, 1])
    """
    g, lean = br.scalar, br.lean
    t = p - g.p0
    bend = t > 0.0
    every = bool(np.logical_and.reduce(bend))
    groups = []
    if lean is None:  # no branch: the straight state, with the end's status for the bending targets
        status = np.full(p.size, _INFLATION, dtype=np.int8)
        theta = np.zeros(p.size)
        l, r, beta, d2 = state(theta, g)
        status[bend] = br.end_kind
    else:
        status = bend.astype(np.int8)  # BENDING (1) where it bends, INFLATION (0) below P0
        tb = t if every else t[bend]
        m = np.zeros(p.size)
        if tb.size:
            mb, settled = solve_lean(lean, tb)
            if not np.logical_and.reduce(settled):
                at = np.arange(p.size) if every else np.flatnonzero(bend)
                groups = [(at[k], zoom) for k, zoom in _trace_groups(br, tb, settled)]
                mb[~settled] = 0.0
            if every:
                m = mb
            else:
                m[bend] = mb
        theta, l, r, beta, d2 = lean.rates.state(m)
    for rest, zoom in groups:
        a = br.arrays()
        th, where, _, _ = trace_inverse(a.rate, a.full, t[None, rest], slope=a.slope, grid_points=br.points,
                                        rtol=br.rtol, atol=br.atol, ptol=a.ptol, pole_at_end=a.pole, memo=br.memo,
                                        zoom=zoom)
        theta[rest], status[rest] = trace_outcome(th[0], where[0], br.end, br.end_kind)
        l[rest], r[rest], beta[rest], d2[rest] = state(theta[rest], g)
    if not every:
        infl = ~bend
        free = br.laws()(p[infl])
        r[infl] = free
        d2[infl] = free * free - g.c
    if limits:
        status = apply_limits(status, theta, l, r, g.l0, stub_mm=br.model.stub_mm)
    return p * KPA_PER_MPA, theta * _DEG_PER_RAD, status, l, r, beta, np.sqrt(np.maximum(d2, 0.0))


def one_curve_floats(br, p, *, limits: bool = True):
    """As :func:`one_curve` for pressures ``p`` [MPa] given as a list of floats: its float columns in one flat
    list and the statuses as ints, or None when a pressure is not a bending point the lean solve settles.

    Parameters
    ----------
    br : branch
        The model's cached branch.
    p : list of float
        Pressures [MPa].
    limits : bool, optional
        Apply the validity limits.

    Returns
    -------
    (list of float, list of int) or None
        The float columns of :func:`one_curve` (P [kPa], theta [deg], l, r, beta, d) one after another, ``len(p)``
        values each, and the status of each pressure.

    Examples
    --------
    >>> from embroact.predict.curve import ActuatorModel, _branch
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0, outer_radius_mm=1.5,
    ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
    >>> br = _branch(m, 1e-10)  # the branch curve(m, ...) keeps
    >>> floats, status = one_curve_floats(br, [0.2])
    >>> floats[1] == float(one_curve(br, np.array([0.2]))[1][0]), status
    (True, [1])
    >>> one_curve_floats(br, [0.05]) is None  # below P0: not a bending point
    True
    """
    lean, g = br.lean, br.scalar
    if lean is None:
        return None
    n = len(p)
    floats, codes = [0.0] * (6 * n), []
    for k, pk in enumerate(p):
        t = pk - g.p0
        m = solve_lean_scalar(lean, t) if t > 0.0 else None
        if m is None:
            return None
        theta, l, r, beta, d2 = lean.rates.state(m, SCALAR)
        if not limits:
            codes.append(_BENDING)
        elif abs(theta) >= FULL_TURN_RAD:  # coiled, the first limit: no bound or test to ask
            codes.append(_COILED)
        else:
            free = br.lazy.get("free")
            if free is None:  # no state of the branch touches below it (its radius is at most r0/cos(beta0))
                free = br.lazy["free"] = contact_free_below_rad(g.l0, g.r_c0, br.model.stub_mm)
            codes.append(apply_limits(_BENDING, theta, l, r, g.l0, SCALAR, br.model.stub_mm, free) if abs(theta) < free
                         else _status_float(br, theta, l, r, free))
        floats[k::n] = pk * KPA_PER_MPA, theta * _DEG_PER_RAD, l, r, beta, math.sqrt(max(d2, 0.0))
    return floats, codes


def _status_float(br, theta: float, l: float, r: float, free: float) -> int:
    """The status of one bending state of the lean span on floats at or past ``free``:
    :func:`~embroact.predict.validity.apply_limits`, or COILED where the branch's contact range says it touches.

    The contact range (:func:`~embroact.predict.validity.contact_range_rad` over the radii of the lean span, whose
    states the float path answers) is made when a second state reaches ``free`` (the first takes the contact test
    alone, a first curve's cost); where it decides a state, the test is spared."""
    contact = br.lazy.get("contact")
    if contact is None:
        br.lazy["contact"] = False  # the first state here: the test alone
    elif contact is False:
        g, lean = br.scalar, br.lean
        r_lo, r_hi = sorted((g.r0, lean.rates.state(lean.span, SCALAR)[2]))
        contact = br.lazy["contact"] = contact_range_rad(g.l0, r_lo, r_hi, br.model.stub_mm, lean.span < 0.0)
    touches = contact.touches(theta, r) if contact else None
    if touches:
        return _COILED
    return apply_limits(_BENDING, theta, l, r, br.scalar.l0, SCALAR, br.model.stub_mm, free if touches is None
                        else math.inf)  # apart: no contact to test
