"""Model-based design rules (EA4xx) and :func:`check_design`, every rule on an analysed design.

Each actuator's model is the analysis's (:func:`embroact.predict.analysis.analyse`: realised
geometry, G and P0 by the calibration policy), its curve the analysis's curve on the standard
grid from 0 to the working pressure ``operation.max_pressure_kpa`` in 10 kPa steps, the same
curve the build's chart and report draw.

* EA401: P0 above the working pressure (error).
* EA402: lock-up: the bend at the working pressure reaches ``lockup_fraction``
  (default 0.9) of the lock-up angle, or the curve reports LOCKED; beyond that
  more pressure gives almost no bend.
* EA403: |bend| at the working pressure above ``operation.max_bend_deg``.
* EA404: the calibration set was extrapolated for this design.
* EA405: between P0 and the working pressure the curve leaves the model's domain,
  snaps through (UNSTABLE), fails or passes a validity limit (a segmented actuator's
  segments one by one, then its whole strip: the bent line with its stub touching itself,
  the clamp or the fixed fabric); or no model can be built.
* EA406 (info): the calibration's notes (approximate match, e.g. another cross width;
  a tube other than the calibrated one).

Examples
--------
>>> from embroact.patterns.design import default_design
>>> from embroact.predict.analysis import analyse
>>> from embroact.predict.rules import check_design
>>> [f.code for f in check_design(analyse(default_design())) if f.is_error]
[]
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from itertools import chain, groupby

import numpy as np

from ..patterns.base.errors import ModelDomainError, check_range
from ..patterns.base.tolerances import DEFAULT_TOLERANCES
from ..patterns.base.findings import RULES, Finding, Inputs, Rule, Severity
from ..patterns.design import OperationSettings
from ..patterns.rules import RuleSettings, finding_order, sort_findings
from .sleeve_rules import DESIGN_RULES, check_without_model
from .status import VALIDITY_LIMITS, Status, is_model_state

__all__ = ["ModelRuleSettings", "PER_FORMAT_RULES", "check_model", "check_design"]

#: States EA405 reports: outside the model's domain, snap-through, a method failure, or past a
#: validity limit (coiled, kinked, overstretched: docs/model.md).
_BAD_STATES = (Status.OUT_OF_DOMAIN, Status.UNSTABLE, Status.FAILED, *VALIDITY_LIMITS)


_E, _W, _I = Severity.ERROR, Severity.WARNING, Severity.INFO
_MODEL = Inputs.DESIGNS | Inputs.MODEL

# The model rules, declared once here: checked together by check_model from one curve per actuator.
for _rule in (
    Rule("EA401", _E, "P0 above working pressure",
         "The predicted transition pressure P0 exceeds operation.max_pressure_kpa: the actuator never "
         "bends in service.",
         "Narrow the pattern (smaller r0) or raise the working pressure.", _MODEL),
    Rule("EA402", _W, "lock-up below working pressure",
         "The sleeve locks up (no further bending) below operation.max_pressure_kpa.",
         "Change the angle or width, or lower the working pressure.", _MODEL),
    Rule("EA403", _W, "bend beyond limit",
         "The predicted bend at the working pressure exceeds operation.max_bend_deg.",
         "Shorten the actuator or lower the working pressure.", _MODEL),
    Rule("EA404", _W, "prediction extrapolated",
         "The calibration (G, P0) is extrapolated outside the measured designs (by more than a sewn "
         "coordinate may differ from the asked one: 0.1 deg of angle, half a grid unit of width).",
         "Measure a sample of this design and fit it ('embroact fit').", _MODEL),
    Rule("EA405", _W, "model outside its domain",
         "Between P0 and the working pressure the model leaves its domain, becomes unstable, or passes a "
         "validity limit (coiled, kinked, over-stretched; docs/model.md); predictions there are not valid.",
         "Lower the working pressure or change the pattern.", _MODEL),
    Rule("EA406", _I, "calibration approximate",
         "The calibration set matches this design only approximately (e.g. a cross width other than the "
         "calibrated one, or a tube other than the one it was fitted with); its notes are listed.",
         "Measure a sample of this design and fit it ('embroact fit').", _MODEL),
):
    RULES.declare(_rule)


@dataclass(frozen=True, slots=True)
class ModelRuleSettings:
    """Thresholds of the model rules.

    Parameters
    ----------
    max_pressure_kpa : float
        Working pressure [kPa], > 0 (design: ``operation.max_pressure_kpa``).
    max_bend_deg : float
        Largest acceptable |bend| at the working pressure [deg] (``operation.max_bend_deg``).
    lockup_fraction : float
        Fraction of the lock-up angle counted as locked, in (0, 1].
    method : str
        Model method (``embroact.predict.curve``), default ``"auto"``.

    Examples
    --------
    >>> ModelRuleSettings()
    ModelRuleSettings(max_pressure_kpa=300.0, max_bend_deg=180.0, lockup_fraction=0.9, method='auto')
    """

    max_pressure_kpa: float = OperationSettings().max_pressure_kpa  # the design's defaults: one home
    max_bend_deg: float = OperationSettings().max_bend_deg
    lockup_fraction: float = 0.9
    method: str = "auto"

    def __post_init__(self) -> None:
        check_range("max_pressure_kpa", self.max_pressure_kpa, low=0.0, high=1e5)
        check_range("max_bend_deg", self.max_bend_deg, low=0.0, high=1e5)
        check_range("lockup_fraction", self.lockup_fraction, low=0.0, high=1.0, high_inclusive=True)

    @classmethod
    def for_operation(cls, operation, **overrides) -> "ModelRuleSettings":
        """From a design's ``OperationSettings`` (``max_pressure_kpa``, ``max_bend_deg``).

        Parameters
        ----------
        operation : OperationSettings
            The design's operation limits.
        **overrides
            Any other field.

        Returns
        -------
        ModelRuleSettings

        Examples
        --------
        >>> from embroact.patterns.design import OperationSettings
        >>> ModelRuleSettings.for_operation(OperationSettings(max_pressure_kpa=250.0), method="stable-analytic-trace")
        ModelRuleSettings(max_pressure_kpa=250.0, max_bend_deg=180.0, lockup_fraction=0.9, method='stable-analytic-trace')
        """
        base = dict(max_pressure_kpa=operation.max_pressure_kpa, max_bend_deg=operation.max_bend_deg)
        base.update(overrides)
        return cls(**base)


def _outside_by(cal) -> float:
    """How far the looked-up coordinate lies outside the calibrated range (0 inside)."""
    return max(cal.range_low - cal.value, cal.value - cal.range_high, 0.0)


def _realisation_tolerance(parameter: str) -> float:
    """How far a sewn coordinate may sit from the one asked for and still count as it: the leg-angle
    tolerance for an angle, half a machine-grid unit for a length (both rails of a width are on the grid)."""
    tol = DEFAULT_TOLERANCES
    return tol.angle_deg if parameter.endswith("_deg") else tol.machine_grid_mm / 2.0


def _model_findings(choice, model_error: str, c, calibration: str, settings: ModelRuleSettings, *,
                    where: dict, prefix: str = "") -> list[Finding]:
    """EA401, EA402 and EA404-EA406 of one segment's model (``prefix`` names the segment) from its curve ``c`` on the
    working pressure's grid (None without a model or with P0 above); the bend limit EA403 is the whole strip's
    (:func:`_actuator_findings`)."""
    from .analysis import pressure_grid_kpa
    from .curve import lockup

    if choice is None:
        return [RULES.finding("EA405", f"{prefix}no model: {model_error}", **where)]
    model, cal = choice.model, choice.calibration
    out = []
    notes = (cal.notes if cal is not None else ()) + choice.notes
    if notes:
        name = cal.name if cal is not None else calibration
        out.append(RULES.finding("EA406", f"{prefix}calibration {name}: " + "; ".join(notes), **where))
    if cal is not None and cal.extrapolated and _outside_by(cal) > _realisation_tolerance(cal.parameter):
        p0_note = (f"; its P0 {model.p0_kpa:.1f} kPa is the set's, the tube law gives {choice.tube_law_p0_kpa:.1f} kPa at this "
                   f"sleeve (p0_source = \"geometry\" uses that)" if choice.p0_source.startswith("calibration") else "")
        out.append(RULES.finding(
            "EA404", f"{prefix}calibration {cal.label}: {cal.parameter} {cal.value:g} outside the calibrated "
            f"range [{cal.range_low:g}, {cal.range_high:g}]{p0_note}", **where))
    p_max = settings.max_pressure_kpa
    if model.p0_kpa > p_max:
        out.append(RULES.finding(
            "EA401", f"{prefix}P0 {model.p0_kpa:.1f} kPa above the working pressure {p_max:g} kPa", **where))
        return out
    pressures = pressure_grid_kpa(p_max)
    bad = np.flatnonzero(np.isin(c.status, [int(s) for s in _BAD_STATES]))
    if len(bad):
        i = int(bad[0])
        out.append(RULES.finding(
            "EA405", f"{prefix}model state {Status(int(c.status[i])).name} from {pressures[i]:.0f} kPa on, below "
            f"the working pressure {p_max:g} kPa", **where))
    theta = float(c.theta_deg[-1])
    lock_theta, lock_p = lockup(model)
    locked = int(c.status[-1]) == Status.LOCKED or (
        np.isinf(lock_p) and lock_theta != 0.0 and abs(theta) >= settings.lockup_fraction * abs(lock_theta))
    if locked:
        out.append(RULES.finding(
            "EA402", f"{prefix}bend {theta:.1f} deg at {p_max:g} kPa is {abs(theta / lock_theta) * 100:.0f} % of "
            f"the lock-up angle {lock_theta:.1f} deg", **where))
    return out


def _actuator_findings(act, analysis, settings: ModelRuleSettings) -> list[Finding]:
    """The model rules of one actuator, segment by segment (a segment's message names it unless the chain is of
    one), and the bend limit on the bend of the whole strip (the sum of its segments')."""
    from .analysis import pressure_grid_kpa

    where = dict(actuator=act.name)
    calibration = act.spec.model.calibration
    out = []
    p_max = settings.max_pressure_kpa
    pressures = pressure_grid_kpa(p_max)
    total, described = np.zeros(len(pressures)), np.ones(len(pressures), dtype=bool)
    for k, seg in enumerate(act.segments):
        if not seg.derived.has_sleeve:
            continue  # EA201 reports it
        bends = seg.choice is not None and seg.model.p0_kpa <= p_max
        c = analysis.model_curve(seg.model, pressures, method=settings.method) if bends else None
        out += _model_findings(seg.choice, seg.model_error, c, calibration, settings, where=where,
                               prefix=act.segments.label(k))
        if c is not None:
            total += c.theta_deg
            described &= is_model_state(c.status)
    if abs(total[-1]) > settings.max_bend_deg:
        out.append(RULES.finding("EA403", _bend_limit_message(act, pressures, total, described, settings), **where))
    return out + _strip_findings(act, analysis, pressures, settings, where)


def _bend_limit_message(act, pressures, total, described, settings: ModelRuleSettings) -> str:
    """EA403's text: the bend at the working pressure where the model describes it, and the pressure of the grid from
    which the bend is past the limit (a bend past a validity limit is the formula's, not the strip's: not quoted)."""
    what = act.segments.one_or_all("bend", lambda: f"total bend of the {len(act.segments)} segments")
    limit, p_max = settings.max_bend_deg, settings.max_pressure_kpa
    first = int(np.argmax(np.abs(total) > limit))
    past = f"past the {limit:g} deg limit from {pressures[first]:g} kPa on"
    if described[-1]:
        return f"{what} {total[-1]:.1f} deg at {p_max:g} kPa, {past}"
    return (f"{what} {past} ({total[first]:.1f} deg there); at {p_max:g} kPa the model describes no state of the "
            f"strip (EA405)" if described[first] else
            f"{what} {past}, where the model describes no state of the strip (EA405)")


def _strip_findings(act, analysis, pressures, settings: ModelRuleSettings, where: dict) -> list[Finding]:
    """EA405 for the whole strip where it touches itself, the clamp or the fixed fabric while every segment's own
    state is valid (:func:`~embroact.predict.validity.strip_status`); none when a segment has no model."""
    try:  # this actuator's strip alone: another actuator without a model must not hide it
        strip = act.strip([analysis.model_curve(s.model, pressures, method=settings.method) for s in act.segments])
    except ModelDomainError:
        return []  # the segment's own EA405 names it
    own = np.all([is_model_state(c.status) for c in strip.segments], axis=0)  # the segments' states are valid
    bad = np.flatnonzero(own & np.isin(strip.status, [int(s) for s in _BAD_STATES]))
    if not len(bad):
        return []
    i = int(bad[0])
    return [RULES.finding(
        "EA405", f"whole strip {Status(int(strip.status[i])).name} from {pressures[i]:.0f} kPa on "
        f"({float(strip.theta_deg[i]):.1f} deg: it touches itself, the clamp or the fixed fabric), below the "
        f"working pressure {settings.max_pressure_kpa:g} kPa", **where)]


#: Per slot of a Finding, its setter (the slot's descriptor: a frozen dataclass refuses setattr).
_SET = {field: getattr(Finding, field).__set__ for field in Finding.__slots__}


def _slots(finding: Finding) -> list:
    """The finding's (slot setter, value) pairs but the actuator's, read once for all its copies (:func:`_copies`)."""
    return [(_SET[field], getattr(finding, field)) for field in Finding.__slots__ if field != "actuator"]


def _copies(findings, names) -> list[Finding]:
    """For each of ``names`` in turn, the findings of ``findings`` (each :func:`_slots`) for that actuator. Slots
    copied: the values were checked when the findings were made, and ``dataclasses.replace`` would introspect
    them again for each of 1000."""
    new, actuator = object.__new__, _SET["actuator"]
    out = []
    for name in names:
        for pairs in findings:
            copy = new(Finding)
            for put, value in pairs:
                put(copy, value)
            actuator(copy, name)
            out.append(copy)
    return out


def check_model(analysis, settings: ModelRuleSettings | None = None) -> tuple[Finding, ...]:
    """The model rules (EA401-EA406) for every actuator of an analysed design.

    Actuators without a sleeve (r0 <= r_f) are left to EA201: the model has no
    inflation phase to start from.

    Parameters
    ----------
    analysis : DesignAnalysis
        The analysed design.
    settings : ModelRuleSettings or None, optional
        Thresholds; None: from the design's operation limits.

    Returns
    -------
    tuple of Finding
        Worst first (:func:`~embroact.patterns.rules.sort_findings`' order).

    Notes
    -----
    Identical actuators (:attr:`~embroact.predict.analysis.DesignAnalysis.same_model_as`) are checked once,
    with their first; each gets its copy of those findings, named for it, where sorting every actuator's
    findings would put it.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> [f.code for f in check_model(analyse(default_design()))]  # bends past 180 deg at 300 kPa; demo calibration
    ['EA403', 'EA406']
    """
    settings = settings or ModelRuleSettings.for_operation(analysis.design.operation)
    acts, same = analysis.actuators, analysis.same_model_as
    kinds: dict[int, list[int]] = {}  # the first actuator of each kind -> the kind's actuators, in sewing order
    for i, first in enumerate(same):
        kinds.setdefault(first, []).append(i)
    rows: dict = {}  # sort key -> first actuator of a kind -> the kind's findings of that key (slots), as made
    for first in kinds:  # a segment without a sleeve is skipped by _actuator_findings (EA201 reports it)
        for f in _actuator_findings(acts[first], analysis, settings):
            rows.setdefault(finding_order(f), {}).setdefault(first, []).append(_slots(f))
    names = [a.name for a in acts]
    found: list[Finding] = []  # sort_findings' order: by key, then as made, actuator by actuator
    for key in sorted(rows):
        row = rows[key]
        for first, run in groupby(sorted(chain.from_iterable(kinds[k] for k in row)), key=same.__getitem__):
            found += _copies(row[first], [names[i] for i in run])
    return tuple(found)


#: The rules that read the target machine format: checked again for each further format of a design.
PER_FORMAT_RULES = tuple(r for r in DESIGN_RULES if r.per_format)


def check_design(
    analysis,
    *,
    format: str | Sequence[str] | None = None,
    rule_settings: RuleSettings | None = None,
    model_settings: ModelRuleSettings | None = None,
    ignore: tuple[str, ...] = (),
) -> tuple[Finding, ...]:
    """Every design rule on an analysed design: geometry, pattern, file structure, model.

    Parameters
    ----------
    analysis : DesignAnalysis
        From :func:`embroact.predict.analysis.analyse`; supplies the design (machine limits,
        working pressure, bend limit), the plan and each actuator's model.
    format : str or sequence of str, optional
        Target machine format(s); default ``design.machine.format``. With several, every rule runs
        for the first and the rules that read the format (``Rule.per_format``: record limits) for
        each further one.
    rule_settings, model_settings : optional
        Override the thresholds derived from the design.
    ignore : tuple of str
        Rule codes to leave out, e.g. ``("EA102",)`` when the writer splits long legs
        on request (``build --split-long``). Unknown codes are rejected.

    Returns
    -------
    tuple of Finding
        Worst first. Commands that write machine files refuse when any is an error.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> [(f.code, f.severity.value) for f in check_design(analyse(default_design()))]
    [('EA403', 'warning'), ('EA406', 'info')]
    >>> [f.code for f in check_design(analyse(default_design()), ignore=("EA403",))]
    ['EA406']
    """
    design = analysis.design
    skip = {RULES[code].code for code in ignore}
    formats = [format] if format is None or isinstance(format, str) else list(format)
    formats = formats[:1] if rule_settings is not None else formats  # given settings: one check suffices
    settings = [rule_settings or RuleSettings.for_machine(design.machine, format=f) for f in formats]
    found = list(check_without_model(analysis.plan, settings[0])) + list(check_model(analysis, model_settings))
    for rs in settings[1:]:
        found += check_without_model(analysis.plan, rs, rules=PER_FORMAT_RULES)
    return sort_findings(dict.fromkeys(f for f in found if f.code not in skip))
