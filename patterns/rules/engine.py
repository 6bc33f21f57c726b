"""The rule engine: one :class:`Subject` per check, rules run on it, findings capped and sorted.

A rule's check function (declared with ``RULES.rule``, see
:mod:`embroact.patterns.base.findings`) takes a :class:`Subject` and returns
a list of findings or, for rules that flag many records at once, :class:`Hits`
(record indices and a message per hit), of which the engine builds findings only
for the first ``max_findings_per_rule`` and summarises the rest in one more.

The subject computes what several rules share once, on first use: record
displacements, stitch lengths, grid moves, the spatial indexes of the tube axes
(:class:`~embroact.patterns.spatial.TubeIndex`), the crossings of legs with tubes,
needle densities.

Examples
--------
>>> from embroact.patterns.plan import Command
>>> from embroact.patterns.rules import Layout, RuleSettings, TubeLayout
>>> tube = TubeLayout.from_path("A", [(0, 0), (20, 0)], outer_radius_mm=1.5, clearance_mm=0.3,
...                             end_margin_mm=0.0, half_width_mm=3.5)
>>> lay = Layout.from_points([(2, 3.5), (3, -3.5)], [Command.STITCH] * 2, [0, 0], tubes=(tube,))
>>> s = Subject(lay, RuleSettings())
>>> s.needles.tolist(), [round(float(v), 3) for v in s.stitch_lengths_mm]
([0, 1], [0.0, 7.071])
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Callable

import numpy as np

from ..base.errors import ParameterError
from ..base.findings import RULES, Finding, Inputs, Rule
from ..limits import record_moves_units
from ..plan import Command, Role, StitchPlan
from ..segments import pattern_parts
from ..spatial import Crossings, TubeIndex, needle_density
from .layout import Layout
from .settings import RuleSettings

__all__ = ["Subject", "Hits", "run_rules", "sort_findings", "finding_order"]


@dataclass(frozen=True, slots=True, eq=False)
class Hits:
    """Records that break one rule, found in bulk.

    Attributes
    ----------
    index : ndarray of int
        Layout record per hit, in report order.
    message : callable
        ``message(j) -> str`` for hit ``j``.
    owner : ndarray of int or None
        Tube index per hit for the finding's actuator (default: the record's owner).

    Examples
    --------
    >>> import numpy as np
    >>> hits = Hits(np.array([3, 8]), lambda j: f"hit {j}")
    >>> len(hits), hits.message(1)
    (2, 'hit 1')
    """

    index: np.ndarray
    message: Callable[[int], str]
    owner: np.ndarray | None = None

    def __len__(self) -> int:
        return len(self.index)


class Subject:
    """One check: the layout, the settings, the plan (for designs) and the values rules share.

    Parameters
    ----------
    layout : Layout
        Records and tubes.
    settings : RuleSettings
        Thresholds.
    plan : StitchPlan or None
        The design's plan; None for embroidery files (rules for designs only are skipped).

    Examples
    --------
    >>> from embroact.patterns.rules import Layout, RuleSettings
    >>> s = Subject(Layout.from_points([(0, 0), (3, 4)], [0, 0], [-1, -1], tubes=()), RuleSettings())
    >>> s.displacements_mm.tolist(), s.plan is None
    ([[0.0, 0.0], [3.0, 4.0]], True)
    """

    def __init__(self, layout: Layout, settings: RuleSettings, plan: StitchPlan | None = None) -> None:
        self.layout, self.settings, self.plan = layout, settings, plan
        self._shared: dict = {}

    @property
    def design_plan(self) -> StitchPlan:
        """The design's plan, for rules of designs (they run only when there is one)."""
        if self.plan is None:
            raise ParameterError("this rule checks a design's plan; an embroidery file has none")
        return self.plan

    def shared(self, key: str, compute: Callable):
        """``compute()`` once per subject under ``key``: a value several rules read.

        Parameters
        ----------
        key : str
            The value's name, unique among the rules.
        compute : callable
            ``compute() -> value``, called on the first request only.

        Returns
        -------
        object
            The value.

        Examples
        --------
        >>> from embroact.patterns.rules import Layout, RuleSettings
        >>> s = Subject(Layout.from_points([(0, 0)], [0], [-1], tubes=()), RuleSettings())
        >>> s.shared("n", lambda: [1]) is s.shared("n", lambda: [2])
        True
        """
        if key not in self._shared:
            self._shared[key] = compute()
        return self._shared[key]

    # ----------------------------------------------------------------- records
    @cached_property
    def displacements_mm(self) -> np.ndarray:
        """Each record's move from the previous one [mm] (0 for the first)."""
        d = np.zeros_like(self.layout.xy_mm)
        d[1:] = np.diff(self.layout.xy_mm, axis=0)
        return d

    @cached_property
    def moves_units(self) -> np.ndarray:
        """Each record's move on the machine grid, as the writer encodes it (the first from the origin)."""
        return record_moves_units(self.layout.xy_mm)

    @cached_property
    def stitch_lengths_mm(self) -> np.ndarray:
        """Length of each record's move [mm]."""
        d = self.displacements_mm
        return np.hypot(d[:, 0], d[:, 1])

    @cached_property
    def needles(self) -> np.ndarray:
        """Indices of the STITCH records (needle points)."""
        return np.flatnonzero(self.layout.commands == Command.STITCH)

    @cached_property
    def consecutive(self) -> np.ndarray:
        """True for a STITCH record right after another STITCH: a leg of thread ends there."""
        stitch = self.layout.commands == Command.STITCH
        return stitch & np.concatenate([[False], stitch[:-1]])

    @cached_property
    def density(self) -> np.ndarray:
        """Needle points within ``density_radius_mm`` of each needle point, itself included."""
        return needle_density(self.layout.xy_mm[self.needles], self.settings.density_radius_mm)

    @cached_property
    def first_needle(self) -> np.ndarray:
        """Per tube, the first needle record it owns (-1 if none)."""
        first = np.full(len(self.layout.tubes), -1, dtype=np.int64)
        owned = self.needles[self.layout.owner[self.needles] >= 0]
        tubes, at = np.unique(self.layout.owner[owned], return_index=True)
        first[tubes] = owned[at]
        return first

    # ----------------------------------------------------------------- tubes
    @cached_property
    def axes(self) -> TubeIndex:
        """Spatial index of every tube's axis (the embroidered path)."""
        return TubeIndex([t.path for t in self.layout.tubes])

    @cached_property
    def laid_paths(self) -> tuple:
        """Every tube's whole laid length (path and end margins) as a LineString."""
        return tuple(t.extended_path() for t in self.layout.tubes)

    @cached_property
    def laid_tubes(self) -> TubeIndex:
        """Spatial index of every tube's whole laid length."""
        return TubeIndex(self.laid_paths)

    @cached_property
    def legs(self) -> np.ndarray:
        """Records where a leg of thread ends (it starts at the record before); legs of a placement
        line, sewn before their tube was laid (``Layout.before_tube``), hold no tube and are left out."""
        early = self.layout.before_tube
        return np.flatnonzero(self.consecutive & ~early & ~np.concatenate([[False], early[:-1]]))

    @cached_property
    def crossings(self) -> Crossings:
        """Every leg crossing every tube axis (one spatial query); ``leg`` indexes :attr:`legs`."""
        xy = self.layout.xy_mm
        return self.axes.crossings(xy[self.legs - 1], xy[self.legs])

    # ----------------------------------------------------------------- plans
    @cached_property
    def first_leg(self) -> np.ndarray:
        """Per plan actuator, the first LEG record (-1 if none)."""
        plan = self.design_plan
        first = np.full(len(plan.actuators), -1, dtype=np.int64)
        legs = np.flatnonzero((plan.roles == Role.LEG) & (plan.actuator >= 0))
        acts, at = np.unique(plan.actuator[legs], return_index=True)
        keep = acts < len(first)
        first[acts[keep]] = legs[at[keep]]
        return first

    def actuator_place(self, k: int) -> dict:
        """``actuator``, ``stitch_index`` and ``xy_mm`` of plan actuator ``k`` (at its first leg).

        Parameters
        ----------
        k : int
            Actuator index in the plan.

        Returns
        -------
        dict
            Keyword arguments for :meth:`RuleRegistry.finding`.

        Examples
        --------
        >>> from embroact.patterns.rules import RuleSettings, layout_from_plan
        >>> from embroact.patterns.zigzag import zigzag
        >>> from embroact.patterns.params import ZigzagParams
        >>> plan = zigzag([[0.0, 0.0], [20.0, 0.0]], ZigzagParams(7.0, 1.0), name="A1")
        >>> place = Subject(layout_from_plan(plan), RuleSettings(), plan).actuator_place(0)
        >>> place["actuator"], place["stitch_index"] > 0
        ('A1', True)
        """
        i = int(self.first_leg[k])
        plan = self.design_plan
        return dict(actuator=plan.actuators[k].name, stitch_index=i if i >= 0 else None,
                    xy_mm=plan.xy_mm[i] if i >= 0 else None)

    def pattern_findings(self, code: str, message: Callable) -> list[Finding]:
        """Findings ``code`` comparing each requested pattern of the design with what was sewn.

        ``message(act, req, real)`` gets the plan actuator, the requested parameters and the
        realised ones of each of its patterns (:func:`~embroact.patterns.segments.pattern_parts`)
        and returns the text, or None when there is nothing to report; the part's label
        prefixes the text and the finding sits at the actuator's first leg.

        Parameters
        ----------
        code : str
            The rule's code.
        message : callable
            ``message(act, req, real) -> str or None``.

        Returns
        -------
        list of Finding

        Examples
        --------
        >>> from embroact.patterns.rules import RuleSettings, layout_from_plan
        >>> from embroact.patterns.zigzag import zigzag
        >>> from embroact.patterns.params import ZigzagParams
        >>> plan = zigzag([[0.0, 0.0], [20.0, 0.0]], ZigzagParams(7.0, 1.0))
        >>> s = Subject(layout_from_plan(plan), RuleSettings(), plan)
        >>> [f.message for f in s.pattern_findings("EA203", lambda act, req, real: f"width {real.width_mm:g} mm")]
        ['width 7 mm']
        """
        out = []
        for k, act in enumerate(self.design_plan.actuators):
            for label, req, real in pattern_parts(act):
                text = message(act, req, real)
                if text is not None:
                    out.append(RULES.finding(code, label + text, **self.actuator_place(k)))
        return out

    # ----------------------------------------------------------------- findings
    def point(self, i: int, code: str, message: str, *, owner: int | None = None) -> Finding:
        """A finding at layout record ``i`` (actuator: the record's owner, or ``owner``).

        Parameters
        ----------
        i : int
            Layout record.
        code, message : str
            The rule's code and the finding's text.
        owner : int or None, optional
            Tube index the finding belongs to; None: the record's owner.

        Returns
        -------
        Finding

        Examples
        --------
        >>> from embroact.patterns.rules import Layout, RuleSettings, TubeLayout
        >>> tube = TubeLayout.from_path("A", [(0, 0), (8, 0)], outer_radius_mm=1.5, clearance_mm=0.3,
        ...                             end_margin_mm=0.0, half_width_mm=3.5)
        >>> s = Subject(Layout.from_points([(2, 3.5), (3, 1.0)], [0, 0], [0, 0], tubes=(tube,)), RuleSettings())
        >>> s.point(1, "EA101", "in the tube").place()
        'A, stitch 1 at (3.00, 1.00) mm'
        """
        lay = self.layout
        return RULES.finding(code, message, actuator=lay.name_of(int(lay.owner[i] if owner is None else owner)),
                             stitch_index=int(lay.index[i]), xy_mm=lay.xy_mm[i])

    def tube_finding(self, k: int, code: str, message: str, xy=None) -> Finding:
        """A finding on tube ``k``, placed at its first needle point unless ``xy`` is given.

        Parameters
        ----------
        k : int
            Tube index.
        code, message : str
            The rule's code and the finding's text.
        xy : (x, y) or None, optional
            Where [mm]; None: at the tube's first needle point.

        Returns
        -------
        Finding

        Examples
        --------
        >>> from embroact.patterns.rules import Layout, RuleSettings, TubeLayout
        >>> tube = TubeLayout.from_path("A", [(0, 0), (8, 0)], outer_radius_mm=1.5, clearance_mm=0.3,
        ...                             end_margin_mm=0.0, half_width_mm=3.5)
        >>> s = Subject(Layout.from_points([(2, 3.5), (3, -3.5)], [0, 0], [0, 0], tubes=(tube,)), RuleSettings())
        >>> s.tube_finding(0, "EA304", "tube A is short").place()
        'A, stitch 0 at (2.00, 3.50) mm'
        """
        i = int(self.first_needle[k])
        if xy is None and i >= 0:
            xy = self.layout.xy_mm[i]
        return RULES.finding(code, message, actuator=self.layout.tubes[k].name,
                             stitch_index=None if i < 0 else int(self.layout.index[i]), xy_mm=xy)


