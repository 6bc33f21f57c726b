"""The bent fabric-side line of an actuator at one pressure: a chain of circular arcs, in closed form.

Kinematics (docs/model.md, segmented actuators)
-----------------------------------------------
A frame ``(T, N, B)`` moves along the fabric-side line, arc length ``s``: ``T`` the
tangent, ``N = B x T`` the in-fabric normal (left of the path in the plan), ``B`` the
fabric normal toward the thread side (plan +z). It turns with the body-frame angular
velocity ``omega = (0, kappa_b, kappa_p)``:

- ``kappa_b(s)``: the model's bending curvature, uniform within a segment,
  ``kappa_b = theta_k / L_k``; then ``dT/ds = kappa_p N - kappa_b B``, so positive
  ``theta`` bends toward the back of the fabric (away from the thread side);
- ``kappa_p(s)``: the path's own in-plane curvature (positive turning left), so a
  curved path bends about its local in-fabric normal at every point.

Both are piecewise constant, so the line is cut into *pieces* where neither changes.
On a piece ``omega`` is constant and perpendicular to ``T`` (no twist): the motion is a
rotation about a fixed axis, with the closed forms (Rodrigues)::

    R(h) = I + sin(phi) K + (1 - cos phi) K^2,            phi = |omega| h
    x(h) = h sinc(phi) T0 + h sin(phi/2) sinc(phi/2) (a x T0),  a = omega / |omega|

which stay exact as ``phi -> 0`` (no division by the curvature). For a straight path
along +x the line stays in the bending plane; in the *profile* coordinates used by
target shapes (``x`` along the clamped tangent, ``y = -z`` toward positive bends) a
single uniform bend ``theta`` of length ``L`` ends at
``(L sin(theta)/theta, L (1 - cos theta)/theta)``.

Examples
--------
>>> import math
>>> from embroact.predict.shape import BentShape
>>> arc = BentShape.chain([100.0], [90.0])
>>> [round(float(v), 4) for v in arc.profile_mm([100.0])[0]]   # 200/pi, 200/pi
[63.662, 63.662]
>>> round(arc.tip_angle_deg, 9)
90.0
>>> two = BentShape.chain([50.0, 50.0], [90.0, -90.0])   # an S: back to heading +x
>>> [round(float(v), 4) for v in two.profile_mm([100.0])[0]], abs(round(two.tip_angle_deg, 9))
([63.662, 63.662], 0.0)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..patterns.base.arrays import frozen_array
from ..patterns.base.display import repr_svg
from ..patterns.base.errors import ParameterError, check_range

__all__ = ["BentShape", "planar_chain_mm", "rotation_step", "sample_count"]

#: Breakpoints of the bending and the path closer than this are one [mm].
_MERGE_MM = 1e-9


def rotation_step(kb: np.ndarray, kp: np.ndarray, h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Body-frame displacement (n, 3) and rotation (n, 3, 3) after arc length ``h`` with omega = (0, kb, kp).

    Parameters
    ----------
    kb, kp : numpy.ndarray (n,)
        Bending and path curvature [1/mm].
    h : numpy.ndarray (n,)
        Arc length [mm].

    Returns
    -------
    dx : numpy.ndarray (n, 3)
        Displacement in the body frame [mm].
    rotation : numpy.ndarray (n, 3, 3)
        The frame's rotation.

    Examples
    --------
    >>> import numpy as np
    >>> dx, dr = rotation_step(np.array([0.0]), np.array([0.0]), np.array([5.0]))
    >>> dx.tolist(), bool(np.allclose(dr[0], np.eye(3)))
    ([[5.0, 0.0, 0.0]], True)
    """
    k = np.hypot(kb, kp)
    safe = np.where(k > 0, k, 1.0)
    axis = np.column_stack([np.zeros_like(k), np.where(k > 0, kb / safe, 0.0), np.where(k > 0, kp / safe, 1.0)])
    phi = k * h
    # int_0^h Rot(a, k t) e1 dt = e1 sin(phi)/k + (a x e1)(1 - cos phi)/k   (a . e1 = 0); np.sinc(x) = sin(pi x)/(pi x)
    a_x_e1 = np.column_stack([np.zeros_like(k), axis[:, 2], -axis[:, 1]])
    sin_k = h * np.sinc(phi / np.pi)
    vers_k = h * np.sin(phi / 2.0) * np.sinc(phi / (2.0 * np.pi))
    dx = sin_k[:, None] * np.array([1.0, 0.0, 0.0]) + vers_k[:, None] * a_x_e1
    kx = np.zeros((len(axis), 3, 3))
    kx[:, 0, 1], kx[:, 0, 2], kx[:, 1, 2] = -axis[:, 2], axis[:, 1], -axis[:, 0]
    kx -= np.transpose(kx, (0, 2, 1))
    s, c = np.sin(phi)[:, None, None], np.cos(phi)[:, None, None]
    return dx, np.eye(3) + s * kx + (1.0 - c) * (kx @ kx)


