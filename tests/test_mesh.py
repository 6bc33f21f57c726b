"""3D shape: bend angle, chordal tolerance, resolution scaling, closed bodies, file formats."""
import math
import subprocess
import sys

import numpy as np
import pytest

from embroact.export.pictures.mesh import (DEFAULT_CHORD_TOLERANCE_MM, BentPath, PlanarPath, actuator_mesh, mesh_bytes,
                                  write_mesh)
from embroact.patterns.centerline import Centerline
from embroact.patterns.base.errors import ExportError, ParameterError

trimesh = pytest.importorskip("trimesh")

R0, W = 2.5814206750769157, 7.0


def _mesh(theta, tol=DEFAULT_CHORD_TOLERANCE_MM, path=None):
    return actuator_mesh(path or PlanarPath.straight(100.0), theta, width_mm=W, r0_mm=R0, tolerance_mm=tol)


def _body(m, name):
    return next(b for b in m.bodies if b.name == name)


def _ring_normal(body, ring):
    """Unit normal of the plane through one cross-section ring (SVD), oriented along +s."""
    k = body.ring_size
    pts = np.asarray(body.vertices)[ring * k:(ring + 1) * k]
    _, _, vt = np.linalg.svd(pts - pts.mean(axis=0))
    return vt[-1]


@pytest.mark.parametrize("theta", [-48.0, 10.0, 45.0, 90.0, 155.0, 234.0])
def test_bend_angle_of_the_mesh_equals_theta(theta):
    m = _mesh(theta)
    tube = _body(m, "tube")
    rings = len(tube.vertices) // tube.ring_size
    first, last = _ring_normal(tube, 0), _ring_normal(tube, rings - 1)
    first = first * np.sign(first[0])  # the path starts along +x
    # the bend is about the y axis: signed angle in the x-z plane, positive toward -z (fabric back)
    last = last * np.sign(last @ BentPath.from_theta(PlanarPath.straight(100.0), theta).frames([100.0])[1][0, :, 0])
    angle = math.degrees(math.atan2(-last[2], last[0]) - math.atan2(-first[2], first[0]))
    assert (angle - theta + 180.0) % 360.0 - 180.0 == pytest.approx(0.0, abs=0.1)
    assert abs(last[1]) < 1e-9  # stays in the x-z plane


def test_frames_orthonormal_and_end_tangent_exact():
    bent = BentPath.from_theta(PlanarPath.straight(100.0), 90.0)
    x, r = bent.frames(np.linspace(0, 100, 11))
    assert np.abs(np.einsum("nij,nik->njk", r, r) - np.eye(3)).max() < 1e-12
    assert r[-1][:, 0] == pytest.approx([0.0, 0.0, -1.0], abs=1e-12)  # T: from +x to straight down (back)
    rr = 200.0 / math.pi
    assert x[-1] == pytest.approx([rr, 0.0, -rr], abs=1e-9)


def test_straight_bend_matches_the_side_view_model():
    from embroact.export.pictures.sideview import bent_line_mm

    bent = BentPath.from_theta(PlanarPath.straight(100.0), 70.0)
    s = np.linspace(0.0, 100.0, 9)
    on_tube_axis = bent.points(s, [[0.0, R0]])[:, 0, :]
    side = bent_line_mm(100.0, 70.0, R0, tolerance_mm=1e-4)
    # side view: clamp at origin, hanging along -z, thread side +x; mesh: path along +x, thread side +z
    end_side = side[-1]
    assert [on_tube_axis[-1][2], -on_tube_axis[-1][0]] == pytest.approx([end_side[0], end_side[1]], abs=1e-9)


def test_tube_vertices_lie_on_the_torus_and_facets_within_tolerance():
    theta, tol = 120.0, DEFAULT_CHORD_TOLERANCE_MM
    m = _mesh(theta, tol)
    tube = _body(m, "tube")
    rr = 100.0 / math.radians(theta)  # fabric-line radius; centre of curvature at (0, 0, -rr), axis along y
    v = np.asarray(tube.vertices)
    f = np.asarray(tube.faces)

    def torus_distance(p):
        rho = np.hypot(p[:, 0], p[:, 2] + rr)
        return np.abs(np.hypot(rho - (rr + R0), p[:, 1]) - R0)

    ring_count = len(v) // tube.ring_size
    side_vertices = v[: ring_count * tube.ring_size]
    assert torus_distance(side_vertices).max() < 1e-9
    # dense samples on every side facet stay within the tolerance of the exact surface
    ring_of = f // tube.ring_size
    side = f[ring_of.min(axis=1) != ring_of.max(axis=1)]  # caps lie within one ring
    assert len(side) == 2 * tube.ring_size * (ring_count - 1)
    bary = np.array([[1, 1, 1], [4, 1, 1], [1, 4, 1], [1, 1, 4], [2, 2, 1], [1, 2, 2], [2, 1, 2]], float)
    bary /= bary.sum(axis=1, keepdims=True)
    samples = np.einsum("kj,fjd->fkd", bary, v[side]).reshape(-1, 3)
    assert torus_distance(samples).max() <= tol
    assert 0.0 < m.max_deviation_mm <= tol


