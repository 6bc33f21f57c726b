"""Inverse design: from the bend or the shape a user wants at one pressure to embroidery parameters.

Two questions (docs/model.md, segmented actuators):

* **target bend** (:func:`design_bend`): which single actuator of length ``L`` bends by
  ``theta*`` at ``P*``? Each pattern has one free parameter inside its calibrated range
  (zigzag: the width ``w``; cross: the angle ``alpha0`` at the calibrated width), the
  interval is the calibrated one (cross: the nearest that closes the pattern, so the
  angle is sewn as asked). ``theta(P*)`` is tabulated over the parameter with the
  vectorised model (:func:`~embroact.predict.curve.sweep`), every crossing of the target
  is polished by regula falsi, and the bends the space reaches in a valid state are refined
  to their exact extremes (the verdict: a target outside them is refused with the true
  extreme). The designs tried are the ones a machine sews: a straight actuator's rails lie
  at +-w/2 on the machine grid, so a zigzag width steps by 0.2 mm on a path along a grid line
  (the grid widths around each crossing are tried); a cross angle is the mean over many legs and is polished on the
  generated needle points. Each candidate is generated and analysed like any design (the
  numbers ``embroact predict`` prints for the written file); it must be in a valid model
  state at ``P*`` (BENDING: not coiled, kinked, overstretched, locked or unstable) and pass
  the design rules without errors; clean candidates rank above ones with warnings, then the
  length asked for, then the narrower 1-sigma band of the bend (a calibration's covariance). A
  straight path moved half a grid unit sideways (:func:`rail_offset_mm`) puts the rails of
  a width of an odd number of grid units on the grid too, so a zigzag's width steps by
  0.1 mm; where that still misses, a length within ``length_tolerance_mm`` of the one asked
  for (default 0: the length stays) meets the bend in 0.1 mm steps of length. A target
  no sewable design meets within the tolerance gets the nearest one and the pressure at
  which that design bends by the target exactly.
* **target shape** (:func:`design_shape`): which segmented actuator bends into a given
  planar curve at ``P*``? The bent fabric line of a segmented actuator is a chain of
  circular arcs (segments decouple), so its curvature is piecewise constant. The target's
  curvature is fitted by ``n`` constant pieces (boundaries and curvatures by least squares
  on the positions, started from an optimal piecewise-constant split of the target's
  curvature, ``n = 1 .. max_segments``, the fewest that fit); each piece's bend
  ``kappa_k L_k`` is then inverted to a pattern parameter at ``P*`` (positive: zigzag
  width, or a cross angle below the neutral angle when no zigzag reaches it; negative:
  a cross angle above it), and all parameters are polished together on the predicted
  shape of the segmented design (legs, transitions and unbent gaps as generated). The widths
  are then moved to sewable ones (the segments share one straight path: all an even number of
  grid units, or, with no cross segment whose calibrated width holds the path on a grid line, all
  odd on a path moved half a unit) and a pattern search on the analysed design (needle points
  on the machine grid) refines widths, angles and segment boundaries.

Unreachable targets get the best achievable design and a plain ``statement`` of why.
Everything is deterministic: the same target gives the same design.

Examples
--------
>>> from embroact.predict.inverse import design_bend
>>> r = design_bend(84.5, 150.0, pattern="zigzag")
>>> r.reached, r.best.pattern, r.best.params.width_mm, round(r.best.theta_deg, 2)
(True, 'zigzag', 6.2, 84.53)
>>> r = design_bend(88.0, 150.0, pattern="zigzag")   # between the sewable widths 6.2 and 6.1 mm
>>> r.reached, r.in_range, r.best.params.width_mm, round(r.best.theta_deg, 2), round(r.best.exact_pressure_kpa, 1)
(False, True, 6.1, 90.22, 148.2)
>>> r = design_bend(88.0, 150.0, pattern="zigzag", length_tolerance_mm=3.0)   # 97.5 mm long meets it
>>> r.reached, r.best.params.width_mm, r.best.length_mm, round(r.best.theta_deg, 2)
(True, 6.1, 97.5, 87.96)
"""
from __future__ import annotations

import dataclasses
import functools
import itertools
import math
from dataclasses import dataclass
from typing import Any, Callable, Iterable

import numpy as np

from ..patterns.base.arrays import median
from ..patterns.base.errors import EmbroactError, ParameterError, check_range
from ..patterns.base.tolerances import DEFAULT_TOLERANCES
from ..patterns.centerline import Centerline
from ..patterns.design import ActuatorSpec, Design, MachineSettings, ModelSettings, OperationSettings
from ..patterns.kinds import PATTERN_KINDS, Interval, param_values, pattern_kind
from ..patterns.limits import grid_origin_mm, rail_offset_mm
from ..patterns.params import PatternParams, Tube, whole_intervals
from ..patterns.segments import SegmentSpec, chain_of_one
from .kinds import model_kind
from .status import Status

__all__ = ["MAX_TARGET_PRESSURE_KPA", "check_target_pressure", "DesignSpace", "design_space",
           "Sensitivity", "BendCandidate", "BendResult", "design_bend", "exact_pressure_kpa", "angle_grid_step_deg",
           "ShapeSegment", "ShapeResult", "design_shape", "fit_curvature", "curvature_range", "shape_unreachable",
           "DEFAULT_TIME_LIMIT_S", "operating_limits"]

#: Points of the parameter table per pattern.
_TABLE_POINTS = 121
#: Models a search keeps (:class:`_Model`).
_MODELS_KEPT = 4096
#: A candidate's bend must match the target within this after polishing [deg].
_BEND_TOL_DEG = 1e-3
#: States in which a segment's prediction is valid.
_VALID = (int(Status.BENDING), int(Status.INFLATION))
#: Target shapes are resampled at this many arc-length points.
_SHAPE_SAMPLES = 201
#: A curvature fit this close (RMSE) needs no more segments [mm].
_FIT_GOOD_MM = 0.02
#: Rounds of the parameter polish (leg extents regenerated between rounds).
_POLISH_ROUNDS = 6
#: Curvature fits worse than this (RMSE) are not tried as designs [mm].
_FIT_PLAUSIBLE_MM = 0.25
#: A reached design this close (RMSE) ends the search over segment counts (fewer segments win) [mm].
_SHAPE_GOOD_MM = 0.2
#: Rounds of single-step moves of the sewable (grid) parameters of a designed shape.
_GRID_ROUNDS = 6
#: The pattern search reports its progress every this many sewn designs.
_PROGRESS_EVERY = 25
#: First step of a continuous parameter (cross angle) in that search [deg], refined to an eighth.
_SHAPE_ANGLE_STEP_DEG = 0.2
#: First step of a segment boundary in that search [mm], refined with the angle step.
_SHAPE_LENGTH_STEP_MM = 1.0
#: Segments beyond the fewest that fit the curvature tried when the sewable designs miss the target.
_EXTRA_SEGMENTS = 2
#: Shortest segment the curvature fit may make [mm].
_MIN_SEGMENT_MM = 8.0
#: Default time limit of a target-shape search [s] (``design_shape(time_limit_s=...)``, ``--time-limit``).
DEFAULT_TIME_LIMIT_S = 60.0
#: Reachability of a target shape (:func:`curvature_range`, :func:`shape_unreachable`): the segment length of
#: the one scan per pattern [mm], the relative slack (the scan at one length stands for every length), the
#: start over which the heading at the clamp is taken [mm] and its slack [deg] (also of the whole bend), the
#: window of a corner [mm] and its slack [deg] (a noisy target, a random walk of 9 deg per 0.5 mm, stays within).
_REACH_LENGTH_MM, _REACH_SLACK = 100.0, 1.1
_REACH_WINDOW_MM, _REACH_HEADING_DEG = 5.0, 30.0
_REACH_CORNER_MM, _REACH_CORNER_DEG = 2.0, 60.0



#: Highest target pressure a search accepts [kPa] (far above any tube; larger is a typo).
MAX_TARGET_PRESSURE_KPA = 10_000.0


def check_target_pressure(value, name: str = "pressure_kpa") -> float:
    """``value`` if it is a pressure in (0, MAX_TARGET_PRESSURE_KPA) kPa, else one-line ParameterError naming ``name``.

    Parameters
    ----------
    value : object
        The pressure [kPa].
    name : str, optional
        The parameter's name for the message.

    Returns
    -------
    float

    Examples
    --------
    >>> check_target_pressure(150.0)
    150.0
    """
    return check_range(name, value, low=0.0, high=MAX_TARGET_PRESSURE_KPA)

@dataclass(frozen=True, slots=True)
class DesignSpace:
    """The one free parameter of a pattern and its allowed range.

    Attributes
    ----------
    pattern : str
        The pattern kind.
    parameter : str
        The kind's calibration axis (``"width_mm"``, ``"angle_deg"``).
    low, high : float
        Range of the parameter [mm or deg].
    width_mm, interval_mm : float
        The calibrated (median) width and the nominal interval; the kind's ``design_params``
        uses what it needs of them.
    calibrated : bool
        False when the range goes beyond the calibration (``allow_extrapolation``).

    Examples
    --------
    >>> s = DesignSpace("zigzag", "width_mm", 5.0, 9.0, 7.0, 1.0)
    >>> s.params(6.5), s.grid_step, s.describe()
    (ZigzagParams(width_mm=6.5, interval_mm=1.0), 0.2, 'width_mm 5 to 9 (calibrated)')
    """

    pattern: str
    parameter: str
    low: float
    high: float
    width_mm: float
    interval_mm: float
    calibrated: bool = True

    def params(self, x: float) -> PatternParams:
        """Pattern parameters at parameter value ``x`` (the kind's :attr:`~embroact.patterns.kinds.PatternKind.design_params`).

        Parameters
        ----------
        x : float
            The free parameter's value [mm or deg].

        Returns
        -------
        PatternParams

        Raises
        ------
        ParameterError
            The kind has no design space.

        Examples
        --------
        >>> s = DesignSpace("cross", "angle_deg", 15.0, 60.0, 7.0, 1.4)
        >>> p = s.params(40.0)
        >>> round(p.interval_mm, 4), round(2 * 7.0 * math.tan(math.radians(40.0)) / p.interval_mm, 9)
        (1.4684, 8.0)
        """
        make = pattern_kind(self.pattern).design_params
        if make is None:
            raise ParameterError(f"pattern {self.pattern!r} has no design space")
        return make(x, self.width_mm, self.interval_mm)

    @property
    def grid_step(self) -> float:
        """Step [mm] between the values of the free parameter a straight actuator on a path along a grid line
        sews exactly; 0 for a parameter the sewn legs realise continuously.

        A straight path's rails lie at +-w/2, so a width lands on the machine grid in steps of two grid
        units (0.2 mm) on a path along a grid line, and in steps of one unit when the path may move half a
        unit sideways (:func:`rail_offset_mm`; ``sewable(..., step=grid / 1)``); a cross angle is the mean
        over many legs whose ends round differently, so the sewn angle follows the asked one closely (the
        analysed design measures it).

        >>> DesignSpace("zigzag", "width_mm", 5.0, 9.0, 7.0, 1.0).grid_step, DesignSpace("cross", "angle_deg", 15.0, 60.0, 7.0, 1.4).grid_step
        (0.2, 0.0)
        """
        if self.parameter != "width_mm":
            return 0.0
        return 2.0 * DEFAULT_TOLERANCES.machine_grid_mm

    def sewable(self, x: float, spread: int = 1, *, step: float | None = None, offset: float = 0.0) -> tuple[float, ...]:
        """The sewable values of the parameter around ``x``: the grid values below and above it and
        ``spread - 1`` more on each side, inside the range (``(x,)`` for a continuous parameter).

        ``step`` is the grid step of the parameter (default :attr:`grid_step`; one machine-grid unit for a
        straight path moved by :func:`rail_offset_mm`); the values are ``offset`` plus whole steps (one
        grid unit: the widths of an odd number of units, on a path moved half a unit).

        Parameters
        ----------
        x : float
            The parameter's value [mm or deg].
        spread : int, optional
            Grid values on each side.
        step : float or None, optional
            The grid step; None: :attr:`grid_step`.
        offset : float, optional
            The grid's value next to 0 [mm].

        Returns
        -------
        tuple of float
            Ascending, inside the range.

        Examples
        --------

        >>> DesignSpace("zigzag", "width_mm", 5.0, 9.0, 7.0, 1.0).sewable(6.1529)
        (6.0, 6.2)
        >>> DesignSpace("zigzag", "width_mm", 5.0, 9.0, 7.0, 1.0).sewable(9.0, spread=2)
        (8.8, 9.0)
        >>> DesignSpace("zigzag", "width_mm", 5.0, 9.0, 7.0, 1.0).sewable(6.1529, step=0.1)
        (6.1, 6.2)
        >>> DesignSpace("zigzag", "width_mm", 5.0, 9.0, 7.0, 1.0).sewable(8.95, offset=0.1)
        (8.9,)
        """
        step = self.grid_step if step is None or self.grid_step == 0.0 else step
        if step == 0.0:
            return (float(x),)
        u = (x - offset) / step
        k_lo, k_hi = math.floor(u + 1e-9), math.ceil(u - 1e-9)
        ks = range(k_lo - spread + 1, k_hi + spread)
        return tuple(v for v in (round(k * step + offset, 10) for k in ks) if self.low - 1e-9 <= v <= self.high + 1e-9)

    def describe(self) -> str:
        """``"width_mm 5 to 9 (calibrated)"``.

        Returns
        -------
        str
            Parameter, range and whether it is the calibrated one.

        Examples
        --------
        >>> DesignSpace("zigzag", "width_mm", 4.0, 9.0, 7.0, 1.0, False).describe()
        'width_mm 4 to 9 (extrapolated)'
        """
        return f"{self.parameter} {self.low:g} to {self.high:g} ({'calibrated' if self.calibrated else 'extrapolated'})"


