"""The public API: ``import embroact``, its version, ``python -m embroact``, the typed marker."""
import importlib.metadata
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

import embroact

ROOT = Path(__file__).resolve().parent.parent


def test_version_is_single_sourced():
    meta = importlib.metadata.version("embroact")
    from embroact.export import __version__ as literal

    assert embroact.__version__ == meta == literal
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert "version" not in pyproject["project"] and "version" in pyproject["project"]["dynamic"]
    assert pyproject["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "embroact.export.__version__"}


@pytest.mark.parametrize("argv", [["-m", "embroact", "--version"], ["-m", "embroact.export", "--version"]])
def test_python_dash_m(argv):
    out = subprocess.run([sys.executable, *argv], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == f"embroact {embroact.__version__}"


@pytest.mark.parametrize("name", sorted(set(embroact.__all__) - {"__version__"}))
def test_every_exported_name_resolves(name):
    obj = getattr(embroact, name)
    assert obj is not None and name in dir(embroact)
    assert getattr(obj, "__doc__", None), f"embroact.{name} has no docstring"


def test_unknown_name_is_an_attribute_error():
    with pytest.raises(AttributeError):
        embroact.no_such_name  # noqa: B018


def test_the_api_agrees_with_the_subpackages():
    from embroact.export.files.designfile import load_design
    from embroact.predict.analysis import analyse

    assert embroact.load_design is load_design and embroact.analyse is analyse


def test_py_typed_ships_with_the_package():
    assert (Path(embroact.__file__).parent / "py.typed").is_file()
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert "py.typed" in pyproject["tool"]["setuptools"]["package-data"]["embroact"]


def test_license_file_is_mit():
    text = (ROOT / "LICENSE").read_text(encoding="utf-8")
    assert text.startswith("MIT License") and "WITHOUT WARRANTY OF ANY KIND" in text
    assert importlib.metadata.metadata("embroact")["License-Expression"] == "MIT"
