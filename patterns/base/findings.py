"""Design-rule findings and the registry where every rule embroact checks is declared.

A :class:`Rule` is declared once, next to the function that checks it, with
:meth:`RuleRegistry.rule`: code, severity, title, description, default fix, the
inputs it applies to (:class:`Inputs`) and the check function. A :class:`Finding`
is one problem a rule found: the code, severity and title of its rule, a message
with the numbers, the place (actuator name, stitch index, coordinates in mm) and a
suggested fix.

Every rule registers in :data:`RULES` when the module that declares it is
imported: ``embroact.patterns.rules`` (geometry, stitches, tubes, machine-file
structure), ``embroact.predict.sleeve_rules`` (sleeve geometry) and the model
rules below. ``embroact.predict.rule_catalogue.all_rules`` imports all of them,
for the ``embroact check --rules`` listing and the README table.

Code groups
-----------
``EA1xx`` needle points and stitches, ``EA2xx`` pattern and sleeve,
``EA3xx`` tube path and placement, ``EA4xx`` model predictions,
``EA5xx`` machine-file structure.

Examples
--------
>>> from embroact.patterns.base.findings import RuleRegistry, Inputs, Severity
>>> reg = RuleRegistry()
>>> @reg.rule("EA999", Severity.WARNING, "demo rule", "What is checked.", "How to fix it.", Inputs.DESIGNS)
... def demo(subject):
...     return [reg.finding("EA999", "found one", stitch_index=7, xy_mm=(1.0, 0.4))]
>>> f, = demo.check(None)
>>> f.severity is Severity.WARNING, f.title, f.stitch_index, f.as_dict()["xy_mm"]
(True, 'demo rule', 7, [1.0, 0.4])
>>> demo.inputs_label, reg["EA999"] is demo
('designs', True)
"""
from __future__ import annotations

from dataclasses import dataclass
from enum import Enum, Flag
from typing import Callable, Iterator

from .errors import ParameterError

__all__ = [
    "SUMMARY_NAMES",
    "summary_line",
    "Severity",
    "Inputs",
    "Rule",
    "Finding",
    "RuleRegistry",
    "RULES",
    "rules_table_markdown",
    "count_by_severity",
    "finding_place",
    "finding_line",
]


class Severity(str, Enum):
    """How bad a finding is: errors stop ``build`` (unless ``--force``), warnings and info do not.

    Examples
    --------
    >>> sorted([Severity.INFO, Severity.ERROR], key=lambda s: s.rank)
    [<Severity.ERROR: 'error'>, <Severity.INFO: 'info'>]
    """

    ERROR = "error"
    WARNING = "warning"
    INFO = "info"

    @property
    def rank(self) -> int:
        """0 for error, 1 for warning, 2 for info (sort key: worst first)."""
        return ("error", "warning", "info").index(self.value)


class Inputs(Flag):
    """What a rule is checked on.

    ``DESIGNS``: embroact designs (their stitch plans); ``FILES``: embroidery files
    read back (records and the tubes given with them); ``MODEL``: designs, through
    the deformation model (``embroact.predict``). A rule for ``DESIGNS`` only reads
    what a plan has and a file has not (requested parameters, the pattern kind).

    Examples
    --------
    >>> (Inputs.DESIGNS | Inputs.FILES).label, Inputs.MODEL.label
    ('designs, files', 'designs (model)')
    """

    DESIGNS = 1
    FILES = 2
    MODEL = 4

    @property
    def label(self) -> str:
        """``"designs, files"``, ``"designs"`` or ``"designs (model)"`` (the README's column)."""
        if Inputs.MODEL in self:
            return "designs (model)"
        return ", ".join(n for n, f in (("designs", Inputs.DESIGNS), ("files", Inputs.FILES)) if f in self)


