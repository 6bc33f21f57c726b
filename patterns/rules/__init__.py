"""Geometric and file-level design rules on stitch plans and sewing layouts (pure functions).

Each rule is declared once, next to its check, in the rule registry
(:data:`embroact.patterns.base.findings.RULES`); the modules here hold them by group:

* :mod:`.needles`: needle points and stitches (EA101-EA106);
* :mod:`.pattern`: the pattern as generated (EA203-EA205);
* :mod:`.tubes`: tube paths and placement, couching (EA301-EA307);
* :mod:`.machine`: the machine file's record structure (EA501-EA504);
* :mod:`.layout` (records and tubes), :mod:`.settings` (thresholds) and
  :mod:`.engine` (one subject per check, capping, sorting).

:func:`check_layout` runs the rules on a layout (an embroidery file's records and
tubes), :func:`check_geometry` on a design's plan. Both take ``rules``: the physics
rules of the sleeve (EA201, EA202, EA206) live in ``embroact.predict.sleeve_rules``,
which passes :data:`GEOMETRY_RULES` plus its own.

Examples
--------
>>> from embroact.patterns.plan import Command
>>> from embroact.patterns.rules import Layout, TubeLayout, RuleSettings, check_layout
>>> tube = TubeLayout.from_path("A", [(0, 0), (8, 0)], outer_radius_mm=1.5,
...                             clearance_mm=0.3, end_margin_mm=0.0, half_width_mm=3.5)
>>> recs = [(2, 3.5), (3, -3.5), (4, 3.5), (5, 1.0), (6, -3.5)]
>>> lay = Layout.from_points(recs, [Command.STITCH] * 5, [0] * 5, tubes=(tube,))
>>> [(f.code, f.stitch_index) for f in check_layout(lay, RuleSettings())]
[('EA101', 3)]
"""
from __future__ import annotations

from ..plan import StitchPlan
from ..spatial import needle_density
from .engine import Subject, finding_order, run_rules, sort_findings
from .layout import FILE_REACH_MM, Layout, TubeLayout, layout_from_plan, layout_from_records
from .machine import MACHINE_RULES
from .needles import NEEDLE_RULES
from .pattern import PATTERN_RULES
from .settings import RuleSettings
from .tubes import TUBE_RULES

__all__ = [
    "RuleSettings",
    "TubeLayout",
    "Layout",
    "layout_from_plan",
    "layout_from_records",
    "FILE_REACH_MM",
    "GEOMETRY_RULES",
    "check_layout",
    "check_geometry",
    "needle_density",
    "sort_findings",
    "finding_order",
]

GEOMETRY_RULES = tuple(sorted(NEEDLE_RULES + PATTERN_RULES + TUBE_RULES + MACHINE_RULES, key=lambda r: r.code))
"""Every rule declared in :mod:`embroact.patterns` (geometry, pattern, tubes, machine file), in code order."""


def check_layout(layout: Layout, settings: RuleSettings | None = None, *, rules=GEOMETRY_RULES):
    """Run the ``rules`` that apply to files on a layout; findings worst first.

    Each rule lists at most ``settings.max_findings_per_rule`` findings plus one
    summary finding for the rest.

    Parameters
    ----------
    layout : Layout
        Records and tubes (an embroidery file's, or a plan's).
    settings : RuleSettings or None, optional
        Thresholds; None: the defaults.
    rules : iterable of Rule, optional
        The rules to run (those for files only; the ones for designs need a plan).

    Returns
    -------
    tuple of Finding
        Worst first.

    Examples
    --------
    >>> tube = TubeLayout.from_path("A", [(0, 0), (8, 0)], outer_radius_mm=1.5,
    ...                             clearance_mm=0.3, end_margin_mm=0.0, half_width_mm=3.5)
    >>> recs = [(2, 3.5), (3, -3.5), (4, 3.5), (5, 1.0), (6, -3.5)]  # the fourth pierces the tube
    >>> lay = Layout.from_points(recs, [0] * 5, [0] * 5, tubes=(tube,))
    >>> [(f.code, f.severity.value) for f in check_layout(lay)]
    [('EA101', 'error')]
    """
    return run_rules(rules, Subject(layout, settings or RuleSettings()))


def check_geometry(plan: StitchPlan, settings: RuleSettings | None = None, *, rules=GEOMETRY_RULES):
    """Every rule of ``rules`` for designs on a stitch plan; findings worst first.

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
        Worst first.

    Examples
    --------
    >>> from embroact.patterns.zigzag import zigzag
    >>> from embroact.patterns.params import ZigzagParams
    >>> check_geometry(zigzag([[0.0, 0.0], [60.0, 0.0]], ZigzagParams(7.0, 1.0)))
    ()
    """
    return run_rules(rules, Subject(layout_from_plan(plan), settings or RuleSettings(), plan))
