"""Bending angles measured with markers: from coordinates, and the model's reading of a layout.

The paper (docs/model.md section 11) put seven markers on each side
of the embroidery, 10 mm apart; the bending angle is the sum of the angles between
consecutive marker chords, averaged over the two rows::

    row:  m1 --- m2 --- m3 --- m4 --- m5 --- m6 --- m7      (clamped end ... tip)
                t1     t2     t3     t4     t5               theta_row = t1 + ... + t5

What a marker sum reads
-----------------------
The sum of the chord-to-chord turning angles is the angle between the first and the
last chord. On a uniform bend of curvature ``kappa = theta/l0`` each chord points
along the arc's tangent at its middle, so ``n`` markers ``h`` apart read
``(n - 2) h kappa`` (50 mm worth of curvature for the paper's layout: half of theta on a
100 mm strip), not theta. On a chain of arcs (a segmented actuator, docs/model.md
section 10) the reading is the turning of the tangent between the middles of the first
and the last chord, the integral of the curvature between them, as long as each of those
two chords lies within one arc; a chord straddling a boundary between arcs points along
neither arc's middle tangent, and markers past the bent length sit on the straight
continuation. :func:`chain_reading_deg` computes the reading from the marker positions
on the bent line (:func:`chain_marker_positions_mm`, :class:`MarkerLayout`), exactly in
every one of these cases; :func:`reading_deg` is its one-arc case, a uniform bend.

From coordinates
----------------
Marker array layout: ``(..., rows * markers_per_side, 2 or 3)``, the markers of row 1
from the clamped end to the tip, then those of row 2, and so on. Leading axes are
frames; a single frame gives scalar results. Angles are measured *in the bending
plane*: chords are projected onto the plane perpendicular to the bending axis (the
strip's lateral direction, which a clamp holds fixed) and each joint's signed turning
angle is taken there, so a 300 deg bend sums without wrapping or flips, and coordinate
noise across the plane is dropped.

The axis is the direction across which all chords of all frames scatter least (SVD);
when the chords do not span a plane (every frame straight) it is ``tangent x normal``.

* Signed (``normal`` given: the direction out of the *back* of the fabric at the clamp,
  the side a positive bend turns toward, docs/model.md section 5): the axis points
  along ``tangent x normal``, with ``tangent`` the strip's direction at the clamp
  (clamped end to tip). Without ``tangent`` it is the first chord of the straightest
  frame: include a frame at or near rest (0 kPa), or pass ``tangent`` when every frame
  is bent far.
* Unsigned (no ``normal``): the axis is oriented so that the most bent frame reads
  positive; the other frames keep their signs relative to it.

Noise: the signed in-plane angle of a chord has no bias under isotropic coordinate
noise, so neither has the reading. The noise itself is estimated from the scatter of
each row's markers along the axis (a row lies in a plane across it): ``noise_mm``, and
from it the standard error of each frame's angle, ``theta_se_deg`` (a chord of length
``c`` turns by ``sqrt(2) sigma / c`` rms; only the first and last chord of a row count).

Examples
--------
>>> import numpy as np
>>> from embroact.predict.markers import bend_angle_deg, MarkerLayout, reading_deg
>>> L = np.array([[0, 0, 0], [10, 0, 0], [20, 0, 0], [20, 10, 0], [20, 20, 0]], float)
>>> round(float(bend_angle_deg(L, markers_per_side=5, sides=1)), 9)
90.0
>>> round(float(bend_angle_deg(L, markers_per_side=5, sides=1, normal=(0, -1, 0))), 9)
-90.0
>>> round(float(reading_deg(120.0, 100.0, MarkerLayout())), 9)   # (7 - 2) * 10 mm of 100 mm
60.0
"""
from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np

from ..patterns.base.arrays import frozen_array
from ..patterns.base.errors import ParameterError, check_range
from ..patterns.base.tolerances import DEFAULT_TOLERANCES

__all__ = ["MarkerSide", "MarkerLayout", "PAPER_LAYOUT", "reading_deg", "marker_positions_mm", "chain_reading_deg",
           "chain_marker_positions_mm", "MarkerAngles", "marker_angles", "bend_angle_deg", "PAPER_MARKERS_PER_SIDE",
           "PAPER_SIDES"]

PAPER_MARKERS_PER_SIDE = 7
PAPER_SIDES = 2
#: The chords span a plane when their second singular value exceeds the third by this factor.
_PLANE_RATIO = 4.0


class MarkerSide(str, enum.Enum):
    """Face of the strip the markers are stuck to.

    Examples
    --------
    >>> MarkerSide("thread").name, MarkerLayout().side.value
    ('THREAD', 'fabric')
    """

    FABRIC = "fabric"  #: on the fabric beside the embroidery (the paper)
    THREAD = "thread"  #: on the thread side, over the tube


