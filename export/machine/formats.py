"""Machine-file writers behind one registry keyed by file suffix.

Every embroidery format pyembroidery writes is here.  The format follows the
file suffix; ``fmt=`` overrides it; an unknown suffix lists the supported ones.
Files are encoded in memory (pyembroidery's stream API with ``encode=False``:
the records come from :mod:`embroact.export.machine.encode`, nothing is re-encoded) and
written atomically.  The same plan always gives the same bytes: JEF's date field
is pinned to :data:`FIXED_DATE` and no writer gets a random filler thread.

========  ===========  ==================================================
format    stop style   notes
========  ===========  ==================================================
dst       stop         Tajima; header rewritten by :mod:`embroact.export.machine.dst`
tbf       needle_stop  Tajima binary: separate stop (0x40) and trim codes
pes       color        Brother, version 6 (thread table names each actuator)
pec       color        Brother
jef       color        Janome; trims written explicitly
exp       stop         Melco / Bernina
vp3       color        Pfaff / Husqvarna (thread table names each actuator)
xxx       color        Singer
u01       needle_stop  Barudan
========  ===========  ==================================================

Examples
--------
>>> machine_format("act.PES").name
'pes'
>>> machine_format("act.dst", fmt="jef").name
'jef'
>>> try:
...     machine_format("act.png")
... except Exception as exc:
...     print(exc)
file suffix must be one of .dst, .tbf, .pes, .pec, .jef, .exp, .vp3, .xxx, .u01, got '.png'
"""
from __future__ import annotations

import io
import os
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Callable

from ...patterns.base.errors import ExportError, ParameterError
from ...patterns.limits import FORMAT_LIMITS, FormatLimit
from ...patterns.plan import StitchPlan
from ..files.atomic import check_output_dir, write_bytes_atomic
from .encode import MachinePattern, to_pattern

__all__ = ["FIXED_DATE", "MachineFormat", "WriteResult", "FORMATS", "machine_format", "encode", "write"]

FIXED_DATE = "20000101000000"
"""Date stamped into formats that carry one (JEF), so output is reproducible."""


def _dst_post(data: bytes, mp: MachinePattern) -> bytes:
    from .dst import fix_dst

    return fix_dst(data, label=mp.pattern.get_metadata("name", ""))


def _vp3_even_center(pattern) -> None:
    """Make the VP3 design centre whole units (pyembroidery 1.5.1 truncates block offsets from it).

    The VP3 writer stores each colour block's start as ``int(start - centre)`` and
    the reader adds back ``int(centre)``: with a half-unit centre every block after
    the first lands 0.1 mm off.  Two jump records before the end (VP3 has no jumps:
    the writer skips them, only the bounds see them) widen the bounds by one unit
    where the sum of the extremes is odd.
    """
    import pyembroidery as pe

    xmin, ymin, xmax, ymax = pattern.bounds()
    if (xmin + xmax) % 2 == 0 and (ymin + ymax) % 2 == 0:
        return
    corner = [xmax + (xmin + xmax) % 2, ymax + (ymin + ymax) % 2]
    last = pattern.stitches[-1]
    pattern.stitches[-1:-1] = [[*corner, pe.JUMP], [last[0], last[1], pe.JUMP]]


@dataclass(frozen=True, slots=True)
class MachineFormat:
    """One writable format.

    Attributes
    ----------
    name : str
        Lower-case suffix without the dot.
    writer : str
        pyembroidery writer module (``"DstWriter"``).
    stop_style : str
        ``"stop"``, ``"color"`` or ``"needle_stop"`` (see :mod:`embroact.export.machine.encode`).
    limit : FormatLimit
        Per-record limits from :mod:`embroact.patterns.limits`.
    settings : tuple of (str, object)
        Extra writer settings.
    postprocess : callable or None
        ``(bytes, MachinePattern) -> bytes`` applied after the writer (DST header).
    prepare : callable or None
        ``(EmbPattern) -> None`` applied to the records before the writer (VP3 centre).
    """

    name: str
    writer: str
    stop_style: str
    limit: FormatLimit
    settings: tuple[tuple[str, object], ...] = ()
    postprocess: Callable[[bytes, MachinePattern], bytes] | None = field(default=None, compare=False)
    prepare: Callable[[object], None] | None = field(default=None, compare=False)

    @property
    def description(self) -> str:
        """Human-readable name."""
        return self.limit.description


def _fmt(name: str, writer: str, style: str, settings=(), post=None, prepare=None) -> MachineFormat:
    return MachineFormat(name, writer, style, FORMAT_LIMITS[name], tuple(settings), post, prepare)


