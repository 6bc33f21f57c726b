"""A small, independent Tajima DST decoder for the tests.

Written from the published description of the ternary record format
(achatina.de "DST (Tajima) design format"; KDE Liberty wiki "Tajima Ternary"),
not from pystitch's reader or embroact's own header code:

* 512-byte ASCII header of ``KEY:value`` fields ending with CR, then 0x1A and
  space padding.
* 3-byte records.  Bit 7 .. bit 0 of each byte mean::

      byte 1:  y+1  y-1  y+9   y-9   x-9   x+9   x-1  x+1
      byte 2:  y+3  y-3  y+27  y-27  x-27  x+27  x-3  x+3
      byte 3:  jump stop y+81  y-81  x-81  x+81  set  set

  (``stop`` is the colour-change bit; byte 3 = 0xC3 is a colour change / stop,
  0xF3 the end of the design.)  y points up (machine frame), units 0.1 mm.
* A trim is a run of jumps that nets to zero (3 by default).
"""
from __future__ import annotations

from dataclasses import dataclass

HEADER_BYTES = 512

_BITS = (
    ("y+1", "y-1", "y+9", "y-9", "x-9", "x+9", "x-1", "x+1"),
    ("y+3", "y-3", "y+27", "y-27", "x-27", "x+27", "x-3", "x+3"),
    ("jump", "stop", "y+81", "y-81", "x-81", "x+81", "set", "set"),
)


@dataclass(frozen=True)
class Record:
    kind: str  # "stitch", "jump", "stop", "end"
    dx: int
    dy: int
    x: int  # absolute, after the move
    y: int


@dataclass(frozen=True)
class Dst:
    header: dict
    records: list
    trailing: bytes  # bytes after the end record


def _record(b: bytes) -> tuple[str, int, int]:
    flags = set()
    dx = dy = 0
    for byte, names in zip(b, _BITS):
        for bit, name in zip(range(7, -1, -1), names):
            if not (byte >> bit) & 1:
                continue
            if name[0] in "xy":
                value = int(name[1:])
                if name[0] == "x":
                    dx += value
                else:
                    dy += value
            else:
                flags.add(name)
    if b[2] & 0b11 != 0b11:
        raise ValueError(f"record {b.hex()} does not have both low bits of byte 3 set")
    if flags >= {"jump", "stop"}:
        if b[2] == 0xF3:
            return "end", 0, 0
        if b[2] == 0xC3:
            return "stop", 0, 0
        raise ValueError(f"record {b.hex()}: jump and stop bits with a move")
    return ("jump" if "jump" in flags else "stitch"), dx, dy


def parse_header(head: bytes) -> dict:
    if len(head) != HEADER_BYTES:
        raise ValueError("header must be 512 bytes")
    text, sub, pad = head.partition(b"\x1a")
    if not sub or pad.strip(b" "):
        raise ValueError("header must end with 0x1A and space padding")
    fields = {}
    for line in text.decode("ascii").split("\r"):
        if line:
            key, _, value = line.partition(":")
            fields[key] = value
    return fields


def decode(data: bytes) -> Dst:
    header = parse_header(data[:HEADER_BYTES])
    body = data[HEADER_BYTES:]
    records = []
    x = y = 0
    pos = 0
    while pos + 3 <= len(body):
        kind, dx, dy = _record(body[pos : pos + 3])
        pos += 3
        x, y = x + dx, y + dy
        records.append(Record(kind, dx, dy, x, y))
        if kind == "end":
            break
    else:
        raise ValueError("no end record")
    return Dst(header, records, body[pos:])


def events(records: list, trim_run: int = 3) -> list:
    """Group records: ('stitch', x, y), ('travel', x, y, n_jumps), ('trim',), ('stop',), ('end',).

    A run of exactly ``trim_run`` jumps netting to zero is a trim; any other jump
    run is a travel to its end point.  A trim followed by travel jumps is split
    into the trim and the travel.
    """
    out = []
    i = 0
    while i < len(records):
        r = records[i]
        if r.kind != "jump":
            out.append((r.kind, r.x, r.y) if r.kind == "stitch" else (r.kind,))
            i += 1
            continue
        j = i
        while j < len(records) and records[j].kind == "jump":
            j += 1
        run = records[i:j]
        if len(run) >= trim_run and sum(q.dx for q in run[:trim_run]) == 0 and sum(q.dy for q in run[:trim_run]) == 0:
            out.append(("trim",))
            run = run[trim_run:]
        if run:
            out.append(("travel", run[-1].x, run[-1].y, len(run)))
        i = j
    return out
