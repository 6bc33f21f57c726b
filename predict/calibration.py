"""Calibration sets: fitted (G, P0) per design, and their lookup for a new design.

The deformation model has one free modulus, the effective shear modulus ``G`` of
tube + sleeve, and usually a fitted transition pressure ``P0``; both depend on the
materials (tube, thread, fabric) and on the design.  A :class:`CalibrationSet`
stores fitted points for one combination of materials; :func:`lookup` turns it into
the parameters for any zigzag width or cross angle.

The built-in set ``"paper-2025"`` holds the paper's fitted parameters (natural rubber
tube, polyester thread, cotton fabric; docs/model.md, calibration policy). The paper does
not give its tube's size, so that set records no tube: with the default tube its G values
over-predict the bends the paper measured.

Provenance
----------
``G`` and the tube's wall constant ``r_f^2 - d_f^2`` enter the energy together, and a
measured angle depends on how it was measured, so a set records what it was fitted with:
the tube (:class:`CalibrationTube`, ``None`` when unknown), the tube law, the angle
measurement (``"whole-strip"`` or a marker layout) and, per point, its pattern coordinate.
:func:`model_for` is the one place that turns a design's settings into a model; it
reports where G and P0 came from and notes a tube that differs from the calibrated one.  Users add their
own sets from :func:`embroact.predict.fit.fit_design` results, either globally with
:func:`register` or per call with ``lookup(..., sets=[...])``; TOML files are read and
written by :mod:`embroact.export.files.calibfile`.

Lookup scheme
-------------
* Points are keyed by the geometry their sample was sewn with: a point fitted from a
  coupon (:func:`embroact.predict.fit.fit_design`) by the width and angle measured on the
  coupon's needle points; the paper's set by the values of the paper's table (all it gives).
  A design is looked up at the coordinate its own needle points realise
  (:func:`lookup_design`), so the set is read where the machine sews, not where the design
  file asked; the requested coordinate is reported beside it where the two differ.
* Zigzag points are interpolated over ``width_mm``; cross points over ``angle_deg``
  (among the cross points of the width closest to the design's; a different
  width is reported in ``notes``).
* Interpolation is monotone piecewise cubic (PCHIP, :mod:`embroact.predict.pchip`) in the
  parameter, separately for ``G`` and ``P0`` (and ``G_e`` when every point has one): exact at
  a calibrated point, continuous with a continuous slope between them, monotone between
  two points, no snapping to a nearby point.  Two points of one design (pattern, width,
  angle, branch) must be identical: a set that holds two different fits of one design
  is refused, naming both points, rather than averaged.
* Outside the calibrated range, ``extrapolation="clamp"`` (default) holds the end
  value, ``extrapolation="linear"`` extends the end segment; either way the result
  says ``extrapolated=True`` so that a design rule can warn.  A linear extrapolation
  that drives ``G`` or ``P0`` out of range is refused (:class:`ModelDomainError`).
* Branches: ``branch="loading"`` uses points fitted to the loading branch or to both
  branches (``"both"``); an exact branch match wins over ``"both"`` at one coordinate.

Examples
--------
>>> from embroact.predict.calibration import lookup
>>> c = lookup("zigzag", width_mm=7.0)
>>> c.g_mpa, c.p0_kpa, c.interpolated, c.extrapolated
(2.7, 85.0, False, False)
>>> c = lookup("zigzag", width_mm=8.0)
>>> round(c.g_mpa, 3), round(c.p0_kpa, 1), c.interpolated
(3.165, 123.3, True)
>>> c = lookup("cross", width_mm=7.0, angle_deg=70.0)
>>> c.g_mpa, c.p0_kpa, c.extrapolated, (c.range_low, c.range_high)
(2.9, 200.0, True, (15.0, 60.0))
>>> c.label
'paper-2025 (cross, angle_deg=70, clamped to [15, 60])'
"""
from __future__ import annotations

import dataclasses
import functools
import math
from bisect import bisect_right
from dataclasses import dataclass, field
from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING

from ..patterns.base.choices import check_choice
from ..patterns.base.errors import ModelDomainError, ParameterError, check_range
from ..patterns.base.records import quick_init
from ..patterns.base.tolerances import DEFAULT_TOLERANCES
from ..patterns.design import ModelSettings, P0Source, TubeLaw
from ..patterns.kinds import PATTERN_KINDS, pattern_kind
from .markers import MarkerLayout
from .pchip import pchip, pchip_slopes

if TYPE_CHECKING:  # pragma: no cover
    from .curve import ActuatorModel

__all__ = [
    "BRANCHES",
    "EXTRAPOLATIONS",
    "CalibrationPoint",
    "CalibrationSet",
    "model_dict",
    "Calibration",
    "PAPER_2025",
    "lookup",
    "register",
    "unregister",
    "get_set",
    "set_names",
    "CalibrationTube",
    "ModelChoice",
    "model_for",
    "lookup_design",
    "as_calibration_sets",
]

BRANCHES = ("loading", "unloading", "both")
EXTRAPOLATIONS = ("clamp", "linear")

_FITTABLE = ("g_mpa", "p0_kpa", "g_e_mpa")
#: Keys of a point's ``tube_law_parameters``: the paper's law (r_f, G_e), the thick wall (r_f, d_f, mu).
_TUBE_LAW_KEYS = ("outer_radius_mm", "inner_radius_mm", "g_e_mpa", "mu_mpa")
_G_MAX_MPA = 1e5
_P_MAX_KPA = 1e5
#: Largest |covariance entry| [MPa^2, kPa^2, MPa kPa]: the square of the largest G or P0, so a band
#: computed from it stays finite (1e308 gave "+-inf deg").
_COV_MAX = _G_MAX_MPA * _P_MAX_KPA
_NAME_CHARS = frozenset("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.")


def _choice(name: str, value: object, valid: tuple[str, ...]) -> str:
    if value not in valid:
        raise ParameterError(f"{name} must be one of {', '.join(map(repr, valid))}, got {value!r}")
    return str(value)


def _optional(name: str, value: float | None, **bounds) -> float | None:
    return None if value is None else check_range(name, value, **bounds)


