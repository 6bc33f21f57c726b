"""Spatial queries that stay linear in the design's size: points and legs against tubes, close pairs.

* :class:`TubeIndex`: every tube's axis segments in one shapely STRtree, so points
  near any tube, the nearest tube of each point and the legs crossing any tube
  are found with one bounded query each, whatever the number of tubes.
* :class:`SegmentIndex`: the nearest segment of one long path for many points, by
  buckets (linear in path length and points; one index per path).
* :func:`needle_density`: needle points within a radius of each point, by a grid
  of buckets one radius wide (numpy only: no scipy import for a few hundred or a
  few hundred thousand points).
* :func:`self_crossings`: where a polyline meets itself, for the path check of
  the generators and the design rule EA302.
* :func:`corridor_hits`: needle points inside a tube corridor, for the generators'
  invariant and the design rule EA101.

Examples
--------
>>> import numpy as np
>>> idx = TubeIndex([[(0, 0), (10, 0)], [(0, 5), (10, 5)]])
>>> point, tube, dist = idx.within([(5, 1), (5, 4.5), (5, 20)], [2.0, 2.0])
>>> point.tolist(), tube.tolist(), dist.tolist()
([0, 1], [0, 1], [1.0, 0.5])
>>> needle_density([(0, 0), (0.3, 0), (0.6, 0), (5, 5)]).tolist()
[2, 3, 2, 1]
"""
from __future__ import annotations

import math

import numpy as np
import shapely

from .base.arrays import median
from .base.tolerances import DEFAULT_TOLERANCES

__all__ = ["TubeIndex", "SegmentIndex", "Crossings", "needle_density", "self_crossings", "corridor_hits"]

#: Candidate pairs examined at once by :func:`needle_density` and :class:`SegmentIndex` (bounds their memory).
_PAIR_CHUNK = 2_000_000
#: Factor between the cell sizes of :class:`SegmentIndex`'s successive passes.
_CELL_GROWTH = 4.0
#: :meth:`SegmentIndex.nearest` on more points than this first finds the nearest segments of that many of
#: them (evenly spaced) and starts at a cell size of the margin times the quantile of their distances.
_SAMPLE_POINTS, _SAMPLE_QUANTILE, _SAMPLE_MARGIN = 256, 0.9, 1.05


class Crossings:
    """Where straight legs cross tube axes (one row per leg-tube crossing).

    Attributes
    ----------
    leg : ndarray of int64
        Index of the leg (into the arrays given to :meth:`TubeIndex.crossings`).
    tube : ndarray of int64
        Index of the tube crossed.
    s_mm : ndarray of float
        Arc length along that tube's axis where the leg crosses it [mm].
    cot : ndarray of float
        |cot| of the angle between leg and axis at the crossing (0: the leg is
        perpendicular to the axis).
    along_mm : ndarray of float
        Length of the leg's projection on the axis direction there [mm].

    Rows are sorted by tube, then arc length, then leg.

    Examples
    --------
    >>> c = TubeIndex([[(0, 0), (10, 0)]]).crossings([(2, -3), (5, -3)], [(2, 3), (8, 3)])
    >>> len(c), c.s_mm.tolist(), c.cot.tolist(), c.along_mm.tolist()
    (2, [2.0, 6.5], [0.0, 0.5], [0.0, 3.0])
    """

    __slots__ = ("leg", "tube", "s_mm", "cot", "along_mm")

    def __init__(self, leg, tube, s_mm, cot, along_mm) -> None:
        self.leg, self.tube, self.s_mm, self.cot, self.along_mm = leg, tube, s_mm, cot, along_mm

    def __len__(self) -> int:
        return len(self.leg)


