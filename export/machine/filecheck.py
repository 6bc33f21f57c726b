"""Check any embroidery file pystitch reads against the tube(s) it is meant to couch.

The file's records are read **in the file's own order** (no trims inserted, no
zero-length jump runs removed: pystitch's reader is called with
``trim_at=None, trim_distance=None, clipping=False``), so a finding's
``stitch_index`` is the record number in the file (DST: record ``i`` is bytes
``512 + 3 i`` to ``512 + 3 i + 2``).

Frame
-----
Positions are those pystitch reads, converted to millimetres: ``x_mm = x / 10``,
``y_mm = y / 10`` with **y pointing down** (pystitch's frame; DST stores y up
and the reader flips it). Tube paths are given in this same frame. For a tube
drawn in an embroact design (plan frame, y up), negate y:
plan ``(x, y)`` -> file ``(x, -y)``.  A VP3 file embroact wrote has its origin
1 mm beside the first needle point and says where in its notes
(:mod:`embroact.export.machine.vp3note`): its positions are shifted back, so it
reads in the same frame as every other format written from the design.

Commands
--------
stitch -> STITCH; jump -> JUMP; trim -> TRIM; stop, colour change and needle set ->
STOP (a colour change is how DST writes a stop; set the machine to stop at each);
end -> END; any other command (sequins, speed) -> JUMP (a frame move).

Tube files
----------
A small TOML file describes one or more tubes and, optionally, the machine::

    [[tube]]
    name = "A1"                       # optional
    path_mm = "0,0 100,0"             # or [[0, 0], [100, 0]]; mm, file frame
    outer_radius_mm = 1.5             # optional, default 1.5
    clearance_mm = 0.3                # optional, default 0.3
    end_margin_mm = 0.0               # optional, default 0

    [machine]                         # optional
    hoop_width_mm = 200.0
    hoop_height_mm = 200.0
    min_stitch_mm = 0.3
    max_stitch_mm = 12.1

Examples
--------
>>> from embroact.export.machine.filecheck import parse_tube_path
>>> parse_tube_path("0,0 100,0 100.5,-20").tolist()
[[0.0, 0.0], [100.0, 0.0], [100.5, -20.0]]
"""
from __future__ import annotations

import io
import os
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...patterns.base.errors import DesignFileError, ParameterError, check_range
from ...patterns.base.findings import Finding
from ...patterns.base.validate import DESIGN_ACTUATORS, check_coordinates, MACHINE_FILE_BYTES, MACHINE_FILE_RECORDS, read_input
from ...patterns.limits import FORMAT_LIMITS, UNITS_PER_MM
from ...patterns.params import Tube
from .vp3note import read_origin_mm
from ...patterns.plan import Command, Role, StitchPlan
from ...patterns.rules import RuleSettings, TubeLayout, layout_from_records
from .census import COLOR_FORMATS, RAW_READ, raw_reader
from .dst import END_BYTE, HEADER_SIZE
from ..files.tomltext import load_toml

__all__ = [
    "FileRecords",
    "read_records",
    "records_plan",
    "parse_tube_path",
    "tube_layout",
    "load_tube_file",
    "check_file",
    "readable_suffixes",
    "default_format",
    "file_rule_settings",
    "dst_header_faults",
    "extent_faults",
    "FILE_FIXES",
]

_DST_RECORD_BYTES = 3
#: Bytes of TBF's text header holding the extents (the needle table and thread list follow).
_TBF_HEADER = 0x376
#: Leading bytes of formats that have a magic number.
_MAGIC = {"pes": b"#PES", "pec": b"#PEC0001", "vp3": b"%vsm%"}
#: Formats whose stitch data ends with an end-of-design code the reader stops at: a reader that runs
#: into the end of the file instead was given a truncated or garbage file. (JEF: see _check_jef_end;
#: EXP has no header and no end code, so a truncated EXP file cannot be told from a short design.)
_END_CODED = {"dst", "pes", "pec", "vp3", "xxx", "tbf", "u01"}
_JEF_CONTROL, _JEF_END = 0x80, 0x10
_TUBE_KEYS = {"name", "path_mm", "outer_radius_mm", "clearance_mm", "end_margin_mm"}
_MACHINE_KEYS = {"hoop_width_mm", "hoop_height_mm", "min_stitch_mm", "max_stitch_mm", "format"}


