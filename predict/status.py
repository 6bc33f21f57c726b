"""Status of each point of a predicted curve (MODEL.md sections 4 and 6).

Every public answer of the model carries one :class:`Status` per point; a point
that has no equilibrium never holds NaN but a documented fill value, and its
status says why.

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
============== ===== ========================================================================

Examples
--------
>>> from embroact.predict.status import Status, status_names
>>> int(Status.LOCKED), Status(1).name
(2, 'BENDING')
>>> status_names([0, 1, 4])
['INFLATION', 'BENDING', 'UNSTABLE']
"""
from __future__ import annotations

import enum

import numpy as np

__all__ = ["Status", "status_names"]


class Status(enum.IntEnum):
    """State of the actuator at one point of a curve (stored as int8 in arrays)."""

    INFLATION = 0
    BENDING = 1
    LOCKED = 2
    OUT_OF_DOMAIN = 3
    UNSTABLE = 4
    FAILED = 5


def status_names(codes) -> list[str]:
    """Names of an array of status codes, for reports and JSON."""
    return [Status(int(c)).name for c in np.asarray(codes).ravel()]
