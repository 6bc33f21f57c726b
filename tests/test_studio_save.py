"""The studio's save of a design read from a file: byte-identical outside the fields the user changed.

The expected text is made from the file's own text by replacing the edited lines by hand
(re.sub on the original), not by the code that saves; drawing references, comments, key
order and number spelling are the user's. Saving into another folder rewrites only the
relative references, so the saved file still names the same drawing.
"""
from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

pytest.importorskip("tomlkit")

from embroact.export.files.designfile import load_design
from embroact.export.studio.session import Studio

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@pytest.fixture
def drawn(tmp_path):
    """The Inkscape example (two actuators drawn in an SVG, comments) in a folder of its own."""
    folder = tmp_path / "design"
    folder.mkdir()
    for name in ("inkscape_tubes.toml", "inkscape_tubes.svg"):
        shutil.copy(EXAMPLES / name, folder / name)
    return folder / "inkscape_tubes.toml"


def _studio(path: Path, out: Path) -> Studio:
    design = load_design(path)
    return Studio(design, out, source=(path, design))


def test_saved_file_is_the_users_file_but_for_the_edited_fields(drawn):
    studio = _studio(drawn, drawn.parent)
    studio.edit({"actuator[1].interval_mm": 1.6, "machine.hoop_width_mm": 260.0})
    studio.save("edited.toml")
    original = drawn.read_text(encoding="utf-8")
    saved = (drawn.parent / "edited.toml").read_text(encoding="utf-8")
    # by hand: the second actuator's interval line changes; a [machine] table is added at the end
    head, sep, tail = original.partition('name = "arc"')
    expected = head + sep + re.sub(r"(?m)^interval_mm = 1\.4$", "interval_mm = 1.6", tail, count=1)
    assert saved.startswith(expected.rstrip("\n")) and expected != original
    added = saved[len(expected.rstrip("\n")):]
    assert "[machine]" in added and "hoop_width_mm = 260.0" in added and added.count("\n") <= 4
    assert 'path = "inkscape_tubes.svg#tube1"     # by id;' in saved  # the reference and its comment
    assert saved.startswith("# Two actuators whose tube paths were drawn in Inkscape")
    again = load_design(drawn.parent / "edited.toml")
    assert again == studio.design


def test_saving_unchanged_writes_the_same_bytes(drawn):
    studio = _studio(drawn, drawn.parent)
    studio.save("same.toml")
    assert (drawn.parent / "same.toml").read_bytes() == drawn.read_bytes()


def test_saving_elsewhere_points_the_references_at_the_same_drawing(drawn, tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    studio = _studio(drawn, out)
    studio.edit({"actuator[0].width_mm": 8.0})
    studio.save("moved.toml")
    saved = (out / "moved.toml").read_text(encoding="utf-8")
    assert 'path = "../design/inkscape_tubes.svg#tube1"     # by id;' in saved
    assert saved.count("\n") == drawn.read_text(encoding="utf-8").count("\n")
    assert load_design(out / "moved.toml") == studio.design


def test_a_design_without_a_file_is_saved_whole(tmp_path):
    from embroact.patterns.design import default_design

    studio = Studio(default_design(), tmp_path)
    studio.save("d.toml")
    assert load_design(tmp_path / "d.toml") == default_design()
