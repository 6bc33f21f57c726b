"""Machine-file writers behind one registry keyed by file suffix.

Every embroidery format pystitch writes is here.  The format follows the file
suffix; ``fmt=`` overrides it; an unknown suffix lists the supported ones.  Files
are encoded in memory (pystitch's stream API with ``encode=False``: the records
come from :mod:`embroact.export.machine.encode`, nothing is re-encoded) and written
atomically.  The same plan always gives the same bytes: JEF's date field is pinned
to :data:`FIXED_DATE` and no writer gets a random filler thread.  What a written
file holds is counted back from its bytes (:mod:`embroact.export.machine.census`).

========  ===========  ==================================================
format    stop style   notes
========  ===========  ==================================================
dst       stop         Tajima; header rewritten by :mod:`embroact.export.machine.dst`
tbf       needle_stop  Tajima binary: own stop (0x40), trim and needle codes; header extents rewritten
pes       color        Brother, version 6 (thread table names each actuator)
pec       color        Brother
jef       color        Janome; trims written explicitly
exp       stop         Melco / Bernina; trim record written without its 0.7 mm offset
vp3       color        Pfaff / Husqvarna (thread table names each actuator); origin 1 mm beside the first needle point,
                       recorded in the file's notes (embroact check reads it in the design's frame)
xxx       color        Singer
u01       needle_stop  Barudan
========  ===========  ==================================================

Corrections of the library's writers that are still needed (pystitch 1.0.1)
--------------------------------------------------------------------------
* DST: ``+Y``/``-Y`` swapped, ``+X``/``-X`` as absolute values of signed bounds, ``ST``
  counting a trim as one record, no 0x1A after the end record (``CO`` now counts stops:
  fixed upstream, rewritten with the rest of the header).
* TBF: the same extent faults as DST (``_tbf_extents``).
* EXP: a trim written as ``80 80 07 00``, which other readers and a Bernina machine take
  as a trim *and* a 0.7 mm move (``_exp_trims``): written as ``80 80 00 00``, a trim
  without a move for every reader.
* VP3: block offsets truncated from a half-unit design centre (``_vp3_even_center``).
* Labels: PES and VP3 write a name's character count as its byte count; every label is
  written as :func:`embroact.export.machine.encode.ascii_label` transliterates it.

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
import re
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Callable

from ...patterns.base.errors import ExportError, ParameterError
from ...patterns.limits import FORMAT_LIMITS, FormatLimit
from ...patterns.plan import StitchPlan
from ...patterns.stops import CordStop
from ..files.atomic import check_output_dir, write_bytes_atomic
from .census import NAMED_FORMATS, census
from .encode import PLACEMENT_LABEL, MachinePattern, to_pattern
from .vp3note import add_origin_note

__all__ = ["FIXED_DATE", "MachineFormat", "WriteResult", "FORMATS", "machine_format", "encode", "write", "read_result"]

FIXED_DATE = "20000101000000"
"""Date stamped into formats that carry one (JEF), so output is reproducible."""


def _dst_post(data: bytes, mp: MachinePattern) -> bytes:
    from .dst import fix_dst

    return fix_dst(data, label=mp.pattern.get_metadata("name", ""))


def _extents(mp: MachinePattern) -> dict[str, int]:
    """Largest excursion from the start point in each direction, 0.1 mm, machine frame (y up)."""
    xs = [0] + [int(s[0]) for s in mp.pattern.stitches]
    ys = [0] + [-int(s[1]) for s in mp.pattern.stitches]
    return {"+X": max(xs), "-X": -min(xs), "+Y": max(ys), "-Y": -min(ys)}


def _tbf_extents(data: bytes, mp: MachinePattern) -> bytes:
    """Rewrite the TBF header's ``+X -X +Y -Y`` fields (same widths, so no offset moves)."""
    ext = _extents(mp)

    def field_(m: re.Match) -> bytes:
        key = m.group(1).decode("ascii")
        return b"%s:%5d\r" % (key.encode("ascii"), ext[key])

    head = re.sub(rb"([+-][XY]):[ 0-9-]{5}\r", field_, data[:0x376], count=4)
    if len(head) != 0x376:
        raise ExportError("TBF header extents do not fit their 5-digit fields")
    return head + data[0x376:]