def _capped(subject: Subject, code: str, found, limit: int) -> list[Finding]:
    """The first ``limit`` findings of one rule and, if there are more, one finding counting the rest."""
    if isinstance(found, Hits):
        n = len(found)
        owner = (lambda j: None) if found.owner is None else (lambda j: int(found.owner[j]))
        head = [subject.point(int(found.index[j]), code, found.message(j), owner=owner(j)) for j in range(min(n, limit))]
        if n <= limit:
            return head
        first = subject.point(int(found.index[limit]), code, "", owner=owner(limit))
    else:
        found = list(found)
        n = len(found)
        head = found[:limit]
        if n <= limit:
            return head
        first = found[limit]
    more = RULES.finding(code, f"{n - limit} more findings of this rule, from stitch {first.stitch_index} on",
                         actuator=first.actuator, stitch_index=first.stitch_index, xy_mm=first.xy_mm,
                         fix=first.fix, count=n - limit)
    return head + [more]


def sort_findings(findings) -> tuple[Finding, ...]:
    """Worst first, then by code and stitch index (deterministic order).

    Parameters
    ----------
    findings : iterable of Finding
        In any order.

    Returns
    -------
    tuple of Finding

    Examples
    --------
    >>> import embroact.patterns.rules  # declares the rules
    >>> fs = [RULES.finding("EA105", "w", stitch_index=2), RULES.finding("EA101", "e", stitch_index=9)]
    >>> [f.code for f in sort_findings(fs)]
    ['EA101', 'EA105']
    """
    return tuple(sorted(findings, key=finding_order))


