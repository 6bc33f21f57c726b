"""Design rules on 10, 100 and 300 actuators: time ratios measured in the same run.

Each design is a grid of 40 mm zigzags (10 columns 110 mm apart, rows 15 mm apart,
every rule passes) in a hoop large enough for all of them. Every rule that runs on
a plan (``embroact.predict.sleeve_rules.check_without_model``: geometry, pattern, tubes,
machine file, sleeve) is timed; the best of ``--repeats`` interleaved rounds is kept
per size (a round checks each design often enough to take about as long as the
300-actuator check), so the ratios compare like with like on a shared machine.

Target (issue 17): 300 actuators at most 35x the time of 10 (linear: 30x).

Model rules (EA401-EA406, :func:`identical_model_rules`): a design of 100 and one of 1000
identical small zigzags (the scale benchmark's grid), each check on a fresh analysis with the
model caches emptied, timed in paired rounds (``benchmarks/run.py`` reports the ratio; target:
1000 at most 3x the time of 100, the work shared between identical actuators done once).

Run: ``python benchmarks/rules_scaling.py [--repeats 15]``; prints one JSON object.
"""
from __future__ import annotations

import argparse
import gc
import json
import statistics
import time

SIZES = (10, 100, 300)
TARGET_300_OVER_10 = 35.0


def grid_design(n: int, *, row_mm: float = 15.0):
    """``n`` zigzag actuators, w 7 mm, s 1 mm, 40 mm long, on a grid of 10 columns."""
    from embroact.patterns.design import design_from_dict

    acts = [{"name": f"A{i}", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 40,
             "origin_mm": [(i % 10) * 110.0, (i // 10) * row_mm]} for i in range(n)]
    return design_from_dict({"name": f"grid-{n}", "actuator": acts})


def measure(repeats: int) -> dict:
    """Best time per check [s] per size, the ratios to 10 actuators, and the work counted."""
    from embroact.patterns.design import build_plan
    from embroact.patterns.rules import RuleSettings, engine, layout_from_plan
    from embroact.predict.sleeve_rules import DESIGN_RULES, check_without_model

    settings = RuleSettings(hoop_width_mm=9000.0, hoop_height_mm=9000.0)
    plans = {n: build_plan(grid_design(n)) for n in SIZES}
    findings = {n: len(check_without_model(p, settings)) for n, p in plans.items()}  # warm-up, and must be 0
    best = {n: float("inf") for n in SIZES}
    gc.disable()
    try:
        for _ in range(repeats):
            for n, plan in plans.items():
                k = max(1, SIZES[-1] // n)
                t = time.perf_counter()
                for _ in range(k):
                    check_without_model(plan, settings)
                best[n] = min(best[n], (time.perf_counter() - t) / k)
    finally:
        gc.enable()
    work = {}
    for n, plan in plans.items():
        s = engine.Subject(layout_from_plan(plan), settings, plan)
        engine.run_rules(DESIGN_RULES, s)
        work[n] = {"records": len(plan), "tree_queries": s.laid_tubes.queries + s.axes.queries,
                   "tube_pairs_compared": len(s.shared("tube pairs", list))}
    ratio = {f"{n}_over_{SIZES[0]}": best[n] / best[SIZES[0]] for n in SIZES[1:]}
    return {
        "best_s": best,
        "ratios": ratio,
        "linear_ratios": {f"{n}_over_{SIZES[0]}": n / SIZES[0] for n in SIZES[1:]},
        "target_300_over_10": TARGET_300_OVER_10,
        "pass": ratio[f"300_over_{SIZES[0]}"] <= TARGET_300_OVER_10,
        "findings": findings,
        "work": work,
    }


def identical_model_rules(rounds: int, sizes=(100, 1000)) -> dict:
    """Paired times of the model rules on ``sizes`` identical actuators (module docstring)."""
    from run import paired_ratio, paired_rounds
    from scale_bench import grid_design

    from embroact.patterns.design import design_from_dict
    from embroact.predict import curve as C
    from embroact.predict.analysis import analyse
    from embroact.predict.rules import check_model

    analyses = {n: analyse(design_from_dict(grid_design(n))) for n in sizes}

    def check(a):
        a._curves.clear()  # a fresh analysis: no curve kept, no branch or lock-up cached
        C._cached_branch.cache_clear()
        C._cached_lockup.cache_clear()
        return check_model(a)

    findings = {n: len(check(a)) for n, a in analyses.items()}
    times = paired_rounds({n: [lambda a=a: check(a)] for n, a in analyses.items()}, rounds)
    lo, hi = sizes
    return {"sizes": list(sizes), "findings": findings, "median_s": {n: statistics.median(t) for n, t in times.items()},
            "ratio": paired_ratio(times, hi, lo), "linear_ratio": hi / lo}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=15, help="interleaved rounds (best kept)")
    res = measure(parser.parse_args(argv).repeats)
    print(json.dumps(res, indent=2, sort_keys=True))
    return 0 if res["pass"] else 1


if __name__ == "__main__":
    raise SystemExit(main())
