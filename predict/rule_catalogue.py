"""The catalogue of every design rule: what ``embroact check --rules`` and the README list.

Rules register in :data:`embroact.patterns.base.findings.RULES` when the module
declaring them is imported; :func:`all_rules` imports every such module first, so
the listing never depends on what else a process happened to load.

Examples
--------
>>> from embroact.predict.rule_catalogue import all_rules, rules_table
>>> codes = [r.code for r in all_rules()]
>>> codes[0], "EA201" in codes, "EA307" in codes, "EA401" in codes
('EA101', True, True, True)
>>> rules_table().splitlines()[0]
'| code | severity | rule | what is checked | checks |'
"""
from __future__ import annotations

__all__ = ["all_rules", "rules_table"]


def all_rules() -> tuple:
    """Every declared rule (geometry, sleeve, model), in code order.

    Returns
    -------
    tuple of Rule

    Examples
    --------
    >>> codes = [r.code for r in all_rules()]
    >>> codes[0], codes == sorted(codes)
    ('EA101', True)
    """
    from ..patterns import rules as _geometry  # noqa: F401  (imports declare the rules)
    from ..patterns.base.findings import RULES
    from . import rules as _model, sleeve_rules as _sleeve  # noqa: F401

    return tuple(RULES)


def rules_table() -> str:
    """The Markdown table of every rule (README's "Design rules" section, ``embroact check --rules``).

    Returns
    -------
    str
        Markdown, a header row and one row per rule.

    Examples
    --------
    >>> rules_table().splitlines()[0]
    '| code | severity | rule | what is checked | checks |'
    """
    from ..patterns.base.findings import rules_table_markdown

    all_rules()
    return rules_table_markdown()
