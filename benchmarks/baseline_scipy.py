"""The straightforward scipy implementation of the model, as a baseline (docs/model.md section 4).

What one would write first, with no embroact code: the strain energy by numerical
double integration of the Neo-Hookean density over the tube wall
(``scipy.integrate.dblquad`` with its default tolerances), ``dE/dtheta`` and
``dV/dtheta`` by central differences with the textbook step ``cbrt(eps) * max(1, |theta|)``,
and ``brentq`` per pressure on the bracket [0, theta_max]. Scalar Python throughout.

Energy: ``E = (G l0 / 2) * integral over rho in [d, r], phi in [0, 2 pi] of
(lambda1^2 + lambda2^2 + (lambda1 lambda2)^-2 - 3) rho``, ``lambda1 = A + B rho sin(phi)``,
``lambda2 = r / r0`` (the paper's stretches; the closed form of docs/model.md section 4 is this integral).

Examples
--------
>>> b = ScipyBaseline(pattern="zigzag", l0=100.0, r0=2.5814206750769157, beta0=0.0,
...                   c=1.25, g=2.7, p0=0.085)
>>> round(b.pressure_kpa(0.0), 6), round(b.pressure_kpa(1.5707963267948966), 2)
(85.0, 187.65)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["ScipyBaseline", "baseline_of"]

#: Central-difference step relative to max(1, |theta|) [rad].
STEP = float(np.cbrt(np.finfo(float).eps))
_KPA_PER_MPA = 1000.0


@dataclass(frozen=True, slots=True)
class ScipyBaseline:
    """One design in model units (mm, MPa, rad): l0, r0, beta0, wall constant c = r_f^2 - d_f^2, G, P0."""

    pattern: str
    l0: float
    r0: float
    beta0: float
    c: float
    g: float
    p0: float

    def state(self, theta: float) -> tuple[float, float]:
        """(l, r) on the pattern constraint."""
        if self.pattern == "zigzag":
            return self.l0 + 2.0 * self.r0 * theta, self.r0
        s0, c0 = math.sin(self.beta0), math.cos(self.beta0)
        gt = 2.0 * self.r0 / (self.l0 * c0) * theta
        l = self.l0 * (1.0 + gt * math.sqrt(c0 * c0 + gt * gt * s0 * s0)) / (1.0 + gt * gt * s0 * s0)
        sinb = l / self.l0 * s0
        return l, self.r0 * math.sqrt(1.0 - sinb * sinb) / c0

    def energy(self, theta: float) -> float:
        """Strain energy [N mm] by dblquad over the wall."""
        from scipy.integrate import dblquad

        l, r = self.state(theta)
        a = (l + self.l0) / (2.0 * self.l0)
        b = (l - self.l0) / (2.0 * r * self.l0)
        lam2 = r / self.r0
        d = math.sqrt(r * r - self.c / a)

        def density(phi, rho):
            lam1 = a + b * rho * math.sin(phi)
            return (lam1 * lam1 + lam2 * lam2 + 1.0 / (lam1 * lam2) ** 2 - 3.0) * rho

        val, _ = dblquad(density, d, r, 0.0, 2.0 * math.pi)
        return self.g * self.l0 / 2.0 * val

    def volume(self, theta: float) -> float:
        """Inner volume pi d^2 (l + l0)/2 [mm^3]."""
        l, r = self.state(theta)
        return math.pi * (r * r - self.c * 2.0 * self.l0 / (l + self.l0)) * (l + self.l0) / 2.0

    def pressure_kpa(self, theta: float) -> float:
        """P(theta) = P0 + dE/dV by central differences [kPa]."""
        h = STEP * max(1.0, abs(theta))
        de = self.energy(theta + h) - self.energy(theta - h)
        dv = self.volume(theta + h) - self.volume(theta - h)
        return (self.p0 + de / dv) * _KPA_PER_MPA

    def theta_deg(self, pressure_kpa: float, theta_max_deg: float) -> float:
        """Equilibrium angle [deg] by brentq on [0, theta_max] (0 below P0)."""
        from scipy.optimize import brentq

        if pressure_kpa <= self.p0 * _KPA_PER_MPA:
            return 0.0
        root = brentq(lambda t: self.pressure_kpa(t) - pressure_kpa, 0.0, math.radians(theta_max_deg))
        return math.degrees(root)

    def curve_deg(self, pressures_kpa, theta_max_deg: float) -> np.ndarray:
        """theta [deg] per pressure, one root per pressure."""
        return np.array([self.theta_deg(float(p), theta_max_deg) for p in pressures_kpa])


def baseline_of(model) -> ScipyBaseline:
    """The baseline for an :class:`~embroact.predict.curve.ActuatorModel` (same float inputs)."""
    return ScipyBaseline(model.pattern, model.length_mm, model.r0_mm, math.radians(model.beta0_deg),
                         model.outer_radius_mm**2 - model.inner_radius_mm**2, model.g_mpa,
                         model.p0_kpa / _KPA_PER_MPA)