@pytest.mark.parametrize("tol", [0.01, 0.05, 0.2])
@pytest.mark.parametrize("theta", [0.0, 30.0, 180.0])
def test_realised_deviation_within_tolerance(theta, tol):
    m = _mesh(theta, tol)
    assert 0.0 < m.max_deviation_mm <= tol
    assert m.stats()["triangle_count"] == m.triangle_count == sum(len(b.faces) for b in m.bodies)


def test_triangle_count_grows_with_bend_and_shrinks_with_tolerance():
    by_angle = [_mesh(t).triangle_count for t in (0.0, 10.0, 45.0, 90.0, 180.0)]
    assert by_angle == sorted(by_angle) and len(set(by_angle)) == len(by_angle)
    by_tol = [_mesh(90.0, t).triangle_count for t in (0.01, 0.05, 0.2, 1.0)]
    assert by_tol == sorted(by_tol, reverse=True) and len(set(by_tol)) == len(by_tol)


def test_straight_strip_is_a_box():
    m = _mesh(0.0)
    assert len(_body(m, "fabric").faces) == 12  # 6 faces x 2 triangles
    assert len(_body(m, "rail_left").faces) == 12
    # tube: n sides with r0 (1 - cos(pi/n)) <= tol/2 -> 2n side + 2(n - 2) cap triangles
    n = math.ceil(math.pi / math.acos(1 - DEFAULT_CHORD_TOLERANCE_MM / 2 / R0))
    assert len(_body(m, "tube").faces) == 4 * n - 4


@pytest.mark.parametrize("theta", [0.0, 75.0, -40.0])
def test_bodies_are_closed_with_outward_normals(theta):
    m = _mesh(theta)
    for b in m.bodies:
        tm = trimesh.Trimesh(np.asarray(b.vertices), np.asarray(b.faces), process=False)
        assert tm.is_watertight and tm.is_winding_consistent, b.name
        assert tm.volume > 0, b.name
    if theta == 0.0:
        n = _body(m, "tube").ring_size
        prism = n / 2 * R0**2 * math.sin(2 * math.pi / n) * 100.0  # volume of an n-gon prism
        tube = _body(m, "tube")
        assert trimesh.Trimesh(np.asarray(tube.vertices), np.asarray(tube.faces)).volume == pytest.approx(prism)


def test_curved_path_bends_along_its_own_path():
    ang = np.linspace(0.0, math.pi / 2, 200)
    arc = Centerline.from_points(np.column_stack([40 * np.sin(ang), 40 * (1 - np.cos(ang))]))
    path = PlanarPath.from_centerline(arc)
    assert len(path.lengths_mm) <= 3  # a flattened arc becomes (nearly) one piece
    assert path.length_mm == pytest.approx(arc.length_mm, rel=1e-12)
    flat = BentPath.from_theta(path, 0.0)
    x, r = flat.frames([path.length_mm])
    assert x[0][:2] == pytest.approx(arc.points_mm[-1], abs=0.01) and x[0][2] == 0.0
    bent = BentPath.from_theta(path, 60.0)
    x, r = bent.frames(np.linspace(0.0, path.length_mm, 50))
    assert (x[1:, 2] < 0).all()  # bends toward the back of the fabric
    # total rotation: the frame turns about omega = (0, kb, kp) piece by piece: |rotation| = sum k_i l_i
    kb = math.radians(60.0) / path.length_mm
    expected = sum(math.hypot(kb, k) * l for k, l in zip(path.kappa_per_mm, path.lengths_mm))
    # for one piece the frame rotation angle is exactly k * l
    if len(path.lengths_mm) == 1:
        rot = r[0].T @ r[-1]
        assert math.acos((np.trace(rot) - 1) / 2) == pytest.approx(expected, abs=1e-9)
    m = actuator_mesh(path, 60.0, width_mm=W, r0_mm=R0)
    assert m.max_deviation_mm <= DEFAULT_CHORD_TOLERANCE_MM


