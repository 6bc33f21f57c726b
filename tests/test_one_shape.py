"""One shape of data: every actuator is a path and a chain of one or more segments.

A single-pattern actuator is a chain of one in the request (``ActuatorSpec.segments``), the
plan (``ActuatorPlan.segments``) and the analysis (``ActuatorAnalysis.segments``), and the
code decides nothing by whether an actuator "has segments": the source is read here (an AST
walk over every module of the package) for a branch whose condition asks something of ``segments``
itself (its truth, length, an item or a property; in ``if``, ``... if ... else ...``, ``while``,
``and``/``or`` and comprehension filters), which may only appear in the chain type itself
(``patterns/chain.py``). A test of the test feeds it modules
with each kind of branch and shows that it finds them.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

from embroact.patterns.centerline import Centerline
from embroact.patterns.design import ActuatorSpec, build_plan, default_design, design_from_dict, design_to_dict
from embroact.patterns.params import CrossParams, ZigzagParams
from embroact.patterns.segments import SegmentSpec
from embroact.predict.analysis import analyse

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("api", "patterns", "predict", "export")
#: The chain type: the one place that decides how a chain of one is shown.
CHAIN_TYPE = ROOT / "patterns" / "chain.py"


def _is_segments(node: ast.AST) -> bool:
    return (isinstance(node, ast.Attribute) and node.attr == "segments") or (isinstance(node, ast.Name)
                                                                              and node.id == "segments")


#: Calls that hand on the segments themselves (their length or a copy): a condition on them is one on the segments.
_AS_IS = {"len", "list", "tuple", "bool", "set", "sorted", "reversed"}


def _decides_on_segments(test: ast.AST) -> bool:
    """True when the condition ``test`` asks something of ``segments`` itself: its truth (``if a.segments``,
    ``a.segments or ...``), its length, a comparison, one of its items or properties (``a.segments.is_single``).

    Going over the segments (``all(s.choice is not None for s in a.segments)``, ``zip(a.segments, ...)``)
    decides nothing about the chain's shape and passes. Keys of plain dicts (a JSON entry's
    ``"segments"``, a design file's ``"segment"`` tables) are the file formats' business, not counted."""
    parents = {child: node for node in ast.walk(test) for child in ast.iter_child_nodes(node)}
    for node in ast.walk(test):
        if not _is_segments(node):
            continue
        up = parents.get(node)
        if isinstance(up, ast.comprehension) and up.iter is node:
            continue
        if isinstance(up, ast.Call) and node in up.args and not (isinstance(up.func, ast.Name) and up.func.id in _AS_IS):
            continue
        return True
    return False


def segment_branches(source: str, filename: str = "<source>") -> list[tuple[int, str]]:
    """``(line, code)`` of every condition in ``source`` that reads ``segments``."""
    tree = ast.parse(source, filename)
    tests: list[ast.AST] = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.If, ast.IfExp, ast.While)):
            tests.append(node.test)
        elif isinstance(node, ast.BoolOp):
            tests += node.values
        elif isinstance(node, ast.comprehension):
            tests += node.ifs
    return sorted((t.lineno, ast.get_source_segment(source, t) or "") for t in tests if _decides_on_segments(t))


def _modules() -> list[Path]:
    return sorted(p for pkg in PACKAGES for p in (ROOT / pkg).rglob("*.py"))


def test_no_branch_on_segments_outside_the_chain_type():
    found = {str(p.relative_to(ROOT)): hits for p in _modules() if p != CHAIN_TYPE
             and (hits := segment_branches(p.read_text(encoding="utf-8"), str(p)))}
    assert len(_modules()) > 100  # the walk sees the package
    assert not found, found


@pytest.mark.parametrize("code", [
    "if act.segments:\n    pass\n",
    "if not spec.segments:\n    pass\n",
    "if len(a.segments) > 1:\n    pass\n",
    "x = 1 if a.segments else 2\n",
    "parts = a.segments or (a,)\n",
    "parts = list(a.segments) or [a]\n",
    "while segments:\n    segments = segments[1:]\n",
    "rows = [r for r in rows if len(a.segments) == 1]\n",
    "def f(a):\n    return (lambda: 1) if a.segments is None else 2\n",
    "if a.segments.is_single:\n    pass\n",
    "if act.segments[1:]:\n    pass\n",
    "ok = bool(x) and len(segments) == 1\n",
])
def test_the_branch_finder_finds_every_kind_of_branch(code):
    assert segment_branches(code), code


def test_the_branch_finder_lets_uses_of_a_chain_pass():
    code = ("for k, seg in enumerate(act.segments):\n    out.append(seg)\n"
            "n = len(act.segments)\nlabel = act.segments.label(0)\n"
            "rows = [s.choice for s in a.segments if s.choice is not None]\n"
            "if all(s.choice is not None for s in act.segments):\n    pass\n"
            "if any(map(bool, zip(a.segments, b))):\n    pass\n")
    assert segment_branches(code) == []


def test_the_chain_type_is_where_the_decision_lives():
    assert segment_branches(CHAIN_TYPE.read_text(encoding="utf-8"))  # it does decide (one place)


def test_every_actuator_is_a_chain_in_request_plan_and_analysis():
    """A single-pattern actuator is a chain of one segment over its whole path, a segmented one a chain of its
    segments; each holds the same kind of values in the same places."""
    d = design_from_dict({"name": "mixed", "actuator": [
        {"name": "Z", "pattern": "zigzag", "width_mm": 7.0, "interval_mm": 1.0, "length_mm": 80.0},
        {"name": "S", "origin_mm": [0.0, 30.0], "segment": [
            {"pattern": "zigzag", "width_mm": 8.0, "interval_mm": 1.0, "length_mm": 40.0},
            {"pattern": "cross", "width_mm": 7.0, "interval_mm": 1.4, "angle_deg": 45.0, "length_mm": 60.0}]}]})
    a = analyse(d)
    for spec, plan, act, n in zip(d.actuators, a.plan.actuators, a.actuators, (1, 2)):
        assert len(spec.segments) == len(plan.segments) == len(act.segments) == n
        assert sum(s.length_mm for s in spec.segments) == pytest.approx(spec.centerline.length_mm)
        assert [s.pattern for s in spec.segments] == [s.pattern for s in plan.segments] \
            == [s.derived.pattern for s in act.segments]
    (z,) = a.plan.actuators[0].segments
    # 81 stations 1 mm apart on the 80 mm path: the legs cover it, 0 to 80 mm, at w = 7 mm
    assert (z.start_mm, z.length_mm, z.first_leg_mm, z.realised.length_mm, z.realised.width_mm) == (0, 80, 0, 80, 7)


def test_a_chain_of_one_is_written_and_read_as_a_plain_actuator():
    """design_to_dict writes a chain of one in the actuator's own table (as design files always had it), and
    a copy with other parameters or another path gets the segment of its new ones."""
    table = design_to_dict(default_design())["actuator"][0]
    assert "segment" not in table and (table["pattern"], table["width_mm"], table["interval_mm"]) == ("zigzag", 7.0, 1.0)
    import dataclasses

    spec = default_design().actuators[0]
    wider = dataclasses.replace(spec, params=ZigzagParams(9.0, 1.0), centerline=Centerline.straight(60.0))
    assert wider.segments == (SegmentSpec(ZigzagParams(9.0, 1.0), 60.0),)
    assert build_plan(dataclasses.replace(default_design(), actuators=(wider,))).actuators[0].realised.width_mm == 9.0
    cross = ActuatorSpec("C", CrossParams(7.0, 1.4, 30.0), Centerline.straight(100.0), adjust="angle")
    assert cross.segments == (SegmentSpec(CrossParams(7.0, 1.4, 30.0), 100.0, adjust="angle"),)


def test_segments_given_as_a_generator_make_the_same_chain():
    """A generator of segments is read once: it was emptied by the emptiness test and then refused as none."""
    segs = (SegmentSpec(ZigzagParams(width_mm=6.0, interval_mm=1.0), 40.0),
            SegmentSpec(CrossParams(width_mm=7.0, interval_mm=1.4, angle_deg=45.0), 60.0))
    cl = Centerline.straight(100.0)
    given = ActuatorSpec("S", segs[0].params, cl, segments=(s for s in segs))
    assert given == ActuatorSpec("S", segs[0].params, cl, segments=segs) and tuple(given.segments) == segs
