"""``embroact check DESIGN.toml | FILE.dst``: the design-rule checks, as a table or JSON.

A ``.toml`` input is an embroact design: it is generated and every rule runs
(geometry, pattern, file structure, model). Any other input is an embroidery file
read with pystitch, checked against the tube(s) given with ``--tube-path``
(repeatable, one per tube, ``"x1,y1 x2,y2 ..."`` in mm in the file's frame as
pystitch reads it: 0.1 mm units divided by 10, y down; SVG path data as ``--path``
takes it, ``"M 0 0 L 100 0"``, in that same y-down frame; or ``drawing.svg#tube1``, a
drawn path in page mm, y down, the frame a design built from that drawing is sewn in; see
:mod:`embroact.export.machine.filecheck`) or ``--tube TUBES.toml``; findings name the
needle point (counted from 0, the same in every format) with the record index in the
file's own order alongside, and give fixes for the file's author. When no needle point
lies near any tube the finding says which frame the path is read in.

Exit codes: 0 no errors (warnings allowed); 1 at least one error; 2 unusable input
(missing, truncated or garbage file, bad option), one line on stderr.

Examples
--------
>>> from embroact.export.cli.main import main
>>> main(["check", "act.dst", "--tube-path", "0,0 100,0"])  # doctest: +SKIP
act.dst: embroidery file, format dst, 1 tube: no findings
0
"""
from __future__ import annotations

import json

__all__ = ["add_arguments", "run", "format_table"]


def add_arguments(parser, name: str) -> None:
    """Options of ``embroact check``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    name : str
        The command's name (``"check"``).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact check")
    >>> add_arguments(parser, "check")
    >>> args = parser.parse_args(["a.dst", "--tube-path", "-50,0 50,0"])
    >>> args.input, args.tube_path
    ('a.dst', ['-50,0 50,0'])
    """
    from ...patterns.limits import FORMAT_LIMITS
    from .args import add_tube_arguments
    from .target import add_model_arguments

    parser.add_argument("input", nargs="?", metavar="DESIGN.toml|FILE",
                        help="embroact design (TOML) or any embroidery file")
    add_model_arguments(parser.add_argument_group("model (design files only; overrides the design's "
                                                  "[actuator.model], as for predict and build)"))
    tube = parser.add_argument_group("tube (embroidery files only)")
    tube.add_argument("--tube-path", action="append", default=[], metavar="'x1,y1 x2,y2 ...'|SVG_D|FILE.svg#ID",
                      help="tube axis in mm, file frame (0.1 mm units / 10, y down): points, SVG path data "
                           "('M 0 0 L 100 0', as --path takes), or a path of an SVG drawing (drawing.svg#tube1: "
                           "page mm, y down); repeat for several tubes")
    add_tube_arguments(tube, fields=("outer_radius_mm", "clearance_mm"))
    tube.add_argument("--end-margin-mm", type=float, default=0.0,
                      help="free tube beyond each end of the path [mm] (default 0)")
    tube.add_argument("--tube", metavar="TUBES.toml", help="tubes (and [machine] limits) from a TOML file")
    tube.add_argument("--origin-mm", metavar="X,Y",
                      help="where the file's start point lies in the frame of the --tube-path paths [mm, y down: a "
                           "drawing's page], as the build's worksheet states it (default 0,0: the paths are in the "
                           "file's own frame)")
    parser.add_argument("--format", choices=sorted(FORMAT_LIMITS),
                        help="target machine format (default: the design's machine.format, or the file's own)")
    parser.add_argument("--json", action="store_true", help="machine-readable output")
    parser.add_argument("--rules", action="store_true", help="print the table of every rule (Markdown) and exit")


def _check_design(args):
    from ...predict.rules import check_design
    from .target import analyse_target, load_target

    target = load_target(args, design_path=args.input)
    design = target.design
    fmt = args.format or design.machine.format
    findings = check_design(analyse_target(target), format=fmt)
    return findings, {"kind": "design", "name": design.name, "format": fmt, "actuators": len(design.actuators)}


def _point_mm(text: str):
    """``--origin-mm``'s ``X,Y`` [mm] as an array (finite, within the coordinate bound)."""
    import numpy as np

    from ...patterns.base.errors import ParameterError
    from ...patterns.origin import check_origin

    try:
        point = check_origin([float(v) for v in str(text).split(",")])
    except (ValueError, ParameterError):
        raise ParameterError(f"--origin-mm must be X,Y in mm, got {text!r:.60}") from None
    return np.array(point)


