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
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import charts  # noqa: E402
import model_bench  # noqa: E402
import stability  # noqa: E402
import stitch_bench  # noqa: E402
from baseline_scipy import baseline_of  # noqa: E402
from sample import reference_points, sample_designs  # noqa: E402

from embroact.predict.curve import METHODS, curve  # noqa: E402

__all__ = ["Config", "CONFIGS", "main", "run", "targets", "write_charts", "markdown_table", "markdown_targets",
           "markdown_notes", "update_readme"]

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


CONFIGS = {
    "full": Config(n_designs=12, n_pressures=200, time_budget_s=0.25, baseline_designs=4, baseline_points=6,
                   stability_grid="full", sweep_designs=1000, cli_runs=11, long_path_mm=10_000.0, long_path_runs=3),
    "quick": Config(n_designs=2, n_pressures=12, time_budget_s=0.0, baseline_designs=1, baseline_points=2,
                    stability_grid="quick", sweep_designs=8, cli_runs=1, long_path_mm=500.0, long_path_runs=1),
}

#: Targets of issue 7: name -> (unit, comparison, limit).
TARGETS = {
    "auto_curve_median_ms": ("ms", "<", 1.0),
    "auto_angle_err_max_deg": ("deg", "<", 1e-6),
    "auto_speedup_vs_scipy": ("x", ">=", 1000.0),
    "auto_error_vs_scipy": ("ratio", "<=", 1.0),
    "sweep_evals_per_s": ("1/s", ">=", 1e6),
    "zigzag_over_import_floor": ("x", "<=", 1.3),
    "help_over_python_pass": ("x", "<=", 2.0),
    "help_heavy_imports": ("modules", "==", 0),
    "long_design_total_s": ("s", "<", 2.0),
    "long_design_peak_rss_mb": ("MB", "<", 200.0),
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
    models = [d.model for d in sample_designs(cfg.sweep_designs, seed=7)]
    pressures = np.linspace(0.0, 400.0, 200 if cfg.sweep_designs > 100 else 12)
    out = {"default_rtol": model_bench.sweep_throughput(models, pressures),
           "rtol_1e-6": model_bench.sweep_throughput(models, pressures, rtol=1e-6)}
    few = models[: min(100, len(models))]
    t = time.perf_counter()
    for m in few:
        curve(m, pressures)
    loop = (time.perf_counter() - t) / len(few)
    out["loop_of_curve_per_design_ms"] = loop * 1e3
    out["vectorised_per_design_ms"] = out["default_rtol"]["time_s"] / len(models) * 1e3
    out["vectorised_over_loop"] = loop / (out["default_rtol"]["time_s"] / len(models))
    return out


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


def _stitches(cfg: Config) -> dict:
    return {
        "needle_rate": [stitch_bench.needle_rate(pt, cfg.long_path_mm) for pt in _PATTERNS],
        "cli": stitch_bench.cli_timings(cfg.cli_runs),
        "help_heavy_imports": stitch_bench.help_imports(),
        "long_design": stitch_bench.ten_metre(cfg.long_path_mm, cfg.long_path_runs),
    }


def targets(res: dict) -> dict:
    """Measured value and PASS/FAIL of each target in :data:`TARGETS`."""
    auto = res["methods"][AUTO]
    base = res["baseline_scipy"]
    values = {
        "auto_curve_median_ms": auto["time_per_curve_ms"],
        "auto_angle_err_max_deg": auto["angle_err_max_deg"],
        "auto_speedup_vs_scipy": base["speedup_auto"],
        "auto_error_vs_scipy": base["auto_angle_err_max_deg"] / base["angle_err_max_deg"]
        if base["angle_err_max_deg"] > 0 else math.inf,
        "sweep_evals_per_s": res["throughput"]["default_rtol"]["evals_per_s"],
        "zigzag_over_import_floor": res["stitches"]["cli"]["zigzag_over_floor"],
        "help_over_python_pass": res["stitches"]["cli"]["help_over_pass"],
        "help_heavy_imports": len(res["stitches"]["help_heavy_imports"]),
        "long_design_total_s": res["stitches"]["long_design"]["total_s"],
        "long_design_peak_rss_mb": res["stitches"]["long_design"]["peak_rss_mb"],
    }
    ops = {"<": lambda a, b: a < b, "<=": lambda a, b: a <= b, ">=": lambda a, b: a >= b, "==": lambda a, b: a == b}
    return {k: {"value": v, "unit": TARGETS[k][0], "target": f"{TARGETS[k][1]} {TARGETS[k][2]:g}",
                "pass": bool(v is not None and ops[TARGETS[k][1]](v, TARGETS[k][2]))} for k, v in values.items()}


def _pareto_points(res: dict) -> list[dict]:
    pts = [{"label": m if m != AUTO else f"auto = {res['methods'][m]['resolved'][0]}",
            "time_ms": res["methods"][m]["time_per_curve_ms"], "error_deg": res["methods"][m]["angle_err_max_deg"],
            "kind": "auto" if m == AUTO else "method"}
           for m in METHODS if m != AUTO or res["methods"][m]["resolved"]]
    b = res["baseline_scipy"]
    pts.append({"label": "scipy baseline (dblquad, central, brentq)", "time_ms": b["time_per_curve_ms"],
                "error_deg": b["angle_err_max_deg"], "kind": "baseline"})
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
        lines.append(f"| {k} | {float(t['value']):.4g} {t['unit']} | {t['target']} | "
                     f"{'PASS' if t['pass'] else '**FAIL**'} |")
    return "\n".join(lines)


def markdown_notes(res: dict) -> str:
    """The README's figures besides the two tables (ratios, sweeps, stitches, command line)."""
    b, pr, tp = res["baseline_scipy"], res["baseline_printed"], res["throughput"]
    st, cli, ld = res["stitches"], res["stitches"]["cli"]["median_s"], res["stitches"]["long_design"]
    rates = ", ".join(f"{r['pattern']} {r['points_per_s']:.3g} needle points/s ({r['needle_points']} points in "
                      f"{r['time_s'] * 1e3:.0f} ms)" for r in st["needle_rate"])
    return "\n".join([
        f"* `auto` against the scipy baseline (same {len(b['designs'])} designs): {b['auto_time_per_curve_ms']:.3g} ms "
        f"against {b['time_per_curve_ms'] / 1e3:.3g} s per curve, **{b['speedup_auto']:.3g} times faster**, with a "
        f"maximum angle error of {b['auto_angle_err_max_deg']:.1e} deg against {b['angle_err_max_deg']:.1e} deg.",
        f"* `auto` against the closed form as printed (`{pr['method']}`, same machinery): the printed form is "
        f"{pr['time_ratio_to_auto']:.3g} times slower and its largest angle error ({pr['angle_err_max_deg']:.1e} deg) "
        f"is {pr['error_ratio_to_auto']:.2g} times `auto`'s.",
        f"* Sweeps: `sweep` of {tp['default_rtol']['designs']} designs x {tp['default_rtol']['pressures']} pressures "
        f"in {tp['default_rtol']['time_s'] * 1e3:.0f} ms = **{tp['default_rtol']['evals_per_s']:.3g} design-pressure "
        f"evaluations/s** ({tp['rtol_1e-6']['evals_per_s']:.3g}/s at rtol 1e-6); "
        f"{tp['vectorised_per_design_ms']:.3g} ms per design against {tp['loop_of_curve_per_design_ms']:.3g} ms in a "
        f"loop of `curve()` ({tp['vectorised_over_loop']:.3g} times).",
        f"* Stitch generation on a {st['needle_rate'][0]['length_mm'] / 1000:g} m curved path: {rates}.",
        f"* The {ld['length_mm'] / 1000:g} m zigzag design ({ld['stitches']} stitches): generated in "
        f"{ld['generate_s'] * 1e3:.0f} ms, checked (every rule, {ld['findings']} findings) in {ld['check_s'] * 1e3:.0f} ms, "
        f"written as DST in {ld['write_s'] * 1e3:.0f} ms; peak memory {ld['peak_rss_mb']:.0f} MB for the whole process "
        f"({ld['tracemalloc_peak_mb']:.0f} MB traced allocations of the work itself).",
        f"* Command line (median wall time of fresh processes): `python -c pass` {cli['python_pass'] * 1e3:.0f} ms, "
        f"`embroact --help` {cli['embroact_help'] * 1e3:.0f} ms; import floor {cli['import_floor'] * 1e3:.0f} ms, "
        f"`embroact zigzag ... -o x.dst` {cli['embroact_zigzag'] * 1e3:.0f} ms. `--help` loads "
        f"{', '.join(st['help_heavy_imports']) or 'none of numpy, shapely, trimesh, scipy'}.",
        f"* Machine: {res['machine']['cpus']} cores, Python {res['machine']['python']}, load average at the start "
        f"{res['machine']['load_average'][0]:.2f} (other jobs were running); whole run {res['elapsed_s']:.0f} s.",
    ])


def update_readme(res: dict, path: Path) -> None:
    """Replace the blocks between ``<!-- begin:NAME -->`` and ``<!-- end:NAME -->`` in the README."""
    text = path.read_text()
    for name, body in (("targets", markdown_targets(res)), ("methods", markdown_table(res)),
                       ("notes", markdown_notes(res))):
        begin, end = f"<!-- begin:{name} -->", f"<!-- end:{name} -->"
        head, rest = text.split(begin, 1)
        text = head + begin + "\n" + body + "\n" + end + rest.split(end, 1)[1]
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
    designs = sample_designs(cfg.n_designs)
    points = [reference_points(d, cfg.n_pressures) for d in designs]
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
    _log("sweep throughput:")
    res["throughput"] = _throughput(cfg)
    tp = res["throughput"]
    _log(f"  {tp['default_rtol']['evals_per_s']:.3g} evals/s (rtol 1e-6: {tp['rtol_1e-6']['evals_per_s']:.3g}); "
         f"vectorised {tp['vectorised_over_loop']:.3g}x a loop of curve()")
    _log("stability maps:")
    res["stability"] = _stability(cfg)
    _log("stitches, files, command line:")
    res["stitches"] = _stitches(cfg)
    for r in res["stitches"]["needle_rate"]:
        _log(f"  {r['pattern']}: {r['needle_points']} needle points on {r['length_mm']:g} mm in "
             f"{r['time_s'] * 1e3:.1f} ms = {r['points_per_s']:.3g} points/s")
    res["targets"] = targets(res)
    res["elapsed_s"] = time.perf_counter() - t_start
    out_dir.mkdir(parents=True, exist_ok=True)
    (out_dir / "results.json").write_text(json.dumps(_jsonable(res), indent=1, sort_keys=True) + "\n")
    write_charts(res, out_dir)
    return res


def write_charts(res: dict, out_dir: Path) -> None:
    """pareto.svg and stability.svg from a results dict (as written to results.json)."""
    g = res["stability"]["grid"]
    (out_dir / "pareto.svg").write_text(charts.pareto_svg(_pareto_points(res)))
    maps = {m: g["maps"][m] for m in METHODS}  # the order of METHODS, whatever the JSON's
    (out_dir / "stability.svg").write_text(charts.stability_svg(
        maps, g["theta_abs_deg"], {pt: (g["row_labels"][pt], g["rows"][pt]) for pt in _PATTERNS}, g["classes"]))


def main(argv=None) -> int:
    """Command line; returns 0 (targets are reported, not enforced: this is a benchmark)."""
    ap = argparse.ArgumentParser(description="embroact benchmarks (speed against accuracy)")
    ap.add_argument("--quick", action="store_true", help="smoke run: tiny sample, timings meaningless")
    ap.add_argument("--out", type=Path, default=None,
                    help="output folder (default: this folder; with --quick a temporary folder, so the smoke run "
                         "never overwrites the committed results)")
    ap.add_argument("--replot", action="store_true",
                    help="only redraw the charts from OUT/results.json (and its README tables, if OUT has a README)")
    args = ap.parse_args(argv)
    if args.out is None:
        args.out = Path(tempfile.gettempdir()) / "embroact-bench-quick" if args.quick else Path(__file__).resolve().parent
    if args.replot:
        res = json.loads((args.out / "results.json").read_text())
        write_charts(res, args.out)
        if (args.out / "README.md").exists():
            update_readme(res, args.out / "README.md")
        return 0
    res = run(CONFIGS["quick" if args.quick else "full"], args.out)
    if (args.out / "README.md").exists() and not args.quick:
        update_readme(json.loads((args.out / "results.json").read_text()), args.out / "README.md")
    _log("\n" + markdown_table(res) + "\n\n" + markdown_targets(res) + "\n")
    _log(f"wrote results.json, pareto.svg, stability.svg to {args.out} in {res['elapsed_s']:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