@dataclass(frozen=True, slots=True)
class CalibrationPoint:
    """Fitted parameters of one design (one branch of its pressure loop).

    Parameters
    ----------
    pattern : str
        A registered pattern kind.
    width_mm : float
        Embroidery width w [mm], > 0.
    g_mpa : float
        Effective shear modulus G of tube + sleeve [MPa], > 0.
    p0_kpa : float
        Transition pressure P0 [kPa], >= 0.
    angle_deg : float
        Cross embroidery angle alpha0 [deg] in (0, 90); 0 for zigzag.
    interval_mm : float, optional
        Stitch interval s [mm] of the fitted sample (documentation only).
    branch : str
        ``"loading"``, ``"unloading"`` or ``"both"`` (fitted to the whole loop).
    g_e_mpa : float, optional
        Fitted tube modulus G_e [MPa], when it was fitted.
    g_mpa_se, p0_kpa_se, g_e_mpa_se : float, optional
        Standard errors of the fit [MPa, kPa, MPa].
    rmse_deg : float, optional
        Root-mean-square residual of the fit [deg].
    n_points : int, optional
        Number of measured points the fit used.
    fitted : tuple of str
        Names of the fitted parameters (``g_mpa``, ``p0_kpa``, ``g_e_mpa``), the order of ``covariance``.
    covariance : tuple of tuples
        Covariance of the fitted parameters [MPa, kPa units]; empty when unknown. G and P0 are
        strongly correlated, so a band from standard errors alone would be wrong.
    tube_law_parameters : tuple of (str, float) pairs
        The parameters of the set's tube law the fit used (``outer_radius_mm`` and ``g_e_mpa``
        for the paper's law; ``outer_radius_mm``, ``inner_radius_mm`` and ``mu_mpa`` for the
        thick wall; [mm, MPa]); empty when unknown. A mapping is accepted.

    Examples
    --------
    >>> pt = CalibrationPoint("zigzag", 7.0, 2.7, 85.0, branch="loading")
    >>> pt.coordinate, pt.as_dict()
    (7.0, {'pattern': 'zigzag', 'width_mm': 7.0, 'g_mpa': 2.7, 'p0_kpa': 85.0, 'angle_deg': 0.0, 'branch': 'loading'})
    """

    pattern: str
    width_mm: float
    g_mpa: float
    p0_kpa: float
    angle_deg: float = 0.0
    interval_mm: float | None = None
    branch: str = "both"
    g_e_mpa: float | None = None
    g_mpa_se: float | None = None
    p0_kpa_se: float | None = None
    g_e_mpa_se: float | None = None
    rmse_deg: float | None = None
    n_points: int | None = None
    fitted: tuple[str, ...] = ()
    covariance: tuple[tuple[float, ...], ...] = ()
    tube_law_parameters: tuple[tuple[str, float], ...] = ()

    def __post_init__(self) -> None:
        _choice("pattern", self.pattern, PATTERN_KINDS.names())
        _choice("branch", self.branch, BRANCHES)
        check_range("width_mm", self.width_mm, low=0.0, high=200.0)
        check_range("g_mpa", self.g_mpa, low=0.0, high=_G_MAX_MPA)
        check_range("p0_kpa", self.p0_kpa, low=0.0, low_inclusive=True, high=_P_MAX_KPA)
        if pattern_kind(self.pattern).has_angle:
            check_range("angle_deg", self.angle_deg, low=0.0, high=90.0)
        else:
            check_range("angle_deg", self.angle_deg, low=-90.0, high=90.0)
        _optional("interval_mm", self.interval_mm, low=0.0, high=100.0)
        _optional("g_e_mpa", self.g_e_mpa, low=0.0, high=_G_MAX_MPA)
        for name in ("g_mpa_se", "p0_kpa_se", "g_e_mpa_se", "rmse_deg"):
            _optional(name, getattr(self, name), low=0.0, low_inclusive=True)
        n = self.n_points
        if n is not None and (isinstance(n, bool) or not isinstance(n, int) or n < 1):
            raise ParameterError(f"n_points must be a positive integer, got {n!r}")
        fitted = tuple(str(f) for f in self.fitted)
        bad = [f for f in fitted if f not in _FITTABLE]
        if bad or len(set(fitted)) != len(fitted):
            raise ParameterError(f"fitted must name distinct parameters of {', '.join(_FITTABLE)}, got {self.fitted!r}")
        cov = tuple(tuple(check_range("covariance entries", v, low=-_COV_MAX, high=_COV_MAX, low_inclusive=True,
                                      high_inclusive=True) for v in row) for row in self.covariance)
        k = len(fitted)
        if cov and (len(cov) != k or any(len(row) != k for row in cov)):
            raise ParameterError(f"covariance must be {k} x {k} (one row per fitted parameter), got {len(cov)} rows")
        if cov and (any(cov[i][i] < 0.0 for i in range(k))
                    or any(abs(cov[i][j] - cov[j][i]) > 1e-9 * (abs(cov[i][j]) + abs(cov[j][i]) + 1e-300)
                           for i in range(k) for j in range(i))):
            raise ParameterError("covariance must be finite and symmetric with a non-negative diagonal")
        if cov:
            from .uncertainty import is_positive_semidefinite

            if not is_positive_semidefinite(cov):
                raise ParameterError(f"covariance must be positive semi-definite (no negative variance along any "
                                     f"combination of {', '.join(fitted)}), got {[list(r) for r in cov]}")
        object.__setattr__(self, "fitted", fitted)
        object.__setattr__(self, "covariance", cov)
        object.__setattr__(self, "tube_law_parameters", _law_parameters(self.tube_law_parameters))

    @property
    def coordinate(self) -> float:
        """The interpolation coordinate, the pattern's calibration axis: width for zigzag, angle for cross."""
        return getattr(self, pattern_kind(self.pattern).calibration_axis)

    def same_design(self, other: "CalibrationPoint") -> bool:
        """True when ``other`` is for the same pattern, width, angle and branch.

        Parameters
        ----------
        other : CalibrationPoint
            Another point.

        Returns
        -------
        bool
            Whatever their fitted values.

        Examples
        --------
        >>> a = CalibrationPoint("zigzag", 7.0, 2.7, 85.0, branch="loading")
        >>> b = CalibrationPoint("zigzag", 7.0, 2.5, 80.0, branch="loading")
        >>> a.same_design(b), a.same_design(CalibrationPoint("zigzag", 7.0, 2.7, 85.0, branch="unloading"))
        (True, False)
        """
        return (self.pattern, self.width_mm, self.angle_deg, self.branch) == (
            other.pattern,
            other.width_mm,
            other.angle_deg,
            other.branch,
        )

    def as_dict(self) -> dict:
        """Plain dict of the set fields (``None`` and empty fields left out).

        Returns
        -------
        dict

        Examples
        --------
        >>> sorted(PAPER_2025.points[0].as_dict())
        ['angle_deg', 'branch', 'g_mpa', 'interval_mm', 'p0_kpa', 'pattern', 'width_mm']
        """
        out = {k: getattr(self, k) for k in self.__slots__ if getattr(self, k) not in (None, ())}
        if "fitted" in out:
            out["fitted"] = list(out["fitted"])
        if "covariance" in out:
            out["covariance"] = [list(row) for row in out["covariance"]]
        if "tube_law_parameters" in out:
            out["tube_law_parameters"] = dict(out["tube_law_parameters"])
        return out