def sample_count(turn_rad: float, radius_mm: float, tolerance_mm: float) -> int:
    """Chords for an arc turning by ``turn_rad`` at ``radius_mm`` with sagitta <= ``tolerance_mm``.

    Parameters
    ----------
    turn_rad : float
        The arc's turn [rad].
    radius_mm : float
        Its radius [mm]; not finite or not positive: a straight line.
    tolerance_mm : float
        Largest sagitta [mm].

    Returns
    -------
    int
        At least 1.

    Examples
    --------
    >>> import math
    >>> sample_count(math.pi, 10.0, 0.05)   # chord angle 2 acos(1 - 0.005) = 0.2 rad
    16
    """
    if turn_rad == 0.0 or not math.isfinite(radius_mm) or radius_mm <= 0.0:
        return 1
    dphi = 2.0 * math.acos(max(1.0 - tolerance_mm / radius_mm, -1.0))
    return max(1, math.ceil(abs(turn_rad) / dphi))


def planar_chain_mm(lengths_mm, theta_deg, s_mm) -> np.ndarray:
    """Profile points (..., n, 2) of a straight-path chain at arc lengths ``s_mm``: the planar case, fast.

    The same line as ``BentShape.chain(lengths_mm, theta_deg).profile_mm(s_mm)`` (x along the
    clamped tangent, y toward positive bends), by complex numbers: on an arc of curvature
    ``k`` starting at ``z0`` with heading ``phi0``, ``z = z0 + h e^{i(phi0 + k h / 2)} sinc(k h / 2)``.
    ``theta_deg`` has one bend per length along its last axis; leading axes are separate
    chains of the same lengths (e.g. one per pressure), and lead the result's. No input
    checks: for inner loops (fits) that call it thousands of times.

    Parameters
    ----------
    lengths_mm : array_like (k,)
        Segment lengths [mm].
    theta_deg : array_like (..., k)
        Bend of each segment [deg].
    s_mm : array_like (n,)
        Arc lengths [mm].

    Returns
    -------
    numpy.ndarray (..., n, 2)
        Profile points [mm].

    Examples
    --------
    >>> planar_chain_mm([50.0, 50.0], [90.0, -90.0], [100.0]).round(4).tolist()
    [[63.662, 63.662]]
    >>> planar_chain_mm([100.0], [[0.0], [90.0]], [100.0]).round(4).tolist()   # two chains
    [[[100.0, 0.0]], [[63.662, 63.662]]]
    """
    lengths = np.asarray(lengths_mm, dtype=np.float64)
    turn = np.radians(np.asarray(theta_deg, dtype=np.float64))
    edges = np.concatenate([[0.0], np.cumsum(lengths)])
    k = turn / lengths
    half = 0.5 * turn
    chords = lengths * np.exp(1j * half) * np.sinc(half / np.pi)
    start = np.zeros(turn.shape[:-1] + (1,))
    phi0 = np.concatenate([start, np.cumsum(turn, axis=-1)], axis=-1)[..., :-1]
    z0 = np.concatenate([start, np.cumsum(np.exp(1j * phi0) * chords, axis=-1)], axis=-1)[..., :-1]
    s = np.asarray(s_mm, dtype=np.float64).reshape(-1)
    i = np.clip(np.searchsorted(edges, s, side="right") - 1, 0, len(lengths) - 1)
    h = np.clip(s - edges[i], 0.0, lengths[i])
    a = 0.5 * k[..., i] * h
    z = z0[..., i] + np.exp(1j * (phi0[..., i] + a)) * h * np.sinc(a / np.pi)
    return np.stack([z.real, z.imag], axis=-1)


