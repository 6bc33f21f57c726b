"""Geometric design rules on stitch plans and sewing layouts (pure functions).

A :class:`Layout` is what every geometric rule needs: records (positions in mm,
:class:`~embroact.patterns.plan.Command` per record, the tube each record belongs
to) and the tubes (path, radius, clearance, end margin, stitched half width).
Stitch plans become layouts with :func:`layout_from_plan`; embroidery files read
by ``embroact.export.machine.filecheck`` become layouts too, so the same rules check both.

Conventions
-----------
* Stitch length: displacement of a STITCH record from the previous record; the
  *minimum* is checked only between two consecutive STITCH records (a stitch after
  a stop, jump or trim is the first penetration, not a thread length).
* Needle density (EA105/EA106) counts, as Ink/Stitch's density map does, every
  needle point within ``density_radius_mm`` (``<=``) **including the point itself**.
* Minimum turning radius: ``turning_radius_factor`` x the tube's outer diameter
  (default 3 x 2 r_f = 9 mm for the default tube), against
  :meth:`Centerline.min_radius_mm` (a vertex turning by more than
  ``MAX_SMOOTH_TURN_DEG`` is a corner of radius 0, as for the generators).
* The tube extends ``end_margin_mm`` beyond each end of its path along the end
  tangent (connector room); needle points there pierce it too.

Examples
--------
>>> from embroact.patterns.plan import Command
>>> from embroact.patterns.rules import Layout, TubeLayout, RuleSettings, check_layout
>>> tube = TubeLayout.from_path("A", [(0, 0), (20, 0)], outer_radius_mm=1.5,
...                             clearance_mm=0.3, end_margin_mm=0.0, half_width_mm=3.5)
>>> recs = [(2, 3.5), (3, -3.5), (4, 3.5), (5, 1.0), (6, -3.5)]
>>> lay = Layout.from_points(recs, [Command.STITCH] * 5, [0] * 5, tubes=(tube,))
>>> [(f.code, f.stitch_index) for f in check_layout(lay, RuleSettings())]
[('EA101', 3)]
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import shapely

from ..base.arrays import frozen_array
from ..centerline import MAX_SMOOTH_TURN_DEG, Centerline, as_centerline
from ..base.errors import ParameterError, PathError, check_range
from ..base.findings import RULES, Finding
from ..limits import format_limit
from ..params import CrossParams
from ..plan import Command, Role, StitchPlan
from ..sleeve import min_sleeve_width_mm, neutral_angle_deg, sleeve_radius_mm
from ..base.tolerances import DEFAULT_TOLERANCES, Tolerances

__all__ = [
    "RuleSettings",
    "TubeLayout",
    "Layout",
    "layout_from_plan",
    "layout_from_records",
    "FILE_REACH_MM",
    "check_layout",
    "check_plan",
    "needle_density",
    "sort_findings",
]

#: Formats whose writer encodes a trim as a run of ``trim_jump_count`` jumps (pyembroidery's DST).
_TRIM_AS_JUMPS = ("dst",)

#: Needle points of a file further than this from every tube belong to no tube [mm].
FILE_REACH_MM = 15.0


@dataclass(frozen=True, slots=True)
class RuleSettings:
    """Thresholds of the geometric and file-level rules.

    Parameters
    ----------
    format : str
        Target machine format (per-record limits from ``patterns/limits.py``).
    min_stitch_mm, max_stitch_mm : float
        Machine stitch-length limits [mm] (EA104, EA103).
    hoop_width_mm, hoop_height_mm : float or None
        Sewing field [mm]; None skips the hoop rules (EA306, EA305's hoop part).
    density_radius_mm : float
        Radius of the density count [mm] (Ink/Stitch: 0.5).
    density_warning_count, density_error_count : int
        Needle points within the radius, the point itself included, for a warning (3) / error (6).
    min_sleeve_gap_mm : float
        Smallest r0 - r_f without a warning [mm] (EA202).
    turning_radius_factor : float
        Minimum tube turning radius in tube outer diameters (EA301).
    neutral_band_deg : float
        Half width of the band around the neutral angle that is flagged [deg] (EA206).
    actuator_clearance_mm : float
        Smallest gap between two actuators' stitched bands [mm] (EA304).
    trim_jump_count : int
        Consecutive jump records the machine reads as a trim (EA501).
    max_records : int or None
        Machine memory limit on records; None uses the format's limit (EA504).
    max_findings_per_rule : int
        Findings listed per rule; the rest are summarised in one more finding.
    tolerances : Tolerances
    """

    format: str = "dst"
    min_stitch_mm: float = 0.3
    max_stitch_mm: float = 12.1
    hoop_width_mm: float | None = None
    hoop_height_mm: float | None = None
    density_radius_mm: float = 0.5
    density_warning_count: int = 3
    density_error_count: int = 6
    min_sleeve_gap_mm: float = 0.1
    turning_radius_factor: float = 3.0
    neutral_band_deg: float = 3.0
    actuator_clearance_mm: float = 1.0
    trim_jump_count: int = 3
    max_records: int | None = None
    max_findings_per_rule: int = 10
    tolerances: Tolerances = field(default_factory=lambda: DEFAULT_TOLERANCES)

    def __post_init__(self) -> None:
        format_limit(self.format)
        check_range("min_stitch_mm", self.min_stitch_mm, low=0.0, low_inclusive=True, high=100.0)
        check_range("max_stitch_mm", self.max_stitch_mm, low=self.min_stitch_mm, high=1000.0)
        for name in ("hoop_width_mm", "hoop_height_mm"):
            if getattr(self, name) is not None:
                check_range(name, getattr(self, name), low=0.0, high=1e4)
        check_range("density_radius_mm", self.density_radius_mm, low=0.0, high=100.0)
        check_range("min_sleeve_gap_mm", self.min_sleeve_gap_mm, low=0.0, low_inclusive=True, high=100.0)
        check_range("turning_radius_factor", self.turning_radius_factor, low=0.0, low_inclusive=True, high=1e3)
        check_range("neutral_band_deg", self.neutral_band_deg, low=0.0, low_inclusive=True, high=90.0)
        check_range("actuator_clearance_mm", self.actuator_clearance_mm, low=0.0, low_inclusive=True, high=1e3)
        for name in ("density_warning_count", "density_error_count", "trim_jump_count", "max_findings_per_rule"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < 1:
                raise ParameterError(f"{name} must be an integer >= 1, got {v!r}")

    @classmethod
    def for_machine(cls, machine, *, format: str | None = None, **overrides) -> "RuleSettings":
        """Settings from a design's machine settings (``format``, hoop and stitch limits).

        ``machine`` is any object with the attributes of ``MachineSettings``
        (``format``, ``hoop_width_mm``, ``hoop_height_mm``, ``min_stitch_mm``, ``max_stitch_mm``).
        """
        base = dict(
            format=format or machine.format,
            min_stitch_mm=machine.min_stitch_mm,
            max_stitch_mm=machine.max_stitch_mm,
            hoop_width_mm=machine.hoop_width_mm,
            hoop_height_mm=machine.hoop_height_mm,
        )
        base.update(overrides)
        return cls(**base)


@dataclass(frozen=True, slots=True)
class TubeLayout:
    """A tube laid on the fabric, as the rules see it.

    Attributes
    ----------
    name : str
    path : shapely.LineString
        Tube axis [mm] in the layout's frame (any line, even one that crosses itself).
    outer_radius_mm, clearance_mm, end_margin_mm : float
        Tube radius r_f, needle clearance, free length beyond each end [mm].
    half_width_mm : float or None
        Half the stitched band width w/2 (realised or measured) [mm]; None if unknown.
    centerline : Centerline or None
        The path as a :class:`~embroact.patterns.centerline.Centerline` (projection,
        curvature); None when the path is not a valid centerline (it crosses itself).
    """

    name: str
    path: object
    outer_radius_mm: float
    clearance_mm: float
    end_margin_mm: float
    half_width_mm: float | None = None
    centerline: Centerline | None = None

    @classmethod
    def from_path(cls, name: str, path, *, outer_radius_mm: float, clearance_mm: float,
                  end_margin_mm: float, half_width_mm: float | None = None) -> "TubeLayout":
        """From a LineString or (n, 2) points; ``centerline`` is None if the path is not a valid one."""
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
        """The path lengthened by ``end_margin_mm`` along the end tangents (the whole laid tube)."""
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
    index : ndarray of int64
        Stitch index to report per record (plan index, or file record index).
    """

    xy_mm: np.ndarray
    commands: np.ndarray
    owner: np.ndarray
    tubes: tuple[TubeLayout, ...]
    index: np.ndarray

    @classmethod
    def from_points(cls, xy_mm, commands, owner, *, tubes, index=None) -> "Layout":
        """Build from array-likes (copied, made read-only); ``index`` defaults to 0..n-1."""
        xy = frozen_array(xy_mm).reshape(-1, 2)
        n = len(xy)
        arrays = [
            xy,
            frozen_array(commands, np.int8).reshape(-1),
            frozen_array(owner, np.int16).reshape(-1),
            frozen_array(np.arange(n) if index is None else index, np.int64).reshape(-1),
        ]
        for a in arrays:
            if len(a) != n:
                raise ParameterError(f"layout arrays must all have {n} entries, got {len(a)}")
        tubes = tuple(tubes)
        if n and not (-1 <= arrays[2].min() and arrays[2].max() < len(tubes)):
            raise ParameterError(f"owner must be in [-1, {len(tubes)}) (tube indices), got {arrays[2].max()}")
        return cls(arrays[0], arrays[1], arrays[2], tubes, arrays[3])

    def __len__(self) -> int:
        return len(self.xy_mm)

    def name_of(self, owner: int) -> str | None:
        """Tube name for an owner index, None for -1."""
        return self.tubes[owner].name if owner >= 0 else None


# ---------------------------------------------------------------------------
# geometry helpers


class _PathIndex:
    """Queries of many points or legs against one polyline, through a shapely STRtree of its segments.

    ``shapely.distance`` / ``line_locate_point`` against one long line cost
    O(points x vertices); the tree's bounded queries make a 10 m path with 20k
    needle points fast.
    """

    __slots__ = ("_a", "_d", "_len", "_s", "_tree")

    def __init__(self, path) -> None:
        xy = np.asarray(path.coords, dtype=np.float64)[:, :2]
        d = np.diff(xy, axis=0)
        keep = np.hypot(d[:, 0], d[:, 1]) > 0.0
        self._a, self._d = xy[:-1][keep], d[keep]
        self._len = np.hypot(self._d[:, 0], self._d[:, 1])
        self._s = np.concatenate([[0.0], np.cumsum(self._len)[:-1]])
        self._tree = shapely.STRtree(shapely.linestrings(np.stack([self._a, self._a + self._d], axis=1)))

    def within(self, xy_mm, radius_mm: float) -> tuple[np.ndarray, np.ndarray]:
        """Indices of the points closer than ``radius_mm`` to the path, and their distances [mm]."""
        p = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
        i, k = self._tree.query(shapely.points(p), predicate="dwithin", distance=radius_mm)
        r = p[i] - self._a[k]
        t = np.clip(np.einsum("ij,ij->i", r, self._d[k]) / self._len[k] ** 2, 0.0, 1.0)
        dist = np.hypot(*(r - t[:, None] * self._d[k]).T)
        close = dist < radius_mm
        i, dist = i[close], dist[close]
        order = np.lexsort((dist, i))
        first = np.concatenate([[True], np.diff(i[order]) != 0]) if len(order) else np.zeros(0, bool)
        return i[order][first], dist[order][first]

    def nearest(self, xy_mm, max_distance_mm: float) -> tuple[np.ndarray, np.ndarray]:
        """Indices of the points within ``max_distance_mm`` of the path and their distances [mm]."""
        p = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
        (i, _), dist = self._tree.query_nearest(shapely.points(p), max_distance=max_distance_mm,
                                                return_distance=True, all_matches=False)
        return i, dist

    def crossings(self, a_mm, b_mm) -> tuple[np.ndarray, np.ndarray]:
        """Where straight legs a -> b cross the path: leg index and arc length of the crossing [mm]."""
        a, b = np.asarray(a_mm, dtype=np.float64), np.asarray(b_mm, dtype=np.float64)
        legs = shapely.linestrings(np.stack([a, b], axis=1))
        j, k = self._tree.query(legs, predicate="intersects")
        e, d, r = b[j] - a[j], self._d[k], a[j] - self._a[k]
        den = e[:, 0] * d[:, 1] - e[:, 1] * d[:, 0]
        ok = den != 0.0  # a leg lying along the path does not cross it
        t = (e[ok, 0] * r[ok, 1] - e[ok, 1] * r[ok, 0]) / den[ok]
        return j[ok], self._s[k[ok]] + np.clip(t, 0.0, 1.0) * self._len[k[ok]]


def needle_density(xy_mm, radius_mm: float = 0.5) -> np.ndarray:
    """Needle points within ``radius_mm`` (``<=``) of each point, the point itself included.

    Ink/Stitch's density map counts the same way (KD-tree ball query). Here scipy's
    ``cKDTree.query_pairs`` (imported only here) lists the close pairs once and a
    ``bincount`` counts them: 10^5 needle points take about 0.06 s.

    Examples
    --------
    >>> needle_density([(0, 0), (0.3, 0), (0.6, 0), (5, 5)]).tolist()
    [2, 3, 2, 1]
    """
    xy = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
    if len(xy) == 0:
        return np.zeros(0, dtype=np.int64)
    from scipy.spatial import cKDTree

    pairs = cKDTree(xy).query_pairs(radius_mm, output_type="ndarray")
    return 1 + np.bincount(pairs.ravel(), minlength=len(xy)).astype(np.int64)


# ---------------------------------------------------------------------------
# the rules: each takes (layout, settings) and returns a list of findings


def _point(layout: Layout, i: int, code: str, message: str, fix: str | None = None) -> Finding:
    return RULES.finding(
        code,
        message,
        actuator=layout.name_of(int(layout.owner[i])),
        stitch_index=int(layout.index[i]),
        xy_mm=layout.xy_mm[i],
        fix=fix,
    )


def _capped(findings: list[Finding], limit: int) -> list[Finding]:
    if len(findings) <= limit:
        return findings
    rest = findings[limit:]
    more = RULES.finding(
        rest[0].code,
        f"{len(rest)} more findings of this rule, from stitch {rest[0].stitch_index} on",
        actuator=rest[0].actuator,
        stitch_index=rest[0].stitch_index,
        xy_mm=rest[0].xy_mm,
        fix=rest[0].fix,
    )
    return findings[:limit] + [more]


def _displacements(layout: Layout) -> np.ndarray:
    d = np.zeros_like(layout.xy_mm)
    d[1:] = np.diff(layout.xy_mm, axis=0)
    return d


def _needle_corridor(layout: Layout, settings: RuleSettings) -> list[Finding]:
    needles = np.flatnonzero(layout.commands == Command.STITCH)
    out = []
    for k, tube in enumerate(layout.tubes):
        if len(needles) == 0:
            break
        hit, dist = _PathIndex(tube.extended_path()).within(
            layout.xy_mm[needles], tube.corridor_radius_mm - settings.tolerances.length_mm
        )
        for j, dj in zip(hit, dist):
            i = needles[j]
            out.append(
                _point(
                    layout,
                    i,
                    "EA101",
                    f"needle point {dj:.2f} mm from the tube axis of {tube.name}, inside its "
                    f"{tube.corridor_radius_mm:.2f} mm corridor (r_f {tube.outer_radius_mm:g} + clearance "
                    f"{tube.clearance_mm:g})",
                )
            )
    out.sort(key=lambda f: f.stitch_index)
    return out


def _record_limit(layout: Layout, settings: RuleSettings) -> list[Finding]:
    lim = format_limit(settings.format)
    d = np.abs(_displacements(layout))
    over = (layout.commands == Command.STITCH) & (d.max(axis=1) > lim.max_record_mm + settings.tolerances.length_mm)
    return [
        _point(
            layout,
            i,
            "EA102",
            f"stitch moves |dx| {d[i, 0]:.2f} mm, |dy| {d[i, 1]:.2f} mm; {lim.name.upper()} allows "
            f"{lim.max_record_mm:g} mm per axis in one record",
        )
        for i in np.flatnonzero(over)
    ]


def _stitch_lengths(layout: Layout) -> tuple[np.ndarray, np.ndarray]:
    d = _displacements(layout)
    length = np.hypot(d[:, 0], d[:, 1])
    stitch = layout.commands == Command.STITCH
    consecutive = stitch & np.concatenate([[False], stitch[:-1]])
    return length, consecutive


def _machine_max(layout: Layout, settings: RuleSettings) -> list[Finding]:
    length, _ = _stitch_lengths(layout)
    over = (layout.commands == Command.STITCH) & (length > settings.max_stitch_mm + settings.tolerances.length_mm)
    over[:1] = False
    return [
        _point(layout, i, "EA103", f"stitch {length[i]:.2f} mm long, machine maximum {settings.max_stitch_mm:g} mm")
        for i in np.flatnonzero(over)
    ]


def _too_short(layout: Layout, settings: RuleSettings) -> list[Finding]:
    length, consecutive = _stitch_lengths(layout)
    short = consecutive & (length < settings.min_stitch_mm - settings.tolerances.length_mm)
    return [
        _point(layout, i, "EA104", f"stitch {length[i]:.2f} mm long, machine minimum {settings.min_stitch_mm:g} mm")
        for i in np.flatnonzero(short)
    ]


def _density(layout: Layout, settings: RuleSettings, code: str) -> list[Finding]:
    needles = np.flatnonzero(layout.commands == Command.STITCH)
    count = needle_density(layout.xy_mm[needles], settings.density_radius_mm)
    error = count >= settings.density_error_count
    hit = error if code == "EA106" else (count >= settings.density_warning_count) & ~error
    return [
        _point(
            layout,
            needles[j],
            code,
            f"{count[j]} needle points within {settings.density_radius_mm:g} mm (this one included); "
            f"limit {(settings.density_error_count if code == 'EA106' else settings.density_warning_count) - 1}",
        )
        for j in np.flatnonzero(hit)
    ]


def _density_warning(layout: Layout, settings: RuleSettings) -> list[Finding]:
    return _density(layout, settings, "EA105")


def _density_error(layout: Layout, settings: RuleSettings) -> list[Finding]:
    return _density(layout, settings, "EA106")


def _first_owned_needle(layout: Layout, k: int) -> int | None:
    idx = np.flatnonzero((layout.owner == k) & (layout.commands == Command.STITCH))
    return int(idx[0]) if len(idx) else None


def _tube_finding(layout: Layout, k: int, code: str, message: str, xy=None) -> Finding:
    i = _first_owned_needle(layout, k)
    if xy is None and i is not None:
        xy = layout.xy_mm[i]
    return RULES.finding(
        code,
        message,
        actuator=layout.tubes[k].name,
        stitch_index=None if i is None else int(layout.index[i]),
        xy_mm=xy,
    )


def _sleeve(layout: Layout, settings: RuleSettings) -> list[Finding]:
    out = []
    for k, tube in enumerate(layout.tubes):
        if tube.half_width_mm is None:
            continue
        w = 2.0 * tube.half_width_mm
        r0 = float(sleeve_radius_mm(w, tube.outer_radius_mm))
        gap = r0 - tube.outer_radius_mm
        if gap <= 0.0:
            out.append(
                _tube_finding(
                    layout, k, "EA201",
                    f"width {w:.2f} mm gives sleeve radius r0 {r0:.3f} mm <= tube radius r_f "
                    f"{tube.outer_radius_mm:g} mm (needs w > {float(min_sleeve_width_mm(tube.outer_radius_mm)):.2f} mm)",
                )
            )
        elif gap < settings.min_sleeve_gap_mm:
            out.append(
                _tube_finding(
                    layout, k, "EA202",
                    f"sleeve radius r0 {r0:.3f} mm exceeds r_f {tube.outer_radius_mm:g} mm by only {gap:.3f} mm "
                    f"(< {settings.min_sleeve_gap_mm:g} mm)",
                )
            )
    return out


def _interval(layout: Layout, settings: RuleSettings) -> list[Finding]:
    """Gaps between neighbouring leg crossings of each tube axis larger than 2 r_f."""
    _, consecutive = _stitch_lengths(layout)
    out = []
    for k, tube in enumerate(layout.tubes):
        legs = np.flatnonzero(consecutive & (layout.owner == k) & np.concatenate([[False], layout.owner[:-1] == k]))
        if len(legs) == 0:
            continue
        leg, sc = _PathIndex(tube.path).crossings(layout.xy_mm[legs - 1], layout.xy_mm[legs])
        if len(sc) < 2:
            continue
        order = np.argsort(sc, kind="stable")
        gaps = np.diff(sc[order])
        limit = 2.0 * tube.outer_radius_mm
        for g in np.flatnonzero(gaps > limit + settings.tolerances.length_mm):
            i = legs[leg[order[g + 1]]]
            out.append(
                _point(
                    layout, i, "EA203",
                    f"legs cross the tube of {tube.name} {gaps[g]:.2f} mm apart along its axis, more than the tube "
                    f"diameter {limit:g} mm",
                )
            )
    out.sort(key=lambda f: f.stitch_index)
    return out


def _turning(layout: Layout, settings: RuleSettings) -> list[Finding]:
    out = []
    for k, tube in enumerate(layout.tubes):
        cl = tube.centerline
        if cl is None:
            continue  # a path that crosses itself: EA302 reports it
        r_min = settings.turning_radius_factor * 2.0 * tube.outer_radius_mm
        radius = cl.min_radius_mm()
        if radius >= r_min - settings.tolerances.length_mm:
            continue
        pts = cl.points_mm
        kappa = np.abs(cl.segment_curvature())
        worst = pts[1 + int(np.argmax(kappa[1:] + kappa[:-1]))] if len(kappa) > 1 else pts[0]
        kind = "a corner (turn > %g deg)" % MAX_SMOOTH_TURN_DEG if radius == 0.0 else f"radius {radius:.2f} mm"
        out.append(
            _tube_finding(
                layout, k, "EA301",
                f"the tube of {tube.name} turns with {kind}; minimum turning radius {r_min:g} mm "
                f"({settings.turning_radius_factor:g} x outer diameter)",
                xy=worst,
            )
        )
    return out


def _self_intersection(layout: Layout, settings: RuleSettings) -> list[Finding]:
    out = []
    for k, tube in enumerate(layout.tubes):
        xy = np.asarray(tube.path.coords, dtype=np.float64)[:, :2]
        closed = np.hypot(*(xy[-1] - xy[0])) <= settings.tolerances.length_mm
        if shapely.is_simple(tube.path) and not closed:
            continue
        segs = shapely.linestrings(np.stack([xy[:-1], xy[1:]], axis=1))
        i, j = shapely.STRtree(segs).query(segs, predicate="intersects")
        keep = (j > i + 1) & ~(closed & (i == 0) & (j == len(segs) - 1))
        where = xy[0]
        if np.any(keep):
            where = shapely.get_coordinates(shapely.intersection(segs[i[keep][0]], segs[j[keep][0]]))[0]
        what = f"crosses itself {np.count_nonzero(keep)} time(s)" if np.any(keep) else "is closed (a tube has two ends)"
        out.append(
            _tube_finding(
                layout, k, "EA302",
                f"the tube path of {tube.name} {what}, first at ({where[0]:.2f}, {where[1]:.2f}) mm",
                xy=where,
            )
        )
    return out


def _pairs(layout: Layout, settings: RuleSettings) -> list[Finding]:
    """EA303 and EA304: every pair of tubes."""
    out = []
    tubes = layout.tubes
    extended = [t.extended_path() for t in tubes]
    for a in range(len(tubes)):
        for b in range(a + 1, len(tubes)):
            ta, tb = tubes[a], tubes[b]
            pa, pb = extended[a], extended[b]
            gap = float(shapely.distance(pa, pb))
            where = shapely.get_coordinates(shapely.shortest_line(pa, pb))[0]
            need = ta.corridor_radius_mm + tb.corridor_radius_mm
            if gap < need - settings.tolerances.length_mm:
                out.append(
                    _tube_finding(
                        layout, b, "EA303",
                        f"the tubes of {ta.name} and {tb.name} are {gap:.2f} mm apart (axis to axis); their corridors "
                        f"need {need:.2f} mm",
                        xy=where,
                    )
                )
                continue
            if ta.half_width_mm is None or tb.half_width_mm is None:
                continue
            band_gap = float(shapely.distance(ta.path, tb.path)) - ta.half_width_mm - tb.half_width_mm
            if band_gap < settings.actuator_clearance_mm - settings.tolerances.length_mm:
                out.append(
                    _tube_finding(
                        layout, b, "EA304",
                        f"stitched bands of {ta.name} and {tb.name} are {band_gap:.2f} mm apart, clearance "
                        f"{settings.actuator_clearance_mm:g} mm",
                        xy=where,
                    )
                )
    return out


def _hoop_window(layout: Layout, settings: RuleSettings):
    if settings.hoop_width_mm is None or settings.hoop_height_mm is None or len(layout) == 0:
        return None
    lo, hi = layout.xy_mm.min(axis=0), layout.xy_mm.max(axis=0)
    centre = (lo + hi) / 2.0
    half = np.array([settings.hoop_width_mm, settings.hoop_height_mm]) / 2.0
    return centre - half, centre + half


def _end_margins(layout: Layout, settings: RuleSettings) -> list[Finding]:
    window = _hoop_window(layout, settings)
    if window is None:
        return []
    lo, hi = window
    out = []
    for k, tube in enumerate(layout.tubes):
        if tube.end_margin_mm <= 0.0:
            continue
        ends = np.asarray(tube.extended_path().coords)[[0, -1]]
        for end, label in zip(ends, ("start", "end")):
            if np.any(end < lo - settings.tolerances.length_mm) or np.any(end > hi + settings.tolerances.length_mm):
                out.append(
                    _tube_finding(
                        layout, k, "EA305",
                        f"the {tube.end_margin_mm:g} mm free tube beyond the {label} of {tube.name} reaches "
                        f"({end[0]:.1f}, {end[1]:.1f}) mm, outside the {settings.hoop_width_mm:g} x "
                        f"{settings.hoop_height_mm:g} mm hoop",
                        xy=end,
                    )
                )
    return out


def _hoop(layout: Layout, settings: RuleSettings) -> list[Finding]:
    window = _hoop_window(layout, settings)
    if window is None:
        return []
    lo, hi = window
    tol = settings.tolerances.length_mm
    outside = np.any((layout.xy_mm < lo - tol) | (layout.xy_mm > hi + tol), axis=1)
    if not np.any(outside):
        return []
    size = layout.xy_mm.max(axis=0) - layout.xy_mm.min(axis=0)
    return [
        _point(
            layout, i, "EA306",
            f"{Command(int(layout.commands[i])).name.lower()} record outside the {settings.hoop_width_mm:g} x "
            f"{settings.hoop_height_mm:g} mm hoop; the design spans {size[0]:.1f} x {size[1]:.1f} mm",
        )
        for i in np.flatnonzero(outside)
    ]


def _jump_records(layout: Layout, settings: RuleSettings) -> np.ndarray:
    """Machine records each record becomes (jumps split at the format's jump limit)."""
    d = np.abs(_displacements(layout)).max(axis=1)
    lim = format_limit(settings.format).max_jump_mm
    n = np.ones(len(layout), dtype=np.int64)
    jump = layout.commands == Command.JUMP
    n[jump] = np.maximum(1, np.ceil(d[jump] / lim - settings.tolerances.length_mm)).astype(np.int64)
    trim = layout.commands == Command.TRIM
    if settings.format in _TRIM_AS_JUMPS:
        n[trim] = settings.trim_jump_count
    return n


def _jump_runs(layout: Layout, settings: RuleSettings) -> list[Finding]:
    jump = layout.commands == Command.JUMP
    if not np.any(jump):
        return []
    edges = np.diff(np.concatenate([[0], jump.astype(np.int8), [0]]))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    records = _jump_records(layout, settings)
    d = _displacements(layout)
    out = []
    for a, b in zip(starts, stops):
        if a == 0 or layout.commands[a - 1] != Command.STITCH:
            continue  # after a trim, stop or at the start a trim does no harm
        n = int(records[a:b].sum())
        if n < settings.trim_jump_count:
            continue
        net = np.cumsum(d[a:b], axis=0)
        if np.any(np.all(np.abs(net[1:]) <= settings.tolerances.length_mm, axis=1)):
            continue  # the run starts with jumps that net to zero: a trim written as jumps
        out.append(
            _point(
                layout, a, "EA501",
                f"{n} consecutive jump records after a stitch; the machine cuts the thread after "
                f"{settings.trim_jump_count}",
            )
        )
    return out


def _stops(layout: Layout, settings: RuleSettings) -> list[Finding]:
    """EA502 (missing stop between tubes) and EA503 (stop inside one tube's stitches).

    Needle records that do not move (a zero-length stitch, e.g. the needle-down some
    writers put at a colour change) lay no thread across a tube and are ignored.
    """
    d = _displacements(layout)
    moves = np.hypot(d[:, 0], d[:, 1]) > settings.tolerances.length_mm
    moves[:1] = True
    owned = np.flatnonzero((layout.commands == Command.STITCH) & (layout.owner >= 0) & moves)
    if len(owned) < 2:
        return []
    is_stop = layout.commands == Command.STOP
    stops_before = np.cumsum(is_stop)
    a, b = owned[:-1], owned[1:]
    between = stops_before[b] - stops_before[a]
    changed = layout.owner[a] != layout.owner[b]
    stop_idx = np.flatnonzero(is_stop)
    out = [
        _point(
            layout, i, "EA502",
            f"sewing moves from {layout.name_of(int(layout.owner[j]))} to {layout.name_of(int(layout.owner[i]))} "
            f"without a stop",
        )
        for j, i in zip(a[changed & (between == 0)], b[changed & (between == 0)])
    ]
    for j in a[~changed & (between > 0)]:
        s = stop_idx[np.searchsorted(stop_idx, j)]
        out.append(
            RULES.finding(
                "EA503",
                f"stop / colour change inside the stitches of {layout.name_of(int(layout.owner[j]))}",
                actuator=layout.name_of(int(layout.owner[j])),
                stitch_index=int(layout.index[s]),
                xy_mm=layout.xy_mm[s],
            )
        )
    return out


def _record_count(layout: Layout, settings: RuleSettings) -> list[Finding]:
    limit = settings.max_records or format_limit(settings.format).max_records
    n = int(_jump_records(layout, settings).sum())
    if n <= limit:
        return []
    return [RULES.finding("EA504", f"{n} machine records, limit {limit} ({settings.format.upper()})")]


_LAYOUT_RULES = (
    _needle_corridor,
    _record_limit,
    _machine_max,
    _too_short,
    _density_warning,
    _density_error,
    _sleeve,
    _interval,
    _turning,
    _self_intersection,
    _pairs,
    _end_margins,
    _hoop,
    _jump_runs,
    _stops,
    _record_count,
)


def sort_findings(findings) -> tuple[Finding, ...]:
    """Worst first, then by code and stitch index (deterministic order)."""
    return tuple(
        sorted(
            findings,
            key=lambda f: (f.severity.rank, f.code, -1 if f.stitch_index is None else f.stitch_index, f.message),
        )
    )


def check_layout(layout: Layout, settings: RuleSettings | None = None) -> tuple[Finding, ...]:
    """Run every geometric and file-level rule on a layout; findings worst first.

    Each rule lists at most ``settings.max_findings_per_rule`` findings plus one
    summary finding for the rest.
    """
    settings = settings or RuleSettings()
    found: list[Finding] = []
    for rule in _LAYOUT_RULES:
        found += _capped(rule(layout, settings), settings.max_findings_per_rule)
    return sort_findings(found)


# ---------------------------------------------------------------------------
# stitch plans


def layout_from_plan(plan: StitchPlan) -> Layout:
    """The layout of a stitch plan: tubes from its actuators, half width from the realised width."""
    tubes = tuple(
        TubeLayout(
            name=a.name,
            path=a.centerline.as_linestring(),
            outer_radius_mm=a.tube.outer_radius_mm,
            clearance_mm=a.tube.clearance_mm,
            end_margin_mm=a.tube.end_margin_mm,
            half_width_mm=a.realised.width_mm / 2.0,
            centerline=a.centerline,
        )
        for a in plan.actuators
    )
    owner = np.where(plan.actuator < len(tubes), plan.actuator, -1)
    return Layout.from_points(plan.xy_mm, plan.commands, owner, tubes=tubes)


def layout_from_records(xy_mm, commands, tubes, *, reach_mm: float = FILE_REACH_MM, index=None) -> Layout:
    """A layout for records without owners (an embroidery file): assign needle points to tubes.

    Each needle point belongs to the nearest tube closer than ``reach_mm`` (else to
    none); each tube's ``half_width_mm`` becomes the median distance of its needle
    points from its axis (the measured w/2) unless already set.

    Parameters
    ----------
    xy_mm : array (n, 2)
        Record positions [mm] in the same frame as the tube paths.
    commands : array (n,)
        :class:`Command` per record.
    tubes : sequence of TubeLayout
    reach_mm : float
        Needle points further than this from every tube belong to none [mm].
    index : array (n,), optional
        Index to report per record (default 0..n-1).
    """
    check_range("reach_mm", reach_mm, low=0.0, high=1e4)
    xy = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
    cmds = np.asarray(commands, dtype=np.int8)
    needles = np.flatnonzero(cmds == Command.STITCH)
    owner = np.full(len(xy), -1, dtype=np.int16)
    best = np.full(len(needles), np.inf)
    measured = []
    for k, tube in enumerate(tubes):
        hit, dist = _PathIndex(tube.path).nearest(xy[needles], reach_mm)
        closer = dist < best[hit]
        best[hit[closer]] = dist[closer]
        owner[needles[hit[closer]]] = k
        measured.append((hit, dist))
    out = []
    for k, (tube, (hit, dist)) in enumerate(zip(tubes, measured)):
        mine = dist[owner[needles[hit]] == k]
        if tube.half_width_mm is None and len(mine):
            tube = replace(tube, half_width_mm=float(np.median(mine)))
        out.append(tube)
    return Layout.from_points(xy, cmds, owner, tubes=out, index=index)


def _pattern_findings(plan: StitchPlan, settings: RuleSettings) -> list[Finding]:
    """EA204-EA206: realised against requested parameters, and the neutral angle."""
    tol = settings.tolerances
    out = []
    for k, act in enumerate(plan.actuators):
        legs = np.flatnonzero((plan.actuator == k) & (plan.roles == Role.LEG))
        where = dict(actuator=act.name, stitch_index=int(legs[0]) if len(legs) else None,
                     xy_mm=plan.xy_mm[legs[0]] if len(legs) else None)
        real, req = act.realised, act.params
        if isinstance(req, CrossParams):
            if abs(real.angle_deg - req.angle_deg) > tol.angle_deg:
                out.append(RULES.finding(
                    "EA204",
                    f"leg angle {real.angle_deg:.2f} deg realised, {req.angle_deg:g} deg requested "
                    f"(tolerance {tol.angle_deg:g} deg)", **where))
            neutral = float(neutral_angle_deg(real.width_mm, act.tube.outer_radius_mm))
            if abs(real.angle_deg - neutral) < settings.neutral_band_deg:
                out.append(RULES.finding(
                    "EA206",
                    f"angle {real.angle_deg:.2f} deg is {abs(real.angle_deg - neutral):.2f} deg from the neutral "
                    f"angle {neutral:.2f} deg (band {settings.neutral_band_deg:g} deg)", **where))
        rel = abs(real.interval_mm - req.interval_mm) / req.interval_mm
        if rel > tol.spacing_rel:
            out.append(RULES.finding(
                "EA205",
                f"stitch interval {real.interval_mm:.3f} mm realised, {req.interval_mm:g} mm requested "
                f"({rel * 100:.1f} % off, tolerance {tol.spacing_rel * 100:g} %)", **where))
    return out


def check_plan(plan: StitchPlan, settings: RuleSettings | None = None) -> tuple[Finding, ...]:
    """Every geometric, pattern and file-level rule on a stitch plan; findings worst first."""
    settings = settings or RuleSettings()
    found = list(check_layout(layout_from_plan(plan), settings))
    found += _pattern_findings(plan, settings)
    return sort_findings(found)
