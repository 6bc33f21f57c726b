"""Rules on the machine file's record structure (EA5xx): trims by accident, stops, record count.

Machine records are counted as the writer makes them: a jump longer than the
format's jump limit becomes several records (:func:`embroact.patterns.limits.records_needed`
on the 0.1 mm grid), and a trim in a format that writes trims as jumps (DST)
becomes ``trim_jump_count`` of them.

Examples
--------
>>> from embroact.patterns.rules.machine import MACHINE_RULES
>>> [r.code for r in MACHINE_RULES]
['EA501', 'EA502', 'EA503', 'EA504', 'EA505']

EA505 holds a file's header against its records: the file check reads the header when it
reads the file (:attr:`embroact.patterns.rules.layout.Layout.header_faults`).
"""
from __future__ import annotations

import numpy as np

from ..base.findings import RULES, Finding, Inputs, Severity
from ..limits import format_limit, records_needed
from ..plan import Command
from .engine import Hits, Subject

__all__ = ["MACHINE_RULES", "machine_records"]

_DF = Inputs.DESIGNS | Inputs.FILES


def machine_records(s: Subject) -> np.ndarray:
    """Machine records each layout record becomes (jumps split at the format's jump limit).

    Parameters
    ----------
    s : Subject
        The check; its settings name the format.

    Returns
    -------
    numpy.ndarray of int64, shape (n,)
        1 per record, more for a long jump, ``trim_jump_count`` for a trim the format writes as jumps.

    Examples
    --------
    >>> from embroact.patterns.rules import Layout, RuleSettings
    >>> lay = Layout.from_points([(0, 0), (30, 0), (30, 0)], [0, 1, 2], [-1, -1, -1], tubes=())
    >>> machine_records(Subject(lay, RuleSettings(format="dst"))).tolist()
    [1, 3, 3]
    """

    def count() -> np.ndarray:
        lim = format_limit(s.settings.format)
        cmds = s.layout.commands
        n = np.ones(len(cmds), dtype=np.int64)
        jump = cmds == Command.JUMP
        n[jump] = records_needed(s.moves_units[jump], lim.max_jump_mm)
        if lim.trim_as_jumps:
            n[cmds == Command.TRIM] = s.settings.trim_jump_count
        return n

    return s.shared("machine records", count)


@RULES.rule("EA501", Severity.WARNING, "jump run reads as trim",
            "Three or more consecutive jump records (the machine's trim count) where no trim is meant: the "
            "machine cuts the thread.",
            "Shorten the travel, add a real trim, or lay actuators closer.", _DF, per_format=True)
def jump_runs(s: Subject) -> Hits:
    cmds, tol = s.layout.commands, s.settings.tolerances.length_mm
    jump = cmds == Command.JUMP
    edges = np.diff(np.concatenate([[0], jump.astype(np.int8), [0]]))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    records = np.concatenate([[0], np.cumsum(machine_records(s))])
    d = s.displacements_mm
    hits, counts = [], []
    for a, b in zip(starts, stops):
        if a == 0 or cmds[a - 1] != Command.STITCH:
            continue  # after a trim, stop or at the start a trim does no harm
        n = int(records[b] - records[a])
        if n < s.settings.trim_jump_count:
            continue
        net = np.cumsum(d[a:b], axis=0)
        if np.any(np.all(np.abs(net[1:]) <= tol, axis=1)):
            continue  # the run starts with jumps that net to zero: a trim written as jumps
        hits.append(a)
        counts.append(n)
    return Hits(np.array(hits, dtype=np.int64), lambda j: (
        f"{counts[j]} consecutive jump records after a stitch; the machine cuts the thread after "
        f"{s.settings.trim_jump_count}"))


def _owned_moves(s: Subject) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Consecutive needle records that lay thread (a, b), and the stops between them.

    Needle records that do not move (a zero-length stitch, e.g. the needle-down some
    writers put at a colour change) lay no thread across a tube and are ignored.
    """
    lay = s.layout
    moves = s.stitch_lengths_mm > s.settings.tolerances.length_mm
    moves[:1] = True
    owned = np.flatnonzero((lay.commands == Command.STITCH) & (lay.owner >= 0) & moves)
    stops_before = np.cumsum(lay.commands == Command.STOP)
    a, b = owned[:-1], owned[1:]
    return a, b, stops_before[b] - stops_before[a]


@RULES.rule("EA502", Severity.ERROR, "missing stop",
            "Sewing moves from one tube to another without a stop: the operator never gets to lay the tube.",
            "Insert a stop (colour change in DST) before each actuator.", _DF)
def missing_stop(s: Subject) -> Hits:
    a, b, between = _owned_moves(s)
    lay = s.layout
    bad = (lay.owner[a] != lay.owner[b]) & (between == 0) & ~lay.before_tube[b]  # a placement line's stop follows it
    j, i = a[bad], b[bad]
    return Hits(i, lambda k: (f"sewing moves from {lay.name_of(int(lay.owner[j[k]]))} to "
                              f"{lay.name_of(int(lay.owner[i[k]]))} without a stop"))


@RULES.rule("EA503", Severity.WARNING, "unexpected stop",
            "A stop or colour change falls inside one actuator's stitches.",
            "Remove the stop, or split the actuator.", _DF)
def unexpected_stop(s: Subject) -> Hits:
    a, b, between = _owned_moves(s)
    lay = s.layout
    j = a[(lay.owner[a] == lay.owner[b]) & (between > 0) & ~lay.before_tube[a]]  # after a placement line: cord in
    stop_idx = np.flatnonzero(lay.commands == Command.STOP)
    at = stop_idx[np.searchsorted(stop_idx, j)] if len(j) else np.zeros(0, np.int64)
    owner = lay.owner[j]
    return Hits(at, lambda k: f"stop / colour change inside the stitches of {lay.name_of(int(owner[k]))}", owner=owner)


@RULES.rule("EA504", Severity.ERROR, "too many records",
            "The number of records exceeds the format's (or the machine's) limit.",
            "Split the design into several files.", _DF, per_format=True)
def record_count(s: Subject) -> list[Finding]:
    limit = s.settings.max_records or format_limit(s.settings.format).max_records
    n = int(machine_records(s).sum())
    if n <= limit:
        return []
    return [RULES.finding("EA504", f"{n} machine records, limit {limit} ({s.settings.format.upper()})")]


@RULES.rule("EA505", Severity.WARNING, "header disagrees with the records",
            "A field of an embroidery file's header (DST: ST the 3-byte records, end record included; CO the "
            "colour-change records; DST and TBF: +X -X +Y -Y the largest excursion from the start point each "
            "way, 0.1 mm, y up) does not match the records that follow it. Machines that read the header may refuse the "
            "file or judge its size wrongly (pystitch and pyembroidery count a trim as one record in ST and "
            "write the extents from signed, y-down bounds). One finding per field.",
            "Rewrite the header from the records (save the file again from the digitising software).",
            Inputs.FILES)
def header(s: Subject) -> list[Finding]:
    return [RULES.finding("EA505", fault) for fault in s.layout.header_faults]


MACHINE_RULES = (jump_runs, missing_stop, unexpected_stop, record_count, header)
"""The EA5xx rules, in code order."""