def _check_file(args):
    import numpy as np

    from ...patterns.base.errors import ParameterError
    from ..machine.filecheck import check_file, file_rule_settings, load_tube_file, parse_tube_path, read_records, tube_layout

    if args.tube and args.tube_path:
        raise ParameterError("give either --tube TUBES.toml or --tube-path, not both")
    if args.origin_mm is not None and not args.tube_path:
        raise ParameterError("--origin-mm places the --tube-path paths; give it with --tube-path")
    machine: dict = {}
    if args.tube:
        tubes, machine = load_tube_file(args.tube)
    else:
        from ..files.svgfile import is_svg_ref, read_svg_path

        origin = np.zeros(2) if args.origin_mm is None else _point_mm(args.origin_mm)
        tubes = tuple(
            tube_layout((read_svg_path(text).points_mm if is_svg_ref(text) else parse_tube_path(text)) - origin,
                        name=f"tube {i + 1}", outer_radius_mm=args.outer_radius_mm,
                        clearance_mm=args.clearance_mm, end_margin_mm=args.end_margin_mm)
            for i, text in enumerate(args.tube_path)
        )
    records = read_records(args.input)
    own = machine.pop("format", None)
    settings = file_rule_settings(records, format=args.format or own, **machine)
    fmt = settings.format
    findings = check_file(args.input, tubes, settings=settings, records=records)
    return findings, {"kind": "embroidery file", "name": args.input, "format": fmt, "tubes": len(tubes),
                      "records": len(records)}


def format_table(findings, header: str) -> str:
    """Findings as text: a summary line, then per severity the code, place, message and fix.

    Parameters
    ----------
    findings : sequence of Finding
        What the rules found.
    header : str
        What was checked (the summary line starts with it).

    Returns
    -------
    str
        Lines, without a final newline.

    Examples
    --------
    >>> from embroact.patterns.base.findings import RULES
    >>> import embroact.patterns.rules  # declares the rules
    >>> print(format_table([RULES.finding("EA101", "needle 0.4 mm from the axis", actuator="A1", stitch_index=7)],
    ...                    "a.dst"))  # doctest: +ELLIPSIS +NORMALIZE_WHITESPACE
    a.dst: 1 error, 0 warnings, 0 info
    <BLANKLINE>
    ERRORS
      EA101  needle in tube corridor  [A1, stitch 7]
             needle 0.4 mm from the axis
             fix: ...
    """
    from ...patterns.base.findings import Severity, count_by_severity

    counts = count_by_severity(findings)
    summary = ", ".join(f"{n} {s}{'s' if n != 1 and s != 'info' else ''}" for s, n in counts.items())
    lines = [f"{header}: {summary if findings else 'no findings'}"]
    for sev in Severity:
        group = [f for f in findings if f.severity is sev]
        if not group:
            continue
        lines += ["", f"{sev.value.upper()}S" if sev is not Severity.INFO else "INFO"]
        for f in group:
            lines.append(f"  {f.code}  {f.title}  [{f.place()}]")
            lines.append(f"         {f.message}")
            lines.append(f"         fix: {f.fix}")
    return "\n".join(lines)


def run(args) -> int:
    """Check the input; print the table or JSON; 1 if any error.

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
    >>> from embroact.export.cli.main import main
    >>> parser = argparse.ArgumentParser(prog="embroact check")
    >>> add_arguments(parser, "check")
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = main(["zigzag", "--width-mm", "7", "-o", f"{tmp}/a.dst"])  # doctest: +ELLIPSIS
    ...     args = parser.parse_args([f"{tmp}/a.dst", "--tube-path", "-50,0 50,0"])
    ...     args.command = "check"
    ...     run(args)  # doctest: +ELLIPSIS
    wrote .../a.dst (dst): 106 stitches, ...
    .../a.dst: embroidery file, format dst, 1 tube(s): no findings
    0
    """
    from ...patterns.base.errors import ParameterError
    from ...patterns.base.findings import count_by_severity
    from ...predict.rule_catalogue import rules_table

    if args.rules:
        print(rules_table(), end="")
        return 0
    if args.input is None:
        raise ParameterError("check needs an input: DESIGN.toml or an embroidery file (or --rules)")
    is_design = args.input.lower().endswith(".toml")
    if is_design and (args.tube_path or args.tube):
        raise ParameterError("--tube-path and --tube apply to embroidery files; a design file carries its tubes")
    from .target import model_flags_given

    model_flags = model_flags_given(args)
    if not is_design and model_flags:
        raise ParameterError(f"{model_flags[0]} applies to design files (the model rules); an embroidery file "
                             "is checked without a model")
    findings, info = _check_design(args) if is_design else _check_file(args)
    counts = count_by_severity(findings)
    if args.json:
        doc = dict(info, input=args.input, counts=counts, findings=[f.as_dict() for f in findings])
        print(json.dumps(doc, indent=2, sort_keys=True, ensure_ascii=False))
    else:
        what = f"{info['kind']}, format {info['format']}"
        if not is_design:
            what += f", {info['tubes']} tube(s)" if info["tubes"] else ", no tube given (tube rules skipped)"
        print(format_table(findings, f"{args.input}: {what}"))
    return 1 if counts["error"] else 0
