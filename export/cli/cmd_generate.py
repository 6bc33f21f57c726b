"""``embroact zigzag`` and ``embroact cross``: one actuator, straight to a machine file.

Examples
--------
>>> import os, tempfile
>>> from embroact.export.cli.main import main
>>> out = os.path.join(tempfile.mkdtemp(), "act.dst")
>>> main(["zigzag", "--width-mm", "7", "--interval-mm", "1", "--length-mm", "100", "-o", out])
wrote ...act.dst (dst): 106 stitches, 1 stop, 1 trim; w 7 mm, s 1 mm, l0 100 mm; r0 2.581 mm, P0 84.5 kPa
0
"""
from __future__ import annotations

import argparse
import json
from pathlib import Path

from .args import TUBE_FLAGS, add_tube_arguments, tube_from_args

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser, name: str) -> None:
    """Options of ``embroact zigzag`` / ``embroact cross``."""
    g = parser.add_argument_group("pattern")
    g.add_argument("--width-mm", type=float, required=True, help="rail spacing w [mm]")
    g.add_argument("--interval-mm", type=float, required=True,
                   help="stitch interval s: axial distance between neighbouring needle points"
                        + (" / parallel legs" if name == "cross" else "") + " [mm]")
    if name == "cross":
        g.add_argument("--angle-deg", type=float, required=True, help="embroidery angle alpha0 from the perpendicular, (0, 90) [deg]")
        g.add_argument("--adjust", choices=("auto", "interval", "angle"), default="auto",
                       help="what to change when s and alpha0 cannot both be met: the smaller relative "
                            "change (auto), the interval or the angle")
    g.add_argument("--length-mm", type=float, default=100.0, help="straight path length l0 [mm] (default 100; ignored with --path)")
    g.add_argument("--path", metavar="SVG_D|FILE.svg#ID",
                   help='tube path: an SVG path "d" string in mm (e.g. "M 0 0 C 30 -20 60 20 90 0") or a path of '
                        "an SVG drawing chosen by id, label or layer (drawing.svg#tube1; real units, transforms applied)")
    g.add_argument("--name", default="A1", help="actuator name for the thread list (default A1)")
    t = parser.add_argument_group("tube")
    add_tube_arguments(t, fields=[flag[1] for flag in TUBE_FLAGS])
    o = parser.add_argument_group("output")
    o.add_argument("-o", "--output", required=True, help="machine file; the suffix picks the format (.dst .pes ...)")
    o.add_argument("--format", help="format overriding the suffix: dst, tbf, pes, pec, jef, exp, vp3, xxx, u01")
    o.add_argument("--split-long", action="store_true",
                   help="split legs longer than the format allows into stitches outside the tube corridor")
    o.add_argument("--worksheet", action="store_true",
                   help="also write OUTPUT_STEM.worksheet.txt and OUTPUT_STEM.worksheet.json")
    o.add_argument("--speed-spm", type=float, default=None,  # None: worksheet.DEFAULT_SPEED_SPM (no numpy for --help)
                   help="machine speed for the worksheet [stitches/min]")
    o.add_argument("--preview", metavar="SVG", help="also write the stitch preview to this SVG file")
    o.add_argument("--json", action="store_true", help="print machine-readable JSON (units in the keys)")


def _plan(args):
    from ...patterns.centerline import Centerline
    from ...patterns.params import CrossParams, ZigzagParams

    tube = tube_from_args(args)
    if args.path is not None:  # an empty --path is an error, not the default straight path
        from ..files.svgfile import is_svg_ref, svg_centerline

        path = svg_centerline(args.path) if is_svg_ref(args.path) else Centerline.from_svg_path(args.path)
    else:
        path = Centerline.straight(_length(args.length_mm))
    if args.command == "cross":
        from ...patterns.cross import cross

        return cross(path, CrossParams(args.width_mm, args.interval_mm, args.angle_deg), tube=tube,
                     name=args.name, adjust=args.adjust)
    from ...patterns.zigzag import zigzag

    return zigzag(path, ZigzagParams(args.width_mm, args.interval_mm), tube=tube, name=args.name)


def _length(v: float) -> float:
    from ...patterns.base.errors import check_range

    return check_range("length_mm", v, low=0.0, high=1e5)


def _realised(r) -> dict:
    return {"width_mm": r.width_mm, "interval_mm": r.interval_mm, "angle_deg": r.angle_deg,
            "length_mm": r.length_mm, "passes": r.passes}


def _summary(path: str, res, derived) -> str:
    r = derived
    angle = f", alpha0 {r.angle_deg:.4g} deg" if r.pattern == "cross" else ""
    stops = f"{res.stops} stop" + ("s" if res.stops != 1 else "")
    trims = f"{res.trims} trim" + ("s" if res.trims != 1 else "")
    split = f", {res.split_legs} long legs split" if res.split_legs else ""
    return (f"wrote {path} ({res.format}): {res.stitches} stitches, {stops}, {trims}{split}; "
            f"w {r.width_mm:.4g} mm, s {r.interval_mm:.4g} mm{angle}, l0 {r.length_mm:.4g} mm; "
            f"r0 {r.r0_mm:.4g} mm, P0 {r.p0_kpa:.1f} kPa")


def run(args) -> int:
    """Generate, encode and write; every output is prepared before the first is written."""
    from ..files.atomic import check_output_dir, write_files_atomic
    from ..machine.formats import encode, machine_format

    out = Path(args.output)
    fmt = machine_format(out, fmt=args.format)
    for p in [out] + ([Path(args.preview)] if args.preview else []):
        check_output_dir(p)
    plan = _plan(args)
    data, res = encode(plan, fmt, split_long=args.split_long)
    outputs = {out: data}
    if args.worksheet:
        from ..report.worksheet import DEFAULT_SPEED_SPM, worksheet

        ws = worksheet(plan, speed_spm=DEFAULT_SPEED_SPM if args.speed_spm is None else args.speed_spm)
        outputs[out.with_name(out.stem + ".worksheet.txt")] = ws.as_text()
        outputs[out.with_name(out.stem + ".worksheet.json")] = json.dumps(ws.as_dict(), indent=2, sort_keys=True) + "\n"
    if args.preview:
        from ..pictures.stitches import plan_svg

        outputs[Path(args.preview)] = plan_svg(plan)
    write_files_atomic({p: c.encode("utf-8") if isinstance(c, str) else c for p, c in outputs.items()})
    from ...predict.derived import derive

    derived = derive(plan.actuators[0])
    if args.json:
        doc = {
            "file": str(out),
            "format": res.format,
            "size_bytes": res.size_bytes,
            "stitch_count": res.stitches,
            "stop_count": res.stops,
            "trim_count": res.trims,
            "jump_count": res.jumps,
            "split_legs": res.split_legs,
            "files": [str(p) for p in outputs],
            "adjustments": list(plan.actuators[0].adjustments),
            "realised": _realised(plan.actuators[0].realised),
            "derived": derived.as_dict(),
        }
        print(json.dumps(doc, indent=2, sort_keys=True))
    else:
        print(_summary(str(out), res, derived))
        for note in plan.actuators[0].adjustments:
            print(f"adjusted: {note} (requested values could not both be met)")
        for p in list(outputs)[1:]:
            print(f"wrote {p}")
    return 0
