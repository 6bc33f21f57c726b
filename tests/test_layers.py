"""The layers hold (tests/layers.py): export -> predict -> patterns, no cycles, export sub-packages one way.

The checker reads every import of every module from the AST (lazy ones inside functions,
sub-packages, relative imports at any depth). The second half feeds it small source trees
with one planted back-import each and shows it reports exactly that import: a checker
that cannot fail proves nothing.
"""
from pathlib import Path

import pytest

import layers

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def graph():
    return layers.import_graph(ROOT)


def test_every_source_module_is_read(graph):
    on_disk = sum(1 for d in layers.PACKAGE_DIRS for _ in (ROOT / d).rglob("*.py"))
    assert len(graph) == on_disk > 100
    assert "embroact.patterns.rules.engine" in graph and "embroact.export.cli.main" in graph


def test_patterns_import_neither_predict_nor_export_and_predict_not_export(graph):
    assert layers.layer_violations(graph) == []


def test_no_import_cycle_inside_a_layer():
    assert layers.cycles(layers.import_graph(ROOT, typing=False)) == []


def test_export_sub_packages_import_one_way(graph):
    # cli and studio on top of report, report on top of photo (annotated measurements) and pictures,
    # pictures on top of machine (a build's stop marks), everything on top of files
    assert layers.export_direction_violations(graph) == []


def test_lazy_and_relative_imports_are_seen(graph):
    # cmd_build imports the report stage inside run(); the layer test must see it
    assert "embroact.export.report.stage" in graph["embroact.export.cli.cmd_build"]
    assert "embroact.predict.curve" in graph["embroact.predict.branch"]  # `from . import curve as _curve`


# ------------------------------------------------------------------ the checker can fail
def _tree(tmp_path: Path, files: dict[str, str]) -> Path:
    for d in layers.PACKAGE_DIRS:
        (tmp_path / d).mkdir(exist_ok=True)
        (tmp_path / d / "__init__.py").touch()
    for rel, text in files.items():
        path = tmp_path / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        for parent in path.relative_to(tmp_path).parents:
            if str(parent) != "." and not (tmp_path / parent / "__init__.py").exists():
                (tmp_path / parent / "__init__.py").touch()
        path.write_text(text, encoding="utf-8")
    return tmp_path


BASE = {"export/cli/main.py": "", "export/report/report.py": "", "export/pictures/chart.py": "",
        "predict/curve.py": "", "patterns/plan.py": ""}


@pytest.mark.parametrize("rel, text, expected", [
    # a lazy back-import, three packages deep, relative
    ("patterns/rules/deep.py", "def f():\n    from ...export.cli import main\n",
     "embroact.patterns.rules.deep -> embroact.export.cli"),
    ("patterns/rules/deep.py", "def f():\n    if True:\n        import embroact.predict.curve\n",
     "embroact.patterns.rules.deep -> embroact.predict.curve"),
    ("predict/solve.py", "class A:\n    def m(self):\n        from ..export.report import report\n",
     "embroact.predict.solve -> embroact.export.report"),
    ("predict/solve.py", "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from embroact.export.cli.main import x\n",
     "embroact.predict.solve -> embroact.export.cli.main"),
    # imports by name: importlib, and a "module:function" a registry loads later
    ("patterns/rules/deep.py", "import importlib\ndef f():\n    return importlib.import_module('embroact.predict.curve')\n",
     "embroact.patterns.rules.deep -> embroact.predict.curve"),
    ("predict/solve.py", "RENDERERS = {'Curve': 'embroact.export.report.report:curve_html'}\n",
     "embroact.predict.solve -> embroact.export.report.report"),
])
def test_a_planted_back_import_is_found(tmp_path, rel, text, expected):
    g = layers.import_graph(_tree(tmp_path, {**BASE, rel: text}))
    found = layers.layer_violations(g)
    assert expected in found
    assert layers.layer_violations(layers.import_graph(_tree(tmp_path, {rel: ""}))) == []  # and gone without it


def test_a_planted_cycle_is_found(tmp_path):
    g = layers.import_graph(_tree(tmp_path, {
        **BASE, "predict/curve.py": "from .onecurve import x\n", "predict/onecurve.py": "from .validity import y\n",
        "predict/validity.py": "def f():\n    from .curve import z\n"}), typing=False)
    assert layers.cycles(g) == [["embroact.predict.curve", "embroact.predict.onecurve", "embroact.predict.validity"]]


def test_a_planted_sideways_export_import_is_found(tmp_path):
    g = layers.import_graph(_tree(tmp_path, {**BASE, "export/pictures/chart.py": "def f():\n    from ..report import report\n"}))
    assert layers.export_direction_violations(g) == ["embroact.export.pictures.chart -> embroact.export.report",
                                                     "embroact.export.pictures.chart -> embroact.export.report.report"]
