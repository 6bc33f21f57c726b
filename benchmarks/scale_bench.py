"""How ``embroact build`` scales: many actuators, long paths, the size of what it writes.

Every figure is a ratio (or a size) measured in this run, each build a fresh
subprocess timed by wall clock with its peak memory from ``resource.getrusage``
(``RUSAGE_CHILDREN``, read in a small wrapper process so each build gets its own):

* a grid of ``n`` small zigzags (20 mm long, w 5 mm, 25 mm apart; every rule passes)
  built with ``n = 10`` and ``n = 100``: time ratio, peak memory, sizes of
  ``report.html`` and ``shape3d.svg``; ``n = 1000`` once: built within limits or
  refused up front (exit code and message);
* one zigzag along a sine meander (amplitude 20 mm, wavelength 200 mm) of 1 m and
  of 10 m: time ratio and the size of the 10 m design's ``shape3d.svg``;
* :func:`long_paths`: a 10 m and a 100 m meander generated and analysed in process (paired
  rounds), and the 100 m design's build refused before anything is generated;
* 100 tiny actuators placed +-999,999 mm apart: refused before anything is generated
  (by the hoop from the paths alone, exit 1, or by the record count, exit 2; time and the message).

Examples
--------
>>> from scale_bench import grid_design
>>> d = grid_design(4)
>>> len(d["actuator"]), d["actuator"][3]["origin_mm"]
(4, [100.0, 25.0])
"""
from __future__ import annotations

import json
import math
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

__all__ = ["grid_design", "meander_design", "far_apart_design", "run_build", "scale", "long_paths"]

#: Small zigzag of the actuator grid: length, width, interval [mm]; grid pitch along and across the tubes
#: [mm] (room for the tube's end margins in line, for the corridors side by side).
GRID_LENGTH_MM, GRID_WIDTH_MM, GRID_INTERVAL_MM = 20.0, 5.0, 1.0
GRID_PITCH_X_MM, GRID_PITCH_Y_MM = 100.0, 25.0
#: Largest hoop a design may name (exclusive limit 10 m).
HOOP_MAX_MM = 9_999.0
#: Limits a build of 1000 actuators must keep (or refuse up front).
LIMIT_1000_S, LIMIT_1000_MB = 60.0, 1024.0

_WRAPPER = """
import json, resource, subprocess, sys, time
t = time.perf_counter()
p = subprocess.run(sys.argv[1:], capture_output=True, text=True)
dt = time.perf_counter() - t
print(json.dumps({"s": dt, "rc": p.returncode, "peak_mb": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024,
                  "stderr": p.stderr.strip().splitlines()[-1:] }))
"""


def _design(name: str, actuators: list[dict], hoop_mm: float) -> dict:
    return {"name": name, "machine": {"hoop_width_mm": hoop_mm, "hoop_height_mm": hoop_mm}, "actuator": actuators}