@dataclass(frozen=True, slots=True, eq=False)
class FileRecords:
    """The records of an embroidery file, in its own order.

    Attributes
    ----------
    path : str
        The file.
    suffix : str
        Lower-case format suffix without the dot.
    xy_mm : ndarray (n, 2)
        Positions [mm], pystitch's frame (y down); read-only.
    commands : ndarray of int8
        :class:`Command` per record.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> from embroact.export.machine.formats import encode
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (1, 1, Command.STITCH, Role.LEG),
    ...                                 (1, 1, Command.END, Role.CONTROL, -1)])
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "a.dst").write_bytes(encode(plan, "dst")[0])
    ...     records = read_records(Path(tmp, "a.dst"))
    >>> records.suffix, len(records), records.xy_mm.tolist()
    ('dst', 3, [[0.0, 0.0], [1.0, -1.0], [1.0, -1.0]])
    """

    path: str
    suffix: str
    xy_mm: np.ndarray
    commands: np.ndarray

    def __len__(self) -> int:
        return len(self.xy_mm)


def readable_suffixes() -> tuple[str, ...]:
    """Embroidery suffixes pystitch can read, sorted.

    Returns
    -------
    tuple of str

    Examples
    --------
    >>> {"dst", "pes", "exp"} <= set(readable_suffixes())
    True
    """
    import pystitch

    return tuple(sorted(f["extension"] for f in pystitch.supported_formats()
                        if f.get("reader") is not None and f.get("category") == "embroidery"))


def _check_dst_bytes(path: str, data: bytes) -> None:
    if len(data) < HEADER_SIZE:
        raise DesignFileError(f"{path}: not a DST file: {len(data)} bytes, shorter than the 512-byte header")
    if not data.startswith(b"LA:"):
        raise DesignFileError(f"{path}: not a DST file: the header does not start with 'LA:'")
    body = data[HEADER_SIZE:]
    if not any(body[i + 2] & END_BYTE == END_BYTE
               for i in range(0, len(body) - _DST_RECORD_BYTES + 1, _DST_RECORD_BYTES)):
        raise DesignFileError(
            f"{path}: truncated DST file: no end record among {len(body) // _DST_RECORD_BYTES} records"
        )


class _TrackedBytes(io.BytesIO):
    """An in-memory file that remembers whether a read came back short (the reader hit the end)."""

    hit_end = False

    def read(self, size=-1):
        data = super().read(size)
        if size is not None and size >= 0 and len(data) < size:
            self.hit_end = True
        return data


def _check_jef_end(path: str, data: bytes) -> None:
    """Walk the JEF records from the header's stitch offset to the end code 0x80 0x10."""
    i = int.from_bytes(data[:4], "little") if len(data) >= 4 else len(data)
    while i + 1 < len(data):
        if data[i] == _JEF_CONTROL:
            if data[i + 1] == _JEF_END:
                return
            i += 2
        i += 2
    raise DesignFileError(f"{path}: truncated or garbage JEF file: no end code (0x80 0x10) after the stitches")


def _read_pattern(path: str, suffix: str, data: bytes):
    """pystitch's reader for ``suffix`` on ``data``; checks magic numbers and end codes first/after."""
    import pystitch

    magic = _MAGIC.get(suffix)
    if magic is not None and not data.startswith(magic):
        raise DesignFileError(f"{path}: not a {suffix.upper()} file: it does not start with {magic.decode()!r}")
    if suffix == "jef":
        _check_jef_end(path, data)
    reader = raw_reader(suffix)
    if getattr(reader, "READ_FILE_IN_TEXT_MODE", False):
        return pystitch.read(path, dict(RAW_READ))
    stream = _TrackedBytes(data)
    try:
        pattern = pystitch.EmbPattern.read_embroidery(reader, stream, dict(RAW_READ))
    except Exception:  # the VP3 reader fails on a cut-short file (None + int) after a short read
        if not (suffix == "vp3" and stream.hit_end):
            raise
        pattern = None
    if suffix in _END_CODED and stream.hit_end:
        raise DesignFileError(
            f"{path}: truncated or garbage {suffix.upper()} file: the data ends before the end-of-design code"
        )
    return pattern


