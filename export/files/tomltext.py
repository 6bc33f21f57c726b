"""TOML text for the files embroact writes (design files, calibration sets), by tomli-w, and
:func:`load_toml` for the TOML files it reads (tube files, calibration sets).

:func:`dumps` hands tomli-w plain Python values: numpy scalars and arrays become Python
numbers and lists (``np.int64(3)`` stays the integer 3), tuples become lists. tomli-w
writes nested tables and arrays of tables, escapes what TOML forbids raw (control
characters, U+007F) and writes floats as their shortest round-trip ``repr``.

Examples
--------
>>> import tomllib
>>> import numpy as np
>>> from embroact.export.files.tomltext import dumps
>>> doc = {"name": 'a"b' + chr(0x7F), "n": np.int64(3), "xy": np.array([0.5, 1.0]),
...        "actuator": [{"name": "A1", "model": {"g_mpa": 2.7}}]}
>>> print(dumps({"n": doc["n"], "tube": {"outer_radius_mm": 1.5}}), end="")
n = 3
<BLANKLINE>
[tube]
outer_radius_mm = 1.5
>>> tomllib.loads(dumps(doc)) == {"name": 'a"b' + chr(0x7F), "n": 3, "xy": [0.5, 1.0],
...                               "actuator": [{"name": "A1", "model": {"g_mpa": 2.7}}]}
True
"""
from __future__ import annotations

import os
import re
from typing import Any

import numpy as np

from ...patterns.base.errors import DesignFileError
from ...patterns.base.validate import TEXT_FILE_BYTES, read_input

__all__ = ["dumps", "load_toml", "loads_toml"]


def load_toml(path: str | os.PathLike, what: str) -> dict:
    """The TOML file ``path`` (at most ``TEXT_FILE_BYTES``, UTF-8) as a dict.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    what : str
        What it is, for the messages (``"tube file"``).

    Returns
    -------
    dict

    Raises
    ------
    DesignFileError
        One line naming the file: ``cannot read <what>``, too large, not UTF-8, or ``TOML syntax
        error`` with the line and column (the wording of design files too).

    Examples
    --------
    >>> load_toml("missing.toml", "tube file")
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.DesignFileError: missing.toml: cannot read tube file: No such file or directory
    """
    return loads_toml(read_input(path, TEXT_FILE_BYTES, what, encoding="utf-8"), source=os.fsdecode(path))


def loads_toml(text: str, *, source: str) -> dict:
    """TOML ``text`` as a dict; a syntax error is ``<source>: TOML syntax error: ...`` (line and column).

    Parameters
    ----------
    text : str
        The TOML.
    source : str
        Where it came from, for the messages.

    Returns
    -------
    dict

    Examples
    --------
    >>> loads_toml("n = 3", source="x.toml")
    {'n': 3}
    """
    import tomllib  # only a file read needs it (check x.dst without a tube file does not)

    _check_shape(text, source)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DesignFileError(f"{source}: TOML syntax error: {exc}") from None


#: Deepest nesting of arrays and inline tables a TOML file may have (embroact's own files nest 3 deep;
#: tomllib recurses per level and fails with a RecursionError past a few hundred).
TOML_DEPTH = 32
#: Most digits of one number in a TOML file, checked before parsing (Python refuses to convert integers
#: of more than 4,300 digits). Shorter numbers that no float holds (400 digits) are parsed and then
#: refused by the range check of their key, which names it.
TOML_DIGITS = 1000
#: Strings, comments, brackets and long digit runs: what the shape check looks at, in one pass.
_TOKENS = re.compile(r'''"""(?:\\.|[^\\])*?"""|\'\'\'.*?\'\'\'|"(?:\\.|[^"\\\n])*"|'[^'\n]*'|#[^\n]*'''
                     r"|(?P<open>[\[{])|(?P<close>[\]}])|(?P<digits>[0-9_]{%d,})" % (TOML_DIGITS + 1), re.S)


def _check_shape(text: str, source: str) -> None:
    """Refuse nesting deeper than :data:`TOML_DEPTH` and numbers longer than :data:`TOML_DIGITS`, before parsing.

    >>> _check_shape("a = " + "[" * 40 + "]" * 40, "x.toml")
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.DesignFileError: x.toml line 1: arrays and inline tables must nest at most 32 deep, got 33
    """
    depth = 0
    for m in _TOKENS.finditer(text):
        if m["open"]:
            depth += 1
            if depth > TOML_DEPTH:
                raise DesignFileError(f"{source} line {text.count(chr(10), 0, m.start()) + 1}: arrays and inline "
                                      f"tables must nest at most {TOML_DEPTH} deep, got {depth}")
        elif m["close"]:
            depth = max(depth - 1, 0)
        elif m["digits"]:
            raise DesignFileError(f"{source} line {text.count(chr(10), 0, m.start()) + 1}: numbers must have at "
                                  f"most {TOML_DIGITS} digits, got {len(m['digits'].replace('_', ''))}")


def _plain(value: Any, where: str) -> Any:
    if isinstance(value, dict):
        return {str(k): _plain(v, f"{where}.{k}" if where else str(k)) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_plain(v, f"{where}[{i}]") for i, v in enumerate(value)]
    if isinstance(value, np.generic):
        return value.item()
    if value is None or not isinstance(value, (str, bool, int, float)):
        raise DesignFileError(f"{where or 'value'}: cannot write {value!r} to TOML (strings, numbers, lists, tables)")
    return value


def dumps(data: dict) -> str:
    """TOML text of a table of strings, booleans, numbers, lists and tables.

    Parameters
    ----------
    data : dict
        The document; numpy values allowed. ``None`` is not TOML.

    Returns
    -------
    str
        The TOML text (tomli-w's layout: keys first, then sub-tables).

    Raises
    ------
    DesignFileError
        A value TOML cannot hold, naming its key path.

    Examples
    --------
    >>> dumps({"model": {"p0_kpa": None}})
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.DesignFileError: model.p0_kpa: cannot write None to TOML (strings, numbers, lists, tables)
    """
    import tomli_w

    return tomli_w.dumps(_plain(data, ""))