@dataclass(frozen=True, slots=True)
class Rule:
    """One design rule: its documentation and the function that checks it.

    Attributes
    ----------
    code : str
        Stable identifier, ``EA`` and three digits.
    severity : Severity
        How bad its findings are.
    title : str
        A few words, lower case.
    description : str
        What is checked and why it matters, with the threshold.
    fix : str
        Default suggested fix (a finding may give a more specific one).
    inputs : Inputs
        What the rule is checked on.
    check : callable or None
        ``check(subject) -> findings`` for the rule engine of ``embroact.patterns.rules``;
        None for the model rules, which ``embroact.predict.rules`` checks together from
        one curve per actuator.
    per_format : bool
        The check reads the target machine format (its record limits): a design written in
        several formats is checked once, and these rules again for each further format.

    Examples
    --------
    >>> rule = Rule("EA999", Severity.INFO, "demo", "What is checked.", "How to fix it.", Inputs.FILES)
    >>> rule.inputs_label, rule.check is None
    ('files', True)
    """

    code: str
    severity: Severity
    title: str
    description: str
    fix: str
    inputs: Inputs
    check: Callable | None = None
    per_format: bool = False

    @property
    def inputs_label(self) -> str:
        """Where the rule runs, as the README lists it."""
        return self.inputs.label


@dataclass(frozen=True, slots=True)
class Finding:
    """One problem found by a design rule.

    Attributes
    ----------
    code : str
        Rule code (see :data:`RULES`).
    severity : Severity
        Its rule's severity.
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
    title : str
        The rule's title.
    count : int
        How many findings this one stands for: 1, or for the finding that closes a capped
        rule ("N more findings of this rule"), N. Summaries count findings by it, so they
        count every finding, shown or not.
    needle_point : int or None
        Embroidery files: the needle point at the record (counted from 0), or the last one
        before it when the record is no needle record (``at_needle`` False); the same place
        has the same number in every format, whatever records the format adds.
    at_needle : bool
        The record is the needle point ``needle_point``.

    Examples
    --------
    >>> f = Finding("EA999", Severity.WARNING, "leg too long", actuator="A1", stitch_index=3)
    >>> f.place(), f.count
    ('A1, stitch 3', 1)
    """

    code: str
    severity: Severity
    message: str
    actuator: str | None = None
    stitch_index: int | None = None
    xy_mm: tuple[float, float] | None = None
    fix: str = ""
    title: str = ""
    count: int = 1
    needle_point: int | None = None
    at_needle: bool = True

    @property
    def is_error(self) -> bool:
        """True for severity error."""
        return self.severity is Severity.ERROR

    def place(self) -> str:
        """Short human-readable place: ``"A1, stitch 57 at (12.30, 4.50) mm"``.

        Returns
        -------
        str
            Actuator, record (or needle point) and coordinates, as far as known; ``"design"`` if none is.

        Examples
        --------
        >>> Finding("EA999", Severity.INFO, "m", actuator="A1", stitch_index=57, xy_mm=(12.3, 4.5)).place()
        'A1, stitch 57 at (12.30, 4.50) mm'
        >>> Finding("EA999", Severity.INFO, "m", stitch_index=9, needle_point=4, at_needle=False).place()
        'record 9, after needle point 4'
        """
        return finding_place(self)

    def as_dict(self) -> dict:
        """Plain dict for JSON (``xy_mm`` as a list or None).

        Returns
        -------
        dict
            Code, severity, title, message, actuator, stitch_index, xy_mm, fix, count and place
            (:meth:`place`, as ``embroact check`` prints it), and ``needle_point``/``at_needle`` for
            findings on embroidery files.

        Examples
        --------
        >>> d = Finding("EA999", Severity.ERROR, "m", xy_mm=(1.0, 2.0)).as_dict()
        >>> d["severity"], d["xy_mm"], "needle_point" in d
        ('error', [1.0, 2.0], False)
        """
        return {
            "code": self.code,
            "severity": self.severity.value,
            "title": self.title,
            "message": self.message,
            "actuator": self.actuator,
            "stitch_index": self.stitch_index,
            "xy_mm": None if self.xy_mm is None else [self.xy_mm[0], self.xy_mm[1]],
            "fix": self.fix,
            "count": self.count,
            "place": self.place(),
            **({} if self.needle_point is None else {"needle_point": self.needle_point, "at_needle": self.at_needle}),
        }


