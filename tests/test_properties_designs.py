"""Property tests of design files: random valid designs build; random mutations fail cleanly.

Valid designs (tests/strategies.py ``design_dicts``) build with ``build_plan``, keep every
needle point outside their own tube corridor, have one stop and one trim per actuator,
and survive the TOML round trip. Mutations of a valid design (wrong types, missing keys,
extra keys, huge/tiny/NaN/inf numbers, unicode names, duplicate actuator names) either
still describe a valid design or give exactly one one-line ``DesignFileError`` that
starts with the key path, never another exception type; through the command line they
give exit code 2 and one line on stderr, never a traceback.
"""
from __future__ import annotations

import contextlib
import copy
import io
import json
import math

import numpy as np
import shapely
from hypothesis import given, note, strategies as st

from strategies import budget, design_dicts
from embroact.export.cli.main import main
from embroact.export.files.designfile import dumps_design, loads_design
from embroact.patterns.design import build_plan, design_from_dict
from embroact.patterns.base.errors import DesignFileError, EmbroactError
from embroact.patterns.plan import Command

#: Replacement values of the "wrong type" mutation.
WRONG_TYPES = ("7", "seven", [1, 2], {"x": 1}, True, [], "")
#: Replacement values of the "bad number" mutation.
BAD_NUMBERS = (1e308, -1e308, 1e-308, 5e-324, 0.0, -0.0, 2**63, 10**30, -(2**31), math.nan, math.inf, -math.inf)
#: Names users type: accents, CJK, emoji, right-to-left, whitespace, quotes, TOML/SVG metacharacters.
NAMES = ("Aktor-ü", "执行器", "🦾 arm", "שריר", "  ", "a\"b'c", "x = 1", "[[actuator]]", "\\", "A" * 300, "é\u0301")


def _leaves(d, path=()):
    """(path, value) of every leaf of a nested dict/list value."""
    if isinstance(d, dict):
        for k, v in d.items():
            yield from _leaves(v, path + (k,))
    elif isinstance(d, list) and d and isinstance(d[0], (dict, list)):
        for i, v in enumerate(d):
            yield from _leaves(v, path + (i,))
    else:
        yield path, d


def _set(d, path, value):
    for k in path[:-1]:
        d = d[k]
    d[path[-1]] = value


def _delete(d, path):
    for k in path[:-1]:
        d = d[k]
    del d[path[-1]]


@st.composite
def mutated_designs(draw):
    """(kind, where, dict): a valid design with one mutation."""
    d = draw(design_dicts())
    m = copy.deepcopy(d)
    kind = draw(st.sampled_from(("wrong_type", "missing", "extra", "bad_number", "unicode_name", "duplicate")))
    leaves = [p for p, _ in _leaves(m)]
    if kind == "wrong_type":
        where = draw(st.sampled_from(leaves))
        _set(m, where, draw(st.sampled_from(WRONG_TYPES)))
    elif kind == "missing":
        tables = [("actuator", i) for i in range(len(m["actuator"]))] + [(k,) for k in ("tube", "machine") if k in m]
        table = draw(st.sampled_from(tables))
        t = m
        for k in table:
            t = t[k]
        key = draw(st.sampled_from(sorted(t)))
        where = table + (key,)
        _delete(m, where)
    elif kind == "extra":
        tables = [()] + [("actuator", i) for i in range(len(m["actuator"]))]
        where = draw(st.sampled_from(tables)) + (draw(st.sampled_from(("widht_mm", "colour", "Name", "länge_mm"))),)
        _set(m, where, 1.0)
    elif kind == "bad_number":
        numeric = [p for p, v in _leaves(m) if isinstance(v, (int, float)) and not isinstance(v, bool)]
        where = draw(st.sampled_from(numeric))
        _set(m, where, draw(st.sampled_from(BAD_NUMBERS)))
    elif kind == "unicode_name":
        where = draw(st.sampled_from([("name",)] + [("actuator", i, "name") for i in range(len(m["actuator"]))]))
        _set(m, where, draw(st.sampled_from(NAMES)))
    else:
        m["actuator"].append(copy.deepcopy(m["actuator"][0]))
        m["actuator"][-1]["origin_mm"] = [0.0, 40.0 * len(m["actuator"])]
        where = ("actuator", len(m["actuator"]) - 1, "name")
    return kind, where, m


