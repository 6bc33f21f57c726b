"""Tube laws of the inflation phase (docs/model.md section 3): pressure <-> outer radius.

``"paper"``
    The paper's fitted law ``P = (G_e/2)((r/r_f)^2 + (r_f/r)^2 - 2)`` (see
    :mod:`embroact.predict.inflation`), the default: it reproduces the paper's P0.
``"thick-wall"``
    The exact thick-walled Neo-Hookean tube in plane strain (no axial stretch),
    ``P = mu (ln(la/lb) + (lb^-2 - la^-2)/2)`` with outer hoop stretch ``lb = r/r_f``,
    inner ``la = a/d_f`` and ``a^2 = r^2 - (r_f^2 - d_f^2)`` (incompressible wall);
    ``mu = G_e``. It rises monotonically to ``mu ln(r_f/d_f)`` as ``r -> inf``
    (pressures at or above that inflate the tube without bound) and needs a hollow
    tube, ``d_f > 0``. Its inverse is solved by bisection in ``t = (r_f/r)^2``.

Examples
--------
>>> from embroact.patterns.params import Tube
>>> from embroact.predict.tubelaws import pressure_kpa, radius_mm
>>> round(float(pressure_kpa(2.5814, Tube(), "thick-wall")), 3)
49.148
>>> round(float(radius_mm(49.148, Tube(), "thick-wall")), 4)
2.5814
>>> round(float(pressure_kpa(2.5814, Tube(), "paper")), 2)
84.45
"""
from __future__ import annotations

import numpy as np

from ..patterns.base.errors import ModelDomainError, ParameterError
from .inflation import KPA_PER_MPA, paper_pressure_kpa, paper_radius_mm
from .solvers import bisect

__all__ = ["TUBE_LAWS", "check_tube_law", "pressure_kpa", "radius_mm", "transition_pressure_kpa", "thick_wall_limit_kpa"]

TUBE_LAWS = ("paper", "thick-wall")
#: Bisection steps of the thick-wall inverse (t in (0, 1] to the last float64 bit).
THICK_WALL_BISECTIONS = 200


def check_tube_law(law: str) -> None:
    """Raise :class:`ParameterError` unless ``law`` is one of :data:`TUBE_LAWS`.

    Parameters
    ----------
    law : str

    Examples
    --------
    >>> check_tube_law("thick-wall")
    >>> try:
    ...     check_tube_law("thin")
    ... except ValueError as exc:
    ...     print(exc)
    tube_law must be one of paper, thick-wall, got 'thin'
    """
    if law not in TUBE_LAWS:
        raise ParameterError(f"tube_law must be one of {', '.join(TUBE_LAWS)}, got {law!r}")


def _thick_wall_mpa(t, rf, df, mu):
    """Thick-wall law with t = (r_f/r)^2 = lb^-2 in (0, 1]."""
    c = rf * rf - df * df
    # la^-2 = d_f^2 / (r^2 - c) = d_f^2 t / (r_f^2 - c t)
    la_m2 = df * df * t / (rf * rf - c * t)
    return mu * (0.5 * np.log(t / la_m2) + 0.5 * (t - la_m2))


def _tube_arrays(tube_or_arrays):
    """(r_f, d_f, G_e) from a Tube or a tuple of arrays."""
    if isinstance(tube_or_arrays, tuple):
        return tuple(np.asarray(v, dtype=np.float64) for v in tube_or_arrays)
    t = tube_or_arrays
    return (np.float64(t.outer_radius_mm), np.float64(t.inner_radius_mm), np.float64(t.g_e_mpa))


def thick_wall_limit_kpa(tube) -> np.ndarray:
    """Highest pressure the thick-walled tube resists, mu ln(r_f/d_f) [kPa] (inf if d_f = 0).

    Parameters
    ----------
    tube : Tube or tuple of arrays
        ``(outer_radius_mm, inner_radius_mm, g_e_mpa)`` as arrays, or a Tube.

    Returns
    -------
    ndarray

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> round(float(thick_wall_limit_kpa(Tube())), 3)   # 0.13 MPa ln(1.5)
    52.71
    """
    rf, df, mu = _tube_arrays(tube)
    with np.errstate(divide="ignore"):
        return mu * np.log(rf / df) * KPA_PER_MPA


