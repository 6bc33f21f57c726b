"""Command-line pieces shared by several commands: tube flags and pressure lists.

Examples
--------
>>> import argparse
>>> from embroact.export.cli.args import add_tube_arguments, tube_from_args, parse_pressures
>>> p = argparse.ArgumentParser()
>>> add_tube_arguments(p)
>>> tube_from_args(p.parse_args(["--tube-radius-mm", "2"])).outer_radius_mm
2.0
>>> parse_pressures("0:30:10").tolist()
[0.0, 10.0, 20.0, 30.0]
"""
from __future__ import annotations

import math

#: Time limit of every command [s] unless ``--time-limit-s`` says otherwise (0: none). An hour: far
#: beyond any command on the documented input limits (the longest, a 5,000-segment path, takes ~30 s).
#: Here (no numpy, no threads) so that ``embroact --help`` and the watchdog read one value.
DEFAULT_TIME_LIMIT_S = 3600.0

__all__ = ["TUBE_FLAGS", "MAX_PRESSURES", "MAX_PRESSURE_KPA", "add_tube_arguments", "tube_from_args", "parse_pressures",
           "check_shape_flags", "input_files", "materials_of", "plus_minus"]

#: Most pressures one command evaluates (a range string with a tiny step is a typo).
MAX_PRESSURES = 100_000
#: Highest pressure a command accepts [kPa] (100 MPa: far beyond any tube; larger is a typo).
MAX_PRESSURE_KPA = 100_000.0

#: Tube options: flag, :class:`~embroact.patterns.params.Tube` field (also the argparse dest),
#: help, default. The defaults repeat Tube's (a test holds them equal) so that a command's
#: ``--help`` needs no numpy.
TUBE_FLAGS = (
    ("--tube-radius-mm", "outer_radius_mm", "tube outer radius r_f [mm]", 1.5),
    ("--tube-inner-radius-mm", "inner_radius_mm", "tube inner radius d_f [mm]", 1.0),
    ("--tube-g-mpa", "g_e_mpa", "tube shear modulus G_e, inflation phase [MPa]", 0.13),
    ("--clearance-mm", "clearance_mm", "needle clearance from the tube [mm]", 0.3),
    ("--end-margin-mm", "end_margin_mm", "free tube at each end for connectors [mm]", 30.0),
)
_MATERIAL_FIELDS = ("outer_radius_mm", "inner_radius_mm", "g_e_mpa")


def add_tube_arguments(group, *, fields=_MATERIAL_FIELDS) -> None:
    """Add the tube flags for ``fields`` (Tube field names) with the Tube defaults.

    Parameters
    ----------
    group : argparse.ArgumentParser or argument group
        Where the flags go.
    fields : tuple of str, optional
        The :class:`~embroact.patterns.params.Tube` fields to give flags (the materials by default).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser()
    >>> add_tube_arguments(parser, fields=("outer_radius_mm",))
    >>> vars(parser.parse_args(["--tube-radius-mm", "2"]))
    {'outer_radius_mm': 2.0}
    """
    for flag, field, text, default in TUBE_FLAGS:
        if field in fields:
            group.add_argument(flag, type=float, default=default, dest=field,
                               metavar=flag[2:].replace("-", "_").upper(), help=f"{text} (default {default:g})")


def tube_from_args(args):
    """The :class:`~embroact.patterns.params.Tube` the parsed tube flags describe (validated there).

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options; the tube fields it lacks keep the Tube defaults.

    Returns
    -------
    Tube

    Examples
    --------
    >>> import argparse
    >>> tube_from_args(argparse.Namespace(outer_radius_mm=2.0)).outer_radius_mm
    2.0
    """
    from ...patterns.base.errors import ParameterError
    from ...patterns.params import Tube

    try:
        return Tube(**{field: getattr(args, field) for _, field, _, _ in TUBE_FLAGS if hasattr(args, field)})
    except ParameterError as exc:  # the field the error names may be one the user never set: say so
        text = str(exc)
        left = [f"{flag} {default:g}" for flag, field, _, default in TUBE_FLAGS
                if text.startswith(field) and getattr(args, field, default) == default]
        raise ParameterError(text + (f" ({left[0]}: its default)" if left else "")) from None


