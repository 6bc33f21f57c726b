r"""``embroact fit DATA.csv``: fit G and P0 to measured bend angles, write a calibration set.

Examples
--------
Noise-free angles from the model (G = 2.7 MPa, P0 = 85 kPa) come back as they went in:

>>> import os, tempfile
>>> from embroact.export.cli.main import main
>>> from embroact.patterns.params import Tube
>>> from embroact.predict.curve import ActuatorModel, curve
>>> from embroact.predict.derived import derive_from_values
>>> d = derive_from_values("zigzag", width_mm=7, interval_mm=1, angle_deg=0, length_mm=100, tube=Tube())
>>> p = list(range(0, 301, 20))
>>> theta = curve(ActuatorModel.from_derived(d, g_mpa=2.7, p0_kpa=85.0), p).theta_deg
>>> path = os.path.join(tempfile.mkdtemp(), "data.csv")
>>> with open(path, "w") as fh:
...     _ = fh.write("pressure_kpa,angle_deg\n" + "".join(f"{a},{t:.4f}\n" for a, t in zip(p, theta)))
>>> main(["fit", path, "--pattern", "zigzag", "--width-mm", "7"])
fit of zigzag w=7 mm s=1 mm l0=100 mm (as generated); model method stable-analytic-trace
branch        n  G [MPa]            P0 [kPa]                 RMSE [deg]
loading      16  2.7 +- ...         85 +- ... fitted ...
0
"""
from __future__ import annotations

import json
import os
import re
import sys

from ...patterns.kinds import PATTERN_KINDS
from .args import materials_of, plus_minus
from .markerargs import add_layout_arguments, layout_from_args
from .target import TUBE_LAWS, add_quick_arguments, reset_notes

__all__ = ["add_arguments", "run"]

_ALIASES = {"g": "g_mpa", "p0": "p0_kpa", "g_e": "g_e_mpa", "ge": "g_e_mpa", "mu": "g_e_mpa"}
#: Pattern names (the registry is light: no numpy for --help).