class RuleRegistry:
    """Every declared rule, keyed by code; iterates in code order.

    Rules are added by :meth:`rule` (a decorator on the check function) or
    :meth:`declare`; a code is declared once.

    Parameters
    ----------
    load_on_miss : tuple of str
        Modules declaring rules, imported (once) when a code is looked up that is not
        declared yet, before the lookup fails: a lookup never depends on what else the
        process happened to import.

    Examples
    --------
    >>> reg = RuleRegistry()
    >>> reg.declare(Rule("EA998", Severity.INFO, "demo", "What.", "Fix.", Inputs.DESIGNS)).code
    'EA998'
    >>> len(reg), "EA998" in reg, [r.code for r in reg]
    (1, True, ['EA998'])
    """

    __slots__ = ("_rules", "_load_on_miss")

    def __init__(self, load_on_miss: tuple[str, ...] = ()) -> None:
        self._rules: dict[str, Rule] = {}
        self._load_on_miss = tuple(load_on_miss)

    def _load(self) -> bool:
        """Import the declaring modules not imported yet; True when there were any."""
        import importlib

        pending, self._load_on_miss = self._load_on_miss, ()
        for name in pending:
            importlib.import_module(name)
        return bool(pending)

    def declare(self, rule: Rule) -> Rule:
        """Add ``rule``; a second, different declaration of its code is refused.

        Parameters
        ----------
        rule : Rule
            The rule to add.

        Returns
        -------
        Rule
            ``rule`` itself.

        Raises
        ------
        ParameterError
            Another rule holds its code already.

        Examples
        --------
        >>> reg = RuleRegistry()
        >>> _ = reg.declare(Rule("EA998", Severity.INFO, "demo", "What.", "Fix.", Inputs.DESIGNS))
        >>> try:
        ...     reg.declare(Rule("EA998", Severity.INFO, "other", "What.", "Fix.", Inputs.DESIGNS))
        ... except ValueError as exc:
        ...     print(exc)
        rule EA998 is declared twice ('demo' and 'other')
        """
        old = self._rules.get(rule.code)
        same = old is not None and old.check is not None and rule.check is not None and (
            old.check.__module__, old.check.__qualname__) == (rule.check.__module__, rule.check.__qualname__)
        if old is not None and not same:
            raise ParameterError(f"rule {rule.code} is declared twice ({old.title!r} and {rule.title!r})")
        self._rules[rule.code] = rule
        return rule

    def rule(self, code: str, severity: Severity, title: str, description: str, fix: str,
             inputs: Inputs, *, per_format: bool = False) -> Callable[[Callable], Rule]:
        """Decorator: declare rule ``code`` checked by the decorated function.

        Parameters
        ----------
        code, severity, title, description, fix, inputs, per_format
            The :class:`Rule`'s fields.

        Returns
        -------
        callable
            The decorator; it returns the declared :class:`Rule` in place of the function.

        Examples
        --------
        >>> reg = RuleRegistry()
        >>> @reg.rule("EA997", Severity.ERROR, "demo", "What.", "Fix.", Inputs.FILES)
        ... def demo(subject):
        ...     return []
        >>> demo.code, demo.check(None)
        ('EA997', [])
        """

        def register(check: Callable) -> Rule:
            return self.declare(Rule(code, severity, title, description, fix, inputs, check, per_format))

        return register

    def __iter__(self) -> Iterator[Rule]:
        return iter(sorted(self._rules.values(), key=lambda r: r.code))

    def __len__(self) -> int:
        return len(self._rules)

    def __contains__(self, code: object) -> bool:
        return code in self._rules or (self._load() and code in self._rules)

    def __getitem__(self, code: str) -> Rule:
        try:
            return self._rules[code]
        except KeyError:
            if self._load() and code in self._rules:
                return self._rules[code]
            raise ParameterError(
                f"rule code must be one of {', '.join(r.code for r in self)}, got {code!r}") from None

    def finding(
        self,
        code: str,
        message: str,
        *,
        actuator: str | None = None,
        stitch_index: int | None = None,
        xy_mm=None,
        fix: str | None = None,
        count: int = 1,
    ) -> Finding:
        """A :class:`Finding` of rule ``code`` with the rule's severity, title and default fix.

        Parameters
        ----------
        code : str
            A declared rule's code.
        message : str
            What is wrong, with the numbers.
        actuator, stitch_index, xy_mm, count
            Where, and how many findings it stands for (see :class:`Finding`).
        fix : str or None, optional
            A fix for this finding; None: the rule's default.

        Returns
        -------
        Finding

        Examples
        --------
        >>> reg = RuleRegistry()
        >>> _ = reg.declare(Rule("EA998", Severity.WARNING, "demo", "What.", "Fix it.", Inputs.DESIGNS))
        >>> f = reg.finding("EA998", "found", xy_mm=(1.23456, 2.0))
        >>> f.severity.value, f.fix, f.xy_mm
        ('warning', 'Fix it.', (1.2346, 2.0))
        """
        rule = self[code]
        return Finding(
            code=code,
            severity=rule.severity,
            message=message,
            actuator=actuator,
            stitch_index=None if stitch_index is None else int(stitch_index),
            xy_mm=None if xy_mm is None else (round(float(xy_mm[0]), 4), round(float(xy_mm[1]), 4)),
            fix=rule.fix if fix is None else fix,
            title=rule.title,
            count=int(count),
        )

    def markdown_table(self) -> str:
        """The README table: code, severity, title, what is checked, where it runs.

        Returns
        -------
        str
            Markdown, one row per rule in code order, ending in a newline.

        Examples
        --------
        >>> reg = RuleRegistry()
        >>> _ = reg.declare(Rule("EA998", Severity.INFO, "demo", "What | why.", "Fix.", Inputs.DESIGNS))
        >>> print(reg.markdown_table().splitlines()[2])
        | EA998 | info | demo | What \\| why. | designs |
        """
        lines = ["| code | severity | rule | what is checked | checks |", "|---|---|---|---|---|"]
        cells = [(r.code, r.severity.value, r.title, r.description, r.inputs_label) for r in self]
        lines += ["| " + " | ".join(c.replace("|", "\\|") for c in row) + " |" for row in cells]
        return "\n".join(lines) + "\n"


