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

from .target import add_model_arguments, add_placement_argument, add_origin_argument

__all__ = ["add_arguments", "run"]

def _stages(args) -> tuple:
    """The preview stage (bend chart, side view, 3D, report) unless ``--no-previews``."""
    if args.no_previews:
        return ()
    from ..report.stage import previews_stage
    from .args import parse_pressures

    pressures = parse_pressures(args.pressure_kpa) if args.pressure_kpa else None
    suffix = None if args.mesh_format == "none" else f".{args.mesh_format}"
    return (previews_stage(pressures_kpa=pressures, mesh_suffix=suffix, tolerance_mm=args.tolerance_mm,
                           shape_pressure_kpa=args.shape_pressure_kpa),)


def add_arguments(parser: argparse.ArgumentParser, name: str) -> None:
    """Options of ``embroact build``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    name : str
        The command's name (``"build"``).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact build")
    >>> add_arguments(parser, "build")
    >>> args = parser.parse_args(["--out", "out", "--format", "dst,pes"])
    >>> args.out, args.format, args.mesh_format
    ('out', 'dst,pes', 'glb')
    """
    parser.add_argument("design", nargs="?", help="design file (TOML); default: the built-in paper zigzag design")
    add_model_arguments(parser.add_argument_group("model (overrides the design's [actuator.model])"))
    parser.add_argument("--out", required=True, help="existing output directory")
    parser.add_argument("--format", help="machine formats, comma separated (default: the design's machine.format, dst)")
    parser.add_argument("--force", action="store_true",
                        help="write even if the design-rule checks find errors (legs over a format's record limit "
                             "are then split as with --split-long)")
    parser.add_argument("--split-long", action="store_true",
                        help="split legs longer than a format allows into stitches outside the tube corridor")
    parser.add_argument("--cord-stop", choices=("sequence", "double"),
                        help="how DST/EXP write a cord-in stop: one stop code (sequence: manual needle mode or "
                             "stops programmed in the needle sequence) or two in a row (double: stops a "
                             "multi-needle machine in automatic mode too); default: the design's, sequence")
    add_placement_argument(parser)
    add_origin_argument(parser)
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
    """Load (or default) the design, analyse it once, gate on its rules, build, report.

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
    >>> import argparse, tempfile
    >>> parser = argparse.ArgumentParser(prog="embroact build")
    >>> add_arguments(parser, "build")
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     args = parser.parse_args(["--out", tmp, "--no-previews"])
    ...     args.command = "build"
    ...     run(args)  # doctest: +ELLIPSIS
    wrote 7 files to ...: paper-zigzag.dst, worksheet.json, worksheet.txt, preview.svg, template.svg, ...
    ...
    0
    """
    from ...patterns.base.validate import check_output_name
    from .args import check_shape_flags, input_files
    from ..files.atomic import check_writable_dir
    from ..report.build import DesignRuleError, build, parse_formats
    from ...patterns.base.findings import summary_line
    from ...patterns.design import check_design_records
    from ...patterns.rules.tubes import hoop_overflow
    from .target import analyse_target, gate, load_target

    formats = parse_formats(args.format) if args.format is not None else None
    check_writable_dir(check_output_name("--out", args.out))
    check_shape_flags(args)
    if args.speed_spm is not None:
        from ..report.worksheet import check_speed_spm

        check_speed_spm(args.speed_spm)
    target = load_target(args, design_path=args.design)
    try:
        if target.design is not None:
            check_design_records(target.design)  # the record limit first (a parameter error), then the hoop
        early = None if args.force or target.design is None else hoop_overflow(target.design)
        if early is not None:  # decided from the paths alone: refused before generating anything
            raise DesignRuleError((early,))
        analysis = analyse_target(target)
        res = build(target.design, args.out, formats=formats, force=args.force, split_long=args.split_long,
                    cord_stop=args.cord_stop,
                    speed_spm=args.speed_spm, analysis=analysis, stages=_stages(args),
                    inputs=input_files(args, target.design), out_flag="--out")
    except DesignRuleError as exc:
        if args.json:
            print(json.dumps({"written": False, "summary": summary_line(exc.findings),
                              "findings": [f.as_dict() for f in exc.findings]}, indent=2))
        gate(exc.findings, force=False)
        return 1
    if args.json:
        print(json.dumps({"written": True, "summary": summary_line(res.findings), **res.as_dict(),
                          "model": [a.as_dict() for a in analysis.actuators]}, indent=2, sort_keys=True))
    else:
        if res.findings:
            gate(res.findings, force=True)
        ws = res.worksheet
        print(f"wrote {len(res.files)} files to {res.out_dir}: {', '.join(res.files)}")
        print(f"{ws.stitch_count} stitches, {ws.stop_count} stop(s); tube to cut: "
              + ", ".join(f"{a.name} {a.tube_cut_mm:.0f} mm" for a in ws.actuators))
        print(_models_line(analysis))
    return 0


def _models_line(analysis) -> str:
    """Per actuator: G and P0 with their sources (one line each)."""
    lines = []
    for a in analysis.actuators:  # one line per segment of the chain, each its own model
        for name, part in [(a.segments.part_name(a.name, k), s) for k, s in enumerate(a.segments)]:
            if part.choice is None:
                lines.append(f"{name}: no model ({part.model_error})")
                continue
            m, c = part.choice.model, part.choice
            lines.append(f"{name}: G {m.g_mpa:.4g} MPa ({c.g_source}), P0 {m.p0_kpa:.4g} kPa ({c.p0_source}); "
                         f"tube law {m.tube_law}")
    return "\n".join(lines)
