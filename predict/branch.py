"""Curve-level queries on a model's stable branch: where it ends, and where it first leaves the validity limits.

They trace the model (:mod:`embroact.predict.curve`), which applies the limits of
:mod:`embroact.predict.validity` to every state; kept apart from those limits so that the
curve's imports run one way (curve -> validity, branch -> curve).

Examples
--------
>>> from embroact.predict.curve import ActuatorModel
>>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0,
...                   outer_radius_mm=1.5, inner_radius_mm=1.0, g_e_mpa=2.7, g_mpa=2.7, p0_kpa=85)
>>> branch_end(m).kind.value, first_limit(m).status.name
('fold', 'COILED')
"""
from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np

from . import curve as _curve
from .status import VALIDITY_LIMITS, Status
from .validity import LIMIT_BISECTIONS

__all__ = ["EndKind", "BranchEnd", "branch_end", "FirstLimit", "first_limit"]


#: Grid points along a branch for the first limit.
_LIMIT_GRID = 257
#: Halvings of the first limit's bisection evaluated in one call (:func:`_bisect_limit`).
_LIMIT_LEVELS = 6


class EndKind(enum.Enum):
    """What ends a model's stable bending branch.

    Examples
    --------
    >>> EndKind("fold") is EndKind.FOLD
    True
    """

    NONE = "none"  #: no branch: the straight state is already at the end (neutral angle, no sleeve)
    LOCK_UP = "lock-up"  #: dV/dl = 0: the sleeve locks, P has a pole (cross designs)
    FOLD = "fold"  #: a maximum of P(theta): the formula folds (zigzag designs, far inside the coiled region)
    TRACING_CAP = "tracing cap"  #: this implementation's cap MAX_BEND_DEG on a branch that never ends


@dataclass(frozen=True, slots=True)
class BranchEnd:
    """End of the stable branch of one model, named for what it is.

    Attributes
    ----------
    kind : EndKind
    theta_deg, pressure_kpa : float
        Where it ends; ``pressure_kpa`` is None at a lock-up (a pole).
    status : Status
        The state's status there: a validity limit when the end lies beyond one
        (a zigzag's fold is COILED), else LOCKED, UNSTABLE, OUT_OF_DOMAIN or INFLATION.

    Examples
    --------
    >>> BranchEnd(EndKind.LOCK_UP, 120.0, None, Status.LOCKED).as_dict()
    {'kind': 'lock-up', 'theta_deg': 120.0, 'pressure_kpa': None, 'status': 'LOCKED'}
    """

    kind: EndKind
    theta_deg: float
    pressure_kpa: float | None
    status: Status

    def as_dict(self) -> dict:
        """JSON-ready: ``kind``, ``theta_deg``, ``pressure_kpa`` (None at a pole), ``status`` name.

        Returns
        -------
        dict

        Examples
        --------
        >>> BranchEnd(EndKind.NONE, 0.0, 0.0, Status.INFLATION).as_dict()["kind"]
        'none'
        """
        return {"kind": self.kind.value, "theta_deg": self.theta_deg, "pressure_kpa": self.pressure_kpa,
                "status": self.status.name}


def branch_end(model) -> BranchEnd:
    """The end of a model's stable branch (:func:`embroact.predict.curve.lockup`), classified.

    Parameters
    ----------
    model : ActuatorModel

    Returns
    -------
    BranchEnd

    Examples
    --------
    >>> from embroact.predict.curve import ActuatorModel
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0,
    ...                   outer_radius_mm=1.5, inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
    >>> e = branch_end(m)
    >>> e.kind.value, round(e.theta_deg), e.status.name
    ('fold', 1889, 'COILED')
    """
    theta, p = _curve.lockup(model)
    if theta == 0.0:
        kind = EndKind.NONE
    elif math.isinf(p):
        kind = EndKind.LOCK_UP
    elif abs(theta) >= _curve.MAX_BEND_DEG:
        kind = EndKind.TRACING_CAP
    else:
        kind = EndKind.FOLD
    state = _curve.pressure_at(model, [theta])
    status = Status(int(state.status[0]))
    if kind is EndKind.FOLD and status is Status.BENDING:
        status = Status.UNSTABLE  # the fold itself: the last stable state
    elif kind is EndKind.TRACING_CAP and status is Status.BENDING:
        status = Status.OUT_OF_DOMAIN
    return BranchEnd(kind, float(theta), None if math.isinf(p) else float(p), status)