class TubeIndex:
    """Points and legs against the axes of many tubes, through one STRtree of all their segments.

    Parameters
    ----------
    paths : sequence of shapely.LineString or (n, 2) arrays
        Tube axes [mm].

    Examples
    --------
    >>> idx = TubeIndex([[(0, 0), (10, 0)], [(0, 20), (10, 20)]])
    >>> [a.tolist() for a in idx.nearest([(5, 1), (5, 18), (5, 50)], 5.0)]
    [[0, 1], [0, 1], [1.0, 2.0]]
    """

    __slots__ = ("_a", "_d", "_len", "_s", "_tube", "_tree", "queries")

    def __init__(self, paths) -> None:
        a, d, tube, s = [], [], [], []
        for k, path in enumerate(paths):
            xy = np.asarray(path.coords if isinstance(path, shapely.LineString) else path, dtype=np.float64)[:, :2]
            dk = np.diff(xy, axis=0)
            keep = np.hypot(dk[:, 0], dk[:, 1]) > 0.0
            lk = np.hypot(dk[keep, 0], dk[keep, 1])
            a.append(xy[:-1][keep])
            d.append(dk[keep])
            tube.append(np.full(len(lk), k, dtype=np.int64))
            s.append(np.concatenate([[0.0], np.cumsum(lk)[:-1]]))
        empty = np.zeros((0, 2))
        self._a = np.concatenate(a) if a else empty
        self._d = np.concatenate(d) if d else empty
        self._len = np.hypot(self._d[:, 0], self._d[:, 1])
        self._s = np.concatenate(s) if s else np.zeros(0)
        self._tube = np.concatenate(tube) if tube else np.zeros(0, dtype=np.int64)
        self._tree = shapely.STRtree(shapely.linestrings(np.stack([self._a, self._a + self._d], axis=1)))
        self.queries = 0  # tree queries made (each one bounded; the tests count them)

    def within(self, xy_mm, radius_mm) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Point-tube pairs closer than the tube's radius: point index, tube index, distance [mm].

        Parameters
        ----------
        xy_mm : array_like (n, 2)
            Points [mm].
        radius_mm : array_like (m,)
            One radius per tube [mm].

        Returns
        -------
        point, tube : numpy.ndarray of int64
            The pairs; each appears once (its nearest segment), sorted by point, then tube.
        distance : numpy.ndarray
            Point to axis [mm].

        Examples
        --------
        >>> idx = TubeIndex([[(0, 0), (10, 0)], [(0, 2), (10, 2)]])
        >>> [a.tolist() for a in idx.within([(5, 1), (5, 5)], [1.5, 1.5])]
        [[0, 0], [0, 1], [1.0, 1.0]]
        """
        p = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
        radius = np.asarray(radius_mm, dtype=np.float64).reshape(-1)
        if len(p) == 0 or len(self._len) == 0:
            return np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
        self.queries += 1
        i, k = self._tree.query(shapely.points(p), predicate="dwithin", distance=float(radius.max()))
        r = p[i] - self._a[k]
        t = np.clip(np.einsum("ij,ij->i", r, self._d[k]) / self._len[k] ** 2, 0.0, 1.0)
        dist = np.hypot(*(r - t[:, None] * self._d[k]).T)
        tube = self._tube[k]
        close = dist < radius[tube]
        i, tube, dist = i[close], tube[close], dist[close]
        order = np.lexsort((dist, tube, i))
        i, tube, dist = i[order], tube[order], dist[order]
        first = np.ones(len(i), dtype=bool)
        first[1:] = (np.diff(i) != 0) | (np.diff(tube) != 0)
        return i[first], tube[first], dist[first]

    def nearest(self, xy_mm, max_distance_mm: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """For each point within ``max_distance_mm`` of some tube: point index, nearest tube, distance [mm].

        Parameters
        ----------
        xy_mm : array_like (n, 2)
            Points [mm].
        max_distance_mm : float
            Points further from every tube are left out [mm].

        Returns
        -------
        point, tube : numpy.ndarray of int64
            Each point near a tube, and its nearest tube.
        distance : numpy.ndarray
            Point to that tube's axis [mm].

        Examples
        --------
        >>> [a.tolist() for a in TubeIndex([[(0, 0), (10, 0)]]).nearest([(5, 3), (5, 30)], 10.0)]
        [[0], [0], [3.0]]
        """
        p = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
        if len(p) == 0 or len(self._len) == 0:
            return np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
        self.queries += 1
        (i, k), dist = self._tree.query_nearest(shapely.points(p), max_distance=max_distance_mm,
                                                return_distance=True, all_matches=False)
        return i, self._tube[k], dist

    def legs_near(self, a_mm, b_mm, radius_mm) -> np.ndarray:
        """True for each straight leg a -> b that comes within its radius of some tube's axis (``radius_mm``: one
        radius per tube; distance <= radius), by one bounded query.

        Parameters
        ----------
        a_mm, b_mm : (m, 2) arrays
            Start and end of each leg [mm].
        radius_mm : sequence of float
            One radius per tube [mm].

        Returns
        -------
        ndarray of bool (m,)

        Examples
        --------
        >>> TubeIndex([[(0, 0), (10, 0)]]).legs_near([(5, 1), (5, 3), (11, 2)], [(6, 4), (7, 9), (11.5, -2)], [1.5]).tolist()
        [True, False, True]
        """
        a = np.asarray(a_mm, dtype=np.float64).reshape(-1, 2)
        b = np.asarray(b_mm, dtype=np.float64).reshape(-1, 2)
        radius = np.asarray(radius_mm, dtype=np.float64).reshape(-1)
        out = np.zeros(len(a), dtype=bool)
        if len(a) == 0 or len(self._len) == 0:
            return out
        self.queries += 1
        lines = shapely.linestrings(np.stack([a, b], axis=1))
        j, k = self._tree.query(lines, predicate="dwithin", distance=float(radius.max()))
        axis = shapely.linestrings(np.stack([self._a[k], self._a[k] + self._d[k]], axis=1))
        out[j[shapely.distance(lines[j], axis) <= radius[self._tube[k]]]] = True
        return out

    def crossings(self, a_mm, b_mm) -> Crossings:
        """Where straight legs a -> b cross the tube axes (a leg lying along an axis does not cross it).

        Parameters
        ----------
        a_mm, b_mm : array_like (n, 2)
            Start and end of each leg [mm].

        Returns
        -------
        Crossings

        Examples
        --------
        >>> c = TubeIndex([[(0, 0), (10, 0)]]).crossings([(2, -3), (0, 0)], [(2, 3), (9, 0)])
        >>> c.leg.tolist(), c.s_mm.tolist()
        ([0], [2.0])
        """
        a = np.asarray(a_mm, dtype=np.float64).reshape(-1, 2)
        b = np.asarray(b_mm, dtype=np.float64).reshape(-1, 2)
        if len(a) == 0 or len(self._len) == 0:
            z, f = np.zeros(0, np.int64), np.zeros(0)
            return Crossings(z, z, f, f, f)
        self.queries += 1
        j, k = self._tree.query(shapely.linestrings(np.stack([a, b], axis=1)), predicate="intersects")
        e, d, r = b[j] - a[j], self._d[k], a[j] - self._a[k]
        cross = e[:, 0] * d[:, 1] - e[:, 1] * d[:, 0]
        ok = cross != 0.0
        j, k, e, d, r, cross = j[ok], k[ok], e[ok], d[ok], r[ok], cross[ok]
        t = np.clip((e[:, 0] * r[:, 1] - e[:, 1] * r[:, 0]) / cross, 0.0, 1.0)
        dot = np.abs(np.einsum("ij,ij->i", e, d))
        s_mm, tube = self._s[k] + t * self._len[k], self._tube[k]
        order = np.lexsort((j, s_mm, tube))
        return Crossings(j[order], tube[order], s_mm[order], (dot / np.abs(cross))[order],
                         (dot / self._len[k])[order])


class SegmentIndex:
    """The nearest segment of one polyline for many points, in time linear in points and segments.

    Buckets of one cell size ``c`` hold every segment whose bounding box meets them; a point's
    candidates are the segments of its cell and the eight around it, which hold every segment
    within ``c`` of it. :meth:`nearest` starts at a cell size just above the distance of most of
    an even sample of the points (at least the longest segment, and twice the median one: the
    fewest candidates that still find them), asks the points left over again on buckets 4x
    coarser, and the few far from the whole path by one STRtree (shapely's nearest query alone
    grows faster than linearly on long paths: 13 us per point on 1,000 segments, 170 us on
    100,000). :meth:`within` needs one pass at the cell size of its radius. Cell sizes are
    rounded up to quarter octaves, and each size's buckets are made once per index.

    Parameters
    ----------
    xy_mm : (n, 2) array
        Polyline vertices [mm], n >= 2 (zero-length segments allowed).

    Examples
    --------
    >>> idx = SegmentIndex([(0, 0), (10, 0), (10, 10)])
    >>> idx.nearest(np.array([(5.0, 1.0), (11.0, 8.0), (500.0, 3.0)])).tolist()
    [0, 1, 1]
    >>> idx.within(np.array([(5.0, 1.0), (11.0, 8.0), (500.0, 3.0)]), 1.5).tolist()
    [0, 1]
    """

    __slots__ = ("_a", "_d", "_len2", "_start_mm", "_c0", "_span", "_grids", "_tree")

    def __init__(self, xy_mm) -> None:
        xy = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
        self._a, self._d = xy[:-1], np.diff(xy, axis=0)
        self._len2 = np.einsum("ij,ij->i", self._d, self._d)
        length = np.sqrt(self._len2)
        self._start_mm = np.concatenate([[0.0], np.cumsum(length)])
        self._c0 = max(float(length.max()), 2.0 * median(length), 1e-9)
        self._span = float(np.ptp(xy, axis=0).max())
        self._grids: dict[float, tuple] = {}
        self._tree: shapely.STRtree | None = None

    def _grid(self, c: float):
        """Buckets of cell size ``c``: (cell offset, row width, sorted cell keys, segment per key)."""
        if c not in self._grids:
            a, b = self._a, self._a + self._d
            lo = np.floor(np.minimum(a, b) / c).astype(np.int64)
            hi = np.floor(np.maximum(a, b) / c).astype(np.int64)
            base = lo.min(axis=0) - 1
            width = int(hi[:, 1].max() - base[1]) + 3
            seg = np.arange(len(a))
            parts = []
            for dx in (0, 1):
                for dy in (0, 1):
                    m = (lo[:, 0] + dx <= hi[:, 0]) & (lo[:, 1] + dy <= hi[:, 1])
                    parts.append(((lo[m, 0] + dx - base[0]) * width + (lo[m, 1] + dy - base[1]), seg[m]))
            keys, owners = np.concatenate([k for k, _ in parts]), np.concatenate([o for _, o in parts])
            order = np.argsort(keys, kind="stable")
            self._grids[c] = (base, width, keys[order], owners[order])
        return self._grids[c]

    def _cell(self, size_mm: float) -> float:
        """The bucket size for ``size_mm``: at least the first one, rounded up to a quarter octave above it."""
        if size_mm <= self._c0:
            return self._c0
        return self._c0 * 2.0 ** (math.ceil(4.0 * math.log2(size_mm / self._c0) - 1e-9) / 4.0)

    def nearest(self, p: np.ndarray) -> np.ndarray:
        """Index of the nearest segment to each point of ``p``.

        Parameters
        ----------
        p : numpy.ndarray, shape (m, 2)
            Points [mm].

        Returns
        -------
        numpy.ndarray of int64, shape (m,)
            Segment i runs from vertex i to i + 1; a tie gives either segment.

        Examples
        --------
        >>> SegmentIndex([(0, 0), (10, 0), (10, 10)]).nearest(np.array([(9.0, 5.0)])).tolist()
        [1]
        """
        out = np.full(len(p), -1, dtype=np.int64)
        todo = np.arange(len(p))
        c = self._c0
        if len(p) > _SAMPLE_POINTS:  # start where most points are found (the sample's own search is small)
            sample = p[np.linspace(0, len(p) - 1, _SAMPLE_POINTS).astype(np.int64)]
            d = self.distance(sample, self.nearest(sample))
            c = self._cell(_SAMPLE_MARGIN * float(np.quantile(d, _SAMPLE_QUANTILE)))
        while todo.size and c <= 4.0 * self._span + self._c0:
            seg, d2 = self._pass(p[todo], c)
            found = (seg >= 0) & (d2 <= c * c)
            out[todo[found]] = seg[found]
            todo = todo[~found]
            c *= _CELL_GROWTH
        if todo.size:  # far from the path: the tree
            tree = self._tree
            if tree is None:
                tree = self._tree = shapely.STRtree(shapely.linestrings(np.stack([self._a, self._a + self._d], axis=1)))
            _, k = tree.query_nearest(shapely.points(p[todo]), all_matches=False)
            out[todo] = k
        return out

    def distance(self, p: np.ndarray, seg: np.ndarray) -> np.ndarray:
        """Distance [mm] of each point of ``p`` from its segment ``seg`` (as :meth:`nearest` returns them).

        Parameters
        ----------
        p : numpy.ndarray, shape (m, 2)
            Points [mm].
        seg : numpy.ndarray of int, shape (m,)
            A segment per point.

        Returns
        -------
        numpy.ndarray, shape (m,)
            Distances [mm].

        Examples
        --------
        >>> SegmentIndex([(0, 0), (10, 0), (10, 10)]).distance(np.array([(5.0, 3.0)]), np.array([1])).tolist()
        [5.0]
        """
        r = p - self._a[seg]
        dd = self._d[seg]
        return np.hypot(*(r - _along(r, dd, self._len2[seg])[:, None] * dd).T)

    @property
    def length_mm(self) -> float:
        """The polyline's length [mm] (the sum :meth:`locate` measures along)."""
        return float(self._start_mm[-1])

    def locate(self, p: np.ndarray) -> np.ndarray:
        """Arc length [mm] along the polyline of the nearest point to each of ``p`` ((m, 2) [mm]), as shapely's
        ``line_locate_point`` gives it (in time linear in points and segments; shapely's grows with their product).

        Parameters
        ----------
        p : (m, 2) array
            Points [mm].

        Returns
        -------
        ndarray (m,)
            Arc length from the first vertex [mm], in [0, :attr:`length_mm`].

        Examples
        --------
        >>> SegmentIndex([(0, 0), (10, 0), (10, 10)]).locate(np.array([(5.0, 1.0), (12.0, 4.0), (-3.0, 0.0)])).tolist()
        [5.0, 14.0, 0.0]
        """
        seg = self.nearest(p)
        return self._start_mm[seg] + _along(p - self._a[seg], self._d[seg], self._len2[seg]) * np.sqrt(self._len2[seg])

    def within(self, p: np.ndarray, radius_mm: float) -> np.ndarray:
        """Indices of the points of ``p`` closer than ``radius_mm`` to the polyline, ascending
        (one pass over the buckets of that size).

        Parameters
        ----------
        p : numpy.ndarray, shape (m, 2)
            Points [mm].
        radius_mm : float
            Corridor radius [mm].

        Returns
        -------
        numpy.ndarray of int64

        Examples
        --------
        >>> SegmentIndex([(0, 0), (10, 0), (10, 10)]).within(np.array([(5.0, 1.0), (5.0, 3.0), (9.5, 8.0)]), 2.0).tolist()
        [0, 2]
        """
        seg, d2 = self._pass(p, self._cell(radius_mm))
        hit = np.flatnonzero(seg >= 0)
        return hit[self.distance(p[hit], seg[hit]) < radius_mm]

    def _pass(self, p, c):
        """(nearest segment among the 3 x 3 cells around each point or -1, its squared distance), in chunks."""
        base, width, keys, owners = self._grid(c)
        cell = np.floor(p / c).astype(np.int64) - base
        column = (cell[:, 0:1] + np.array([-1, 0, 1])) * width + cell[:, 1:2]  # 3 cells above each other: a key range
        lo = np.searchsorted(keys, column - 1, side="left").ravel()
        hi = np.searchsorted(keys, column + 1, side="right").ravel()
        size = hi - lo
        per_point = size.reshape(-1, 3).sum(axis=1)
        best = np.full(len(p), -1, dtype=np.int64)
        best_d2 = np.full(len(p), np.inf)
        ends = np.cumsum(per_point)
        start = 0
        while start < len(p):
            stop = max(start + 1, int(np.searchsorted(ends, ends[start] - per_point[start] + _PAIR_CHUNK,
                                                       side="right")))
            sz = size[3 * start:3 * stop]
            owner = np.repeat(np.repeat(np.arange(start, stop), 3), sz)
            offs = np.cumsum(sz) - sz
            idx = np.repeat(lo[3 * start:3 * stop] - offs, sz) + np.arange(int(sz.sum()))
            seg = owners[idx]
            r = p[owner] - self._a[seg]
            dd = self._d[seg]
            r -= _along(r, dd, self._len2[seg])[:, None] * dd
            d2 = np.einsum("ij,ij->i", r, r)
            counts = per_point[start:stop]
            has = counts > 0
            if owner.size:
                group = (np.cumsum(counts) - counts)[has]
                low = np.minimum.reduceat(d2, group)
                pos = np.flatnonzero(d2 == np.repeat(low, counts[has]))
                pick = pos[np.r_[True, owner[pos][1:] != owner[pos][:-1]]]  # the first minimum of each point
                best[owner[pick]] = seg[pick]
                best_d2[owner[pick]] = d2[pick]
            start = stop
        return best, best_d2


