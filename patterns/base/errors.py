"""One small error hierarchy for embroact.

Every error a user can cause inherits from :class:`EmbroactError` *and* from the
built-in kind it resembles, so ``except ValueError`` keeps working.  Messages are
one line and name the parameter, its value and the allowed range.

Examples
--------
>>> from embroact.patterns.base.errors import ParameterError, check_range
>>> check_range("width_mm", 7.0, low=0.0)
7.0
>>> try:
...     check_range("angle_deg", 95.0, low=0.0, high=90.0)
... except ParameterError as exc:
...     print(exc)
angle_deg must be in (0, 90), got 95
>>> try:
...     check_range("width_mm", 10**320, low=0.0, high=200.0)
... except ParameterError as exc:
...     print(exc)
width_mm must be in (0, 200), got an integer of 321 digits
>>> try:
...     check_range("width_mm", math.nextafter(200.0, math.inf), low=0.0, high=200.0)
... except ParameterError as exc:
...     print(exc)
width_mm must be in (0, 200), got 200.00000000000003
"""
from __future__ import annotations

import math
import sys

__all__ = [
    "EmbroactError",
    "ParameterError",
    "PatternError",
    "PathError",
    "DesignFileError",
    "ModelDomainError",
    "SolverError",
    "ExportError",
    "check_range",
]


class EmbroactError(Exception):
    """Base class of every error embroact raises on purpose."""


class ParameterError(EmbroactError, ValueError):
    """A public argument is out of its allowed range or of the wrong type."""


class PatternError(EmbroactError, ValueError):
    """The requested stitch pattern cannot be built (e.g. path too short)."""


class PathError(PatternError):
    """The centerline is unusable: too tight a bend, self-crossing, degenerate."""


class DesignFileError(EmbroactError, ValueError):
    """A design file is unreadable, has unknown keys or wrong types."""


class ModelDomainError(EmbroactError, ValueError):
    """The model is asked for a state outside its domain."""


class SolverError(EmbroactError, RuntimeError):
    """A numerical method did not converge; the message gives iterations and residual."""


class ExportError(EmbroactError, OSError):
    """A file could not be written (format limits, unknown suffix, I/O)."""


def _fmt(value: float) -> str:
    return f"{value:g}" if isinstance(value, (int, float)) else repr(value)


def check_range(
    name: str,
    value: object,
    *,
    low: float | None = None,
    high: float | None = None,
    low_inclusive: bool = False,
    high_inclusive: bool = False,
) -> float:
    """Return ``value`` as a finite float, or raise :class:`ParameterError`.

    Subnormal numbers (``5e-324``: below ``sys.float_info.min`` in size, not zero) are refused
    whatever the bounds: they carry a few bits of precision and their reciprocals overflow.

    Parameters
    ----------
    name : str
        Parameter name as the user wrote it (``"width_mm"``).
    value : object
        The value to check; bools and non-numbers are rejected.
    low, high : float, optional
        Bounds; open unless ``low_inclusive``/``high_inclusive``.
    low_inclusive, high_inclusive : bool, optional
        Whether ``value == low`` (``value == high``) is accepted.

    Returns
    -------
    float
        ``value`` as a float.

    Examples
    --------
    >>> check_range("width_mm", 7, low=0.0)
    7.0
    >>> try:
    ...     check_range("angle_deg", 90, low=0.0, high=90.0)
    ... except ValueError as exc:
    ...     print(exc)
    angle_deg must be in (0, 90), got 90
    """
    if type(value) is float and low is not None and high is not None and (
            low < value < high or (value == low and low_inclusive) or (value == high and high_inclusive)) and (
            value == 0.0 or abs(value) >= sys.float_info.min):
        return value  # the common case, checked before any message is formatted
    lo_b, hi_b = ("[" if low_inclusive else "("), ("]" if high_inclusive else ")")
    rng = f"{lo_b}{_fmt(low) if low is not None else '-inf'}, {_fmt(high) if high is not None else 'inf'}{hi_b}"
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        try:
            import numpy as np  # numpy scalars are fine

            if not isinstance(value, np.number) or isinstance(value, np.complexfloating):
                raise TypeError
        except (ImportError, TypeError):
            raise ParameterError(f"{name} must be a number in {rng}, got {value!r}") from None
    try:
        v = float(value)
    except OverflowError:  # an int too large for a float (10**320 in a TOML file): out of range
        raise ParameterError(f"{name} must be in {rng}, got an integer of {len(str(abs(value)))} digits") from None
    if not math.isfinite(v):
        raise ParameterError(f"{name} must be a finite number in {rng}, got {value!r}")
    bad_low = low is not None and (v < low or (v == low and not low_inclusive))
    bad_high = high is not None and (v > high or (v == high and not high_inclusive))
    if bad_low or bad_high:
        got = _fmt(v)
        if v not in (low, high) and got in (_fmt(low) if low is not None else None, _fmt(high) if high is not None else None):
            got = repr(v)  # just past a bound: 200.00000000000003, not "200"
        raise ParameterError(f"{name} must be in {rng}, got {got}")
    if v != 0.0 and abs(v) < sys.float_info.min:  # subnormal: precision lost, and 1/v overflows
        raise ParameterError(f"{name} must be in {rng} and not subnormal (0 or of size >= {sys.float_info.min:g}), "
                             f"got {v:g}")
    return v
