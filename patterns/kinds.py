"""The pattern kinds embroact knows, in one registry: parameters, generator, record estimate, calibration axis.

Importing this module is light (no numpy, no shapely): a kind names its module (its layout),
which loads on first use, so the command line can list the choices in ``--help`` cheaply.

Every place that needs to know "which patterns exist" or "what is special about this one"
(the design-file schema, the command line's choices, the record-count estimate, the
calibration lookup) asks :data:`PATTERN_KINDS` instead of branching on a name. A third
pattern is one new module (its layout) plus one :func:`register` call.

Examples
--------
>>> from embroact.patterns.kinds import PATTERN_KINDS, pattern_kind
>>> PATTERN_KINDS.names()[:2]
('zigzag', 'cross')
>>> k = pattern_kind("cross")
>>> k.param_keys, k.calibration_axis, k.options
(('width_mm', 'interval_mm', 'angle_deg'), 'angle_deg', ('adjust',))
>>> pattern_kind("zigzag").calibration_axis, k.interval.value, k.default_interval_mm
('width_mm', 'parallel legs', 1.4)
>>> try:
...     pattern_kind("satin")
... except ValueError as exc:
...     print(exc)  # doctest: +ELLIPSIS
pattern must be one of 'zigzag', 'cross'..., got 'satin'
"""
from __future__ import annotations

import enum
import functools
import importlib
import math
from dataclasses import dataclass, fields
from typing import Callable

from .base.errors import ParameterError
from .kindnames import BUILTIN_KINDS
from .params import ADJUST_METHODS, CrossParams, PatternParams, ZigzagParams

__all__ = ["Interval", "KindFields", "KindOf", "PatternKind", "PatternKinds", "PATTERN_KINDS", "pattern_kind",
           "param_values", "params_text", "register"]


class Interval(enum.Enum):
    """What a pattern's stitch interval ``interval_mm`` spaces, measured along the path.

    A member is also the measurement: called with the legs' start and end points in the path
    frame (arc length ``sa``, ``sb`` and signed offset ``oa``, ``ob``, arrays [mm]) it returns
    the realised interval [mm]. A kind whose interval is neither may give any callable of the
    same signature as its :attr:`PatternKind.interval`.

    Examples
    --------
    >>> import numpy as np
    >>> Interval.NEEDLE_POINTS(np.array([0.0, 1.0]), np.array([3.5, -3.5]), np.array([1.0, 2.0]), np.array([-3.5, 3.5]))
    1.0
    """

    NEEDLE_POINTS = "needle points"
    """Neighbouring needle points (the zigzag: one leg per interval)."""
    PARALLEL_LEGS = "parallel legs"
    """Neighbouring parallel legs of one family (the cross: two families of legs cross)."""

    def __call__(self, sa, oa, sb, ob) -> float:
        from .intervals import family_interval_mm, needle_interval_mm

        return (needle_interval_mm if self is Interval.NEEDLE_POINTS else family_interval_mm)(sa, oa, sb, ob)


def _no_minimum(params: object) -> float:
    return 0.0


@functools.lru_cache(maxsize=None)
def _field_names(cls: type) -> tuple[str, ...]:
    """The field names of the dataclass ``cls``, in declaration order: kept per class (asked for every design a
    search derives, through :attr:`PatternKind.has_angle`)."""
    return tuple(f.name for f in fields(cls))