def _exp_trims(data: bytes, mp: MachinePattern) -> bytes:
    """EXP trim records ``80 80 07 00`` -> ``80 80 00 00`` (walking the 2- and 4-byte records)."""
    out = bytearray(data)
    i = 0
    while i + 1 < len(out):
        if out[i] != 0x80:
            i += 2
            continue
        if out[i + 1] == 0x80:
            out[i + 2 : i + 4] = b"\x00\x00"
        i += 4
    return bytes(out)


def _pec_label(data: bytes, mp: MachinePattern) -> bytes:
    """PEC's 16-character ``LA:`` field (also inside PES) holds 16 of the name's letters and digits.

    The writer keeps letters and digits only (other characters upset machines, its source
    says) and then only the first 8 of them; readers read all 16.
    """
    start = 8 if data[:8] == b"#PEC0001" else int.from_bytes(data[8:12], "little")
    if data[start:start + 3] != b"LA:" or data[start + 19:start + 20] != b"\r":
        raise ExportError("PEC label field not found where the writer puts it")
    name = re.sub(r"[^A-Za-z0-9]+", "", mp.pattern.get_metadata("name", "")) or "Untitled"
    return data[:start + 3] + b"%-16s" % name[:16].encode("ascii") + data[start + 19:]


def _vp3_origin(data: bytes, mp: MachinePattern) -> bytes:
    """VP3: record the file's origin in its notes string (:mod:`embroact.export.machine.vp3note`)."""
    return add_origin_note(data, mp.origin_mm)


def _vp3_even_center(pattern) -> None:
    """Make the VP3 design centre whole units (the writer truncates block offsets from it).

    The VP3 writer stores each colour block's start as ``int(start - centre)`` and
    the reader adds back ``int(centre)``: with a half-unit centre every block after
    the first lands 0.1 mm off.  Two jump records before the end (VP3 has no jumps:
    the writer skips them, only the bounds see them) widen the bounds by one unit
    where the sum of the extremes is odd.
    """
    import pystitch as pe

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
        pystitch writer module (``"DstWriter"``).
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
    color_after_travel : bool
        Colour formats: change colour at the next actuator's first needle point (after
        the travel) rather than where the last one ended.
    trim_is_jump : bool
        The format trims only at a trim-flagged jump (PEC/PES).
    end_trims : bool
        The format's end code trims (VP3): no separate trim before it.
    first_at_origin : bool
        The format cannot move the frame before its first stitch (VP3): its origin is
        the first needle point.
    label_chars : int or None
        Width of the format's fixed label field (DST, TBF: 16 characters): the design
        name is cut to it after transliteration, so no field after it moves.
    no_jumps : bool
        The format has no jump record (VP3): a travel after sewing begins a colour block
        (whose start is a header position), never a stitch longer than the format allows.

    Examples
    --------
    >>> f = FORMATS["pes"]
    >>> f.writer, f.stop_style, f.trim_is_jump, f.limit.max_record_mm
    ('PesWriter', 'color', True, 204.7)
    """

    name: str
    writer: str
    stop_style: str
    limit: FormatLimit
    settings: tuple[tuple[str, object], ...] = ()
    postprocess: Callable[[bytes, MachinePattern], bytes] | None = field(default=None, compare=False)
    prepare: Callable[[object], None] | None = field(default=None, compare=False)
    color_after_travel: bool = True
    trim_is_jump: bool = False
    end_trims: bool = False
    first_at_origin: bool = False
    no_jumps: bool = False
    label_chars: int | None = None

    @property
    def description(self) -> str:
        """Human-readable name."""
        return self.limit.description


def _fmt(name: str, writer: str, style: str, settings=(), post=None, prepare=None, **flags) -> MachineFormat:
    return MachineFormat(name, writer, style, FORMAT_LIMITS[name], tuple(settings), post, prepare, **flags)


FORMATS: dict[str, MachineFormat] = {
    f.name: f
    for f in (
        _fmt("dst", "DstWriter", "stop", post=_dst_post, label_chars=16),
        _fmt("tbf", "TbfWriter", "needle_stop", post=_tbf_extents, label_chars=16),
        _fmt("pes", "PesWriter", "color", [("version", 6)], post=_pec_label, color_after_travel=False,
             trim_is_jump=True),
        _fmt("pec", "PecWriter", "color", post=_pec_label, color_after_travel=False, trim_is_jump=True),
        _fmt("jef", "JefWriter", "color", [("trims", True), ("date", FIXED_DATE)]),
        _fmt("exp", "ExpWriter", "stop", post=_exp_trims),
        _fmt("vp3", "Vp3Writer", "color", post=_vp3_origin, prepare=_vp3_even_center, end_trims=True, first_at_origin=True,
             no_jumps=True),
        _fmt("xxx", "XxxWriter", "color"),
        _fmt("u01", "U01Writer", "needle_stop"),
    )
}


def machine_format(path: str | os.PathLike, *, fmt: str | None = None) -> MachineFormat:
    """The format for ``path``'s suffix, or ``fmt`` when given.

    Parameters
    ----------
    path : str or os.PathLike
        A file name; its suffix names the format.
    fmt : str or None, optional
        The format's name, overriding the suffix.

    Returns
    -------
    MachineFormat

    Raises
    ------
    ParameterError
        Unknown suffix or format name; the message lists the supported ones.

    Examples
    --------
    >>> machine_format("a.PES").name, machine_format("a.bin", fmt="dst").name
    ('pes', 'dst')
    >>> try:
    ...     machine_format("a.svg")
    ... except ValueError as exc:
    ...     print(exc)  # doctest: +ELLIPSIS
    file suffix must be one of .dst, ..., got '.svg'
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


