"""DST specifics: a correct 512-byte header and the 0x1A terminator.

pystitch writes the DST records correctly, but its header does not describe them
(docs/machine.md section 4; pyembroidery 1.5.1, which pystitch forks, also left stops out of
``CO``):
``+Y``/``-Y`` are swapped,
``+X``/``-X`` take absolute values of signed bounds, ``ST`` counts a trim as one
record although it is written as three, and no 0x1A follows the end record.
:func:`fix_dst` keeps the records and rewrites the header from them.

Header written (fixed offsets, each field ends with CR)
-------------------------------------------------------
``LA:`` label, printable ASCII, 16 chars; ``ST:`` number of 3-byte records in the
body, the end record included; ``CO:`` number of colour-change/stop records
(0xC3); ``+X:``/``-X:``/``+Y:``/``-Y:`` largest excursion from the start point in
each direction, 0.1 mm, machine frame (y up), over every record's end point;
``AX:``/``AY:`` signed end position relative to the start; ``MX:``/``MY:`` 0 (no
linked previous file); ``PD:******``; then 0x1A and spaces up to 512 bytes.

Examples
--------
>>> body = bytes([0x01, 0x00, 0x03]) + bytes([0x00, 0x00, 0xF3])  # x+1, end
>>> data = fix_dst(bytes(512) + body, label="demo")
>>> data[:23]
b'LA:demo            \\rST:'
>>> header_fields(data)["ST"], header_fields(data)["+X"], data[-1:]
('2', '1', b'\\x1a')
"""
from __future__ import annotations

import numpy as np

from ...patterns.base.errors import ExportError

__all__ = ["HEADER_SIZE", "END_BYTE", "COLOR_BYTE", "decode_moves", "build_header", "fix_dst", "header_fields"]

HEADER_SIZE = 512
END_BYTE = 0xF3
"""Third byte of the end record."""
COLOR_BYTE = 0xC3
"""Third byte of a colour-change / stop record."""
_SUB = b"\x1a"

# (byte, bit) -> (dx, dy) weight, machine frame (y up).
_WEIGHTS = {
    (0, 0): (1, 0), (0, 1): (-1, 0), (0, 2): (9, 0), (0, 3): (-9, 0),
    (0, 4): (0, -9), (0, 5): (0, 9), (0, 6): (0, -1), (0, 7): (0, 1),
    (1, 0): (3, 0), (1, 1): (-3, 0), (1, 2): (27, 0), (1, 3): (-27, 0),
    (1, 4): (0, -27), (1, 5): (0, 27), (1, 6): (0, -3), (1, 7): (0, 3),
    (2, 2): (81, 0), (2, 3): (-81, 0), (2, 4): (0, -81), (2, 5): (0, 81),
}


def move_array(body: bytes) -> tuple[np.ndarray, np.ndarray]:
    """Every record's move ``(n, 2)`` [0.1 mm, y up] and third byte ``(n,)``, up to and including the end
    record (all records of a body without one), decoded at once.

    Parameters
    ----------
    body : bytes
        The records after the header.

    Returns
    -------
    moves : numpy.ndarray of int64 (n, 2)
        [0.1 mm, y up]; 0 for end and colour records.
    byte3 : numpy.ndarray of uint8 (n,)

    Examples
    --------
    >>> moves, b3 = move_array(bytes([0x01, 0x00, 0x03, 0x00, 0x00, 0xF3, 0x01, 0x00, 0x03]))
    >>> moves.tolist(), b3.tolist()
    ([[1, 0], [0, 0]], [3, 243])
    """
    rec = np.frombuffer(body[:len(body) - len(body) % 3], dtype=np.uint8).reshape(-1, 3)
    end = np.flatnonzero(rec[:, 2] == END_BYTE)
    rec = rec[:int(end[0]) + 1] if len(end) else rec
    weights = np.zeros((3, 8, 2), dtype=np.int64)
    for (b, bit), w in _WEIGHTS.items():
        weights[b, bit] = w
    bits = (rec[:, :, None] >> np.arange(8, dtype=np.uint8)) & 1  # (n, byte, bit)
    moves = np.einsum("nbk,bkd->nd", bits.astype(np.int64), weights)
    moves[np.isin(rec[:, 2], (END_BYTE, COLOR_BYTE))] = 0
    return moves, rec[:, 2].copy()


