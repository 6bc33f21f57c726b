"""Run every embroact benchmark: ``python benchmarks/run.py [--quick] [--out DIR]``.

Writes ``results.json``, ``pareto.svg`` and ``stability.svg`` to ``--out`` (default:
this folder; a full run there also refreshes the tables of its README) and prints each
figure with its target and PASS/FAIL. ``--quick`` is
the smoke run (tiny sample, one repeat; its timings mean nothing). See
``benchmarks/README.md`` for what is measured and how.

Examples
--------
>>> from run import CONFIGS
>>> CONFIGS["quick"].n_pressures < CONFIGS["full"].n_pressures
True
"""
from __future__ import annotations

import argparse
import json
import math
import os
import platform
import statistics
import sys
import tempfile
import time
from dataclasses import asdict, dataclass, replace
from functools import lru_cache
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import charts  # noqa: E402
import inverse_bench  # noqa: E402
import model_bench  # noqa: E402
import rules_scaling  # noqa: E402
import scale_bench  # noqa: E402
import stability  # noqa: E402
import stitch_bench  # noqa: E402
from baseline_scipy import baseline_of  # noqa: E402
from competitor_numpy import DENSE_POINTS, DENSE_STEPS, competitor_batch, competitor_of  # noqa: E402
from sample import reference_points, sample_designs  # noqa: E402

from embroact.predict.curve import METHODS, curve, sweep  # noqa: E402
from embroact.predict.status import Status  # noqa: E402

__all__ = ["Config", "CONFIGS", "main", "run", "targets", "write_charts", "markdown_table", "markdown_targets",
           "markdown_notes", "markdown_stability", "update_readme", "readme_blocks", "paired_rounds", "paired_ratio",
           "README_BLOCKS", "READMES"]

#: The default method, "the closed form as printed" baseline and its printed-form twin.
AUTO, PRINTED = "auto", "printed-analytic-trace"
_PATTERNS = ("zigzag", "cross")


@dataclass(frozen=True, slots=True)
class Config:
    """Sizes of one benchmark run."""

    n_designs: int
    n_pressures: int
    time_budget_s: float
    baseline_designs: int
    baseline_points: int
    stability_grid: str
    sweep_designs: int
    cli_runs: int
    long_path_mm: float
    long_path_runs: int
    scale_runs: int
    curve_rounds: int
    sweep_rounds: int
    rules_rounds: int
    inverse_rounds: int


CONFIGS = {
    "full": Config(n_designs=12, n_pressures=200, time_budget_s=0.25, baseline_designs=4, baseline_points=6,
                   stability_grid="full", sweep_designs=1000, cli_runs=11, long_path_mm=10_000.0, long_path_runs=3,
                   scale_runs=3, curve_rounds=31, sweep_rounds=7, rules_rounds=5, inverse_rounds=5),
    "quick": Config(n_designs=2, n_pressures=12, time_budget_s=0.0, baseline_designs=1, baseline_points=2,
                    stability_grid="quick", sweep_designs=8, cli_runs=1, long_path_mm=500.0, long_path_runs=1,
                    scale_runs=0, curve_rounds=3, sweep_rounds=2, rules_rounds=0, inverse_rounds=0),
}

#: Targets (issue 17: ratios measured in the same run, sizes, limits): name -> (unit, comparison, limit).
TARGETS = {
    "auto_angle_err_max_deg": ("deg", "<=", 1e-9),
    "competitor_angle_err_max_deg": ("deg", "<=", 1e-9),
    "dense_angle_err_max_deg": ("deg", "<=", 1e-9),
    "auto_speedup_vs_competitor": ("x", ">=", 1.5),
    "auto_over_closed_form_eval": ("x", "<=", 5.0),
    "one_over_200_pressures": ("ratio", "<=", 0.15),
    "cold_speedup_vs_competitor": ("x", ">=", 1.5),
    "cold_speedup_vs_dense": ("x", ">=", 1.5),
    "cold_one_over_200_pressures": ("ratio", "<=", 0.2),
    "sweep_speedup_vs_competitor": ("x", ">=", 1.5),
    "sweep_competitor_agrees_rel": ("rel.", "<=", 1e-9),
    "auto_speedup_vs_scipy": ("x", ">=", 1000.0),
    "model_rules_1000_over_100_identical": ("x", "<=", 3.0),
    "build_over_import_floor": ("x", "<=", 2.5),
    "check_dst_over_import_floor": ("x", "<=", 1.5),
    "help_over_argparse": ("x", "<=", 1.5),
    "help_heavy_imports": ("modules", "==", 0),
    "build_100_over_10_actuators": ("x", "<=", 12.0),
    "build_100_actuators_peak_mb": ("MB", "<", 300.0),
    "build_10m_over_1m_path": ("x", "<=", 12.0),
    "analyse_100m_over_10m_path": ("x", "<=", 12.0),
    "path_past_limits_refused_s": ("s", "<", 1.0),
    "shape3d_10m_mb": ("MB", "<", 2.0),
    "report_100_actuators_mb": ("MB", "<", 5.0),
    "build_1000_actuators_ok": ("ok", "==", 1),
    "far_apart_refused_s": ("s", "<", 5.0),
    "inverse_unreachable_s": ("s", "<", 1.0),
    "inverse_bend_median_s": ("s", "<", 0.5),
}


def _log(msg: str) -> None:
    print(msg, flush=True)


def _methods(cfg: Config, designs, points) -> dict:
    import scipy.integrate  # noqa: F401  (the root inverse and the baseline import scipy lazily:
    import scipy.optimize  # noqa: F401   load it here so no timing includes an import)

    out = {}
    for m in METHODS:
        rows = []
        for d, (p, th) in zip(designs, points):
            r = model_bench.evaluate_method(d.model, p, th, m, budget_s=cfg.time_budget_s)
            rows.append({**r, "design": d.name})
        out[m] = {**model_bench.summarise(rows, cfg.n_pressures), "per_design": rows}
        s = out[m]
        _log(f"  {m:<26} {_fmt(s['time_per_curve_ms'], '{:9.3f}')} ms/curve  "
             f"angle err {s['angle_err_max_deg']:.2e} deg  P err {s['pressure_err_max_rel']:.2e}"
             + (f"  failed points {s['failed_points']}" if s["failed_points"] else ""))
    return out


