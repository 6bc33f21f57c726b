"""Where the studio may write: plain file names inside the one output directory given on the command line.

The page names files, never paths: a name with a directory part, ``..``, a leading dot,
control characters or the wrong suffix is refused (:class:`OutsideOutputError`), and so is
a name that already exists as a symbolic link (it could point anywhere).

Examples
--------
>>> import tempfile
>>> out = tempfile.mkdtemp()
>>> output_path(out, "my-design.toml", ".toml").name
'my-design.toml'
>>> try:
...     output_path(out, "../elsewhere.toml", ".toml")
... except OutsideOutputError as exc:
...     print(exc)
name must be a plain file name inside the output directory (no folders, no leading dot), got '../elsewhere.toml'
"""
from __future__ import annotations

import os
import re
from pathlib import Path

from ...patterns.base.errors import ExportError, ParameterError
from ..files.atomic import NAME_BYTES

__all__ = ["OutsideOutputError", "output_path", "MAX_NAME_CHARS"]

MAX_NAME_CHARS = 120
# Longest name in bytes (UTF-8): NAME_BYTES, what Linux, macOS and Windows file systems allow in one
# name. The staged copy ``.NAME.XXXXXXXX.part`` cuts the name to 200 characters, so it fits too.
_PLAIN = re.compile(r"^[^\x00-\x1f\x7f/\\:]+$")


class OutsideOutputError(ParameterError):
    """A write the studio refuses: the name does not stay inside the output directory."""


def output_path(out_dir: str | os.PathLike, name: object, suffix: str) -> Path:
    """``out_dir / name`` when ``name`` is a plain file name ending in ``suffix``; else :class:`OutsideOutputError`.

    Parameters
    ----------
    out_dir : str or os.PathLike
        The studio's output directory.
    name : object
        The file name the page asked for.
    suffix : str
        The suffix it must have (lower case, with the dot).

    Returns
    -------
    pathlib.Path

    Raises
    ------
    OutsideOutputError
        A folder, a leading dot, another suffix, or a name leading out of ``out_dir``.

    Examples
    --------
    >>> output_path("/tmp", "design.toml", ".toml").name
    'design.toml'
    >>> try:
    ...     output_path("/tmp", "../design.toml", ".toml")
    ... except OutsideOutputError as exc:
    ...     print(exc)
    name must be a plain file name inside the output directory (no folders, no leading dot), got '../design.toml'
    """
    if not isinstance(name, str) or not name or len(name) > MAX_NAME_CHARS or not _PLAIN.match(name) \
            or name.startswith(".") or name.strip() != name:
        raise OutsideOutputError("name must be a plain file name inside the output directory "
                                 f"(no folders, no leading dot), got {name!r:.80}")
    try:
        size = len(name.encode("utf-8"))
    except UnicodeEncodeError:
        raise ParameterError(f"name must be valid Unicode text, got {name!r:.80}") from None
    if size > NAME_BYTES:  # the file system's limit: a longer name is ENAMETOOLONG at the write
        raise ParameterError(f"name must be at most {NAME_BYTES} bytes in UTF-8, got {size}")
    if not name.lower().endswith(suffix):
        raise OutsideOutputError(f"name must end in {suffix}, got {name!r:.80}")
    root = Path(out_dir).resolve()
    target = root / name
    if target.is_symlink() or target.resolve().parent != root:
        raise OutsideOutputError(f"name must stay inside the output directory {root}, got {name!r:.80}")
    if target.exists() and not target.is_file():
        raise ExportError(f"{target}: exists and is not a file")
    return target