RULES = RuleRegistry(load_on_miss=(__package__.rpartition(".")[0] + ".rules",))
"""The registry of every rule embroact declares (filled as the declaring modules are imported).

A lookup of a code not declared yet imports ``embroact.patterns.rules`` (the geometric
rules, this layer's) first; the sleeve and model rules are declared by the
``embroact.predict`` modules that check them, imported wherever their findings are made.
"""



def _field(finding, name: str, default=None):
    """``finding.name`` of a :class:`Finding`, ``finding[name]`` of its ``as_dict()`` (``default`` if absent)."""
    if isinstance(finding, Finding):
        return getattr(finding, name)
    value = finding.get(name, default)
    return default if value is None and default is not None else value


def finding_place(finding) -> str:
    """Where ``finding`` is, as ``embroact check`` prints it: ``"A1, stitch 57 at (12.30, 4.50) mm"``.

    Parameters
    ----------
    finding : Finding or mapping
        A finding or its :meth:`Finding.as_dict` (the worksheet's and the report's entries).

    Returns
    -------
    str
        Actuator, record (or needle point) and coordinates, as far as known; ``"design"`` if none is.

    Examples
    --------
    >>> finding_place({"code": "EA101", "actuator": "A1", "stitch_index": 12, "xy_mm": [3.0, -1.25]})
    'A1, stitch 12 at (3.00, -1.25) mm'
    >>> finding_place({"code": "EA501", "stitch_index": 9, "needle_point": 4, "at_needle": True})
    'needle point 4 (record 9)'
    >>> finding_place({"code": "EA406"})
    'design'
    """
    parts = []
    actuator = _field(finding, "actuator")
    if actuator is not None:
        parts.append(str(actuator))
    n, r = _field(finding, "needle_point"), _field(finding, "stitch_index")
    if r is not None and n is None:
        parts.append(f"stitch {r}")
    elif r is not None and n is not None:
        parts.append(f"needle point {n} (record {r})" if _field(finding, "at_needle", True) else
                     f"record {r}, before the first needle point" if n < 0 else
                     f"record {r}, after needle point {n}")
    where = ", ".join(parts)
    xy = _field(finding, "xy_mm")
    if xy is not None:
        where += f"{' ' if where else ''}at ({float(xy[0]):.2f}, {float(xy[1]):.2f}) mm"
    return where or "design"


