"""Design files: TOML in (:func:`load_design`), TOML out (:func:`dumps_design`, :func:`save_design`).

The schema is documented in :mod:`embroact.patterns.design`. Every problem with a
file (missing, unreadable, not UTF-8, TOML syntax with its line, schema) is one
:class:`DesignFileError` line that starts with the file name.

Examples
--------
>>> import os, tempfile
>>> from embroact.export.files.designfile import load_design, save_design
>>> from embroact.patterns.design import default_design
>>> path = os.path.join(tempfile.mkdtemp(), "d.toml")
>>> save_design(default_design(), path)
>>> load_design(path) == default_design()
True
>>> with open(path, "w") as fh:
...     _ = fh.write("name = 'x'\\n[[actuator]]\\nwidht_mm = 7\\n")
>>> try:
...     load_design(path)
... except Exception as exc:
...     print(str(exc).replace(path, "d.toml").split(";")[0])
d.toml: actuator[0].widht_mm: unknown key
"""
from __future__ import annotations

import os
import tomllib
from pathlib import Path

from ...patterns.design import Design, design_from_dict, design_to_dict
from ...patterns.base.errors import DesignFileError
from .atomic import write_text_atomic
from .tomltext import toml_key, toml_value

__all__ = ["load_design", "loads_design", "dumps_design", "save_design"]


def loads_design(text: str, *, source: str = "<string>") -> Design:
    """Parse TOML text into a :class:`Design`; errors start with ``source``."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DesignFileError(f"{source}: TOML syntax error: {exc}") from None
    try:
        return design_from_dict(data)
    except DesignFileError as exc:
        raise DesignFileError(f"{source}: {exc}") from None


def load_design(path: str | os.PathLike) -> Design:
    """Read and validate a TOML design file.

    Raises
    ------
    DesignFileError
        One line naming the file: cannot read, not UTF-8, TOML syntax error (with line and
        column), or a schema error (with the key path).
    """
    p = Path(path)
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise DesignFileError(f"{p}: cannot read design file: {exc.strerror or exc}") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise DesignFileError(f"{p}: design file is not UTF-8 text (byte {exc.start})") from None
    return loads_design(text, source=str(p))


def _lines(d: dict) -> list[str]:
    return [f"{toml_key(k)} = {toml_value(v)}" for k, v in d.items() if not isinstance(v, dict)]


def dumps_design(design: Design) -> str:
    """TOML text of ``design`` (paths as point lists), readable by :func:`loads_design`."""
    d = design_to_dict(design)
    out = _lines({"name": d["name"]})
    for table in ("tube", "machine", "operation"):
        out += ["", f"[{table}]"] + _lines(d[table])
    for act in d["actuator"]:
        out += ["", "[[actuator]]"] + _lines(act)
        if act["model"]:
            out += ["[actuator.model]"] + _lines(act["model"])
    return "\n".join(out) + "\n"


def save_design(design: Design, path: str | os.PathLike) -> None:
    """Write ``design`` as TOML to ``path`` atomically."""
    write_text_atomic(path, dumps_design(design))
