"""The machine origin: the written file starts where the embroiderer expects, and build and check agree.

20 seeded drawings, each a tube drawn anywhere on an A4 or A3 page (groups, rotations), are
built as designs; the DST is read back with pystitch (a reader embroact did not write) and
checked with ``embroact check``. With the default origin (the centre of the design's extent)
every needle point lies within the 200 x 200 mm hoop centred on the file's start point; with
the origin at the page's corner (the frame the drawing was made in) the build's rule gate and
the check of the file written anyway agree on EA306 for every drawing.
"""
from __future__ import annotations

import json

import numpy as np
import pystitch
import pytest

from embroact.export.cli.main import main
from embroact.export.files.designfile import load_design, loads_design
from embroact.patterns.base.errors import DesignFileError
from embroact.patterns.design import build_plan
from embroact.patterns.origin import origin_point_mm
from embroact.patterns.plan import Command
from embroact.predict.analysis import analyse
from embroact.predict.rules import check_design

PAGES_MM = {"A4": (210.0, 297.0), "A3": (297.0, 420.0)}
HOOP_MM = 200.0
SEEDS = range(20)
SVG = ('<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
       'width="{w}mm" height="{h}mm" viewBox="0 0 {w} {h}"><g inkscape:groupmode="layer" inkscape:label="Tubes" '
       'transform="translate({tx:.3f},{ty:.3f}) rotate({rot:.2f})">'
       '<path id="tube" style="fill:none;stroke:#000" d="M 0 0 C {c1x:.2f} {c1y:.2f} {c2x:.2f} {c2y:.2f} {ex:.2f} 0"/>'
       '</g>{extra}</svg>')


def _drawing(tmp_path, seed: int, origin: str = "") -> tuple:
    """A tube 70-150 mm long at a random place and angle on an A4 (even seeds) or A3 page."""
    rng = np.random.default_rng(seed)
    page = "A4" if seed % 2 == 0 else "A3"
    w, h = PAGES_MM[page]
    span = rng.uniform(70.0, 150.0)
    rot = rng.uniform(-180.0, 180.0)
    dx, dy = span * np.cos(np.radians(rot)), span * np.sin(np.radians(rot))
    margin = 25.0  # room for the bulge and the zigzag: the whole tube on the page
    tx = rng.uniform(margin - min(0.0, dx), w - margin - max(0.0, dx))
    ty = rng.uniform(margin - min(0.0, dy), h - margin - max(0.0, dy))
    bulge = rng.uniform(-15.0, 15.0)
    extra = '<circle id="embroact-origin" cx="30" cy="40" r="1"/>' if origin == "marker" else ""
    svg = SVG.format(w=w, h=h, tx=tx, ty=ty, rot=rot, extra=extra, c1x=span / 3, c1y=bulge, c2x=2 * span / 3,
                     c2y=-bulge, ex=span)
    folder = tmp_path / f"d{seed}"
    folder.mkdir()
    (folder / "drawing.svg").write_text(svg, encoding="utf-8")
    machine = f"[machine]\norigin = {origin}\n" if origin and origin != "marker" else ""
    (folder / "design.toml").write_text(
        f'name = "seed{seed}"\n{machine}[[actuator]]\nname = "A1"\npattern = "zigzag"\nwidth_mm = 7.0\n'
        'interval_mm = 1.0\npath = "drawing.svg#tube"\n', encoding="utf-8")
    return folder, page


def _build_and_check(folder, capsys) -> tuple[set, set, np.ndarray]:
    """(the build gate's codes, the check's codes of the file written, the file's records [mm, y up])."""
    design = load_design(folder / "design.toml")
    gate = {f.code for f in check_design(analyse(design))}
    out = folder / "out"
    out.mkdir()
    assert main(["build", str(folder / "design.toml"), "--out", str(out), "--force"]) in (0, 1)
    dst = out / f"{design.name}.dst"
    capsys.readouterr()
    main(["check", str(dst), "--json"])
    checked = {f["code"] for f in json.loads(capsys.readouterr().out)["findings"]}
    pattern = pystitch.read(str(dst))
    xy = np.array([(x, -y) for x, y, cmd in pattern.stitches if cmd == pystitch.STITCH]) / 10.0
    return gate, checked, xy


@pytest.mark.parametrize("seed", SEEDS)
def test_default_origin_puts_the_design_in_the_hoop_around_the_start_point(tmp_path, capsys, seed):
    folder, page = _drawing(tmp_path, seed)
    gate, checked, xy = _build_and_check(folder, capsys)
    assert "EA306" not in gate and "EA306" not in checked, (page, gate, checked)
    # the machine starts at the hoop's centre: every needle point, the first included, within the hoop
    assert np.all(np.abs(xy[0]) <= HOOP_MM / 2.0)
    assert np.all(np.abs(xy) <= HOOP_MM / 2.0), np.abs(xy).max(axis=0)
    # the start point is the centre of the design's extent (to the 0.1 mm grid)
    np.testing.assert_allclose((xy.min(axis=0) + xy.max(axis=0)) / 2.0, 0.0, atol=0.11)


@pytest.mark.parametrize("seed", SEEDS)
def test_build_and_check_agree_on_the_hoop_with_the_origin_at_the_page_corner(tmp_path, capsys, seed):
    folder, page = _drawing(tmp_path, seed, origin="[0.0, 0.0]")
    gate, checked, _ = _build_and_check(folder, capsys)
    assert ("EA306" in gate) == ("EA306" in checked), (page, gate, checked)


def test_the_page_corner_is_outside_the_hoop_for_most_drawings(tmp_path, capsys):
    """The agreement above is not vacuous: the corner origin puts most of these drawings out of the hoop."""
    hits = 0
    for seed in SEEDS:
        folder, _ = _drawing(tmp_path, seed, origin="[0.0, 0.0]")
        hits += "EA306" in {f.code for f in check_design(analyse(load_design(folder / "design.toml")))}
    assert hits >= 10


def test_first_stitch_and_marker_origins(tmp_path):
    folder, _ = _drawing(tmp_path, 3, origin='"first-stitch"')
    plan = build_plan(load_design(folder / "design.toml"))
    np.testing.assert_allclose(plan.xy_mm[plan.commands == Command.STITCH][0], 0.0, atol=0.051)
    marked, _ = _drawing(tmp_path, 4, origin="marker")  # a circle at (30, 40) mm on the page, y down
    design = load_design(marked / "design.toml")
    assert design.machine.origin == pytest.approx((30.0, -40.0), abs=1e-9)


def test_origin_values_are_checked(tmp_path):
    base = '[[actuator]]\nname = "A"\npattern = "zigzag"\nwidth_mm = 7\ninterval_mm = 1\nlength_mm = 50\n'
    for bad in ('"middle"', "[1, 2, 3]", '["a", 1]', "[1e300, 0]"):
        with pytest.raises(DesignFileError, match=r"machine: origin must be \"center\", \"first-stitch\" or a point"):
            loads_design(f"[machine]\norigin = {bad}\n" + base)
    point = loads_design("[machine]\norigin = [10, 5]\n" + base)
    assert point.machine.origin == (10.0, 5.0)
    plan = build_plan(point)  # a 50 mm path from (0, 0): the point (10, 5) becomes the start
    assert origin_point_mm(plan, "center").tolist() == [15.0, -5.0]
