"""Atomic file output: a failed write leaves any existing file untouched and no partial file.

Examples
--------
>>> import os, tempfile
>>> from embroact.export.atomic import write_bytes_atomic
>>> d = tempfile.mkdtemp()
>>> write_bytes_atomic(os.path.join(d, "a.txt"), b"hello")
>>> open(os.path.join(d, "a.txt"), "rb").read()
b'hello'
"""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

from ..patterns.errors import ExportError

__all__ = ["write_bytes_atomic", "write_text_atomic", "check_output_dir"]


def check_output_dir(path: str | os.PathLike) -> Path:
    """Return ``path`` as a Path whose parent directory exists and is writable.

    Raises
    ------
    ExportError
        One line naming the directory when it is missing or not writable.
    """
    p = Path(path)
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        what = "is not a directory" if parent.exists() else "does not exist"
        raise ExportError(f"output directory {str(parent)!r} {what}")
    if not os.access(parent, os.W_OK):
        raise ExportError(f"output directory {str(parent)!r} is not writable")
    return p


def write_bytes_atomic(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` via a temporary file in the same directory and ``os.replace``."""
    p = check_output_dir(path)
    try:  # a directory root may not write to (/proc, a read-only mount) passes os.access
        fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".part", dir=p.parent)
    except OSError as exc:
        raise ExportError(f"cannot write {str(p)!r}: {exc.strerror or exc}") from exc
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, p)
    except BaseException as exc:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        if isinstance(exc, OSError) and not isinstance(exc, ExportError):
            raise ExportError(f"cannot write {str(p)!r}: {exc.strerror or exc}") from exc
        raise


def write_text_atomic(path: str | os.PathLike, text: str) -> None:
    """UTF-8 text version of :func:`write_bytes_atomic` (newlines kept as given)."""
    write_bytes_atomic(path, text.encode("utf-8"))
