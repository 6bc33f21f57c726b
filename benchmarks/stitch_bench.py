"""Stitch generation, file writing and the command line, timed.

* Needle points per second of the generators on a long curved path (a meander).
* ``embroact zigzag ... -o x.dst``, ``embroact check x.dst`` and the default
  ``embroact build`` against the import floor ``python -c "import numpy, shapely,
  pystitch"`` (the machine-file library), and ``embroact --help`` against
  ``python -c "import argparse"`` (and ``python -c pass``): wall time of subprocesses, median of several runs after one
  warm-up. The subprocesses run with bytecode caching on (in a temporary
  ``PYTHONPYCACHEPREFIX``), as an installed package runs; the shell's
  ``PYTHONDONTWRITEBYTECODE`` would otherwise recompile embroact on every start.
* Which heavy modules ``embroact --help`` imports (``sys.modules`` in a subprocess).
* A 10 m curved design generated, checked (every rule) and written as DST in a fresh
  subprocess: wall time of those three steps and the process's peak memory
  (``ru_maxrss``: everything, interpreter and libraries included) and the peak of
  traced allocations (``tracemalloc``, timed separately because tracing slows it).

Examples
--------
>>> from stitch_bench import meander
>>> pts = meander(1000.0)
>>> pts.shape[1], 990.0 < float(((pts[1:] - pts[:-1]) ** 2).sum(axis=1).__pow__(0.5).sum()) < 1010.0
(2, True)
"""
from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

__all__ = ["meander", "needle_rate", "cli_timings", "help_imports", "ten_metre", "HEAVY"]

#: The machine-file library the import floor loads with numpy and shapely.
MACHINE_LIBRARY = "pystitch"
#: Modules ``embroact --help`` must not import.
HEAVY = ("numpy", "shapely", "trimesh", "scipy")
#: Meander: amplitude and wavelength [mm] (curvature radius >= 50 mm, far above the 9 mm rule).
AMPLITUDE_MM, WAVELENGTH_MM = 20.0, 200.0
#: Path vertex spacing along x [mm].
VERTEX_SPACING_MM = 1.0
_ZIGZAG_ARGS = ["zigzag", "--width-mm", "7", "--interval-mm", "1", "--length-mm", "100"]


def meander(length_mm: float) -> np.ndarray:
    """Vertices [mm] of a sine meander whose arc length is ``length_mm`` (to 0.1 %)."""
    k = 2 * np.pi / WAVELENGTH_MM
    x = np.linspace(0.0, WAVELENGTH_MM, 2001)
    y = np.sqrt(1 + (AMPLITUDE_MM * k * np.cos(k * x)) ** 2)
    stretch = float(np.sum((y[1:] + y[:-1]) * np.diff(x))) / 2.0 / WAVELENGTH_MM  # trapezoid rule (np.trapezoid is numpy >= 2)
    span = length_mm / stretch
    x = np.linspace(0.0, span, int(span / VERTEX_SPACING_MM) + 2)
    return np.column_stack([x, AMPLITUDE_MM * np.sin(k * x)])


def _plan(pattern: str, length_mm: float):
    from embroact.patterns.centerline import Centerline
    from embroact.patterns.params import CrossParams, ZigzagParams

    path = Centerline.from_points(meander(length_mm))
    if pattern == "cross":
        from embroact.patterns.cross import cross

        return lambda: cross(path, CrossParams(7.0, 1.4, 45.0))
    from embroact.patterns.zigzag import zigzag

    return lambda: zigzag(path, ZigzagParams(7.0, 1.0))


def needle_rate(pattern: str, length_mm: float, *, repeats: int = 3) -> dict:
    """Needle points per second generating ``pattern`` along a meander of ``length_mm``."""
    make = _plan(pattern, length_mm)
    plan = make()
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        make()
        times.append(time.perf_counter() - t)
    med = statistics.median(times)
    return {"pattern": pattern, "length_mm": length_mm, "needle_points": plan.stitch_count, "time_s": med,
            "points_per_s": plan.stitch_count / med}


def _env() -> dict:
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env["PYTHONPYCACHEPREFIX"] = str(Path(tempfile.gettempdir()) / "embroact-bench-pycache")
    return env


def _entry() -> list[str]:
    """How ``embroact`` starts: the interpreter running the installed console script."""
    script = Path(sys.executable).with_name("embroact")
    if script.exists():
        return [sys.executable, str(script)]
    return [sys.executable, "-c", "import sys; from embroact.export.cli.main import main; sys.exit(main())"]


