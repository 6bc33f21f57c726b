"""Machine-format facts the generators and rules need: per-record travel limits.

Values from pyembroidery 1.5.1's writers (EMBROIDERY.md), in mm per axis (not
Euclidean). A stitch whose |dx| or |dy| exceeds the limit cannot be one record.
XXX: the writer encodes a stitch of 124 units (12.4 mm) or more per axis with the
long-move code 0x7D, which every reader takes as a jump, so its stitch limit is
12.3 mm (frame moves of 12.4 mm are fine).

Examples
--------
>>> from embroact.patterns.limits import FORMAT_LIMITS, format_limit
>>> format_limit("dst").max_record_mm
12.1
>>> sorted(FORMAT_LIMITS)[:3]
['dst', 'exp', 'jef']
"""
from __future__ import annotations

from dataclasses import dataclass

from .base.errors import ParameterError

__all__ = ["FormatLimit", "FORMAT_LIMITS", "format_limit"]


@dataclass(frozen=True, slots=True)
class FormatLimit:
    """Limits of one machine-file format.

    Attributes
    ----------
    name : str
        Lower-case suffix without the dot.
    max_record_mm : float
        Largest stitch per axis in one record [mm].
    max_jump_mm : float
        Largest jump per axis in one record [mm].
    max_records : int
        Largest number of records the format (or its header field) can hold.
    separate_stop : bool
        True when STOP has its own code; False when it shares the colour-change code.
    description : str
    """

    name: str
    max_record_mm: float
    max_jump_mm: float
    max_records: int
    separate_stop: bool
    description: str


FORMAT_LIMITS: dict[str, FormatLimit] = {
    f.name: f
    for f in (
        FormatLimit("dst", 12.1, 12.1, 9_999_999, False, "Tajima DST (default)"),
        FormatLimit("tbf", 12.7, 12.7, 9_999_999, True, "Tajima TBF, separate stop and trim codes"),
        FormatLimit("exp", 12.7, 12.7, 9_999_999, False, "Melco / Bernina EXP"),
        FormatLimit("jef", 12.7, 12.7, 9_999_999, False, "Janome JEF"),
        FormatLimit("u01", 12.7, 12.7, 9_999_999, True, "Barudan U01"),
        FormatLimit("xxx", 12.3, 12.4, 9_999_999, False, "Singer XXX"),
        FormatLimit("pes", 204.7, 204.7, 9_999_999, False, "Brother PES"),
        FormatLimit("pec", 204.7, 204.7, 9_999_999, False, "Brother PEC"),
        FormatLimit("vp3", 25.5, 320.0, 9_999_999, False, "Pfaff / Husqvarna VP3"),
    )
}


def format_limit(name: str) -> FormatLimit:
    """Limits for a format name or suffix (``"dst"``, ``".DST"``); unknown names list the valid ones."""
    key = name.lower().lstrip(".")
    if key not in FORMAT_LIMITS:
        raise ParameterError(f"format must be one of {', '.join(FORMAT_LIMITS)}, got {name!r}")
    return FORMAT_LIMITS[key]