def design_space(pattern: str, settings: ModelSettings = ModelSettings(), *, sets=(), tube: Tube = Tube(),
                 allow_extrapolation: bool = False) -> DesignSpace:
    """The range a pattern's free parameter may take: the calibration set's coverage, and for a cross
    pattern the angles whose legs (``w / cos(alpha0)``, rounded to the machine grid) fit one stitch of the
    default machine.

    Parameters
    ----------
    pattern : str
        A registered pattern kind.
    settings : ModelSettings, optional
        The calibration and tube law.
    sets : iterable of CalibrationSet, optional
        Extra calibration sets.
    tube : Tube, optional
        The tube.
    allow_extrapolation : bool, optional
        Go beyond the calibrated range, to the range the model holds.

    Returns
    -------
    DesignSpace

    Raises
    ------
    ParameterError
        The kind has no design space, or the calibration has no points of it.

    Examples
    --------
    >>> design_space("zigzag").describe(), design_space("cross").describe()
    ('width_mm 5 to 9 (calibrated)', 'angle_deg 15 to 54.172 (calibrated)')
    """
    from .calibration import get_set

    kind = pattern_kind(pattern)  # a registered kind, else one line naming them
    if kind.design_params is None:
        raise ParameterError(f"pattern {pattern!r} has no design space (its kind gives no design_params); "
                             "choose another pattern")
    cset = get_set(settings.calibration, tuple(sets))
    cover = cset.coverage().get(pattern)
    points = [p for p in cset.points if p.pattern == pattern]
    if cover is None or not points:
        raise ParameterError(f"calibration {cset.name!r} has no {pattern} points; choose another pattern or set")
    interval = median([p.interval_mm for p in points if p.interval_mm is not None] or [1.0])
    width = median([p.width_mm for p in points])
    param = kind.calibration_axis
    low, high = cover
    if pattern_kind(pattern).has_angle:  # a leg w / cos(alpha0) must fit one machine stitch, rounded to the grid
        from ..patterns.limits import GRID_ROUNDING_MM

        longest = MachineSettings().max_stitch_mm - 2.0 * GRID_ROUNDING_MM
        if width < longest:
            high = min(high, math.degrees(math.acos(width / longest)))
    if allow_extrapolation:
        wide = model_kind(pattern).extrapolated_range
        low, high = min(low, wide[0]), max(high, wide[1])
        if param == "width_mm":  # a width clears the tube corridor
            low = max(low, 2.0 * tube.corridor_radius_mm + 0.2)
    return DesignSpace(pattern, param, float(low), float(high), width, interval, not allow_extrapolation)


def design_spaces(settings: ModelSettings = ModelSettings(), *, sets=(), tube: Tube = Tube(),
                  allow_extrapolation: bool = False) -> tuple[dict[str, DesignSpace], tuple[str, ...]]:
    """The design space of every registered kind that has one, and a note for each kind skipped.

    A kind is skipped when it gives no ``design_params`` or the calibration holds no points of it.

    Parameters
    ----------
    settings, sets, tube, allow_extrapolation
        As for :func:`design_space`.

    Returns
    -------
    spaces : dict of str to DesignSpace
        By kind name.
    notes : tuple of str
        One line per kind skipped.

    Examples
    --------
    >>> spaces, notes = design_spaces()
    >>> spaces["zigzag"].describe(), [n for n in notes if "zigzag" in n or "cross" in n]
    ('width_mm 5 to 9 (calibrated)', [])
    """
    spaces, notes = {}, []
    for kind in PATTERN_KINDS:
        try:
            spaces[kind.name] = design_space(kind.name, settings, sets=sets, tube=tube,
                                             allow_extrapolation=allow_extrapolation)
        except ParameterError as exc:
            notes.append(f"{kind.name} skipped: {str(exc).split(';')[0]}")
    if not spaces:
        raise ParameterError("no pattern kind has a design space with this calibration: " + "; ".join(notes))
    return spaces, tuple(notes)


def _legs(params, length_mm: float) -> tuple[float, float]:
    """(gap before the legs, legs' length) of a segment of ``length_mm`` on a straight path, nominally.

    The span the generators fill: the largest multiple of the interval, centred. A zigzag's
    legs cover it exactly; a cross pattern's may end up to a leg short of it where passes
    turn (:func:`_legs_sewn` generates it).
    """
    return _span_legs(params.interval_mm, length_mm)


def _span_legs(s: float, length_mm: float) -> tuple[float, float]:
    """:func:`_legs` for interval ``s`` [mm]."""
    span = whole_intervals(length_mm, s) * s
    return 0.5 * (length_mm - span), span


@functools.lru_cache(maxsize=4096)
def _legs_sewn(params, length_mm: float) -> tuple[float, float]:
    """(gap before the legs, legs' length) of a segment as its generator sews it on a straight path."""
    if pattern_kind(params.pattern).interval is Interval.NEEDLE_POINTS:  # one leg per interval: the span exactly
        return _legs(params, length_mm)
    from ..patterns.plan import Role

    plan = chain_of_one(Centerline.straight(length_mm), params)
    x = plan.xy_mm[:, 0]
    legs = np.flatnonzero(plan.roles == Role.LEG)
    ends = np.union1d(legs, legs - 1)
    return float(x[ends].min()), float(plan.actuators[0].realised.length_mm)


class _Model:
    """theta(P*) of pattern parameters, through the same derived geometry and model factory as a design."""

    def __init__(self, pressure_kpa: float, tube: Tube, settings: ModelSettings, sets,
                 stub_mm: float | None = None) -> None:
        # stub_mm: a one-actuator design's models are whole strips (the tube's end margin); a segment's are arcs
        self.p, self.tube, self.settings, self.sets = float(pressure_kpa), tube, settings, tuple(sets)
        self.stub_mm = stub_mm
        # a search's bisections and golden sections come back to values they evaluated (one in eight in a
        # target-bend search): the models of the latest parameters kept
        self.model: Callable[[Any, float], Any] = functools.lru_cache(maxsize=_MODELS_KEPT)(self._model)

    def _model(self, params, l0_mm: float):
        """The model of a design of ``params`` and length ``l0_mm`` (:attr:`model` keeps the latest)."""
        from .calibration import model_for
        from .derived import derive_from_values

        d = derive_from_values(params.pattern, width_mm=params.width_mm, interval_mm=params.interval_mm,
                               angle_deg=getattr(params, "angle_deg", 0.0), length_mm=l0_mm, tube=self.tube)
        return model_for(d, self.settings, sets=self.sets, stub_mm=self.stub_mm).model

    def theta(self, params_list, l0_list) -> tuple[np.ndarray, np.ndarray]:
        """Bend [deg] and status at P* of each (params, l0)."""
        from .curve import sweep

        c = sweep([self.model(p, l0) for p, l0 in zip(params_list, l0_list)], [self.p])
        return np.asarray(c.theta_deg)[:, 0], np.asarray(c.status)[:, 0]

    def table(self, space: DesignSpace, length_mm: float, points: int = _TABLE_POINTS):
        """(x grid, theta, status) of a segment of ``length_mm`` over the space."""
        x = np.linspace(space.low, space.high, points)
        params = [space.params(v) for v in x]
        theta, status = self.theta(params, [_legs(p, length_mm)[1] for p in params])
        return x, theta, status


def _roots(model: _Model, space: DesignSpace, length_mm: float, target_deg: float, table=None) -> list[float]:
    """Parameter values where the segment bends by ``target_deg`` at P* in a valid state.

    Every sign change of the tabulated bend between two valid points brackets a root;
    all brackets are polished at once by the vectorised Illinois method of
    :mod:`embroact.predict.solvers` (no scipy import: a target bend answers in well under
    the command's start-up time).
    """
    from .solvers import illinois

    x, theta, status = table if table is not None else model.table(space, length_mm)
    ok = np.isin(status, _VALID)
    f = theta - target_deg
    exact = [float(x[i]) for i in range(len(x)) if ok[i] and f[i] == 0.0]
    i = np.flatnonzero(ok[:-1] & ok[1:] & (f[:-1] * f[1:] < 0.0))
    if i.size == 0:
        return exact

    def residual(v, idx):
        params = [space.params(float(u)) for u in v]
        t, _ = model.theta(params, [_legs(p, length_mm)[1] for p in params])
        return t - target_deg

    found = illinois(residual, x[i], x[i + 1], f[i], f[i + 1], rtol=1e-12, atol=1e-10)
    return sorted(exact + [float(v) for v in found])


# ---------------------------------------------------------------------------- target bend
@dataclass(frozen=True, slots=True)
class Sensitivity:
    """The bend of a design sewn one machine-grid step off in one parameter.

    The design is generated and analysed again with the parameter one step lower and one
    step higher: the needle points move on the grid, and the derived geometry, G and P0
    (from the calibration, at the new coordinate) follow, as they do for any sewn design.

    Attributes
    ----------
    parameter : str
        ``"width_mm"`` or ``"angle_deg"``.
    step : float
        One grid step of the parameter [mm or deg]: a width moves one rail by one grid unit (0.1 mm,
        the path moving by half a unit, :func:`grid_origin_mm`), an angle moves a leg end by one grid
        unit along the path.
    minus_deg, plus_deg : float
        Change of the bend at the target pressure for one step lower / higher [deg].

    Examples
    --------
    >>> s = Sensitivity("width_mm", 0.2, 12.5, -11.3)
    >>> s.text()
    'width_mm -0.2: +12.50 deg, +0.2: -11.30 deg'
    """

    parameter: str
    step: float
    minus_deg: float
    plus_deg: float

    def text(self) -> str:
        """One line: both steps and what they do.

        Returns
        -------
        str

        Examples
        --------
        >>> Sensitivity("angle_deg", 0.4, -3.0, 2.9).text()
        'angle_deg -0.4: -3.00 deg, +0.4: +2.90 deg'
        """
        return f"{self.parameter} -{self.step:.3g}: {self.minus_deg:+.2f} deg, +{self.step:.3g}: {self.plus_deg:+.2f} deg"

    def as_dict(self) -> dict:
        """JSON-ready, units in the keys.

        Returns
        -------
        dict

        Examples
        --------
        >>> d = Sensitivity("width_mm", 0.2, 12.5, -11.3).as_dict()
        >>> d["step_mm"], d["plus_step_theta_change_deg"]
        (0.2, -11.3)
        """
        unit = "mm" if self.parameter.endswith("_mm") else "deg"
        return {"parameter": self.parameter, f"step_{unit}": self.step, "minus_step_theta_change_deg": self.minus_deg,
                "plus_step_theta_change_deg": self.plus_deg,
                "what": "bend change at the target pressure for one machine-grid step, the design generated and "
                        "analysed again (G, P0 and geometry following)"}


