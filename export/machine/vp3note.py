"""The VP3 file's origin, recorded in its notes string so a check can restore the design's frame.

A VP3 file cannot move the frame before its first stitch, so embroact writes it with its
origin 1 mm beside the first needle point (:mod:`embroact.export.machine.encode`): read
back, every position is shifted by that origin.  The file's global notes string (empty as
pystitch writes it, skipped by readers) then says where that origin lies in the design::

    embroact origin_mm=-40.7,40.3

(plan frame: mm, y up).  :func:`read_origin_mm` finds it again, so ``embroact check`` of
embroact's own VP3 reads positions in the frame of every other format: the design's, y down.

Layout of the file's start: ``%vsm%\\0``, a UTF-16BE string (2-byte length), ``00 02 00``,
the file block's byte count (int32 BE, from after it to the block's end), then the notes
string (2-byte length, UTF-16BE).

Examples
--------
>>> data = add_origin_note(b"%vsm%\\0" + b"\\0\\2A\\0" + b"\\0\\2\\0" + (7).to_bytes(4, "big") + b"\\0\\0" + b"12345",
...                        (-40.7, 40.3))
>>> read_origin_mm(data)
(-40.7, 40.3)
>>> read_origin_mm(b"%vsm%\\0") is None
True
"""
from __future__ import annotations

import re

_MAGIC = b"%vsm%\x00"
_NOTE = re.compile(r"embroact origin_mm=(-?\d{1,8}(?:\.\d)?),(-?\d{1,8}(?:\.\d)?)")


def _notes_at(data: bytes) -> int | None:
    """Offset of the notes string's 2-byte length, or None when the file does not start as a VP3."""
    if not data.startswith(_MAGIC) or len(data) < len(_MAGIC) + 2:
        return None
    p = len(_MAGIC) + 2 + int.from_bytes(data[len(_MAGIC):len(_MAGIC) + 2], "big") + 3 + 4
    return p if p + 2 <= len(data) else None


def add_origin_note(data: bytes, origin_mm: tuple[float, float]) -> bytes:
    """``data`` (a VP3 file with an empty notes string) with the note naming ``origin_mm``.

    Parameters
    ----------
    data : bytes
        The VP3 file as pystitch writes it.
    origin_mm : tuple of float
        Plan position of the file's origin [mm, y up], on the 0.1 mm grid.

    Returns
    -------
    bytes
        The file with the note; the file block's byte count grows by the note's bytes.

    Examples
    --------
    >>> import io, pystitch
    >>> p = pystitch.EmbPattern()
    >>> p.add_stitch_absolute(pystitch.STITCH, 0, 0); p.add_stitch_absolute(pystitch.STITCH, 10, 10)
    >>> p.add_command(pystitch.END)
    >>> buf = io.BytesIO(); pystitch.write_vp3(p, buf)
    >>> raw = buf.getvalue()  # as pystitch writes it: an empty note
    >>> read_origin_mm(raw), read_origin_mm(add_origin_note(raw, (10.0, -5.0)))
    (None, (10.0, -5.0))
    """
    p = _notes_at(data)
    if p is None or data[p:p + 2] != b"\x00\x00":
        raise ValueError("not a VP3 file with an empty notes string")
    text = f"embroact origin_mm={origin_mm[0]:.1f},{origin_mm[1]:.1f}".replace("-0.0", "0.0")
    note = text.encode("utf-16-be")
    count = int.from_bytes(data[p - 4:p], "big") + len(note)
    return data[:p - 4] + count.to_bytes(4, "big") + len(note).to_bytes(2, "big") + note + data[p + 2:]


def read_origin_mm(data: bytes) -> tuple[float, float] | None:
    """The origin a VP3 file's note names [mm, plan frame, y up], or None without one.

    Parameters
    ----------
    data : bytes
        A file's bytes (anything: a file without the note, or not a VP3 file, gives None).

    Returns
    -------
    tuple of float or None

    Examples
    --------
    >>> read_origin_mm(b"not a VP3 file") is None
    True
    """
    p = _notes_at(data)
    if p is None:
        return None
    n = int.from_bytes(data[p:p + 2], "big")
    m = _NOTE.fullmatch(data[p + 2:p + 2 + n].decode("utf-16-be", errors="replace"))
    return None if m is None else (float(m[1]), float(m[2]))