def needle_density(xy_mm, radius_mm: float = 0.5) -> np.ndarray:
    """Needle points within ``radius_mm`` (``<=``) of each point, the point itself included.

    Ink/Stitch's density map counts the same way (a KD-tree ball query). Here the
    points go into square buckets one radius wide; each point is compared with the
    points of its own and the 8 neighbouring buckets only (numpy, in chunks), so
    the work grows with the number of points times their local density. Coincident
    points are counted once with their multiplicity, so points on a machine grid (0.1 mm:
    at most about 80 positions within 0.5 mm) cost the same however many are piled on
    one spot (a mutated file with 10^5 stitches in one place).

    Parameters
    ----------
    xy_mm : array_like (n, 2)
        Needle points [mm].
    radius_mm : float, optional
        Radius of the count [mm].

    Returns
    -------
    numpy.ndarray of int64, shape (n,)

    Examples
    --------
    >>> needle_density([(0, 0), (0.3, 0.4), (5, 5)], 0.5).tolist()  # 0.5 mm apart exactly: counted
    [2, 2, 1]
    """
    xy_all = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
    if len(xy_all) == 0:
        return np.zeros(0, dtype=np.int64)
    xy, where, weight = np.unique(xy_all, axis=0, return_inverse=True, return_counts=True)
    n = len(xy)
    cell = np.floor((xy - xy.min(axis=0)) / radius_mm).astype(np.int64)
    rows = int(cell[:, 1].max()) + 3  # an empty row of buckets on each side: neighbour keys never wrap
    key = (cell[:, 0] + 1) * rows + (cell[:, 1] + 1)
    order = np.argsort(key, kind="stable")
    key, pts, w = key[order], xy[order], weight[order]  # sorted by bucket: 3 buckets above each other are one range
    count = np.zeros(n, dtype=np.int64)
    for dx in (-1, 0, 1):
        lo = np.searchsorted(key, key + dx * rows - 1, side="left")
        hi = np.searchsorted(key, key + dx * rows + 1, side="right")
        _count_close(pts, w, lo, hi, radius_mm, count)
    out = np.empty(n, dtype=np.int64)
    out[order] = count
    return out[where.reshape(-1)]


