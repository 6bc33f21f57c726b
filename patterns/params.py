"""Frozen parameter values: the tube and the two embroidery patterns.

All lengths are millimetres, moduli MPa, angles degrees; validation happens here,
at construction, with one-line messages naming parameter, value and range.

Examples
--------
>>> from embroact.patterns.params import Tube, ZigzagParams, CrossParams
>>> Tube().outer_radius_mm
1.5
>>> ZigzagParams(width_mm=7.0, interval_mm=1.0).pattern
'zigzag'
>>> CrossParams(width_mm=7.0, interval_mm=1.4, angle_deg=45.0).angle_deg
45.0
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, Protocol

from .base.errors import ParameterError, check_range
from .base.records import quick_init
from .base.tolerances import DEFAULT_TOLERANCES

__all__ = ["Tube", "StitchOptions", "ZigzagParams", "CrossParams", "PatternParams", "ADJUST_METHODS", "FABRIC_THICKNESS_MM", "whole_intervals"]


def whole_intervals(length_mm: float, interval_mm: float) -> int:
    """Whole intervals along ``length_mm`` (within the length tolerance): the generators fill that
    many times ``interval_mm`` of a path, centred on it.

    Parameters
    ----------
    length_mm : float
        Path length [mm].
    interval_mm : float
        Stitch interval [mm], > 0.

    Returns
    -------
    int

    Examples
    --------
    >>> whole_intervals(100.0, 1.4), whole_intervals(2.8 - 1e-12, 1.4)
    (71, 2)
    """
    return math.floor((length_mm + DEFAULT_TOLERANCES.length_mm) / interval_mm)


@dataclass(frozen=True, slots=True)
class Tube:
    """The inflatable rubber tube (the cord) and how close needles may come to it.

    Parameters
    ----------
    outer_radius_mm : float
        Unpressurised outer radius r_f [mm], > 0.
    inner_radius_mm : float
        Unpressurised inner radius d_f [mm], in [0, r_f).
    g_e_mpa : float
        Fitted shear modulus of the tube alone, inflation phase G_e [MPa], > 0.
    clearance_mm : float
        Extra distance kept between any needle point and the tube surface [mm], >= 0.
        The tube corridor is ``|distance to centerline| < r_f + clearance``.
    end_margin_mm : float
        Free tube length left at each end for connectors [mm], >= 0 (paper: 30 mm).

    Examples
    --------
    >>> t = Tube()                      # the paper's tube: r_f 1.5 mm, d_f 1.0 mm
    >>> t.corridor_radius_mm
    1.8
    >>> Tube(inner_radius_mm=2.0)
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.ParameterError: inner_radius_mm must be in [0, outer_radius_mm=1.5), got 2
    """

    outer_radius_mm: float = 1.5
    inner_radius_mm: float = 1.0
    g_e_mpa: float = 0.13
    clearance_mm: float = 0.3
    end_margin_mm: float = 30.0

    def __post_init__(self) -> None:
        r_f = check_range("outer_radius_mm", self.outer_radius_mm, low=0.0, high=50.0)
        d_f = check_range("inner_radius_mm", self.inner_radius_mm, low=0.0, low_inclusive=True, high=50.0)
        if d_f >= r_f:
            raise ParameterError(
                f"inner_radius_mm must be in [0, outer_radius_mm={r_f:g}), got {d_f:g}"
            )
        check_range("g_e_mpa", self.g_e_mpa, low=0.0, high=1e4)
        check_range("clearance_mm", self.clearance_mm, low=0.0, low_inclusive=True, high=50.0)
        check_range("end_margin_mm", self.end_margin_mm, low=0.0, low_inclusive=True, high=1e4)

    @property
    def corridor_radius_mm(self) -> float:
        """Half width of the forbidden corridor around the centerline [mm]."""
        return self.outer_radius_mm + self.clearance_mm


@dataclass(frozen=True, slots=True)
class StitchOptions:
    """How an actuator is started and ended on the machine.

    Parameters
    ----------
    tie_stitch_mm : float
        Length of each lock (tie-in / tie-off) stitch, laid along a rail [mm], in (0, 5]: the
        straight distance between its two needle points on that rail (on a bend the inner rail
        needs more centerline for it, the outer less); a rail shorter than that near the end
        of a short path gets the longest stitch it holds.
    tie_count : int
        Number of lock stitches at each end, in [2, 10].

    Examples
    --------
    >>> StitchOptions()
    StitchOptions(tie_stitch_mm=0.7, tie_count=3)
    >>> StitchOptions(tie_count=1)
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.ParameterError: tie_count must be an integer in [2, 10], got 1
    """

    tie_stitch_mm: float = 0.7
    tie_count: int = 3

    def __post_init__(self) -> None:
        check_range("tie_stitch_mm", self.tie_stitch_mm, low=0.0, high=5.0, high_inclusive=True)
        if isinstance(self.tie_count, bool) or not isinstance(self.tie_count, int) or not 2 <= self.tie_count <= 10:
            raise ParameterError(f"tie_count must be an integer in [2, 10], got {self.tie_count!r}")


@quick_init
@dataclass(frozen=True, slots=True)
class ZigzagParams:
    """Zigzag pattern: legs cross the tube alternately from rail to rail.

    Parameters
    ----------
    width_mm : float
        Rail spacing w [mm], > 0 (the generator also requires w/2 > corridor radius).
    interval_mm : float
        Stitch interval s: axial advance between neighbouring needle points [mm], > 0.

    Examples
    --------
    >>> ZigzagParams(width_mm=7.0, interval_mm=1.0).pattern
    'zigzag'
    """

    pattern: ClassVar[str] = "zigzag"
    width_mm: float
    interval_mm: float

    def __post_init__(self) -> None:
        check_range("width_mm", self.width_mm, low=0.0, high=200.0)
        check_range("interval_mm", self.interval_mm, low=0.0, high=100.0)


#: Thickness of the fabric the tube lies on [mm]: the thread each needle penetration takes through it
#: (the worksheet's thread lengths) and the fabric strip the side view and the 3D shape draw.
FABRIC_THICKNESS_MM = 0.5

#: Values of the cross pattern's generator option ``adjust`` (:func:`embroact.patterns.cross.closing`).
ADJUST_METHODS = ("auto", "interval", "angle")


@quick_init
@dataclass(frozen=True, slots=True)
class CrossParams:
    """Cross pattern: two families of legs at +-alpha0 from the perpendicular.

    Parameters
    ----------
    width_mm : float
        Rail spacing w [mm], > 0.
    interval_mm : float
        Spacing s between neighbouring parallel legs, measured along the path [mm], > 0.
    angle_deg : float
        Embroidery angle alpha0 from the line perpendicular to the tube [deg], in (0, 90).

    Examples
    --------
    >>> CrossParams(width_mm=7.0, interval_mm=1.4, angle_deg=45.0).pattern
    'cross'
    >>> CrossParams(width_mm=7.0, interval_mm=1.4, angle_deg=90.0)
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.ParameterError: angle_deg must be in (0, 90), got 90
    """

    pattern: ClassVar[str] = "cross"
    width_mm: float
    interval_mm: float
    angle_deg: float

    def __post_init__(self) -> None:
        check_range("width_mm", self.width_mm, low=0.0, high=200.0)
        check_range("interval_mm", self.interval_mm, low=0.0, high=100.0)
        check_range("angle_deg", self.angle_deg, low=0.0, high=90.0)


class PatternParams(Protocol):
    """What every pattern kind's parameter class has (:attr:`embroact.patterns.kinds.PatternKind.params`).

    A frozen dataclass with the class attribute ``pattern`` (the kind's name) and the fields
    ``width_mm`` and ``interval_mm``, checking its own ranges; a kind may add fields
    (``angle_deg``).

    Attributes
    ----------
    pattern : str
        The kind's name (a class attribute).
    width_mm : float
        Rail spacing [mm].
    interval_mm : float
        Stitch interval along the path [mm].

    Examples
    --------
    >>> p: PatternParams = ZigzagParams(7.0, 1.0)
    >>> p.pattern, p.width_mm, p.interval_mm
    ('zigzag', 7.0, 1.0)
    """

    @property
    def pattern(self) -> str:
        """The kind's name, ``"zigzag"``."""
        ...

    @property
    def width_mm(self) -> float:
        """Rail spacing [mm]."""
        ...

    @property
    def interval_mm(self) -> float:
        """Stitch interval along the path [mm]."""
        ...
