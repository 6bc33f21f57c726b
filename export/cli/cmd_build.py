"""``embroact build [DESIGN.toml] --out DIR``: every output of a design in one directory.

Without DESIGN the built-in default design is built (the paper's zigzag
actuator, w = 7 mm, s = 1.0 mm, l0 = 100 mm).  Writes ``<name>.<fmt>`` per
format, ``worksheet.json``, ``worksheet.txt`` and ``preview.svg`` (plus what the
build stages add, see :mod:`embroact.export.report.build`).

Exit codes: 0 written; 1 design-rule errors (nothing written; ``--force`` writes
anyway); 2 bad design or option; 3 output directory missing or not writable.

Examples
--------
>>> import tempfile
>>> from embroact.export.cli.main import main
>>> main(["build", "--out", tempfile.mkdtemp(), "--format", "dst,pes"])  # doctest: +SKIP
wrote 5 files to /tmp/...: ...
0
"""
from __future__ import annotations

import argparse
import json
import sys

__all__ = ["add_arguments", "run"]

def _check(args):
    """The design-rule gate ``check(design, plan) -> findings`` (see ``embroact check``).

    With ``--split-long`` the writer splits over-long legs on request, so their
    record-limit finding (EA102) is not an error of the build.
    """
    from ...predict.analysis import analyse
    from ...predict.rules import check_design

    ignore = ("EA102",) if args.split_long else ()
    return lambda design, plan: check_design(analyse(design, plan=plan), ignore=ignore)


def _stages(args) -> tuple:
    """The preview stage (bend chart, side view, 3D, report) unless ``--no-previews``."""
    if args.no_previews:
        return ()
    from .args import parse_pressures
    from ..pictures.previews import previews_stage

    pressures = parse_pressures(args.pressure_kpa) if args.pressure_kpa else None
    suffix = None if args.mesh_format == "none" else f".{args.mesh_format}"
    return (previews_stage(pressures_kpa=pressures, mesh_suffix=suffix, tolerance_mm=args.tolerance_mm,
                           shape_pressure_kpa=args.shape_pressure_kpa),)


def add_arguments(parser: argparse.ArgumentParser, name: str) -> None:
    """Options of ``embroact build``."""
    parser.add_argument("design", nargs="?", help="design file (TOML); default: the built-in paper zigzag design")
    parser.add_argument("--out", required=True, help="existing output directory")
    parser.add_argument("--format", help="machine formats, comma separated (default: the design's machine.format, dst)")
    parser.add_argument("--force", action="store_true", help="write even if the design-rule checks find errors")
    parser.add_argument("--split-long", action="store_true",
                        help="split legs longer than a format allows into stitches outside the tube corridor")
    parser.add_argument("--speed-spm", type=float,
                        help="machine speed for the worksheet [stitches/min] (default: the design's, 600)")
    parser.add_argument("--pressure-kpa", help="pressures for the bend chart, 'start:stop:step' or a list "
                        "(default: 0 to the design's max_pressure_kpa in 10 kPa steps)")
    parser.add_argument("--shape-pressure-kpa", type=float,
                        help="pressure of the 3D shape (default: the highest predicted pressure)")
    parser.add_argument("--mesh-format", default="glb", choices=("glb", "stl", "obj", "ply", "none"),
                        help="3D shape file format (default glb; none: no mesh file)")
    parser.add_argument("--tolerance-mm", type=float,
                        help="chordal tolerance of the 3D mesh [mm] (default 0.05)")
    parser.add_argument("--no-previews", action="store_true",
                        help="write only machine files, worksheet and stitch preview (no model previews)")
    parser.add_argument("--json", action="store_true", help="print machine-readable JSON (units in the keys)")


def run(args) -> int:
    """Load (or default) the design, build, report."""
    from ..files.atomic import check_writable_dir
    from ..report.build import DesignRuleError, build, parse_formats

    formats = parse_formats(args.format) if args.format is not None else None
    check_writable_dir(args.out)
    if args.design:
        from ..files.designfile import load_design

        design = load_design(args.design)
    else:
        from ...patterns.design import default_design

        design = default_design()
    try:
        res = build(design, args.out, formats=formats, force=args.force, split_long=args.split_long,
                    speed_spm=args.speed_spm, check=_check(args), stages=_stages(args))
    except DesignRuleError as exc:
        if args.json:
            print(json.dumps({"written": False, "findings": [f.as_dict() for f in exc.findings]}, indent=2))
        else:
            for f in exc.findings:
                print(f"{getattr(f, 'severity', '')}: {getattr(f, 'code', '')} {getattr(f, 'message', f)}",
                      file=sys.stderr)
            print(f"embroact: error: {exc}", file=sys.stderr)
        return 1
    if args.json:
        print(json.dumps(res.as_dict(), indent=2, sort_keys=True))
    else:
        ws = res.worksheet
        print(f"wrote {len(res.files)} files to {res.out_dir}: {', '.join(res.files)}")
        print(f"{ws.stitch_count} stitches, {ws.stop_count} stop(s); tube to cut: "
              + ", ".join(f"{a.name} {a.tube_cut_mm:.0f} mm" for a in ws.actuators))
    return 0
