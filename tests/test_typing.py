"""mypy finds no errors in the package (``py.typed`` ships, so users' type checkers read these types).

The source folders (api/, patterns/, predict/, export/) become one ``embroact`` package only when
installed; the test lays them out that way with symlinks in a temporary folder and runs
``mypy -p embroact`` there with the project's configuration ([tool.mypy] in pyproject.toml).
About 11-20 s from a cold cache. The user-script test reads the package through the same tree and
cache, so after the package check it analyses only its script (run alone, it starts cold).
"""
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

pytest.importorskip("mypy")


def _package_tree(tmp: Path) -> Path:
    pkg = tmp / "embroact"
    pkg.mkdir()
    for entry in (ROOT / "api").iterdir():
        if entry.name != "__pycache__":
            os.symlink(entry, pkg / entry.name)
    for sub in ("patterns", "predict", "export"):
        os.symlink(ROOT / sub, pkg / sub)
    return pkg


@pytest.fixture(scope="module")
def tree(tmp_path_factory):
    """The installed layout in a temporary folder, with one mypy cache (``cache/``) for the module's runs."""
    tmp = tmp_path_factory.mktemp("typing")
    _package_tree(tmp)
    return tmp


def test_mypy_reports_no_errors_on_the_package(tree):
    out = subprocess.run([sys.executable, "-m", "mypy", "-p", "embroact", "--config-file", str(ROOT / "pyproject.toml"),
                          "--cache-dir", str(tree / "cache"), "--no-error-summary"],
                         cwd=tree, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    assert [line for line in out.stdout.splitlines() if ": error:" in line] == []


USER_SCRIPT = '''\
import embroact

design = embroact.default_design()
plan = embroact.build_plan(design)
reveal_type(design)
reveal_type(embroact.analyse(design).actuators[0])
count: str = plan.stitch_count  # a deliberate error: an int is no str
'''


def test_mypy_sees_real_types_through_import_embroact(tree):
    """A user's script: mypy knows ``embroact.default_design()`` is a Design and reports a wrong type."""
    (tree / "user.py").write_text(USER_SCRIPT, encoding="utf-8")
    out = subprocess.run([sys.executable, "-m", "mypy", "user.py", "--config-file", str(ROOT / "pyproject.toml"),
                          "--cache-dir", str(tree / "cache"), "--no-error-summary"],
                         cwd=tree, capture_output=True, text=True, timeout=300)
    lines = out.stdout.splitlines()
    assert 'user.py:5: note: Revealed type is "embroact.patterns.design.Design"' in lines, out.stdout
    assert 'user.py:6: note: Revealed type is "embroact.predict.analysis.ActuatorAnalysis"' in lines, out.stdout
    errors = [line for line in lines if ": error:" in line]
    assert len(errors) == 1 and errors[0].startswith("user.py:7: error: Incompatible types in assignment "
                                                     '(expression has type "int", variable has type "str")'), out.stdout


def test_the_stub_lists_what_import_embroact_provides():
    import embroact

    for name in embroact.__all__:
        assert getattr(embroact, name) is not None
    assert "load_design" in dir(embroact) and len(set(embroact.__all__)) == len(embroact.__all__)