def _law_parameters(value) -> tuple[tuple[str, float], ...]:
    """Validated ``(key, value)`` pairs of a tube law's parameters (keys of ``_TUBE_LAW_KEYS``)."""
    try:
        pairs = tuple((value.items() if isinstance(value, Mapping) else value))
        keys = [str(k) for k, _ in pairs]
    except (TypeError, ValueError):
        raise ParameterError(f"tube_law_parameters must map names to numbers, got {value!r}") from None
    bad = [k for k in keys if k not in _TUBE_LAW_KEYS]
    if bad or len(set(keys)) != len(keys):
        raise ParameterError(f"tube_law_parameters must name distinct keys of {', '.join(_TUBE_LAW_KEYS)}, "
                             f"got {keys!r}")
    return tuple((k, check_range(f"tube_law_parameters.{k}", v, low=0.0, low_inclusive=k == "inner_radius_mm",
                                 high=_G_MAX_MPA)) for k, (_, v) in zip(keys, pairs))


@dataclass(frozen=True, slots=True)
class CalibrationTube:
    """The tube a calibration set was fitted with.

    Parameters
    ----------
    outer_radius_mm, inner_radius_mm : float
        Unpressurised outer and inner radius r_f, d_f [mm].
    g_e_mpa : float
        Its inflation-phase modulus G_e [MPa].

    Examples
    --------
    >>> CalibrationTube(1.5, 1.0, 0.13).g_e_mpa
    0.13
    """

    outer_radius_mm: float
    inner_radius_mm: float
    g_e_mpa: float

    def __post_init__(self) -> None:
        r_f = check_range("outer_radius_mm", self.outer_radius_mm, low=0.0, high=50.0)
        check_range("inner_radius_mm", self.inner_radius_mm, low=0.0, low_inclusive=True, high=r_f)
        check_range("g_e_mpa", self.g_e_mpa, low=0.0, high=1e4)

    @classmethod
    def of(cls, tube) -> "CalibrationTube":
        """The calibration record of a :class:`~embroact.patterns.params.Tube`.

        Parameters
        ----------
        tube : Tube
            A design's tube.

        Returns
        -------
        CalibrationTube

        Examples
        --------
        >>> from embroact.patterns.params import Tube
        >>> CalibrationTube.of(Tube())
        CalibrationTube(outer_radius_mm=1.5, inner_radius_mm=1.0, g_e_mpa=0.13)
        """
        return cls(tube.outer_radius_mm, tube.inner_radius_mm, tube.g_e_mpa)

    def differences(self, tube) -> tuple[str, ...]:
        """``key a != b`` for each of r_f, d_f, G_e where ``tube`` differs (relative 1e-9).

        Parameters
        ----------
        tube : Tube or CalibrationTube
            The tube a design uses.

        Returns
        -------
        tuple of str
            Empty when they agree.

        Examples
        --------
        >>> from embroact.patterns.params import Tube
        >>> CalibrationTube(1.5, 1.0, 0.13).differences(Tube(outer_radius_mm=1.6))
        ('outer_radius_mm 1.6 (calibrated with 1.5)',)
        """
        out = []
        for key in ("outer_radius_mm", "inner_radius_mm", "g_e_mpa"):
            a, b = getattr(self, key), getattr(tube, key)
            if abs(a - b) > 1e-9 * max(abs(a), abs(b)):
                out.append(f"{key} {b:g} (calibrated with {a:g})")
        return tuple(out)


def _check_duplicates(points: tuple[CalibrationPoint, ...]) -> None:
    """Refuse two points of one design (pattern, width, angle, branch) with different values.

    The lookup averages points at one coordinate; two fits of one design that disagree (G 2.7
    and 9.0 MPa) are a mistake in the set, not a measurement to split the difference of.
    Identical copies are harmless and kept.
    """
    seen: dict[tuple, int] = {}
    for i, p in enumerate(points):
        key = (p.pattern, p.width_mm, p.angle_deg, p.branch)
        j = seen.setdefault(key, i)
        if j != i and points[j] != p:
            q = points[j]
            diff = next((f"{k} {getattr(q, k)!r} and {getattr(p, k)!r}" for k in p.__slots__
                         if getattr(q, k) != getattr(p, k)), "")
            raise ParameterError(f"points[{j}] and points[{i}] are one design ({p.pattern} width_mm {p.width_mm:g}"
                                 f"{f' angle_deg {p.angle_deg:g}' if pattern_kind(p.pattern).has_angle else ''}, "
                                 f"{p.branch}) with different values ({diff}): keep one")


