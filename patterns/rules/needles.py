"""Rules on needle points and stitches (EA1xx).

Conventions
-----------
* Stitch length: displacement of a STITCH record from the previous record; the
  *minimum* is checked only between two consecutive STITCH records (a stitch after
  a stop, jump or trim is the first penetration, not a thread length).
* Per-record limit (EA102): judged on the machine's 0.1 mm grid, exactly as the
  writer encodes the record (:func:`embroact.patterns.limits.records_needed`).
* Needle density (EA105/EA106) counts, as Ink/Stitch's density map does, every
  needle point within ``density_radius_mm`` (``<=``) **including the point itself**.
* The tube extends ``end_margin_mm`` beyond each end of its path along the end
  tangent (connector room); needle points there pierce it too (EA101).
* A placement line (:mod:`embroact.patterns.placement`) is sewn along the tube axis
  before the tube is laid: EA101 does not count its needle points in their own tube's
  corridor (they are checked against every other tube).

Examples
--------
>>> from embroact.patterns.rules.needles import NEEDLE_RULES
>>> [r.code for r in NEEDLE_RULES]
['EA101', 'EA102', 'EA103', 'EA104', 'EA105', 'EA106']
"""
from __future__ import annotations

import numpy as np

from ..base.findings import RULES, Inputs, Severity
from ..limits import UNITS_PER_MM, format_limit, framed_first, records_needed
from ..plan import Command
from .engine import Hits, Subject

__all__ = ["NEEDLE_RULES"]

_DF = Inputs.DESIGNS | Inputs.FILES


@RULES.rule("EA101", Severity.ERROR, "needle in tube corridor",
            "A needle point lies closer to the tube axis than r_f + clearance (the tube extended by its "
            "end margins included): the needle would pierce the tube. A placement line, sewn along the axis "
            "before its tube is laid, pierces nothing.",
            "Widen the pattern or move the needle point out of the corridor.", _DF)
def needle_corridor(s: Subject) -> Hits:
    tubes = s.layout.tubes
    tol = s.settings.tolerances.length_mm
    point, tube, dist = s.laid_tubes.within(s.layout.xy_mm[s.needles], [t.corridor_radius_mm - tol for t in tubes])
    record = s.needles[point]
    there = ~(s.layout.before_tube[record] & (s.layout.owner[record] == tube))  # a placement line: no tube yet
    record, tube, dist = record[there], tube[there], dist[there]

    def message(j: int) -> str:
        t = tubes[tube[j]]
        return (f"needle point {dist[j]:.2f} mm from the tube axis of {t.name}, inside its "
                f"{t.corridor_radius_mm:.2f} mm corridor (r_f {t.outer_radius_mm:g} + clearance {t.clearance_mm:g})")

    return Hits(record, message)


@RULES.rule("EA102", Severity.ERROR, "record over format limit",
            "A stitch moves further per axis (|dx| or |dy|, on the 0.1 mm machine grid the writer rounds to) "
            "than the target format allows in one record (DST 12.1 mm, EXP/JEF/U01/TBF 12.7 mm, ...); the "
            "writer would have to split it.",
            "Narrow the pattern, choose a format with longer records, or split the leg explicitly.", _DF,
            per_format=True)
def record_limit(s: Subject) -> Hits:
    lim = format_limit(s.settings.format)
    moves = s.moves_units
    stitch = (s.layout.commands == Command.STITCH) & ~framed_first(s.layout.commands)  # that one is travel
    over = np.flatnonzero(stitch & (records_needed(moves, lim.max_record_mm) > 1))

    def message(j: int) -> str:
        dx, dy = np.abs(moves[over[j]]) / UNITS_PER_MM
        return (f"stitch moves |dx| {dx:.2f} mm, |dy| {dy:.2f} mm on the machine grid; {lim.name.upper()} allows "
                f"{lim.max_record_mm:g} mm per axis in one record")

    return Hits(over, message)


@RULES.rule("EA103", Severity.ERROR, "stitch over machine maximum",
            "A stitch is longer than the machine's maximum stitch length (machine.max_stitch_mm).",
            "Narrow the pattern or raise machine.max_stitch_mm if the machine allows it.", _DF)
def machine_max(s: Subject) -> Hits:
    length = s.stitch_lengths_mm
    over = (s.layout.commands == Command.STITCH) & (length > s.settings.max_stitch_mm + s.settings.tolerances.length_mm)
    over[:1] = False
    idx = np.flatnonzero(over)
    return Hits(idx, lambda j: f"stitch {length[idx[j]]:.2f} mm long, machine maximum {s.settings.max_stitch_mm:g} mm")


@RULES.rule("EA104", Severity.WARNING, "stitch too short",
            "Two consecutive needle points are closer than the machine's minimum stitch "
            "(machine.min_stitch_mm): the thread breaks or the needle hits its own hole.",
            "Increase the stitch interval or the tie-stitch length.", _DF)
def too_short(s: Subject) -> Hits:
    length = s.stitch_lengths_mm
    idx = np.flatnonzero(s.consecutive & (length < s.settings.min_stitch_mm - s.settings.tolerances.length_mm))
    return Hits(idx, lambda j: f"stitch {length[idx[j]]:.2f} mm long, machine minimum {s.settings.min_stitch_mm:g} mm")


def _density(s: Subject, error: bool) -> Hits:
    count, cfg = s.density, s.settings
    is_error = count >= cfg.density_error_count
    hit = np.flatnonzero(is_error if error else (count >= cfg.density_warning_count) & ~is_error)
    limit = (cfg.density_error_count if error else cfg.density_warning_count) - 1
    return Hits(s.needles[hit], lambda j: f"{count[hit[j]]} needle points within {cfg.density_radius_mm:g} mm "
                                          f"(this one included); limit {limit}")


@RULES.rule("EA105", Severity.WARNING, "needle points dense",
            "A needle point has 3 or more needle points within 0.5 mm, counted as Ink/Stitch's density "
            "map does (the point itself included, distance <= 0.5 mm): the fabric is perforated.",
            "Increase the stitch interval or spread the passes.", _DF)
def density_warning(s: Subject) -> Hits:
    return _density(s, error=False)


@RULES.rule("EA106", Severity.ERROR, "needle points too dense",
            "A needle point has 6 or more needle points within 0.5 mm (Ink/Stitch's red density level): "
            "the fabric tears along the rail.",
            "Increase the stitch interval or reduce the number of passes.", _DF)
def density_error(s: Subject) -> Hits:
    return _density(s, error=True)


NEEDLE_RULES = (needle_corridor, record_limit, machine_max, too_short, density_warning, density_error)
"""The EA1xx rules, in code order."""
