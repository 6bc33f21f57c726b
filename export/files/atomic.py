"""Atomic file output: a failed write leaves any existing file untouched and no partial file.

Examples
--------
>>> import os, tempfile
>>> from embroact.export.files.atomic import write_bytes_atomic
>>> d = tempfile.mkdtemp()
>>> write_bytes_atomic(os.path.join(d, "a.txt"), b"hello")
>>> open(os.path.join(d, "a.txt"), "rb").read()
b'hello'
"""
from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Mapping

from ...patterns.base.errors import ExportError

__all__ = ["write_bytes_atomic", "write_text_atomic", "write_files_atomic", "check_output_dir", "check_writable_dir"]


def check_output_dir(path: str | os.PathLike) -> Path:
    """Return ``path`` as a Path whose parent directory exists and is writable.

    Raises
    ------
    ExportError
        One line naming the directory when it is missing or not writable.
    """
    p = Path(path)
    check_writable_dir(p.parent)
    return p


def check_writable_dir(path: str | os.PathLike) -> Path:
    """Return ``path`` as a Path if it is an existing directory files can be created in.

    Raises
    ------
    ExportError
        One line naming the directory when it is missing, not a directory or not writable.
    """
    d = Path(path)
    if not d.is_dir():
        what = "is not a directory" if d.exists() else "does not exist"
        raise ExportError(f"output directory {str(d)!r} {what}")
    if not os.access(d, os.W_OK | os.X_OK):
        raise ExportError(f"output directory {str(d)!r} is not writable")
    return d


def _cannot_write(p: Path, exc: OSError) -> ExportError:
    return ExportError(f"cannot write {str(p)!r}: {exc.strerror or exc}")


def _stage(p: Path, data: bytes) -> str:
    """Write ``data`` to a synced temporary file next to ``p``; return its name (removed on failure)."""
    try:  # a directory root may not write to (/proc, a read-only mount) passes os.access
        fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".part", dir=p.parent)
    except OSError as exc:
        raise _cannot_write(p, exc) from exc
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o644)
    except BaseException as exc:
        _remove(tmp)
        if isinstance(exc, OSError):
            raise _cannot_write(p, exc) from exc
        raise
    return tmp


def _remove(tmp: str) -> None:
    try:
        os.unlink(tmp)
    except FileNotFoundError:
        pass


def write_files_atomic(outputs: Mapping[str | os.PathLike, bytes]) -> None:
    """Write several files so that a failed run changes none of them, as far as the file system allows.

    Every file is first written and synced to a temporary file next to its target; only when
    all are ready are they renamed over their targets (``os.replace``). A failure while
    preparing (disk full, I/O error, interrupt) leaves every target untouched and no
    temporary file; only a failing rename, after the earlier ones, can leave a mix.
    """
    targets = [check_output_dir(path) for path in outputs]
    staged: list[tuple[str, Path]] = []
    try:
        for p, data in zip(targets, outputs.values()):
            staged.append((_stage(p, data), p))
        while staged:
            tmp, p = staged[0]
            try:
                os.replace(tmp, p)
            except OSError as exc:
                raise _cannot_write(p, exc) from exc
            staged.pop(0)
    finally:
        for tmp, _ in staged:
            _remove(tmp)


def write_bytes_atomic(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` via a temporary file in the same directory and ``os.replace``."""
    write_files_atomic({path: data})


def write_text_atomic(path: str | os.PathLike, text: str) -> None:
    """UTF-8 text version of :func:`write_bytes_atomic` (newlines kept as given)."""
    write_bytes_atomic(path, text.encode("utf-8"))
