"""Where the model stops describing a real actuator (docs/model.md section 12).

The deformation model is a formula in theta; it keeps answering past the states a
sewn actuator can reach. Three limits are checked on every state (bend angle theta,
thread-side length l, tube outer radius r, fabric-side length l0) and reported as
statuses (:class:`~embroact.predict.status.Status`, precedence documented there):

``COILED``
    The strip touches itself, the clamp or the fixed fabric (:func:`strip_contact`). Its
    body is the band the tube fills, ``2 r`` thick on the thread side of the fabric line,
    over the bent length and over the sealed tube stub beyond the tip (``stub_mm``, cut
    square); behind the clamp the same band is fixed (the fabric held flat, the supply
    line leaving along the base tangent). For one uniform arc (one model's curve,
    :func:`arc_contact`) the first contact is always the stub's end meeting that fixed
    band. Without a stub a negative bend's tip lands on the supply tube's top once
    ``l0 (1 - cos(theta)) <= 2 r |theta|`` (315.70 deg for ``l0 = 100 mm``,
    ``r = 2.58 mm``) and a positive bend's tube-side tip corner enters the supply tube at
    ``cos theta = R / (R + 2 r)`` (320.9 deg); the worksheet's 30 mm stub reaches it at
    243.1 and 253.9 deg.
``KINKED``
    The bend radius ``l0/|theta|`` is below the tube's diameter ``2 r``: the tube's
    inner side would have to pass through the centre of its own bend.
``OVERSTRETCHED``
    The thread side's stretch ``l/l0`` reaches :data:`STRETCH_LIMIT` (2). The paper
    validated the model up to about 155 deg on 100 mm (a stretch near 1.1 for its
    zigzags); a sleeve twice its length is not a state of a real sleeve. Shortening
    (negative bends) is bounded by the pattern itself (the cross pattern's lock-up).

For a zigzag (``r = r0``, ``l = l0 + 2 r0 theta``) the kink and the stretch limit fall
on the same angle, ``theta = l0/(2 r0)``.

A model's curve checks its one arc (with the stub when the model is a whole strip,
``ActuatorModel.stub_mm``). A strip is valid only as a whole: :func:`strip_contact` tests
its bent line (a chain of arcs, with the sealed tube stub beyond the tip) against itself
and against the fixed part behind the clamp, and :func:`strip_status` decides the status
of a whole strip per pressure from its segments' curves and that test; it is the status
every view reads.

Examples
--------
>>> import numpy as np
>>> from embroact.predict.validity import limit_flags, coil_angle_deg
>>> f = limit_flags(np.radians([90.0, 400.0, -320.0]), [104.0, 118.0, 86.0], 2.58, 100.0)
>>> f.coiled.tolist(), f.kinked.tolist(), f.overstretched.tolist()
([False, True, True], [False, False, False], [False, False, False])
>>> round(coil_angle_deg(100.0, 2.58, negative=True), 1), round(coil_angle_deg(100.0, 2.58, negative=False), 1)
(315.7, 320.9)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..patterns.base.arrays import array_max, array_min
from ..patterns.base.errors import ParameterError, check_range
from .floats import SCALAR
from .status import VALIDITY_LIMITS, Status, is_model_state

__all__ = [
    "STRETCH_LIMIT",
    "FULL_TURN_RAD",
    "LimitFlags",
    "limit_flags",
    "apply_limits",
    "contact_free_below_rad",
    "contact_range_rad",
    "ContactRange",
    "coil_angle_deg",
    "arc_contact",
    "valid_mask",
    "LIMIT_BISECTIONS",
    "strip_contact",
    "strip_status",
    "strip_coil_angle_deg",
    "CONTACT_TOLERANCE_MM",
]

#: Largest thread-side stretch l/l0 reported as a state of a real sleeve (docs/model.md section 12).
STRETCH_LIMIT = 2.0
#: A bend [rad] at or past which a strip is coiled whatever else it exceeds (it has turned onto itself).
FULL_TURN_RAD = 2.0 * math.pi
#: Bisection steps locating a limit angle (to ~1e-15 of the turn; branch.first_limit uses the same).
LIMIT_BISECTIONS = 60


@dataclass(frozen=True, slots=True)
class LimitFlags:
    """Which validity limits each state exceeds (boolean arrays of the states' shape).

    Attributes
    ----------
    coiled, kinked, overstretched : numpy.ndarray of bool
        One flag per state for each limit (:mod:`embroact.predict.status`).

    Examples
    --------
    >>> f = limit_flags([0.5, 7.0], 118.0, 2.58, 100.0)
    >>> f.coiled.tolist(), f.kinked.tolist()
    ([False, True], [False, False])
    """

    coiled: np.ndarray
    kinked: np.ndarray
    overstretched: np.ndarray

    def names(self) -> list[list[str]]:
        """Per point (flattened), the names of the limits it exceeds, in precedence order.

        Returns
        -------
        list of list of str

        Examples
        --------
        >>> limit_flags([0.5, 7.0], 118.0, 2.58, 100.0).names()
        [[], ['COILED']]
        """
        rows = zip(*(np.ravel(getattr(self, k)) for k in ("coiled", "kinked", "overstretched")))
        return [[s.name for s, hit in zip(VALIDITY_LIMITS, row) if hit]
                for row in rows]


def limit_flags(theta_rad, length_mm, radius_mm, l0_mm, stub_mm=0.0) -> LimitFlags:
    """The limits exceeded at states (theta [rad], l, r, l0 [mm]; arrays broadcast).

    Parameters
    ----------
    theta_rad : array_like
        Bend angle (signed as docs/model.md section 5).
    length_mm : array_like
        Thread-side length l.
    radius_mm : array_like
        Tube outer radius r at the state.
    l0_mm : array_like
        Fabric-side length.
    stub_mm : float, optional
        Sealed tube beyond the tip [mm] (as :func:`apply_limits`).

    Returns
    -------
    LimitFlags
        Arrays of the broadcast shape.

    Examples
    --------
    >>> limit_flags(0.1, 260.0, 2.58, 100.0).overstretched.tolist()
    True
    """
    th = np.asarray(theta_rad, dtype=np.float64)
    l, r, l0 = (np.asarray(v, dtype=np.float64) for v in (length_mm, radius_mm, l0_mm))
    flags = _exceeded(th, l, r, l0, stub=stub_mm)
    shape = np.broadcast(th, l, r, l0).shape
    return LimitFlags(*(f if f.shape == shape else np.broadcast_to(f, shape).copy() for f in flags))


def _exceeded(th, l, r, l0, xp=np, stub=0.0, free=0.0):
    """(coiled, kinked, overstretched) at states: arrays, or floats with ``xp=SCALAR`` (``free``: as
    :func:`apply_limits` takes it)."""
    a = abs(th)
    return _coiled(th, a, r, l0, xp, stub, free), 2.0 * r * a > l0, l >= STRETCH_LIMIT * l0


def _coiled(th, a, r, l0, xp=np, stub=0.0, free=0.0):
    """The coiled flags at states of bend ``th`` (``a = |th|``): :func:`arc_contact` with the stub
    (None: an arc inside a chain); one state on floats with ``xp=SCALAR``. The bound
    :func:`_contact_free_below` spares the contact test of a state far from contact, and it alone decides
    which states take it: a short arc with a long stub touches well before a quarter turn."""
    stub = math.nan if stub is None else stub
    if xp is np:
        shape = np.broadcast_shapes(np.shape(th), np.shape(r), np.shape(l0), np.shape(stub))
        return _contact_past_bound(*(np.broadcast_to(np.asarray(v, dtype=np.float64), shape).reshape(-1)
                                     for v in (th, r, l0, stub))).reshape(shape)
    return a >= FULL_TURN_RAD or (a >= (free if free > 0.0 else _contact_free_below(l0, 2.0 * r, stub))
                               and _arc_contact_float(th, r, l0, stub))


#: Margin of :func:`_contact_free_below`'s reach, relative to the lengths involved (the round-off of
#: :func:`arc_contact`'s corners is a few 1e-16 of them).
_BOUND_MARGIN = 1e-9
_SMALLEST = math.ulp(0.0)
#: Bisection steps of :func:`_contact_free_below` (to 1/4096 of the range: the bound need not be tight).
_BOUND_BISECTIONS = 12


def contact_free_below_rad(l0_mm: float, radius_mm: float, stub_mm: float | None) -> float:
    """|theta| [rad] below which one arc of length ``l0_mm``, its tube's radius at most ``radius_mm``, with the stub
    ``stub_mm`` (None: inside a chain) cannot touch (:func:`_contact_free_below`; a bound, not the contact angle).

    Parameters
    ----------
    l0_mm, radius_mm : float
        Arc length and the largest tube radius [mm].
    stub_mm : float or None
        Sealed tube beyond the tip [mm]; None for an arc inside a chain.

    Returns
    -------
    float
        [rad], 0 when the bound says nothing.

    Examples
    --------
    >>> round(math.degrees(contact_free_below_rad(100.0, 2.58, 0.0)), 1)  # the contact itself: 315.7 deg
    290.6
    """
    return _contact_free_below(l0_mm, 2.0 * radius_mm, math.nan if stub_mm is None else stub_mm)


@dataclass(frozen=True, slots=True)
class ContactRange:
    """What the contact bounds decide of one arc's states whose tube radius lies in a range
    (:func:`contact_range_rad`).

    Attributes
    ----------
    radius_lo_mm, radius_hi_mm : float
        The range of tube radii [mm].
    below_rad : float
        States of a smaller ``|theta|`` are apart [rad].
    start_rad, end_rad : float
        States of ``|theta|`` between them touch [rad] (``start_rad`` inf: no sure contact).

    Examples
    --------
    >>> c = contact_range_rad(100.0, 2.58, 2.58, 0.0, False)
    >>> [c.touches(math.radians(a), 2.58) for a in (300.0, 330.0, 359.999)], c.touches(5.8, 2.6)
    ([False, True, None], None)
    """

    radius_lo_mm: float
    radius_hi_mm: float
    below_rad: float
    start_rad: float
    end_rad: float

    def touches(self, theta_rad: float, radius_mm: float) -> bool | None:
        """Whether the state of bend ``theta_rad`` and radius ``radius_mm`` touches (:func:`arc_contact`), where the
        bounds decide it; None where the test must (a radius outside the range, a bend between the ends).

        Parameters
        ----------
        theta_rad, radius_mm : float
            The state [rad, mm].

        Returns
        -------
        bool or None

        Examples
        --------
        >>> c = ContactRange(2.0, 2.5, 5.0, 5.5, 6.0)
        >>> c.touches(-5.7, 2.2), c.touches(4.0, 2.2), c.touches(5.2, 2.2)
        (True, False, None)
        """
        if not self.radius_lo_mm <= radius_mm <= self.radius_hi_mm:
            return None
        a = abs(theta_rad)
        return False if a < self.below_rad else True if self.start_rad <= a <= self.end_rad else None


def contact_range_rad(l0_mm: float, radius_lo_mm: float, radius_hi_mm: float, stub_mm: float | None,
                      negative: bool) -> ContactRange:
    """The :class:`ContactRange` of one arc of length ``l0_mm`` bending one way (``negative``), its tube's radius
    anywhere in ``[radius_lo_mm, radius_hi_mm]``, with the stub ``stub_mm`` (None: inside a chain):
    :func:`contact_free_below_rad` at the largest radius and :func:`_contact_bounds` over the range (bounds, as the
    array path's states take them).

    Parameters
    ----------
    l0_mm : float
        Arc length [mm].
    radius_lo_mm, radius_hi_mm : float
        The smallest and the largest tube radius of the states [mm].
    stub_mm : float or None
        Sealed tube beyond the tip [mm]; None for an arc inside a chain (only its own full turn).
    negative : bool
        The arc bends toward negative angles.

    Returns
    -------
    ContactRange

    Examples
    --------
    >>> c = contact_range_rad(100.0, 2.58, 2.58, 0.0, False)  # touches at 320.88 deg
    >>> [round(math.degrees(v), 2) for v in (c.below_rad, c.start_rad, c.end_rad)]
    [320.88, 320.88, 359.99]
    """
    m = math.nan if stub_mm is None else float(stub_mm)
    free = max(_contact_free_below(l0_mm, 2.0 * radius_hi_mm, m), _SMALLEST)
    below, start, end = (free, math.inf, math.inf) if m != m else _contact_bounds(
        l0_mm, 2.0 * radius_lo_mm, 2.0 * radius_hi_mm, m, negative, free)
    return ContactRange(radius_lo_mm, radius_hi_mm, below, *((start, end) if start <= end else (math.inf, math.inf)))


def _contact_free_below(l0: float, w: float, m: float) -> float:
    """|theta| [rad] below which one arc (length ``l0``, band width ``w = 2 r`` or less, stub ``m``; NaN: an arc
    inside a chain) cannot touch: :func:`arc_contact` is False at every smaller bend (0: the bound says
    nothing).

    Every corner of the stub's rectangle lies within ``m + w`` of the tip ``(px, py)`` (``|t| = |n| = 1``), so
    :func:`arc_contact`'s first tests separate it from the band ``x <= 0, -w <= y <= 0`` once
    ``px > m + w`` or ``|py| > reach = m + 2 w`` (each with a margin for round-off). With ``a = |theta|``,
    ``px = l0 sin(a)/a`` and ``|py| = q(a) = l0 (1 - cos a)/a``. ``px`` falls on ``[0, pi]`` and
    ``sin(a)/a >= max(1 - a/pi, 2/pi [a <= pi/2])`` there, which clears ``[0, a1)``; ``q`` rises, then falls on
    ``[pi/2, 2 pi]``, so from ``a1 >= pi/2`` with ``q(a1) > reach`` it stays above ``reach`` up to its root on
    the falling side. Where ``pi reach < l0`` that root is at least ``2 pi - 2 asin(sqrt(pi reach/l0))``
    (``q >= (l0/pi) sin^2(b/2)`` with ``b = 2 pi - a``, and ``q >= l0/pi`` on ``[pi/2, pi]``): for
    ``l0 = 100 mm``, ``r = 2.58 mm`` and no stub 290.6 deg (the contact comes at 315.7 deg); else a
    bisection of ``q`` finds it from below.
    """
    if m != m:
        return FULL_TURN_RAD  # an arc inside a chain: only its own full turn
    size, reach = _reach(l0, w, m)
    if math.pi * reach < l0:
        return _short_reach_bound(l0, reach, math.asin, math.sqrt)
    k = m + w + size
    if not k < l0:  # also NaN
        return 0.0
    a1 = max(math.pi * (1.0 - k / l0), 0.5 * math.pi if k < 2.0 * l0 / math.pi else 0.0)
    lo, hi = a1, FULL_TURN_RAD
    if not (lo >= 0.5 * math.pi and l0 * (1.0 - math.cos(lo)) / lo > reach):
        return lo
    for _ in range(_BOUND_BISECTIONS):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if l0 * (1.0 - math.cos(mid)) / mid > reach else (lo, mid)
    return lo


def _reach(l0, w, m):
    """(margin, reach) of :func:`_contact_free_below`: its round-off margin and ``m + 2 w`` with it."""
    size = _BOUND_MARGIN * (l0 + m + w)
    return size, m + 2.0 * w + size


def _short_reach_bound(l0, reach, asin=np.arcsin, sqrt=np.sqrt):
    """:func:`_contact_free_below` where ``pi reach < l0``: ``2 pi - 2 asin(sqrt(pi reach/l0))`` (on floats with
    ``math``'s functions)."""
    return FULL_TURN_RAD - 2.0 * asin(sqrt(math.pi * reach / l0))


def _contact_past_bound(th, r, l0, m):
    """:func:`arc_contact` of states (1-D arrays, ``m`` NaN inside a chain), the test run on
    the states short of a full turn (which touch) and at or past :func:`_contact_free_below` only, where its
    bound is closed form (``pi reach < l0``; a NaN stub: the full turn), else on all of them: every state short
    of it is apart."""
    _, reach = _reach(l0, 2.0 * r, m)
    short = np.flatnonzero(math.pi * reach < l0)  # NaN: False
    free = np.where(np.isnan(m), FULL_TURN_RAD, 0.0)
    free[short] = _short_reach_bound(l0.take(short), reach.take(short))
    a = np.abs(th)
    out = a >= FULL_TURN_RAD
    test = np.flatnonzero((a >= free) & ~out)
    out[test] = arc_contact(*(v.take(test) for v in (th, r, l0, m)))
    return out


def _coiled_states(th, a, top, r, l0, stub):
    """:func:`arc_contact` of one model's states (``l0`` and ``stub`` one value each; ``top = max(a)``), or None
    where no state touches. The contact test runs only on the
    states the bounds cannot decide: below :func:`_contact_free_below` (and, without a stub, the tighter end of
    :func:`_contact_bounds`) they are apart, between :func:`_contact_bounds`' touching ends they touch (the
    straight state never touches: its stub points away along +x)."""
    if not (stub is None or isinstance(stub, float)) and np.size(stub) != 1:
        return arc_contact(th, r, l0, stub)
    m = math.nan if stub is None else stub if isinstance(stub, float) else np.asarray(stub).item()
    free = max(_contact_free_below(l0, 2.0 * float(array_max(r, axis=None)), m), _SMALLEST)
    if top < free:
        return None
    if m != m:
        return arc_contact(th, r, l0, m)
    near = np.flatnonzero(a >= free)  # the states the free bound cannot clear, as floats
    a_near, r_near = a.reshape(-1)[near].tolist(), r.reshape(-1)[near].tolist()
    w_lo, w_hi = 2.0 * min(r_near), 2.0 * max(r_near)
    below, start, end = math.inf, -math.inf, math.inf
    hi, lo = float(array_max(th, axis=None)), float(array_min(th, axis=None))
    for negative in (n for n, on in ((False, hi >= free), (True, -lo >= free)) if on):  # the ways states bend
        b, s, e = _contact_bounds(l0, w_lo, w_hi, m, negative, free)
        below, start, end = min(below, b), max(start, s), min(end, e)
    if not start <= end:  # no sure contact: every state from ``below`` to the full turn takes the test
        start = end = FULL_TURN_RAD
    out = a >= start  # past a full turn too
    at = [k for k, x in zip(near.tolist(), a_near) if below <= x < start or end < x < FULL_TURN_RAD]
    if len(at) <= _FLOAT_TESTS:
        for k in at:
            out.flat[k] = _arc_contact_float(th.item(k), r.item(k), l0, m)
    else:
        test = np.zeros(a.shape, dtype=bool)
        test.flat[at] = True
        out[test] = ~_apart(th[test], r[test], l0, m)
    return out


#: At most this many states of one model take the contact test on floats (:func:`_arc_contact_float`); more
#: take it on arrays.
_FLOAT_TESTS = 6
_THREE_QUARTERS = 1.5 * math.pi


def _contact_bounds(l0: float, w_lo: float, w_hi: float, m: float, negative: bool, free: float):
    """(below, start, end) [rad] for one arc of length ``l0`` bending one way (``negative``), its band ``w = 2 r``
    in ``[w_lo, w_hi]``, stub ``m`` (not NaN), ``free`` from :func:`_contact_free_below`: every bend ``a = |theta|``
    in ``[free, below)`` is apart and every one in ``[start, end]`` touches (:func:`arc_contact`); the others
    need the test (``start`` inf: no sure contact).

    With ``q(a) = l0 (1 - cos a)/a`` (``|py|`` of the tip; ``q`` falls on ``[pi, 2 pi]``) and ``a`` in
    ``[3 pi/2, 2 pi)``, where ``cos a >= 0``:

    * apart (no stub, from ``free >= pi/2`` on): up to ``3 pi/2`` a positive bend's tip and tube-side corner
      lie above the band (``q >= 2 l0/(3 pi)`` there, the corner higher), a negative bend's below it while
      ``l0/a > w`` (the corner's ``y + w = -(1 - cos a)(l0/a - w)``, the tip lower); from ``3 pi/2`` on a
      negative bend's corner lies below its tip, so both lie below the band while ``q > w``, and a positive
      bend's tip and corner lie above it while ``q > w cos a`` (``w cos a - q`` rises);
    * touching (any stub): a point of the stub's rectangle inside the band ``x < 0, -w < y < 0`` leaves no
      separating axis: a negative bend's tip ``(l0 sin(a)/a, -q)`` once ``q < w``, a positive bend's
      tube-side corner ``(sin(a) (l0/a + w), q - w cos a)`` once ``w cos a > q``; ``end`` is where it nears
      the band's corner ``(0, 0)`` (``x`` rises to 0, ``q`` and ``q + w (1 - cos a)`` fall to it).

    A wider band is a superset of the band and of the rectangle, so ``w_hi`` bounds the apart side and ``w_lo``
    the touching one. Each inequality holds with a margin of ``1e-9`` of the lengths (over the round-off of
    :func:`arc_contact`) and is monotone on the range, so checking it at the ends makes the claim rigorous;
    Newton's steps only find the ends.
    """
    size = _BOUND_MARGIN * (l0 + m + w_hi)
    if negative:
        def edge(a, w):  # q(a) - w and its slope
            c, s = math.cos(a), math.sin(a)
            return l0 * (1.0 - c) / a - w, l0 * (a * s - 1.0 + c) / (a * a)

        def apart(a):
            return l0 * (1.0 - math.cos(a)) / a > w_hi + size

        def touches(a):
            q = l0 * (1.0 - math.cos(a)) / a
            return size < q < w_lo - size and l0 * math.sin(a) / a < -size

        guess = FULL_TURN_RAD - math.sqrt(4.0 * math.pi * w_lo / l0)
        close = 2.0 * math.sqrt(4.0 * math.pi * size / l0) + 4.0 * math.pi * size / l0
    else:
        def edge(a, w):  # w cos(a) - q(a) and its slope
            c, s = math.cos(a), math.sin(a)
            return w * c - l0 * (1.0 - c) / a, -w * s - l0 * (a * s - 1.0 + c) / (a * a)

        def apart(a):
            c = math.cos(a)
            return w_hi * c - l0 * (1.0 - c) / a < -size

        def touches(a):
            c, s = math.cos(a), math.sin(a)
            q = l0 * (1.0 - c) / a
            return w_lo * c - q > size and s * (l0 / a + w_lo) < -size and q + w_lo * (1.0 - c) > size

        rad = l0 / FULL_TURN_RAD
        guess = FULL_TURN_RAD - math.acos(rad / (rad + w_lo))
        close = 2.0 * math.sqrt(size / (0.5 * rad + 0.5 * w_lo)) + 2.0 * size / (rad + w_lo)
    end = FULL_TURN_RAD - close
    edge_lo = start = _newton_edge(edge, w_lo, guess)
    for step in (1e-7, 1e-5, 1e-3):  # the first point past the edge that checks
        if touches(start):
            break
        start += step
    if not (start < end and touches(start) and touches(end)):
        start = math.inf
    below = free
    if m == 0.0 and free >= 0.5 * math.pi and (free >= _THREE_QUARTERS or (
            l0 / _THREE_QUARTERS > w_hi + size if negative else 2.0 * l0 / (3.0 * math.pi) > size)):
        a = (edge_lo if w_hi == w_lo else _newton_edge(edge, w_hi, edge_lo)) - 1e-7
        if free < a and apart(a):
            below = a
    return below, start, end


def _newton_edge(edge, w, a):
    """Where ``edge(a, w)`` (value, slope) is 0 on ``[3 pi/2, 2 pi]``, by at most six Newton steps from ``a``, kept
    in the range (the caller checks what it claims of the result)."""
    a = min(max(a, _THREE_QUARTERS), FULL_TURN_RAD)
    for _ in range(6):
        f, df = edge(a, w)
        if df == 0.0:
            break
        step = f / df
        a = min(max(a - step, _THREE_QUARTERS), FULL_TURN_RAD)
        if abs(step) < 1e-10:
            break
    return a


def _apart(th, r, l0, m):
    """Whether the stub's rectangle and the fixed band are apart at states ``th`` (arrays broadcast, ``m`` not
    NaN): :func:`arc_contact`'s separation test, on the rectangle's corners and the four edge normals."""
    half = 0.5 * th
    sin_h, cos_h = np.sin(half), np.cos(half)
    zero = half == 0.0
    chord = l0 * np.where(zero, 1.0, sin_h / np.where(zero, 1.0, half))  # l0 sin(half)/half: the chord
    px, py = chord * cos_h, chord * sin_h  # the tip (fabric side)
    tx, ty = cos_h * cos_h - sin_h * sin_h, 2.0 * (sin_h * cos_h)  # tangent there; the tube side is (ty, -tx)
    nx, ny = ty, -tx
    w = 2.0 * r
    wx, wy = w * nx, w * ny
    if isinstance(m, float) and m == 0.0:  # the stub's corners are the tip's (x + 0.0 * t is x)
        x_lo, y_lo, y_hi = np.minimum(px, px + wx), np.minimum(py, py + wy), np.maximum(py, py + wy)
    else:
        x2, y2 = px + m * tx, py + m * ty
        x_lo = np.minimum(np.minimum(px, px + wx), np.minimum(x2, x2 + wx))
        y0, y1, y3 = py + wy, y2, y2 + wy
        y_lo = np.minimum(np.minimum(py, y0), np.minimum(y1, y3))
        y_hi = np.maximum(np.maximum(py, y0), np.maximum(y1, y3))
    neg_w = -w
    apart = (x_lo > 0.0) | (y_lo > 0.0) | (y_hi < neg_w)
    for ux, uy, low, span in ((tx, ty, px * tx + py * ty, m), (nx, ny, px * nx + py * ny, w)):
        b1 = neg_w * uy  # the band's corners (0, 0) and (0, -2 r) on the axis; it runs on toward -x
        apart |= (ux >= 0.0) & (low > np.maximum(0.0, b1))
        apart |= (ux <= 0.0) & ((low + span) < np.minimum(0.0, b1))
    return apart


def _arc_contact_float(th: float, r: float, l0: float, m: float) -> bool:
    """:func:`arc_contact` of one state on Python floats: its operations in its order (numpy's sin and cos on
    floats), so the same answer without a numpy array per operation."""
    inside = m != m
    m = 0.0 if inside else m
    half = 0.5 * th
    sin_h, cos_h = SCALAR.sin(half), SCALAR.cos(half)
    chord = l0 * (sin_h / half if half != 0.0 else 1.0)
    px, py = chord * cos_h, chord * sin_h
    tx, ty = cos_h * cos_h - sin_h * sin_h, 2.0 * (sin_h * cos_h)
    nx, ny = ty, -tx
    w = 2.0 * r
    cx = (px, px + w * nx, px + m * tx, px + m * tx + w * nx)
    cy = (py, py + w * ny, py + m * ty, py + m * ty + w * ny)
    apart = min(cx) > 0.0 or min(cy) > 0.0 or max(cy) < -w
    for ux, uy, low, span in ((tx, ty, px * tx + py * ty, m), (nx, ny, px * nx + py * ny, w)):
        b0, b1 = 0.0, -w * uy
        b_lo = -math.inf if ux > 0.0 else min(b0, b1)
        b_hi = math.inf if ux < 0.0 else max(b0, b1)
        apart = apart or low > b_hi or low + span < b_lo
    return abs(th) >= FULL_TURN_RAD or (not apart and not inside)


def arc_contact(theta_rad, radius_mm, l0_mm, stub_mm=0.0) -> np.ndarray:
    """:func:`strip_contact` of one uniform arc clamped at its start, in closed form (arrays broadcast).

    For one arc the first contact is always between the square-cut end of the straight
    stub (from the tip section to the stub's end: a rectangle ``stub_mm`` by ``2 r``) and
    the fixed band behind the clamp: the arc's own band reaches lowest at its tip and the
    stub can reach the arc's start only across the clamp's section. So the strip touches
    once it has turned a full turn, or once that rectangle meets the band
    ``x <= 0, -2 r <= y <= 0``; two convex sets meet unless one of their four edge normals
    (``x``, ``y``, the tip's tangent and normal) separates them.

    Parameters
    ----------
    theta_rad : array_like
        Bend [rad] (signed).
    radius_mm : array_like
        Tube outer radius r [mm].
    l0_mm : array_like
        Arc length [mm].
    stub_mm : array_like
        Sealed tube beyond the tip [mm], >= 0; NaN (a model's ``stub_mm=None``) for an arc inside
        a chain, which is only checked for its own full turn (the chain is tested as a whole).

    Returns
    -------
    ndarray of bool

    Examples
    --------
    >>> arc_contact(np.radians([-315.0, -316.0, 253.0, 255.0]), 2.58, 100.0, [0.0, 0.0, 30.0, 30.0]).tolist()
    [False, True, False, True]
    >>> arc_contact(np.radians([-316.0, 360.0]), 2.58, 100.0, np.nan).tolist()
    [False, True]
    """
    th, r, l0, m = np.broadcast_arrays(*(np.asarray(v, dtype=np.float64) for v in (theta_rad, radius_mm, l0_mm,
                                                                                    stub_mm)))
    inside = np.isnan(m)
    return (np.abs(th) >= FULL_TURN_RAD) | (~_apart(th, r, l0, np.where(inside, 0.0, m)) & ~inside)


_KEPT = (int(Status.FAILED), int(Status.OUT_OF_DOMAIN))
_LIMIT_CODES = tuple(int(s) for s in (Status.COILED, Status.KINKED, Status.OVERSTRETCHED))


def _limited(st, flags):
    """Status with the first limit of ``flags`` (coiled, kinked, overstretched) a state exceeds (arrays)."""
    coiled, kinked, over = flags
    out = np.where(over, _LIMIT_CODES[2], st)
    out = np.where(kinked, _LIMIT_CODES[1], out)
    out = np.where(coiled, _LIMIT_CODES[0], out)
    return np.where((st == _KEPT[0]) | (st == _KEPT[1]), st, out)


def apply_limits(status, theta_rad, length_mm, radius_mm, l0_mm, xp=np, stub_mm=0.0, free_rad=0.0):
    """Status codes with the validity limits applied (precedence: :mod:`embroact.predict.status`).

    FAILED and OUT_OF_DOMAIN points keep their status (their theta is a fill value);
    every other point takes the first limit it exceeds. Arrays give an int8 array; one state
    in Python numbers with ``xp=SCALAR`` (:mod:`embroact.predict.floats`) gives an int.

    Parameters
    ----------
    status : array_like of int or int
        The model's statuses.
    theta_rad, length_mm, radius_mm, l0_mm : array_like or float
        The states (as :func:`limit_flags`).
    xp : module, optional
        numpy, or :data:`~embroact.predict.floats.SCALAR` for one state.
    stub_mm : float, array_like or None, optional
        Sealed tube beyond the tip [mm] of a whole strip (:attr:`ActuatorModel.stub_mm
        <embroact.predict.curve.ActuatorModel>`; 0: clamped at its start, no stub; None or
        NaN: an arc inside a chain, its own full turn only).
    free_rad : float, optional
        With ``xp=SCALAR``: a bend [rad] below which the caller knows the state cannot touch (one model's
        :func:`contact_free_below_rad` at its largest radius, kept for its curves), which spares the state's own
        bound; 0 by default.

    Returns
    -------
    numpy.ndarray of int8 or int

    Examples
    --------
    >>> import math
    >>> from embroact.predict.floats import SCALAR
    >>> apply_limits(int(Status.BENDING), math.radians(400.0), 118.0, 2.58, 100.0, SCALAR) == Status.COILED
    True
    """
    if xp is not np:  # one state: the first limit it exceeds
        if status in _KEPT:
            return status
        coiled, kinked, over = _exceeded(theta_rad, length_mm, radius_mm, l0_mm, xp, stub_mm, free_rad)
        return _LIMIT_CODES[0] if coiled else _LIMIT_CODES[1] if kinked else _LIMIT_CODES[2] if over else status
    st = np.asarray(status, dtype=np.int8)
    th, l, r, l0 = (np.asarray(v, dtype=np.float64) for v in (theta_rad, length_mm, radius_mm, l0_mm))
    if not (th.size and l0.size == 1 and th.shape == l.shape == r.shape):
        return _limited(st, _exceeded(th, l, r, l0, stub=stub_mm)).astype(np.int8)
    # one model's states: reductions first, then only the flags some state can raise (the same flags)
    a = np.abs(th)
    half = r * a  # 2 r a > l0 exactly when r a > l0/2 (scaling by 2 is exact)
    l0 = l0.item()
    top = float(array_max(a, axis=None))
    coiled = _coiled_states(th, a, top, r, l0, stub_mm)
    kinked = half > 0.5 * l0 if array_max(half, axis=None) > 0.5 * l0 else None
    over = l >= STRETCH_LIMIT * l0 if array_max(l, axis=None) >= STRETCH_LIMIT * l0 else None
    out = np.array(st, dtype=np.int8)  # a new array in every case
    if coiled is None and kinked is None and over is None:
        return out
    for flag, code in ((over, _LIMIT_CODES[2]), (kinked, _LIMIT_CODES[1]), (coiled, _LIMIT_CODES[0])):
        if flag is not None:
            out[flag] = code
    if int(array_max(st, axis=None)) >= min(_KEPT):  # FAILED and OUT_OF_DOMAIN keep their status
        kept = (st == _KEPT[0]) | (st == _KEPT[1])
        out[kept] = st[kept]
    return out


def coil_angle_deg(l0_mm: float, radius_mm: float, *, negative: bool, stub_mm: float = 0.0) -> float:
    """|theta| [deg] at which one uniform arc, clamped at its start, first touches (:func:`arc_contact`).

    Found by bisection between the straight state (no contact) and a full turn (contact), for a
    constant tube radius. Without a stub a negative bend's tip lands on the supply tube where
    ``l0 (1 - cos theta) = 2 r |theta|`` and a positive bend's tube-side corner of the tip
    enters it where ``cos theta = R / (R + 2 r)``, ``R = l0 / theta``; a stub reaches sooner.

    Parameters
    ----------
    l0_mm : float
        Fabric-side length [mm], > 0.
    radius_mm : float
        Tube outer radius [mm], > 0.
    negative : bool
        The bend is negative (towards the tube).
    stub_mm : float, optional
        Sealed tube beyond the tip [mm], >= 0.

    Returns
    -------
    float
        [deg].

    Examples
    --------
    >>> [round(coil_angle_deg(100.0, 2.58, negative=n, stub_mm=m), 1) for m in (0.0, 30.0) for n in (True, False)]
    [315.7, 320.9, 243.1, 253.9]
    """
    l0 = check_range("l0_mm", l0_mm, low=0.0)
    r = check_range("radius_mm", radius_mm, low=0.0)
    m = check_range("stub_mm", stub_mm, low=0.0, low_inclusive=True, high=1e4)
    sign = -1.0 if negative else 1.0
    lo, hi = 0.0, FULL_TURN_RAD
    for _ in range(LIMIT_BISECTIONS):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        lo, hi = (lo, mid) if arc_contact(sign * mid, r, l0, m) else (mid, hi)
    return math.degrees(hi)


def valid_mask(curve) -> np.ndarray:
    """True where a curve's theta is a state the model describes (draw it as valid).

    Equilibria (INFLATION, BENDING) and the branch end a point stops at (LOCKED,
    UNSTABLE); False for the validity limits and for fill values (OUT_OF_DOMAIN, FAILED).
    Views and charts call this instead of testing statuses themselves.

    Parameters
    ----------
    curve : Curve
        A predicted curve.

    Returns
    -------
    numpy.ndarray of bool

    Examples
    --------
    >>> from embroact.predict.curve import ActuatorModel, curve
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.04, beta0_deg=0, outer_radius_mm=1.5,
    ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=0.8, p0_kpa=50)
    >>> valid_mask(curve(m, [0, 60, 250])).tolist()
    [True, True, False]
    """
    return is_model_state(curve.status)


#: Chordal tolerance of the polylines the whole-strip contact test draws the strip's outline with [mm].
CONTACT_TOLERANCE_MM = 0.005
#: Total turning [deg] up to which a strip cannot touch itself or the fixed part (:func:`strip_contact`).
_NO_CONTACT_TURNING_DEG = 90.0


def strip_contact(lengths_mm, theta_deg, radius_mm, stub_mm: float = 0.0) -> np.ndarray:
    """Whether the bent strip touches itself, the clamp or the fixed fabric (docs/model.md section 12).

    The strip is seen in its bending plane (the profile of a straight path: ``x`` along the
    clamped tangent, ``y`` toward positive bends). Its body is the band the tube fills: from
    the fabric line to ``2 r`` on the tube's side (the thread side, to the right of the line
    when it heads +x), over the chain of arcs and then ``stub_mm`` of sealed tube straight on
    beyond the tip, cut square at its end. The fixed part is the same band behind the clamp,
    ``x <= 0``, ``-2 r <= y <= 0``: the fabric held flat there and the supply line leaving
    the clamp along the base tangent. The strip touches when its outline crosses itself, or
    a corner or an edge of it reaches into the fixed part. A band of arcs whose radius is at
    least its thickness ``2 r`` (not kinked) crosses itself nowhere locally, so a crossing is
    a real contact; a strip that turns by 90 deg or less in all cannot reach back.

    Parameters
    ----------
    lengths_mm : sequence of float
        Lengths of the pieces from the clamp [mm], > 0 (unbent pieces bend by 0).
    theta_deg : array_like
        Bend of each piece [deg], shape ``(pieces,)`` or ``(states, pieces)``.
    radius_mm : float or array_like
        Tube outer radius r [mm], > 0, one or one per state.
    stub_mm : float
        Sealed tube beyond the tip [mm], >= 0 (a design's ``tube.end_margin_mm``).

    Returns
    -------
    ndarray of bool
        One per state (a 0-d array for one state).

    Examples
    --------
    One 100 mm arc, r = 2.58 mm: without a stub a negative bend's tip lands on the supply line
    at 315.7 deg; a 30 mm stub reaches it already at 243 deg, and a positive bend's stub reaches
    the fixed fabric at 254 deg.

    >>> strip_contact([100.0], [[-315.0], [-316.0], [300.0]], 2.58).tolist()
    [False, True, False]
    >>> strip_contact([100.0], [[-242.0], [-244.0], [253.0], [255.0]], 2.58, 30.0).tolist()
    [False, True, False, True]
    """
    lengths = np.asarray(lengths_mm, dtype=np.float64).reshape(-1)
    theta = np.asarray(theta_deg, dtype=np.float64)
    rows = np.atleast_2d(theta)
    if rows.shape[-1] != len(lengths):
        raise ParameterError(f"theta_deg must have one bend per piece ({len(lengths)}), got shape {theta.shape}")
    radius = np.broadcast_to(np.asarray(radius_mm, dtype=np.float64), rows.shape[:1])
    stub = check_range("stub_mm", stub_mm, low=0.0, low_inclusive=True, high=1e4)
    out = np.zeros(len(rows), dtype=bool)
    busy = np.sum(np.abs(rows), axis=1) > _NO_CONTACT_TURNING_DEG
    bent = rows != 0.0
    one = busy & (np.sum(bent, axis=1) == 1)  # one arc between straight pieces: the closed form
    if np.any(one):
        # a straight lead-in moves the clamp (it continues the fixed band), a straight tail lengthens the stub
        j = np.argmax(bent[one], axis=1)
        after = np.concatenate([np.cumsum(lengths[::-1])[::-1][1:], [0.0]])
        out[one] = arc_contact(np.radians(rows[one, j]), radius[one], lengths[j], stub + after[j])
    for i in np.flatnonzero(busy & ~one):
        out[i] = _touches(lengths, rows[i], float(radius[i]), stub)
    return out.reshape(theta.shape[:-1])


def _outline(lengths: np.ndarray, theta_deg: np.ndarray, r: float, stub: float):
    """Fabric line and tube-side edge (complex points) of the strip and its stub, sampled chordally."""
    from .shape import sample_count

    pts, heads = [np.zeros(1, dtype=complex)], [np.zeros(1)]
    z, phi = 0j, 0.0
    for length, t in zip(lengths.tolist(), np.radians(theta_deg).tolist()):
        radius = length / abs(t) + 2.0 * r if t else math.inf
        n = sample_count(t, radius, CONTACT_TOLERANCE_MM) if t else 1
        h = length * np.arange(1, n + 1) / n
        k = t / length
        pts.append(z + np.exp(1j * (phi + 0.5 * k * h)) * h * np.sinc(0.5 * k * h / math.pi))
        heads.append(phi + k * h)
        z, phi = complex(pts[-1][-1]), float(heads[-1][-1])
    if stub > 0.0:
        pts.append(np.array([z + stub * complex(math.cos(phi), math.sin(phi))]))
        heads.append(np.array([phi]))
    fabric, head = np.concatenate(pts), np.concatenate(heads)
    return fabric, fabric - 2j * r * np.exp(1j * head)


def _touches(lengths: np.ndarray, theta_deg: np.ndarray, r: float, stub: float) -> bool:
    """:func:`strip_contact` of one state."""
    if np.any(np.abs(theta_deg) >= 360.0):
        return True  # an arc past a full turn overlaps itself
    fabric, edge = _outline(lengths, theta_deg, r, stub)
    # the outline without the clamp's section (it is the fixed part's edge): fabric line, end, tube edge back
    ring = np.concatenate([fabric, edge[::-1]])
    a, b = ring[:-1], ring[1:]
    inner = np.ones(len(ring), dtype=bool)
    inner[[0, -1]] = False  # the two clamp corners lie on the fixed part's edge
    x, y = ring.real, ring.imag
    if np.any(inner & (x <= 0.0) & (y <= 0.0) & (y >= -2.0 * r)):
        return True
    free = np.ones(len(a), dtype=bool)
    free[[0, -1]] = False  # the edges leaving the clamp corners
    for level in (0.0, -2.0 * r):  # the fixed band's two edges behind the clamp
        da, db = a.imag - level, b.imag - level
        cross = free & (da * db < 0.0)
        xc = a.real + (b.real - a.real) * da / np.where(cross, da - db, 1.0)
        if np.any(cross & (xc <= 0.0)):
            return True
    return _self_crossing(a, b)


def _self_crossing(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether two non-neighbouring edges ``a[i] -> b[i]`` of an open polyline cross properly."""
    lo_x, hi_x = np.minimum(a.real, b.real), np.maximum(a.real, b.real)
    lo_y, hi_y = np.minimum(a.imag, b.imag), np.maximum(a.imag, b.imag)
    i, j = np.triu_indices(len(a), k=2)
    near = (lo_x[i] <= hi_x[j]) & (lo_x[j] <= hi_x[i]) & (lo_y[i] <= hi_y[j]) & (lo_y[j] <= hi_y[i])
    i, j = i[near], j[near]
    if not len(i):
        return False

    def side(p, q, s):
        return ((q - p).conjugate() * (s - p)).imag

    d1, d2 = side(a[i], b[i], a[j]), side(a[i], b[i], b[j])
    d3, d4 = side(a[j], b[j], a[i]), side(a[j], b[j], b[i])
    return bool(np.any((d1 * d2 < 0.0) & (d3 * d4 < 0.0)))


def strip_coil_angle_deg(lengths_mm, bends_deg, radius_mm: float, stub_mm: float = 0.0) -> float:
    """The turning [deg] at which a strip bending in proportion to ``bends_deg`` first touches.

    The pieces bend by ``f * bends_deg``; the smallest ``f`` in ``(0, 360 / max|bend|]`` at
    which :func:`strip_contact` reports contact is found by bisection (one arc: the bend at
    which it coils).

    Parameters
    ----------
    lengths_mm : sequence of float
        Piece lengths from the clamp [mm].
    bends_deg : sequence of float
        The pattern of the bends (any scale; at least one non-zero).
    radius_mm : float
        Tube outer radius r [mm].
    stub_mm : float
        Sealed tube beyond the tip [mm].

    Returns
    -------
    float
        ``f * sum(bends_deg)`` at the first contact [deg] (signed).

    Examples
    --------
    >>> round(strip_coil_angle_deg([100.0], [-1.0], 2.58), 2), round(strip_coil_angle_deg([100.0], [1.0], 2.58, 30.0), 2)
    (-315.7, 253.9)
    """
    bends = np.asarray(bends_deg, dtype=np.float64).reshape(-1)
    top = float(np.max(np.abs(bends)))
    if top == 0.0:
        raise ParameterError("bends_deg must hold a non-zero bend")
    lo, hi = 0.0, 360.0 / top
    for _ in range(LIMIT_BISECTIONS // 2):  # to about 1e-9 of the range
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if strip_contact(lengths_mm, mid * bends, radius_mm, stub_mm) else (mid, hi)
    return float(hi * bends.sum())


def strip_status(pieces, segment_curves, stub_mm: float = 0.0) -> np.ndarray:
    """The status of a whole strip per pressure, from its segments' curves and its bent line.

    The one place a strip's status is decided; every view reads it (through
    :meth:`embroact.predict.analysis.DesignAnalysis.curves`). Per pressure: the first segment
    whose state the model does not describe gives its status (out of the domain, failed, or a
    segment past its own limit); else ``COILED`` where the strip touches itself, the clamp or
    the fixed fabric (:func:`strip_contact`, with the stub and the largest tube radius of its
    segments at that pressure); else a single segment's own status, and for several segments
    BENDING where any bends, INFLATION otherwise.

    Parameters
    ----------
    pieces : sequence of (float, int)
        The fabric line from the clamp as ``(length_mm, segment index)``, index -1 unbent
        (:meth:`~embroact.predict.analysis.ActuatorAnalysis.bend_pieces`).
    segment_curves : sequence of Curve
        One per segment, at the same pressures.
    stub_mm : float
        Sealed tube beyond the tip [mm].

    Returns
    -------
    ndarray of int8
        Read-only, one :class:`~embroact.predict.status.Status` code per pressure.

    Examples
    --------
    Two 50 mm arcs bending 130 deg each stay apart; with 30 mm of stub beyond the tip
    (260 deg in all) the stub reaches the fixed fabric behind the clamp:

    >>> from types import SimpleNamespace as C
    >>> arc = C(theta_deg=np.array([130.0]), status=np.array([1], dtype=np.int8), radius_mm=np.array([2.58]))
    >>> [Status(int(strip_status([(50.0, 0), (50.0, 1)], [arc, arc], stub)[0])).name for stub in (0.0, 30.0)]
    ['BENDING', 'COILED']
    """
    curves = tuple(segment_curves)
    codes = np.stack([np.asarray(c.status, dtype=np.int8).reshape(-1) for c in curves])
    model = is_model_state(codes)
    zero = np.zeros(codes.shape[1])
    bends = np.stack([np.asarray(curves[k].theta_deg, dtype=np.float64).reshape(-1) if k >= 0 else zero
                      for _, k in pieces], axis=-1)
    radius = np.max([np.asarray(c.radius_mm, dtype=np.float64).reshape(-1) for c in curves], axis=0)
    ok = np.all(model, axis=0)
    touching = np.zeros(len(zero), dtype=bool)
    if np.any(ok):
        touching[ok] = strip_contact([length for length, _ in pieces], bends[ok], radius[ok], stub_mm)
    first_bad = codes[np.argmin(model, axis=0), np.arange(codes.shape[1])]
    if len(curves) == 1:
        own = codes[0]
    else:
        own = np.where(np.any(codes == int(Status.BENDING), axis=0), int(Status.BENDING), int(Status.INFLATION))
    out = np.where(~ok, first_bad, np.where(touching, int(Status.COILED), own)).astype(np.int8)
    out.setflags(write=False)
    return out
