r"""``embroact design``: from the bend or the shape wanted at a pressure to a design file.

Target bend (one actuator)::

    embroact design --bend-deg 90 --at-kpa 150 [--pattern KIND|any] [--length-mm 100] [--length-tolerance-mm 0] -o design.toml

Target shape (a segmented actuator)::

    embroact design --target-shape SHAPE.csv --at-kpa 200 [--max-segments 6] [--time-limit 60] -o design.toml [--svg FILE]

``SHAPE`` is a CSV of ``x_mm,y_mm`` points (header row ``x_mm,y_mm``) or an SVG drawing's
path (``drawing.svg`` or ``drawing.svg#id``, real units, y up after reading): the fabric line
wanted at ``--at-kpa``, from the clamped end (moved to the origin) heading +x there, +y toward
the back of the fabric (where positive bends turn). The overlay of the predicted shape on the
target goes to ``--svg`` (default ``<design stem>-shape.svg``). The search is
:mod:`embroact.predict.inverse`; the answer names the design's predicted bend or shape error,
and for a target it cannot reach, the nearest design and why. A target no design can follow (a
corner, a bend tighter than any pattern reaches at that pressure, a start not heading +x) is
refused before the search; the search stops at ``--time-limit`` with the best design so far,
and on a terminal says what it is doing. Every design tried is one a machine sews: its needle
points on the machine grid, the bend reported the one ``embroact predict`` computes from them.
A target no sewable design meets (``--tolerance-deg``, ``--tolerance-mm``) exits with code 5 for
every pattern choice and writes nothing unless ``--write-nearest``. Both files are written
atomically; the same target writes the same bytes.

Examples
--------
>>> import os, tempfile
>>> from embroact.export.cli.main import main
>>> out = os.path.join(tempfile.mkdtemp(), "d.toml")
>>> main(["design", "--bend-deg", "-40", "--at-kpa", "250", "--pattern", "cross", "-o", out])  # doctest: +ELLIPSIS
target -40 deg at 250 kPa, l0 100 mm: met: cross bends -39.95 deg at 250 kPa...
...
0
>>> main(["design", "--bend-deg", "88", "--at-kpa", "150", "--pattern", "zigzag", "-o", out])  # doctest: +ELLIPSIS
target 88 deg at 150 kPa, l0 100 mm: not met: no sewable design within 0.5 deg: the machine grid steps width_mm by 0.1 (a length of 97.5 mm would meet it...
...
nothing written: the target is not met (--write-nearest writes the nearest design)
5
>>> main(["design", "--bend-deg", "88", "--at-kpa", "150", "--pattern", "zigzag", "--length-tolerance-mm", "3",
...       "-o", out])  # doctest: +ELLIPSIS
target 88 deg at 150 kPa, l0 100 mm: met: zigzag bends 87.96 deg at 150 kPa with a length of 97.5 mm (asked 100)...
...
0
"""
from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from ...patterns.kinds import PATTERN_KINDS
from .args import add_tube_arguments, tube_from_args
from .main import EXIT_NOT_MET
from .target import P0_SOURCES, TUBE_LAWS

if TYPE_CHECKING:  # pragma: no cover
    from ...patterns.design import Design

__all__ = ["add_arguments", "run", "read_target_shape"]