@dataclass(frozen=True, slots=True)
class BendCandidate:
    """One design meeting (or nearest to) a target bend.

    Attributes
    ----------
    pattern : str
        Its pattern kind.
    params : pattern parameters
        What the design file asks for.
    design : Design
        A one-actuator design, ready to write.
    theta_deg : float
        Predicted bend at the target pressure, from the generated and analysed design [deg].
    p0_kpa, g_mpa : float
        The model's transition pressure and modulus (from the calibration).
    limit : str
        The first validity limit or lock-up along the branch (``"COILED at 231.4 kPa"``), or ``"none"``.
    margin_kpa : float
        Pressure from the target to that limit [kPa] (``inf``: none).
    range_margin : float
        Distance of the parameter from the nearer end of its range, as a fraction of the range.
    sensitivity : tuple of Sensitivity
        What one machine-grid step of each design parameter does to the bend at the target
        pressure, the design generated and analysed again (G, P0 and the geometry following).
    binding : str
        The constraint closest to binding (or that binds, for an unreachable target).
    warnings : tuple of str
        Codes of the design-rule findings (no candidate has errors).
    theta_sd_deg : float or None
        1-sigma uncertainty of the bend from the calibration's covariance
        (:meth:`~embroact.predict.analysis.DesignAnalysis.bands`); None when the calibration
        claims none for this design (interpolated or published values).
    warning_count : int
        Design-rule warnings among the findings (a clean candidate ranks first).
    exact_pressure_kpa : float or None
        Pressure at which this design bends by the target exactly in a valid state; None if none.
    findings : tuple of str
        ``"CODE severity: message"`` of every finding ``embroact check`` gives for the written design.
    length_mm : float
        The actuator's length in the design [mm]: the one asked for, or one within the length tolerance
        fitted to whole stitch intervals (:func:`design_bend`'s ``length_tolerance_mm``).

    Examples
    --------
    >>> r = design_bend(84.5, 150.0, pattern="zigzag")
    >>> c = r.best
    >>> c.pattern, c.params.width_mm, round(c.theta_deg, 2), c.design.actuators[0].name
    ('zigzag', 6.2, 84.53, 'A1')
    """

    pattern: str
    params: PatternParams
    design: Design
    theta_deg: float
    p0_kpa: float
    g_mpa: float
    limit: str
    margin_kpa: float
    range_margin: float
    sensitivity: tuple["Sensitivity", ...]
    binding: str
    warnings: tuple[str, ...] = ()
    theta_sd_deg: float | None = None
    warning_count: int = 0
    exact_pressure_kpa: float | None = None
    findings: tuple[str, ...] = ()
    length_mm: float = math.nan

    def as_dict(self) -> dict:
        """JSON-ready, units in the keys.

        Returns
        -------
        dict
            Every field but the design; the parameters by name.

        Examples
        --------
        >>> r = design_bend(84.5, 150.0, pattern="zigzag")
        >>> d = r.best.as_dict()
        >>> d["pattern"], round(d["theta_deg"], 2), d["margin_kpa"] is None or d["margin_kpa"] > 0
        ('zigzag', 84.53, True)
        """
        return {"pattern": self.pattern, "params": param_values(self.params), "length_mm": self.length_mm,
                "theta_deg": self.theta_deg, "p0_kpa": self.p0_kpa, "g_mpa": self.g_mpa, "limit": self.limit,
                "margin_kpa": None if math.isinf(self.margin_kpa) else self.margin_kpa,
                "range_margin_fraction": self.range_margin,
                "sensitivity": [s.as_dict() for s in self.sensitivity], "binding": self.binding,
                "warnings": list(self.warnings), "theta_sd_deg": self.theta_sd_deg,
                "exact_pressure_kpa": self.exact_pressure_kpa, "findings": list(self.findings)}


@dataclass(frozen=True, slots=True)
class BendResult:
    """The answer to a target bend: the best candidate, the runners-up and whether the target is met.

    Attributes
    ----------
    target_deg, pressure_kpa, length_mm : float
        The target bend [deg], at that pressure [kPa], of that length [mm].
    best : BendCandidate
        The sewable design meeting the target best (the nearest one when none meets it).
    runners_up : tuple of BendCandidate
        The next best designs.
    reached : bool
        A sewable design bends within ``tolerance_deg`` of the target in a valid state without
        rule errors.
    statement : str
        The verdict in one line, with the physical reason when the target is not met.
    in_range : bool
        The target lies inside the bends the calibrated design space produces in a valid state
        at the pressure (continuous parameters), whether or not a sewable design meets it.
    range_deg : tuple of float or None
        (lowest, highest) such bend over the searched patterns; None when no design has a
        valid state at the pressure.
    tolerance_deg : float
        The tolerance the target was met within [deg].
    notes : tuple of str
        Pattern kinds the search skipped, and why.

    Examples
    --------
    >>> r = design_bend(84.5, 150.0, pattern="zigzag")
    >>> r.reached, r.in_range, r.statement.split(":")[0]
    (True, True, 'met')
    """

    target_deg: float
    pressure_kpa: float
    length_mm: float
    best: BendCandidate
    runners_up: tuple[BendCandidate, ...]
    reached: bool
    statement: str
    in_range: bool = True
    range_deg: tuple[float, float] | None = None
    tolerance_deg: float = 0.5
    notes: tuple[str, ...] = ()
    """Pattern kinds the search skipped, and why (no design space, no calibration points)."""

    def as_dict(self) -> dict:
        """JSON-ready.

        Returns
        -------
        dict
            Every field, the candidates as :meth:`BendCandidate.as_dict`.

        Examples
        --------
        >>> r = design_bend(84.5, 150.0, pattern="zigzag")
        >>> d = r.as_dict()
        >>> d["reached"], d["best"]["pattern"], d["target_deg"]
        (True, 'zigzag', 84.5)
        """
        return {"target_deg": self.target_deg, "pressure_kpa": self.pressure_kpa, "length_mm": self.length_mm,
                "reached": self.reached, "statement": self.statement, "best": self.best.as_dict(),
                "runners_up": [c.as_dict() for c in self.runners_up], "in_range": self.in_range,
                "range_deg": None if self.range_deg is None else list(self.range_deg),
                "tolerance_deg": self.tolerance_deg, "notes": list(self.notes)}


def operating_limits(limits: OperationSettings, pressure_kpa: float, bend_deg: float | None = None) -> OperationSettings:
    """The written design's ``[operation]``: the user's (or default) ``limits`` with the target as operating point.

    The limits stay what they were (the rules judge the design up to ``max_pressure_kpa``, as
    ``check`` and ``build`` do on the written file); only a target beyond them widens them to it
    (the target pressure, the target's |bend|), since the design is meant to work there.

    Parameters
    ----------
    limits : OperationSettings
        The user's (or default) limits.
    pressure_kpa : float
        The target pressure [kPa].
    bend_deg : float or None, optional
        The target bend [deg]; None for a shape.

    Returns
    -------
    OperationSettings

    Examples
    --------
    >>> operating_limits(OperationSettings(), 150.0, 84.5)
    OperationSettings(max_pressure_kpa=300.0, max_bend_deg=180.0, target_pressure_kpa=150.0, target_bend_deg=84.5)
    >>> o = operating_limits(OperationSettings(), 400.0, -250.0)
    >>> o.max_pressure_kpa, o.max_bend_deg
    (400.0, 250.0)
    """
    top_bend = limits.max_bend_deg if bend_deg is None else min(720.0, max(limits.max_bend_deg, abs(bend_deg)))
    return dataclasses.replace(limits, max_pressure_kpa=max(limits.max_pressure_kpa, pressure_kpa),
                               max_bend_deg=top_bend, target_pressure_kpa=pressure_kpa, target_bend_deg=bend_deg)


#: Where the one straight actuator of a target-bend search lies: its start [mm] and direction [deg].
_Place = tuple[tuple[float, float], float]


def _one_actuator(params, length_mm: float, tube: Tube, settings: ModelSettings, name: str,
                  operation: OperationSettings, place: _Place = ((0.0, 0.0), 0.0)) -> Design:
    """The written design: one straight actuator of ``length_mm`` from ``place``, moved across its path by
    :func:`grid_origin_mm` (so both rails of its width lie on the machine grid)."""
    origin, rotation = place
    path = _straight(length_mm, grid_origin_mm(params.width_mm, origin, rotation), rotation)
    return Design(name, tube, MachineSettings(), operation, (ActuatorSpec(name, params, path, model=settings),))


@functools.lru_cache(maxsize=64)
def _straight(length_mm: float, origin_mm: tuple[float, float], rotation_deg: float) -> Centerline:
    """The straight path of :func:`_one_actuator`: one object per length and place, so the designs of one search
    that lie there share it and the segment index it makes on first use (:meth:`Centerline.segment_index`)."""
    return Centerline.straight(length_mm, origin_mm=origin_mm, rotation_deg=rotation_deg)


def _analysed(params, length_mm: float, pressure_kpa: float, *, tube: Tube, settings: ModelSettings, sets,
              name: str, operation: OperationSettings, place: _Place = ((0.0, 0.0), 0.0)):
    """(design, analysis, theta_deg or None, status or None) of the generated one-actuator design."""
    from .analysis import analyse

    d = _one_actuator(params, length_mm, tube, settings, name, operation, place)
    a = analyse(d, calibration_sets=sets)
    act = a.actuators[0]
    if act.choice is None:
        return d, a, None, None
    c = a.curves([pressure_kpa])[0]  # the whole strip's status: its stub and the clamp count (validity.py)
    return d, a, float(c.theta_deg[0]), int(c.status[0])


def angle_grid_step_deg(width_mm: float, angle_deg: float) -> float:
    """The turn of a leg of a cross pattern whose end moves one machine-grid unit along the path [deg].

    Parameters
    ----------
    width_mm : float
        Rail spacing [mm].
    angle_deg : float
        Embroidery angle [deg].

    Returns
    -------
    float
        [deg].

    Examples
    --------
    >>> round(angle_grid_step_deg(7.0, 45.0), 4)
    0.4063
    """
    a = math.radians(angle_deg)
    return math.degrees(math.atan(math.tan(a) + DEFAULT_TOLERANCES.machine_grid_mm / width_mm) - a)


def _sensitivity(params, theta_deg: float, analysed) -> tuple[Sensitivity, ...]:
    """One machine-grid step of the width (and the angle of a cross pattern), both ways, analysed again
    (``analysed(params)``, :func:`_analysed` at the candidate's length and pressure): one grid unit of width (the
    path moves to keep both rails on the grid, :func:`grid_origin_mm`); an angle as the kind's design space moves
    it (:attr:`~embroact.patterns.kinds.PatternKind.design_params`: the interval follows, so that the pattern still
    closes; the generator would otherwise close it by turning the angle back)."""
    kind = pattern_kind(params.pattern)
    steps = [("width_mm", DEFAULT_TOLERANCES.machine_grid_mm)]
    if kind.has_angle:
        steps.append(("angle_deg", angle_grid_step_deg(params.width_mm, params.angle_deg)))
    out = []
    for key, step in steps:
        change = []
        for sign in (-1.0, 1.0):
            value = round(getattr(params, key) + sign * step, 10)
            moved = (kind.design_params(value, params.width_mm, params.interval_mm)
                     if key == kind.calibration_axis and kind.design_params is not None
                     else dataclasses.replace(params, **{key: value}))
            try:
                _, _, theta, _ = analysed(moved)
            except EmbroactError:
                theta = None
            change.append(math.nan if theta is None else theta - theta_deg)
        out.append(Sensitivity(key, step, change[0], change[1]))
    return tuple(out)


def _limits(model, p: float) -> tuple[str, float]:
    from .curve import lockup
    from .branch import first_limit

    found = []
    lim = first_limit(model)
    if lim is not None:
        found.append((lim.pressure_kpa, f"{lim.status.name} at {lim.pressure_kpa:.1f} kPa ({lim.theta_deg:.1f} deg)"))
    lock_theta, lock_p = lockup(model)
    if math.isfinite(lock_p):
        found.append((lock_p, f"end of the stable branch at {lock_p:.1f} kPa ({lock_theta:.1f} deg)"))
    elif lock_theta != 0.0:
        found.append((math.inf, f"lock-up at {lock_theta:.1f} deg"))
    finite = [f for f in found if math.isfinite(f[0])]
    if not finite:
        return (found[0][1] if found else "none"), math.inf
    p_lim, text = min(finite)
    if p_lim > _LIMIT_HORIZON * p:  # a limit at 80 MPa is no limit of a sewn actuator: the tube bursts long before
        return f"none up to {_LIMIT_HORIZON * p:.0f} kPa ({_LIMIT_HORIZON:g} x the target pressure)", math.inf
    return text, p_lim - p


#: Past this many times the target pressure a design's first limit is reported as none (the state the formula gives
#: there, tens of MPa, says nothing of a sewn actuator).
_LIMIT_HORIZON = 10.0