@dataclass(frozen=True, slots=True)
class CalibrationSet:
    """A named collection of calibration points for one combination of materials.

    Parameters
    ----------
    name : str
        Identifier: letters, digits, ``-``, ``_``, ``.``.
    points : tuple of CalibrationPoint
        At least one point.
    description : str
        Free text (where the data came from).
    materials : mapping or tuple of (key, value) pairs
        e.g. ``{"tube": "natural rubber", "thread": "polyester", "fabric": "cotton"}``;
        stored as a tuple of string pairs.
    tube : CalibrationTube or None
        The tube the points were fitted with; ``None``: unknown (the paper's set).
    tube_law : str
        Inflation-phase tube law used in the fit (``"paper"`` or ``"thick-wall"``).
    measurement : str
        How the fitted angles were measured: ``"whole-strip"`` (the angle between the two
        ends of the strip) or a marker layout, e.g. ``"markers: 7 per side, 10 mm apart"``.
    marker_layout : MarkerLayout or None
        The layout the fit compared the data through (its reading of the model's bend), and
        so the default layout of marker readings predicted with the set
        (:func:`embroact.predict.layoutchoice.layout_for`); ``None``: whole-strip angles, or a
        layout not known in numbers (the paper's set). With a layout, ``measurement``
        defaults to its label.
    source : str
        The file the set was read from (absolute path), empty for a set made in memory; a
        design's ``calibration`` setting may name the set by it (not part of equality).

    Examples
    --------
    >>> s = CalibrationSet("lab", (CalibrationPoint("zigzag", 7.0, 2.5, 80.0, branch="loading"),))
    >>> s.name, s.coverage(), s.measurement
    ('lab', {'zigzag': (7.0, 7.0)}, 'whole-strip')
    """

    name: str
    points: tuple[CalibrationPoint, ...]
    description: str = ""
    materials: tuple[tuple[str, str], ...] = field(default=())
    tube: CalibrationTube | None = None
    tube_law: str = "paper"
    measurement: str = "whole-strip"
    marker_layout: MarkerLayout | None = None
    source: str = field(default="", compare=False)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name or not set(self.name) <= _NAME_CHARS:
            raise ParameterError(
                f"calibration name must be a non-empty string of letters, digits, '-', '_', '.', got {self.name!r}"
            )
        points = tuple(self.points)
        if not points or not all(isinstance(p, CalibrationPoint) for p in points):
            raise ParameterError(f"calibration set {self.name!r} needs at least one CalibrationPoint")
        _check_duplicates(points)
        mats = self.materials.items() if isinstance(self.materials, Mapping) else self.materials
        object.__setattr__(self, "points", points)
        object.__setattr__(self, "materials", tuple((str(k), str(v)) for k, v in mats))
        object.__setattr__(self, "description", str(self.description))
        if self.tube is not None and not isinstance(self.tube, CalibrationTube):
            raise ParameterError(f"tube must be a CalibrationTube or None, got {type(self.tube).__name__}")
        object.__setattr__(self, "tube_law", check_choice("tube_law", self.tube_law, TubeLaw).value)
        if not isinstance(self.measurement, str) or not self.measurement.strip():
            raise ParameterError(f"measurement must be a non-empty description, got {self.measurement!r}")
        if self.marker_layout is not None:
            if not isinstance(self.marker_layout, MarkerLayout):
                raise ParameterError(f"marker_layout must be a MarkerLayout or None, got {type(self.marker_layout).__name__}")
            if self.measurement == "whole-strip":
                object.__setattr__(self, "measurement", self.marker_layout.label)

    def with_points(self, points: Iterable[CalibrationPoint]) -> "CalibrationSet":
        """A copy whose points are merged with ``points`` (a new point replaces an old one of the same design).

        Parameters
        ----------
        points : iterable of CalibrationPoint
            The new points.

        Returns
        -------
        CalibrationSet

        Examples
        --------
        >>> s = CalibrationSet("lab", (CalibrationPoint("zigzag", 7.0, 2.5, 80.0, branch="loading"),))
        >>> [p.g_mpa for p in s.with_points([CalibrationPoint("zigzag", 7.0, 2.6, 82.0, branch="loading")]).points]
        [2.6]
        """
        new = tuple(points)
        kept = tuple(p for p in self.points if not any(p.same_design(q) for q in new))
        return dataclasses.replace(self, points=kept + new)

    def coverage(self) -> dict[str, tuple[float, float]]:
        """Covered range of each pattern's calibration axis: ``{pattern: (low, high)}`` (width or angle).

        Returns
        -------
        dict of str to tuple of float

        Examples
        --------
        >>> PAPER_2025.coverage()
        {'zigzag': (5.0, 9.0), 'cross': (15.0, 60.0)}
        """
        out: dict[str, tuple[float, float]] = {}
        for p in self.points:
            lo, hi = out.get(p.pattern, (p.coordinate, p.coordinate))
            out[p.pattern] = (min(lo, p.coordinate), max(hi, p.coordinate))
        return out


@quick_init
@dataclass(frozen=True, slots=True)
class Calibration:
    """Parameters a calibration set gives for one design, and how they were obtained.

    Attributes
    ----------
    name : str
        Name of the calibration set.
    pattern, branch : str
        The design's pattern kind and the branch looked up.
    g_mpa, p0_kpa : float
        Effective shear modulus [MPa] and transition pressure [kPa].
    g_e_mpa : float or None
        Tube modulus [MPa] when every point used carries one.
    parameter : str
        The interpolation coordinate: the kind's calibration axis (``"width_mm"`` for the zigzag).
    value : float
        The coordinate looked up: for a design, the one realised on its needle points
        (:func:`lookup_design`).
    range_low, range_high : float
        Calibrated range of the coordinate.
    interpolated : bool
        True when the value lies strictly between two calibrated points.
    extrapolated : bool
        True when the value lies outside the calibrated range.
    extrapolation : str
        ``"clamp"`` or ``"linear"``: what was done outside the range.
    notes : tuple of str
        Other mismatches (e.g. a cross width different from the calibrated one).
    fitted, covariance : tuple
        The fitted parameters and their covariance when the design matches one fitted point
        exactly, or, between points that each carry a G and P0 covariance (a profile), the
        covariance of the interpolated values propagated from theirs (:func:`_propagated`);
        empty when averaged or unknown: no band is claimed then.
    requested_value : float or None
        The coordinate the design asked for, when the needle points realise another
        (:func:`lookup_design`); None when they realise it or nothing was requested.

    Examples
    --------
    >>> c = lookup("zigzag", width_mm=7.0)
    >>> c.g_mpa, c.p0_kpa, c.parameter, c.interpolated, c.extrapolated
    (2.7, 85.0, 'width_mm', False, False)
    """

    name: str
    pattern: str
    branch: str
    g_mpa: float
    p0_kpa: float
    g_e_mpa: float | None
    parameter: str
    value: float
    range_low: float
    range_high: float
    interpolated: bool
    extrapolated: bool
    extrapolation: str
    notes: tuple[str, ...] = ()
    fitted: tuple[str, ...] = ()
    covariance: tuple[tuple[float, ...], ...] = ()
    requested_value: float | None = None

    @property
    def label(self) -> str:
        """Short provenance string, e.g. for ``ActuatorModel.calibration``: the coordinate looked up, the
        requested one where it differs, and how the values were obtained.

        Examples
        --------
        >>> import dataclasses
        >>> dataclasses.replace(lookup("zigzag", width_mm=6.0), requested_value=6.1).label
        'paper-2025 (zigzag, width_mm=6, requested 6.1, interpolated in [5, 9])'
        """
        lo, hi = f"{self.range_low:g}", f"{self.range_high:g}"
        if self.extrapolated:
            how = "clamped to" if self.extrapolation == "clamp" else "extrapolated beyond"
            how = f", {how} [{lo}, {hi}]"
        elif self.interpolated:
            how = f", interpolated in [{lo}, {hi}]"
        else:
            how = ""
        asked = "" if self.requested_value is None else f", requested {self.requested_value:g}"
        return f"{self.name} ({self.pattern}, {self.parameter}={self.value:g}{asked}{how})"

    def as_dict(self) -> dict:
        """Plain dict with unit-suffixed keys, plus ``label``.

        Returns
        -------
        dict

        Examples
        --------
        >>> lookup("zigzag", width_mm=7.0).as_dict()["label"]
        'paper-2025 (zigzag, width_mm=7)'
        """
        d = {k: getattr(self, k) for k in self.__slots__}
        d["notes"] = list(self.notes)
        d["fitted"] = list(self.fitted)
        d["covariance"] = [list(row) for row in self.covariance]
        d["label"] = self.label
        return d