def add_arguments(parser, name: str) -> None:
    """Options of ``embroact design``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    name : str
        The command's name (``"design"``).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact design")
    >>> add_arguments(parser, "design")
    >>> args = parser.parse_args(["--bend-deg", "90", "--at-kpa", "150", "-o", "d.toml"])
    >>> args.bend_deg, args.at_kpa, args.pattern
    (90.0, 150.0, 'any')
    """
    target = parser.add_argument_group("target (a bend, or a shape)")
    what = target.add_mutually_exclusive_group(required=True)
    what.add_argument("--bend-deg", type=float, help="bend wanted at --at-kpa [deg] (negative: toward the thread side)")
    what.add_argument("--target-shape", metavar="SHAPE.csv|SHAPE.svg[#ID]",
                      help="fabric line wanted at --at-kpa: x_mm,y_mm points or an SVG path")
    target.add_argument("--at-kpa", type=float, required=True, help="pressure of the target [kPa]")
    space = parser.add_argument_group("design space")
    space.add_argument("--pattern", choices=PATTERN_KINDS.names() + ("any",), default="any", help="target bend: pattern to use (default any)")
    space.add_argument("--length-mm", type=float, default=100.0, help="target bend: actuator length [mm] (default 100)")
    space.add_argument("--max-segments", type=int, default=6, help="target shape: at most this many segments (default 6)")
    space.add_argument("--time-limit", type=float, default=None, metavar="S",
                       help="target shape: seconds the search may take; then the best design so far is written "
                            "(default 60; a target no design can follow is refused at once)")
    space.add_argument("--allow-extrapolation", action="store_true",
                       help="search beyond the calibrated range (predictions there are extrapolated)")
    space.add_argument("--name", default="A1", help="actuator name in the written design (default A1)")
    add_tube_arguments(space)
    model = parser.add_argument_group("model")
    model.add_argument("--calibration", metavar="NAME|FILE.toml", default="paper-2025",
                       help="calibration set: a built-in name or a file written by 'embroact fit' (default paper-2025)")
    model.add_argument("--p0-source", choices=P0_SOURCES, default="calibration",
                       help="P0: the calibration set's fitted P0 (default) or the tube law's at r0")
    model.add_argument("--tube-law", choices=TUBE_LAWS, default="paper", help="tube law of the inflation phase")
    out = parser.add_argument_group("output")
    out.add_argument("-o", "--output", required=True, metavar="DESIGN.toml", help="design file to write")
    out.add_argument("--svg", metavar="FILE.svg", help="target shape: predicted shape over the target "
                                                       "(default <DESIGN stem>-shape.svg; refused with --bend-deg, "
                                                       "which writes the design file alone)")
    out.add_argument("--json", action="store_true", help="machine-readable result on stdout")
    out.add_argument("--write-nearest", action="store_true",
                     help="when no sewable design meets the target, write the nearest one anyway (exit code 5 "
                          "either way)")
    space.add_argument("--tolerance-deg", type=float, default=0.5,
                       help="target bend: a sewn design within this of the target meets it [deg] (default 0.5)")
    space.add_argument("--length-tolerance-mm", type=float, default=0.0,
                       help="target bend: the length may differ from --length-mm by up to this (0.1 mm steps, the "
                            "stitch interval fitted to whole intervals) where the grid's width steps miss the target "
                            "(default 0: the length stays)")
    space.add_argument("--tolerance-mm", type=float, default=0.5,
                       help="target shape: a sewn design within this RMSE of the target meets it [mm] (default 0.5)")
    limits = parser.add_argument_group("operation limits the written design keeps (the target is added as its "
                                       "operating point, [operation] target_pressure_kpa)")
    limits.add_argument("--max-pressure-kpa", type=float, default=None,
                        help="highest supply pressure; the rules judge the design up to it (default 300, at least "
                             "--at-kpa)")
    limits.add_argument("--max-bend-deg", type=float, default=None,
                        help="largest bend the application needs (default 180, at least the target bend)")


def read_target_shape(ref: str):
    """Points (n, 2) [mm] of a target shape file: CSV ``x_mm,y_mm`` or an SVG path reference.

    Parameters
    ----------
    ref : str
        ``SHAPE.csv``, or ``SHAPE.svg`` / ``SHAPE.svg#ID`` (a path in the drawing).

    Returns
    -------
    numpy.ndarray (n, 2)
        [mm].

    Raises
    ------
    DesignFileError
        Unreadable file, missing header, a row that is not two numbers (named by line).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     csv = Path(tmp, "hook.csv")
    ...     _ = csv.write_text("x_mm,y_mm\\n0,0\\n50,0\\n80,20\\n")
    ...     read_target_shape(str(csv)).tolist()
    [[0.0, 0.0], [50.0, 0.0], [80.0, 20.0]]
    """
    import numpy as np

    from ...patterns.base.errors import DesignFileError

    path = Path(ref.split("#", 1)[0])
    if path.suffix.lower() == ".svg":
        from ..files.svgfile import svg_centerline

        return np.asarray(svg_centerline(ref).points_mm, dtype=np.float64)
    from ..files.calibfile import check_csv_coordinates, read_csv_table  # the limits of every CSV reader

    columns, rows = read_csv_table(path)
    if "x_mm" not in columns or "y_mm" not in columns:
        raise DesignFileError(f"target shape {str(path)!r}: the first row must be the header x_mm,y_mm")
    points = []
    for line, row in rows:
        try:
            x, y = float(row[columns["x_mm"]]), float(row[columns["y_mm"]])
        except (ValueError, IndexError):
            raise DesignFileError(f"target shape {str(path)!r} row {line}: x_mm,y_mm must be two numbers, "
                                  f"got {','.join(row)[:40]!r}") from None
        points.append((x, y))
    xy = np.array(points, dtype=np.float64).reshape(-1, 2)
    if not np.all(np.isfinite(xy)):
        line = rows[int(np.argwhere(~np.isfinite(xy))[0][0])][0]
        raise DesignFileError(f"target shape {str(path)!r} row {line}: x_mm,y_mm must be finite numbers")
    check_csv_coordinates(path, rows, xy, ("x_mm", "y_mm"))
    return xy


