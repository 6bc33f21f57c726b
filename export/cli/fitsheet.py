"""``embroact fit --sheet SHEET.csv -o PROFILE.toml``: one material profile from a whole measurement sheet.

The sheet is the coupon's (``embroact calibrate coupon``), its ``bend_deg`` filled in by
``embroact measure`` or by hand. Each row names its hoop's design file (relative to the
sheet) and the actuator in it, so every actuator is fitted as generated (realised
geometry), through the marker layout of the ``coupon.json`` beside the sheet (the layout
flags change fields of it). Rows without a bend are skipped. The profile, its leave-one-out
errors and the coupons that disagree with the rest: :mod:`embroact.predict.profile`.
"""
from __future__ import annotations

import json
import os
import re
import sys

__all__ = ["run_sheet"]


def _coupons(rows, base: str):
    """CouponData per measured actuator, in sheet order, and the tube of their designs."""
    import numpy as np

    from ...patterns.base.errors import ParameterError
    from ...predict.analysis import analyse
    from ...predict.profile import CouponData
    from ..files.designfile import load_design

    groups: dict[tuple[str, str], list] = {}
    for r in rows:
        if r.bend_deg is not None:
            groups.setdefault((r.design, r.actuator), []).append(r)
    if not groups:
        raise ParameterError("the measurement sheet has no measured row (bend_deg is empty everywhere)")
    analyses: dict[str, object] = {}
    out, tubes = [], {}
    for (design, name), rs in groups.items():
        if design not in analyses:
            d = load_design(os.path.join(base, design))
            analyses[design] = analyse(d)
            tubes[design] = d.tube
        acts = {a.name: a for a in analyses[design].actuators}  # type: ignore[attr-defined]
        if name not in acts:
            raise ParameterError(f"sheet line {rs[0].line}: actuator {name!r} is not in {design!r} "
                                 f"(it has {', '.join(map(repr, acts))})")
        segs = acts[name].segments
        coupon = segs.single(f"sheet line {rs[0].line}: actuator {name!r} in {design!r} has {len(segs)} segments: "
                             "a coupon is one pattern")
        out.append(CouponData(name, coupon.derived, np.array([r.pressure_kpa for r in rs]),
                              np.array([r.bend_deg for r in rs]), tuple(r.branch for r in rs)))
    first = next(iter(tubes.values()))
    if any(t != first for t in tubes.values()):
        raise ParameterError("the sheet's designs use different tubes: one profile is for one tube")
    return out, first


def run_sheet(args) -> int:
    """Fit the whole sheet, write the profile, print the table; return the exit code.

    Parameters
    ----------
    args : argparse.Namespace
        ``embroact fit``'s options (:func:`embroact.export.cli.cmd_fit.add_arguments`) with ``--sheet``.

    Returns
    -------
    int
        The exit code.

    Examples
    --------
    >>> import argparse
    >>> from embroact.export.cli.cmd_fit import add_arguments
    >>> parser = argparse.ArgumentParser(prog="embroact fit")
    >>> add_arguments(parser, "fit")
    >>> try:
    ...     run_sheet(parser.parse_args(["loop.csv", "--sheet", "sheet.csv"]))
    ... except ValueError as exc:
    ...     print(exc)
    give DATA.csv or --sheet, not both
    """
    from ...patterns.base.errors import ParameterError
    from ...predict.photomarkers import COUPON_LAYOUT
    from ...predict.profile import DISAGREE_FACTOR, fit_profile
    from ..files.calibfile import write_calibration
    from ..files.couponfile import read_coupon_layout, read_sheet
    from .args import materials_of, plus_minus
    from .markerargs import layout_from_args

    if args.data is not None:
        raise ParameterError("give DATA.csv or --sheet, not both")
    if args.output is not None:
        from ...patterns.base.validate import check_output_name
        from ..files.atomic import check_output_dir

        check_output_dir(check_output_name("--output", args.output))
    rows = read_sheet(args.sheet)
    base = os.path.dirname(os.path.abspath(args.sheet))
    coupon = os.path.join(base, "coupon.json")
    recorded = read_coupon_layout(coupon)[0].markers if os.path.exists(coupon) else COUPON_LAYOUT.markers
    layout = layout_from_args(args, markers=True, recorded=recorded, calibration="coupon").layout
    coupons, tube = _coupons(rows, base)
    stem = os.path.splitext(os.path.basename(args.output))[0] if args.output else "profile"
    name = args.name or re.sub(r"[^A-Za-z0-9._-]", "-", stem)
    description = args.description or f"material profile fitted by embroact fit --sheet from {len(coupons)} coupon actuators"
    prof = fit_profile(coupons, layout=layout, name=name, tube=tube, description=description,
                       materials=materials_of(args.material), tube_law=args.tube_law)
    if args.output:
        write_calibration(args.output, prof.calibration)
    flagged = [e for e in prof.loo if e.flagged]
    if args.json:
        doc = {"calibration": {"name": name, "path": args.output, "points": len(prof.calibration.points),
                               "marker_layout": layout.as_dict()},
               "coupons": [{"name": f.name, "fits": [r.as_dict() for r in f.results],
                            "leave_one_out_rmse_deg": e.rmse_deg, "leave_one_out_expected_deg": e.expected_deg,
                            "extrapolated": e.extrapolated, "flagged": e.flagged} for f, e in zip(prof.fits, prof.loo)],
               "unexplained": [{"pattern": p, "worst_leave_one_out_rmse_deg": v} for p, v in prof.unexplained]}
        json.dump(doc, sys.stdout, indent=1, sort_keys=True, allow_nan=False)
        sys.stdout.write("\n")
        return 0
    print(f"profile {name!r}: {len(coupons)} coupon actuators through {layout.label}")
    print(f"{'actuator':<22} {'branch':<10} {'n':>3}  {'G [MPa]':<18} {'P0 [kPa]':<18} {'RMSE':>6} {'LOO':>7}")
    for f, e in zip(prof.fits, prof.loo):
        loo = "-" if e.rmse_deg is None else f"{e.rmse_deg:.2f}" + ("*" if e.extrapolated else "")
        for k, r in enumerate(f.results):
            print(f"{f.name if k == 0 else '':<22} {r.branch:<10} {r.n_points:>3}  {plus_minus(r.g_mpa, r.g_mpa_se):<18} "
                  f"{plus_minus(r.p0_kpa, r.p0_kpa_se):<18} {r.rmse_deg:>6.2f} {loo if k == 0 else '':>7}")
    print("RMSE and LOO (leave-one-out: predicted from the other coupons of its pattern) in deg of the marker reading; "
          "* extrapolated (an end of the range)")
    for e in flagged:
        print(f"disagrees: {e.name}: leave-one-out error {e.rmse_deg:.2f} deg, over {DISAGREE_FACTOR:g} times the "
              f"{e.expected_deg:.2f} deg that the measurement noise and the other coupons' uncertainty explain, and "
              "without it the others predict each other (a bad sample, a wrong label or a misread photo, or the "
              "coordinate sampled too coarsely there: sew another one there)")
    for pattern, worst in prof.unexplained:
        print(f"unresolved: the {pattern} coupons disagree (leave-one-out errors up to {worst:.2f} deg, over "
              f"{DISAGREE_FACTOR:g} times what noise and their uncertainty explain) and no single coupon explains it: "
              f"sew more {pattern} coupons (at least 4 tell which one is off)")
    if args.output:
        print(f"wrote calibration set {name!r} ({len(prof.calibration.points)} point(s)) to {args.output}")
    return 0
