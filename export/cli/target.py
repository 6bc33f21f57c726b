"""What a command works on: a design file or quick parameters, with model flags, analysed once; the rule gate.

Every command that reads a design goes through :func:`load_target` (design file, or quick
parameters that become a one-actuator design) and :func:`analyse_target` (the design
analysed by :func:`embroact.predict.analysis.analyse` after the model flags are applied:
flag > design file > default). Every command that writes a machine file passes its
findings through :func:`gate`: errors refuse (exit 1, nothing written) unless ``--force``;
warnings are summarised in one line with their codes and actuators.

Examples
--------
>>> import argparse
>>> from embroact.export.cli.target import add_model_arguments
>>> p = argparse.ArgumentParser()
>>> add_model_arguments(p)
>>> a = p.parse_args(["--g-mpa", "2", "--p0-source", "geometry"])
>>> a.g_mpa, a.p0_source, a.calibration
(2.0, 'geometry', None)
"""
from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from .args import TUBE_FLAGS, add_tube_arguments

if TYPE_CHECKING:  # pragma: no cover
    from ...patterns.design import Design
    from ...predict.calibration import CalibrationSet

__all__ = ["Target", "add_model_arguments", "add_quick_arguments", "add_placement_argument", "add_origin_argument",
           "parse_origin", "MODEL_FLAGS", "model_flags_given", "load_target",
           "analyse_target", "gate", "P0_SOURCES", "TUBE_LAWS", "DEMO_CALIBRATION", "DEMO_NOTE",
           "note_demo_calibration", "print_notes", "reset_notes"]

#: Values of ``--p0-source`` and ``--tube-law`` (the enums' values; a test holds them equal, so
#: that ``--help`` needs no numpy).
P0_SOURCES = ("calibration", "geometry")
TUBE_LAWS = ("paper", "thick-wall")
#: Quick-parameter default actuator length [mm] (the interval's is the pattern kind's).
DEFAULT_LENGTH_MM = 100.0


@dataclass(frozen=True)
class Target:
    """A loaded design and the calibration sets its settings name (read from files).

    Attributes
    ----------
    design : Design
        The design, with the model flags applied.
    calibration_sets : tuple of CalibrationSet
        The sets its settings name that come from files.
    source : str
        The design file, or ``"quick parameters"``.
    quick : bool
        True when the design came from quick parameters (one actuator).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser()
    >>> add_quick_arguments(parser, pattern="zigzag")
    >>> add_model_arguments(parser)
    >>> args = parser.parse_args(["--width-mm", "6.5", "--g-mpa", "2.5"])
    >>> target = load_target(args, pattern="zigzag")
    >>> target.source, target.quick, target.design.actuators[0].params.width_mm
    ('quick parameters', True, 6.5)
    """

    design: Design
    calibration_sets: tuple
    source: str
    quick: bool


#: The model flags add_model_arguments adds (their argparse names).
MODEL_FLAGS = ("g_mpa", "p0_kpa", "p0_source", "calibration", "tube_law")


def model_flags_given(args) -> list[str]:
    """The model flags given on the command line, as typed (``--g-mpa``).

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options.

    Returns
    -------
    list of str

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser()
    >>> add_quick_arguments(parser, pattern="zigzag")
    >>> add_model_arguments(parser)
    >>> args = parser.parse_args(["--width-mm", "6.5", "--g-mpa", "2.5"])
    >>> model_flags_given(args)
    ['--g-mpa']
    """
    return [f"--{k.replace('_', '-')}" for k in MODEL_FLAGS if getattr(args, k, None) is not None]