def pressure_kpa(radius_mm, tube, law: str = "paper"):
    """Pressure [kPa] that inflates the free tube to outer radius ``radius_mm`` >= r_f.

    Parameters
    ----------
    radius_mm : float or array
        Outer radius [mm].
    tube : Tube or tuple of arrays
        A :class:`~embroact.patterns.params.Tube` or ``(outer_radius_mm, inner_radius_mm, g_e_mpa)``.
    law : {"paper", "thick-wall"}

    Returns
    -------
    ndarray
        [kPa].

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> round(float(pressure_kpa(2.5814, Tube(), "paper")), 2)
    84.45
    """
    check_tube_law(law)
    rf, df, mu = _tube_arrays(tube)
    r = np.asarray(radius_mm, dtype=np.float64)
    if law == "paper":
        return paper_pressure_kpa(r, rf, mu)
    if np.any(df <= 0.0):
        raise ModelDomainError("tube_law 'thick-wall' needs a hollow tube: inner_radius_mm must be > 0")
    return _thick_wall_mpa((rf / r) ** 2, rf, df, mu) * KPA_PER_MPA


def radius_mm(pressure_kpa, tube, law: str = "paper"):
    """Outer radius [mm] of the free tube at ``pressure_kpa`` >= 0 (inverse of the law).

    Parameters
    ----------
    pressure_kpa : float or array
        [kPa], >= 0.
    tube : Tube or tuple of arrays
    law : {"paper", "thick-wall"}

    Returns
    -------
    ndarray
        [mm].

    Raises
    ------
    ModelDomainError
        The thick-wall law at or above its limit.

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> round(float(radius_mm(84.455, Tube(), "paper")), 4)
    2.5814
    """
    check_tube_law(law)
    rf, df, mu = _tube_arrays(tube)
    p = np.asarray(pressure_kpa, dtype=np.float64)
    if law == "paper":
        return paper_radius_mm(p, rf, mu)
    limit = thick_wall_limit_kpa((rf, df, mu))
    if np.any(p >= limit):
        raise ModelDomainError(
            f"pressure_kpa must be below the thick-wall tube's limit mu*ln(r_f/d_f) = {float(np.min(limit)):.6g}, "
            f"got {float(np.max(p)):.6g}"
        )
    target = np.maximum(p, 0.0) / KPA_PER_MPA
    shape = np.broadcast(p, rf, df, mu).shape
    # P decreases in t = (r_f/r)^2; "inside" = P(t) >= target, i.e. t small enough
    t = bisect(lambda t: _thick_wall_mpa(t, rf, df, mu) <= target, np.ones(shape),
               np.zeros(shape), THICK_WALL_BISECTIONS)
    return rf / np.sqrt(t)


def transition_pressure_kpa(r0_mm, tube, law: str = "paper"):
    """P0 [kPa]: the tube law's pressure at the sleeve radius r0; 0 if r0 <= r_f.

    The one tube-law P0 of embroact: the model factory (``p0_source = "geometry"``), the
    fit's start and fixed values, the rules' notes, the worksheet and the studio all read it
    through here, with the tube law in force.

    Parameters
    ----------
    r0_mm : float or array
        Sleeve radius [mm].
    tube : Tube or tuple of arrays
    law : {"paper", "thick-wall"}

    Returns
    -------
    ndarray
        [kPa].

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> round(float(transition_pressure_kpa(2.5814206750769157, Tube(), "paper")), 3)
    84.455
    >>> round(float(transition_pressure_kpa(2.5814206750769157, Tube(), "thick-wall")), 3)
    49.148
    >>> float(transition_pressure_kpa(1.2, Tube()))
    0.0
    """
    rf = _tube_arrays(tube)[0]
    r0 = np.asarray(r0_mm, dtype=np.float64)
    return np.where(r0 > rf, pressure_kpa(np.maximum(r0, rf), tube, law), 0.0)
