"""50-digit mpmath reference of the deformation model, written from the equations of docs/model.md alone.

Independent of ``embroact.predict``: every formula is re-typed here from the spec
(sections 2-4 and the thick-walled tube law of section 3), evaluated with mpmath at
a working precision high enough that results carry 50 significant digits (the printed
``T`` term loses about ``2*log10(1/(B r))`` digits near the straight state, so the
working precision is raised by that much). Derivatives are ``mpmath.diff`` at that
precision, inverses ``mpmath.findroot``. Used by the tests and by the benchmarks.

Units: mm, MPa, rad inside; helpers ending ``_kpa`` / ``_deg`` convert.

Examples
--------
>>> d = Ref.zigzag(width_mm=7, g_mpa=2.7, p0_kpa=85)
>>> float(d.pressure(0)) == 0.085
True
"""
from __future__ import annotations

import mpmath as mp

DIGITS = 50


def _digits(extra=10):
    """Working precision: at least DIGITS + extra, never lower than the caller's (mp.diff raises it)."""
    return mp.workdps(max(mp.mp.dps, DIGITS) + extra)

__all__ = ["DIGITS", "Ref", "sleeve_radius", "thread_angle", "paper_law", "thick_wall_law", "thick_wall_quad"]


def sleeve_radius(w, rf):
    """docs/model.md section 2: r0 = (w + 2 sqrt((w/2)^2 + (2 r_f)^2)) / (2 pi)."""
    with _digits():
        w, rf = mp.mpf(w), mp.mpf(rf)
        return (w + 2 * mp.sqrt((w / 2) ** 2 + (2 * rf) ** 2)) / (2 * mp.pi)


def thread_angle(w, alpha0_deg, rf):
    """docs/model.md section 2: beta0 [rad] from width, embroidery angle and tube radius."""
    with _digits():
        h, t = mp.mpf(w) / 2, mp.tan(mp.radians(mp.mpf(alpha0_deg)))
        return mp.asin(h * t / mp.sqrt((2 * mp.mpf(rf)) ** 2 + h**2 * (1 + t**2)))


def paper_law(r, rf, ge):
    """Paper's inflation law P(r) [MPa]."""
    with _digits():
        r, rf = mp.mpf(r), mp.mpf(rf)
        return mp.mpf(ge) / 2 * ((r / rf) ** 2 + (rf / r) ** 2 - 2)


def thick_wall_law(r, rf, df, mu):
    """docs/model.md section 3 closed form: mu (ln(la/lb) + (lb^-2 - la^-2)/2), [MPa]."""
    with _digits():
        r, rf, df = mp.mpf(r), mp.mpf(rf), mp.mpf(df)
        a = mp.sqrt(r**2 - (rf**2 - df**2))
        la, lb = a / df, r / rf
        return mp.mpf(mu) * (mp.log(la / lb) + (lb**-2 - la**-2) / 2)


def thick_wall_quad(r, rf, df, mu):
    """Plane-strain equilibrium integrated numerically (no closed form used).

    Radial equilibrium d(sigma_r)/d(rho) = (sigma_t - sigma_r)/rho with the Neo-Hookean
    stress difference mu (lambda^2 - lambda^-2), lambda = rho/R the hoop stretch and
    incompressibility rho^2 - R^2 = r^2 - r_f^2; sigma_r = -P inside, 0 outside, so
    P = integral over the deformed wall of mu (lambda^2 - lambda^-2) / rho.
    """
    with _digits():
        r, rf, df = mp.mpf(r), mp.mpf(rf), mp.mpf(df)
        k = r**2 - rf**2
        a = mp.sqrt(df**2 + k)

        def integrand(rho):
            lam2 = rho**2 / (rho**2 - k)
            return mp.mpf(mu) * (lam2 - 1 / lam2) / rho

        return mp.quad(integrand, [a, r])