def add_model_arguments(group) -> None:
    """``--g-mpa``, ``--p0-kpa``, ``--p0-source``, ``--calibration``, ``--tube-law`` (None: the design's).

    Parameters
    ----------
    group : argparse.ArgumentParser or argument group
        Where the flags go.

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser()
    >>> add_quick_arguments(parser, pattern="zigzag")
    >>> add_model_arguments(parser)
    >>> args = parser.parse_args(["--width-mm", "6.5", "--g-mpa", "2.5"])
    >>> args.g_mpa, args.p0_kpa, args.calibration
    (2.5, None, None)
    """
    group.add_argument("--g-mpa", type=float, help="effective modulus G [MPa] (default: design file, else calibration set)")
    group.add_argument("--p0-kpa", type=float, help="transition pressure P0 [kPa] (default: see --p0-source)")
    group.add_argument("--p0-source", choices=P0_SOURCES,
                       help="P0 when not given: the calibration set's fitted P0 (default) or the tube law's at r0")
    group.add_argument("--calibration", metavar="NAME|FILE.toml",
                       help="calibration set: a built-in name or a file written by 'embroact fit' "
                            "(default: design file's, else paper-2025)")
    group.add_argument("--tube-law", choices=TUBE_LAWS, help="tube law of the inflation phase (default paper)")


def add_quick_arguments(group, *, pattern: str | None, required: bool = False, tube_fields=None,
                        name_flag: bool = True) -> None:
    """Quick-parameter flags: ``--width-mm``, ``--interval-mm``, ``--angle-deg``, ``--adjust``, ``--length-mm``,
    ``--path``, ``--name`` and the tube flags.

    Parameters
    ----------
    group : argparse.ArgumentParser or argument group
        Where the flags go.
    pattern : str or None
        The pattern of the quick command (its kind's flags only); None adds the flags of every kind,
        for a pattern chosen elsewhere.
    required : bool, optional
        ``--width-mm`` is required.
    tube_fields : sequence of str, optional
        The tube fields to give flags (default: all).
    name_flag : bool, optional
        Add ``--name``.

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser()
    >>> add_quick_arguments(parser, pattern="zigzag")
    >>> add_model_arguments(parser)
    >>> args = parser.parse_args(["--width-mm", "6.5", "--g-mpa", "2.5"])
    >>> args.width_mm, args.interval_mm, args.length_mm, hasattr(args, "angle_deg")
    (6.5, None, 100.0, False)
    """
    from ...patterns.kinds import PATTERN_KINDS, pattern_kind

    kinds = list(PATTERN_KINDS) if pattern is None else [pattern_kind(pattern)]
    defaults = ", ".join(f"{k.default_interval_mm:g} {k.name}" for k in kinds)
    group.add_argument("--width-mm", type=float, required=required, help="rail spacing w [mm]")
    group.add_argument("--interval-mm", type=float,
                       help="stitch interval s: axial distance between neighbouring needle points / parallel legs [mm] "
                            f"(default: the paper's, {defaults})")
    angled = "/".join(k.name for k in kinds if k.has_angle)
    if angled:
        group.add_argument("--angle-deg", type=float, required=required and pattern is not None,
                           help=f"{angled} embroidery angle alpha0 from the perpendicular, (0, 90) [deg]")
    adjusted = [k for k in kinds if "adjust" in k.options]
    if adjusted:
        values = adjusted[0].option_values[adjusted[0].options.index("adjust")]
        group.add_argument("--adjust", choices=values, default=values[0],
                           help=f"{'/'.join(k.name for k in adjusted)}: what to change when s and alpha0 cannot "
                                f"both be met (default {values[0]})")
    group.add_argument("--length-mm", type=float, default=DEFAULT_LENGTH_MM,
                       help="straight path length l0 [mm] (default 100; ignored with --path)")
    group.add_argument("--path", metavar="SVG_D|FILE.svg#ID",
                       help='tube path: an SVG path "d" string in mm, or a path of an SVG drawing chosen by id, '
                            "label or layer (drawing.svg#tube1; real units, transforms applied)")
    if name_flag:  # embroact fit's --name names the calibration set
        group.add_argument("--name", default="A1", help="actuator name (default A1)")
    add_tube_arguments(group, fields=tube_fields or [flag[1] for flag in TUBE_FLAGS])