@dataclass(frozen=True, slots=True)
class FirstLimit:
    """The first validity limit along a model's stable branch.

    Attributes
    ----------
    status : Status
        The limit reached (COILED, KINKED or OVERSTRETCHED).
    theta_deg, pressure_kpa : float
        Angle and pressure where it is reached.

    Examples
    --------
    >>> FirstLimit(Status.COILED, 360.0, 231.4).status.name
    'COILED'
    """

    status: Status
    theta_deg: float
    pressure_kpa: float


def first_limit(model) -> FirstLimit | None:
    """Where the stable branch first leaves the validity limits; None if it ends before.

    A rule warns when the working pressure reaches ``pressure_kpa``.

    Parameters
    ----------
    model : ActuatorModel

    Returns
    -------
    FirstLimit or None

    Examples
    --------
    >>> from embroact.predict.curve import ActuatorModel
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0,
    ...                   outer_radius_mm=1.5, inner_radius_mm=1.0, g_e_mpa=2.7, g_mpa=2.7, p0_kpa=85)
    >>> f = first_limit(m)
    >>> f.status.name, round(f.theta_deg, 6)   # the tip's tube-side corner enters the supply tube
    ('COILED', 320.870003)
    """
    end = branch_end(model)
    if end.kind is EndKind.NONE:
        return None
    grid = np.linspace(0.0, end.theta_deg, _LIMIT_GRID)
    st = _curve.pressure_at(model, grid).status
    hit = np.flatnonzero(np.isin(st, [int(s) for s in VALIDITY_LIMITS]))
    if hit.size == 0:
        return None
    hi = _bisect_limit(model, float(grid[hit[0] - 1]), float(grid[hit[0]]))
    c = _curve.pressure_at(model, [hi])
    return FirstLimit(Status(int(c.status[0])), float(c.theta_deg[0]), float(c.pressure_kpa[0]))


def _bisect_limit(model, lo: float, hi: float) -> float:
    """The bisection of ``[lo, hi]`` (``lo`` within the validity limits, ``hi`` beyond one) to the last angle
    beyond: at most :data:`LIMIT_BISECTIONS` halvings, stopped when the midpoint is an end.

    Its midpoints are taken :data:`_LIMIT_LEVELS` halvings at a time: every midpoint those halvings may visit
    (a tree of ``2 ** _LIMIT_LEVELS - 1``, each computed as one halving computes it) is evaluated in one
    :func:`~embroact.predict.curve.pressure_at` call, whose fixed cost dominates, and the halvings then follow
    their path through it: the same midpoints and statuses as one call per halving.

    Examples
    --------
    >>> from embroact.predict.curve import ActuatorModel, pressure_at
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0,
    ...                   outer_radius_mm=1.5, inner_radius_mm=1.0, g_e_mpa=2.7, g_mpa=2.7, p0_kpa=85)
    >>> a = _bisect_limit(m, 300.0, 330.0)
    >>> [Status(int(s)).name for s in pressure_at(m, [np.nextafter(a, 0.0), a]).status]
    ['BENDING', 'COILED']
    """
    limits = [int(s) for s in VALIDITY_LIMITS]
    left = LIMIT_BISECTIONS
    while left > 0:
        steps = min(_LIMIT_LEVELS, left)
        mids: dict[tuple[float, float], float] = {}
        level = [(lo, hi)]
        for _ in range(steps):
            below = []
            for a, b in level:
                mid = mids[a, b] = 0.5 * (a + b)
                if mid not in (a, b):
                    below += [(a, mid), (mid, b)]
            level = below
        points = [m for (a, b), m in mids.items() if m not in (a, b)]
        beyond = {}
        if points:
            beyond = dict(zip(points, np.isin(_curve.pressure_at(model, points).status, limits).tolist()))
        left -= steps
        for _ in range(steps):
            mid = mids[lo, hi]
            if mid in (lo, hi):
                return hi
            if beyond[mid]:
                hi = mid
            else:
                lo = mid
    return hi
