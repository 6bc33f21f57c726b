"""The sleeve rules (EA201, EA202, EA206) and the geometric checks of designs and files with them.

These rules judge the sleeve the thread makes around the tube (docs/model.md), so
they live with the model's geometry (:mod:`embroact.predict.sleeve`) rather than
in :mod:`embroact.patterns`, which knows no physics. They are declared in the same
registry and run by the same engine as the geometric rules:

* :func:`check_without_model`: every geometric, pattern, file-structure and sleeve rule on a
  design's plan, no model (``embroact.predict.rules.check_design``, the one rule gate of every command, adds the model rules);
* :func:`check_layout`: the same rules for embroidery files (layouts from their records).

Examples
--------
>>> from embroact.patterns.design import build_plan, default_design
>>> from embroact.patterns.rules import RuleSettings
>>> from embroact.predict.sleeve_rules import DESIGN_RULES, check_without_model
>>> [r.code for r in DESIGN_RULES][:8]
['EA101', 'EA102', 'EA103', 'EA104', 'EA105', 'EA106', 'EA201', 'EA202']
>>> check_without_model(build_plan(default_design()), RuleSettings(hoop_width_mm=200.0, hoop_height_mm=200.0))
()
"""
from __future__ import annotations

from ..patterns.base.findings import RULES, Finding, Inputs, Severity
from ..patterns.plan import StitchPlan
from ..patterns.segments import pattern_parts
from ..patterns import rules as geometry
from ..patterns.rules import GEOMETRY_RULES, Layout, RuleSettings
from ..patterns.rules.engine import Subject
from .kinds import model_kind
from .sleeve import min_sleeve_width_mm, neutral_angle_deg, sleeve_radius_mm

__all__ = ["SLEEVE_RULES", "DESIGN_RULES", "check_without_model", "check_layout"]


def _sleeve_gaps(s: Subject) -> list[tuple[int, str, float, float, float, object]]:
    """Per tube with a known width, per pattern part: tube index, message prefix, width w, sleeve radius r0,
    r0 - r_f [mm] and where to place a finding (None: the tube's first needle point).

    A design's actuator is checked segment by segment at each segment's realised width (the first
    segment placed at the tube's first needle point, each later one where its legs start); a
    file's tube at the width read from its needle points.
    """
    out = []
    for k, tube in enumerate(s.layout.tubes):
        act = s.plan.actuators[k] if s.plan is not None and k < len(s.plan.actuators) else None
        parts: list[tuple[str, float, object]]
        if act is not None:
            parts = [(label, real.width_mm, act.centerline.point_at(seg.first_leg_mm) if j else None)
                     for j, ((label, _, real), seg) in enumerate(zip(pattern_parts(act), act.segments))]
        elif tube.half_width_mm is not None:
            parts = [("", 2.0 * tube.half_width_mm, None)]
        else:
            continue
        for label, w, xy in parts:
            r0 = float(sleeve_radius_mm(w, tube.outer_radius_mm))
            out.append((k, label, w, r0, r0 - tube.outer_radius_mm, xy))
    return out


def _gap_findings(s: Subject, code: str, flagged, message) -> list[Finding]:
    """Findings ``code`` on the sleeves of :func:`_sleeve_gaps` whose ``flagged(gap)`` holds.

    The text is the part's label then ``message(w, r0, rf, gap)`` (width, sleeve radius, tube
    radius, r0 - rf, all mm); each finding sits where its part starts.
    """
    out = []
    for k, label, w, r0, gap, xy in _sleeve_gaps(s):
        if flagged(gap):
            out.append(s.tube_finding(k, code, label + message(w, r0, s.layout.tubes[k].outer_radius_mm, gap), xy))
    return out


@RULES.rule("EA201", Severity.ERROR, "no sleeve",
            "The realised width leaves no sleeve: r0 <= r_f, i.e. w <= (pi^2 - 4)/pi * r_f (docs/model.md); "
            "the thread squeezes the tube before any pressure and the model has no inflation phase.",
            "Increase the width.", Inputs.DESIGNS | Inputs.FILES)
