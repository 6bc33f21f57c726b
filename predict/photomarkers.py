"""The bend of a strip from marker positions in a photo's plane: the geometry, no image work.

A photo measurement (``embroact measure``) sees the bending plane face on. Each marker is
a small square printed on a fin that stands on the strip at a marker position of the
layout (:class:`~embroact.predict.markers.MarkerLayout`, docs/model.md section 11), its
face in the bending plane, its centre ``fin_offset_mm`` from the fabric line along the
strip's normal and its printed "up" pointing away from the fabric::

         [m0]  [m1]  [m2]  ...          fins: marker centres fin_offset_mm off the line
          |     |     |
    clamp ================================ tip      fabric line, markers spacing_mm apart

A reference board of markers at known positions (:class:`ReferenceBoard`) lies in the
same plane; a homography from it turns pixels into millimetres (the image side lives in
:mod:`embroact.export.photo`). Here, given each fin marker's centre and axes in board
millimetres, :func:`read_strip`

* moves each centre back onto the fabric line (``- fin_offset_mm`` along the marker's up
  axis), giving the layout's marker points;
* fits a chain of arcs, one constant curvature between neighbouring markers, to those
  points and to the markers' directions (a marker's x axis is the strip's tangent there):
  the bent centreline;
* reads the bend as the layout's marker sum on that chain (the angle between its first
  and its last chord, :func:`embroact.predict.markers.bend_angle_deg`), so the number is
  the reading ``fit`` compares with the model, signed as the model signs bends (positive
  toward the back of the fabric).

The fin side sets the sign: fins on the fabric side have their up axis toward the back,
fins on the thread side toward the front (:class:`~embroact.predict.markers.MarkerSide`).

Examples
--------
Eleven markers 10 mm apart on a 100 mm arc bending 90 deg toward the back (fins on the
thread side, outside the bend): the marker sum reads 81 deg (90 mm of its curvature):

>>> import numpy as np
>>> from embroact.predict.photomarkers import PhotoLayout, read_strip
>>> lay = PhotoLayout()
>>> s = np.arange(11) * 10.0
>>> k = np.radians(90.0) / 100.0
>>> phi = k * s
>>> line = np.stack([np.sin(phi) / k, (1 - np.cos(phi)) / k], axis=1)
>>> tangent = np.stack([np.cos(phi), np.sin(phi)], axis=1)
>>> front = np.stack([np.sin(phi), -np.cos(phi)], axis=1)          # thread side: up is the front
>>> r = read_strip(line + lay.fin_offset_mm * front, tangent, front, lay, side="thread")
>>> round(r.reading_deg, 6), round(r.rms_mm, 9)
(81.0, 0.0)
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..patterns.base.arrays import frozen_array
from ..patterns.base.errors import ParameterError, check_range
from .markers import MarkerLayout, MarkerSide, bend_angle_deg

__all__ = ["COUPON_LAYOUT", "DEFAULT_BOARD", "PhotoLayout", "ReferenceBoard", "StripReading", "read_strip"]

#: Weight of a marker's direction residual in the centreline fit [mm per rad]: a tangent
#: error of 1 mrad counts as 0.01 mm of position (a marker's axes are measured over its
#: whole side, its centre from four corners).
_TANGENT_WEIGHT_MM = 10.0
#: Most Gauss-Newton steps of the centreline fit (it converges in 3-6).
_GN_ITERATIONS = 12


@dataclass(frozen=True, slots=True)
class ReferenceBoard:
    """Markers at known positions in the bending plane: the photo's scale and perspective.

    Parameters
    ----------
    ids : tuple of int
        Marker ids (ArUco 4x4 dictionary of 250), distinct.
    centres_mm : tuple of (x, y)
        Their centres on the board [mm], x to the right, y up as printed.
    size_mm : float
        Side of each printed square, black border included [mm], > 0.

    Examples
    --------
    >>> DEFAULT_BOARD.corners_mm(0).round(1).tolist()
    [[-86.0, 61.0], [-74.0, 61.0], [-74.0, 49.0], [-86.0, 49.0]]
    """

    ids: tuple[int, ...] = (0, 1, 2, 3, 4, 5, 6, 7)
    centres_mm: tuple[tuple[float, float], ...] = ((-80.0, 55.0), (0.0, 55.0), (80.0, 55.0), (80.0, 0.0),
                                                   (80.0, -55.0), (0.0, -55.0), (-80.0, -55.0), (-80.0, 0.0))
    size_mm: float = 12.0

    def __post_init__(self) -> None:
        ids = tuple(int(i) for i in self.ids)
        centres = tuple((float(x), float(y)) for x, y in self.centres_mm)
        if len(ids) < 4 or len(set(ids)) != len(ids) or len(centres) != len(ids):
            raise ParameterError(f"a reference board needs at least 4 distinct ids, one centre each, got {len(ids)} "
                                 f"ids and {len(centres)} centres")
        check_range("size_mm", self.size_mm, low=0.0, high=1000.0)
        object.__setattr__(self, "ids", ids)
        object.__setattr__(self, "centres_mm", centres)

    def corners_mm(self, index: int) -> np.ndarray:
        """Corners of marker ``index`` [mm], (4, 2): top-left, top-right, bottom-right, bottom-left (ArUco's order).

        Parameters
        ----------
        index : int
            The marker's index on the board.

        Returns
        -------
        numpy.ndarray (4, 2)
            [mm], y up.

        Examples
        --------
        >>> DEFAULT_BOARD.centres_mm[0], DEFAULT_BOARD.corners_mm(0)[0].tolist()
        ((-80.0, 55.0), [-86.0, 61.0])
        """
        x, y = self.centres_mm[index]
        h = self.size_mm / 2.0
        return np.array([[x - h, y + h], [x + h, y + h], [x + h, y - h], [x - h, y - h]])


DEFAULT_BOARD = ReferenceBoard()
"""Eight 12 mm markers (ids 0-7) around a 160 x 110 mm window, for a 100 mm strip inside it."""


@dataclass(frozen=True, slots=True)
class PhotoLayout:
    """Where the markers of a photo measurement are, on the strip and on the board.

    Parameters
    ----------
    markers : MarkerLayout
        Marker positions along the strip (one row: a photo sees one face). Default: 11
        markers 10 mm apart from the clamped end, covering a 100 mm bent length.
    marker_size_mm : float
        Side of each printed fin marker, black border included [mm], > 0.
    fin_offset_mm : float
        Distance from the fabric line to a fin marker's centre along the normal [mm], >= 0.
    first_id : int
        Id of the first marker of the first actuator; actuator ``k``'s marker ``j`` has id
        ``first_id + k * markers_per_side + j`` (:meth:`ids`).
    board : ReferenceBoard
        The reference board (its ids must lie below ``first_id``).

    Examples
    --------
    >>> COUPON_LAYOUT.ids(1)[:3], COUPON_LAYOUT.blocks
    ((19, 20, 21), 22)
    """

    markers: MarkerLayout = field(default_factory=lambda: MarkerLayout(markers_per_side=11, spacing_mm=10.0,
                                                                       offset_mm=0.0, rows=1))
    marker_size_mm: float = 5.0
    fin_offset_mm: float = 5.0
    first_id: int = 8
    board: ReferenceBoard = DEFAULT_BOARD

    #: ArUco 4x4 dictionary size: ids 0..249.
    DICTIONARY_SIZE = 250

    def __post_init__(self) -> None:
        if not isinstance(self.markers, MarkerLayout):
            raise ParameterError(f"markers must be a MarkerLayout, got {type(self.markers).__name__}")
        if self.markers.rows != 1:
            raise ParameterError(f"a photo sees one row of markers: rows must be 1, got {self.markers.rows}")
        check_range("marker_size_mm", self.marker_size_mm, low=0.0, high=100.0)
        check_range("fin_offset_mm", self.fin_offset_mm, low=0.0, low_inclusive=True, high=100.0)
        if max(self.board.ids) >= self.first_id or self.blocks < 1:
            raise ParameterError(f"first_id must lie above the board's ids (max {max(self.board.ids)}) and leave room "
                                 f"for one actuator's {self.markers.markers_per_side} ids below "
                                 f"{self.DICTIONARY_SIZE}, got {self.first_id}")

    @property
    def blocks(self) -> int:
        """How many actuators have their own ids in the dictionary."""
        return (self.DICTIONARY_SIZE - self.first_id) // self.markers.markers_per_side

    def ids(self, block: int) -> tuple[int, ...]:
        """Marker ids of actuator ``block`` (0-based), clamped end to tip.

        Parameters
        ----------
        block : int
            In ``[0, blocks)``.

        Returns
        -------
        tuple of int

        Examples
        --------
        >>> PhotoLayout().ids(1)[:3]
        (19, 20, 21)
        """
        if not 0 <= block < self.blocks:
            raise ParameterError(f"actuator block must be in [0, {self.blocks - 1}], got {block}")
        n = self.markers.markers_per_side
        return tuple(range(self.first_id + block * n, self.first_id + (block + 1) * n))

    def block_of(self, marker_id: int) -> tuple[int, int] | None:
        """(block, index along the strip) of a fin marker id; None for a board id or one outside every block.

        Parameters
        ----------
        marker_id : int
            An ArUco id.

        Returns
        -------
        tuple of int or None

        Examples
        --------
        >>> lay = PhotoLayout()
        >>> lay.block_of(lay.first_id + 3), lay.block_of(0)
        ((0, 3), None)
        """
        k, j = divmod(int(marker_id) - self.first_id, self.markers.markers_per_side)
        return (k, j) if marker_id >= self.first_id and k < self.blocks else None

    def positions_mm(self) -> np.ndarray:
        """Arc lengths of the markers from the clamped end of the bent length [mm].

        Returns
        -------
        numpy.ndarray (markers_per_side,)

        Examples
        --------
        >>> PhotoLayout().positions_mm()[:3].tolist()
        [0.0, 10.0, 20.0]
        """
        m = self.markers
        return m.offset_mm + m.spacing_mm * np.arange(m.markers_per_side)


COUPON_LAYOUT = PhotoLayout()
"""The calibration coupon's layout: 11 fin markers of 5 mm, 10 mm apart, 5 mm off the line."""


@dataclass(frozen=True, slots=True)
class StripReading:
    """What a photo's markers say about the strip.

    Attributes
    ----------
    reading_deg : float
        The layout's marker sum on the fitted centreline [deg], signed (positive toward the back).
    chord_sum_deg : float
        The same sum straight from the measured marker points (no fit) [deg].
    points_mm : ndarray, (n, 2)
        The layout's marker points on the fabric line, in board millimetres.
    curvature_per_mm : ndarray, (n - 1,)
        Fitted curvature of each piece between neighbouring markers [1/mm], signed as the bend.
    centreline_mm : ndarray, (m, 2)
        The fitted fabric line from the first to the last marker, every 1 mm or closer.
    rms_mm : float
        Root-mean-square distance between the measured and the fitted marker points [mm].

    Examples
    --------
    >>> lay = PhotoLayout()
    >>> s = np.arange(11) * 10.0
    >>> phi = np.radians(90.0) / 100.0 * s  # a quarter circle of 100 mm, the fins on the thread side
    >>> line = np.stack([np.sin(phi), 1 - np.cos(phi)], axis=1) * (100.0 / np.radians(90.0))
    >>> tangent, front = np.stack([np.cos(phi), np.sin(phi)], axis=1), np.stack([np.sin(phi), -np.cos(phi)], axis=1)
    >>> r = read_strip(line + lay.fin_offset_mm * front, tangent, front, lay, side="thread")
    >>> round(r.reading_deg, 6), r.points_mm.shape
    (81.0, (11, 2))
    """

    reading_deg: float
    chord_sum_deg: float
    points_mm: np.ndarray
    curvature_per_mm: np.ndarray
    centreline_mm: np.ndarray
    rms_mm: float

    def centreline_at(self, s_mm) -> np.ndarray:
        """Fitted fabric-line points at arc lengths ``s_mm`` from the first marker [mm], (k, 2).

        Parameters
        ----------
        s_mm : array_like (k,)
            Arc lengths [mm].

        Returns
        -------
        numpy.ndarray (k, 2)
            In board millimetres.

        Raises
        ------
        ParameterError
            The reading was not made by :func:`read_strip`.

        Examples
        --------
        >>> lay = PhotoLayout()
        >>> s = np.arange(11) * 10.0
        >>> phi = np.radians(90.0) / 100.0 * s  # a quarter circle of 100 mm, the fins on the thread side
        >>> line = np.stack([np.sin(phi), 1 - np.cos(phi)], axis=1) * (100.0 / np.radians(90.0))
        >>> tangent, front = np.stack([np.cos(phi), np.sin(phi)], axis=1), np.stack([np.sin(phi), -np.cos(phi)], axis=1)
        >>> r = read_strip(line + lay.fin_offset_mm * front, tangent, front, lay, side="thread")
        >>> r.centreline_at([100.0]).round(3).tolist()
        [[63.662, 63.662]]
        """
        s = np.asarray(s_mm, dtype=np.float64).reshape(-1)
        if self._start is None or self._lengths is None or self._kappa is None:
            raise ParameterError("centreline_at needs a reading made by read_strip")
        return _chain_points(self._start, self._heading, self._lengths, self._kappa, s)

    # fit pose: not part of the reading's value
    _start: np.ndarray | None = field(default=None, repr=False, compare=False)
    _heading: float = field(default=0.0, repr=False, compare=False)
    _lengths: np.ndarray | None = field(default=None, repr=False, compare=False)
    _kappa: np.ndarray | None = field(default=None, repr=False, compare=False)  # counter-clockwise


def _chain_points(start, heading, lengths, kappa, s) -> np.ndarray:
    """Points at arc lengths ``s`` of a chain of arcs (curvatures ``kappa``) from ``start`` heading ``heading``."""
    edges = np.concatenate([[0.0], np.cumsum(lengths)])
    phi = heading + np.concatenate([[0.0], np.cumsum(kappa * lengths)])
    half = 0.5 * kappa * lengths
    z0 = complex(start[0], start[1]) + np.concatenate(
        [[0.0], np.cumsum(np.exp(1j * (phi[:-1] + half)) * lengths * np.sinc(half / np.pi))])
    i = np.clip(np.searchsorted(edges, s, side="right") - 1, 0, len(lengths) - 1)
    h = s - edges[i]
    a = 0.5 * kappa[i] * h
    z = z0[i] + np.exp(1j * (phi[i] + a)) * h * np.sinc(a / np.pi)
    return np.stack([z.real, z.imag], axis=-1)


def _unit_rows(name: str, v, n: int) -> np.ndarray:
    a = np.asarray(v, dtype=np.float64)
    if a.shape != (n, 2) or not np.all(np.isfinite(a)):
        raise ParameterError(f"{name} must be {n} finite (x, y) rows, got shape {a.shape}")
    norm = np.linalg.norm(a, axis=1, keepdims=True)
    if np.any(norm <= 0.0):
        raise ParameterError(f"{name} must be non-zero vectors")
    return a / norm


def read_strip(centres_mm, x_axes, up_axes, layout: PhotoLayout = COUPON_LAYOUT, *,
               side: MarkerSide | str = MarkerSide.FABRIC) -> StripReading:
    """Bend reading and centreline from the fin markers' centres and axes in the plane (module docstring).

    Parameters
    ----------
    centres_mm : array_like, (n, 2)
        Marker centres in board millimetres, clamped end to tip (n = ``markers_per_side``).
    x_axes, up_axes : array_like, (n, 2)
        Each marker's printed x axis (along the strip's tangent, toward the tip or the clamp:
        oriented here along the markers' order) and up axis (away from the fabric), in the
        same frame; any length.
    layout : PhotoLayout
        The strip's fin layout.
    side : MarkerSide or str
        Face the fins stand on: ``"fabric"`` (up toward the back) or ``"thread"`` (up toward the front).

    Returns
    -------
    StripReading

    Examples
    --------
    >>> lay = PhotoLayout()
    >>> s = np.arange(11) * 10.0
    >>> phi = np.radians(90.0) / 100.0 * s  # a quarter circle of 100 mm, the fins on the thread side
    >>> line = np.stack([np.sin(phi), 1 - np.cos(phi)], axis=1) * (100.0 / np.radians(90.0))
    >>> tangent, front = np.stack([np.cos(phi), np.sin(phi)], axis=1), np.stack([np.sin(phi), -np.cos(phi)], axis=1)
    >>> r = read_strip(line + lay.fin_offset_mm * front, tangent, front, lay, side="thread")
    >>> round(r.rms_mm, 9), round(r.chord_sum_deg, 6)
    (0.0, 81.0)
    """
    n = layout.markers.markers_per_side
    c = np.asarray(centres_mm, dtype=np.float64)
    if c.shape != (n, 2) or not np.all(np.isfinite(c)):
        raise ParameterError(f"centres_mm must be {n} finite (x, y) rows, got shape {c.shape}")
    tx = _unit_rows("x_axes", x_axes, n)
    up = _unit_rows("up_axes", up_axes, n)
    try:
        back_sign = 1.0 if MarkerSide(side) is MarkerSide.FABRIC else -1.0
    except ValueError:
        raise ParameterError(f"side must be one of 'fabric', 'thread', got {side!r}") from None
    points = c - layout.fin_offset_mm * up
    # a fin faces the camera with its printed side, so its x axis points to the tip or to the clamp
    # depending on the face the camera sees: orient each along the chords, clamp to tip (ids' order)
    chords = np.diff(points, axis=0)
    along = np.concatenate([chords, chords[-1:]]) + np.concatenate([chords[:1], chords])
    tx = tx * np.where(np.einsum("ij,ij->i", tx, along) < 0.0, -1.0, 1.0)[:, None]
    back0 = back_sign * up[0]
    s = layout.positions_mm() - layout.positions_mm()[0]
    lengths = np.diff(s)
    # in a frame where the back is to the left of the tangent, a positive bend turns counter-clockwise
    hand = float(np.sign(tx[0, 0] * back0[1] - tx[0, 1] * back0[0])) or 1.0
    kappa, start, heading, rms = _fit_chain(points, np.arctan2(tx[:, 1], tx[:, 0]), s, lengths)
    line_s = np.linspace(0.0, float(s[-1]), max(int(np.ceil(s[-1])) + 1, 2))
    fitted = _chain_points(start, heading, lengths, kappa, s)
    reading = float(bend_angle_deg(fitted, markers_per_side=n, sides=1, normal=back0, tangent=tx[0]))
    direct = float(bend_angle_deg(points, markers_per_side=n, sides=1, normal=back0, tangent=tx[0]))
    return StripReading(reading, direct, frozen_array(points), frozen_array(hand * kappa),
                        frozen_array(_chain_points(start, heading, lengths, kappa, line_s)), rms,
                        frozen_array(start), heading, frozen_array(lengths), frozen_array(kappa))


def _fit_chain(points: np.ndarray, tangent_rad: np.ndarray, s: np.ndarray, lengths: np.ndarray):
    """Least-squares chain of arcs through ``points`` with tangents ``tangent_rad`` at arc lengths ``s``.

    Unknowns: start point, start heading, one curvature per piece. Start values from the
    markers' directions; Gauss-Newton with a forward-difference Jacobian (13 unknowns for 11
    markers; the problem is nearly linear once the headings are close, so a handful of steps
    converge; numpy only, no scipy import for a photo).
    """
    tangent = np.unwrap(tangent_rad)
    x = np.concatenate([points[0], [tangent[0]], np.diff(tangent) / lengths])

    def residuals(x):
        start, heading, kappa = x[:2], x[2], x[3:]
        p = _chain_points(start, heading, lengths, kappa, s)
        phi = heading + np.concatenate([[0.0], np.cumsum(kappa * lengths)])
        return np.concatenate([(p - points).ravel(), _TANGENT_WEIGHT_MM * (phi - tangent)])

    r = residuals(x)
    steps = np.concatenate([[1e-6, 1e-6, 1e-8], np.full(len(lengths), 1e-9)])
    for _ in range(_GN_ITERATIONS):
        jac = np.stack([(residuals(x + np.eye(len(x))[k] * steps[k]) - r) / steps[k] for k in range(len(x))], axis=1)
        dx = np.linalg.lstsq(jac, -r, rcond=None)[0]
        x = x + dx
        r = residuals(x)
        if np.max(np.abs(dx[3:] * lengths)) < 1e-9 and np.max(np.abs(dx[:3])) < 1e-7:  # nm, 0.1 urad
            break
    fitted = _chain_points(x[:2], x[2], lengths, x[3:], s)
    rms = float(np.sqrt(np.mean(np.sum((fitted - points) ** 2, axis=1))))
    return x[3:], x[:2], float(x[2]), rms
