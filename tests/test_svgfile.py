"""SVG drawings as tube paths: units, viewBox, transforms, selection, and the Inkscape example end to end.

Expected geometry is derived by hand from the drawing's numbers (px = 25.4/96 mm, the layer's
translate, the group's rotation about the arc centre), and the machine file is read back with
the independent DST decoder in tests/dst_decoder.py.
"""
import json
from pathlib import Path

import numpy as np
import pytest
import shapely

import dst_decoder
from embroact.export.cli.main import main
from embroact.export.files.designfile import load_design, loads_design
from embroact.export.files.svgfile import is_svg_ref, read_svg_path, split_ref, svg_centerline, svg_origin_mm
from embroact.patterns.base.errors import DesignFileError, PathError

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
DRAWING = EXAMPLES / "inkscape_tubes.svg"
MM = 25.4 / 96.0  # mm per CSS px
LAYER_PX = np.array([-37.795276, 75.590551])  # the example layer's translate
W_MM = 7.0
DST_GRID_MM = 0.1

SVG_HEAD = ('<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
            'width="{w}" height="{h}"{vb}>')


def _svg(tmp_path, body, *, w="210mm", h="297mm", vb=' viewBox="0 0 793.70081 1122.5197"', name="d.svg"):
    path = tmp_path / name
    path.write_text(SVG_HEAD.format(w=w, h=h, vb=vb) + body + "</svg>", encoding="utf-8")
    return path


def _tube1_page_mm(n=20001):
    """The example's tube1 (relative cubic from (188.97638, 151.1811) px), in page mm, y down."""
    p0 = np.array([188.97638, 151.1811])
    c1, c2, p3 = p0 + [125.98413, -75.59055], p0 + [251.96863, 75.59055], p0 + [377.95276, 0.0]
    t = np.linspace(0.0, 1.0, n)[:, None]
    b = (1 - t) ** 3 * p0 + 3 * (1 - t) ** 2 * t * c1 + 3 * (1 - t) * t**2 * c2 + t**3 * p3
    return (b + LAYER_PX) * MM


ARC_CENTRE_PAGE_MM = (np.array([377.95276, 491.33858]) + LAYER_PX) * MM  # the rotation is about the centre
ARC_R_MM = 188.97638 * MM
ARC_DEG = (170.0 + 30.0, 310.0 + 30.0)  # drawn from 170 to 310 deg (y down), group rotated by +30 deg


def _actuator_stitches(dst_bytes):
    """Needle points [mm] per actuator (a stop starts the next one), DST frame (y up)."""
    groups: list[list] = []
    for r in dst_decoder.decode(dst_bytes).records:
        if r.kind == "stop":
            groups.append([])
        elif r.kind == "stitch" and groups:
            groups[-1].append((r.x / 10.0, r.y / 10.0))
    return [np.array(g) for g in groups]


# ---------------------------------------------------------------------- the example, end to end
@pytest.fixture(scope="module")
def example_dst(tmp_path_factory):
    out = tmp_path_factory.mktemp("inkscape")
    assert main(["build", str(EXAMPLES / "inkscape_tubes.toml"), "--out", str(out)]) == 0
    return (out / "inkscape-tubes.dst").read_bytes()


def test_hand_values_of_the_drawing():
    # the numbers the tests below rely on, from the drawing by hand: page (90, 150) mm, R 50 mm
    np.testing.assert_allclose(ARC_CENTRE_PAGE_MM, [90.0, 150.0], atol=1e-5)
    assert ARC_R_MM == pytest.approx(50.0, abs=1e-5)
    np.testing.assert_allclose(_tube1_page_mm()[[0, -1]], [[40.0, 60.0], [140.0, 60.0]], atol=1e-5)


def _origin_mm():
    """Where the example's machine file starts in its design (plan frame): the centre of its extent."""
    from embroact.patterns.design import build_plan

    return np.array(build_plan(load_design(EXAMPLES / "inkscape_tubes.toml")).origin_mm)


