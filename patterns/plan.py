"""The immutable stitch plan: needle points in sewing order, with what each one is.

Frame: millimetres, x to the right, **y up** (the machine frame of DST). The
pystitch frame (0.1 mm, y down) is the export layer's business.

Examples
--------
>>> import numpy as np
>>> from embroact.patterns.plan import Command, Role, StitchPlan
>>> plan = StitchPlan.from_records(
...     [(0.0, 0.0, Command.STITCH, Role.TIE_IN), (0.0, 3.5, Command.STITCH, Role.LEG),
...      (0.0, 3.5, Command.END, Role.CONTROL)], actuators=(), name="demo")
>>> len(plan), plan.stitch_count
(3, 2)
>>> plan.xy_mm.flags.writeable
False
"""
from __future__ import annotations

from dataclasses import dataclass, field
from enum import IntEnum
from typing import TYPE_CHECKING, Iterable

import numpy as np

from .base.arrays import frozen_array
from .base.display import repr_svg
from .chain import UNGIVEN, Chain, strip_pattern
from .kinds import KindOf
from .params import PatternParams, StitchOptions, Tube

if TYPE_CHECKING:  # pragma: no cover
    from .centerline import Centerline

__all__ = ["Command", "Role", "Realised", "SegmentPlan", "ActuatorPlan", "StitchPlan"]


class Command(IntEnum):
    """What the machine does at a record.

    Examples
    --------
    >>> Command.TRIM, int(Command.STOP)
    (<Command.TRIM: 2>, 3)
    """

    STITCH = 0
    JUMP = 1
    TRIM = 2
    STOP = 3
    END = 4


class Role(IntEnum):
    """What a record is for in the actuator.

    Examples
    --------
    >>> Role(1).name
    'LEG'
    """

    TIE_IN = 0
    LEG = 1
    EDGE = 2
    TIE_OFF = 3
    TRAVEL = 4
    CONTROL = 5
    PLACEMENT = 6
    """A placement-line stitch along the tube axis, sewn before the tube is laid
    (:mod:`embroact.patterns.placement`): no tube there yet to pierce or to hold."""


@dataclass(frozen=True, slots=True)
class Realised:
    """Pattern parameters measured on the generated stitches.

    Attributes
    ----------
    width_mm : float
        Mean rail spacing of the needle points [mm].
    interval_mm : float
        Mean spacing of neighbouring needle points / parallel legs along the path [mm].
    angle_deg : float
        Mean leg angle from the local perpendicular [deg] (zigzag: its small lean).
    length_mm : float
        Embroidered length along the centerline, first to last leg [mm].
    passes : int
        Number of passes over the path (1 for zigzag).
    start_mm : float
        Arc length along the centerline where the legs start (the first leg's nearer end) [mm].

    Examples
    --------
    >>> from embroact.patterns.zigzag import zigzag
    >>> from embroact.patterns.params import ZigzagParams
    >>> act = zigzag([[0.0, 0.0], [20.0, 0.0]], ZigzagParams(7.0, 1.0), name="A1").actuators[0]
    >>> r = act.realised
    >>> r.width_mm, r.interval_mm, round(r.angle_deg, 4), r.length_mm, r.passes
    (7.0, 1.0, 8.1301, 20.0, 1)
    """

    width_mm: float
    interval_mm: float
    angle_deg: float
    length_mm: float
    passes: int = 1
    start_mm: float = 0.0