def exact_pressure_kpa(model, target_deg: float) -> float | None:
    """The pressure at which ``model`` bends by ``target_deg`` in a valid state (BENDING), or None.

    Parameters
    ----------
    model : ActuatorModel
        The design's model.
    target_deg : float
        The bend [deg].

    Returns
    -------
    float or None
        [kPa]; None when no pressure bends it so in a valid state (e.g. the other direction).

    Examples
    --------
    >>> from embroact.predict.curve import ActuatorModel, curve
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814, beta0_deg=0, outer_radius_mm=1.5,
    ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
    >>> p = exact_pressure_kpa(m, 90.0)
    >>> round(float(curve(m, [p]).theta_deg[0]), 6), exact_pressure_kpa(m, -10.0)
    (90.0, None)
    """
    from .curve import pressure_at

    c = pressure_at(model, [target_deg])
    if int(c.status[0]) != int(Status.BENDING):
        return None
    return float(c.pressure_kpa[0])


def _candidate(space: DesignSpace, x: float, length_mm: float, pressure_kpa: float, target_deg: float, *,
               tube: Tube, settings: ModelSettings, sets, name: str, operation: OperationSettings,
               polish: bool, place: _Place = ((0.0, 0.0), 0.0), interval_mm: float | None = None,
               memo: dict) -> BendCandidate | None:
    """Generate and analyse the design at x (a continuous parameter polished on the analysed design, whose
    needle points are on the machine grid); None if it is not in a valid state or fails the rules.
    ``interval_mm`` replaces the space's interval (a length fitted to whole intervals, :func:`_fitted_lengths`).
    ``memo`` holds the analyses of one search by (params, length, pressure): a candidate's grid neighbours, analysed
    for its sensitivity, are often candidates too (the other arguments are the search's own)."""
    from .rules import check_design

    def params_at(v):
        q = space.params(v)
        return q if interval_mm is None else dataclasses.replace(q, interval_mm=interval_mm)

    kw: dict[str, Any] = dict(tube=tube, settings=settings, sets=sets, name=name, operation=operation, place=place)

    def analysed(q):
        key = q, length_mm, pressure_kpa
        if key not in memo:
            memo[key] = _analysed(q, length_mm, pressure_kpa, **kw)
        return memo[key]

    d, a, theta, status = analysed(params_at(x))
    if polish and theta is not None:  # secant steps on the analysed design (it is what `predict` prints)
        x0, t0 = x, theta
        x1 = min(max(x + 1e-4 * (space.high - space.low), space.low), space.high)
        for _ in range(8):
            if abs(t0 - target_deg) <= _BEND_TOL_DEG:
                break
            _, _, t1, _ = analysed(params_at(x1))
            if t1 is None or t1 == t0:
                break
            x0, x1, t0 = x1, min(max(x1 - (t1 - target_deg) * (x1 - x0) / (t1 - t0), space.low), space.high), t1
        x = round(x0, 6)
        d, a, theta, status = analysed(params_at(x))
    if theta is None or status not in _VALID:
        return None
    findings = check_design(a)
    if any(f.severity.name == "ERROR" for f in findings):
        return None
    model = a.actuators[0].segments.single("a target-bend design is one pattern").model
    limit, margin = _limits(model, pressure_kpa)
    span = space.high - space.low
    edge = min(x - space.low, space.high - x) / span if span > 0.0 else 0.0  # a one-point calibration: no room
    range_note = (f"the {space.describe()} range: {space.parameter} {x:.4g} is "
                  f"{min(x - space.low, space.high - x):.3g} from its end")
    limit_note = f"{limit} ({margin:.1f} kPa above the target pressure)" if math.isfinite(margin) else limit
    binding = range_note if edge * pressure_kpa <= (margin if math.isfinite(margin) else math.inf) * 0.5 \
        else limit_note
    band = a.bands([pressure_kpa])[0]
    params = params_at(x)
    return BendCandidate(space.pattern, params, d, theta, model.p0_kpa, model.g_mpa, limit, margin, edge,
                         _sensitivity(params, theta, analysed), binding,
                         tuple(sorted({f.code for f in findings})),
                         None if band is None else float(band.theta_sd_deg[0]),
                         sum(f.severity.name == "WARNING" for f in findings), exact_pressure_kpa(model, target_deg),
                         tuple(f"{f.code} {f.severity.name.lower()}: {f.message}" for f in findings), float(length_mm))


#: Bisection (golden-section) steps locating a boundary of the valid states (an extreme of the bend) in the
#: parameter: a table step of 1/120 of the range shrinks to below 1e-8 of it.
_EXTREME_STEPS = 32


#: Points of the (cheap, model-free) scan that locates the jumps of a pattern's sewn geometry.
_JUMP_SCAN_POINTS = 2401


def _length_jumps(space: DesignSpace, length_mm: float) -> np.ndarray:
    """(k, 2) parameter values just below and above each jump of the sewn geometry over the range: a cross
    pattern's leg pitches and its embroidered length, whole intervals of a
    continuously changing interval, both jump; bisected to 1e-12 of the range. Empty for a zigzag."""
    if not pattern_kind(space.pattern).has_angle:
        return np.zeros((0, 2))

    def key(v):  # the whole numbers the sewn geometry is made of: leg pitches, intervals along the length
        q = space.params(float(v))
        pitches = round(2.0 * q.width_mm * math.tan(math.radians(q.angle_deg)) / q.interval_mm)
        return pitches, whole_intervals(length_mm, q.interval_mm)

    x = np.linspace(space.low, space.high, _JUMP_SCAN_POINTS)
    keys = [key(v) for v in x]
    out = []
    for i in range(len(x) - 1):
        if keys[i] == keys[i + 1]:
            continue
        lo, hi = float(x[i]), float(x[i + 1])
        k_lo = keys[i]
        while hi - lo > 1e-12 * (space.high - space.low):
            mid = 0.5 * (lo + hi)
            if key(mid) == k_lo:
                lo = mid
            else:
                hi = mid
        out.append((lo, hi))
    return np.asarray(out, dtype=np.float64).reshape(-1, 2)


def _bend_range(model: _Model, space: DesignSpace, length_mm: float, table,
                jumps: np.ndarray | None = None) -> tuple[float, float] | None:
    """(lowest, highest) bend at P* in a valid state over the space's continuous parameter; None if none.

    The table brackets every candidate: its valid points, each boundary of the valid states
    between two table points (bisected, keeping the valid side), each interior extreme of
    the bend (golden-section search between its neighbours) and both sides of each jump of the
    sewn geometry (:func:`_length_jumps`); all brackets are refined together, one
    vectorised model evaluation per step.
    """
    x, theta, status = table
    ok = np.isin(status, _VALID)
    if not ok.any():
        return None

    def at(values):
        params = [space.params(float(v)) for v in values]
        th, st = model.theta(params, [_legs(q, length_mm)[1] for q in params])
        return np.asarray(th, dtype=np.float64), np.isin(st, _VALID)

    found = [float(v) for v in theta[ok]]
    jumps = _length_jumps(space, length_mm) if jumps is None else jumps
    if jumps.size:  # where the sewn geometry jumps, either side of it (between jumps the bend is smooth)
        th, valid = at(np.concatenate([jumps[:, 0], jumps[:, 1]]))
        found += th[valid].tolist()
    edge = np.flatnonzero(ok[:-1] != ok[1:])
    if edge.size:  # boundaries of the valid states: bisect, keep the valid side
        good = np.where(ok[edge], x[edge], x[edge + 1])
        bad = np.where(ok[edge], x[edge + 1], x[edge])
        for _ in range(_EXTREME_STEPS):
            mid = 0.5 * (good + bad)
            _, valid = at(mid)
            good, bad = np.where(valid, mid, good), np.where(valid, bad, mid)
        found += at(good)[0].tolist()
    inner = np.arange(1, len(x) - 1)
    inner = inner[ok[inner - 1] & ok[inner] & ok[inner + 1]]
    peaks = [(i, s) for s in (1.0, -1.0) for i in inner
             if s * theta[i] > s * theta[i - 1] and s * theta[i] >= s * theta[i + 1]]  # a plateau is no peak
    if peaks:  # interior maxima (sign 1) and minima (sign -1): golden section, all at once
        sign = np.array([s for _, s in peaks])
        a = np.array([x[i - 1] for i, _ in peaks], dtype=np.float64)
        b = np.array([x[i + 1] for i, _ in peaks], dtype=np.float64)
        g = (math.sqrt(5.0) - 1.0) / 2.0
        for _ in range(_EXTREME_STEPS):
            c, d = b - g * (b - a), a + g * (b - a)
            th, valid = at(np.concatenate([c, d]))
            score = np.where(valid, np.concatenate([sign, sign]) * th, -np.inf)
            left = score[: len(c)] >= score[len(c):]
            a, b = np.where(left, a, c), np.where(left, d, b)
        th, valid = at(0.5 * (a + b))
        found += th[valid].tolist()
    return min(found), max(found)


def _with_points(model: _Model, space: DesignSpace, length_mm: float, table, extra) -> tuple:
    """``table`` (x, theta, status) with the parameter values ``extra`` added (both sides of each jump of the sewn
    geometry, :func:`_length_jumps`), in order."""
    x, theta, status = table
    extra = np.asarray(extra, dtype=np.float64)
    params = [space.params(float(v)) for v in extra]
    th, st = model.theta(params, [_legs(q, length_mm)[1] for q in params])
    order = np.argsort(np.concatenate([x, extra]), kind="stable")
    return (np.concatenate([x, extra])[order], np.concatenate([theta, th])[order], np.concatenate([status, st])[order])


def _why_not(space: DesignSpace, target_deg: float, pressure_kpa: float, bend_range, p0_low_kpa: float) -> str:
    """One line, in physical terms, why no design of ``space`` bends by the target at the pressure."""
    if bend_range is None:
        if pressure_kpa <= p0_low_kpa:
            return (f"{space.pattern}: {pressure_kpa:g} kPa is below the transition pressure P0 of every calibrated "
                    f"{space.pattern} design (lowest {p0_low_kpa:.1f} kPa): the tube only inflates, nothing bends")
        return f"{space.pattern}: no valid state at {pressure_kpa:g} kPa anywhere in {space.describe()}"
    lo, hi = bend_range
    if target_deg > hi:
        return (f"{space.pattern}: at {pressure_kpa:g} kPa bends at most {hi:+.2f} deg in a valid state over "
                f"{space.describe()}")
    return (f"{space.pattern}: at {pressure_kpa:g} kPa bends at least {lo:+.2f} deg in a valid state over "
            f"{space.describe()}")


def _lowest_p0_kpa(space: DesignSpace, length_mm: float, model: _Model) -> float:
    """The lowest transition pressure over the space's table [kPa]."""
    xs = np.linspace(space.low, space.high, 21)
    return float(min(model.model(space.params(v), length_mm).p0_kpa for v in xs))


def _rank(c: BendCandidate, target_deg: float, p: float, length_mm: float, tol: float):
    """Candidates that meet the target (within ``tol``) first, the others by how far they miss it; then clean ones,
    then the asked length, then the narrower 1-sigma band of the bend (a candidate without one after those with
    one), then the closer bend, then the wider margin to limit and range end.

    The band comes after the length: the same design bends, and is uncertain, in proportion to its length, so
    across lengths it would only prefer the shorter one. A candidate that misses ranks by its miss first: a clean
    cross that does not bend at this pressure (84 deg off) ranked above a zigzag 5 deg off."""
    miss = round(abs(c.theta_deg - target_deg), 6)
    off = miss if miss > tol else 0.0
    band = math.inf if c.theta_sd_deg is None else round(c.theta_sd_deg, 6)
    return (off, c.warning_count > 0, round(abs(c.length_mm - length_mm), 6), band, miss,
            -min(c.margin_kpa / p, 10.0) - c.range_margin, c.pattern)


def _fitted_lengths(c: BendCandidate, length_mm: float, tolerance_mm: float, target_deg: float, interval_mm: float,
                    make) -> list[BendCandidate]:
    """Candidates of ``c``'s parameter at other lengths within ``tolerance_mm`` of ``length_mm``, nearer the target.

    The bend of a uniform actuator is its curvature times its bent length, and the curvature does not
    depend on the length: the length that bends by the target is ``L theta* / theta(L)``, moved to the
    machine grid and to ``length_mm +- tolerance_mm``. Its stitch interval is ``interval_mm`` (the space's)
    adjusted to a whole number of intervals over it (the legs then span the length exactly, first and last
    needle point on the grid); one more step corrects what the rounding left. ``make(length, interval)``
    generates and analyses a candidate of the parameter (None when it is invalid).
    """
    grid = DEFAULT_TOLERANCES.machine_grid_mm
    low, high = max(10.0, length_mm - tolerance_mm), min(1000.0, length_mm + tolerance_mm)
    out: list[BendCandidate] = []
    at = c
    for _ in range(2):
        if at.theta_deg == 0.0 or math.copysign(1.0, at.theta_deg) != math.copysign(1.0, target_deg):
            break
        want = min(max(at.length_mm * target_deg / at.theta_deg, low), high)
        fitted = round(round(want / grid) * grid, 10)
        fitted = fitted if low - 1e-9 <= fitted <= high + 1e-9 else round(round(at.length_mm / grid) * grid, 10)
        if any(abs(fitted - o.length_mm) < 1e-9 for o in [c, *out]):
            break
        n = max(1, round(fitted / interval_mm))
        at = make(fitted, fitted / n)
        if at is None:
            break
        out.append(at)
    return out


