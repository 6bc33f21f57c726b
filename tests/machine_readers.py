"""Machine files read by two libraries embroact did not write (pystitch, pyembroidery) and
counted by each format's own conventions (docs/machine.md section 5), record by record.

``file_records`` turns a reader's output into the file's records: ``(kind, x, y)`` in
0.1 mm, y down, with kind one of stitch, jump, trim, stop, color, needle, end, and
``block`` for a VP3 colour block's start (a header position, not a record).  A PEC/PES
trim-flagged jump is one record (``trim`` carrying the move); JEF's 3 zero-length jumps and
DST's 3 jumps netting to zero are one ``trim``; pyembroidery's reading of the PEC lead-in
move (pystitch writes one from the design's corner and its own reader skips it) is dropped.
"""
from __future__ import annotations

import importlib
import io
from dataclasses import dataclass

RAW = {"trim_at": None, "trim_distance": None, "clipping": False}
LIBRARIES = ("pystitch", "pyembroidery")


@dataclass(frozen=True)
class Record:
    kind: str
    x: int
    y: int
    dx: int
    dy: int
    needle: int = 0


def read(data: bytes, fmt: str, library: str):
    """The library's reader on ``data``, keeping the file's own records."""
    lib = importlib.import_module(library)
    reader = importlib.import_module(f"{library}.{fmt.capitalize()}Reader")
    return lib, lib.EmbPattern.read_embroidery(reader, io.BytesIO(data), dict(RAW))


def _raw(lib, pattern):
    names = {lib.STITCH: "stitch", lib.JUMP: "jump", lib.TRIM: "trim", lib.STOP: "stop",
             lib.COLOR_CHANGE: "color", lib.NEEDLE_SET: "needle", lib.END: "end"}
    out = []
    for x, y, c in pattern.stitches:
        needle = lib.decode_embroidery_command(c)[2] if c & lib.COMMAND_MASK == lib.NEEDLE_SET else 0
        out.append((names.get(c & lib.COMMAND_MASK, "other"), int(round(x)), int(round(y)), needle))
    return out


def file_records(data: bytes, fmt: str, library: str) -> list[Record]:
    """The file's records as ``library`` reads them, grouped by the format's conventions."""
    lib, pattern = read(data, fmt, library)
    raw = _raw(lib, pattern)
    if library == "pyembroidery" and fmt in ("pec", "pes") and raw and raw[0][0] == "jump":
        x0, y0 = raw[0][1], raw[0][2]  # the lead-in move pystitch's reader skips: drop it, same frame
        raw = [(k, x - x0, y - y0, n) for k, x, y, n in raw[1:]]
    out: list[Record] = []
    x = y = 0
    i = 0
    while i < len(raw):
        kind, nx, ny, needle = raw[i]
        if fmt == "dst" and kind == "jump":
            run = [r for r in raw[i:i + 3] if r[0] == "jump"]
            if len(run) == 3 and (run[2][1], run[2][2]) == (x, y) and _all_jumps(raw, i, 3):
                out.append(Record("trim", x, y, 0, 0))
                i += 3
                continue
        if fmt == "jef" and kind in ("jump", "trim") and (nx, ny) == (x, y):
            j = i
            while j < len(raw) and raw[j][0] in ("jump", "trim") and (raw[j][1], raw[j][2]) == (x, y):
                j += 1
            if j - i == 3:
                out.append(Record("trim", x, y, 0, 0))
                i = j
                continue
        if fmt in ("pec", "pes") and kind == "trim" and i + 1 < len(raw) and raw[i + 1][0] == "jump":
            nx, ny = raw[i + 1][1], raw[i + 1][2]
            out.append(Record("trim", nx, ny, nx - x, ny - y))
            x, y = nx, ny
            i += 2
            continue
        if fmt == "vp3" and kind == "jump" and out and out[-1].kind == "color":
            kind = "block"
        out.append(Record(kind, nx, ny, nx - x, ny - y, needle))
        x, y = nx, ny
        i += 1
    return out


def _all_jumps(raw, i, n) -> bool:
    return all(r[0] == "jump" for r in raw[i:i + n])


STOP_SHARED = {"dst", "exp"}  # the colour-change code is the stop


def counts(records: list[Record], fmt: str) -> dict:
    """Every count embroact reports, from the grouped records."""
    kinds = [r.kind for r in records]
    runs = sum(1 for i, k in enumerate(kinds) if k == "trim" and (i == 0 or kinds[i - 1] != "trim"))
    colour_is_stop = fmt in STOP_SHARED
    return {
        "stitches": kinds.count("stitch"),
        "jumps": kinds.count("jump"),
        "trims": runs,
        "stops": kinds.count("stop") + (kinds.count("color") if colour_is_stop else 0),
        "color_changes": (0 if colour_is_stop else kinds.count("color")) + kinds.count("needle"),
    }


def over_limit(records: list[Record], stitch_units: int, jump_units: int) -> list[tuple[int, Record]]:
    """Records moving the frame further than the format allows (per axis)."""
    bad = []
    for n, r in enumerate(records):
        lim = stitch_units if r.kind == "stitch" else jump_units if r.kind in ("jump", "trim") else None
        if lim is not None and max(abs(r.dx), abs(r.dy)) > lim:
            bad.append((n, r))
    return bad
