"""Rules on the stitch pattern as generated (EA203-EA205, EA207).

EA203 reads where the legs cross the tube (designs and files); EA204, EA205 and
EA207 compare the realised pattern with the request, which only a design has. The
sleeve rules of the same group (EA201, EA202, EA206) are physics and live in
:mod:`embroact.predict.sleeve_rules`.

Examples
--------
>>> from embroact.patterns.rules.pattern import PATTERN_RULES
>>> [(r.code, r.inputs_label) for r in PATTERN_RULES]
[('EA203', 'designs, files'), ('EA204', 'designs'), ('EA205', 'designs'), ('EA207', 'designs')]
"""
from __future__ import annotations

import numpy as np

from ..base.findings import RULES, Finding, Inputs, Severity
from ..kinds import pattern_kind
from .engine import Hits, Subject

__all__ = ["PATTERN_RULES"]


@RULES.rule("EA203", Severity.WARNING, "stitch interval over tube diameter",
            "Neighbouring legs cross the tube further apart than its diameter 2 r_f: the tube bulges between "
            "legs, which the model does not describe. The transition the generator leaves between two segments "
            "of a segmented actuator is not reported (the model counts it as unbent tube): in a design where its "
            "plan puts it; in a file, a gap across which the legs change (the extents across or along the tube of "
            "the legs on its two sides lie more than 1.5 grid units apart: one segment's pattern ends, another's "
            "begins).",
            "Decrease the stitch interval.", Inputs.DESIGNS | Inputs.FILES)
def interval(s: Subject) -> Hits:
    """Gaps between neighbouring crossings of a tube by the legs it owns, larger than 2 r_f, except the gap across
    a transition between two segments (a design's, :func:`_transitions`; a file's, :func:`_pattern_changes`)."""
    c, owner, legs = s.crossings, s.layout.owner, s.legs
    end = legs[c.leg]
    mine = (owner[end] == c.tube) & (owner[end - 1] == c.tube)
    tube, s_mm, end, along = c.tube[mine], c.s_mm[mine], end[mine], c.along_mm[mine]
    order = np.lexsort((s_mm, tube))  # by tube, then along it
    tube, s_mm, end, along = tube[order], s_mm[order], end[order], along[order]
    same = tube[1:] == tube[:-1]
    gaps = np.diff(s_mm)
    limit = 2.0 * np.array([t.outer_radius_mm for t in s.layout.tubes])[tube[1:]] if len(tube) else np.zeros(0)
    bad = np.flatnonzero(same & (gaps > limit + s.settings.tolerances.length_mm))
    if s.plan is not None and len(bad):
        mids = _transitions(s.plan)
        made = [any(s_mm[g] < m < s_mm[g + 1] for m in mids.get(int(tube[g + 1]), ())) for g in bad]
        bad = bad[~np.asarray(made, dtype=bool)]
    elif len(bad):
        leg = s.layout.xy_mm[end] - s.layout.xy_mm[end - 1]
        across = np.sqrt(np.maximum(np.sum(leg**2, axis=1) - along**2, 0.0))
        bad = bad[~_pattern_changes(tube, np.column_stack([across, along]), bad, s.settings.tolerances.machine_grid_mm)]
    bad = bad[np.argsort(end[bad + 1], kind="stable")]

    def message(j: int) -> str:
        g = bad[j]
        return (f"legs cross the tube of {s.layout.tubes[tube[g + 1]].name} {gaps[g]:.2f} mm apart along its axis, "
                f"more than the tube diameter {limit[g]:g} mm")

    return Hits(end[bad + 1], message)


#: Crossing legs on each side of a gap that stand for the pattern there (a file's transitions).
_SIDE_LEGS = 4