def design_bend(bend_deg: float, pressure_kpa: float, *, pattern: str = "any", length_mm: float = 100.0,
                tube: Tube = Tube(), settings: ModelSettings = ModelSettings(), sets: Iterable = (),
                allow_extrapolation: bool = False, name: str = "A1", tolerance_deg: float = 0.5,
                operation: OperationSettings = OperationSettings(), origin_mm=(0.0, 0.0), rotation_deg: float = 0.0,
                length_tolerance_mm: float = 0.0) -> BendResult:
    """The single sewable actuator that bends by ``bend_deg`` at ``pressure_kpa`` (see the module docstring).

    The continuous parameter's roots are found on the model; the designs tried are those a
    machine sews (a zigzag width on the 0.1 mm grid, both rails on it, :func:`grid_origin_mm`; a cross
    angle polished on the generated needle points), each generated and analysed as ``embroact
    predict`` does, so the reported bend is that of the written file's needle points.

    Parameters
    ----------
    bend_deg : float
        Target bend [deg], non-zero, |.| <= 720 (negative: toward the thread side).
    pressure_kpa : float
        Target pressure [kPa], > 0.
    pattern : str
        A registered pattern kind, or ``"any"`` (every kind with a design space).
    length_mm : float
        Actuator length [mm], in [10, 1000].
    tube, settings, sets
        Tube, model settings (calibration, tube law) and extra calibration sets.
    allow_extrapolation : bool
        Search beyond the calibrated range.
    name : str
        The actuator's name in the written design.
    tolerance_deg : float
        A sewable design within this of the target meets it [deg], in (0, 10].
    operation : OperationSettings
        The operation limits the written design keeps (:func:`operating_limits`: the target is added
        as its operating point); every candidate is judged by the rules up to them.
    origin_mm, rotation_deg
        Where the straight actuator starts [mm] and its direction [deg, counter-clockwise from +x] (the
        studio searches an actuator where it lies). Each design is moved across its path to where both
        rails of its width lie on the machine grid (:func:`grid_origin_mm`; half a grid unit for a width
        of an odd number of units), so widths step by one grid unit (0.1 mm) on a path along a grid axis.
    length_tolerance_mm : float
        The length may differ from ``length_mm`` by up to this, on the machine grid, where the grid's width
        steps miss the target (:func:`_fitted_lengths`: the stitch interval is adjusted to whole intervals
        over the new length), in [0, length_mm); 0 keeps the length asked for.

    Returns
    -------
    BendResult
        ``reached`` False: ``best`` is the nearest sewable design (with the pressure at which it
        reaches the target exactly, where it does) and ``statement`` says why.

    Examples
    --------
    >>> r = design_bend(-60.0, 250.0, pattern="cross")
    >>> r.reached, r.best.pattern, round(r.best.theta_deg) == -60
    (True, 'cross', True)
    """
    target = check_range("bend_deg", bend_deg, low=-720.0, high=720.0, high_inclusive=True, low_inclusive=True)
    if target == 0.0:
        raise ParameterError("bend_deg must be non-zero, got 0")
    p = check_target_pressure(pressure_kpa)
    length = check_range("length_mm", length_mm, low=10.0, high=1000.0, low_inclusive=True, high_inclusive=True)
    tol = check_range("tolerance_deg", tolerance_deg, low=0.0, high=10.0, high_inclusive=True)
    if pattern != "any" and pattern not in PATTERN_KINDS.names():
        choices = PATTERN_KINDS.names() + ("any",)
        raise ParameterError(f"pattern must be one of {', '.join(map(repr, choices))}, got {pattern!r}")
    sets = tuple(sets)
    if pattern == "any":
        spaces, notes = design_spaces(settings, sets=sets, tube=tube, allow_extrapolation=allow_extrapolation)
    else:
        spaces, notes = {pattern: design_space(pattern, settings, sets=sets, tube=tube,
                                               allow_extrapolation=allow_extrapolation)}, ()
    model = _Model(p, tube, settings, sets, tube.end_margin_mm)  # one actuator: a whole strip with its stub
    length_tolerance_mm = check_range("length_tolerance_mm", length_tolerance_mm, low=0.0, high=length,
                                      low_inclusive=True)
    kw: dict[str, Any] = dict(tube=tube, settings=settings, sets=sets, name=name,
                              operation=operating_limits(operation, p, target),
                              place=((float(origin_mm[0]), float(origin_mm[1])), float(rotation_deg)), memo={})
    cands: list[BendCandidate] = []
    reasons, ranges = [], []
    step = DEFAULT_TOLERANCES.machine_grid_mm  # one grid unit of width: the path moves (grid_origin_mm)

    def add(c):
        if c is not None and all((c.params, c.length_mm) != (o.params, o.length_mm) for o in cands):
            cands.append(c)

    for space in spaces.values():
        table = model.table(space, length)
        jumps = _length_jumps(space, length)
        bend_range = _bend_range(model, space, length, table, jumps)
        if bend_range == (0.0, 0.0):  # only inflation: no design of the space bends at this pressure
            bend_range = None
        if bend_range is not None:
            ranges.append(bend_range)
        inside = bend_range is not None and bend_range[0] <= target <= bend_range[1]
        xs = list(_roots(model, space, length, target, table)) if inside else []
        if inside and not xs and jumps.size:  # the bend crosses the target only between two jumps of the table
            xs = list(_roots(model, space, length, target, _with_points(model, space, length, table, jumps.ravel())))
        if not xs:  # the nearest the space comes: its valid table point closest to the target, refined
            x, theta, status = table
            ok = np.flatnonzero(np.isin(status, _VALID))
            xs = [float(x[i]) for i in ok[np.argsort(np.abs(theta[ok] - target), kind="stable")][:1]]
            if not inside:
                reasons.append(_why_not(space, target, p, bend_range, _lowest_p0_kpa(space, length, model)))
        for root in xs:
            for v in space.sewable(root, spread=2, step=step):
                c = _candidate(space, v, length, p, target, polish=space.grid_step == 0.0 and inside, **kw)
                add(c)
                if c is not None and inside and space.grid_step > 0.0 and length_tolerance_mm > 0.0 \
                        and abs(c.theta_deg - target) > _BEND_TOL_DEG:
                    for other in _fitted_lengths(c, length, length_tolerance_mm, target, space.interval_mm,
                                                 lambda L, s, space=space, v=v: _candidate(
                                                     space, v, L, p, target, polish=False, interval_mm=s, **kw)):
                        add(other)
    whole = (min(r[0] for r in ranges), max(r[1] for r in ranges)) if ranges else None
    in_range = whole is not None and any(r[0] <= target <= r[1] for r in ranges)
    if not cands:
        raise ParameterError(f"bend_deg {target:g} at pressure_kpa {p:g}: no valid sewable design in any pattern; "
                             + "; ".join(reasons or ["every design fails the design rules or leaves the valid states"]))
    met = sorted((c for c in cands if in_range and abs(c.theta_deg - target) <= tol),
                 key=lambda c: _rank(c, target, p, length, tol))

    def sized(c):  # the statement's length note: a length other than the one asked for
        return "" if c.length_mm == length else f" with a length of {c.length_mm:g} mm (asked {length:g})"

    if met:
        best = met[0]
        others = [c for c in sorted(cands, key=lambda c: _rank(c, target, p, length, tol)) if c is not best]
        note = f" ({best.warning_count} rule warning(s): no clean design meets it)" if best.warning_count else ""
        band = "" if best.theta_sd_deg is None else f" (+- {best.theta_sd_deg:.2f} deg, 1 sigma of the calibration)"
        return BendResult(target, p, length, best, tuple(others[:2]), True,
                          f"met: {best.pattern} bends {best.theta_deg:.2f} deg{band} at {p:g} kPa{sized(best)}{note}",
                          in_range, whole, tol, notes)
    cands.sort(key=lambda c: (round(abs(c.theta_deg - target), 6), c.warning_count > 0, c.pattern))
    best = cands[0]
    exact = (f"; it bends by {target:g} deg at {best.exact_pressure_kpa:.1f} kPa" if best.exact_pressure_kpa
             else f"; it bends by {target:g} deg at no pressure in a valid state")
    if in_range:
        why = (f"no sewable design within {tol:g} deg: the machine grid steps "
               f"{best.sensitivity[0].parameter} by {best.sensitivity[0].step:g}")
        if best.theta_deg * target > 0.0 and spaces[best.pattern].grid_step > 0.0:  # the bend scales with the length
            grid = DEFAULT_TOLERANCES.machine_grid_mm
            fits = round(round(best.length_mm * target / best.theta_deg / grid) * grid, 10)
            if abs(fits - length) > length_tolerance_mm and 10.0 <= fits <= 1000.0:
                why += (f" (a length of {fits:g} mm would meet it: allow {abs(fits - length):.3g} mm with the "
                        f"length tolerance)")
    else:
        extreme = "at most" if whole is not None and target > whole[1] else "at least"
        bound = None if whole is None else (whole[1] if target > whole[1] else whole[0])
        why = "; ".join(reasons) if bound is None else (f"the calibrated designs bend {extreme} {bound:+.2f} deg at "
                                                        f"{p:g} kPa in a valid state ({'; '.join(reasons)})")
    statement = (f"not met: {why}. Nearest: {best.pattern} {best.theta_deg:.2f} deg{sized(best)} "
                 f"({best.theta_deg - target:+.2f} deg off){exact}")
    return BendResult(target, p, length, dataclasses.replace(best, binding=why), tuple(cands[1:3]), False, statement,
                      in_range, whole, tol, notes)


# ---------------------------------------------------------------------------- target shape
def _resample(target_xy_mm) -> tuple[np.ndarray, np.ndarray, float]:
    """Arc lengths and points of the target at _SHAPE_SAMPLES even steps; its length."""
    xy = np.asarray(target_xy_mm, dtype=np.float64)
    if xy.ndim != 2 or xy.shape[1] != 2 or len(xy) < 3 or not np.all(np.isfinite(xy)):
        raise ParameterError(f"target shape must be at least 3 finite (x_mm, y_mm) points, got array of shape "
                             f"{xy.shape}")
    xy = xy - xy[0]
    step = np.hypot(*np.diff(xy, axis=0).T)
    keep = np.concatenate([[True], step > 1e-9])
    xy = xy[keep]
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(xy, axis=0).T))])
    length = float(s[-1])
    check_range("target shape length_mm", length, low=2.0 * _MIN_SEGMENT_MM, high=2000.0)
    sj = np.linspace(0.0, length, _SHAPE_SAMPLES)
    return sj, np.column_stack([np.interp(sj, s, xy[:, 0]), np.interp(sj, s, xy[:, 1])]), length


def _split(kappa: np.ndarray, n: int, min_len: int) -> list[int]:
    """Optimal split of a sampled signal into n constant pieces (least squares), as piece start indices."""
    m = len(kappa)
    c1 = np.concatenate([[0.0], np.cumsum(kappa)])
    c2 = np.concatenate([[0.0], np.cumsum(kappa**2)])

    def sse(i, j):  # pieces [i, j) for arrays i, scalar j
        cnt = j - i
        tot = c1[j] - c1[i]
        return c2[j] - c2[i] - tot**2 / np.maximum(cnt, 1)

    cost = np.full((n + 1, m + 1), np.inf)
    back = np.zeros((n + 1, m + 1), dtype=int)
    cost[0, 0] = 0.0
    for k in range(1, n + 1):
        for j in range(k * min_len, m + 1):
            i = np.arange((k - 1) * min_len, j - min_len + 1)
            if len(i) == 0:
                continue
            v = cost[k - 1, i] + sse(i, j)
            best = int(np.argmin(v))
            cost[k, j], back[k, j] = v[best], i[best]
    starts, j = [], m
    for k in range(n, 0, -1):
        j = back[k, j]
        starts.append(j)
    return starts[::-1]


