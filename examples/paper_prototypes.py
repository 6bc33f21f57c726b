"""Reproduce the paper's seven prototypes: derived geometry, P0 and predicted bend curves.

Ota & Funabora (2025) sewed three zigzag actuators (s = 1.0 mm; w = 5, 7, 9 mm) and
four cross actuators (w = 7 mm, s = 1.4 mm; alpha0 = 15, 30, 45, 60 deg), all
l0 = 100 mm.  For each one this script

1. generates the stitches and measures the realised width and leg angle, from which
   the sleeve radius r0, thread angle beta0 and the transition pressure P0 follow
   (docs/model.md sections 2-3; default tube r_f = 1.5 mm, d_f = 1.0 mm, G_e = 0.13 MPa);
2. takes G and P0 from the calibration set "paper-2025" at the realised width or angle (the 30 and
   60 deg crosses sew 30.96 and 59.53 deg, between the paper's points; the paper's fitted values: demonstration
   data, fitted on a tube whose size the paper does not give; with the default tube the w = 5 mm
   zigzag coils far below the paper's measured ~155 deg at 290 kPa, and the table marks such states
   as ``embroact predict`` reports them: C coiled, K kinked, S overstretched);
3. predicts the bend angle from 0 to 300 kPa and reports its direction and lock-up.

What to look for: P0 from geometry for w = 5, 7, 9 mm close to the paper's predicted
25, 85, 180 kPa; the cross pattern bending positive for alpha0 = 15 and 30 deg and
negative for 45 and 60 deg (the neutral angle, tan(beta0) = 1/2, is alpha0 = 33.37 deg).

Run::

    python examples/paper_prototypes.py                    # table
    python examples/paper_prototypes.py --json             # everything, curves included
    python examples/paper_prototypes.py --svg-dir charts   # also zigzag.svg, cross.svg
    python examples/paper_prototypes.py --geometry requested   # skip stitch generation
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from embroact.patterns.centerline import Centerline
from embroact.patterns.design import ActuatorSpec, generate_actuator
from embroact.patterns.params import CrossParams, Tube, ZigzagParams
from embroact.predict.calibration import model_for
from embroact.predict.curve import curve, lockup
from embroact.predict.derived import derive, derive_from_values
from embroact.predict.status import status_names

LENGTH_MM = 100.0
PRESSURES_KPA = np.arange(0.0, 301.0, 10.0)
REPORT_AT_KPA = (200.0, 250.0, 300.0)
#: The paper's P0 predicted from geometry for its zigzag prototypes [kPa] (docs/model.md section 7).
PAPER_PREDICTED_P0_KPA = {5.0: 25.0, 7.0: 85.0, 9.0: 180.0}
#: (name, params) of the seven prototypes.
PROTOTYPES = (
    ("zigzag w5", ZigzagParams(width_mm=5.0, interval_mm=1.0)),
    ("zigzag w7", ZigzagParams(width_mm=7.0, interval_mm=1.0)),
    ("zigzag w9", ZigzagParams(width_mm=9.0, interval_mm=1.0)),
    ("cross a15", CrossParams(width_mm=7.0, interval_mm=1.4, angle_deg=15.0)),
    ("cross a30", CrossParams(width_mm=7.0, interval_mm=1.4, angle_deg=30.0)),
    ("cross a45", CrossParams(width_mm=7.0, interval_mm=1.4, angle_deg=45.0)),
    ("cross a60", CrossParams(width_mm=7.0, interval_mm=1.4, angle_deg=60.0)),
)


def derived_geometry(name, params, geometry: str, tube: Tube):
    """Derived geometry from the generated stitches ("generated") or the request ("requested")."""
    if geometry == "generated":
        spec = ActuatorSpec(name, params, Centerline.straight(LENGTH_MM))
        return derive(generate_actuator(spec, tube).actuators[0])
    angle = params.angle_deg if params.pattern == "cross" else 0.0
    return derive_from_values(params.pattern, width_mm=params.width_mm, interval_mm=params.interval_mm,
                              angle_deg=angle, length_mm=LENGTH_MM, tube=tube, name=name)


def prototype(name, params, geometry: str, tube: Tube) -> dict:
    """Geometry, paper calibration and predicted curve of one prototype, as plain data."""
    d = derived_geometry(name, params, geometry, tube)
    choice = model_for(d)  # looked up at the requested width / angle
    model, cal = choice.model, choice.calibration
    c = curve(model, PRESSURES_KPA)
    lock_deg, lock_kpa = lockup(model)
    idx = [int(np.flatnonzero(PRESSURES_KPA == p)[0]) for p in REPORT_AT_KPA]
    at = {f"theta_at_{p:g}_kpa_deg": float(c.theta_deg[i]) for p, i in zip(REPORT_AT_KPA, idx)}
    at_status = {f"status_at_{p:g}_kpa": status_names(c.status[[i]])[0] for p, i in zip(REPORT_AT_KPA, idx)}
    return {
        "name": name,
        "pattern": d.pattern,
        "requested_width_mm": d.requested_width_mm,
        "width_mm": d.width_mm,
        "requested_interval_mm": d.requested_interval_mm,
        "interval_mm": d.interval_mm,
        "requested_angle_deg": d.requested_angle_deg if d.pattern == "cross" else None,
        "angle_deg": d.angle_deg if d.pattern == "cross" else None,
        "r0_mm": d.r0_mm,
        "beta0_deg": d.beta0_deg,
        "neutral_angle_deg": d.neutral_angle_deg,
        "p0_geometry_kpa": choice.tube_law_p0_kpa,
        "p0_paper_predicted_kpa": PAPER_PREDICTED_P0_KPA.get(params.width_mm) if d.pattern == "zigzag" else None,
        "p0_fitted_kpa": cal.p0_kpa,
        "g_mpa": cal.g_mpa,
        "calibration": c.calibration,
        "direction": "positive" if d.bends_positive else "negative",
        **at,
        **at_status,
        "end_of_branch_deg": lock_deg,
        "end_of_branch_kpa": lock_kpa if np.isfinite(lock_kpa) else None,
        "method": c.method,
        "curve": {"pressure_kpa": c.pressure_kpa.tolist(), "theta_deg": c.theta_deg.tolist(),
                  "status": status_names(c.status)},
        "_curve": c,
    }


#: Table marks of point states other than bending / inflation: the branch ends, and the validity
#: limits past which ``embroact predict`` reports the state as COILED, KINKED or OVERSTRETCHED.
_MARKS = {"LOCKED": "L", "UNSTABLE": "U", "OUT_OF_DOMAIN": "D", "FAILED": "F", "COILED": "C", "KINKED": "K",
          "OVERSTRETCHED": "S"}


def _fmt(v, spec="8.2f") -> str:
    return f"{'-':>{spec.split('.')[0]}}" if v is None else format(v, spec)


def table(rows) -> str:
    """Fixed-width text table of the prototypes (angles in deg, pressures in kPa)."""
    head = (f"{'prototype':<10} {'w':>5} {'alpha0':>6} {'real':>6} {'r0':>6} {'beta0':>6} {'P0 geo':>7} {'P0 pap':>7} "
            f"{'P0 fit':>7} {'G':>5} {'dir':>4} " + " ".join(f"{'th@' + format(p, 'g'):>8} " for p in REPORT_AT_KPA))
    units = (f"{'':<10} {'mm':>5} {'deg':>6} {'deg':>6} {'mm':>6} {'deg':>6} {'kPa':>7} {'kPa':>7} {'kPa':>7} {'MPa':>5} "
             f"{'':>4} " + " ".join(f"{'deg':>8} " for _ in REPORT_AT_KPA))
    lines = [head, units]
    for r in rows:
        th = " ".join(_fmt(r[f"theta_at_{p:g}_kpa_deg"]) + _MARKS.get(r[f"status_at_{p:g}_kpa"], " ")
                      for p in REPORT_AT_KPA)
        lines.append(
            f"{r['name']:<10} {r['width_mm']:5.2f} {_fmt(r['requested_angle_deg'], '6.1f')} "
            f"{_fmt(r['angle_deg'], '6.2f')} {r['r0_mm']:6.3f} "
            f"{r['beta0_deg']:6.2f} {r['p0_geometry_kpa']:7.1f} {_fmt(r['p0_paper_predicted_kpa'], '7.0f')} "
            f"{r['p0_fitted_kpa']:7.0f} {r['g_mpa']:5.1f} {'+' if r['direction'] == 'positive' else '-':>4} {th}"
        )
    neutral = rows[-1]["neutral_angle_deg"]
    lines.append(f"cross neutral angle (tan beta0 = 1/2) for w = 7 mm: alpha0 = {neutral:.2f} deg; "
                 f"model method {rows[0]['method']}; calibration paper-2025 (demonstration data, not a "
                 "calibration of your materials: embroact calibrate coupon makes one)")
    lines.append("alpha0: requested, real: realised by the generator; w realised; "
                 "marks: " + ", ".join(f"{m} {name.lower()}" for name, m in _MARKS.items()))
    return "\n".join(line.rstrip() for line in lines)


def write_charts(rows, out_dir: Path) -> list[str]:
    """One SVG bend chart per pattern (embroact.export.pictures.chart); returns the paths written."""
    from embroact.export.files.atomic import write_text_atomic
    from embroact.export.pictures.chart import Series, bend_chart_svg

    out_dir.mkdir(parents=True, exist_ok=True)
    written = []
    for pattern in ("zigzag", "cross"):
        series = [Series.from_curve(r["_curve"], label=r["name"], p0_kpa=r["p0_fitted_kpa"])
                  for r in rows if r["pattern"] == pattern]
        path = out_dir / f"{pattern}.svg"
        write_text_atomic(path, bend_chart_svg(series, title=f"Paper prototypes, {pattern} (calibration paper-2025)"))
        written.append(str(path))
    return written


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="The paper's seven prototypes: geometry, P0, predicted bend.")
    parser.add_argument("--json", action="store_true", help="print JSON (units in the keys, curves included)")
    parser.add_argument("--svg-dir", type=Path, help="also write zigzag.svg and cross.svg bend charts here")
    parser.add_argument("--geometry", choices=("generated", "requested"), default="generated",
                        help="derive r0, beta0 from the generated stitches (default) or from the request")
    args = parser.parse_args(argv)
    tube = Tube()
    rows = [prototype(name, params, args.geometry, tube) for name, params in PROTOTYPES]
    charts = write_charts(rows, args.svg_dir) if args.svg_dir else []
    if args.json:
        doc = {"prototypes": [{k: v for k, v in r.items() if k != "_curve"} for r in rows], "charts": charts}
        json.dump(doc, sys.stdout, indent=1, allow_nan=False)
        sys.stdout.write("\n")
    else:
        print(table(rows))
        for path in charts:
            print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
