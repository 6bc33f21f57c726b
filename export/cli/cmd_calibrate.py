"""``embroact calibrate coupon --out DIR``: the calibration coupon to sew, measure and fit.

Writes into DIR (nothing when a value is refused; docs/calibration.md defends the choices):

* ``coupon-hoopK.toml`` per hoop, and ``hoopK/`` with what ``embroact build`` writes for
  it (machine files, worksheet, stitch preview, 1:1 template);
* ``fins-1.svg``, ``fins-2.svg``, ... (the marker fins of every actuator, as many sheets as they
  need) and ``board.svg`` (the reference board), to print at 100 % on A4 or Letter;
* ``measurements.csv``: the measurement sheet, one row per actuator and pressure step,
  loading then unloading, for ``embroact measure --sheet`` and ``embroact fit --sheet``;
* ``coupon.json``: the actuators, their marker blocks and the marker layout.

Examples
--------
>>> import os, tempfile
>>> from embroact.export.cli.main import main
>>> out = tempfile.mkdtemp()
>>> main(["calibrate", "coupon", "--patterns", "zigzag", "--width-count", "2", "--out", out])  # doctest: +ELLIPSIS
coupon: 2 actuators on 1 hoop(s) (zigzag w 5-9 mm): ...
0
>>> sorted(os.listdir(out))
['board.svg', 'coupon-hoop1.toml', 'coupon.json', 'fins-1.svg', 'hoop1', 'measurements.csv']
"""
from __future__ import annotations

import argparse
import json
import os

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser, name: str) -> None:
    """Options of ``embroact calibrate``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    name : str
        The command's name (``"calibrate"``).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact calibrate")
    >>> add_arguments(parser, "calibrate")
    >>> args = parser.parse_args(["coupon", "--out", "coupon"])
    >>> args.what, args.out
    ('coupon', 'coupon')
    """
    from ...predict.coupon import coupon_kinds
    from .args import add_tube_arguments

    parser.add_argument("what", choices=("coupon",), help="what to make: coupon (test actuators to sew and measure)")
    parser.add_argument("--out", required=True, help="existing output directory")
    c = parser.add_argument_group("coupon")
    kinds = ",".join(coupon_kinds())
    c.add_argument("--patterns", default=kinds, help=f"patterns to calibrate (default every registered kind: {kinds})")
    c.add_argument("--width-count", type=int, default=5, help="widths per kind calibrated along its width (default 5)")
    c.add_argument("--angle-count", type=int, default=6,
                   help="angles per kind calibrated along its angle, half on each side of a neutral angle (default 6)")
    c.add_argument("--width-range-mm", metavar="LO:HI",
                   help="the widths' range [mm] (default 10/3 to 6 tube radii: 5:9 for the default tube)")
    c.add_argument("--angle-range-deg", metavar="LO:HI", default="15:60", help="the angles' range [deg] (default 15:60)")
    c.add_argument("--angle-width-mm", type=float,
                   help="width of the actuators sampled along their angle [mm] (default: middle of the widths)")
    c.add_argument("--length-mm", type=float, default=100.0, help="bent length of each actuator [mm] (default 100)")
    c.add_argument("--pitch-mm", type=float, default=25.0, help="distance between neighbouring tubes on a hoop [mm] "
                                                                   "(default 25)")
    c.add_argument("--max-pressure-kpa", type=float, default=300.0, help="highest pressure step [kPa] (default 300)")
    c.add_argument("--pressure-step-kpa", type=float, default=25.0, help="pressure step of the sheet [kPa] (default 25)")
    m = parser.add_argument_group("machine")
    m.add_argument("--format", help="machine formats, comma separated (default dst)")
    m.add_argument("--hoop-width-mm", type=float, default=200.0, help="sewing field width [mm] (default 200)")
    m.add_argument("--hoop-height-mm", type=float, default=200.0, help="sewing field height [mm] (default 200)")
    add_tube_arguments(parser.add_argument_group("tube"))
    parser.add_argument("--json", action="store_true", help="print machine-readable JSON")


