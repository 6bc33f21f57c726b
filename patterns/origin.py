"""The machine origin: where a design's machine file starts, as the embroiderer expects it.

A machine file's coordinates are relative to its start point: the needle position when the
operator starts the machine, which the operator places in the hoop. A design's plan is
moved so that this point is the plan frame's (0, 0) (:func:`to_machine_frame`), chosen by
``[machine] origin``:

* ``"center"`` (default): the centre of the design's extent (the bounding box of its needle
  points), as Ink/Stitch and home machines place a design: start with the needle at the
  hoop's centre and the design is centred in the hoop;
* ``"first-stitch"``: the first needle point (the operator puts the needle where sewing
  begins; no travel before it);
* ``[x, y]``: that point of the design (mm, plan frame, y up), e.g. a mark on the fabric.
  A drawing can carry it too: Ink/Stitch's origin command, or a shape named
  ``embroact-origin`` (:func:`embroact.export.files.svgfile.svg_origin_mm`), used when the
  design file names no origin.

The point is rounded to the machine grid (0.1 mm), so every record keeps its place on the
grid. The hoop rules (EA305, EA306) centre the hoop on the needle points and the start point
in this frame, the frame of the written file, so a build and a check of its file agree.

Examples
--------
>>> from embroact.patterns.design import build_plan, default_design
>>> plan = build_plan(default_design())          # a 100 mm zigzag from (0, 0) to (100, 0)
>>> [round(float(v), 1) for v in plan.xy_mm.min(axis=0)], [round(float(v), 1) for v in plan.xy_mm.max(axis=0)]
([-50.0, -3.5], [50.0, 3.5])
>>> check_origin([10, -4]), check_origin("first-stitch")
((10.0, -4.0), 'first-stitch')
"""
from __future__ import annotations

import dataclasses
import enum
import math

import numpy as np

from .base.errors import ParameterError
from .base.tolerances import DEFAULT_TOLERANCES
from .base.validate import COORD_MM
from .plan import StitchPlan

__all__ = ["MachineOrigin", "check_origin", "origin_point_mm", "to_machine_frame"]


class MachineOrigin(str, enum.Enum):
    """Where the machine file starts (``[machine] origin``), besides an explicit point.

    Examples
    --------
    >>> MachineOrigin("first-stitch").name
    'FIRST_STITCH'
    """

    CENTER = "center"  #: centre of the design's extent
    FIRST_STITCH = "first-stitch"  #: the first needle point


def check_origin(value) -> str | tuple[float, float]:
    """``"center"``, ``"first-stitch"`` or a finite point ``(x, y)`` [mm]; anything else is refused.

    Parameters
    ----------
    value : str or pair of numbers
        A :class:`MachineOrigin` value (any case) or a point [mm].

    Returns
    -------
    str or tuple of float
        The origin's value, or the point as floats.

    Raises
    ------
    ParameterError
        One line naming ``origin``, the value and what is allowed.

    Examples
    --------
    >>> check_origin(" Center"), check_origin([10, -5])
    ('center', (10.0, -5.0))
    """
    if isinstance(value, str):
        try:
            return MachineOrigin(value.strip().lower()).value
        except ValueError:
            pass
    elif isinstance(value, (list, tuple)) and len(value) == 2 and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
        x, y = (float(v) for v in value)
        if math.isfinite(x) and math.isfinite(y) and max(abs(x), abs(y)) <= COORD_MM:
            return (x + 0.0, y + 0.0)
    raise ParameterError(f"origin must be \"center\", \"first-stitch\" or a point [x, y] in mm (|x|, |y| <= "
                         f"{COORD_MM:g}), got {value!r:.60}")


def origin_point_mm(plan: StitchPlan, origin: str | tuple[float, float]) -> np.ndarray:
    """The plan position [mm] of the machine's start point for ``origin``, on the 0.1 mm grid.

    Parameters
    ----------
    plan : StitchPlan
        A plan in the design's frame.
    origin : str or tuple of float
        As :func:`check_origin` returns it.

    Returns
    -------
    ndarray, shape (2,)
        The start point [mm] in the plan's frame.

    Examples
    --------
    >>> from embroact.patterns.zigzag import zigzag
    >>> from embroact.patterns.params import ZigzagParams
    >>> plan = zigzag([[0.0, 0.0], [20.0, 0.0]], ZigzagParams(7.0, 1.0))
    >>> origin_point_mm(plan, "center").tolist(), origin_point_mm(plan, (1.04, 2.0)).tolist()
    ([10.0, 0.0], [1.0, 2.0])
    """
    from .plan import Command

    stitches = plan.xy_mm[plan.commands == Command.STITCH]
    if origin == MachineOrigin.CENTER.value:
        point = (stitches.min(axis=0) + stitches.max(axis=0)) / 2.0 if len(stitches) else np.zeros(2)
    elif origin == MachineOrigin.FIRST_STITCH.value:
        point = stitches[0] if len(stitches) else np.zeros(2)
    else:
        point = np.asarray(origin, dtype=np.float64)
    grid = DEFAULT_TOLERANCES.machine_grid_mm
    return np.round(point / grid) * grid + 0.0


def to_machine_frame(plan: StitchPlan, origin: str | tuple[float, float]) -> StitchPlan:
    """``plan`` moved so that the machine's start point (:func:`origin_point_mm`) is (0, 0).

    Parameters
    ----------
    plan : StitchPlan
        A plan in the design's frame.
    origin : str or tuple of float
        As :func:`check_origin` returns it.

    Returns
    -------
    StitchPlan
        The same records and actuators, every position and tube path moved; ``origin_mm``
        says where its (0, 0) lies in the design's frame.

    Examples
    --------
    >>> from embroact.patterns.zigzag import zigzag
    >>> from embroact.patterns.params import ZigzagParams
    >>> plan = to_machine_frame(zigzag([[0.0, 0.0], [20.0, 0.0]], ZigzagParams(7.0, 1.0)), "center")
    >>> plan.origin_mm, float(plan.xy_mm[:, 0].min() + plan.xy_mm[:, 0].max())
    ((10.0, 0.0), 0.0)
    """
    shift = origin_point_mm(plan, origin)
    if not np.any(shift):
        return plan
    move = (-float(shift[0]), -float(shift[1]))
    actuators = tuple(dataclasses.replace(a, centerline=a.centerline.transformed(origin_mm=move))
                      for a in plan.actuators)
    origin = (float(plan.origin_mm[0] + shift[0]) + 0.0, float(plan.origin_mm[1] + shift[1]) + 0.0)
    return StitchPlan(plan.xy_mm - shift, plan.commands, plan.roles, plan.actuator, actuators, plan.name, origin)
