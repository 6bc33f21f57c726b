"""Fit the effective modulus G and the transition pressure P0 to measured bend angles.

Measured data are (pressure_kpa, angle_deg) pairs, usually one hysteresis loop:
pressure rises in steps, then falls (docs/model.md section 11).
The loading and the unloading branch are fitted separately (:func:`split_branches`),
each by least squares in degrees (``scipy.optimize.least_squares``, trust-region
reflective with bounds), with

* start values from the data: P0 from the onset of bending (and the geometry's P0
  when known), G from a coarse logarithmic scan;
* the covariance of the fitted parameters from the Jacobian at the solution,
  ``cov = inv(J^T J) * s^2`` with ``s^2 = sum(residual^2) / (n - k)`` (k fitted
  parameters), and their standard errors; :mod:`embroact.predict.uncertainty` turns the
  covariance into a band on theta(P);
* RMSE [deg] and the residuals ``model - data`` [deg] per point.

What the data measured: :func:`fit_design` compares them with the whole-strip angle
theta, or, given a :class:`~embroact.predict.markers.MarkerLayout`, with what that
layout's marker sum reads on the model's bend (``reading_deg``: half of theta for the
paper's 7 markers on 100 mm). Fitting marker data to theta instead overestimates G
(77 % for the paper's layout).

Tube laws: P0 from the geometry is the tube law's pressure at r0, for the paper's law
(parameter ``G_e``) or the thick-walled Neo-Hookean tube (parameter ``mu``, fitted under
the name ``g_e_mpa``); both are linear in their modulus, so P0 is proportional to it.
The result records the law and its parameters (``tube_law_parameters``).

Which parameters are fitted is a choice among ``g_mpa``, ``p0_kpa``, ``g_e_mpa``.  The
deformation phase depends on G_e only through P0 = P(r0; G_e) (docs/model.md section 3), so
``g_e_mpa`` can be fitted only when P0 comes from the geometry, never together with
``p0_kpa``.

:func:`fit_curve` fits any predictor ``predict_deg(pressure_kpa, g_mpa, p0_kpa,
g_e_mpa) -> theta_deg``; :func:`fit_design` fits the deformation model of a design
(:func:`embroact.predict.curve.curve`).

Examples
--------
A stand-in predictor, theta = (P - P0) / (2 G) above P0 [deg, with kPa and MPa]:

>>> import numpy as np
>>> from embroact.predict.fit import fit_curve
>>> def predict_deg(p, g, p0, ge):
...     return np.maximum(np.asarray(p) - p0, 0.0) / (2.0 * g)
>>> p = np.arange(0.0, 301.0, 10.0)
>>> r = fit_curve(p, predict_deg(p, 2.0, 85.0, None), predict_deg)
>>> round(r.g_mpa, 6), round(r.p0_kpa, 4), r.rmse_deg < 1e-6
(2.0, 85.0, True)
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Callable, Iterable, Mapping

import numpy as np

from ..patterns.base.arrays import frozen_array
from ..patterns.base.errors import ModelDomainError, ParameterError, SolverError
from ..patterns.base.tolerances import DEFAULT_TOLERANCES
from ..patterns.kinds import pattern_kind
from .calibration import CalibrationPoint
from .derived import DerivedGeometry
from .markers import MarkerLayout, reading_deg
from .status import VALIDITY_LIMITS, Status
from .tubelaws import check_tube_law, transition_pressure_kpa

__all__ = [
    "FIT_PARAMETERS",
    "BRANCH_CHOICES",
    "MIN_BEND_DEG",
    "FitResult",
    "split_branches",
    "closure_gap_deg",
    "fit_curve",
    "fit_design",
    "model_predictor",
]

FIT_PARAMETERS = ("g_mpa", "p0_kpa", "g_e_mpa")
#: ``both`` fits each branch present separately; ``pooled`` fits all points at once.
BRANCH_CHOICES = ("loading", "unloading", "both", "pooled")
_BRANCHES = ("loading", "unloading")

#: Data whose largest |angle| is below this show no deformation phase [deg].
MIN_BEND_DEG = 1.0
#: Pressure steps smaller than this fraction of the data's pressure range are holds (no branch change).
HOLD_FRACTION = 0.01
#: A loop is reported open when its end angle differs from its start by more than this
#: fraction of the largest |angle| (and by more than MIN_BEND_DEG).
CLOSURE_FRACTION = 0.02
#: A point counts as bent for the onset estimate above this fraction of the largest |angle|.
_ONSET_FRACTION = 0.05
#: Decimals a fitted point keeps of its realised coordinates: the needle points' float noise
#: (7.000000000000001 mm) goes, and the rounding (at most half the lookup's tolerance for "the same
#: coordinate", DEFAULT_TOLERANCES.length_mm) keeps a design sewn like the sample on the point.
_KEY_DECIMALS = round(-math.log10(DEFAULT_TOLERANCES.length_mm))
#: Coarse scan of G for the start value [MPa], logarithmic.
_G_SCAN_MPA = (1e-2, 1e3, 31)
#: Candidate-pressure points of the start scan evaluated at once (its curves are ~60 bytes a point).
_SCAN_POINTS = 200_000
#: Scan of G_e when it is fitted without a start value [MPa], logarithmic.
_GE_SCAN_MPA = (1e-3, 10.0, 17)
#: Parameter bounds: G and G_e [MPa]; P0 from 0 to the largest measured pressure [kPa].
_MODULUS_BOUNDS_MPA = (1e-4, 1e5)
#: Relative step of the finite-difference Jacobian: large enough to swamp the model's
#: solver tolerance (~1e-7 deg), small enough for a 3-point truncation error ~1e-8.
_FD_STEP_REL = 1e-4
#: Relative singular-value floor below which the fitted parameters are not identifiable.
_RANK_RTOL = 1e-8
_MAX_NFEV = 400


@dataclass(frozen=True, slots=True)
class FitResult:
    """One fitted branch.

    Attributes
    ----------
    branch : str
        ``"loading"``, ``"unloading"`` or ``"pooled"``.
    fitted : tuple of str
        Names of the fitted parameters (subset of ``FIT_PARAMETERS``).
    g_mpa, p0_kpa : float
        Effective shear modulus [MPa] and transition pressure [kPa] (fitted or fixed).
    g_e_mpa : float or None
        Tube modulus [MPa] used for P0 from geometry, when relevant.
    g_mpa_se, p0_kpa_se, g_e_mpa_se : float or None
        Standard errors of fitted values (P0 from geometry inherits G_e's relative error).
    p0_source : str
        ``"fitted"``, ``"given"``, ``"geometry"`` (:func:`fit_design`) or ``"default"``
        (:func:`fit_curve` left P0 to the predictor).
    rmse_deg : float
        Root-mean-square residual [deg].
    n_points : int
        Data points fitted.
    pressure_kpa, angle_deg, residuals_deg : ndarray (read-only)
        The data fitted and ``model - data`` at the solution [kPa, deg, deg].
    method : str
        Model method the predictions used.
    nfev : int
        Model evaluations by the optimiser.
    design : tuple of (str, float) pairs
        The design fields the sample's needle points realise (pattern, width_mm, angle_deg,
        interval_mm, length_mm), when known: the calibration point's key (:meth:`to_point`).
    covariance : tuple of tuples
        Covariance of the fitted parameters, in the order of ``fitted`` [MPa, kPa units].
    measurement : MarkerLayout or None
        The marker layout the data were compared through; None: whole-strip angle.
    tube_law : str
        Tube law of P0 from geometry and of the inflation states.
    tube_law_parameters : tuple of (str, float) pairs
        That law's parameters: ``outer_radius_mm`` and ``g_e_mpa`` (paper's law) or
        ``outer_radius_mm``, ``inner_radius_mm`` and ``mu_mpa`` (thick wall).
    closure_gap_deg : float or None
        Last minus first measured angle of the data this branch came from, when they
        end at (or below) the pressure they started at; None when the data stop
        higher (the loop is not closed).
    beyond_validity : int
        Data points where the fitted model's state is past a validity limit.
    notes : tuple of str
        Warnings: an open loop, states beyond validity.

    Examples
    --------
    >>> def predict_deg(p, g, p0, ge):  # a stand-in model: theta = (P - P0) / (2 G)
    ...     return np.maximum(np.asarray(p) - p0, 0.0) / (2.0 * g)
    >>> p = np.arange(0.0, 301.0, 10.0)
    >>> r = fit_curve(p, predict_deg(p, 2.0, 85.0, None), predict_deg, branch="loading")
    >>> r.branch, r.fitted, round(r.g_mpa, 6), round(r.p0_kpa, 4), r.n_points
    ('loading', ('g_mpa', 'p0_kpa'), 2.0, 85.0, 31)
    """

    branch: str
    fitted: tuple[str, ...]
    g_mpa: float
    p0_kpa: float | None
    g_e_mpa: float | None
    g_mpa_se: float | None
    p0_kpa_se: float | None
    g_e_mpa_se: float | None
    p0_source: str
    rmse_deg: float
    n_points: int
    pressure_kpa: np.ndarray
    angle_deg: np.ndarray
    residuals_deg: np.ndarray
    method: str
    nfev: int
    design: tuple = ()
    covariance: tuple = ()
    measurement: MarkerLayout | None = None
    tube_law: str = "paper"
    tube_law_parameters: tuple = ()
    closure_gap_deg: float | None = None
    beyond_validity: int = 0
    notes: tuple = ()

    def as_dict(self) -> dict:
        """JSON-ready dict with unit-suffixed keys; arrays as lists.

        Returns
        -------
        dict
            Every field; ``measurement`` is ``"whole-strip"`` or the layout's dict.

        Examples
        --------
        >>> def predict_deg(p, g, p0, ge):  # a stand-in model: theta = (P - P0) / (2 G)
        ...     return np.maximum(np.asarray(p) - p0, 0.0) / (2.0 * g)
        >>> p = np.arange(0.0, 301.0, 10.0)
        >>> r = fit_curve(p, predict_deg(p, 2.0, 85.0, None), predict_deg, branch="loading")
        >>> d = r.as_dict()
        >>> d["fitted"], d["measurement"], len(d["pressure_kpa"])
        (['g_mpa', 'p0_kpa'], 'whole-strip', 31)
        """
        d = {k: getattr(self, k) for k in self.__slots__}
        for k in ("pressure_kpa", "angle_deg", "residuals_deg"):
            d[k] = d[k].tolist()
        d["fitted"] = list(self.fitted)
        d["design"] = dict(self.design)
        d["covariance"] = [list(row) for row in self.covariance]
        d["measurement"] = "whole-strip" if self.measurement is None else self.measurement.as_dict()
        d["tube_law_parameters"] = dict(self.tube_law_parameters)
        d["notes"] = list(self.notes)
        return d

    def to_point(self) -> CalibrationPoint:
        """The fit as a calibration point (needs ``design``, i.e. a :func:`fit_design` result).

        The point keeps the fitted names, their covariance (for uncertainty bands) and the
        tube law's parameters.

        Returns
        -------
        CalibrationPoint

        Raises
        ------
        ParameterError
            The design is unknown (a :func:`fit_curve` result) or P0 is None.

        Examples
        --------
        >>> from embroact.patterns.params import Tube
        >>> from embroact.predict.derived import derive_from_values
        >>> d = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
        >>> p = np.arange(0.0, 301.0, 25.0)
        >>> (r,) = fit_design(d, p, model_predictor(d)(p, 2.7, 85.0, None))
        >>> pt = r.to_point()
        >>> pt.pattern, round(pt.g_mpa, 6), round(pt.p0_kpa, 4), pt.branch
        ('zigzag', 2.7, 85.0, 'loading')
        """
        des = dict(self.design)
        if "pattern" not in des:
            raise ParameterError("to_point needs a fit_design result (design fields unknown)")
        if self.p0_kpa is None:
            raise ParameterError("to_point needs a P0: p0_kpa must be fitted or given, got None")
        return CalibrationPoint(
            pattern=des["pattern"],
            width_mm=des["width_mm"],
            angle_deg=des["angle_deg"],
            interval_mm=des.get("interval_mm"),
            g_mpa=self.g_mpa,
            p0_kpa=self.p0_kpa,
            branch="both" if self.branch == "pooled" else self.branch,
            g_e_mpa=self.g_e_mpa if "g_e_mpa" in self.fitted else None,
            g_mpa_se=self.g_mpa_se,
            p0_kpa_se=self.p0_kpa_se,
            g_e_mpa_se=self.g_e_mpa_se,
            rmse_deg=self.rmse_deg,
            n_points=self.n_points,
            fitted=self.fitted,
            covariance=self.covariance,
            tube_law_parameters=self.tube_law_parameters,
        )


def _as_data(pressure_kpa, angle_deg) -> tuple[np.ndarray, np.ndarray]:
    p = np.asarray(pressure_kpa, dtype=np.float64)
    a = np.asarray(angle_deg, dtype=np.float64)
    if p.ndim != 1 or a.shape != p.shape or p.size == 0:
        raise ParameterError(
            f"pressure_kpa and angle_deg must be 1-D arrays of equal, non-zero length, got shapes {p.shape} and {a.shape}"
        )
    for name, v in (("pressure_kpa", p), ("angle_deg", a)):
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise ParameterError(f"{name}[{bad[0]}] must be a finite number, got {v[bad[0]]!r}")
    neg = np.flatnonzero(p < 0.0)
    if neg.size:
        raise ParameterError(f"pressure_kpa[{neg[0]}] must be >= 0 (gauge pressure), got {p[neg[0]]:g}")
    return p, a


def split_branches(pressure_kpa, angle_deg, labels=None) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Split a pressure loop into its loading and unloading branches.

    Parameters
    ----------
    pressure_kpa, angle_deg : array_like, shape (n,)
        Measurements in the order they were taken.
    labels : sequence of str, optional
        ``"loading"`` / ``"unloading"`` per point.  Without labels each point belongs to
        the branch of the pressure step that led to it: a rise is loading, a fall
        unloading, a hold (a step below ``HOLD_FRACTION`` of the pressure range) keeps the
        previous branch, the first point is loading.  So the top point of a loop is a
        loading point only (it was reached by a rise), repeated cycles pool their
        loading and their unloading points, and a loop that stops before it returns
        (an open loop) has a shorter unloading branch; no point is invented or moved.

    Returns
    -------
    dict
        ``{"loading": (p, a), "unloading": (p, a)}`` with only the non-empty branches.

    Examples
    --------
    >>> br = split_branches([0, 10, 20, 10, 0], [0, 1, 3, 2, 0])
    >>> {k: v[0].tolist() for k, v in br.items()}
    {'loading': [0.0, 10.0, 20.0], 'unloading': [10.0, 0.0]}
    """
    p, a = _as_data(pressure_kpa, angle_deg)
    if labels is not None:
        lab = np.array([str(x).strip().lower() for x in labels])
        if lab.shape != p.shape:
            raise ParameterError(f"branch labels must have one entry per point ({p.size}), got {lab.size}")
        bad = np.flatnonzero(~np.isin(lab, _BRANCHES))
        if bad.size:
            raise ParameterError(f"branch[{bad[0]}] must be one of 'loading', 'unloading', got {labels[bad[0]]!r}")
        return {b: (p[lab == b], a[lab == b]) for b in _BRANCHES if np.any(lab == b)}
    falling = _falling(p)
    return {b: (p[sel], a[sel]) for b, sel in (("loading", ~falling), ("unloading", falling)) if np.any(sel)}


