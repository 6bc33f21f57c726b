"""Placement line: a running stitch along the tube axis, sewn before the actuator's cord-in stop.

Like an appliqué placement line, it marks on the bare fabric where the operator lays the
tube: the machine sews it, stops at the actuator's cord-in stop, the operator lays the tube
over it and the actuator is embroidered over both (docs/machine.md, cord-in stops).

Records, inserted right before the actuator's STOP, all STITCH with
:attr:`~embroact.patterns.plan.Role.PLACEMENT`, owned by the actuator:

1. the line starts at the *end* of the path with ``tie_count`` lock stitches of
   ``tie_stitch_mm`` (the actuator's :class:`~embroact.patterns.params.StitchOptions`)
   back and forth along the axis, towards the inside;
2. running stitches back along the axis to the path's start, the fewest equal pieces
   of at most ``stitch_mm`` along the path (a chord on a bend is a little shorter);
3. straight stitches of at most ``stitch_mm`` from there out to the cord-in stop's point
   (where the actuator's lock stitches start, on the first rail, ``w/2`` from the axis).

So the line ends where the actuator starts: no trim and no travel, the machine waits there
(in every format: a colour format's pause follows a needle point, not a jump, which PES/PEC
would turn into a trim), and the actuator's tie-in stitches lock the thread, under the tube.

The needle points lie on the tube axis, inside the tube's corridor, but the tube is not
there yet: the corridor rule (EA101) and the couching rule (EA307) leave them out.

Examples
--------
>>> from embroact.patterns.placement import placement_records, with_placement
>>> from embroact.patterns.zigzag import zigzag
>>> from embroact.patterns.centerline import Centerline
>>> from embroact.patterns.params import ZigzagParams
>>> from embroact.patterns.plan import Command, Role
>>> plan = zigzag(Centerline.straight(10.0), ZigzagParams(7.0, 1.0))
>>> placed = with_placement(plan, 2.5)
>>> line = placed.xy_mm[placed.roles == Role.PLACEMENT]
>>> line.tolist()   # 3 lock stitches at x = 10, 4 of about 2.325 mm to x = 0, 2 out to the stop point, on the 0.1 mm grid
[[10.0, 0.0], [9.3, 0.0], [10.0, 0.0], [9.3, 0.0], [7.0, 0.0], [4.6, 0.0], [2.3, 0.0], [0.0, 0.0], [0.4, 1.8], [0.7, 3.5]]
>>> Command(int(placed.commands[len(line)])).name, placed.xy_mm[len(line)].round(9).tolist()  # the cord-in stop
('STOP', [0.7, 3.5])
>>> len(line) <= placement_records(10.0, 2.5, 3, 3.5)
True
"""
from __future__ import annotations

import math

import numpy as np

from .assemble import rail_positions, tie_step_mm
from .base.errors import ParameterError, check_range
from .limits import on_grid
from .plan import Command, Role, StitchPlan

__all__ = ["placement_records", "placement_line", "with_placement"]


def placement_records(length_mm: float, stitch_mm: float, tie_count: int, half_width_mm: float) -> int:
    """Records a placement line adds at most along a path of ``length_mm`` (the lock stitches'
    start point, ``tie_count`` lock stitches, ``ceil(length / stitch)`` running stitches and
    the stitches out to a first needle point up to ``length + half_width`` away).

    Parameters
    ----------
    length_mm : float
        Path length [mm].
    stitch_mm : float
        Longest running stitch [mm], > 0.
    tie_count : int
        Lock stitches at the start of the line.
    half_width_mm : float
        Half the pattern's width [mm].

    Returns
    -------
    int

    Examples
    --------
    >>> placement_records(100.0, 2.5, 3, 3.5)
    86
    """
    out = max(1, math.ceil((float(length_mm) + float(half_width_mm)) / float(stitch_mm)))
    return 1 + int(tie_count) + max(1, math.ceil(float(length_mm) / float(stitch_mm))) + out