def no_sleeve(s: Subject) -> list[Finding]:
    return _gap_findings(s, "EA201", lambda gap: gap <= 0.0, lambda w, r0, rf, gap: (
        f"width {w:.2f} mm gives sleeve radius r0 {r0:.3f} mm <= tube radius r_f {rf:g} mm "
        f"(needs w > {float(min_sleeve_width_mm(rf)):.2f} mm)"))


@RULES.rule("EA202", Severity.WARNING, "sleeve barely wider than the tube",
            "The sleeve radius r0 exceeds r_f by less than min_sleeve_gap_mm: P0 is tiny and very sensitive "
            "to the width.",
            "Increase the width.", Inputs.DESIGNS | Inputs.FILES)
def tight_sleeve(s: Subject) -> list[Finding]:
    least = s.settings.min_sleeve_gap_mm
    return _gap_findings(s, "EA202", lambda gap: 0.0 < gap < least, lambda w, r0, rf, gap: (
        f"sleeve radius r0 {r0:.3f} mm exceeds r_f {rf:g} mm by only {gap:.3f} mm (< {least:g} mm)"))


@RULES.rule("EA206", Severity.WARNING, "angle near neutral",
            "The cross-pattern angle alpha0 lies within neutral_band_deg of the neutral angle "
            "(tan beta0 = 1/2): the bending direction is ill-conditioned.",
            "Move alpha0 away from the neutral angle.", Inputs.DESIGNS)
def near_neutral(s: Subject) -> list[Finding]:
    band = s.settings.neutral_band_deg

    def message(act, req, real):
        if not model_kind(req.pattern).has_thread_angle:  # no thread angle, no neutral one
            return None
        neutral = float(neutral_angle_deg(real.width_mm, act.tube.outer_radius_mm))
        if abs(real.angle_deg - neutral) < band:
            return (f"angle {real.angle_deg:.2f} deg is {abs(real.angle_deg - neutral):.2f} deg from "
                    f"the neutral angle {neutral:.2f} deg (band {band:g} deg)")
        return None
    return s.pattern_findings("EA206", message)


SLEEVE_RULES = (no_sleeve, tight_sleeve, near_neutral)
"""The sleeve rules, in code order."""

DESIGN_RULES = tuple(sorted(GEOMETRY_RULES + SLEEVE_RULES, key=lambda r: r.code))
"""Every rule checked on a plan or layout (all but the model rules), in code order."""


def check_without_model(plan: StitchPlan, settings: RuleSettings | None = None, *, rules=DESIGN_RULES):
    """Every geometric, pattern, file-structure and sleeve rule (or those of ``rules``) on a design's plan;
    findings worst first.

    Parameters
    ----------
    plan : StitchPlan
        A design's plan.
    settings : RuleSettings or None, optional
        Thresholds; None: the defaults.
    rules : iterable of Rule, optional
        The rules to run.

    Returns
    -------
    tuple of Finding

    Examples
    --------
    >>> from embroact.patterns.design import build_plan, default_design
    >>> check_without_model(build_plan(default_design()))
    ()
    """
    return geometry.check_geometry(plan, settings, rules=rules)


def check_layout(layout: Layout, settings: RuleSettings | None = None):
    """The same rules for an embroidery file's layout (rules for designs only are skipped).

    Parameters
    ----------
    layout : Layout
        An embroidery file's records and tubes.
    settings : RuleSettings or None, optional
        Thresholds; None: the defaults.

    Returns
    -------
    tuple of Finding

    Examples
    --------
    >>> from embroact.patterns.rules import TubeLayout
    >>> tube = TubeLayout.from_path("A", [(0, 0), (8, 0)], outer_radius_mm=1.5, clearance_mm=0.3, end_margin_mm=0.0,
    ...                             half_width_mm=1.6)
    >>> sorted({f.code for f in check_layout(Layout.from_points([(2, 1.6), (3, -1.6)], [0, 0], [0, 0], tubes=(tube,)))})
    ['EA101', 'EA202']
    """
    return geometry.check_layout(layout, settings, rules=DESIGN_RULES)
