"""Speed and accuracy of every predict method on the design sample, and sweep throughput.

For each method of :data:`embroact.predict.curve.METHODS` and each design: the
wall time of ``curve(model, pressures)`` (median of repeats on one core) and, against
the reference of :mod:`sample`, the largest angle error [deg] over the curve and the
largest relative pressure error of ``pressure_at`` at the reference angles. A method
that raises, or returns a status other than the reference's (INFLATION below P0,
BENDING above) counts as a failure at those points; its error there is still measured
(the fill angle against the reference angle).

Examples
--------
>>> import numpy as np
>>> from model_bench import angle_errors
>>> angle_errors(np.array([0.0, 1.5]), np.array([0.0, 1.0])).tolist()
[0.0, 0.5]
"""
from __future__ import annotations

import gc
import statistics
import time

import numpy as np

from embroact.predict.curve import ActuatorModel, curve, pressure_at
from embroact.predict.status import Status

__all__ = ["timed", "angle_errors", "pressure_errors", "evaluate_method", "summarise"]

#: Per-design timing budget [s] and repeat cap; at least one run always.
TIME_BUDGET_S = 0.25
MAX_REPEATS = 25


def timed(fn, *, budget_s: float = TIME_BUDGET_S, max_repeats: int = MAX_REPEATS):
    """(result of the first call, list of wall times [s]) repeating ``fn()`` within the budget.

    As :mod:`timeit` does, the garbage collector is off while timing.
    """
    enabled = gc.isenabled()
    gc.disable()
    try:
        t0 = time.perf_counter()
        result = fn()
        times = [time.perf_counter() - t0]
        while sum(times) < budget_s and len(times) < max_repeats:
            t = time.perf_counter()
            fn()
            times.append(time.perf_counter() - t)
    finally:
        if enabled:
            gc.enable()
    return result, times


def angle_errors(theta_deg: np.ndarray, reference_deg: np.ndarray) -> np.ndarray:
    """Absolute angle error [deg] per point (inf where the method gave no finite angle)."""
    err = np.abs(np.asarray(theta_deg, dtype=float) - reference_deg)
    return np.where(np.isfinite(err), err, np.inf)


def pressure_errors(pressure_kpa: np.ndarray, reference_kpa: np.ndarray) -> np.ndarray:
    """Relative pressure error per point (inf where not finite)."""
    err = np.abs(np.asarray(pressure_kpa, dtype=float) - reference_kpa) / np.abs(reference_kpa)
    return np.where(np.isfinite(err), err, np.inf)


def _failed(status: np.ndarray, theta_ref_deg: np.ndarray) -> np.ndarray:
    """Points whose status is not the reference's: INFLATION below P0; above it BENDING, or a validity
    limit (COILED, KINKED, OVERSTRETCHED: a stable equilibrium the model answers, flagged as unlike a real
    sleeve)."""
    from stability import ANSWERED

    bending = np.isin(status, ANSWERED)
    return np.where(theta_ref_deg == 0.0, status != Status.INFLATION, ~bending)


def evaluate_method(model: ActuatorModel, pressures_kpa, theta_ref_deg, method: str, *,
                    budget_s: float = TIME_BUDGET_S) -> dict:
    """Timing and errors of one method on one design (see the module docstring)."""
    out = {"method": method}
    try:
        c, times = timed(lambda: curve(model, pressures_kpa, method=method), budget_s=budget_s)
    except Exception as exc:  # a method's documented failure is a result, not a crash of the harness
        return {**out, "error": f"{type(exc).__name__}: {exc}", "time_s": None, "angle_err_deg": float("inf"),
                "pressure_err_rel": float("inf"), "failed_points": len(pressures_kpa)}
    out["resolved"] = c.method
    out["time_s"] = statistics.median(times)
    out["time_min_s"] = min(times)
    out["repeats"] = len(times)
    err = angle_errors(c.theta_deg, theta_ref_deg)
    bad = _failed(c.status, theta_ref_deg)
    out["angle_err_deg"] = float(err.max())
    out["failed_points"] = int(bad.sum())
    out["failed_status"] = sorted({Status(int(s)).name for s in c.status[bad]})
    bending = theta_ref_deg != 0.0
    try:
        p = pressure_at(model, theta_ref_deg[bending], method=method)
        out["pressure_err_rel"] = float(pressure_errors(p.pressure_kpa, np.asarray(pressures_kpa)[bending]).max())
    except Exception as exc:
        out["pressure_err_rel"] = float("inf")
        out["pressure_error"] = f"{type(exc).__name__}: {exc}"
    return out


def summarise(per_design: list[dict], n_pressures: int) -> dict:
    """Median time per curve and per pressure point, error maxima, failures, over designs."""
    times = [r["time_s"] for r in per_design if r.get("time_s") is not None]
    med = statistics.median(times) if times else None
    return {
        "time_per_curve_ms": None if med is None else med * 1e3,
        "time_per_point_us": None if med is None else med / n_pressures * 1e6,
        "time_per_curve_min_ms": min(r["time_min_s"] for r in per_design if "time_min_s" in r) * 1e3 if times
        else None,
        "angle_err_max_deg": max(r["angle_err_deg"] for r in per_design),
        "angle_err_median_deg": statistics.median(r["angle_err_deg"] for r in per_design),
        "pressure_err_max_rel": max(r["pressure_err_rel"] for r in per_design),
        "failed_designs": sorted({r["design"] for r in per_design if r.get("error") or r["failed_points"]}),
        "failed_points": sum(r["failed_points"] for r in per_design),
        "exceptions": sorted({r["error"] for r in per_design if r.get("error")}),
        "resolved": sorted({r["resolved"] for r in per_design if "resolved" in r}),
    }
