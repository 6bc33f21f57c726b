"""One analysed design: the plan, and per actuator the realised geometry, the calibration and the model.

:func:`analyse` is the one place where a design becomes numbers. Every command
(``build``, ``check``, ``predict``, ``fit``, ``preview``, ``zigzag``/``cross``) and the
Python API call it, so they all see the same plan, the same derived sleeve geometry and
the same model, computed once per run::

    Design --build_plan--> StitchPlan --derive--> DerivedGeometry --model_for--> ModelChoice
      |                        |                        \\                      /
      +------------------------+-------------------> ActuatorAnalysis (frozen) per actuator
                                                          |
                                       DesignAnalysis.curves(pressures) -> Curve per actuator
                                       (a segmented one: StripCurve, the sum of its segments'
                                       curves; computed once per pressure grid and method, then reused)

The policy for G and P0 (what a design's ``[actuator.model]`` means, what command-line
flags override) is :func:`embroact.predict.calibration.model_for`'s; a command applies its
flags by changing the design's settings (:func:`with_model_overrides`) before analysing, so
there is no second way in.

Examples
--------
>>> from embroact.patterns.design import default_design
>>> from embroact.predict.analysis import analyse
>>> a = analyse(default_design())
>>> act = a.actuators[0]
>>> act.name, round(act.derived.r0_mm, 4), act.model.g_mpa, act.model.p0_kpa
('A1', 2.5814, 2.7, 85.0)
>>> act.choice.p0_source
'calibration paper-2025 (zigzag, width_mm=7)'
>>> c = a.curves([0.0, 100.0, 200.0])[0]
>>> [round(float(t), 3) for t in c.theta_deg]
[0.0, 11.539, 102.93]
>>> a.curves([0.0, 100.0, 200.0])[0] is c   # computed once
True
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Iterable, Mapping, Sequence

import numpy as np

from ..patterns.base.display import repr_html
from ..patterns.base.errors import EmbroactError, ModelDomainError, ParameterError
from ..patterns.chain import Chain, common
from ..patterns.design import ActuatorSpec, Design, ModelSettings, build_plan
from ..patterns.plan import ActuatorPlan, SegmentPlan, StitchPlan
from .calibration import CalibrationSet, ModelChoice, as_calibration_sets, model_for
from .derived import DerivedGeometry, derive
from .strip import StripChoice, StripGeometry, StripModel, strip_choice, strip_geometry

if TYPE_CHECKING:  # pragma: no cover
    from .layoutchoice import LayoutChoice
    from .markers import MarkerLayout
    from .uncertainty import Band

__all__ = ["ActuatorAnalysis", "SegmentAnalysis", "StripCurve", "whole_strip", "DesignAnalysis", "analyse",
           "segment_plans", "with_model_overrides", "PRESSURE_STEP_KPA", "pressure_grid_kpa"]

#: Step of a design's standard pressure grid (0 to the working pressure) [kPa].
PRESSURE_STEP_KPA = 10.0


def pressure_grid_kpa(max_pressure_kpa: float, step_kpa: float = PRESSURE_STEP_KPA) -> tuple[float, ...]:
    """0 to ``max_pressure_kpa`` in ``step_kpa`` steps, the top pressure always included.

    Parameters
    ----------
    max_pressure_kpa : float
        The top [kPa].
    step_kpa : float, optional
        The step [kPa].

    Returns
    -------
    tuple of float

    Examples
    --------
    >>> pressure_grid_kpa(25.0)
    (0.0, 10.0, 20.0, 25.0)
    """
    n = int(np.floor(max_pressure_kpa / step_kpa * (1.0 + 1e-12)))
    grid = tuple(float(v) for v in np.linspace(0.0, n * step_kpa, n + 1))
    return grid if abs(grid[-1] - max_pressure_kpa) <= 1e-9 * step_kpa else grid + (float(max_pressure_kpa),)


@dataclass(frozen=True, slots=True)
class SegmentAnalysis:
    """One segment of an actuator's chain: what was sewn there and its own model (docs/model.md, segments).

    Attributes
    ----------
    plan : SegmentPlan
        The generated segment (request, realised parameters, where its legs lie).
    derived : DerivedGeometry
        Sleeve geometry of the segment (``length_mm``: its legs' extent, the part that bends).
    choice : ModelChoice or None
        The segment's model (calibration at its own pattern); ``None`` with ``model_error``.
    model_error : str
        Why it has no model (empty when it has one).

    Examples
    --------
    >>> from embroact.patterns.design import design_from_dict
    >>> d = design_from_dict({"actuator": [{"name": "S", "segment": [
    ...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
    ...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]})
    >>> analysis = analyse(d)
    >>> seg = analysis.actuators[0].segments[1]
    >>> seg.plan.start_mm, round(seg.derived.r0_mm, 4), seg.choice.model.g_mpa, seg.model_error
    (50.0, 3.1539, 3.4, '')
    """

    plan: SegmentPlan
    derived: DerivedGeometry
    choice: ModelChoice | None
    model_error: str = ""

    @property
    def model(self):
        """The segment's :class:`~embroact.predict.curve.ActuatorModel` (:class:`ModelDomainError` when none)."""
        if self.choice is None:
            raise ModelDomainError(self.model_error)
        return self.choice.model

    def as_dict(self) -> dict:
        """JSON-ready: where the segment lies, its derived geometry and model.

        Returns
        -------
        dict

        Examples
        --------
        >>> from embroact.patterns.design import design_from_dict
        >>> d = design_from_dict({"actuator": [{"name": "S", "segment": [
        ...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
        ...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]})
        >>> analysis = analyse(d)
        >>> d = analysis.actuators[0].segments[1].as_dict()
        >>> d["pattern"], d["start_mm"], d["model_error"]
        ('zigzag', 50.0, None)
        """
        p = self.plan
        return {"pattern": p.pattern, "start_mm": p.start_mm, "length_mm": p.length_mm,
                "first_leg_mm": p.first_leg_mm, "transition_mm": p.transition_mm, "join_run_mm": p.join_run_mm,
                "adjustments": list(p.adjustments), "derived": self.derived.as_dict(),
                "model": self.choice.as_dict() if self.choice is not None else None,
                "model_error": self.model_error or None}


@dataclass(frozen=True, slots=True)
class StripCurve:
    """A segmented actuator's whole-strip curve: the sum of its segments' bends (docs/model.md, segments).

    Attributes
    ----------
    pressure_kpa, theta_deg : ndarray
        Pressure [kPa] and the whole strip's bend, the sum of the segments' bends [deg].
    status : ndarray of int8
        :class:`~embroact.predict.status.Status` code of the whole strip per pressure
        (:func:`~embroact.predict.validity.strip_status`): a model state only where every
        segment's state is one and the strip touches neither itself nor the clamp, so
        :func:`~embroact.predict.validity.valid_mask` tells the views which shapes to draw.
    segments : tuple of Curve
        Each segment's own curve, in order along the path.
    method : str
        The segments' methods (one name when they agree).

    Examples
    --------
    >>> from embroact.patterns.design import design_from_dict
    >>> d = design_from_dict({"actuator": [{"name": "S", "segment": [
    ...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
    ...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]})
    >>> analysis = analyse(d)
    >>> strip = analysis.curves([0.0, 200.0])[0]
    >>> type(strip).__name__, strip.theta_deg.round(2).tolist(), len(strip.segments)
    ('StripCurve', [0.0, 58.94], 2)
    """

    pressure_kpa: np.ndarray
    theta_deg: np.ndarray
    status: np.ndarray
    segments: tuple
    method: str

    def segment_theta_deg(self, index: int) -> tuple[float, ...]:
        """Each segment's bend at pressure number ``index`` [deg].

        Parameters
        ----------
        index : int
            Index into ``pressure_kpa``.

        Returns
        -------
        tuple of float
            In order along the path; they add up to ``theta_deg[index]``.

        Examples
        --------
        >>> from embroact.patterns.design import design_from_dict
        >>> d = design_from_dict({"actuator": [{"name": "S", "segment": [
        ...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
        ...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]})
        >>> analysis = analyse(d)
        >>> [round(t, 2) for t in analysis.curves([0.0, 200.0])[0].segment_theta_deg(1)]
        [51.47, 7.47]
        """
        return tuple(float(c.theta_deg[index]) for c in self.segments)

    def as_dict(self) -> dict:
        """JSON-ready, in the keys of :meth:`Curve.as_dict <embroact.predict.curve.Curve.as_dict>`, by the chain's rule.

        ``theta_deg`` and ``status`` are the whole strip's, ``length_mm`` the sum of the
        segments' thread-side lengths; ``radius_mm``, ``beta_deg`` and ``inner_radius_mm`` are
        per pressure the value every segment has (``None`` where they differ), ``calibration``
        likewise; ``method`` names the segments' methods.

        Returns
        -------
        dict

        Examples
        --------
        >>> from embroact.patterns.design import design_from_dict
        >>> d = design_from_dict({"actuator": [{"name": "S", "segment": [
        ...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
        ...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]})
        >>> analysis = analyse(d)
        >>> d = analysis.curves([0.0, 200.0])[0].as_dict()
        >>> d["status"], d["radius_mm"][0], d["radius_mm"][1], d["calibration"]
        (['INFLATION', 'BENDING'], 1.5, None, None)
        >>> d["length_mm"] == [a + b for a, b in zip(*(c.length_mm.tolist() for c in analysis.curves([0.0, 200.0])[0].segments))]
        True
        """
        from .status import status_names

        segs = self.segments
        return {"pressure_kpa": self.pressure_kpa.tolist(), "theta_deg": self.theta_deg.tolist(),
                "status": status_names(self.status),
                "length_mm": [math.fsum(v) for v in zip(*(c.length_mm.tolist() for c in segs))],
                **{k: [common(v) for v in zip(*(getattr(c, k).tolist() for c in segs))]
                   for k in ("radius_mm", "beta_deg", "inner_radius_mm")},
                "method": self.method, "calibration": common(c.calibration for c in segs)}

    def __repr__(self) -> str:
        from .status import status_names

        names = status_names(self.status)
        counts = ", ".join(f"{name} {names.count(name)}" for name in dict.fromkeys(names))
        return f"StripCurve({len(self.segments)} segments, {len(names)} pressures; {counts or 'no statuses'})"


def whole_strip(segment_curves: Sequence, pieces: Sequence[tuple[float, int]], stub_mm: float = 0.0):
    """The whole strip's curve of a chain of segments, its status decided on the whole bent line.

    The bend is the sum of the segments' bends; the status per pressure is
    :func:`~embroact.predict.validity.strip_status`'s (a segment's own limit first, then the
    strip touching itself, the clamp or the fixed fabric, with its sealed stub). A chain of
    one gives its segment's :class:`~embroact.predict.curve.Curve` with that status (the same
    object when nothing changes), a longer chain a :class:`StripCurve`.

    Parameters
    ----------
    segment_curves : sequence of Curve
        One per segment, all at the same pressures.
    pieces : sequence of (float, int)
        The fabric line from the clamp, :meth:`ActuatorAnalysis.bend_pieces`.
    stub_mm : float
        Sealed tube beyond the tip [mm] (the tube's ``end_margin_mm``).

    Returns
    -------
    Curve or StripCurve

    Examples
    --------
    >>> from embroact.predict.curve import ActuatorModel, curve
    >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.58, beta0_deg=0, outer_radius_mm=1.5,
    ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
    >>> c = curve(m, [0, 100, 200, 300])
    >>> whole_strip([c], [(100.0, 0)]) is c, whole_strip([c], [(100.0, 0)], 30.0).status.tolist()
    (True, [0, 1, 1, 1])
    >>> s = whole_strip([c, c], [(100.0, 0), (100.0, 1)])   # at 300 kPa each bends 233.9 deg
    >>> [round(float(t), 2) for t in s.theta_deg], s.as_dict()["status"]
    ([0.0, 23.07, 205.71, 467.89], ['INFLATION', 'BENDING', 'BENDING', 'COILED'])
    """
    from .validity import strip_status

    curves = tuple(segment_curves)
    if not curves:
        raise ParameterError("segment_curves must hold at least one curve")
    p = curves[0].pressure_kpa
    if any(c.pressure_kpa.shape != p.shape or not np.array_equal(c.pressure_kpa, p) for c in curves):
        raise ParameterError("segment_curves must all be at the same pressures")
    status = strip_status(pieces, curves, stub_mm)
    if len(curves) == 1:
        one = curves[0]
        return one if np.array_equal(one.status, status) else dataclasses.replace(one, status=status)
    theta = np.sum([c.theta_deg for c in curves], axis=0)
    theta.setflags(write=False)
    method = ", ".join(dict.fromkeys(c.method for c in curves))
    return StripCurve(p, theta, status, curves, method)


@dataclass(frozen=True, slots=True)
class ActuatorAnalysis:
    """One actuator: what was asked, what was sewn, and the model of what was sewn.

    Attributes
    ----------
    spec : ActuatorSpec
        The request.
    plan : ActuatorPlan
        The generated actuator (realised parameters, centerline, rails).
    segments : Chain of SegmentAnalysis
        The actuator as a chain of one or more segments, each with its pattern, where it lies,
        its derived geometry and model (a single-pattern actuator: a chain of one). Outputs
        give one entry per segment, in the same keys for one segment as for five.
    derived : StripGeometry
        The whole strip's sleeve geometry (:mod:`embroact.predict.strip`): ``length_mm`` the sum
        of the segments' legs, every other value the one all segments have, ``None`` where they
        differ (a chain of one: its segment's numbers).
    choice : StripChoice or None
        The whole strip's model and sources by the same rule; ``None`` when a segment has no
        model (``model_error`` names it). A curve is computed from each segment's own model
        (:meth:`DesignAnalysis.curves`, :meth:`DesignAnalysis.segment_curves`).
    model_error : str
        Empty when every segment has a model; else each model-less segment's reason, prefixed
        with the segment (:meth:`~embroact.patterns.chain.Chain.label`).

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> act = analyse(default_design()).actuators[0]
    >>> act.name, act.plan.pattern, act.model.g_mpa, len(act.segments)
    ('A1', 'zigzag', 2.7, 1)
    """

    spec: ActuatorSpec
    plan: ActuatorPlan
    segments: Chain
    derived: StripGeometry = field(init=False, repr=False, compare=False)
    choice: StripChoice | None = field(init=False, repr=False, compare=False)
    model_error: str = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        segs = self.segments
        object.__setattr__(self, "derived", strip_geometry(self.spec.name, [s.derived for s in segs], self.plan.tube))
        errors = [s.model_error for s in segs if s.choice is None]
        object.__setattr__(self, "model_error", "; ".join(errors))
        object.__setattr__(self, "choice", None if errors else strip_choice([s.choice for s in segs],
                                                                            self.plan.tube.end_margin_mm))

    def strip(self, segment_curves: Sequence):
        """The whole strip's curve from one curve per segment of :attr:`segments` (:func:`whole_strip`).

        Its status is decided on the bent line of :meth:`bend_pieces` with the tube's sealed
        stub (``end_margin_mm``) beyond the tip and the supply line at the clamp.

        Parameters
        ----------
        segment_curves : sequence of Curve
            One per link of :attr:`segments`, at the same pressures.

        Returns
        -------
        Curve or StripCurve
            A chain of one: its curve with the whole strip's status; else the sum of the bends.

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> from embroact.predict.curve import curve
        >>> act = analyse(default_design()).actuators[0]
        >>> act.segments[0].model.stub_mm   # a single-pattern actuator's model is its whole strip, with the tube's stub
        30.0
        >>> c = curve(act.segments[0].model, [310.0, 320.0])   # 250.9 and 268.5 deg: the stub reaches the clamp at 253.9
        >>> c.status.tolist(), act.strip([c]).status.tolist()
        ([1, 6], [1, 6])
        """
        return whole_strip(segment_curves, self.bend_pieces(), self.plan.tube.end_margin_mm)

    def bend_pieces(self) -> tuple[tuple[float, int], ...]:
        """The fabric line from the clamp as ``(length_mm, segment index)`` pieces; index -1 bends by zero.

        The pieces cover the path: the unbent lead-in before the first legs, the legs
        (``l0``, index 0) of a single-pattern actuator or each segment's legs with the
        transitions between them, and the tail after the last legs.

        Returns
        -------
        tuple of (float, int)

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> [(round(length, 6), k) for length, k in analyse(default_design()).actuators[0].bend_pieces()]
        [(100.0, 0)]
        """
        spans = [(seg.plan.first_leg_mm, seg.derived.length_mm) for seg in self.segments]
        out, at = [], 0.0
        for k, (start, length) in enumerate(spans):
            if start - at > 1e-9:
                out.append((start - at, -1))
            out.append((length, k))
            at = start + length
        tail = self.plan.centerline.length_mm - at
        if tail > 1e-9:
            out.append((tail, -1))
        return tuple(out)

    @property
    def name(self) -> str:
        """The actuator's name."""
        return self.spec.name

    @property
    def model(self) -> StripModel:
        """The whole strip's model (:attr:`choice`'s); :class:`ModelDomainError` when a segment has none.

        Returns
        -------
        StripModel
            Fields common to every segment's model, ``None`` where they differ; each segment's own
            :class:`~embroact.predict.curve.ActuatorModel` is ``segments[k].model``.

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> analyse(default_design()).actuators[0].model.g_mpa
        2.7
        """
        if self.choice is None:
            raise ModelDomainError(f"actuator {self.name!r}: {self.model_error}")
        return self.choice.model

    def as_dict(self) -> dict:
        """JSON-ready: name, pattern, derived geometry, model with sources (or the model error), segments.

        Returns
        -------
        dict

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> d = analyse(default_design()).actuators[0].as_dict()
        >>> d["name"], d["pattern"], d["model_error"]
        ('A1', 'zigzag', None)
        """
        return {"name": self.name, "pattern": self.derived.pattern, "derived": self.derived.as_dict(),
                "model": self.choice.as_dict() if self.choice is not None else None,
                "model_error": self.model_error or None, "segments": [s.as_dict() for s in self.segments]}

    def __repr__(self) -> str:
        d = self.derived
        model = (f"no model: {self.model_error}" if self.choice is None
                 else f"G {_shown(self.choice.model.g_mpa, 'MPa')}, P0 {_shown(self.choice.model.p0_kpa, 'kPa')}")
        return (f"ActuatorAnalysis({self.name!r}: {d.pattern}, w {_shown(d.width_mm, 'mm')}, "
                f"l0 {_shown(d.length_mm, 'mm')}, r0 {_shown(d.r0_mm, 'mm')}; {model})")

    #: Table row and bend chart in Jupyter (registered by ``embroact``).
    _repr_html_ = repr_html


def _shown(value: float | None, unit: str) -> str:
    """A whole-strip number for a one-line summary: ``"7 mm"``, or ``"per segment"`` where the segments differ."""
    return "per segment" if value is None else f"{value:.4g} {unit}"


@dataclass(frozen=True, slots=True)
class DesignAnalysis:
    """A design analysed once: its plan and one :class:`ActuatorAnalysis` per actuator, in sewing order.

    Curves are computed on request and kept: the same pressures and method give the same
    :class:`~embroact.predict.curve.Curve` objects, so a build's rules, chart, side view,
    3D shape and report share one evaluation.

    Attributes
    ----------
    design : Design
        The design analysed.
    plan : StitchPlan
        Its stitch plan.
    actuators : tuple of ActuatorAnalysis
        One per actuator, in sewing order.
    calibration_sets : tuple of CalibrationSet
        The sets read from files that its settings name.
    same_model_as : tuple of int
        Per actuator, the index of the first actuator whose model is the same in every respect but the name
        and the place (:func:`_alike`: each segment's model or model error and sleeve, the bent line, the
        tube's stub, the calibration setting): its own index for the first of its kind. Identical actuators
        share their curves and their model rules' work (:func:`~embroact.predict.rules.check_model`).

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> a = analyse(default_design())
    >>> a.curves() is a.curves(), len(a.pressures_kpa), a.same_model_as
    (True, 31, (0,))
    """

    design: Design
    plan: StitchPlan
    actuators: tuple[ActuatorAnalysis, ...]
    calibration_sets: tuple[CalibrationSet, ...] = ()
    _curves: dict = field(default_factory=dict, compare=False, repr=False)
    same_model_as: tuple[int, ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        first: dict = {}
        object.__setattr__(self, "same_model_as",
                           tuple(first.setdefault(_alike(a), i) for i, a in enumerate(self.actuators)))

    def actuator(self, name: str) -> ActuatorAnalysis:
        """The actuator called ``name``.

        Parameters
        ----------
        name : str

        Returns
        -------
        ActuatorAnalysis

        Raises
        ------
        ParameterError
            No actuator has that name (the message lists them).

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> analyse(default_design()).actuator("B")
        Traceback (most recent call last):
        ...
        embroact.patterns.base.errors.ParameterError: actuator must be one of A1, got 'B'
        """
        for a in self.actuators:
            if a.name == name:
                return a
        valid = ", ".join(a.name for a in self.actuators)
        raise ParameterError(f"actuator must be one of {valid}, got {name!r}")

    @property
    def pressures_kpa(self) -> tuple[float, ...]:
        """The standard grid: 0 to the design's working pressure in 10 kPa steps."""
        return pressure_grid_kpa(self.design.operation.max_pressure_kpa)

    def _grid(self, pressures_kpa: Sequence[float] | None) -> tuple[float, ...]:
        """``pressures_kpa`` as a tuple of floats (the memo key); :attr:`pressures_kpa` when None."""
        return tuple(float(v) for v in (self.pressures_kpa if pressures_kpa is None else pressures_kpa))

    def curves(self, pressures_kpa: Sequence[float] | None = None, *, method: str = "auto") -> tuple:
        """Predicted curve per actuator at ``pressures_kpa`` (default :attr:`pressures_kpa`), memoised.

        A segmented actuator's curve is its whole strip (:class:`StripCurve`, the sum of its
        segments' bends); its segments' own curves are :meth:`segment_curves`.

        Parameters
        ----------
        pressures_kpa : sequence of float, optional
            Pressures [kPa], >= 0.
        method : str
            As for :func:`~embroact.predict.curve.curve`.

        Returns
        -------
        tuple of Curve or StripCurve
            One per actuator, in sewing order.

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> [round(float(t), 1) for t in analyse(default_design()).curves([100.0, 200.0])[0].theta_deg]
        [11.5, 102.9]

        Raises
        ------
        ModelDomainError
            An actuator (or a segment) has no model (``model_error``).
        """
        p = self._grid(pressures_kpa)
        key = (p, method)
        if key not in self._curves:
            pieces = self.segment_curves(p, method=method)
            self._curves[key] = self._per_kind(lambda i, a: a.strip(pieces[i]))
        return self._curves[key]

    def _per_kind(self, make) -> tuple:
        """``make(index, actuator)`` for the first actuator of each kind (:attr:`same_model_as`), in sewing order,
        and per actuator its kind's result (identical actuators share one object)."""
        made: dict = {}
        for i, (a, first) in enumerate(zip(self.actuators, self.same_model_as)):
            if first == i:
                made[i] = make(i, a)
        return tuple(made[first] for first in self.same_model_as)

    def segment_curves(self, pressures_kpa: Sequence[float] | None = None, *, method: str = "auto") -> tuple:
        """Per actuator, one predicted curve per segment (a single-pattern actuator: its one curve), memoised.

        Segments decouple (docs/model.md, segmented actuators): each bends by its own
        ``theta_k(P)``, zero while ``P <= P0_k``. These are the curves :meth:`curves` gives
        (a single-pattern actuator's is the same object).

        Parameters
        ----------
        pressures_kpa : sequence of float, optional
            Pressures [kPa], >= 0; default :attr:`pressures_kpa`.
        method : str
            As for :func:`~embroact.predict.curve.curve`.

        Returns
        -------
        tuple of tuple of Curve
            Per actuator, one curve per segment.

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> [len(c) for c in analyse(default_design()).segment_curves([200.0])]
        [1]

        Raises
        ------
        ModelDomainError
            A segment (or actuator) has no model.
        """
        p = self._grid(pressures_kpa)
        key = ("segments", p, method)
        if key not in self._curves:
            self._curves[key] = self._per_kind(
                lambda i, a: tuple(self._model_curve(s.model, p, method) for s in a.segments))
        return self._curves[key]

    def model_curve(self, model, pressures_kpa: Sequence[float], *, method: str = "auto"):
        """The curve of one segment's model at these pressures, memoised: identical models (identical
        actuators or segments) share one curve (curves are read-only).

        Parameters
        ----------
        model : ActuatorModel
            A segment's model (:attr:`SegmentAnalysis.model`).
        pressures_kpa : sequence of float
            Pressures [kPa], >= 0.
        method : str
            As for :func:`~embroact.predict.curve.curve`.

        Returns
        -------
        Curve

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> a = analyse(default_design())
        >>> a.model_curve(a.actuators[0].segments[0].model, [200.0]) is a.segment_curves([200.0])[0][0]
        True
        """
        return self._model_curve(model, self._grid(pressures_kpa), method)

    def _model_curve(self, model, p: tuple[float, ...], method: str):
        from .curve import curve

        key = ("model", model, p, method)
        if key not in self._curves:
            self._curves[key] = curve(model, p, method=method)
        return self._curves[key]

    def shapes(self, name: str, pressures_kpa: Sequence[float], *, method: str = "auto") -> tuple:
        """The bent fabric line of actuator ``name`` at each pressure: a chain of arcs (straight path frame).

        Parameters
        ----------
        name : str
            The actuator.
        pressures_kpa : sequence of float
            Pressures [kPa], >= 0.
        method : str
            As for :func:`~embroact.predict.curve.curve`.

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> shape, pieces = analyse(default_design()).shapes("A1", [200.0])[0]
        >>> shape
        BentShape(1 piece, 100 mm, turning 102.9 deg)

        Returns
        -------
        tuple of (BentShape, tuple of float)
            Per pressure the shape (:class:`~embroact.predict.shape.BentShape`, the
            profile frame) and the bend of each piece of :meth:`ActuatorAnalysis.bend_pieces` [deg].
        """
        from .shape import BentShape

        lengths, bends = self._piece_bends(name, pressures_kpa, method)
        out = []
        for row in bends.tolist():
            theta = tuple(row)
            out.append((BentShape.chain(lengths, theta), theta))
        return tuple(out)

    def _piece_bends(self, name: str, pressures_kpa, method: str) -> tuple[list[float], np.ndarray]:
        """Lengths of :meth:`ActuatorAnalysis.bend_pieces` [mm] and their bends (pressures, pieces) [deg]."""
        index = [a.name for a in self.actuators].index(self.actuator(name).name)
        act, curves = self.actuators[index], self.segment_curves(pressures_kpa, method=method)[index]
        pieces = act.bend_pieces()
        zero = np.zeros(len(curves[0].theta_deg))
        bends = np.stack([np.asarray(curves[k].theta_deg, dtype=np.float64) if k >= 0 else zero for _, k in pieces],
                         axis=-1)
        return [length for length, _ in pieces], bends

    def marker_layout(self, name: str, **given) -> LayoutChoice:
        """The marker layout of actuator ``name``'s readings, and where it came from.

        Policy (:func:`~embroact.predict.layoutchoice.layout_for`): each field given here, else
        the layout recorded by the calibration set the actuator's model (a segmented one's:
        its segments') drew G or P0 from, else the paper's layout.

        Parameters
        ----------
        name : str
            The actuator.
        **given
            :class:`~embroact.predict.markers.MarkerLayout` fields to set (``None``: not given).

        Returns
        -------
        LayoutChoice

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> c = analyse(default_design()).marker_layout("A1", spacing_mm=8.0)
        >>> c.layout.spacing_mm, c.source
        (8.0, "given spacing_mm; the rest the paper's (calibration set 'paper-2025' records none)")
        """
        from .calibration import get_set
        from .layoutchoice import layout_for

        act = self.actuator(name)
        choices = [s.choice for s in act.segments]
        if not any(c is not None and c.calibration is not None for c in choices):
            return layout_for(given=given)
        cset = get_set(act.spec.model.calibration, self.calibration_sets)
        return layout_for(cset.marker_layout, calibration=cset.name, given=given)

    def marker_reading_deg(self, name: str, layout: MarkerLayout, pressures_kpa: Sequence[float] | None = None, *,
                           method: str = "auto") -> np.ndarray:
        """What ``layout``'s marker sum reads on actuator ``name``'s predicted bent line, per pressure [deg].

        The line is the chain of arcs of :meth:`shapes` (a single-pattern actuator: one arc),
        clamped where the first legs start (the layout's offset counts from there) and
        straight past the last ones; the reading is
        :func:`~embroact.predict.markers.chain_reading_deg` of it (docs/model.md section 11).
        Memoised.

        Parameters
        ----------
        name : str
            The actuator.
        layout : MarkerLayout
        pressures_kpa : sequence of float, optional
            Pressures [kPa], >= 0; default :attr:`pressures_kpa`.
        method : str
            As for :func:`~embroact.predict.curve.curve`.

        Returns
        -------
        ndarray
            One reading per pressure (read-only).

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> from embroact.predict.markers import PAPER_LAYOUT
        >>> [round(float(r), 3) for r in analyse(default_design()).marker_reading_deg("A1", PAPER_LAYOUT, [200.0])]
        [51.465]
        """
        from .markers import chain_reading_deg

        p = self._grid(pressures_kpa)
        key = ("reading", self.actuator(name).name, p, method, layout)
        if key not in self._curves:
            lengths, bends = self._piece_bends(name, p, method)
            first = next(j for j, (_, k) in enumerate(self.actuator(name).bend_pieces()) if k >= 0)
            out = np.asarray(chain_reading_deg(lengths[first:], bends[:, first:], layout), dtype=np.float64)
            out.setflags(write=False)
            self._curves[key] = out
        return self._curves[key]

    def bands(self, pressures_kpa: Sequence[float] | None = None, *, method: str = "auto",
              measurement=None) -> tuple:
        """1-sigma band of theta(P) per actuator (:class:`~embroact.predict.uncertainty.Band`), memoised.

        An actuator gets a band when G and P0 come from one fitted calibration point with a
        covariance (``embroact fit`` records it); otherwise ``None``: the built-in paper set and
        interpolated or given values carry no uncertainty, and no band is claimed for them.

        Parameters
        ----------
        pressures_kpa : sequence of float, optional
            Pressures [kPa], >= 0; default :attr:`pressures_kpa`.
        method : str
            As for :func:`~embroact.predict.curve.curve`.
        measurement : MarkerLayout, optional
            Also give the band of that layout's marker reading (``Band.reading_sd_deg``).

        Returns
        -------
        tuple of (Band or None)
            One per actuator (``None`` for a segmented one).

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> analyse(default_design()).bands([100.0])   # the built-in set has no covariance
        (None,)
        """
        p = self._grid(pressures_kpa)
        key = ("band", p, method, measurement)
        if key not in self._curves:
            # no band is claimed for a sum of segments
            self._curves[key] = tuple(a.segments.one_or_all(lambda a=a: _band(a.segments[0], p, method, measurement), None)
                                      for a in self.actuators)
        return self._curves[key]

    def as_dict(self) -> dict:
        """JSON-ready summary of every actuator.

        Returns
        -------
        dict
            ``design`` (the name) and ``actuators`` (:meth:`ActuatorAnalysis.as_dict` each).

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> analyse(default_design()).as_dict()["design"]
        'paper-zigzag'
        """
        return {"design": self.design.name, "actuators": [a.as_dict() for a in self.actuators]}

    def __repr__(self) -> str:
        inner = "; ".join(repr(a)[len("ActuatorAnalysis("):-1] for a in self.actuators)
        return f"DesignAnalysis({self.design.name!r}: {inner})"

    #: Actuator table, stitch preview, bend chart and side view in Jupyter (registered by ``embroact``).
    _repr_html_ = repr_html


def _band(seg: SegmentAnalysis, pressures_kpa: tuple, method: str, measurement) -> Band | None:
    """The 1-sigma band of a single-pattern actuator's fitted calibration point, or None (:meth:`DesignAnalysis.bands`).

    The model's G and P0 must both be the point's: fitted as (G, P0), or as (G, G_e) with P0 the tube
    law's at the fitted modulus (its band acts through P0, scaled by that modulus, not the design's).
    """
    from .uncertainty import theta_band

    choice = seg.choice
    if choice is None or choice.calibration is None or not choice.calibration.covariance:
        return None
    if not (choice.g_source.startswith("calibration") and choice.p0_source.startswith("calibration")):
        return None  # G or P0 given, or P0 from the geometry: not the fitted pair
    cal = choice.calibration
    model = seg.model
    if set(cal.fitted) <= {"g_mpa", "g_e_mpa"} and "g_e_mpa" in cal.fitted and cal.g_e_mpa is not None:
        model = dataclasses.replace(model, g_e_mpa=cal.g_e_mpa)
    elif not set(cal.fitted) <= {"g_mpa", "p0_kpa"}:
        return None
    return theta_band(model, pressures_kpa, cal.fitted, cal.covariance, method=method, measurement=measurement)


def with_model_overrides(design: Design, *, actuators: Iterable[str] | None = None, **overrides) -> Design:
    """``design`` with some :class:`ModelSettings` fields replaced (``None`` values are ignored).

    How command-line flags (``--g-mpa``, ``--p0-kpa``, ``--p0-source``, ``--calibration``,
    ``--tube-law``) take precedence over a design file: flag > design file > default.

    Parameters
    ----------
    design : Design
        The design.
    actuators : iterable of str or None, optional
        Only these actuators (default: all).
    **overrides
        :class:`ModelSettings` fields; None values are ignored.

    Returns
    -------
    Design

    Raises
    ------
    ParameterError
        A name that is no ModelSettings field.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> d = with_model_overrides(default_design(), g_mpa=3.0, p0_kpa=None)
    >>> d.actuators[0].model.g_mpa, d.actuators[0].model.p0_kpa
    (3.0, None)
    """
    given = {k: v for k, v in overrides.items() if v is not None}
    unknown = sorted(set(given) - {f.name for f in dataclasses.fields(ModelSettings)})
    if unknown:
        raise ParameterError(f"model override must be a ModelSettings field, got {unknown[0]!r}")
    if not given:
        return design
    names = None if actuators is None else set(actuators)
    specs = tuple(dataclasses.replace(s, model=dataclasses.replace(s.model, **given))
                  if names is None or s.name in names else s for s in design.actuators)
    return dataclasses.replace(design, actuators=specs)


def _alike(act: ActuatorAnalysis) -> tuple:
    """What the model rules and the whole strip's curve read of an actuator but its name and its place
    (:attr:`DesignAnalysis.same_model_as`): the calibration setting, the bent line, the tube's stub, and per
    segment its model choice, model error and whether it has a sleeve."""
    return (act.spec.model.calibration, act.bend_pieces(), act.plan.tube.end_margin_mm,
            tuple((s.choice, s.model_error, s.derived.has_sleeve) for s in act.segments))


def _model_of(derived: DerivedGeometry, settings: ModelSettings, sets,
              stub_mm: float | None) -> tuple[ModelChoice | None, str]:
    if not derived.has_sleeve:
        return None, (f"no sleeve: sleeve radius r0 {derived.r0_mm:.4g} mm is not above the tube radius "
                      f"{derived.tube.outer_radius_mm:g} mm (width_mm {derived.width_mm:.4g} too small)")
    try:
        return model_for(derived, settings, sets=sets, stub_mm=stub_mm), ""
    except EmbroactError as exc:
        return None, str(exc)


def segment_plans(act: ActuatorPlan) -> tuple[ActuatorPlan, ...]:
    """Each segment of an actuator's chain as a single-pattern plan (named ``A1[0]``..., a chain of one
    ``A1``), what its sleeve geometry is derived from.

    Parameters
    ----------
    act : ActuatorPlan
        A generated actuator.

    Returns
    -------
    tuple of ActuatorPlan

    Examples
    --------
    >>> from embroact.patterns.design import default_design, design_from_dict
    >>> d = design_from_dict({"actuator": [{"name": "S", "segment": [
    ...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 40},
    ...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 40}]}]})
    >>> [(p.name, p.realised.width_mm) for p in segment_plans(build_plan(d).actuators[0])]
    [('S[0]', 7.0), ('S[1]', 9.0)]
    >>> [p.name for p in segment_plans(build_plan(default_design()).actuators[0])]
    ['A1']
    """
    return tuple(ActuatorPlan(act.segments.ref(act.name, k), seg.params, act.tube, act.centerline, seg.realised,
                              seg.adjustments, act.options) for k, seg in enumerate(act.segments))


def _analyse_actuator(spec: ActuatorSpec, plan: StitchPlan, index: int, sets, models: dict) -> ActuatorAnalysis:
    """Actuator ``index`` of ``plan``; ``models`` maps what a segment's model is made of (its geometry but the
    name, which the model does not read, the settings and the stub) to the model made of it, shared by identical
    segments and filled here."""
    act = plan.actuators[index]
    segs = []
    # a chain of one is the whole strip's model, with the tube's sealed stub; a longer chain's links check their
    # own arcs, the strip being tested as a whole (ActuatorAnalysis.strip)
    stub = act.segments.one_or_all(act.tube.end_margin_mm, None)
    for k, (seg, part) in enumerate(zip(act.segments, segment_plans(act))):
        derived = derive(part)
        made_of = (dataclasses.replace(derived, name=""), spec.model, stub)
        if made_of not in models:
            models[made_of] = _model_of(derived, spec.model, sets, stub)
        choice, error = models[made_of]
        segs.append(SegmentAnalysis(seg, derived, choice, f"{act.segments.label(k)}{error}" if error else ""))
    return ActuatorAnalysis(spec, act, Chain(segs))


def analyse(design: Design, *, calibration_sets: Iterable[CalibrationSet] | Mapping[str, CalibrationSet] = (),
            plan: StitchPlan | None = None) -> DesignAnalysis:
    """Generate ``design`` and analyse every actuator (the one model factory of every command).

    Parameters
    ----------
    design : Design
    calibration_sets : iterable of CalibrationSet, optional
        Sets searched before the built-in registry (e.g. read from calibration files), with
        the design's own :attr:`~embroact.patterns.design.Design.calibration_sets`.
    plan : StitchPlan, optional
        ``build_plan(design)`` when already generated.

    Returns
    -------
    DesignAnalysis

    Examples
    --------
    >>> from embroact.patterns.design import design_from_dict
    >>> d = design_from_dict({"actuator": [{"name": "X", "pattern": "cross", "width_mm": 7,
    ...                       "interval_mm": 1.4, "angle_deg": 30, "length_mm": 100, "adjust": "angle"}]})
    >>> x = analyse(d).actuators[0]
    >>> round(x.derived.angle_deg, 2), x.derived.requested_angle_deg, round(x.model.g_mpa, 3)  # G where it is sewn
    (30.96, 30.0, 11.873)
    """
    given = as_calibration_sets(calibration_sets)
    sets = given + tuple(s for s in design.calibration_sets if s not in given)  # the files the design names
    plan = build_plan(design) if plan is None else plan
    index = {a.name: i for i, a in enumerate(plan.actuators)}
    models: dict = {}  # identical segments share one model choice
    acts = tuple(_analyse_actuator(spec, plan, index[spec.name], sets, models) for spec in design.actuators)
    return DesignAnalysis(design, plan, acts, sets)
