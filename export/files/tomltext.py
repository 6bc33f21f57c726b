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

    A key's value that is an array of arrays of plain decimal numbers (a path's points) is read by
    :func:`_number_rows` (tomllib takes 5 us a number: 0.9 s for a 100 m path), the rest by tomllib;
    the result is the same dict, and an error is tomllib's on the whole text.

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
    >>> loads_toml("[[actuator]]\\npath = [[0, 0],\\n  [1.5, -2e1]]  # mm\\n", source="x.toml")
    {'actuator': [{'path': [[0, 0], [1.5, -20.0]]}]}
    """
    import tomllib  # only a file read needs it (check x.dst without a tube file does not)

    rest, rows = _check_shape(text, source)
    try:
        return _put_rows(tomllib.loads(rest), rows) if rows else tomllib.loads(text)
    except tomllib.TOMLDecodeError:
        pass
    try:  # the error as tomllib places it in the text as written
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
#: A plain decimal TOML number (no underscores, no inf/nan, no hexadecimal: those go to tomllib), the
#: blanks TOML allows inside arrays, and an array of such numbers (possessive: nothing is tried twice).
_NUMBER = r"[+-]?+(?:0|[1-9][0-9]{0,30}+)(?:\.[0-9]{1,30}+)?+(?:[eE][+-]?+[0-9]{1,4}+)?+"
_BLANK = r"(?:[ \t\n]|\r\n)*+"
_ROW = rf"\[{_BLANK}{_NUMBER}{_BLANK}(?:,{_BLANK}{_NUMBER}{_BLANK})*+,?+{_BLANK}\]"
#: Strings, comments, a key's array of number rows ending its line, brackets and long digit runs: what the
#: shape check looks at, in one pass.
_TOKENS = re.compile(r'''"""(?:\\.|[^\\])*?"""|\'\'\'.*?\'\'\'|"(?:\\.|[^"\\\n])*"|'[^'\n]*'|#[^\n]*'''
                     rf"|=[ \t]*+(?P<rows>\[{_BLANK}{_ROW}{_BLANK}(?:,{_BLANK}{_ROW}{_BLANK})*+,?+{_BLANK}\])"
                     r"(?=[ \t]*(?:#[^\n]*)?(?:\r?\n|\Z))"
                     r"|(?P<open>[\[{])|(?P<close>[\]}])|(?P<digits>[0-9_]{%d,})" % (TOML_DIGITS + 1), re.S)
#: Stands for an array of number rows in the text tomllib reads (a private-use character: a file holding it
#: is read by tomllib alone).
_MARK = "\ue000"


def _check_shape(text: str, source: str) -> tuple[str, list[str]]:
    """Refuse nesting deeper than :data:`TOML_DEPTH` and numbers longer than :data:`TOML_DIGITS`, before parsing;
    return the text with each top-level key's array of number rows replaced by a string ``_MARK + k``, and those
    arrays' texts.

    >>> _check_shape("a = " + "[" * 40 + "]" * 40, "x.toml")
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.DesignFileError: x.toml line 1: arrays and inline tables must nest at most 32 deep, got 33
    >>> _check_shape('p = [[1, 2],\\n     [3, 4]]\\nq = "[[5]]"', "x.toml")
    ('p = "\\ue0000"\\nq = "[[5]]"', ['[[1, 2],\\n     [3, 4]]'])
    """
    depth = 0
    rows: list[str] = []
    parts: list[str] = []
    done = 0
    fast = _MARK not in text
    for m in _TOKENS.finditer(text):
        if m["rows"] is not None:
            if fast and depth == 0:
                parts += [text[done:m.start("rows")], f'"{_MARK}{len(rows)}"']
                rows.append(m["rows"])
                done = m.end("rows")
            elif depth + 2 > TOML_DEPTH:
                raise DesignFileError(f"{source} line {text.count(chr(10), 0, m.start()) + 1}: arrays and inline "
                                      f"tables must nest at most {TOML_DEPTH} deep, got {depth + 2}")
        elif m["open"]:
            depth += 1
            if depth > TOML_DEPTH:
                raise DesignFileError(f"{source} line {text.count(chr(10), 0, m.start()) + 1}: arrays and inline "
                                      f"tables must nest at most {TOML_DEPTH} deep, got {depth}")
        elif m["close"]:
            depth = max(depth - 1, 0)
        elif m["digits"]:
            raise DesignFileError(f"{source} line {text.count(chr(10), 0, m.start()) + 1}: numbers must have at "
                                  f"most {TOML_DIGITS} digits, got {len(m['digits'].replace('_', ''))}")
    return ("".join(parts) + text[done:] if rows else text), rows


def _number_rows(array: str) -> list[list[int | float]]:
    """The rows of a TOML array of number rows (as :data:`_TOKENS` matched it), as tomllib reads them: an
    integer without fraction or exponent, else a float.

    >>> _number_rows("[[0, -1.5], [+2, 1e3,]]")
    [[0, -1.5], [2, 1000.0]]
    """
    return [[float(v) if "." in v or "e" in v or "E" in v else int(v) for v in row.replace(",", " ").split()]
            for row in array.strip()[1:-1].replace("[", "").split("]")[:-1]]


def _put_rows(value: Any, rows: list[str]) -> Any:
    """``value`` (tomllib's result) with each ``_MARK + k`` string replaced by the rows of array k (the garbage
    collector paused: a long path's 100,000 new lists would start full collections that find nothing)."""
    import gc

    enabled = gc.isenabled()
    gc.disable()
    try:
        return _replaced(value, rows)
    finally:
        if enabled:
            gc.enable()


def _replaced(value: Any, rows: list[str]) -> Any:
    if isinstance(value, dict):
        return {k: _replaced(v, rows) for k, v in value.items()}
    if isinstance(value, list):
        return [_replaced(v, rows) for v in value]
    if isinstance(value, str) and value.startswith(_MARK):
        return _number_rows(rows[int(value[1:])])
    return value


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