def add_placement_argument(group) -> None:
    """``--placement-line``: sew a running stitch along each tube axis before its cord-in stop
    (the design setting ``machine.placement_line``, turned on).

    Parameters
    ----------
    group : argparse.ArgumentParser or argument group
        Where the flag goes.

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser()
    >>> add_placement_argument(parser)
    >>> parser.parse_args(["--placement-line"]).placement_line, parser.parse_args([]).placement_line
    (True, False)
    """
    group.add_argument("--placement-line", action="store_true",
                       help="sew a placement line (running stitch along each tube axis) before its cord-in stop, "
                            "so the operator sees where to lay the tube (design: machine.placement_line)")


def add_origin_argument(group) -> None:
    """``--origin``: the machine file's start point (the design setting ``machine.origin``).

    Parameters
    ----------
    group : argparse.ArgumentParser or argument group
        Where the flag goes.

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser()
    >>> add_origin_argument(parser)
    >>> parse_origin(parser.parse_args(["--origin", "10,-5"]).origin)
    (10.0, -5.0)
    """
    group.add_argument("--origin", metavar="center|first-stitch|X,Y",
                       help="where the machine file starts: the centre of the design's extent (default), its first "
                            "needle point, or a point X,Y of the design [mm, plan frame, y up] (design: machine.origin)")


def parse_origin(text: str):
    """``--origin``'s text -> ``machine.origin`` (``"center"``, ``"first-stitch"`` or ``(x, y)``).

    Parameters
    ----------
    text : str
        The flag's value.

    Returns
    -------
    str or tuple of float

    Raises
    ------
    ParameterError
        Neither a name nor two numbers.

    Examples
    --------
    >>> parse_origin("center"), parse_origin("10,-5")
    ('center', (10.0, -5.0))
    """
    from ...patterns.base.errors import ParameterError
    from ...patterns.origin import check_origin

    parts = text.split(",")
    try:
        return check_origin([float(p) for p in parts] if len(parts) == 2 else text)
    except (ValueError, ParameterError):
        raise ParameterError(f"--origin must be center, first-stitch or X,Y in mm, got {text!r:.60}") from None


def _with_placement(design, args):
    """``design`` with ``machine.placement_line`` on when ``--placement-line`` was given, and
    ``machine.origin`` from ``--origin``."""
    import dataclasses

    machine = {}
    if getattr(args, "placement_line", False):
        machine["placement_line"] = True
    if getattr(args, "origin", None) is not None:
        machine["origin"] = parse_origin(args.origin)
    if not machine:
        return design
    return dataclasses.replace(design, machine=dataclasses.replace(design.machine, **machine))


def _quick_design(args, pattern: str):
    from ...patterns.base.errors import ParameterError, check_range
    from ...patterns.centerline import Centerline
    from ...patterns.design import ActuatorSpec, Design, MachineSettings, OperationSettings
    from ...patterns.kinds import pattern_kind
    from .args import tube_from_args

    kind = pattern_kind(pattern)
    if args.width_mm is None:
        raise ParameterError(f"--width-mm is required for a {pattern} design")
    values = {"width_mm": args.width_mm,
              "interval_mm": args.interval_mm if args.interval_mm is not None else kind.default_interval_mm}
    if kind.has_angle:
        if getattr(args, "angle_deg", None) is None:
            raise ParameterError(f"--angle-deg is required for the {pattern} pattern")
        values["angle_deg"] = args.angle_deg
    params = kind.params(**values)
    if args.path is not None:  # an empty --path is an error, not the default straight path
        from ..files.svgfile import is_svg_ref, svg_centerline

        path = svg_centerline(args.path) if is_svg_ref(args.path) else Centerline.from_svg_path(args.path)
    else:
        from ...patterns.limits import grid_origin_mm

        # moved half a grid unit across for a width of an odd number of units: both rails on the grid
        path = Centerline.straight(check_range("length_mm", args.length_mm, low=0.0, high=1e5),
                                   origin_mm=grid_origin_mm(params.width_mm))
    extra = {k: getattr(args, k) for k in kind.options if getattr(args, k, None) is not None}
    spec = ActuatorSpec(getattr(args, "name", None) or "A1", params, path, **extra)
    return Design("quick", tube_from_args(args), MachineSettings(), OperationSettings(), (spec,))