def _command_map() -> dict[int, Command]:
    import pystitch as pe

    return {pe.STITCH: Command.STITCH, pe.JUMP: Command.JUMP, pe.TRIM: Command.TRIM, pe.STOP: Command.STOP,
            pe.COLOR_CHANGE: Command.STOP, pe.NEEDLE_SET: Command.STOP, pe.END: Command.END}


def read_records(path: str | os.PathLike) -> FileRecords:
    """Read an embroidery file into arrays, one row per record in the file's own order.

    Parameters
    ----------
    path : str or os.PathLike
        The file; its suffix names the format.

    Returns
    -------
    FileRecords

    Raises
    ------
    DesignFileError
        One line when the file is missing, of an unknown kind, truncated or garbage.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> from embroact.export.machine.formats import encode
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (1, 1, Command.STITCH, Role.LEG),
    ...                                 (1, 1, Command.END, Role.CONTROL, -1)])
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "a.dst").write_bytes(encode(plan, "dst")[0])
    ...     records = read_records(Path(tmp, "a.dst"))
    >>> [Command(c).name for c in records.commands]
    ['STITCH', 'STITCH', 'END']
    >>> try:
    ...     read_records("a.svg")
    ... except ValueError as exc:
    ...     print(exc)  # doctest: +ELLIPSIS
    a.svg: cannot read '.svg' embroidery files; readable: ...
    """
    import pystitch

    p = str(path)
    suffix = Path(p).suffix.lower().lstrip(".")
    if suffix not in readable_suffixes():
        kind = f"cannot read '.{suffix}' embroidery files" if suffix else "no file suffix to tell its format by"
        raise DesignFileError(f"{p}: {kind}; readable: {', '.join(readable_suffixes())}")
    data = read_input(p, MACHINE_FILE_BYTES, "embroidery file")
    if not data:
        raise DesignFileError(f"{p}: empty file")
    if suffix == "dst":
        _check_dst_bytes(p, data)
    try:
        pattern = _read_pattern(p, suffix, data)
    except DesignFileError:
        raise
    except Exception as exc:  # any reader failure on garbage is unusable input, one line
        raise DesignFileError(f"{p}: unreadable {suffix.upper()} file ({type(exc).__name__}: {exc})") from None
    if pattern is None or not any(s[2] & pystitch.COMMAND_MASK == pystitch.STITCH for s in pattern.stitches):
        raise DesignFileError(f"{p}: no stitches in this {suffix.upper()} file")
    if len(pattern.stitches) > MACHINE_FILE_RECORDS:
        raise DesignFileError(f"{p}: embroidery file must have at most {MACHINE_FILE_RECORDS:,} records, "
                              f"got {len(pattern.stitches):,}")
    raw = np.array(pattern.stitches, dtype=np.float64).reshape(-1, 3)
    cmap = _command_map()
    commands = np.array([cmap.get(int(c) & pystitch.COMMAND_MASK, Command.JUMP) for c in raw[:, 2]], dtype=np.int8)
    xy = raw[:, :2] / 10.0
    origin = read_origin_mm(data) if suffix == "vp3" else None
    if origin is not None:  # embroact's VP3: back to the design's frame (origin 0, 0; y down)
        xy += (origin[0], -origin[1])
    xy.setflags(write=False)
    commands.setflags(write=False)
    return FileRecords(p, suffix, xy, commands)


#: Role a file's record is drawn with (a file says nothing of legs, ties or edges: every stitch is a leg).
_FILE_ROLES = {Command.STITCH: Role.LEG, Command.JUMP: Role.TRAVEL}


def records_plan(records: FileRecords) -> StitchPlan:
    """A file's records as a stitch plan (plan frame: mm, y up; no actuators), for pictures.

    Parameters
    ----------
    records : FileRecords
        What :func:`read_records` gives.

    Returns
    -------
    StitchPlan

    Examples
    --------
    >>> import os, tempfile
    >>> from embroact.export.cli.main import main
    >>> out = os.path.join(tempfile.mkdtemp(), "z.dst")
    >>> main(["zigzag", "--width-mm", "7", "--interval-mm", "1", "--length-mm", "30", "-o", out]) == 0
    wrote ...
    True
    >>> plan = records_plan(read_records(out))
    >>> plan.stitch_count, [round(float(v), 1) for v in plan.xy_mm.max(axis=0)]
    (36, [15.0, 3.7])
    """
    roles = np.array([_FILE_ROLES.get(Command(int(c)), Role.CONTROL) for c in records.commands], dtype=np.int8)
    xy = records.xy_mm * np.array([1.0, -1.0]) + 0.0
    stop = records.commands == Command.STOP
    pause = stop & ~np.concatenate([[False], stop[:-1]])  # a run of stops (a double stop) is one pause
    # pause k lays tube k + 1 (a colour format's first tube is laid before start: its colour changes lay the next)
    tube = np.maximum(np.cumsum(pause) - (records.suffix not in COLOR_FORMATS), 0)
    return StitchPlan(xy, records.commands, roles, tube, (), Path(records.path).stem)


