"""Designs: strict dict validation, plan concatenation, TOML files and the shipped examples."""
import math
from pathlib import Path

import numpy as np
import pytest

from embroact.export.files.designfile import dumps_design, load_design, loads_design, save_design
from embroact.patterns.centerline import Centerline
from embroact.patterns.design import (
    ActuatorSpec,
    Design,
    MachineSettings,
    OperationSettings,
    build_plan,
    default_design,
    design_from_dict,
    design_to_dict,
    join_plans,
)
from embroact.patterns.base.errors import DesignFileError, ParameterError, PatternError
from embroact.patterns.params import Tube, ZigzagParams
from embroact.patterns.plan import Command, Role

from h1_checks import assert_outside_corridor

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _act(**kw):
    a = {"name": "A", "pattern": "zigzag", "width_mm": 7.0, "interval_mm": 1.0, "length_mm": 50.0}
    a.update(kw)
    return {k: v for k, v in a.items() if v is not None}


def _err(d) -> str:
    with pytest.raises(DesignFileError) as exc:
        design_from_dict(d)
    msg = str(exc.value)
    assert "\n" not in msg
    return msg


# ---------------------------------------------------------------------- defaults and examples
def test_default_design_is_the_papers_zigzag():
    d = default_design()
    (a,) = d.actuators
    assert a.params == ZigzagParams(width_mm=7.0, interval_mm=1.0)
    assert a.centerline.length_mm == 100.0
    assert d.tube == Tube(outer_radius_mm=1.5, inner_radius_mm=1.0, g_e_mpa=0.13)
    assert d.machine == MachineSettings() and d.machine.format == "dst"
    assert d.operation == OperationSettings(max_pressure_kpa=300.0, max_bend_deg=180.0)


def test_paper_zigzag_example_equals_default_design():
    assert load_design(EXAMPLES / "paper_zigzag.toml") == default_design()


@pytest.mark.parametrize("name", ["paper_zigzag", "paper_cross", "three_actuators", "curved"])
def test_examples_build(name):
    design = load_design(EXAMPLES / f"{name}.toml")
    plan = build_plan(design)
    n = len(design.actuators)
    assert plan.count(Command.STOP) == n and plan.count(Command.TRIM) == n and plan.count(Command.END) == 1
    assert plan.commands[-1] == Command.END and plan.actuator[-1] == -1
    assert [a.name for a in plan.actuators] == [a.name for a in design.actuators]
    assert_outside_corridor(plan)
    xmin, ymin, xmax, ymax = plan.bounds_mm()
    assert xmax - xmin <= design.machine.hoop_width_mm and ymax - ymin <= design.machine.hoop_height_mm


def test_paper_cross_example_is_exact():
    a = build_plan(load_design(EXAMPLES / "paper_cross.toml")).actuators[0]
    assert a.adjustments == () and a.realised.passes == 10


def test_three_actuators_mixed_patterns_unicode_name():
    d = load_design(EXAMPLES / "three_actuators.toml")
    assert [a.pattern for a in d.actuators] == ["zigzag", "zigzag", "cross"]
    assert d.actuators[2].name == "cross 45°"


def test_curved_example_is_an_s_curve_above_the_radius_limit():
    c = load_design(EXAMPLES / "curved.toml").actuators[0].centerline
    k = c.curvature_at(np.linspace(0, c.length_mm, 200))
    assert k.max() > 0 > k.min()  # turns both ways
    assert c.min_radius_mm() > 35.0


# ---------------------------------------------------------------------- build_plan / join_plans
def test_build_plan_joins_with_jumps():
    d = design_from_dict({"name": "two", "actuator": [
        _act(name="A1"), _act(name="A2", origin_mm=[0.0, 40.0], pattern="cross", angle_deg=45.0, interval_mm=1.4)]})
    plan = build_plan(d)
    stops = np.flatnonzero(plan.commands == Command.STOP)
    jumps = np.flatnonzero(plan.commands == Command.JUMP)
    trims = np.flatnonzero(plan.commands == Command.TRIM)
    assert len(stops) == 2 and len(trims) == 2 and stops[0] == 0
    # the jumps run from the first actuator's TRIM to the second one's STOP, contiguous
    np.testing.assert_array_equal(jumps, np.arange(trims[0] + 1, stops[1]))
    assert np.all(plan.roles[jumps] == Role.TRAVEL) and np.all(plan.actuator[jumps] == 1)
    np.testing.assert_allclose(plan.xy_mm[jumps[-1]], plan.xy_mm[stops[1]])
    steps = np.abs(np.diff(plan.xy_mm[np.r_[trims[0], jumps]], axis=0))
    assert steps.max() <= 12.1 - 0.1 + 1e-9
    # distance trim -> stop is about 43 mm in y: ceil(43 / 12) = 4 jumps
    assert len(jumps) == math.ceil(np.abs(plan.xy_mm[stops[1]] - plan.xy_mm[trims[0]]).max() / 12.0)
    assert plan.actuator[: trims[0] + 1].tolist() == [0] * (trims[0] + 1)
    assert np.all(plan.actuator[stops[1] : -1] == 1)
    assert plan.select(1).count(Command.STOP) == 1