def _settings(args):
    from ...patterns.design import ModelSettings, names_calibration_file
    from .target import note_demo_calibration

    name, sets = args.calibration, ()
    if names_calibration_file(args.calibration):  # a set's name needs no file reader
        from ..files.calibfile import calibration_reference

        name, sets = calibration_reference(args.calibration, Path.cwd())
    note_demo_calibration({name})
    return ModelSettings(calibration=name, p0_source=args.p0_source, tube_law=args.tube_law), sets


def _limits(args):
    """The user's operation limits (``--max-pressure-kpa``, ``--max-bend-deg``; the defaults where not given)."""
    from ...patterns.base.errors import ParameterError
    from ...patterns.design import OperationSettings

    given = {k: v for k, v in (("max_pressure_kpa", args.max_pressure_kpa), ("max_bend_deg", args.max_bend_deg))
             if v is not None}
    try:
        return OperationSettings(**given)
    except ParameterError as exc:  # named as the user typed it
        raise ParameterError("--" + str(exc).replace("_", "-", 2)) from None


def _operation_line(design) -> str:
    """What the written design's ``[operation]`` holds: the limits the rules judge it by, and the target."""
    op = design.operation
    bend = "" if op.target_bend_deg is None else f"{op.target_bend_deg:g} deg at "
    return (f"operation: limits max_pressure_kpa {op.max_pressure_kpa:g}, max_bend_deg {op.max_bend_deg:g} (the rules "
            f"judge the design up to them); operating point {bend}{op.target_pressure_kpa:g} kPa")


def _bend(args, tube, settings, sets, operation) -> tuple[dict, Design, list[str], bool]:
    from ...patterns.kinds import params_text
    from ...predict.inverse import design_bend

    r = design_bend(args.bend_deg, args.at_kpa, pattern=args.pattern, length_mm=args.length_mm, tube=tube,
                    settings=settings, sets=sets, allow_extrapolation=args.allow_extrapolation, name=args.name,
                    tolerance_deg=args.tolerance_deg, operation=operation,
                    length_tolerance_mm=args.length_tolerance_mm)
    lines = [f"target {r.target_deg:g} deg at {r.pressure_kpa:g} kPa, l0 {r.length_mm:g} mm: {r.statement}"]
    if r.range_deg is not None:
        lines.append(f"  reachable at {r.pressure_kpa:g} kPa over the calibrated designs: {r.range_deg[0]:+.2f} to "
                     f"{r.range_deg[1]:+.2f} deg")
    lines += [f"note: {n}" for n in r.notes]
    for label, c in [("best" if r.reached else "nearest", r.best)] + [(f"runner-up {i + 1}", c)
                                                                     for i, c in enumerate(r.runners_up)]:
        miss = c.theta_deg - r.target_deg
        sized = "" if c.length_mm == r.length_mm else f" length_mm={c.length_mm:g} (asked {r.length_mm:g})"
        lines.append(f"{label}: {c.pattern} {params_text(c.params)}{sized} -> {c.theta_deg:.3f} deg sewn"
                     + (f" (misses the target by {miss:+.2f} deg)" if abs(miss) > r.tolerance_deg else "")
                     + f"; P0 {c.p0_kpa:.1f} kPa, G {c.g_mpa:.4g} MPa")
        margin = "" if c.margin_kpa == float("inf") else f" ({c.margin_kpa:.1f} kPa above the target pressure)"
        band = ("none claimed (the calibration records no covariance for this design)" if c.theta_sd_deg is None
                else f"+-{c.theta_sd_deg:.2f} deg (1 sigma, from the calibration's covariance)")
        exact = ("none in a valid state" if c.exact_pressure_kpa is None
                 else f"{c.exact_pressure_kpa:.1f} kPa bends it by {r.target_deg:g} deg")
        lines += [f"  limit: {c.limit}{margin}", f"  exact pressure: {exact}", f"  uncertainty: {band}",
                  "  sensitivity, one machine-grid step (the design sewn again; G, P0 and geometry follow): "
                  + "; ".join(s.text() for s in c.sensitivity),
                  f"  binding: {c.binding}"]
        lines += [f"  finding {f}" for f in c.findings]
    lines.append(_operation_line(r.best.design))
    return r.as_dict(), r.best.design, lines, r.reached


