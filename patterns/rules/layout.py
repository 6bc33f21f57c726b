"""What every geometric rule reads: records and tubes (:class:`Layout`), from plans or files.

A :class:`Layout` holds records (positions in mm, a
:class:`~embroact.patterns.plan.Command` per record, the tube each record belongs
to) and the tubes (path, radius, clearance, end margin, stitched half width).
Stitch plans become layouts with :func:`layout_from_plan`; the records of an
embroidery file become one with :func:`layout_from_records`, so the same rules
check both.

Examples
--------
>>> from embroact.patterns.plan import Command
>>> tube = TubeLayout.from_path("A", [(0, 0), (20, 0)], outer_radius_mm=1.5,
...                             clearance_mm=0.3, end_margin_mm=0.0, half_width_mm=3.5)
>>> lay = Layout.from_points([(2, 3.5), (3, -3.5)], [Command.STITCH] * 2, [0, 0], tubes=(tube,))
>>> len(lay), lay.name_of(0), round(tube.corridor_radius_mm, 3)
(2, 'A', 1.8)
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import shapely

from ..base.arrays import frozen_array
from ..base.errors import ParameterError, PathError, check_range
from ..base.tolerances import DEFAULT_TOLERANCES
from ..centerline import Centerline, as_centerline
from ..plan import Command, Role, StitchPlan
from ..spatial import TubeIndex

__all__ = ["TubeLayout", "Layout", "layout_from_plan", "layout_from_records", "FILE_REACH_MM"]

#: Needle points of a file further than this from every tube belong to no tube [mm].
FILE_REACH_MM = 15.0


@dataclass(frozen=True, slots=True)
class TubeLayout:
    """A tube laid on the fabric, as the rules see it.

    Attributes
    ----------
    name : str
        The actuator's (or tube's) name.
    path : shapely.LineString
        Tube axis [mm] in the layout's frame (any line, even one that crosses itself).
    outer_radius_mm, clearance_mm, end_margin_mm : float
        Tube radius r_f, needle clearance, free length beyond each end [mm].
    half_width_mm : float or None
        Half the stitched band width w/2 (realised or measured) [mm]; None if unknown.
    centerline : Centerline or None
        The path as a :class:`~embroact.patterns.centerline.Centerline` (projection,
        curvature); None when the path is not a valid centerline (it crosses itself).

    Examples
    --------
    >>> tube = TubeLayout.from_path("A", [(0, 0), (8, 0)], outer_radius_mm=1.5, clearance_mm=0.3,
    ...                             end_margin_mm=2.0, half_width_mm=3.5)
    >>> tube.path.length, tube.centerline.length_mm, tube.extended_path().length
    (8.0, 8.0, 12.0)
    """

    name: str
    path: shapely.LineString
    outer_radius_mm: float
    clearance_mm: float
    end_margin_mm: float
    half_width_mm: float | None = None
    centerline: Centerline | None = None

    @classmethod
    def from_path(cls, name: str, path, *, outer_radius_mm: float, clearance_mm: float,
                  end_margin_mm: float, half_width_mm: float | None = None) -> "TubeLayout":
        """From a LineString or (n, 2) points; ``centerline`` is None if the path is not a valid one.

        Parameters
        ----------
        name : str
            The tube's name.
        path : shapely.LineString or array_like (n, 2)
            Its axis [mm], at least 2 finite points and a length > 0.
        outer_radius_mm, clearance_mm, end_margin_mm, half_width_mm : float
            As the attributes.

        Returns
        -------
        TubeLayout

        Examples
        --------
        >>> crossing = TubeLayout.from_path("B", [(0, 0), (5, 5), (5, 0), (0, 5)], outer_radius_mm=1.5,
        ...                                 clearance_mm=0.3, end_margin_mm=0.0)
        >>> crossing.centerline is None, crossing.half_width_mm is None
        (True, True)
        """
        xy = np.asarray(path.coords if isinstance(path, shapely.LineString) else path, dtype=np.float64)
        if xy.ndim != 2 or xy.shape[1] < 2 or len(xy) < 2 or not np.all(np.isfinite(xy)):
            raise ParameterError(f"tube path of {name} must be finite (x, y) points, at least 2, got shape {xy.shape}")
        line = shapely.LineString(xy[:, :2])
        if line.length <= DEFAULT_TOLERANCES.length_mm:
            raise ParameterError(f"tube path of {name} must have a length > 0, got {line.length:g} mm")
        try:
            cl = as_centerline(line)
        except PathError:
            cl = None
        return cls(name, line, outer_radius_mm, clearance_mm, end_margin_mm, half_width_mm, cl)

    @property
    def corridor_radius_mm(self) -> float:
        """r_f + clearance [mm]."""
        return self.outer_radius_mm + self.clearance_mm

    def extended_path(self):
        """The path lengthened by ``end_margin_mm`` along the end tangents (the whole laid tube).

        Returns
        -------
        shapely.LineString
            ``path`` itself when there is no margin.

        Examples
        --------
        >>> tube = TubeLayout.from_path("A", [(0, 0), (8, 0)], outer_radius_mm=1.5, clearance_mm=0.3,
        ...                             end_margin_mm=2.0, half_width_mm=3.5)
        >>> list(tube.extended_path().coords)[0]
        (-2.0, 0.0)
        """
        if self.end_margin_mm <= 0.0:
            return self.path
        xy = np.asarray(self.path.coords, dtype=np.float64)[:, :2]
        t0, t1 = xy[0] - xy[1], xy[-1] - xy[-2]
        head = xy[0] + t0 / np.hypot(*t0) * self.end_margin_mm
        tail = xy[-1] + t1 / np.hypot(*t1) * self.end_margin_mm
        return shapely.LineString(np.vstack([head, xy, tail]))


@dataclass(frozen=True, slots=True, eq=False)
class Layout:
    """Records and tubes: everything the geometric and file-level rules read.

    Attributes
    ----------
    xy_mm : ndarray, shape (n, 2)
        Record positions [mm], read-only.
    commands : ndarray of int8
        :class:`Command` per record.
    owner : ndarray of int16
        Index into ``tubes`` of the tube a record belongs to, -1 for none.
    tubes : tuple of TubeLayout
        The tubes, indexed by ``owner``.
    index : ndarray of int64
        Stitch index to report per record (plan index, or file record index).
    before_tube : ndarray of bool
        True for a record sewn before its own tube was laid (a placement line): it can neither
        pierce nor hold that tube.
    header_faults : tuple of str
        Fields of an embroidery file's header that disagree with its records (rule EA505), as
        found when the file was read; empty for designs.

    Examples
    --------
    >>> lay = Layout.from_points([(0, 0), (1, 2)], [0, 1], [-1, -1], tubes=())
    >>> lay.index.tolist(), lay.xy_mm.flags.writeable, lay.name_of(-1)
    ([0, 1], False, None)
    """

    xy_mm: np.ndarray
    commands: np.ndarray
    owner: np.ndarray
    tubes: tuple[TubeLayout, ...]
    index: np.ndarray
    before_tube: np.ndarray
    header_faults: tuple[str, ...] = ()

    @classmethod
    def from_points(cls, xy_mm, commands, owner, *, tubes, index=None, before_tube=None,
                    header_faults=()) -> "Layout":
        """Build from array-likes (copied, made read-only).

        Parameters
        ----------
        xy_mm, commands, owner : array_like
            As the attributes, one entry per record; ``owner`` in ``[-1, len(tubes))``.
        tubes : sequence of TubeLayout
            The tubes.
        index, before_tube : array_like, optional
            As the attributes; default 0..n-1 and all False.
        header_faults : sequence of str, optional
            As the attribute.

        Returns
        -------
        Layout

        Examples
        --------
        >>> tube = TubeLayout.from_path("A", [(0, 0), (8, 0)], outer_radius_mm=1.5, clearance_mm=0.3,
        ...                             end_margin_mm=2.0, half_width_mm=3.5)
        >>> Layout.from_points([(2, 3.5)], [0], [0], tubes=(tube,), index=[40]).index.tolist()
        [40]
        """
        xy = frozen_array(xy_mm).reshape(-1, 2)
        n = len(xy)
        arrays = [
            xy,
            frozen_array(commands, np.int8).reshape(-1),
            frozen_array(owner, np.int16).reshape(-1),
            frozen_array(np.arange(n) if index is None else index, np.int64).reshape(-1),
            frozen_array(np.zeros(n, bool) if before_tube is None else before_tube, bool).reshape(-1),
        ]
        for a in arrays:
            if len(a) != n:
                raise ParameterError(f"layout arrays must all have {n} entries, got {len(a)}")
        tubes = tuple(tubes)
        if n and not (-1 <= arrays[2].min() and arrays[2].max() < len(tubes)):
            raise ParameterError(f"owner must be in [-1, {len(tubes)}) (tube indices), got {arrays[2].max()}")
        return cls(arrays[0], arrays[1], arrays[2], tubes, arrays[3], arrays[4], tuple(header_faults))

    def __len__(self) -> int:
        return len(self.xy_mm)

    def name_of(self, owner: int) -> str | None:
        """Tube name for an owner index, None for -1.

        Parameters
        ----------
        owner : int
            Index into ``tubes``, or -1.

        Returns
        -------
        str or None

        Examples
        --------
        >>> tube = TubeLayout.from_path("A", [(0, 0), (8, 0)], outer_radius_mm=1.5, clearance_mm=0.3,
        ...                             end_margin_mm=2.0, half_width_mm=3.5)
        >>> Layout.from_points([(2, 3.5)], [0], [0], tubes=(tube,)).name_of(0)
        'A'
        """
        return self.tubes[owner].name if owner >= 0 else None


def layout_from_plan(plan: StitchPlan) -> Layout:
    """The layout of a stitch plan: tubes from its actuators, half width from the realised width;
    placement-line records (:attr:`~embroact.patterns.plan.Role.PLACEMENT`) come before their tube.

    Parameters
    ----------
    plan : StitchPlan
        A design's plan.

    Returns
    -------
    Layout

    Examples
    --------
    >>> from embroact.patterns.zigzag import zigzag
    >>> from embroact.patterns.params import ZigzagParams
    >>> lay = layout_from_plan(zigzag([[0.0, 0.0], [20.0, 0.0]], ZigzagParams(7.0, 1.0), name="A1"))
    >>> lay.tubes[0].name, lay.tubes[0].half_width_mm, bool(lay.before_tube.any())
    ('A1', 3.5, False)
    """
    tubes = tuple(
        TubeLayout(
            name=a.name,
            path=a.centerline.as_linestring(),
            outer_radius_mm=a.tube.outer_radius_mm,
            clearance_mm=a.tube.clearance_mm,
            end_margin_mm=a.tube.end_margin_mm,
            half_width_mm=max(seg.realised.width_mm for seg in a.segments) / 2.0,  # the widest segment's
            centerline=a.centerline,
        )
        for a in plan.actuators
    )
    owner = np.where(plan.actuator < len(tubes), plan.actuator, -1)
    return Layout.from_points(plan.xy_mm, plan.commands, owner, tubes=tubes, before_tube=plan.roles == Role.PLACEMENT)


def layout_from_records(xy_mm, commands, tubes, *, reach_mm: float = FILE_REACH_MM, index=None,
                        header_faults=()) -> Layout:
    """A layout for records without owners (an embroidery file): assign needle points to tubes.

    Each needle point belongs to the nearest tube closer than ``reach_mm`` (else to
    none); each tube's ``half_width_mm`` becomes the median distance of its needle
    points from its axis (the measured w/2) unless already set. One spatial query
    over every tube's axis assigns all needle points.

    A file carries no roles, so which needle points came before their tube is read from the
    order of its records: the stops split a tube's needle points into stretches, and the
    stretches before the first one whose points lie mostly (median) outside the tube's corridor
    run along its axis: a placement line, sewn before the tube was laid at the stop that ends it.
    A tube laid before start, or whose first stretch couches it, has none.

    Parameters
    ----------
    xy_mm : array (n, 2)
        Record positions [mm] in the same frame as the tube paths.
    commands : array (n,)
        :class:`Command` per record.
    tubes : sequence of TubeLayout
        The tubes the file was sewn over.
    reach_mm : float
        Needle points further than this from every tube belong to none [mm].
    index : array (n,), optional
        Index to report per record (default 0..n-1).
    header_faults : sequence of str
        Header fields that disagree with the records (:attr:`Layout.header_faults`).

    Returns
    -------
    Layout

    Examples
    --------
    >>> tube = TubeLayout.from_path("A", [(0, 0), (8, 0)], outer_radius_mm=1.5, clearance_mm=0.3,
    ...                             end_margin_mm=0.0)
    >>> lay = layout_from_records([(2, 3.4), (3, -3.6), (40, 0)], [0, 0, 0], [tube])
    >>> lay.owner.tolist(), lay.tubes[0].half_width_mm
    ([0, 0, -1], 3.5)
    """
    check_range("reach_mm", reach_mm, low=0.0, high=1e4)
    xy = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
    cmds = np.asarray(commands, dtype=np.int8)
    tubes = tuple(tubes)
    needles = np.flatnonzero(cmds == Command.STITCH)
    owner = np.full(len(xy), -1, dtype=np.int16)
    hit, tube, dist = TubeIndex([t.path for t in tubes]).nearest(xy[needles], reach_mm)
    owner[needles[hit]] = tube
    order = np.argsort(tube, kind="stable")
    cuts = np.searchsorted(tube[order], np.arange(1, len(tubes)))
    groups = np.split(dist[order], cuts)
    out = tuple(
        replace(t, half_width_mm=float(np.median(mine))) if t.half_width_mm is None and len(mine) else t
        for t, mine in zip(tubes, groups)
    )
    before = _before_tube(len(xy), np.flatnonzero(cmds == Command.STOP), np.split(needles[hit][order], cuts), groups,
                          tubes)
    return Layout.from_points(xy, cmds, owner, tubes=out, index=index, before_tube=before,
                              header_faults=header_faults)


def _before_tube(n: int, stops: np.ndarray, records, dists, tubes) -> np.ndarray:
    """Records sewn before their tube was laid (see :func:`layout_from_records`), of ``n``.

    ``records`` and ``dists``: per tube, its needle records and their distances from its axis.
    """
    before = np.zeros(n, dtype=bool)
    if not len(stops):
        return before
    for t, rec, d in zip(tubes, records, dists):
        stretch = np.searchsorted(stops, rec)
        for k in np.unique(stretch):
            if np.median(d[stretch == k]) >= t.corridor_radius_mm:
                before[rec[stretch < k]] = True  # the stretches before the first that couches the tube
                break
    return before
