"""Smoke run of the benchmark harness (``benchmarks/run.py --quick``): correctness, not timings.

Checks that every method, target and chart is there with the right shapes, and that
the errors the harness reports are errors against the 50-digit reference: a method
shifted by a known amount is reported with exactly that error, and the reference
angles agree with an independent mpmath root.
"""
import dataclasses
import json
import math
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"
sys.path.insert(0, str(BENCH))

import model_bench  # noqa: E402
import run as bench_run  # noqa: E402
import stability  # noqa: E402
from baseline_scipy import baseline_of  # noqa: E402
from sample import design, reference_points, sample_designs  # noqa: E402

from embroact.predict.curve import METHODS, curve, pressure_at  # noqa: E402


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("bench")
    assert bench_run.main(["--quick", "--out", str(out)]) == 0
    return out, json.loads((out / "results.json").read_text())


def test_results_have_every_method_target_and_section(quick):
    _, res = quick
    assert set(res) >= {"config", "machine", "designs", "methods", "baseline_scipy", "baseline_printed", "competitor",
                        "throughput", "stability", "stitches", "targets"}
    assert set(res["methods"]) == set(METHODS)
    cfg = bench_run.CONFIGS["quick"]
    for m, s in res["methods"].items():
        assert len(s["per_design"]) == cfg.n_designs, m
        assert {"time_per_curve_ms", "angle_err_max_deg", "pressure_err_max_rel", "failed_points"} <= set(s)
    assert set(res["targets"]) == set(bench_run.TARGETS)
    for t in res["targets"].values():
        assert {"value", "unit", "target", "pass"} == set(t)


def test_targets_report_the_measured_values(quick):
    _, res = quick
    t = res["targets"]
    assert t["auto_angle_err_max_deg"]["value"] == res["methods"]["auto"]["angle_err_max_deg"]
    c = res["competitor"]
    assert t["auto_speedup_vs_competitor"]["value"] == c["ratios"]["auto_speedup"]["median"]
    assert t["one_over_200_pressures"]["value"] == c["ratios"]["one_over_200"]["median"]
    assert t["cold_speedup_vs_dense"]["value"] == c["ratios"]["cold_speedup_vs_dense"]["median"]
    for r in c["ratios"].values():  # paired: every ratio from the same rounds
        assert r["rounds"] == bench_run.CONFIGS["quick"].curve_rounds and r["min"] <= r["median"] <= r["max"]
    assert c["angle_err_max_deg"] < 1e-9  # the competitor is as accurate as auto (against the mpmath reference)
    assert c["dense_angle_err_max_deg"] < 1e-9  # and so is the dense-grid version
    assert t["help_heavy_imports"] == {"value": 0, "unit": "modules", "target": "== 0", "pass": True}
    tp = res["throughput"]["default_rtol"]
    assert tp["evaluations"] == tp["designs"] * tp["pressures"]


def test_auto_is_accurate_and_stable_printed_form_is_not_better(quick):
    _, res = quick
    auto = res["methods"]["auto"]
    assert auto["resolved"] == ["stable-analytic-trace"]
    assert auto["failed_points"] == 0 and auto["angle_err_max_deg"] < 1e-9
    assert res["methods"]["printed-central-trace"]["angle_err_max_deg"] > auto["angle_err_max_deg"]


def test_stability_maps_have_the_grid_shape_and_common_no_equilibrium_cells(quick):
    _, res = quick
    grid = res["stability"]["grid"]
    n_theta, rows = stability.GRID["quick"]
    assert len(grid["theta_abs_deg"]) == n_theta
    none = stability.NO_EQUILIBRIUM_CLASS
    for pattern in ("zigzag", "cross"):
        assert len(grid["rows"][pattern]) == rows
        masks = []
        for m in METHODS:
            a = np.array(grid["maps"][m][pattern])
            assert a.shape == (rows, n_theta)
            masks.append(a == none)
        # past the branch end is a property of the design, not of the method
        assert all((mk == masks[0]).all() for mk in masks)
    auto = np.array(grid["maps"]["auto"]["zigzag"])
    visible = np.array(grid["theta_abs_deg"]) >= 1e-3  # below, auto's ~1e-12 deg floor exceeds 1e-6 relative
    assert (auto[:, visible] <= 1).all() and (auto <= 2).all()


def test_charts_are_svg_naming_every_method(quick):
    out, _ = quick
    for name in ("pareto.svg", "stability.svg"):
        root = ET.parse(out / name).getroot()
        assert root.tag.endswith("svg")
    text = (out / "stability.svg").read_text()
    assert all(m in text for m in METHODS)
    assert "Pareto front" in (out / "pareto.svg").read_text()


def test_reference_angles_agree_with_an_independent_mpmath_root():
    d = sample_designs(2)[1]
    p, th = reference_points(d, 10)
    ref = d.ref()
    k = 7
    with mp.workdps(60):
        root = mp.findroot(lambda t: ref.pressure(t) - mp.mpf(p[k]) / 1000, mp.radians(th[k]))
        assert abs(float(mp.degrees(root)) - th[k]) < 1e-12
    assert (th[: np.argmax(th != 0)] == 0).all() and (p[th == 0] < d.model.p0_kpa).all()