#: The curve section's variants, timed in the same rounds: name -> what one call runs (per design).
CURVE_VARIANTS = ("auto", "auto_one", "auto_cold", "auto_cold_one", "competitor", "dense", "eval")


def paired_rounds(calls: dict, rounds: int) -> dict:
    """Times [s] of every variant in each round: ``calls`` maps a name to a list of zero-argument
    functions (one per design, or per item), each called once per round; the variants take turns in
    each round (the order rotates from round to round), so a ratio of two variants compares times
    taken under the same load. Returns name -> list of per-round totals.

    Examples
    --------
    >>> t = paired_rounds({"a": [lambda: None], "b": [lambda: None, lambda: None]}, 3)
    >>> sorted(t), len(t["a"])
    (['a', 'b'], 3)
    """
    import gc

    names = list(calls)
    out = {n: [] for n in names}
    enabled = gc.isenabled()
    gc.disable()
    try:
        for r in range(rounds):
            order = names[r % len(names):] + names[:r % len(names)]
            per = dict.fromkeys(names, 0.0)
            for k in range(max(len(calls[n]) for n in names)):  # design by design, every variant in turn
                for n in order:
                    if k < len(calls[n]):
                        t = time.perf_counter()
                        calls[n][k]()
                        per[n] += time.perf_counter() - t
            for n in names:
                out[n].append(per[n])
    finally:
        if enabled:
            gc.enable()
    return out


def paired_ratio(times: dict, num: str, den: str) -> dict:
    """min / median / max over rounds of ``times[num][r] / times[den][r]`` (:func:`paired_rounds`)."""
    r = sorted(a / b for a, b in zip(times[num], times[den]))
    return {"min": r[0], "median": statistics.median(r), "max": r[-1], "rounds": len(r)}


def _fresh_models(model, n: int, tag: str) -> list:
    """``n`` copies of ``model`` that share nothing cached with it (a new calibration label each)."""
    return [replace(model, calibration=f"{tag} {k}") for k in range(n)]


def _competitor(cfg: Config, designs, points) -> dict:
    """The curve section, every ratio paired: in each of ``cfg.curve_rounds`` rounds every variant runs once
    per design, interleaved (:func:`paired_rounds`). Variants: ``auto`` (repeated calls on one model: its
    branch nodes kept), ``auto_one`` (the same with only the last pressure), ``auto_cold`` and
    ``auto_cold_one`` (a first call on a model: a new model each call, built before the timing), the
    competitor (no cache: every call is a first call), the dense-grid version and one closed-form
    evaluation of the competitor at the 200 reference angles."""
    rounds = cfg.curve_rounds
    calls = {n: [] for n in CURVE_VARIANTS}
    errs = {"competitor": [], "dense": []}
    for d, (p, th) in zip(designs, points):
        comp = competitor_of(d.model)
        errs["competitor"].append(float(model_bench.angle_errors(comp.theta_deg(p), th).max()))
        errs["dense"].append(float(model_bench.angle_errors(
            comp.theta_deg(p, grid_points=DENSE_POINTS, steps=DENSE_STEPS), th).max()))
        curve(d.model, p)  # warm: the branch nodes are kept from here on
        cold, cold_one = iter(_fresh_models(d.model, rounds, "cold")), iter(_fresh_models(d.model, rounds, "cold1"))
        angles = np.radians(th)
        calls["auto"].append(lambda m=d.model, p=p: curve(m, p))
        calls["auto_one"].append(lambda m=d.model, p=p[-1:]: curve(m, p))
        calls["auto_cold"].append(lambda it=cold, p=p: curve(next(it), p))
        calls["auto_cold_one"].append(lambda it=cold_one, p=p[-1:]: curve(next(it), p))
        calls["competitor"].append(lambda m=d.model, p=p: competitor_of(m).theta_deg(p))
        calls["dense"].append(lambda m=d.model, p=p: competitor_of(m).theta_deg(p, grid_points=DENSE_POINTS,
                                                                                steps=DENSE_STEPS))
        calls["eval"].append(lambda c=comp, a=angles: c.pressure_mpa(a))
    times = paired_rounds(calls, rounds)
    n = len(designs)
    per_curve_ms = {k: statistics.median(v) / n * 1e3 for k, v in times.items()}
    ratios = {"auto_speedup": paired_ratio(times, "competitor", "auto"),
              "auto_over_eval": paired_ratio(times, "auto", "eval"),
              "one_over_200": paired_ratio(times, "auto_one", "auto"),
              "cold_speedup": paired_ratio(times, "competitor", "auto_cold"),
              "cold_speedup_vs_dense": paired_ratio(times, "dense", "auto_cold"),
              "cold_one_over_200": paired_ratio(times, "auto_cold_one", "auto_cold"),
              "cold_over_warm": paired_ratio(times, "auto_cold", "auto")}
    solved = sum(int((th != 0.0).sum()) for _, th in points)
    return {"rounds": rounds, "per_curve_ms": per_curve_ms,
            "per_curve_min_ms": {k: min(v) / n * 1e3 for k, v in times.items()},
            "ratios": ratios, "angle_err_max_deg": max(errs["competitor"]),
            "dense_angle_err_max_deg": max(errs["dense"]), "dense": {"grid_points": DENSE_POINTS,
                                                                     "secant_steps": DENSE_STEPS},
            "time_per_curve_ms": per_curve_ms["competitor"], "auto_ms": per_curve_ms["auto"],
            "solved_points": solved}


def _fmt(v, spec: str) -> str:
    return "      n/a" if v is None else spec.format(v)


