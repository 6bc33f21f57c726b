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

Disagreement: a pattern's coupons disagree when a leave-one-out error exceeds
:data:`DISAGREE_FLOOR_DEG` and :data:`DISAGREE_FACTOR` times its expected size
(:attr:`LeaveOneOut.expected_deg`: the pattern's measurement noise, the median RMSE of the
coupons' own fits, with the others' covariance propagated to the coupon). Which coupon is to
blame is not the one with the largest error: one bad coupon spoils its neighbours'
predictions too, and an end coupon, predicted by extrapolating through a bad neighbour,
reads about twice the bad coupon's own error. So each coupon is deleted in turn and the
others are predicted again without it as well (leave two out); the coupon whose deletion
leaves the smallest worst error is flagged when its own error is over the limit and its
deletion at least halves the worst error (:data:`DISAGREE_EXPLAINED`): it explains the
disagreement (one coupon per pattern at most). A disagreement no single coupon explains
(three coupons of a pattern cannot tell which one is off: a trend through two of them always
predicts the third equally badly) is reported for the pattern (:attr:`Profile.unexplained`).
A flagged coupon disagrees with the rest (a bad sample, a wrong label, a misread photo), or
the coordinate is sampled too coarsely there; either way, sew another one there.

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

Three coupons of a pattern show a disagreement (G is not linear in the width here) but cannot
tell which coupon is off:

>>> [pattern for pattern, worst_deg in prof.unexplained], prof.loo[0].rmse_deg > 10 * prof.loo[0].expected_deg
(['zigzag'], True)
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..patterns.base.errors import ModelDomainError, ParameterError
from .calibration import CalibrationSet, CalibrationTube, lookup_design
from .derived import DerivedGeometry
from .fit import FitResult, fit_design
from .markers import MarkerLayout, reading_deg

__all__ = ["DISAGREE_EXPLAINED", "DISAGREE_FACTOR", "DISAGREE_FLOOR_DEG", "CouponData", "CouponFit", "LeaveOneOut", "Profile",
           "fit_profile", "predicted_reading_deg"]

#: A coupon disagrees when its leave-one-out error exceeds this many times its expected size ...
DISAGREE_FACTOR = 3.0
#: ... and this many degrees.
DISAGREE_FLOOR_DEG = 2.0
#: A coupon explains a disagreement when deleting it leaves at most this fraction of the worst error.
DISAGREE_EXPLAINED = 0.5


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
        Its calibration coordinate as its needle points realise it.
    rmse_deg : float or None
        RMSE of its readings predicted from the others [deg]; None: fewer than 2 other
        coupons of its pattern.
    extrapolated : bool
        It lies outside the others' range.
    flagged : bool
        It explains its pattern's disagreement (module docstring).
    expected_deg : float or None
        The RMSE the measurement noise and the others' fit uncertainty explain [deg].

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
    expected_deg: float | None = None


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
    unexplained : tuple of (str, float)
        Patterns whose coupons disagree without a coupon that explains it, with their worst
        leave-one-out error [deg] (module docstring).

    Examples
    --------
    See :func:`fit_profile`.

    >>> [f.name for f in Profile.__dataclass_fields__.values()]
    ['calibration', 'fits', 'loo', 'unexplained']
    """

    calibration: CalibrationSet
    fits: tuple[CouponFit, ...]
    loo: tuple[LeaveOneOut, ...]
    unexplained: tuple[tuple[str, float], ...] = ()


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


def _coordinate(d: DerivedGeometry) -> float:
    """The coupon's calibration coordinate as its needle points realise it (what its point is keyed by)."""
    from ..patterns.kinds import pattern_kind

    return float(getattr(d, pattern_kind(d.pattern).calibration_axis))


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

    patterns = [c.derived.pattern for c in coupons]
    noise = {pat: float(np.median([r.rmse_deg for f, q in zip(fits, patterns) if q == pat for r in f.results]))
             for pat in set(patterns)}

    def error(k: int, others) -> tuple[float, bool, float] | None:
        return _prediction_error(coupons[k], [fits[j] for j in others], noise[patterns[k]], name, kw)

    loo = []
    for k, c in enumerate(coupons):
        got = error(k, [j for j in range(len(coupons)) if j != k and patterns[j] == patterns[k]])
        rmse, extrap, expected = got or (None, False, None)
        loo.append(LeaveOneOut(c.name, patterns[k], _coordinate(c.derived), rmse, extrap, False, expected))
    flagged, unexplained = _flag(loo, error)
    return Profile(_set(name, fits, **kw), tuple(fits),
                   tuple(dataclasses.replace(e, flagged=k in flagged) for k, e in enumerate(loo)), unexplained)