def _count_close(xy, weight, lo, hi, radius_mm, count) -> None:
    """Add to ``count[i]`` the weights of the points ``xy[lo[i]:hi[i]]`` within ``radius_mm`` of point i
    (in chunks)."""
    sizes = hi - lo
    ends = np.cumsum(sizes)
    start = 0
    while start < len(xy):
        stop = max(start + 1, int(np.searchsorted(ends, ends[start] - sizes[start] + _PAIR_CHUNK, side="right")))
        size = sizes[start:stop]
        owner = np.repeat(np.arange(start, stop), size)
        other = np.repeat(lo[start:stop] - (np.cumsum(size) - size), size) + np.arange(len(owner))
        d = xy[owner] - xy[other]
        close = np.hypot(d[:, 0], d[:, 1]) <= radius_mm
        count += np.bincount(owner[close], weights=weight[other[close]], minlength=len(xy)).astype(np.int64)
        start = stop


def self_crossings(xy_mm) -> tuple[np.ndarray, np.ndarray | None]:
    """Pairs of segments of a polyline that meet other than at their shared joint, and where the first meets.

    Neighbouring segments count only when they overlap (the path doubles back on
    itself); a closed polyline (last point on the first) does not count its closing joint.

    Parameters
    ----------
    xy_mm : array_like (n, 2)
        Polyline vertices [mm].

    Returns
    -------
    pairs : ndarray (m, 2) of int64
        Segment indices ``(i, j)``, ``i < j``, sorted; segment i runs from point i to i + 1.
    first_xy : ndarray (2,) or None
        A point where the first pair meets [mm]; None when there is no pair.

    Examples
    --------
    >>> pairs, where = self_crossings([(0, 0), (10, 0), (10, 10), (5, 10), (5, -5)])
    >>> pairs.tolist(), where.tolist()
    ([[0, 3]], [5.0, 0.0])
    >>> self_crossings([(0, 0), (10, 0), (4, 0)])[0].tolist()  # doubles back
    [[0, 1]]
    """
    pts = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
    segs = shapely.linestrings(np.stack([pts[:-1], pts[1:]], axis=1))
    i, j = shapely.STRtree(segs).query(segs, predicate="intersects")
    closed = np.hypot(*(pts[-1] - pts[0])) <= DEFAULT_TOLERANCES.length_mm
    keep = (j > i + 1) & ~(closed & (i == 0) & (j == len(segs) - 1))
    near = np.flatnonzero(j == i + 1)
    keep[near[shapely.length(shapely.intersection(segs[i[near]], segs[j[near]])) > 0.0]] = True
    pairs = np.column_stack([i[keep], j[keep]]).astype(np.int64)
    if len(pairs) == 0:
        return pairs, None
    pairs = pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]
    meet = shapely.intersection(segs[pairs[0, 0]], segs[pairs[0, 1]])
    return pairs, shapely.get_coordinates(meet)[0]