def test_decoded_dst_lies_on_the_drawn_paths_within_0p1_mm(example_dst):
    zig, arc = (p + _origin_mm() for p in _actuator_stitches(example_dst))  # the file's frame -> the drawing's
    # zigzag on the S-curve: every needle point on a rail, w/2 from the drawn curve
    curve = shapely.LineString(_tube1_page_mm() * [1.0, -1.0])  # plan frame = DST frame: y up
    d = shapely.distance(curve, shapely.points(zig))
    assert np.abs(d - W_MM / 2).max() <= DST_GRID_MM, np.abs(d - W_MM / 2).max()
    # cross pattern on the rotated arc: every needle point w/2 from the circle of radius 50 mm
    c = ARC_CENTRE_PAGE_MM * [1.0, -1.0]
    r = np.hypot(*(arc - c).T)
    assert np.abs(np.abs(r - ARC_R_MM) - W_MM / 2).max() <= DST_GRID_MM
    # ... and between the arc's drawn end angles (page frame: y down)
    ang = np.degrees(np.arctan2(-(arc[:, 1] - c[1]), arc[:, 0] - c[0])) % 360.0
    assert ang.min() >= ARC_DEG[0] - 0.5 and ang.max() <= ARC_DEG[1] + 0.5
    assert ang.min() <= ARC_DEG[0] + 2.0 and ang.max() >= ARC_DEG[1] - 2.0  # covers the whole arc
    # the S-curve's needles span it from end to end too
    s = shapely.line_locate_point(curve, shapely.points(zig))
    assert s.min() <= 2.0 and s.max() >= curve.length - 2.0