def decode_moves(body: bytes) -> list[tuple[int, int, int]]:
    """``(dx, dy, byte3)`` per record up to and including the end record (0.1 mm, y up).

    Parameters
    ----------
    body : bytes
        The records after the header.

    Returns
    -------
    list of tuple of int

    Examples
    --------
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> from embroact.export.machine.formats import encode
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (1, 1, Command.STITCH, Role.LEG),
    ...                                 (1, 1, Command.END, Role.CONTROL, -1)])
    >>> data, _ = encode(plan, "dst")
    >>> decode_moves(data[HEADER_SIZE:])
    [(0, 0, 3), (10, 10, 3), (0, 0, 243)]
    """
    moves, b3 = move_array(body)
    return [(int(dx), int(dy), int(b)) for (dx, dy), b in zip(moves.tolist(), b3.tolist())]


def build_header(moves: list[tuple[int, int, int]], *, label: str) -> bytes:
    """The 512-byte header describing ``moves`` (see the module docstring).

    Parameters
    ----------
    moves : list of tuple of int
        ``(dx, dy, byte3)`` per record (:func:`decode_moves`).
    label : str
        The design's name (printable ASCII, cut to 16 characters).

    Returns
    -------
    bytes
        ``HEADER_SIZE`` bytes.

    Examples
    --------
    >>> head = build_header([(10, 10, 3), (0, 0, END_BYTE)], label="demo")
    >>> len(head), header_fields(head)["ST"], header_fields(head)["+X"]
    (512, '2', '10')
    """
    x = y = 0
    xmin = xmax = ymin = ymax = 0
    for dx, dy, _ in moves:
        x, y = x + dx, y + dy
        xmin, xmax, ymin, ymax = min(xmin, x), max(xmax, x), min(ymin, y), max(ymax, y)
    colors = sum(1 for *_, b3 in moves if b3 == COLOR_BYTE)
    text = "".join(ch if 32 <= ord(ch) < 127 else "_" for ch in label)[:16]
    fields = [
        f"LA:{text:<16}", f"ST:{len(moves):7d}", f"CO:{colors:3d}",
        f"+X:{xmax:5d}", f"-X:{-xmin:5d}", f"+Y:{ymax:5d}", f"-Y:{-ymin:5d}",
        f"AX:{'+' if x >= 0 else '-'}{abs(x):5d}", f"AY:{'+' if y >= 0 else '-'}{abs(y):5d}",
        f"MX:+{0:5d}", f"MY:+{0:5d}", "PD:******",
    ]
    head = ("\r".join(fields) + "\r").encode("ascii") + _SUB
    return head + b" " * (HEADER_SIZE - len(head))


def fix_dst(data: bytes, *, label: str) -> bytes:
    """Replace the header of a DST file with one built from its records; end with 0x1A.

    Parameters
    ----------
    data : bytes
        A DST file.
    label : str
        The name the header carries.

    Returns
    -------
    bytes

    Raises
    ------
    ExportError
        The body has no end record.

    Examples
    --------
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> from embroact.export.machine.formats import encode
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (1, 1, Command.STITCH, Role.LEG),
    ...                                 (1, 1, Command.END, Role.CONTROL, -1)])
    >>> data, _ = encode(plan, "dst")
    >>> header_fields(fix_dst(data, label="renamed"))["LA"]
    'renamed'
    """
    moves = decode_moves(data[HEADER_SIZE:])
    if not moves or moves[-1][2] != END_BYTE:
        raise ExportError("DST body has no end record")
    body = data[HEADER_SIZE : HEADER_SIZE + 3 * len(moves)]
    return build_header(moves, label=label) + body + _SUB


def header_fields(data: bytes) -> dict[str, str]:
    """Header ``KEY:value`` fields of a DST file, blanks removed from the values.

    Parameters
    ----------
    data : bytes
        A DST file (or its header).

    Returns
    -------
    dict of str to str

    Examples
    --------
    >>> from embroact.patterns.plan import Command, Role, StitchPlan
    >>> from embroact.export.machine.formats import encode
    >>> plan = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (1, 1, Command.STITCH, Role.LEG),
    ...                                 (1, 1, Command.END, Role.CONTROL, -1)])
    >>> data, _ = encode(plan, "dst")
    >>> fields = header_fields(data)
    >>> fields["LA"], fields["ST"], fields["AX"]
    ('embroact', '3', '+10')
    """
    head = data[:HEADER_SIZE].split(_SUB, 1)[0].decode("ascii", "replace")
    return {part[:2]: part[3:].replace(" ", "") for part in head.split("\r") if part[2:3] == ":"}