def parse_tube_path(text: str, *, name: str = "tube_path") -> np.ndarray:
    """Points from ``"x1,y1 x2,y2 ..."`` or SVG path data (``"M 0 0 L 100 0"``, as ``--path`` takes;
    SVG's frame, y down, is the file's frame) [mm]; one-line :class:`ParameterError` on bad text.

    Parameters
    ----------
    text : str
        The points or the path data.
    name : str, optional
        The option's name, for the messages.

    Returns
    -------
    numpy.ndarray (n, 2)
        [mm], n >= 2.

    Examples
    --------
    >>> parse_tube_path("-50,0 50,0").tolist()
    [[-50.0, 0.0], [50.0, 0.0]]
    >>> parse_tube_path("M 0 0 h 100 v -20").tolist()
    [[0.0, 0.0], [100.0, 0.0], [100.0, -20.0]]
    """
    usage = f"{name} must be 'x1,y1 x2,y2 ...' with at least 2 points in mm, or SVG path data ('M 0 0 L 100 0')"
    if str(text).lstrip()[:1] in ("M", "m"):
        from ...patterns.base.errors import PatternError
        from ...patterns.svgpath import flatten, parse_d

        try:
            pts = np.asarray(flatten(parse_d(str(text))), dtype=np.float64)
        except PatternError as exc:
            raise ParameterError(f"{name}: {exc}") from None
        if pts.ndim != 2 or len(pts) < 2 or not np.all(np.isfinite(pts)):
            raise ParameterError(f"{usage}, got {text!r}")
        return _in_range(pts, name)
    try:
        pts = np.array([[float(v) for v in pair.split(",")] for pair in str(text).split()], dtype=np.float64)
    except ValueError:
        raise ParameterError(f"{usage}, got {text!r}") from None
    if pts.ndim != 2 or pts.shape[1:] != (2,) or len(pts) < 2:
        raise ParameterError(f"{usage}, got {text!r}")
    if not np.all(np.isfinite(pts)):
        raise ParameterError(f"{name} must hold finite numbers, got {text!r}")
    return _in_range(pts, name)


def _in_range(pts: np.ndarray, name: str) -> np.ndarray:
    """``pts`` if every coordinate lies within the range paths may use (before any arithmetic on them)."""
    check_coordinates(name, float(np.abs(pts).max()) if pts.size else 0.0)  # the bound of design paths
    return pts


def tube_layout(
    points_mm,
    *,
    name: str = "tube",
    outer_radius_mm: float = Tube().outer_radius_mm,
    clearance_mm: float = Tube().clearance_mm,
    end_margin_mm: float = 0.0,
) -> TubeLayout:
    """A tube for file checks from path points in the file's frame [mm], with range checks.

    The points may come from anywhere (a ``--tube-path`` string, a tube file, an SVG
    drawing): every source meets the same coordinate bound here, before any arithmetic.

    Parameters
    ----------
    points_mm : array_like (n, 2)
        The tube's axis [mm].
    name : str, optional
        The tube's name.
    outer_radius_mm, clearance_mm, end_margin_mm : float, optional
        As :class:`~embroact.patterns.rules.TubeLayout` (the default tube's).

    Returns
    -------
    TubeLayout

    Examples
    --------
    >>> t = tube_layout([(0, 0), (100, 0)], name="A")
    >>> t.name, t.outer_radius_mm, t.path.length
    ('A', 1.5, 100.0)
    """
    return TubeLayout.from_path(
        name,
        _in_range(np.asarray(points_mm, dtype=np.float64), name),
        outer_radius_mm=check_range("outer_radius_mm", outer_radius_mm, low=0.0, high=50.0),
        clearance_mm=check_range("clearance_mm", clearance_mm, low=0.0, low_inclusive=True, high=50.0),
        end_margin_mm=check_range("end_margin_mm", end_margin_mm, low=0.0, low_inclusive=True, high=1e4),
    )