def _shape(args, tube, settings, sets, operation) -> tuple[dict, Design, list[str], str, bool]:
    from ...patterns.kinds import params_text
    from ...predict.inverse import DEFAULT_TIME_LIMIT_S, design_shape
    from ..pictures.shapefit import design_shape_svg

    progress = (lambda message: print(f"design: {message}", file=sys.stderr, flush=True)) \
        if sys.stderr.isatty() and not args.json else None  # on a terminal: what the search is doing
    r = design_shape(read_target_shape(args.target_shape), args.at_kpa, max_segments=args.max_segments, tube=tube,
                     settings=settings, sets=sets, allow_extrapolation=args.allow_extrapolation, name=args.name,
                     time_limit_s=DEFAULT_TIME_LIMIT_S if args.time_limit is None else args.time_limit,
                     tolerance_mm=args.tolerance_mm, progress=progress, operation=operation)
    lines = [f"target shape {args.target_shape} at {r.pressure_kpa:g} kPa: {r.statement}",
             f"RMSE {r.rmse_mm:.3f} mm, max deviation {r.max_deviation_mm:.3f} mm, tip {r.tip_error_mm:.3f} mm off, "
             f"tip angle {r.tip_angle_error_deg:+.2f} deg off (curvature fit alone: RMSE {r.fit_rmse_mm:.3f} mm)"]
    lines += [f"note: {n}" for n in r.notes]
    for i, s in enumerate(r.segments):
        note = f"  ({s.note})" if s.note else ""
        lines.append(f"segment {i}: {s.pattern} {params_text(s.params)} length_mm={s.length_mm:g} -> "
                     f"{s.theta_deg:+.2f} deg{note}")
    lines += [f"finding {f}" for f in r.findings]
    lines.append(_operation_line(r.design))
    return r.as_dict(), r.design, lines, design_shape_svg(r), r.reached


def _check_svg_used(args) -> None:
    """Refuse ``--svg`` with a bend target: only a target shape has an overlay to write.

    Examples
    --------
    >>> import argparse
    >>> _check_svg_used(argparse.Namespace(bend_deg=None, svg="o.svg"))
    >>> try:
    ...     _check_svg_used(argparse.Namespace(bend_deg=90.0, svg="o.svg"))
    ... except ValueError as exc:
    ...     print(str(exc).split(";")[0])
    --svg 'o.svg': only a --target-shape target writes an overlay
    """
    if args.bend_deg is not None and args.svg is not None:
        from ...patterns.base.errors import ParameterError
        from ...patterns.base.validate import shown

        raise ParameterError(f"--svg {shown(args.svg)}: only a --target-shape target writes an overlay; "
                             "--bend-deg writes the design file alone (drop --svg)")


def run(args) -> int:
    """Search, print, write the design (and the overlay SVG for a shape).

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
    >>> parser = argparse.ArgumentParser(prog="embroact design")
    >>> add_arguments(parser, "design")
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     args = parser.parse_args(["--bend-deg", "84.5", "--at-kpa", "150", "--pattern", "zigzag", "-o", f"{tmp}/d.toml"])
    ...     args.command = "design"
    ...     run(args)  # doctest: +ELLIPSIS
    target 84.5 deg at 150 kPa, l0 100 mm: met: zigzag bends 84.53 deg at 150 kPa ...
    ...
    wrote .../d.toml
    0
    """
    from ..files.atomic import check_command_files, write_files_atomic
    from ..files.designfile import dumps_design

    from ...predict.inverse import check_target_pressure
    from .args import input_files

    check_target_pressure(args.at_kpa, "--at-kpa")  # named as the user typed it, before any search
    operation = _limits(args)
    if args.bend_deg is not None and args.length_tolerance_mm:
        from ...patterns.base.errors import check_range

        check_range("--length-tolerance-mm", args.length_tolerance_mm, low=0.0, high=args.length_mm,
                    low_inclusive=True)
    _check_svg_used(args)
    outputs = [("--output", args.output)]
    if args.bend_deg is None:  # the overlay's default name derives from a checked --output
        out = check_command_files(outputs, input_files(args))[0]
        outputs.append(("--svg", args.svg) if args.svg is not None else
                       ("--svg (from --output)", out.with_name(f"{out.stem}-shape.svg")))
    out, *more = check_command_files(outputs, input_files(args))
    tube = tube_from_args(args)
    settings, sets = _settings(args)
    if args.bend_deg is not None:
        result, design, lines, reached = _bend(args, tube, settings, sets, operation)
        files: dict[str | os.PathLike, bytes] = {out: dumps_design(design).encode("utf-8")}
    else:
        result, design, lines, svg, reached = _shape(args, tube, settings, sets, operation)
        files = {out: dumps_design(design).encode("utf-8"), more[0]: svg.encode("utf-8")}
        result["svg"] = str(more[0])
    write = reached or args.write_nearest
    if write:
        write_files_atomic(files)
    result["design_file"] = str(out) if write else None
    if args.json:
        import json

        json.dump(result, sys.stdout, indent=2, sort_keys=True, allow_nan=False)
        sys.stdout.write("\n")
    else:
        done = (f"wrote {', '.join(str(p) for p in files)}" if write else
                "nothing written: the target is not met (--write-nearest writes the nearest design)")
        print("\n".join(lines + [done]))
    return 0 if reached else EXIT_NOT_MET