def _breaks(lengths: np.ndarray) -> np.ndarray:
    return np.concatenate([[0.0], np.cumsum(lengths)])


@dataclass(frozen=True, slots=True, eq=False)
class BentShape:
    """The bent line as pieces of constant bending and path curvature, with exact frames anywhere.

    Build it with :meth:`chain`. Arrays are read-only.

    Attributes
    ----------
    lengths_mm : ndarray
        Piece lengths [mm] (the bending segments' and the path's breakpoints merged).
    kappa_b_per_mm, kappa_p_per_mm : ndarray
        Bending and path curvature of each piece [1/mm].

    Examples
    --------
    >>> shape = BentShape.chain([50.0, 50.0], [45.0, 45.0])
    >>> shape.length_mm, shape.profile_mm([100.0]).round(4).tolist()
    (100.0, [[63.662, 63.662]])
    """

    lengths_mm: np.ndarray
    kappa_b_per_mm: np.ndarray
    kappa_p_per_mm: np.ndarray
    _s0: np.ndarray
    _x0: np.ndarray
    _r0: np.ndarray

    @classmethod
    def chain(cls, segment_lengths_mm: ArrayLike, theta_deg: ArrayLike, *,
              path_lengths_mm: ArrayLike | None = None, path_kappa_per_mm: ArrayLike | None = None,
              start_mm: tuple[float, float] = (0.0, 0.0), heading_deg: float = 0.0) -> "BentShape":
        """Segments ``k`` of length ``L_k`` bent by ``theta_k`` (uniformly within each), along a path.

        Parameters
        ----------
        segment_lengths_mm : sequence of float
            Fabric-side length of each segment [mm], > 0, in order from the clamp.
        theta_deg : sequence of float
            Bend angle of each segment [deg] (finite).
        path_lengths_mm, path_kappa_per_mm : sequence of float, optional
            The plan path as pieces of constant curvature (default: straight). Their total
            length must equal the segments' total (within 1e-6 mm).
        start_mm, heading_deg : optional
            Clamp position (x, y) [mm] and direction [deg, counter-clockwise from +x].

        Returns
        -------
        BentShape

        Raises
        ------
        ParameterError
            A length not positive, a non-finite angle, counts or totals that disagree.

        Examples
        --------
        >>> BentShape.chain([100.0], [90.0], start_mm=(10.0, 0.0), heading_deg=90.0).frames([0.0])[0].tolist()
        [[10.0, 0.0, 0.0]]
        >>> try:
        ...     BentShape.chain([100.0], [90.0, 10.0])
        ... except ValueError as exc:
        ...     print(exc)
        theta_deg must have one value per segment length (1), got 2
        """
        lengths = np.asarray(segment_lengths_mm, dtype=np.float64).reshape(-1)
        theta = np.asarray(theta_deg, dtype=np.float64).reshape(-1)
        if len(lengths) == 0 or len(lengths) != len(theta):
            raise ParameterError(f"theta_deg must have one value per segment length ({len(lengths)}), got {len(theta)}")
        for i, (length, t) in enumerate(zip(lengths.tolist(), theta.tolist())):
            check_range(f"segment_lengths_mm[{i}]", length, low=0.0)
            check_range(f"theta_deg[{i}]", t)
        kb_seg = np.radians(theta) / lengths
        if path_lengths_mm is None:
            pl, pk = lengths.copy(), np.zeros(len(lengths))
        else:
            pl = np.asarray(path_lengths_mm, dtype=np.float64).reshape(-1)
            pk = np.asarray(path_kappa_per_mm if path_kappa_per_mm is not None else np.zeros(len(pl)),
                            dtype=np.float64).reshape(-1)
            if len(pl) == 0 or len(pl) != len(pk) or not np.all(pl > 0):
                raise ParameterError("path_lengths_mm must be positive, one per path curvature, at least one piece")
            if abs(pl.sum() - lengths.sum()) > 1e-6:
                raise ParameterError(f"path_lengths_mm must add up to the segments' length {lengths.sum():g} mm, "
                                     f"got {pl.sum():g}")
        seg_b, path_b = _breaks(lengths), _breaks(pl)
        cuts = np.sort(np.concatenate([seg_b, path_b[1:-1]]))  # sorted; repeats go with the close ones
        cuts = cuts[np.concatenate([[True], np.diff(cuts) > _MERGE_MM])]  # (np.unique would load numpy.ma)
        cuts[-1] = seg_b[-1]
        mids = 0.5 * (cuts[:-1] + cuts[1:])
        kb = kb_seg[np.clip(np.searchsorted(seg_b, mids, side="right") - 1, 0, len(lengths) - 1)]
        kp = pk[np.clip(np.searchsorted(path_b, mids, side="right") - 1, 0, len(pl) - 1)]
        h = math.radians(check_range("heading_deg", heading_deg))
        x = np.array([float(start_mm[0]), float(start_mm[1]), 0.0])
        r = np.array([[math.cos(h), -math.sin(h), 0.0], [math.sin(h), math.cos(h), 0.0], [0.0, 0.0, 1.0]])
        pieces = np.diff(cuts)
        dx, dr = rotation_step(kb, kp, pieces)
        xs, rs = [x], [r]
        for i in range(len(pieces) - 1):
            x, r = x + r @ dx[i], r @ dr[i]
            xs.append(x)
            rs.append(r)
        return cls(frozen_array(pieces), frozen_array(kb), frozen_array(kp), frozen_array(cuts[:-1]),
                   frozen_array(xs), frozen_array(rs))

    @property
    def length_mm(self) -> float:
        """Total length [mm]."""
        return float(self.lengths_mm.sum())

    def moved(self, dx_mm: float, dy_mm: float) -> "BentShape":
        """The same shape with its clamp moved by (``dx_mm``, ``dy_mm``) in the plan.

        Parameters
        ----------
        dx_mm, dy_mm : float
            The displacement [mm].

        Returns
        -------
        BentShape

        Examples
        --------
        >>> BentShape.chain([100.0], [90.0]).moved(10.0, -5.0).frames([100.0])[0].round(3).tolist()
        [[73.662, -5.0, -63.662]]
        """
        return type(self)(self.lengths_mm, self.kappa_b_per_mm, self.kappa_p_per_mm, self._s0,
                          frozen_array(self._x0 + np.array([float(dx_mm), float(dy_mm), 0.0])), self._r0)

    def __repr__(self) -> str:
        n = len(self.lengths_mm)
        curved = bool(np.any(self.kappa_p_per_mm != 0.0))
        return (f"BentShape({n} piece{'s' * (n != 1)}, {self.length_mm:.4g} mm, turning {self.turning_deg:.4g} deg"
                f"{', curved path' if curved else ''})")

    #: Side view in Jupyter (registered by ``embroact``).
    _repr_svg_ = repr_svg

    def frames(self, s_mm) -> tuple[np.ndarray, np.ndarray]:
        """Positions (n, 3) [mm] and frames (n, 3, 3), columns T, N, B, at arc lengths ``s_mm`` (clipped).

        Parameters
        ----------
        s_mm : array_like (n,)
            Arc lengths from the clamp [mm].

        Returns
        -------
        positions : numpy.ndarray (n, 3)
            [mm].
        frames : numpy.ndarray (n, 3, 3)
            Columns T, N, B.

        Examples
        --------
        >>> shape = BentShape.chain([100.0], [90.0])
        >>> x, f = shape.frames([100.0])
        >>> x.round(4).tolist(), (f[0][:, 0].round(4) + 0.0).tolist()  # a quarter turn: the tip points along -z
        ([[63.662, 0.0, -63.662]], [0.0, 0.0, -1.0])
        """
        s = np.clip(np.asarray(s_mm, dtype=np.float64).reshape(-1), 0.0, self.length_mm)
        i = np.clip(np.searchsorted(self._s0, s, side="right") - 1, 0, len(self._s0) - 1)
        dx, dr = rotation_step(self.kappa_b_per_mm[i], self.kappa_p_per_mm[i], s - self._s0[i])
        r0 = self._r0[i]
        return self._x0[i] + np.einsum("nij,nj->ni", r0, dx), r0 @ dr

    def points(self, s_mm, offsets_uv_mm) -> np.ndarray:
        """World points (n, m, 3) of profile offsets (m, 2) = (u along N, v along B) at ``s_mm``.

        Parameters
        ----------
        s_mm : array_like (n,)
            Arc lengths [mm].
        offsets_uv_mm : array_like (m, 2)
            Offsets (u along N, v along B) [mm].

        Returns
        -------
        numpy.ndarray (n, m, 3)
            [mm].

        Examples
        --------
        >>> shape = BentShape.chain([100.0], [90.0])
        >>> shape.points([100.0], [(0.0, 1.0)]).round(4).tolist()
        [[[64.662, 0.0, -63.662]]]
        """
        x, r = self.frames(s_mm)
        uv = np.asarray(offsets_uv_mm, dtype=np.float64).reshape(-1, 2)
        return x[:, None, :] + uv[None, :, 0, None] * r[:, None, :, 1] + uv[None, :, 1, None] * r[:, None, :, 2]

    def pieces(self):
        """``(s_start, length, kappa_b, kappa_p)`` of each piece.

        Returns
        -------
        iterator of tuple of float
            [mm, mm, 1/mm, 1/mm].

        Examples
        --------
        >>> [round(v, 6) for v in next(iter(BentShape.chain([100.0], [90.0]).pieces()))]
        [0.0, 100.0, 0.015708, 0.0]
        """
        return zip(self._s0.tolist(), self.lengths_mm.tolist(), self.kappa_b_per_mm.tolist(),
                   self.kappa_p_per_mm.tolist())

    def profile_mm(self, s_mm) -> np.ndarray:
        """In-plane coordinates (n, 2) of a straight-path shape: x along the clamped tangent, y = -z.

        ``y > 0`` toward positive bends (the fabric's back). Only meaningful for a straight
        path starting at the origin heading +x (the default of :meth:`chain`).

        Parameters
        ----------
        s_mm : array_like (n,)
            Arc lengths [mm].

        Returns
        -------
        numpy.ndarray (n, 2)
            [mm].

        Examples
        --------
        >>> shape = BentShape.chain([100.0], [90.0])
        >>> shape.profile_mm([100.0]).round(4).tolist()
        [[63.662, 63.662]]
        """
        p, _ = self.frames(s_mm)
        return np.column_stack([p[:, 0], -p[:, 2]])

    def samples_mm(self, tolerance_mm: float, offset_mm: float = 0.0) -> np.ndarray:
        """Arc lengths at which a line at ``offset_mm`` along ``B`` is drawn within ``tolerance_mm`` (chordal).

        Straight-path shapes only (the centre of curvature lies on the -B side, so the offset
        line of a piece is an arc of radius ``|1/kappa_b + offset|``); every piece boundary is included.

        Parameters
        ----------
        tolerance_mm : float
            Largest chordal error [mm], > 0.
        offset_mm : float, optional
            The line's offset along B [mm].

        Returns
        -------
        numpy.ndarray
            Arc lengths [mm], from 0.

        Examples
        --------
        >>> shape = BentShape.chain([100.0], [90.0])
        >>> s = shape.samples_mm(0.05)
        >>> len(s), s[:3].tolist()
        (21, [0.0, 5.0, 10.0])
        """
        tol = check_range("tolerance_mm", tolerance_mm, low=0.0)
        out = [np.zeros(1)]
        for s0, length, kb, _ in self.pieces():
            radius = abs(1.0 / kb + offset_mm) if kb else math.inf
            n = sample_count(kb * length, radius, tol)
            out.append(s0 + length * np.arange(1, n + 1) / n)
        return np.concatenate(out)

    @property
    def tip_mm(self) -> np.ndarray:
        """Position of the free end (3,) [mm]."""
        return self.frames([self.length_mm])[0][0]

    @property
    def tip_angle_deg(self) -> float:
        """Angle of the free end's tangent in the profile plane (x, -z) [deg], in (-180, 180]; straight paths."""
        t = self.frames([self.length_mm])[1][0, :, 0]
        return math.degrees(math.atan2(-t[2], t[0]))

    @property
    def turning_deg(self) -> float:
        """Sum of the segments' bend angles [deg] (the tip angle of a straight path, unwrapped)."""
        return float(np.degrees(np.sum(self.kappa_b_per_mm * self.lengths_mm)))
