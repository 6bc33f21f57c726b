"""3D shape of a bent actuator: fabric strip, tube and rail footprints swept along the bent path.

Kinematics
----------
A frame ``(T, N, B)`` moves along the fabric-side centerline, arc length ``s`` in
[0, l0]: ``T`` the tangent, ``N = B x T`` the in-fabric normal (left of the path in
the plan), ``B`` the fabric normal toward the thread side (plan +z).  It turns with
the body-frame angular velocity ``omega = (0, kappa_b, kappa_p)``:

- ``kappa_p(s)``: the path's own in-plane curvature (positive: turning left);
  a curved-path design keeps bending along its own path;
- ``kappa_b = theta / l0``: the model's bending curvature, uniform along one segment
  (a segmented actuator has one per segment); with ``omega = kappa_b N`` the tangent
  obeys ``dT/ds = -kappa_b B``: positive ``theta`` bends toward the back of the fabric
  (docs/model.md sign convention).

The path is stored as pieces of constant ``kappa_p`` (:class:`PlanarPath`), so on a
piece (cut also where the bending segments meet) ``omega`` is constant and the motion is
a rotation about a fixed axis (``omega`` is perpendicular to ``T``: no pitch).  The frame
and the position then have closed forms (Rodrigues), integrated exactly piece by piece
in :mod:`embroact.predict.shape`, the one bent-shape kinematics (the side view uses it
too).  A straight path bends in a plane and the angle between its end tangents is
``|theta|`` exactly.

Resolution ("model no more than a scene needs")
-----------------------------------------------
Each body is a closed profile (rectangle or circle, in the ``(N, B)`` plane) swept
along the path.  Half the chordal tolerance goes along the path: a profile point at
distance ``rho`` from the rotation axis moves on a circle, and a step of rotation
``dphi`` has sagitta ``rho (1 - cos(dphi/2))``, kept below ``tol/2``; a straight,
unbent piece needs one step.  The other half goes round the tube:
``r0 (1 - cos(pi/n)) <= tol/2``.  The realised deviation is then *measured*: the exact
surface is sampled on a grid inside every mesh cell and its distance to that cell's
two triangles taken.

::

        tube (radius r0, axis at v = r0)
          .-.
         (   )
    ______'-'______     <- rail footprints at u = +-w/2 (thread side, v = 0 .. 0.2)
    |_______________|   <- fabric strip, v = -t .. 0 (t = FABRIC_THICKNESS_MM)

Examples
--------
>>> from embroact.export.pictures.mesh import PlanarPath, actuator_mesh
>>> m = actuator_mesh(PlanarPath.straight(100.0), 0.0, width_mm=7.0, r0_mm=2.58)
>>> m.triangle_count, m.max_deviation_mm <= 0.05
(124, True)
>>> bent = actuator_mesh(PlanarPath.straight(100.0), 90.0, width_mm=7.0, r0_mm=2.58)
>>> bent.triangle_count > m.triangle_count
True
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ...patterns.base.arrays import frozen_array
from ...patterns.base.errors import ExportError, ParameterError, check_range
from ...predict.shape import BentShape
from ..files.atomic import write_bytes_atomic
from .glb import GlbMesh, glb_bytes
from ...patterns.params import FABRIC_THICKNESS_MM
from .triangles import point_triangle_distance

__all__ = [
    "DEFAULT_CHORD_TOLERANCE_MM",
    "MESH_FORMATS",
    "PlanarPath",
    "BentPath",
    "Body",
    "ShapeMesh",
    "actuator_mesh",
    "shapes_of",
    "MovedMeshes",
    "remeshed_all",
    "mesh_bytes",
    "write_mesh",
]

#: Default maximum distance between the mesh and the exact bent surface [mm].
DEFAULT_CHORD_TOLERANCE_MM = 0.05
#: Fabric beyond the rails on each side, when no strip width is given [mm].
FABRIC_MARGIN_MM = 5.0
#: Width and height of the thread footprint band along each rail [mm].
RAIL_BAND_WIDTH_MM = 0.6
RAIL_BAND_HEIGHT_MM = 0.2
#: Relative difference below which neighbouring path pieces are merged into one arc.
KAPPA_MERGE_REL = 1e-3
#: Suffix -> writer kind.  GLB is written in metres, Y up (glTF convention); the others in mm, plan frame.
MESH_FORMATS = {".glb": "glb", ".stl": "stl", ".obj": "obj", ".ply": "ply"}

#: Where the deviation is sampled in a cell, along and across (fractions): its edges' midpoints and its centre,
#: where a chord is farthest from its arc (the quarter points as well found the same maxima at 4x the cost).
_SAMPLE_FRACTIONS = (0.0, 0.5)
_MAX_MEASURED_STEPS = 2048  # steps along the path whose cells the deviation is measured on
_M_PER_MM = 1e-3
_MIN_TUBE_SEGMENTS = 8
#: Most triangles one actuator's mesh may have: building, measuring and writing it then stays
#: within about 300 MB (the deviation measure costs ~4 KB per triangle). A smaller
#: ``tolerance_mm`` is refused before anything is allocated, naming the smallest that fits.
MESH_MAX_TRIANGLES = 60_000
#: Curvature below which a piece is straight [1/mm] (radius 1e100 mm; its square stays a normal double).
_STRAIGHT_KAPPA_PER_MM = 1e-100
_COLOURS = {"fabric": (225, 214, 190, 255), "tube": (70, 130, 200, 255), "rails": (200, 60, 60, 255)}


@dataclass(frozen=True, slots=True, eq=False)
class PlanarPath:
    """A plan-frame path made of pieces of constant curvature.

    Attributes
    ----------
    start_mm : tuple of float
        Start point (x, y) [mm].
    heading_deg : float
        Start direction, counter-clockwise from +x [deg].
    lengths_mm : ndarray
        Piece lengths [mm], > 0.
    kappa_per_mm : ndarray
        Piece curvatures [1/mm], positive turning left.

    Examples
    --------
    >>> p = PlanarPath.straight(100.0)
    >>> p.length_mm, p.lengths_mm.tolist(), p.kappa_per_mm.tolist()
    (100.0, [100.0], [0.0])
    """

    start_mm: tuple[float, float]
    heading_deg: float
    lengths_mm: np.ndarray
    kappa_per_mm: np.ndarray

    def __post_init__(self) -> None:
        lengths, kappa = frozen_array(self.lengths_mm).reshape(-1), frozen_array(self.kappa_per_mm).reshape(-1)
        if len(lengths) == 0 or len(lengths) != len(kappa) or not np.all(lengths > 0):
            raise ParameterError("lengths_mm must be positive, one per curvature, at least one piece")
        object.__setattr__(self, "lengths_mm", lengths)
        object.__setattr__(self, "kappa_per_mm", kappa)

    @property
    def length_mm(self) -> float:
        """Total length [mm]."""
        return float(self.lengths_mm.sum())

    @classmethod
    def straight(cls, length_mm: float) -> "PlanarPath":
        """A straight path along +x from the origin.

        Parameters
        ----------
        length_mm : float
            Its length [mm], > 0.

        Returns
        -------
        PlanarPath

        Examples
        --------
        >>> PlanarPath.straight(60.0).start_mm, PlanarPath.straight(60.0).heading_deg
        ((0.0, 0.0), 0.0)
        """
        return cls((0.0, 0.0), 0.0, np.array([check_range("length_mm", length_mm, low=0.0)]), np.zeros(1))

    @classmethod
    def from_centerline(cls, centerline) -> "PlanarPath":
        """The path of a :class:`~embroact.patterns.centerline.Centerline`, in its smooth-tangent model.

        The centerline's tangent angle varies linearly between its vertices, so each
        segment is a piece of constant curvature; neighbouring pieces whose curvatures
        differ by less than ``KAPPA_MERGE_REL`` are merged (total length and turning kept
        exactly), so a finely flattened arc becomes one piece.

        Parameters
        ----------
        centerline : Centerline
            The tube path.

        Returns
        -------
        PlanarPath

        Examples
        --------
        >>> from embroact.patterns.centerline import Centerline
        >>> p = PlanarPath.from_centerline(Centerline.from_svg_path("M 0,0 A 50,50 0 0,0 50,50"))
        >>> round(p.length_mm, 2), round(float(p.kappa_per_mm.max()), 4)  # a quarter circle of radius 50
        (78.54, 0.02)
        """
        p = np.asarray(centerline.points_mm, dtype=np.float64)
        seg = np.hypot(*np.diff(p, axis=0).T)
        s_mid = np.concatenate([[0.0], np.cumsum(seg)])[:-1] + seg / 2.0
        turn = np.asarray(centerline.curvature_at(s_mid), dtype=np.float64) * seg
        merged: list[list[float]] = []  # [length, turning]
        for length, t in zip(seg.tolist(), turn.tolist()):
            if merged:
                k, mk = t / length, merged[-1][1] / merged[-1][0]
                if abs(k - mk) <= KAPPA_MERGE_REL * max(abs(k), abs(mk)):
                    merged[-1][0] += length
                    merged[-1][1] += t
                    continue
            merged.append([length, t])
        arr = np.array(merged)
        tx, ty = np.asarray(centerline.tangent_at(0.0), dtype=np.float64)
        return cls((float(p[0, 0]), float(p[0, 1])), math.degrees(math.atan2(ty, tx)), arr[:, 0], arr[:, 1] / arr[:, 0])


@dataclass(frozen=True, slots=True, eq=False)
class BentPath:
    """The bent centerline: exact frames at any arc length, from :class:`embroact.predict.shape.BentShape`.

    Attributes
    ----------
    path : PlanarPath
        The path in the plan.
    shape : BentShape
        The chain of arcs (the one bent-shape kinematics, shared with the side view).
    segment_lengths_mm, segment_theta_deg : tuple of float
        The bending segments along the path and each one's bend [mm, deg] (one segment: uniform).

    Examples
    --------
    >>> bent = BentPath.from_theta(PlanarPath.straight(100.0), 90.0)
    >>> bent.segment_lengths_mm, bent.segment_theta_deg, bent.frames([100.0])[0].round(3).tolist()
    ((100.0,), (90.0,), [[63.662, 0.0, -63.662]])
    """

    path: PlanarPath
    shape: BentShape
    segment_lengths_mm: tuple[float, ...]
    segment_theta_deg: tuple[float, ...]

    @classmethod
    def from_theta(cls, path: PlanarPath, theta_deg: float) -> "BentPath":
        """Bend ``path`` uniformly by ``theta_deg`` over its length.

        Parameters
        ----------
        path : PlanarPath
            The path.
        theta_deg : float
            The bend [deg].

        Returns
        -------
        BentPath

        Examples
        --------
        >>> bent = BentPath.from_theta(PlanarPath.straight(100.0), 90.0)
        >>> list(bent.pieces())[0][2]  # curvature pi/2 over 100 mm
        0.015707963267948967
        """
        return cls.from_segments(path, [path.length_mm], [check_range("theta_deg", theta_deg)])

    @classmethod
    def from_segments(cls, path: PlanarPath, segment_lengths_mm, segment_theta_deg) -> "BentPath":
        """Bend consecutive segments of ``path`` (lengths adding up to the path's) each by its own angle.

        Parameters
        ----------
        path : PlanarPath
            The path.
        segment_lengths_mm : sequence of float
            The segments' lengths [mm], adding up to the path's.
        segment_theta_deg : sequence of float
            Each one's bend [deg].

        Returns
        -------
        BentPath

        Examples
        --------
        >>> s = BentPath.from_segments(PlanarPath.straight(100.0), [50.0, 50.0], [90.0, -90.0])  # an S
        >>> (s.frames([100.0])[1][0][:, 0].round(6) + 0.0).tolist()  # the tip points along +x again
        [1.0, 0.0, 0.0]
        """
        lengths = tuple(float(v) for v in segment_lengths_mm)
        theta = tuple(float(v) for v in segment_theta_deg)
        shape = BentShape.chain(lengths, theta, path_lengths_mm=path.lengths_mm, path_kappa_per_mm=path.kappa_per_mm,
                                start_mm=path.start_mm, heading_deg=path.heading_deg)
        return cls(path, shape, lengths, theta)

    def frames(self, s_mm) -> tuple[np.ndarray, np.ndarray]:
        """Positions (n, 3) and frames (n, 3, 3), columns T, N, B, at arc lengths ``s_mm``.

        Parameters
        ----------
        s_mm : array_like (n,)
            Arc lengths [mm].

        Returns
        -------
        positions : numpy.ndarray (n, 3)
        frames : numpy.ndarray (n, 3, 3)

        Examples
        --------
        >>> bent = BentPath.from_theta(PlanarPath.straight(100.0), 90.0)
        >>> bent.frames([0.0])[0].tolist()
        [[0.0, 0.0, 0.0]]
        """
        return self.shape.frames(s_mm)

    def moved(self, dx_mm: float, dy_mm: float) -> "BentPath":
        """The same bent path with its start moved by (``dx_mm``, ``dy_mm``) in the plan.

        Parameters
        ----------
        dx_mm, dy_mm : float
            The displacement [mm].

        Returns
        -------
        BentPath

        Examples
        --------
        >>> BentPath.from_theta(PlanarPath.straight(100.0), 90.0).moved(0.0, 2.0).frames([0.0])[0].tolist()
        [[0.0, 2.0, 0.0]]
        """
        x, y = self.path.start_mm
        return BentPath(replace(self.path, start_mm=(x + float(dx_mm), y + float(dy_mm))),
                        self.shape.moved(dx_mm, dy_mm), self.segment_lengths_mm, self.segment_theta_deg)

    def points(self, s_mm, offsets_uv_mm) -> np.ndarray:
        """World points (n, m, 3) of profile offsets (m, 2) = (u along N, v along B) at ``s_mm``.

        Parameters
        ----------
        s_mm : array_like (n,)
            Arc lengths [mm].
        offsets_uv_mm : array_like (m, 2)
            Offsets [mm].

        Returns
        -------
        numpy.ndarray (n, m, 3)

        Examples
        --------
        >>> bent = BentPath.from_theta(PlanarPath.straight(100.0), 90.0)
        >>> bent.points([100.0], [(0.0, 1.0)]).round(3).tolist()
        [[[64.662, 0.0, -63.662]]]
        """
        return self.shape.points(s_mm, offsets_uv_mm)

    def pieces(self):
        """(s_start, length, kappa_b, kappa_p) of each piece of constant bending and path curvature.

        Returns
        -------
        iterator of tuple of float

        Examples
        --------
        >>> bent = BentPath.from_theta(PlanarPath.straight(100.0), 90.0)
        >>> [round(v, 6) for v in next(iter(bent.pieces()))]
        [0.0, 100.0, 0.015708, 0.0]
        """
        return self.shape.pieces()


@dataclass(frozen=True, slots=True, eq=False)
class Body:
    """One closed body of the mesh.

    Attributes
    ----------
    name : str
        ``"fabric"``, ``"tube"``, ``"rail_left"`` or ``"rail_right"``.
    vertices : ndarray (n, 3)
        World positions [mm], plan frame, z toward the thread side; read-only.
    faces : ndarray of int64 (m, 3)
        Triangles, outward normals; read-only.
    ring_size : int
        Vertices per cross-section ring (rings are stored in order along the path;
        vertex ``i`` belongs to ring ``i // ring_size``).
    ring_s_mm : ndarray
        Arc length of each ring along the path [mm]; read-only.
    colour : tuple of int
        RGBA 0-255.

    Examples
    --------
    >>> m = actuator_mesh(PlanarPath.straight(100.0), 90.0, width_mm=7.0, r0_mm=2.58, measure=False, name="A1")
    >>> body = m.bodies[0]
    >>> body.name, body.ring_size, body.vertices.shape[1], len(body.ring_s_mm) * body.ring_size == len(body.vertices)
    ('fabric', 4, 3, True)
    """

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    ring_size: int
    ring_s_mm: np.ndarray
    colour: tuple[int, int, int, int]


@dataclass(frozen=True, slots=True, eq=False)
class ShapeMesh:
    """The bent actuator's bodies and what the mesh achieved.

    Attributes
    ----------
    name : str
        Actuator name (prefixes the body names in exported files).
    bodies : tuple of Body
        Fabric, tube and rails.
    bent : BentPath
        The bent centerline.
    theta_deg : float
        Bend angle the shape was built for [deg].
    tolerance_mm : float
        Requested chordal tolerance [mm].
    max_deviation_mm : float or None
        Realised maximum distance of the exact surface from the mesh (sampled) [mm];
        None when not measured (``actuator_mesh(measure=False)``, pictures).
    section_mm : tuple of float
        Rail spacing w, sleeve radius r0 and strip width the bodies were swept with [mm]
        (what :meth:`remeshed` needs).

    Examples
    --------
    >>> m = actuator_mesh(PlanarPath.straight(100.0), 90.0, width_mm=7.0, r0_mm=2.58, measure=False, name="A1")
    >>> [b.name for b in m.bodies], m.triangle_count, m.max_deviation_mm
    (['fabric', 'tube', 'rail_left', 'rail_right'], 2130, None)
    """

    name: str
    bodies: tuple[Body, ...]
    bent: BentPath
    theta_deg: float
    tolerance_mm: float
    max_deviation_mm: float | None
    section_mm: tuple[float, float, float]

    def remeshed(self, tolerance_mm: float, *, measure: bool = False) -> "ShapeMesh":
        """The same shape meshed at another chordal tolerance (a picture's, say).

        Parameters
        ----------
        tolerance_mm : float
            The chordal tolerance [mm].
        measure : bool, optional
            Measure the realised deviation.

        Returns
        -------
        ShapeMesh

        Examples
        --------
        >>> m = actuator_mesh(PlanarPath.straight(100.0), 90.0, width_mm=7.0, r0_mm=2.58, measure=False, name="A1")
        >>> coarse = m.remeshed(0.5)
        >>> coarse.tolerance_mm, coarse.triangle_count < m.triangle_count
        (0.5, True)
        """
        return actuator_mesh(self.bent.path, self.theta_deg, **self._remesh_options(tolerance_mm, measure))

    def _remesh_options(self, tolerance_mm: float, measure: bool = False) -> dict:
        w, r0, strip = self.section_mm
        return {"width_mm": w, "r0_mm": r0, "strip_width_mm": strip, "tolerance_mm": tolerance_mm, "name": self.name,
                "measure": measure, "coarsen": True, "segment_lengths_mm": self.bent.segment_lengths_mm,
                "segment_theta_deg": self.bent.segment_theta_deg}

    def moved(self, dx_mm: float, dy_mm: float, name: str) -> "ShapeMesh":
        """The same shape moved by (``dx_mm``, ``dy_mm``) in the plan, called ``name`` (an identical actuator's).

        Parameters
        ----------
        dx_mm, dy_mm : float
            The displacement [mm].
        name : str
            The moved shape's name.

        Returns
        -------
        ShapeMesh

        Examples
        --------
        >>> m = actuator_mesh(PlanarPath.straight(100.0), 90.0, width_mm=7.0, r0_mm=2.58, measure=False, name="A1")
        >>> b = m.moved(0.0, 25.0, "A2")
        >>> b.name, b.triangle_count == m.triangle_count, (b.bodies[1].vertices - m.bodies[1].vertices).max(axis=0).tolist()
        ('A2', True, [0.0, 25.0, 0.0])
        """
        d = np.array([float(dx_mm), float(dy_mm), 0.0])
        return replace(self, name=name, bent=self.bent.moved(dx_mm, dy_mm),
                       bodies=tuple(replace(b, vertices=frozen_array(b.vertices + d)) for b in self.bodies))

    @property
    def triangle_count(self) -> int:
        """Triangles over all bodies."""
        return int(sum(len(b.faces) for b in self.bodies))

    def stats(self) -> dict:
        """Plain dict for reports.

        Returns
        -------
        dict
            Triangle count, tolerance, deviation, bend and triangles per body.

        Examples
        --------
        >>> m = actuator_mesh(PlanarPath.straight(100.0), 90.0, width_mm=7.0, r0_mm=2.58, measure=False, name="A1")
        >>> m.stats()["bodies"]
        {'fabric': 236, 'tube': 1422, 'rail_left': 236, 'rail_right': 236}
        """
        return {"triangle_count": self.triangle_count, "tolerance_mm": self.tolerance_mm,
                "max_deviation_mm": self.max_deviation_mm, "theta_deg": self.theta_deg,
                "bodies": {b.name: len(b.faces) for b in self.bodies}}


@dataclass(frozen=True, slots=True)
class _Profile:
    """A closed convex cross-section: polygon vertices in (u, v) and how to sample its exact outline."""

    name: str
    uv: np.ndarray
    centre: tuple[float, float] | None = None  # a circle's centre (None: straight-edged polygon)
    radius: float = 0.0

    def outline(self, j: np.ndarray, g: np.ndarray) -> np.ndarray:
        """Exact outline points between vertex j and j + 1 at fractions g."""
        n = len(self.uv)
        if self.centre is None:
            a, b = self.uv[j % n], self.uv[(j + 1) % n]
            return a + g[:, None] * (b - a)
        ang = 2.0 * np.pi * (j + g) / n
        return np.column_stack([self.centre[0] + self.radius * np.cos(ang), self.centre[1] + self.radius * np.sin(ang)])

    def reach(self, axis_point: np.ndarray, axis_dir: np.ndarray) -> float:
        """Largest distance of the exact outline from an axis lying in the (u, v) plane."""
        normal = np.array([-axis_dir[1], axis_dir[0]])
        if self.centre is None:
            return float(np.abs((self.uv - axis_point) @ normal).max())
        return float(abs((np.asarray(self.centre) - axis_point) @ normal) + self.radius)


def _rect(name: str, u0: float, u1: float, v0: float, v1: float) -> _Profile:
    return _Profile(name, np.array([[u0, v0], [u1, v0], [u1, v1], [u0, v1]]))


def _half_chord_angle(tol: float, radius: float) -> float:
    """Half the angle of a chord whose sagitta on a circle of ``radius`` is ``tol``:
    ``acos(1 - tol / radius)``, written as ``2 asin(sqrt(x / 2))`` so that it stays accurate
    (and non-zero) when ``tol / radius`` is far below the float epsilon (a nearly straight
    piece of an S-curve, a subnormal tolerance)."""
    return 2.0 * math.asin(math.sqrt(min(tol / radius, 2.0) / 2.0))


def _circle(name: str, centre: tuple[float, float], radius: float, tol: float) -> _Profile:
    n = max(_MIN_TUBE_SEGMENTS, math.ceil(math.pi / _half_chord_angle(tol, radius)))
    ang = 2.0 * np.pi * np.arange(n) / n
    return _Profile(name, np.column_stack([centre[0] + radius * np.cos(ang), centre[1] + radius * np.sin(ang)]),
                    centre, radius)


def _triangle_bound(bent: BentPath, r0: float, extent: float, tol: float) -> float:
    """Upper bound on the tube body's triangles at ``tol``, from the pieces alone (no allocation).

    Segments round the tube as :func:`_circle` makes them; rings as :func:`_stations` makes
    them, with every piece's reach taken as its bend radius plus ``extent`` (the profile's
    largest distance from the path), which only shortens the allowed step.
    """
    half = tol / 2.0
    a = _half_chord_angle(half, r0)
    if a == 0.0:
        return math.inf
    rings = 1.0
    for _, length, kb, kp in bent.pieces():
        k = math.hypot(kb, kp)
        rings += 1.0
        if k >= _STRAIGHT_KAPPA_PER_MM:  # as _stations
            d = 2.0 * _half_chord_angle(half, 1.0 / k + extent)
            rings += math.inf if d == 0.0 else k * length / d
    return 2.0 * rings * max(_MIN_TUBE_SEGMENTS, math.pi / a + 1.0)


def _fitting_tolerance(bent: BentPath, r0: float, extent: float, tol: float) -> float:
    """The smallest tolerance from ``tol`` up (in 1.25x steps, at most 10 mm) whose mesh fits :data:`MESH_MAX_TRIANGLES`."""
    fit = tol  # the count goes as 1/tol (rings and segments each as 1/sqrt(tol))
    while _triangle_bound(bent, r0, extent, fit) > MESH_MAX_TRIANGLES and fit < 10.0:
        fit = min(10.0, fit * 1.25 * min(_triangle_bound(bent, r0, extent, fit) / MESH_MAX_TRIANGLES, 1e12))
    return fit


def _check_triangles(bent: BentPath, r0: float, extent: float, tol: float, name: str, *, coarsen: bool) -> float:
    """The tolerance to mesh at: ``tol``, or with ``coarsen`` the smallest that fits :data:`MESH_MAX_TRIANGLES`;
    without ``coarsen`` a tolerance whose mesh would exceed the limit is refused (one line)."""
    n = _triangle_bound(bent, r0, extent, tol)
    if n <= MESH_MAX_TRIANGLES:
        return tol
    fit = _fitting_tolerance(bent, r0, extent, tol)
    if coarsen:
        return fit
    about = "more than 1e308" if math.isinf(n) else f"about {n:.3g}"
    raise ParameterError(f"tolerance_mm={tol:g} would make {about} triangles for {name!r}, more than "
                         f"the limit {MESH_MAX_TRIANGLES:,}; use tolerance_mm >= {fit:.2g}")


def _stations(bent: BentPath, prof: _Profile, tol: float) -> np.ndarray:
    """Arc lengths of the rings: steps whose sagitta stays within tol.

    Each piece uses up ``k length / dphi`` of a step (its rotation over the rotation
    whose sagitta is ``tol``). Consecutive pieces share one step while their budgets
    add up to at most 1 (their rotations add, so the step's deviation stays within
    ``tol``), so the ring count follows the turning, not the number of pieces; a piece
    that needs more gets ``ceil(budget)`` even steps of its own, and a straight piece one.
    """
    out = [0.0]
    used = 0.0  # budget since the last ring
    for s0, length, kb, kp in bent.pieces():
        k = math.hypot(kb, kp)
        if k < _STRAIGHT_KAPPA_PER_MM:  # straight (k**2 below would underflow: a 1e-300 kPa bend)
            if used > 0:
                out.append(s0)
            out.append(s0 + length)
            used = 0.0
            continue
        # rotation axis in the (u, v) plane: through (kp, -kb)/k^2, direction (kb, kp)/k
        rho = prof.reach(np.array([kp, -kb]) / k**2, np.array([kb, kp]) / k)
        dphi = 2.0 * _half_chord_angle(tol, rho) if rho > 0 else math.pi
        need = k * length / dphi
        if used + need <= 1.0:
            used += need
            continue
        if used > 0:  # close the shared step at this piece's start
            out.append(s0)
        steps = math.ceil(need)
        out += (s0 + length * np.arange(1, steps + 1) / steps).tolist()
        used = 0.0
    if used > 0:
        out.append(bent.path.length_mm)
    return np.array(out)


def _sweep(bent: BentPath, prof: _Profile, s: np.ndarray, colour) -> Body:
    ring = bent.points(s, prof.uv)  # (rings, m, 3)
    rings, m = ring.shape[:2]
    verts = ring.reshape(-1, 3)
    i, j = np.meshgrid(np.arange(rings - 1), np.arange(m), indexing="ij")
    a, b = i * m + j, i * m + (j + 1) % m
    c, d = b + m, a + m
    sides = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    fan = np.arange(1, m - 1)
    start = np.column_stack([np.zeros_like(fan), fan + 1, fan])
    end = np.column_stack([np.zeros_like(fan), fan, fan + 1]) + (rings - 1) * m
    faces = np.concatenate([start, sides, end]).astype(np.int64)
    return Body(prof.name, frozen_array(verts), frozen_array(faces).astype(np.int64), m, frozen_array(s), colour)


def _deviation(bent: BentPath, prof: _Profile, s: np.ndarray, body: Body) -> float:
    """Max distance of exact-surface samples inside each side cell from that cell's two triangles.

    Every cell of up to ``_MAX_MEASURED_STEPS`` steps along the path; a longer body is
    measured on that many steps spread evenly along it, always including the first and
    the last (the steps of a piece are alike: the measurement stays representative and
    its cost bounded, where measuring all of a 10 m path took 19 s).
    """
    m, f = body.ring_size, np.array(_SAMPLE_FRACTIONS)
    # strictly increasing (spaced at least 1 apart before rounding): no duplicates to remove
    steps = np.linspace(0, len(s) - 2, min(len(s) - 1, _MAX_MEASURED_STEPS)).round().astype(np.int64)
    n, nf = len(steps), len(f)
    k, j, kf, gs = (x.reshape(-1) for x in np.meshgrid(np.arange(n), np.arange(m), np.arange(nf), f, indexing="ij"))
    i = steps[k]
    # a sample's frame depends only on its step and fraction along the path, not on its place round the ring
    x, r = (a[k * nf + kf] for a in bent.frames(s[steps, None] + f * (s[steps + 1] - s[steps])[:, None]))
    uv = prof.outline(j, gs)
    pts = x + uv[:, :1] * r[:, :, 1] + uv[:, 1:] * r[:, :, 2]
    v = body.vertices
    a, b = i * m + j, i * m + (j + 1) % m
    c, d = b + m, a + m
    best = np.full(len(pts), np.inf)
    for tri in ((a, b, c), (a, c, d)):
        tris = v[np.stack(tri, axis=1)]
        best = np.minimum(best, point_triangle_distance(tris, pts))
    return float(best.max())


def actuator_mesh(
    path: PlanarPath,
    theta_deg: float,
    *,
    width_mm: float,
    r0_mm: float,
    strip_width_mm: float | None = None,
    tolerance_mm: float = DEFAULT_CHORD_TOLERANCE_MM,
    name: str = "actuator",
    measure: bool = True,
    segment_lengths_mm=(),
    segment_theta_deg=(),
    coarsen: bool = False,
) -> ShapeMesh:
    """Mesh of the actuator bent by ``theta_deg``, with its realised deviation measured.

    Parameters
    ----------
    path : PlanarPath
        Fabric-side centerline in the plan, length l0.
    theta_deg : float
        Predicted bend angle [deg].
    width_mm : float
        Rail spacing w [mm] (where the footprints lie), > 0.
    r0_mm : float
        Sleeve radius r0 [mm]: tube radius in the deformation phase, > 0.
    strip_width_mm : float, optional
        Fabric strip width [mm]; default ``width_mm + 2 * FABRIC_MARGIN_MM``.
    tolerance_mm : float
        Chordal tolerance [mm], in (0, 10].
    name : str
        Actuator name.
    measure : bool
        Measure the realised deviation (``max_deviation_mm``). Pictures,
        whose tolerance is a fraction of a pixel, skip it.
    segment_lengths_mm, segment_theta_deg : sequence of float, optional
        A segmented actuator: each segment's length along the path [mm] and its own bend
        [deg] (``theta_deg`` is then their sum); default one segment bent uniformly.
    coarsen : bool
        When the mesh at ``tolerance_mm`` would exceed :data:`MESH_MAX_TRIANGLES` (a long path at the
        default tolerance), mesh at the smallest tolerance that fits instead of refusing; the result's
        ``tolerance_mm`` says which was used. For the default tolerance; a tolerance the user asked for
        is refused instead (``coarsen=False``).

    Returns
    -------
    ShapeMesh
        Closed bodies ``fabric``, ``tube``, ``rail_left``, ``rail_right``.

    Examples
    --------
    >>> m = actuator_mesh(PlanarPath.straight(100.0), 90.0, width_mm=7.0, r0_mm=2.58)
    >>> m.max_deviation_mm <= m.tolerance_mm
    True
    """
    w = check_range("width_mm", width_mm, low=0.0)
    r0 = check_range("r0_mm", r0_mm, low=0.0)
    tol = check_range("tolerance_mm", tolerance_mm, low=0.0, high=10.0, high_inclusive=True)
    strip = check_range("strip_width_mm", strip_width_mm if strip_width_mm is not None else w + 2 * FABRIC_MARGIN_MM,
                        low=w + RAIL_BAND_WIDTH_MM)
    half = strip / 2.0
    bent = (BentPath.from_segments(path, segment_lengths_mm, segment_theta_deg) if len(segment_lengths_mm)
            else BentPath.from_theta(path, theta_deg))
    tol = _check_triangles(bent, r0, max(half, 2.0 * r0), tol, name, coarsen=coarsen)
    rb = RAIL_BAND_WIDTH_MM / 2.0
    profiles = [
        (_rect("fabric", -half, half, -FABRIC_THICKNESS_MM, 0.0), "fabric"),
        (_circle("tube", (0.0, r0), r0, tol / 2.0), "tube"),
        (_rect("rail_left", w / 2 - rb, w / 2 + rb, 0.0, RAIL_BAND_HEIGHT_MM), "rails"),
        (_rect("rail_right", -w / 2 - rb, -w / 2 + rb, 0.0, RAIL_BAND_HEIGHT_MM), "rails"),
    ]
    bodies, dev = [], 0.0
    for prof, colour in profiles:
        s = _stations(bent, prof, tol / 2.0)
        body = _sweep(bent, prof, s, _COLOURS[colour])
        if measure:
            dev = max(dev, _deviation(bent, prof, s, body))
        bodies.append(body)
    return ShapeMesh(name, tuple(bodies), bent, float(theta_deg), tol, dev if measure else None, (w, r0, strip))


class MovedMeshes:
    """:func:`actuator_mesh`, made once for paths that differ only in their start (identical actuators side by
    side): a later call's mesh is the first one's moved (:meth:`ShapeMesh.moved`).

    Examples
    --------
    >>> meshes = MovedMeshes()
    >>> a = meshes.mesh(PlanarPath.straight(50.0), 40.0, width_mm=7.0, r0_mm=2.58, name="A1", measure=False)
    >>> b = meshes.mesh(replace(PlanarPath.straight(50.0), start_mm=(0.0, 30.0)), 40.0, width_mm=7.0, r0_mm=2.58,
    ...                 name="A2", measure=False)
    >>> b.name, meshes.made, float(b.bodies[0].vertices[:, 1].min() - a.bodies[0].vertices[:, 1].min())
    ('A2', 1, 30.0)
    """

    def __init__(self) -> None:
        self._first: dict[tuple, tuple[tuple[float, float], ShapeMesh]] = {}

    @property
    def made(self) -> int:
        """How many meshes were made (not moved)."""
        return len(self._first)

    def mesh(self, path: PlanarPath, theta_deg: float, *, name: str = "actuator", **options) -> ShapeMesh:
        """:func:`actuator_mesh` of these arguments (an earlier one's mesh moved when only the start differs).

        Parameters
        ----------
        path : PlanarPath
            The path.
        theta_deg : float
            The bend [deg].
        name : str
            The shape's name.
        **options
            Further keywords of :func:`actuator_mesh`.

        Returns
        -------
        ShapeMesh

        Examples
        --------
        >>> MovedMeshes().mesh(PlanarPath.straight(50.0), 40.0, width_mm=7.0, r0_mm=2.58, name="A1").name
        'A1'
        """
        key = (float(path.heading_deg), path.lengths_mm.tobytes(), path.kappa_per_mm.tobytes(), float(theta_deg),
               tuple((k, tuple(np.asarray(v, dtype=np.float64).reshape(-1).tolist()) if isinstance(
                   v, (tuple, list, np.ndarray)) else v) for k, v in sorted(options.items())))
        first = self._first.get(key)
        if first is None:
            made = actuator_mesh(path, theta_deg, name=name, **options)
            self._first[key] = (path.start_mm, made)
            return made
        (x0, y0), made = first
        return made.moved(path.start_mm[0] - x0, path.start_mm[1] - y0, name)


def remeshed_all(shapes, tolerance_mm: float) -> tuple[ShapeMesh, ...]:
    """Every shape meshed again at ``tolerance_mm`` (:meth:`ShapeMesh.remeshed`), each distinct one once
    (:class:`MovedMeshes`).

    Parameters
    ----------
    shapes : sequence of ShapeMesh
        The shapes.
    tolerance_mm : float
        The chordal tolerance [mm].

    Returns
    -------
    tuple of ShapeMesh

    Examples
    --------
    >>> m = actuator_mesh(PlanarPath.straight(100.0), 90.0, width_mm=7.0, r0_mm=2.58, measure=False, name="A1")
    >>> [s.name for s in remeshed_all([m, m.moved(0.0, 20.0, "A2")], 0.5)]
    ['A1', 'A2']
    """
    meshes = MovedMeshes()
    return tuple(meshes.mesh(s.bent.path, s.theta_deg, **s._remesh_options(tolerance_mm)) for s in shapes)


def shapes_of(shapes) -> tuple[ShapeMesh, ...]:
    """One ShapeMesh or a sequence of them, as a non-empty tuple.

    Parameters
    ----------
    shapes : ShapeMesh or sequence of ShapeMesh
        The shapes.

    Returns
    -------
    tuple of ShapeMesh

    Raises
    ------
    ParameterError
        An empty sequence, or anything else.

    Examples
    --------
    >>> m = actuator_mesh(PlanarPath.straight(100.0), 90.0, width_mm=7.0, r0_mm=2.58, measure=False, name="A1")
    >>> shapes_of(m) == (m,), shapes_of([m, m]) == (m, m)
    (True, True)
    """
    out = (shapes,) if isinstance(shapes, ShapeMesh) else tuple(shapes)
    if not out or not all(isinstance(s, ShapeMesh) for s in out):
        raise ParameterError("shapes must be a ShapeMesh or a non-empty sequence of them")
    return out


def _export_bytes(shapes: tuple[ShapeMesh, ...], kind: str) -> bytes:
    if kind == "glb":  # written without trimesh (glb.py): the default build's file
        # glTF: metres, Y up.  Plan frame (x, y, z_thread) -> (x, z_thread, -y) / 1000.
        to_gltf = np.array([[1, 0, 0], [0, 0, 1], [0, -1, 0]], dtype=float) * _M_PER_MM
        return glb_bytes(GlbMesh(f"{shape.name}.{b.name}", np.asarray(b.vertices) @ to_gltf.T, b.faces, b.colour)
                         for shape in shapes for b in shape.bodies)
    import trimesh

    meshes = []
    for shape in shapes:
        for b in shape.bodies:
            mesh = trimesh.Trimesh(vertices=np.array(b.vertices), faces=np.array(b.faces), process=False)
            face_colours = np.tile(np.array(b.colour, dtype=np.uint8), (len(b.faces), 1))
            mesh.visual.face_colors = face_colours  # type: ignore[union-attr]
            meshes.append((f"{shape.name}.{b.name}", mesh))
    joined = trimesh.util.concatenate([m for _, m in meshes])
    data = joined.export(None, file_type=kind)
    return data.encode("utf-8") if isinstance(data, str) else data


def mesh_bytes(shapes, suffix: str) -> bytes:
    """File contents of one shape or several in the format named by ``suffix`` (``".glb"``...).

    Parameters
    ----------
    shapes : ShapeMesh or sequence of ShapeMesh
        The shapes.
    suffix : str
        One of ``MESH_FORMATS``.

    Returns
    -------
    bytes

    Raises
    ------
    ExportError
        Unknown suffix; the message lists the valid ones.

    Examples
    --------
    >>> m = actuator_mesh(PlanarPath.straight(100.0), 90.0, width_mm=7.0, r0_mm=2.58, measure=False, name="A1")
    >>> mesh_bytes(m, ".glb")[:4]
    b'glTF'
    """
    kind = MESH_FORMATS.get(str(suffix).lower())
    if kind is None:
        raise ExportError(f"mesh file suffix must be one of {', '.join(MESH_FORMATS)}, got {suffix!r}")
    return _export_bytes(shapes_of(shapes), kind)


def write_mesh(shapes, path) -> Path:
    """Write one shape or several (one per actuator) to ``path``; the suffix picks the format.

    See ``MESH_FORMATS``.  GLB keeps one named node per body (``"A1.tube"``); STL, OBJ
    and PLY get one joined mesh.

    Parameters
    ----------
    shapes : ShapeMesh or sequence of ShapeMesh
        The shapes.
    path : str or os.PathLike
        The file.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ExportError
        Unknown suffix (the message lists the valid ones) or the file cannot be written.

    Examples
    --------
    >>> import tempfile
    >>> m = actuator_mesh(PlanarPath.straight(100.0), 90.0, width_mm=7.0, r0_mm=2.58, measure=False, name="A1")
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write_mesh(m, f"{tmp}/A1.glb").name
    'A1.glb'
    """
    p = Path(path)
    write_bytes_atomic(p, mesh_bytes(shapes, p.suffix or p.name))
    return p