def parse_pressures(text: str, flag: str = "--pressure-kpa"):
    """Pressures [kPa] from ``start:stop:step`` or ``p1,p2,...``; one-line errors name ``flag``.

    Parameters
    ----------
    text : str
        The flag's value.
    flag : str, optional
        The flag, for the messages.

    Returns
    -------
    numpy.ndarray
        [kPa], each in [0, MAX_PRESSURE_KPA].

    Examples
    --------
    >>> parse_pressures("0:30:10").tolist(), parse_pressures("0:25:10").tolist(), parse_pressures("5, 7.5").tolist()
    ([0.0, 10.0, 20.0, 30.0], [0.0, 10.0, 20.0], [5.0, 7.5])
    """
    import numpy as np

    from ...patterns.base.errors import ParameterError

    def number(s: str) -> float:
        try:
            v = float(s)
        except ValueError:
            raise ParameterError(f"{flag}: {s.strip()!r} is not a number in {text!r}") from None
        if not math.isfinite(v) or v < 0:
            raise ParameterError(f"{flag}: pressures must be finite and >= 0 kPa, got {s.strip()!r} in {text!r}")
        if v > MAX_PRESSURE_KPA:
            raise ParameterError(f"{flag}: pressures must be <= {MAX_PRESSURE_KPA:g} kPa, got {s.strip()!r} in {text!r}")
        return v

    if ":" in text:
        parts = text.split(":")
        if len(parts) != 3:
            raise ParameterError(f"{flag} must be 'start:stop:step' or a comma-separated list, got {text!r}")
        start, stop = number(parts[0]), number(parts[1])
        try:
            step = float(parts[2])
        except ValueError:
            raise ParameterError(f"{flag}: {parts[2].strip()!r} is not a number in {text!r}") from None
        if not (math.isfinite(step) and step > 0):
            raise ParameterError(f"{flag}: step must be > 0 in 'start:stop:step', got {text!r}")
        if stop < start:
            raise ParameterError(f"{flag}: stop must be >= start in 'start:stop:step', got {text!r}")
        n = math.floor((stop - start) / step * (1 + 1e-12) + 1e-9) + 1
        if n > MAX_PRESSURES:
            raise ParameterError(f"{flag}: at most {MAX_PRESSURES} pressures, {text!r} gives {n}")
        return start + step * np.arange(n)
    values = [number(s) for s in text.split(",") if s.strip()]
    if not values or len(values) > MAX_PRESSURES:
        raise ParameterError(f"{flag} must list 1 to {MAX_PRESSURES} pressures, got {text!r}")
    return np.array(values)


def check_shape_flags(args) -> None:
    """``--shape-pressure-kpa`` and ``--tolerance-mm``, where a command has them, checked before any work.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options.

    Raises
    ------
    ParameterError
        A value out of range.

    Examples
    --------
    >>> import argparse
    >>> check_shape_flags(argparse.Namespace(shape_pressure_kpa=1e308))
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.ParameterError: shape_pressure_kpa must be in [0, 100000], got 1e+308
    """
    from ...patterns.base.errors import check_range

    if getattr(args, "shape_pressure_kpa", None) is not None:
        check_range("shape_pressure_kpa", args.shape_pressure_kpa, low=0.0, low_inclusive=True,
                    high=MAX_PRESSURE_KPA, high_inclusive=True)
    if getattr(args, "tolerance_mm", None) is not None:
        check_range("tolerance_mm", args.tolerance_mm, low=0.0, high=10.0, high_inclusive=True)


#: Options (argparse dest -> what the file is) whose value may name a file a command reads.
_INPUT_FLAGS = (("design", "design file"), ("data", "data file"), ("target_shape", "target shape"),
                ("calibration", "calibration file"), ("path", "path drawing"), ("tube", "tube file"))


def input_files(args, design=None) -> list[tuple[str, str]]:
    """(what, file) of every input file the parsed ``args`` name: what no output may replace.

    A value counts when it names a file (``--calibration lab.toml``, not a set name;
    ``--path drawing.svg#t1`` without the ``#t1``, not path data); with ``design``, the
    files it was read from follow (:attr:`~embroact.patterns.design.Design.source_files`:
    its drawings and calibration files).

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options.
    design : Design, optional
        The design the run loaded.

    Returns
    -------
    list of tuple of str

    Examples
    --------
    >>> import argparse
    >>> input_files(argparse.Namespace(data="d.csv", calibration="paper-2025", path="a.svg#t", output="o"))
    [('data file', 'd.csv'), ('path drawing', 'a.svg')]
    """
    from ...patterns.design import names_calibration_file

    out = []
    for dest, what in _INPUT_FLAGS:
        value = getattr(args, dest, None)
        if not isinstance(value, str) or not value:
            continue
        if dest == "calibration" and not names_calibration_file(value):
            continue  # a set name
        if dest in ("path", "target_shape"):  # these may name a drawing (only they need its reader)
            from ..files.svgfile import is_svg_ref, split_ref

            if dest == "path" and not is_svg_ref(value):
                continue  # path data
            value = split_ref(value)[0]
        out.append((what, value))
    return out + list(getattr(design, "source_files", ()))


def materials_of(items):
    """``--material KEY=VALUE`` items as a dict (what a calibration set records of its materials).

    Parameters
    ----------
    items : iterable of str
        ``KEY=VALUE`` each.

    Returns
    -------
    dict of str to str

    Examples
    --------
    >>> materials_of(["tube=silicone 3 mm", "thread=polyester"])
    {'tube': 'silicone 3 mm', 'thread': 'polyester'}
    """
    from ...patterns.base.errors import ParameterError

    out = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key.strip():
            raise ParameterError(f"--material must be KEY=VALUE, got {item!r}")
        out[key.strip()] = value.strip()
    return out


def plus_minus(value, se, digits=4) -> str:
    """``value`` to ``digits`` significant digits, with `` +- se`` when the standard error is known.

    Parameters
    ----------
    value : float
        The value.
    se : float or None
        Its standard error.
    digits : int, optional
        Significant digits of ``value``.

    Returns
    -------
    str

    Examples
    --------
    >>> plus_minus(2.68312, 0.0213), plus_minus(85.0, None)
    ('2.683 +- 0.021', '85')
    """
    return f"{value:.{digits}g}" + ("" if se is None else f" +- {se:.2g}")