def _pattern_changes(tube: np.ndarray, extent: np.ndarray, gaps: np.ndarray, grid_mm: float) -> np.ndarray:
    """For a file, which has no plan to name its segments: True for each gap (between crossings ``g`` and
    ``g + 1``, sorted by tube then along it) across which the legs change: the ranges of the extents across or
    along the tube (``extent``, (n, 2) [mm]) of up to ``_SIDE_LEGS`` crossing legs on each side lie more than 1.5
    grid units apart (the rounding of the needle points spreads each side by up to two units, so a gap inside
    a pattern, or with legs of both patterns on one side, is no change). One segment's pattern ends there and the
    next one's begins, as at the transition the generator leaves between two segments.

    >>> extent = np.array([[7.0, 3.4], [7.0, 3.6]] * 4 + [[7.0, 7.0]] * 4)  # gaps in a zigzag; where a cross begins
    >>> _pattern_changes(np.zeros(12, dtype=np.int64), extent, np.array([3, 5, 7]), 0.1).tolist()
    [False, False, True]
    """
    out = np.zeros(len(gaps), dtype=bool)
    for k, g in enumerate(gaps):
        before = extent[[i for i in range(max(g - _SIDE_LEGS + 1, 0), g + 1) if tube[i] == tube[g]]]
        after = extent[[i for i in range(g + 1, min(g + 1 + _SIDE_LEGS, len(tube))) if tube[i] == tube[g]]]
        apart = np.maximum(after.min(axis=0) - before.max(axis=0), before.min(axis=0) - after.max(axis=0))
        out[k] = bool(np.any(apart > 1.5 * grid_mm))
    return out


def _transitions(plan) -> dict[int, tuple[float, ...]]:
    """Per plan actuator (the layout's tube of the same index), the middle of each transition between two of its
    segments, as arc length along its path [mm]: the generator's run from one segment's last leg to the next one's
    first (:attr:`~embroact.patterns.segments.SegmentPlan.transition_mm`)."""
    out = {}
    for k, act in enumerate(plan.actuators):
        segs = act.segments
        out[k] = tuple(0.5 * (a.first_leg_mm + a.realised.length_mm + b.first_leg_mm) for a, b in zip(segs, segs[1:]))
    return out


@RULES.rule("EA204", Severity.WARNING, "leg angle off request",
            "The realised cross-pattern leg angle differs from the requested alpha0 by more than the angle "
            "tolerance (patterns/base/tolerances.py).",
            "Adjust the interval or length so that angle and spacing fit, or accept the realised angle.",
            Inputs.DESIGNS)
def angle_off(s: Subject) -> list[Finding]:
    tol = s.settings.tolerances.angle_deg

    def message(act, req, real):
        kind = pattern_kind(req.pattern)
        if kind.has_angle and abs(real.angle_deg - kind.angle_deg(req)) > tol:
            return (f"leg angle {real.angle_deg:.2f} deg realised, {kind.angle_deg(req):g} deg requested "
                    f"(tolerance {tol:g} deg)")
        return None
    return s.pattern_findings("EA204", message)


@RULES.rule("EA205", Severity.WARNING, "stitch interval off request",
            "The realised stitch interval differs from the request by more than the relative spacing "
            "tolerance (patterns/base/tolerances.py) plus half the machine grid the needle points lie on.",
            "Adjust the length or the interval so that a whole number of legs fits.", Inputs.DESIGNS)
def interval_off(s: Subject) -> list[Finding]:
    tol = s.settings.tolerances.spacing_rel
    grid = s.settings.tolerances.machine_grid_mm

    def message(act, req, real):
        rel = abs(real.interval_mm - req.interval_mm) / req.interval_mm
        if abs(real.interval_mm - req.interval_mm) > tol * req.interval_mm + grid / 2.0:
            return (f"stitch interval {real.interval_mm:.3f} mm realised, {req.interval_mm:g} mm "
                    f"requested ({rel * 100:.1f} % off, tolerance {tol * 100:g} % + {grid / 2.0:g} mm of the "
                    f"machine grid)")
        return None
    return s.pattern_findings("EA205", message)


@RULES.rule("EA207", Severity.WARNING, "width off request",
            "The realised width (its rails' needle points on the machine grid) differs from the requested one by "
            "more than half a grid unit: the rails rounded to the grid away from each other or towards each other "
            "(a straight path along a grid line keeps both rails on it; a curved or slanted one may not).",
            "Lay the path along a grid line, or ask for the width that is sewn (its sleeve and model follow it).",
            Inputs.DESIGNS)
def width_off(s: Subject) -> list[Finding]:
    half = s.settings.tolerances.machine_grid_mm / 2.0

    def message(act, req, real):
        if abs(real.width_mm - req.width_mm) > half + 1e-9:
            return (f"width {real.width_mm:.2f} mm realised, {req.width_mm:g} mm requested (tolerance half the "
                    f"{2.0 * half:g} mm machine grid)")
        return None
    return s.pattern_findings("EA207", message)


PATTERN_RULES = (interval, angle_off, interval_off, width_off)
"""The EA2xx rules of patterns, in code order."""