def _baseline(cfg: Config, designs, points, methods) -> dict:
    """scipy baseline on a few designs; per-curve time extrapolated from timed pressures."""
    rows = []
    auto = {r["design"]: r for r in methods[AUTO]["per_design"]}
    for i in range(min(cfg.baseline_designs, len(designs))):  # alternately zigzag and cross
        d, (p, th) = designs[i], points[i]
        bending = np.flatnonzero(th != 0.0)
        idx = bending[np.linspace(0, bending.size - 1, cfg.baseline_points).round().astype(int)]
        b = baseline_of(d.model)
        hi = float(th[-1]) * (1.0 + 1e-3)
        t = time.perf_counter()
        got = np.array([b.theta_deg(float(p[k]), hi) for k in idx])
        per_point = (time.perf_counter() - t) / idx.size
        rows.append({"design": d.name, "timed_points": int(idx.size), "time_per_point_s": per_point,
                     "time_per_curve_s": per_point * bending.size,
                     "angle_err_deg": float(model_bench.angle_errors(got, th[idx]).max()),
                     "auto_time_s": auto[d.name]["time_s"], "auto_angle_err_deg": auto[d.name]["angle_err_deg"]})
    curve_s = statistics.median(r["time_per_curve_s"] for r in rows)
    auto_s = statistics.median(r["auto_time_s"] for r in rows)
    return {"designs": rows, "time_per_curve_ms": curve_s * 1e3, "angle_err_max_deg": max(r["angle_err_deg"]
                                                                                          for r in rows),
            "auto_time_per_curve_ms": auto_s * 1e3, "speedup_auto": curve_s / auto_s,
            "auto_angle_err_max_deg": max(r["auto_angle_err_deg"] for r in rows),
            "note": "per-curve time = mean time per timed pressure x bending pressures of the 200 (one brentq "
                    "per pressure, so the cost is linear in the count)"}


def _throughput(cfg: Config) -> dict:
    """``sweep`` of many designs against the competitor vectorised across the same designs (one call each,
    every ratio paired over ``cfg.sweep_rounds`` rounds), at the default rtol and at 1e-6, and against a
    Python loop of ``curve()`` on the first 100 designs."""
    models = [d.model for d in sample_designs(cfg.sweep_designs, seed=7)]
    pressures = np.linspace(0.0, 400.0, 200 if cfg.sweep_designs > 100 else 12)
    few = models[: min(100, len(models))]
    ref = sweep(models, pressures)  # warm-up; its answer gives the counts and the competitor's agreement
    comp = competitor_batch(models).theta_deg_rows(pressures)
    bending = ref.status == int(Status.BENDING)
    times = paired_rounds({"sweep": [lambda: sweep(models, pressures)],
                           "sweep_rtol_1e-6": [lambda: sweep(models, pressures, rtol=1e-6)],
                           "competitor": [lambda: competitor_batch(models).theta_deg_rows(pressures)],
                           "loop": [lambda: [curve(m, pressures) for m in few]]}, cfg.sweep_rounds)
    n = len(models) * len(pressures)
    solved = int((ref.status != Status.INFLATION).sum())
    med = {k: statistics.median(v) for k, v in times.items()}
    out = {k: {"designs": len(models), "pressures": len(pressures), "evaluations": n, "time_s": med[k],
               "evals_per_s": n / med[k], "solved_points": solved, "solved_per_s": solved / med[k]}
           for k in ("sweep", "sweep_rtol_1e-6", "competitor")}
    loop = med["loop"] / len(few)
    return {"default_rtol": out["sweep"], "rtol_1e-6": out["sweep_rtol_1e-6"], "competitor": out["competitor"],
            "rounds": cfg.sweep_rounds,
            "sweep_speedup_vs_competitor": paired_ratio(times, "competitor", "sweep"),
            "competitor_vs_sweep_max_deg": float(np.abs(comp - ref.theta_deg)[bending].max()),
            "competitor_vs_sweep_max_rel": float((np.abs(comp - ref.theta_deg) / np.maximum(np.abs(ref.theta_deg), 1.0))
                                                 [bending].max()),
            "loop_of_curve_per_design_ms": loop * 1e3,
            "vectorised_per_design_ms": med["sweep"] / len(models) * 1e3,
            "vectorised_over_loop": {k: v * len(models) / len(few) for k, v in
                                     paired_ratio(times, "loop", "sweep").items() if k != "rounds"}}


def _stability(cfg: Config) -> dict:
    n_theta, rows = stability.GRID[cfg.stability_grid]
    panels = {pt: stability.panel_reference(pt, n_theta, rows) for pt in _PATTERNS}
    maps, summary = {}, {}
    for m in METHODS:
        maps[m], summary[m] = {}, {}
        for pt, panel in panels.items():
            r = stability.method_panel(panel, m)
            maps[m][pt] = r["cls"]
            counts = np.bincount(r["cls"].ravel(), minlength=len(stability.CLASSES))
            bad = (r["cls"] >= 2) & (r["cls"] != stability.NO_EQUILIBRIUM_CLASS)
            cols = np.flatnonzero(bad.any(axis=0))
            thetas = panel["theta_abs_deg"]
            summary[m][pt] = {"counts": dict(zip([c for c, _ in stability.CLASSES], counts.tolist())),
                              "within_tolerance_from_deg": float(thetas[0]) if cols.size == 0
                              else (float(thetas[cols[-1] + 1]) if cols[-1] + 1 < thetas.size else None),
                              "notes": r["notes"][:6]}
    grid = {"theta_abs_deg": panels["zigzag"]["theta_abs_deg"].tolist(),
            "rows": {pt: p["row_values"] for pt, p in panels.items()},
            "row_labels": {pt: p["row_label"] for pt, p in panels.items()},
            "classes": [c for c, _ in stability.CLASSES],
            "maps": {m: {pt: v.tolist() for pt, v in by.items()} for m, by in maps.items()}}
    return {"summary": summary, "grid": grid}


