"""mypy finds no errors in the package (``py.typed`` ships, so users' type checkers read these types).

The source folders (api/, patterns/, predict/, export/) become one ``embroact`` package only when
installed; the test lays them out that way with symlinks in a temporary folder and runs
``mypy -p embroact`` there with the project's configuration ([tool.mypy] in pyproject.toml).
About 11-20 s from a cold cache.
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


def test_mypy_reports_no_errors_on_the_package(tmp_path):
    _package_tree(tmp_path)
    out = subprocess.run([sys.executable, "-m", "mypy", "-p", "embroact", "--config-file", str(ROOT / "pyproject.toml"),
                          "--cache-dir", str(tmp_path / "cache"), "--no-error-summary"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    assert [line for line in out.stdout.splitlines() if ": error:" in line] == []