def _integer(label: str, v, low: int) -> int:
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < low:
        raise ParameterError(f"{label} must be an integer >= {low}, got {v!r}")
    return int(v)


@dataclass(frozen=True, slots=True)
class MarkerLayout:
    """How a data set's angles were measured: a row of markers along the strip.

    Parameters
    ----------
    markers_per_side : int
        Markers in each row, >= 3 (paper: 7).
    spacing_mm : float
        Distance between neighbouring markers along the fabric at rest [mm], > 0 (paper: 10).
    offset_mm : float
        Distance along the fabric from the clamped end of the bent length to the first
        marker [mm], >= 0 (the paper does not state it; on a uniform bend every offset up
        to ``l0 - (n - 1) h`` reads the same).
    rows : int
        Marker rows (one per side of the embroidery), >= 1 (paper: 2); the angle is their mean.
    side : MarkerSide or str
        Face the markers are on, ``"fabric"`` (paper) or ``"thread"``. Chords of parallel
        curves turn by the same angles, so the reading does not depend on it; it is
        recorded with the data set.

    Examples
    --------
    >>> MarkerLayout().label
    'markers: 2 rows of 7, 10 mm apart, first 0 mm from the clamped end, fabric side'
    """

    markers_per_side: int = PAPER_MARKERS_PER_SIDE
    spacing_mm: float = 10.0
    offset_mm: float = 0.0
    rows: int = PAPER_SIDES
    side: MarkerSide = MarkerSide.FABRIC

    def __post_init__(self) -> None:
        object.__setattr__(self, "markers_per_side", _integer("markers_per_side", self.markers_per_side, 3))
        object.__setattr__(self, "rows", _integer("rows", self.rows, 1))
        check_range("spacing_mm", self.spacing_mm, low=0.0, high=1e4)
        check_range("offset_mm", self.offset_mm, low=0.0, low_inclusive=True, high=1e5)
        try:
            object.__setattr__(self, "side", MarkerSide(self.side))
        except ValueError:
            raise ParameterError(f"side must be one of 'fabric', 'thread', got {self.side!r}") from None

    @property
    def label(self) -> str:
        """One-line description, e.g. for a calibration set's ``measurement``."""
        return (f"markers: {self.rows} rows of {self.markers_per_side}, {self.spacing_mm:g} mm apart, "
                f"first {self.offset_mm:g} mm from the clamped end, {self.side.value} side")

    def as_dict(self) -> dict:
        """Plain dict with unit-suffixed keys (``side`` as its string).

        Returns
        -------
        dict

        Examples
        --------
        >>> MarkerLayout().as_dict()
        {'markers_per_side': 7, 'spacing_mm': 10.0, 'offset_mm': 0.0, 'rows': 2, 'side': 'fabric'}
        """
        return {"markers_per_side": self.markers_per_side, "spacing_mm": float(self.spacing_mm),
                "offset_mm": float(self.offset_mm), "rows": self.rows, "side": self.side.value}


PAPER_LAYOUT = MarkerLayout()
"""The paper's layout: 2 rows of 7 markers 10 mm apart (offset not stated; 0 assumed)."""


def chain_marker_positions_mm(lengths_mm, theta_deg, layout: MarkerLayout) -> np.ndarray:
    """Marker positions in the bending plane on a chain of arcs, the fabric line [mm].

    Arc ``k`` of the chain has length ``lengths_mm[k]`` and bends uniformly by
    ``theta_deg[..., k]``; the chain starts at the origin (the clamped end of the bent
    length, where ``layout.offset_mm`` is counted from) with its tangent along +x, a
    positive bend turning toward +y, and continues straight past its last arc. Marker
    ``j`` sits at arc length ``offset + j * spacing`` along the line (the fabric does not
    stretch). Leading axes of ``theta_deg`` are separate chains (e.g. one per pressure).

    Parameters
    ----------
    lengths_mm : sequence of float
        Arc lengths [mm], each > 0, from the clamped end (a straight piece is an arc bending by 0).
    theta_deg : array_like, shape (..., len(lengths_mm))
        Bend of each arc [deg], finite.
    layout : MarkerLayout

    Returns
    -------
    ndarray, shape theta.shape[:-1] + (markers_per_side, 2)

    Examples
    --------
    >>> lay = MarkerLayout(markers_per_side=3, spacing_mm=50.0, rows=1)
    >>> chain_marker_positions_mm([50.0, 50.0], [0.0, 180.0], lay).round(4).tolist()
    [[0.0, 0.0], [50.0, 0.0], [50.0, 31.831]]
    """
    lengths = np.asarray(lengths_mm, dtype=np.float64).reshape(-1)
    theta = np.asarray(theta_deg, dtype=np.float64)
    if theta.ndim == 0 or theta.shape[-1] != len(lengths) or not len(lengths):
        raise ParameterError(f"theta_deg must have one bend per arc length ({len(lengths)}) along its last axis, "
                             f"got shape {theta.shape}")
    for i, length in enumerate(lengths.tolist()):
        check_range(f"lengths_mm[{i}]", length, low=0.0)
    if not np.all(np.isfinite(theta)):
        raise ParameterError("theta_deg must be finite numbers, got NaN or infinity")
    return _chain_positions(lengths, theta, layout)