def _paper_2025() -> CalibrationSet:
    zig = [(5.0, 0.8, 50.0), (7.0, 2.7, 85.0), (9.0, 3.4, 180.0)]
    cross = [(15.0, 2.9, 150.0), (30.0, 12.0, 160.0), (45.0, 1.3, 170.0), (60.0, 2.9, 200.0)]
    points = [CalibrationPoint("zigzag", w, g, p0, interval_mm=1.0) for w, g, p0 in zig]
    points += [CalibrationPoint("cross", 7.0, g, p0, angle_deg=a, interval_mm=1.4) for a, g, p0 in cross]
    return CalibrationSet(
        "paper-2025",
        tuple(points),
        "Ota & Funabora 2025 (arXiv 2510.23188), fitted parameters of the seven prototypes. The paper does "
        "not give the tube's radii, so the set records no tube; G and the tube's wall constant enter the "
        "model together, and with embroact's default tube these G values bend far more than the paper "
        "measured (w = 5 mm zigzag: about 2000 deg at 250 kPa against about 155 deg measured at 290 kPa).",
        (("tube", "natural rubber (Hagitec T-2 02-089-01-02)"), ("thread", "polyester"), ("fabric", "cotton")),
        tube=None,
        tube_law="paper",
        measurement="markers: the paper's marker sum (7 per side, 10 mm apart); how its fit compared them "
                    "with the model is not stated",
    )


PAPER_2025 = _paper_2025()
"""The paper's fitted parameters (docs/model.md section 7)."""

_REGISTRY: dict[str, CalibrationSet] = {PAPER_2025.name: PAPER_2025}


def register(cset: CalibrationSet, *, replace: bool = False) -> None:
    """Make ``cset`` available to :func:`lookup` by its name.

    Parameters
    ----------
    cset : CalibrationSet
        The set.
    replace : bool, optional
        Replace a user set of the same name.

    Raises
    ------
    ParameterError
        If a set of that name exists and ``replace`` is false, or if it is the built-in set.

    Examples
    --------
    >>> register(CalibrationSet("doc-lab", (CalibrationPoint("zigzag", 7.0, 2.5, 80.0, branch="loading"),)))
    >>> lookup("zigzag", width_mm=7.0, name="doc-lab").g_mpa
    2.5
    >>> unregister("doc-lab")
    """
    if not isinstance(cset, CalibrationSet):
        raise ParameterError(f"register expects a CalibrationSet, got {type(cset).__name__}")
    if cset.name == PAPER_2025.name or (cset.name in _REGISTRY and not replace):
        raise ParameterError(f"calibration set {cset.name!r} is already registered (pass replace=True)")
    _REGISTRY[cset.name] = cset


def unregister(name: str) -> None:
    """Remove a user set registered with :func:`register` (the built-in set stays).

    Parameters
    ----------
    name : str
        The set's name.

    Raises
    ------
    ParameterError
        No user set has that name.

    Examples
    --------
    >>> try:
    ...     unregister("paper-2025")
    ... except ValueError as exc:
    ...     print(exc)  # doctest: +ELLIPSIS
    no user calibration set 'paper-2025'; registered: paper-2025...
    """
    if name == PAPER_2025.name or name not in _REGISTRY:
        raise ParameterError(f"no user calibration set {name!r}; registered: {', '.join(set_names())}")
    del _REGISTRY[name]


def set_names() -> tuple[str, ...]:
    """Names of the registered calibration sets, built-in first.

    Returns
    -------
    tuple of str

    Examples
    --------
    >>> set_names()[0]
    'paper-2025'
    """
    return tuple(_REGISTRY)


def get_set(name: str, sets: Iterable[CalibrationSet] | None = None) -> CalibrationSet:
    """The set called ``name`` (its name, or the file it was read from): from ``sets`` first, then the registry.

    Parameters
    ----------
    name : str
        A set's name or source file.
    sets : iterable of CalibrationSet, optional
        Sets searched first.

    Returns
    -------
    CalibrationSet

    Raises
    ------
    ParameterError
        No set is called ``name``; the message lists those that are.

    Examples
    --------
    >>> get_set("paper-2025") is PAPER_2025
    True
    >>> lab = CalibrationSet("lab", (CalibrationPoint("zigzag", 7.0, 2.5, 80.0, branch="loading"),))
    >>> get_set("lab", [lab]) is lab
    True
    """
    extra = {s.name: s for s in (sets or ())}
    extra.update({s.source: s for s in (sets or ()) if s.source})
    found = extra.get(name) or _REGISTRY.get(name)
    if found is None:
        valid = sorted(set(extra) | set(_REGISTRY))
        raise ParameterError(f"calibration must be one of {', '.join(map(repr, valid))}, got {name!r}")
    return found


def _same_coordinate(x: float, value: float) -> bool:
    """True when a point's coordinate is ``value`` itself (to rounding): the calibrated point, not a band
    around it; the interpolant passes through it, so nearby values differ from it continuously."""
    return abs(x - value) <= DEFAULT_TOLERANCES.length_mm * max(1.0, abs(value))


def _candidates(cset: CalibrationSet, pattern: str, branch: str, width: float) -> _Table:
    """The merged points of ``cset`` a design of ``pattern`` at ``width`` interpolates between (:func:`_table`),
    with the notes on how they fit it."""
    return _table(cset, pattern, branch, None if pattern_kind(pattern).calibration_axis == "width_mm" else width)


@dataclass(frozen=True, slots=True)
class _Table:
    """The points a lookup interpolates between: one (coordinate, points) pair per calibrated coordinate, and
    per coordinate the points' mean G, P0 and G_e (``ge`` None unless every point has one) with the
    interpolant's slopes through them (:func:`~embroact.predict.pchip.pchip_slopes`; None for one point); the
    notes on how they fit the design."""

    merged: tuple[tuple[float, tuple[CalibrationPoint, ...]], ...]
    xs: tuple[float, ...]
    g: tuple[float, ...]
    p0: tuple[float, ...]
    ge: tuple[float, ...] | None
    slopes: tuple[tuple[float, ...] | None, ...]
    notes: tuple[str, ...]


#: Tables kept (:func:`_table`): one per set, pattern, branch and width a process looks up.
_TABLES = 64