def _range(flag: str, text: str | None):
    from ...patterns.base.errors import ParameterError

    if text is None:
        return None
    try:
        lo, hi = (float(t) for t in text.split(":"))
    except ValueError:
        raise ParameterError(f"{flag} must be LO:HI (two numbers), got {text!r}") from None
    return lo, hi


def _sampled(coupon, name: str) -> str:
    """What the coupon samples of kind ``name``: ``zigzag w 5-9 mm``, ``cross alpha0 16.7, ... deg (neutral 33.4)``."""
    from ...patterns.kinds import pattern_kind

    acts = [x for x in coupon.actuators if x.pattern == name]
    if pattern_kind(name).calibration_axis == "width_mm":
        return f"{name} w {min(x.width_mm for x in acts):g}-{max(x.width_mm for x in acts):g} mm"
    neutral = "" if coupon.neutral_angle_deg is None else f" (neutral {coupon.neutral_angle_deg:.1f})"
    return f"{name} alpha0 {', '.join(f'{x.angle_deg:g}' for x in acts)} deg{neutral}"


def _pressures(args) -> list[float]:
    from ...patterns.base.errors import check_range

    top = check_range("max_pressure_kpa", args.max_pressure_kpa, low=0.0, high=10_000.0)
    step = check_range("pressure_step_kpa", args.pressure_step_kpa, low=top / 200.0, low_inclusive=True, high=top,
                       high_inclusive=True)
    n = round(top / step)
    out = [round(step * k, 6) for k in range(n + 1) if step * k <= top + 1e-9]
    return out if out[-1] >= top - 1e-9 else out + [top]


def _designs(coupon, tube, args):
    """One Design per hoop (actuators in sewing order) and its file text."""
    from ...patterns.design import design_from_dict
    from ..files.designfile import dumps_design

    out = []
    tube_table = {k: getattr(tube, k) for k in ("outer_radius_mm", "inner_radius_mm", "g_e_mpa", "clearance_mm",
                                                  "end_margin_mm")}
    for h in range(coupon.hoops):
        d = design_from_dict({
            "name": f"coupon-hoop{h + 1}", "tube": tube_table,
            "machine": {"format": (args.format or "dst").split(",")[0].strip(), "hoop_width_mm": coupon.hoop_mm[0],
                        "hoop_height_mm": coupon.hoop_mm[1]},
            "operation": {"max_pressure_kpa": args.max_pressure_kpa},
            "actuator": [a.design_table() for a in coupon.on_hoop(h)]})
        out.append((d, dumps_design(d)))
    return out