def _chain_positions(lengths: np.ndarray, theta: np.ndarray, layout: MarkerLayout) -> np.ndarray:
    """:func:`chain_marker_positions_mm` of checked float arrays (fits call it in their inner loop)."""
    from .shape import planar_chain_mm

    s = layout.offset_mm + layout.spacing_mm * np.arange(layout.markers_per_side)
    tail = max(float(s[-1]) - float(lengths.sum()), 0.0) + layout.spacing_mm  # the straight continuation
    straight = np.zeros(theta.shape[:-1] + (1,))
    return planar_chain_mm(np.append(lengths, tail), np.concatenate([theta, straight], axis=-1), s)


def marker_positions_mm(theta_deg, length_mm, layout: MarkerLayout) -> np.ndarray:
    """Marker positions in the bending plane on a uniform bend of the fabric line [mm].

    The one-arc chain of :func:`chain_marker_positions_mm`: the bent length ``length_mm``
    (l0) carries curvature ``theta/l0``; beyond it the strip continues straight.

    Parameters
    ----------
    theta_deg : float or array_like
        Bend of the length ``length_mm`` [deg].
    length_mm : float
        The bent length l0 [mm], > 0.
    layout : MarkerLayout
        Where the markers sit.

    Returns
    -------
    numpy.ndarray
        Shape ``theta.shape + (markers_per_side, 2)`` [mm].

    Examples
    --------
    >>> marker_positions_mm(0.0, 100.0, MarkerLayout(markers_per_side=3, rows=1)).tolist()
    [[0.0, 0.0], [10.0, 0.0], [20.0, 0.0]]
    """
    l0 = check_range("length_mm", length_mm, low=0.0)
    return _chain_positions(np.array([l0]), np.asarray(theta_deg, dtype=np.float64)[..., None], layout)


def _marker_sum_deg(pos: np.ndarray):
    """Sum of the signed turning angles between consecutive chords of planar points (..., n, 2) [deg]."""
    d = np.diff(pos, axis=-2)
    cross = d[..., :-1, 0] * d[..., 1:, 1] - d[..., :-1, 1] * d[..., 1:, 0]
    dot = np.einsum("...i,...i->...", d[..., :-1, :], d[..., 1:, :])
    out = np.degrees(np.arctan2(cross, dot).sum(axis=-1))
    return float(out) if np.ndim(out) == 0 else out


def chain_reading_deg(lengths_mm, theta_deg, layout: MarkerLayout = PAPER_LAYOUT):
    """What the layout's marker sum reads on a chain of arcs [deg] (module docstring).

    The sum of the signed chord-to-chord turning angles of :func:`chain_marker_positions_mm`,
    exact also where a chord straddles a boundary between arcs. While the first and the
    last chord each lie within one arc it is the bend between their middles (the integral
    of the curvature there).

    Parameters
    ----------
    lengths_mm : array_like (k,)
        Arc lengths [mm].
    theta_deg : array_like (..., k)
        Bend of each arc [deg].
    layout : MarkerLayout, optional
        Where the markers sit (the paper's).

    Returns
    -------
    float or numpy.ndarray
        A float for one chain, an array over the leading axes of ``theta_deg`` otherwise [deg].

    Examples
    --------
    >>> # 7 markers 10 mm apart on 20 mm straight, then 40 mm bending by 80 deg: the chords' middles
    >>> # at 5 and 55 mm hold 35 mm of that arc (70 deg); the first marker is at the clamp
    >>> round(chain_reading_deg([20.0, 40.0], [0.0, 80.0]), 9)
    70.0
    """
    return _marker_sum_deg(chain_marker_positions_mm(lengths_mm, theta_deg, layout))