def add_arguments(parser, name: str) -> None:
    """Options of ``embroact fit``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    name : str
        The command's name (``"fit"``).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact fit")
    >>> add_arguments(parser, "fit")
    >>> args = parser.parse_args(["loop.csv", "--pattern", "zigzag", "--width-mm", "7", "-o", "cal.toml"])
    >>> args.data, args.pattern, args.width_mm
    ('loop.csv', 'zigzag', 7.0)
    """
    parser.add_argument("data", metavar="DATA.csv", nargs="?",
                        help="pressure_kpa,angle_deg[,branch] rows (or markers with --markers)")
    parser.add_argument("--sheet", metavar="SHEET.csv",
                        help="a whole coupon measurement sheet (embroact calibrate coupon, filled by embroact measure): "
                             "fit every actuator, write one profile, report leave-one-out errors")
    design = parser.add_argument_group("design (quick parameters or a design file)")
    design.add_argument(
        "--design", metavar="DESIGN.toml", help="design file: its first (or --actuator) actuator, tube from the file"
    )
    design.add_argument("--actuator", metavar="NAME", help="actuator name in the design file")
    design.add_argument("--pattern", choices=PATTERN_KINDS.names(), help="pattern of the measured sample")
    add_quick_arguments(design, pattern=None, name_flag=False)
    fit = parser.add_argument_group("fit")
    fit.add_argument("--fit", default="g,p0",
                     help="parameters to fit: g, p0, g_e (comma-separated; default g,p0); with --tube-law "
                          "thick-wall g_e (or mu) is the tube's mu")
    fit.add_argument("--tube-law", choices=TUBE_LAWS, default="paper",
                     help="tube law of P0 from the geometry and of the inflation phase (default paper)")
    fit.add_argument(
        "--branch",
        choices=("loading", "unloading", "both", "pooled"),
        default="both",
        help="fit each branch present separately (both, default), one of them, or all points at once (pooled)",
    )
    fit.add_argument("--g-mpa", type=float, help="G [MPa] when not fitted (also a start value)")
    fit.add_argument("--p0-kpa", type=float, help="P0 [kPa] when not fitted (default: from geometry and G_e)")
    fit.add_argument("--method", default="auto", help="model method (default auto)")
    marks = parser.add_argument_group("how the angles were measured (markers: DATA.csv may hold m1_x, m1_y[, m1_z] "
                                      "... per frame)")
    marks.add_argument("--markers", action="store_true",
                       help="DATA.csv holds marker coordinates: compute the marker sums first (implies "
                            "--measurement markers)")
    add_layout_arguments(marks, recorded="the layout of the set --append merges into", measurement_help=(
        "how the angles in DATA.csv were measured: whole-strip (the angle between the strip's two ends, default) "
        "or markers (the layout's marker sum: the fit compares the data with what the layout reads on the "
        "model's bend); recorded in the set"))
    marks.add_argument(
        "--normal",
        metavar="X,Y,Z",
        help="direction out of the fabric's back: signs the angles; without it the unsigned angles "
        "take the design's bending direction",
    )
    marks.add_argument("--tangent", metavar="X,Y,Z",
                       help="with --normal: the strip's direction at the clamp, clamped end to tip (default: the "
                            "first marker chord of the straightest frame)")
    out = parser.add_argument_group("output")
    out.add_argument("-o", "--output", metavar="CAL.toml", help="write the fits as a calibration set")
    out.add_argument("--name", help="calibration set name (default: the output file's stem)")
    out.add_argument("--description", default="", help="calibration set description")
    out.add_argument("--material", action="append", default=[], metavar="KEY=VALUE", help="e.g. tube=silicone (repeatable)")
    out.add_argument("--append", action="store_true", help="merge into an existing calibration file instead of replacing it")
    out.add_argument("--json", action="store_true", help="machine-readable output")


def _fit_names(text: str) -> tuple[str, ...]:
    from ...patterns.base.errors import ParameterError

    names = [t.strip().lower() for t in text.split(",") if t.strip()]
    bad = [n for n in names if n not in _ALIASES and n not in _ALIASES.values()]
    if bad or not names:
        raise ParameterError(f"--fit must list parameters from g, p0, g_e, got {text!r}")
    return tuple(_ALIASES.get(n, n) for n in names)


def _actuator(args):
    """The measured actuator, analysed as every command analyses it (realised geometry).

    Quick parameters generate the actuator (``embroact predict`` does the same), so the fit
    models the angle, interval and length the generator realised, not the requested ones.
    """
    import argparse

    from ...patterns.base.errors import ParameterError
    from .target import analyse_target, load_target

    if args.design:
        acts = analyse_target(load_target(args, design_path=args.design)).actuators
        found = [a for a in acts if args.actuator is None or a.name == args.actuator]
        if not found:
            names = ", ".join(repr(a.name) for a in acts)
            raise ParameterError(f"--actuator must be one of {names}, got {args.actuator!r}")
        return found[0]
    if args.pattern is None or args.width_mm is None:
        raise ParameterError("give the design: --pattern and --width-mm (and --angle-deg for cross), or --design FILE")
    quick = argparse.Namespace(**{**vars(args), "name": None})  # --name names the calibration set here
    return analyse_target(load_target(quick, pattern=args.pattern)).actuators[0]


def _vector(flag: str, text: str | None):
    from ...patterns.base.errors import ParameterError

    if text is None:
        return None
    try:
        return [float(t) for t in text.split(",")]
    except ValueError:
        raise ParameterError(f"{flag} must be 2 or 3 comma-separated numbers, got {text!r}") from None