def placement_line(centerline, stitch_mm: float, end_mm, *, tie_stitch_mm: float, tie_count: int) -> np.ndarray:
    """Needle points of the placement line along ``centerline`` (see the module docstring) [mm].

    Parameters
    ----------
    centerline : Centerline
        The tube's path.
    stitch_mm : float
        Longest running stitch [mm], > 0.
    end_mm : (x, y)
        Where the line ends: the actuator's cord-in stop point [mm].
    tie_stitch_mm : float
        Lock stitch length (straight, along the axis) [mm].
    tie_count : int
        Lock stitches at the start of the line.

    Returns
    -------
    numpy.ndarray, shape (n, 2)
        On the machine grid, from the path's end back to its start and out to ``end_mm``.

    Examples
    --------
    >>> from embroact.patterns.centerline import Centerline
    >>> xy = placement_line(Centerline.straight(10.0), 2.5, (0.0, 3.5), tie_stitch_mm=0.5, tie_count=2)
    >>> xy[0].tolist(), xy[-1].tolist(), len(xy)
    ([10.0, 0.0], [0.0, 3.5], 9)
    """
    check_range("placement_stitch_mm", stitch_mm, low=0.0, high=1000.0, high_inclusive=True)
    length = centerline.length_mm
    back = float(tie_step_mm(centerline, [length], [0.0], [-1], tie_stitch_mm)[0])
    ties = length - back * (np.arange(tie_count + 1) % 2)
    run = rail_positions(centerline, float(ties[-1]), 0.0, 0.0, stitch_mm)
    axis = centerline.offset_point_at(np.concatenate([ties, run]), np.zeros(len(ties) + len(run)))
    gap = np.asarray(end_mm, dtype=np.float64) - axis[-1]
    pieces = math.ceil(float(np.hypot(*gap)) / stitch_mm)
    return on_grid(np.vstack([axis, axis[-1] + gap * (np.arange(1, pieces + 1) / max(pieces, 1))[:, None]]))


def with_placement(plan: StitchPlan, stitch_mm: float) -> StitchPlan:
    """A one-actuator ``plan`` with its placement line inserted before its cord-in STOP.

    Parameters
    ----------
    plan : StitchPlan
        One actuator's plan, with its one STOP.
    stitch_mm : float
        Longest running stitch of the line [mm], > 0.

    Returns
    -------
    StitchPlan
        The same records, with the line's records (role PLACEMENT) before the STOP.

    Raises
    ------
    ParameterError
        ``plan`` is not one actuator's plan with a STOP (a joined design: add the lines
        before joining).

    Examples
    --------
    >>> from embroact.patterns.zigzag import zigzag
    >>> from embroact.patterns.params import ZigzagParams
    >>> plan = zigzag([[0.0, 0.0], [20.0, 0.0]], ZigzagParams(7.0, 1.0))
    >>> int((with_placement(plan, 2.5).roles == Role.PLACEMENT).sum()) > 0
    True
    """
    stops = np.flatnonzero(plan.commands == Command.STOP)
    if len(plan.actuators) != 1 or len(stops) != 1:
        raise ParameterError(f"plan must be one actuator's plan with one STOP, got {len(plan.actuators)} "
                             f"actuator(s) and {len(stops)} STOP record(s)")
    act = plan.actuators[0]
    xy = placement_line(act.centerline, stitch_mm, plan.xy_mm[stops[0]], tie_stitch_mm=act.options.tie_stitch_mm,
                        tie_count=act.options.tie_count)
    at, n = int(stops[0]), len(xy)
    return StitchPlan(
        np.insert(plan.xy_mm, at, xy, axis=0),
        np.insert(plan.commands, at, np.full(n, Command.STITCH)),
        np.insert(plan.roles, at, np.full(n, Role.PLACEMENT)),
        np.insert(plan.actuator, at, np.full(n, plan.actuator[at])),
        plan.actuators,
        plan.name,
    )
