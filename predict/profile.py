"""A material profile: one calibration set fitted from every coupon actuator, and how well it predicts.

``embroact fit --sheet`` reads a whole measurement sheet (docs/calibration.md): every coupon
actuator, both branches. :func:`fit_profile` fits G and P0 to each actuator's branches
(:func:`embroact.predict.fit.fit_design`, compared through the marker layout's reading),
keeps each fit as a calibration point with its covariance, and puts them in one
:class:`~embroact.predict.calibration.CalibrationSet` (tube, tube law, marker layout and
the materials as named by the user).

Leave-one-out: each actuator is predicted from the set fitted *without* it (G and P0 looked
up at its coordinate from the other coupons of its pattern, as the profile interpolates; at
an end of the range the neighbours' trend carried on, marked ``extrapolated``), and the RMSE
of that prediction against its measured readings is its leave-one-out error [deg].

Disagreement: a coupon is flagged when its leave-one-out error exceeds
:data:`DISAGREE_FACTOR` times its pattern's measurement noise (the median RMSE of the
coupons' own fits; at least :data:`DISAGREE_FLOOR_DEG`) and the leave-one-out errors of its
neighbours along the coordinate (one bad coupon spoils its neighbours' predictions too, by
about half as much, since they are interpolated through it). It disagrees with the rest (a
bad sample, a wrong label, a misread photo), or the coordinate is sampled too coarsely
there; either way, sew another one there. An end coupon (predicted by extrapolation through
its neighbours) is not flagged when an interior coupon of its pattern is.

Examples
--------
>>> from embroact.patterns.params import Tube
>>> from embroact.predict.derived import derive_from_values
>>> from embroact.predict.markers import MarkerLayout
>>> import numpy as np
>>> lay = MarkerLayout(markers_per_side=11, spacing_mm=10.0, rows=1)
>>> data = []
>>> for w, g, p0 in ((5.0, 4.0, 50.0), (7.0, 2.7, 85.0), (9.0, 2.0, 150.0)):
...     d = derive_from_values("zigzag", width_mm=w, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
...     p = np.arange(0.0, 301.0, 25.0)
...     data.append(CouponData(f"w{w:g}", d, p, predicted_reading_deg(d, g, p0, p, lay), ("loading",) * len(p)))
>>> prof = fit_profile(data, layout=lay, name="demo", tube=Tube())
>>> [round(f.results[0].g_mpa, 3) for f in prof.fits]
[4.0, 2.7, 2.0]
>>> prof.calibration.name, len(prof.calibration.points), prof.loo[1].flagged
('demo', 3, False)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..patterns.base.errors import ModelDomainError, ParameterError
from .calibration import CalibrationSet, CalibrationTube, lookup
from .derived import DerivedGeometry
from .fit import FitResult, fit_design
from .markers import MarkerLayout, reading_deg

__all__ = ["DISAGREE_FACTOR", "DISAGREE_FLOOR_DEG", "CouponData", "CouponFit", "LeaveOneOut", "Profile",
           "fit_profile", "predicted_reading_deg"]

#: A coupon disagrees when its leave-one-out error exceeds this many times its pattern's median ...
DISAGREE_FACTOR = 3.0
#: ... and this many degrees.
DISAGREE_FLOOR_DEG = 2.0


@dataclass(frozen=True, slots=True)
class CouponData:
    """One coupon actuator's measurements: its name, derived geometry, pressures, readings, branches.

    Attributes
    ----------
    name : str
        The coupon actuator's label.
    derived : DerivedGeometry
        Its geometry as sewn.
    pressure_kpa, reading_deg : numpy.ndarray (n,)
        The measurements [kPa, deg].
    branch : tuple of str
        ``"loading"`` or ``"unloading"`` per measurement.

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> from embroact.predict.derived import derive_from_values
    >>> d = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
    >>> c = CouponData("w7", d, np.array([0.0, 200.0]), np.array([0.0, 92.6]), ("loading", "loading"))
    >>> c.derived.width_mm, c.branch[1]
    (7.0, 'loading')
    """

    name: str
    derived: DerivedGeometry
    pressure_kpa: np.ndarray
    reading_deg: np.ndarray
    branch: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class CouponFit:
    """The fits (one per branch) of one coupon actuator.

    Attributes
    ----------
    name : str
        The coupon actuator's label.
    derived : DerivedGeometry
        Its geometry.
    results : tuple of FitResult
        One per branch measured.

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> from embroact.predict.derived import derive_from_values
    >>> d = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
    >>> CouponFit("w7", d, ()).results
    ()
    """

    name: str
    derived: DerivedGeometry
    results: tuple[FitResult, ...]


@dataclass(frozen=True, slots=True)
class LeaveOneOut:
    """One coupon predicted from the others: RMSE per branch [deg] and whether it disagrees.

    Attributes
    ----------
    name, pattern : str
        The coupon actuator and its pattern kind.
    coordinate : float
        Its calibration coordinate.
    rmse_deg : float or None
        RMSE of its readings predicted from the others [deg]; None: fewer than 2 other
        coupons of its pattern.
    extrapolated : bool
        It lies outside the others' range.
    flagged : bool
        Its error stands out from the others' (module docstring).

    Examples
    --------
    >>> LeaveOneOut("w7", "zigzag", 7.0, 0.4, False).flagged
    False
    """

    name: str
    pattern: str
    coordinate: float
    rmse_deg: float | None  # None: fewer than 2 other coupons of its pattern
    extrapolated: bool
    flagged: bool = False


@dataclass(frozen=True, slots=True)
class Profile:
    """The fitted material profile: the calibration set, the per-coupon fits and the leave-one-out errors.

    Attributes
    ----------
    calibration : CalibrationSet
        The set made from every coupon's fit.
    fits : tuple of CouponFit
        Per coupon.
    loo : tuple of LeaveOneOut
        Per coupon.

    Examples
    --------
    See :func:`fit_profile`.

    >>> [f.name for f in Profile.__dataclass_fields__.values()]
    ['calibration', 'fits', 'loo']
    """

    calibration: CalibrationSet
    fits: tuple[CouponFit, ...]
    loo: tuple[LeaveOneOut, ...]


def predicted_reading_deg(derived: DerivedGeometry, g_mpa: float, p0_kpa: float, pressure_kpa,
                          layout: MarkerLayout | None) -> np.ndarray:
    """The model's bend at ``pressure_kpa`` as ``layout`` reads it (theta when None) [deg].

    Parameters
    ----------
    derived : DerivedGeometry
        The design.
    g_mpa, p0_kpa : float
        The model's G [MPa] and P0 [kPa].
    pressure_kpa : array_like
        Pressures [kPa].
    layout : MarkerLayout or None
        The marker layout; None: theta.

    Returns
    -------
    numpy.ndarray
        [deg].

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> from embroact.predict.derived import derive_from_values
    >>> d = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
    >>> predicted_reading_deg(d, 2.7, 85.0, [100.0, 200.0], None).round(3).tolist()
    [11.539, 102.93]
    """
    from .curve import ActuatorModel, curve

    c = curve(ActuatorModel.from_derived(derived, g_mpa=g_mpa, p0_kpa=p0_kpa), np.asarray(pressure_kpa, float))
    theta = np.asarray(c.theta_deg, dtype=np.float64)
    return theta if layout is None else np.asarray(reading_deg(theta, derived.length_mm, layout), dtype=np.float64)


def _set(name, fits, *, description, materials, tube, tube_law, layout) -> CalibrationSet:
    points = tuple(r.to_point() for f in fits for r in f.results)
    return CalibrationSet(name, points, description, materials, tube=None if tube is None else CalibrationTube.of(tube),
                          tube_law=tube_law, marker_layout=layout)


def _coordinate(d: DerivedGeometry) -> tuple[str, float]:
    from ..patterns.kinds import pattern_kind

    axis = pattern_kind(d.pattern).calibration_axis
    return axis, float(d.requested_width_mm if axis == "width_mm" else d.requested_angle_deg)


def fit_profile(coupons, *, layout: MarkerLayout | None, name: str, tube=None, description: str = "",
                materials=(), tube_law: str = "paper") -> Profile:
    """Fit every coupon, make the set, and predict each coupon from the others (module docstring).

    Parameters
    ----------
    coupons : iterable of CouponData
        The measured coupon actuators, at least one.
    layout : MarkerLayout or None
        The layout the readings were taken with; None: theta.
    name : str
        The calibration set's name.
    tube : Tube, optional
        The tube the coupon was sewn over.
    description : str, optional
        The set's description.
    materials : sequence, optional
        Material notes recorded with the set.
    tube_law : str, optional
        The tube law of P0 from geometry.

    Returns
    -------
    Profile

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> from embroact.predict.derived import derive_from_values
    >>> d = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
    >>> p = np.arange(0.0, 301.0, 25.0)
    >>> one = CouponData("w7", d, p, predicted_reading_deg(d, 2.7, 85.0, p, None), ("loading",) * len(p))
    >>> prof = fit_profile([one], layout=None, name="demo", tube=Tube())
    >>> round(prof.fits[0].results[0].g_mpa, 6), prof.loo[0].rmse_deg  # no others to predict it from
    (2.7, None)
    """
    coupons = tuple(coupons)
    if not coupons:
        raise ParameterError("a profile needs at least one measured coupon actuator, got none")
    fits = []
    for c in coupons:
        try:
            res = fit_design(c.derived, c.pressure_kpa, c.reading_deg, labels=list(c.branch), measurement=layout,
                             tube_law=tube_law)
        except (ParameterError, ModelDomainError) as exc:
            raise type(exc)(f"coupon {c.name!r}: {exc}") from None
        fits.append(CouponFit(c.name, c.derived, res))
    kw = {"description": description, "materials": materials, "tube": tube, "tube_law": tube_law, "layout": layout}
    full = _set(name, fits, **kw)
    loo = []
    for k, (c, f) in enumerate(zip(coupons, fits)):
        others = [g for j, g in enumerate(fits) if j != k and g.derived.pattern == c.derived.pattern]
        axis, coord = _coordinate(c.derived)
        if len(others) < 2:
            loo.append(LeaveOneOut(c.name, c.derived.pattern, coord, None, False))
            continue
        cset = _set(name, others, **kw)
        sq, n, extrap = 0.0, 0, False
        for branch in sorted(set(c.branch)):
            mask = np.array([b == branch for b in c.branch])
            where = {"width_mm": c.derived.requested_width_mm, "name": name, "sets": [cset], "branch": branch,
                     "angle_deg": c.derived.requested_angle_deg if axis == "angle_deg" else None}
            # linear between the others: a spoiled coupon then moves only its own intervals (the flag's premise)
            try:  # an end coupon: the others' trend carried on (clamped where it leaves the model's domain)
                cal = lookup(c.derived.pattern, extrapolation="linear", interpolation="linear", **where)
            except ModelDomainError:
                cal = lookup(c.derived.pattern, interpolation="linear", **where)
            extrap = extrap or cal.extrapolated
            pred = predicted_reading_deg(c.derived, cal.g_mpa, cal.p0_kpa, c.pressure_kpa[mask], layout)
            sq += float(np.sum((pred - c.reading_deg[mask]) ** 2))
            n += int(mask.sum())
        loo.append(LeaveOneOut(c.name, c.derived.pattern, coord, math.sqrt(sq / n), extrap))
    return Profile(full, tuple(fits), tuple(_flag(loo, fits)))


def _flag(loo: list[LeaveOneOut], fits: list[CouponFit]) -> list[LeaveOneOut]:
    """``loo`` with the disagreeing coupons flagged (module docstring)."""
    out = []
    for k, e in enumerate(loo):
        same = sorted((o.coordinate, j) for j, o in enumerate(loo) if o.pattern == e.pattern)
        noise = float(np.median([r.rmse_deg for _, j in same for r in fits[j].results]))
        pos = [j for _, j in same].index(k)
        neighbours = [same[i][1] for i in (pos - 1, pos + 1) if 0 <= i < len(same)]
        err = e.rmse_deg
        bad = (err is not None and err > max(DISAGREE_FACTOR * noise, DISAGREE_FLOOR_DEG)
               and all(err > (loo[j].rmse_deg or 0.0) for j in neighbours))
        out.append(LeaveOneOut(e.name, e.pattern, e.coordinate, e.rmse_deg, e.extrapolated, bad))
    # an end coupon is extrapolated through its neighbours: when an interior one disagrees, it is the cause
    inner = {e.pattern for e in out if e.flagged and not e.extrapolated}
    return [LeaveOneOut(e.name, e.pattern, e.coordinate, e.rmse_deg, e.extrapolated, False)
            if e.flagged and e.extrapolated and e.pattern in inner else e for e in out]
