"""Inflation phase (P < P0): the tube fills its sleeve without bending (docs/model.md section 3).

The paper's fitted law, ``P(r) = (G_e/2) ((r/r_f)^2 + (r_f/r)^2 - 2) = (G_e/2)(x - 1/x)^2``
with ``x = r/r_f``, and its closed-form inverse. Pressures are MPa inside the model
(1 MPa = 1000 kPa); the public helpers that end in ``_kpa`` take and give kPa.

Examples
--------
>>> from embroact.predict.inflation import paper_pressure_kpa, paper_radius_mm
>>> round(float(paper_pressure_kpa(2.581421, 1.5, 0.13)), 2)
84.46
>>> round(float(paper_radius_mm(84.455, 1.5, 0.13)), 4)
2.5814
"""
from __future__ import annotations

import numpy as np

__all__ = ["paper_pressure_kpa", "paper_radius_mm"]

KPA_PER_MPA = 1000.0


def paper_pressure_kpa(radius_mm, outer_radius_mm, g_e_mpa):
    """Pressure [kPa] that inflates the free tube to outer radius ``radius_mm``.

    Written as (G_e/2)(x - 1/x)^2, which has no cancellation near x = 1.

    Parameters
    ----------
    radius_mm : float or array
        Outer radius of the inflated tube [mm].
    outer_radius_mm : float or array
        Its outer radius unpressurised r_f [mm].
    g_e_mpa : float or array
        The law's modulus G_e [MPa].

    Returns
    -------
    numpy.ndarray
        Pressure [kPa].

    Examples
    --------
    >>> float(paper_pressure_kpa(1.5, 1.5, 0.13)), round(float(paper_pressure_kpa(2.581421, 1.5, 0.13)), 2)
    (0.0, 84.46)
    """
    x = np.asarray(radius_mm, dtype=np.float64) / np.asarray(outer_radius_mm, dtype=np.float64)
    return 0.5 * np.asarray(g_e_mpa, dtype=np.float64) * (x - 1.0 / x) ** 2 * KPA_PER_MPA


def paper_radius_mm(pressure_kpa, outer_radius_mm, g_e_mpa):
    """Outer radius [mm] of the free tube at ``pressure_kpa`` >= 0 (inverse of the law).

    x - 1/x = q with q = sqrt(2 P / G_e) gives x = (q + sqrt(q^2 + 4)) / 2.

    Parameters
    ----------
    pressure_kpa : float or array
        Pressure [kPa], >= 0.
    outer_radius_mm : float or array
        Outer radius unpressurised r_f [mm].
    g_e_mpa : float or array
        The law's modulus G_e [MPa].

    Returns
    -------
    numpy.ndarray
        Outer radius [mm].

    Examples
    --------
    >>> paper_radius_mm([0.0, 84.455], 1.5, 0.13).round(4).tolist()
    [1.5, 2.5814]
    """
    p = np.asarray(pressure_kpa, dtype=np.float64) / KPA_PER_MPA
    q = np.sqrt(np.maximum(2.0 * p / np.asarray(g_e_mpa, dtype=np.float64), 0.0))
    return np.asarray(outer_radius_mm, dtype=np.float64) * 0.5 * (q + np.sqrt(q * q + 4.0))