def _falling(p: np.ndarray) -> np.ndarray:
    """True for points reached by a pressure fall (holds keep the previous step's direction)."""
    hold = HOLD_FRACTION * float(np.ptp(p)) if p.size else 0.0
    step = np.diff(p)
    direction = np.where(step > hold, 1, np.where(step < -hold, -1, 0))
    out = np.zeros(p.size, dtype=bool)
    last = 1
    for k, d in enumerate(direction, start=1):
        last = d if d != 0 else last
        out[k] = last < 0
    return out


def closure_gap_deg(pressure_kpa, angle_deg) -> float | None:
    """Last minus first angle of a loop that ends where it started, else None (docs: open loops).

    "Ends where it started": the last pressure is at most the first plus a hold
    (``HOLD_FRACTION`` of the range). A residual bend shows as a non-zero gap.

    Parameters
    ----------
    pressure_kpa, angle_deg : array_like (n,)
        The loop, in measurement order [kPa, deg].

    Returns
    -------
    float or None
        The gap [deg].

    Examples
    --------
    >>> closure_gap_deg([0, 10, 20, 10, 0], [0, 1, 3, 2, 0.5]), closure_gap_deg([0, 20, 10], [0, 3, 2])
    (0.5, None)
    """
    p, a = _as_data(pressure_kpa, angle_deg)
    if p[-1] > p[0] + HOLD_FRACTION * float(np.ptp(p)):
        return None
    return float(a[-1] - a[0])