def test_errors_are_measured_against_the_reference(monkeypatch):
    d = design("zigzag", 7.0, 0.0, 2.7)
    p, th = reference_points(d, 12)
    exact = model_bench.evaluate_method(d.model, p, th, "auto", budget_s=0.0)
    assert exact["angle_err_deg"] < 1e-9 and exact["pressure_err_rel"] < 1e-12

    shift_deg, scale = 0.01, 1.0 + 1e-3

    def shifted_curve(model, pressures, *, method):
        c = curve(model, pressures, method=method)
        return dataclasses.replace(c, theta_deg=np.where(c.theta_deg != 0, c.theta_deg + shift_deg, 0.0))

    def scaled_pressure_at(model, theta, *, method):
        c = pressure_at(model, theta, method=method)
        return dataclasses.replace(c, pressure_kpa=c.pressure_kpa * scale)

    monkeypatch.setattr(model_bench, "curve", shifted_curve)
    monkeypatch.setattr(model_bench, "pressure_at", scaled_pressure_at)
    off = model_bench.evaluate_method(d.model, p, th, "auto", budget_s=0.0)
    assert off["angle_err_deg"] == pytest.approx(shift_deg, rel=1e-6)
    assert off["pressure_err_rel"] == pytest.approx(scale - 1.0, rel=1e-6)


def test_a_raising_method_is_a_failed_result_not_a_crash(monkeypatch):
    d = design("cross", 7.0, 45.0, 1.3)
    p, th = reference_points(d, 6)

    def broken(*args, **kwargs):
        raise ValueError("The function value at x=0.0 is NaN")

    monkeypatch.setattr(model_bench, "curve", broken)
    r = model_bench.evaluate_method(d.model, p, th, "printed-analytic-root", budget_s=0.0)
    assert r["error"].startswith("ValueError") and math.isinf(r["angle_err_deg"]) and r["failed_points"] == 6


def test_scipy_baseline_matches_the_reference_to_its_own_accuracy():
    d = design("cross", 7.0, 15.0, 2.9)
    p, th = reference_points(d, 8)
    got = baseline_of(d.model).theta_deg(float(p[-2]), float(th[-1]) * 1.001)
    assert abs(got - th[-2]) < 1e-5


def test_stability_classes_follow_the_tolerance():
    err = np.array([0.0, 1e-9, 2e-9, stability.REL_TOL, 2e-6, 1e-2, 0.5, np.inf])
    assert stability.classify(err).tolist() == [0, 0, 1, 1, 2, 2, 3, stability.FAILED_CLASS]


def test_paired_rounds_time_every_variant_in_every_round_and_ratios_pair_them():
    ticks = []
    t = bench_run.paired_rounds({"a": [lambda: ticks.append("a")] * 2, "b": [lambda: ticks.append("b")]}, 4)
    assert len(t["a"]) == len(t["b"]) == 4 and ticks.count("a") == 8 and ticks.count("b") == 4
    r = bench_run.paired_ratio({"x": [2.0, 6.0, 3.0], "y": [1.0, 2.0, 3.0]}, "x", "y")
    assert r == {"min": 1.0, "median": 2.0, "max": 3.0, "rounds": 3}  # per round: 2, 3, 1


def test_the_vectorised_competitor_gives_the_competitors_angles():
    from competitor_numpy import competitor_batch, competitor_of

    designs = sample_designs(4)
    p = np.linspace(0.0, 300.0, 25)
    rows = competitor_batch([d.model for d in designs]).theta_deg_rows(p)
    for d, row in zip(designs, rows):
        c = curve(d.model, p)
        ok = c.status == 1  # BENDING: both answer the same equilibrium
        assert np.abs(row[ok] - competitor_of(d.model).theta_deg(p)[ok]).max() < 1e-9
        assert np.abs(row[ok] - c.theta_deg[ok]).max() < 1e-9 and (row[c.theta_deg == 0.0] == 0.0).all()


@pytest.mark.parametrize("readme", bench_run.READMES, ids=lambda p: str(p.relative_to(p.parents[1])))
def test_readme_speed_and_stability_text_is_the_committed_results(readme):
    """The generated blocks of both READMEs are what run.py writes from the committed results.json."""
    res = json.loads((BENCH / "results.json").read_text())
    blocks = bench_run.readme_blocks(readme.read_text())
    assert {"targets", "notes", "stability"} <= set(blocks)
    for name, body in blocks.items():
        assert body == bench_run.README_BLOCKS[name](res), name


def test_a_coiled_cell_is_answered_not_failed():
    assert int(stability.Status.COILED) in stability.ANSWERED and int(stability.Status.FAILED) not in stability.ANSWERED


def test_the_stitches_section_runs_again_alone(quick, tmp_path):
    """``run.py --only stitches`` measures the command-line timings again into an existing results.json and
    keeps what the other sections measured."""
    out, res = quick
    (tmp_path / "results.json").write_text((out / "results.json").read_text())
    assert bench_run.main(["--quick", "--only", "stitches", "--out", str(tmp_path)]) == 0
    again = json.loads((tmp_path / "results.json").read_text())
    assert again["methods"] == res["methods"] and "load_average_stitches" in again["machine"]
    assert set(again["stitches"]) == set(res["stitches"])
    assert again["targets"]["help_over_argparse"]["value"] == again["stitches"]["cli"]["help_over_argparse"]
