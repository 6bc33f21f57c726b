"""The pattern kinds embroact knows, in one registry: parameters, generator, record estimate, calibration axis.

Importing this module is light (no numpy, no shapely): a kind names its generator module,
which loads on first use, so the command line can list the choices in ``--help`` cheaply.

Every place that needs to know "which patterns exist" or "what is special about this one"
(the design-file schema, the command line's choices, the record-count estimate, the
calibration lookup) asks :data:`PATTERN_KINDS` instead of branching on a name. A third
pattern is one new generator module plus one :func:`register` call.

Examples
--------
>>> from embroact.patterns.kinds import PATTERN_KINDS, pattern_kind
>>> PATTERN_KINDS.names()
('zigzag', 'cross')
>>> k = pattern_kind("cross")
>>> k.param_keys, k.calibration_axis, k.options
(('width_mm', 'interval_mm', 'angle_deg'), 'angle_deg', ('adjust',))
>>> pattern_kind("zigzag").calibration_axis, k.interval.value, k.default_interval_mm
('width_mm', 'parallel legs', 1.4)
>>> try:
...     pattern_kind("satin")
... except ValueError as exc:
...     print(exc)
pattern must be one of 'zigzag', 'cross', got 'satin'
"""
from __future__ import annotations

import enum
import importlib
from dataclasses import dataclass, fields
from typing import Callable

from .base.errors import ParameterError
from .params import CrossParams, PatternParams, ZigzagParams

__all__ = ["Interval", "KindFields", "KindOf", "PatternKind", "PatternKinds", "PATTERN_KINDS", "pattern_kind", "register"]


class Interval(enum.Enum):
    """What a pattern's stitch interval ``interval_mm`` spaces, measured along the path."""

    NEEDLE_POINTS = "needle points"
    """Neighbouring needle points (the zigzag: one leg per interval)."""
    PARALLEL_LEGS = "parallel legs"
    """Neighbouring parallel legs of one family (the cross: two families of legs cross)."""


@dataclass(frozen=True, slots=True)
class PatternKind:
    """What embroact needs to know about one pattern kind.

    Attributes
    ----------
    name : str
        The pattern's name in design files and on the command line.
    params : type
        Its frozen parameter class (``ZigzagParams``, ``CrossParams``).
    module : str
        The generator module inside ``embroact.patterns``; it defines ``<name>`` (the
        generator), ``<name>_stations`` and ``<name>_realised_params`` (see the properties).
    calibration_axis : str
        The parameter a calibration set interpolates over for this pattern.
    options : tuple of str
        Extra generator options a design may set (``("adjust",)`` for the cross pattern).
    interval : Interval
        What ``interval_mm`` spaces (how :func:`embroact.patterns.measure.measure` reads it back).
    default_interval_mm : float
        The paper's stitch interval, used when a quick command gives none [mm].
    """

    name: str
    params: type
    module: str
    calibration_axis: str
    options: tuple[str, ...] = ()
    interval: Interval = Interval.NEEDLE_POINTS
    default_interval_mm: float = 1.0

    def _function(self, suffix: str) -> Callable:
        module = importlib.import_module(f".{self.module}", __package__)
        return getattr(module, self.name + suffix)

    @property
    def generate(self) -> Callable:
        """``generate(centerline, params, *, tube, options, name, **options) -> StitchPlan``."""
        return self._function("")

    @property
    def stations(self) -> Callable:
        """``stations(length_mm, params, **options) -> float``: upper bound of needle stations, no allocation."""
        return self._function("_stations")

    @property
    def realised_params(self) -> Callable:
        """``realised_params(params, **options) -> params`` the generator really uses (cross: closed)."""
        return self._function("_realised_params")

    @property
    def param_keys(self) -> tuple[str, ...]:
        """The parameter names, in declaration order (``width_mm``, ``interval_mm``, ...)."""
        return tuple(f.name for f in fields(self.params))

    @property
    def has_angle(self) -> bool:
        """True when the pattern has an embroidery angle ``angle_deg``."""
        return "angle_deg" in self.param_keys

    def angle_deg(self, params: object) -> float:
        """The embroidery angle alpha0 of ``params`` (this kind's parameters) [deg]; 0 for a kind without one."""
        return float(getattr(params, "angle_deg")) if self.has_angle else 0.0


class PatternKinds:
    """Registry of :class:`PatternKind` by name, in registration order."""

    def __init__(self) -> None:
        self._kinds: dict[str, PatternKind] = {}

    def add(self, kind: PatternKind) -> None:
        """Register ``kind`` (its name must be new)."""
        if kind.name in self._kinds:
            raise ParameterError(f"pattern kind {kind.name!r} is already registered")
        self._kinds[kind.name] = kind

    def names(self) -> tuple[str, ...]:
        """Registered names, in order."""
        return tuple(self._kinds)

    def __getitem__(self, name: object) -> PatternKind:
        found = self._kinds.get(name) if isinstance(name, str) else None
        if found is None:
            raise ParameterError(f"pattern must be one of {', '.join(map(repr, self._kinds))}, got {name!r}")
        return found

    def __iter__(self):
        return iter(self._kinds.values())

    def for_params(self, params: object) -> PatternKind:
        """The kind whose parameter class ``params`` is an instance of."""
        for kind in self._kinds.values():
            if isinstance(params, kind.params):
                return kind
        valid = " or ".join(k.params.__name__ for k in self._kinds.values())
        raise ParameterError(f"params must be {valid}, got {type(params).__name__}")


PATTERN_KINDS = PatternKinds()
"""Every pattern kind embroact generates."""


def register(kind: PatternKind) -> None:
    """Add a pattern kind to :data:`PATTERN_KINDS`."""
    PATTERN_KINDS.add(kind)


def pattern_kind(name: object) -> PatternKind:
    """The registered kind called ``name`` (:class:`ParameterError` listing the valid names otherwise)."""
    return PATTERN_KINDS[name]


class KindOf:
    """Mixin of a value holding pattern parameters ``params`` (request or plan): its kind's name and angle.

    Examples
    --------
    >>> from embroact.patterns.segments import SegmentSpec
    >>> s = SegmentSpec(CrossParams(7.0, 1.4, 30.0), 40.0, adjust="angle")
    >>> s.pattern, s.requested_angle_deg
    ('cross', 30.0)
    """

    __slots__ = ()
    params: PatternParams

    @property
    def pattern(self) -> str:
        """The pattern kind's name (``"zigzag"``, ``"cross"``)."""
        return self.params.pattern

    @property
    def requested_angle_deg(self) -> float:
        """alpha0 asked for (0 for a kind without an angle, zigzag) [deg]."""
        return pattern_kind(self.pattern).angle_deg(self.params)


class KindFields(KindOf):
    """Mixin of a request holding ``params`` and its kind's generator options as fields (actuator, segment).

    Examples
    --------
    >>> from embroact.patterns.segments import SegmentSpec
    >>> s = SegmentSpec(CrossParams(7.0, 1.4, 30.0), 40.0, adjust="angle")
    >>> s.pattern, s.kind_options
    ('cross', {'adjust': 'angle'})
    """

    __slots__ = ()

    @property
    def kind_options(self) -> dict:
        """The generator options this pattern kind takes (``{"adjust": ...}`` for cross)."""
        return {key: getattr(self, key) for key in pattern_kind(self.pattern).options}


register(PatternKind("zigzag", ZigzagParams, "zigzag", "width_mm"))
register(PatternKind("cross", CrossParams, "cross", "angle_deg", ("adjust",), Interval.PARALLEL_LEGS, 1.4))
