"""Triangle geometry in numpy: distance of points from triangles, subdivision to an edge length.

:func:`point_triangle_distance` is the closest-point test by Voronoi regions of the
triangle (vertex, edge or face region from the barycentric signs; C. Ericson,
*Real-Time Collision Detection*, 2005, section 5.1.5), vectorised over pairs.
:func:`subdivide_to_size` bisects every edge longer than a length at one midpoint
shared by the faces on both sides (no cracks), splitting each face by how many of its
edges were cut, until no edge is longer; faces already short enough are kept. Both
replace trimesh's routines of the same job in the mesh checks and the 3D picture, so
neither needs trimesh (and with it scipy) at start-up.

Examples
--------
>>> import numpy as np
>>> from embroact.export.pictures.triangles import point_triangle_distance, subdivide_to_size
>>> tri = np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]] * 3)
>>> point_triangle_distance(tri, np.array([[0.2, 0.2, 0.5], [2.0, 0, 0], [0.5, 0.5, 0]])).round(12).tolist()
[0.5, 1.0, 0.0]
>>> v, f, parent = subdivide_to_size(tri[0], np.array([[0, 1, 2]]), 0.75)
>>> len(f), parent.tolist()
(4, [0, 0, 0, 0])
"""
from __future__ import annotations

import numpy as np

from ...patterns.base.errors import ParameterError

__all__ = ["point_triangle_distance", "subdivide_to_size"]

#: Rounds of subdivision before giving up (each halves the longest edges: 2^10 shorter).
MAX_SUBDIVISIONS = 10


def _dot(a, b):
    return np.einsum("ij,ij->i", a, b)