#: What each kind of format cannot hold, said wherever its counts are reported.
_CANNOT = {
    "stop": "stop and colour change share one code",
    "needle_stop": "",
    "color": "no stop code: the machine pauses at each colour change (one colour per later actuator), "
             "so tube 1 is laid before start",
    "color_placed": "no stop code: the machine pauses at each colour change (one colour after each placement "
                    "line)",
}


def _notes(f: MachineFormat, mp: MachinePattern) -> tuple[str, ...]:
    notes = [] if f.name in NAMED_FORMATS else [f"{f.name}: no thread names (actuator names are not in the file)"]
    style = "color_placed" if f.stop_style == "color" and mp.lead_block else f.stop_style
    if _CANNOT[style]:
        notes.append(f"{f.name}: {_CANNOT[style]}")
    if f.first_at_origin:
        notes.append(f"{f.name}: the file's origin is {mp.origin_mm[0]:g}, {mp.origin_mm[1]:g} mm (plan frame), 1 mm "
                     "beside the first needle point: the format cannot move the frame before its first stitch "
                     "(recorded in the file's notes: embroact check reads the file in the design's frame)")
    return tuple(notes)


@dataclass(frozen=True, slots=True)
class WriteResult:
    """What a machine-file write produced, counted back from the file's bytes.

    Attributes
    ----------
    path : str or None
        File written (None for :func:`encode`).
    format : str
    size_bytes : int
    stitches, jumps, trims, stops, color_changes : int
        Records the file holds (:mod:`embroact.export.machine.census`).
    split_legs : int
        Legs split because they exceeded the per-record limit.
    cord_stop : str or None
        How cord-in stops were written (:class:`embroact.patterns.stops.CordStop`); None for
        formats whose bytes it does not change (all but DST and EXP).
    pauses_mm : tuple of (float, float)
        Where the machine waits for the operator, plan frame [mm, y up].
    thread_names : tuple of str
        Thread names the file carries (empty where the format has none).
    origin_mm : tuple of float
        Plan position of the file's origin [mm] ((0, 0) but for VP3).
    notes : tuple of str
        What this format cannot carry.
    pause_stops : tuple of int
        Stop records at each pause (2: a double stop; 0: a colour change).
    trims_mm : tuple of (float, float)
        Where each trim cuts, plan frame [mm, y up].

    Examples
    --------
    >>> from embroact.patterns.design import build_plan, default_design
    >>> _, res = encode(build_plan(default_design()), "dst")
    >>> res.path, res.format, res.stitches, res.pauses
    (None, 'dst', 106, 1)
    """

    path: str | None
    format: str
    size_bytes: int
    stitches: int
    jumps: int
    trims: int
    stops: int
    color_changes: int
    split_legs: int
    cord_stop: str | None = CordStop.SEQUENCE.value
    pauses_mm: tuple[tuple[float, float], ...] = ()
    thread_names: tuple[str, ...] = ()
    origin_mm: tuple[float, float] = (0.0, 0.0)
    notes: tuple[str, ...] = ()
    pause_stops: tuple[int, ...] = ()
    trims_mm: tuple[tuple[float, float], ...] = ()

    @property
    def pauses(self) -> int:
        """Times the machine waits for the operator after start."""
        return len(self.pauses_mm)

    def tube_pauses(self) -> tuple[bool, ...]:
        """For each pause: is a tube laid there (False: a colour block that begins a later actuator's
        placement line, VP3, whose travel cannot be a record; the machine only waits for start)?

        Returns
        -------
        tuple of bool
            One per pause, in order.

        Examples
        --------
        >>> WriteResult(None, "vp3", 0, 9, 0, 2, 0, 3, 0, None, ((0, 0),) * 3,
        ...             ("A placement", "A", "B placement", "B")).tube_pauses()
        (True, False, True)
        """
        names = self.thread_names
        if len(names) != self.pauses + 1:
            return (True,) * self.pauses
        return tuple(not name.endswith(PLACEMENT_LABEL) for name in names[1:])

    def counts_text(self) -> str:
        """The file's counts as every command prints them (``106 stitches, 1 stop, 1 trim``).

        Returns
        -------
        str

        Examples
        --------
        >>> WriteResult(None, "dst", 0, 106, 0, 1, 2, 0, 0).counts_text()
        '106 stitches, 2 stops, 1 trim'
        """
        return (f"{self.stitches} stitches, {self.stops} stop{'s' * (self.stops != 1)}, "
                f"{self.trims} trim{'s' * (self.trims != 1)}")

    def as_dict(self) -> dict:
        """Plain dict for JSON output (lists for tuples).

        Returns
        -------
        dict
            One key per field.

        Examples
        --------
        >>> from embroact.patterns.design import build_plan, default_design
        >>> encode(build_plan(default_design()), "dst")[1].as_dict()["pauses_mm"]
        [[-49.3, 3.5]]
        """
        out = {}
        for k in self.__slots__:
            v = getattr(self, k)
            out[k] = [list(p) for p in v] if k in ("pauses_mm", "trims_mm") else list(v) if isinstance(v, tuple) else v
        return out


