"""Stability maps: where each method's answer leaves the tolerance or fails.

Two panels per method: zigzag over (|theta|, width) and cross over (|theta|, angle
alpha0) at ``CROSS_WIDTH_MM``. |theta| is log-spaced from ``THETA_MIN_DEG`` (near the
straight state, where the printed form cancels) to ``THETA_MAX_DEG``, taken in each
design's bending direction. In every cell the pressure is the reference pressure at
that angle (:func:`sample.reference_point`) and the method must return the reference
angle: ``curve(model, [P], method=...)``. Each cell gets one class of
:data:`CLASSES`: the error in angle against the tolerance, FAILED (an exception, no
finite number, or a status other than BENDING) or "no equilibrium" (past the end of
the stable branch: lock-up, fold, domain end).

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
from embroact.predict.status import Status
from sample import design, reference_point

__all__ = ["CLASSES", "ANGLE_TOL_DEG", "GRID", "classify", "panel_designs", "panel_reference", "method_panel"]

#: Tolerance on the angle [deg] (the ``auto`` target).
ANGLE_TOL_DEG = 1e-6
#: (label, upper bound of the angle error [deg]) per class; then FAILED and no equilibrium.
CLASSES = (("error <= 1e-9 deg", 1e-9), ("error <= tolerance 1e-6 deg", ANGLE_TOL_DEG),
           ("error <= 1e-2 deg (inaccurate)", 1e-2), ("error > 1e-2 deg (wrong)", math.inf),
           ("FAILED / exception / wrong status", None), ("no equilibrium (past branch end)", None))
FAILED_CLASS, NO_EQUILIBRIUM_CLASS = 4, 5
THETA_MIN_DEG, THETA_MAX_DEG = 1e-7, 330.0
CROSS_WIDTH_MM = 7.0
#: G [MPa] of the map designs: the paper's fits for w = 7 mm (zigzag) and alpha0 = 60 deg (cross).
ZIGZAG_G_MPA, CROSS_G_MPA = 2.7, 2.9
#: Grid sizes (thetas, rows) for the full run and the quick run.
GRID = {"full": (28, 17), "quick": (6, 3)}


def classify(err_deg: np.ndarray) -> np.ndarray:
    """Class index per cell from the angle error [deg] (inf: failed)."""
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
    p = np.full((rows, n_theta), np.nan)
    th = np.full((rows, n_theta), np.nan)
    for i, d in enumerate(designs):
        end, _ = lockup(d.model)
        ref = d.ref()
        for j, m in enumerate(mags):
            if m < abs(end):
                p[i, j], th[i, j] = reference_point(ref, math.copysign(m, end) if end != 0 else m)
    return {"pattern": pattern, "designs": designs, "theta_abs_deg": mags, "pressure_kpa": p, "theta_ref_deg": th,
            "row_values": [d.width_mm if pattern == "zigzag" else d.angle_deg for d in designs],
            "row_label": "width [mm]" if pattern == "zigzag" else f"alpha0 [deg] (w = {CROSS_WIDTH_MM:g} mm)"}


def method_panel(panel: dict, method: str) -> dict:
    """Angle error [deg] and class per cell of one panel for one method."""
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
            notes.add(f"{type(exc).__name__}: {str(exc)[:120]}")
            continue
        e = np.abs(c.theta_deg - th[i, ok])
        bad = (c.status != Status.BENDING) | ~np.isfinite(e)
        notes.update(f"status {Status(int(s)).name}" for s in c.status[bad])
        err[i, ok] = np.where(bad, np.inf, e)
    cls = np.where(np.isnan(err), NO_EQUILIBRIUM_CLASS, classify(np.where(np.isnan(err), 0.0, err)))
    return {"err_deg": err, "cls": cls, "notes": sorted(notes)}
