"""The competitor: the model's closed form in vectorised numpy, written in an afternoon.

What a careful numerical programmer writes from docs/model.md section 4 alone, without
embroact's solver: the strain energy in the rationalised form (the ``T`` term as
``2 c / (sqrt(a) sqrt(b) (sqrt(a) + sqrt(b)))`` with ``a = l/l0``,
``b = a + B^2 c/A``, so it keeps its digits near theta = 0), its total derivative
along the pattern constraint by the chain rule carried line by line (value and
derivative of every intermediate, forward mode), and an inverse that tabulates
P(theta) once on the branch, starts each pressure by linear interpolation in that
table and finishes with a few vectorised secant steps on the residual
``dE/dtheta - (P - P0) dV/dtheta`` (no division, so the lock-up pole does no harm).
Nothing here imports ``embroact.predict``; it shares only the inputs.

Branch: from theta = 0 in the direction where the volume grows; it ends at the
cross pattern's lock-up (dV/dtheta = 0: ``sin(beta) = (sqrt(s0^2 + 3) - s0)/3``) or,
for the zigzag, at one full roll of the strip (360 deg), the largest bend the
benchmark samples. Pressures beyond the tabulated rise return the last rising point.

Examples
--------
>>> import numpy as np
>>> z = Competitor("zigzag", l0=100.0, r0=2.5814206750769157, beta0=0.0, c=1.25, g=2.7, p0=0.085)
>>> np.round(z.pressure_mpa(np.radians([0.0, 90.0])) * 1000, 3).tolist()
[85.0, 187.65]
>>> round(float(z.theta_deg([187.65005790858362])[0]), 9)
90.0
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Competitor", "competitor_of", "competitor_batch", "GRID_POINTS", "SECANT_STEPS", "DENSE_POINTS",
           "DENSE_STEPS"]

#: Points of the table of P(theta) along the branch, and secant steps after the interpolated start.
GRID_POINTS = 64
SECANT_STEPS = 4
#: The dense-grid version (the benchmark's second competitor): a table this fine and this many secant steps,
#: the cheapest two-step grid at <= 1e-9 deg on the sample (4096 points: 3.7e-9 deg).
DENSE_POINTS, DENSE_STEPS = 8192, 2
#: The zigzag branch is tabulated up to this bend [rad] (one full roll of the strip).
ZIGZAG_END_RAD = 2.0 * math.pi
_KPA_PER_MPA = 1000.0


@dataclass(frozen=True, slots=True)
class Competitor:
    """One design in model units: l0, r0 [mm], beta0 [rad], c = r_f^2 - d_f^2 [mm^2], G, P0 [MPa]."""

    pattern: str
    l0: float
    r0: float
    beta0: float
    c: float
    g: float
    p0: float

    def _sin_cos(self):
        b = self.beta0
        return (math.sin(b), math.cos(b)) if isinstance(b, float) else (np.sin(b), np.cos(b))

    def _state(self, theta):
        """(l, dl/dtheta, r, dr/dtheta) on the constraint."""
        if self.pattern == "zigzag":
            one = np.ones_like(theta)
            return self.l0 + 2.0 * self.r0 * theta, 2.0 * self.r0 * one, self.r0 * one, 0.0 * one
        s0, c0 = self._sin_cos()
        gam = 2.0 * self.r0 / (self.l0 * c0)
        gt = gam * theta
        u = (1.0 + gt * np.sqrt(c0 * c0 + gt * gt * s0 * s0)) / (1.0 + gt * gt * s0 * s0)  # l/l0
        cb = np.sqrt(1.0 - u * u * s0 * s0)  # cos(beta)
        # u = 1 + gam theta cos(beta), cos(beta)' = -u u' s0^2 / cos(beta)
        du = gam * cb / (1.0 + gt * u * s0 * s0 / cb)
        return self.l0 * u, self.l0 * du, self.r0 * cb / c0, -self.r0 / c0 * u * du * s0 * s0 / cb

    def rates(self, theta):
        """(dE/dtheta [N mm], dV/dtheta [mm^3]) at bend angles ``theta`` [rad]."""
        l0, c = self.l0, self.c
        l, dl, r, dr = self._state(np.asarray(theta, dtype=np.float64))
        A, dA = (l + l0) / (2.0 * l0), dl / (2.0 * l0)
        B = (l - l0) / (2.0 * l0 * r)
        dB = (dA - B * dr) / r
        lam, dlam = r / self.r0, dr / self.r0
        q = c / A
        dq = -q * dA / A
        a, da = l / l0, dl / l0
        b = a + B * B * q
        db = da + 2.0 * B * dB * q + B * B * dq
        sa, sb = np.sqrt(a), np.sqrt(b)
        T = 2.0 * c / (sa * sb * (sa + sb))
        dT = -T * (0.5 * da / a + 0.5 * db / b + (0.5 * da / sa + 0.5 * db / sb) / (sa + sb))
        lam2 = lam * lam
        w = 2.0 * r * r - q
        dF = ((2.0 * A * dA + 2.0 * lam * dlam) * q + (A * A + lam2 - 3.0) * dq
              + 0.5 * B * dB * q * w + 0.25 * B * B * (dq * w + q * (4.0 * r * dr - dq))
              + dT / lam2 - 2.0 * T * dlam / (lam2 * lam))
        dE = 0.5 * math.pi * self.g * l0 * dF
        dV = math.pi * (r * dr * (l + l0) + 0.5 * r * r * dl)
        return dE, dV

    def pressure_mpa(self, theta):
        """P(theta) = P0 + (dE/dtheta)/(dV/dtheta) [MPa]; P0 at theta = 0."""
        theta = np.asarray(theta, dtype=np.float64)
        with np.errstate(divide="ignore", invalid="ignore"):
            dE, dV = self.rates(theta)
            return np.where(theta == 0.0, self.p0, self.p0 + dE / dV)

    def branch_end_rad(self):
        """Signed end of the tabulated branch: lock-up (cross) or ``ZIGZAG_END_RAD`` (per row of a batch)."""
        if self.pattern == "zigzag":
            return ZIGZAG_END_RAD
        s0, c0 = self._sin_cos()
        with np.errstate(divide="ignore", invalid="ignore"):
            x = (np.sqrt(s0 * s0 + 3.0) - s0) / 3.0  # sin(beta) at the volume maximum
            l = self.l0 * x / s0
            end = (l - self.l0) / (2.0 * self.r0 * np.sqrt(1.0 - x * x) / c0)
        return float(end) if self.pattern == "cross" else np.where(s0 > 0.0, end, ZIGZAG_END_RAD)

    def theta_deg(self, pressures_kpa, *, grid_points: int = GRID_POINTS, steps: int = SECANT_STEPS) -> np.ndarray:
        """Equilibrium angle [deg] per pressure (0 below P0); ``grid_points`` and ``steps`` as the module's
        defaults (the dense-grid version: :data:`DENSE_POINTS`, :data:`DENSE_STEPS`)."""
        p = np.asarray(pressures_kpa, dtype=np.float64) / _KPA_PER_MPA
        t = p - self.p0
        out = np.zeros(p.shape)
        bend = t > 0.0
        if not bend.any():
            return out
        t = t[bend]
        grid = np.linspace(0.0, self.branch_end_rad(), grid_points + 1)[:-1]  # the end is a pole for the cross
        with np.errstate(divide="ignore", invalid="ignore"):
            dE, dV = self.rates(grid)
            pg = dE / dV
        pg[0] = 0.0
        rise = np.flatnonzero(np.diff(pg) <= 0.0)
        top = grid_points - 1 if rise.size == 0 else int(rise[0])
        grid, pg = grid[:top + 1], pg[:top + 1]
        i = np.clip(np.searchsorted(pg, t) - 1, 0, max(top - 1, 0))
        out[bend] = np.degrees(self._secant(t, grid[i], dE[i] - t * dV[i], np.interp(t, pg, grid), steps))
        return out

    def _secant(self, t, x0, f0, x1, steps=SECANT_STEPS):
        """``steps`` secant steps on ``dE/dtheta - t dV/dtheta`` from ``x0`` (residual ``f0``) and ``x1``."""
        with np.errstate(divide="ignore", invalid="ignore"):
            for _ in range(steps):
                dE1, dV1 = self.rates(x1)
                f1 = dE1 - t * dV1
                step = f1 * (x1 - x0) / (f1 - f0)
                x2 = np.where(np.isfinite(step) & (f1 != f0), x1 - step, x1)
                x0, f0, x1 = x1, f1, x2
        return x1

    def theta_deg_rows(self, pressures_kpa) -> np.ndarray:
        """A batch (:func:`competitor_batch`): the angle [deg] per design (row) and pressure, the same
        algorithm as :meth:`theta_deg` vectorised across designs (each row its own table)."""
        p = np.asarray(pressures_kpa, dtype=np.float64)[None, :] / _KPA_PER_MPA
        t = np.broadcast_to(p - self.p0, (self.p0.shape[0], p.shape[1]))
        grid = self.branch_end_rad() * np.linspace(0.0, 1.0, GRID_POINTS + 1)[:-1]
        with np.errstate(divide="ignore", invalid="ignore"):
            dE, dV = self.rates(grid)
            pg = dE / dV
        pg[:, 0] = 0.0
        falls = np.diff(pg, axis=1) <= 0.0
        top = np.where(falls.any(axis=1), np.argmax(falls, axis=1), GRID_POINTS - 1)[:, None]
        pg = np.where(np.arange(GRID_POINTS) <= top, pg, np.inf)  # the rising part of each row's table
        below = (pg[:, None, :] < t[:, :, None]).sum(axis=2)  # searchsorted per row
        i = np.clip(below - 1, 0, np.maximum(top - 1, 0))
        rows = np.arange(t.shape[0])[:, None]
        j = np.minimum(i + 1, top)
        g0, g1, p0, p1 = grid[rows, i], grid[rows, j], pg[rows, i], pg[rows, j]
        with np.errstate(divide="ignore", invalid="ignore"):  # np.interp per row: the rise's last point beyond it
            x1 = np.where(t >= pg[rows, top], grid[rows, top], g0 + (t - p0) * np.where(p1 > p0, (g1 - g0) / (p1 - p0),
                                                                                         0.0))
        x1 = np.where(t <= 0.0, 0.0, x1)
        theta = self._secant(t, g0, dE[rows, i] - t * dV[rows, i], x1)
        return np.where(t > 0.0, np.degrees(theta), 0.0)


def competitor_batch(models) -> Competitor:
    """The competitor for many models at once: columns ``(n, 1)`` (pattern "mixed": the cross formula,
    exact for a zigzag's beta0 = 0, and each row's own branch end), for :meth:`Competitor.theta_deg_rows`."""
    col = [competitor_of(m) for m in models]
    return Competitor("mixed", *(np.array([[getattr(c, k)] for c in col]) for k in ("l0", "r0", "beta0", "c", "g",
                                                                                      "p0")))


def competitor_of(model) -> Competitor:
    """The competitor for an :class:`~embroact.predict.curve.ActuatorModel` (same float inputs)."""
    return Competitor(model.pattern, model.length_mm, model.r0_mm, math.radians(model.beta0_deg),
                      model.outer_radius_mm**2 - model.inner_radius_mm**2, model.g_mpa,
                      model.p0_kpa / _KPA_PER_MPA)