def load_target(args, *, pattern: str | None = None, design_path: str | None = None) -> Target:
    """The design a command works on, with the model flags applied.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options (the model flags, the quick-parameter flags for ``pattern``).
    pattern : str or None, optional
        Make the design from quick parameters of this kind.
    design_path : str or None, optional
        Read the design from this TOML file; neither: the built-in default design.

    Returns
    -------
    Target

    Examples
    --------
    >>> import argparse
    >>> target = load_target(argparse.Namespace())
    >>> target.source, target.design.name
    ('built-in default design', 'paper-zigzag')
    """
    from ...predict.analysis import with_model_overrides

    sets: tuple[CalibrationSet, ...]
    if pattern is not None:
        design, sets, source, quick = _quick_design(args, pattern), (), "quick parameters", True
    elif design_path is not None:
        from ..files.designfile import load_design

        design = load_design(design_path)  # what the API's load_design reads: SVG paths, calibration files
        sets, source, quick = design.calibration_sets, str(design_path), False
    else:
        from ...patterns.design import default_design

        design, sets, source, quick = default_design(), (), "built-in default design", False
    flag_sets: tuple[CalibrationSet, ...] = ()
    flag_cal = getattr(args, "calibration", None)
    if flag_cal is not None:
        from ..files.calibfile import calibration_reference

        flag_cal, flag_sets = calibration_reference(flag_cal, Path.cwd())
    overrides = {k: getattr(args, k, None) for k in ("g_mpa", "p0_kpa", "p0_source", "tube_law")}
    design = _with_placement(with_model_overrides(design, calibration=flag_cal, **overrides), args)
    merged = {s.source or s.name: s for s in sets + flag_sets}
    return Target(design, tuple(merged.values()), source, quick)


def analyse_target(target: Target):
    """The :class:`~embroact.predict.analysis.DesignAnalysis` of a target (and the demonstration note, once).

    Parameters
    ----------
    target : Target
        What :func:`load_target` gives.

    Returns
    -------
    DesignAnalysis

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser()
    >>> add_quick_arguments(parser, pattern="zigzag")
    >>> add_model_arguments(parser)
    >>> args = parser.parse_args(["--width-mm", "6.5", "--g-mpa", "2.5"])
    >>> analyse_target(load_target(args, pattern="zigzag")).actuators[0].model.g_mpa
    2.5
    """
    from ...predict.analysis import analyse

    analysis = analyse(target.design, calibration_sets=target.calibration_sets)
    note_demo_calibration(_calibrations_used(analysis))
    return analysis


#: The built-in demonstration set, and the line a command prints once when it uses it.
DEMO_CALIBRATION = "paper-2025"
DEMO_NOTE = ("note: calibration 'paper-2025' is the paper's demonstration data, not a calibration of your tube, "
             "thread and fabric; 'embroact calibrate coupon' makes one (docs/calibration.md)")
#: Whether the running command used the demonstration set, and whether the note is out.
_NOTE = {"used": False, "printed": False}


def _calibrations_used(analysis) -> set[str]:
    """Names of the calibration sets the analysis's models took G or P0 from."""
    names = set()
    for a in analysis.actuators:
        for part in a.segments:
            c = part.choice
            if c is not None and c.calibration is not None:
                names.add(c.calibration.name)
    return names


def note_demo_calibration(names, *, now: bool = False) -> None:
    """Remember that the command uses the demonstration set when ``names`` holds it.

    The note is one line on stderr, printed once per command run by :func:`print_notes` when
    the command is done (after its own output; not with ``--json``, whose stderr holds errors
    only), or at once with ``now`` (a server that runs until it is stopped).

    Parameters
    ----------
    names : collection of str
        The calibration sets the command used.
    now : bool, optional
        Print the note at once.

    Examples
    --------
    >>> reset_notes()
    >>> note_demo_calibration({"lab"})
    >>> _NOTE["used"]
    False
    """
    if DEMO_CALIBRATION in names:
        _NOTE["used"] = True
        if now:
            print_notes()