def _data(args, derived, choice):
    """(pressure_kpa, angle_deg, branch labels, note) from the CSV; ``choice`` the LayoutChoice or None."""
    import numpy as np

    from ...patterns.base.errors import ParameterError
    from ...predict.markers import marker_angles
    from ..files.calibfile import read_bend_csv, read_marker_csv

    if not args.markers:
        if args.normal is not None or args.tangent is not None:
            raise ParameterError("--normal and --tangent orient marker coordinates: they need --markers")
        d = read_bend_csv(args.data)
        return (d.pressure_kpa, d.angle_deg, d.branch,
                "" if choice is None else f"angles are {choice.layout.label} (layout: {choice.source})")
    layout = choice.layout
    normal, tangent = _vector("--normal", args.normal), _vector("--tangent", args.tangent)
    if tangent is not None and normal is None:
        raise ParameterError("--tangent needs --normal (it only orients the signed angles)")
    m = read_marker_csv(args.data, n_markers=layout.markers_per_side * layout.rows)
    angles = marker_angles(m.markers_mm, markers_per_side=layout.markers_per_side, sides=layout.rows, normal=normal,
                           tangent=tangent)
    theta = np.asarray(angles.theta_deg)
    note = f"marker sums of {layout.label} (layout: {choice.source}); coordinate noise {angles.noise_mm:.2g} mm"
    if normal is None and not derived.bends_positive:
        theta = -theta
        note += " (unsigned; given this design's negative bending direction)"
    return m.pressure_kpa, theta, m.branch, note


def _appended_set(args):
    """The calibration set ``--append`` merges into (None: no such file, or no ``--append``)."""
    from ..files.calibfile import read_calibration

    return read_calibration(args.output) if args.output and args.append and os.path.exists(args.output) else None


def _write_set(args, act, results, layout, old):
    """Write (or merge into ``old``) the calibration file: the points plus the tube and tube law the fit used."""
    from ...patterns.base.errors import ParameterError
    from ...predict.calibration import CalibrationSet, CalibrationTube
    from ..files.calibfile import write_calibration

    points = tuple(r.to_point() for r in results)
    tube = CalibrationTube.of(act.derived.tube)
    stem = os.path.splitext(os.path.basename(args.output))[0]
    name = args.name or re.sub(r"[^A-Za-z0-9._-]", "-", stem)
    if old is not None:
        if args.name and args.name != old.name:
            raise ParameterError(f"--name {args.name!r} differs from the set {old.name!r} in {args.output!r}")
        if old.tube is not None and old.tube.differences(act.derived.tube):
            raise ParameterError(f"tube differs from the one of the set in {args.output!r}: "
                                 + "; ".join(old.tube.differences(act.derived.tube)))
        if old.tube_law != args.tube_law:
            raise ParameterError(f"--tube-law {args.tube_law} differs from the set's {old.tube_law!r} in {args.output!r}")
        if old.marker_layout != layout:
            now = "whole-strip" if layout is None else layout.label
            raise ParameterError(f"the measurement ({now}) differs from the set's ({old.measurement}) in {args.output!r}")
        cset = old.with_points(points)
    else:
        cset = CalibrationSet(name, points, args.description, materials_of(args.material), tube=tube,
                              tube_law=args.tube_law, marker_layout=layout)
    write_calibration(args.output, cset)
    return cset


