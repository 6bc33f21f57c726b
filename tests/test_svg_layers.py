"""Output SVGs in Inkscape layers, their tube axes with ids: edited in Inkscape, read back as input.

``template.svg`` and the stitch preview group their parts in Inkscape layers (``inkscape:groupmode``,
``inkscape:label``); each tube's axis carries the Inkscape label ``tube-NAME`` and that as an id (``svg_id``: other
characters as ``_``), so ``--path template.svg#tube-A1`` reads it back. The read-back path is the plan's tube path, moved by the picture's page offset
(the drawing's frame is its page), point for point. Where Inkscape is installed it must list
the same ids.
"""
from __future__ import annotations

import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from embroact.export.cli.main import main
from embroact.export.files.designfile import load_design
from embroact.export.files.svgfile import read_svg_path
from embroact.patterns.design import build_plan

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
INK = "{http://www.inkscape.org/namespaces/inkscape}"


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("layers")
    assert main(["build", str(EXAMPLES / "three_actuators.toml"), "--out", str(out)]) == 0
    return out, build_plan(load_design(EXAMPLES / "three_actuators.toml"))


@pytest.mark.parametrize("picture, layers", [
    ("template.svg", ["hoop", "start", "tubes", "scale-bar", "notes"]),
    ("preview.svg", ["fabric", "corridor", "tube", "centerline", "rails", "travel", "placement", "legs",
                     "needle-points", "ties", "stops", "trims", "scale-bar", "params", "legend"]),
])
def test_pictures_are_in_inkscape_layers(built, picture, layers):
    root = ET.parse(built[0] / picture).getroot()
    found = [(g.get("id"), g.get(f"{INK}label")) for g in root.iter("{http://www.w3.org/2000/svg}g")
             if g.get(f"{INK}groupmode") == "layer"]
    assert found == [(name, name) for name in layers]


@pytest.mark.parametrize("picture", ["template.svg", "preview.svg"])
def test_tube_axes_read_back_as_the_plan_paths(built, picture):
    out, plan = built
    root = ET.parse(out / picture).getroot()
    vx, vy = (float(v) for v in root.get("viewBox").split()[:2])
    for a in plan.actuators:
        back = read_svg_path(f"{out / picture}#tube-{a.name}").points_mm  # mm, page frame, y down
        expected = a.centerline.points_mm * [1.0, -1.0] - [vx, vy]
        if picture == "template.svg":  # the template draws the embroidered stretch: the whole path here
            assert len(back) == len(expected)
        np.testing.assert_allclose(back, expected, atol=1e-3)  # the pictures write 0.001 mm


def test_a_tube_from_the_template_builds_the_same_actuator(built, tmp_path, capsys):
    out, plan = built
    dst = tmp_path / "again.dst"
    a = plan.actuators[0]
    args = ["zigzag", "--path", f"{out / 'template.svg'}#tube-{a.name}", "--width-mm", f"{a.params.width_mm:g}",
            "--interval-mm", f"{a.params.interval_mm:g}", "-o", str(dst), "--json"]
    assert main(args) == 0
    import json

    doc = json.loads(capsys.readouterr().out)
    from embroact.patterns.plan import Command

    assert doc["stitch_count"] == int(np.count_nonzero((plan.commands == Command.STITCH) & (plan.actuator == 0)))


@pytest.mark.skipif(shutil.which("inkscape") is None, reason="Inkscape is not installed")
def test_inkscape_sees_the_layers_and_ids(built):
    out = subprocess.run(["inkscape", "--query-all", str(built[0] / "template.svg")], capture_output=True,
                         text=True, timeout=120, check=True).stdout
    ids = {line.split(",")[0] for line in out.splitlines()}
    assert {"hoop", "start", "tubes", "tube-narrow_zigzag", "tube-wide_zigzag", "tube-cross_45_"} <= ids
