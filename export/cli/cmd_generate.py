"""``embroact zigzag`` and ``embroact cross``: one actuator, straight to a machine file.

The quick parameters become a one-actuator design, analysed once
(:func:`embroact.export.cli.target.load_target`, :func:`embroact.predict.analysis.analyse`),
and every design rule runs on it before anything is written (the rule gate
:func:`embroact.export.cli.target.gate`): errors refuse with exit code 1 and write nothing
unless ``--force``; warnings are summarised on stderr in one line; the worksheet lists all.

Examples
--------
>>> import os, tempfile
>>> from embroact.export.cli.main import main
>>> out = os.path.join(tempfile.mkdtemp(), "act.dst")
>>> main(["zigzag", "--width-mm", "7", "--interval-mm", "1", "--length-mm", "100", "-o", out])
wrote ...act.dst (dst): 106 stitches, 1 stop, 1 trim; w 7 mm, s 1 mm, l0 100 mm; r0 2.581 mm; G 2.7 MPa, P0 85 kPa (calibration paper-2025 (zigzag, width_mm=7))
0
"""
from __future__ import annotations

import argparse
import json
from pathlib import Path

from .target import add_model_arguments, add_placement_argument, add_origin_argument, add_quick_arguments

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser, name: str) -> None:
    """Options of a quick command (``embroact <kind>``), one per registered pattern kind.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    name : str
        The command's name (a pattern kind, ``"zigzag"``).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact zigzag")
    >>> add_arguments(parser, "zigzag")
    >>> args = parser.parse_args(["--width-mm", "6.5", "-o", "a.dst"])
    >>> args.width_mm, args.output
    (6.5, 'a.dst')
    """
    add_quick_arguments(parser.add_argument_group("pattern and tube"), pattern=name, required=True)
    add_model_arguments(parser.add_argument_group("model (for the design rules and the summary)"))
    o = parser.add_argument_group("output")
    o.add_argument("-o", "--output", required=True, help="machine file; the suffix picks the format (.dst .pes ...)")
    o.add_argument("--format", help="format overriding the suffix: dst, tbf, pes, pec, jef, exp, vp3, xxx, u01")
    o.add_argument("--force", action="store_true",
                   help="write even if the design-rule checks find errors (legs over the format's record limit "
                        "are then split as with --split-long)")
    o.add_argument("--cord-stop", choices=("sequence", "double"), default="sequence",
                   help="how DST/EXP write the cord-in stop: one stop code (sequence, default) or two in a row "
                        "(double: stops a multi-needle machine in automatic needle mode too)")
    add_placement_argument(o)
    add_origin_argument(o)
    o.add_argument("--split-long", action="store_true",
                   help="split legs longer than the format allows into stitches outside the tube corridor")
    o.add_argument("--worksheet", action="store_true",
                   help="also write OUTPUT_STEM.worksheet.txt and OUTPUT_STEM.worksheet.json")
    o.add_argument("--speed-spm", type=float, default=None,  # None: worksheet.DEFAULT_SPEED_SPM (no numpy for --help)
                   help="machine speed for the worksheet [stitches/min]")
    o.add_argument("--preview", metavar="SVG", help="also write the stitch preview to this SVG file")
    o.add_argument("--json", action="store_true", help="print machine-readable JSON (units in the keys)")


def _realised(r) -> dict:
    return {"width_mm": r.width_mm, "interval_mm": r.interval_mm, "angle_deg": r.angle_deg,
            "length_mm": r.length_mm, "passes": r.passes}


def _summary(path: str, res, act) -> str:
    from ...patterns.kinds import pattern_kind

    r = act.derived
    angle = f", alpha0 {r.angle_deg:.4g} deg" if pattern_kind(r.pattern).has_angle else ""
    split = f", {res.split_legs} long legs split" if res.split_legs else ""
    model = (f"G {act.model.g_mpa:.4g} MPa, P0 {act.model.p0_kpa:.4g} kPa ({act.choice.p0_source})"
             if act.choice is not None else f"no model ({act.model_error})")
    return (f"wrote {path} ({res.format}): {res.counts_text()}{split}; "
            f"w {r.width_mm:.4g} mm, s {r.interval_mm:.4g} mm{angle}, l0 {r.length_mm:.4g} mm; "
            f"r0 {r.r0_mm:.4g} mm; {model}")


def run(args) -> int:
    """Generate and analyse once, gate on the design rules, encode and write; every output is
    checked before anything is generated.

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
    >>> parser = argparse.ArgumentParser(prog="embroact zigzag")
    >>> add_arguments(parser, "zigzag")
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     args = parser.parse_args(["--width-mm", "7", "-o", f"{tmp}/a.dst"])
    ...     args.command = "zigzag"
    ...     run(args)  # doctest: +ELLIPSIS
    wrote .../a.dst (dst): 106 stitches, 1 stop, 1 trim; w 7 mm, s 1 mm, l0 100 mm; r0 2.581 mm; G 2.7 MPa, P0 85 kPa (...)
    0
    """
    from ...predict.rules import check_design
    from ...patterns.base.validate import check_output_name
    from ..files.atomic import check_command_files, write_files_atomic
    from .args import input_files
    from ..machine.formats import encode, machine_format
    from ..report.build import SPLIT_LONG_IGNORES, forced_split
    from .target import analyse_target, gate, load_target

    if args.speed_spm is not None:
        from ..report.worksheet import check_speed_spm

        check_speed_spm(args.speed_spm)
    out = Path(check_output_name("--output", args.output))
    fmt = machine_format(out, fmt=args.format)
    sheets = [out.with_name(out.stem + ".worksheet.txt"), out.with_name(out.stem + ".worksheet.json")]
    check_command_files([("--output", out)] + [("--worksheet", s) for s in sheets if args.worksheet]
                        + ([("--preview", args.preview)] if args.preview is not None else []), input_files(args))
    analysis = analyse_target(load_target(args, pattern=args.command))
    plan, act = analysis.plan, analysis.actuators[0]
    findings = check_design(analysis, format=fmt.name, ignore=SPLIT_LONG_IGNORES if args.split_long else ())
    if not gate(findings, force=args.force):
        if args.json:
            print(json.dumps({"written": False, "findings": [f.as_dict() for f in findings]}, indent=2))
        return 1
    data, res = encode(plan, fmt, split_long=args.split_long or forced_split(findings, args.force),
                       cord_stop=args.cord_stop)
    outputs: dict[Path, str | bytes] = {out: data}
    if args.worksheet:
        from ..report.worksheet import DEFAULT_SPEED_SPM, worksheet

        ws = worksheet(plan, speed_spm=DEFAULT_SPEED_SPM if args.speed_spm is None else args.speed_spm,
                       findings=findings, analysis=analysis, machine=res)
        outputs[sheets[0]] = ws.as_text()
        outputs[sheets[1]] = json.dumps(ws.as_dict(), indent=2, sort_keys=True) + "\n"
    if args.preview:
        from ..pictures.stitches import plan_svg

        outputs[Path(args.preview)] = plan_svg(plan)
    write_files_atomic({p: c.encode("utf-8") if isinstance(c, str) else c for p, c in outputs.items()})
    if args.json:
        doc = {
            "written": True,
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
            **act.as_dict(),
            "findings": [f.as_dict() for f in findings],
        }
        print(json.dumps(doc, indent=2, sort_keys=True))
    else:
        print(_summary(str(out), res, act))
        for note in plan.actuators[0].adjustments:
            print(f"adjusted: {note} (requested values could not both be met)")
        for p in list(outputs)[1:]:
            print(f"wrote {p}")
    return 0