def test_join_plans_keeps_single_plan_and_rejects_empty():
    p = build_plan(default_design())
    assert join_plans([p], name=p.name) == p
    with pytest.raises(ParameterError, match="at least one plan"):
        join_plans([])


def test_generation_errors_name_the_actuator():
    d = design_from_dict({"actuator": [_act(name="short one", length_mm=1.0)]})
    with pytest.raises(PatternError, match="^actuator 'short one': path length_mm must be >= 2"):
        build_plan(d)


def test_placement_straight_and_path():
    d = design_from_dict({"actuator": [
        _act(name="s", origin_mm=[10.0, 20.0], rotation_deg=90.0),
        _act(name="p", length_mm=None, path=[[0, 0], [30, 0]], origin_mm=[5.0, 5.0], rotation_deg=180.0),
        _act(name="svg", length_mm=None, path="M 0 0 L 30 0", rotation_deg=-90.0)]})
    np.testing.assert_allclose(d.actuators[0].centerline.points_mm, [[10, 20], [10, 70]], atol=1e-12)
    np.testing.assert_allclose(d.actuators[1].centerline.points_mm, [[5, 5], [-25, 5]], atol=1e-12)
    np.testing.assert_allclose(d.actuators[2].centerline.points_mm, [[0, 0], [0, -30]], atol=1e-12)


# ---------------------------------------------------------------------- strict validation
@pytest.mark.parametrize(
    "d, fragment",
    [
        ({"actuator": [_act(), _act(name="B", widht_mm=7.0)]},
         "actuator[1].widht_mm: unknown key; allowed: name, pattern, width_mm, interval_mm, angle_deg, adjust, "
         "length_mm, path, origin_mm, rotation_deg, tie_stitch_mm, tie_count, model"),
        ({"colour": "red", "actuator": [_act()]},
         "colour: unknown key; allowed: name, tube, machine, operation, actuator"),
        ({"tube": {"radius_mm": 1.5}, "actuator": [_act()]},
         "tube.radius_mm: unknown key; allowed: outer_radius_mm, inner_radius_mm, g_e_mpa, clearance_mm, end_margin_mm"),
        ({"actuator": [_act(model={"G": 2.0})]}, "actuator[0].model.G: unknown key; allowed: g_mpa, p0_kpa, calibration"),
        ({"name": "x"}, "actuator: missing key"),
        ({"actuator": [_act(interval_mm=None)]}, "actuator[0].interval_mm: missing key"),
        ({"actuator": [_act(pattern="cross")]}, "actuator[0].angle_deg: missing key"),
        ({"actuator": [_act(angle_deg=45.0)]}, "actuator[0].angle_deg: only allowed with pattern 'cross'"),
        ({"actuator": [_act(adjust="angle")]}, "actuator[0].adjust: only allowed with pattern 'cross'"),
        ({"actuator": [_act(pattern="satin")]}, "actuator[0].pattern: must be one of 'zigzag', "),
        ({"actuator": [_act(width_mm="7")]}, "actuator[0].width_mm: must be a number, got '7'"),
        ({"actuator": [_act(width_mm=True)]}, "actuator[0].width_mm: must be a number, got True"),
        ({"actuator": [_act(width_mm=math.nan)]}, "actuator[0].width_mm: must be a finite number, got nan"),
        ({"tube": {"g_e_mpa": math.inf}, "actuator": [_act()]}, "tube.g_e_mpa: must be a finite number, got inf"),
        ({"actuator": [_act(width_mm=-1)]}, "actuator[0]: width_mm must be in (0, 200), got -1"),
        ({"actuator": [_act(name=5)]}, "actuator[0].name: must be a string, got 5"),
        ({"actuator": [_act(), _act()]}, "actuator[1].name: duplicate actuator name 'A' (also actuator[0])"),
        ({"actuator": [_act(path="M 0 0 L 10 0")]}, "actuator[0]: give exactly one of length_mm (straight) or path, got both"),
        ({"actuator": [_act(length_mm=None)]}, "actuator[0]: give exactly one of length_mm (straight) or path, got neither"),
        ({"actuator": [_act(length_mm=None, path="M 0 0 B 1 1")]},
         "actuator[0].path: SVG path: unsupported character 'B'"),
        ({"actuator": [_act(length_mm=None, path=[[0, 0]])]}, "actuator[0].path: path needs at least 2 distinct points, got 1"),
        ({"actuator": [_act(length_mm=None, path=[[0, 0], [1]])]}, "actuator[0].path[1]: must be a pair [x, y]"),
        ({"actuator": [_act(length_mm=None, path=5)]}, "actuator[0].path: must be an SVG path string or a list"),
        ({"actuator": [_act(origin_mm=[0.0])]}, "actuator[0].origin_mm: must be a pair [x, y]"),
        ({"actuator": []}, "actuator: must be a non-empty list of tables"),
        ({"actuator": {"name": "A"}}, "actuator: must be a non-empty list of tables"),
        ({"actuator": ["A"]}, "actuator[0]: must be a table, got str"),
        ({"machine": {"format": "xyz"}, "actuator": [_act()]}, "machine: format must be one of dst, tbf"),
        ({"machine": {"min_stitch_mm": 20.0}, "actuator": [_act()]}, "machine: min_stitch_mm must be in [0, 12.1)"),
        ({"operation": {"max_pressure_kpa": 0}, "actuator": [_act()]}, "operation: max_pressure_kpa must be in (0, 100000)"),
        ({"actuator": [_act(tie_count=3.5)]}, "actuator[0]: tie_count must be an integer in [2, 10], got 3.5"),
        ({"actuator": [_act(model={"g_mpa": -2.0})]}, "actuator[0].model: g_mpa must be in (0, 100000), got -2"),
        ([1, 2], "design: must be a table, got list"),
    ],
)
def test_design_from_dict_errors(d, fragment):
    assert fragment in _err(d)


