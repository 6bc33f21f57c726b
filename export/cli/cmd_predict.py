"""``embroact predict``: pressure-to-bend curves for quick parameters or a design file.

``embroact predict zigzag|cross --width-mm W ...`` generates the actuator (so that r0
and beta0 come from the realised stitches, MODEL.md section 2) and predicts theta(P);
``embroact predict DESIGN.toml`` does the same for every actuator of a design file
with each actuator's ``[actuator.model]`` settings. Without ``--g-mpa`` / ``--p0-kpa``
(or the design's values) the calibration set supplies G and P0
(:func:`embroact.predict.calibration.calibrated_model`); ``--p0-from geometry`` takes
P0 from the tube law instead. Pressures are ``start:stop:step`` (stop included when it
lies on the grid) or a comma-separated list, in kPa.

Examples
--------
>>> from embroact.export.cli.main import main
>>> main(["predict", "zigzag", "--width-mm", "7", "--g-mpa", "2.7", "--p0-kpa", "85",
...       "--pressure-kpa", "0,100,200"])
A1: zigzag w=7 mm s=1 mm l0=100 mm; r0 2.581 mm; G 2.7 MPa, P0 85 kPa [given (g_mpa, p0_kpa)]; tube law paper; method stable-analytic-trace
pressure_kpa  theta_deg  status       l_mm     r_mm    beta_deg  d_mm
     0.000       0.000   INFLATION     100.000  1.5000  0.000     1.0000
   100.000      11.539   BENDING       101.040  2.5814  0.000     2.3281
   200.000     102.930   BENDING       109.275  2.5814  0.000     2.3386
0
>>> main(["predict", "zigzag", "--width-mm", "7", "--pressure-kpa", "0:300:-10"])  # one line on stderr
2
"""
from __future__ import annotations

import argparse
import json
import math
import sys

from .args import add_tube_arguments, parse_pressures, tube_from_args

__all__ = ["add_arguments", "run", "parse_pressures"]

_DEFAULT_STEP_KPA = 10.0


def add_arguments(parser: argparse.ArgumentParser, name: str) -> None:
    """Options of ``embroact predict``."""
    parser.add_argument("target", metavar="zigzag|cross|DESIGN.toml",
                        help="a pattern with quick parameters, or a design file")
    g = parser.add_argument_group("quick parameters (zigzag / cross)")
    g.add_argument("--width-mm", type=float, help="rail spacing w [mm] (required)")
    g.add_argument("--interval-mm", type=float, default=1.0, help="stitch interval s [mm] (default 1)")
    g.add_argument("--angle-deg", type=float, help="cross embroidery angle alpha0, (0, 90) [deg] (cross: required)")
    g.add_argument("--length-mm", type=float, default=100.0, help="actuator length l0 [mm] (default 100)")
    add_tube_arguments(g)
    m = parser.add_argument_group("model")
    m.add_argument("--actuator", metavar="NAME", help="design file: only this actuator")
    m.add_argument("--g-mpa", type=float, help="effective modulus G [MPa] (default: design file or calibration set)")
    m.add_argument("--p0-kpa", type=float, help="transition pressure P0 [kPa] (default: design file or calibration)")
    m.add_argument("--p0-from", choices=("calibration", "geometry"), default="calibration",
                   help="P0 when not given: the calibration set's, or the tube law's at r0 (default calibration)")
    m.add_argument("--calibration", help="calibration set name (default: design file's, else paper-2025)")
    m.add_argument("--tube-law", choices=("paper", "thick-wall"), default="paper",
                   help="tube law of the inflation phase (default paper)")
    m.add_argument("--method", default="auto", help="model method, e.g. stable-analytic-trace (default auto)")
    o = parser.add_argument_group("output")
    o.add_argument("--pressure-kpa", metavar="START:STOP:STEP|P1,P2,...",
                   help="pressures [kPa] (default 0:MAX:10, MAX = design's max_pressure_kpa, 300 for quick)")
    o.add_argument("--json", action="store_true", help="print machine-readable JSON (units in the keys)")


