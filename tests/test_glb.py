"""GLB writer and triangle geometry without trimesh, checked against trimesh (an independent implementation)."""
import json
import struct
import subprocess
import sys

import numpy as np
import pytest

from embroact.export.pictures.glb import GlbMesh, glb_bytes
from embroact.export.pictures.mesh import PlanarPath, actuator_mesh, mesh_bytes
from embroact.export.pictures.triangles import point_triangle_distance, subdivide_to_size

trimesh = pytest.importorskip("trimesh")

R0, W = 2.5814206750769157, 7.0


def _chunks(data):
    """(JSON document, BIN bytes) of a GLB file, read by the specification's layout."""
    magic, version, length = struct.unpack("<4sII", data[:12])
    assert (magic, version, length) == (b"glTF", 2, len(data))
    n_json, kind = struct.unpack("<I4s", data[12:20])
    assert kind == b"JSON" and n_json % 4 == 0
    n_bin, kind = struct.unpack("<I4s", data[20 + n_json:28 + n_json])
    assert kind == b"BIN\x00" and n_bin % 4 == 0 and 28 + n_json + n_bin == len(data)
    return json.loads(data[20:20 + n_json]), data[28 + n_json:]


def test_glb_geometry_equals_trimesh_scene_of_the_same_bodies():
    """The file trimesh wrote before (one node per body, metres, Y up) and ours hold the same triangles."""
    m = actuator_mesh(PlanarPath.from_centerline(_arc()), 120.0, width_mm=W, r0_mm=R0, name="A1")
    ours = trimesh.load(trimesh.util.wrap_as_stream(mesh_bytes(m, ".glb")), file_type="glb")
    to_gltf = np.array([[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, 0, 1]], dtype=float)
    to_gltf[:3, :3] *= 1e-3
    assert sorted(ours.geometry) == sorted(f"A1.{b.name}" for b in m.bodies)
    for b in m.bodies:
        ref = trimesh.Trimesh(np.array(b.vertices), np.array(b.faces), process=False)
        ref.apply_transform(to_gltf)
        got = ours.geometry[f"A1.{b.name}"]
        assert np.array_equal(got.faces, b.faces)
        assert np.array_equal(got.vertices, ref.vertices.astype(np.float32))  # float32, as glTF stores them
        assert np.abs(got.vertices - ref.vertices).max() <= 0.5 * np.spacing(np.float32(0.2))  # < 1e-5 mm
        assert tuple(got.visual.material.baseColorFactor) == b.colour


def _arc():
    from embroact.patterns.centerline import Centerline

    t = np.linspace(0.0, np.pi / 2, 60)
    return Centerline(np.column_stack([40 * np.cos(t), 40 * np.sin(t)]))


def test_glb_layout_accessors_and_materials():
    tri = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    faces = np.array([[0, 1, 2], [0, 3, 1]])
    data = glb_bytes([GlbMesh("a", tri, faces, (10, 20, 30, 255)), GlbMesh("b", tri * 2.0 + 2.0, faces,
                                                                            (10, 20, 30, 255))])
    doc, blob = _chunks(data)
    assert doc["asset"]["version"] == "2.0" and [n["name"] for n in doc["nodes"]] == ["a", "b"]
    assert len(doc["materials"]) == 1 and doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] == [
        10 / 255, 20 / 255, 30 / 255, 1.0]
    prims = [mesh["primitives"][0] for mesh in doc["meshes"]]
    assert prims[0]["indices"] == prims[1]["indices"]  # equal triangles stored once
    pos = doc["accessors"][prims[1]["attributes"]["POSITION"]]
    view = doc["bufferViews"][pos["bufferView"]]
    xyz = np.frombuffer(blob, dtype="<f4", count=pos["count"] * 3, offset=view["byteOffset"]).reshape(-1, 3)
    assert xyz.tolist() == (tri * 2.0 + 2.0).tolist() and pos["min"] == [2.0] * 3 and pos["max"] == [4.0] * 3
    idx = doc["accessors"][prims[0]["indices"]]
    view = doc["bufferViews"][idx["bufferView"]]
    assert np.frombuffer(blob, dtype="<u4", count=idx["count"], offset=view["byteOffset"]).tolist() == [0, 1, 2, 0,
                                                                                                          3, 1]
    assert glb_bytes([GlbMesh("a", tri, faces, (10, 20, 30, 255))]) == glb_bytes([GlbMesh("a", tri, faces,
                                                                                         (10, 20, 30, 255))])


def test_a_moved_copy_of_a_body_is_a_node_naming_its_mesh():
    """A body that is an earlier one of the same part moved (identical actuators side by side) is stored once: its
    node names the earlier mesh with the displacement as its translation; trimesh (an independent reader) places it where it
    was, and 200 copies cost a node each, not a mesh."""
    tri = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    faces = np.array([[0, 1, 2], [0, 3, 1]])
    shifts = [np.array([0.1 * k, -0.3 * k, 0.05 * k]) for k in range(200)]
    copies = [GlbMesh(f"c{k}.tube", tri + d, faces, (10, 20, 30, 255)) for k, d in enumerate(shifts)]
    other = GlbMesh("scaled.tube", tri * 1.5, faces, (10, 20, 30, 255))
    rail = GlbMesh("c0.rail", tri + 1.0, faces, (10, 20, 30, 255))  # another part moved: its own mesh
    data = glb_bytes(copies + [other, rail])
    doc, _ = _chunks(data)
    assert len(doc["meshes"]) == 3 and [n["name"] for n in doc["nodes"]] == [f"c{k}.tube" for k in range(200)] + [
        "scaled.tube", "c0.rail"]
    assert [n["mesh"] for n in doc["nodes"]] == [0] * 200 + [1, 2]
    assert np.allclose(doc["nodes"][7]["translation"], shifts[7], atol=1e-12)
    scene = trimesh.load(trimesh.util.wrap_as_stream(data), file_type="glb", process=False)
    for k in (0, 7, 199):
        transform, geometry = scene.graph[f"c{k}.tube"]
        placed = trimesh.transformations.transform_points(scene.geometry[geometry].vertices, transform)
        assert np.abs(placed - (tri + shifts[k])).max() < 1e-6
    assert len(data) < len(glb_bytes(copies[:1] + [other, rail])) + 200 * 120