def _stitches(cfg: Config, res: dict) -> None:
    _log("stitches, files, command line:")
    res["stitches"] = {
        "needle_rate": [stitch_bench.needle_rate(pt, cfg.long_path_mm) for pt in _PATTERNS],
        "cli": stitch_bench.cli_timings(cfg.cli_runs),
        "help_heavy_imports": stitch_bench.help_imports(),
        "long_design": stitch_bench.ten_metre(cfg.long_path_mm, cfg.long_path_runs),
    }
    for r in res["stitches"]["needle_rate"]:
        _log(f"  {r['pattern']}: {r['needle_points']} needle points on {r['length_mm']:g} mm in "
             f"{r['time_s'] * 1e3:.1f} ms = {r['points_per_s']:.3g} points/s")
    _log(f"  help over argparse {res['stitches']['cli']['help_over_argparse']:.3g}")


def targets(res: dict) -> dict:
    """Measured value and PASS/FAIL of each target in :data:`TARGETS`."""
    auto = res["methods"][AUTO]
    base = res["baseline_scipy"]
    comp, cli, sc = res["competitor"], res["stitches"]["cli"], res.get("scale")
    values = {
        "auto_angle_err_max_deg": auto["angle_err_max_deg"],
        "competitor_angle_err_max_deg": comp["angle_err_max_deg"],
        "dense_angle_err_max_deg": comp["dense_angle_err_max_deg"],
        "auto_speedup_vs_competitor": comp["ratios"]["auto_speedup"]["median"],
        "auto_over_closed_form_eval": comp["ratios"]["auto_over_eval"]["median"],
        "one_over_200_pressures": comp["ratios"]["one_over_200"]["median"],
        "cold_speedup_vs_competitor": comp["ratios"]["cold_speedup"]["median"],
        "cold_speedup_vs_dense": comp["ratios"]["cold_speedup_vs_dense"]["median"],
        "cold_one_over_200_pressures": comp["ratios"]["cold_one_over_200"]["median"],
        "sweep_speedup_vs_competitor": res["throughput"]["sweep_speedup_vs_competitor"]["median"],
        "sweep_competitor_agrees_rel": res["throughput"]["competitor_vs_sweep_max_rel"],
        "auto_speedup_vs_scipy": base["speedup_auto"],
        "model_rules_1000_over_100_identical": res["rules"]["ratio"]["median"] if res.get("rules") else None,
        "build_over_import_floor": cli["build_over_floor"],
        "check_dst_over_import_floor": cli["check_dst_over_floor"],
        "help_over_argparse": cli["help_over_argparse"],
        "help_heavy_imports": len(res["stitches"]["help_heavy_imports"]),
    }
    if sc:
        g, m = sc["grid"], sc["meander"]
        big = g.get("1000")
        values.update({
            "build_100_over_10_actuators": g["ratio_100_over_10"],
            "build_100_actuators_peak_mb": g["100"]["peak_mb"],
            "build_10m_over_1m_path": m["ratio_10m_over_1m"],
            "shape3d_10m_mb": m["10m"]["sizes_mb"].get("shape3d.svg"),
            "report_100_actuators_mb": g["100"]["sizes_mb"].get("report.html"),
            "build_1000_actuators_ok": None if big is None else int(
                (big["rc"] == 0 and big["s"] < scale_bench.LIMIT_1000_S and big["peak_mb"] < scale_bench.LIMIT_1000_MB)
                or (big["rc"] == 2 and big["s"] < scale_bench.LIMIT_1000_S)),
            "analyse_100m_over_10m_path": sc["long_paths"]["ratio"]["median"],
            "path_past_limits_refused_s": sc["long_paths"]["refused"]["s"] if sc["long_paths"]["refused"]["rc"] in (1, 2)
            and not sc["long_paths"]["refused"]["sizes_mb"] else math.inf,
            "far_apart_refused_s": sc["far_apart"]["s"] if sc["far_apart"]["rc"] in (1, 2) and not
            sc["far_apart"]["sizes_mb"] else math.inf,
        })
    inv = res.get("inverse")
    if inv:
        values.update({
            "inverse_unreachable_s": max(v["median_s"] for v in inv["unreachable"].values())
            if inv["unreachable_answered"] else math.inf,
            "inverse_bend_median_s": inv["bend_median_s"] if inv["bends_met"] else math.inf,
        })
    ops = {"<": lambda a, b: a < b, "<=": lambda a, b: a <= b, ">=": lambda a, b: a >= b, "==": lambda a, b: a == b}
    return {k: {"value": values.get(k), "unit": TARGETS[k][0], "target": f"{TARGETS[k][1]} {TARGETS[k][2]:g}",
                "pass": bool(values.get(k) is not None and ops[TARGETS[k][1]](values[k], TARGETS[k][2]))}
            for k in TARGETS}


def _pareto_points(res: dict) -> list[dict]:
    pts = [{"label": m if m != AUTO else f"auto = {res['methods'][m]['resolved'][0]}",
            "time_ms": res["methods"][m]["time_per_curve_ms"], "error_deg": res["methods"][m]["angle_err_max_deg"],
            "kind": "auto" if m == AUTO else "method"}
           for m in METHODS if m != AUTO or res["methods"][m]["resolved"]]
    b, c = res["baseline_scipy"], res["competitor"]
    pts.append({"label": "scipy baseline (dblquad, central, brentq)", "time_ms": b["time_per_curve_ms"],
                "error_deg": b["angle_err_max_deg"], "kind": "baseline"})
    pts.append({"label": "numpy competitor (closed form, table, 4 secant steps)", "time_ms": c["time_per_curve_ms"],
                "error_deg": c["angle_err_max_deg"], "kind": "baseline"})
    pts.append({"label": f"dense-grid numpy ({c['dense']['grid_points']} points, {c['dense']['secant_steps']} steps)",
                "time_ms": c["per_curve_ms"]["dense"], "error_deg": c["dense_angle_err_max_deg"], "kind": "baseline"})
    pts.append({"label": "auto, first call on a new model", "time_ms": c["per_curve_ms"]["auto_cold"],
                "error_deg": res["methods"][AUTO]["angle_err_max_deg"], "kind": "auto"})
    return [p for p in pts if not (p["kind"] == "method" and p["label"] == res["methods"][AUTO]["resolved"][0])]