def _prediction_error(c: CouponData, others: list[CouponFit], noise_deg: float, name: str,
                      kw: dict) -> tuple[float, bool, float] | None:
    """(RMSE [deg], extrapolated, expected RMSE [deg]) of ``c``'s readings predicted from the set of
    ``others``, None below two; the expected RMSE adds the predicted values' band, propagated from
    the others' covariances, to the measurement noise ``noise_deg``."""
    from .curve import ActuatorModel
    from .uncertainty import theta_band

    if len(others) < 2:
        return None
    cset = _set(name, others, **kw)
    sq, band_sq, n, extrap = 0.0, 0.0, 0, False
    for branch in sorted(set(c.branch)):
        mask = np.array([b == branch for b in c.branch])
        where: dict[str, Any] = {"name": name, "sets": [cset], "branch": branch}
        # linear between the others: a spoiled coupon then moves only its own intervals
        try:  # an end coupon: the others' trend carried on (clamped where it leaves the model's domain)
            cal = lookup_design(c.derived, extrapolation="linear", interpolation="linear", **where)
        except ModelDomainError:
            cal = lookup_design(c.derived, interpolation="linear", **where)
        extrap = extrap or cal.extrapolated
        p = c.pressure_kpa[mask]
        pred = predicted_reading_deg(c.derived, cal.g_mpa, cal.p0_kpa, p, kw["layout"])
        sq += float(np.sum((pred - c.reading_deg[mask]) ** 2))
        n += int(mask.sum())
        if cal.covariance:
            b = theta_band(ActuatorModel.from_derived(c.derived, g_mpa=cal.g_mpa, p0_kpa=cal.p0_kpa), p, cal.fitted,
                           cal.covariance, measurement=kw["layout"])
            band_sq += float(np.sum((b.theta_sd_deg if b.reading_sd_deg is None else b.reading_sd_deg) ** 2))
    return math.sqrt(sq / n), extrap, math.sqrt(noise_deg**2 + band_sq / n)


def _flag(loo: list[LeaveOneOut], error) -> tuple[set[int], tuple[tuple[str, float], ...]]:
    """The coupons (indices) that explain their pattern's disagreement, and the patterns that disagree
    without one, with their worst error [deg] (module docstring); ``error(k, others)`` predicts coupon k."""
    flagged: set[int] = set()
    unexplained = []
    for pattern in dict.fromkeys(e.pattern for e in loo):
        seen = {k: (e.rmse_deg, e.expected_deg) for k, e in enumerate(loo)
                if e.pattern == pattern and e.rmse_deg is not None and e.expected_deg is not None}
        excess = {k: _excess(*v) for k, v in seen.items()}
        if not excess or max(excess.values()) <= DISAGREE_FACTOR:
            continue
        worst = max(excess.values())
        without: dict[int, float] = {}
        for k in seen if len(seen) >= 4 else ():
            again = [error(j, [i for i in seen if i not in (j, k)]) for j in seen if j != k]
            without[k] = max(_excess(r[0], r[2]) for r in again if r is not None)
        best = min(without, key=lambda i: without[i], default=None)
        if best is None or excess[best] <= DISAGREE_FACTOR or without[best] > DISAGREE_EXPLAINED * worst:
            unexplained.append((pattern, max(v[0] for v in seen.values())))
        else:
            flagged.add(best)
    return flagged, tuple(unexplained)


def _excess(rmse_deg: float, expected_deg: float) -> float:
    """How many times its expected size a prediction error is, 0 below :data:`DISAGREE_FLOOR_DEG`."""
    return rmse_deg / expected_deg if rmse_deg > DISAGREE_FLOOR_DEG else 0.0