@dataclass(frozen=True, slots=True)
class SegmentPlan(KindOf):
    """One generated segment of an actuator's chain (a single-pattern actuator: one over its whole path).

    Attributes
    ----------
    params : PatternParams
        The request.
    start_mm, length_mm : float
        Where the segment's share of the path starts and how long it is [mm].
    realised : Realised
        Measured on the segment's needle points (``length_mm`` there: first to last leg).
    first_leg_mm : float
        Arc length where the segment's legs start [mm] (``realised.start_mm``); they end at
        ``first_leg_mm + realised.length_mm`` (the part of the path that bends).
    transition_mm : float
        Path length from the end of this segment's legs to the start of the next
        segment's [mm] (bends by zero); 0 for the last segment.
    join_run_mm : float
        Path length the thread runs along a rail from this segment's last needle point to
        the next segment's first [mm]; 0 for the last segment.
    adjustments : tuple of str
        What the generator changed (cross closing).
    mirrored : bool
        True when the segment starts on the right rail (:mod:`embroact.patterns.segments`).

    Examples
    --------
    >>> from embroact.patterns.params import ZigzagParams
    >>> seg = SegmentPlan(ZigzagParams(7.0, 1.0), 0.0, 100.0, Realised(7.0, 1.0, 8.13, 100.0), 0.0, 0.0)
    >>> seg.pattern, seg.length_mm, seg.first_leg_mm
    ('zigzag', 100.0, 0.0)
    """

    params: PatternParams
    start_mm: float
    length_mm: float
    realised: Realised
    transition_mm: float
    join_run_mm: float
    adjustments: tuple[str, ...] = ()
    mirrored: bool = False

    @property
    def first_leg_mm(self) -> float:
        """Arc length where the segment's legs start [mm]: the realised ``start_mm``."""
        return self.realised.start_mm


@dataclass(frozen=True, slots=True)
class ActuatorPlan(KindOf):
    """One actuator's share of a plan: what was asked, what was built, on which path.

    Attributes
    ----------
    name : str
        Actuator name (thread list / colour table entry).
    params : PatternParams
        What a chain of one is made of when no ``segments`` are given (the single-pattern
        generators' plan); equal to ``segments[0].params``. Read each segment's from ``segments``.
    tube : Tube
        The tube it is sewn over.
    centerline : Centerline
        The tube path, mm, plan frame.
    realised : Realised
        Likewise, measured on the generated stitches: ``segments[0].realised``. The whole strip's
        realised geometry is the analysis's (:attr:`~embroact.predict.analysis.ActuatorAnalysis.derived`).
    adjustments : tuple of str
        Human-readable notes where the generator had to change a request (prefixed with the
        segment, :meth:`~embroact.patterns.chain.Chain.where`).
    options : StitchOptions
        Lock-stitch settings used.
    segments : Chain of SegmentPlan
        The actuator's segments (:mod:`embroact.patterns.segments`), one or more, in order along
        the path. Given none, a chain of one over the whole path made of ``params`` and ``realised``.

    Examples
    --------
    >>> from embroact.patterns.zigzag import zigzag
    >>> from embroact.patterns.params import ZigzagParams
    >>> act = zigzag([[0.0, 0.0], [20.0, 0.0]], ZigzagParams(7.0, 1.0), name="A1").actuators[0]
    >>> act.name, act.pattern, act.params.width_mm, len(act.segments)
    ('A1', 'zigzag', 7.0, 1)
    """

    name: str
    params: PatternParams
    tube: Tube
    centerline: "Centerline"
    realised: Realised
    adjustments: tuple[str, ...] = ()
    options: StitchOptions = field(default_factory=StitchOptions)
    segments: Chain = UNGIVEN

    def __post_init__(self) -> None:
        object.__setattr__(self, "segments", Chain.given_or_one(self.segments, lambda: SegmentPlan(
            self.params, 0.0, self.centerline.length_mm, self.realised, 0.0, 0.0,
            tuple(self.adjustments))))

    @property
    def pattern(self) -> str:
        """The chain's pattern: its segments' kinds in chain order (:func:`~embroact.patterns.chain.strip_pattern`;
        a chain of one: its kind)."""
        return strip_pattern(seg.pattern for seg in self.segments)

    def rails(self) -> tuple:
        """The rails at +-w/2 of each segment's realised width, as shapely LineStrings.

        Each segment's own pair along its share of the path, in path order (``left_0, right_0,
        left_1, right_1, ...``); a chain of one: ``(left, right)`` along the whole path.

        Returns
        -------
        tuple of shapely.LineString

        Examples
        --------
        >>> from embroact.patterns.design import ActuatorSpec, generate_actuator
        >>> from embroact.patterns.params import ZigzagParams
        >>> from embroact.patterns.segments import SegmentSpec
        >>> from embroact.patterns.centerline import Centerline
        >>> segs = (SegmentSpec(ZigzagParams(8.0, 1.0), 40.0), SegmentSpec(ZigzagParams(6.0, 1.0), 40.0))
        >>> plan = generate_actuator(ActuatorSpec("A1", segs[0].params, Centerline.straight(80.0), segments=segs))
        >>> rails = plan.actuators[0].rails()
        >>> len(rails), [round(r.coords[0][1], 1) for r in rails], [r.coords[0][0] for r in rails]
        (4, [4.0, -4.0, 3.0, -3.0], [0.0, 0.0, 40.0, 40.0])
        """
        return tuple(rail for seg in self.segments
                     for rail in self.centerline.offset_curves(seg.realised.width_mm / 2.0, seg.start_mm,
                                                               seg.start_mm + seg.length_mm))

    def corridor(self):
        """Shapely polygon where no needle may land: centerline buffered by r_f + clearance.

        Returns
        -------
        shapely.Polygon

        Examples
        --------
        >>> from embroact.patterns.zigzag import zigzag
        >>> from embroact.patterns.params import ZigzagParams
        >>> act = zigzag([[0.0, 0.0], [20.0, 0.0]], ZigzagParams(7.0, 1.0), name="A1").actuators[0]
        >>> act.corridor().bounds, act.corridor().area  # 1.5 + 0.3 mm each side of a 20 mm path
        ((0.0, -1.8, 20.0, 1.8), 72.0)
        """
        return self.centerline.as_linestring().buffer(self.tube.corridor_radius_mm, cap_style="flat")


