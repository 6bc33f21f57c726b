"""One actuator, one answer: every command and the API agree to the last digit.

Each design goes through the Python API (:func:`embroact.predict.analysis.analyse` and
:func:`embroact.predict.rules.check_design`), ``embroact predict --json``, ``embroact build``
(``report.json``, ``worksheet.json``, ``bend.svg``), ``embroact check --json`` and
``embroact preview bend --json``. For every actuator the derived geometry, G and P0 with their
sources, the tube and tube law, the curve's angles and statuses (a segmented actuator's for every
segment and for the whole strip), and the findings must be
*equal* (JSON numbers are shortest round-trip reprs, so equality is to the last digit), and
the chart the build draws must be byte-identical to the one drawn from the API's curves.

The designs: every ``examples/*.toml`` and a small fixed-seed hypothesis sample of valid
design dicts (``strategies.design_dicts``), plus quick parameters through ``predict``,
``zigzag``/``cross`` and ``fit``.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from hypothesis import HealthCheck, assume, given, settings

from embroact.export.cli.main import main
from embroact.export.files.designfile import load_design, save_design
from embroact.export.report.build import SPLIT_LONG_IGNORES
from embroact.patterns.design import design_from_dict
from embroact.predict.rules import check_design
from strategies import design_dicts

EXAMPLES = sorted((Path(__file__).resolve().parent.parent / "examples").glob("*.toml"))
MODEL_KEYS = ("g_mpa", "g_source", "p0_kpa", "p0_source", "tube_law", "tube", "notes")


def _json(capsys, argv, codes=(0,)):
    code = main(argv)
    captured = capsys.readouterr()
    assert code in codes, (argv, code, captured.err)
    return json.loads(captured.out)


def _plain(value):
    """JSON round trip: tuples become lists, numbers stay the same floats."""
    return json.loads(json.dumps(value))


def _api(path: Path):
    """What the API says: the analysis of the design file (calibration files resolved as the commands do)."""
    from types import SimpleNamespace

    from embroact.export.cli.target import analyse_target, load_target

    args = SimpleNamespace(calibration=None, g_mpa=None, p0_kpa=None, p0_source=None, tube_law=None)
    return analyse_target(load_target(args, design_path=str(path)))


def _parts(entry: dict) -> list[tuple[dict, dict]]:
    """(derived, model) of each pattern part of an actuator entry: its segments, or the actuator itself."""
    segs = entry.get("segments")
    return [(s["derived"], s["model"]) for s in segs] if segs else [(entry["derived"], entry["model"])]


def _curves(entry: dict, whole: dict) -> list[dict]:
    """The actuator's curve (a segmented one's whole strip) followed by each segment's."""
    return [whole] + list(entry.get("segment_curves") or [])


def _assert_commands_agree(capsys, tmp_path: Path, path: Path) -> bool:
    """Assert that every command agrees with the API; False (nothing compared) when an actuator or a segment
    has no model (no sleeve)."""
    analysis = _api(path)
    if any(p.choice is None for a in analysis.actuators for p in (a.segments or (a,))):
        return False
    curves = analysis.curves()
    api = {}
    for a, c in zip(analysis.actuators, curves):
        whole = _plain(c.as_dict())
        segment_curves = [_plain(sc.as_dict()) for sc in getattr(c, "segments", ())]
        if a.segments:  # the whole strip is the sum of the segments' bends
            sums = [math.fsum(t) for t in zip(*(sc["theta_deg"] for sc in segment_curves))]
            assert whole["theta_deg"] == pytest.approx(sums, abs=1e-9)
        api[a.name] = {"parts": _parts(_plain(a.as_dict())), "curves": [whole] + segment_curves}
    api_findings = _plain([f.as_dict() for f in check_design(analysis)])

    # embroact predict --json (default grid: 0 to the design's working pressure, 10 kPa steps)
    predicted = _json(capsys, ["predict", str(path), "--json"])["actuators"]
    # embroact build: report.json, worksheet.json, bend.svg
    out = tmp_path / "out"
    out.mkdir()
    # --force: designs with rule errors are built too; --split-long: legs over the format's record limit
    # (EA102/EA103, which --split-long leaves out) are split instead of refused by the writer
    assert main(["build", str(path), "--out", str(out), "--force", "--split-long", "--mesh-format", "none"]) == 0
    capsys.readouterr()
    report = json.loads((out / "report.json").read_text(encoding="utf-8"))
    sheet = json.loads((out / "worksheet.json").read_text(encoding="utf-8"))
    # embroact check --json; embroact preview bend --json
    checked = _json(capsys, ["check", str(path), "--json"], codes=(0, 1))
    preview = _json(capsys, ["preview", "bend", str(path), "-o", str(tmp_path / "bend.svg"), "--json"])

    names = list(api)
    assert [a["name"] for a in predicted] == [a["name"] for a in report["actuators"]] == names
    assert [a["name"] for a in sheet["actuators"]] == [a["name"] for a in preview["actuators"]] == names
    for name, p, r, w, v in zip(names, predicted, report["actuators"], sheet["actuators"], preview["actuators"]):
        want = api[name]
        for got in (p, r, w, v):  # every segment's derived geometry and model
            assert len(_parts(got)) == len(want["parts"]), name
            for (derived, model), (want_derived, want_model) in zip(_parts(got), want["parts"]):
                assert derived == want_derived, name
                assert {k: model[k] for k in MODEL_KEYS} == {k: want_model[k] for k in MODEL_KEYS}, name
        for got in (_curves(p, p), _curves(r, r["curve"]), _curves(v, v["curve"])):  # the total and every segment
            assert len(got) == len(want["curves"]), name
            for got_curve, want_curve in zip(got, want["curves"]):
                for key in ("pressure_kpa", "theta_deg", "status", "method", "calibration"):
                    if key in want_curve:
                        assert got_curve[key] == want_curve[key], (name, key)
    # the findings: the API, check, the report and the worksheet list the same ones
    assert checked["findings"] == api_findings
    built_findings = _plain([f.as_dict() for f in check_design(analysis, ignore=SPLIT_LONG_IGNORES)])
    assert report["findings"] == built_findings == sheet["findings"]
    assert checked["counts"] == {s: sum(f["count"] for f in api_findings if f["severity"] == s)
                                 for s in ("error", "warning", "info")}  # every finding, listed or not
    # the chart is drawn from the same curves: byte-identical to one drawn from the API's
    from embroact.export.pictures.previews import bend_chart

    assert (out / "bend.svg").read_text(encoding="utf-8") == bend_chart(analysis, curves)
    assert (tmp_path / "bend.svg").read_text(encoding="utf-8") == bend_chart(analysis, curves)
    return True


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_every_example_gives_one_answer(capsys, tmp_path, path):
    assert _assert_commands_agree(capsys, tmp_path, path)  # segmented ones (designed_hook) too