def _table(derived, results, note, cset, path) -> str:
    from ...patterns.kinds import pattern_kind

    d = derived
    design = f"{d.pattern} w={d.width_mm:.4g} mm s={d.interval_mm:.4g} mm l0={d.length_mm:.4g} mm"
    if pattern_kind(d.pattern).has_angle:
        design += f" alpha0={d.angle_deg:.4g} deg"
    lines = [f"fit of {design} (as generated); model method {results[0].method}" + (f"; {note}" if note else "")]
    lines.append(f"{'branch':<10} {'n':>4}  {'G [MPa]':<18} {'P0 [kPa]':<24} {'RMSE [deg]':>10}")
    for r in results:
        p0 = f"{plus_minus(r.p0_kpa, r.p0_kpa_se)} {r.p0_source}"
        lines.append(f"{r.branch:<10} {r.n_points:>4}  {plus_minus(r.g_mpa, r.g_mpa_se):<18} {p0:<24} {r.rmse_deg:>10.3g}")
        if "g_e_mpa" in r.fitted:
            modulus = "mu" if r.tube_law == "thick-wall" else "G_e"
            lines.append(f"{'':<16}{modulus} = {plus_minus(r.g_e_mpa, r.g_e_mpa_se)} MPa (tube law {r.tube_law})")
        lines += [f"{'':<16}note: {n}" for n in r.notes]
    if cset is not None:
        lines.append(f"wrote calibration set {cset.name!r} ({len(cset.points)} point(s)) to {path}")
    return "\n".join(lines)


def run(args) -> int:
    """Read the data, fit, print, write the calibration set; return the exit code.

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
    >>> from pathlib import Path
    >>> parser = argparse.ArgumentParser(prog="embroact fit")
    >>> add_arguments(parser, "fit")
    >>> rows = "pressure_kpa,angle_deg\\n" + "".join(f"{p},{a}\\n" for p, a in ((0, 0), (100, 11.5), (150, 44.1), (200, 102.9)))
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "loop.csv").write_text(rows)
    ...     args = parser.parse_args([f"{tmp}/loop.csv", "--pattern", "zigzag", "--width-mm", "7", "-o", f"{tmp}/c.toml"])
    ...     args.command = "fit"
    ...     run(args)  # doctest: +ELLIPSIS
    fit of zigzag w=7 mm s=1 mm l0=100 mm (as generated); model method ...
    branch        n  G [MPa] ...
    ...
    wrote calibration set 'c' (1 point(s)) to .../c.toml
    0
    """
    if args.sheet is not None:
        from .fitsheet import run_sheet

        return run_sheet(args)
    if args.data is None:
        from ...patterns.base.errors import ParameterError

        raise ParameterError("give the measurements: DATA.csv (one sample) or --sheet SHEET.csv (a whole coupon)")
    from ...predict.fit import fit_design
    from ..files.atomic import check_command_files
    from .args import input_files

    if args.output is not None:
        check_command_files([("--output", args.output)], input_files(args))
    old = _appended_set(args)
    choice = layout_from_args(args, markers=args.markers, recorded=None if old is None else old.marker_layout,
                              calibration="" if old is None else old.name)
    layout = None if choice is None else choice.layout
    act = _actuator(args)
    reset_notes()  # the fit takes the measured geometry only, no calibration's G or P0: no demonstration note
    derived = act.segments.single(f"actuator {act.name!r} has {len(act.segments)} segments: "
                                  "a fit is of one pattern (fit each segment's coupon alone)").derived
    pressure, angle, labels, note = _data(args, derived, choice)
    results = fit_design(
        derived,
        pressure,
        angle,
        fit=_fit_names(args.fit),
        branch=args.branch,
        labels=labels,
        g_mpa=args.g_mpa,
        p0_kpa=args.p0_kpa,
        method=args.method,
        measurement=layout,
        tube_law=args.tube_law,
    )
    cset = _write_set(args, act, results, layout, old) if args.output else None
    if args.json:
        doc = {
            "design": derived.as_dict(),
            "note": note,
            "fits": [r.as_dict() for r in results],
            "calibration": None if cset is None else {"name": cset.name, "path": args.output, "points": len(cset.points),
                                                      "tube_law": cset.tube_law, "measurement": cset.measurement,
                                                      "marker_layout": None if layout is None else layout.as_dict(),
                                                      "marker_layout_source": None if choice is None else choice.source},
        }
        json.dump(doc, sys.stdout, indent=1, sort_keys=True, allow_nan=False)
        sys.stdout.write("\n")
    else:
        print(_table(derived, results, note, cset, args.output))
    return 0
