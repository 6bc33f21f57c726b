"""The whole strip of an actuator's chain: its sleeve geometry and model, one definition for any chain length.

An actuator is a chain of one or more segments, each with its own derived geometry
(:class:`~embroact.predict.derived.DerivedGeometry`) and model
(:class:`~embroact.predict.calibration.ModelChoice`). The whole strip's values follow the
chain's rule (:mod:`embroact.patterns.chain`): lengths add up, the pattern names the kinds
in chain order, gamma is the whole strip's ``2 r0 / (l0 cos beta0)`` and every other value
is the one all segments have, ``None`` where they differ. The types here hold those values
in the same fields (and :meth:`as_dict` keys) as a segment's, so one segment and five give
the same keys; a chain of one gives its segment's numbers to the last digit.

Examples
--------
>>> from embroact.patterns.design import design_from_dict
>>> from embroact.predict.analysis import analyse
>>> d = design_from_dict({"actuator": [{"name": "S", "segment": [
...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]})
>>> act = analyse(d).actuators[0]
>>> act.derived.pattern, act.derived.width_mm, act.derived.interval_mm, act.derived.length_mm
('zigzag', None, 1.0, 100.0)
>>> act.model.g_mpa, act.model.length_mm, [s.model.g_mpa for s in act.segments]
(None, 100.0, [2.7, 3.4])
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

from ..patterns.chain import common, strip_pattern
from ..patterns.params import Tube
from .calibration import Calibration, ModelChoice, model_dict
from .derived import DerivedGeometry, geometry_dict
from .sleeve import gamma

__all__ = ["StripGeometry", "StripModel", "StripChoice", "strip_geometry", "strip_choice"]


@dataclass(frozen=True, slots=True)
class StripGeometry:
    """The whole strip's sleeve geometry: :class:`~embroact.predict.derived.DerivedGeometry`'s fields for a chain.

    Attributes
    ----------
    name : str
        The actuator's name.
    pattern : str
        The segments' kinds in chain order (:func:`~embroact.patterns.chain.strip_pattern`).
    length_mm : float
        l0 of the strip: the sum of its segments' legs [mm] (the parts that bend).
    width_mm, interval_mm, angle_deg, requested_width_mm, requested_interval_mm, requested_angle_deg : float or None
        The value all segments have, ``None`` where they differ [mm, mm, deg].
    r0_mm, beta0_deg, neutral_angle_deg : float or None
        Likewise [mm, deg, deg].
    gamma : float or None
        ``2 r0 / (l0 cos beta0)`` of the strip (its ``length_mm``) when r0 and beta0 are common [1/rad].
    tube : Tube
        The actuator's tube.
    has_sleeve, bends_positive : bool or None
        Common to all segments, ``None`` where they differ.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> act = analyse(default_design()).actuators[0]
    >>> act.derived.as_dict() == act.segments[0].derived.as_dict()   # a chain of one: its segment's numbers
    True
    """

    name: str
    pattern: str
    length_mm: float
    width_mm: float | None
    interval_mm: float | None
    angle_deg: float | None
    requested_width_mm: float | None
    requested_interval_mm: float | None
    requested_angle_deg: float | None
    r0_mm: float | None
    beta0_deg: float | None
    gamma: float | None
    neutral_angle_deg: float | None
    tube: Tube
    has_sleeve: bool | None
    bends_positive: bool | None

    def as_dict(self) -> dict:
        """Plain dict in the keys of :meth:`DerivedGeometry.as_dict <embroact.predict.derived.DerivedGeometry.as_dict>`.

        Returns
        -------
        dict

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> from embroact.predict.analysis import analyse
        >>> act = analyse(default_design()).actuators[0]
        >>> list(act.derived.as_dict()) == list(act.segments[0].derived.as_dict())
        True
        """
        return geometry_dict(self)


def strip_geometry(name: str, parts: Sequence[DerivedGeometry], tube: Tube) -> StripGeometry:
    """The whole strip's geometry of a chain's segments (:class:`StripGeometry`).

    Parameters
    ----------
    name : str
        The actuator's name.
    parts : sequence of DerivedGeometry
        One per segment, in chain order (at least one).
    tube : Tube
        The actuator's tube.

    Returns
    -------
    StripGeometry

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> from embroact.predict.derived import derive_from_values
    >>> a, b = (derive_from_values("zigzag", width_mm=w, interval_mm=1.0, angle_deg=0.0, length_mm=40.0, tube=Tube())
    ...         for w in (7.0, 9.0))
    >>> s = strip_geometry("S", [a, b], Tube())
    >>> s.length_mm, s.width_mm, s.beta0_deg, s.gamma, s.has_sleeve
    (80.0, None, 0.0, None, True)
    >>> strip_geometry("S", [a, a], Tube()).gamma == a.gamma / 2   # the same sleeve over twice the length
    True
    """
    length = math.fsum(p.length_mm for p in parts)
    values = {f: common(getattr(p, f) for p in parts) for f in _COMMON_GEOMETRY}
    r0, beta0 = values["r0_mm"], values["beta0_deg"]
    g = None if r0 is None or beta0 is None else float(gamma(r0, beta0, length))
    return StripGeometry(name=name, pattern=strip_pattern(p.pattern for p in parts), length_mm=length, gamma=g,
                         tube=tube, **values)


_COMMON_GEOMETRY = ("width_mm", "interval_mm", "angle_deg", "requested_width_mm", "requested_interval_mm",
                    "requested_angle_deg", "r0_mm", "beta0_deg", "neutral_angle_deg", "has_sleeve", "bends_positive")


@dataclass(frozen=True, slots=True)
class StripModel:
    """The whole strip's model: :class:`~embroact.predict.curve.ActuatorModel`'s fields for a chain.

    A summary, not a model to evaluate: the strip's curve is the sum of its segments' (each
    segment's :attr:`~embroact.predict.analysis.SegmentAnalysis.model`;
    :meth:`~embroact.predict.analysis.DesignAnalysis.curves`).

    Attributes
    ----------
    pattern : str
        The segments' kinds in chain order.
    length_mm : float
        The sum of the segments' l0 [mm].
    r0_mm, beta0_deg, outer_radius_mm, inner_radius_mm, g_e_mpa, g_mpa, p0_kpa : float or None
        The value all segments' models have, ``None`` where they differ.
    tube_law, calibration : str or None
        Likewise.
    stub_mm : float
        Sealed tube beyond the strip's tip [mm] (the tube's ``end_margin_mm``).

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> m = analyse(default_design()).actuators[0].model
    >>> m.g_mpa, m.p0_kpa, m.length_mm, m.stub_mm
    (2.7, 85.0, 100.0, 30.0)
    """

    pattern: str
    length_mm: float
    r0_mm: float | None
    beta0_deg: float | None
    outer_radius_mm: float | None
    inner_radius_mm: float | None
    g_e_mpa: float | None
    g_mpa: float | None
    p0_kpa: float | None
    tube_law: str | None
    calibration: str | None
    stub_mm: float


_COMMON_MODEL = ("r0_mm", "beta0_deg", "outer_radius_mm", "inner_radius_mm", "g_e_mpa", "g_mpa", "p0_kpa",
                 "tube_law", "calibration")


@dataclass(frozen=True, slots=True)
class StripChoice:
    """The whole strip's model and sources: :class:`~embroact.predict.calibration.ModelChoice`'s fields for a chain.

    Attributes
    ----------
    model : StripModel
    calibration : Calibration or None
        The lookup all segments share; ``None`` where they differ or none was made.
    g_source, p0_source : str or None
        Common to all segments, ``None`` where they differ.
    tube_law_p0_kpa : float or None
        Likewise [kPa].
    notes : tuple of str
        Every distinct note of the segments, in chain order.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> act = analyse(default_design()).actuators[0]
    >>> act.choice.p0_source, act.choice.as_dict() == act.segments[0].choice.as_dict()
    ('calibration paper-2025 (zigzag, width_mm=7)', True)
    """

    model: StripModel
    calibration: Calibration | None
    g_source: str | None
    p0_source: str | None
    tube_law_p0_kpa: float | None
    notes: tuple[str, ...] = ()

    def as_dict(self) -> dict:
        """JSON-ready, in the keys of :meth:`ModelChoice.as_dict <embroact.predict.calibration.ModelChoice.as_dict>`.

        Returns
        -------
        dict

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> from embroact.predict.analysis import analyse
        >>> act = analyse(default_design()).actuators[0]
        >>> sorted(act.choice.as_dict()) == sorted(act.segments[0].choice.as_dict())
        True
        """
        return model_dict(self)


def strip_choice(choices: Sequence[ModelChoice], stub_mm: float) -> StripChoice:
    """The whole strip's model and sources of a chain's segments (:class:`StripChoice`).

    Parameters
    ----------
    choices : sequence of ModelChoice
        One per segment, in chain order (at least one).
    stub_mm : float
        Sealed tube beyond the strip's tip [mm].

    Returns
    -------
    StripChoice

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> from embroact.predict.calibration import model_for
    >>> from embroact.predict.derived import derive_from_values
    >>> a, b = (model_for(derive_from_values("zigzag", width_mm=w, interval_mm=1.0, angle_deg=0.0, length_mm=40.0,
    ...                                      tube=Tube())) for w in (7.0, 9.0))
    >>> s = strip_choice([a, b], 30.0)
    >>> s.model.g_mpa, s.model.tube_law, s.model.length_mm, s.calibration is None, s.g_source is None
    (None, 'paper', 80.0, True, True)
    """
    models = [c.model for c in choices]
    model = StripModel(pattern=strip_pattern(m.pattern for m in models),
                       length_mm=math.fsum(m.length_mm for m in models), stub_mm=stub_mm,
                       **{f: common(getattr(m, f) for m in models) for f in _COMMON_MODEL})
    return StripChoice(model, common(c.calibration for c in choices), common(c.g_source for c in choices),
                       common(c.p0_source for c in choices), common(c.tube_law_p0_kpa for c in choices),
                       tuple(dict.fromkeys(n for c in choices for n in c.notes)))
