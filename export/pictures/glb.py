"""Binary glTF 2.0 (``.glb``) of coloured triangle meshes, in numpy alone.

A GLB file is a 12-byte header, a JSON chunk (the scene: one node and one mesh per
body, a material per colour, accessors into the buffer) and a BIN chunk (per body
its ``uint32`` triangle indices and ``float32`` positions), each chunk padded to 4
bytes (glTF 2.0 specification, section 4.4 "GLB file format"). A body that is an earlier
one of the same part moved (the same name after its last ``.``, ``tube`` in ``A7.tube``; the same
triangles and colour; every vertex displaced by one vector to within :data:`INSTANCE_TOLERANCE`
file units: identical actuators side by side) is not stored again:
its node names the earlier body's mesh with that displacement as its ``translation``, so the
file grows by a node, not a mesh, per identical actuator. Positions are
written as given (the caller converts to metres, Y up), with unit vertex normals
(:func:`vertex_normals`: the area-weighted mean of the normals of the triangles
around each vertex), so viewers shade a tube round rather than faceted. The same
meshes give the same bytes.

Writing it here rather than through trimesh keeps the default build from importing
trimesh and scipy (about 0.6 s of start-up for a file of a few lines of JSON);
pygltflib would add ~0.1 s of import and six dependencies for the same bytes.

Examples
--------
>>> import json, struct
>>> import numpy as np
>>> from embroact.export.pictures.glb import GlbMesh, glb_bytes
>>> tri = GlbMesh("t", np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float), np.array([[0, 1, 2]]),
...               (255, 0, 0, 255))
>>> data = glb_bytes([tri])
>>> data[:4], struct.unpack("<I", data[8:12])[0] == len(data), len(data) % 4
(b'glTF', True, 0)
>>> doc = json.loads(data[20:20 + struct.unpack("<I", data[12:16])[0]])
>>> doc["meshes"][0]["name"], doc["accessors"][1]["max"]
('t', [1.0, 1.0, 0.0])
"""
from __future__ import annotations

import json
import struct
from dataclasses import dataclass

import numpy as np

__all__ = ["GlbMesh", "glb_bytes", "vertex_normals", "INSTANCE_TOLERANCE"]

#: Largest difference [file units; 1e-9 m = 1 nm in a build's metres] between a body's vertices and an earlier
#: body's moved by one vector for the file to draw it as that body moved (well below float32's resolution there).
INSTANCE_TOLERANCE = 1e-9

_MAGIC, _VERSION = b"glTF", 2
_JSON, _BIN = b"JSON", b"BIN\x00"
_FLOAT, _UINT32 = 5126, 5125  # accessor componentType
_ARRAY_BUFFER, _ELEMENT_ARRAY_BUFFER = 34962, 34963  # bufferView target
_TRIANGLES = 4  # primitive mode
#: Surface of every material: a dielectric (glTF's default material is a metal), fairly matt.
_METALLIC, _ROUGHNESS = 0.0, 0.8


@dataclass(frozen=True, slots=True, eq=False)
class GlbMesh:
    """One named body: vertices (n, 3) in file units, triangles (m, 3) of vertex indices, RGBA 0-255.

    Attributes
    ----------
    name : str
        The node's name (``"A1.tube"``).
    vertices : numpy.ndarray (n, 3)
        Positions, file units.
    faces : numpy.ndarray (m, 3)
        Triangles of vertex indices.
    colour : tuple of int
        RGBA, 0-255.

    Examples
    --------
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float)
    >>> tri = GlbMesh("A1.tube", v, np.array([[0, 1, 2]]), (200, 80, 80, 255))
    >>> tri.name, tri.faces.shape
    ('A1.tube', (1, 3))
    """

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    colour: tuple[int, int, int, int]


