"""Stability maps: where each method's answer leaves the tolerance or fails.

Two panels per method: zigzag over (|theta|, width) and cross over (|theta|, angle
alpha0) at ``CROSS_WIDTH_MM``. |theta| is log-spaced from ``THETA_MIN_DEG`` (near the
straight state, where the printed form cancels) to ``THETA_MAX_DEG``, taken in each
design's bending direction. In every cell the pressure is the reference pressure at
that angle (:func:`sample.reference_point`) and the method must return the reference
angle: ``curve(model, [P], method=...)``. Each cell gets one class of
:data:`CLASSES`: the *relative* angle error against the tolerance, FAILED (an exception, no
finite number, or a status other than BENDING) or "no equilibrium" (past the end of
the stable branch: lock-up, fold, domain end).

The error is relative, ``|theta - theta_ref| / |theta_ref|``, because the map spans ten
decades of angle (an absolute tolerance would excuse any answer near the straight
state), less the part no float64 method can avoid: the pressure itself is rounded to
float64, which moves the exact angle by up to ``INPUT_ULPS * ulp(P) / |dP/dtheta|``
(near theta = 0 this is ~1e-6 of a 1e-7 deg bend).

Examples
--------
>>> import numpy as np
>>> from stability import classify
>>> classify(np.array([1e-12, 1e-7, 1e-4, 1.0, np.inf])).tolist()
[0, 1, 2, 3, 4]
"""
from __future__ import annotations

import math

import numpy as np

from embroact.predict.curve import curve, lockup
from embroact.predict.status import VALIDITY_LIMITS, Status
from sample import design, reference_point

__all__ = ["CLASSES", "REL_TOL", "GRID", "classify", "panel_designs", "panel_reference", "method_panel"]

#: Tolerance on the relative angle error (1e-6 deg at 1 deg).
REL_TOL = 1e-6
#: Rounding units of P counted as unavoidable input uncertainty.
INPUT_ULPS = 4
#: (label, upper bound of the relative angle error) per class; then FAILED and no equilibrium.
CLASSES = (("rel. error <= 1e-9", 1e-9), ("<= tolerance 1e-6", REL_TOL), ("<= 1e-2 (inaccurate)", 1e-2),
           ("> 1e-2 (wrong)", math.inf), ("FAILED / exception / wrong status", None),
           ("no equilibrium (past branch end)", None))
FAILED_CLASS, NO_EQUILIBRIUM_CLASS = 4, 5
#: Statuses that answer the cell (the methods table counts the same ones as not failed).
ANSWERED = [int(Status.BENDING)] + [int(s) for s in VALIDITY_LIMITS]
THETA_MIN_DEG, THETA_MAX_DEG = 1e-7, 330.0
CROSS_WIDTH_MM = 7.0
#: G [MPa] of the map designs: the paper's fits for w = 7 mm (zigzag) and alpha0 = 60 deg (cross).
ZIGZAG_G_MPA, CROSS_G_MPA = 2.7, 2.9
#: Grid sizes (thetas, rows) for the full run and the quick run.
GRID = {"full": (28, 17), "quick": (6, 3)}


def classify(err_deg: np.ndarray) -> np.ndarray:
    """Class index per cell from the relative angle error (inf: failed)."""
    bounds = [b for _, b in CLASSES[:4]]
    cls = np.searchsorted(np.array(bounds), err_deg, side="left")
    return np.where(np.isfinite(err_deg), cls, FAILED_CLASS)


def panel_designs(pattern: str, rows: int) -> list:
    """The designs of one panel: widths 4-12 mm (zigzag) or angles 5-80 deg (cross)."""
    if pattern == "zigzag":
        return [design("zigzag", float(w), 0.0, ZIGZAG_G_MPA) for w in np.linspace(4.0, 12.0, rows)]
    return [design("cross", CROSS_WIDTH_MM, float(a), CROSS_G_MPA) for a in np.linspace(5.0, 80.0, rows)]


def _thetas(n: int) -> np.ndarray:
    return np.logspace(math.log10(THETA_MIN_DEG), math.log10(THETA_MAX_DEG), n)


def panel_reference(pattern: str, n_theta: int, rows: int) -> dict:
    """Reference pressures and angles of a panel; NaN where there is no equilibrium."""
    designs = panel_designs(pattern, rows)
    mags = _thetas(n_theta)
    p, th, slope = (np.full((rows, n_theta), np.nan) for _ in range(3))
    for i, d in enumerate(designs):
        end, _ = lockup(d.model)
        ref = d.ref()
        for j, m in enumerate(mags):
            if m < abs(end):
                p[i, j], th[i, j], slope[i, j] = reference_point(ref, math.copysign(m, end))
    floor = INPUT_ULPS * np.spacing(np.abs(p)) / np.abs(slope)
    return {"pattern": pattern, "designs": designs, "theta_abs_deg": mags, "pressure_kpa": p, "theta_ref_deg": th,
            "input_floor_deg": floor,
            "row_values": [d.width_mm if pattern == "zigzag" else d.angle_deg for d in designs],
            "row_label": "width [mm]" if pattern == "zigzag" else f"alpha0 [deg] (w = {CROSS_WIDTH_MM:g} mm)"}


def method_panel(panel: dict, method: str) -> dict:
    """Relative angle error and class per cell of one panel for one method."""
    p, th = panel["pressure_kpa"], panel["theta_ref_deg"]
    err = np.full(p.shape, np.nan)
    notes = set()
    for i, d in enumerate(panel["designs"]):
        ok = np.isfinite(p[i])
        if not ok.any():
            continue
        try:
            c = curve(d.model, p[i, ok], method=method)
        except Exception as exc:  # the failure is the result
            err[i, ok] = np.inf
            notes.add(f"{d.name}: {type(exc).__name__}: {str(exc)[:120]}")
            continue
        e = np.maximum(np.abs(c.theta_deg - th[i, ok]) - panel["input_floor_deg"][i, ok], 0.0) / np.abs(th[i, ok])
        # a validity limit (COILED, KINKED, OVERSTRETCHED) is an answered equilibrium, as in the methods table
        bad = ~np.isin(c.status, ANSWERED) | ~np.isfinite(e)
        notes.update(f"status {Status(int(s)).name}" for s in c.status[bad])
        err[i, ok] = np.where(bad, np.inf, e)
    cls = np.where(np.isnan(err), NO_EQUILIBRIUM_CLASS, classify(np.where(np.isnan(err), 0.0, err)))
    return {"err_rel": err, "cls": cls, "notes": sorted(notes)}
