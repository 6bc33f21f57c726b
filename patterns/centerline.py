"""The tube path: an arc-length parametrised plane curve in the plan frame (mm, y up).

A :class:`Centerline` is stored as a polyline. Dense polylines (flattened SVG
curves, sampled functions) are treated as a sampled *smooth* curve: the tangent
angle is known at every vertex (bisector of the two neighbouring segments) and
varies linearly in arc length between vertices. So ``normal_at`` turns smoothly
along a curve and the legs of a pattern follow the local normal; on a straight
segment it is exactly the segment's normal. A vertex that turns by more than
:data:`MAX_SMOOTH_TURN_DEG` is a *corner*: its curvature radius counts as 0, and
:meth:`Centerline.check_radius` rejects it with advice to round it.

SVG paths (:meth:`Centerline.from_svg_path`, parsed by :mod:`embroact.patterns.svgpath`
with svgelements): path units are read as mm and y is flipped (SVG's y points down, the
plan frame's up), so the drawing looks the same on screen as in an SVG viewer. Curves are
flattened to a chordal error of at most ``DEFAULT_TOLERANCES.curve_flatness_mm``; several
subpaths are joined when each starts where the one before ended, else rejected. SVG
*files* (units, transforms, ids) are read by :mod:`embroact.export.files.svgfile`.

End points carry the direction of their segment (no extrapolation), so on a coarsely
sampled curve the frame at the very ends is off by half a chord angle.

Examples
--------
>>> from embroact.patterns.centerline import Centerline
>>> c = Centerline.straight(100.0, origin_mm=(10.0, 5.0), rotation_deg=90.0)
>>> c.length_mm
100.0
>>> c.point_at(25.0).round(9).tolist()
[10.0, 30.0]
>>> c.normal_at(0.0).round(9).tolist()   # unit LEFT normal
[-1.0, 0.0]
>>> s, off = c.project([[8.0, 40.0]])
>>> round(float(s[0]), 9), round(float(off[0]), 9)
(35.0, 2.0)
>>> Centerline.from_svg_path("M 0 0 H 10 V 10").points_mm.tolist()  # y flipped
[[0.0, 0.0], [10.0, 0.0], [10.0, -10.0]]
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import shapely

from .base.arrays import frozen_array
from .base.errors import ParameterError, PathError, check_range
from .base.tolerances import DEFAULT_TOLERANCES
from .base.validate import PATH_POINTS, check_coordinates
from .spatial import SegmentIndex, self_crossings

__all__ = ["Centerline", "as_centerline", "MAX_SMOOTH_TURN_DEG", "RADIUS_RTOL"]

#: A vertex turning by more than this is a corner (curvature radius 0) [deg].
MAX_SMOOTH_TURN_DEG = 10.0
#: Relative slack of :meth:`Centerline.check_radius`: a polyline flattened from an arc of
#: radius R, turning by up to MAX_SMOOTH_TURN_DEG per vertex, has a curvature radius up
#: to turn^2/24 (0.13 %) smaller than R, so an arc of exactly the limit still passes.
RADIUS_RTOL = 2e-3
#: Shortest straight path [mm] (1 um: far below the machine grid; 5e-324 is a typo, not a tube).
MIN_LENGTH_MM = 1e-3
#: Newton steps used by :meth:`Centerline.project` to invert the smooth-normal frame.
_PROJECT_STEPS = 6


@dataclass(frozen=True, slots=True, eq=False)
class Centerline:
    """A plane path [mm], plan frame, y up; use the constructors, not the raw field.

    Attributes
    ----------
    points_mm : ndarray, shape (n, 2)
        Polyline vertices [mm], read-only, no repeated points, n >= 2.

    Examples
    --------
    >>> c = Centerline.from_points([(0, 0), (30, 0), (30, 40)])
    >>> c.length_mm, c
    (70.0, Centerline(n_points=3, length_mm=70))
    """

    points_mm: np.ndarray
    _s: np.ndarray = field(init=False, repr=False)
    _theta: np.ndarray = field(init=False, repr=False)
    _turn: np.ndarray = field(init=False, repr=False)
    _index: SegmentIndex | None = field(init=False, repr=False, default=None)

    def __post_init__(self) -> None:
        pts = _clean_points(self.points_mm)
        seg = np.diff(pts, axis=0)
        h = np.hypot(seg[:, 0], seg[:, 1])
        phi = np.unwrap(np.arctan2(seg[:, 1], seg[:, 0]))
        turn = np.diff(phi)
        theta = np.concatenate([phi[:1], 0.5 * (phi[:-1] + phi[1:]), phi[-1:]])
        object.__setattr__(self, "points_mm", frozen_array(pts))
        object.__setattr__(self, "_s", frozen_array(np.concatenate([[0.0], np.cumsum(h)])))
        object.__setattr__(self, "_theta", frozen_array(theta))
        object.__setattr__(self, "_turn", frozen_array(turn))

    # ------------------------------------------------------------------ constructors
    @classmethod
    def straight(
        cls, length_mm: float, *, origin_mm: tuple[float, float] = (0.0, 0.0), rotation_deg: float = 0.0
    ) -> "Centerline":
        """Straight path of ``length_mm`` from ``origin_mm``, direction ``rotation_deg`` from +x (CCW).

        Parameters
        ----------
        length_mm : float
            Length [mm], in [1e-3, 1e6].
        origin_mm : (float, float)
            Start point [mm].
        rotation_deg : float
            Direction [deg, counter-clockwise from +x], in (-3600, 3600).

        Returns
        -------
        Centerline

        Examples
        --------
        >>> Centerline.straight(10.0, origin_mm=(5.0, 0.0), rotation_deg=90.0).points_mm.round(9).tolist()
        [[5.0, 0.0], [5.0, 10.0]]
        """
        length = check_range("length_mm", length_mm, low=MIN_LENGTH_MM, low_inclusive=True, high=1e6)
        ox, oy = _xy("origin_mm", origin_mm)
        a = math.radians(check_range("rotation_deg", rotation_deg, low=-3600.0, high=3600.0))
        return cls(np.array([[ox, oy], [ox + length * math.cos(a), oy + length * math.sin(a)]]))

    @classmethod
    def from_points(cls, points) -> "Centerline":
        """Path through ``points`` (sequence or array of (x, y) in mm); exact repeats are dropped.

        Parameters
        ----------
        points : array-like, shape (n, 2)
            Vertices [mm], at least two distinct, finite.

        Returns
        -------
        Centerline

        Examples
        --------
        >>> Centerline.from_points([(0, 0), (0, 0), (3, 4)]).points_mm.tolist()
        [[0.0, 0.0], [3.0, 4.0]]
        """
        return cls(points)

    @classmethod
    def from_svg_path(cls, d: str) -> "Centerline":
        """Path from an SVG path ``d`` string (M L H V C S Q T A Z, absolute and relative).

        Units are mm; y is flipped (SVG y down -> plan y up). Subpaths are joined when each
        starts where the one before ended (:func:`embroact.patterns.svgpath.flatten`).

        Parameters
        ----------
        d : str
            SVG path data in mm, e.g. ``"M 0 0 a5,5 0 01 10,0"``.

        Returns
        -------
        Centerline
            The flattened path in the plan frame.

        Examples
        --------
        >>> Centerline.from_svg_path("M 0 0 L 10 0 M 10 0 L 10 5").points_mm.tolist()
        [[0.0, 0.0], [10.0, 0.0], [10.0, -5.0]]
        """
        from .svgpath import flatten, parse_d, to_plan

        return cls(to_plan(flatten(parse_d(d))))

    # ------------------------------------------------------------------ basic geometry
    @property
    def length_mm(self) -> float:
        """Arc length of the path [mm]."""
        return float(self._s[-1])

    @property
    def vertex_s_mm(self) -> np.ndarray:
        """Arc length at each vertex of ``points_mm`` [mm], read-only (0 ... ``length_mm``)."""
        return self._s

    def segment_curvature(self) -> np.ndarray:
        """Signed curvature per segment [1/mm] (> 0 turning left); :meth:`curvature_at` looks it up.

        Returns
        -------
        ndarray, shape (n - 1,)

        Examples
        --------
        >>> Centerline.straight(10.0).segment_curvature().tolist()
        [0.0]
        """
        return np.diff(self._theta) / np.diff(self._s)

    def as_linestring(self) -> shapely.LineString:
        """The path as a shapely LineString.

        Returns
        -------
        shapely.LineString

        Examples
        --------
        >>> Centerline.from_points([(0, 0), (3, 4)]).as_linestring().length
        5.0
        """
        return shapely.LineString(self.points_mm)

    def _clamped(self, s_mm) -> np.ndarray:
        """Arc length(s) ``s_mm`` as floats clipped to [0, length] [mm]."""
        return np.clip(np.asarray(s_mm, dtype=np.float64), 0.0, self.length_mm)

    def _angle_at(self, s_mm):
        return np.interp(self._clamped(s_mm), self._s, self._theta)

    def _xy_angle_at(self, s_mm) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The x and y of :meth:`point_at` and the tangent angle at ``s_mm``, the arc length clipped once."""
        s = self._clamped(s_mm)
        return (np.interp(s, self._s, self.points_mm[:, 0]), np.interp(s, self._s, self.points_mm[:, 1]),
                np.interp(s, self._s, self._theta))

    def point_at(self, s_mm) -> np.ndarray:
        """Point(s) at arc length ``s_mm`` (clipped to [0, length]) [mm], shape (..., 2).

        Parameters
        ----------
        s_mm : float or array-like
            Arc length from the start [mm].

        Returns
        -------
        ndarray, shape (..., 2)

        Examples
        --------
        >>> Centerline.from_points([(0, 0), (10, 0), (10, 10)]).point_at([5.0, 15.0, 99.0]).tolist()
        [[5.0, 0.0], [10.0, 5.0], [10.0, 10.0]]
        """
        s = self._clamped(s_mm)
        return np.stack([np.interp(s, self._s, self.points_mm[:, 0]), np.interp(s, self._s, self.points_mm[:, 1])], axis=-1)

    def tangent_at(self, s_mm) -> np.ndarray:
        """Unit tangent(s) at arc length ``s_mm``, smooth along dense curves, shape (..., 2).

        Parameters
        ----------
        s_mm : float or array-like
            Arc length from the start [mm].

        Returns
        -------
        ndarray, shape (..., 2)

        Examples
        --------
        >>> Centerline.straight(10.0, rotation_deg=90.0).tangent_at(2.0).round(9).tolist()
        [0.0, 1.0]
        """
        th = self._angle_at(s_mm)
        return np.stack([np.cos(th), np.sin(th)], axis=-1)

    def normal_at(self, s_mm) -> np.ndarray:
        """Unit LEFT normal(s) (tangent turned +90 deg), shape (..., 2).

        Parameters
        ----------
        s_mm : float or array-like
            Arc length from the start [mm].

        Returns
        -------
        ndarray, shape (..., 2)

        Examples
        --------
        >>> Centerline.straight(10.0).normal_at(2.0).tolist()
        [-0.0, 1.0]
        """
        th = self._angle_at(s_mm)
        return np.stack([-np.sin(th), np.cos(th)], axis=-1)

    def offset_point_at(self, s_mm, offset_mm) -> np.ndarray:
        """``point_at(s) + offset * normal_at(s)`` (offset > 0 to the left) [mm].

        Parameters
        ----------
        s_mm : float or array-like
            Arc length from the start [mm].
        offset_mm : float or array-like
            Distance along the left normal [mm] (negative: to the right).

        Returns
        -------
        ndarray, shape (..., 2)

        Examples
        --------
        >>> Centerline.straight(10.0).offset_point_at(4.0, -3.5).tolist()
        [4.0, -3.5]
        """
        return np.stack(self.offset_xy_at(s_mm, offset_mm), axis=-1)

    def offset_xy_at(self, s_mm, offset_mm) -> tuple[np.ndarray, np.ndarray]:
        """The x and the y of :meth:`offset_point_at`, each of the shape of ``s_mm`` and ``offset_mm`` together
        [mm]: the arc length clipped once and nothing stacked (a search along a rail takes many such steps).

        Parameters
        ----------
        s_mm, offset_mm : float or array-like
            As for :meth:`offset_point_at`.

        Returns
        -------
        x, y : ndarray

        Examples
        --------
        >>> x, y = Centerline.straight(10.0, rotation_deg=90.0).offset_xy_at([4.0, 12.0], 1.5)
        >>> x.round(9).tolist(), y.round(9).tolist()
        ([-1.5, -1.5], [4.0, 10.0])
        """
        x, y, th = self._xy_angle_at(s_mm)
        off = np.asarray(offset_mm, dtype=np.float64)
        return x + off * -np.sin(th), y + off * np.cos(th)

    def curvature_at(self, s_mm) -> np.ndarray:
        """Signed curvature [1/mm] (> 0 turning left) of the smooth-tangent model.

        Piecewise constant per segment; corners are included at their share of the turn
        (use :meth:`min_radius_mm` to detect them).

        Parameters
        ----------
        s_mm : float or array-like
            Arc length from the start [mm].

        Returns
        -------
        ndarray

        Examples
        --------
        >>> float(Centerline.straight(10.0).curvature_at(5.0))
        0.0
        """
        kappa = self.segment_curvature()
        s = self._clamped(s_mm)
        i = np.clip(np.searchsorted(self._s, s, side="right") - 1, 0, len(kappa) - 1)
        return kappa[i]

    def _radii(self) -> np.ndarray:
        """Curvature radius per segment [mm]; 0 on both segments of a corner."""
        kappa = np.abs(self.segment_curvature())
        with np.errstate(divide="ignore"):
            r = np.where(kappa > 0.0, 1.0 / np.where(kappa > 0.0, kappa, 1.0), np.inf)
        corner = np.abs(self._turn) > math.radians(MAX_SMOOTH_TURN_DEG)
        r[:-1][corner] = 0.0
        r[1:][corner] = 0.0
        return r

    def min_radius_mm(self) -> float:
        """Smallest curvature radius along the path [mm]; ``inf`` if straight, 0 at a corner.

        Returns
        -------
        float

        Examples
        --------
        >>> Centerline.straight(10.0).min_radius_mm(), Centerline.from_points([(0, 0), (10, 0), (10, 10)]).min_radius_mm()
        (inf, 0.0)
        """
        return float(self._radii().min())

    def check_radius(self, min_radius_mm: float, name: str) -> None:
        """Raise :class:`PathError` if the path bends tighter than ``min_radius_mm``.

        Parameters
        ----------
        min_radius_mm : float
            Smallest allowed curvature radius [mm].
        name : str
            Where the limit comes from (``"width_mm/2"``), named in the message.

        Returns
        -------
        None

        Raises
        ------
        PathError
            A corner, or a bend tighter than the limit (the message gives where).

        Examples
        --------
        >>> Centerline.from_points([(0, 0), (10, 0), (10, 10)]).check_radius(3.5, "width_mm/2")
        Traceback (most recent call last):
        ...
        embroact.patterns.base.errors.PathError: path has a corner at (10.00, 0.00) mm (turn 90.0 deg > ...
        """
        corner = np.flatnonzero(np.abs(self._turn) > math.radians(MAX_SMOOTH_TURN_DEG))
        if corner.size:
            i = int(corner[0])
            x, y = self.points_mm[i + 1]
            raise PathError(
                f"path has a corner at ({x:.2f}, {y:.2f}) mm (turn {math.degrees(abs(self._turn[i])):.1f} deg > "
                f"{MAX_SMOOTH_TURN_DEG:g} deg), which counts as curvature radius 0 < {name} = {min_radius_mm:g} mm; "
                f"round the corner with radius >= {min_radius_mm:g} mm or give a smooth path (SVG curve or denser points)"
            )
        r = self._radii()
        i = int(np.argmin(r))
        if r[i] < min_radius_mm * (1.0 - RADIUS_RTOL):
            x, y = 0.5 * (self.points_mm[i] + self.points_mm[i + 1])
            raise PathError(
                f"path curvature radius must be >= {name} = {min_radius_mm:g} mm, "
                f"got {r[i]:.3g} mm near ({x:.2f}, {y:.2f}) mm"
            )

    def offset_curves(self, distance_mm: float, start_mm: float = 0.0,
                      end_mm: float | None = None) -> tuple[shapely.LineString, shapely.LineString]:
        """The two rails at +-``distance_mm`` along the smooth normal: (left, right) LineStrings.

        Parameters
        ----------
        distance_mm : float
            Offset of each rail from the path [mm], >= 0.
        start_mm, end_mm : float
            The stretch of the path the rails follow [mm] (default: the whole path); clamped to it.

        Returns
        -------
        (shapely.LineString, shapely.LineString)
            Left and right rail, through the path's vertices and the midpoints between them.

        Examples
        --------
        >>> left, right = Centerline.straight(10.0).offset_curves(3.5)
        >>> left.coords[0], right.coords[-1]
        ((0.0, 3.5), (10.0, -3.5))
        >>> Centerline.straight(10.0).offset_curves(1.0, 2.0, 12.0)[0].coords[:]
        [(2.0, 1.0), (5.0, 1.0), (10.0, 1.0)]
        """
        d = check_range("distance_mm", distance_mm, low=0.0, low_inclusive=True)
        a = min(max(float(start_mm), 0.0), self.length_mm)
        b = min(max(float(self.length_mm if end_mm is None else end_mm), a), self.length_mm)
        s = np.empty(2 * len(self._s) - 1)  # vertices and midpoints, interleaved (sorted: _s increases)
        s[0::2], s[1::2] = self._s, 0.5 * (self._s[1:] + self._s[:-1])
        s = np.concatenate([[a], s[1:-1][(s[1:-1] > a) & (s[1:-1] < b)], [b]])
        return (shapely.LineString(self.offset_point_at(s, d)), shapely.LineString(self.offset_point_at(s, -d)))

    def project(self, xy_mm) -> tuple[np.ndarray, np.ndarray]:
        """Arc-length coordinate and signed offset (left > 0) of points [mm].

        The exact inverse of :meth:`offset_point_at` near the path: starts at the closest
        point of the polyline (shapely STRtree over its segments) and solves ``(p - c(s)) . t(s) = 0`` by Newton steps.

        Parameters
        ----------
        xy_mm : array-like, shape (n, 2) or (2,)
            Points [mm].

        Returns
        -------
        (ndarray, ndarray)
            Arc length ``s`` [mm] and signed offset [mm] of each point.

        Examples
        --------
        >>> s, off = Centerline.straight(10.0).project([(4.0, -3.5)])
        >>> s.tolist(), off.tolist()
        ([4.0], [-3.5])
        """
        p = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
        s = self._closest_s(p)
        kappa = self.segment_curvature()
        for _ in range(_PROJECT_STEPS):
            i = np.clip(np.searchsorted(self._s, s, side="right") - 1, 0, len(kappa) - 1)
            point, tangent, normal = self._frame_at(s)
            r = p - point
            f = np.einsum("ij,ij->i", r, tangent)
            df = -1.0 + kappa[i] * np.einsum("ij,ij->i", r, normal)
            moved = np.clip(s - f / np.where(np.abs(df) > 0.5, df, -1.0), 0.0, self.length_mm)
            if np.array_equal(moved, s):  # a fixed point (a straight path's is the first): no step moves it again
                break
            s = moved
        point, _, normal = self._frame_at(s)
        off = np.einsum("ij,ij->i", p - point, normal)
        return s, off

    def _frame_at(self, s_mm) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(:meth:`point_at`, :meth:`tangent_at`, :meth:`normal_at`) at ``s_mm``, the arc length clipped and the
        tangent angle looked up once for the three."""
        x, y, th = self._xy_angle_at(s_mm)
        c, sn = np.cos(th), np.sin(th)
        return np.stack([x, y], axis=-1), np.stack([c, sn], axis=-1), np.stack([-sn, c], axis=-1)

    def segment_index(self) -> SegmentIndex:
        """The path's :class:`~embroact.patterns.spatial.SegmentIndex` (nearest segments, points within a
        distance), made on first use and kept.

        Returns
        -------
        SegmentIndex
            The same object on every call.

        Examples
        --------
        >>> Centerline.straight(10.0).segment_index().within(np.array([(4.0, 1.0), (4.0, 3.0)]), 2.0).tolist()
        [0]
        """
        index = self._index
        if index is None:
            index = SegmentIndex(self.points_mm)
            object.__setattr__(self, "_index", index)
        return index

    def _closest_s(self, p: np.ndarray) -> np.ndarray:
        """Arc length of the closest polyline point to each of ``p`` (by :meth:`segment_index`)."""
        a, b = self.points_mm[:-1], self.points_mm[1:]
        seg = self.segment_index().nearest(p)
        d = b[seg] - a[seg]
        u = np.einsum("ij,ij->i", p - a[seg], d) / np.einsum("ij,ij->i", d, d)
        return self._s[seg] + np.clip(u, 0.0, 1.0) * np.diff(self._s)[seg]

    def transformed(self, *, origin_mm=(0.0, 0.0), rotation_deg: float = 0.0) -> "Centerline":
        """This path rotated by ``rotation_deg`` about (0, 0), then moved by ``origin_mm``.

        Parameters
        ----------
        origin_mm : (float, float)
            Translation [mm], applied after the rotation.
        rotation_deg : float
            Rotation [deg, counter-clockwise], in (-3600, 3600).

        Returns
        -------
        Centerline

        Examples
        --------
        >>> Centerline.straight(10.0).transformed(origin_mm=(1.0, 2.0), rotation_deg=180.0).points_mm.round(9).tolist()
        [[1.0, 2.0], [-9.0, 2.0]]
        """
        ox, oy = _xy("origin_mm", origin_mm)
        a = math.radians(check_range("rotation_deg", rotation_deg, low=-3600.0, high=3600.0))
        rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        return Centerline(self.points_mm @ rot.T + np.array([ox, oy]))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Centerline):
            return NotImplemented
        return np.array_equal(self.points_mm, other.points_mm)

    def __hash__(self) -> int:
        return hash(self.points_mm.tobytes())

    def __repr__(self) -> str:
        return f"Centerline(n_points={len(self.points_mm)}, length_mm={self.length_mm:.6g})"


def as_centerline(obj) -> Centerline:
    """A :class:`Centerline` from a Centerline, shapely LineString, (n, 2) points or SVG ``d`` string.

    Parameters
    ----------
    obj : Centerline, shapely.LineString, array_like (n, 2) or str
        The path [mm]; a string is SVG path data.

    Returns
    -------
    Centerline
        ``obj`` itself if it is one.

    Raises
    ------
    PathError
        A shapely geometry that is no LineString, or points that make no path.

    Examples
    --------
    >>> as_centerline("M 0,0 L 30,40").length_mm
    50.0
    >>> as_centerline([[0, 0], [3, 4]]).length_mm
    5.0
    """
    if isinstance(obj, Centerline):
        return obj
    if isinstance(obj, str):
        return Centerline.from_svg_path(obj)
    if isinstance(obj, shapely.LineString):
        return Centerline(np.asarray(obj.coords)[:, :2])
    if isinstance(obj, shapely.Geometry):
        raise PathError(f"path must be a LineString, got a {obj.geom_type}")
    return Centerline(obj)


# ---------------------------------------------------------------------- validation
def _xy(name: str, value) -> tuple[float, float]:
    try:
        a, b = value
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a pair [x, y] of numbers in mm, got {value!r}") from None
    return check_range(f"{name}[0]", a, low=-1e6, high=1e6), check_range(f"{name}[1]", b, low=-1e6, high=1e6)


def _clean_points(points) -> np.ndarray:
    try:
        pts = np.array(points, dtype=np.float64)
    except (TypeError, ValueError):
        raise PathError(f"path points must be numbers [[x, y], ...] in mm, got {points!r:.60}") from None
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise PathError(f"path points must have shape (n, 2), got {pts.shape}")
    if len(pts) > PATH_POINTS:
        raise PathError(f"path must have at most {PATH_POINTS} points, got {len(pts)}")
    if not np.all(np.isfinite(pts)):
        raise PathError("path points must be finite numbers, got NaN or inf")
    if len(pts):
        check_coordinates("path", float(np.abs(pts).max()))
    if len(pts) >= 2:
        step = np.hypot(*np.diff(pts, axis=0).T)
        pts = pts[np.concatenate([[True], step > DEFAULT_TOLERANCES.length_mm])]
    if len(pts) < 2:
        raise PathError(f"path needs at least 2 distinct points, got {len(pts)}")
    if np.hypot(*(pts[-1] - pts[0])) <= DEFAULT_TOLERANCES.length_mm:
        raise PathError("path must be open (a tube has two ends), got a closed path")
    if not shapely.LineString(pts).is_simple:
        _, where = self_crossings(pts)
        x, y = pts[0] if where is None else where
        raise PathError(f"path crosses or touches itself near ({x:.2f}, {y:.2f}) mm; give a path that does not")
    return pts