def _cord_stop_written(f: MachineFormat, cord_stop: CordStop | str) -> str | None:
    """The cord-stop mode where it changes the bytes (stop-code formats DST, EXP), else None."""
    return str(getattr(cord_stop, "value", cord_stop)) if f.stop_style == "stop" else None


def encode(plan: StitchPlan, fmt: str | MachineFormat = "dst", *, split_long: bool = False,
           cord_stop: CordStop | str = CordStop.SEQUENCE) -> tuple[bytes, WriteResult]:
    """Encode ``plan`` as bytes of format ``fmt`` (no file touched); the counts are read back from them.

    Parameters
    ----------
    plan : StitchPlan
        The records.
    fmt : str or MachineFormat, optional
        The format.
    split_long : bool, optional
        Split legs longer than the format allows into stitches outside the tube corridor.
    cord_stop : CordStop or str, optional
        How a stop-code format writes a cord-in stop.

    Returns
    -------
    data : bytes
        The file's bytes.
    result : WriteResult
        The counts, read back from ``data``.

    Examples
    --------
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (1, 1, Command.STITCH, Role.LEG),
    ...                                 (1, 1, Command.END, Role.CONTROL, -1)])
    >>> data, res = encode(plan, "dst")
    >>> len(data), res.stitches, res.stops
    (522, 2, 0)
    """
    import importlib

    f = fmt if isinstance(fmt, MachineFormat) else machine_format("", fmt=fmt)
    mp = to_pattern(plan, f, split_long=split_long, cord_stop=cord_stop)
    writer = importlib.import_module(f"pystitch.{f.writer}")
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
    return data, _result(census(data, f.name), len(data), mp.split_legs, _cord_stop_written(f, cord_stop),
                         mp.origin_mm, _notes(f, mp))