def markdown_table(res: dict) -> str:
    """The README's table of methods (speed, accuracy, failures) from a results dict."""
    auto_ms = res["methods"][AUTO]["time_per_curve_ms"]
    lines = ["| method | median ms / 200-pressure curve | (fastest run) | x auto | max angle error [deg] | "
             "max rel. P error | failed points |", "|---|---:|---:|---:|---:|---:|---:|"]
    for m in METHODS:
        s = res["methods"][m]
        t = s["time_per_curve_ms"]
        lines.append(f"| `{m}` | {_fmt(t, '{:.3g}').strip()} | {_fmt(s['time_per_curve_min_ms'], '{:.3g}').strip()} | "
                     f"{_fmt(None if t is None else t / auto_ms, '{:.3g}').strip()}"
                     f" | {s['angle_err_max_deg']:.1e} | {s['pressure_err_max_rel']:.1e} | {s['failed_points']} |")
    b = res["baseline_scipy"]
    lines.append(f"| scipy baseline | {b['time_per_curve_ms']:.4g} | | {b['time_per_curve_ms'] / auto_ms:.3g} | "
                 f"{b['angle_err_max_deg']:.1e} | n/a | 0 |")
    return "\n".join(lines)


def markdown_targets(res: dict) -> str:
    """The README's table of targets from a results dict."""
    lines = ["| target | measured | limit | |", "|---|---:|---|---|"]
    for k in TARGETS:
        t = res["targets"][k]
        shown = "not run" if t["value"] is None else f"{float(t['value']):.4g} {t['unit']}"
        lines.append(f"| {k} | {shown} | {t['target']} | "
                     f"{'PASS' if t['pass'] else '**FAIL**'} |")
    return "\n".join(lines)


