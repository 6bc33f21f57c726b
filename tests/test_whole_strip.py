"""The whole strip's values: one definition for any chain length, in the same keys for one segment as for five.

The rule (``embroact.patterns.chain``): lengths add up, the pattern names the kinds in chain order,
every other value is the one all segments have, None where they differ. The references are
independent of the code under test: the legs' extent measured here on the needle points of the
stitch plan, the widths asked for, and the outputs of a chain of one (whose whole strip is its
segment, to the last digit).
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from embroact.export.cli.main import main
from embroact.export.files.designfile import load_design, save_design
from embroact.patterns.base.errors import ModelDomainError
from embroact.patterns.design import design_from_dict
from embroact.patterns.plan import Command
from embroact.predict.analysis import analyse
from embroact.predict.calibration import CalibrationPoint, CalibrationSet

EXAMPLES = sorted((Path(__file__).resolve().parent.parent / "examples").glob("*.toml"))

ONE = {"name": "chain", "actuator": [
    {"name": "A1", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 100}]}
FIVE = {"name": "chain", "actuator": [{"name": "A1", "segment": [
    {"pattern": "zigzag", "width_mm": w, "interval_mm": 1, "length_mm": 20} for w in (6.0, 7.0, 8.0, 7.0, 6.0)]}]}


def _shape(value):
    """The key structure of a JSON value: dicts by their keys, lists by their items' shapes (any length);
    None stands for a value the segments do not share and fits any shape."""
    if isinstance(value, dict):
        return {k: _shape(v) for k, v in value.items()}
    if isinstance(value, list):
        shapes = [_shape(v) for v in value if v is not None]
        return ["list", *({json.dumps(s, sort_keys=True) for s in shapes})]
    return None if value is None else "value"


def _same_keys(a, b, where="") -> None:
    """Assert ``a`` and ``b`` have the same keys at every depth (None fits anything: a value not shared)."""
    if a is None or b is None:
        return
    if isinstance(a, dict) or isinstance(b, dict):
        assert isinstance(a, dict) and isinstance(b, dict), where
        assert sorted(a) == sorted(b), (where, sorted(set(a) ^ set(b)))
        for k in a:
            _same_keys(a[k], b[k], f"{where}/{k}")
    elif isinstance(a, list) or isinstance(b, list):
        assert isinstance(a, list) and isinstance(b, list), where
        for x in a[:1]:
            for y in b[:1]:
                _same_keys(x, y, f"{where}[]")


def _outputs(tmp_path: Path, capsys, d: dict, tag: str) -> dict:
    """predict --json, build's report.json, worksheet.json and --json, and the API's as_dict, of design ``d``."""
    path = tmp_path / f"{tag}.toml"
    save_design(design_from_dict(d), path)
    out = {}
    assert main(["predict", str(path), "--json"]) == 0
    out["predict"] = json.loads(capsys.readouterr().out)
    folder = tmp_path / tag
    folder.mkdir()
    assert main(["build", str(path), "--out", str(folder), "--force", "--mesh-format", "none", "--json"]) == 0
    out["build"] = json.loads(capsys.readouterr().out)
    out["report"] = json.loads((folder / "report.json").read_text(encoding="utf-8"))
    out["worksheet"] = json.loads((folder / "worksheet.json").read_text(encoding="utf-8"))
    out["api"] = json.loads(json.dumps(analyse(load_design(path)).as_dict()))
    return out


def test_a_chain_of_one_and_a_chain_of_five_give_the_same_keys(tmp_path, capsys):
    one, five = _outputs(tmp_path, capsys, ONE, "one"), _outputs(tmp_path, capsys, FIVE, "five")
    for name in one:
        _same_keys(one[name], five[name], name)
    acts = five["predict"]["actuators"][0]
    assert len(acts["segments"]) == len(acts["segment_curves"]) == 5
    assert acts["derived"]["width_mm"] is None and acts["derived"]["interval_mm"] == 1.0
    assert acts["model"]["g_mpa"] is None and acts["model"]["tube_law"] == "paper" and acts["model_error"] is None
    # the whole strip's thread-side length is its segments' sum at every pressure
    sums = np.sum([s["length_mm"] for s in acts["segment_curves"]], axis=0)
    np.testing.assert_allclose(acts["length_mm"], sums, rtol=1e-12)
    for got in (five["report"], five["worksheet"], five["api"]):
        assert got["actuators"][0]["derived"] == acts["derived"]


def test_two_segments_of_different_widths_hand_check():
    d = design_from_dict({"actuator": [{"name": "S", "segment": [
        {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
        {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]})
    a = analyse(d)
    act = a.actuators[0]
    # the legs' extent along the straight path, measured on the needle points: the 7 mm segment's needle
    # points lie 3.5 mm from the path, the 9 mm one's 4.5 mm
    plan = a.plan
    points = plan.xy_mm[plan.commands == Command.STITCH]
    extent = [np.ptp(points[np.isclose(np.abs(points[:, 1]), half), 0]) for half in (3.5, 4.5)]
    assert extent == pytest.approx([50.0, 50.0], abs=1e-9)  # 51 stations 1 mm apart in each 50 mm share
    s = act.derived
    assert (s.name, s.pattern) == ("S", "zigzag")
    assert s.length_mm == pytest.approx(sum(extent), abs=1e-9)
    assert (s.width_mm, s.requested_width_mm, s.r0_mm, s.gamma) == (None, None, None, None)  # 7 and 9 mm differ
    assert (s.interval_mm, s.requested_interval_mm, s.beta0_deg, s.has_sleeve) == (1.0, 1.0, 0.0, True)
    m = act.model  # G 2.7 and 3.4 MPa (the paper's points at 7 and 9 mm) differ; the tube is shared
    assert [seg.model.g_mpa for seg in act.segments] == [2.7, 3.4]
    assert (m.g_mpa, m.p0_kpa, m.outer_radius_mm, m.tube_law, m.stub_mm) == (None, None, 1.5, "paper", 30.0)
    assert m.length_mm == pytest.approx(100.0, abs=1e-9)
    assert act.choice.g_source is None and act.choice.calibration is None
    assert repr(act) == "ActuatorAnalysis('S': zigzag, w per segment, l0 100 mm, r0 per segment; " \
        "G per segment, P0 per segment)"


def test_two_equal_segments_share_every_value_and_gamma_is_the_strips():
    d = design_from_dict({"actuator": [{"name": "S", "segment": [
        {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
        {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50}]}]})
    act = analyse(d).actuators[0]
    seg = act.segments[0].derived
    assert (act.derived.width_mm, act.derived.r0_mm) == (seg.width_mm, seg.r0_mm) == (7.0, seg.r0_mm)
    # gamma = 2 r0 / (l0 cos beta0) over the whole strip's l0 (beta0 = 0 for the zigzag)
    assert act.derived.gamma == pytest.approx(2.0 * seg.r0_mm / act.derived.length_mm, rel=1e-12)
    assert (act.model.g_mpa, act.model.p0_kpa) == (2.7, 85.0)
    assert act.choice.g_source == act.segments[1].choice.g_source


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_a_chain_of_one_keeps_its_segments_numbers(path):
    from types import SimpleNamespace

    from embroact.export.cli.target import analyse_target, load_target

    args = SimpleNamespace(calibration=None, g_mpa=None, p0_kpa=None, p0_source=None, tube_law=None)
    for act in analyse_target(load_target(args, design_path=str(path))).actuators:
        if len(act.segments) != 1:
            continue
        (seg,) = act.segments
        assert act.derived.as_dict() == {**seg.derived.as_dict(), "name": act.name}
        assert (act.choice is None) == (seg.choice is None) and act.model_error == seg.model_error
        if seg.choice is not None:
            assert act.choice.as_dict() == seg.choice.as_dict()


def test_model_error_names_the_segment_without_a_model(tmp_path, capsys):
    """A calibration set with zigzag points only: the cross segment has no model, and the whole strip says which."""
    lab = CalibrationSet("zigzag-only", (CalibrationPoint("zigzag", 7.0, 2.7, 85.0),))
    d = design_from_dict({"actuator": [{"name": "S", "model": {"calibration": "zigzag-only"}, "segment": [
        {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 40},
        {"pattern": "cross", "width_mm": 7, "interval_mm": 1.4, "angle_deg": 45, "length_mm": 60}]}]})
    act = analyse(d, calibration_sets=[lab]).actuators[0]
    assert act.segments[0].choice is not None and act.segments[1].choice is None
    assert act.model_error.startswith("segment 1: ") and act.model_error == act.segments[1].model_error
    assert act.choice is None
    with pytest.raises(ModelDomainError, match="actuator 'S': segment 1: "):
        act.model
    entry = act.as_dict()
    assert entry["model"] is None and entry["model_error"].startswith("segment 1: ")
    assert entry["derived"]["width_mm"] == 7.0 and entry["derived"]["pattern"] == "zigzag+cross"


def test_the_request_and_the_plan_name_the_chains_pattern_and_derive_takes_one_segment():
    """An actuator's pattern is its chain's (it was the first segment's), and the geometry of a longer chain is
    derived segment by segment, not from its first segment under the actuator's name."""
    from embroact.patterns.design import build_plan
    from embroact.patterns.base.errors import ParameterError
    from embroact.predict.analysis import segment_plans
    from embroact.predict.derived import derive

    d = design_from_dict({"actuator": [{"name": "H", "segment": [
        {"pattern": "zigzag", "width_mm": 8, "interval_mm": 1, "length_mm": 40},
        {"pattern": "cross", "width_mm": 7, "interval_mm": 1.4, "angle_deg": 45, "length_mm": 60}]}]})
    plan = build_plan(d).actuators[0]
    assert d.actuators[0].pattern == plan.pattern == "zigzag+cross"
    assert build_plan(design_from_dict(ONE)).actuators[0].pattern == "zigzag"
    with pytest.raises(ParameterError, match="'H' has 2 segments: derive each"):
        derive(plan)
    assert [derive(p).pattern for p in segment_plans(plan)] == ["zigzag", "cross"]
