"""A design checked for several machine formats: every rule once, the format's rules per format.

``check_design(analysis, format=[a, b, ...])`` must find exactly what checking each format on
its own finds (the union), while running the rules that do not read the format only once.
"""
from __future__ import annotations

import pytest

from embroact.patterns.base.findings import RULES
from embroact.patterns.design import design_from_dict
from embroact.predict.analysis import analyse
from embroact.predict.rules import PER_FORMAT_RULES, check_design


def _design(width_mm: float):
    return design_from_dict({"actuator": [{"name": "A", "pattern": "zigzag", "width_mm": width_mm,
                                           "interval_mm": 1.0, "length_mm": 60.0}]})


@pytest.mark.parametrize("width_mm", [7.0, 12.4])
def test_several_formats_find_the_union_of_each_format_alone(width_mm):
    a = analyse(_design(width_mm))
    formats = ["dst", "exp", "pes", "jef"]
    alone = {f for fmt in formats for f in check_design(a, format=fmt)}
    together = check_design(a, format=formats)
    assert set(together) == alone and len(together) == len(alone)
    if width_mm > 12.1:  # a 12.4 mm leg: one record in EXP and JEF (12.7 mm), two in DST (12.1 mm)
        assert any(f.code == "EA102" and "DST" in f.message for f in together)
        assert not any(f.code == "EA102" and "EXP" in f.message for f in together)


def test_the_per_format_rules_are_those_whose_findings_change_with_the_format():
    """Each rule's findings on designs that stress the record limits, format by format: a rule outside
    PER_FORMAT_RULES finds the same in every format."""
    per_format = {r.code for r in PER_FORMAT_RULES}
    assert per_format == {"EA102", "EA501", "EA504"}
    for width_mm in (7.0, 12.4):
        a = analyse(_design(width_mm))
        by_format = {fmt: {(f.code, f.message, f.stitch_index) for f in check_design(a, format=fmt)
                           if f.code not in per_format}
                     for fmt in ("dst", "exp", "pes", "jef", "vp3")}
        assert len({frozenset(v) for v in by_format.values()}) == 1, by_format
    assert all(RULES[c].per_format for c in per_format)
