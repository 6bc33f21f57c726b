"""Bending angle from motion-capture marker coordinates, as the paper measured it.

The paper (MODEL.md section 8) put fourteen markers on the actuator, seven per side
of the embroidery, 10 mm apart.  On each side the six segments between consecutive
markers make five angles; their sum is that side's bending angle, and the bending
angle is the mean over the two sides::

    side:  m1 --- m2 --- m3 --- m4 --- m5 --- m6 --- m7      (base ... tip)
                 t1     t2     t3     t4     t5               theta_side = t1 + ... + t5

Marker array layout: ``(..., n_markers, 2 or 3)``, the markers of side 1 from base to
tip, then those of side 2, and so on (``markers_per_side`` each).  Leading axes are
frames; a single frame ``(n_markers, 3)`` gives scalar results.

Sign convention
---------------
Unsigned by default (the paper's magnitude).  Given ``normal``, a vector pointing
out of the *back* of the fabric (the side the strip bends toward when the thread
side lengthens, theta > 0 in MODEL.md section 4), each joint angle gets the sign of
``(u_i x u_{i+1}) . (u_1 x normal)``, where ``u_i`` is the unit vector of segment i and
``u_1`` the first segment of that side in the same frame: positive when the side
turns toward ``normal``.  For a bend in one plane this is the signed turning angle;
it needs the first segment not parallel to ``normal`` (true near a clamped base).
2-D coordinates are treated as lying in the plane z = 0.

Examples
--------
>>> import numpy as np
>>> from embroact.predict.markers import bend_angle_deg
>>> L = np.array([[0, 0, 0], [10, 0, 0], [20, 0, 0], [20, 10, 0], [20, 20, 0]], float)
>>> round(float(bend_angle_deg(L, markers_per_side=5, sides=1)), 9)
90.0
>>> round(float(bend_angle_deg(L, markers_per_side=5, sides=1, normal=(0, -1, 0))), 9)
-90.0
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..patterns.base.arrays import frozen_array
from ..patterns.base.errors import ParameterError
from ..patterns.base.tolerances import DEFAULT_TOLERANCES

__all__ = ["MarkerAngles", "marker_angles", "bend_angle_deg", "PAPER_MARKERS_PER_SIDE", "PAPER_SIDES"]

PAPER_MARKERS_PER_SIDE = 7
PAPER_SIDES = 2


@dataclass(frozen=True, slots=True)
class MarkerAngles:
    """Bending angles measured from markers.

    Attributes
    ----------
    theta_deg : ndarray, shape (...)
        Bending angle, mean over the sides [deg].
    side_deg : ndarray, shape (..., sides)
        Sum of the joint angles of each side [deg].
    joint_deg : ndarray, shape (..., sides, markers_per_side - 2)
        Angle between consecutive segments at each inner marker [deg].
    signed : bool
        True when a reference normal gave the angles a sign.
    """

    theta_deg: np.ndarray
    side_deg: np.ndarray
    joint_deg: np.ndarray
    signed: bool


def _unit(v: np.ndarray, what: str) -> np.ndarray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    if np.any(n <= DEFAULT_TOLERANCES.length_mm):
        raise ParameterError(f"markers: two consecutive {what} coincide (segment length 0); each marker needs its own position")
    return v / n


def marker_angles(
    markers_mm,
    *,
    markers_per_side: int = PAPER_MARKERS_PER_SIDE,
    sides: int = PAPER_SIDES,
    normal=None,
) -> MarkerAngles:
    """Joint, side and mean bending angles from marker positions.

    Parameters
    ----------
    markers_mm : array_like, shape (..., sides * markers_per_side, 2 or 3)
        Marker coordinates [mm] (any length unit works), side by side, base to tip.
    markers_per_side : int
        Markers on each side, >= 3 (paper: 7).
    sides : int
        Number of marker rows, >= 1 (paper: 2).
    normal : array_like, shape (2 or 3,), optional
        Direction out of the back of the fabric; gives the angles a sign (module docstring).

    Returns
    -------
    MarkerAngles

    Examples
    --------
    >>> import numpy as np
    >>> t = np.radians(np.arange(7) * 10.0)              # 7 markers on a 60 deg arc
    >>> side = np.stack([np.sin(t), 1 - np.cos(t), 0 * t], axis=1) * 57.3
    >>> two = np.concatenate([side, side + [0, 0, 8]])   # second row 8 mm away
    >>> r = marker_angles(two)
    >>> round(float(r.theta_deg), 9), r.joint_deg.shape
    (50.0, (2, 5))
    """
    for label, v, low in (("markers_per_side", markers_per_side, 3), ("sides", sides, 1)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < low:
            raise ParameterError(f"{label} must be an integer >= {low}, got {v!r}")
    m = np.asarray(markers_mm, dtype=np.float64)
    if m.ndim < 2 or m.shape[-1] not in (2, 3) or m.shape[-2] != sides * markers_per_side:
        raise ParameterError(
            f"markers must have shape (..., {sides * markers_per_side}, 2 or 3) for {sides} side(s) "
            f"of {markers_per_side} markers, got {m.shape}"
        )
    if not np.all(np.isfinite(m)):
        raise ParameterError("markers must be finite numbers, got NaN or infinity (missing marker?)")
    if m.shape[-1] == 2:
        m = np.concatenate([m, np.zeros(m.shape[:-1] + (1,))], axis=-1)
    m = m.reshape(m.shape[:-2] + (sides, markers_per_side, 3))
    u = _unit(np.diff(m, axis=-2), "markers")  # (..., sides, k-1, 3)
    cos = np.einsum("...i,...i->...", u[..., :-1, :], u[..., 1:, :])
    sin = np.linalg.norm(np.cross(u[..., :-1, :], u[..., 1:, :]), axis=-1)
    joint = np.degrees(np.arctan2(sin, cos))  # unsigned, accurate at 0 and 180 deg
    signed = normal is not None
    if signed:
        n = np.asarray(normal, dtype=np.float64)
        if n.shape not in ((2,), (3,)) or not np.all(np.isfinite(n)) or not np.any(n):
            raise ParameterError(f"normal must be a non-zero vector of 2 or 3 finite numbers, got {normal!r}")
        n = np.concatenate([n, [0.0]]) if n.shape == (2,) else n
        hinge = np.cross(u[..., :1, :], n)  # (..., sides, 1, 3)
        turn = np.einsum("...i,...i->...", np.cross(u[..., :-1, :], u[..., 1:, :]), hinge)
        joint = np.where(turn < 0.0, -joint, joint)
    side = joint.sum(axis=-1)
    return MarkerAngles(
        theta_deg=frozen_array(side.mean(axis=-1)),
        side_deg=frozen_array(side),
        joint_deg=frozen_array(joint),
        signed=signed,
    )


def bend_angle_deg(markers_mm, *, markers_per_side: int = PAPER_MARKERS_PER_SIDE, sides: int = PAPER_SIDES, normal=None):
    """Bending angle [deg] only (see :func:`marker_angles`); a float for one frame, an array for many."""
    theta = marker_angles(markers_mm, markers_per_side=markers_per_side, sides=sides, normal=normal).theta_deg
    return float(theta) if theta.ndim == 0 else theta
