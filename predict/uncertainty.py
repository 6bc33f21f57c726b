"""Uncertainty bands: a fitted calibration's covariance propagated to theta(P).

A fit (:mod:`embroact.predict.fit`) gives the covariance ``C`` of its parameters
(``g_mpa``, ``p0_kpa`` or ``g_e_mpa``). At a fixed pressure the equilibrium angle moves
with them as (linearisation, derivatives from the model itself)::

    P(theta) = P0 + G f(theta)          (the energy is proportional to G)
    d theta / d P0  = -1 / P'(theta)
    d theta / d G   = -(P - P0) / (G P'(theta))
    d theta / d G_e = (d theta / d P0) * P0 / G_e    (P0 from the tube law, linear in its modulus)

with ``P'(theta)`` the slope of the model's P(theta) at the solution (a central
difference of :func:`~embroact.predict.curve.pressure_at`). The variance of theta is
``J C J^T``, its square root the 1-sigma half-width of the band. A marker reading
(:func:`~embroact.predict.markers.reading_deg`) gets its band through its own slope,
``d reading / d theta``. ``noise_sd_deg`` (a fit's residual scatter, in the measured
quantity: theta, or the reading when there is a layout) gives the prediction band for
new measurements, :meth:`Band.prediction_sd_deg`.

Points that are not equilibria of the formula (inflation: theta = 0 does not move;
lock-up, fold, domain end, failed: fill values) get a zero half-width; equilibria past
a validity limit keep theirs (the formula's), with their validity status.

Examples
--------
>>> from embroact.predict.curve import ActuatorModel
>>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0, outer_radius_mm=1.5,
...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
>>> b = theta_band(m, [50, 200], ("g_mpa", "p0_kpa"), ((0.01, 0.0), (0.0, 4.0)))
>>> float(b.theta_sd_deg[0]), round(float(b.theta_deg[1]), 3), round(float(b.theta_sd_deg[1]), 3)
(0.0, 102.93, 5.033)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..patterns.base.arrays import frozen_array
from ..patterns.base.errors import ParameterError
from .markers import MarkerLayout, reading_deg
from .status import Status
from .validity import apply_limits

__all__ = ["BAND_PARAMETERS", "Band", "theta_band", "fit_band"]

BAND_PARAMETERS = ("g_mpa", "p0_kpa", "g_e_mpa")
#: Central-difference step of P(theta) and reading(theta) [deg] (P is smooth: ~1e-8 relative).
_STEP_DEG = 1e-4


@dataclass(frozen=True, slots=True)
class Band:
    """A 1-sigma band on theta(P) (and on a marker reading), read-only arrays per pressure.

    Attributes
    ----------
    pressure_kpa, theta_deg, theta_sd_deg : ndarray
        Pressures [kPa], the model's angle and its standard deviation [deg].
    theta_low_deg, theta_high_deg : ndarray
        ``theta -+ sd``: the 1-sigma confidence band of the curve, its edge toward zero held at
        zero (no G or P0 turns a bend to the other side: a later P0 only keeps the strip straight).
    status : ndarray of int8
        The curve's statuses (the band means something where the state does).
    reading_deg, reading_sd_deg : ndarray or None
        The marker reading and its standard deviation, when a layout was given.
    parameters : tuple of str
        Parameters of the covariance, in its order.
    covariance : tuple of tuples
        Their covariance [MPa, kPa units].
    noise_sd_deg : float
        Measurement scatter of the measured quantity (the reading with a layout, else theta).

    Examples
    --------
    >>> from embroact.predict.curve import ActuatorModel
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0, outer_radius_mm=1.5,
    ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
    >>> b = theta_band(m, [50, 200], ("g_mpa", "p0_kpa"), ((0.01, 0.0), (0.0, 4.0)), noise_sd_deg=2.0)
    >>> b.theta_deg.round(3).tolist(), b.theta_low_deg.round(3).tolist(), b.reading_deg is None
    ([0.0, 102.93], [0.0, 97.897], True)
    """

    pressure_kpa: np.ndarray
    theta_deg: np.ndarray
    theta_sd_deg: np.ndarray
    theta_low_deg: np.ndarray
    theta_high_deg: np.ndarray
    status: np.ndarray
    reading_deg: np.ndarray | None
    reading_sd_deg: np.ndarray | None
    parameters: tuple
    covariance: tuple
    noise_sd_deg: float

    def as_dict(self) -> dict:
        """JSON-ready dict (lists; status names); ``reading_*`` None without a layout.

        Returns
        -------
        dict
            Every field, and ``prediction_sd_deg``.

        Examples
        --------
        >>> from embroact.predict.curve import ActuatorModel
        >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0, outer_radius_mm=1.5,
        ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
        >>> b = theta_band(m, [50, 200], ("g_mpa", "p0_kpa"), ((0.01, 0.0), (0.0, 4.0)), noise_sd_deg=2.0)
        >>> b.as_dict()["status"], b.as_dict()["prediction_sd_deg"][0]
        (['INFLATION', 'BENDING'], 2.0)
        """
        from .status import status_names

        out = {k: (getattr(self, k).tolist() if isinstance(getattr(self, k), np.ndarray) else getattr(self, k))
               for k in self.__slots__}
        out["status"] = status_names(self.status)
        out["parameters"] = list(self.parameters)
        out["covariance"] = [list(row) for row in self.covariance]
        out["prediction_sd_deg"] = self.prediction_sd_deg().tolist()
        return out

    def summary(self) -> dict:
        """The band per point as ``predict --json`` and ``report.json`` quote it: ``theta_sd_deg``,
        ``theta_low_deg``, ``theta_high_deg`` (lists), ``parameters`` and ``covariance``; with a
        layout also ``reading_sd_deg``.

        Returns
        -------
        dict

        Examples
        --------
        >>> from embroact.predict.curve import ActuatorModel
        >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0, outer_radius_mm=1.5,
        ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
        >>> b = theta_band(m, [50, 200], ("g_mpa", "p0_kpa"), ((0.01, 0.0), (0.0, 4.0)), noise_sd_deg=2.0)
        >>> sorted(b.summary())
        ['covariance', 'parameters', 'theta_high_deg', 'theta_low_deg', 'theta_sd_deg']
        """
        out = {"theta_sd_deg": self.theta_sd_deg.tolist(), "theta_low_deg": self.theta_low_deg.tolist(),
               "theta_high_deg": self.theta_high_deg.tolist(), "parameters": list(self.parameters),
               "covariance": [list(row) for row in self.covariance]}
        if self.reading_sd_deg is not None:
            out["reading_sd_deg"] = self.reading_sd_deg.tolist()
        return out

    def prediction_sd_deg(self) -> np.ndarray:
        """Scatter of a new measurement about the model: sqrt(sd^2 + noise^2) of the measured quantity.

        Returns
        -------
        numpy.ndarray
            [deg], per pressure.

        Examples
        --------
        >>> from embroact.predict.curve import ActuatorModel
        >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0, outer_radius_mm=1.5,
        ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
        >>> b = theta_band(m, [50, 200], ("g_mpa", "p0_kpa"), ((0.01, 0.0), (0.0, 4.0)), noise_sd_deg=2.0)
        >>> b.prediction_sd_deg().round(3).tolist()
        [2.0, 5.416]
        """
        sd = self.theta_sd_deg if self.reading_sd_deg is None else self.reading_sd_deg
        return np.sqrt(sd**2 + self.noise_sd_deg**2)


def _check_covariance(parameters, covariance) -> tuple[tuple[str, ...], np.ndarray]:
    names = (parameters,) if isinstance(parameters, str) else tuple(parameters)
    if not names or len(set(names)) != len(names) or not set(names) <= set(BAND_PARAMETERS):
        raise ParameterError(f"parameters must be distinct names from {', '.join(BAND_PARAMETERS)}, got {names!r}")
    if {"p0_kpa", "g_e_mpa"} <= set(names):
        raise ParameterError("parameters cannot hold both p0_kpa and g_e_mpa (G_e acts only through P0)")
    c = np.asarray(covariance, dtype=np.float64)
    k = len(names)
    if c.shape != (k, k) or not np.all(np.isfinite(c)) or not np.allclose(c, c.T, rtol=1e-9, atol=0.0):
        raise ParameterError(f"covariance must be a finite symmetric {k} x {k} matrix for {names!r}, got shape {c.shape}")
    if not is_positive_semidefinite(c):
        raise ParameterError("covariance must be positive semi-definite")
    return names, c


def is_positive_semidefinite(covariance) -> bool:
    """True when the finite symmetric matrix ``covariance`` has no eigenvalue below -1e-12 of its largest entry.

    Parameters
    ----------
    covariance : array_like (k, k)
        A finite symmetric matrix.

    Returns
    -------
    bool

    Examples
    --------
    >>> is_positive_semidefinite([[1.0, 0.5], [0.5, 1.0]]), is_positive_semidefinite([[1.0, 2.0], [2.0, 1.0]])
    (True, False)
    """
    c = np.asarray(covariance, dtype=np.float64)
    return not np.any(np.linalg.eigvalsh(c) < -1e-12 * max(float(np.max(np.abs(c))), 1e-300))


def _slope(fn, x):
    """Central difference of fn at x [per degree]."""
    h = _STEP_DEG * np.maximum(1.0, np.abs(x) * 1e-3)
    return (fn(x + h) - fn(x - h)) / (2.0 * h)


def theta_band(model, pressures_kpa, parameters, covariance, *, measurement: MarkerLayout | None = None,
               noise_sd_deg: float = 0.0, method: str = "auto") -> Band:
    """The 1-sigma band of theta(P) for a model whose parameters have a covariance.

    Parameters
    ----------
    model : ActuatorModel
        The fitted model (its G and P0 at the solution).
    pressures_kpa : array_like
        Pressures [kPa].
    parameters : sequence of str
        Names of the covariance's rows, from ``BAND_PARAMETERS``; ``g_e_mpa`` means P0 from
        the tube law (proportional to it).
    covariance : array_like, shape (k, k)
        Covariance in MPa and kPa units (a :class:`~embroact.predict.fit.FitResult`'s).
    measurement : MarkerLayout, optional
        Also give the band of that layout's marker reading.
    noise_sd_deg : float
        Measurement scatter to add (prediction band), >= 0.
    method : str
        Model method.

    Returns
    -------
    Band

    Examples
    --------
    >>> from embroact.predict.curve import ActuatorModel
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0, outer_radius_mm=1.5,
    ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
    >>> b = theta_band(m, [50, 200], ("g_mpa", "p0_kpa"), ((0.01, 0.0), (0.0, 4.0)), noise_sd_deg=2.0)
    >>> b.theta_sd_deg.round(3).tolist(), b.noise_sd_deg
    ([0.0, 5.033], 2.0)
    """
    from .curve import curve, pressure_at

    names, cov = _check_covariance(parameters, covariance)
    noise = float(noise_sd_deg)
    if not np.isfinite(noise) or noise < 0.0:
        raise ParameterError(f"noise_sd_deg must be a finite number >= 0, got {noise_sd_deg!r}")
    c = curve(model, pressures_kpa, method=method, limits=False)
    theta = np.asarray(c.theta_deg)
    equilibrium = c.status == Status.BENDING  # of the formula, also past a validity limit
    status = apply_limits(c.status, np.radians(theta), c.length_mm, c.radius_mm, model.length_mm,
                          stub_mm=model.stub_mm)

    def p_of(t):
        return np.asarray(pressure_at(model, t, method=method, limits=False).pressure_kpa)

    slope = np.ones_like(theta)  # kPa per degree
    if equilibrium.any():
        slope[equilibrium] = _slope(p_of, theta[equilibrium])
    excess = np.asarray(c.pressure_kpa) - model.p0_kpa
    d_p0 = np.where(equilibrium, -1.0 / slope, 0.0)
    columns = {"p0_kpa": d_p0, "g_mpa": d_p0 * excess / model.g_mpa, "g_e_mpa": d_p0 * model.p0_kpa / model.g_e_mpa}
    jac = np.stack([columns[n] for n in names], axis=-1)  # (points, k) [deg per unit]
    sd = np.sqrt(np.maximum(np.einsum("pi,ij,pj->p", jac, cov, jac), 0.0))
    reading = reading_sd = None
    if measurement is not None:
        reading = reading_deg(theta, model.length_mm, measurement)
        gain = _slope(lambda t: reading_deg(t, model.length_mm, measurement), theta)
        reading_sd = frozen_array(np.abs(gain) * sd)
        reading = frozen_array(reading)
    low = np.where(theta > 0.0, np.maximum(theta - sd, 0.0), theta - sd)
    high = np.where(theta < 0.0, np.minimum(theta + sd, 0.0), theta + sd)
    return Band(pressure_kpa=frozen_array(c.pressure_kpa), theta_deg=frozen_array(theta),
                theta_sd_deg=frozen_array(sd), theta_low_deg=frozen_array(low),
                theta_high_deg=frozen_array(high), status=frozen_array(status, dtype=None), reading_deg=reading,
                reading_sd_deg=reading_sd, parameters=names,
                covariance=tuple(tuple(float(v) for v in row) for row in cov), noise_sd_deg=noise)


def fit_band(derived, result, pressures_kpa, *, prediction: bool = False, method: str = "auto") -> Band:
    """The band of a :func:`~embroact.predict.fit.fit_design` result at ``pressures_kpa``.

    Uses the result's parameters, covariance, tube law and measurement (the reading's
    band comes with it). ``prediction=True`` adds the fit's residual scatter
    ``rmse * sqrt(n / (n - k))`` (a band for new measurements).

    Parameters
    ----------
    derived : DerivedGeometry
        The design the data were measured on.
    result : FitResult
        Its fit, with a covariance.
    pressures_kpa : array_like
        Pressures [kPa].
    prediction : bool, optional
        Add the residual scatter.
    method : str, optional
        Model method.

    Returns
    -------
    Band

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> from embroact.predict.derived import derive_from_values
    >>> from embroact.predict.fit import fit_design, model_predictor
    >>> d = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
    >>> p = np.arange(0.0, 301.0, 25.0)
    >>> (r,) = fit_design(d, p, model_predictor(d)(p, 2.7, 85.0, None) + np.sin(p))  # scattered data
    >>> fit_band(d, r, [100.0, 200.0]).theta_sd_deg.round(3).tolist()
    [0.085, 0.055]
    """
    import dataclasses

    from .curve import ActuatorModel

    if not result.covariance:
        raise ParameterError("the fit result has no covariance (fit with embroact.predict.fit)")
    model = ActuatorModel.from_derived(derived, g_mpa=result.g_mpa, p0_kpa=result.p0_kpa, calibration="fit",
                                       tube_law=result.tube_law)
    modulus = dict(result.tube_law_parameters).get("mu_mpa" if result.tube_law == "thick-wall" else "g_e_mpa")
    if modulus is not None:  # the fitted tube modulus (P0 from geometry moves with it)
        model = dataclasses.replace(model, g_e_mpa=modulus)
    k = len(result.fitted)
    noise = result.rmse_deg * np.sqrt(result.n_points / (result.n_points - k)) if prediction else 0.0
    return theta_band(model, pressures_kpa, result.fitted, result.covariance, measurement=result.measurement,
                      noise_sd_deg=float(noise), method=method)