def _check_fit_names(fit: Iterable[str]) -> tuple[str, ...]:
    names = (fit,) if isinstance(fit, str) else tuple(fit)
    if not names or len(set(names)) != len(names) or not set(names) <= set(FIT_PARAMETERS):
        raise ParameterError(
            f"fit must be a non-empty set of distinct names from {', '.join(map(repr, FIT_PARAMETERS))}, got {names!r}"
        )
    if {"p0_kpa", "g_e_mpa"} <= set(names):
        raise ParameterError(
            "fit cannot contain both 'p0_kpa' and 'g_e_mpa': G_e changes the bend only through P0; "
            "fit g_e_mpa with P0 from the geometry, or fit p0_kpa"
        )
    return tuple(n for n in FIT_PARAMETERS if n in names)


def _onset_kpa(p: np.ndarray, a: np.ndarray) -> tuple[float, float]:
    """(last flat pressure before bending, first bent pressure) [kPa]."""
    bent = np.abs(a) > max(MIN_BEND_DEG, _ONSET_FRACTION * float(np.max(np.abs(a))))
    first_bent = float(np.min(p[bent]))
    flat = p[~bent & (p < first_bent)]
    return (float(np.max(flat)) if flat.size else 0.0), first_bent


def _check_bent(p: np.ndarray, a: np.ndarray, k: int, branch: str) -> None:
    n_bent = int(np.sum(np.abs(a) >= MIN_BEND_DEG))
    if n_bent == 0:
        raise ModelDomainError(
            f"angle_deg: all {a.size} {branch} points bend less than {MIN_BEND_DEG:g} deg "
            f"(up to {float(np.max(p)):g} kPa); no deformation phase to fit G and P0 to"
        )
    if a.size <= k or n_bent < k:
        raise ParameterError(
            f"{branch} data: fitting {k} parameter(s) needs more than {k} points and at least {k} bent "
            f"(>= {MIN_BEND_DEG:g} deg), got {a.size} points, {n_bent} bent"
        )