def reading_deg(theta_deg, length_mm, layout: MarkerLayout = PAPER_LAYOUT):
    """What the layout's marker sum reads on a uniform bend theta of length l0 [deg].

    The one-arc case of :func:`chain_reading_deg`: ``(n - 2) h theta / l0`` while every
    marker lies on the bent length.

    Parameters
    ----------
    theta_deg : float or array_like
        The bend [deg].
    length_mm : float
        The bent length l0 [mm].
    layout : MarkerLayout, optional
        Where the markers sit (the paper's).

    Returns
    -------
    float or numpy.ndarray
        A float for a scalar theta, an array otherwise [deg].

    Examples
    --------
    >>> round(reading_deg(100.0, 100.0), 9)   # the paper's layout: half of theta on 100 mm
    50.0
    """
    return _marker_sum_deg(marker_positions_mm(theta_deg, length_mm, layout))


@dataclass(frozen=True, slots=True)
class MarkerAngles:
    """Bending angles measured from markers.

    Attributes
    ----------
    theta_deg : ndarray, shape (...)
        Bending angle, mean over the rows [deg].
    side_deg : ndarray, shape (..., rows)
        Sum of the joint angles of each row [deg].
    joint_deg : ndarray, shape (..., rows, markers_per_side - 2)
        Signed turning angle at each inner marker, in the bending plane [deg].
    signed : bool
        True when ``normal`` gave the angles their sign (else the most bent frame is positive).
    axis : ndarray, shape (3,)
        Unit bending axis used (positive turning is counter-clockwise about it).
    noise_mm : float
        Coordinate noise estimated from the rows' scatter along the axis [mm] (NaN-free:
        0 for noise-free data).
    theta_se_deg : ndarray, shape (...)
        Standard error of ``theta_deg`` from ``noise_mm`` [deg].

    Examples
    --------
    >>> L = np.array([[0, 0, 0], [10, 0, 0], [20, 0, 0], [20, 10, 0], [20, 20, 0]], float)
    >>> a = marker_angles(L, markers_per_side=5, sides=1, normal=(0, -1, 0))
    >>> round(float(a.theta_deg), 9), a.signed, a.noise_mm
    (-90.0, True, 0.0)
    """

    theta_deg: np.ndarray
    side_deg: np.ndarray
    joint_deg: np.ndarray
    signed: bool
    axis: np.ndarray
    noise_mm: float
    theta_se_deg: np.ndarray


def _vector(name: str, v) -> np.ndarray:
    a = np.asarray(v, dtype=np.float64)
    if a.shape not in ((2,), (3,)) or not np.all(np.isfinite(a)) or not np.any(a):
        raise ParameterError(f"{name} must be a non-zero vector of 2 or 3 finite numbers, got {v!r}")
    return np.concatenate([a, [0.0]]) if a.shape == (2,) else a


def _unit(v: np.ndarray, what: str) -> np.ndarray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    if np.any(n <= DEFAULT_TOLERANCES.length_mm):
        raise ParameterError(f"markers: two consecutive {what} coincide (segment length 0); each marker needs its own position")
    return v / n


def _turning(u: np.ndarray, axis: np.ndarray) -> np.ndarray:
    """Signed turning angles [rad] between consecutive chords, about ``axis``."""
    cross = np.einsum("...i,i->...", np.cross(u[..., :-1, :], u[..., 1:, :]), axis)
    # in-plane dot: remove the components along the axis
    ua = np.einsum("...i,i->...", u, axis)
    dot = np.einsum("...i,...i->...", u[..., :-1, :], u[..., 1:, :]) - ua[..., :-1] * ua[..., 1:]
    return np.arctan2(cross, dot)


def _signed_axis(u: np.ndarray, normal, tangent) -> np.ndarray:
    n = _vector("normal", normal)
    if tangent is None:  # first chord of the straightest frame (the rest state when it is present)
        flat = u.reshape((-1,) + u.shape[-3:])
        bend = np.arccos(np.clip(np.einsum("...i,...i->...", flat[..., :-1, :], flat[..., 1:, :]), -1, 1))
        t = flat[int(np.argmin(bend.sum(axis=(-1, -2)))), 0, 0]
    else:
        t = _vector("tangent", tangent)
    a = np.cross(t, n)
    if np.linalg.norm(a) <= 1e-9 * np.linalg.norm(t) * np.linalg.norm(n):
        raise ParameterError("normal must not be parallel to the strip's tangent at the clamp (pass tangent)")
    return a / np.linalg.norm(a)


def _estimated_axis(u: np.ndarray) -> np.ndarray | None:
    """Least-scatter direction of all chords, None when they do not span a plane (all straight)."""
    _, sv, vt = np.linalg.svd(u.reshape(-1, 3), full_matrices=False)
    return vt[-1] if sv[-2] > _PLANE_RATIO * sv[-1] else None