def _toml_value(v) -> str:
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v == math.inf else "-inf" if v == -math.inf else repr(v))
    if isinstance(v, int):
        return str(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    return "{" + ", ".join(f"{json.dumps(k, ensure_ascii=False)} = {_toml_value(x)}" for k, x in v.items()) + "}"


def _toml(d: dict) -> str:
    """TOML text of a design dict, written here (inline tables) independently of designfile.dumps_design."""
    return "".join(f"{json.dumps(k, ensure_ascii=False)} = {_toml_value(v)}\n" for k, v in d.items())


def _one_line(text: str) -> None:
    assert text and "\n" not in text.strip() and "Traceback" not in text, text


# ------------------------------------------------------------------------------ valid designs
@budget(1.0)
@given(design_dicts())
def test_random_valid_designs_build(d):
    note(json.dumps(d, ensure_ascii=False))
    design = design_from_dict(d)
    plan = build_plan(design)
    n = len(d["actuator"])
    assert [a.name for a in plan.actuators] == [a["name"] for a in d["actuator"]]
    assert plan.count(Command.STOP) == n and plan.count(Command.TRIM) == n and plan.count(Command.END) == 1
    assert plan.commands[-1] == Command.END and np.all(np.isfinite(plan.xy_mm))
    for k, a in enumerate(plan.actuators):
        pts = plan.xy_mm[(plan.commands == Command.STITCH) & (plan.actuator == k)]
        dist = shapely.distance(a.centerline.as_linestring(), shapely.points(pts))
        assert dist.min() >= a.tube.corridor_radius_mm - 1e-9, (a.name, dist.min())
    assert loads_design(dumps_design(design)) == design
    assert design_from_dict(__import__("tomllib").loads(_toml(d))) == design  # the test's own TOML writer


# ------------------------------------------------------------------------------ mutations
@budget(3.0)
@given(mutated_designs())
def test_mutated_designs_fail_with_one_clear_line(case):
    kind, where, d = case
    note(f"{kind} at {where}: {json.dumps(d, ensure_ascii=False, default=str)}")
    try:
        design = design_from_dict(d)
    except DesignFileError as exc:
        msg = str(exc)
        _one_line(msg)
        key = ".".join(str(k) for k in where if not isinstance(k, int))
        if kind == "missing":
            assert "missing key" in msg or "give exactly one of length_mm" in msg or "must be" in msg, msg
        elif kind == "extra":
            assert f"{where[-1]}: unknown key; allowed:" in msg, msg
        elif kind == "duplicate":
            assert f"actuator[{where[1]}].name: duplicate actuator name" in msg, msg
        elif kind == "bad_number" and isinstance(d_get(d, where), float) and not math.isfinite(d_get(d, where)):
            assert "finite" in msg, msg
        assert key.split(".")[-1] in msg or kind in ("missing", "duplicate") or "actuator" in msg, (key, msg)
        return
    except Exception as exc:  # noqa: BLE001 - the property: no other exception type escapes
        raise AssertionError(f"{type(exc).__name__} escaped design_from_dict: {exc}") from exc
    # accepted: it must still describe a buildable design, or fail with one EmbroactError line
    assert kind not in ("extra", "duplicate"), "an unknown key or a duplicate name was accepted"
    try:
        build_plan(design)
    except EmbroactError as exc:
        _one_line(str(exc))


def d_get(d, path):
    for k in path:
        d = d[k]
    return d


@budget(1.0)
@given(mutated_designs())
def test_mutated_design_files_on_the_command_line(tmp_path_factory, case):
    kind, where, d = case
    note(f"{kind} at {where}")
    path = tmp_path_factory.mktemp("design") / "d.toml"
    path.write_text(_toml(d), encoding="utf-8")
    err, out = io.StringIO(), io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        code = main(["check", str(path), "--json"])
    assert code in (0, 1, 2), code
    if code == 2:
        _one_line(err.getvalue())
        assert err.getvalue().startswith("embroact: error: ")
    else:
        assert json.loads(out.getvalue())["kind"] == "design" and err.getvalue() == ""