@settings(max_examples=6, derandomize=True, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(design_dicts())
def test_sampled_designs_give_one_answer(capsys, tmp_path_factory, d):
    tmp_path = tmp_path_factory.mktemp("design")
    path = tmp_path / "d.toml"
    save_design(design_from_dict(d), path)
    assume(_assert_commands_agree(capsys, tmp_path, path))


def test_build_analyses_and_predicts_once(tmp_path, monkeypatch):
    """One build: one derivation per actuator and one curve evaluation per actuator (rules, chart,
    side view, 3D shape and report share it)."""
    import embroact.predict.analysis as analysis_module
    import embroact.predict.curve as curve_module
    from embroact.export.report.stage import previews_stage
    from embroact.export.report.build import build

    calls = {"derive": 0, "curve": 0}
    real_derive, real_curve = analysis_module.derive, curve_module.curve

    def derive(*args, **kwargs):
        calls["derive"] += 1
        return real_derive(*args, **kwargs)

    def curve(*args, **kwargs):
        calls["curve"] += 1
        return real_curve(*args, **kwargs)

    monkeypatch.setattr(analysis_module, "derive", derive)
    monkeypatch.setattr(curve_module, "curve", curve)
    design = load_design(next(p for p in EXAMPLES if p.stem == "three_actuators"))
    build(design, tmp_path, force=True, stages=[previews_stage(mesh_suffix=".stl")])
    assert calls == {"derive": 3, "curve": 3}


@pytest.mark.parametrize("quick", [
    ["zigzag", "--width-mm", "7", "--interval-mm", "1"],
    ["cross", "--width-mm", "7", "--interval-mm", "1.4", "--angle-deg", "30"],  # sewn at 30.96 deg
])
def test_quick_parameters_give_one_answer(capsys, tmp_path, quick):
    """predict, zigzag/cross and fit model the actuator the generator realised, with one G and P0."""
    pattern = quick[0]
    (predicted,) = _json(capsys, ["predict", *quick, "--pressure-kpa", "0:300:25", "--json"])["actuators"]
    written = _json(capsys, [*quick, "-o", str(tmp_path / "a.dst"), "--force", "--json"])
    csv = tmp_path / "data.csv"
    csv.write_text("pressure_kpa,angle_deg\n" + "".join(
        f"{p!r},{t!r}\n" for p, t in zip(predicted["pressure_kpa"], predicted["theta_deg"])))
    fitted = _json(capsys, ["fit", str(csv), "--pattern", *quick, "--json"])
    assert predicted["derived"] == written["derived"] == fitted["design"]
    assert {k: predicted["model"][k] for k in MODEL_KEYS} == {k: written["model"][k] for k in MODEL_KEYS}
    if pattern == "cross":  # tan(alpha0) = 3 s / w = 0.6: the generator's whole passes, not the requested 30 deg
        assert predicted["derived"]["angle_deg"] == pytest.approx(math.degrees(math.atan(0.6)), abs=1e-12)
        assert predicted["derived"]["requested_angle_deg"] == 30.0
