"""Status of each point of a predicted curve (docs/model.md sections 9 and 12).

Every public answer of the model carries one :class:`Status` per point; a point
that has no equilibrium never holds NaN but a documented fill value, and its
status says why. The last three statuses are limits of *validity*, not of the
mathematics (:mod:`embroact.predict.validity`): the formula still has an answer
there, but it no longer describes a real actuator; theta and the state arrays keep
the formula's values, so a caller can see how far past the limit a point is.

============== ===== ========================================================================
name           value meaning; fill values of ``curve`` (theta) and ``pressure_at`` (pressure)
============== ===== ========================================================================
INFLATION      0     P <= P0: the tube fills the sleeve, theta = 0, r from the tube law
                     (``pressure_at``: theta = 0 gives P0)
BENDING        1     deformation phase, a stable equilibrium (dP/dtheta > 0 along the bend)
LOCKED         2     dV/dl -> 0: the sleeve has locked and no pressure bends it further.
                     ``curve``: theta = lock-up angle (0 at the neutral angle);
                     ``pressure_at``: angles at or past lock-up, pressure = P0
OUT_OF_DOMAIN  3     l <= 0, sin(beta) >= 1, d^2 <= 0, past the tracing cap, or an angle on
                     the side no pressure >= P0 reaches. ``curve``: theta = the domain end
                     (0 when the straight state is already outside); ``pressure_at``: P0
UNSTABLE       4     dP/dtheta < 0: snap-through. ``curve``: theta = the fold angle (the
                     last stable state before the jump); ``pressure_at``: the real P(theta)
FAILED         5     the chosen method produced no finite number (a documented failure of
                     that method, e.g. "printed" where B^2 underflows); theta 0, pressure P0
COILED         6     the strip touches itself, the clamp or the fixed fabric: one arc past a
                     full turn, a negative bend's tip on the tube where it leaves the clamped
                     end, or (the whole strip, :func:`~embroact.predict.validity.strip_status`)
                     its bent line with the sealed stub beyond the tip crossing itself or the
                     fixed band behind the clamp
KINKED         7     the bend radius l0/|theta| is below the tube's diameter 2 r
OVERSTRETCHED  8     the thread side is stretched to l/l0 >= 2
============== ===== ========================================================================

Precedence: a point gets the first status that applies, in the order FAILED,
OUT_OF_DOMAIN (their theta is a fill value, not a state), COILED, KINKED,
OVERSTRETCHED (checked on the state at the point's theta, which for UNSTABLE and
LOCKED points is the fold or lock angle), then the model's own UNSTABLE, LOCKED,
BENDING or INFLATION. So a zigzag's fold, thousands of degrees into the coiled region,
reads COILED. :func:`embroact.predict.validity.limit_flags` gives every limit a point
exceeds, not only the first.

Examples
--------
>>> from embroact.predict.status import Status, status_names
>>> int(Status.LOCKED), Status(1).name
(2, 'BENDING')
>>> status_names([0, 1, 4, 6])
['INFLATION', 'BENDING', 'UNSTABLE', 'COILED']
>>> sorted(s.name for s in MODEL_STATES)
['BENDING', 'INFLATION', 'LOCKED', 'UNSTABLE']
"""
from __future__ import annotations

import enum

import numpy as np

__all__ = ["Status", "status_names", "VALIDITY_LIMITS", "MODEL_STATES", "is_model_state"]


class Status(enum.IntEnum):
    """State of the actuator at one point of a curve (stored as int8 in arrays).

    Examples
    --------
    >>> Status(7).name, int(Status.OVERSTRETCHED)
    ('KINKED', 8)
    """

    INFLATION = 0
    BENDING = 1
    LOCKED = 2
    OUT_OF_DOMAIN = 3
    UNSTABLE = 4
    FAILED = 5
    COILED = 6
    KINKED = 7
    OVERSTRETCHED = 8


#: Statuses of the validity limits, in order of precedence.
VALIDITY_LIMITS = (Status.COILED, Status.KINKED, Status.OVERSTRETCHED)
#: Statuses whose theta is a state the model describes: an equilibrium (INFLATION, BENDING)
#: or the end of the stable branch the point stops at (LOCKED: lock angle, UNSTABLE: fold angle).
MODEL_STATES = frozenset((Status.INFLATION, Status.BENDING, Status.LOCKED, Status.UNSTABLE))


def is_model_state(codes) -> np.ndarray:
    """True where a status is one of :data:`MODEL_STATES` (draw the shape; chart it as valid).

    Parameters
    ----------
    codes : array_like of int
        Status codes.

    Returns
    -------
    numpy.ndarray of bool

    Examples
    --------
    >>> is_model_state([0, 1, 3, 6]).tolist()
    [True, True, False, False]
    """
    return np.isin(np.asarray(codes), [int(s) for s in MODEL_STATES])


def status_names(codes) -> list[str]:
    """Names of an array of status codes, for reports and JSON.

    Parameters
    ----------
    codes : array_like of int
        Status codes, any shape (read flat).

    Returns
    -------
    list of str

    Examples
    --------
    >>> status_names([[0, 1], [2, 5]])
    ['INFLATION', 'BENDING', 'LOCKED', 'FAILED']
    """
    return [Status(int(c)).name for c in np.asarray(codes).ravel()]
