"""Deformation phase physics (docs/model.md section 4): energy, volume, constraint, P(theta).

Equations only, vectorised over numpy arrays that broadcast against a
:class:`Geometry` (one design per row, shape ``(n, 1)``); no loops. Units inside:
mm, MPa (N/mm^2), N*mm, rad. The numerical machinery (difference quotients,
quadrature rules, root finders) lives in :mod:`embroact.predict.solvers`.

Notation: ``A = (l + l0)/(2 l0)``, ``B = (l - l0)/(2 r l0)``, ``lambda2 = r/r0``,
``c = r_f^2 - d_f^2``, ``q = r^2 - d^2 = c/A`` (incompressible wall),
``a = A^2 - B^2 r^2 = l/l0`` (exactly) and ``b = A^2 - B^2 d^2 = a + B^2 q``.

Energy forms (``form=``)
------------------------
``"printed"``
    ``E_s`` exactly as the paper prints it (docs/model.md section 4): ``d^2`` first, then ``r^2 - d^2``,
    ``r^4 - d^4`` and ``T = (2A/B^2)(a^-1/2 - b^-1/2)``. Fails near the straight
    state: the difference in ``T`` cancels, losing about ``2 log10(1/(B r))`` digits
    (all of them by ``|theta| ~ 1e-8 rad``) and dividing 0 by 0 at ``B = 0``.
``"stable"``
    The same function rationalised: ``T = 2 c / (sqrt(a) sqrt(b) (sqrt(a) + sqrt(b)))``
    with ``a = l/l0``, ``q = c/A``, ``r^4 - d^4 = q (2 r^2 - q)``. No cancellation
    anywhere in the domain; fails only where the model does (``l <= 0``, ``d^2 <= 0``).
``"reference"``
    Independent of the closed form: ``(G/2)(I1 - 3)`` with ``lambda1 = A + B rho sin(phi)``
    (the paper's axial stretch at depth ``rho`` in the wall, angle ``phi``),
    ``lambda2 = r/r0``, ``lambda3 = 1/(lambda1 lambda2)``, integrated by tensor
    Gauss-Legendre over ``rho in [d, r]``, ``phi in [0, 2 pi]`` and multiplied by the
    length ``l0``. Accurate to ~1e-13 relative up to ``B r / A ~ 0.85`` (64 nodes in
    phi); the phi integrand ``1/lambda1^2`` sharpens as ``B r / A -> 1`` (lambda1 -> 0 on
    the wall) and the rule then loses digits; ~100x slower than the closed forms.

Derivatives (``derivative=`` of :func:`energy_rate`): ``"analytic"`` differentiates the
closed forms by hand (the stable one in the variables ``A`` and ``r`` with
``m = A - 1 = B r``, free of cancellation; the printed one term by term, inheriting
its cancellation); ``"complex"`` and ``"central"`` differentiate ``E_s(theta)``
numerically (see :mod:`embroact.predict.solvers`).

The pattern constraint is one formula for every thread angle: the cross pattern's
``l(theta)`` with ``beta0 = 0`` is the zigzag's ``l = l0 + 2 r0 theta, r = r0``.

Examples
--------
>>> import numpy as np
>>> from embroact.predict.model import Geometry, pressure_mpa
>>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.5814206750769157,
...                            c_mm2=1.25, g_mpa=2.7, p0_mpa=0.085)
>>> p = pressure_mpa(np.radians([0.0, 90.0]), geo, form="stable", derivative="analytic")
>>> np.round(p * 1000, 3).tolist()
[[85.0, 187.65]]
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..patterns.base.errors import ParameterError
from ..patterns.base.records import quick_init
from . import solvers
from .floats import SCALAR

__all__ = [
    "ENERGY_FORMS",
    "DERIVATIVES",
    "Geometry",
    "constraint",
    "constraint_rates",
    "energy",
    "energy_gradient",
    "volume",
    "volume_gradient",
    "energy_rate",
    "pressure_mpa",
    "lock_theta",
    "inner_radius_sq",
    "rate_fast",
    "pantograph",
    "StretchRates",
]

ENERGY_FORMS = ("stable", "printed", "reference")
#: Derivative methods; "analytic" exists for the closed forms only.
DERIVATIVES = ("analytic", "complex", "central")

#: Gauss-Legendre nodes of the reference energy (wall depth, angle around the tube).
REFERENCE_NODES = (12, 64)
_DEG_PER_RAD = 180.0 / np.pi  # numpy's degrees() multiplies by this same double


@quick_init
@dataclass(frozen=True, slots=True)
class Geometry:
    """Model constants of one or more designs, as ``(n, 1)`` float64 arrays (mm, MPa, rad).

    Attributes
    ----------
    l0, r0 : ndarray
        Fabric-side length and sleeve radius [mm].
    s0, c0 : ndarray
        sin(beta0), cos(beta0) (0 and 1 for the zigzag).
    c : ndarray
        Wall constant r_f^2 - d_f^2 [mm^2].
    g, p0 : ndarray
        Effective shear modulus G and transition pressure P0 [MPa].
    gamma, r_c0, r_slope, e_scale : ndarray
        Derived once: 2 r0/(l0 c0) [1/rad], r0/c0 [mm], r0 s0/(l0 c0) [-] and the
        energy's factor pi G l0/2 [N].
    s0sq, c0sq : ndarray
        sin^2(beta0), cos^2(beta0) (the fused rate's constants).

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=[0.0, np.radians(45.0)], l0_mm=100.0, r0_mm=2.6, c_mm2=1.25,
    ...                            g_mpa=1.3, p0_mpa=0.17)
    >>> geo.l0.shape, np.round(geo.s0.ravel(), 4).tolist(), round(float(geo.gamma[0, 0]), 3)
    ((2, 1), [0.0, 0.7071], 0.052)
    """

    l0: np.ndarray
    r0: np.ndarray
    s0: np.ndarray
    c0: np.ndarray
    c: np.ndarray
    g: np.ndarray
    p0: np.ndarray
    gamma: np.ndarray
    r_c0: np.ndarray
    r_slope: np.ndarray
    e_scale: np.ndarray
    s0sq: np.ndarray
    c0sq: np.ndarray

    @classmethod
    def from_values(cls, *, beta0_rad, l0_mm, r0_mm, c_mm2, g_mpa, p0_mpa) -> "Geometry":
        """Broadcast scalars or 1-D arrays (one entry per design) to ``(n, 1)`` columns.

        Parameters
        ----------
        beta0_rad : float or array_like
            Initial thread angle beta0 [rad] (0: zigzag).
        l0_mm, r0_mm : float or array_like
            Fabric-side length and sleeve radius [mm].
        c_mm2 : float or array_like
            Wall constant r_f^2 - d_f^2 [mm^2].
        g_mpa, p0_mpa : float or array_like
            Shear modulus G and transition pressure P0 [MPa].

        Returns
        -------
        Geometry
            One row per design.

        Examples
        --------
        >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=2.7, p0_mpa=0.085)
        >>> geo.r0.tolist(), geo.p0.tolist()
        ([[2.6]], [[0.085]])
        """
        cols = np.broadcast_arrays(*(np.atleast_1d(np.asarray(v, dtype=np.float64))
                                     for v in (beta0_rad, l0_mm, r0_mm, c_mm2, g_mpa, p0_mpa)))
        beta0, l0, r0, c, g, p0 = (np.ascontiguousarray(v.reshape(-1, 1)) for v in cols)
        return cls._derived(l0, r0, np.sin(beta0), np.cos(beta0), c, g, p0)

    @classmethod
    def of_floats(cls, *, beta0_rad: float, l0_mm: float, r0_mm: float, c_mm2: float, g_mpa: float,
                  p0_mpa: float) -> "Geometry":
        """One design as Python floats, bit for bit the :meth:`scalar` of :meth:`from_values` (no arrays:
        a first curve of a new model pays no numpy calls for its constants).

        Parameters
        ----------
        beta0_rad, l0_mm, r0_mm, c_mm2, g_mpa, p0_mpa : float
            As for :meth:`from_values`.

        Returns
        -------
        Geometry
            Its fields are floats.

        Examples
        --------
        >>> v = dict(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
        >>> Geometry.of_floats(**v) == Geometry.from_values(**v).scalar()
        True
        """
        b = float(beta0_rad)
        s0, c0 = (float(np.sin(b)), float(np.cos(b))) if b != 0.0 else (b, 1.0)  # sin(+-0) = +-0, cos(+-0) = 1
        return cls._derived(float(l0_mm), float(r0_mm), s0, c0, float(c_mm2), float(g_mpa), float(p0_mpa))

    @classmethod
    def _derived(cls, l0, r0, s0, c0, c, g, p0) -> "Geometry":
        """The geometry with its derived constants (the same operations on arrays and on floats)."""
        return cls(l0, r0, s0, c0, c, g, p0, 2.0 * r0 / (l0 * c0), r0 / c0, r0 * s0 / (l0 * c0), np.pi * g * l0 / 2.0,
                   s0 * s0, c0 * c0)  # gamma, r_c0, r_slope, e_scale, s0sq, c0sq (positional: a first curve's cost)

    def take(self, rows) -> "Geometry":
        """The designs at ``rows`` (index array or boolean mask).

        Parameters
        ----------
        rows : array_like of int or bool
            Which designs.

        Returns
        -------
        Geometry

        Examples
        --------
        >>> geo = Geometry.from_values(beta0_rad=[0.0, 0.6], l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3,
        ...                            p0_mpa=0.17)
        >>> geo.take([1]).s0.shape, geo.take(np.array([True, False])).s0.tolist()
        ((1, 1), [[0.0]])
        """
        at = np.asarray(rows)
        at = np.flatnonzero(at) if at.dtype == bool else at
        return Geometry(*(getattr(self, k).take(at, axis=0) for k in self.__slots__))

    def scalar(self) -> "Geometry":
        """The (first) design with Python floats for fields: broadcasts against 1-D theta, and with
        ``xp=SCALAR`` (:mod:`embroact.predict.floats`) the fast formulas run on floats.

        Returns
        -------
        Geometry
            Its fields are floats.

        Examples
        --------
        >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=2.7, p0_mpa=0.085)
        >>> geo.scalar().l0, geo.scalar().c0
        (100.0, 1.0)
        """
        return Geometry(*(float(getattr(self, k)[0, 0]) for k in self.__slots__))  # type: ignore[arg-type]


# -- pattern constraint -----------------------------------------------------------------
def constraint(theta, geo: Geometry):
    """State along the constraint at bend angle ``theta`` [rad]: (l, r, sin(beta), cos(beta)).

    ``u = l/l0`` is the positive root of ``u = 1 + gamma theta cos(beta)``,
    ``sin(beta) = u s0``, ``r = r0 cos(beta)/c0``; complex ``theta`` is allowed
    (complex-step derivatives). ``cos(beta)`` comes from a rationalised form, so it
    stays accurate (and real) as ``sin(beta) -> 1`` at any angle.

    Parameters
    ----------
    theta : float or array_like
        Bend angle [rad], broadcast against the geometry's rows.
    geo : Geometry
        The designs.

    Returns
    -------
    l, r, sinb, cosb : numpy.ndarray
        Thread-side length [mm], sleeve radius [mm], sin(beta) and cos(beta).

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=np.radians(45.0), l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3,
    ...                            p0_mpa=0.17)
    >>> np.round(constraint(np.radians(90.0), geo), 4).ravel().tolist()
    [107.5052, 2.389, 0.7602, 0.6497]
    """
    if not np.any(geo.s0):  # zigzag rows only: u = 1 + gamma theta, r = r0, beta = 0
        gt = geo.gamma * theta
        zero = 0.0 * gt
        return geo.l0 * (1.0 + gt), geo.r0 + zero, zero, 1.0 + zero
    u, cos2, _, _, _ = pantograph(theta, geo)
    cosb = np.sqrt(cos2)
    return geo.l0 * u, geo.r_c0 * cosb, u * geo.s0, cosb


def pantograph(theta, geo: Geometry, xp=np):
    """(u = l/l0, cos^2(beta), g S, g^2 s0^2, 1 + g^2 s0^2) with ``g = gamma theta``, ``S = sqrt(c0^2 + g^2 s0^2)``.

    ``cos^2(beta) = 1 - u^2 s0^2 = (X - Y)/den^2 = c0^4/(X + Y)`` with ``X = c0^2 + g^2 s0^2 (1 + s0^2)``,
    ``Y = 2 s0^2 g S``: the form without cancellation for each sign of g (never below 0).

    Parameters
    ----------
    theta : float or array_like
        Bend angle [rad].
    geo : Geometry
        The designs.
    xp : module, optional
        numpy, or :data:`~embroact.predict.floats.SCALAR` for a :meth:`Geometry.scalar` geometry.

    Returns
    -------
    tuple
        ``(u, cos^2(beta), g S, g^2 s0^2, 1 + g^2 s0^2)``.

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=np.radians(45.0), l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3,
    ...                            p0_mpa=0.17)
    >>> u, cos2, _, _, _ = pantograph(np.radians(90.0), geo)
    >>> round(float(u[0, 0]), 4), round(float(cos2[0, 0]), 4)
    (1.0751, 0.4221)
    """
    gt = geo.gamma * theta
    gs2 = gt * gt * geo.s0sq
    den = 1.0 + gs2
    gS = gt * xp.sqrt(geo.c0sq + gs2)
    x = geo.c0sq + gs2 * (1.0 + geo.s0sq)
    y = (2.0 * geo.s0sq) * gS
    ahead = xp.real(gt) >= 0.0  # pick numerator and denominator first: the other form may divide by 0
    cos2 = xp.where(ahead, geo.c0sq * geo.c0sq, x - y) / xp.where(ahead, x + y, den * den)
    return (1.0 + gS) / den, cos2, gS, gs2, den


def constraint_rates(theta, l, r, sinb, cosb, geo: Geometry):
    """(dl/dtheta, dr/dtheta) along the constraint.

    From ``theta = (l - l0)/(2 r)`` and ``dr/dl = -(r0 s0/(l0 c0)) tan(beta)``:
    ``dtheta/dl = (1 - 2 theta dr/dl)/(2 r)``.

    Parameters
    ----------
    theta : float or array_like
        Bend angle [rad].
    l, r, sinb, cosb : array_like
        The state there (:func:`constraint`).
    geo : Geometry
        The designs.

    Returns
    -------
    l_t, r_t : numpy.ndarray
        dl/dtheta and dr/dtheta [mm/rad].

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=np.radians(45.0), l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3,
    ...                            p0_mpa=0.17)
    >>> theta = np.radians(90.0)
    >>> np.round(constraint_rates(theta, *constraint(theta, geo), geo), 4).ravel().tolist()
    [4.3612, -0.1327]
    """
    r_l = geo.r_slope * sinb / cosb  # -dr/dl
    l_t = r / (0.5 + theta * r_l)
    return l_t, -r_l * l_t


def inner_radius_sq(l, r, geo: Geometry):
    """d^2 = r^2 - c/A [mm^2] (incompressible wall, no change of wall volume).

    Parameters
    ----------
    l, r : float or array_like
        Thread-side length and sleeve radius [mm].
    geo : Geometry
        The designs.

    Returns
    -------
    numpy.ndarray
        The inner radius squared [mm^2].

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=2.7, p0_mpa=0.085)
    >>> inner_radius_sq(100.0, 2.6, geo).round(12).tolist()  # straight: r0^2 - c
    [[5.51]]
    """
    return r * r - geo.c * 2.0 * geo.l0 / (l + geo.l0)


def lock_theta(geo: Geometry, xp=np):
    """Lock-up angle [rad] of each design, where dV/dtheta = 0 (inf for the zigzag).

    With ``V = pi (r^2 (l + l0)/2 - c l0)`` on the pantograph, ``dV/dbeta`` is
    proportional to ``cos(beta) (1 - 3 x^2 - 2 s0 x)``, ``x = sin(beta)``, so
    ``x_L = (sqrt(s0^2 + 3) - s0)/3``; ``x_L = s0`` exactly at ``tan(beta0) = 1/2``.
    With a :meth:`Geometry.scalar` geometry and ``xp=SCALAR`` one float (the same bits).

    Parameters
    ----------
    geo : Geometry
        The designs.
    xp : module, optional
        numpy, or :data:`~embroact.predict.floats.SCALAR`.

    Returns
    -------
    numpy.ndarray or float
        The lock-up angle [rad] per design.

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=[0.0, np.radians(45.0)], l0_mm=100.0, r0_mm=2.6, c_mm2=1.25,
    ...                            g_mpa=1.3, p0_mpa=0.17)
    >>> np.round(np.degrees(lock_theta(geo)), 2).ravel().tolist()  # tan(beta0) > 1/2 bends negative
    [inf, -381.59]
    """
    s0, c0 = geo.s0, geo.c0
    if xp is not np:
        return _lock_of(geo, s0, c0, xp) if s0 > 0.0 else np.inf
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(s0 > 0.0, _lock_of(geo, s0, c0, xp), np.inf)


def _lock_of(geo, s0, c0, xp):
    """:func:`lock_theta` where s0 > 0."""
    root = xp.sqrt(s0 * s0 + 3.0)
    x = (root - s0) / 3.0
    # x - s0 = (1 - 5 s0^2)/(root + 4 s0): no cancellation near the neutral angle
    dl = geo.l0 * (c0 - 2.0 * s0) * (c0 + 2.0 * s0) / ((root + 4.0 * s0) * s0)
    return dl / (2.0 * geo.r_c0 * xp.sqrt(1.0 - x * x))


# -- energy ---------------------------------------------------------------------------
def _invariants(l, r, geo: Geometry):
    A = (l + geo.l0) / (2.0 * geo.l0)
    B = (l - geo.l0) / (2.0 * r * geo.l0)
    return A, B, r / geo.r0


def _stable_t_partials(a, b, c, xp=np):
    """(T, dT/da, dT/db) of the rationalised ``T = 2 c / (sqrt(a) sqrt(b) (sqrt(a) + sqrt(b)))`` (no cancellation
    near ``a = b``, where the printed difference of inverse square roots loses its digits)."""
    sa, sb = xp.sqrt(a), xp.sqrt(b)
    total = sa + sb
    T = 2.0 * c / (sa * sb * total)
    hs, minus_t = 0.5 / total, -T
    return T, minus_t * (0.5 / a + hs / sa), minus_t * (0.5 / b + hs / sb)


def _energy_closed(l, r, geo: Geometry, form: str):
    A, B, lam = _invariants(l, r, geo)
    if form == "stable":
        q = geo.c / A
        f2 = B * B / 4.0 * q * (2.0 * r * r - q)
        T = _stable_t_partials(l / geo.l0, l / geo.l0 + B * B * q, geo.c)[0]
    else:  # printed
        d2 = inner_radius_sq(l, r, geo)
        q = r * r - d2
        f2 = B * B / 4.0 * (r**4 - d2 * d2)
        T = 2.0 * A / B**2 * ((A * A - B * B * r * r) ** -0.5 - (A * A - B * B * d2) ** -0.5)
    return (A * A + lam * lam - 3.0) * q + f2 + T / (lam * lam)


def _energy_reference(l, r, geo: Geometry):
    A, B, lam = _invariants(l, r, geo)
    d = np.sqrt(inner_radius_sq(l, r, geo))
    (x_rho, w_rho), (x_phi, w_phi) = (solvers.gauss_legendre(n) for n in REFERENCE_NODES)
    # rho in [d, r] on axis -2, phi in [0, 2 pi] on axis -1
    half = ((r - d) / 2.0)[..., None, None]
    rho = ((r + d) / 2.0)[..., None, None] + half * x_rho[:, None]
    phi = np.pi * (x_phi + 1.0)
    lam1 = A[..., None, None] + B[..., None, None] * rho * np.sin(phi)
    lam2 = lam[..., None, None]
    density = lam1 * lam1 + lam2 * lam2 + 1.0 / (lam1 * lam2) ** 2 - 3.0
    # (1/pi) * integral over the wall cross-section: the closed forms' bracket; the
    # phi map [-1, 1] -> [0, 2 pi] has Jacobian pi, which cancels the 1/pi
    return np.einsum("...ij,i,j->...", density * rho, w_rho, w_phi) * half[..., 0, 0]


def _check_form(form: str) -> str:
    if form not in ENERGY_FORMS:
        raise ParameterError(f"form must be one of {', '.join(map(repr, ENERGY_FORMS))}, got {form!r}")
    return form


def energy(l, r, geo: Geometry, form: str = "stable"):
    """Strain energy E_s [N mm] at (l, r).

    Parameters
    ----------
    l, r : float or array_like
        Thread-side length and sleeve radius [mm].
    geo : Geometry
        The designs.
    form : {"stable", "printed", "reference"}, optional
        Which form of E_s (module docstring); others are refused.

    Returns
    -------
    numpy.ndarray
        E_s [N mm].

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=2.7, p0_mpa=0.085)
    >>> energy(110.0, 2.6, geo).round(4).tolist(), energy(110.0, 2.6, geo, "reference").round(4).tolist()
    ([[6.8112]], [[6.8112]])
    """
    if _check_form(form) == "reference":
        return geo.e_scale * _energy_reference(l, r, geo)
    return geo.e_scale * _energy_closed(l, r, geo, form)


def energy_gradient(l, r, geo: Geometry, form: str = "stable"):
    """Analytic partial derivatives (dE/dl, dE/dr) of a closed form [N, N].

    Parameters
    ----------
    l, r : float or array_like
        Thread-side length and sleeve radius [mm].
    geo : Geometry
        The designs.
    form : {"stable", "printed"}, optional
        The closed form to differentiate.

    Returns
    -------
    e_l, e_r : numpy.ndarray
        dE/dl and dE/dr [N].

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=2.7, p0_mpa=0.085)
    >>> [v.round(4).tolist() for v in energy_gradient(110.0, 2.6, geo)]
    [[[1.2819]], [[35.1615]]]
    """
    gradients = {"stable": _gradient_stable, "printed": _gradient_printed}
    if form not in gradients:
        raise ParameterError(f"form must be one of {', '.join(gradients)} for analytic derivatives, got {form!r}")
    f_l, f_r = gradients[form](l, r, geo)
    return geo.e_scale * f_l, geo.e_scale * f_r


def _gradient_stable(l, r, geo: Geometry):
    """Gradient of the stable bracket in the variables (A, r).

    With ``m = A - 1 = B r``, ``s = c/r^2`` and ``w = B^2 q = m^2 s/A`` the bracket is
    ``c A + (lambda2^2 - 3) c/A + c m^2 (2A - s)/(4 A^2) + T/lambda2^2`` with
    ``a = 2A - 1``, ``b = a + w``; r enters only through lambda2 and s.
    """
    c = geo.c
    inv2l0 = 0.5 / geo.l0
    A = (l + geo.l0) * inv2l0
    m = (l - geo.l0) * inv2l0
    ia = 1.0 / A
    ir = 1.0 / r
    s = c * ir * ir
    lam2 = (r / geo.r0) ** 2
    w = m * m * s * ia
    a = l / geo.l0
    b = a + w
    T, T_a, T_b = _stable_t_partials(a, b, c)
    il2 = 1.0 / lam2
    f_a = (c * (1.0 - (lam2 - 3.0) * ia * ia)
           + 0.5 * c * m * ia * ia * ((2.0 * A - s) - m * (1.0 - s * ia))
           + (2.0 * T_a + T_b * (2.0 + s * m * (A + 1.0) * ia * ia)) * il2)
    f_r = (2.0 * c * lam2 * ia + 0.5 * c * m * m * s * ia * ia - 2.0 * (T_b * w + T) * il2) * ir
    return f_a * inv2l0, f_r


def _gradient_printed(l, r, geo: Geometry):
    """Gradient of the printed bracket, term by term as printed (inherits its cancellation)."""
    A, B, lam = _invariants(l, r, geo)
    A_l = 0.5 / geo.l0
    B_l, B_r = 1.0 / (2.0 * r * geo.l0), -B / r
    q_l = -geo.c * A_l / (A * A)
    d2 = inner_radius_sq(l, r, geo)
    q = r * r - d2
    ap, bp = A * A - B * B * r * r, A * A - B * B * d2
    D = ap**-0.5 - bp**-0.5
    ap_l = 2.0 * A * A_l - 2.0 * B * B_l * r * r
    bp_l = 2.0 * A * A_l - 2.0 * B * B_l * d2 + B * B * q_l
    bp_r = -2.0 * B * B_r * d2 - 2.0 * B * B * r
    ap_r = -2.0 * B * B_r * r * r - 2.0 * B * B * r
    T = 2.0 * A / B**2 * D
    T_l = (2.0 * A_l / B**2 - 4.0 * A * B_l / B**3) * D + A / B**2 * (bp_l * bp**-1.5 - ap_l * ap**-1.5)
    T_r = -4.0 * A * B_r / B**3 * D + A / B**2 * (bp_r * bp**-1.5 - ap_r * ap**-1.5)
    s = 2.0 * r * r * q - q * q
    f_l = 2.0 * A * A_l * q + (A * A + lam * lam - 3.0) * q_l \
        + 0.5 * B * B_l * s + 0.25 * B * B * (2.0 * r * r - 2.0 * q) * q_l + T_l / (lam * lam)
    f_r = 2.0 * lam / geo.r0 * q + 0.5 * B * B_r * s + B * B * r * q \
        + T_r / (lam * lam) - 2.0 * T / (lam**3 * geo.r0)
    return f_l, f_r


def volume(l, r, geo: Geometry):
    """Inner volume V_i = pi d^2 (l + l0)/2 = pi (r^2 (l + l0)/2 - c l0) [mm^3].

    Parameters
    ----------
    l, r : float or array_like
        Thread-side length and sleeve radius [mm].
    geo : Geometry
        The designs.

    Returns
    -------
    numpy.ndarray
        V_i [mm^3].

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=2.7, p0_mpa=0.085)
    >>> volume(100.0, 2.6, geo).round(3).tolist()  # pi (r0^2 - c) l0
    [[1731.018]]
    """
    return np.pi * inner_radius_sq(l, r, geo) * (l + geo.l0) / 2.0


def volume_gradient(l, r, geo: Geometry):
    """(dV/dl, dV/dr) = (pi r^2/2, pi r (l + l0)) [mm^2, mm^2].

    Parameters
    ----------
    l, r : float or array_like
        Thread-side length and sleeve radius [mm].
    geo : Geometry
        The designs.

    Returns
    -------
    v_l, v_r : numpy.ndarray or float
        dV/dl and dV/dr [mm^2].

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=2.7, p0_mpa=0.085)
    >>> v_l, v_r = volume_gradient(100.0, 2.6, geo)
    >>> round(v_l, 4), v_r.round(4).tolist()
    (10.6186, [[1633.6282]])
    """
    return (0.5 * np.pi) * (r * r), np.pi * r * (l + geo.l0)


# -- pressure ---------------------------------------------------------------------------
def _energy_of_theta(geo: Geometry, form: str):
    def e(theta):
        l, r, _, _ = constraint(theta, geo)
        return energy(l, r, geo, form)

    return e


def _zigzag_rate_stable(theta, geo: Geometry):
    """(dE/dtheta, dV/dtheta) of the stable form on zigzag rows (beta0 = 0), the fast path.

    On the zigzag ``r = r0`` (so ``lambda2 = 1`` and ``s = c/r0^2`` are constants),
    ``m = A - 1 = (r0/l0) theta`` exactly and ``dV/dtheta = pi r0^3``: the bracket's
    A-derivative of :func:`_gradient_stable` alone, with nothing recomputed.
    """
    c, k = geo.c, geo.r0 / geo.l0
    m = k * theta
    A = 1.0 + m
    ia = 1.0 / A
    ia2 = ia * ia
    s = c / (geo.r0 * geo.r0)
    a = 1.0 + 2.0 * m
    w = m * m * s * ia
    b = a + w
    T, T_a, T_b = _stable_t_partials(a, b, c)
    f_a = (c * (1.0 + 2.0 * ia2) + 0.5 * c * m * ia2 * ((2.0 * A - s) - m * (1.0 - s * ia))
           + 2.0 * T_a + T_b * (2.0 + s * m * (A + 1.0) * ia2))
    de = geo.e_scale * k * f_a
    return np.where(theta == 0.0, 0.0, de), np.pi * geo.r0 ** 3 + 0.0 * theta


def _cross_rate_stable(theta, geo: Geometry):
    """(dE/dtheta, dV/dtheta) of the stable form with the analytic derivative, fused (any beta0), the fast path.

    :func:`constraint`, :func:`constraint_rates`, :func:`volume_gradient` and
    :func:`_gradient_stable` written out once in the variables of the constraint:
    ``A = (1 + u)/2``, ``m = A - 1 = (u - 1)/2`` taken without cancellation as
    ``(g S - g^2 s0^2)/(2 den)``, ``lambda2^2 = cos^2(beta)/c0^2``, ``s = c/r^2``;
    no intermediate is computed twice (real theta only).
    """
    c = geo.c
    u, cos2, gS, gs2, den = pantograph(theta, geo)
    cosb = np.sqrt(cos2)
    r = geo.r_c0 * cosb
    # constraint rates: -dr/dl = r_slope tan(beta), dl/dtheta = r/(1/2 + theta (-dr/dl))
    r_l = geo.r_slope * (u * geo.s0) / cosb
    l_t = r / (0.5 + theta * r_l)
    r_t = -r_l * l_t
    A = 0.5 * (1.0 + u)
    m = (gS - gs2) / (2.0 * den)
    ia = 1.0 / A
    ia2 = ia * ia
    ir = 1.0 / r
    s = c * ir * ir
    lam2 = cos2 / geo.c0sq
    il2 = 1.0 / lam2
    w = m * m * s * ia
    b = u + w
    T, T_a, T_b = _stable_t_partials(u, b, c)
    cm = 0.5 * c * m * ia2
    f_a = (c * (1.0 - (lam2 - 3.0) * ia2) + cm * ((2.0 * A - s) - m * (1.0 - s * ia))
           + (2.0 * T_a + T_b * (2.0 + s * m * (A + 1.0) * ia2)) * il2)
    f_r = (2.0 * c * lam2 * ia + cm * m * s - 2.0 * (T_b * w + T) * il2) * ir
    l_sum = geo.l0 * (1.0 + u)  # l + l0
    de = geo.e_scale * (f_a * (0.5 / geo.l0) * l_t + f_r * r_t)
    dv = np.pi * r * (0.5 * r * l_t + l_sum * r_t)
    return np.where(theta == 0.0, 0.0, de), dv


def rate_fast(theta, geo: Geometry):
    """(dE/dtheta, dV/dtheta) of the stable form with the analytic derivative, the fused fast path, on
    real theta: the zigzag's formula when no row has an angle, else the cross pattern's.

    Parameters
    ----------
    theta : numpy.ndarray
        Bend angle [rad], real.
    geo : Geometry
        The designs.

    Returns
    -------
    de, dv : numpy.ndarray
        dE/dtheta [N mm/rad] and dV/dtheta [mm^3/rad].

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
    >>> theta = np.array([0.4, 0.5])
    >>> de, dv = rate_fast(theta, geo)
    >>> bool(np.allclose(de, energy_rate(theta, geo, derivative="complex")[0], rtol=1e-12))
    True
    """
    rate = _cross_rate_stable if np.any(geo.s0) else _zigzag_rate_stable
    return rate(theta, geo)


# -- the stretch m: P without the constraint's theta-derivatives ---------------------------------
#: Complex step of the stretch in :meth:`StretchRates.slope` (any tiny value: no cancellation).
_STRETCH_STEP = 1e-30


@quick_init
@dataclass(frozen=True, slots=True)
class StretchRates:
    """dF/dm and dV/dm in the stretch ``m = (l - l0)/(2 l0) = A - 1``, scaled so that ``P - P0 = scale F'/V'``.

    On the constraint every state is a function of ``u = l/l0 = 1 + 2 m`` alone
    (``cos^2(beta) = 1 - s0^2 u^2``, ``lambda2^2 = cos^2(beta)/c0^2``, ``s = c/r^2 = sigma/cos^2(beta)``
    with ``sigma = c c0^2/r0^2``), and so is theta, ``theta = (l0 c0/r0) m/cos(beta)``; P is a ratio of
    rates along the constraint, the same in any variable, so in ``m`` it needs no derivative of
    theta. With ``F`` the stable bracket over ``c`` (:func:`_gradient_stable`'s, in ``A``, ``m``):

    * ``F = A + (lambda2^2 - 3)/A + m^2/(2A) - m^2 s/(4 A^2) + tau/lambda2^2``,
      ``tau = 2/(sqrt(u) sqrt(b) (sqrt(u) + sqrt(b)))``, ``b = u + w``, ``w = m^2 s/A``;
    * ``V = pi l0 r0^2/c0^2 (cos^2(beta) (1 + u)/2 - c c0^2/r0^2)``, so ``dV/dm`` is that factor times
      ``1 - s0^2 u (2 + 3 u)`` (zero at lock-up);
    * ``P - P0 = (G sigma/2) F'/V'`` (:attr:`scale`).

    Attributes
    ----------
    s0sq, c0sq : float or numpy.ndarray
        sin^2(beta0), cos^2(beta0).
    sigma : float or numpy.ndarray
        ``c c0^2/r0^2``.
    lam_k, inv_c0sq : float or numpy.ndarray
        ``4 s0^2/c0^2`` and ``1/c0^2``.
    theta_per_m : float or numpy.ndarray
        ``l0 c0/r0``: theta over m at the straight state [rad].
    scale : float or numpy.ndarray
        ``G sigma/2`` [MPa].
    geo : Geometry
        The design(s).
    zigzag : bool
        Zigzag designs only (s0 = 0: one on floats, or every row of arrays): :meth:`__call__` and :meth:`state`
        take their shorter formulas (the general ones hold for s0 = 0 too, so rows of both patterns take those).

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
    >>> k = StretchRates.of(geo.scalar())
    >>> theta = 0.4
    >>> f, v = k(k.m_of(theta))
    >>> bool(abs(k.scale * f / v + 0.17 - float(pressure_mpa(theta, geo)[0, 0])) < 1e-15)
    True
    >>> bool(abs(k.theta(k.m_of(theta)) - theta) < 1e-15)
    True
    """

    s0sq: Any  # float, or an array for an array geometry
    c0sq: Any
    sigma: Any
    lam_k: Any
    inv_c0sq: Any
    theta_per_m: Any
    scale: Any
    geo: Geometry
    zigzag: bool = False

    @classmethod
    def of(cls, g: Geometry) -> "StretchRates":
        """The rates of a :meth:`Geometry.scalar` geometry (floats), or of several designs ((n, 1) arrays).

        Parameters
        ----------
        g : Geometry
            The design(s).

        Returns
        -------
        StretchRates

        Examples
        --------
        >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.5, c_mm2=1.25, g_mpa=1.0, p0_mpa=0.1)
        >>> StretchRates.of(geo.scalar()).theta_per_m  # l0/r0 for a zigzag
        40.0
        """
        sigma = g.c * g.c0sq / (g.r0 * g.r0)
        zigzag = g.s0sq == 0.0 if isinstance(g.s0sq, float) else not g.s0sq.any()
        return cls(g.s0sq, g.c0sq, sigma, 4.0 * g.s0sq / g.c0sq, 1.0 / g.c0sq, g.l0 / g.r_c0, 0.5 * g.g * sigma, g,
                   zigzag)

    def __call__(self, m, xp=np):
        """(F', V') at stretches ``m`` (arrays, or one float with ``xp=SCALAR``); V' is 1.0 for a zigzag (class
        docstring)."""
        u = 1.0 + 2.0 * m
        ia = 1.0 / (1.0 + m)
        ia2 = ia * ia
        mm = m * m
        if self.zigzag:  # cos(beta) = 1, s = sigma
            w = self.sigma * mm * ia
            big_n = (2.0 * self.sigma) * m
            tau, t_u, t_b = _stable_t_partials(u, u + w, 1.0, xp)
            return (1.0 + 2.0 * ia2 + 0.5 * ia2 * (m * (2.0 + m) - 0.5 * big_n + w)
                    + 2.0 * t_u + t_b * (2.0 + (big_n - w) * ia)), 1.0
        cos2 = 1.0 - self.s0sq * (u * u)
        k = 1.0 / cos2
        s = self.sigma * k
        ks = (4.0 * self.s0sq) * u
        w = mm * s * ia
        big_n = (2.0 * m) * s + mm * (ks * s * k)  # (m^2 s)' A = 2 m s + m^2 s'
        tau, t_u, t_b = _stable_t_partials(u, u + w, 1.0, xp)
        d_tau = 2.0 * t_u + t_b * (2.0 + (big_n - w) * ia)
        f = (1.0 - (self.lam_k * u) * ia - (cos2 * self.inv_c0sq - 3.0) * ia2
             + 0.5 * ia2 * (m * (2.0 + m) - 0.5 * big_n + w) + self.c0sq * k * (d_tau + ks * k * tau))
        return f, 1.0 - self.s0sq * u * (2.0 + 3.0 * u)

    @property
    def rise(self):
        """dF'/dm at the straight state (where F' is 0): ``2 (6 - 20 s0^2 + 30 s0^4 - sigma c0^2)/c0^4``, the
        closed form's Taylor coefficient (``12 - 2 sigma`` for a zigzag); there ``dP/dm = scale rise/V'``,
        ``V' = 1 - 5 s0^2``.

        Examples
        --------
        >>> geo = Geometry.from_values(beta0_rad=0.6, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
        >>> k = StretchRates.of(geo.scalar())
        >>> h = 1e-6
        >>> bool(abs((k(h, SCALAR)[0] - k(-h, SCALAR)[0]) / (2.0 * h) / k.rise - 1.0) < 1e-8)
        True
        """
        s = self.s0sq
        return 2.0 * (6.0 - 20.0 * s + 30.0 * s * s - self.sigma * self.c0sq) / (self.c0sq * self.c0sq)

    def slope(self, m):
        """``F'' V' - F' V''`` at stretches ``m`` (arrays; F'' and V'' by a complex step, exact to round-off): the
        sign of dP/dm, zero at a fold of P, with no pole at lock-up (P has one).

        Parameters
        ----------
        m : numpy.ndarray
            Stretch ``(l - l0)/(2 l0)``, broadcast against the designs.

        Returns
        -------
        numpy.ndarray

        Examples
        --------
        >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.5, c_mm2=1.25, g_mpa=1.0, p0_mpa=0.1)
        >>> k = StretchRates.of(geo)
        >>> (k.slope(np.array([[0.5, 0.95]])) > 0.0).tolist()  # a zigzag's P rises, then folds near m = 0.9
        [[True, False]]
        """
        f, v = self(m + 1j * _STRETCH_STEP)
        return (f.imag * v.real - f.real * v.imag) * (1.0 / _STRETCH_STEP)

    def theta(self, m, xp=np):
        """The bend angle [rad] at stretches ``m``.

        Parameters
        ----------
        m : float or numpy.ndarray
            Stretch ``(l - l0)/(2 l0)``.
        xp : module, optional
            numpy, or :data:`~embroact.predict.floats.SCALAR` for one float.

        Returns
        -------
        float or numpy.ndarray
            theta [rad].

        Examples
        --------
        >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.5, c_mm2=1.25, g_mpa=1.0, p0_mpa=0.1)
        >>> float(StretchRates.of(geo.scalar()).theta(np.array(0.0125)))  # (l - l0)/(2 r0)
        0.5
        """
        u = 1.0 + 2.0 * m
        return self.theta_per_m * m / xp.sqrt(1.0 - self.s0sq * (u * u))

    def state(self, m, xp=np):
        """(theta [rad], l, r, beta [deg], d^2) at stretches ``m`` (as :meth:`theta`; ``d^2 = r^2 - 2 c/(1 + u)``).

        Parameters
        ----------
        m : float or numpy.ndarray
            Stretch ``(l - l0)/(2 l0)``.
        xp : module, optional
            numpy, or :data:`~embroact.predict.floats.SCALAR` for one float.

        Returns
        -------
        theta, l, r, beta, d2
            Bend angle [rad], thread-side length and tube radius [mm], thread angle [deg], inner radius
            squared [mm^2].

        Examples
        --------
        >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.5, c_mm2=1.25, g_mpa=1.0, p0_mpa=0.1)
        >>> [round(float(v[0]), 6) for v in StretchRates.of(geo.scalar()).state(np.array([0.0125]))]
        [0.5, 102.5, 2.5, 0.0, 5.015432]
        """
        g = self.geo
        u = 1.0 + 2.0 * m
        if self.zigzag:  # r = r0, beta = 0
            r, beta = (g.r0, 0.0) if xp is SCALAR else (np.full(np.shape(m), g.r0), np.zeros(np.shape(m)))
            return self.theta_per_m * m, g.l0 * u, r, beta, g.r0 * g.r0 - g.c * 2.0 / (1.0 + u)
        cosb = xp.sqrt(1.0 - self.s0sq * (u * u))
        r = g.r_c0 * cosb
        beta = xp.arcsin(xp.minimum(xp.maximum(u * g.s0, -1.0), 1.0)) * _DEG_PER_RAD
        return self.theta_per_m * m / cosb, g.l0 * u, r, beta, r * r - g.c * 2.0 / (1.0 + u)

    def m_of(self, theta):
        """The stretch at bend angles [rad]: one float, or arrays of the designs (from :func:`pantograph`: no
        cancellation).

        Parameters
        ----------
        theta : float or numpy.ndarray
            Bend angle [rad]; arrays broadcast against the designs' ``(n, 1)`` columns.

        Returns
        -------
        float or numpy.ndarray
            The stretch ``m``.

        Examples
        --------
        >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.5, c_mm2=1.25, g_mpa=1.0, p0_mpa=0.1)
        >>> StretchRates.of(geo.scalar()).m_of(0.5)  # (r0/l0) theta for a zigzag
        0.0125
        """
        _, _, g_s, gs2, den = pantograph(theta, self.geo, SCALAR if isinstance(theta, float) else np)
        return (g_s - gs2) / (2.0 * den)


def energy_rate(theta, geo: Geometry, *, form: str = "stable", derivative: str = "analytic"):
    """(dE/dtheta, dV/dtheta) along the constraint [N mm, mm^3], total derivatives.

    Parameters
    ----------
    theta : float or array_like
        Bend angle [rad]; complex for a complex-step derivative of it.
    geo : Geometry
        The designs.
    form : {"stable", "printed", "reference"}, optional
        The energy form.
    derivative : {"analytic", "complex", "central"}, optional
        How dE/dtheta is taken (module docstring).

    Returns
    -------
    de, dv : numpy.ndarray
        dE/dtheta [N mm/rad] and dV/dtheta [mm^3/rad]; dE/dtheta is 0 at theta = 0.

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=2.7, p0_mpa=0.085)
    >>> de, dv = energy_rate(np.array([0.5]), geo)
    >>> de.round(4).tolist(), dv.round(4).tolist()
    ([[1.9827]], [[55.2166]])
    >>> np.allclose(energy_rate(np.array([0.5]), geo, derivative="complex")[0], de, rtol=1e-12)
    True
    """
    if form == "stable" and derivative == "analytic" and not np.iscomplexobj(theta):
        return rate_fast(theta, geo)
    l, r, sinb, cosb = constraint(theta, geo)
    l_t, r_t = constraint_rates(theta, l, r, sinb, cosb, geo)
    v_l, v_r = volume_gradient(l, r, geo)
    dv = v_l * l_t + v_r * r_t
    if derivative == "analytic":
        e_l, e_r = energy_gradient(l, r, geo, form)
        de = e_l * l_t + e_r * r_t
    else:
        scale = geo.l0 / (2.0 * geo.r0)  # theta over which l changes by l0
        de = solvers.derivative(_energy_of_theta(geo, form), theta, scale=scale, method=derivative)
    # the straight state is stationary (dE_s/dl = 0 at l = l0) whatever the form can evaluate there
    return np.where(theta == 0.0, 0.0, de), dv


def pressure_mpa(theta, geo: Geometry, *, form: str = "stable", derivative: str = "analytic"):
    """P(theta) = P0 + (dE/dtheta)/(dV/dtheta) [MPa]; P0 exactly at theta = 0.

    The ratio of total derivatives along the constraint equals (dE_s/dl)/(dV_i/dl).
    Poles (dV/dtheta = 0) and points outside the domain give inf or nan here; the
    public layer turns them into statuses.

    Parameters
    ----------
    theta : float or array_like
        Bend angle [rad].
    geo : Geometry
        The designs.
    form, derivative : str, optional
        As for :func:`energy_rate`.

    Returns
    -------
    numpy.ndarray
        Pressure [MPa], one row per design.

    Examples
    --------
    >>> geo = Geometry.from_values(beta0_rad=0.0, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=2.7, p0_mpa=0.085)
    >>> (pressure_mpa(np.radians([0.0, 90.0]), geo) * 1000).round(3).tolist()
    [[85.0, 186.851]]
    """
    theta = np.asarray(theta, dtype=np.float64)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        de, dv = energy_rate(theta, geo, form=form, derivative=derivative)
        p = geo.p0 + de / dv
    return np.where(theta == 0.0, geo.p0, p)  # 0/0 at the neutral angle: P0 by continuity