def _along(r: np.ndarray, d: np.ndarray, len2: np.ndarray) -> np.ndarray:
    """Where along segments ``d`` (squared lengths ``len2``) the nearest point to each offset ``r`` from a
    segment's start lies, in [0, 1] (0 on a zero-length segment)."""
    return np.clip(np.einsum("ij,ij->i", r, d) / np.where(len2 > 0, len2, 1.0), 0.0, 1.0)


def corridor_hits(path, xy_mm, radius_mm: float) -> np.ndarray:
    """Indices of the points closer than ``radius_mm`` to ``path`` (a :class:`SegmentIndex`, a line or (n, 2)
    points), ascending.

    Parameters
    ----------
    path : shapely.LineString or array_like (n, 2)
        The axis [mm].
    xy_mm : array_like (m, 2)
        Points [mm].
    radius_mm : float
        Corridor radius [mm].

    Returns
    -------
    numpy.ndarray of int64

    Examples
    --------
    >>> corridor_hits([(0, 0), (10, 0)], [(5, 1.0), (5, 1.9), (12, 0)], 1.8).tolist()
    [0]
    """
    if not isinstance(path, SegmentIndex):
        path = SegmentIndex(shapely.get_coordinates(path) if isinstance(path, shapely.Geometry) else path)
    return path.within(np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2), radius_mm)