@dataclass(frozen=True, slots=True, eq=False)
class StitchPlan:
    """Needle points in sewing order with command, role and owning actuator.

    Attributes
    ----------
    xy_mm : ndarray, shape (n, 2)
        Positions [mm], plan frame (y up); read-only.
    commands : ndarray of int8, shape (n,)
        :class:`Command` per record.
    roles : ndarray of int8, shape (n,)
        :class:`Role` per record.
    actuator : ndarray of int16, shape (n,)
        Index into ``actuators`` per record, -1 for design-level records (END).
    actuators : tuple of ActuatorPlan
    name : str
    origin_mm : tuple of float
        Where the plan's (0, 0), the machine's start point, lies in the design's own frame
        [mm, y up] (:func:`embroact.patterns.origin.to_machine_frame` moved the plan by it).

    Examples
    --------
    >>> from embroact.patterns.design import build_plan, default_design
    >>> plan = build_plan(default_design())
    >>> plan
    StitchPlan('paper-zigzag': 109 records, 106 stitches, 1 actuator (A1), extent 100.0 x 7.0 mm)
    >>> plan.xy_mm.shape, plan.count(Command.STOP)
    ((109, 2), 1)
    """

    xy_mm: np.ndarray
    commands: np.ndarray
    roles: np.ndarray
    actuator: np.ndarray
    actuators: tuple[ActuatorPlan, ...] = ()
    name: str = "embroact"
    origin_mm: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self) -> None:
        xy = np.asarray(self.xy_mm, dtype=np.float64).reshape(-1, 2)
        n = len(xy)
        for attr, dtype in (("commands", np.int8), ("roles", np.int8), ("actuator", np.int16)):
            arr = np.asarray(getattr(self, attr), dtype=dtype).reshape(-1)
            if len(arr) != n:
                raise ValueError(f"{attr} has {len(arr)} entries, xy_mm has {n}")
            object.__setattr__(self, attr, frozen_array(arr, dtype=None))
        object.__setattr__(self, "xy_mm", frozen_array(xy))

    @classmethod
    def from_records(
        cls,
        records: Iterable[tuple[float, float, int, int] | tuple[float, float, int, int, int]],
        *,
        actuators: tuple[ActuatorPlan, ...] = (),
        name: str = "embroact",
    ) -> "StitchPlan":
        """Build from ``(x_mm, y_mm, command, role[, actuator])`` tuples.

        Parameters
        ----------
        records : iterable of tuple
            ``(x_mm, y_mm, command, role)`` or with the owning actuator's index last (default 0).
        actuators : tuple of ActuatorPlan
            The actuators the indices refer to.
        name : str
            The plan's (design's) name.

        Returns
        -------
        StitchPlan

        Examples
        --------
        >>> p = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (1, 0, Command.END, Role.CONTROL, -1)])
        >>> p.commands.tolist(), p.actuator.tolist()
        ([0, 4], [0, -1])
        """
        rows = [tuple(r) + ((0,) if len(r) == 4 else ()) for r in records]
        if not rows:
            return cls(np.zeros((0, 2)), np.zeros(0), np.zeros(0), np.zeros(0), actuators, name)
        arr = np.array(rows, dtype=np.float64)
        return cls(arr[:, :2], arr[:, 2], arr[:, 3], arr[:, 4], actuators, name)

    def __len__(self) -> int:
        return len(self.xy_mm)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, StitchPlan):
            return NotImplemented
        return (
            self.name == other.name
            and self.actuators == other.actuators
            and all(
                np.array_equal(getattr(self, a), getattr(other, a))
                for a in ("xy_mm", "commands", "roles", "actuator")
            )
        )

    __hash__ = None  # type: ignore[assignment]

    def isclose(self, other: "StitchPlan", *, atol_mm: float = 1e-9) -> bool:
        """Same records with positions equal within ``atol_mm``.

        Parameters
        ----------
        other : StitchPlan
        atol_mm : float
            Largest allowed difference of any coordinate [mm].

        Returns
        -------
        bool

        Examples
        --------
        >>> a = StitchPlan.from_records([(0.0, 0.0, Command.STITCH, Role.LEG)])
        >>> b = StitchPlan.from_records([(0.0, 1e-12, Command.STITCH, Role.LEG)])
        >>> a == b, a.isclose(b)
        (False, True)
        """
        return (
            len(self) == len(other)
            and np.array_equal(self.commands, other.commands)
            and np.array_equal(self.roles, other.roles)
            and bool(np.all(np.abs(self.xy_mm - other.xy_mm) <= atol_mm))
        )

    @property
    def stitch_count(self) -> int:
        """Number of STITCH records."""
        return int(np.count_nonzero(self.commands == Command.STITCH))

    def count(self, command: Command) -> int:
        """Number of records with the given command.

        Parameters
        ----------
        command : Command

        Returns
        -------
        int

        Examples
        --------
        >>> StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG), (0, 0, Command.TRIM, Role.CONTROL)]).count(Command.TRIM)
        1
        """
        return int(np.count_nonzero(self.commands == command))

    def bounds_mm(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) over all records [mm].

        Returns
        -------
        (float, float, float, float)
            All zero for an empty plan.

        Examples
        --------
        >>> StitchPlan.from_records([(0, 1, Command.STITCH, Role.LEG), (5, -2, Command.STITCH, Role.LEG)]).bounds_mm()
        (0.0, -2.0, 5.0, 1.0)
        """
        if len(self) == 0:
            return (0.0, 0.0, 0.0, 0.0)
        lo, hi = self.xy_mm.min(axis=0), self.xy_mm.max(axis=0)
        return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))

    def __repr__(self) -> str:
        x0, y0, x1, y1 = self.bounds_mm()
        names = ", ".join(a.name for a in self.actuators)
        return (f"StitchPlan({self.name!r}: {len(self)} records, {self.stitch_count} stitches, "
                f"{len(self.actuators)} actuator{'s' * (len(self.actuators) != 1)}"
                f"{f' ({names})' if names else ''}, extent {x1 - x0:.1f} x {y1 - y0:.1f} mm)")

    #: Stitch preview in Jupyter (:func:`embroact.export.pictures.stitches.plan_svg`, registered by ``embroact``).
    _repr_svg_ = repr_svg

    def select(self, index: int) -> "StitchPlan":
        """Records of one actuator only (its STOP/TRIM included).

        Parameters
        ----------
        index : int
            Position of the actuator in :attr:`actuators` (sewing order).

        Returns
        -------
        StitchPlan

        Examples
        --------
        >>> p = StitchPlan.from_records([(0, 0, Command.STITCH, Role.LEG, 0), (9, 0, Command.STITCH, Role.LEG, 1)])
        >>> p.select(1).xy_mm.tolist()
        [[9.0, 0.0]]
        """
        m = self.actuator == index
        return StitchPlan(self.xy_mm[m], self.commands[m], self.roles[m], self.actuator[m], self.actuators, self.name,
                          self.origin_mm)