def test_point_triangle_distance_matches_trimesh_closest_point():
    from trimesh.triangles import closest_point

    rng = np.random.default_rng(20251201)
    tri = rng.normal(size=(5000, 3, 3))
    pts = rng.normal(size=(5000, 3)) * 2.0
    ref = np.linalg.norm(closest_point(tri, pts) - pts, axis=1)
    assert point_triangle_distance(tri, pts) == pytest.approx(ref, abs=1e-12)


def test_point_triangle_distance_hand_values():
    tri = np.array([[[0.0, 0, 0], [4, 0, 0], [0, 3, 0]]] * 4)
    # above the face; beyond vertex B; beyond the hypotenuse (3-4-5: distance (3*4+... )); below edge AB
    pts = np.array([[1.0, 1, 2], [6.0, -1, 0], [4.0, 3, 0], [2.0, -2, 1]])
    d = point_triangle_distance(tri, pts)
    # hypotenuse x/4 + y/3 = 1: distance of (4, 3) is (4/4 + 3/3 - 1) / sqrt(1/16 + 1/9) = 12/5
    assert d == pytest.approx([2.0, np.hypot(2.0, 1.0), 12.0 / 5.0, np.hypot(2.0, 1.0)], abs=1e-14)


@pytest.mark.parametrize("max_edge", [0.08, 0.3, 1.5])
def test_subdivide_to_size_matches_trimesh(max_edge):
    from trimesh.remesh import subdivide_to_size as reference

    sphere = trimesh.creation.icosphere(subdivisions=1)
    v0, f0, p0 = reference(sphere.vertices, sphere.faces, max_edge, return_index=True)
    v, f, parent = subdivide_to_size(sphere.vertices, sphere.faces, max_edge)
    assert np.array_equal(v0[f0], v[f]) and np.array_equal(p0, parent)
    edges = v[f[:, [1, 2, 0]]] - v[f]
    assert np.linalg.norm(edges, axis=2).max() <= max_edge
    assert trimesh.Trimesh(v, f).is_watertight  # shared midpoints: no cracks


def test_glb_and_measured_mesh_load_no_trimesh(tmp_path):
    code = ("import sys; from embroact.export.pictures.mesh import PlanarPath, actuator_mesh, mesh_bytes; "
            "from embroact.export.pictures.meshview import mesh_svg; "
            f"m = actuator_mesh(PlanarPath.straight(50.0), 40.0, width_mm={W}, r0_mm={R0}); mesh_bytes(m, '.glb'); "
            "mesh_svg(m); print(m.max_deviation_mm <= 0.05, [k for k in ('trimesh', 'scipy') if k in sys.modules])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split("\n")[0] == "True []"


def test_vertex_normals_are_unit_outward_and_agree_with_trimesh():
    """NORMAL of every body: unit length, one per position, and the area-weighted normals trimesh's face
    normals, areas and vertex-face incidence give for the same triangles (as trimesh reads the file)."""
    m = actuator_mesh(PlanarPath.from_centerline(_arc()), 120.0, width_mm=W, r0_mm=R0, name="A1")
    data = mesh_bytes(m, ".glb")
    doc, blob = _chunks(data)
    for mesh in doc["meshes"]:
        attrs = mesh["primitives"][0]["attributes"]
        pos, nor = doc["accessors"][attrs["POSITION"]], doc["accessors"][attrs["NORMAL"]]
        assert (nor["count"], nor["type"], nor["componentType"]) == (pos["count"], "VEC3", 5126)
        view = doc["bufferViews"][nor["bufferView"]]
        assert view["byteOffset"] + view["byteLength"] <= len(blob) and view["byteLength"] == 12 * nor["count"]
        n = np.frombuffer(blob, dtype="<f4", count=nor["count"] * 3, offset=view["byteOffset"]).reshape(-1, 3)
        np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-6)  # glTF: unit normals
    scene = trimesh.load(trimesh.util.wrap_as_stream(data), file_type="glb", process=False)
    for b in m.bodies:
        got = scene.geometry[f"A1.{b.name}"]
        read = np.asarray(got.vertex_normals)  # the file's NORMAL, as trimesh reads it
        t = trimesh.Trimesh(np.asarray(got.vertices, float), np.asarray(got.faces), process=False)
        ref = t.faces_sparse @ (t.face_normals * t.area_faces[:, None])  # trimesh's area-weighted sum per vertex
        ref /= np.linalg.norm(ref, axis=1)[:, None]
        assert np.einsum("ij,ij->i", read, ref).min() > 1.0 - 1e-5, b.name