def vertex_normals(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Unit normal per vertex: the sum of its triangles' cross products (area-weighted), normalised.

    A vertex of no triangle of non-zero area gets (0, 0, 1) (glTF wants unit normals).

    Parameters
    ----------
    vertices : numpy.ndarray (n, 3)
        Positions.
    faces : numpy.ndarray (m, 3)
        Triangles of vertex indices.

    Returns
    -------
    numpy.ndarray (n, 3)
        Unit vectors.

    Examples
    --------
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    >>> vertex_normals(v, np.array([[0, 1, 2], [0, 3, 1]])).round(4).tolist()
    [[0.0, 0.7071, 0.7071], [0.0, 0.7071, 0.7071], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]]
    """
    v = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    cross = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    total = np.zeros_like(v)
    for k in range(3):
        np.add.at(total, f[:, k], cross)
    length = np.linalg.norm(total, axis=1)
    out = np.tile([0.0, 0.0, 1.0], (len(v), 1))
    ok = length > 0.0
    out[ok] = total[ok] / length[ok, None]
    return out


def _shape_key(verts: np.ndarray) -> bytes:
    """The vertices relative to the first, on a grid of :data:`INSTANCE_TOLERANCE` (moved copies share it)."""
    rel = (verts - verts[:1]) / INSTANCE_TOLERANCE
    return np.round(rel).astype(np.int64).tobytes() if np.all(np.abs(rel) < 2.0**62) else verts.tobytes()


def _moved_copy(earlier: list[tuple[int, np.ndarray]], verts: np.ndarray) -> tuple[int, list[float]] | None:
    """(mesh, translation) of the first earlier body ``verts`` is a moved copy of, else None."""
    for mesh, ref in earlier:
        shift = verts[0] - ref[0] if len(verts) else np.zeros(3)  # (no vertex: no triangle, any shift)
        if np.all(np.isfinite(shift)) and np.abs(verts - shift - ref).max(initial=0.0) <= INSTANCE_TOLERANCE:
            return mesh, [float(x) for x in shift]
    return None


def _pad(data: bytes, fill: bytes) -> bytes:
    return data + fill * (-len(data) % 4)


def glb_bytes(meshes) -> bytes:
    """The ``.glb`` file of ``meshes`` (a sequence of :class:`GlbMesh`), one node each.

    Parameters
    ----------
    meshes : iterable of GlbMesh
        The bodies.

    Returns
    -------
    bytes
        A binary glTF 2.0 file: positions, area-weighted normals, one material per colour.

    Examples
    --------
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float)
    >>> tri = GlbMesh("A1.tube", v, np.array([[0, 1, 2]]), (200, 80, 80, 255))
    >>> data = glb_bytes([tri])
    >>> data[:4], int.from_bytes(data[4:8], "little")  # magic and version
    (b'glTF', 2)
    """
    meshes = list(meshes)
    blob, colours = bytearray(), {}
    views: list[dict] = []
    accessors: list[dict] = []
    materials: list[dict] = []
    gltf_meshes: list[dict] = []
    shared = {}  # index bytes -> accessor: bodies of one ring layout (fabric, rails) share their triangles

    def view(data: bytes, target: int) -> int:
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(_pad(data, b"\x00"))
        return len(views) - 1

    nodes: list[dict] = []
    stored: dict[tuple, list[tuple[int, np.ndarray]]] = {}  # (part, faces, colour, shape) -> [(mesh, vertices)]
    for m in meshes:
        idx = np.ascontiguousarray(m.faces, dtype="<u4").reshape(-1).tobytes()
        colour = tuple(int(c) for c in m.colour)
        verts = np.asarray(m.vertices, dtype=np.float64).reshape(-1, 3)
        earlier = stored.setdefault((m.name.rsplit(".", 1)[-1], idx, colour, _shape_key(verts)), [])
        moved = _moved_copy(earlier, verts)
        if moved is not None:
            nodes.append({"name": m.name, "mesh": moved[0], "translation": moved[1]})
            continue
        earlier.append((len(gltf_meshes), verts))
        nodes.append({"name": m.name, "mesh": len(gltf_meshes)})
        pos = np.ascontiguousarray(verts, dtype="<f4").reshape(-1, 3)
        if idx not in shared:
            shared[idx] = len(accessors)
            accessors.append({"bufferView": view(idx, _ELEMENT_ARRAY_BUFFER), "componentType": _UINT32,
                              "count": len(idx) // 4, "type": "SCALAR"})
        accessors.append({"bufferView": view(pos.tobytes(), _ARRAY_BUFFER), "componentType": _FLOAT,
                          "count": int(len(pos)), "type": "VEC3",
                          "min": [float(x) for x in pos.min(axis=0)], "max": [float(x) for x in pos.max(axis=0)]})
        normals = np.ascontiguousarray(vertex_normals(m.vertices, m.faces), dtype="<f4")
        accessors.append({"bufferView": view(normals.tobytes(), _ARRAY_BUFFER), "componentType": _FLOAT,
                          "count": int(len(normals)), "type": "VEC3"})
        if colour not in colours:
            colours[colour] = len(materials)
            materials.append({"pbrMetallicRoughness": {"baseColorFactor": [c / 255.0 for c in colour],
                                                       "metallicFactor": _METALLIC, "roughnessFactor": _ROUGHNESS}}
                             | ({"alphaMode": "BLEND"} if colour[3] < 255 else {}))
        gltf_meshes.append({"name": m.name, "primitives": [
            {"attributes": {"POSITION": len(accessors) - 2, "NORMAL": len(accessors) - 1}, "indices": shared[idx],
             "material": colours[colour], "mode": _TRIANGLES}]})
    doc = {"asset": {"version": "2.0", "generator": "embroact"}, "scene": 0,
           "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
           "meshes": gltf_meshes, "materials": materials, "accessors": accessors, "bufferViews": views,
           "buffers": [{"byteLength": len(blob)}]}
    text = _pad(json.dumps(doc, separators=(",", ":")).encode("utf-8"), b" ")
    chunks = struct.pack("<I4s", len(text), _JSON) + text + struct.pack("<I4s", len(blob), _BIN) + bytes(blob)
    return struct.pack("<4sII", _MAGIC, _VERSION, 12 + len(chunks)) + chunks