@functools.lru_cache(maxsize=_TABLES)
def _table(cset: CalibrationSet, pattern: str, branch: str, width: float | None) -> _Table:
    """The merged points of ``cset`` of ``pattern`` and ``branch`` a design of width ``width`` interpolates
    between (None: the kind's calibration axis is the width, every point counts): kept, as an inverse search
    looks up hundreds of designs in one."""
    pts = [p for p in cset.points if p.pattern == pattern and p.branch in (branch, "both")]
    if not pts:
        raise ModelDomainError(
            f"calibration set {cset.name!r} has no {pattern} points for the {branch} branch"
        )
    notes: tuple[str, ...] = ()
    if width is not None:  # points along another axis share one width
        nearest = min(pts, key=lambda p: abs(p.width_mm - width)).width_mm
        pts = [p for p in pts if p.width_mm == nearest]
        if abs(nearest - width) > DEFAULT_TOLERANCES.spacing_rel * width:
            notes = (f"width_mm {width:g} differs from the calibrated {pattern} width {nearest:g}",)
    # one point per coordinate: an exact branch match wins over "both"; equals are averaged
    by_coord: dict[float, list[CalibrationPoint]] = {}
    for p in pts:
        by_coord.setdefault(p.coordinate, []).append(p)
    merged = []
    for x in sorted(by_coord):
        group = by_coord[x]
        exact = tuple(p for p in group if p.branch == branch)
        merged.append((x, exact or tuple(group)))
    xs = tuple(x for x, _ in merged)
    g = tuple(_mean([p.g_mpa for p in group]) for _, group in merged)
    p0 = tuple(_mean([p.p0_kpa for p in group]) for _, group in merged)
    has_ge = all(p.g_e_mpa is not None for _, group in merged for p in group)
    ge = tuple(_mean([p.g_e_mpa for p in group if p.g_e_mpa is not None]) for _, group in merged) if has_ge else None
    slopes = tuple(None if len(xs) == 1 or ys is None else tuple(pchip_slopes(xs, ys)) for ys in (g, p0, ge))
    return _Table(tuple(merged), xs, g, p0, ge, slopes, notes)


_PAIR = ("g_mpa", "p0_kpa")


def _propagated(merged, interpolate, g: list[float], p0: list[float]):
    """(fitted, covariance) of interpolated G and P0 from the points' own covariances, or ((), ()).

    Each calibrated coordinate must hold one point fitted for G and P0 with a covariance (the
    points of a profile, ``embroact fit --sheet``); the points' fits are independent, so with
    ``d_i = dG/dG_i`` and ``e_i = dP0/dP0_i`` (the interpolation's weights, found by
    differentiating ``interpolate`` itself, whatever its scheme) the interpolated values have
    ``var G = sum d_i^2 var G_i``, ``var P0 = sum e_i^2 var P0_i`` and
    ``cov(G, P0) = sum d_i e_i cov(G_i, P0_i)``. It is the fits' uncertainty carried to the
    design; the interpolation's own error between coordinates is not in it (the leave-one-out
    errors of ``fit --sheet`` show that one).
    """
    blocks = []
    for _, group in merged:
        if len(group) != 1 or not set(_PAIR) <= set(group[0].fitted) or not group[0].covariance:
            return (), ()
        pt = group[0]
        i, j = pt.fitted.index("g_mpa"), pt.fitted.index("p0_kpa")
        blocks.append((pt.covariance[i][i], pt.covariance[j][j], pt.covariance[i][j]))

    def weights(ys: list[float]) -> list[float]:
        base = interpolate(ys)
        out = []
        for k, y in enumerate(ys):
            h = 1e-6 * max(abs(y), 1.0)
            out.append((interpolate(ys[:k] + [y + h] + ys[k + 1:]) - base) / h)
        return out

    d, e = weights(g), weights(p0)
    vg = math.fsum(dk * dk * b[0] for dk, b in zip(d, blocks))
    vp = math.fsum(ek * ek * b[1] for ek, b in zip(e, blocks))
    c = math.fsum(dk * ek * b[2] for dk, ek, b in zip(d, e, blocks))
    return _PAIR, ((vg, c), (c, vp))


def _mean(values: list[float]) -> float:
    return math.fsum(values) / len(values)


def _interpolate(xs, ys, x: float, extrapolation: str, interpolation: str = "pchip", slopes=None) -> float:
    """Monotone piecewise-cubic y(x) (:func:`~embroact.predict.pchip.pchip`, with its ``slopes`` when known), or
    piecewise linear; outside the range clamp or extend the end segment's secant."""
    if len(xs) == 1:
        return ys[0]
    if x <= xs[0]:
        return ys[0] if extrapolation == "clamp" else ys[0] + (ys[1] - ys[0]) * (x - xs[0]) / (xs[1] - xs[0])
    if x >= xs[-1]:
        return ys[-1] if extrapolation == "clamp" else ys[-1] + (ys[-1] - ys[-2]) * (x - xs[-1]) / (xs[-1] - xs[-2])
    if interpolation == "linear":
        k = min(max(bisect_right(xs, x) - 1, 0), len(xs) - 2)
        return ys[k] + (ys[k + 1] - ys[k]) * (x - xs[k]) / (xs[k + 1] - xs[k])
    return pchip(xs, ys, x, slopes=slopes)