def print_notes() -> None:
    """Print the demonstration note if the command used that set and it is not printed yet.

    Examples
    --------
    >>> reset_notes()
    >>> print_notes()  # the set was not used: nothing on stderr
    >>> _NOTE["printed"]
    False
    """
    if _NOTE["used"] and not _NOTE["printed"]:
        _NOTE["printed"] = True
        print(f"embroact: {DEMO_NOTE}", file=sys.stderr)


def reset_notes() -> None:
    """Forget the note (each command run starts afresh).

    Examples
    --------
    >>> _NOTE["used"] = True
    >>> reset_notes()
    >>> _NOTE
    {'used': False, 'printed': False}
    """
    _NOTE.update(used=False, printed=False)


#: Errors the gate prints per rule code; the rest are counted on one line.
GATE_ERRORS_PER_CODE = 3


def error_lines(errors, per_code: int = GATE_ERRORS_PER_CODE) -> list[str]:
    """The gate's error lines: at most ``per_code`` of each rule code, then how many more there are.

    Parameters
    ----------
    errors : iterable of Finding
        The error findings.
    per_code : int, optional
        Lines per rule code.

    Returns
    -------
    list of str

    Examples
    --------
    >>> from embroact.patterns.base.findings import RULES
    >>> fs = [RULES.finding("EA103", f"stitch {k}", stitch_index=k) for k in range(5)]
    >>> fs.append(RULES.finding("EA103", "90 more findings of this rule", count=90))
    >>> for line in error_lines(fs, per_code=2):
    ...     print(line)
    error: EA103 stitch 0 (stitch 0)
    error: EA103 stitch 1 (stitch 1)
    error: EA103 ... and 93 more (see the worksheet / embroact check --json)
    """
    by_code: dict[str, list] = {}
    for f in errors:
        by_code.setdefault(f.code, []).append(f)
    lines: list[str] = []
    for code, fs in by_code.items():
        lines += [f"error: {code} {f.message} ({f.place()})" for f in fs[:per_code]]
        if len(fs) > per_code:
            more = sum(f.count for f in fs[per_code:])
            lines.append(f"error: {code} ... and {more} more (see the worksheet / embroact check --json)")
    return lines


def gate(findings, *, force: bool, stream=None) -> bool:
    """The rule gate of every command that writes a machine file.

    Prints the summary line (and the first :data:`GATE_ERRORS_PER_CODE` errors of each
    rule code, see :func:`error_lines`) to ``stream`` (stderr) when there are findings.

    Parameters
    ----------
    findings : iterable of Finding
        The design's findings.
    force : bool
        Write despite errors.
    stream : file, optional
        Where the lines go (default: stderr).

    Returns
    -------
    bool
        True when the command may write: no errors, or ``force``.

    Examples
    --------
    >>> import io, sys
    >>> from embroact.patterns.base.findings import RULES
    >>> import embroact.patterns.rules  # declares the rules
    >>> gate([RULES.finding("EA101", "needle in the tube", actuator="A1")], force=False, stream=sys.stdout)
    design rules: 1 error, 0 warnings, 0 info: EA101 (A1)
    error: EA101 needle in the tube (A1)
    embroact: error: design-rule errors; nothing written (use --force to write anyway)
    False
    """
    stream = sys.stderr if stream is None else stream
    findings = tuple(findings)
    if not findings:
        return True
    errors = [f for f in findings if f.is_error]
    from ...patterns.base.findings import summary_line

    print(f"design rules: {summary_line(findings)}", file=stream)
    for line in error_lines(errors):
        print(line, file=stream)
    if errors and not force:
        print("embroact: error: design-rule errors; nothing written (use --force to write anyway)", file=stream)
        return False
    return True