@dataclass(frozen=True, slots=True)
class PatternKind:
    """What embroact needs to know about one pattern kind.

    Attributes
    ----------
    name : str
        The pattern's name in design files and on the command line.
    params : type
        Its frozen parameter class (fields ``width_mm``, ``interval_mm`` and any others, each
        checked against its range by the class itself).
    module : str
        The module's absolute name (``"embroact.patterns.zigzag"``); it defines ``<name>_layout`` (the needle
        stations), ``<name>_stations`` and ``<name>_realised_params`` (see the properties), loaded on first use.
    calibration_axis : str
        The parameter a calibration set interpolates over for this pattern.
    options : tuple of str
        Extra generator options a design may set (``("adjust",)`` for the cross pattern).
    option_values : tuple of tuple of str
        The values each option may take, in the order of ``options`` (the first is the default).
    interval : Interval or callable
        What ``interval_mm`` spaces, and so how :func:`embroact.patterns.measure.measure` reads
        it back: ``interval(sa, oa, sb, ob) -> float`` on the legs' end points (see :class:`Interval`).
    default_interval_mm : float
        The paper's stitch interval, used when a quick command gives none [mm].
    description : str
        One line for the kind's quick command (``embroact <name> --help``).
    design_params : callable or None
        Inverse design's free parameter: ``design_params(x, width_mm, interval_mm) -> params``
        gives the pattern parameters at value ``x`` of :attr:`calibration_axis` (with the
        calibrated width and the nominal interval); None: inverse design does not search this kind.

    Examples
    --------
    >>> k = pattern_kind("zigzag")
    >>> k.name, k.params.__name__, k.calibration_axis, k.interval is Interval.NEEDLE_POINTS
    ('zigzag', 'ZigzagParams', 'width_mm', True)
    >>> k.design_params(6.5, 7.0, 1.0)
    ZigzagParams(width_mm=6.5, interval_mm=1.0)
    """

    name: str
    params: type
    module: str
    calibration_axis: str
    options: tuple[str, ...] = ()
    option_values: tuple[tuple[str, ...], ...] = ()
    interval: Callable = Interval.NEEDLE_POINTS
    default_interval_mm: float = 1.0
    description: str = ""
    design_params: Callable | None = None

    def _function(self, suffix: str) -> Callable:
        return getattr(self._module(), self.name + suffix)

    def _module(self):
        return importlib.import_module(self.module)

    @property
    def layout(self) -> Callable:
        """``layout(cl, params, start_mm, length_mm, *, options, **options) -> Layout``: the needle stations on a
        stretch of the path (:class:`~embroact.patterns.assemble.Layout`)."""
        return self._function("_layout")

    @property
    def stations(self) -> Callable:
        """``stations(length_mm, params, **options) -> float``: upper bound of needle stations, no allocation."""
        return self._function("_stations")

    @property
    def realised_params(self) -> Callable:
        """``realised_params(params, **options) -> params`` the generator really uses (cross: closed)."""
        return self._function("_realised_params")

    @property
    def min_length_mm(self) -> Callable:
        """``min_length_mm(params) -> float``: the shortest path the pattern fits on [mm] (0 unless the module says).

        The module's ``<name>_min_length_mm``; inverse design keeps a segment's pattern within it.
        """
        return getattr(self._module(), self.name + "_min_length_mm", _no_minimum)

    @property
    def param_keys(self) -> tuple[str, ...]:
        """The parameter names, in declaration order (``width_mm``, ``interval_mm``, ...)."""
        return _field_names(self.params)

    def values(self, params: object) -> dict[str, float]:
        """``params`` (this kind's parameters) as ``{key: value}`` in declaration order.

        Parameters
        ----------
        params : PatternParams
            Parameters of this kind.

        Returns
        -------
        dict of str to float

        Examples
        --------
        >>> pattern_kind("zigzag").values(ZigzagParams(7.0, 1.0))
        {'width_mm': 7.0, 'interval_mm': 1.0}
        """
        return {k: float(getattr(params, k)) for k in self.param_keys}

    @property
    def has_angle(self) -> bool:
        """True when the pattern has an embroidery angle ``angle_deg``."""
        return "angle_deg" in self.param_keys

    def angle_deg(self, params: object) -> float:
        """The embroidery angle alpha0 of ``params`` (this kind's parameters) [deg]; 0 for a kind without one.

        Parameters
        ----------
        params : PatternParams
            Parameters of this kind.

        Returns
        -------
        float

        Examples
        --------
        >>> pattern_kind("cross").angle_deg(CrossParams(7.0, 1.4, 45.0))
        45.0
        """
        return float(getattr(params, "angle_deg")) if self.has_angle else 0.0