def lookup(
    pattern: str,
    *,
    width_mm: float,
    angle_deg: float | None = None,
    name: str = "paper-2025",
    sets: Iterable[CalibrationSet] | None = None,
    branch: str = "loading",
    extrapolation: str = "clamp",
    interpolation: str = "pchip",
) -> Calibration:
    """Parameters (G, P0) of the calibration set ``name`` for one design.

    Parameters
    ----------
    pattern : str
        A registered pattern kind.
    width_mm : float
        Embroidery width [mm].
    angle_deg : float, optional
        Cross embroidery angle alpha0 [deg]; required for cross.
    name : str
        Calibration set name (``"paper-2025"`` built in).
    sets : iterable of CalibrationSet, optional
        Extra sets searched before the registry.
    branch : str
        ``"loading"``, ``"unloading"`` or ``"both"``.
    extrapolation : str
        ``"clamp"`` or ``"linear"`` outside the calibrated range (see module docstring).
    interpolation : str
        ``"pchip"`` (default: monotone cubic, the model's lookup) or ``"linear"`` between points
        (a neighbour's value enters only its own interval: what a leave-one-out check that blames
        the coupon spoiling its neighbours by about half relies on).

    Returns
    -------
    Calibration
        Values plus provenance: interpolated / extrapolated flags, range, notes.

    Raises
    ------
    ParameterError
        Unknown set, pattern, branch or extrapolation; bad width or angle.
    ModelDomainError
        The set has no points for the pattern/branch, or a linear extrapolation leaves
        the valid range of G or P0.

    Examples
    --------
    >>> c = lookup("cross", width_mm=7.0, angle_deg=45.0)
    >>> c.g_mpa, c.p0_kpa, c.label
    (1.3, 170.0, 'paper-2025 (cross, angle_deg=45)')
    >>> lookup("zigzag", width_mm=11.0).extrapolated  # beyond the calibrated widths: clamped
    True
    """
    _choice("pattern", pattern, PATTERN_KINDS.names())
    _choice("branch", branch, BRANCHES)
    _choice("extrapolation", extrapolation, EXTRAPOLATIONS)
    _choice("interpolation", interpolation, ("pchip", "linear"))
    w = check_range("width_mm", width_mm, low=0.0, high=200.0)
    axis = pattern_kind(pattern).calibration_axis
    if axis == "angle_deg":
        if angle_deg is None:
            raise ParameterError(f"angle_deg is required for a {pattern} design, got None")
        value = check_range("angle_deg", angle_deg, low=0.0, high=90.0)
    else:
        value = w
    cset = get_set(name, sets)
    table = _candidates(cset, pattern, branch, w)
    merged, xs, g, p0, ge, notes = table.merged, table.xs, table.g, table.p0, table.ge, table.notes
    slopes_g, slopes_p0, slopes_ge = table.slopes

    hit = [i for i, x in enumerate(xs) if _same_coordinate(x, value)]
    extrapolated = not hit and (value < xs[0] or value > xs[-1])
    fitted: tuple[str, ...] = ()
    cov: tuple[tuple[float, ...], ...] = ()
    if hit:
        i = hit[0]
        g_v, p0_v, ge_v = g[i], p0[i], (ge[i] if ge else None)
        group = merged[i][1]
        if len(group) == 1:
            fitted, cov = group[0].fitted, group[0].covariance
    else:
        g_v = _interpolate(xs, g, value, extrapolation, interpolation, slopes_g)
        p0_v = _interpolate(xs, p0, value, extrapolation, interpolation, slopes_p0)
        ge_v = _interpolate(xs, ge, value, extrapolation, interpolation, slopes_ge) if ge else None
        fitted, cov = _propagated(merged, lambda ys: _interpolate(xs, ys, value, extrapolation, interpolation),
                                  list(g), list(p0))
    label = f"calibration {name!r} extrapolated linearly to {pattern} {axis}={value:g}"
    if not 0.0 < g_v <= _G_MAX_MPA or not 0.0 <= p0_v <= _P_MAX_KPA or (ge_v is not None and ge_v <= 0.0):
        raise ModelDomainError(
            f"{label} gives g_mpa={g_v:.4g}, p0_kpa={p0_v:.4g} outside (0, {_G_MAX_MPA:g}] / [0, {_P_MAX_KPA:g}]; "
            f"calibrated range is [{xs[0]:g}, {xs[-1]:g}], use extrapolation='clamp'"
        )
    return Calibration(
        name=cset.name,
        pattern=pattern,
        branch=branch,
        g_mpa=float(g_v),
        p0_kpa=float(p0_v),
        g_e_mpa=None if ge_v is None else float(ge_v),
        parameter=axis,
        value=value,
        range_low=float(xs[0]),
        range_high=float(xs[-1]),
        interpolated=not hit and not extrapolated,
        extrapolated=bool(extrapolated),
        extrapolation=extrapolation,
        notes=tuple(notes),
        fitted=fitted,
        covariance=cov,
    )


def lookup_design(derived, *, name: str = "paper-2025", sets: Iterable[CalibrationSet] | None = None,
                  branch: str = "loading", extrapolation: str = "clamp", interpolation: str = "pchip") -> Calibration:
    """:func:`lookup` at the calibration coordinate a design's needle points realise.

    The coordinate is the kind's calibration axis measured on the generated stitches
    (``derived.width_mm``, with ``derived.angle_deg`` for a kind with an angle): the geometry
    the machine file holds and the model uses, not the value the design asked for. Where the
    two differ (a 6.1 mm zigzag on a straight path sews rails 6.0 mm apart on the 0.1 mm grid)
    the result records the requested one as ``requested_value``. A realised value equal to a
    calibrated coordinate up to float noise (7.000000000000001 mm) is that point.

    Parameters
    ----------
    derived : DerivedGeometry
        The design's derived geometry.
    name, sets, branch, extrapolation, interpolation
        As for :func:`lookup`.

    Returns
    -------
    Calibration

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> from embroact.predict.derived import derive_from_values
    >>> d = derive_from_values("zigzag", width_mm=6.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0,
    ...                        tube=Tube(), requested=(6.1, 1.0, 0.0))
    >>> c = lookup_design(d)
    >>> c.value, c.requested_value, c.g_mpa == lookup("zigzag", width_mm=6.0).g_mpa
    (6.0, 6.1, True)
    """
    kind = pattern_kind(derived.pattern)
    cal = lookup(derived.pattern, width_mm=derived.width_mm, angle_deg=derived.angle_deg if kind.has_angle else None,
                 name=name, sets=sets, branch=branch, extrapolation=extrapolation, interpolation=interpolation)
    requested = float(getattr(derived, "requested_" + kind.calibration_axis))
    return cal if _same_coordinate(cal.value, requested) else dataclasses.replace(cal, requested_value=requested)


@quick_init
@dataclass(frozen=True, slots=True)
class ModelChoice:
    """The model of one actuator (or segment) and where each of its numbers came from.

    Attributes
    ----------
    model : ActuatorModel
        The model.
    calibration : Calibration or None
        The lookup result; ``None`` when neither G nor P0 came from a set.
    g_source, p0_source : str
        ``"calibration <label>"``, ``"given"`` or ``"geometry (tube law <law> at r0)"``.
    tube_law_p0_kpa : float
        The tube law's P0 at the realised r0, with the tube law in force
        (:func:`embroact.predict.tubelaws.transition_pressure_kpa`) [kPa]: the model's P0 when
        ``p0_source`` is geometry; shown beside the set's P0 otherwise.
    notes : tuple of str
        Mismatches between the design and what the calibration was fitted with (tube).

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> from embroact.predict.derived import derive_from_values
    >>> d = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
    >>> choice = model_for(d)
    >>> choice.model.g_mpa, choice.p0_source, round(choice.tube_law_p0_kpa, 3)
    (2.7, 'calibration paper-2025 (zigzag, width_mm=7)', 84.455)
    """

    model: ActuatorModel
    calibration: Calibration | None
    g_source: str
    p0_source: str
    tube_law_p0_kpa: float
    notes: tuple[str, ...] = ()

    def as_dict(self) -> dict:
        """JSON-ready: G, P0, tube law, tube and the source of each; P0 once per source.

        ``p0_kpa`` is the model's (its source ``p0_source``), ``tube_law_p0_kpa`` the tube law's
        at r0 and ``calibration.p0_kpa`` the calibration set's (when one was looked up).

        Returns
        -------
        dict

        Examples
        --------
        >>> from embroact.patterns.params import Tube
        >>> from embroact.predict.derived import derive_from_values
        >>> d = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
        >>> choice = model_for(d)
        >>> d = choice.as_dict()
        >>> d["p0_kpa"], round(d["tube_law_p0_kpa"], 3), d["calibration"]["p0_kpa"]
        (85.0, 84.455, 85.0)
        """
        return model_dict(self)