def test_quick_command_takes_the_same_path_and_check_agrees(tmp_path, capsys, example_dst):
    _, arc_design = _actuator_stitches(example_dst)
    out = tmp_path / "arc.dst"
    ref = f"{DRAWING}#tube2"
    ox, oy = _origin_mm()
    assert main(["cross", "--width-mm", "7", "--interval-mm", "1.4", "--angle-deg", "45", "--name", "arc",
                 "--path", ref, "-o", str(out), "--origin", f"{ox:g},{oy:g}"]) == 0  # the design's start point
    (arc_quick,) = _actuator_stitches(out.read_bytes())
    np.testing.assert_array_equal(arc_quick, arc_design)  # the same needle points, design or quick command
    capsys.readouterr()
    # check speaks the file's frame (y down); --origin-mm places the drawing's page coordinates in it
    at = ["--origin-mm", f"{ox:g},{-oy:g}"]
    assert main(["check", str(out), "--tube-path", ref, "--json", *at]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["tubes"] == 1 and not [f for f in doc["findings"] if f["code"] == "EA101"]
    # control: the same tube drawn 3 mm lower puts the rail's needle points inside its corridor
    moved = tmp_path / "moved.svg"  # the layer moved 3 mm (11.338583 px) further down
    moved.write_text(DRAWING.read_text().replace("translate(-37.795276,75.590551)", "translate(-37.795276,86.929134)"))
    assert main(["check", str(out), "--tube-path", f"{moved}#tube2", "--json", *at]) == 1
    assert any(f["code"] == "EA101" for f in json.loads(capsys.readouterr().out)["findings"])


def test_check_design_against_its_own_drawing(tmp_path, capsys, example_dst):
    dst = tmp_path / "d.dst"
    dst.write_bytes(example_dst)
    ox, oy = _origin_mm()
    tubes = ["--tube-path", f"{DRAWING}#tube1", "--tube-path", f"{DRAWING}#cross tube"]
    assert main(["check", str(dst), *tubes, "--origin-mm", f"{ox:g},{-oy:g}", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["tubes"] == 2 and doc["counts"]["error"] == 0
    # the worksheet states that origin for this check
    out = tmp_path / "out"
    out.mkdir()
    assert main(["build", str(EXAMPLES / "inkscape_tubes.toml"), "--out", str(out), "--no-previews"]) == 0
    assert f"--origin-mm {ox:g},{-oy:g})" in (out / "worksheet.txt").read_text(encoding="utf-8")
    capsys.readouterr()
    assert main(["check", str(dst), *tubes, "--json"]) == 1  # without it, the drawing's frame is not the file's


# ---------------------------------------------------------------------- units, viewBox, transforms
@pytest.mark.parametrize("w, h, vb, scale", [
    ("210mm", "297mm", ' viewBox="0 0 793.70081 1122.5197"', MM),  # Inkscape 1.x, px user unit
    ("793.70081", "1122.5197", "", MM),  # no unit, no viewBox: user unit = px
    ("210mm", "297mm", ' viewBox="0 0 210 297"', 1.0),  # mm user unit
    ("8.2677165in", "11.692913in", ' viewBox="0 0 210 297"', 1.0 - 5.4e-7),  # svgelements' inch, documented
    ("100mm", "100mm", ' viewBox="0 0 50 50"', 2.0),  # 2 mm per user unit
])
def test_units_and_viewbox(tmp_path, w, h, vb, scale):
    p = _svg(tmp_path, '<path id="t" d="M 10 20 L 40 20"/>', w=w, h=h, vb=vb)
    np.testing.assert_allclose(read_svg_path(f"{p}#t").points_mm, [[10 * scale, 20 * scale], [40 * scale, 20 * scale]],
                               atol=1e-5)  # 10 nm: Inkscape rounds viewBox numbers to 8 digits


def test_nested_transforms_apply_in_order(tmp_path):
    body = ('<g inkscape:groupmode="layer" inkscape:label="L" transform="translate(100,0)">'
            '<g transform="rotate(90)"><g transform="scale(2)"><path id="t" d="M 0 0 L 10 0"/></g></g></g>')
    p = _svg(tmp_path, body, w="200mm", h="200mm", vb=' viewBox="0 0 200 200"')
    # scale 2 -> (20, 0); rotate 90 (y down: +x to +y) -> (0, 20); translate -> (100, 20)
    np.testing.assert_allclose(read_svg_path(p).points_mm, [[100.0, 0.0], [100.0, 20.0]], atol=1e-9)


def test_arc_under_non_uniform_scale_stays_an_ellipse(tmp_path):
    p = _svg(tmp_path, '<path id="t" transform="scale(2,1)" d="M 0 10 A 10 10 0 0 1 20 10"/>',
             w="100mm", h="100mm", vb=' viewBox="0 0 100 100"')
    x, y = read_svg_path(p).points_mm.T
    # circle centre (10, 10) r 10, scaled by 2 in x: ellipse centre (20, 10), semi-axes 20, 10
    np.testing.assert_allclose(((x - 20) / 20) ** 2 + ((y - 10) / 10) ** 2, 1.0, atol=1e-9)


# ---------------------------------------------------------------------- choosing a path
def test_choose_by_id_label_and_layer():
    by_id, by_label = read_svg_path(f"{DRAWING}#tube2"), read_svg_path(f"{DRAWING}#cross tube")
    by_group = read_svg_path(f"{DRAWING}#rotated arc")
    np.testing.assert_array_equal(by_id.points_mm, by_label.points_mm)
    np.testing.assert_array_equal(by_id.points_mm, by_group.points_mm)
    assert (by_id.element_id, by_id.label, by_id.layer) == ("tube2", "cross tube", "Tubes")
    with pytest.raises(PathError, match="2 paths in the group or layer with label 'Tubes'"):
        read_svg_path(f"{DRAWING}#Tubes")  # the layer holds two paths


@pytest.mark.parametrize("ref, fragment", [
    ("#tube9", "no visible path, group or layer with id or label 'tube9'; paths: tube1 (label 'zigzag tube'"),
    ("#scale-bar", "no visible path"),  # on a hidden layer
    ("", "holds 2 visible paths, name one with"),
])
def test_choice_errors_name_the_file_and_list_the_paths(ref, fragment):
    with pytest.raises(PathError) as exc:
        read_svg_path(f"{DRAWING}{ref}")
    assert str(exc.value).startswith(str(DRAWING)) and fragment in str(exc.value)


@pytest.mark.parametrize("body, fragment", [
    ('<path id="t" d="M 0 0 L 10 0 M 20 0 L 30 0"/>', "gap of"),
    ('<path id="t" d="M 0 0 L 10 0 L 10 10 Z"/>', "closed path"),
    ('<circle id="t" cx="50" cy="50" r="10"/>', "closed path"),
])
def test_path_errors(tmp_path, body, fragment):
    p = _svg(tmp_path, body, w="100mm", h="100mm", vb=' viewBox="0 0 100 100"')
    with pytest.raises(PathError) as exc:
        svg_centerline(f"{p}#t")
    assert str(exc.value).startswith(f"{p}#t: ") and fragment in str(exc.value)


def test_unreadable_files(tmp_path):
    garbage = tmp_path / "g.svg"
    garbage.write_text("<svg><path d=", encoding="utf-8")
    with pytest.raises(PathError, match="not a readable SVG file"):
        read_svg_path(garbage)
    with pytest.raises(PathError, match="cannot read SVG file"):
        read_svg_path(tmp_path / "none.svg")


def test_reference_syntax():
    assert split_ref("dir/a b.svg#tube 1") == ("dir/a b.svg", "tube 1")
    assert is_svg_ref("x.svg") and is_svg_ref("X.SVG#t") and not is_svg_ref("M 0 0 L 1 0") and not is_svg_ref(3)


# ---------------------------------------------------------------------- design files and commands
def test_design_file_resolves_relative_to_itself(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # not the examples folder
    d = load_design(EXAMPLES / "inkscape_tubes.toml")
    np.testing.assert_allclose(d.actuators[1].centerline.points_mm, svg_centerline(f"{DRAWING}#tube2").points_mm)
    np.testing.assert_allclose(d.actuators[0].centerline.points_mm[[0, -1]], [[40.0, -60.0], [140.0, -60.0]],
                               atol=1e-3)


def test_design_file_svg_errors_name_the_key(tmp_path):
    text = ('[[actuator]]\nname = "A"\npattern = "zigzag"\nwidth_mm = 7\ninterval_mm = 1\n'
            'path = "inkscape_tubes.svg#nope"\n')
    with pytest.raises(DesignFileError) as exc:
        loads_design(text, source="x.toml", base_dir=EXAMPLES)
    assert str(exc.value).startswith("x.toml: actuator[0].path: ") and "'nope'" in str(exc.value)
    with pytest.raises(DesignFileError, match="x.toml: actuator.0..path: .*cannot read SVG file"):
        loads_design(text, source="x.toml", base_dir=tmp_path)


def test_origin_and_rotation_apply_after_the_drawing():
    text = ('[[actuator]]\nname = "A"\npattern = "zigzag"\nwidth_mm = 7\ninterval_mm = 1\n'
            'path = "inkscape_tubes.svg#tube1"\norigin_mm = [-40.0, 60.0]\n')
    start = loads_design(text, base_dir=EXAMPLES).actuators[0].centerline.points_mm[0]
    np.testing.assert_allclose(start, [0.0, 0.0], atol=1e-3)


def test_quick_command_errors_are_one_line(tmp_path, capsys):
    code = main(["zigzag", "--width-mm", "7", "--interval-mm", "1", "--path", f"{DRAWING}#nope",
                 "-o", str(tmp_path / "a.dst")])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and "'nope'" in err
    assert not (tmp_path / "a.dst").exists()


# ---------------------------------------------------------------------- malformed data, clones, markers
@pytest.mark.parametrize("d, fragment", [
    ("M 0 0 L 10 0 L 20", "'L' at character 13 needs numbers in groups of 2, got 1"),
    ("M 0 0 L 10 0 L 20 x 5", "unexpected 'x' at character 18"),  # svgelements would stop there: a 10 mm tube
    ("M 0 0 A 5 5 0 2 1 10 0", "arc flag at character 14 must be 0 or 1, got '2'"),
])
def test_malformed_path_data_names_the_element_and_the_character(tmp_path, d, fragment):
    p = _svg(tmp_path, f'<path id="t" d="{d}"/>', w="100mm", h="100mm", vb=' viewBox="0 0 100 100"')
    with pytest.raises(PathError) as exc:
        read_svg_path(f"{p}#t")
    assert str(exc.value).startswith(f"{p}#t: path data d: ") and fragment in str(exc.value)
    assert "\n" not in str(exc.value)


def test_clones_beyond_the_budget_or_of_themselves_are_refused(tmp_path):
    from embroact.export.files.svgclones import MAX_CLONES

    # each level clones the one below 10 times: 10**5 copies of the path from a 2 kB file
    levels = ['<g id="g0"><path id="p" d="M 0 0 H 10"/></g>']
    levels += [f'<g id="g{k}">' + f'<use xlink:href="#g{k - 1}"/>' * 10 + "</g>" for k in range(1, 6)]
    p = _svg(tmp_path, '<defs xmlns:xlink="http://www.w3.org/1999/xlink">' + "".join(levels) + "</defs>"
             '<use href="#g5"/>', name="bomb.svg")
    with pytest.raises(PathError, match=f"more than {MAX_CLONES:,} copies"):
        read_svg_path(p)
    loop = _svg(tmp_path, '<g id="a"><path d="M 0 0 H 10"/><use href="#a"/></g>', name="loop.svg")
    with pytest.raises(PathError, match="names an element holding it"):
        read_svg_path(loop)


def test_origin_marker_is_the_centre_of_the_shape_so_named(tmp_path):
    p = _svg(tmp_path, '<path id="t" d="M 0 0 H 50"/><g transform="translate(10,20)">'
             '<circle inkscape:label="embroact-origin" cx="30" cy="40" r="2"/></g>',
             w="100mm", h="100mm", vb=' viewBox="0 0 100 100"')
    assert svg_origin_mm(p) == pytest.approx((40.0, 60.0))
    assert read_svg_path(p).element_id == "t"  # the marker is no tube
    two = _svg(tmp_path, '<path d="M 0 0 H 50"/><circle id="embroact-origin" r="1"/>'
               '<circle inkscape:label="embroact-origin" r="1"/>', name="two.svg")
    with pytest.raises(PathError, match="2 origin markers"):
        svg_origin_mm(two)