class PatternKinds:
    """Registry of :class:`PatternKind` by name, in registration order.

    Examples
    --------
    >>> kinds = PatternKinds()
    >>> kinds.add(pattern_kind("zigzag"))
    >>> kinds.names(), kinds["zigzag"] is pattern_kind("zigzag")
    (('zigzag',), True)
    """

    def __init__(self) -> None:
        self._kinds: dict[str, PatternKind] = {}

    def add(self, kind: PatternKind) -> None:
        """Register ``kind`` (its name must be new).

        Parameters
        ----------
        kind : PatternKind

        Raises
        ------
        ParameterError
            A kind of that name is registered already.

        Examples
        --------
        >>> try:
        ...     PATTERN_KINDS.add(pattern_kind("zigzag"))
        ... except ValueError as exc:
        ...     print(exc)
        pattern kind 'zigzag' is already registered
        """
        if kind.name in self._kinds:
            raise ParameterError(f"pattern kind {kind.name!r} is already registered")
        self._kinds[kind.name] = kind

    def remove(self, name: str) -> None:
        """Take the kind ``name`` out of the registry (a plug-in unloaded, a test cleaning up).

        Parameters
        ----------
        name : str

        Examples
        --------
        >>> kinds = PatternKinds()
        >>> kinds.add(pattern_kind("zigzag"))
        >>> kinds.remove("zigzag")
        >>> kinds.names()
        ()
        """
        del self._kinds[self[name].name]

    def names(self) -> tuple[str, ...]:
        """Registered names, in order.

        Returns
        -------
        tuple of str

        Examples
        --------
        >>> PATTERN_KINDS.names()[:2]
        ('zigzag', 'cross')
        """
        return tuple(self._kinds)

    def __getitem__(self, name: object) -> PatternKind:
        found = self._kinds.get(name) if isinstance(name, str) else None
        if found is None:
            raise ParameterError(f"pattern must be one of {', '.join(map(repr, self._kinds))}, got {name!r}")
        return found

    def __iter__(self):
        return iter(self._kinds.values())

    def for_params(self, params: object) -> PatternKind:
        """The kind whose parameter class ``params`` is an instance of.

        Parameters
        ----------
        params : object

        Returns
        -------
        PatternKind

        Raises
        ------
        ParameterError
            ``params`` is no registered kind's parameters (the message names the classes).

        Examples
        --------
        >>> PATTERN_KINDS.for_params(CrossParams(7.0, 1.4, 45.0)).name
        'cross'
        """
        for kind in self._kinds.values():
            if isinstance(params, kind.params):
                return kind
        valid = " or ".join(k.params.__name__ for k in self._kinds.values())
        raise ParameterError(f"params must be {valid}, got {type(params).__name__}")


PATTERN_KINDS = PatternKinds()
"""Every pattern kind embroact generates."""


def register(kind: PatternKind) -> None:
    """Add a pattern kind to :data:`PATTERN_KINDS` (the README's "Adding a pattern kind").

    Parameters
    ----------
    kind : PatternKind
        Its name must be new; the model's row follows with
        :func:`embroact.predict.kinds.register_model`.

    Examples
    --------
    >>> try:
    ...     register(pattern_kind("cross"))
    ... except ValueError as exc:
    ...     print(exc)
    pattern kind 'cross' is already registered
    """
    PATTERN_KINDS.add(kind)


def pattern_kind(name: object) -> PatternKind:
    """The registered kind called ``name``.

    Parameters
    ----------
    name : str

    Returns
    -------
    PatternKind

    Raises
    ------
    ParameterError
        No kind of that name (the message lists the registered ones).

    Examples
    --------
    >>> pattern_kind("cross").options
    ('adjust',)
    """
    return PATTERN_KINDS[name]


def param_values(params: PatternParams) -> dict[str, float]:
    """The parameters of any kind as ``{key: value}`` (:meth:`PatternKind.values` of its kind).

    Parameters
    ----------
    params : PatternParams

    Returns
    -------
    dict of str to float

    Examples
    --------
    >>> param_values(CrossParams(7.0, 1.4, 45.0))
    {'width_mm': 7.0, 'interval_mm': 1.4, 'angle_deg': 45.0}
    """
    return pattern_kind(params.pattern).values(params)


def params_text(params) -> str:
    """Pattern parameters as ``key=value`` words (5 significant digits).

    Parameters
    ----------
    params : PatternParams
        A pattern's parameters.

    Returns
    -------
    str

    Examples
    --------
    >>> params_text(ZigzagParams(width_mm=7.0, interval_mm=1.0))
    'width_mm=7 interval_mm=1'
    """
    return " ".join(f"{k}={getattr(params, k):.5g}" for k in params.__slots__)


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


def _zigzag_design(x: float, width_mm: float, interval_mm: float) -> ZigzagParams:
    """Zigzag at width ``x`` (the free parameter) and the nominal interval."""
    return ZigzagParams(float(x), interval_mm)


def _cross_design(x: float, width_mm: float, interval_mm: float) -> CrossParams:
    """Cross at angle ``x`` and the calibrated width, the interval closing the pattern exactly."""
    reach = 2.0 * width_mm * math.tan(math.radians(x))
    n = max(1, round(reach / interval_mm))
    return CrossParams(width_mm, reach / n, float(x))


register(PatternKind("zigzag", ZigzagParams, f"{__package__}.zigzag", "width_mm", description=BUILTIN_KINDS["zigzag"],
                     design_params=_zigzag_design))
register(PatternKind("cross", CrossParams, f"{__package__}.cross", "angle_deg", ("adjust",), (ADJUST_METHODS,),
                     Interval.PARALLEL_LEGS, 1.4,
                     description=BUILTIN_KINDS["cross"], design_params=_cross_design))