@pytest.mark.parametrize("suffix", [".glb", ".stl", ".obj", ".ply"])
def test_formats_round_trip_and_same_bytes(tmp_path, suffix):
    m = _mesh(60.0, 0.2)
    p = write_mesh(m, tmp_path / f"shape{suffix}")
    first = p.read_bytes()
    write_mesh(m, p)
    assert p.read_bytes() == first == mesh_bytes(m, suffix)
    loaded = trimesh.load(p, force="mesh") if suffix != ".glb" else trimesh.load(p).to_mesh()
    assert len(loaded.faces) == m.triangle_count
    if suffix == ".glb":
        scene = trimesh.load(p)
        assert sorted(scene.geometry) == sorted(f"actuator.{b.name}" for b in m.bodies)
        # metres, Y up: plan (x, y, z) -> (x, z, -y) / 1000
        plan = np.vstack([np.asarray(b.vertices) for b in m.bodies])
        gltf = np.column_stack([plan[:, 0], plan[:, 2], -plan[:, 1]]) / 1000.0
        assert scene.bounds == pytest.approx(np.array([gltf.min(axis=0), gltf.max(axis=0)]), abs=1e-7)  # float32


def test_unknown_suffix_lists_valid_ones(tmp_path):
    with pytest.raises(ExportError, match=r"\.glb, \.stl, \.obj, \.ply.*'\.fbx'"):
        write_mesh(_mesh(10.0, 0.5), tmp_path / "shape.fbx")
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("kwargs, match", [
    (dict(tolerance_mm=0.0), "tolerance_mm must be in"),
    (dict(r0_mm=-1.0), "r0_mm must be in"),
    (dict(strip_width_mm=5.0), "strip_width_mm must be in"),
])
def test_bad_parameters(kwargs, match):
    args = dict(width_mm=W, r0_mm=R0) | kwargs
    with pytest.raises(ParameterError, match=match):
        actuator_mesh(PlanarPath.straight(100.0), 30.0, **args)


def test_mesh_module_imports_trimesh_lazily():
    code = "import sys, embroact.export.pictures.mesh, embroact.export.pictures.previews; print('trimesh' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"


@pytest.mark.parametrize("az, el", [(0.0, 0.0), (60.0, 20.0), (-135.0, 75.0), (0.0, 90.0)])
def test_view_rotation_is_a_proper_rotation(az, el):
    from embroact.export.pictures.meshview import view_rotation

    r = view_rotation(az, el)
    assert r @ r.T == pytest.approx(np.eye(3), abs=1e-12) and np.linalg.det(r) == pytest.approx(1.0)
    # the camera looks along -z': its toward-viewer axis is at elevation el above the plan
    assert math.degrees(math.asin(r[2, 2])) == pytest.approx(el)
    if el == 0.0:
        assert r[1] == pytest.approx([0.0, 0.0, 1.0])  # plan +z is screen up


def test_picture_draws_front_faces_only_and_is_stable():
    import xml.etree.ElementTree as ET

    from embroact.export.pictures.meshview import mesh_svg

    m = _mesh(90.0, 0.5)
    svg = mesh_svg(m)
    assert svg == mesh_svg(m)
    polys = list(ET.fromstring(svg).iter("{http://www.w3.org/2000/svg}polygon"))
    # closed bodies: roughly half of the (subdivided) triangles face the camera
    from trimesh.remesh import subdivide_to_size

    total = sum(len(subdivide_to_size(np.asarray(b.vertices), np.asarray(b.faces), 0.04 * 100.0)[1])
                for b in m.bodies)
    assert 0.3 * total < len(polys) < 0.7 * total
    with pytest.raises(ParameterError, match="elevation_deg must be in"):
        mesh_svg(m, elevation_deg=95.0)


def test_default_tolerance_coarsens_to_the_triangle_limit_an_asked_one_is_refused():
    from embroact.export.pictures.mesh import MESH_MAX_TRIANGLES

    long_path = PlanarPath.straight(10_000.0)  # a 10 m strip wound 3000 deg: far more rings than the limit allows
    with pytest.raises(ParameterError, match=r"tolerance_mm=0.05 would make .* use tolerance_mm >= "):
        actuator_mesh(long_path, 3000.0, width_mm=W, r0_mm=R0, tolerance_mm=0.05, measure=False)
    m = actuator_mesh(long_path, 3000.0, width_mm=W, r0_mm=R0, tolerance_mm=0.05, measure=False, coarsen=True)
    # the result says what it used; the limit is judged on the mesh's estimated size (within tens of percent)
    assert m.tolerance_mm > 0.05 and m.triangle_count < 1.5 * MESH_MAX_TRIANGLES