def marker_angles(
    markers_mm,
    *,
    markers_per_side: int = PAPER_MARKERS_PER_SIDE,
    sides: int = PAPER_SIDES,
    normal=None,
    tangent=None,
) -> MarkerAngles:
    """Joint, row and mean bending angles from marker positions (module docstring).

    Parameters
    ----------
    markers_mm : array_like, shape (..., sides * markers_per_side, 2 or 3)
        Marker coordinates [mm], row by row, clamped end to tip; 2-D ones lie in z = 0.
    markers_per_side : int
        Markers in each row, >= 3 (paper: 7).
    sides : int
        Number of marker rows, >= 1 (paper: 2).
    normal : array_like, shape (2 or 3,), optional
        Direction out of the back of the fabric at the clamp; signs the angles.
    tangent : array_like, shape (2 or 3,), optional
        Strip direction at the clamp (clamped end to tip), with ``normal``.

    Returns
    -------
    MarkerAngles

    Examples
    --------
    >>> import numpy as np
    >>> t = np.radians(np.arange(7) * 10.0)              # 7 markers on a 60 deg arc
    >>> side = np.stack([np.sin(t), 1 - np.cos(t), 0 * t], axis=1) * 57.3
    >>> two = np.concatenate([side, side + [0, 0, 8]])   # second row 8 mm away
    >>> r = marker_angles(two, normal=(0, 1, 0))
    >>> round(float(r.theta_deg), 9), r.joint_deg.shape, round(r.noise_mm, 9)
    (50.0, (2, 5), 0.0)
    """
    markers_per_side = _integer("markers_per_side", markers_per_side, 3)
    sides = _integer("sides", sides, 1)
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
    chords = np.diff(m, axis=-2)
    u = _unit(chords, "markers")  # (..., sides, k-1, 3)
    signed = normal is not None
    if tangent is not None and not signed:
        raise ParameterError("tangent needs normal (it only orients the signed angles)")
    axis = _estimated_axis(u)
    if signed:
        oriented = _signed_axis(u, normal, tangent)
        axis = oriented if axis is None else axis * np.sign(axis @ oriented)
    elif axis is None:
        axis = np.linalg.svd(u.reshape(-1, 3), full_matrices=False)[2][-1]
    joint = _turning(u, axis)
    side = joint.sum(axis=-1)
    theta = side.mean(axis=-1)
    if not signed and theta.size and theta.ravel()[np.argmax(np.abs(theta.ravel()))] < 0.0:
        axis, joint, side, theta = -axis, -joint, -side, -theta
    # noise from each row's scatter along the axis (a row lies in a plane across it)
    along = np.einsum("...i,i->...", m, axis)
    noise = float(np.sqrt(np.mean(np.var(along, axis=-1, ddof=1))))
    c = np.linalg.norm(chords, axis=-1)
    side_var = 2.0 * noise**2 * (1.0 / c[..., 0] ** 2 + 1.0 / c[..., -1] ** 2)
    se = np.sqrt(side_var.sum(axis=-1)) / sides
    return MarkerAngles(
        theta_deg=frozen_array(np.degrees(theta)),
        side_deg=frozen_array(np.degrees(side)),
        joint_deg=frozen_array(np.degrees(joint)),
        signed=signed,
        axis=frozen_array(axis),
        noise_mm=noise,
        theta_se_deg=frozen_array(np.degrees(se)),
    )


def bend_angle_deg(markers_mm, *, markers_per_side: int = PAPER_MARKERS_PER_SIDE, sides: int = PAPER_SIDES,
                   normal=None, tangent=None):
    """Bending angle [deg] only (see :func:`marker_angles`); a float for one frame, an array for many.

    Parameters
    ----------
    markers_mm : array_like (..., sides * markers_per_side, 3)
        Marker positions [mm], as :func:`marker_angles` takes them.
    markers_per_side, sides : int, optional
        The layout (the paper's: 7 and 2).
    normal, tangent : array_like (3,), optional
        As for :func:`marker_angles`.

    Returns
    -------
    float or numpy.ndarray
        [deg].

    Examples
    --------
    >>> L = np.array([[0, 0, 0], [10, 0, 0], [20, 0, 0], [20, 10, 0], [20, 20, 0]], float)
    >>> round(bend_angle_deg(L, markers_per_side=5, sides=1, normal=(0, -1, 0)), 9)
    -90.0
    """
    theta = marker_angles(markers_mm, markers_per_side=markers_per_side, sides=sides, normal=normal,
                          tangent=tangent).theta_deg
    return float(theta) if theta.ndim == 0 else theta
