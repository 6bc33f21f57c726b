"""Pressure-to-bend curves: the public API of the deformation model.

``curve(model, pressures_kpa)`` answers theta(P), ``pressure_at(model, theta_deg)``
answers P(theta), ``lockup(model)`` gives the end of the stable branch and
``sweep(models, pressures_kpa)`` answers theta(P) for many designs at once
(vectorised across designs). Every answer carries a status per point
(:class:`~embroact.predict.status.Status`), the method used and the calibration
the parameters came from; no public function returns NaN.

Methods
-------
A method name is ``"<energy>-<derivative>-<inverse>"`` or ``"auto"``:

* energy ``stable`` | ``printed`` | ``reference`` (see :mod:`embroact.predict.model`);
* derivative ``analytic`` (closed forms only) | ``complex`` | ``central``
  (see :mod:`embroact.predict.solvers`);
* inverse ``trace`` (tabulate E' and V' along the branch, zoom onto the part the
  pressures need, bracket each pressure, start from a cubic and polish by Newton;
  follows the branch from the straight state, so it cannot jump branches; a fold
  narrower than the tabulation step is missed) | ``root`` (scipy ``brentq`` per
  pressure on the whole branch; may land on an unstable or later branch, or miss
  the branch, when P(theta) is not monotone; 10-20x slower).

``stable-analytic-trace`` runs the trace as a *lean solve* (:mod:`embroact.predict.lean`,
:mod:`embroact.predict.onecurve`), in the stretch ``m = (l - l0)/(2 l0)`` where P needs no
derivative of the constraint: each pressure is bracketed among fixed nodes of the branch
(nested grids, each interval at most 1/32 of the stretches it serves; for one model all
evaluated at once and kept, for a handful of pressures on Python floats only the few a search
visits, with the same bits), starts from the secant of the residuals there and is settled by
the root of a cubic through four model evaluations around it, so a first curve of a new model
costs two closed-form evaluations per pressure and one over the nodes. The trace inverse
takes only what that leaves (at or above the last node, near a fold, round-off-sized targets).
``sweep`` runs the same lean solve across designs.

Accuracy of P: ``ACCURACY * |P| + PRESSURE_FLOOR_PER_G[derivative] * G``, a relative
part (:data:`ACCURACY`) above an absolute floor (:data:`PRESSURE_FLOOR_PER_G`), both
held by the tests against the 50-digit reference over the parameter space, near
theta = 0, the neutral angle and lock-up. Relative: stable-analytic, stable-complex
and reference-complex 1e-12 (observed <= 1e-13); stable-central and reference-central
3e-7 (round-off of the difference quotient: the energy's terms are ~G l0 c and cancel
to E ~ 0 near the straight state, so the error is worst when P0 is small against G,
and near the neutral angle where dV/dtheta is small). Absolute floor: 32 eps G for
analytic and complex derivatives (7e-12 kPa per MPa of G), 128 eps^(2/3) G for central
ones (4.7e-6 kPa per MPa of G; observed <= 1.1e-6). The floor only shows where P itself
is small against G: with P0 = 0 near the straight state P -> 0 and the relative error
of central differences grows without bound (6e-7 at theta = 5.7e-5 rad, 6 % at 1e-9 rad
for l0 = 10 mm, G = 1 MPa); with P0 >= 10 kPa per MPa of G the relative part holds
alone. printed-* none: near theta = 0 the printed T loses every
digit (at |theta| = 1e-3 rad the pressure is wrong in the 1st-3rd digit, at 1e-5 rad
by orders of magnitude); it is good to ~1e-6 only beyond |theta| ~ 0.5 rad.
``"auto"`` picks the cheapest method whose accuracy meets ``rtol``
(``stable-analytic-trace`` for any ``rtol >= 1e-12``) and ``Curve.method`` names it.
``pressure_at`` uses the energy and derivative parts only.

Branch ends
-----------
The bending branch starts at theta = 0 and runs in the direction where dV/dtheta > 0
(zigzag and cross with tan(beta0) < 1/2: positive). It ends at lock-up (dV/dtheta = 0,
where P has a pole: cross designs), where the model's domain ends (d^2 <= 0), or, for
designs that never lock (zigzag), at ``MAX_BEND_DEG``, this implementation's cap.
A fold of P(theta) (dP/dtheta = 0) ends the stable part early: higher pressures snap
through and are reported ``UNSTABLE`` at the fold angle.

Examples
--------
>>> from embroact.predict.curve import ActuatorModel, curve, pressure_at, lockup
>>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0,
...                   outer_radius_mm=1.5, inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
>>> c = curve(m, [50, 85, 187.65005790858362])
>>> c.theta_deg.round(6).tolist(), c.as_dict()["status"], c.method
([0.0, 0.0, 90.0], ['INFLATION', 'INFLATION', 'BENDING'], 'stable-analytic-trace')
>>> round(float(pressure_at(m, [90.0]).pressure_kpa[0]), 6)
187.650058
>>> x = ActuatorModel("cross", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=37.20782535885358,
...                   outer_radius_mm=1.5, inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=1.3, p0_kpa=170)
>>> round(float(curve(x, [200]).theta_deg[0]), 3), round(lockup(x)[0], 3), lockup(x)[1]
(-45.638, -312.091, inf)
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, fields
from functools import lru_cache

import numpy as np

from ..patterns.base.arrays import array_max, array_min, frozen_array
from ..patterns.base.display import repr_svg
from ..patterns.base.errors import ModelDomainError, ParameterError, check_range
from ..patterns.base.records import quick_init
from ..patterns.base.tolerances import DEFAULT_TOLERANCES
from . import model as _m
from . import solvers
from .inflation import KPA_PER_MPA
from .floats import SCALAR
from .kinds import MODEL_KINDS, model_kind
from .lean import RISE_M, LeanTable, lean_table, solve_rows, solve_to_fold
from .onecurve import FLOAT_PATH_MAX, free_tube_radius, one_curve, one_curve_floats, trace_outcome, tube_radius_of
from .status import Status, status_names
from .tubelaws import check_tube_law, pressure_kpa, transition_pressure_kpa
from .validity import apply_limits

__all__ = ["ActuatorModel", "Curve", "METHODS", "ACCURACY", "PRESSURE_FLOOR_PER_G", "MAX_BEND_DEG", "ANGLE_LIMIT_DEG",
           "curve", "pressure_at", "lockup", "sweep"]

_DERIVATIVES_OF = {e: tuple(d for d in _m.DERIVATIVES if not (e == "reference" and d == "analytic"))
                   for e in _m.ENERGY_FORMS}
_INVERSES = ("trace", "root")
METHODS: tuple[str, ...] = ("auto",) + tuple(
    f"{e}-{d}-{i}" for e, ds in _DERIVATIVES_OF.items() for d in ds for i in _INVERSES
)
#: Documented relative accuracy of P per (energy, derivative), in the order "auto" tries them, above
#: the absolute floor PRESSURE_FLOOR_PER_G (the tests hold every method to it against the 50-digit reference).
ACCURACY = {("stable", "analytic"): 1e-12, ("stable", "complex"): 1e-12, ("stable", "central"): 3e-7,
            ("reference", "complex"): 1e-12, ("reference", "central"): 3e-7}
#: Largest bend the tracer follows on a branch that never locks [deg].
MAX_BEND_DEG = 3600.0
#: Largest |theta| ``pressure_at`` accepts [deg] (the constraint overflows near 1e300).
ANGLE_LIMIT_DEG = 1e6
#: Angle below which convergence is absolute: steps < rtol * THETA_FLOOR_RAD stop [rad].
THETA_FLOOR_RAD = 1e-12
#: Absolute round-off floor of P - P0 per MPa of G, by derivative: the energy's terms (~G l0 c)
#: cancel near the straight state, leaving up to ~4 eps G (analytic, complex) and ~30 eps^(2/3) G
#: (central; measured against the 50-digit reference with P0 = 0 over the property tests' designs,
#: worst a cross with l0 = 10 mm, beta0 = 26 deg). About 4-8x that is documented as the absolute
#: part of the accuracy of P, and the inverse stops where its residual is within it.
PRESSURE_FLOOR_PER_G = {"analytic": 32 * solvers.EPS, "complex": 32 * solvers.EPS,
                        "central": 128 * solvers.EPS ** (2.0 / 3.0)}
#: Tabulation points along a branch (trace inverse).
TRACE_POINTS = 128
#: Designs solved together by ``sweep`` (arrays of a block stay in cache), at most.
SWEEP_BLOCK = 128
#: Design-pressure points a ``sweep`` block holds at most: a block's working arrays (~50 of them) then
#: stay near 10 MB however many pressures a design has (fits with thousands of data rows).
SWEEP_BLOCK_POINTS = 25_600


@dataclass(frozen=True, slots=True)
class ActuatorModel:
    """Everything the model needs for one actuator, in interface units.

    Parameters
    ----------
    pattern : str
        A registered pattern kind.
    length_mm, r0_mm : float
        Fabric-side length l0 and sleeve radius r0 [mm], > 0.
    beta0_deg : float
        Thread angle at r0 [deg], in [0, 90) (0 for the zigzag).
    outer_radius_mm, inner_radius_mm, g_e_mpa : float
        Unpressurised tube r_f, d_f [mm] and its inflation-phase modulus G_e [MPa].
    g_mpa : float
        Effective modulus of tube and sleeve, G [MPa], > 0.
    p0_kpa : float
        Transition pressure P0 [kPa], >= 0.
    tube_law : str
        "paper" or "thick-wall": tube radius below P0 (see :mod:`embroact.predict.tubelaws`).
    calibration : str
        Where ``g_mpa`` and ``p0_kpa`` came from; carried into every result.
    stub_mm : float or None
        Sealed tube beyond the tip [mm], >= 0: the model is a whole strip clamped at its start
        (a single-pattern actuator: its tube's ``end_margin_mm``; 0, the default: no stub), and
        its curve's COILED status tests the stub and the supply line
        (:func:`~embroact.predict.validity.arc_contact`). ``None``: one segment of a chain,
        checked for its own full turn only (the analysis tests the chain as a whole).

    Examples
    --------
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.58, beta0_deg=0, outer_radius_mm=1.5,
    ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
    >>> m.calibration, m.tube_law
    ('given', 'paper')
    >>> ActuatorModel("zigzag", length_mm=100, r0_mm=1.4, beta0_deg=0, outer_radius_mm=1.5,
    ...               inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.ModelDomainError: r0_mm must be > outer_radius_mm=1.5 (no sleeve: ...
    """

    pattern: str
    length_mm: float
    r0_mm: float
    beta0_deg: float
    outer_radius_mm: float
    inner_radius_mm: float
    g_e_mpa: float
    g_mpa: float
    p0_kpa: float
    tube_law: str = "paper"
    calibration: str = "given"
    stub_mm: float | None = 0.0
    #: The hash of the fields, computed once (every curve looks its model's branch up by it).
    _hash: int = field(default=0, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        for name in ("beta0_deg", "p0_kpa", "inner_radius_mm"):  # those that may be 0: -0.0 is 0.0, one cache entry
            if isinstance(getattr(self, name), float) and getattr(self, name) == 0.0:
                object.__setattr__(self, name, 0.0)
        if not isinstance(self.pattern, str) or self.pattern not in MODEL_KINDS:
            raise ParameterError(f"pattern must be one of {', '.join(MODEL_KINDS)}, got {self.pattern!r}")
        for name, hi in (("length_mm", 1e5), ("r0_mm", 1e3), ("outer_radius_mm", 50.0), ("g_mpa", 1e5),
                         ("g_e_mpa", 1e4)):
            check_range(name, getattr(self, name), low=0.0, high=hi)
        check_range("inner_radius_mm", self.inner_radius_mm, low=0.0, low_inclusive=True,
                    high=float(self.outer_radius_mm))
        check_range("p0_kpa", self.p0_kpa, low=0.0, low_inclusive=True, high=1e6)
        if self.stub_mm is not None:
            check_range("stub_mm", self.stub_mm, low=0.0, low_inclusive=True, high=1e4)
        if not self.r0_mm > self.outer_radius_mm:
            raise ModelDomainError(
                f"r0_mm must be > outer_radius_mm={self.outer_radius_mm:g} (no sleeve: the thread squeezes the tube "
                f"before any pressure, the model has no inflation phase), got {self.r0_mm:g}")
        if MODEL_KINDS[self.pattern].has_thread_angle:
            check_range("beta0_deg", self.beta0_deg, low=0.0, high=90.0)
        elif self.beta0_deg != 0:
            raise ParameterError(f"beta0_deg must be 0 for the {self.pattern} pattern, got {self.beta0_deg!r}")
        check_tube_law(self.tube_law)
        if self.tube_law == "thick-wall" and self.inner_radius_mm == 0:
            raise ParameterError("inner_radius_mm must be > 0 with tube_law 'thick-wall' (a solid rod does not "
                                 "inflate), got 0")
        object.__setattr__(self, "_hash", hash(self._values()))

    def _values(self) -> tuple:
        return tuple(getattr(self, name) for name in _MODEL_FIELDS)

    def __hash__(self) -> int:
        return self._hash

    def __reduce__(self):
        """Pickled as its fields, so the hash is the unpickling process's own (strings hash per process)."""
        return type(self), self._values()

    @classmethod
    def from_derived(cls, derived, *, g_mpa, p0_kpa=None, calibration="given", tube_law="paper"):
        """Model of a :class:`~embroact.predict.derived.DerivedGeometry` with G (and P0).

        Parameters
        ----------
        derived : DerivedGeometry
            Sleeve geometry measured on generated stitches (:func:`embroact.predict.derived.derive`).
        g_mpa : float
            Effective modulus G [MPa].
        p0_kpa : float, optional
            Transition pressure [kPa]; ``None`` takes it from the geometry: the tube law's
            pressure at r0.
        calibration : str
            Where G and P0 came from.
        tube_law : str
            ``"paper"`` or ``"thick-wall"``.

        Returns
        -------
        ActuatorModel

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> from embroact.predict.analysis import analyse
        >>> d = analyse(default_design()).actuators[0].derived
        >>> m = ActuatorModel.from_derived(d, g_mpa=2.7)
        >>> m.r0_mm == d.r0_mm, round(m.p0_kpa, 3)
        (True, 84.455)
        """
        t = derived.tube
        if p0_kpa is None:
            p0_kpa = float(transition_pressure_kpa(derived.r0_mm, t, tube_law))
        return cls(derived.pattern, length_mm=derived.length_mm, r0_mm=derived.r0_mm,
                   beta0_deg=derived.beta0_deg if model_kind(derived.pattern).has_thread_angle else 0.0,
                   outer_radius_mm=t.outer_radius_mm, inner_radius_mm=t.inner_radius_mm,
                   g_e_mpa=t.g_e_mpa, g_mpa=g_mpa, p0_kpa=p0_kpa, tube_law=tube_law,
                   calibration=calibration)


#: The fields of an :class:`ActuatorModel` its hash and pickle hold (those of ``__init__``), in order.
_MODEL_FIELDS = tuple(f.name for f in fields(ActuatorModel) if f.init)


@quick_init
@dataclass(frozen=True, slots=True)
class Curve:
    """A predicted curve: read-only float64 arrays of one shape (1-D; 2-D rows per design from ``sweep``).

    Attributes
    ----------
    pressure_kpa, theta_deg : ndarray
        Pressure [kPa] and bending angle [deg] (positive: thread side longer).
    status : ndarray of int8
        :class:`~embroact.predict.status.Status` codes.
    length_mm, radius_mm, beta_deg, inner_radius_mm : ndarray
        Thread-side length l, tube outer radius r, thread angle beta, inner radius d.
    method, calibration : str
        Method used (resolved from "auto") and where G/P0 came from.

    Examples
    --------
    >>> c = curve(ActuatorModel("zigzag", length_mm=100, r0_mm=2.58, beta0_deg=0, outer_radius_mm=1.5,
    ...                     inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85), [0, 100, 200])
    >>> c
    Curve(3 pressures, 0-200 kPa, method stable-analytic-trace, calibration 'given'; INFLATION 1, BENDING 2)
    >>> c.theta_deg.flags.writeable
    False
    """

    pressure_kpa: np.ndarray
    theta_deg: np.ndarray
    status: np.ndarray
    length_mm: np.ndarray
    radius_mm: np.ndarray
    beta_deg: np.ndarray
    inner_radius_mm: np.ndarray
    method: str
    calibration: str

    def __repr__(self) -> str:
        p = self.pressure_kpa
        shape = " x ".join(str(n) for n in self.theta_deg.shape)
        span = f"{float(np.min(p)):g}-{float(np.max(p)):g} kPa" if p.size else "no pressures"
        names = status_names(self.status.reshape(-1))
        counts = ", ".join(f"{name} {names.count(name)}" for name in dict.fromkeys(names))
        return (f"Curve({shape} pressure{'s' * (p.size != 1)}, {span}, method {self.method}, "
                f"calibration {self.calibration!r}; {counts or 'no statuses'})")

    #: Bend chart in Jupyter (registered by ``embroact``).
    _repr_svg_ = repr_svg

    @property
    def segments(self) -> tuple:
        """The curves of the chain this curve is the whole strip of: itself (a chain of one segment).

        A segmented actuator's whole strip (:class:`~embroact.predict.analysis.StripCurve`) holds
        one per segment, so the views read each segment's bend the same way for one or five.
        """
        return (self,)

    def as_dict(self) -> dict:
        """Plain dict (lists, status names) with unit-suffixed keys, for JSON.

        Returns
        -------
        dict
            One key per field; arrays as lists, ``status`` as names.

        Examples
        --------
        >>> c = curve(ActuatorModel("zigzag", length_mm=100, r0_mm=2.58, beta0_deg=0, outer_radius_mm=1.5,
        ...                     inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85), [0, 100])
        >>> c.as_dict()["status"], c.as_dict()["method"]
        (['INFLATION', 'BENDING'], 'stable-analytic-trace')
        """
        out = {}
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name == "status":
                out[f.name] = status_names(v) if v.ndim <= 1 else [status_names(row) for row in v]
            else:
                out[f.name] = v.tolist() if isinstance(v, np.ndarray) else v
        return out


# -- method resolution -------------------------------------------------------------------
def _resolve(method: str, rtol: float):
    if method == "auto":
        for (energy, deriv), acc in ACCURACY.items():
            if acc <= rtol:
                return energy, deriv, "trace"
        best = min(ACCURACY.values())
        raise ParameterError(f"rtol must be >= {best:g} (the most accurate method's limit), got {rtol:g}")
    if method not in METHODS:
        raise ParameterError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    energy, deriv, inverse = method.split("-")
    return energy, deriv, inverse


# -- inputs --------------------------------------------------------------------------------
def _geometry(models) -> _m.Geometry:
    cols = np.array([(m.beta0_deg, m.length_mm, m.r0_mm, m.outer_radius_mm**2 - m.inner_radius_mm**2,
                      m.g_mpa, m.p0_kpa) for m in models], dtype=np.float64).T
    return _m.Geometry.from_values(beta0_rad=np.radians(cols[0]), l0_mm=cols[1], r0_mm=cols[2],
                                   c_mm2=cols[3], g_mpa=cols[4], p0_mpa=cols[5] / KPA_PER_MPA)


def _values(name: str, values, *, low=-np.inf, high=np.inf) -> np.ndarray:
    a = np.asarray(values, dtype=np.float64)
    a = a if a.ndim == 1 else np.atleast_1d(a)
    if a.ndim > 1:
        raise ParameterError(f"{name} must be a number or a 1-D sequence, got shape {a.shape}")
    lo, hi = (float(array_min(a)), float(array_max(a))) if a.size else (0.0, 0.0)  # NaN: both NaN
    if not (low <= lo and hi <= high and math.isfinite(lo) and math.isfinite(hi)):
        bad = ~np.isfinite(a) | (a < low) | (a > high)  # NaN fails both comparisons above
        raise ParameterError(f"{name} must be finite numbers in [{low:g}, {high:g}], got {float(a[bad][0]):g}")
    return a


def _calibrations(models) -> str:
    return ", ".join(dict.fromkeys(m.calibration for m in models))


# -- branch geometry ------------------------------------------------------------------------
def _branch_end(geo: _m.Geometry, xp=np):
    """Signed end of each design's bending branch and the status beyond it, (n, 1) each (a float and an
    int with a :meth:`~embroact.predict.model.Geometry.scalar` geometry and ``xp=SCALAR``: the same values).

    The branch runs where V grows, and ``V = pi l0 A d^2``: with ``d^2 > 0`` at the
    straight state (``r0^2 > c``) it stays positive up to lock-up, and so do ``l`` and
    ``1 - sin(beta)`` (``sin(beta)`` lies between ``s0`` and ``x_L < 1``). The domain
    therefore holds on the whole branch or, when ``r0^2 <= c``, nowhere.
    """
    lock = _m.lock_theta(geo, xp)
    cap = math.radians(MAX_BEND_DEG)
    direction = xp.where(lock < 0.0, -1.0, 1.0)
    # a lock closer to the straight state than the angle tolerance is the neutral angle
    lock = xp.where(abs(lock) < math.radians(DEFAULT_TOLERANCES.angle_solution_deg), 0.0, lock)
    kind = xp.where(abs(lock) <= cap, _LOCKED, _OUT_OF_DOMAIN)
    squeezed = geo.r0 * geo.r0 <= geo.c  # the wall does not fit in the sleeve: d^2 <= 0 already
    full = xp.where(squeezed, 0.0, direction * xp.minimum(abs(lock), cap))
    kind = xp.where(squeezed, _OUT_OF_DOMAIN, kind)
    return (full, kind) if xp is not np else (full, kind.astype(np.int8))


def _rate_fn(geo: _m.Geometry, energy: str, deriv: str):
    """rate(theta, rows=None) -> (dE/dtheta, dV/dtheta): theta (n, k) for every design, or
    at the designs ``rows`` with 1-D theta (one value each) or 2-D theta (one row each),
    the solvers' calling convention."""
    single = geo.l0.shape[0] == 1  # one design: rows need no gathering, theta lies along axis 1

    def rate(theta, rows=None):
        g = geo if rows is None or single else geo.take(rows)
        flat = theta.ndim == 1
        th = theta if not flat else theta[None, :] if single else theta[:, None]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            de, dv = _m.energy_rate(th, g, form=energy, derivative=deriv)
        return (de.ravel(), dv.ravel()) if flat else (de, dv)

    return rate


def _slope_fn(geo, energy, deriv):
    """slope(theta, rows=None) = (E'' V' - E' V'') * direction, which has the sign of dP/dtheta
    along the branch: central differences of the smooth rates (E', V' have no pole at
    lock-up; P has); for the stable analytic rates exact to round-off (:func:`_stretch_slope_fn`)."""
    if (energy, deriv) == _FAST[:2]:
        return _stretch_slope_fn(geo)
    rate = _rate_fn(geo, energy, deriv)
    direction = np.sign(_m.lock_theta(geo))
    scale = geo.l0 / (2.0 * geo.r0)

    def slope(theta, rows=None):
        de, dv = rate(theta, rows)
        d, s = (direction, scale) if rows is None else (direction[rows, 0], scale[rows, 0])
        dde, ddv = solvers.derivative(lambda t: np.stack(rate(t, rows)), theta, scale=s, method="central")
        return (dde * dv - de * ddv) * d

    return slope


def _stretch_slope_fn(geo):
    """slope(theta, rows=None) of the stable analytic rates, as :func:`_slope_fn`, exact to round-off:
    ``(F'' V' - F' V'') * direction`` in the stretch (:meth:`~embroact.predict.model.StretchRates.slope`),
    which has the sign of dP/dtheta along the branch (theta rises with the stretch) and, like the rates, no
    pole at lock-up. So a fold lies where P's slope is 0, not where the round-off of a difference quotient
    puts it (up to 4e-10 of its angle away, depending on the grid that bracketed it)."""
    rates = _m.StretchRates.of(geo)
    direction = np.sign(_m.lock_theta(geo))
    single = geo.l0.shape[0] == 1

    def slope(theta, rows=None):
        sub = rows is not None and not single
        k, d = (_m.StretchRates.of(geo.take(rows)), direction[rows]) if sub else (rates, direction)
        flat = theta.ndim == 1
        th = theta if not flat else theta[None, :] if single else theta[:, None]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            s = k.slope(k.m_of(th)) * d
        return s.ravel() if flat else s

    return slope


def _trace(geo, t, full, kind, energy, deriv, rtol):
    """The "trace" inverse on non-empty branches: (theta, status)."""
    th, where, _, _ = solvers.trace_inverse(_rate_fn(geo, energy, deriv), full, t,
                                            slope=_slope_fn(geo, energy, deriv), grid_points=TRACE_POINTS,
                                            rtol=rtol, atol=rtol * THETA_FLOOR_RAD,
                                            ptol=PRESSURE_FLOOR_PER_G[deriv] * geo.g, pole_at_end=kind == Status.LOCKED)
    return trace_outcome(th, where, full, kind)


def _lean_rows(geo, t, full, kind, energy, deriv, rtol, later=None):
    """The "trace" inverse of ``stable-analytic-trace`` on non-empty branches by the lean solve across designs
    (:func:`~embroact.predict.lean.solve_rows`); the trace inverse itself for the rows with targets it leaves,
    or, given a list ``later``, those rows and their settled entries appended to it (the caller traces the
    rows of many blocks in one call: :func:`_trace_later`)."""
    theta, settled = solve_rows(geo, t, full, kind == Status.LOCKED, rtol=rtol, atol=rtol * THETA_FLOOR_RAD,
                                floor=PRESSURE_FLOOR_PER_G[deriv] * geo.g)
    status = np.full(t.shape, Status.BENDING, dtype=np.int8)
    rows = np.flatnonzero(~settled.all(axis=1))
    if rows.size and later is not None:
        later.append((rows, settled[rows]))
    elif rows.size:  # only the targets left (the trace's zoom follows them; the others are 0: ignored)
        th, st = _trace(geo.take(rows), np.where(settled[rows], 0.0, t[rows]), full[rows], kind[rows], energy,
                        deriv, rtol)
        keep = settled[rows]
        theta[rows], status[rows] = np.where(keep, theta[rows], th), np.where(keep, Status.BENDING, st)
    return theta, status


def _fold_later(models, zigzag, blocks, later, size, rtol):
    """The entries the lean solve left in ``blocks`` (as :func:`_trace_later` takes them) on designs of
    ``s0 = 0`` (``zigzag``, per model) whose nodes end at ``RISE_M``, solved up to their fold or UNSTABLE at it
    (:func:`~embroact.predict.lean.solve_to_fold`), ``size`` rows at a time; returns ``later`` without them
    (what is left: the trace inverse's)."""
    picks = [zigzag[blocks[b][0] + rows] for b, (rows, _) in enumerate(later)]
    jobs = [(b, rows[pick], settled[pick]) for b, ((rows, settled), pick) in enumerate(zip(later, picks))]
    ours = [models[blocks[b][0] + r] for b, rows, _ in jobs for r in rows]
    if not ours:
        return later
    t = np.concatenate([np.where(keep, 0.0, blocks[b][3][rows]) for b, rows, keep in jobs])
    th, done, unstable = (np.concatenate(parts) for parts in zip(
        *(_to_fold(ours[k:k + size], t[k:k + size], rtol) for k in range(0, len(ours), size))))
    out, k = [], 0
    for (b, rows, keep), (all_rows, settled), pick in zip(jobs, later, picks):
        mine, now = slice(k, k + rows.size), settled.copy()
        k += rows.size
        theta, status = blocks[b][4], blocks[b][5]
        theta[rows] = np.where(done[mine] | unstable[mine], th[mine], theta[rows])
        status[rows] = np.where(unstable[mine], Status.UNSTABLE, np.where(done[mine], Status.BENDING, status[rows]))
        now[pick] = keep | done[mine] | unstable[mine]
        left = ~now.all(axis=1)
        out.append((all_rows[left], now[left]))
    return out


def _to_fold(models, t, rtol):
    """:func:`~embroact.predict.lean.solve_to_fold` of designs of ``s0 = 0`` at targets ``t`` (n, k), those of a
    branch that ends short of ``RISE_M`` ignored."""
    geo = _geometry(models)
    full, _ = _branch_end(geo)
    m_end = _m.StretchRates.of(geo).m_of(full)
    return solve_to_fold(geo, np.where(m_end > RISE_M, t, 0.0), m_end, rtol=rtol, atol=rtol * THETA_FLOOR_RAD)


def _trace_later(models, blocks, later, size, rtol):
    """The trace inverse of the entries the lean solve left in ``blocks`` (``[geo, pressure, targets, theta,
    status]`` of the models from ``start``, by :func:`_block_theta`), ``later`` holding (start, rows, settled)
    per block: the rows of all blocks together, ``size`` at a time (a block leaves a few rows: their calls
    would cost mostly numpy's fixed cost per operation). Each row's answers are those of its own call."""
    jobs = [(b, r, keep) for b, (rows, settled) in enumerate(later) for r, keep in zip(rows, settled)]
    for k in range(0, len(jobs), size):
        part = jobs[k:k + size]
        starts = [blocks[b][0] for b, _, _ in part]
        geo = _geometry([models[start + r] for start, (_, r, _) in zip(starts, part)])
        full, kind = _branch_end(geo)
        t = np.array([np.where(keep, 0.0, blocks[b][3][r]) for b, r, keep in part])
        th, st = _trace(geo, t, full, kind, *_FAST[:2], rtol)
        bad = ~np.isfinite(th)
        for j, (b, r, keep) in enumerate(part):
            theta, status = blocks[b][4], blocks[b][5]
            theta[r] = np.where(keep, theta[r], np.where(bad[j], 0.0, th[j]))
            status[r] = np.where(keep, status[r], np.where(bad[j], Status.FAILED, st[j]))


def _root(geo, t, full, kind, energy, deriv, rtol):
    """The "root" inverse: brentq per design and pressure on the whole branch."""
    th = np.empty_like(t)
    for k in range(t.shape[0]):
        rate = _rate_fn(geo.take([k]), energy, deriv)

        def residual(x, j, rate=rate, k=k):
            de, dv = rate(np.array([[x]]))
            return float(de[0, 0] - t[k, j] * dv[0, 0])

        th[k] = solvers.root_each(residual, np.zeros(t.shape[1]), np.full(t.shape[1], full[k, 0]), rtol=rtol,
                                  atol=rtol * THETA_FLOOR_RAD)
    p_end = np.where(kind == Status.LOCKED, np.inf, _m.pressure_mpa(full, geo, form=energy, derivative=deriv) - geo.p0)
    beyond = ~(t < np.where(np.isnan(p_end), np.inf, p_end))
    unstable = _slope_fn(geo, energy, deriv)(th) < 0
    return th, np.where(beyond, kind, np.where(unstable, Status.UNSTABLE, Status.BENDING))


@quick_init
@dataclass(frozen=True, slots=True, eq=False)
class _Branch:
    """What one model's ``auto`` curves share, computed once per (model, rtol) and cached: the geometry
    as floats, the branch end and its status, tolerances, the lean table (:mod:`embroact.predict.lean`;
    None without a branch; its node arrays are made on first use), and, made on first use only (a first curve whose pressures the lean
    solve settles needs none of them), the arrays the trace inverse and the tube law take
    (:meth:`arrays`), the trace inverse's memo (its tabulation, fold and zooms) and the float path's contact
    bound (:mod:`embroact.predict.onecurve`)."""

    model: ActuatorModel
    scalar: _m.Geometry
    end: float
    end_kind: int
    rtol: float
    atol: float
    lean: LeanTable | None
    memo: dict
    points: int
    lazy: dict

    def arrays(self) -> "_BranchArrays":
        """The numpy side of the branch (made once, on first use)."""
        if "arrays" not in self.lazy:
            geo = _geometry([self.model])
            full, kind = _branch_end(geo)
            self.lazy["arrays"] = _BranchArrays(full, kind, _rate_fn(geo, *_FAST[:2]), _slope_fn(geo, *_FAST[:2]),
                                                PRESSURE_FLOOR_PER_G[_FAST[1]] * geo.g, kind == Status.LOCKED)
        return self.lazy["arrays"]

    def laws(self):
        """The free tube's radius at pressures [MPa] below P0 (:func:`~embroact.predict.onecurve.tube_radius_of`
        with the model's tube law, as :func:`_tube_laws` gives it for one model; made once, on first use)."""
        if "laws" not in self.lazy:
            mo = self.model
            tube = (mo.outer_radius_mm, mo.inner_radius_mm, mo.g_e_mpa)
            r0 = max(self.scalar.r0, mo.outer_radius_mm)
            x = r0 / mo.outer_radius_mm  # the paper's law on floats: paper_pressure_kpa's operations
            p_sleeve = (0.5 * mo.g_e_mpa * (x - 1.0 / x) ** 2 * KPA_PER_MPA if mo.tube_law == "paper"
                        else float(pressure_kpa(r0, tube, mo.tube_law)))
            self.lazy["laws"] = tube_radius_of(mo.tube_law, tube, r0, p_sleeve, self.scalar.r0)
        return self.lazy["laws"]

    @property
    def full(self) -> np.ndarray:
        """The branch end as a (1, 1) array."""
        return self.arrays().full


@dataclass(frozen=True, slots=True)
class _BranchArrays:
    """A branch's arrays for the trace inverse: end and status (1, 1), rate, slope, pressure floor, pole."""

    full: np.ndarray
    kind: np.ndarray
    rate: object
    slope: object
    ptol: np.ndarray
    pole: np.ndarray


#: Models whose branches are kept (the studio and inverse design ask one model many times); each
#: holds its lean nodes (~16 KB: 64 branches ~1 MB) and at most one tabulation per zoom the trace
#: inverse needed (~3 KB each).
BRANCH_CACHE = 64
_FAST = ("stable", "analytic", "trace")  # what "auto" resolves to at the default rtol
_FAST_NAME = "-".join(_FAST)
#: The smallest rtol "auto" resolves to _FAST at (it is ACCURACY's first entry: tests/test_curve.py).
_FAST_RTOL = ACCURACY[_FAST[:2]]
_LOCKED, _OUT_OF_DOMAIN = int(Status.LOCKED), int(Status.OUT_OF_DOMAIN)


#: Hashes of the models a curve has asked for (:func:`_branch`, ``keep=False``), at most ``ASKED_MAX`` (then
#: forgotten at once): a model's branch is kept from its second curve on.
ASKED_MAX = 4096
_ASKED: set = set()


def _branch(model: ActuatorModel, rtol: float, *, keep: bool = True) -> _Branch:
    """The branch of ``model`` (keyed also by the module settings it depends on): the cached one, except on the first
    ``keep=False`` ask of a model none has kept, which gets one made for the call alone.

    A model asked once (a first curve, inverse design's candidates) then costs no cache entry and evicts none:
    inserting a branch and freeing the one it evicts, made long before, cost a first one-pressure curve as much as
    making it. A second ask keeps it (the same values: the branch is made the same way).
    """
    if model._hash not in _ASKED:
        if len(_ASKED) >= ASKED_MAX:
            _ASKED.clear()
        _ASKED.add(model._hash)
        if not keep:
            return _cached_branch.__wrapped__(model, rtol, MAX_BEND_DEG, TRACE_POINTS)
    return _cached_branch(model, rtol, MAX_BEND_DEG, TRACE_POINTS)


@lru_cache(maxsize=BRANCH_CACHE)
def _cached_branch(model: ActuatorModel, rtol: float, *settings) -> _Branch:
    g = _m.Geometry.of_floats(beta0_rad=math.radians(model.beta0_deg), l0_mm=model.length_mm, r0_mm=model.r0_mm,
                              c_mm2=model.outer_radius_mm**2 - model.inner_radius_mm**2, g_mpa=model.g_mpa,
                              p0_mpa=model.p0_kpa / KPA_PER_MPA)
    end, kind = _branch_end(g, SCALAR)
    atol = rtol * THETA_FLOOR_RAD
    lean = lean_table(g, theta_end=end, pole_at_end=kind == _LOCKED, rtol=rtol, atol=atol,
                      floor=PRESSURE_FLOOR_PER_G[_FAST[1]] * g.g)
    return _Branch(model, g, end, kind, rtol, atol, lean, {}, settings[1], {})


def _solve_theta(geo, targets, energy, deriv, inverse, rtol, later=None):
    """theta (n, m) for P - P0 = targets > 0 (other entries ignored) and the status per point; with a list
    ``later``, the rows the lean solve leaves (``"auto"``) appended to it as (rows, settled entries), to be
    traced by the caller."""
    full, kind = _branch_end(geo)
    theta = np.zeros(targets.shape)
    status = np.broadcast_to(kind, targets.shape).astype(np.int8)  # empty branches: the end's status
    rows = np.flatnonzero(full[:, 0] != 0.0)
    if rows.size == 0:
        return theta, status
    sub = slice(None) if rows.size == full.shape[0] else rows
    g = geo if rows.size == full.shape[0] else geo.take(rows)
    if (energy, deriv, inverse) == _FAST:
        left: list | None = None if later is None else []
        th, st = _lean_rows(g, targets[sub], full[sub], kind[sub], energy, deriv, rtol, left)
        if left:
            later += [(rows[r] if sub is rows else r, keep) for r, keep in left]
    else:
        th, st = (_trace if inverse == "trace" else _root)(g, targets[sub], full[sub], kind[sub], energy, deriv, rtol)
    bad = ~np.isfinite(th)
    theta[sub] = np.where(bad, 0.0, th)
    status[sub] = np.where(bad, Status.FAILED, st)
    return theta, status


def _tube_laws(geo, models):
    """Per tube law of the models: (rows, law, tube (r_f, d_f, G_e) columns, r0 met, pressure at r0 [kPa])."""
    out = []
    for law in dict.fromkeys(mo.tube_law for mo in models):
        sel = np.array([mo.tube_law == law for mo in models])
        tube = tuple(np.array([[getattr(mo, k)] for mo in models])[sel]
                     for k in ("outer_radius_mm", "inner_radius_mm", "g_e_mpa"))
        r0 = np.maximum(geo.r0[sel], tube[0])
        out.append((sel, law, tube, r0, pressure_kpa(r0, tube, law)))  # below the thick-wall limit: r0 is finite
    return out


def _states(geo, theta, pressure_mpa, status, laws):
    """State arrays (l, r, beta, d) at each point; inflation points from the tube law (``_tube_laws``,
    :func:`~embroact.predict.onecurve.free_tube_radius`)."""
    l, r, sinb, _ = _m.constraint(theta, geo)
    d2 = _m.inner_radius_sq(l, r, geo)
    infl = status == Status.INFLATION
    if infl.any():
        r_law = np.empty_like(theta)
        for sel, law, tube, r0, p_sleeve in laws:
            r_law[sel] = free_tube_radius(pressure_mpa[sel], law, tube, r0, p_sleeve, geo.r0[sel])
        r = np.where(infl, r_law, r)
        d2 = np.where(infl, r * r - geo.c, d2)
    return l, r, np.degrees(np.arcsin(np.clip(sinb, -1.0, 1.0))), np.sqrt(np.maximum(d2, 0.0))


def _block_theta(models, start, p, energy, deriv, inverse, rtol, later=None):
    """[start, geo, pressure [MPa], targets, theta, status] of a block of models at pressures ``p`` [MPa]
    (``later``: as :func:`_solve_theta` takes it)."""
    geo = _geometry(models)
    pressure = p[None, :] if len(models) == 1 else np.broadcast_to(p, (len(models), p.size))
    targets = pressure - geo.p0
    theta, status = _solve_theta(geo, np.where(targets > 0.0, targets, 0.0), energy, deriv, inverse, rtol, later)
    return [start, geo, pressure, np.where(targets > 0.0, targets, 0.0), theta, status]


def _block_states(models, block, limits=True):
    """Arrays (P, theta, status, l, r, beta, d) of a block (:func:`_block_theta`)."""
    _, geo, pressure, targets, theta, status = block
    infl = targets <= 0.0
    theta = np.where(infl, 0.0, theta)
    status = np.where(infl, Status.INFLATION, status).astype(np.int8)
    states = _states(geo, theta, pressure, status, _tube_laws(geo, models))
    if limits:  # validity limits (validity.py)
        stub = np.array([[math.nan if m.stub_mm is None else m.stub_mm] for m in models], dtype=np.float64)
        status = apply_limits(status, theta, states[0], states[1], geo.l0, stub_mm=stub)
    return (pressure * KPA_PER_MPA, np.degrees(theta), status) + states


# -- public API ----------------------------------------------------------------------------
def sweep(models, pressures_kpa, *, method: str = "auto", rtol: float = DEFAULT_TOLERANCES.model_rtol,
          limits: bool = True) -> Curve:
    """theta(P) for many designs at once: a :class:`Curve` of 2-D arrays, one row per model.

    Parameters
    ----------
    models : sequence of ActuatorModel
        The designs, at least one.
    pressures_kpa : array_like
        Pressures [kPa], >= 0, shared by all models.
    method : str
        One of :data:`METHODS` (see the module docstring).
    rtol : float
        Relative tolerance of the equilibrium angle (and the accuracy "auto" must meet).
    limits : bool
        Report the validity limits (COILED, KINKED, OVERSTRETCHED; :mod:`embroact.predict.validity`);
        False gives the formula's own statuses, for studies of the formula beyond them.

    Returns
    -------
    Curve
        Every array of shape (models, pressures).

    Examples
    --------
    >>> from embroact.predict.curve import ActuatorModel, sweep
    >>> ms = [ActuatorModel("zigzag", length_mm=100, r0_mm=r0, beta0_deg=0, outer_radius_mm=1.5,
    ...                     inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85) for r0 in (2.4, 2.6)]
    >>> sweep(ms, [50, 150]).theta_deg.shape
    (2, 2)
    """
    models = list(models)
    if not models or not all(isinstance(mo, ActuatorModel) for mo in models):
        raise ParameterError("models must be a non-empty sequence of ActuatorModel")
    return _solve(models, pressures_kpa, method, rtol, squeeze=False, limits=limits)


def _solve(models, pressures_kpa, method, rtol, *, squeeze, limits=True):
    check_range("rtol", rtol, low=0.0, high=1.0)
    energy, deriv, inverse = _resolve(method, rtol)
    p = _values("pressure_kpa", pressures_kpa, low=0.0) / KPA_PER_MPA
    if len(models) == 1 and (energy, deriv, inverse) == _FAST:  # one model: its cached branch, the lean solve
        arrays = one_curve(_branch(models[0], rtol, keep=False), p, limits=limits)
        if not squeeze:
            arrays = tuple(a[None, :] for a in arrays)
    else:
        arrays = _blocks(models, p, energy, deriv, inverse, rtol, limits)
        if squeeze:
            arrays = tuple(a[0] for a in arrays)
    return Curve(*(_frozen(a) for a in arrays), method=f"{energy}-{deriv}-{inverse}",
                 calibration=_calibrations(models))


def _blocks(models, p, energy, deriv, inverse, rtol, limits):
    """The arrays (P, theta, status, l, r, beta, d) of ``sweep``, (models, pressures) each: the models solved
    ``SWEEP_BLOCK`` (or fewer, by ``SWEEP_BLOCK_POINTS``) at a time, zigzag designs first (a block then holds one
    pattern and takes its shorter closed forms: :class:`~embroact.predict.model.StretchRates` and
    :func:`~embroact.predict.model.constraint` on zigzag rows only), the rows the lean solve leaves in every
    block traced together."""
    zigzag = np.array([mo.beta0_deg == 0.0 for mo in models], dtype=bool)  # s0 = 0
    order = np.concatenate([np.flatnonzero(zigzag), np.flatnonzero(~zigzag)])
    models, zigzag = [models[k] for k in order], zigzag[order]
    size = max(1, min(SWEEP_BLOCK, SWEEP_BLOCK_POINTS // max(p.size, 1)))
    blocks, left = [], []  # per block, the rows the lean solve leaves: traced together
    for k in range(0, len(models), size):
        mine: list = []
        blocks.append(_block_theta(models[k:k + size], k, p, energy, deriv, inverse, rtol, mine))
        left.append(mine)
    later = [(np.concatenate([r for r, _ in mine]), np.concatenate([s for _, s in mine]))
             if mine else (np.empty(0, dtype=np.intp), np.empty((0, p.size), dtype=bool)) for mine in left]
    if any(rows.size for rows, _ in later):
        later = _fold_later(models, zigzag, blocks, later, size, rtol)
    if any(rows.size for rows, _ in later):
        _trace_later(models, blocks, later, size, rtol)
    parts = [_block_states(models[b[0]:b[0] + size], b, limits) for b in blocks]
    return tuple(_in_order(order, size, [part[j] for part in parts]) for j in range(len(parts[0])))


def _in_order(order, size, parts):
    """One array of the blocks' ``parts`` (the rows of models ``order[k:k + size]`` each) in the models' order."""
    out = np.empty((order.size,) + parts[0].shape[1:], dtype=parts[0].dtype)
    for k, part in zip(range(0, order.size, size), parts):
        out[order[k:k + size]] = part
    return out


def _frozen(a: np.ndarray) -> np.ndarray:
    """``a`` read-only, without a copy where it owns a fresh buffer (not a view of a shared input)."""
    if isinstance(a, np.ndarray) and a.flags.writeable and (a.base is None or a.base.flags.owndata):
        a.setflags(write=False)
        return a
    return frozen_array(a, dtype=None)


def curve(model: ActuatorModel, pressures_kpa, *, method: str = "auto",
          rtol: float = DEFAULT_TOLERANCES.model_rtol, limits: bool = True) -> Curve:
    """Bending angle theta(P) and state at each pressure [kPa] (1-D arrays).

    Below P0: ``INFLATION``, theta = 0. Above: the equilibrium on the branch that
    starts straight; pressures past a fold are ``UNSTABLE`` at the fold angle,
    past a lock-up ``LOCKED`` at the lock angle, past the domain or the tracing cap
    ``OUT_OF_DOMAIN`` at the end angle; states beyond a validity limit take that
    limit's status (COILED, KINKED, OVERSTRETCHED) with the formula's values.

    Parameters
    ----------
    model : ActuatorModel
    pressures_kpa : array_like
        Pressures [kPa], >= 0.
    method, rtol, limits
        As for :func:`sweep`.

    Returns
    -------
    Curve
        1-D arrays, one value per pressure.

    Raises
    ------
    ParameterError
        A negative or non-finite pressure, an unknown method, an rtol out of range.

    Examples
    --------
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.58, beta0_deg=0, outer_radius_mm=1.5,
    ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
    >>> [round(float(t), 1) for t in curve(m, [50, 100, 200]).theta_deg]
    [0.0, 11.5, 102.9]
    """
    if not isinstance(model, ActuatorModel):
        raise ParameterError(f"model must be an ActuatorModel, got {type(model).__name__}")
    quick = _float_path(model, pressures_kpa, method, rtol, limits)
    return quick if quick is not None else _solve([model], pressures_kpa, method, rtol, squeeze=True, limits=limits)


def _float_path(model, pressures_kpa, method, rtol, limits):
    """The curve of a handful of bending pressures on Python floats (:func:`~embroact.predict.onecurve.
    one_curve_floats`), or None for the array path (which also reports bad input)."""
    if not (type(rtol) is float and _FAST_RTOL <= rtol < 1.0 and (method == "auto" or method == _FAST_NAME)):
        return None  # another method, or an rtol the array path checks
    if isinstance(pressures_kpa, np.ndarray):  # of numbers: its values are Python numbers
        if not (pressures_kpa.ndim == 1 and 0 < pressures_kpa.size <= FLOAT_PATH_MAX
                and pressures_kpa.dtype.kind in "fiu"):
            return None
        values = pressures_kpa.tolist()
    else:
        values = ([pressures_kpa] if isinstance(pressures_kpa, (float, int)) else pressures_kpa
                  if isinstance(pressures_kpa, (list, tuple)) and len(pressures_kpa) <= FLOAT_PATH_MAX else None)
        if not values or not all(isinstance(v, (float, int)) and not isinstance(v, bool) for v in values):
            return None
    for v in values:
        if not 0.0 <= v < math.inf:  # also NaN
            return None
    got = one_curve_floats(_branch(model, rtol, keep=False), [v / KPA_PER_MPA for v in values], limits=limits)
    if got is None:
        return None
    rows = np.array(got[0])  # the float columns: one array, whose rows are read-only views
    rows.setflags(write=False)
    rows = rows.reshape(6, len(values))  # indexed, not unpacked: an iterator over rows costs more
    return Curve(rows[0], rows[1], _status_array(tuple(got[1])), rows[2], rows[3], rows[4], rows[5], _FAST_NAME,
                 model.calibration)  # by position: a first curve's cost


@lru_cache(maxsize=256)
def _status_array(codes: tuple) -> np.ndarray:
    """The read-only int8 array of a float path's statuses (one per tuple: curves may share it, as none can
    change it)."""
    return frozen_array(codes, dtype=np.int8)


def pressure_at(model: ActuatorModel, theta_deg, *, method: str = "auto", limits: bool = True) -> Curve:
    """Pressure P(theta) [kPa] holding each bending angle [deg], with the state there.

    theta = 0 gives P0 (``INFLATION``). Angles no pressure >= P0 reaches carry the
    fill pressure P0: the wrong bending direction and angles past the domain end
    (``OUT_OF_DOMAIN``), angles at or past lock-up (``LOCKED``). Angles on a falling
    part of P(theta) are ``UNSTABLE`` with their (real) pressure. Angles beyond a
    validity limit take its status and keep the pressure of the status they replace
    (``limits`` as for :func:`sweep`).

    Parameters
    ----------
    model : ActuatorModel
        The design.
    theta_deg : array_like
        Bend angles [deg].
    method : str, optional
        One of :data:`METHODS`.
    limits : bool, optional
        As for :func:`sweep`.

    Returns
    -------
    Curve
        One point per angle; ``pressure_kpa`` holds the answer.

    Examples
    --------
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814206750769157, beta0_deg=0, outer_radius_mm=1.5,
    ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
    >>> c = pressure_at(m, [0.0, 90.0])
    >>> c.pressure_kpa.round(3).tolist(), status_names(c.status)
    ([85.0, 187.65], ['INFLATION', 'BENDING'])
    """
    energy, deriv, inverse = _resolve(method, DEFAULT_TOLERANCES.model_rtol)
    th = np.radians(_values("theta_deg", theta_deg, low=-ANGLE_LIMIT_DEG, high=ANGLE_LIMIT_DEG))[None, :]
    geo = _geometry([model])
    full, kind = _branch_end(geo)
    p = _m.pressure_mpa(th, geo, form=energy, derivative=deriv)
    slope = _slope_fn(geo, energy, deriv)(th)
    along = th * np.sign(np.where(full == 0.0, 1.0, full))  # progress along the branch
    past = (along > np.abs(full)) | ((full == 0.0) & (th != 0.0))
    status = np.where(th == 0.0, Status.INFLATION,
             np.where((along < 0.0) & (full != 0.0), Status.OUT_OF_DOMAIN,
             np.where(past | ((kind == Status.LOCKED) & (along >= np.abs(full))), kind,
             np.where(~np.isfinite(p), Status.FAILED,
             np.where(slope < 0.0, Status.UNSTABLE, Status.BENDING))))).astype(np.int8)
    filled = (status != Status.BENDING) & (status != Status.UNSTABLE)
    p = np.where(filled, geo.p0, p)
    theta = np.where(status == Status.FAILED, 0.0, th)  # other points show the state at the angle asked for
    states = _states(geo, theta, p, status, _tube_laws(geo, [model]))
    if limits:  # validity limits (validity.py); the pressure keeps the value of the status replaced
        status = apply_limits(status, theta, states[0], states[1], geo.l0, stub_mm=model.stub_mm)
    arrays = [p * KPA_PER_MPA, np.degrees(theta), status, *states]
    return Curve(*(frozen_array(a[0], dtype=None) for a in arrays), method=f"{energy}-{deriv}-{inverse}",  # type: ignore[misc, arg-type]
                 calibration=model.calibration)


def lockup(model: ActuatorModel) -> tuple[float, float]:
    """(theta_deg, pressure_kpa) where the stable branch ends (stable analytic method).

    Lock-up (cross designs): the lock angle and ``math.inf`` (P has a pole there).
    Otherwise the fold (snap-through), the domain end or the tracing cap
    ``MAX_BEND_DEG``, with the finite pressure there. Kept per model (identical actuators, repeated
    checks: the search runs once).

    Parameters
    ----------
    model : ActuatorModel
        The design.

    Returns
    -------
    theta_deg, pressure_kpa : float
        Where the stable branch ends [deg] and the pressure there [kPa].

    Examples
    --------
    >>> m = ActuatorModel("cross", length_mm=100, r0_mm=2.6, beta0_deg=20.0, outer_radius_mm=1.5,
    ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=1.3, p0_kpa=170)
    >>> theta, p = lockup(m)
    >>> round(theta, 2), p
    (455.58, inf)
    """
    return _cached_lockup(model, MAX_BEND_DEG, TRACE_POINTS)


@lru_cache(maxsize=BRANCH_CACHE)
def _cached_lockup(model: ActuatorModel, *settings) -> tuple[float, float]:
    geo = _geometry([model])
    full, kind = _branch_end(geo)
    if full[0, 0] == 0.0:
        return 0.0, (math.inf if kind[0, 0] == Status.LOCKED else float(model.p0_kpa))
    rate = _rate_fn(geo, "stable", "analytic")
    _, _, stop, p_stop = solvers.trace_inverse(rate, full, np.empty((1, 0)), slope=_slope_fn(geo, "stable", "analytic"),
                                               grid_points=TRACE_POINTS * 4,
                                               rtol=DEFAULT_TOLERANCES.model_rtol, atol=0.0,
                                               pole_at_end=kind == Status.LOCKED)
    theta = float(np.degrees(stop[0, 0]))
    if stop[0, 0] == full[0, 0] and kind[0, 0] == Status.LOCKED:
        return theta, math.inf
    return theta, float((geo.p0[0, 0] + p_stop[0, 0]) * KPA_PER_MPA)