def _quick_design(args):
    from ...patterns.centerline import Centerline
    from ...patterns.design import ActuatorSpec, Design, MachineSettings, ModelSettings, OperationSettings
    from ...patterns.base.errors import ParameterError
    from ...patterns.params import CrossParams, ZigzagParams

    if args.width_mm is None:
        raise ParameterError(f"--width-mm is required for 'embroact predict {args.target}'")
    if args.target == "cross":
        if args.angle_deg is None:
            raise ParameterError("--angle-deg is required for the cross pattern")
        params = CrossParams(args.width_mm, args.interval_mm, args.angle_deg)
    else:
        params = ZigzagParams(args.width_mm, args.interval_mm)
    tube = tube_from_args(args)
    spec = ActuatorSpec("A1", params, Centerline.straight(args.length_mm), model=ModelSettings())
    return Design("quick", tube, MachineSettings(), OperationSettings(), (spec,))


def _model(derived, settings, args):
    """ActuatorModel from flags > design settings > calibration set."""
    from ...predict.calibration import calibrated_model

    g = args.g_mpa if args.g_mpa is not None else settings.g_mpa
    p0 = args.p0_kpa if args.p0_kpa is not None else settings.p0_kpa
    name = args.calibration or settings.calibration
    return calibrated_model(derived, name=name, g_mpa=g, p0_kpa=p0, p0=args.p0_from, tube_law=args.tube_law)[0]


def _finite(x: float):
    return x if math.isfinite(x) else None


def _result(spec, derived, model, c, lock) -> dict:
    out = {"name": spec.name, "pattern": derived.pattern, "derived": derived.as_dict(),
           "model": {"g_mpa": model.g_mpa, "p0_kpa": model.p0_kpa, "tube_law": model.tube_law},
           "lockup_theta_deg": lock[0], "lockup_pressure_kpa": _finite(lock[1])}
    out.update(c.as_dict())
    return out


_COLUMNS = ("pressure_kpa", "theta_deg", "status", "length_mm", "radius_mm", "beta_deg", "inner_radius_mm")


def _table(spec, derived, model, c) -> str:
    angle = f" alpha0={derived.angle_deg:.4g} deg beta0={derived.beta0_deg:.4g} deg" if derived.pattern == "cross" else ""
    head = (f"{spec.name}: {derived.pattern} w={derived.width_mm:.4g} mm s={derived.interval_mm:.4g} mm "
            f"l0={derived.length_mm:.4g} mm{angle}; r0 {derived.r0_mm:.4g} mm; G {model.g_mpa:.4g} MPa, "
            f"P0 {model.p0_kpa:.4g} kPa [{c.calibration}]; tube law {model.tube_law}; method {c.method}")
    rows = [head, "pressure_kpa  theta_deg  status       l_mm     r_mm    beta_deg  d_mm"]
    d = c.as_dict()
    for p, t, s, l, r, b, di in zip(*(d[k] for k in _COLUMNS)):
        rows.append(f"{p:10.3f}  {t:10.3f}   {s:<13s}{l:8.3f}  {r:6.4f}  {b:<8.3f}  {di:6.4f}")
    return "\n".join(rows)


def run(args) -> int:
    """Predict and print; return the exit code."""
    from ...patterns.design import build_plan
    from ...patterns.base.errors import ParameterError
    from ...predict.curve import curve, lockup
    from ...predict.derived import derive

    if args.target in ("zigzag", "cross"):
        design = _quick_design(args)  # default OperationSettings: max_pressure_kpa 300
    else:
        from ..files.designfile import load_design

        design = load_design(args.target)
    default = f"0:{design.operation.max_pressure_kpa:g}:{_DEFAULT_STEP_KPA:g}"
    pressures = parse_pressures(args.pressure_kpa if args.pressure_kpa is not None else default)
    specs = design.actuators
    if args.actuator is not None:
        specs = tuple(s for s in specs if s.name == args.actuator)
        if not specs:
            names = ", ".join(s.name for s in design.actuators)
            raise ParameterError(f"--actuator must be one of {names}, got {args.actuator!r}")
    plan = build_plan(design)
    by_name = {a.name: a for a in plan.actuators}
    results, tables = [], []
    for spec in specs:
        derived = derive(by_name[spec.name])
        model = _model(derived, spec.model, args)
        c = curve(model, pressures, method=args.method)
        results.append(_result(spec, derived, model, c, lockup(model)))
        tables.append(_table(spec, derived, model, c))
    if args.json:
        payload = results[0] if args.target in ("zigzag", "cross") else {"design": design.name, "actuators": results}
        json.dump(payload, sys.stdout, indent=1, allow_nan=False)
        print()
    else:
        print("\n\n".join(tables))
    return 0
