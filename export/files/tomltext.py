"""TOML text for the files embroact writes (design files, calibration sets): keys and values.

Strings are TOML basic strings: ``"`` and ``\\`` escaped, the control characters
U+0000-U+001F and U+007F escaped (TOML forbids them raw), everything else kept as UTF-8.
Floats are written by ``repr`` (shortest round trip; ``inf``/``nan`` are TOML too).

Examples
--------
>>> from embroact.export.files.tomltext import toml_key, toml_value
>>> toml_value("a\\"b\\n"), toml_value(True), toml_value([1, 0.5])
('"a\\\\"b\\\\n"', 'true', '[1, 0.5]')
>>> print(toml_value("line\\n" + chr(0x7F)))  # raw control characters are not TOML
"line\\n\\u007f"
>>> toml_key("width_mm"), toml_key("tube 1")
('width_mm', '"tube 1"')
"""
from __future__ import annotations

import numbers
import re

from ...patterns.base.errors import DesignFileError

__all__ = ["toml_key", "toml_value"]

_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")
_ESCAPES = {'"': '\\"', "\\": "\\\\", "\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f", "\r": "\\r"}


def _escape(ch: str) -> str:
    if ch in _ESCAPES:
        return _ESCAPES[ch]
    return f"\\u{ord(ch):04x}" if ord(ch) < 0x20 or ord(ch) == 0x7F else ch


def toml_value(value) -> str:
    """TOML text of a string, bool, number or list of them.

    Raises
    ------
    DesignFileError
        Any other type (a table, None, ...).
    """
    if isinstance(value, str):
        return '"' + "".join(_escape(ch) for ch in value) + '"'
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, numbers.Real):
        return repr(float(value))
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in value) + "]"
    raise DesignFileError(f"cannot write value {value!r} to TOML")


def toml_key(key: str) -> str:
    """``key`` bare when it may be, else quoted."""
    return key if _BARE_KEY.fullmatch(key) else toml_value(key)
