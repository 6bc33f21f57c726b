"""Design-rule findings and the registry of every rule embroact checks.

A :class:`Finding` is one problem found on a design or an embroidery file: a
stable ``code`` (``EA101`` ...), a severity, a message with the numbers, the
place (actuator name, stitch index, coordinates in mm) and a suggested fix.
The codes, their severities, titles and descriptions live in one table,
:data:`RULES`, which also renders the README's rules table.

Code groups
-----------
``EA1xx`` needle points and stitches, ``EA2xx`` pattern and sleeve,
``EA3xx`` tube path and placement, ``EA4xx`` model predictions,
``EA5xx`` machine-file structure.

Examples
--------
>>> from embroact.patterns.base.findings import RULES, Severity
>>> f = RULES.finding("EA101", "needle point 0.4 mm from the tube axis", stitch_index=7, xy_mm=(1.0, 0.4))
>>> f.severity is Severity.ERROR, f.code, f.stitch_index
(True, 'EA101', 7)
>>> f.as_dict()["xy_mm"]
[1.0, 0.4]
>>> RULES["EA105"].title
'needle points dense'
"""
from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import Iterator

from .errors import ParameterError

__all__ = ["Severity", "Rule", "Finding", "RuleSet", "RULES", "rules_table_markdown", "count_by_severity"]


class Severity(str, Enum):
    """How bad a finding is: errors stop ``build`` (unless ``--force``), warnings and info do not."""

    ERROR = "error"
    WARNING = "warning"
    INFO = "info"

    @property
    def rank(self) -> int:
        """0 for error, 1 for warning, 2 for info (sort key: worst first)."""
        return ("error", "warning", "info").index(self.value)


@dataclass(frozen=True, slots=True)
class Rule:
    """One design rule as documented.

    Attributes
    ----------
    code : str
        Stable identifier, ``EA`` and three digits.
    severity : Severity
    title : str
        A few words, lower case.
    description : str
        What is checked and why it matters, with the threshold.
    fix : str
        Default suggested fix (a finding may give a more specific one).
    checks : str
        Where the rule runs: ``"designs"``, ``"designs, files"`` or ``"designs (model)"``.
    """

    code: str
    severity: Severity
    title: str
    description: str
    fix: str
    checks: str = "designs, files"


@dataclass(frozen=True, slots=True)
class Finding:
    """One problem found by a design rule.

    Attributes
    ----------
    code : str
        Rule code (see :data:`RULES`).
    severity : Severity
    message : str
        What is wrong, with the measured and allowed numbers.
    actuator : str or None
        Actuator (or tube) name, when the finding belongs to one.
    stitch_index : int or None
        Record index in the plan, or in the file's own record order for files.
    xy_mm : tuple of float or None
        Where on the design [mm] (plan frame for designs, the file's frame for files).
    fix : str
        Suggested fix.
    """

    code: str
    severity: Severity
    message: str
    actuator: str | None = None
    stitch_index: int | None = None
    xy_mm: tuple[float, float] | None = None
    fix: str = ""

    @property
    def is_error(self) -> bool:
        """True for severity error."""
        return self.severity is Severity.ERROR

    def place(self) -> str:
        """Short human-readable place: ``"A1, stitch 57 at (12.3, 4.5) mm"``."""
        parts = []
        if self.actuator is not None:
            parts.append(self.actuator)
        if self.stitch_index is not None:
            parts.append(f"stitch {self.stitch_index}")
        where = ", ".join(parts)
        if self.xy_mm is not None:
            where += f"{' ' if where else ''}at ({self.xy_mm[0]:.2f}, {self.xy_mm[1]:.2f}) mm"
        return where or "design"

    def as_dict(self) -> dict:
        """Plain dict for JSON (``xy_mm`` as a list or None)."""
        return {
            "code": self.code,
            "severity": self.severity.value,
            "title": RULES[self.code].title,
            "message": self.message,
            "actuator": self.actuator,
            "stitch_index": self.stitch_index,
            "xy_mm": None if self.xy_mm is None else [self.xy_mm[0], self.xy_mm[1]],
            "fix": self.fix,
        }