def _unknown(table: dict, allowed: set[str], where: str, path: str) -> None:
    extra = sorted(set(table) - allowed)
    if extra:
        raise DesignFileError(f"{path}: unknown key {extra[0]!r} in {where}; allowed: {', '.join(sorted(allowed))}")


def _toml_points(raw, where: str) -> np.ndarray:
    if isinstance(raw, str):
        return parse_tube_path(raw, name=where)
    try:
        pts = np.array(raw, dtype=np.float64)
    except (TypeError, ValueError, OverflowError):  # OverflowError: an integer no float holds
        pts = np.zeros(0)
    if pts.ndim != 2 or pts.shape[1:] != (2,) or len(pts) < 2 or not np.all(np.isfinite(pts)):
        raise DesignFileError(f"{where} must be [[x, y], ...] with at least 2 finite points in mm, got {raw!r:.80}")
    return _in_range(pts, where)


def load_tube_file(path: str | os.PathLike) -> tuple[tuple[TubeLayout, ...], dict]:
    """Tubes and machine settings (a dict of :class:`RuleSettings` fields) from a tube TOML file.

    Parameters
    ----------
    path : str or os.PathLike
        The file: ``[[tube]]`` tables with ``path_mm`` (and optionally ``name``, ``outer_radius_mm``,
        ``clearance_mm``, ``end_margin_mm``) and a ``[machine]`` table.

    Returns
    -------
    tubes : tuple of TubeLayout
    machine : dict

    Raises
    ------
    DesignFileError
        One line naming the file and the table.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "t.toml").write_text('[[tube]]\\nname = "A"\\npath_mm = [[0, 0], [100, 0]]\\n'
    ...                                    '[machine]\\nhoop_width_mm = 130.0\\n')
    ...     tubes, machine = load_tube_file(Path(tmp, "t.toml"))
    >>> [t.name for t in tubes], machine
    (['A'], {'hoop_width_mm': 130.0})
    """
    p = str(path)
    doc = load_toml(p, "tube file")
    _unknown(doc, {"tube", "machine"}, "the file", p)
    entries = doc.get("tube")
    if not isinstance(entries, list) or not entries or not all(isinstance(t, dict) for t in entries):
        raise DesignFileError(f"{p}: needs at least one [[tube]] table with path_mm")
    if len(entries) > DESIGN_ACTUATORS:
        raise DesignFileError(f"{p}: must have at most {DESIGN_ACTUATORS:,} [[tube]] tables (one per actuator), "
                              f"got {len(entries):,}")
    tubes = []
    for i, t in enumerate(entries):
        _unknown(t, _TUBE_KEYS, f"[[tube]] {i + 1}", p)
        if "path_mm" not in t:
            raise DesignFileError(f"{p}: [[tube]] {i + 1} has no path_mm")
        pts = _toml_points(t["path_mm"], f"{p}: [[tube]] {i + 1} path_mm")
        opts = {k: t[k] for k in ("outer_radius_mm", "clearance_mm", "end_margin_mm") if k in t}
        tubes.append(tube_layout(pts, name=str(t.get("name", f"tube {i + 1}")), **opts))
    machine = doc.get("machine", {})
    if not isinstance(machine, dict):
        raise DesignFileError(f"{p}: [machine] must be a table")
    _unknown(machine, _MACHINE_KEYS, "[machine]", p)
    return tuple(tubes), dict(machine)


def default_format(records: FileRecords) -> str:
    """The file's own format when it has per-record limits in ``patterns/limits.py``, else ``"dst"``.

    Parameters
    ----------
    records : FileRecords
        The file's records.

    Returns
    -------
    str

    Examples
    --------
    >>> import numpy as np
    >>> default_format(FileRecords("a.pes", "pes", np.zeros((0, 2)), np.zeros(0))), \\
    ...     default_format(FileRecords("a.10o", "10o", np.zeros((0, 2)), np.zeros(0)))
    ('pes', 'dst')
    """
    return records.suffix if records.suffix in FORMAT_LIMITS else "dst"