def finding_order(finding: Finding) -> tuple:
    """The sort key of :func:`sort_findings`: severity (worst first), code, stitch index (none first), message.

    Parameters
    ----------
    finding : Finding

    Returns
    -------
    tuple

    Examples
    --------
    >>> import embroact.patterns.rules  # declares the rules
    >>> finding_order(RULES.finding("EA105", "w", stitch_index=2))
    (1, 'EA105', 2, 'w')
    """
    return (finding.severity.rank, finding.code, -1 if finding.stitch_index is None else finding.stitch_index,
            finding.message)


def applies(rule: Rule, subject: Subject) -> bool:
    """True when ``rule`` runs on ``subject``: file rules always, design-only rules with a plan.

    Parameters
    ----------
    rule : Rule
        A declared rule.
    subject : Subject
        What is checked.

    Returns
    -------
    bool

    Examples
    --------
    >>> from embroact.patterns.rules import Layout, RuleSettings
    >>> s = Subject(Layout.from_points([(0, 0)], [0], [-1], tubes=()), RuleSettings())
    >>> applies(RULES["EA101"], s), applies(RULES["EA204"], s)
    (True, False)
    """
    if rule.check is None:
        return False
    return Inputs.FILES in rule.inputs or (subject.plan is not None and Inputs.DESIGNS in rule.inputs)


def run_rules(rules, subject: Subject) -> tuple[Finding, ...]:
    """Every rule of ``rules`` that applies to ``subject``, capped per rule; findings worst first.

    Parameters
    ----------
    rules : iterable of Rule
        The rules to run.
    subject : Subject
        What is checked.

    Returns
    -------
    tuple of Finding
        Worst first; a rule with more than ``settings.max_findings_per_rule`` findings closes
        with one that counts the rest.

    Examples
    --------
    >>> from embroact.patterns.rules import Layout, RuleSettings
    >>> s = Subject(Layout.from_points([(0, 0), (30, 0)], [0, 0], [-1, -1], tubes=()), RuleSettings())
    >>> [f.code for f in run_rules([RULES["EA102"]], s)]
    ['EA102']
    """
    found: list[Finding] = []
    for rule in rules:
        if applies(rule, subject):
            found += _capped(subject, rule.code, rule.check(subject), subject.settings.max_findings_per_rule)
    return sort_findings(found)