FORMATS: dict[str, MachineFormat] = {
    f.name: f
    for f in (
        _fmt("dst", "DstWriter", "stop", post=_dst_post),
        _fmt("tbf", "TbfWriter", "needle_stop"),
        _fmt("pes", "PesWriter", "color", [("version", 6)]),
        _fmt("pec", "PecWriter", "color"),
        _fmt("jef", "JefWriter", "color", [("trims", True), ("date", FIXED_DATE)]),
        _fmt("exp", "ExpWriter", "stop"),
        _fmt("vp3", "Vp3Writer", "color", prepare=_vp3_even_center),
        _fmt("xxx", "XxxWriter", "color"),
        _fmt("u01", "U01Writer", "needle_stop"),
    )
}


def machine_format(path: str | os.PathLike, *, fmt: str | None = None) -> MachineFormat:
    """The format for ``path``'s suffix, or ``fmt`` when given.

    Raises
    ------
    ParameterError
        Unknown suffix or format name; the message lists the supported ones.
    """
    if fmt is not None:
        key = str(fmt).lower().lstrip(".")
        if key not in FORMATS:
            raise ParameterError(f"format must be one of {', '.join(FORMATS)}, got {fmt!r}")
        return FORMATS[key]
    suffix = Path(path).suffix.lower()
    if suffix.lstrip(".") not in FORMATS:
        raise ParameterError(
            f"file suffix must be one of {', '.join('.' + k for k in FORMATS)}, got {suffix or str(path)!r}"
        )
    return FORMATS[suffix.lstrip(".")]


@dataclass(frozen=True, slots=True)
class WriteResult:
    """What a machine-file write produced.

    Attributes
    ----------
    path : str or None
        File written (None for :func:`encode`).
    format : str
    size_bytes : int
    stitches, stops, trims, jumps : int
        Records written (stitches include split-leg needle points).
    split_legs : int
        Legs split because they exceeded the per-record limit.
    """

    path: str | None
    format: str
    size_bytes: int
    stitches: int
    stops: int
    trims: int
    jumps: int
    split_legs: int

    def as_dict(self) -> dict:
        """Plain dict for JSON output."""
        return {k: getattr(self, k) for k in self.__slots__}


def encode(plan: StitchPlan, fmt: str | MachineFormat = "dst", *, split_long: bool = False) -> tuple[bytes, WriteResult]:
    """Encode ``plan`` as bytes of format ``fmt`` (no file touched).

    Examples
    --------
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (1, 1, Command.STITCH, Role.LEG),
    ...                                 (1, 1, Command.END, Role.CONTROL, -1)])
    >>> data, res = encode(plan, "dst")
    >>> len(data), res.stitches
    (522, 2)
    """
    import importlib

    f = fmt if isinstance(fmt, MachineFormat) else machine_format("", fmt=fmt)
    mp = to_pattern(plan, f, split_long=split_long)
    writer = importlib.import_module(f"pyembroidery.{f.writer}")
    if f.prepare is not None:
        f.prepare(mp.pattern)
    settings = {"encode": False, **dict(f.settings)}
    buf = io.BytesIO()
    try:
        mp.pattern.write_embroidery(writer, mp.pattern, buf, settings)
    except (ValueError, IndexError, AssertionError, OverflowError) as exc:  # writer-level format limits
        raise ExportError(f"{f.name} writer refused the design: {exc}") from exc
    data = buf.getvalue()
    if f.postprocess is not None:
        data = f.postprocess(data, mp)
    n_stitch = mp.pattern.count_stitch_commands(writer.STITCH)
    return data, WriteResult(None, f.name, len(data), n_stitch, mp.stops, mp.trims, mp.jumps, mp.split_legs)


def write(
    plan: StitchPlan,
    path: str | os.PathLike,
    *,
    fmt: str | None = None,
    split_long: bool = False,
) -> WriteResult:
    """Write ``plan`` to ``path`` atomically in the format of its suffix (or ``fmt``).

    Raises
    ------
    ParameterError
        Unknown suffix/format.
    LongLegError
        A leg exceeds the format's per-record limit and ``split_long`` is false.
    ExportError
        The directory is missing or not writable; no file is left behind.
    """
    f = machine_format(path, fmt=fmt)
    check_output_dir(path)
    data, res = encode(plan, f, split_long=split_long)
    write_bytes_atomic(path, data)
    return replace(res, path=str(path))