def file_rule_settings(records: FileRecords, *, format: str | None = None, **machine) -> RuleSettings:
    """Rule settings for a file: the default machine's limits and hoop, its own format, ``machine`` overrides.

    Parameters
    ----------
    records : FileRecords
        The file's records.
    format : str or None, optional
        Check against this format's limits instead of the file's own.
    **machine
        :class:`RuleSettings` fields (a tube file's ``[machine]`` table).

    Returns
    -------
    RuleSettings

    Examples
    --------
    >>> import numpy as np
    >>> s = file_rule_settings(FileRecords("a.exp", "exp", np.zeros((0, 2)), np.zeros(0)), hoop_width_mm=100.0)
    >>> s.format, s.hoop_width_mm
    ('exp', 100.0)
    """
    from ...patterns.design import MachineSettings

    return RuleSettings.for_machine(MachineSettings(), format=format or default_format(records), **machine)


#: Fixes for the author of an embroidery file (the rules' own fixes are worded for embroact designs).
FILE_FIXES = {
    "EA101": "re-digitise with the needle points beside the tube (a wider pattern), or check the tube path",
    "EA102": "re-digitise with a shorter maximum stitch, or split this leg into stitches beside the tube",
    "EA103": "split this leg (re-digitise with a maximum stitch within the machine's), or raise max_stitch_mm "
             "in the tube file's [machine] table if the machine sews longer stitches",
    "EA104": "re-digitise with a longer minimum stitch, or remove this needle point",
    "EA105": "re-digitise with a longer stitch interval (fewer needle points along the rail)",
    "EA106": "re-digitise with a longer stitch interval (fewer needle points along the rail)",
    "EA306": "re-digitise or move the design so that this record lies in the hoop, or give the hoop size in the "
             "tube file's [machine] table",
    "EA307": "re-digitise with legs over this stretch of tube, or check the tube path (the file's frame, y down)",
    "EA308": "give the tube path these legs were digitised for, or re-digitise without them",
    "EA501": "re-digitise with a trim before this travel, or with shorter travel",
    "EA502": "re-digitise with a stop (DST: a colour change) before this tube's stitches",
    "EA503": "re-digitise without this stop, or check that the tube paths given are the file's",
    "EA504": "split the embroidery into several files",
    "EA505": "save the file again from the digitising software (the header is rewritten from the records)",
}


def dst_header_faults(data: bytes) -> tuple[str, ...]:
    r"""The DST header's ST, CO and extent fields that disagree with the records after it.

    ``ST`` must count the 3-byte records (the end record included), ``CO`` the colour-change
    records (0xC3, DST's stop), ``+X -X +Y -Y`` the largest excursion from the start point in
    each direction (0.1 mm, y up), over every record.

    Parameters
    ----------
    data : bytes
        A DST file.

    Returns
    -------
    tuple of str
        One line per field that disagrees; empty when the header is right.

    Examples
    --------
    >>> body = bytes([0x01, 0x00, 0x03, 0x00, 0x00, 0xC3, 0x00, 0x00, 0xF3])
    >>> head = b"LA:x               \rST:      3\rCO:  1\r+X:    1\r-X:    0\r+Y:    0\r-Y:    0\r"
    >>> dst_header_faults(head.ljust(512, b" ") + body)
    ()
    >>> dst_header_faults(head.replace(b"ST:      3", b"ST:     99").ljust(512, b" ") + body)
    ('header ST 99, but the body holds 3 records (the end record included)',)
    """
    from .dst import COLOR_BYTE, move_array

    text = data[:HEADER_SIZE].decode("latin-1")
    fields = {m.group(1): m.group(2).strip() for m in re.finditer(r"(ST|CO):([^\r]*)\r", text)}
    moves, b3 = move_array(data[HEADER_SIZE:])
    counts = _field_faults(fields, {"ST": (len(b3), "records (the end record included)"),
                                    "CO": (int(np.count_nonzero(b3 == COLOR_BYTE)), "colour-change (stop) records")})
    return counts + extent_faults(data[:HEADER_SIZE], np.cumsum(moves, axis=0) * (1.0, -1.0) / UNITS_PER_MM)