class Ref:
    """One design, every quantity of docs/model.md section 4 at 50 digits."""

    def __init__(self, pattern, *, l0, r0, beta0, rf, df, g, p0):
        with _digits():
            self.pattern = pattern
            self.l0, self.r0, self.beta0 = mp.mpf(l0), mp.mpf(r0), mp.mpf(beta0)
            self.c = mp.mpf(rf) ** 2 - mp.mpf(df) ** 2
            self.g, self.p0 = mp.mpf(g), mp.mpf(p0)

    @classmethod
    def zigzag(cls, *, width_mm, g_mpa, p0_kpa, rf=1.5, df=1.0, l0=100):
        return cls("zigzag", l0=l0, r0=sleeve_radius(width_mm, rf), beta0=0, rf=rf, df=df,
                   g=g_mpa, p0=mp.mpf(p0_kpa) / 1000)

    @classmethod
    def cross(cls, *, width_mm, angle_deg, g_mpa, p0_kpa, rf=1.5, df=1.0, l0=100):
        return cls("cross", l0=l0, r0=sleeve_radius(width_mm, rf), beta0=thread_angle(width_mm, angle_deg, rf),
                   rf=rf, df=df, g=g_mpa, p0=mp.mpf(p0_kpa) / 1000)

    # -- constraint -------------------------------------------------------------
    def l_r(self, theta):
        """(l, r) at bend angle theta [rad] (section 4, experimental sign)."""
        theta = mp.mpf(theta)
        if self.pattern == "zigzag":
            return self.l0 + 2 * self.r0 * theta, self.r0
        s0, c0 = mp.sin(self.beta0), mp.cos(self.beta0)
        gam = 2 * self.r0 / (self.l0 * c0)
        gt = gam * theta
        l = self.l0 * (1 + gt * mp.sqrt(c0**2 + gt**2 * s0**2)) / (1 + gt**2 * s0**2)
        sinb = l / self.l0 * s0
        return l, self.r0 * mp.sqrt(1 - sinb**2) / c0

    def beta(self, theta):
        if self.pattern == "zigzag":
            return mp.mpf(0)
        return mp.asin(self.l_r(theta)[0] / self.l0 * mp.sin(self.beta0))

    # -- energy and volume as printed --------------------------------------------
    def _d2(self, l, r):
        return r**2 - self.c / ((l + self.l0) / (2 * self.l0))

    def energy(self, l, r):
        """E_s(l) exactly as the paper prints it (docs/model.md section 4) [N mm]."""
        l0 = self.l0
        A = (l + l0) / (2 * l0)
        B = (l - l0) / (2 * r * l0)
        lam2 = r / self.r0
        d2 = self._d2(l, r)
        if B == 0:  # the limit B -> 0 of T: (A^2 - x)^(-1/2) expanded, T -> A (r^2 - d^2) / A^3 * ...
            T = 2 * A * (r**2 - d2) / (2 * A**3)
        else:
            T = 2 * A / B**2 * ((A**2 - B**2 * r**2) ** mp.mpf(-0.5) - (A**2 - B**2 * d2) ** mp.mpf(-0.5))
        return mp.pi * self.g * l0 / 2 * ((A**2 + lam2**2 - 3) * (r**2 - d2) + B**2 / 4 * (r**4 - d2**2) + T / lam2**2)

    def volume(self, l, r):
        return mp.pi * self._d2(l, r) * (l + self.l0) / 2

    def _extra_digits(self, theta):
        t = abs(mp.mpf(theta))
        return 20 + (int(-2 * mp.log10(t)) if 0 < t < 1 else 0)

    def energy_theta(self, theta):
        with _digits(self._extra_digits(theta)):
            return self.energy(*self.l_r(theta))

    def pressure(self, theta):
        """P(theta) = P0 + (dE/dtheta)/(dV/dtheta) [MPa], total derivatives along the constraint."""
        theta = mp.mpf(theta)
        if theta == 0:
            return +self.p0
        with _digits(self._extra_digits(theta)):
            de = mp.diff(lambda t: self.energy(*self.l_r(t)), theta)
            dv = mp.diff(lambda t: self.volume(*self.l_r(t)), theta)
            return self.p0 + de / dv

    def dvolume(self, theta):
        with _digits():
            return mp.diff(lambda t: self.volume(*self.l_r(t)), mp.mpf(theta))

    def lock_theta(self, direction):
        """Lock-up angle: first sign change of dV/dtheta from 0 towards ``direction`` (+1/-1),
        scanned in steps of 0.05 rad, then refined by the Anderson-Bjorck bracketing solver."""
        with _digits():
            step = mp.mpf(direction) / 20
            a, fa = step / 1000, self.dvolume(step / 1000)
            while True:
                b = a + step
                fb = self.dvolume(b)
                if fa * fb <= 0:
                    return mp.findroot(self.dvolume, (a, b), solver="anderson")
                a, fa = b, fb

    def theta(self, pressure_mpa, guess):
        """theta [rad] with P(theta) = pressure, Newton/secant from ``guess``."""
        with _digits():
            return mp.findroot(lambda t: self.pressure(t) - mp.mpf(pressure_mpa), mp.mpf(guess))

    def bend_deg(self, pressures_kpa, step=0.05):
        """theta [deg] at each pressure [kPa], from the equations alone: zero up to P0, else the root of
        P(theta) = p on the bending side (the sign of theta along which P rises from P0), started from a
        scan of P(theta) in ``step`` rad steps (no model code gives a start value)."""
        ps = [mp.mpf(p) / 1000 for p in pressures_kpa]
        side = 1 if self.pressure(mp.mpf("0.01")) > self.pressure(mp.mpf("-0.01")) else -1
        grid, top = [mp.mpf(0)], max(ps)
        while self.pressure(grid[-1]) < top:
            grid.append(grid[-1] + side * mp.mpf(step))
        values = [self.pressure(t) for t in grid]
        out = []
        for p in ps:
            if p <= self.p0:
                out.append(0.0)
                continue
            k = next(i for i, v in enumerate(values) if v >= p)
            lo, hi = grid[k - 1], grid[k]
            guess = lo + (hi - lo) * (p - values[k - 1]) / (values[k] - values[k - 1])
            out.append(float(mp.degrees(self.theta(p, guess))))
        return out