def _result(c, size_bytes: int, split_legs: int, cord_stop: str | None, origin_mm, notes) -> WriteResult:
    """A :class:`WriteResult` of census ``c``, its positions moved from the file frame to the plan frame."""
    ox, oy = origin_mm

    def plan_frame(points):
        return tuple((round(x + ox, 1) + 0.0, round(y + oy, 1) + 0.0) for x, y in points)

    return WriteResult(None, c.format, size_bytes, c.stitches, c.jumps, c.trims, c.stops, c.color_changes, split_legs,
                       cord_stop, plan_frame(c.pauses_mm), c.thread_names, tuple(origin_mm), notes, c.pause_stops,
                       plan_frame(c.trims_mm))


def read_result(data: bytes, fmt: str, path: str | None = None) -> WriteResult:
    """What a machine file's bytes hold, as :func:`encode` reports it for a file it writes.

    Parameters
    ----------
    data : bytes
        The file's bytes.
    fmt : str
        Its format's suffix.
    path : str, optional
        The file, for the result's ``path``.

    Returns
    -------
    WriteResult
        Counted by :func:`embroact.export.machine.census.census`; positions in the frame
        :func:`embroact.export.machine.filecheck.records_plan` draws the file in (a VP3 file
        embroact wrote: the design's).

    Examples
    --------
    >>> from embroact.patterns.design import build_plan, default_design
    >>> data, res = encode(build_plan(default_design()), "jef")
    >>> read_result(data, "jef").counts_text(), res.counts_text()
    ('106 stitches, 0 stops, 1 trim', '106 stitches, 0 stops, 1 trim')
    """
    from .vp3note import read_origin_mm

    c = census(data, fmt)
    origin = (read_origin_mm(data) if fmt == "vp3" else None) or (0.0, 0.0)
    stop_records = set(c.pause_stops) if fmt in ("dst", "exp") else set()
    cord_stop = None if not stop_records else CordStop.DOUBLE.value if stop_records == {2} else CordStop.SEQUENCE.value
    return replace(_result(c, len(data), 0, cord_stop, origin, ()), path=path)


def write(
    plan: StitchPlan,
    path: str | os.PathLike,
    *,
    fmt: str | None = None,
    split_long: bool = False,
    cord_stop: CordStop | str = CordStop.SEQUENCE,
) -> WriteResult:
    """Write ``plan`` to ``path`` atomically in the format of its suffix (or ``fmt``).

    Parameters
    ----------
    plan : StitchPlan
    path : path-like
        The file to write; its suffix names the format unless ``fmt`` is given.
    fmt : str, optional
        Format name (``"dst"``, ``"exp"``, ...), overriding the suffix.
    split_long : bool
        Split legs above the format's per-record limit instead of refusing.
    cord_stop : CordStop or str
        ``"sequence"`` or ``"double"`` (:class:`embroact.patterns.stops.CordStop`).

    Returns
    -------
    WriteResult
        Counted back from the written bytes.

    Examples
    --------
    >>> import os, tempfile
    >>> from embroact.patterns.design import build_plan, default_design
    >>> res = write(build_plan(default_design()), os.path.join(tempfile.mkdtemp(), "a1.exp"))
    >>> res.format, res.stitches, res.stops, os.path.getsize(res.path) == res.size_bytes
    ('exp', 106, 1, True)

    Raises
    ------
    ParameterError
        Unknown suffix/format or cord-stop mode.
    LongLegError
        A leg exceeds the format's per-record limit and ``split_long`` is false.
    ExportError
        The directory is missing or not writable; no file is left behind.
    """
    f = machine_format(path, fmt=fmt)
    check_output_dir(path)
    data, res = encode(plan, f, split_long=split_long, cord_stop=cord_stop)
    write_bytes_atomic(path, data)
    return replace(res, path=str(path))