def _scan(names, start, p, a):
    """Candidate start values per fitted parameter."""
    lo, first = _onset_kpa(p, a)
    grids = {
        "g_mpa": np.geomspace(*_G_SCAN_MPA),
        "p0_kpa": np.unique([lo, 0.5 * (lo + first)]),
        "g_e_mpa": np.geomspace(*_GE_SCAN_MPA),
    }
    for name, value in start.items():
        if name == "p0_kpa":
            grids[name] = np.unique(np.append(grids[name], min(max(value, 0.0), float(np.max(p)))))
        else:
            grids[name] = np.array([value])
    mesh = np.meshgrid(*[grids[n] for n in names], indexing="ij")
    return np.stack([m.ravel() for m in mesh], axis=1)


def _bounds(names, p):
    lo = [0.0 if n == "p0_kpa" else _MODULUS_BOUNDS_MPA[0] for n in names]
    hi = [float(np.max(p)) if n == "p0_kpa" else _MODULUS_BOUNDS_MPA[1] for n in names]
    return np.array(lo), np.array(hi)


def fit_curve(
    pressure_kpa,
    angle_deg,
    predict_deg: Callable,
    *,
    fit: Iterable[str] = ("g_mpa", "p0_kpa"),
    fixed: Mapping[str, float | None] | None = None,
    start: Mapping[str, float | None] | None = None,
    branch: str = "pooled",
    method: str = "callable",
) -> FitResult:
    """Least-squares fit of ``predict_deg`` to one branch of data.

    Parameters
    ----------
    pressure_kpa, angle_deg : array_like, shape (n,)
        Measured pressures [kPa] and signed bend angles [deg].
    predict_deg : callable
        ``predict_deg(pressure_kpa, g_mpa, p0_kpa, g_e_mpa) -> theta_deg``, finite for all
        pressures and parameters within bounds.  Parameters neither fitted nor in
        ``fixed`` are passed as ``None`` (the predictor's default, e.g. P0 from geometry).
        The start-value scan passes fitted parameters as (m, 1) arrays and expects
        (m, n) angles back (numpy broadcasting against the n pressures).
    fit : iterable of str
        Parameters to fit, from ``FIT_PARAMETERS``; not ``p0_kpa`` with ``g_e_mpa``.
    fixed : mapping, optional
        Values of the parameters that are not fitted.
    start : mapping, optional
        Start values; fitted parameters without one are scanned (module docstring).
    branch : str
        Label stored in the result.
    method : str
        Label of the model method stored in the result.

    Returns
    -------
    FitResult

    Raises
    ------
    ModelDomainError
        No point bends by ``MIN_BEND_DEG``, or the parameters are not identifiable.
    ParameterError
        Bad data or parameter names; too few points.
    SolverError
        The optimiser failed.

    Examples
    --------
    >>> def predict_deg(p, g, p0, ge):  # a stand-in model: theta = (P - P0) / (2 G)
    ...     return np.maximum(np.asarray(p) - p0, 0.0) / (2.0 * g)
    >>> p = np.arange(0.0, 301.0, 10.0)
    >>> r = fit_curve(p, predict_deg(p, 2.0, 85.0, None), predict_deg, branch="loading")
    >>> round(r.g_mpa, 6), round(r.p0_kpa, 4), r.rmse_deg < 1e-6
    (2.0, 85.0, True)
    """
    from scipy.optimize import least_squares

    names = _check_fit_names(fit)
    p, a = _as_data(pressure_kpa, angle_deg)
    fixed = dict(fixed or {})
    start = {k: float(v) for k, v in (start or {}).items() if k in names and v is not None}
    _check_bent(p, a, len(names), branch)

    def params(x) -> dict:
        """Fitted values from x, shape (k,) -> floats, or (m, k) -> (m, 1) columns."""
        values = {n: fixed.get(n) for n in FIT_PARAMETERS}
        if np.ndim(x) == 1:
            values.update(zip(names, map(float, x)))
        else:
            values.update((n, x[:, i : i + 1]) for i, n in enumerate(names))
        return values

    def residual(x) -> np.ndarray:
        v = params(x)
        theta = np.asarray(predict_deg(p, v["g_mpa"], v["p0_kpa"], v["g_e_mpa"]), dtype=np.float64)
        return theta - a

    candidates = _scan(names, start, p, a)
    chunk = max(1, _SCAN_POINTS // max(p.size, 1))  # candidates at a time: memory stays bounded with the data
    sse = np.concatenate([np.sum(residual(candidates[k:k + chunk]) ** 2, axis=-1)
                          for k in range(0, len(candidates), chunk)])
    x0 = candidates[int(np.nanargmin(sse))]
    lo, hi = _bounds(names, p)
    x0 = np.clip(x0, lo + _FD_STEP_REL * np.maximum(np.abs(lo), 1.0), hi * (1.0 - _FD_STEP_REL))
    res = least_squares(
        residual, x0, bounds=(lo, hi), jac="3-point", diff_step=_FD_STEP_REL, x_scale="jac", max_nfev=_MAX_NFEV
    )
    if res.status <= 0 or not np.all(np.isfinite(res.fun)):
        raise SolverError(f"least squares did not converge on the {branch} branch after {res.nfev} evaluations: {res.message}")
    cov = _covariance(res.jac, res.fun, names, branch)
    se = {name: float(math.sqrt(max(cov[i, i], 0.0))) for i, name in enumerate(names)}
    values = params(res.x)
    return FitResult(
        branch=branch,
        fitted=names,
        g_mpa=values["g_mpa"],
        p0_kpa=values["p0_kpa"],
        g_e_mpa=values["g_e_mpa"],
        g_mpa_se=se.get("g_mpa"),
        p0_kpa_se=se.get("p0_kpa"),
        g_e_mpa_se=se.get("g_e_mpa"),
        p0_source="fitted" if "p0_kpa" in names else ("given" if fixed.get("p0_kpa") is not None else "default"),
        rmse_deg=float(math.sqrt(np.mean(res.fun**2))),
        n_points=int(p.size),
        pressure_kpa=frozen_array(p),
        angle_deg=frozen_array(a),
        residuals_deg=frozen_array(res.fun),
        method=method,
        nfev=int(res.nfev),
        covariance=tuple(tuple(float(v) for v in row) for row in cov),
    )


def _covariance(jac, fun, names, branch) -> np.ndarray:
    """inv(J^T J) * s^2, via the SVD of J; refuse rank-deficient fits."""
    n, k = jac.shape
    _, sv, vt = np.linalg.svd(np.asarray(jac, dtype=np.float64), full_matrices=False)
    if sv.size < k or sv[-1] <= _RANK_RTOL * sv[0]:
        raise ModelDomainError(
            f"{branch} data do not determine {', '.join(names)} independently "
            f"(Jacobian condition {sv[0] / max(sv[-1], 1e-300):.3g}); fit fewer parameters"
        )
    s2 = float(np.sum(fun**2)) / (n - k)
    cov = (vt.T / sv**2) @ vt * s2
    return 0.5 * (cov + cov.T)  # symmetric exactly (the product is only to round-off)


def model_predictor(derived: DerivedGeometry, *, method: str = "auto", measurement: MarkerLayout | None = None,
                    tube_law: str = "paper") -> Callable:
    """``predict_deg(pressure_kpa, g_mpa, p0_kpa, g_e_mpa)`` for a design, via the model.

    ``p0_kpa=None`` means P0 from the geometry with tube modulus ``g_e_mpa`` (the
    design's tube when that is ``None`` too) under ``tube_law``.  Scalar parameters give
    one curve (:func:`~embroact.predict.curve.curve`); parameter arrays of shape (m, 1)
    give m curves at once (:func:`~embroact.predict.curve.sweep`), shape (m, n).  With a
    ``measurement`` layout the angles are what its marker sum reads
    (:func:`~embroact.predict.markers.reading_deg`), else theta.  The function's
    attributes ``last_method`` and ``last_status`` are the method and the statuses of
    its latest call.

    Parameters
    ----------
    derived : DerivedGeometry
        The design.
    method : str, optional
        Model method.
    measurement : MarkerLayout or None, optional
        The layout whose reading the data are; None: theta.
    tube_law : str, optional
        The tube law of P0 from geometry.

    Returns
    -------
    callable

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> from embroact.predict.derived import derive_from_values
    >>> d = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
    >>> p = np.arange(0.0, 301.0, 25.0)
    >>> f = model_predictor(d)
    >>> f(np.array([100.0, 200.0]), 2.7, 85.0, None).round(3).tolist(), f.last_method
    ([11.539, 102.93], 'stable-analytic-trace')
    """
    from .curve import ActuatorModel, sweep

    check_tube_law(tube_law)

    def predict_deg(pressure_kpa, g_mpa, p0_kpa, g_e_mpa):
        g_e = derived.tube.g_e_mpa if g_e_mpa is None else g_e_mpa
        p0 = _geometry_p0_kpa(derived, g_e, tube_law) if p0_kpa is None else p0_kpa
        batch = np.ndim(g_mpa) + np.ndim(p0) > 0
        g_col, p0_col = np.broadcast_arrays(np.ravel(g_mpa), np.ravel(p0))
        models = [
            ActuatorModel.from_derived(derived, g_mpa=float(g), p0_kpa=float(q), calibration="fit", tube_law=tube_law)
            for g, q in zip(g_col, p0_col)
        ]
        c = sweep(models, pressure_kpa, method=method)
        predict_deg.last_method, predict_deg.last_status = c.method, c.status
        theta = _theta_of(c)
        if measurement is not None:
            theta = reading_deg(theta, derived.length_mm, measurement)
        return theta if batch else theta[0]

    predict_deg.last_method, predict_deg.last_status = method, None  # type: ignore[attr-defined]
    return predict_deg


def _theta_of(c) -> np.ndarray:
    """Curve angles; locked, unstable and out-of-domain points carry ``curve``'s fill values
    (lock-up angle, fold angle, domain end), which keep the residuals finite and pull the
    optimiser back into the model's domain.  A method failure is an error, not data."""
    failed = np.flatnonzero(np.asarray(c.status) == Status.FAILED)
    if failed.size:
        raise SolverError(
            f"model method {c.method!r} failed at pressure_kpa={float(np.ravel(c.pressure_kpa)[failed[0]]):g} during the fit"
        )
    return np.asarray(c.theta_deg, dtype=np.float64)


def _geometry_p0_kpa(derived: DerivedGeometry, g_e_mpa, tube_law: str = "paper"):
    t = derived.tube
    tube = tuple(np.broadcast_arrays(np.float64(t.outer_radius_mm), np.float64(t.inner_radius_mm),
                                     np.asarray(g_e_mpa, dtype=np.float64)))
    return transition_pressure_kpa(derived.r0_mm, tube, tube_law)


def _design_fields(derived: DerivedGeometry) -> tuple:
    """The design parameters its needle points realise: a fitted point is keyed by them (see calibration.py),
    to :data:`_KEY_DECIMALS` decimals."""
    return (
        ("pattern", derived.pattern),
        ("width_mm", round(derived.width_mm, _KEY_DECIMALS)),
        ("angle_deg", round(derived.angle_deg, _KEY_DECIMALS) if pattern_kind(derived.pattern).has_angle else 0.0),
        ("interval_mm", round(derived.interval_mm, _KEY_DECIMALS)),
        ("length_mm", derived.length_mm),
    )


def _check_direction(derived: DerivedGeometry, a: np.ndarray) -> None:
    big = a[np.abs(a) >= MIN_BEND_DEG]
    if big.size and (np.median(big) > 0) != derived.bends_positive:
        want = "positive" if derived.bends_positive else "negative"
        raise ParameterError(
            f"angle_deg: the data bend {'positive' if np.median(big) > 0 else 'negative'} but this "
            f"{derived.pattern} design bends {want} (theta > 0: thread side longer, docs/model.md section 5); "
            "check the sign of the measured angles or the design"
        )


def fit_design(
    derived: DerivedGeometry,
    pressure_kpa,
    angle_deg,
    *,
    fit: Iterable[str] = ("g_mpa", "p0_kpa"),
    branch: str = "both",
    labels=None,
    g_mpa: float | None = None,
    p0_kpa: float | None = None,
    g_e_mpa: float | None = None,
    method: str = "auto",
    measurement: MarkerLayout | None = None,
    tube_law: str = "paper",
) -> tuple[FitResult, ...]:
    """Fit the deformation model of one design to measured data, per branch.

    Parameters
    ----------
    derived : DerivedGeometry
        The design (``embroact.predict.derived.derive`` or ``derive_from_values``).
    pressure_kpa, angle_deg : array_like, shape (n,)
        Measurements in the order taken [kPa, deg]; angles signed as docs/model.md section 5.
    fit : iterable of str
        Parameters to fit (``FIT_PARAMETERS``).
    branch : str
        ``"loading"``, ``"unloading"``, ``"both"`` (each branch present, separately) or
        ``"pooled"`` (all points in one fit).
    labels : sequence of str, optional
        Branch label per point (otherwise by the direction of each pressure step,
        :func:`split_branches`).
    g_mpa, p0_kpa, g_e_mpa : float, optional
        Fixed values of parameters that are not fitted; without ``p0_kpa`` P0 comes from
        the geometry and ``g_e_mpa`` (default: the design's tube) under ``tube_law``.
        Also used as start values of fitted ones.
    method : str
        Model method passed to ``curve``.
    measurement : MarkerLayout, optional
        How the angles were measured: a marker layout (the data are compared with its
        reading of the model's bend), or None for the whole-strip angle theta.
    tube_law : str
        ``"paper"`` or ``"thick-wall"`` (its ``mu`` is fitted as ``g_e_mpa``).

    Returns
    -------
    tuple of FitResult
        One per fitted branch, loading first.

    Examples
    --------
    Marker sums of the paper's layout read half the bend of a 100 mm strip; fitted as
    such, they give the model's parameters back:

    >>> import numpy as np
    >>> from embroact.patterns.params import Tube
    >>> from embroact.predict.curve import ActuatorModel, curve
    >>> from embroact.predict.derived import derive_from_values
    >>> from embroact.predict.markers import PAPER_LAYOUT, reading_deg
    >>> d = derive_from_values("zigzag", width_mm=7, interval_mm=1, angle_deg=0, length_mm=100, tube=Tube())
    >>> p = np.arange(0.0, 301.0, 10.0)
    >>> seen = reading_deg(curve(ActuatorModel.from_derived(d, g_mpa=2.7, p0_kpa=85.0), p).theta_deg, 100.0)
    >>> (r,) = fit_design(d, p, seen, branch="loading", measurement=PAPER_LAYOUT)
    >>> round(r.g_mpa, 6), round(r.p0_kpa, 4), r.measurement.markers_per_side
    (2.7, 85.0, 7)
    """
    if branch not in BRANCH_CHOICES:
        raise ParameterError(f"branch must be one of {', '.join(map(repr, BRANCH_CHOICES))}, got {branch!r}")
    if measurement is not None and not isinstance(measurement, MarkerLayout):
        raise ParameterError(f"measurement must be a MarkerLayout or None (whole-strip angle), got {measurement!r}")
    if measurement is not None and measurement.offset_mm >= derived.length_mm:
        raise ParameterError(f"marker offset_mm must be below the bent length l0 = {derived.length_mm:.4g} mm "
                             f"(markers beyond it lie on the straight end and read no bend), got {measurement.offset_mm:g}")
    check_tube_law(tube_law)
    names = _check_fit_names(fit)
    if "g_mpa" not in names and g_mpa is None:
        raise ParameterError("g_mpa must be given when it is not fitted, got None")
    p, a = _as_data(pressure_kpa, angle_deg)
    _check_direction(derived, a)
    if branch == "pooled":
        parts = {"pooled": (p, a)}
    else:
        parts = split_branches(p, a, labels)
        if branch != "both":
            if branch not in parts:
                raise ParameterError(f"branch {branch!r} has no points in these data (found: {', '.join(parts)})")
            parts = {branch: parts[branch]}
    predictor = model_predictor(derived, method=method, measurement=measurement, tube_law=tube_law)
    fixed = {"g_mpa": g_mpa, "p0_kpa": p0_kpa, "g_e_mpa": g_e_mpa}
    start = dict(fixed)
    if "p0_kpa" in names and p0_kpa is None:
        start["p0_kpa"] = float(_geometry_p0_kpa(derived, derived.tube.g_e_mpa, tube_law))
    if "g_e_mpa" in names and g_e_mpa is None:
        # P0 is proportional to the law's modulus: start where the geometry's P0 meets the data's onset
        lo, first = _onset_kpa(p, a)
        geo = float(_geometry_p0_kpa(derived, 1.0, tube_law))
        start["g_e_mpa"] = 0.5 * (lo + first) / geo if geo > 0 else derived.tube.g_e_mpa
    context = {"measurement": measurement, "tube_law": tube_law, "closure_gap_deg": closure_gap_deg(p, a)}
    results = []
    for name, (pb, ab) in parts.items():
        r = fit_curve(pb, ab, predictor, fit=names, fixed=fixed, start=start, branch=name, method=method)
        predictor(pb, r.g_mpa, r.p0_kpa, r.g_e_mpa)  # method and statuses at the solution
        results.append(_complete(r, derived, p0_kpa, predictor, context, float(np.max(np.abs(a)))))
    return tuple(results)


def _tube_law_parameters(derived: DerivedGeometry, tube_law: str, g_e: float) -> tuple:
    t = derived.tube
    if tube_law == "thick-wall":
        return (("outer_radius_mm", t.outer_radius_mm), ("inner_radius_mm", t.inner_radius_mm), ("mu_mpa", g_e))
    return (("outer_radius_mm", t.outer_radius_mm), ("g_e_mpa", g_e))


def _complete(r: FitResult, derived: DerivedGeometry, p0_given: float | None, predictor, context: dict,
              largest_deg: float) -> FitResult:
    """Fill in P0 from geometry (with its error from G_e's), the method, design, tube law and notes."""
    law = context["tube_law"]
    g_e = derived.tube.g_e_mpa if r.g_e_mpa is None else r.g_e_mpa
    beyond = int(np.count_nonzero(np.isin(predictor.last_status, [int(s) for s in VALIDITY_LIMITS])))
    gap = context["closure_gap_deg"]
    notes = []
    if gap is None:
        notes.append("the loop is not closed: the data end above the pressure they started at")
    elif abs(gap) > max(MIN_BEND_DEG, CLOSURE_FRACTION * largest_deg):
        notes.append(f"the loop does not close: it ends {gap:+.3g} deg from where it started (residual bend); "
                     "the branches are fitted as measured")
    if beyond:
        notes.append(f"{beyond} of {r.n_points} points need model states beyond its validity limits "
                     "(coiled, kinked or over-stretched): the fitted values describe the formula, not a real sleeve")
    changes: dict = {"method": predictor.last_method, "design": _design_fields(derived), "tube_law": law,
                     "tube_law_parameters": _tube_law_parameters(derived, law, g_e), "beyond_validity": beyond,
                     "measurement": context["measurement"], "closure_gap_deg": gap, "notes": tuple(notes)}
    if "p0_kpa" not in r.fitted:
        changes["g_e_mpa"] = g_e
        if p0_given is None:
            p0 = float(_geometry_p0_kpa(derived, g_e, law))
            changes["p0_kpa"] = p0
            changes["p0_source"] = "geometry"
            if r.g_e_mpa_se is not None:  # P0 is proportional to the law's modulus
                changes["p0_kpa_se"] = p0 * r.g_e_mpa_se / g_e
    return dataclasses.replace(r, **changes)
