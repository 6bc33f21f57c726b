"""SVG drawings read as Inkscape reads them: every length and point within 0.01 mm.

The drawings in tests/data/inkscape cover arcs under non-uniform scale, skew, rotation and
general matrices, clones (of paths, of groups, of clones), layers (locked, hidden), nested
groups, mm / px / in / pt documents and Ink/Stitch commands. Their references come from
Inkscape 1.2 (``make_references.sh`` there): ``--query-all`` bounding boxes, and the
drawings as Inkscape flattens them (clones unlinked, groups ungrouped: Inkscape itself
pushes every transform into the path data, turning an arc under a matrix into another
arc). Lengths and points of those flattened paths are computed by tests/inkref.py (SVG 1.1
arc formulas, mpmath quadrature), independent of embroact and svgelements. Where Inkscape
is installed, one more test runs it on the drawings and compares with the committed files.
"""
from __future__ import annotations

import csv
import io
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from embroact.export.files.svgfile import read_svg_path, svg_origin_mm
from embroact.patterns.base.errors import PathError

import inkref

DATA = Path(__file__).parent / "data" / "inkscape"
MM_PER_PX = 25.4 / 96.0
#: mm per user unit of each drawing (its width unit over its viewBox)
UNIT_MM = {"arcs": 1.0, "clones": 1.0, "inkstitch": 1.0, "units_mm": 1.0, "units_px": MM_PER_PX,
           "units_in": 25.4, "units_pt": 25.4 / 72.0}
#: (drawing, the name a user gives (id or label), the id of the path in Inkscape's flattened output;
#: None: the one path Inkscape made, a copy it named itself)
CASES = [
    ("arcs", "scaled", "scaled"), ("arcs", "skewed", "skewed"), ("arcs", "rotated", "rotated"),
    ("arcs", "matrix", "matrix"), ("arcs", "nested", "nested"),
    ("units_mm", "bezier", "bezier"), ("units_mm", "poly", "poly"), ("units_mm", "quad", "quad"),
    ("units_mm", "line", "line"), ("units_px", "pxcurve", "pxcurve"), ("units_px", "pxarc", "pxarc"),
    ("units_in", "incurve", "incurve"), ("units_pt", "ptcurve", "ptcurve"),
    ("clones", "original", "original"), ("clones", "clone", "clone"), ("clones", "pair", "inpair"),
    ("clones", "pairclone", None), ("clones", "cloneofclone", "cloneofclone"), ("clones", "Locked", "locked"),
    ("inkstitch", "tube", "tube"),
]
#: ids --query-all lists where the name is a label or the flattened copy was renamed
QUERY_ID = {"Locked": "locked", "pairclone": "pairclone"}
TOL_MM = 0.01


def _flattened(drawing: str) -> dict[str | None, str]:
    root = ET.parse(DATA / f"{drawing}.inkscape.svg").getroot()
    paths = {el.get("id"): el.get("d") for el in root.iter() if el.get("d") is not None}
    drawn = {el.get("id") for el in ET.parse(DATA / f"{drawing}.svg").getroot().iter()}
    made = [k for k in paths if k not in drawn]
    return paths | ({None: paths[made[0]]} if len(made) == 1 else {})


def _query(drawing: str) -> dict[str, np.ndarray]:
    rows = csv.reader(io.StringIO((DATA / f"{drawing}.query.csv").read_text()))
    return {r[0]: np.array([float(v) for v in r[1:]]) * MM_PER_PX for r in rows if r}


@pytest.mark.parametrize("drawing, name, flat_id", CASES)
def test_length_and_points_agree_with_inkscape(drawing, name, flat_id):
    ours = read_svg_path(DATA / f"{drawing}.svg#{name}").points_mm
    segs = inkref.segments(_flattened(drawing)[flat_id])
    scale = UNIT_MM[drawing]
    ref_len = float(inkref.length(segs, scale))
    our_len = float(np.sum(np.hypot(*np.diff(ours, axis=0).T)))
    assert abs(our_len - ref_len) <= TOL_MM, (our_len, ref_len)
    ref = inkref.sample(segs, 400, scale)
    assert inkref.distances_to_polyline(ref, ours).max() <= TOL_MM  # every point of Inkscape's curve
    assert inkref.distances_to_polyline(ours, ref).max() <= TOL_MM  # every point read
    np.testing.assert_allclose(ours[[0, -1]], ref[[0, -1]], atol=1e-3)  # ends (inches: svgelements 5.4e-7 short)


@pytest.mark.parametrize("drawing, name, flat_id", CASES)
def test_bounding_boxes_agree_with_inkscape_query_all(drawing, name, flat_id):
    ours = read_svg_path(DATA / f"{drawing}.svg#{name}").points_mm
    x, y, w, h = _query(drawing)[QUERY_ID.get(name, flat_id)]
    np.testing.assert_allclose([*ours.min(axis=0), *ours.max(axis=0)], [x, y, x + w, y + h], atol=TOL_MM)


def test_the_arcs_svgelements_reifies_wrongly_are_exact():
    """The issue's case: an arc under matrix(2,0,0,1) read 2.3 mm too long before (104.96 for 102.62 mm)."""
    segs = inkref.segments(_flattened("arcs")["scaled"])
    ours = read_svg_path(DATA / "arcs.svg#scaled").points_mm
    assert abs(float(np.sum(np.hypot(*np.diff(ours, axis=0).T))) - float(inkref.length(segs))) < 0.005


def test_hidden_layers_are_not_drawn_locked_ones_are():
    with pytest.raises(PathError, match="no visible path"):
        read_svg_path(DATA / "clones.svg#hidden")
    assert read_svg_path(DATA / "clones.svg#locked").layer == "Locked"


def test_clones_are_found_by_their_own_id_and_the_original_by_its():
    by_clone = read_svg_path(DATA / "clones.svg#clone")
    assert by_clone.element_id == "original"  # the drawn element is a copy of the original
    original = read_svg_path(DATA / "clones.svg#original").points_mm
    assert not np.allclose(by_clone.points_mm[0], original[0])
    with pytest.raises(PathError, match="holds 6 visible paths"):  # 3 drawn (1 locked) + 3 clones
        read_svg_path(DATA / "clones.svg")


def test_inkstitch_commands_are_no_tubes_and_its_origin_command_is_the_origin():
    tube = read_svg_path(DATA / "inkstitch.svg")  # the only path: connector and symbols ignored
    assert tube.element_id == "tube"
    # origin command at x=100, y=150 under translate(5,-3)
    assert svg_origin_mm(DATA / "inkstitch.svg") == pytest.approx((105.0, 147.0), abs=1e-9)
    assert svg_origin_mm(DATA / "arcs.svg") is None


@pytest.mark.skipif(shutil.which("inkscape") is None, reason="Inkscape is not installed")
def test_committed_references_are_what_inkscape_reports_now(tmp_path):
    for drawing in UNIT_MM:
        out = subprocess.run(["inkscape", "--query-all", str(DATA / f"{drawing}.svg")], capture_output=True,
                             text=True, timeout=120, check=True).stdout
        live = {r[0]: np.array([float(v) for v in r[1:]]) for r in csv.reader(io.StringIO(out)) if r}
        committed = {k: v / MM_PER_PX for k, v in _query(drawing).items()}
        assert live.keys() == committed.keys()
        for key in live:
            np.testing.assert_allclose(live[key], committed[key], atol=1e-3)
