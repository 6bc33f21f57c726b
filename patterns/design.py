"""Designs: several actuators on one fabric, as values; dicts in, plans out (no file I/O).

A design holds a tube, machine and operation limits and one or more actuators.
:func:`design_from_dict` validates a plain dict (as read from TOML) strictly;
:func:`build_plan` generates every actuator and joins them into one plan.

Design-file schema (TOML; every table but ``[[actuator]]`` optional, defaults shown)::

    name = "paper-zigzag"            # design name (any unicode), default "design"
    [tube]                           # embroact.patterns.params.Tube
    outer_radius_mm = 1.5            # r_f
    inner_radius_mm = 1.0            # d_f
    g_e_mpa = 0.13                   # G_e, inflation phase
    clearance_mm = 0.3               # needle-to-tube clearance
    end_margin_mm = 30.0             # free tube at each end (connectors)
    [machine]
    format = "dst"                   # dst tbf exp jef u01 xxx pes pec vp3
    hoop_width_mm = 200.0
    hoop_height_mm = 200.0
    min_stitch_mm = 0.3
    max_stitch_mm = 12.1
    speed_spm = 600                  # stitches per minute
    cord_stop = "sequence"           # DST/EXP cord-in stop: "sequence" (one stop code) or "double"
    placement_line = false           # sew a running stitch along each tube axis before its cord-in stop
    placement_stitch_mm = 2.5        # its longest stitch, within [min_stitch_mm, max_stitch_mm]
    origin = "center"                # machine file's start point: "center" (of the design's extent),
                                     # "first-stitch" or [x, y] (mm, plan frame); patterns/origin.py
    [operation]
    max_pressure_kpa = 300.0         # the rules judge every actuator up to this pressure
    max_bend_deg = 180.0
    # target_pressure_kpa = 150.0    # operating point (written by `embroact design`), <= max_pressure_kpa
    # target_bend_deg = 84.5         # the bend wanted there (a target-bend design)
    [[actuator]]                     # one table per actuator, sewn in this order
    name = "A1"                      # required, unique
    pattern = "zigzag"               # required: a registered pattern kind (zigzag, cross, ...)
    width_mm = 7.0                   # required: rail spacing w
    interval_mm = 1.0                # required: stitch interval s
    # angle_deg = 45.0               # cross only (required there): alpha0
    # adjust = "auto"                # cross only: "auto", "interval" or "angle"
    length_mm = 100.0                # one of length_mm or path is required: a straight path ...
    # path = "M 0 0 A 40 40 0 0 1 40 40"  # ... or an SVG path d (M L H V C S Q T A Z;
    #                                      mm, y down as in SVG; flipped to the plan) ...
    # path = [[0, 0], [50, 10], ...] # ... or points (mm, plan frame, y up)
    origin_mm = [0.0, 0.0]           # start of a straight path / offset of a path
    rotation_deg = 0.0               # direction of a straight path / rotation of a path
    tie_stitch_mm = 0.7              # lock stitch length
    tie_count = 3                    # lock stitches at each end
    # [[actuator.segment]]           # a segmented actuator (patterns/segments.py): instead of
    # pattern = "zigzag"             # pattern/width_mm/interval_mm/angle_deg/adjust above, one
    # width_mm = 7.0                 # table per segment in order along the path, each with its
    # interval_mm = 1.0              # own pattern keys and length_mm; the lengths add up to the
    # length_mm = 40.0               # path's (without length_mm/path: a straight path of their sum)
    [actuator.model]                 # optional prediction settings (docs/model.md, calibration policy)
    calibration = "paper-2025"       # a built-in set's name, or a calibration file (relative to this file)
    # g_mpa = 2.7                    # effective shear modulus G (default: from the calibration set)
    # p0_kpa = 85.0                  # transition pressure P0 (default: see p0_source)
    p0_source = "calibration"        # P0 without p0_kpa: "calibration" (the set's fitted P0, the
                                     # pair G and P0 was fitted as) or "geometry" (the tube law at r0)
    tube_law = "paper"               # inflation-phase tube law: "paper" or "thick-wall"

A ``path`` is rotated by ``rotation_deg`` about its own (0, 0) and then moved by
``origin_mm``.

Examples
--------
>>> from embroact.patterns.design import build_plan, default_design, design_from_dict
>>> from embroact.patterns.plan import Command
>>> d = design_from_dict({"name": "two", "actuator": [
...     {"name": "A1", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
...     {"name": "A2", "pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50,
...      "origin_mm": [0, 20]}]})
>>> plan = build_plan(d)
>>> [a.name for a in plan.actuators], int(plan.actuator.max()), plan.count(Command.STOP)
(['A1', 'A2'], 1, 2)
>>> default_design().actuators[0].params
ZigzagParams(width_mm=7.0, interval_mm=1.0)
>>> try:
...     design_from_dict({"actuator": [{"name": "A", "pattern": "zigzag", "widht_mm": 7}]})
... except Exception as exc:
...     print(str(exc).split(";")[0])
actuator[0].widht_mm: unknown key
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

import numpy as np

import enum

from .assemble import MAX_RECORDS
from .base.choices import check_choice
from .base.display import repr_svg
from .base.errors import DesignFileError, EmbroactError, ParameterError, PatternError, check_range
from .base.tolerances import DEFAULT_TOLERANCES
from .base.validate import ACTUATOR_SEGMENTS, DESIGN_ACTUATORS, DESIGN_SEGMENTS, check_name, shown
from .centerline import Centerline, as_centerline
from .chain import UNGIVEN, Chain, strip_pattern
from .kinds import PATTERN_KINDS, KindFields, pattern_kind
from .limits import MAX_STITCH_MM, MIN_STITCH_MM, format_limit, on_grid
from .params import PatternParams, StitchOptions, Tube, ZigzagParams
from .plan import ActuatorPlan, Command, Role, StitchPlan
from .segments import SegmentSpec, chain_records, check_segments, segmented
from .origin import MachineOrigin, check_origin, to_machine_frame
from .placement import placement_records, with_placement
from .stops import cord_stop as _cord_stop

__all__ = [
    "MachineSettings",
    "OperationSettings",
    "ModelSettings",
    "names_calibration_file",
    "ActuatorSpec",
    "Design",
    "design_from_dict",
    "check_design_records",
    "design_to_dict",
    "default_design",
    "generate_actuator",
    "build_plan",
    "join_plans",
    "P0Source",
    "TubeLaw",
]


class P0Source(str, enum.Enum):
    """Where an actuator's transition pressure P0 comes from when no ``p0_kpa`` is given.

    Examples
    --------
    >>> P0Source("geometry"), ModelSettings().p0_source.value
    (<P0Source.GEOMETRY: 'geometry'>, 'calibration')
    """

    CALIBRATION = "calibration"  #: the calibration set's fitted P0 (fitted together with its G)
    GEOMETRY = "geometry"  #: the tube law's pressure at the sleeve radius r0 of the generated stitches


class TubeLaw(str, enum.Enum):
    """Inflation-phase law of the tube (docs/model.md, inflation phase).

    Examples
    --------
    >>> TubeLaw("thick-wall").name, ModelSettings().tube_law.value
    ('THICK_WALL', 'paper')
    """

    PAPER = "paper"  #: the paper's fitted Neo-Hookean law with G_e
    THICK_WALL = "thick-wall"  #: exact thick-walled plane-strain Neo-Hookean tube


@dataclass(frozen=True, slots=True)
class MachineSettings:
    """Machine and fabric limits.

    Parameters
    ----------
    format : str
        Machine-file format (``embroact.patterns.limits.FORMAT_LIMITS``), default ``"dst"``.
    hoop_width_mm, hoop_height_mm : float
        Sewable field [mm], > 0.
    min_stitch_mm, max_stitch_mm : float
        Shortest sensible and longest allowed stitch [mm], 0 <= min < max.
    speed_spm : float
        Sewing speed [stitches/min], >= 1 (time estimates).
    cord_stop : str
        How a stop-code format (DST, EXP) writes a cord-in stop: ``"sequence"`` (one stop
        code; a multi-needle machine in manual mode or with stops programmed in its needle
        sequence) or ``"double"`` (two in a row: stops one in automatic mode too);
        :class:`embroact.patterns.stops.CordStop`.
    placement_line : bool
        Sew a placement line (:mod:`embroact.patterns.placement`) along each actuator's tube
        axis before its cord-in stop, so the operator sees where to lay the tube.
    placement_stitch_mm : float
        Longest running stitch of the placement line [mm]; with ``placement_line`` it must lie
        in [min_stitch_mm, max_stitch_mm].
    origin : str or tuple of float
        The machine file's start point (:mod:`embroact.patterns.origin`): ``"center"`` (the
        centre of the design's extent, default), ``"first-stitch"`` or a point ``(x, y)``
        [mm, plan frame].

    Examples
    --------
    >>> MachineSettings(format="EXP", cord_stop="double").format
    'exp'
    >>> MachineSettings(min_stitch_mm=20.0)
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.ParameterError: min_stitch_mm must be in [0, 12.1), got 20
    """

    format: str = "dst"
    hoop_width_mm: float = 200.0
    hoop_height_mm: float = 200.0
    min_stitch_mm: float = MIN_STITCH_MM
    max_stitch_mm: float = MAX_STITCH_MM
    speed_spm: float = 600.0
    cord_stop: str = "sequence"
    placement_line: bool = False
    placement_stitch_mm: float = 2.5
    origin: str | tuple[float, float] = "center"

    def __post_init__(self) -> None:
        object.__setattr__(self, "origin", check_origin(self.origin))
        if not isinstance(self.format, str):
            raise ParameterError(f"format must be a string, got {self.format!r}")
        object.__setattr__(self, "format", format_limit(self.format).name)
        object.__setattr__(self, "cord_stop", _cord_stop(self.cord_stop).value)
        check_range("hoop_width_mm", self.hoop_width_mm, low=0.0, high=10_000.0)
        check_range("hoop_height_mm", self.hoop_height_mm, low=0.0, high=10_000.0)
        mx = check_range("max_stitch_mm", self.max_stitch_mm, low=0.0, high=1000.0)
        check_range("min_stitch_mm", self.min_stitch_mm, low=0.0, low_inclusive=True, high=mx)
        check_range("speed_spm", self.speed_spm, low=1.0, low_inclusive=True, high=10_000.0)
        if not isinstance(self.placement_line, bool):
            raise ParameterError(f"placement_line must be true or false, got {self.placement_line!r}")
        check_range("placement_stitch_mm", self.placement_stitch_mm, low=0.0, high=1000.0, high_inclusive=True)
        if self.placement_line:
            check_range("placement_stitch_mm", self.placement_stitch_mm, low=self.min_stitch_mm, low_inclusive=True,
                        high=mx, high_inclusive=True)


@dataclass(frozen=True, slots=True)
class OperationSettings:
    """How the actuator will be driven: the limits, and where a designed actuator is meant to work.

    Parameters
    ----------
    max_pressure_kpa : float
        Highest supply pressure [kPa], > 0; the design rules judge the actuator up to it.
    max_bend_deg : float
        Largest bend the application needs [deg], in (0, 720].
    target_pressure_kpa : float or None
        The operating point: the pressure the design was made for [kPa], in (0, max_pressure_kpa]
        (``embroact design`` writes its target pressure here; the bend chart marks it and the
        worksheet names it). None: no operating point.
    target_bend_deg : float or None
        The bend wanted at ``target_pressure_kpa`` [deg], in [-720, 720] (a target-bend design); only with it.

    Examples
    --------
    >>> OperationSettings(max_pressure_kpa=250.0)
    OperationSettings(max_pressure_kpa=250.0, max_bend_deg=180.0, target_pressure_kpa=None, target_bend_deg=None)
    >>> OperationSettings(target_pressure_kpa=150.0, target_bend_deg=84.5).max_pressure_kpa
    300.0
    """

    max_pressure_kpa: float = 300.0
    max_bend_deg: float = 180.0
    target_pressure_kpa: float | None = None
    target_bend_deg: float | None = None

    def __post_init__(self) -> None:
        check_range("max_pressure_kpa", self.max_pressure_kpa, low=0.0, high=100_000.0)
        check_range("max_bend_deg", self.max_bend_deg, low=0.0, high=720.0, high_inclusive=True)
        if self.target_pressure_kpa is not None:
            check_range("target_pressure_kpa", self.target_pressure_kpa, low=0.0, high=self.max_pressure_kpa,
                        high_inclusive=True)
        if self.target_bend_deg is not None:
            if self.target_pressure_kpa is None:
                raise ParameterError(f"target_bend_deg {self.target_bend_deg!r} needs target_pressure_kpa (the "
                                     "pressure of the operating point)")
            check_range("target_bend_deg", self.target_bend_deg, low=-720.0, high=720.0, low_inclusive=True,
                        high_inclusive=True)


def names_calibration_file(value: str) -> bool:
    """True when a calibration setting names a file (``.toml`` or a path) rather than a set.

    Parameters
    ----------
    value : str
        A ``calibration`` setting.

    Returns
    -------
    bool

    Examples
    --------
    >>> names_calibration_file("paper-2025"), names_calibration_file("lab.toml"), names_calibration_file("cal/lab")
    (False, True, True)
    """
    return value.endswith(".toml") or "/" in value or "\\" in value


@dataclass(frozen=True, slots=True)
class ModelSettings:
    """Prediction settings of one actuator.

    Parameters
    ----------
    g_mpa : float or None
        Effective shear modulus G [MPa], > 0; None: from the calibration set.
    p0_kpa : float or None
        Transition pressure P0 [kPa], >= 0; None: as ``p0_source`` says.
    calibration : str
        Name of the calibration set (``embroact.predict.calibration``; a design file may
        name a calibration file instead, which the loader reads and replaces by its set's name).
    p0_source : P0Source or str
        Without ``p0_kpa``: ``"calibration"`` (default; the set's P0, fitted together with its G)
        or ``"geometry"`` (the tube law's pressure at the realised sleeve radius r0).
    tube_law : TubeLaw or str
        ``"paper"`` (default) or ``"thick-wall"``.

    Examples
    --------
    >>> m = ModelSettings(g_mpa=2.0, p0_source="geometry")
    >>> m.p0_source is P0Source.GEOMETRY, m.tube_law.value
    (True, 'paper')
    """

    g_mpa: float | None = None
    p0_kpa: float | None = None
    calibration: str = "paper-2025"
    p0_source: P0Source = P0Source.CALIBRATION
    tube_law: TubeLaw = TubeLaw.PAPER

    def __post_init__(self) -> None:
        if self.g_mpa is not None:
            check_range("g_mpa", self.g_mpa, low=0.0, high=1e5)
        if self.p0_kpa is not None:
            check_range("p0_kpa", self.p0_kpa, low=0.0, low_inclusive=True, high=1e5)
        if not isinstance(self.calibration, str) or not self.calibration:
            raise ParameterError(f"calibration must be a non-empty name, got {self.calibration!r}")
        object.__setattr__(self, "p0_source", check_choice("p0_source", self.p0_source, P0Source))
        object.__setattr__(self, "tube_law", check_choice("tube_law", self.tube_law, TubeLaw))


@dataclass(frozen=True, slots=True)
class ActuatorSpec(KindFields):
    """One actuator as the user asked for it.

    Parameters
    ----------
    name : str
        Unique within the design (any unicode).
    params : PatternParams
    centerline : Centerline
        Tube path in the plan frame [mm].
    options : StitchOptions
    model : ModelSettings
    adjust : str
        Cross only: which of interval/angle may change to make the pattern close
        (``"auto"``, ``"interval"``, ``"angle"``; see :mod:`embroact.patterns.cross`); the first
        segment's when ``segments`` are given.
    segments : Chain of SegmentSpec
        The actuator's chain (:mod:`embroact.patterns.segments`): its segments in order along
        the path, lengths adding up to the path's; ``params`` must be the first segment's
        (:meth:`segmented` sets it). Given none (default): a chain of one, ``params`` (and
        ``adjust``) over the whole path.

    Examples
    --------
    >>> a = ActuatorSpec("A1", ZigzagParams(width_mm=7.0, interval_mm=1.0), Centerline.straight(100.0))
    >>> a.pattern, a.centerline.length_mm, a.model.calibration
    ('zigzag', 100.0, 'paper-2025')
    >>> a.segments
    (SegmentSpec(params=ZigzagParams(width_mm=7.0, interval_mm=1.0), length_mm=100.0, adjust='auto'),)
    """

    name: str
    params: PatternParams
    centerline: Centerline
    options: StitchOptions = field(default_factory=StitchOptions)
    model: ModelSettings = field(default_factory=ModelSettings)
    adjust: str = "auto"
    segments: Chain = UNGIVEN

    def __post_init__(self) -> None:
        check_name("name", self.name)
        PATTERN_KINDS.for_params(self.params)
        object.__setattr__(self, "centerline", as_centerline(self.centerline))
        segs = Chain.given_or_one(self.segments, lambda: SegmentSpec(self.params, self.centerline.length_mm,
                                                                     self.adjust))
        check_segments(self.centerline, segs)
        if self.params != segs[0].params:
            raise ParameterError("params must be the first segment's parameters for a segmented actuator")
        object.__setattr__(self, "segments", segs)
        object.__setattr__(self, "adjust", segs[0].adjust)  # the first segment's too (a chain of one: its own)

    @property
    def pattern(self) -> str:
        """The chain's pattern: its segments' kinds in chain order (:func:`~embroact.patterns.chain.strip_pattern`;
        a chain of one: its kind)."""
        return strip_pattern(seg.pattern for seg in self.segments)

    @classmethod
    def segmented(cls, name: str, segments, centerline=None, **kwargs) -> "ActuatorSpec":
        """A segmented actuator; ``centerline`` defaults to a straight path of the segments' total length.

        Parameters
        ----------
        name : str
        segments : sequence of SegmentSpec
            At least one, in order from the path's start; lengths add up to the path's.
        centerline : Centerline, optional
            The tube path (anything :func:`~embroact.patterns.centerline.as_centerline` takes).
        **kwargs
            The other :class:`ActuatorSpec` fields (``options``, ``model``, ``adjust``).

        Returns
        -------
        ActuatorSpec
            ``params`` is the first segment's.

        Examples
        --------
        >>> from embroact.patterns.segments import SegmentSpec
        >>> a = ActuatorSpec.segmented("S", [SegmentSpec(ZigzagParams(7.0, 1.0), 30.0),
        ...                                  SegmentSpec(ZigzagParams(9.0, 1.0), 50.0)])
        >>> a.centerline.length_mm, a.pattern, len(a.segments)
        (80.0, 'zigzag', 2)
        """
        segs = tuple(segments)
        if not segs:
            raise ParameterError("segments must hold at least one SegmentSpec, got none")
        if centerline is None:
            centerline = Centerline.straight(sum(seg.length_mm for seg in segs))
        return cls(name, segs[0].params, centerline, segments=Chain(segs), **kwargs)


@dataclass(frozen=True, slots=True)
class Design:
    """A fabric with one or more actuators, sewn in order.

    Parameters
    ----------
    name : str
    tube : Tube
    machine : MachineSettings
    operation : OperationSettings
    actuators : tuple of ActuatorSpec
        At least one; names unique.
    calibration_sets : tuple
        Calibration sets read from the files the actuators' ``calibration`` settings name
        (:func:`embroact.export.files.designfile.load_design` reads them, relative to the
        design file); :func:`embroact.predict.analysis.analyse` searches them. Not part of the
        design's value (equality, the design file).
    source_files : tuple of (str, str)
        (what, path) of every file the design file names and its loader read: each SVG
        drawing an actuator's ``path`` names and each calibration file
        (:func:`~embroact.export.files.designfile.load_design`); what no output of a run may
        replace. Not part of the design's value either.

    Examples
    --------
    >>> d = default_design()
    >>> d.name, [a.name for a in d.actuators], d.tube.outer_radius_mm
    ('paper-zigzag', ['A1'], 1.5)
    >>> Design("two", Tube(), MachineSettings(), OperationSettings(), d.actuators * 2)
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.ParameterError: actuator names must be unique, got 'A1' 2 times
    """

    name: str
    tube: Tube
    machine: MachineSettings
    operation: OperationSettings
    actuators: tuple[ActuatorSpec, ...]
    calibration_sets: tuple = field(default=(), compare=False, repr=False)
    source_files: tuple = field(default=(), compare=False, repr=False)

    def __post_init__(self) -> None:
        check_name("name", self.name)
        object.__setattr__(self, "calibration_sets", tuple(self.calibration_sets))
        object.__setattr__(self, "actuators", tuple(self.actuators))
        if not self.actuators:
            raise ParameterError("actuators must hold at least one actuator, got none")
        if len(self.actuators) > DESIGN_ACTUATORS:
            raise ParameterError(f"a design must have at most {DESIGN_ACTUATORS:,} actuators, got {len(self.actuators):,}")
        _check_total_segments(sum(len(a.segments) for a in self.actuators), "a design")
        names = [a.name for a in self.actuators]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise ParameterError(f"actuator names must be unique, got {dup[0]!r} {names.count(dup[0])} times")

    #: Stitch preview in Jupyter (generated when shown; registered by ``embroact``).
    _repr_svg_ = repr_svg


def default_design() -> Design:
    """The paper's zigzag actuator: w = 7 mm, s = 1.0 mm, l0 = 100 mm, default tube.

    Returns
    -------
    Design
        Named ``"paper-zigzag"``, one actuator ``"A1"``.

    Examples
    --------
    >>> default_design().actuators[0].params
    ZigzagParams(width_mm=7.0, interval_mm=1.0)
    """
    return Design(
        name="paper-zigzag",
        tube=Tube(),
        machine=MachineSettings(),
        operation=OperationSettings(),
        actuators=(ActuatorSpec("A1", ZigzagParams(width_mm=7.0, interval_mm=1.0), Centerline.straight(100.0)),),
    )


# ---------------------------------------------------------------------- dict -> Design
_ACTUATOR_KEYS = (
    "name", "pattern", "width_mm", "interval_mm", "angle_deg", "adjust", "length_mm", "path",
    "origin_mm", "rotation_deg", "tie_stitch_mm", "tie_count", "model", "segment",
)  # fmt: skip
#: keys of one [[actuator.segment]] table (the pattern keys of its kind, and its length)
_SEGMENT_KEYS = ("pattern", "width_mm", "interval_mm", "angle_deg", "adjust", "length_mm")
#: keys that belong to some pattern kinds only
_KIND_KEYS = {k for kind in PATTERN_KINDS for k in (*kind.param_keys, *kind.options)} - {"width_mm", "interval_mm"}
_MODEL_CHOICES = {"p0_source": P0Source, "tube_law": TubeLaw}


def _names(cls) -> tuple[str, ...]:
    return tuple(f.name for f in fields(cls))


def _where(path: str, key: str) -> str:
    return f"{path}.{key}" if path else key


def _table(value, path: str, allowed: tuple[str, ...], required: tuple[str, ...] = ()) -> dict:
    if not isinstance(value, dict):
        raise DesignFileError(f"{path or 'design'}: must be a table, got {type(value).__name__}")
    for key in value:
        if key not in allowed:
            raise DesignFileError(f"{_where(path, key)}: unknown key; allowed: {', '.join(allowed)}")
    for key in required:
        if key not in value:
            raise DesignFileError(f"{_where(path, key)}: missing key")
    return value


def _number(value, where: str) -> float | int:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise DesignFileError(f"{where}: must be a number, got {shown(value)}")
    try:
        finite = math.isfinite(value)
    except OverflowError:  # a TOML integer too large for a float (10**320)
        raise DesignFileError(f"{where}: must be a finite number, got an integer of {len(str(abs(value)))} digits") from None
    if not finite:
        raise DesignFileError(f"{where}: must be a finite number, got {value!r}")
    return value


def _flag(value, where: str) -> bool:
    if not isinstance(value, bool):
        raise DesignFileError(f"{where}: must be true or false, got {value!r}")
    return value


def _string(value, where: str) -> str:
    if not isinstance(value, str):
        raise DesignFileError(f"{where}: must be a string, got {value!r}")
    return value


def _pair(value, where: str) -> tuple[float, float]:
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        raise DesignFileError(f"{where}: must be a pair [x, y] of numbers in mm, got {value!r}")
    return (_number(value[0], f"{where}[0]"), _number(value[1], f"{where}[1]"))


def _points(values: list, where: str):
    """A path's ``[x, y]`` points as an (n, 2) array; a bad one named as :func:`_pair` names it (checked point
    by point only then: a long path's points are read in one pass)."""
    number = (int, float)  # not bool
    if all(type(v) in (list, tuple) and len(v) == 2 and type(v[0]) in number and type(v[1]) in number
           for v in values):
        try:
            xy = np.array(values, dtype=np.float64).reshape(-1, 2)
        except OverflowError:  # an integer too large for a float: named below
            xy = None
        if xy is not None and np.isfinite(xy).all():
            return xy
    return [_pair(v, f"{where}[{i}]") for i, v in enumerate(values)]


def _build(path: str, cls, kwargs: dict):
    """Construct a value, turning its ParameterError into a DesignFileError with the key path."""
    try:
        return cls(**kwargs)
    except EmbroactError as exc:
        raise DesignFileError(f"{path}: {exc}") from None


def _numbers_table(value, path: str, cls, strings: tuple[str, ...] = (), optional: tuple[str, ...] = (),
                   flags: tuple[str, ...] = (), as_given: tuple[str, ...] = ()):
    keys = _names(cls)
    table = _table(value, path, keys)
    kwargs: dict[str, object] = {}
    for key, v in table.items():
        where = _where(path, key)
        if key in as_given:  # checked by cls itself
            kwargs[key] = v
        elif key in strings:
            kwargs[key] = _string(v, where)
        elif key in flags:
            kwargs[key] = _flag(v, where)
        elif not (key in optional and v is None):
            kwargs[key] = _number(v, where)
    return _build(path, cls, kwargs)


def _centerline(a: dict, path: str) -> Centerline:
    has_len, has_path = "length_mm" in a, "path" in a
    if has_len == has_path:
        what = "both" if has_len else "neither"
        raise DesignFileError(f"{path}: give exactly one of length_mm (straight) or path, got {what}")
    origin = _pair(a.get("origin_mm", (0.0, 0.0)), f"{path}.origin_mm")
    rotation = _number(a.get("rotation_deg", 0.0), f"{path}.rotation_deg")
    if has_len:
        length = _number(a["length_mm"], f"{path}.length_mm")
        return _build(path, Centerline.straight, {"length_mm": length, "origin_mm": origin, "rotation_deg": rotation})
    raw = a["path"]
    if not isinstance(raw, (str, list)):
        raise DesignFileError(f"{path}.path: must be an SVG path string or a list of [x, y] points, got {raw!r}")
    if isinstance(raw, list):
        raw = _points(raw, f"{path}.path")
    try:
        return as_centerline(raw).transformed(origin_mm=origin, rotation_deg=rotation)
    except EmbroactError as exc:
        raise DesignFileError(f"{path}.path: {exc}") from None


def _pattern_params(a: dict, path: str, allowed: tuple[str, ...]):
    """The pattern parameters and the ``adjust`` option of one actuator or segment table."""
    pattern = _string(a["pattern"], f"{path}.pattern")
    if pattern not in PATTERN_KINDS.names():
        valid = ", ".join(map(repr, PATTERN_KINDS.names()))
        raise DesignFileError(f"{path}.pattern: must be one of {valid}, got {pattern!r}")
    kind = pattern_kind(pattern)
    own = set(kind.param_keys) | set(kind.options)
    for key in _KIND_KEYS - own:
        if key in a:
            takers = " or ".join(repr(k.name) for k in PATTERN_KINDS if key in (*k.param_keys, *k.options))
            raise DesignFileError(f"{path}.{key}: only allowed with pattern {takers}, got pattern {pattern!r}")
    _table(a, path, allowed, kind.param_keys)
    params = _build(path, kind.params, {k: _number(a[k], f"{path}.{k}") for k in kind.param_keys})
    return params, _string(a.get("adjust", "auto"), f"{path}.adjust")


def _check_total_segments(n: int, what: str) -> None:
    """Refuse more than :data:`DESIGN_SEGMENTS` segment tables in one design (checking costs ~10 ms each)."""
    if n > DESIGN_SEGMENTS:
        raise ParameterError(f"{what} must have at most {DESIGN_SEGMENTS:,} segments in all its actuators, got {n:,}")


def _segments(value, path: str) -> tuple[SegmentSpec, ...]:
    if not isinstance(value, list) or not value:
        raise DesignFileError(f"{path}: must be a non-empty list of tables ([[actuator.segment]]), got {value!r:.60}")
    if len(value) > ACTUATOR_SEGMENTS:
        raise DesignFileError(f"{path}: an actuator must have at most {ACTUATOR_SEGMENTS:,} segments, got {len(value):,}")
    out = []
    for k, table in enumerate(value):
        where = f"{path}[{k}]"
        t = _table(table, where, _SEGMENT_KEYS, ("pattern", "width_mm", "interval_mm", "length_mm"))
        params, adjust = _pattern_params(t, where, _SEGMENT_KEYS)
        out.append(_build(where, SegmentSpec, {"params": params, "adjust": adjust,
                                               "length_mm": _number(t["length_mm"], f"{where}.length_mm")}))
    return tuple(out)


def _actuator(value, i: int) -> ActuatorSpec:
    path = f"actuator[{i}]"
    if isinstance(value, dict) and "segment" in value:
        return _segmented_actuator(value, path)
    a = _table(value, path, _ACTUATOR_KEYS, ("name", "pattern", "width_mm", "interval_mm"))
    params, adjust = _pattern_params(a, path, _ACTUATOR_KEYS)
    return _build(path, ActuatorSpec, dict(name=_string(a["name"], f"{path}.name"), params=params,
                                           centerline=_centerline(a, path), adjust=adjust, **_extras(a, path)))


def _segmented_actuator(a: dict, path: str) -> ActuatorSpec:
    for key in _SEGMENT_KEYS[:-1]:
        if key in a:
            raise DesignFileError(f"{path}.{key}: a segmented actuator sets {key} per [[actuator.segment]]")
    _table(a, path, _ACTUATOR_KEYS, ("name",))
    segs = _segments(a["segment"], f"{path}.segment")
    if "length_mm" not in a and "path" not in a:
        a = {**a, "length_mm": sum(seg.length_mm for seg in segs)}
    return _build(path, ActuatorSpec, dict(name=_string(a["name"], f"{path}.name"), params=segs[0].params,
                                           centerline=_centerline(a, path), segments=segs, **_extras(a, path)))


def _extras(a: dict, path: str) -> dict:
    """Lock-stitch options and model settings of an actuator table."""
    opts = {k: a[k] for k in ("tie_stitch_mm", "tie_count") if k in a}
    options = _build(path, StitchOptions, {k: _number(v, f"{path}.{k}") for k, v in opts.items()})
    model = _numbers_table(a.get("model", {}), f"{path}.model", ModelSettings, ("calibration", *_MODEL_CHOICES),
                           ("g_mpa", "p0_kpa"))
    return {"options": options, "model": model}


def design_from_dict(d) -> Design:
    """Validate a plain dict (parsed TOML) into a :class:`Design`.

    Parameters
    ----------
    d : mapping
        The design file's tables: ``name``, ``tube``, ``machine``, ``operation`` and the
        ``actuator`` list (schema in the module docstring).

    Returns
    -------
    Design

    Raises
    ------
    DesignFileError
        One line starting with the key path (``actuator[1].widht_mm: unknown key; allowed: ...``).

    Examples
    --------
    >>> d = design_from_dict({"name": "c", "actuator": [{"name": "C1", "pattern": "cross", "width_mm": 7.0,
    ...                       "interval_mm": 1.4, "angle_deg": 45.0, "length_mm": 100}]})
    >>> d.actuators[0].params
    CrossParams(width_mm=7.0, interval_mm=1.4, angle_deg=45.0)
    """
    top = _table(d, "", ("name", "tube", "machine", "operation", "actuator"), ("actuator",))
    acts = top["actuator"]
    if not isinstance(acts, list) or not acts:
        raise DesignFileError(f"actuator: must be a non-empty list of tables ([[actuator]]), got {acts!r:.60}")
    if len(acts) > DESIGN_ACTUATORS:
        raise DesignFileError(f"actuator: a design must have at most {DESIGN_ACTUATORS:,} actuators, got {len(acts):,}")
    try:  # before any actuator is read: 20 actuators of 200 segments took a minute to check
        _check_total_segments(sum(len(a["segment"]) if isinstance(a, dict) and isinstance(a.get("segment"), list)
                                  else 1 for a in acts), "actuator: a design")
    except ParameterError as exc:
        raise DesignFileError(str(exc)) from None
    specs = tuple(_actuator(a, i) for i, a in enumerate(acts))
    seen: dict[str, int] = {}
    for i, spec in enumerate(specs):
        if spec.name in seen:
            raise DesignFileError(f"actuator[{i}].name: duplicate actuator name {spec.name!r} (also actuator[{seen[spec.name]}])")
        seen[spec.name] = i
    return Design(
        name=_build("name", check_name, {"name": "name", "value": _string(top.get("name", "design"), "name")}),
        tube=_numbers_table(top.get("tube", {}), "tube", Tube),
        machine=_numbers_table(top.get("machine", {}), "machine", MachineSettings, ("format", "cord_stop"),
                                flags=("placement_line",), as_given=("origin",)),
        operation=_numbers_table(top.get("operation", {}), "operation", OperationSettings),
        actuators=specs,
    )


def _plain(value) -> dict:
    return {f.name: getattr(value, f.name) for f in fields(value)}


def design_to_dict(design: Design) -> dict:
    """Plain dict (TOML/JSON-ready) that :func:`design_from_dict` turns back into ``design``.

    Paths are written as point lists in the plan frame; ``None`` model values are left out.

    Parameters
    ----------
    design : Design

    Returns
    -------
    dict

    Examples
    --------
    >>> d = design_to_dict(default_design())
    >>> d["actuator"][0]["path"], design_from_dict(d) == default_design()
    ([[0.0, 0.0], [100.0, 0.0]], True)
    """
    acts = []
    for a in design.actuators:
        tables = [{"pattern": seg.pattern, **_plain(seg.params), **seg.kind_options, "length_mm": seg.length_mm}
                  for seg in a.segments]  # a chain of one: its segment's keys in the actuator's table, as written
        d: dict[str, object] = {"name": a.name, **a.segments.one_or_all(
            lambda: {k: v for k, v in tables[0].items() if k != "length_mm"}, lambda: {"segment": tables})}
        d["path"] = a.centerline.points_mm.tolist()
        d.update(_plain(a.options))
        d["model"] = {k: v.value if isinstance(v, enum.Enum) else v for k, v in _plain(a.model).items() if v is not None}
        acts.append(d)
    return {
        "name": design.name,
        "tube": _plain(design.tube),
        "machine": _plain(design.machine),
        "operation": {k: v for k, v in _plain(design.operation).items() if v is not None},
        "actuator": acts,
    }


# ---------------------------------------------------------------------- plans
def generate_actuator(spec: ActuatorSpec, tube: Tube = Tube()) -> StitchPlan:
    """One actuator's complete plan; errors are prefixed with the actuator's name.

    Parameters
    ----------
    spec : ActuatorSpec
        The actuator as the design asks for it.
    tube : Tube, optional
        The design's tube.

    Returns
    -------
    StitchPlan
        One actuator's plan.

    Examples
    --------
    >>> d = default_design()
    >>> plan = generate_actuator(d.actuators[0], d.tube)
    >>> plan.actuators[0].name, plan.stitch_count
    ('A1', 106)
    """
    try:
        return segmented(spec.centerline, spec.segments, tube=tube, options=spec.options, name=spec.name)
    except EmbroactError as exc:
        raise type(exc)(f"actuator {spec.name!r}: {exc}") from None


def _jumps(a: np.ndarray, b: np.ndarray, max_jump_mm: float) -> np.ndarray:
    """Points from ``a`` (excluded) to ``b`` (included), per-axis steps <= max_jump_mm - grid."""
    step = max_jump_mm - DEFAULT_TOLERANCES.machine_grid_mm
    n = max(1, math.ceil(float(np.max(np.abs(b - a))) / step))
    return on_grid(a + (b - a) * (np.arange(1, n + 1) / n)[:, None])


def join_plans(plans, *, name: str = "embroact", max_jump_mm: float = MAX_STITCH_MM) -> StitchPlan:
    """Concatenate complete plans into one, in order.

    Each plan's END is dropped; JUMP records (role TRAVEL, owned by the next actuator) lead
    from one plan's last point to the next plan's first, each step at most
    ``max_jump_mm - machine_grid_mm`` per axis (room for rounding to the machine grid);
    actuator indices are renumbered; one END closes the result.

    Parameters
    ----------
    plans : iterable of StitchPlan
        Complete plans, at least one.
    name : str, optional
        The joined plan's name.
    max_jump_mm : float, optional
        Longest jump per axis [mm].

    Returns
    -------
    StitchPlan

    Examples
    --------
    >>> d = default_design()
    >>> one = generate_actuator(d.actuators[0], d.tube)
    >>> both = join_plans([one, one])  # the second sewn over the first: 100 mm of travel back
    >>> len(both.actuators), both.stitch_count, int((both.commands == Command.JUMP).sum())
    (2, 212, 9)
    """
    plans = list(plans)
    if not plans:
        raise ParameterError("plans must hold at least one plan, got none")
    limit = check_range("max_jump_mm", max_jump_mm, low=2.0 * DEFAULT_TOLERANCES.machine_grid_mm)
    xy: list[np.ndarray] = []
    cmd: list[np.ndarray] = []
    role: list[np.ndarray] = []
    owner: list[np.ndarray] = []
    acts: list[ActuatorPlan] = []
    for p in plans:
        keep = p.commands != Command.END
        index = np.where(p.actuator[keep] >= 0, p.actuator[keep] + len(acts), -1)
        if xy and len(p.xy_mm[keep]):
            hop = _jumps(xy[-1][-1], p.xy_mm[keep][0], limit)
            xy.append(hop)
            cmd.append(np.full(len(hop), Command.JUMP))
            role.append(np.full(len(hop), Role.TRAVEL))
            owner.append(np.full(len(hop), index[0]))
        xy.append(p.xy_mm[keep])
        cmd.append(p.commands[keep])
        role.append(p.roles[keep])
        owner.append(index)
        acts.extend(p.actuators)
    last = xy[-1][-1:] if len(xy[-1]) else np.zeros((1, 2))
    return StitchPlan(
        np.vstack(xy + [last]),
        np.concatenate(cmd + [[Command.END]]),
        np.concatenate(role + [[Role.CONTROL]]),
        np.concatenate(owner + [[-1]]),
        tuple(acts),
        name,
    )


def _records(spec: ActuatorSpec, tube: Tube) -> int:
    """Records the actuator will need, from its parameters alone (refuses one above the cap).

    The generator's own input checks run first, so a degenerate interval or width is reported
    as such (not as an overflowing count).
    """
    try:
        return chain_records(spec.centerline, spec.segments, tube, spec.options)
    except EmbroactError as exc:
        raise type(exc)(f"actuator {spec.name!r}: {exc}") from None


def _half_width_mm(spec: ActuatorSpec) -> float:
    """Half the widest segment's width [mm]: how far its needle points can lie from the path."""
    return max(seg.params.width_mm for seg in spec.segments) / 2.0


def _placement_records(design: Design) -> int:
    """Records the placement lines will add (none unless ``machine.placement_line``)."""
    m = design.machine
    if not m.placement_line:
        return 0
    return sum(placement_records(spec.centerline.length_mm, m.placement_stitch_mm, spec.options.tie_count,
                                 _half_width_mm(spec)) for spec in design.actuators)


def _travel_records(design: Design) -> int:
    """Jump records the travel moves will need (from the machine's start point to the first
    actuator and between consecutive ones), from the paths alone: an upper bound that
    widens each path end by the pattern's half width (where the first and last needle
    points can lie; a placement line starts at the path's end), split as :func:`_jumps` splits them."""
    step = design.machine.max_stitch_mm - DEFAULT_TOLERANCES.machine_grid_mm
    ends = [_start_estimate(design)]
    total = 0
    for spec in design.actuators:
        pts = spec.centerline.points_mm
        half = _half_width_mm(spec)
        last, reach = ends[-1]
        first = pts[-1] if design.machine.placement_line else pts[0]
        total += max(1, math.ceil((float(np.max(np.abs(first - last))) + reach + half) / step))
        ends.append((pts[-1], half))
    return total


def _start_estimate(design: Design) -> tuple[np.ndarray, float]:
    """The machine's start point before generating, and how far the real one can lie from it [mm]."""
    origin = design.machine.origin
    half = max(_half_width_mm(spec) for spec in design.actuators)
    if origin == MachineOrigin.CENTER.value:  # the records' box is the paths' box widened by at most a half width
        pts = np.vstack([spec.centerline.points_mm for spec in design.actuators])
        return (pts.min(axis=0) + pts.max(axis=0)) / 2.0, half
    if origin == MachineOrigin.FIRST_STITCH.value:
        return design.actuators[0].centerline.points_mm[0], half
    return np.asarray(origin, dtype=np.float64), 0.0


def check_design_records(design: Design) -> None:
    """PatternError when ``design`` would need more than :data:`~embroact.patterns.assemble.MAX_RECORDS`
    records, travel jumps between actuators included; counted from the parameters, nothing generated.

    Parameters
    ----------
    design : Design
        The design.

    Raises
    ------
    PatternError
        Too many records; the message says how many and what to change.

    Examples
    --------
    >>> check_design_records(default_design()) is None
    True
    """
    stitched = sum(_records(spec, design.tube) for spec in design.actuators) + _placement_records(design)
    travel = _travel_records(design)
    if stitched + travel > MAX_RECORDS:
        raise PatternError(
            f"design would need about {stitched + travel:.3g} records ({travel:.3g} of them travel jumps between "
            f"actuators) over {len(design.actuators)} actuators, more than the limit {MAX_RECORDS:,}; use larger "
            "interval_mm values, shorter paths, fewer actuators or actuators closer together"
        )


def build_plan(design: Design) -> StitchPlan:
    """Generate every actuator of ``design`` and join them (see :func:`join_plans`); with
    ``machine.placement_line`` each actuator's placement line comes before its cord-in stop.

    Every record the machine will read is counted before anything is generated, the
    travel jumps between actuators included: a design above
    :data:`~embroact.patterns.assemble.MAX_RECORDS` is refused without allocating.

    Parameters
    ----------
    design : Design

    Returns
    -------
    StitchPlan
        Every actuator in order, travel jumps between them, one END; in the machine frame:
        moved so that ``machine.origin`` (:mod:`embroact.patterns.origin`) is (0, 0).

    Raises
    ------
    PatternError
        Too many records, or an actuator its generator refuses (the message names it).

    Examples
    --------
    >>> plan = build_plan(default_design())
    >>> [a.name for a in plan.actuators], plan.stitch_count
    (['A1'], 106)
    """
    check_design_records(design)
    plans = [generate_actuator(spec, design.tube) for spec in design.actuators]
    if design.machine.placement_line:
        plans = [with_placement(p, design.machine.placement_stitch_mm) for p in plans]
    joined = join_plans(plans, name=design.name, max_jump_mm=design.machine.max_stitch_mm)
    return to_machine_frame(joined, design.machine.origin)
