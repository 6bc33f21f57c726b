"""Centerline: constructors, SVG parsing against hand values, frames, projection, validation."""
import math
import subprocess
import sys

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from embroact.patterns.centerline import MAX_SMOOTH_TURN_DEG, Centerline, as_centerline
from embroact.patterns.base.errors import ParameterError, PathError
from embroact.patterns.base.tolerances import DEFAULT_TOLERANCES

from h1_checks import arc


def test_straight_frame_by_hand():
    c = Centerline.straight(10.0, origin_mm=(1.0, 2.0), rotation_deg=90.0)
    assert c.length_mm == pytest.approx(10.0, abs=1e-12)
    np.testing.assert_allclose(c.point_at([0.0, 4.0, 10.0]), [[1, 2], [1, 6], [1, 12]], atol=1e-12)
    np.testing.assert_allclose(c.tangent_at(3.0), [0.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(c.normal_at(3.0), [-1.0, 0.0], atol=1e-12)  # left of +y is -x
    assert c.curvature_at(5.0) == 0.0
    assert c.min_radius_mm() == math.inf


def test_point_at_clips_and_vectorises():
    c = Centerline.straight(10.0)
    out = c.point_at(np.array([[-1.0, 5.0], [11.0, 2.5]]))
    assert out.shape == (2, 2, 2)
    np.testing.assert_allclose(out[0, 0], [0, 0])
    np.testing.assert_allclose(out[1, 0], [10, 0])


def test_points_read_only_and_equality():
    c = Centerline.from_points([[0, 0], [1, 0], [2, 1]])
    with pytest.raises(ValueError):
        c.points_mm[0, 0] = 5.0
    assert c == Centerline.from_points(np.array([[0.0, 0.0], [1, 0], [2, 1]]))
    assert c != Centerline.straight(3.0)
    assert hash(c) == hash(Centerline.from_points([[0, 0], [1, 0], [2, 1]]))


def test_exact_repeats_dropped():
    c = Centerline.from_points([[0, 0], [0, 0], [5, 0], [5, 0], [10, 0]])
    assert c.points_mm.tolist() == [[0, 0], [5, 0], [10, 0]]


@pytest.mark.parametrize(
    "points, fragment",
    [
        ([[1, 1]], "at least 2 distinct points, got 1"),
        ([[1, 1], [1, 1]], "at least 2 distinct points, got 1"),
        ([[0, 0], [math.nan, 1]], "finite"),
        ([[0, 0, 0], [1, 1, 1]], "shape (n, 2)"),
        ([[0, 0], [10, 0], [10, 10], [0, 0]], "closed"),
        ([[0, 0], [10, 10], [10, 0], [0, 10]], "crosses or touches itself near (5.00, 5.00) mm"),
        ([[0, 0], [10, 0], [5, 0]], "crosses or touches itself near (5.00, 0.00) mm"),
        ("not a path", "unsupported character"),
    ],
)
def test_bad_paths(points, fragment):
    with pytest.raises(PathError) as exc:
        as_centerline(points)
    assert fragment in str(exc.value)
    assert "\n" not in str(exc.value)


def test_as_centerline_accepts_all_forms():
    pts = [[0.0, 0.0], [3.0, 4.0]]
    ref = Centerline.from_points(pts)
    assert as_centerline(ref) is ref
    assert as_centerline(pts) == ref
    assert as_centerline(np.array(pts)) == ref
    assert as_centerline(shapely.LineString(pts)) == ref
    assert as_centerline("M 0 0 L 3 -4") == ref  # SVG y is down
    with pytest.raises(PathError, match="must be a LineString, got a Polygon"):
        as_centerline(shapely.box(0, 0, 1, 1))


def test_straight_rejects_bad_values():
    with pytest.raises(ParameterError, match=r"length_mm must be in \[0.001, 1e\+06\), got -1"):
        Centerline.straight(-1.0)
    with pytest.raises(ParameterError, match=r"length_mm must be in \[0.001, 1e\+06\), got 4.94066e-324"):
        Centerline.straight(5e-324)  # the smallest subnormal: refused, not a 1-point path
    with pytest.raises(ParameterError, match="origin_mm must be a pair"):
        Centerline.straight(1.0, origin_mm=(1.0,))


# ---------------------------------------------------------------------- SVG
def test_svg_lines_absolute_relative_hand_values():
    c = Centerline.from_svg_path("M 10 20 L 30 20 h 5 v -10 l -5 -5 H 20 V 0")
    # SVG (x, y) -> plan (x, -y)
    assert c.points_mm.tolist() == [[10, -20], [30, -20], [35, -20], [35, -10], [30, -5], [20, -5], [20, 0]]


def test_svg_implicit_lineto_after_move_and_compact_numbers():
    a = Centerline.from_svg_path("m1,1 2,0 0-2")
    assert a.points_mm.tolist() == [[1, -1], [3, -1], [3, 1]]
    b = Centerline.from_svg_path("M.5.5L1.5.5 1.5-.5e1")
    assert b.points_mm.tolist() == [[0.5, -0.5], [1.5, -0.5], [1.5, 5.0]]


def _bezier_hand(p, t):
    """De Casteljau evaluation (independent of the flattener's Bernstein sum)."""
    pts = [np.asarray(q, float) for q in p]
    while len(pts) > 1:
        pts = [(1 - t) * a + t * b for a, b in zip(pts[:-1], pts[1:])]
    return pts[0]


def _max_chord_error(c: Centerline, ctrl):
    line = c.as_linestring()
    pts = np.array([_bezier_hand(ctrl, t) for t in np.linspace(0, 1, 801)]) * [1, -1]
    return float(shapely.distance(line, shapely.points(pts)).max())


def test_svg_cubic_endpoints_and_flatness():
    ctrl = [(0, 0), (0, 10), (10, 10), (10, 0)]
    c = Centerline.from_svg_path("M0 0 C 0 10 10 10 10 0")
    np.testing.assert_allclose(c.points_mm[0], [0, 0])
    np.testing.assert_allclose(c.points_mm[-1], [10, 0])
    # B(1/2) = (P0 + 3 P1 + 3 P2 + P3) / 8 = (5, 7.5) -> plan (5, -7.5)
    mid = np.array([5.0, -7.5])
    assert float(shapely.distance(c.as_linestring(), shapely.Point(mid))) < 1e-9 + DEFAULT_TOLERANCES.curve_flatness_mm
    assert _max_chord_error(c, ctrl) <= DEFAULT_TOLERANCES.curve_flatness_mm


def test_svg_quadratic_flatness_and_relative_equals_absolute():
    a = Centerline.from_svg_path("M 5 5 Q 15 25 25 5")
    b = Centerline.from_svg_path("M 5 5 q 10 20 20 0")
    np.testing.assert_allclose(a.points_mm, b.points_mm, atol=1e-12)
    assert _max_chord_error(a, [(5, 5), (15, 25), (25, 5)]) <= DEFAULT_TOLERANCES.curve_flatness_mm


def test_svg_smooth_reflections():
    s = Centerline.from_svg_path("M0 0 C 0 10 10 10 10 0 S 20 -10 20 0")
    c = Centerline.from_svg_path("M0 0 C 0 10 10 10 10 0 C 10 -10 20 -10 20 0")
    np.testing.assert_allclose(s.points_mm, c.points_mm, atol=1e-12)
    t = Centerline.from_svg_path("M0 0 Q 5 10 10 0 T 20 0")
    q = Centerline.from_svg_path("M0 0 Q 5 10 10 0 Q 15 -10 20 0")
    np.testing.assert_allclose(t.points_mm, q.points_mm, atol=1e-12)
    # S after a line: first control point is the current point
    s2 = Centerline.from_svg_path("M0 0 L 5 0 S 10 10 15 10")
    c2 = Centerline.from_svg_path("M0 0 L 5 0 C 5 0 10 10 15 10")
    np.testing.assert_allclose(s2.points_mm, c2.points_mm, atol=1e-12)


def test_svg_arc_semicircle_by_hand():
    up = Centerline.from_svg_path("M 0 0 A 10 10 0 0 1 20 0")  # sweep 1: clockwise on screen = up in plan
    np.testing.assert_allclose(np.hypot(*(up.points_mm - [10.0, 0.0]).T), 10.0, atol=1e-12)
    assert up.points_mm[:, 1].max() == pytest.approx(10.0, abs=DEFAULT_TOLERANCES.curve_flatness_mm)
    assert up.points_mm[:, 1].min() >= 0.0
    np.testing.assert_array_equal(up.points_mm[-1], [20.0, 0.0])
    down = Centerline.from_svg_path("M 0 0 A 10 10 0 0 0 20 0")
    assert down.points_mm[:, 1].min() == pytest.approx(-10.0, abs=DEFAULT_TOLERANCES.curve_flatness_mm)
    # chordal error: the true circle's points lie within the flatness of the polyline
    th = np.linspace(0.0, np.pi, 721)
    true = np.c_[10.0 - 10.0 * np.cos(th), 10.0 * np.sin(th)]
    assert shapely.distance(up.as_linestring(), shapely.points(true)).max() <= DEFAULT_TOLERANCES.curve_flatness_mm


def test_svg_arc_radius_scaled_up_relative_and_ellipse():
    small = Centerline.from_svg_path("M 0 0 A 1 1 0 0 1 20 0")  # radius too small: scaled to 10
    assert small.length_mm == pytest.approx(10.0 * np.pi, rel=5e-4)  # chords: shorter by step^2/24
    rel = Centerline.from_svg_path("M 5 5 a 10 10 0 0 1 20 0")
    np.testing.assert_allclose(rel.points_mm, small.points_mm + [5.0, -5.0], atol=1e-12)
    # quarter of the ellipse x^2/20^2 + (y-10)^2/10^2 = 1 (SVG frame), from its bottom to its right end
    q = Centerline.from_svg_path("M 0 0 A 20 10 0 0 1 20 10")
    x, y_svg = q.points_mm[:, 0], -q.points_mm[:, 1]
    np.testing.assert_allclose((x / 20.0) ** 2 + ((y_svg - 10.0) / 10.0) ** 2, 1.0, atol=1e-12)
    assert x.min() == 0.0 and x.max() == 20.0
    line = Centerline.from_svg_path("M 0 0 A 0 5 0 0 1 20 0")  # zero radius: a straight line
    assert line.points_mm.tolist() == [[0.0, 0.0], [20.0, 0.0]]


def test_svg_compact_arc_flags_equal_the_spaced_form():
    # SVG 1.1 grammar: flags are single characters, so "01" is large-arc 0, sweep 1
    compact = Centerline.from_svg_path("M0,0a5,5 0 01 10,0")
    spaced = Centerline.from_svg_path("M 0 0 a 5 5 0 0 1 10 0")
    np.testing.assert_array_equal(compact.points_mm, spaced.points_mm)
    np.testing.assert_allclose(np.hypot(*(compact.points_mm - [5.0, 0.0]).T), 5.0, atol=1e-12)  # centre (5, 0)
    assert compact.points_mm[:, 1].max() == pytest.approx(5.0, abs=DEFAULT_TOLERANCES.curve_flatness_mm)


def test_svg_subpaths_that_continue_are_joined():
    joined = Centerline.from_svg_path("M 0 0 L 10 0 M 10 0 L 10 5 m 0 0 l 5 0")  # each starts where the last ended
    assert joined.points_mm.tolist() == [[0.0, 0.0], [10.0, 0.0], [10.0, -5.0], [15.0, -5.0]]
    assert Centerline.from_svg_path("M 3 3 M 0 0 L 4 0").points_mm.tolist() == [[0.0, 0.0], [4.0, 0.0]]  # a lone move draws nothing


@pytest.mark.parametrize(
    "d, fragment",
    [
        ("M 0 0 R 5 5", "unsupported character 'R'"),
        ("M 0 0 A 5 5 0 2 1 10 0", "arc flag at character 14 must be 0 or 1"),
        ("L 1 1", "must start with a move-to (M)"),
        ("M 0 0 L 1", "'L' at character 6 needs numbers in groups of 2, got 1"),
        ("M 0 0 L 1 1 M 5 5 L 6 6", "2 subpaths with a gap of 5.657 mm"),
        ("M 0 0 M 5 5", "draws nothing"),
        ("M 0 0 L 1e999 0", "finite"),
        ("drawing.svg#tube1", "looks like an SVG file reference"),
        ("M 0 0 L 10 0 L 10 10 Z", "closed"),
        ("", "non-empty string"),
    ],
)
def test_svg_errors(d, fragment):
    with pytest.raises(PathError) as exc:
        Centerline.from_svg_path(d)
    assert fragment in str(exc.value)


# ---------------------------------------------------------------------- curvature and radius
def test_arc_curvature_sign_and_radius():
    left, right = arc(20.0, 90.0), arc(20.0, 90.0, left=False)
    assert left.curvature_at(10.0) == pytest.approx(1 / 20.0, rel=1e-4)
    assert right.curvature_at(10.0) == pytest.approx(-1 / 20.0, rel=1e-4)
    assert left.min_radius_mm() == pytest.approx(20.0, rel=1e-3)
    assert left.length_mm == pytest.approx(20.0 * math.pi / 2, rel=1e-6)


def test_smooth_normals_on_dense_arc_point_to_centre():
    r = 20.0
    c = arc(r, 180.0)
    s = np.linspace(0.0, c.length_mm, 37)
    # hand: left normal at angle phi = s / r is (-sin phi, cos phi)
    # (end points carry their segment's direction: off by half a chord angle, 0.8 mrad here)
    phi = s / r
    chord_angle = math.pi / (len(c.points_mm) - 1)
    np.testing.assert_allclose(c.normal_at(s[1:-1]), np.c_[-np.sin(phi), np.cos(phi)][1:-1], atol=1e-6)
    np.testing.assert_allclose(c.tangent_at(s), np.c_[np.cos(phi), np.sin(phi)], atol=chord_angle / 2 + 1e-9)


def test_corner_counts_as_radius_zero():
    c = Centerline.from_points([[0, 0], [50, 0], [50, 50]])
    assert c.min_radius_mm() == 0.0
    with pytest.raises(PathError) as exc:
        c.check_radius(3.5, "width_mm/2")
    msg = str(exc.value)
    assert "corner at (50.00, 0.00) mm" in msg and "turn 90.0 deg" in msg
    assert "radius 0 < width_mm/2 = 3.5 mm" in msg and "round the corner" in msg


def test_gentle_vertex_is_smooth():
    turn = MAX_SMOOTH_TURN_DEG / 2
    c = Centerline.from_points([[0, 0], [20, 0], [20 + 20 * math.cos(math.radians(turn)), 20 * math.sin(math.radians(turn))]])
    # the tangent turns linearly from vertex to vertex: half the turn on each 20 mm segment
    assert c.min_radius_mm() == pytest.approx(20.0 / (math.radians(turn) / 2), rel=1e-9)
    c.check_radius(3.5, "width_mm/2")


def test_check_radius_message():
    with pytest.raises(PathError) as exc:
        arc(3.0, 90.0).check_radius(3.5, "width_mm/2")
    assert str(exc.value).startswith("path curvature radius must be >= width_mm/2 = 3.5 mm, got 3")


# ---------------------------------------------------------------------- rails and projection
def test_offset_curves_straight_hand():
    left, right = Centerline.straight(10.0).offset_curves(3.5)
    assert left.coords[0] == (0.0, 3.5) and left.coords[-1] == (10.0, 3.5)
    assert right.coords[0] == (0.0, -3.5) and right.coords[-1] == (10.0, -3.5)


def test_offset_curves_arc_at_radius():
    c = arc(20.0, 180.0)
    left, right = c.offset_curves(3.5)
    centre = np.array([0.0, 20.0])
    np.testing.assert_allclose(np.hypot(*(np.asarray(left.coords) - centre).T), 16.5, atol=1e-5)
    np.testing.assert_allclose(np.hypot(*(np.asarray(right.coords) - centre).T), 23.5, atol=1e-5)


@pytest.mark.parametrize("path", [arc(12.0, 250.0), Centerline.from_svg_path("M0 0 C 30 0 30 40 60 40 S 90 0 120 0")])
def test_project_inverts_offset_point(path):
    rng = np.random.default_rng(1)
    s = rng.uniform(0.0, path.length_mm, 400)
    off = rng.uniform(-3.5, 3.5, 400)
    s2, off2 = path.project(path.offset_point_at(s, off))
    np.testing.assert_allclose(s2, s, atol=1e-7)
    np.testing.assert_allclose(off2, off, atol=1e-7)


@settings(max_examples=60, deadline=None)
@given(
    st.floats(1.0, 500.0),
    st.floats(-180.0, 180.0, allow_subnormal=False),  # subnormal angles are refused (check_range)
    st.floats(0.0, 1.0),
    st.floats(-20.0, 20.0),
)
def test_project_straight_property(length, rot, frac, off):
    c = Centerline.straight(length, origin_mm=(3.0, -7.0), rotation_deg=rot)
    s, o = c.project(c.offset_point_at(frac * length, off))
    assert s[0] == pytest.approx(frac * length, abs=1e-7)
    assert o[0] == pytest.approx(off, abs=1e-7)


def test_transformed_rotates_then_moves():
    c = Centerline.from_points([[0, 0], [10, 0]]).transformed(origin_mm=(5, 5), rotation_deg=90)
    np.testing.assert_allclose(c.points_mm, [[5, 5], [5, 15]], atol=1e-12)


def test_import_patterns_is_light():
    code = "import sys, embroact.patterns; print(any(m.split('.')[0] in ('scipy', 'trimesh') for m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


@given(st.integers(2, 60), st.integers(0, 2**31 - 1))
@settings(max_examples=40, deadline=None)
def test_segment_index_finds_the_nearest_segment_as_brute_force_does(n, seed):
    """Against the distance to every segment: random polylines (zero-length segments, long and short ones)
    and points near, on and far from them."""
    from embroact.patterns.spatial import SegmentIndex

    rng = np.random.default_rng(seed)
    xy = np.cumsum(rng.normal(0.0, 1.0, (n, 2)) * rng.choice([0.0, 0.1, 1.0, 20.0], (n, 1)), axis=0)
    p = np.concatenate([xy[rng.integers(0, n, 30)] + rng.normal(0.0, 2.0, (30, 2)), xy[:3],
                        rng.normal(0.0, 500.0, (10, 2))])
    a, d = xy[:-1], np.diff(xy, axis=0)

    def dist(seg, q):
        r = q - a[seg]
        len2 = np.einsum("ij,ij->i", d[seg], d[seg])
        t = np.clip(np.einsum("ij,ij->i", r, d[seg]) / np.where(len2 > 0, len2, 1.0), 0.0, 1.0)
        return np.hypot(*(r - t[:, None] * d[seg]).T)

    every = np.array([dist(np.full(len(p), k), p) for k in range(n - 1)])
    index = SegmentIndex(xy)
    got = dist(index.nearest(p), p)
    assert np.allclose(got, every.min(axis=0), rtol=0.0, atol=1e-9)
    many = np.repeat(p, 10, axis=0) + rng.normal(0.0, 0.01, (10 * len(p), 2))  # past the sample's size
    many_every = np.array([dist(np.full(len(many), k), many) for k in range(n - 1)]).min(axis=0)
    assert np.allclose(dist(index.nearest(many), many), many_every, rtol=0.0, atol=1e-9)
    for radius in (0.05, 1.0, 3.0, 50.0):  # points within a radius: the same points as brute force, ascending
        far_enough = np.abs(many_every - radius) > 1e-9
        want = np.flatnonzero(many_every < radius)
        got_within = index.within(many, radius)
        assert np.array_equal(got_within[far_enough[got_within]], want[far_enough[want]]), radius


def test_project_on_a_long_path_is_linear_and_builds_its_index_once():
    """A 10x longer sine path (10x the points) costs about 10x, not 100x; the index is made on the first
    projection and kept (counted, not timed: the second call builds nothing)."""
    from embroact.patterns import spatial

    x = np.linspace(0.0, 20_000.0, 20_001)
    c = Centerline.from_points(np.column_stack([x, 20.0 * np.sin(x / 30.0)]))
    made = []
    original = spatial.SegmentIndex._grid

    def counted(self, cell):
        made.append(cell not in self._grids)
        return original(self, cell)

    spatial.SegmentIndex._grid = counted
    try:
        q = c.offset_point_at(np.linspace(0.0, c.length_mm, 5000), 3.0)
        s1, off1 = c.project(q)
        first = sum(made)
        s2, _ = c.project(q)
    finally:
        spatial.SegmentIndex._grid = original
    assert first >= 1 and sum(made) == first  # no bucket made again
    assert np.allclose(off1, 3.0, atol=1e-6) and np.array_equal(s1, s2)
    assert np.allclose(s1, np.linspace(0.0, c.length_mm, 5000), atol=1e-6)