@dataclass(frozen=True, slots=True)
class RuleSet:
    """The registry of rules, keyed by code; iterates in code order."""

    rules: tuple[Rule, ...]

    def __iter__(self) -> Iterator[Rule]:
        return iter(self.rules)

    def __len__(self) -> int:
        return len(self.rules)

    def __getitem__(self, code: str) -> Rule:
        for r in self.rules:
            if r.code == code:
                return r
        raise ParameterError(f"rule code must be one of {', '.join(r.code for r in self.rules)}, got {code!r}")

    def finding(
        self,
        code: str,
        message: str,
        *,
        actuator: str | None = None,
        stitch_index: int | None = None,
        xy_mm=None,
        fix: str | None = None,
    ) -> Finding:
        """A :class:`Finding` of rule ``code`` with the rule's severity and default fix."""
        rule = self[code]
        return Finding(
            code=code,
            severity=rule.severity,
            message=message,
            actuator=actuator,
            stitch_index=None if stitch_index is None else int(stitch_index),
            xy_mm=None if xy_mm is None else (round(float(xy_mm[0]), 4), round(float(xy_mm[1]), 4)),
            fix=rule.fix if fix is None else fix,
        )

    def markdown_table(self) -> str:
        """The README table: code, severity, title, what is checked, where it runs."""
        lines = ["| code | severity | rule | what is checked | checks |", "|---|---|---|---|---|"]
        cells = [(r.code, r.severity.value, r.title, r.description, r.checks) for r in self.rules]
        lines += ["| " + " | ".join(c.replace("|", "\\|") for c in row) + " |" for row in cells]
        return "\n".join(lines) + "\n"


_E, _W, _I = Severity.ERROR, Severity.WARNING, Severity.INFO
_D, _DF, _DM = "designs", "designs, files", "designs (model)"