def extent_faults(head: bytes, xy_mm: np.ndarray) -> tuple[str, ...]:
    """The ``+X -X +Y -Y`` fields of a text header (DST, TBF) that disagree with positions ``xy_mm``
    (every record, mm, y down as read; the fields are 0.1 mm, y up, from the start point).

    Parameters
    ----------
    head : bytes
        The header.
    xy_mm : numpy.ndarray (n, 2)
        Every record's position as read [mm, y down].

    Returns
    -------
    tuple of str
        One line per field that disagrees.

    Examples
    --------
    >>> import numpy as np
    >>> head = b"+X:   10\\r-X:    0\\r+Y:    0\\r-Y:    0\\r"
    >>> extent_faults(head, np.array([[1.0, 0.0]])), len(extent_faults(head, np.array([[2.0, 0.0]])))
    ((), 1)
    """
    text = head.decode("latin-1")
    fields = {m.group(1): m.group(2).strip() for m in re.finditer(r"([+-][XY]):([^\r]*)\r", text)}
    at = np.vstack([np.zeros((1, 2)), np.rint(np.asarray(xy_mm, dtype=np.float64) * (10.0, -10.0))])
    (xmin, ymin), (xmax, ymax) = at.min(axis=0).astype(int).tolist(), at.max(axis=0).astype(int).tolist()
    body = {"+X": (xmax, "right of"), "-X": (-xmin, "left of"), "+Y": (ymax, "above"), "-Y": (-ymin, "below")}
    return _field_faults(fields, {k: (v, f"units {where} the start point") for k, (v, where) in body.items()})


def _field_faults(fields: dict, body: dict) -> tuple[str, ...]:
    faults = []
    for key, (value, what) in body.items():
        given = fields.get(key)
        if given is None or not re.fullmatch(r"[+-]?\d+", given):
            faults.append(f"header has no {key} number (got {given!r}); the body holds {value} {what}")
        elif int(given) != value:
            verb = "holds" if key in ("ST", "CO") else "reaches"
            faults.append(f"header {key} {int(given)}, but the body {verb} {value} {what}")
    return tuple(faults)


def _split_legs(records: FileRecords, max_stitch_mm: float, trim_run: int) -> np.ndarray:
    """Jump records inside sewing (a stitch before the run, a stitch after it, nothing else between,
    fewer than ``trim_run`` jumps: no trim) whose stitch-to-stitch leg is longer than ``max_stitch_mm``
    and at most twice it: a writer split one long stitch into jump(s) + stitch, and the machine sews
    the one long leg.  Longer moves are travel (EA501 judges a run that reads as a trim)."""
    cmds, xy = records.commands, records.xy_mm
    drop = np.zeros(len(cmds), dtype=bool)
    jump = np.concatenate([[False], cmds == Command.JUMP, [False]])
    starts = np.flatnonzero(jump[1:-1] & ~jump[:-2])  # first jump of each run
    ends = np.flatnonzero(jump[1:-1] & ~jump[2:]) + 1  # the record after each run
    ok = (starts > 0) & (ends < len(cmds))
    starts, ends = starts[ok], ends[ok]
    ok = (cmds[starts - 1] == Command.STITCH) & (cmds[ends] == Command.STITCH) & (ends - starts < trim_run)
    leg = np.hypot(*(xy[ends] - xy[starts - 1]).T)
    split = ok & (leg > max_stitch_mm) & (leg <= 2 * max_stitch_mm)
    for a, b in zip(starts[split], ends[split]):
        drop[a:b] = True
    return drop


def _frame_hint(layout, records: FileRecords) -> str:
    """When no needle point lies near any tube: which frame the tube paths are read in."""
    from ...patterns.rules.layout import FILE_REACH_MM
    from ...patterns.spatial import TubeIndex

    needles = records.xy_mm[records.commands == Command.STITCH]
    if not layout.tubes or np.any(layout.owner >= 0):
        return ""
    flipped = [np.asarray(t.path.coords) * (1.0, -1.0) for t in layout.tubes]
    if len(TubeIndex(flipped).nearest(needles, FILE_REACH_MM)[0]) > len(needles) / 2:
        return ("; with y negated the tube path lies on the stitches: it was given y up (an embroact design's "
                "plan frame), and files are read y down (plan (x, y) is file (x, -y))")
    return (f"; no needle point lies within {FILE_REACH_MM:g} mm of any tube: tube paths are in the file's frame "
            "(0.1 mm units / 10, y down, origin at the file's start point)")