def markdown_notes(res: dict) -> str:
    """The README's figures besides the two tables (ratios, sweeps, stitches, command line)."""
    b, pr, tp = res["baseline_scipy"], res["baseline_printed"], res["throughput"]
    st, cli, ld = res["stitches"], res["stitches"]["cli"]["median_s"], res["stitches"]["long_design"]
    rates = ", ".join(f"{r['pattern']} {r['points_per_s']:.3g} needle points/s ({r['needle_points']} points in "
                      f"{r['time_s'] * 1e3:.0f} ms)" for r in st["needle_rate"])
    c = res["competitor"]
    sc = res.get("scale")
    scale_lines = [] if not sc else [
        f"* Scale (fresh `embroact build` processes): 10 / 100 small zigzags {sc['grid']['10']['s']:.2f} s / "
        f"{sc['grid']['100']['s']:.2f} s ({sc['grid']['ratio_100_over_10']:.3g} x; peak {sc['grid']['100']['peak_mb']:.0f} MB"
        f", report.html {sc['grid']['100']['sizes_mb'].get('report.html', 0):.2f} MB, shape3d.svg "
        f"{sc['grid']['100']['sizes_mb'].get('shape3d.svg', 0):.2f} MB); 1 m / 10 m meander {sc['meander']['1m']['s']:.2f} s / "
        f"{sc['meander']['10m']['s']:.2f} s ({sc['meander']['ratio_10m_over_1m']:.3g} x; 10 m shape3d.svg "
        f"{sc['meander']['10m']['sizes_mb'].get('shape3d.svg', 0):.2f} MB)"
        + ("" if "1000" not in sc["grid"] else
           f"; 1000 zigzags: exit {sc['grid']['1000']['rc']} in {sc['grid']['1000']['s']:.1f} s, peak "
           f"{sc['grid']['1000']['peak_mb']:.0f} MB" + (f" ({sc['grid']['1000']['stderr'][0]})" if sc['grid']['1000']['rc']
                                                       else ""))
        + (f"; a 10 m / 100 m meander generated and analysed in process {sc['long_paths']['median_s']['10m']:.3g} / "
           f"{sc['long_paths']['median_s']['100m']:.3g} s "
           f"(**{sc['long_paths']['ratio']['median']:.3g} x** [{sc['long_paths']['ratio']['min']:.3g}, "
           f"{sc['long_paths']['ratio']['max']:.3g}], linear 10 x), its build refused before generating (exit "
           f"{sc['long_paths']['refused']['rc']}) in {sc['long_paths']['refused']['s']:.2f} s (`"
           f"{(sc['long_paths']['refused']['stderr'] or [''])[0]}`)" if "long_paths" in sc else "")
        + f"; 100 tiny actuators +-999,999 mm apart: exit {sc['far_apart']['rc']} in {sc['far_apart']['s']:.2f} s"
        + (f" (`{sc['far_apart']['stderr'][0]}`)" if sc['far_apart']['stderr'] else "") + "."]
    r, ms = c["ratios"], c["per_curve_ms"]

    def x(k):
        return f"{r[k]['median']:.3g} x [{r[k]['min']:.3g}, {r[k]['max']:.3g}]"

    ru = res.get("rules")
    ru_s = ru["median_s"] if ru else {}
    rules_lines = [] if not ru else [
        f"* Model rules (EA401-EA406) on identical small zigzags, a fresh analysis each time: "
        f"{' / '.join(str(n) for n in ru['sizes'])} actuators in "
        f"{' / '.join(f'{ru_s[str(n)]:.3g}' for n in ru['sizes'])} s (**{ru['ratio']['median']:.3g} x** "
        f"[{ru['ratio']['min']:.3g}, {ru['ratio']['max']:.3g}], {ru['ratio']['rounds']} paired rounds; linear would be "
        f"{ru['linear_ratio']:.3g} x): the curve and the lock-up search of identical models are made once."]
    inv = res.get("inverse")
    inverse_lines = [] if not inv else [
        f"* Inverse design from the command line (fresh `embroact design` processes, {inv['rounds']} rounds paired with "
        f"the import floor `python {inv['floor']}`, {inv['floor_s']:.2f} s): unreachable targets answered without a "
        f"search in " + ", ".join(f"{k.replace('_', ' ')} {v['median_s']:.2f} s ({v['over_floor']['median']:.3g} x "
                                  f"floor, exit {'/'.join(map(str, v['exit_codes']))})"
                                  for k, v in inv["unreachable"].items())
        + "; target bends " + ", ".join(f"{k.split('_')[1]} {k.split('_')[2]} deg at {k.split('_')[4]} kPa "
                                        f"{v['median_s']:.2f} s ({v['over_floor']['median']:.3g} x floor)"
                                        for k, v in inv["bend"].items())
        + f" (median **{inv['bend_median_s']:.2f} s**)."]
    return "\n".join([
        f"* Curves, every ratio paired ({c['rounds']} interleaved rounds over the {len(res['designs'])} designs; median "
        f"[min, max] of the per-round ratios): repeated calls on one model (its branch nodes kept, as the studio and "
        f"inverse design make them) `auto` {ms['auto']:.3g} ms per 200-pressure curve against the competitor's "
        f"{ms['competitor']:.3g} ms (`competitor_numpy.py`: closed form, table + 4 secant steps, "
        f"{c['angle_err_max_deg']:.1e} deg; speed-up **{x('auto_speedup')}**); a first call on a new model "
        f"{ms['auto_cold']:.3g} ms: speed-up **{x('cold_speedup')}** over the competitor's first call (it keeps "
        f"nothing: every call is a first call), {x('cold_speedup_vs_dense')} over the dense-grid version ({ms['dense']:.3g} ms: "
        f"{c['dense']['grid_points']} points, {c['dense']['secant_steps']} secant steps, "
        f"{c['dense_angle_err_max_deg']:.1e} deg), {x('cold_over_warm')} a repeated call. One pressure: "
        f"{ms['auto_one']:.3g} ms repeated ({x('one_over_200')} of 200), {ms['auto_cold_one']:.3g} ms first "
        f"({x('cold_one_over_200')} of a first 200-pressure call); one closed-form evaluation at the 200 angles "
        f"{ms['eval']:.3g} ms (a repeated `auto` curve = {x('auto_over_eval')} evaluations).",
        f"* `auto` against the scipy baseline (same {len(b['designs'])} designs): {b['auto_time_per_curve_ms']:.3g} ms "
        f"against {b['time_per_curve_ms'] / 1e3:.3g} s per curve, **{b['speedup_auto']:.3g} times faster**, with a "
        f"maximum angle error of {b['auto_angle_err_max_deg']:.1e} deg against {b['angle_err_max_deg']:.1e} deg.",
        f"* `auto` against the closed form as printed (`{pr['method']}`, same machinery): the printed form is "
        f"{pr['time_ratio_to_auto']:.3g} times slower and its largest angle error ({pr['angle_err_max_deg']:.1e} deg) "
        f"is {pr['error_ratio_to_auto']:.2g} times `auto`'s.",
        f"* Sweeps: `sweep` of {tp['default_rtol']['designs']} designs x {tp['default_rtol']['pressures']} pressures "
        f"in {tp['default_rtol']['time_s'] * 1e3:.0f} ms = {tp['default_rtol']['evals_per_s']:.3g} design-pressure "
        f"evaluations/s ({tp['rtol_1e-6']['evals_per_s']:.3g}/s at rtol 1e-6); the competitor vectorised across the "
        f"same designs (one call, each row its own table) {tp['competitor']['time_s'] * 1e3:.0f} ms: `sweep` "
        f"**{tp['sweep_speedup_vs_competitor']['median']:.3g} x** [{tp['sweep_speedup_vs_competitor']['min']:.3g}, "
        f"{tp['sweep_speedup_vs_competitor']['max']:.3g}] ({tp['rounds']} paired rounds; the two agree to "
        f"{tp['competitor_vs_sweep_max_deg']:.1e} deg on the bending points); "
        f"{tp['vectorised_per_design_ms']:.3g} ms per design against {tp['loop_of_curve_per_design_ms']:.3g} ms in a "
        f"loop of `curve()` ({tp['vectorised_over_loop']['median']:.3g} times).",
        f"* Stitch generation on a {st['needle_rate'][0]['length_mm'] / 1000:g} m curved path: {rates}.",
        f"* The {ld['length_mm'] / 1000:g} m zigzag design ({ld['stitches']} stitches): generated in "
        f"{ld['generate_s'] * 1e3:.0f} ms, checked (every rule, {ld['findings']} findings) in {ld['check_s'] * 1e3:.0f} ms, "
        f"written as DST in {ld['write_s'] * 1e3:.0f} ms; peak memory {ld['peak_rss_mb']:.0f} MB for the whole process "
        f"({ld['tracemalloc_peak_mb']:.0f} MB traced allocations of the work itself).",
        f"* Command line (median wall time of fresh processes): `python -c pass` {cli['python_pass'] * 1e3:.0f} ms, "
        f"`python -c 'import argparse'` {cli['python_argparse'] * 1e3:.0f} ms, "
        f"`embroact --help` {cli['embroact_help'] * 1e3:.0f} ms; import floor (numpy, shapely, "
        f"{stitch_bench.MACHINE_LIBRARY}) {cli['import_floor'] * 1e3:.0f} ms, "
        f"`embroact zigzag ... -o x.dst` {cli['embroact_zigzag'] * 1e3:.0f} ms, `embroact check x.dst` "
        f"{cli['embroact_check_dst'] * 1e3:.0f} ms, `embroact build` (default design, every output) "
        f"{cli['embroact_build'] * 1e3:.0f} ms. `--help` loads "
        f"{', '.join(st['help_heavy_imports']) or 'none of numpy, shapely, trimesh, scipy'}.",
        f"* Machine: {res['machine']['cpus']} cores, Python {res['machine']['python']}, load average at the start "
        f"{res['machine']['load_average'][0]:.2f} (other jobs were running); whole run {res['elapsed_s']:.0f} s.",
    ] + rules_lines + scale_lines + inverse_lines)