RULES = RuleSet(
    (
        Rule("EA101", _E, "needle in tube corridor",
             "A needle point lies closer to the tube axis than r_f + clearance (the tube extended by its "
             "end margins included): the needle would pierce the tube.",
             "Widen the pattern or move the needle point out of the corridor.", _DF),
        Rule("EA102", _E, "record over format limit",
             "A stitch moves further per axis (|dx| or |dy|) than the target format allows in one record "
             "(DST 12.1 mm, EXP/JEF/U01/TBF 12.7 mm, ...); the writer would silently split it into jumps.",
             "Narrow the pattern, choose a format with longer records, or split the leg explicitly.", _DF),
        Rule("EA103", _E, "stitch over machine maximum",
             "A stitch is longer than the machine's maximum stitch length (machine.max_stitch_mm).",
             "Narrow the pattern or raise machine.max_stitch_mm if the machine allows it.", _DF),
        Rule("EA104", _W, "stitch too short",
             "Two consecutive needle points are closer than the machine's minimum stitch "
             "(machine.min_stitch_mm): the thread breaks or the needle hits its own hole.",
             "Increase the stitch interval or the tie-stitch length.", _DF),
        Rule("EA105", _W, "needle points dense",
             "A needle point has 3 or more needle points within 0.5 mm, counted as Ink/Stitch's density "
             "map does (the point itself included, distance <= 0.5 mm): the fabric is perforated.",
             "Increase the stitch interval or spread the passes.", _DF),
        Rule("EA106", _E, "needle points too dense",
             "A needle point has 6 or more needle points within 0.5 mm (Ink/Stitch's red density level): "
             "the fabric tears along the rail.",
             "Increase the stitch interval or reduce the number of passes.", _DF),
        Rule("EA201", _E, "no sleeve",
             "The realised width leaves no sleeve: r0 <= r_f, i.e. w <= (pi^2 - 4)/pi * r_f (MODEL.md 3); "
             "the thread squeezes the tube before any pressure and the model has no inflation phase.",
             "Increase the width.", _DF),
        Rule("EA202", _W, "sleeve barely wider than the tube",
             "The sleeve radius r0 exceeds r_f by less than min_sleeve_gap_mm: P0 is tiny and very sensitive "
             "to the width.",
             "Increase the width.", _DF),
        Rule("EA203", _W, "stitch interval over tube diameter",
             "Neighbouring legs cross the tube further apart than its diameter 2 r_f: the tube bulges between "
             "legs, which the model does not describe.",
             "Decrease the stitch interval.", _DF),
        Rule("EA204", _W, "leg angle off request",
             "The realised cross-pattern leg angle differs from the requested alpha0 by more than the angle "
             "tolerance (patterns/tolerances.py).",
             "Adjust the interval or length so that angle and spacing fit, or accept the realised angle.", _D),
        Rule("EA205", _W, "stitch interval off request",
             "The realised stitch interval differs from the request by more than the relative spacing "
             "tolerance (patterns/tolerances.py).",
             "Adjust the length or the interval so that a whole number of legs fits.", _D),
        Rule("EA206", _W, "angle near neutral",
             "The cross-pattern angle alpha0 lies within neutral_band_deg of the neutral angle "
             "(tan beta0 = 1/2): the bending direction is ill-conditioned.",
             "Move alpha0 away from the neutral angle.", _D),
        Rule("EA301", _E, "turn tighter than the tube allows",
             "The tube path's curvature radius falls below the minimum turning radius "
             "(turning_radius_factor x tube outer diameter, default 3 x 2 r_f): the tube kinks.",
             "Smooth the path: larger bend radii.", _DF),
        Rule("EA302", _E, "tube path crosses itself",
             "The tube path intersects itself: the tube would be laid over itself.",
             "Change the path so that it does not cross itself.", _DF),
        Rule("EA303", _E, "tube corridors overlap",
             "Two tubes' corridors (r_f + clearance around each path) overlap.",
             "Move the actuators apart.", _DF),
        Rule("EA304", _W, "actuators too close",
             "The stitched bands (w/2 around each path) of two actuators are closer than "
             "actuator_clearance_mm.",
             "Move the actuators apart.", _DF),
        Rule("EA305", _W, "tube end margin missing",
             "The free tube beyond an end (end_margin_mm along the end tangent, for the connector) leaves the "
             "hoop or runs into needle points.",
             "Move the actuator inward, shorten it, or reduce tube.end_margin_mm.", _DF),
        Rule("EA306", _E, "outside the hoop",
             "A record (stitch, jump or trim excursion) lies outside the hoop's sewing field "
             "(machine.hoop_width_mm x machine.hoop_height_mm, centred on the design).",
             "Use a larger hoop or make the design smaller.", _DF),
        Rule("EA401", _E, "P0 above working pressure",
             "The predicted transition pressure P0 exceeds operation.max_pressure_kpa: the actuator never "
             "bends in service.",
             "Narrow the pattern (smaller r0) or raise the working pressure.", _DM),
        Rule("EA402", _W, "lock-up below working pressure",
             "The sleeve locks up (no further bending) below operation.max_pressure_kpa.",
             "Change the angle or width, or lower the working pressure.", _DM),
        Rule("EA403", _W, "bend beyond limit",
             "The predicted bend at the working pressure exceeds operation.max_bend_deg.",
             "Shorten the actuator or lower the working pressure.", _DM),
        Rule("EA404", _W, "prediction extrapolated",
             "The calibration (G, P0) is extrapolated outside the measured designs.",
             "Measure a sample of this design and fit it ('embroact fit').", _DM),
        Rule("EA405", _W, "model outside its domain",
             "Between P0 and the working pressure the model leaves its domain or becomes unstable "
             "(MODEL.md 6); predictions there are not valid.",
             "Lower the working pressure or change the pattern.", _DM),
        Rule("EA406", _I, "calibration approximate",
             "The calibration set matches this design only approximately (e.g. a cross width other than the "
             "calibrated one); its notes are listed.",
             "Measure a sample of this design and fit it ('embroact fit').", _DM),
        Rule("EA501", _W, "jump run reads as trim",
             "Three or more consecutive jump records (the machine's trim count) where no trim is meant: the "
             "machine cuts the thread.",
             "Shorten the travel, add a real trim, or lay actuators closer.", _DF),
        Rule("EA502", _E, "missing stop",
             "Sewing moves from one tube to another without a stop: the operator never gets to lay the tube.",
             "Insert a stop (colour change in DST) before each actuator.", _DF),
        Rule("EA503", _W, "unexpected stop",
             "A stop or colour change falls inside one actuator's stitches.",
             "Remove the stop, or split the actuator.", _DF),
        Rule("EA504", _E, "too many records",
             "The number of records exceeds the format's (or the machine's) limit.",
             "Split the design into several files.", _DF),
    )
)


def rules_table_markdown() -> str:
    """The Markdown table of every rule, for the README.

    Examples
    --------
    >>> print(rules_table_markdown().splitlines()[2])  # doctest: +ELLIPSIS
    | EA101 | error | needle in tube corridor | A needle point lies closer ... | designs, files |
    """
    return RULES.markdown_table()


def count_by_severity(findings) -> dict[str, int]:
    """``{"error": n, "warning": n, "info": n}`` for a sequence of findings.

    Examples
    --------
    >>> count_by_severity([RULES.finding("EA104", "short")])
    {'error': 0, 'warning': 1, 'info': 0}
    """
    counts = {s.value: 0 for s in Severity}
    for f in findings:
        counts[f.severity.value] += 1
    return counts