def check_file(
    path: str | os.PathLike,
    tubes,
    *,
    settings: RuleSettings | None = None,
    records: FileRecords | None = None,
) -> tuple[Finding, ...]:
    """Read an embroidery file and run the design rules for files against ``tubes``.

    Besides the rules on its records: a DST file's header is held against them, a TBF file's extents
    too (EA505); a
    long stitch a writer split into jump(s) + stitch is checked as the one leg the machine
    sews (EA103 names it); each finding gives its place as a needle-point number with the
    record number alongside (both counted from 0), the same for every format, and a fix for
    the file's author.

    Parameters
    ----------
    path : str or PathLike
        Any file pystitch reads.
    tubes : sequence of TubeLayout
        Tube paths in the file's frame (mm, y down); see :func:`tube_layout`.
    settings : RuleSettings, optional
        Defaults to :func:`file_rule_settings`: the file's own format, the default
        machine's stitch limits and hoop.
    records : FileRecords, optional
        ``read_records(path)`` when the caller has read it already (the file is not read twice).

    Returns
    -------
    tuple of Finding
        Worst first; ``stitch_index`` is the record index in the file, ``needle_point`` the
        needle point there (or the last one before it).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from embroact.patterns.zigzag import zigzag
    >>> from embroact.patterns.params import ZigzagParams
    >>> from embroact.export.machine.formats import encode
    >>> plan = zigzag([[0.0, 0.0], [40.0, 0.0]], ZigzagParams(7.0, 1.0))
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "z.dst").write_bytes(encode(plan, "dst")[0])
    ...     found = check_file(Path(tmp, "z.dst"), [tube_layout([(0, 0), (40, 0)])])
    ...     wrong = check_file(Path(tmp, "z.dst"), [tube_layout([(0, 3.5), (40, 3.5)])])  # along a rail
    >>> found, sorted({f.code for f in wrong})[:1]
    ((), ['EA101'])
    """
    from dataclasses import replace

    from ...predict.sleeve_rules import check_layout

    records = read_records(path) if records is None else records
    settings = settings or file_rule_settings(records)
    faults: tuple[str, ...] = ()
    if records.suffix in ("dst", "tbf"):
        data = read_input(str(path), MACHINE_FILE_BYTES, "embroidery file")
        faults = dst_header_faults(data) if records.suffix == "dst" else extent_faults(data[:_TBF_HEADER], records.xy_mm)
    drop = _split_legs(records, settings.max_stitch_mm, settings.trim_jump_count)
    keep = np.flatnonzero(~drop)
    layout = layout_from_records(records.xy_mm[keep], records.commands[keep], tuple(tubes), index=keep,
                                 header_faults=faults)
    hint = _frame_hint(layout, records)
    merged = {int(j) for j in np.flatnonzero(drop[:-1] & ~drop[1:]) + 1}  # the stitch after each dropped run
    needle_count = np.cumsum(records.commands == Command.STITCH)
    out = []
    for f in check_layout(layout, settings):
        if f.code == "EA102" and f.stitch_index in merged:
            continue  # the file already splits it: EA103 names the long leg
        message = f.message
        if f.code == "EA103" and f.stitch_index in merged:
            r = f.stitch_index
            first = r - 1
            while first > 0 and drop[first - 1]:
                first -= 1
            message += (f"; written as {r - first} jump record(s) + 1 stitch (records {first} to {r}): the machine "
                        "sews one leg from the needle point before")
        if f.code == "EA307" and hint:
            message += hint
        more = re.fullmatch(r"(\d+ more findings of this rule, from )stitch (\d+) on", message)
        if more:  # the capped rule's closing finding: its first record, as a file's places are given
            r = int(more.group(2))
            message = f"{more.group(1)}record {r} on (needle point {int(needle_count[r]) - 1})"
        extra = {}
        if f.stitch_index is not None:
            r = int(f.stitch_index)
            extra = {"needle_point": int(needle_count[r]) - 1, "at_needle": bool(records.commands[r] == Command.STITCH)}
        out.append(replace(f, message=message, fix=FILE_FIXES.get(f.code, f.fix), **extra))
    return tuple(out)
