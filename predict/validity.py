"""Where the model stops describing a real actuator (docs/model.md section 12).

The deformation model is a formula in theta; it keeps answering past the states a
sewn actuator can reach. Three limits are checked on every state (bend angle theta,
thread-side length l, tube outer radius r, fabric-side length l0) and reported as
statuses (:class:`~embroact.predict.status.Status`, precedence documented there):

``COILED``
    A uniform bend puts the fabric line on a circle of radius ``R = l0/|theta|``; it
    closes a full turn at ``|theta| = 2 pi``. In a *negative* bend the tube lies on the
    inner side: between the fabric line and the centre, with thickness ``2 r``. Where
    the tube leaves the clamped end it continues straight along the base tangent (into
    the clamp and the supply line), so it stands inside the circle: at the tangent
    line's point a distance ``x`` behind the base, the circle is ``R - sqrt(R^2 - x^2)``
    away from the fabric line. The tip, ``phi = 2 pi - |theta|`` short of a full turn,
    is at height ``R (1 - cos(phi))`` above the fabric line and a distance
    ``R sin(phi)`` behind the base; it lands on the tube's top (height ``2 r``) once
    ``R (1 - cos(phi)) <= 2 r`` with ``pi < |theta| < 2 pi``, i.e. once
    ``l0 (1 - cos(theta)) <= 2 r |theta|``. In a positive bend the tube is outside the
    circle and the fabric (of negligible thickness) is the inner side: the limit is the
    full turn. For ``l0 = 100 mm`` and ``r = 2.58 mm`` a negative bend coils at 315.70 deg.
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

Examples
--------
>>> import numpy as np
>>> from embroact.predict.validity import limit_flags, coil_angle_deg
>>> f = limit_flags(np.radians([90.0, 400.0, -320.0]), [104.0, 118.0, 86.0], 2.58, 100.0)
>>> f.coiled.tolist(), f.kinked.tolist(), f.overstretched.tolist()
([False, True, True], [False, False, False], [False, False, False])
>>> round(coil_angle_deg(100.0, 2.58, negative=True), 1), coil_angle_deg(100.0, 2.58, negative=False)
(315.7, 360.0)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..patterns.base.errors import check_range
from .status import VALIDITY_LIMITS, Status, is_model_state

__all__ = [
    "STRETCH_LIMIT",
    "LimitFlags",
    "limit_flags",
    "apply_limits",
    "coil_angle_deg",
    "valid_mask",
    "LIMIT_BISECTIONS",
]

#: Largest thread-side stretch l/l0 reported as a state of a real sleeve (docs/model.md section 12).
STRETCH_LIMIT = 2.0
_FULL_TURN = 2.0 * math.pi
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


def limit_flags(theta_rad, length_mm, radius_mm, l0_mm) -> LimitFlags:
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
    flags = _exceeded(th, l, r, l0)
    shape = np.broadcast(th, l, r, l0).shape
    return LimitFlags(*(f if f.shape == shape else np.broadcast_to(f, shape).copy() for f in flags))


def _exceeded(th, l, r, l0, xp=np):
    """(coiled, kinked, overstretched) at states: arrays, or floats with ``xp=SCALAR``."""
    a = abs(th)
    return _coiled(th, a, r, l0, xp), 2.0 * r * a > l0, l >= STRETCH_LIMIT * l0


def _coiled(th, a, r, l0, xp=np):
    """The coiled flags at states of bend ``th`` (``a = |th|``)."""
    back = th < -math.pi  # the inner coil needs a negative bend past half a turn
    coiled = a >= _FULL_TURN
    if xp.any(back):
        coiled = coiled | (back & (l0 * (1.0 - xp.cos(th)) <= 2.0 * r * a))
    return coiled


_KEPT = (int(Status.FAILED), int(Status.OUT_OF_DOMAIN))
_LIMIT_CODES = tuple(int(s) for s in (Status.COILED, Status.KINKED, Status.OVERSTRETCHED))


def _limited(st, flags, xp=np):
    """Status with the first limit of ``flags`` (coiled, kinked, overstretched) a state exceeds."""
    coiled, kinked, over = flags
    out = xp.where(over, _LIMIT_CODES[2], st)
    out = xp.where(kinked, _LIMIT_CODES[1], out)
    out = xp.where(coiled, _LIMIT_CODES[0], out)
    return xp.where((st == _KEPT[0]) | (st == _KEPT[1]), st, out)


def apply_limits(status, theta_rad, length_mm, radius_mm, l0_mm, xp=np):
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
    if xp is not np:
        return _limited(status, _exceeded(theta_rad, length_mm, radius_mm, l0_mm, xp), xp)
    st = np.asarray(status, dtype=np.int8)
    th, l, r, l0 = (np.asarray(v, dtype=np.float64) for v in (theta_rad, length_mm, radius_mm, l0_mm))
    if not (th.size and l0.size == 1 and th.shape == l.shape == r.shape):
        return _limited(st, _exceeded(th, l, r, l0)).astype(np.int8)
    # one model's states: reductions first, then only the flags some state can raise (the same flags)
    a = np.abs(th)
    width = 2.0 * r * a
    coiled = _coiled(th, a, r, l0) if a.max() >= _FULL_TURN or th.min() < -math.pi else None
    kinked = width > l0 if width.max() > l0 else None
    over = l >= STRETCH_LIMIT * l0 if l.max() >= STRETCH_LIMIT * l0 else None
    out = np.array(st, dtype=np.int8)  # a new array in every case
    if coiled is None and kinked is None and over is None:
        return out
    for flag, code in ((over, _LIMIT_CODES[2]), (kinked, _LIMIT_CODES[1]), (coiled, _LIMIT_CODES[0])):
        if flag is not None:
            out[flag] = code
    kept = (st == _KEPT[0]) | (st == _KEPT[1])
    if kept.any():
        out[kept] = st[kept]
    return out


def coil_angle_deg(l0_mm: float, radius_mm: float, *, negative: bool) -> float:
    """|theta| [deg] at which a uniform bend coils, for a constant tube radius.

    Positive bends: 360. Negative bends: the root of ``theta + arccos(1 - 2 r theta/l0)
    = 2 pi`` (module docstring), found by bisection in ``(pi, 2 pi]``; when the bend is
    kinked before it can coil (``l0 <= pi r``) the full-turn angle is returned.

    Parameters
    ----------
    l0_mm : float
        Fabric-side length [mm], > 0.
    radius_mm : float
        Tube outer radius [mm], > 0.
    negative : bool
        The bend is negative (towards the tube).

    Returns
    -------
    float
        [deg].

    Examples
    --------
    >>> coil_angle_deg(100.0, 2.58, negative=False), round(coil_angle_deg(100.0, 2.58, negative=True), 2)
    (360.0, 315.7)
    """
    l0 = check_range("l0_mm", l0_mm, low=0.0)
    r = check_range("radius_mm", radius_mm, low=0.0)
    if not negative or l0 <= math.pi * r:
        return 360.0
    lo, hi = math.pi, _FULL_TURN  # contact false at pi (no kink: l0 > pi r), true at 2 pi
    for _ in range(LIMIT_BISECTIONS):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if l0 * (1.0 - math.cos(mid)) <= 2.0 * r * mid else (mid, hi)
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