def grid_design(n: int) -> dict:
    """``n`` small zigzags on a square grid (a design dict as the TOML reader takes it)."""
    side = math.ceil(math.sqrt(n))
    acts = [{"name": f"A{k}", "pattern": "zigzag", "width_mm": GRID_WIDTH_MM, "interval_mm": GRID_INTERVAL_MM,
             "length_mm": GRID_LENGTH_MM, "origin_mm": [GRID_PITCH_X_MM * (k % side), GRID_PITCH_Y_MM * (k // side)]}
            for k in range(n)]
    return _design(f"grid-{n}", acts, min(HOOP_MAX_MM, GRID_PITCH_X_MM * (side + 2) * 2))


def meander_design(length_mm: float) -> dict:
    """One zigzag along a sine meander of ``length_mm``."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from stitch_bench import meander

    pts = meander(length_mm)
    span = float(pts[:, 0].max()) + 200.0
    act = {"name": "S", "pattern": "zigzag", "width_mm": 7.0, "interval_mm": 1.0,
           "path": [[round(float(x), 4), round(float(y), 4)] for x, y in pts]}
    return _design(f"meander-{length_mm:g}", [act], min(HOOP_MAX_MM, 2 * span))


def far_apart_design(n: int = 100, spread_mm: float = 999_999.0) -> dict:
    """``n`` 10 mm zigzags alternately at -spread and +spread mm (the travel jumps are the records)."""
    acts = [{"name": f"T{k}", "pattern": "zigzag", "width_mm": GRID_WIDTH_MM, "interval_mm": GRID_INTERVAL_MM,
             "length_mm": 10.0, "origin_mm": [spread_mm * (-1) ** k, 0.0]} for k in range(n)]
    return _design("far-apart", acts, HOOP_MAX_MM)


def _toml(design: dict) -> str:
    """The design dict as TOML (its values are strings, numbers and lists of numbers only)."""
    def value(v):
        return json.dumps(v) if isinstance(v, (str, list)) else repr(float(v))

    lines = [f"name = {value(design['name'])}", "[machine]"]
    lines += [f"{k} = {value(v)}" for k, v in design["machine"].items()]
    for a in design["actuator"]:
        lines += ["[[actuator]]"] + [f"{k} = {value(v)}" for k, v in a.items()]
    return "\n".join(lines) + "\n"


def _entry() -> list[str]:
    from stitch_bench import _entry as entry

    return entry()


def run_build(design: dict, out_dir: Path, *extra: str) -> dict:
    """Build ``design`` into ``out_dir`` in a fresh process: wall time, exit code, peak MB, file sizes."""
    from stitch_bench import _env

    out_dir.mkdir(parents=True, exist_ok=True)
    src = out_dir / "design.toml"
    src.write_text(_toml(design))
    cmd = [sys.executable, "-c", _WRAPPER] + _entry() + ["build", str(src), "--out", str(out_dir), *extra]
    res = json.loads(subprocess.run(cmd, capture_output=True, text=True, env=_env(), check=True).stdout)
    res["sizes_mb"] = {p.name: p.stat().st_size / 2**20 for p in out_dir.iterdir() if p.name != "design.toml"}
    return res


def _median_build(design: dict, tmp: Path, runs: int) -> dict:
    results = [run_build(design, tmp / f"{design['name']}-{k}") for k in range(runs)]
    out = dict(results[0])
    out["s"] = statistics.median(r["s"] for r in results)
    out["runs"] = runs
    return out


def long_paths(rounds: int, lengths_mm=(10_000.0, 100_000.0)) -> dict:
    """A zigzag along a 10 m and a 100 m sine meander generated and analysed in this process (``analyse``:
    stitches, measurement, model), every round a fresh design of each (nothing cached), paired over
    ``rounds``; and the 100 m design built in a fresh process, refused before generating (its path alone
    spans more than any hoop): wall time of that refusal."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from run import paired_ratio, paired_rounds

    from embroact.patterns.design import design_from_dict
    from embroact.predict.analysis import analyse

    dicts = {mm: meander_design(mm) for mm in lengths_mm}
    fresh = {mm: iter([design_from_dict(d) for _ in range(rounds)]) for mm, d in dicts.items()}
    times = paired_rounds({mm: [lambda it=it: analyse(next(it))] for mm, it in fresh.items()}, rounds)
    lo, hi = lengths_mm
    with tempfile.TemporaryDirectory() as tmp:
        t = time.perf_counter()
        refused = run_build(dicts[hi], Path(tmp) / "long")
        refused["s"] = time.perf_counter() - t
    return {"lengths_mm": list(lengths_mm), "median_s": {f"{mm / 1000:g}m": statistics.median(v)
                                                        for mm, v in times.items()},
            "ratio": paired_ratio(times, hi, lo), "refused": refused}


def scale(runs: int, *, big: bool = True) -> dict:
    """Every scale figure (see the module docstring); ``big=False`` skips the 1000-actuator build."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        g10, g100 = (_median_build(grid_design(n), tmp, runs) for n in (10, 100))
        out["grid"] = {"10": g10, "100": g100, "ratio_100_over_10": g100["s"] / g10["s"]}
        m1, m10 = (_median_build(meander_design(mm), tmp, runs) for mm in (1_000.0, 10_000.0))
        out["meander"] = {"1m": m1, "10m": m10, "ratio_10m_over_1m": m10["s"] / m1["s"]}
        t = time.perf_counter()
        far = run_build(far_apart_design(), tmp / "far")
        out["far_apart"] = {**far, "s": time.perf_counter() - t}
        if big:
            out["grid"]["1000"] = run_build(grid_design(1000), tmp / "grid-1000")
    return out