def point_triangle_distance(triangles, points) -> np.ndarray:
    """Distance of each point (k, 3) from its triangle (k, 3, 3) [same units].

    Parameters
    ----------
    triangles : array_like (k, 3, 3)
        Corners of each triangle.
    points : array_like (k, 3)
        One point per triangle.

    Returns
    -------
    numpy.ndarray (k,)

    Examples
    --------
    >>> tri = [[[0, 0, 0], [1, 0, 0], [0, 1, 0]]] * 2
    >>> point_triangle_distance(tri, [[0.2, 0.2, 1.0], [2.0, 0.0, 0.0]]).tolist()  # above the face; beyond a corner
    [1.0, 1.0]
    """
    tri = np.asarray(triangles, dtype=np.float64)
    p = np.asarray(points, dtype=np.float64)
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = _dot(ab, ap), _dot(ac, ap)
    bp = p - b
    d3, d4 = _dot(ab, bp), _dot(ac, bp)
    cp = p - c
    d5, d6 = _dot(ab, cp), _dot(ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        # inside the face: barycentric (1 - v - w, v, w)
        den = va + vb + vc
        v, w = vb / den, vc / den
        q = a + v[:, None] * ab + w[:, None] * ac
        # Ericson's early returns (A, B, AB, C, AC, BC, face) applied last to first, so earlier ones win
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        q = np.where(((va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0))[:, None], b + t_bc[:, None] * (c - b), q)
        t_ac = d2 / (d2 - d6)
        q = np.where(((vb <= 0) & (d2 >= 0) & (d6 <= 0))[:, None], a + t_ac[:, None] * ac, q)
        q = np.where(((d6 >= 0) & (d5 <= d6))[:, None], c, q)
        t_ab = d1 / (d1 - d3)
        q = np.where(((vc <= 0) & (d1 >= 0) & (d3 <= 0))[:, None], a + t_ab[:, None] * ab, q)
    q = np.where(((d3 >= 0) & (d4 <= d3))[:, None], b, q)
    q = np.where(((d1 <= 0) & (d2 <= 0))[:, None], a, q)
    return np.linalg.norm(p - q, axis=1)


def subdivide_to_size(vertices, faces, max_edge: float):
    """(vertices, faces, parent) with every edge at most ``max_edge``; ``parent`` is each new face's input face.

    Winding is kept. A face with one long edge becomes two, with two long edges three
    (the quadrilateral left is cut along its shorter diagonal), with three the regular
    four; faces keep their input order within each of those groups, round by round.

    Parameters
    ----------
    vertices : array_like (n, 3)
        Positions.
    faces : array_like (m, 3)
        Triangles of vertex indices.
    max_edge : float
        Longest edge allowed (same units).

    Returns
    -------
    vertices : numpy.ndarray
    faces : numpy.ndarray of int64
    parent : numpy.ndarray of int64

    Examples
    --------
    >>> v, f, parent = subdivide_to_size([[0, 0, 0], [2, 0, 0], [0, 2, 0]], [[0, 1, 2]], 1.5)
    >>> len(v), len(f), parent.tolist()
    (6, 4, [0, 0, 0, 0])
    """
    v = np.array(vertices, dtype=np.float64)
    f = np.array(faces, dtype=np.int64).reshape(-1, 3)
    parent = np.arange(len(f))
    # faces with no long edge are final (their edges are never cut): set aside, in the order they became so,
    # which is where the faces with no cut edge of each round go; only the rest is looked at again
    done: list[np.ndarray] = []
    done_parent: list[np.ndarray] = []
    for _ in range(MAX_SUBDIVISIONS + 1):
        ends = f[:, [1, 2, 0]]  # edges v0 v1, v1 v2, v2 v0, each as (lower, higher) index (a sort of the pairs: 1.7x)
        edges = np.stack([np.minimum(f, ends), np.maximum(f, ends)], axis=-1).reshape(-1, 2)
        # each edge as one integer (first * n + second sorts as the pairs do): a 1-D unique, not a row sort
        keys, inverse = np.unique(edges[:, 0] * len(v) + edges[:, 1], return_inverse=True)
        unique = np.column_stack([keys // len(v), keys % len(v)])
        long_edge = np.linalg.norm(v[unique[:, 0]] - v[unique[:, 1]], axis=1) > max_edge
        if not long_edge.any():
            return v, np.vstack(done + [f]), np.concatenate(done_parent + [parent])
        mid = np.full(len(unique), -1, dtype=np.int64)
        mid[long_edge] = len(v) + np.arange(int(long_edge.sum()))
        v = np.vstack([v, 0.5 * (v[unique[long_edge, 0]] + v[unique[long_edge, 1]])])
        face_mid = mid[inverse.reshape(-1)].reshape(-1, 3)  # edges (v0 v1, v1 v2, v2 v0)
        split = face_mid >= 0
        count = split.sum(axis=1)
        done.append(f[count == 0])
        done_parent.append(parent[count == 0])
        parts, parents = [], []
        # one cut edge, rotated to (a, b): [a, p, c], [p, b, c]
        one = count == 1
        a, b, c, p, _ = _rotated(f[one], face_mid[one], np.argmax(split[one], axis=1))
        parts.append(np.column_stack([a, p, c, p, b, c]).reshape(-1, 3))
        parents.append(np.repeat(parent[one], 2))
        # two cut edges, the uncut one rotated to (c, a): corner [p, b, q] and the quad (a, p, q, c)
        two = count == 2
        a, b, c, p, q = _rotated(f[two], face_mid[two], (np.argmin(split[two], axis=1) + 1) % 3)
        use_aq = (np.sum((v[a] - v[q]) ** 2, axis=1) <= np.sum((v[p] - v[c]) ** 2, axis=1))[:, None]
        parts += [np.column_stack([p, b, q]), np.where(use_aq, np.column_stack([a, p, q]), np.column_stack([a, p, c])),
                  np.where(use_aq, np.column_stack([a, q, c]), np.column_stack([p, q, c]))]
        parents.append(np.tile(parent[two], 3))
        # three cut edges: the regular split into four
        three = count == 3
        (v0, v1, v2), (m0, m1, m2) = f[three].T, face_mid[three].T
        parts.append(np.column_stack([v0, m0, m2, m0, v1, m1, m2, m1, v2, m0, m1, m2]).reshape(-1, 3))
        parents.append(np.repeat(parent[three], 4))
        f, parent = np.vstack(parts).astype(np.int64), np.concatenate(parents)
    raise ParameterError(f"max_edge={max_edge:g} needs more than {MAX_SUBDIVISIONS} rounds of subdivision")


def _rotated(f, face_mid, j):
    """Corners (a, b, c) of each face starting at corner j, and the midpoints of its edges a-b and b-c."""
    r = np.arange(len(j))
    return f[r, j], f[r, (j + 1) % 3], f[r, (j + 2) % 3], face_mid[r, j], face_mid[r, (j + 1) % 3]