def markdown_stability(res: dict) -> str:
    """The table of where each method is within the stability map's tolerance, from a results dict."""
    st, classes = res["stability"]["summary"], res["stability"]["grid"]["classes"]
    failed = classes[stability.FAILED_CLASS]

    def start(v):
        return "never" if v is None else f"{v:.2g}"

    lines = ["| method | zigzag: within 1e-6 rel. from [deg] | cross: from [deg] | failed cells (zigzag / cross) | "
             "largest error on the sample [deg] |", "|---|---:|---:|---:|---:|"]
    for m in METHODS:
        z, x = st[m]["zigzag"], st[m]["cross"]
        lines.append(f"| `{m}` | {start(z['within_tolerance_from_deg'])} | {start(x['within_tolerance_from_deg'])} | "
                     f"{z['counts'][failed]} / {x['counts'][failed]} | {res['methods'][m]['angle_err_max_deg']:.1e} |")
    return "\n".join(lines)


#: The generated blocks of a README: name -> the function that writes it from a results dict.
README_BLOCKS = {"targets": markdown_targets, "methods": markdown_table, "notes": markdown_notes,
                 "stability": markdown_stability}
#: The READMEs whose blocks come from the committed results.json.
READMES = (Path(__file__).resolve().parent / "README.md", Path(__file__).resolve().parents[1] / "README.md")


def readme_blocks(text: str) -> dict:
    """The generated blocks found in a README's text: name -> body (between the markers)."""
    out = {}
    for name in README_BLOCKS:
        begin, end = f"<!-- begin:{name} -->\n", f"\n<!-- end:{name} -->"
        if begin in text:
            out[name] = text.split(begin, 1)[1].split(end, 1)[0]
    return out


def update_readme(res: dict, path: Path) -> None:
    """Replace the body of each ``<!-- begin:NAME -->`` ... ``<!-- end:NAME -->`` block of the README by the
    text :data:`README_BLOCKS` makes from ``res``."""
    text = path.read_text()
    for name in readme_blocks(text):
        begin, end = f"<!-- begin:{name} -->", f"<!-- end:{name} -->"
        head, rest = text.split(begin, 1)
        text = head + begin + "\n" + README_BLOCKS[name](res) + "\n" + end + rest.split(end, 1)[1]
    path.write_text(text)