def model_dict(choice) -> dict:
    """The dict of a segment's or a whole strip's model and sources (:meth:`ModelChoice.as_dict`).

    Parameters
    ----------
    choice : ModelChoice or StripChoice
        Anything with a ``model`` and the sources of its G and P0.

    Returns
    -------
    dict

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> from embroact.predict.derived import derive_from_values
    >>> d = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
    >>> model_dict(model_for(d))["tube"]
    {'outer_radius_mm': 1.5, 'inner_radius_mm': 1.0, 'g_e_mpa': 0.13}
    """
    m = choice.model
    return {"g_mpa": m.g_mpa, "g_source": choice.g_source, "p0_kpa": m.p0_kpa, "p0_source": choice.p0_source,
            "tube_law_p0_kpa": choice.tube_law_p0_kpa,
            "tube_law": m.tube_law, "tube": {"outer_radius_mm": m.outer_radius_mm,
                                             "inner_radius_mm": m.inner_radius_mm, "g_e_mpa": m.g_e_mpa},
            "calibration": None if choice.calibration is None else choice.calibration.as_dict(),
            "notes": list(choice.notes)}


def model_for(derived, settings: ModelSettings | None = None, *,
              sets: Mapping[str, CalibrationSet] | Iterable[CalibrationSet] | None = None,
              branch: str = "loading", extrapolation: str = "clamp", stub_mm: float | None = 0.0) -> ModelChoice:
    """The deformation model of a design under its settings: the one model factory.

    Policy (docs/model.md, calibration policy): G is ``settings.g_mpa`` when given, else
    the calibration set's; P0 is ``settings.p0_kpa`` when given, else the set's fitted P0
    (``p0_source="calibration"``, default: the set's G and P0 were fitted as a pair) or the
    tube law's pressure at the realised sleeve radius (``p0_source="geometry"``). The set is
    looked up at the pattern coordinate the needle points realise (:func:`lookup_design`), the
    geometry the model uses too; the requested one is reported where it differs.

    Parameters
    ----------
    derived : DerivedGeometry
    settings : ModelSettings, optional
        Default ``ModelSettings()`` (``paper-2025``, P0 from the set, paper tube law).
    sets : mapping name -> CalibrationSet, or iterable of sets, optional
        Sets searched before the registry (e.g. read from calibration files).
    branch, extrapolation
        As for :func:`lookup`.
    stub_mm : float or None, optional
        The model's sealed tube beyond the tip (:class:`~embroact.predict.curve.ActuatorModel`):
        a single-pattern actuator's ``tube.end_margin_mm``; None for a segment of a chain.

    Returns
    -------
    ModelChoice

    Examples
    --------
    >>> from embroact.patterns.design import ModelSettings
    >>> from embroact.patterns.params import Tube
    >>> from embroact.predict.derived import derive_from_values
    >>> d = derive_from_values("cross", width_mm=7.0, interval_mm=1.4, angle_deg=40.0,
    ...                        length_mm=100.0, tube=Tube())
    >>> c = model_for(d)
    >>> round(c.model.g_mpa, 4), round(c.model.p0_kpa, 2), c.g_source
    (4.0741, 165.93, 'calibration paper-2025 (cross, angle_deg=40, interpolated in [15, 60])')
    >>> c = model_for(d, ModelSettings(g_mpa=2.0, p0_source="geometry"))
    >>> c.g_source, c.p0_source
    ('given', 'geometry (tube law paper at r0 = 2.581 mm)')
    """
    from .curve import ActuatorModel

    settings = ModelSettings() if settings is None else settings
    law = check_choice("tube_law", settings.tube_law, TubeLaw).value
    p0_from_set = settings.p0_kpa is None and settings.p0_source is P0Source.CALIBRATION
    cal = None
    csets = as_calibration_sets(sets)
    if settings.g_mpa is None or p0_from_set:
        cal = lookup_design(derived, name=settings.calibration, sets=csets, branch=branch,
                            extrapolation=extrapolation)
    from_set = "" if cal is None else f"calibration {cal.label}"
    tube = derived.tube
    tube_p0 = _tube_law_p0_kpa(derived.r0_mm, tube, law)
    if settings.p0_kpa is not None:
        p0, p0_src = float(settings.p0_kpa), "given"
    elif p0_from_set and cal is not None:
        p0, p0_src = cal.p0_kpa, from_set
    else:
        p0 = tube_p0
        p0_src = f"geometry (tube law {law} at r0 = {derived.r0_mm:.4g} mm)"
    if settings.g_mpa is not None:
        g, g_src = float(settings.g_mpa), "given"
    else:
        assert cal is not None  # looked up above whenever G is not given
        g, g_src = cal.g_mpa, from_set
    notes: tuple[str, ...] = ()
    if cal is not None:
        cset = get_set(settings.calibration, csets)
        if cset.tube is None:
            notes = (f"calibration {cset.name!r} records no tube: its G may not carry over to this tube",)
        else:
            notes = tuple(f"tube {d}" for d in cset.tube.differences(tube))
        if cset.tube_law != law:
            notes += (f"tube law {law} (calibrated with {cset.tube_law})",)
    label = g_src if g_src == p0_src else f"G {g_src}; P0 {p0_src}"
    model = ActuatorModel(derived.pattern, length_mm=derived.length_mm, r0_mm=derived.r0_mm,
                          beta0_deg=derived.beta0_deg, outer_radius_mm=tube.outer_radius_mm,
                          inner_radius_mm=tube.inner_radius_mm, g_e_mpa=tube.g_e_mpa, g_mpa=g, p0_kpa=p0,
                          tube_law=law, calibration=label, stub_mm=stub_mm)
    return ModelChoice(model, cal, g_src, p0_src, tube_p0, notes)


@functools.lru_cache(maxsize=256)
def _tube_law_p0_kpa(r0_mm: float, tube, law: str) -> float:
    """The tube law's P0 at ``r0_mm`` (:func:`~embroact.predict.tubelaws.transition_pressure_kpa`) [kPa]: kept, as
    a search over a cross pattern's angle makes hundreds of models of one sleeve radius."""
    from .tubelaws import transition_pressure_kpa

    return float(transition_pressure_kpa(r0_mm, tube, law))


def as_calibration_sets(sets) -> tuple[CalibrationSet, ...]:
    """Calibration sets given as None, an iterable of sets or a mapping name -> set, as a tuple.

    Parameters
    ----------
    sets : None, iterable of CalibrationSet or mapping of str to CalibrationSet
        The sets.

    Returns
    -------
    tuple of CalibrationSet

    Examples
    --------
    >>> as_calibration_sets({"paper-2025": PAPER_2025}) == (PAPER_2025,), as_calibration_sets(None)
    (True, ())
    """
    if sets is None:
        return ()
    return tuple(sets.values()) if isinstance(sets, Mapping) else tuple(sets)