def cli_timings(runs: int) -> dict:
    """Median wall times [s] of the commands (interleaved runs) and their ratios to the floors."""
    with tempfile.TemporaryDirectory() as tmp:
        dst = str(Path(tmp) / "x.dst")
        (Path(tmp) / "build").mkdir()
        cmds = {
            "python_pass": [sys.executable, "-c", "pass"],
            "python_argparse": [sys.executable, "-c", "import argparse"],
            "embroact_help": _entry() + ["--help"],
            "import_floor": [sys.executable, "-c", f"import numpy, shapely, {MACHINE_LIBRARY}"],
            "embroact_zigzag": _entry() + _ZIGZAG_ARGS + ["-o", dst],
            "embroact_check_dst": _entry() + ["check", dst],
            "embroact_build": _entry() + ["build", "--out", str(Path(tmp) / "build")],
        }
        env = _env()
        times = {k: [] for k in cmds}
        for i in range(runs + 1):
            for k, c in cmds.items():
                t = time.perf_counter()
                subprocess.run(c, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, check=True)
                if i:  # the first round warms the bytecode cache and the OS file cache
                    times[k].append(time.perf_counter() - t)
    med = {k: statistics.median(v) for k, v in times.items()}
    return {"median_s": med, "min_s": {k: min(v) for k, v in times.items()}, "runs": runs,
            "zigzag_over_floor": med["embroact_zigzag"] / med["import_floor"],
            "check_dst_over_floor": med["embroact_check_dst"] / med["import_floor"],
            "build_over_floor": med["embroact_build"] / med["import_floor"],
            "help_over_pass": med["embroact_help"] / med["python_pass"],
            "help_over_argparse": med["embroact_help"] / med["python_argparse"]}


def help_imports() -> list[str]:
    """Heavy modules loaded after ``main(["--help"])`` in a fresh interpreter."""
    code = ("import contextlib, io, json, sys\nfrom embroact.export.cli.main import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n    main(['--help'])\n"
            f"print(json.dumps(sorted(m for m in {HEAVY!r} if m in sys.modules)))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=_env())
    return json.loads(out.stdout.strip().splitlines()[-1])


_TEN_METRE = """
import json, resource, sys, time, tracemalloc
sys.path.insert(0, {here!r})
from stitch_bench import meander
from embroact.patterns.centerline import Centerline
from embroact.patterns.params import ZigzagParams
from embroact.patterns.rules import check_geometry
from embroact.patterns.zigzag import zigzag
from embroact.export.machine.formats import write
trace = {trace!r}
if trace:
    tracemalloc.start()
t = time.perf_counter()
plan = zigzag(Centerline.from_points(meander({length!r})), ZigzagParams(7.0, 1.0))
t_gen = time.perf_counter()
findings = check_geometry(plan)
t_check = time.perf_counter()
res = write(plan, {out!r})
t_write = time.perf_counter()
print(json.dumps({{"generate_s": t_gen - t, "check_s": t_check - t_gen, "write_s": t_write - t_check,
                  "total_s": t_write - t, "stitches": res.stitches, "findings": len(findings),
                  "errors": sum(f.severity.name == "ERROR" for f in findings),
                  "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                  "tracemalloc_peak_mb": tracemalloc.get_traced_memory()[1] / 2**20 if trace else None}}))
"""


def ten_metre(length_mm: float, runs: int) -> dict:
    """Generate + check + write a curved design of ``length_mm`` in fresh subprocesses (median of runs)."""
    here = str(Path(__file__).resolve().parent)
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for trace in [False] * runs + [True]:
            code = _TEN_METRE.format(here=here, trace=trace, length=length_mm, out=str(Path(tmp) / "ten.dst"))
            out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=_env())
            if out.returncode:
                raise RuntimeError(f"10 m design run failed: {out.stderr.strip().splitlines()[-1]}")
            results.append(json.loads(out.stdout.strip().splitlines()[-1]))
    timed_runs = results[:-1]
    summary = {k: statistics.median(r[k] for r in timed_runs) for k in ("generate_s", "check_s", "write_s",
                                                                         "total_s", "peak_rss_mb")}
    summary.update(length_mm=length_mm, runs=runs, stitches=timed_runs[0]["stitches"],
                   findings=timed_runs[0]["findings"], errors=timed_runs[0]["errors"],
                   tracemalloc_peak_mb=results[-1]["tracemalloc_peak_mb"])
    return summary
