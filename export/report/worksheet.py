"""Production worksheet: what the operator cuts, lays and waits for, in text and JSON.

Formulas (all lengths mm, reported in m where marked)
-----------------------------------------------------
Tube cut length per actuator
    ``L_tube = path length + 2 * end_margin_mm`` (the margins take the connectors).
Top thread
    ``sum(leg lengths) + sum(over-tube extra) + n_stitch * t_fabric + n_thread_ends * TAIL_MM``.
    A leg whose two needle points lie on opposite sides of the centerline
    crosses the tube.  Pulled taut over a tube of radius ``r`` lying on the
    fabric, between points ``a = L/2`` either side of its axis, the thread runs
    along two tangents of length ``a`` and wraps an arc ``r * phi`` with
    ``phi = pi - 2 (acos(r / sqrt(a^2 + r^2)) - atan(r / a))``; the extra length
    over the straight leg is ``r * phi`` (exact for legs perpendicular to the
    tube, a lower bound for oblique ones).  Each needle penetration costs the
    fabric thickness ``t_fabric`` (half in, half out to the interlock at
    mid-thickness); each start and trim leaves a tail of :data:`TAIL_MM`.
Bobbin thread
    ``sum(leg lengths) + n_stitch * t_fabric``: under the fabric the bobbin runs
    straight from needle point to needle point.
Sewing time
    ``(stitches + jumps) / speed_spm`` minutes, plus :data:`TRIM_TIME_S` per trim
    and :data:`STOP_RESTART_S` per stop (machine stop and restart).  Handling
    time at each stop (laying the tube, :data:`LAY_TUBE_S`) is reported separately.

Examples
--------
>>> from embroact.patterns.plan import Command, Role, StitchPlan
>>> plan = StitchPlan.from_records([
...     (0, 3.5, Command.STOP, Role.CONTROL), (0, 3.5, Command.STITCH, Role.TIE_IN),
...     (1, -3.5, Command.STITCH, Role.LEG), (2, 3.5, Command.STITCH, Role.LEG),
...     (2, 3.5, Command.TRIM, Role.CONTROL), (2, 3.5, Command.END, Role.CONTROL, -1)])
>>> ws = worksheet(plan, speed_spm=600)
>>> ws.stitch_count, ws.stop_count, ws.trim_count
(3, 1, 1)
>>> round(ws.size_mm[0], 3), round(ws.size_mm[1], 3)
(2.0, 7.0)
>>> ws.as_dict()["sewing_time_s"]
8.3
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...patterns.base.errors import check_range
from ...patterns.plan import ActuatorPlan, Command, StitchPlan

__all__ = [
    "DEFAULT_SPEED_SPM",
    "TAIL_MM",
    "TRIM_TIME_S",
    "STOP_RESTART_S",
    "LAY_TUBE_S",
    "FABRIC_THICKNESS_MM",
    "over_tube_extra_mm",
    "ActuatorSheet",
    "Worksheet",
    "worksheet",
]

DEFAULT_SPEED_SPM = 600.0
"""Machine speed used when neither the caller nor the design gives one [stitches/min]."""
TAIL_MM = 20.0
"""Top-thread tail left at each start and trim [mm]."""
TRIM_TIME_S = 3.0
"""Machine time per trim (slow down, cut, pick up) [s]."""
STOP_RESTART_S = 5.0
"""Machine time per stop: slow down, stop and restart [s]."""
LAY_TUBE_S = 60.0
"""Operator time per stop to lay and tape the tube along its path [s]."""
FABRIC_THICKNESS_MM = 0.5
"""Default fabric thickness used for the per-penetration thread allowance [mm]."""


def over_tube_extra_mm(half_span_mm, radius_mm):
    """Extra thread for a leg pulled taut over a tube, beyond the straight leg [mm].

    Parameters
    ----------
    half_span_mm : float or array
        Distance ``a`` from the tube axis to each needle point, along the leg [mm].
    radius_mm : float
        Tube outer radius [mm].

    Examples
    --------
    >>> round(float(over_tube_extra_mm(3.5, 1.5)), 4)   # paper's zigzag, 7 mm wide
    2.4294
    """
    a = np.asarray(half_span_mm, dtype=np.float64)
    r = float(radius_mm)
    phi = np.pi - 2.0 * (np.arccos(r / np.hypot(a, r)) - np.arctan2(r, a))
    return r * phi


@dataclass(frozen=True, slots=True)
class ActuatorSheet:
    """One actuator's lines on the worksheet.

    Attributes
    ----------
    name, pattern : str
    path_length_mm : float
        Centerline length [mm].
    end_margin_mm : float
        Free tube at each end [mm].
    tube_cut_mm : float
        Tube length to cut [mm] = path length + 2 * end margin.
    stitches : int
    top_thread_mm, bobbin_thread_mm : float
        Estimated consumption [mm].
    legs_over_tube : int
        Legs that cross the tube.
    derived : dict
        Realised parameters and derived geometry (``DerivedGeometry.as_dict()``).
    adjustments : tuple of str
    """

    name: str
    pattern: str
    path_length_mm: float
    end_margin_mm: float
    tube_cut_mm: float
    stitches: int
    top_thread_mm: float
    bobbin_thread_mm: float
    legs_over_tube: int
    derived: dict = field(compare=False)
    adjustments: tuple[str, ...] = ()


@dataclass(frozen=True, slots=True)
class Worksheet:
    """Production worksheet of one plan (see the module docstring for the formulas).

    Attributes
    ----------
    name : str
    size_mm : tuple of float
        Width and height of the needle points' bounding box [mm].
    stitch_count, jump_count, trim_count, stop_count : int
    stops : tuple of str
        What the operator does at each stop, in order.
    actuators : tuple of ActuatorSheet
    top_thread_mm, bobbin_thread_mm : float
    speed_spm : float
    sewing_time_s, handling_time_s : float
    findings : tuple of dict
        Design-rule findings passed in (``Finding.as_dict()``).
    """

    name: str
    size_mm: tuple[float, float]
    stitch_count: int
    jump_count: int
    trim_count: int
    stop_count: int
    stops: tuple[str, ...]
    actuators: tuple[ActuatorSheet, ...]
    top_thread_mm: float
    bobbin_thread_mm: float
    speed_spm: float
    sewing_time_s: float
    handling_time_s: float
    findings: tuple[dict, ...] = ()

    def as_dict(self) -> dict:
        """JSON-ready dict with unit-suffixed keys (lengths mm, thread also m, times s)."""
        return {
            "name": self.name,
            "size_mm": [round(v, 3) for v in self.size_mm],
            "stitch_count": self.stitch_count,
            "jump_count": self.jump_count,
            "trim_count": self.trim_count,
            "stop_count": self.stop_count,
            "stops": list(self.stops),
            "top_thread_m": round(self.top_thread_mm / 1000.0, 3),
            "bobbin_thread_m": round(self.bobbin_thread_mm / 1000.0, 3),
            "speed_spm": self.speed_spm,
            "sewing_time_s": round(self.sewing_time_s, 1),
            "handling_time_s": round(self.handling_time_s, 1),
            "actuators": [
                {
                    "name": a.name,
                    "pattern": a.pattern,
                    "path_length_mm": round(a.path_length_mm, 3),
                    "end_margin_mm": a.end_margin_mm,
                    "tube_cut_mm": round(a.tube_cut_mm, 1),
                    "stitches": a.stitches,
                    "legs_over_tube": a.legs_over_tube,
                    "top_thread_m": round(a.top_thread_mm / 1000.0, 3),
                    "bobbin_thread_m": round(a.bobbin_thread_mm / 1000.0, 3),
                    "derived": a.derived,
                    "adjustments": list(a.adjustments),
                }
                for a in self.actuators
            ],
            "findings": list(self.findings),
        }

    def as_text(self) -> str:
        """Human-readable worksheet (plain text, fixed layout)."""
        t = self.sewing_time_s
        lines = [
            f"PRODUCTION WORKSHEET  {self.name}",
            "",
            f"design size      {self.size_mm[0]:.1f} x {self.size_mm[1]:.1f} mm",
            f"stitches         {self.stitch_count}   jumps {self.jump_count}   trims {self.trim_count}   stops {self.stop_count}",
            f"sewing time      {int(t // 60)} min {t % 60:04.1f} s at {self.speed_spm:g} stitches/min"
            f" (+ {self.handling_time_s / 60:.0f} min laying tubes)",
            f"top thread       {self.top_thread_mm / 1000:.2f} m",
            f"bobbin thread    {self.bobbin_thread_mm / 1000:.2f} m",
            "",
            "STOP SEQUENCE",
            *[f"  {s}" for s in self.stops],
        ]
        for a in self.actuators:
            lines += ["", f"ACTUATOR {a.name} ({a.pattern})",
                      f"  tube cut length  {a.tube_cut_mm:.0f} mm"
                      f" = {a.path_length_mm:.1f} mm path + 2 x {a.end_margin_mm:g} mm end margin",
                      f"  stitches         {a.stitches} ({a.legs_over_tube} legs over the tube)",
                      f"  thread           top {a.top_thread_mm / 1000:.2f} m, bobbin {a.bobbin_thread_mm / 1000:.2f} m"]
            lines += [f"  {k:<24} {_fmt(v)}" for k, v in a.derived.items() if k != "name"]
            lines += [f"  adjustment: {s}" for s in a.adjustments]
        lines += ["", "DESIGN-RULE FINDINGS"]
        lines += [f"  {f.get('severity', '')} {f.get('code', '')}: {f.get('message', '')}" for f in self.findings] or ["  none"]
        return "\n".join(lines) + "\n"


def _fmt(v) -> str:
    return f"{v:.4g}" if isinstance(v, float) else str(v)


def _legs(plan: StitchPlan, k: int):
    """Needle points of actuator ``k`` and the index pairs of consecutive stitches (legs)."""
    m = (plan.actuator == k) & (plan.commands == Command.STITCH)
    idx = np.flatnonzero(m)
    # a leg joins two needle points with no trim, stop or jump between them
    consecutive = np.diff(idx) == 1
    return plan.xy_mm[idx], np.flatnonzero(consecutive)


def _actuator_sheet(plan: StitchPlan, k: int, act: ActuatorPlan | None, t_fabric: float) -> ActuatorSheet:
    pts, legs = _legs(plan, k)
    seg = pts[legs + 1] - pts[legs]
    lengths = np.hypot(seg[:, 0], seg[:, 1])
    extra = np.zeros(0)
    if act is not None:
        _, off = act.centerline.project(pts)
        crossing = np.sign(off[legs]) * np.sign(off[legs + 1]) < 0
        extra = over_tube_extra_mm(lengths[crossing] / 2.0, act.tube.outer_radius_mm)
    n = len(pts)
    tails = 1 + int(np.count_nonzero((plan.actuator == k) & (plan.commands == Command.TRIM)))
    top = float(lengths.sum() + extra.sum() + n * t_fabric + tails * TAIL_MM)
    bobbin = float(lengths.sum() + n * t_fabric)
    if act is None:
        return ActuatorSheet(f"A{k + 1}", "unknown", 0.0, 0.0, 0.0, n, top, bobbin, 0, {})
    from ...predict.derived import derive

    path = act.centerline.length_mm
    margin = act.tube.end_margin_mm
    return ActuatorSheet(act.name, act.pattern, path, margin, path + 2 * margin, n, top, bobbin,
                         len(extra), derive(act).as_dict(), tuple(act.adjustments))


def _stop_lines(plan: StitchPlan, sheets: dict[int, ActuatorSheet]) -> tuple[str, ...]:
    out = []
    for n, i in enumerate(np.flatnonzero(plan.commands == Command.STOP), start=1):
        k = int(plan.actuator[i])
        a = sheets.get(k)
        x, y = plan.xy_mm[i]
        if a is None or a.tube_cut_mm == 0.0:
            out.append(f"stop {n}: lay the tube for actuator A{k + 1}; needle at ({x:.1f}, {y:.1f}) mm")
            continue
        out.append(
            f"stop {n}: lay tube for actuator {a.name} along its path, {a.tube_cut_mm:.0f} mm cut length "
            f"({a.end_margin_mm:g} mm free at each end); the needle waits at the actuator's start "
            f"({x:.1f}, {y:.1f}) mm; tape the ends, press start"
        )
    return tuple(out)


def worksheet(
    plan: StitchPlan,
    design=None,
    *,
    speed_spm: float = DEFAULT_SPEED_SPM,
    fabric_thickness_mm: float = FABRIC_THICKNESS_MM,
    findings=(),
) -> Worksheet:
    """Build the production worksheet of ``plan``.

    Parameters
    ----------
    plan : StitchPlan
    design : optional
        The design the plan came from; its ``name`` (if any) titles the sheet.
    speed_spm : float
        Machine speed [stitches/min], in (0, 2000].
    fabric_thickness_mm : float
        For the per-penetration thread allowance [mm], in [0, 10].
    findings : iterable of Finding or dict
        Design-rule findings to list (``Finding.as_dict()`` is called when present).
    """
    spm = check_range("speed_spm", speed_spm, low=0.0, high=2000.0, high_inclusive=True)
    t_f = check_range("fabric_thickness_mm", fabric_thickness_mm, low=0.0, high=10.0, low_inclusive=True,
                      high_inclusive=True)
    ids = sorted({int(a) for a in plan.actuator.tolist() if a >= 0})
    sheets = {
        k: _actuator_sheet(plan, k, plan.actuators[k] if k < len(plan.actuators) else None, t_f) for k in ids
    }
    needles = plan.xy_mm[plan.commands == Command.STITCH]
    size = tuple(float(v) for v in np.ptp(needles, axis=0)) if len(needles) else (0.0, 0.0)
    n_st, n_j, n_tr, n_sp = (plan.count(c) for c in (Command.STITCH, Command.JUMP, Command.TRIM, Command.STOP))
    sewing = 60.0 * (n_st + n_j) / spm + n_tr * TRIM_TIME_S + n_sp * STOP_RESTART_S
    name = getattr(design, "name", None) or plan.name
    return Worksheet(
        name=name,
        size_mm=size,
        stitch_count=n_st,
        jump_count=n_j,
        trim_count=n_tr,
        stop_count=n_sp,
        stops=_stop_lines(plan, sheets),
        actuators=tuple(sheets[k] for k in ids),
        top_thread_mm=math.fsum(s.top_thread_mm for s in sheets.values()),
        bobbin_thread_mm=math.fsum(s.bobbin_thread_mm for s in sheets.values()),
        speed_spm=spm,
        sewing_time_s=sewing,
        handling_time_s=n_sp * LAY_TUBE_S,
        findings=tuple(f.as_dict() if hasattr(f, "as_dict") else dict(f) for f in findings),
    )