def finding_line(finding) -> str:
    """One line for ``finding``: severity, code, message and its place (:func:`finding_place`) in brackets.

    Parameters
    ----------
    finding : Finding or mapping
        A finding or its :meth:`Finding.as_dict`.

    Returns
    -------
    str
        ``"error EA101: needle in the tube [A1, stitch 12 at (3.00, -1.25) mm]"``.

    Examples
    --------
    >>> finding_line(Finding("EA101", Severity.ERROR, "needle in the tube", actuator="A1", stitch_index=12,
    ...                      xy_mm=(3.0, -1.25)))
    'error EA101: needle in the tube [A1, stitch 12 at (3.00, -1.25) mm]'
    """
    severity = _field(finding, "severity", "")
    severity = getattr(severity, "value", severity)
    return f"{severity} {_field(finding, 'code', '')}: {_field(finding, 'message', '')} [{finding_place(finding)}]"


def rules_table_markdown(rules=RULES) -> str:
    """The Markdown table of ``rules`` (default: every rule declared so far).

    Parameters
    ----------
    rules : RuleRegistry, optional
        The rules to list.

    Returns
    -------
    str
        See :meth:`RuleRegistry.markdown_table`.

    Examples
    --------
    >>> import embroact.patterns.rules  # declares the geometric rules
    >>> print(rules_table_markdown().splitlines()[2])  # doctest: +ELLIPSIS
    | EA... | ...
    """
    return rules.markdown_table()


def count_by_severity(findings) -> dict[str, int]:
    """``{"error": n, "warning": n, "info": n}`` for a sequence of findings, each counted by its ``count``
    (a capped rule's closing finding stands for the findings it does not list).

    Parameters
    ----------
    findings : iterable of Finding
        The findings to count.

    Returns
    -------
    dict of str to int
        Every severity, in order, with its count (0 included).

    Examples
    --------
    >>> count_by_severity([RULES.finding("EA101", "needle in the tube")])
    {'error': 1, 'warning': 0, 'info': 0}
    """
    counts = {s.value: 0 for s in Severity}
    for f in findings:
        counts[f.severity.value] += f.count
    return counts


#: Actuators the summary line names per rule code (the rest are counted: the line stays one line).
SUMMARY_NAMES = 5


def summary_line(findings) -> str:
    """One line: counts of all findings by severity, and the codes with their actuators.

    Parameters
    ----------
    findings : sequence of Finding
        The findings to summarise.

    Returns
    -------
    str
        ``"N errors, N warnings, N info"``, then the codes in order, each with at most
        :data:`SUMMARY_NAMES` actuator names.

    Examples
    --------
    >>> import embroact.patterns.rules  # declares the geometric rules
    >>> fs = [RULES.finding("EA105", "x", actuator="A1"), RULES.finding("EA105", "y", actuator="A2"),
    ...       RULES.finding("EA304", "z", actuator="A1")]
    >>> summary_line(fs)
    '0 errors, 3 warnings, 0 info: EA105 (A1, A2), EA304 (A1)'
    >>> summary_line([RULES.finding("EA105", "x", actuator=f"A{k}") for k in range(1000)])
    '0 errors, 1000 warnings, 0 info: EA105 (A0, A1, A2, A3, A4 and 995 more)'
    """
    counts = count_by_severity(findings)
    by_code: dict[str, dict[str, None]] = {}
    for f in findings:
        names = by_code.setdefault(f.code, {})
        if f.actuator is not None:
            names[f.actuator] = None

    def named(names) -> str:
        shown = ", ".join(list(names)[:SUMMARY_NAMES])
        return shown if len(names) <= SUMMARY_NAMES else f"{shown} and {len(names) - SUMMARY_NAMES} more"

    codes = ", ".join(f"{c} ({named(n)})" if n else c for c, n in sorted(by_code.items()))
    n_err, n_warn = counts["error"], counts["warning"]
    head = (f"{n_err} error{'s' if n_err != 1 else ''}, {n_warn} warning{'s' if n_warn != 1 else ''}, "
            f"{counts['info']} info")  # spelled as check's header
    return f"{head}: {codes}" if codes else head