def run(args) -> int:
    """Plan the coupon, check every hoop, write everything; return the exit code.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options (:func:`add_arguments`), with ``command`` set to the command's name.

    Returns
    -------
    int
        The exit code (:mod:`embroact.export.cli.main`).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact calibrate")
    >>> add_arguments(parser, "calibrate")
    >>> args = parser.parse_args(["coupon", "--out", "no-such-dir"])
    >>> args.command = "calibrate"
    >>> from embroact.patterns.base.errors import ExportError
    >>> try:
    ...     run(args)
    ... except ExportError as exc:
    ...     print(exc)
    output directory 'no-such-dir' does not exist
    """
    from ...patterns.base.validate import check_output_name
    from ...predict.coupon import plan_coupon
    from ...predict.rules import check_design
    from ..files.atomic import check_writable_dir, write_files_atomic
    from ..files.couponfile import layout_as_dict, sheet_rows, sheet_text
    from ..photo.sheet import board_svg, fins_svgs
    from ..report.build import build, parse_formats
    from .args import tube_from_args
    from .target import gate

    out = check_writable_dir(check_output_name("--out", args.out))
    formats = parse_formats(args.format) if args.format is not None else ("dst",)
    tube = tube_from_args(args)
    coupon = plan_coupon(tuple(p.strip() for p in args.patterns.split(",") if p.strip()), tube=tube,
                         width_count=args.width_count, angle_count=args.angle_count,
                         width_range_mm=_range("--width-range-mm", args.width_range_mm),
                         angle_range_deg=_range("--angle-range-deg", args.angle_range_deg),
                         angle_width_mm=args.angle_width_mm, length_mm=args.length_mm,
                         hoop_mm=(args.hoop_width_mm, args.hoop_height_mm), pitch_mm=args.pitch_mm)
    pressures = _pressures(args)
    designs = _designs(coupon, tube, args)
    from ...predict.analysis import analyse

    analyses = [analyse(d) for d, _ in designs]
    def rules(analysis):  # every rule but the model's (EA4xx): the coupon exists to find G and P0
        return [f for f in check_design(analysis, format=formats) if not f.code.startswith("EA4")]

    for a in analyses:
        findings = rules(a)
        if any(f.is_error for f in findings):
            gate(findings, force=False)
            return 1
    files: dict[str, bytes] = {}
    rows = []
    for h, ((design, text), a) in enumerate(zip(designs, analyses)):
        files[f"coupon-hoop{h + 1}.toml"] = text.encode("utf-8")
        for act in coupon.on_hoop(h):
            rows.append({"design": f"coupon-hoop{h + 1}.toml", "actuator": act.label, "pattern": act.pattern,
                         "coordinate": act.coordinate, "block": act.block, "fin_side": act.fin_side.value})
    fins = fins_svgs(coupon)
    files.update({f"fins-{k + 1}.svg": svg.encode("utf-8") for k, svg in enumerate(fins)})
    files["board.svg"] = board_svg(coupon.layout.board).encode("utf-8")
    files["measurements.csv"] = sheet_text(sheet_rows(rows, pressures)).encode("utf-8")
    doc = {"layout": layout_as_dict(coupon.layout), "pressures_kpa": pressures,
           "neutral_angle_deg": coupon.neutral_angle_deg,
           "actuators": [{**r, "order": a.order, "width_mm": a.width_mm, "angle_deg": a.angle_deg,
                          "interval_mm": a.interval_mm, "length_mm": a.length_mm, "hoop": a.hoop + 1,
                          "marker_ids": list(coupon.layout.ids(a.block))}
                         for r, a in zip(rows, coupon.actuators)]}
    files["coupon.json"] = (json.dumps(doc, indent=1, sort_keys=True) + "\n").encode("utf-8")
    for h in range(coupon.hoops):
        os.makedirs(out / f"hoop{h + 1}", exist_ok=True)
    written, notes = [], []
    for h, ((design, _), a) in enumerate(zip(designs, analyses)):
        # a kind the calibration holds no points of has no model yet (the coupon is there to make one): its hoop
        # gets the machine files, worksheet, stitch preview and template, without the model's previews
        missing = list(dict.fromkeys(s.model_error for act in a.actuators for s in act.segments if s.choice is None))
        if missing:
            notes.append(f"hoop {h + 1}: no bend previews ({'; '.join(missing)})")
        res = build(design, out / f"hoop{h + 1}", formats=formats, analysis=a, check=rules,
                    stages=() if missing else None)
        written += [f"hoop{h + 1}/{f}" for f in res.files]
    write_files_atomic({out / name: data for name, data in files.items()})
    written = sorted(files) + written
    parts = [_sampled(coupon, name) for name in dict.fromkeys(x.pattern for x in coupon.actuators)]
    if args.json:
        print(json.dumps({"out_dir": str(out), "files": written, "hoops": coupon.hoops, "notes": notes, **doc}, indent=1,
                         sort_keys=True))
    else:
        print(f"coupon: {len(coupon.actuators)} actuators on {coupon.hoops} hoop(s) ({'; '.join(parts)}): "
              f"wrote {len(written)} files to {out}")
        for note in notes:
            print(f"note: {note}")
        print(f"measurement sheet: {len(pressures)} pressure steps up to {pressures[-1]:g} kPa and back, per actuator")
        print("next: sew each hoop (hoopK/), glue the fins "
              f"({', '.join(f'fins-{k + 1}.svg' for k in range(len(fins)))}), photograph each pressure step with the board "
              "(board.svg), then embroact measure PHOTOS --sheet measurements.csv and embroact fit --sheet")
    return 0