def fit_curvature(target_xy_mm, segments: int) -> tuple[np.ndarray, np.ndarray, float]:
    """Piecewise-constant curvature fitted to a planar curve: (lengths_mm, kappa_per_mm, rmse_mm).

    The curve starts at its first point heading +x (its first point is moved to the
    origin). Boundaries and curvatures minimise the squared position error at
    evenly spaced arc lengths; the start is the optimal split of the curve's sampled
    curvature into ``segments`` constant pieces.

    Parameters
    ----------
    target_xy_mm : array_like (m, 2)
        The curve [mm].
    segments : int
        Pieces, in [1, 20].

    Returns
    -------
    lengths_mm, kappa_per_mm : numpy.ndarray
        Length [mm] and curvature [1/mm] of each piece.
    rmse_mm : float
        Position error of the fit [mm].

    Examples
    --------
    >>> import numpy as np
    >>> from embroact.predict.shape import BentShape
    >>> s = np.linspace(0.0, 100.0, 2001)
    >>> xy = BentShape.chain([40.0, 60.0], [90.0, -45.0]).profile_mm(s)
    >>> lengths, kappa, rmse = fit_curvature(xy, 2)
    >>> np.round(lengths, 2).tolist(), np.round(np.degrees(kappa * lengths), 2).tolist(), rmse < 1e-3
    ([40.0, 60.0], [90.0, -45.0], True)
    """
    from scipy.optimize import least_squares

    sj, xy, length = _resample(target_xy_mm)
    n = int(segments)
    if not 1 <= n <= 20:
        raise ParameterError(f"segments must be in [1, 20], got {segments!r}")
    ds = sj[1] - sj[0]
    phi = np.unwrap(np.arctan2(*np.diff(xy, axis=0).T[::-1]))
    kappa_est = np.diff(phi) / ds  # at sj[1:-1]
    min_len = max(1, int(_MIN_SEGMENT_MM / ds))
    n = min(n, max(1, len(kappa_est) // min_len), max(1, int(length // _MIN_SEGMENT_MM)))
    starts = _split(kappa_est, n, min_len)
    edges = np.concatenate([[0.0], [sj[1 + i] for i in starts[1:]], [length]])
    kappa0 = np.array([kappa_est[a:b].mean() for a, b in zip(starts, starts[1:] + [len(kappa_est)])])
    free = length - n * _MIN_SEGMENT_MM  # every piece is _MIN_SEGMENT_MM plus a share of the rest

    def unpack(v):
        share = np.concatenate([v[: n - 1], [1.0]])
        return _MIN_SEGMENT_MM + free * share / share.sum(), v[n - 1:]

    from .shape import planar_chain_mm  # here: a target bend needs no fabric line

    def residual(v):
        lengths, k = unpack(v)
        return (planar_chain_mm(lengths, np.degrees(k * lengths), sj) - xy).ravel()

    share0 = np.maximum(np.diff(edges) - _MIN_SEGMENT_MM, 1e-3 * max(free, 1e-9))
    v0 = np.concatenate([share0[:-1] / share0[-1], kappa0])
    lo = np.concatenate([np.full(n - 1, 1e-6), np.full(n, -np.inf)])
    v0 = np.maximum(v0, lo + 1e-9)
    sol = least_squares(residual, v0, bounds=(lo, np.inf), x_scale="jac", xtol=1e-12, ftol=1e-12, gtol=1e-12,
                        max_nfev=200 * (2 * n))
    lengths, k = unpack(sol.x)
    rmse = float(np.sqrt(np.mean(np.sum(residual(sol.x).reshape(-1, 2) ** 2, axis=1))))
    return lengths, k, rmse


@dataclass(frozen=True, slots=True)
class ShapeSegment:
    """One segment of a designed shape: its pattern parameters, length and what it does at P*.

    Attributes
    ----------
    params : PatternParams
        Its pattern.
    length_mm : float
        Its length [mm].
    theta_deg : float
        Its predicted bend at the target pressure [deg].
    target_kappa_per_mm : float
        The curvature the fit asked of it [1/mm].
    note : str
        What was adjusted, or empty.

    Examples
    --------
    >>> from embroact.patterns.params import ZigzagParams
    >>> seg = ShapeSegment(ZigzagParams(6.2, 1.0), 50.0, 42.0, 0.0147)
    >>> seg.pattern, seg.as_dict()["params"]
    ('zigzag', {'width_mm': 6.2, 'interval_mm': 1.0})
    """

    params: PatternParams
    length_mm: float
    theta_deg: float
    target_kappa_per_mm: float
    note: str = ""

    @property
    def pattern(self) -> str:
        """Its pattern kind (the parameters' ``pattern``)."""
        return self.params.pattern

    def as_dict(self) -> dict:
        """JSON-ready.

        Returns
        -------
        dict

        Examples
        --------
        >>> from embroact.patterns.params import ZigzagParams
        >>> ShapeSegment(ZigzagParams(6.2, 1.0), 50.0, 42.0, 0.0147).as_dict()["note"] is None
        True
        """
        return {"pattern": self.pattern, "params": param_values(self.params),
                "length_mm": self.length_mm, "theta_deg": self.theta_deg,
                "target_kappa_per_mm": self.target_kappa_per_mm, "note": self.note or None}


@dataclass(frozen=True, slots=True, eq=False)
class ShapeResult:
    """The answer to a target shape.

    Attributes
    ----------
    design : Design
        One segmented actuator (or a single pattern when one segment fits), ready to write.
    segments : tuple of ShapeSegment
        Clamp to tip.
    pressure_kpa : float
        The target pressure [kPa].
    target_xy_mm, predicted_xy_mm : ndarray (m, 2)
        Target and predicted fabric line at the same arc lengths [mm] (profile frame).
    rmse_mm, max_deviation_mm : float
        Position error of the prediction against the target at those points [mm].
    tip_error_mm, tip_angle_error_deg : float
        Distance between predicted and target tips [mm]; tip angle difference [deg].
    fit_rmse_mm : float
        RMSE of the piecewise-constant curvature fit alone [mm] (what any chain of arcs reaches).
    reached : bool
        Every segment meets its curvature in a valid state and the design passes the rules.
    statement : str
        The verdict in one line.
    warnings : tuple of str
        Codes of the design-rule findings.
    findings : tuple of str
        ``"CODE severity: message"`` of every finding ``embroact check`` gives for the written design.
    notes : tuple of str
        Pattern kinds the search skipped, and why.

    Examples
    --------
    >>> from embroact.predict.shape import BentShape
    >>> target = BentShape.chain([100.0], [60.0]).profile_mm(np.linspace(0.0, 100.0, 201))
    >>> r = design_shape(target, 150.0, max_segments=1)
    >>> r.reached, len(r.segments), r.rmse_mm < 0.5
    (True, 1, True)
    """

    design: Design
    segments: tuple[ShapeSegment, ...]
    pressure_kpa: float
    target_xy_mm: np.ndarray
    predicted_xy_mm: np.ndarray
    rmse_mm: float
    max_deviation_mm: float
    tip_error_mm: float
    tip_angle_error_deg: float
    fit_rmse_mm: float
    reached: bool
    statement: str
    warnings: tuple[str, ...] = ()
    findings: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()

    def as_dict(self) -> dict:
        """JSON-ready (without the point arrays).

        Returns
        -------
        dict
            Every field but the design and the point arrays; segments as :meth:`ShapeSegment.as_dict`.

        Examples
        --------
        >>> from embroact.predict.shape import BentShape
        >>> target = BentShape.chain([100.0], [60.0]).profile_mm(np.linspace(0.0, 100.0, 201))
        >>> r = design_shape(target, 150.0, max_segments=1)
        >>> d = r.as_dict()
        >>> d["reached"], d["segments"][0]["pattern"], "target_xy_mm" in d
        (True, 'zigzag', False)
        """
        return {"pressure_kpa": self.pressure_kpa, "reached": self.reached, "statement": self.statement,
                "rmse_mm": self.rmse_mm, "max_deviation_mm": self.max_deviation_mm,
                "tip_error_mm": self.tip_error_mm, "tip_angle_error_deg": self.tip_angle_error_deg,
                "fit_rmse_mm": self.fit_rmse_mm, "segments": [s.as_dict() for s in self.segments],
                "warnings": list(self.warnings), "findings": list(self.findings), "notes": list(self.notes)}


def _branch(x: np.ndarray, theta: np.ndarray, ok: np.ndarray, at: float) -> tuple[float, float]:
    """The stretch of the table around ``at`` where the bend is valid and monotone in the parameter."""
    i = int(np.clip(np.searchsorted(x, at) - 1, 0, len(x) - 2))
    rising = theta[i + 1] >= theta[i]
    lo = i
    while lo > 0 and ok[lo - 1] and (theta[lo] >= theta[lo - 1]) == rising:
        lo -= 1
    hi = i + 1
    while hi < len(x) - 1 and ok[hi + 1] and (theta[hi + 1] >= theta[hi]) == rising:
        hi += 1
    return float(x[lo]), float(x[hi])


def _choose(model: _Model, spaces: dict, length_mm: float, theta_deg: float):
    """(space, x, (low, high), note): the pattern parameter bending a segment by theta at P*, or the nearest.

    ``(low, high)`` is the monotone branch of the bend around ``x`` (within the segment's
    length limit for a cross pattern: two leg pitches, ``4 w tan(alpha0) <= L``), where the
    joint polish may move it.
    """
    options, near = [], None
    # a negative bend needs a kind that can bend negative: one with a thread angle
    order = tuple(k for k in spaces if theta_deg >= 0.0 or model_kind(k).has_thread_angle)
    for rank, kind in enumerate(order):
        space = spaces[kind]
        x, theta, status = model.table(space, length_mm, points=61)
        shortest = pattern_kind(kind).min_length_mm
        fits = np.array([shortest(space.params(v)) <= length_mm for v in x])
        ok = np.isin(status, _VALID) & fits
        for r in _roots(model, space, length_mm, theta_deg, (x, theta, np.where(ok, status, -1))):
            slope = abs(float(np.interp(r, x, np.gradient(theta, x))))
            options.append((rank, slope, r, space, _branch(x, theta, ok, r)))
        for xi, ti in zip(x[ok], theta[ok]):
            if near is None or abs(ti - theta_deg) < near[0]:
                near = (abs(ti - theta_deg), space, float(xi), float(ti), _branch(x, theta, ok, float(xi)))
        if options:
            break
    if options:
        _, _, r, space, branch = min(options, key=lambda o: (o[0], o[1], o[2]))
        return space, r, branch, ""
    if near is None:
        raise ParameterError(f"a {length_mm:.1f} mm segment has no valid pattern at this pressure")
    _, space, xb, tb, branch = near
    return space, xb, branch, f"{theta_deg:.1f} deg needed, {tb:.1f} deg is the nearest a {space.pattern} reaches"


def _nominal_xy(model: _Model, spaces, x, lengths, sj, legs) -> tuple[np.ndarray, np.ndarray]:
    """Predicted line at arc lengths ``sj`` with the segments' parameters ``x`` and leg extents ``legs``."""
    from .shape import planar_chain_mm

    params = [sp.params(v) for sp, v in zip(spaces, x)]
    theta, status = model.theta(params, [l0 for _, l0 in legs])
    pieces, bends = [], []
    for (gap, l0), L, t in zip(legs, lengths, theta):
        pieces += [gap, l0, L - gap - l0]
        bends += [0.0, float(t), 0.0]
    keep = np.asarray(pieces) > 1e-9
    return planar_chain_mm(np.asarray(pieces)[keep], np.asarray(bends)[keep], sj), status


def curvature_range(model: _Model, spaces: dict) -> tuple[float, float]:
    """(most negative, most positive) curvature [1/mm] a segment reaches at the model's pressure in a valid state,
    over every design space: one scan per pattern at ``_REACH_LENGTH_MM``. The model's P(theta) depends on the
    length only through theta / l0, so a scan at one length gives the curvature at every length (the realised
    geometry moves a little with length: ``_REACH_SLACK``).

    Parameters
    ----------
    model : _Model
        The search's model at the target pressure.
    spaces : dict of str to DesignSpace
        The design spaces searched.

    Returns
    -------
    tuple of float
        [1/mm].

    Examples
    --------
    >>> from embroact.patterns.design import ModelSettings
    >>> lo, hi = curvature_range(_Model(250.0, Tube(), ModelSettings(), ()), {"zigzag": design_space("zigzag")})
    >>> lo, round(hi, 4)  # a zigzag bends one way only
    (0.0, 0.0625)
    """
    lo = hi = 0.0
    for space in spaces.values():
        x, theta, status = model.table(space, _REACH_LENGTH_MM)
        ok = np.isin(status, _VALID)
        if not ok.any():
            continue
        l0 = np.array([_legs(space.params(float(v)), _REACH_LENGTH_MM)[1] for v in x[ok]])
        kappa = np.radians(theta[ok]) / l0
        lo, hi = min(lo, float(kappa.min())), max(hi, float(kappa.max()))
    return lo, hi


def _target_touches(sj: np.ndarray, xy: np.ndarray, tube: Tube) -> str | None:
    """Why a strip along the resampled target would touch itself or the clamp, or None.

    The target as a chain of short arcs (each turning by its chord's change of heading) with the
    tube's sealed stub beyond its tip, tested as a sewn strip's line is
    (:func:`~embroact.predict.validity.strip_contact`), with the thinnest strip a design can be (the
    unpressurised tube's radius): a strip thicker still touches sooner.
    """
    from .validity import strip_contact

    d = np.diff(xy, axis=0)
    heading = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    turns = np.degrees(np.diff(np.concatenate([[0.0], heading])))
    if not strip_contact(np.diff(sj), turns, tube.outer_radius_mm, tube.end_margin_mm):
        return None
    return (f"touches itself or the clamp as a strip with the {tube.end_margin_mm:g} mm sealed tube beyond its tip "
            f"(even one as thin as the unpressurised tube, radius {tube.outer_radius_mm:g} mm)")


def shape_unreachable(sj: np.ndarray, xy: np.ndarray, kappa_range: tuple[float, float]) -> str | None:
    """Why no chain of segments with curvatures in ``kappa_range`` [1/mm] can follow the resampled target
    (``sj``, ``xy`` as :func:`design_shape` resamples it), or None when one may come near it. Only clear
    cases, so that a noisy target still gets its nearest design: the heading at the clamp (a bent strip
    leaves it along +x; the mean heading of the first ``_REACH_WINDOW_MM`` may differ by at most what the
    curvature allows plus ``_REACH_HEADING_DEG``), a corner (a turn within ``_REACH_CORNER_MM`` beyond what
    the curvature allows by ``_REACH_CORNER_DEG``) and the whole target's bend (its net turning beyond the
    range times its length by ``_REACH_HEADING_DEG``). Decided from the target and the range alone.

    Parameters
    ----------
    sj : numpy.ndarray (m,)
        Evenly spaced arc lengths [mm].
    xy : numpy.ndarray (m, 2)
        The target at them [mm].
    kappa_range : tuple of float
        Reachable curvature (:func:`curvature_range`) [1/mm].

    Returns
    -------
    str or None
        The reason, in words.

    Examples
    --------
    >>> sj = np.linspace(0.0, 100.0, 201)
    >>> shape_unreachable(sj, np.column_stack([sj, 0.0 * sj]), (-0.02, 0.03)) is None
    True
    >>> corner = np.column_stack([np.minimum(sj, 50.0), np.maximum(sj - 50.0, 0.0)])
    >>> shape_unreachable(sj, corner, (-0.02, 0.03))
    'turns by +90.0 deg in the 2 mm from 48.5 mm along it (a corner): no design turns more than +3.8 deg there'
    """
    lo, hi = kappa_range
    step = float(sj[1] - sj[0])
    d = np.diff(xy, axis=0)
    heading = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    top = max(-lo, hi)
    n = min(len(heading), max(1, int(math.ceil(_REACH_WINDOW_MM / step))))
    start = math.degrees(float(heading[:n].mean()))
    allowed = math.degrees(_REACH_SLACK * top * n * step / 2.0) + _REACH_HEADING_DEG
    if abs(start) > allowed:
        return (f"leaves the clamp heading {start:+.1f} deg from +x over its first {n * step:.3g} mm; a bent strip "
                f"leaves it along +x (within {allowed:.1f} deg there)")
    n = max(1, int(math.ceil(_REACH_CORNER_MM / step)))
    if len(heading) > n:
        turn = np.degrees(heading[n:] - heading[:-n])
        up, down = (math.degrees(_REACH_SLACK * k * n * step) for k in (hi, lo))
        for k, bound in ((int(np.argmax(turn - up)), up), (int(np.argmin(turn - down)), down)):
            if abs(turn[k] - bound) > _REACH_CORNER_DEG and (turn[k] > bound if bound > 0 else turn[k] < bound):
                return (f"turns by {turn[k]:+.1f} deg in the {n * step:.3g} mm from {sj[k + 1]:.3g} mm along it (a "
                        f"corner): no design turns more than {bound:+.1f} deg there")
    net = math.degrees(float(heading[-1] - heading[0]))
    length = float(sj[-1])
    for bound in (math.degrees(_REACH_SLACK * hi * length), math.degrees(_REACH_SLACK * lo * length)):
        if (net > bound + _REACH_HEADING_DEG) if bound > 0 else (net < bound - _REACH_HEADING_DEG):
            return (f"bends by {net:+.1f} deg over its {length:.3g} mm; no design bends more than {bound:+.1f} deg "
                    f"over that length at this pressure (curvature {bound / math.degrees(length):+.2g} /mm)")
    return None


def design_shape(target_xy_mm, pressure_kpa: float, *, max_segments: int = 6, tube: Tube = Tube(),
                 settings: ModelSettings = ModelSettings(), sets: Iterable = (), allow_extrapolation: bool = False,
                 name: str = "A1", time_limit_s: float = DEFAULT_TIME_LIMIT_S, tolerance_mm: float = 0.5,
                 progress=None, operation: OperationSettings = OperationSettings()) -> ShapeResult:
    """The segmented actuator whose fabric line bends into ``target_xy_mm`` at ``pressure_kpa``.

    Parameters
    ----------
    target_xy_mm : array (m, 2)
        The curve [mm], from the clamped end (moved to the origin) heading +x there; +y
        toward the back of the fabric (the side positive bends turn to).
    pressure_kpa : float
        Pressure at which the shape is wanted [kPa], > 0.
    max_segments : int
        At most this many segments, in [1, 12].
    tube, settings, sets, allow_extrapolation, name
        As for :func:`design_bend`.
    time_limit_s : float
        Wall-clock budget of the search [s], in (0, 86400]: no new curvature fit is polished once it is
        spent; the best design so far is returned (its statement says so), or, with none yet, a
        ParameterError asks for a larger limit.
    tolerance_mm : float
        The sewn design meets the shape when its RMSE against the target is at most this [mm], in (0, 100].
    progress : callable, optional
        ``progress(message)`` at each step of the search (the command prints them on a terminal).
    operation : OperationSettings
        The operation limits the written design keeps, with the target pressure as its operating point
        (:func:`operating_limits`).

    Returns
    -------
    ShapeResult

    Raises
    ------
    ParameterError
        Bad input; a target no design can follow (:func:`shape_unreachable`, decided before any search);
        no design within the time limit.

    Examples
    --------
    >>> from embroact.predict.shape import BentShape
    >>> target = BentShape.chain([100.0], [60.0]).profile_mm(np.linspace(0.0, 100.0, 201))
    >>> r = design_shape(target, 150.0, max_segments=1)
    >>> r.reached, r.segments[0].pattern, r.statement.split(":")[0]
    (True, 'zigzag', 'met with 1 segment(s)')
    """
    import time

    start = time.monotonic()
    p = check_target_pressure(pressure_kpa)
    if isinstance(max_segments, bool) or not isinstance(max_segments, int) or not 1 <= max_segments <= 12:
        raise ParameterError(f"max_segments must be an integer in [1, 12], got {max_segments!r}")
    limit = check_range("time_limit_s", time_limit_s, low=0.0, high=86400.0, high_inclusive=True)
    tolerance_mm = check_range("tolerance_mm", tolerance_mm, low=0.0, high=100.0, high_inclusive=True)
    say = progress if progress is not None else (lambda message: None)
    sets = tuple(sets)
    sj, xy, length = _resample(target_xy_mm)
    model = _Model(p, tube, settings, sets)
    spaces, notes = design_spaces(settings, sets=sets, tube=tube, allow_extrapolation=allow_extrapolation)
    reach = curvature_range(model, spaces)
    why = shape_unreachable(sj, xy, reach) or _target_touches(sj, xy, tube)
    if why is not None:
        raise ParameterError(f"target shape at pressure_kpa {p:g}: not reachable by any design: it {why}")
    say(f"reachable curvature at {p:g} kPa: {reach[0]:+.3g} to {reach[1]:+.3g} /mm; fitting the target")
    fits = []
    for n in range(1, max_segments + 1):
        fits.append(fit_curvature(xy, n))
        if fits[-1][2] <= _FIT_GOOD_MM:
            break
    # fewest segments first, among fits any chain of arcs could be polished from; the first that is
    # reached and close wins, else the closest reached one, else the closest
    plausible = [f for f in fits if f[2] <= max(_FIT_PLAUSIBLE_MM, 1.25 * min(g[2] for g in fits))]
    # the machine grid steps a zigzag's width: where the fewest segments miss, more segments mix neighbouring widths
    extra = range(len(fits) + 1, min(max_segments, len(fits) + _EXTRA_SEGMENTS) + 1)
    results, failures = [], []
    for lengths, kappa, rmse_fit in itertools.chain(plausible, (fit_curvature(xy, n) for n in extra)):
        if time.monotonic() - start > limit:
            failures.append(f"time limit {limit:g} s reached before {len(lengths)} segments were tried")
            break
        say(f"trying {len(lengths)} segment(s) (curvature fit RMSE {rmse_fit:.3f} mm; {time.monotonic() - start:.1f} s)")
        try:
            r = _shape_attempt(model, spaces, sj, xy, length, lengths, kappa, rmse_fit, tube, settings, sets, name, p,
                               tolerance_mm, progress, operation=operating_limits(operation, p))
        except EmbroactError as exc:  # e.g. a segment too short for any pattern at this pressure
            failures.append(f"{len(lengths)} segments: {exc}")
            continue
        results.append(dataclasses.replace(r, notes=notes))
        if r.reached and r.rmse_mm <= _SHAPE_GOOD_MM:
            return results[-1]
    if not results:
        more = "; raise the time limit" if failures and failures[-1].startswith("time limit") else ""
        raise ParameterError(f"target shape at pressure_kpa {p:g}: no design found; " + "; ".join(failures) + more)
    reached = [r for r in results if r.reached]
    best = min(reached or results, key=lambda r: (r.rmse_mm, len(r.segments)))
    if failures and failures[-1].startswith("time limit"):
        best = dataclasses.replace(best, statement=f"{best.statement} ({failures[-1]})")
    return best


def _shape_design(seg_spaces, x, lengths, name: str, tube: Tube, settings: ModelSettings,
                  operation: OperationSettings) -> Design:
    """The (segmented) one-actuator design of parameters ``x`` and segment ``lengths``, its straight path moved
    half a grid unit across itself where every width is an odd number of units (:func:`rail_offset_mm`: the
    segments share the path, so the rails of all of them lie on the grid)."""
    segs = tuple(SegmentSpec(sp.params(v), float(L)) for sp, v, L in zip(seg_spaces, x, lengths))
    shifts = {rail_offset_mm(sg.params.width_mm) for sg in segs}
    path = Centerline.straight(float(np.sum(lengths)), origin_mm=(0.0, shifts.pop() if len(shifts) == 1 else 0.0))
    if len(segs) == 1:
        spec = ActuatorSpec(name, segs[0].params, path, model=settings)
    else:
        spec = ActuatorSpec.segmented(name, segs, path, model=settings)
    return Design(name, tube, MachineSettings(), operation, (spec,))


def _split_stepped(model: _Model, seg_spaces, x, lengths, offset: float = 0.0):
    """Each segment whose stepped parameter (a zigzag width) lies between two grid values (``offset`` plus whole
    grid steps, :meth:`DesignSpace.sewable`), as two segments of those values whose bends add up to its own:
    ``(spaces, x, lengths, index)``, ``index`` the segment each new one comes from.

    A segment bends by its curvature times its bent length, so the grid widths ``a`` and ``b`` around ``x``
    share its length ``L`` as ``L_a kappa_a + L_b kappa_b = L kappa_x``; a segment whose share would be
    shorter than ``_MIN_SEGMENT_MM`` (or than the pattern's shortest) keeps one segment.
    """
    out_sp, out_x, out_len, index = [], [], [], []
    for i, (sp, v, L) in enumerate(zip(seg_spaces, x, lengths)):
        around = sp.sewable(float(v), offset=offset)
        parts = [(float(v), float(L))]
        if sp.grid_step > 0.0 and len(around) == 2:
            params = [sp.params(u) for u in (around[0], around[1], float(v))]
            legs = [_legs(q, float(L))[1] for q in params]
            theta, _ = model.theta(params, legs)
            ka, kb, kv = (t / l0 for t, l0 in zip(theta, legs))
            if abs(ka - kb) > 1e-12:
                la = round(float(L) * (kv - kb) / (ka - kb), 2)
                shortest = max(_MIN_SEGMENT_MM, *(pattern_kind(sp.pattern).min_length_mm(q) for q in params[:2]))
                if shortest <= la <= float(L) - shortest:
                    parts = [(around[0], la), (around[1], round(float(L) - la, 2))]
        for u, length_k in parts:
            out_sp.append(sp)
            out_x.append(u)
            out_len.append(length_k)
            index.append(i)
    return out_sp, np.array(out_x), np.array(out_len), tuple(index)


def _on_grid(seg_spaces, x, lengths, sj, xy, name, tube, settings, sets, p, progress=None, *,
             operation: OperationSettings, offset: float = 0.0):
    """The sewable design nearest ``x`` that fits the target best on the analysed (sewn) design.

    Each stepped parameter (a zigzag width) is moved to a value a straight actuator sews exactly, ``offset``
    plus whole grid steps (one grid unit: every width odd, the path moved half a unit, :func:`_shape_design`);
    then a pattern search on the analysed design (its needle points on the machine grid) keeps every
    single move that lowers the position error: a stepped parameter one grid step either way, a
    continuous one (a cross angle) by 0.2 deg, and, while the error is above ``_SHAPE_GOOD_MM``, a
    boundary between two segments by 1 mm (the grid's coarse widths are met by segment lengths);
    the continuous steps are refined to an eighth. Returns ``(x, lengths, rmse_mm, (design, analysis, shape,
    theta))``, ``rmse_mm`` the sewn line's against the target.
    """
    from .analysis import analyse

    tried = [0]

    def evaluate(v, ls, trial=True):
        tried[0] += 1
        if progress is not None and tried[0] % _PROGRESS_EVERY == 1:
            progress(f"{len(ls)} segment(s) on the machine grid: {tried[0]} sewn designs tried")
        try:  # a trial move may ask what no generator sews (a cross angle too steep for its segment's length)
            design = _shape_design(seg_spaces, v, ls, name, tube, settings, operation)
            a = analyse(design, calibration_sets=sets)
        except EmbroactError:
            if not trial:
                raise
            return math.inf, None
        shape, theta = a.shapes(name, [p])[0]
        return float(np.mean(np.sum((shape.profile_mm(sj) - xy) ** 2, axis=1))), (design, a, shape, theta)

    v = np.array([min(sp.sewable(u, offset=offset), key=lambda g: (abs(g - u), g)) for sp, u in zip(seg_spaces, x)])
    ls = np.asarray(lengths, dtype=np.float64).copy()
    cost, found = evaluate(v, ls, trial=False)
    angle_step, length_step = _SHAPE_ANGLE_STEP_DEG, _SHAPE_LENGTH_STEP_MM
    for _ in range(_GRID_ROUNDS):
        trials = []
        for i, sp in enumerate(seg_spaces):
            near = sp.sewable(v[i], spread=2, offset=offset) if sp.grid_step else (v[i] - angle_step, v[i] + angle_step)
            trials += [(i, round(float(g), 4)) for g in near if g != v[i] and sp.low <= g <= sp.high]
        moves = []
        if cost > _SHAPE_GOOD_MM**2:
            moves = [(b, d) for b in range(len(ls) - 1) for d in (-length_step, length_step)
                     if min(ls[b] + d, ls[b + 1] - d) >= _MIN_SEGMENT_MM]
        moved = False
        for i, g in trials:
            trial = v.copy()
            trial[i] = g
            c, f = evaluate(trial, ls)
            if c < cost - 1e-12:
                v, cost, found, moved = trial, c, f, True
        for b, d in moves:
            trial = ls.copy()
            trial[b], trial[b + 1] = round(trial[b] + d, 2), round(trial[b + 1] - d, 2)
            c, f = evaluate(v, trial)
            if c < cost - 1e-12:
                ls, cost, found, moved = trial, c, f, True
        if not moved:
            if angle_step <= _SHAPE_ANGLE_STEP_DEG / 8.0:
                break
            angle_step, length_step = angle_step / 2.0, length_step / 2.0
    return v, ls, math.sqrt(cost), found


def _width_offsets(seg_spaces) -> tuple[float, ...]:
    """The grids the stepped widths of one chain may take: 0 (even numbers of grid units) and, where no segment's
    width is fixed (a cross segment's calibrated 7 mm holds the shared path on a grid line), one unit (all odd).

    >>> z, c = DesignSpace("zigzag", "width_mm", 5.0, 9.0, 7.0, 1.0), DesignSpace("cross", "angle_deg", 15.0, 60.0, 7.0, 1.4)
    >>> _width_offsets([z, z]), _width_offsets([z, c])
    ((0.0, 0.1), (0.0,))
    """
    grid = DEFAULT_TOLERANCES.machine_grid_mm
    fixed = {round(sp.width_mm / grid) % 2 for sp in seg_spaces if not sp.grid_step}
    return tuple(float(o) * grid for o in ((0, 1) if not fixed else sorted(fixed)))


def _grid_note(seg_spaces) -> str:
    """What the machine grid lets the chain's stepped widths be, for a not-reached shape's statement.

    >>> z, c = DesignSpace("zigzag", "width_mm", 5.0, 9.0, 7.0, 1.0), DesignSpace("cross", "angle_deg", 15.0, 60.0, 7.0, 1.4)
    >>> print(_grid_note([z, c]))  # doctest: +NORMALIZE_WHITESPACE
    zigzag widths in 0.2 mm steps, even numbers of 0.1 mm units: the segments share one path,
    which the cross segments' fixed widths keep on a grid line
    """
    grid = DEFAULT_TOLERANCES.machine_grid_mm
    stepped = sorted({sp.pattern for sp in seg_spaces if sp.grid_step})
    if not stepped:
        return "on the machine grid"
    fixed = sorted({sp.pattern for sp in seg_spaces if not sp.grid_step})
    what = f"{', '.join(stepped)} widths in {2 * grid:g} mm steps"
    if fixed:
        return (f"{what}, even numbers of {grid:g} mm units: the segments share one path, which the "
                f"{', '.join(fixed)} segments' fixed widths keep on a grid line")
    return (f"{what}, all even or all odd numbers of {grid:g} mm units: the segments share one path, moved half a "
            f"unit across for odd widths")


def _shape_attempt(model, spaces, sj, xy, length, lengths, kappa, rmse_fit, tube, settings, sets, name,
                   p, tolerance_mm=0.5, progress=None, *, operation: OperationSettings) -> ShapeResult:
    """Design for one curvature fit: choose each segment's pattern, polish the parameters, analyse."""
    from scipy.optimize import least_squares

    from .rules import check_design

    lengths = np.round(lengths, 2)
    lengths[-1] = round(length - float(lengths[:-1].sum()), 2)
    chosen = []
    for L, k in zip(lengths, kappa):
        gap, l0 = _span_legs(next(iter(spaces.values())).interval_mm, L)
        chosen.append(_choose(model, spaces, float(L), math.degrees(k * l0)))
    seg_spaces = [c[0] for c in chosen]
    x0 = np.array([c[1] for c in chosen])
    def residual(v, legs):
        pred, _ = _nominal_xy(model, seg_spaces, v, lengths, sj, legs)
        return (pred - xy).ravel()

    lo = np.array([c[2][0] for c in chosen])
    hi = np.array([c[2][1] for c in chosen])
    lo, hi = np.minimum(lo, x0), np.maximum(hi, x0)
    hi = np.where(hi - lo > 1e-9, hi, lo + 1e-9)
    x = np.clip(x0, lo + 1e-9, hi - 1e-9)
    best: tuple[float, np.ndarray] | None = None
    for _ in range(_POLISH_ROUNDS):  # the sewn leg extents change in steps with the parameters: hold them per round
        legs = [_legs_sewn(sp.params(v), float(L)) for sp, v, L in zip(seg_spaces, x, lengths)]
        cost = float(np.sum(residual(x, legs) ** 2))  # x as sewn: its own leg extents
        if best is None or cost < best[0]:
            best = (cost, x)
        x = least_squares(residual, x, bounds=(lo, hi), x_scale="jac", diff_step=1e-7, xtol=1e-8, ftol=1e-10,
                          max_nfev=30 * len(x), args=(legs,)).x
        if legs == [_legs_sewn(sp.params(v), float(L)) for sp, v, L in zip(seg_spaces, x, lengths)]:
            best = (0.0, x)
            break
    x = np.round(best[1] if best is not None else x, 4)
    grid = dict(name=name, tube=tube, settings=settings, sets=sets, p=p, progress=progress, operation=operation)
    # the segments share one straight path: all widths even (the path on a grid line), or, where every width is
    # stepped (no fixed width of a cross segment holds the path), all odd (the path half a unit across)
    offsets = _width_offsets(seg_spaces)
    found, offset = min(((_on_grid(seg_spaces, x, lengths, sj, xy, offset=o, **grid), o) for o in offsets),
                        key=lambda f: f[0][2])
    if found[2] > tolerance_mm:  # not met: mix the two grid widths around each width wanted
        split_spaces, split_x, split_lengths, source = _split_stepped(model, seg_spaces, x, lengths, offset)
        if len(split_spaces) > len(seg_spaces):
            mixed = _on_grid(split_spaces, split_x, split_lengths, sj, xy, offset=offset, **grid)
            if mixed[2] < found[2]:
                seg_spaces, found = split_spaces, mixed
                kappa, chosen = np.asarray(kappa)[list(source)], [chosen[i] for i in source]
    x, lengths, _, (design, a, shape, theta) = found
    segs = tuple(SegmentSpec(sp.params(v), float(L)) for sp, v, L in zip(seg_spaces, x, lengths))
    act = a.actuators[0]
    seg_thetas = [float(t) for (length_k, k), t in zip(act.bend_pieces(), theta) if k >= 0]
    curves = a.segment_curves([p])[0]
    bad = [i for i, c in enumerate(curves) if int(c.status[0]) not in _VALID]
    strip = Status(int(a.curves([p])[0].status[0]))  # the whole bent line with its stub (validity.py)
    pred = shape.profile_mm(sj)
    dev = np.hypot(*(pred - xy).T)
    t_tgt = math.degrees(math.atan2(*(xy[-1] - xy[-2])[::-1]))
    t_pred = math.degrees(math.atan2(*(pred[-1] - pred[-2])[::-1]))
    angle_err = (t_pred - t_tgt + 180.0) % 360.0 - 180.0
    findings = check_design(a)  # the gate `embroact check` and `build` run on the written file
    errors = sorted({f.code for f in findings if f.severity.name == "ERROR"})
    near = "; ".join(f"segment {i}: {c[3]}" for i, c in enumerate(chosen) if c[3])  # what each segment misses
    out_segs = tuple(ShapeSegment(sg.params, sg.length_mm, t, float(k), note)
                     for sg, t, k, note in zip(segs, seg_thetas, kappa, [c[3] for c in chosen]))
    rmse = float(np.sqrt(np.mean(dev**2)))
    # a segment whose curvature alone is out of reach may still leave the whole line close: the sewn line decides
    reached = not bad and int(strip) in _VALID and not errors and rmse <= tolerance_mm
    why = []
    if near:
        why.append(near)
    if bad:
        why.append(f"segments {bad} leave the valid model states at {p:g} kPa")
    elif int(strip) not in _VALID:
        why.append(f"the whole strip is {strip.name} at {p:g} kPa: with its {tube.end_margin_mm:g} mm sealed stub "
                   f"it touches itself, the clamp or the fixed fabric")
    if errors:
        why.append(f"design-rule errors {', '.join(errors)}")
    if rmse > tolerance_mm:
        why.append(f"the sewable designs ({_grid_note(seg_spaces)}) leave an RMSE above {tolerance_mm:g} mm")
    statement = (f"met with {len(segs)} segment(s): RMSE {rmse:.3f} mm, max {dev.max():.3f} mm"
                 + (f" ({near}; the whole sewn line is within {tolerance_mm:g} mm)" if near else "") if reached else
                 f"not reachable as asked: {'; '.join(why)}; best achievable: RMSE {rmse:.3f} mm")
    return ShapeResult(design, out_segs, p, xy, pred, rmse, float(dev.max()), float(dev[-1]), float(angle_err),
                       float(rmse_fit), reached, statement, tuple(sorted({f.code for f in findings})),
                       tuple(f"{f.code} {f.severity.name.lower()}: {f.message}" for f in findings))