def test_unicode_names_and_optional_tables():
    d = design_from_dict({"name": "試作 ①", "actuator": [_act(name="アクチュエータ", model={"g_mpa": 2.7, "p0_kpa": 85})]})
    assert d.name == "試作 ①" and d.actuators[0].name == "アクチュエータ"
    assert d.actuators[0].model.g_mpa == 2.7 and d.actuators[0].model.calibration == "paper-2025"
    assert d.tube == Tube()


def test_value_objects_validate_directly():
    with pytest.raises(ParameterError, match="actuators must hold at least one actuator"):
        Design("x", Tube(), MachineSettings(), OperationSettings(), ())
    spec = ActuatorSpec("A", ZigzagParams(7.0, 1.0), Centerline.straight(10.0))
    with pytest.raises(ParameterError, match="actuator names must be unique, got 'A' 2 times"):
        Design("x", Tube(), MachineSettings(), OperationSettings(), (spec, spec))
    assert MachineSettings(format=".PES").format == "pes"


# ---------------------------------------------------------------------- round trips and files
def _rich_design() -> Design:
    return design_from_dict({"name": "ümlaut \"quoted\"", "tube": {"outer_radius_mm": 1.2, "inner_radius_mm": 0.8},
                             "machine": {"format": "pes", "speed_spm": 450},
                             "actuator": [_act(name="zz", tie_count=4, model={"p0_kpa": 90.0}),
                                          _act(name="x", pattern="cross", angle_deg=30.0, interval_mm=1.4,
                                               adjust="interval", length_mm=None, path="M0 0 C 20 0 40 20 60 20")]})


def test_dict_round_trip():
    d = _rich_design()
    assert design_from_dict(design_to_dict(d)) == d


def test_toml_round_trip(tmp_path):
    d = _rich_design()
    path = tmp_path / "rich.toml"
    save_design(d, path)
    assert load_design(path) == d
    assert loads_design(dumps_design(d)) == d
    assert build_plan(load_design(path)) == build_plan(d)


def test_load_design_errors(tmp_path):
    missing = tmp_path / "nope.toml"
    with pytest.raises(DesignFileError, match=r"nope\.toml: cannot read design file: No such file or directory"):
        load_design(missing)
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "x"\n[[actuator]\n')
    with pytest.raises(DesignFileError) as exc:
        load_design(bad)
    assert str(exc.value).startswith(f"{bad}: TOML syntax error:") and "line 2" in str(exc.value)
    schema = tmp_path / "schema.toml"
    schema.write_text('[[actuator]]\nname = "A"\npattern = "zigzag"\nwidht_mm = 7\n')
    with pytest.raises(DesignFileError, match=r"^.*schema\.toml: actuator\[0\]\.widht_mm: unknown key"):
        load_design(schema)
    binary = tmp_path / "bin.toml"
    binary.write_bytes(b"name = '\xff'\n")
    with pytest.raises(DesignFileError, match=r"bin\.toml: design file is not UTF-8 text \(byte 8\)"):
        load_design(binary)
