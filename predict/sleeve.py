"""Geometry of the thread-and-fabric sleeve (docs/model.md).

Vectorised over numpy arrays; lengths in mm, angles in degrees at the interface.

Examples
--------
>>> from embroact.predict.sleeve import sleeve_radius_mm, thread_angle_deg, neutral_angle_deg
>>> round(float(sleeve_radius_mm(7.0, 1.5)), 6)
2.581421
>>> round(float(thread_angle_deg(7.0, 45.0, 1.5)), 4)
37.2078
>>> round(float(neutral_angle_deg(7.0, 1.5)), 2)
33.37
"""
from __future__ import annotations

import numpy as np

__all__ = [
    "sleeve_radius_mm",
    "thread_angle_deg",
    "gamma",
    "min_sleeve_width_mm",
    "neutral_angle_deg",
]


def sleeve_radius_mm(width_mm, outer_radius_mm):
    """Sleeve radius r0 = (w + 2 sqrt((w/2)^2 + (2 r_f)^2)) / (2 pi) [mm].

    Parameters
    ----------
    width_mm : float or array
        Realised rail spacing w [mm].
    outer_radius_mm : float or array
        Tube outer radius r_f [mm].

    Returns
    -------
    numpy.ndarray
        r0 [mm].

    Examples
    --------
    >>> round(float(sleeve_radius_mm(7.0, 1.5)), 4)
    2.5814
    """
    w = np.asarray(width_mm, dtype=np.float64)
    rf = np.asarray(outer_radius_mm, dtype=np.float64)
    return (w + 2.0 * np.hypot(w / 2.0, 2.0 * rf)) / (2.0 * np.pi)


def thread_angle_deg(width_mm, angle_deg, outer_radius_mm):
    """beta0, thread angle to the circumferential direction at r = r0 [deg].

    sin(beta0) = (w/2) tan(alpha0) / sqrt((2 r_f)^2 + (w/2)^2 (1 + tan(alpha0)^2)),
    always below 1 for alpha0 in (0, 90) deg.

    Parameters
    ----------
    width_mm : float or array
        Realised rail spacing w [mm].
    angle_deg : float or array
        Embroidery angle alpha0 [deg].
    outer_radius_mm : float or array
        Tube outer radius r_f [mm].

    Returns
    -------
    numpy.ndarray
        beta0 [deg].

    Examples
    --------
    >>> round(float(thread_angle_deg(7.0, 45.0, 1.5)), 4)
    37.2078
    """
    h = np.asarray(width_mm, dtype=np.float64) / 2.0
    t = np.tan(np.radians(np.asarray(angle_deg, dtype=np.float64)))
    rf2 = 2.0 * np.asarray(outer_radius_mm, dtype=np.float64)
    # sqrt((2rf)^2 + h^2 + (h t)^2) = hypot(hypot(2rf, h), h t): no overflow for t large
    s = h * t / np.hypot(np.hypot(rf2, h), h * t)
    return np.degrees(np.arcsin(s))


def gamma(r0_mm, beta0_deg, length_mm):
    """gamma = 2 r0 / (l0 cos(beta0)) [1/rad] of the cross pattern's l(theta) relation.

    Parameters
    ----------
    r0_mm : float or array
        Sleeve radius [mm].
    beta0_deg : float or array
        Thread angle [deg].
    length_mm : float or array
        Fabric-side length l0 [mm].

    Returns
    -------
    numpy.ndarray
        gamma [1/rad].

    Examples
    --------
    >>> round(float(gamma(2.5, 0.0, 100.0)), 6)
    0.05
    """
    return 2.0 * np.asarray(r0_mm, float) / (np.asarray(length_mm, float) * np.cos(np.radians(beta0_deg)))


def min_sleeve_width_mm(outer_radius_mm):
    """Width at which r0 = r_f: w = (pi^2 - 4)/pi * r_f [mm]; narrower leaves no sleeve.

    Parameters
    ----------
    outer_radius_mm : float or array
        Tube outer radius r_f [mm].

    Returns
    -------
    numpy.ndarray
        The width [mm].

    Examples
    --------
    >>> w = min_sleeve_width_mm(1.5)
    >>> round(float(w), 4), round(float(sleeve_radius_mm(w, 1.5)), 12)
    (2.8025, 1.5)
    """
    return (np.pi**2 - 4.0) / np.pi * np.asarray(outer_radius_mm, dtype=np.float64)


def neutral_angle_deg(width_mm, outer_radius_mm):
    """Embroidery angle alpha0 whose beta0 satisfies tan(beta0) = 1/2 [deg].

    From sin^2(beta0) = 1/5: (w/2)^2 t^2 * 4 = (2 r_f)^2 + (w/2)^2, t = tan(alpha0).

    Parameters
    ----------
    width_mm : float or array
        Realised rail spacing w [mm].
    outer_radius_mm : float or array
        Tube outer radius r_f [mm].

    Returns
    -------
    numpy.ndarray
        alpha0 [deg].

    Examples
    --------
    >>> a = neutral_angle_deg(7.0, 1.5)
    >>> round(float(a), 4), round(float(np.tan(np.radians(thread_angle_deg(7.0, a, 1.5)))), 12)
    (33.3665, 0.5)
    """
    h = np.asarray(width_mm, dtype=np.float64) / 2.0
    rf2 = 2.0 * np.asarray(outer_radius_mm, dtype=np.float64)
    return np.degrees(np.arctan(np.hypot(rf2, h) / (2.0 * h)))