def _jsonable(obj):
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _jsonable(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        v = float(obj)
        return v if math.isfinite(v) else str(v)
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def run(cfg: Config, out_dir: Path) -> dict:
    """Every benchmark with ``cfg``; writes the three files into ``out_dir`` and returns the results."""
    t_start = time.perf_counter()
    res = {"config": asdict(cfg), "machine": {"python": platform.python_version(), "cpus": os.cpu_count(),
                                              "platform": platform.platform(),
                                              "load_average": list(os.getloadavg())}}
    _log(f"design sample: {cfg.n_designs} designs x {cfg.n_pressures} pressures; 50-digit references")
    designs, points = _sample(cfg.n_designs, cfg.n_pressures)
    res["designs"] = [{**d.as_dict(), "max_pressure_kpa": float(p[-1]), "max_theta_deg": float(th[-1])}
                      for d, (p, th) in zip(designs, points)]
    _log("methods (time per curve, max errors vs mpmath):")
    res["methods"] = _methods(cfg, designs, points)
    _log("scipy baseline:")
    res["baseline_scipy"] = _baseline(cfg, designs, points, res["methods"])
    auto, printed = res["methods"][AUTO], res["methods"][PRINTED]
    res["baseline_printed"] = {"method": PRINTED, "time_ratio_to_auto": printed["time_per_curve_ms"]
                               / auto["time_per_curve_ms"], "angle_err_max_deg": printed["angle_err_max_deg"],
                               "error_ratio_to_auto": printed["angle_err_max_deg"] / max(auto["angle_err_max_deg"],
                                                                                         1e-300)}
    b = res["baseline_scipy"]
    _log(f"  scipy {b['time_per_curve_ms']:.4g} ms/curve (auto {b['auto_time_per_curve_ms']:.3g} ms on the same "
         f"designs: {b['speedup_auto']:.3g}x), angle err {b['angle_err_max_deg']:.2e} deg")
    _log("stability maps:")
    res["stability"] = _stability(cfg)
    run_sections(cfg, res, SECTIONS)
    res["targets"] = targets(res)
    res["elapsed_s"] = time.perf_counter() - t_start
    out_dir.mkdir(parents=True, exist_ok=True)
    (out_dir / "results.json").write_text(json.dumps(_jsonable(res), indent=1, sort_keys=True) + "\n")
    write_charts(res, out_dir)
    return res


@lru_cache(maxsize=2)
def _sample(n_designs: int, n_pressures: int):
    """The design sample and its 50-digit reference points (made once per run: the methods and the curve
    section time the same designs)."""
    designs = sample_designs(n_designs)
    return designs, [reference_points(d, n_pressures) for d in designs]


def _curve(cfg: Config, res: dict) -> None:
    designs, points = _sample(cfg.n_designs, cfg.n_pressures)
    _log(f"curves, paired rounds ({cfg.curve_rounds}): auto warm and cold, the competitor, the dense grid:")
    res["competitor"] = _competitor(cfg, designs, points)
    c, r = res["competitor"], res["competitor"]["ratios"]
    _log("  ms/curve " + ", ".join(f"{k} {v:.3f}" for k, v in c["per_curve_ms"].items()))
    _log("  ratios (median [min, max]) " + ", ".join(f"{k} {v['median']:.3g} [{v['min']:.3g}, {v['max']:.3g}]"
                                                  for k, v in r.items()))
    _log(f"sweep against the competitor vectorised across designs, paired rounds ({cfg.sweep_rounds}):")
    res["throughput"] = _throughput(cfg)
    tp = res["throughput"]
    _log(f"  sweep {tp['default_rtol']['time_s'] * 1e3:.0f} ms, competitor {tp['competitor']['time_s'] * 1e3:.0f} ms: "
         f"{tp['sweep_speedup_vs_competitor']['median']:.3g}x (agree to {tp['competitor_vs_sweep_max_rel']:.1e} of the angle)")


def _rules(cfg: Config, res: dict) -> None:
    if cfg.rules_rounds:
        _log("model rules on identical actuators, paired rounds:")
        res["rules"] = rules_scaling.identical_model_rules(cfg.rules_rounds)
        _log(f"  {res['rules']['median_s']} s: {res['rules']['ratio']['median']:.3g}x")


def _scale(cfg: Config, res: dict) -> None:
    if cfg.scale_runs:
        _log("scale (fresh build processes):")
        res["scale"] = scale_bench.scale(cfg.scale_runs)
        res["scale"]["long_paths"] = scale_bench.long_paths(cfg.scale_runs)
        lp = res["scale"]["long_paths"]
        _log(f"  10 m / 100 m meander analysed {lp['median_s']}: {lp['ratio']['median']:.3g}x; 100 m build refused "
             f"(exit {lp['refused']['rc']}) in {lp['refused']['s']:.2f} s")


def _inverse(cfg: Config, res: dict) -> None:
    if cfg.inverse_rounds:
        _log(f"inverse design from the command line, paired rounds ({cfg.inverse_rounds}) with the import floor:")
        res["inverse"] = inv = inverse_bench.cli_timings(cfg.inverse_rounds)
        _log("  " + ", ".join(f"{k} {v['median_s']:.2f} s ({v['over_floor']['median']:.3g} x floor)"
                              for k, v in {**inv["unreachable"], **inv["bend"]}.items()))


#: The sections :func:`run_sections` can run again into an existing results.json (``run.py --only``).
SECTIONS = {"stitches": _stitches, "curve": _curve, "rules": _rules, "scale": _scale, "inverse": _inverse}


def run_sections(cfg: Config, res: dict, names) -> dict:
    """Run the sections ``names`` of :data:`SECTIONS` with ``cfg`` into ``res`` (a results dict; what the others
    measured is kept) and recompute the targets; returns ``res``.

    Examples
    --------
    >>> sorted(SECTIONS)
    ['curve', 'inverse', 'rules', 'scale', 'stitches']
    """
    for name in names:
        SECTIONS[name](cfg, res)
    if "methods" in res and "stitches" in res:
        res["targets"] = targets(res)
    return res


def write_charts(res: dict, out_dir: Path) -> None:
    """pareto.svg and stability.svg from a results dict (as written to results.json)."""
    g = res["stability"]["grid"]
    (out_dir / "pareto.svg").write_text(charts.pareto_svg(_pareto_points(res)))
    maps = {m: g["maps"][m] for m in METHODS}  # the order of METHODS, whatever the JSON's
    (out_dir / "stability.svg").write_text(charts.stability_svg(
        maps, g["theta_abs_deg"], {pt: (g["row_labels"][pt], g["rows"][pt]) for pt in _PATTERNS}, g["classes"]))


def _update_readmes(res: dict, out: Path) -> None:
    """The README of ``out`` (and, when ``out`` is this folder, the project's README) from ``res``."""
    paths = READMES if out.resolve() == READMES[0].parent else (out / "README.md",)
    for path in paths:
        if path.exists():
            update_readme(res, path)


def main(argv=None) -> int:
    """Command line; returns 0 (targets are reported, not enforced: this is a benchmark)."""
    ap = argparse.ArgumentParser(description="embroact benchmarks (speed against accuracy)")
    ap.add_argument("--quick", action="store_true", help="smoke run: tiny sample, timings meaningless")
    ap.add_argument("--out", type=Path, default=None,
                    help="output folder (default: this folder; with --quick a temporary folder, so the smoke run "
                         "never overwrites the committed results)")
    ap.add_argument("--only", default=None, metavar="SECTIONS",
                    help=f"run only these sections again ({', '.join(SECTIONS)}; comma-separated) into OUT/results.json, "
                         "keeping the rest, and regenerate the charts and README blocks")
    ap.add_argument("--replot", action="store_true",
                    help="only redraw the charts from OUT/results.json (and its README tables, if OUT has a README)")
    args = ap.parse_args(argv)
    if args.out is None:
        args.out = Path(tempfile.gettempdir()) / "embroact-bench-quick" if args.quick else Path(__file__).resolve().parent
    if args.only:
        names = [n for n in args.only.split(",") if n]
        unknown = sorted(set(names) - set(SECTIONS))
        if unknown:
            ap.error(f"--only: unknown section(s) {', '.join(unknown)}; choose from {', '.join(SECTIONS)}")
        res = json.loads((args.out / "results.json").read_text())
        res["machine"][f"load_average_{'_'.join(names)}"] = list(os.getloadavg())
        run_sections(CONFIGS["quick" if args.quick else "full"], res, names)
        (args.out / "results.json").write_text(json.dumps(_jsonable(res), indent=1, sort_keys=True) + "\n")
        res = json.loads((args.out / "results.json").read_text())  # as --replot reads it (keys are strings)
        write_charts(res, args.out)
        _update_readmes(res, args.out)
        _log("\n" + markdown_targets(res) + "\n")
        return 0
    if args.replot:
        res = json.loads((args.out / "results.json").read_text())
        write_charts(res, args.out)
        _update_readmes(res, args.out)
        return 0
    res = run(CONFIGS["quick" if args.quick else "full"], args.out)
    if not args.quick:
        _update_readmes(json.loads((args.out / "results.json").read_text()), args.out)
    _log("\n" + markdown_table(res) + "\n\n" + markdown_targets(res) + "\n")
    _log(f"wrote results.json, pareto.svg, stability.svg to {args.out} in {res['elapsed_s']:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
