"""Generated hostile inputs of the third robustness round, every case under the 500 MB ceiling.

The classes, each generated rather than listed (the worker, ceiling and per-case time limit
are those of tests/test_hostile_generated.py):

* output clashes in every command that writes: two outputs naming one file (same name,
  ``./``, a hard link, a symbolic link) and an output naming an input (``fit data.csv -o
  data.csv``, ``design --target-shape hook.csv -o hook.csv``), and outputs that are no file
  (``.``, ``""``, ``/``);

Every error case ends with exit 2 (or 3), exactly one stderr line and no file changed.
"""
from __future__ import annotations

import itertools
import os
from pathlib import Path

from test_hostile import FIT, GOOD_CSV, ZZ
from test_hostile_generated import check_clean, check_error, run_cases

HOOK = "x_mm,y_mm\n0,0\n20,0\n40,2\n55,10\n62,25\n"
PATH_SVG = '<svg xmlns="http://www.w3.org/2000/svg" width="200mm" height="50mm" viewBox="0 0 200 50">' \
           '<path id="t" d="M 10 20 H 150"/></svg>'
DESIGN_SHAPE = ["design", "--target-shape", "hook.csv", "--at-kpa", "250", "--max-segments", "2"]
DESIGN_BEND = ["design", "--bend-deg", "60", "--at-kpa", "150", "--pattern", "zigzag"]


def _inputs(d: Path) -> dict[str, bytes]:
    files = {"hook.csv": HOOK.encode(), "data.csv": GOOD_CSV.encode(), "path.svg": PATH_SVG.encode()}
    for name, data in files.items():
        (d / name).write_bytes(data)
    os.link(d / "data.csv", d / "data-link.csv")
    (d / "hook-sym.csv").symlink_to(d / "hook.csv")
    (d / "sub").mkdir()
    return {p.name: p.read_bytes() for p in d.iterdir() if p.is_file()}


def test_output_clashes_in_every_writing_command(tmp_path):
    """Outputs naming one file or an input, in each spelling, are refused before any work."""
    before = _inputs(tmp_path)
    spellings = lambda name: [name, f"./{name}", f"sub/../{name}", str(tmp_path / name)]  # noqa: E731
    cases = []
    for i, o in enumerate(spellings("hook.csv") + ["hook-sym.csv"]):
        cases.append((f"design-input-{i}", DESIGN_SHAPE + ["-o", o], "target shape 'hook.csv'"))
    for i, (a, b) in enumerate(itertools.product(["a.toml"], spellings("a.toml"))):
        cases.append((f"design-svg-{i}", DESIGN_SHAPE + ["-o", a, "--svg", b], "two outputs"))
    for i, o in enumerate(spellings("data.csv") + ["data-link.csv"]):
        cases.append((f"fit-input-{i}", ["fit", "data.csv", *FIT, "-o", o], "data file 'data.csv'"))
        cases.append((f"fit-design-{i}", ["fit", "data.csv", *FIT, "--design", "hook.csv", "-o", "hook.csv"],
                      "design file 'hook.csv'"))
    for i, o in enumerate(spellings("path.svg")):
        cases.append((f"zigzag-preview-{i}", ZZ + ["--path", "path.svg#t", "-o", "a.dst", "--preview", o],
                      "path drawing 'path.svg'"))
    runs = [{"id": cid, "argv": argv, "cwd": str(tmp_path)} for cid, argv, _ in cases]
    results = run_cases(runs)
    for cid, argv, needle in cases:
        r = results[cid]
        check_error(r, 2)
        if needle == "two outputs":
            assert "two outputs name one file: --output 'a.toml' and --svg" in r["err"], r
        else:
            assert f"would replace the input {needle}: write the output to another file" in r["err"], r
    check_clean(results, "output clashes")
    for name, data in before.items():
        assert (tmp_path / name).read_bytes() == data, name
    assert not (tmp_path / "a.toml").exists() and not (tmp_path / "a.dst").exists()


def test_outputs_that_are_no_file(tmp_path):
    """``-o .``, ``-o ""``, ``-o /``, ``-o sub/`` in design (bend and shape) and fit: one line each."""
    _inputs(tmp_path)
    cases, expect = [], {}
    for k, prefix in enumerate([DESIGN_BEND, DESIGN_SHAPE, ["fit", "data.csv", *FIT]]):
        for o, message in ((".", "cannot write '.': it is a directory"),
                           ("", "--output must be a non-empty file name, got ''"),
                           ("/", "cannot write '/': it is a directory"),
                           ("sub", "cannot write 'sub': it is a directory"),
                           ("sub/", "cannot write 'sub/': it is a directory"),
                           ("..", "cannot write '..': it is a directory")):
            cid = f"{k}-{o!r}"
            cases.append({"id": cid, "argv": prefix + ["-o", o], "cwd": str(tmp_path)})
            expect[cid] = message
    results = run_cases(cases)
    for cid, message in expect.items():
        check_error(results[cid], 2 if "non-empty" in message else 3, message)
    check_clean(results, "outputs that are no file")
