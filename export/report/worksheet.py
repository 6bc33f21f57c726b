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
Fabric to hoop
    The hoop's sewing field plus :data:`FABRIC_BORDER_MM` on every side (the hoop clamps
    the fabric outside its field), and never smaller than the tubes with their free ends.

Counts and pauses are those of the machine file when one is given (``machine=``, the
:class:`~embroact.export.machine.formats.WriteResult` of the written file, whose numbers
are read back from its bytes); without it they are the plan's.  The set-up section tells
the operator how to set the machine for that file's kind of stop, which tubes are laid
before start, where each tube runs relative to the needle waiting for it, which end takes
the connector and how much fabric to hoop.  With placement lines
(:mod:`embroact.patterns.placement`) every tube is laid at a pause that follows its line.

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
from ...patterns.base.findings import finding_line, finding_place
from ...patterns.chain import Chain
from ...patterns.params import FABRIC_THICKNESS_MM
from ...patterns.plan import ActuatorPlan, Command, Role, StitchPlan
from ..machine.census import COLOR_FORMATS
from ..pictures.template import start_from_centre

__all__ = [
    "DEFAULT_SPEED_SPM",
    "check_speed_spm",
    "TAIL_MM",
    "TRIM_TIME_S",
    "STOP_RESTART_S",
    "LAY_TUBE_S",
    "FABRIC_BORDER_MM",
    "machine_setup",
    "over_tube_extra_mm",
    "ActuatorSheet",
    "Worksheet",
    "worksheet",
    "operating_point",
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
FABRIC_BORDER_MM = 40.0
"""Fabric beyond the hoop's sewing field on every side, for the hoop to clamp [mm]."""


def over_tube_extra_mm(half_span_mm, radius_mm):
    """Extra thread for a leg pulled taut over a tube, beyond the straight leg [mm].

    Parameters
    ----------
    half_span_mm : float or array
        Distance ``a`` from the tube axis to each needle point, along the leg [mm].
    radius_mm : float
        Tube outer radius [mm].

    Returns
    -------
    numpy.ndarray or float
        [mm].

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
        The actuator's name and pattern kind.
    path_length_mm : float
        Centerline length [mm].
    end_margin_mm : float
        Free tube at each end [mm].
    tube_cut_mm : float
        Tube length to cut [mm] = path length + 2 * end margin.
    stitches : int
        Its needle points.
    top_thread_mm, bobbin_thread_mm : float
        Estimated consumption [mm].
    legs_over_tube : int
        Legs that cross the tube.
    derived : dict
        The whole strip's realised parameters and derived geometry
        (:meth:`~embroact.predict.strip.StripGeometry.as_dict`: values common to its segments,
        ``None`` where they differ, ``length_mm`` the sum of their legs).
    adjustments : tuple of str
        What the generator changed to close the pattern.
    model : dict or None
        The whole strip's G, P0, tube and tube law with their sources
        (:meth:`~embroact.predict.strip.StripChoice.as_dict`), when the worksheet was made from
        an analysis and every segment has a model.
    segments : tuple of dict
        The actuator's chain of segments in order along the path, one or more
        (:meth:`~embroact.predict.analysis.SegmentAnalysis.as_dict`: where each lies, its legs,
        the unbent transition to the next and the thread's run there, the realised parameters
        and derived geometry, its model); empty for a tube read from a machine file.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> sheet = worksheet(analysis.plan, analysis.design, analysis=analysis)
    >>> a = sheet.actuators[0]
    >>> a.name, a.path_length_mm, a.tube_cut_mm, a.stitches, a.legs_over_tube
    ('A1', 100.0, 160.0, 106, 100)
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
    model: dict | None = field(default=None, compare=False)
    segments: tuple[dict, ...] = field(default=(), compare=False)


@dataclass(frozen=True, slots=True)
class Worksheet:
    """Production worksheet of one plan (see the module docstring for the formulas).

    Attributes
    ----------
    name : str
        The design's name.
    size_mm : tuple of float
        Width and height of the needle points' bounding box [mm].
    stitch_count, jump_count, trim_count, stop_count : int
        Record counts.
    stops : tuple of str
        What the operator does at each stop, in order.
    actuators : tuple of ActuatorSheet
        One per actuator.
    top_thread_mm, bobbin_thread_mm : float
        Thread for the whole design [mm].
    speed_spm : float
        Machine speed [stitches/min].
    sewing_time_s, handling_time_s : float
        Sewing time, and the operator's time laying tubes [s].
    findings : tuple of dict
        Design-rule findings passed in (``Finding.as_dict()``).
    color_change_count : int
        Colour changes (colour formats) or needle-set records (TBF, U01) in the machine file.
    machine_format : str or None
        Format of the machine file the counts come from (None: counted on the plan).
    setup : tuple of str
        How to set the machine and hoop the fabric, in plain words.
    notes : tuple of str
        What the machine file's format cannot carry.
    fabric_mm : tuple of float
        Fabric to cut and hoop, width and height [mm].
    operating_point : dict or None
        The design's operating point (``[operation] target_pressure_kpa``, ``target_bend_deg``) beside
        the pressure the rules judge up to (``max_pressure_kpa``); None when the design names none.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> sheet = worksheet(analysis.plan, analysis.design, analysis=analysis)
    >>> sheet.name, sheet.size_mm, sheet.stitch_count, sheet.stop_count
    ('paper-zigzag', (100.0, 7.0), 106, 1)
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
    color_change_count: int = 0
    machine_format: str | None = None
    setup: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()
    fabric_mm: tuple[float, float] = (0.0, 0.0)
    operating_point: dict | None = None

    def as_dict(self) -> dict:
        """JSON-ready dict with unit-suffixed keys (lengths mm, thread also m, times s).

        Returns
        -------
        dict

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> from embroact.predict.analysis import analyse
        >>> analysis = analyse(default_design())
        >>> sheet = worksheet(analysis.plan, analysis.design, analysis=analysis)
        >>> d = sheet.as_dict()
        >>> d["stitch_count"], d["top_thread_m"]
        (106, 1.044)
        """
        return {
            "name": self.name,
            "size_mm": [round(v, 3) for v in self.size_mm],
            "stitch_count": self.stitch_count,
            "jump_count": self.jump_count,
            "trim_count": self.trim_count,
            "stop_count": self.stop_count,
            "color_change_count": self.color_change_count,
            "machine_format": self.machine_format,
            "setup": list(self.setup),
            "notes": list(self.notes),
            "fabric_mm": [round(v, 1) for v in self.fabric_mm],
            "operating_point": self.operating_point,
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
                    "model": a.model,
                    "adjustments": list(a.adjustments),
                    "segments": list(a.segments),
                }
                for a in self.actuators
            ],
            "findings": list(self.findings),
        }

    def as_text(self) -> str:
        """Human-readable worksheet (plain text, fixed layout).

        Returns
        -------
        str

        Examples
        --------
        >>> from embroact.patterns.design import default_design
        >>> from embroact.predict.analysis import analyse
        >>> analysis = analyse(default_design())
        >>> sheet = worksheet(analysis.plan, analysis.design, analysis=analysis)
        >>> print(sheet.as_text().splitlines()[0])
        PRODUCTION WORKSHEET  paper-zigzag
        """
        t = self.sewing_time_s
        lines = [
            f"PRODUCTION WORKSHEET  {self.name}",
            "",
            f"design size      {self.size_mm[0]:.1f} x {self.size_mm[1]:.1f} mm",
            f"machine file     {self.machine_format or 'none (counts of the stitch plan)'}",
            f"stitches         {self.stitch_count}   jumps {self.jump_count}   trims {self.trim_count}   stops {self.stop_count}"
            f"   colour changes {self.color_change_count}",
            f"sewing time      {int(t // 60)} min {t % 60:04.1f} s at {self.speed_spm:g} stitches/min"
            f" (+ {self.handling_time_s / 60:.0f} min laying tubes)",
            f"top thread       {self.top_thread_mm / 1000:.2f} m",
            f"bobbin thread    {self.bobbin_thread_mm / 1000:.2f} m",
            f"fabric to hoop   {self.fabric_mm[0]:.0f} x {self.fabric_mm[1]:.0f} mm",
            *_operating_lines(self.operating_point),
            *[f"note             {n}" for n in self.notes],
            "",
            "MACHINE SET-UP",
            *[f"  {s}" for s in self.setup],
            "",
            "STOP SEQUENCE",
            *[f"  {s}" for s in self.stops],
        ]
        for a in self.actuators:  # a chain of one: its segment is the actuator, shown as one block
            kind = Chain.shown(a.segments, a.pattern,
                               lambda: f"{len(a.segments)} segments: {', '.join(s['pattern'] for s in a.segments)}")
            lines += ["", f"ACTUATOR {a.name} ({kind})",
                      f"  tube cut length  {a.tube_cut_mm:.0f} mm"
                      f" = {a.path_length_mm:.1f} mm path + 2 x {a.end_margin_mm:g} mm end margin",
                      f"  stitches         {a.stitches} ({a.legs_over_tube} legs over the tube)",
                      f"  thread           top {a.top_thread_mm / 1000:.2f} m, bobbin {a.bobbin_thread_mm / 1000:.2f} m"]
            lines += Chain.shown(
                a.segments,
                lambda: _derived_lines(a.derived) + _model_lines(a.model) + [f"  adjustment: {s}" for s in a.adjustments],
                lambda: [line for k, seg in enumerate(a.segments) for line in _segment_lines(k, seg)])
        lines += ["", "DESIGN-RULE FINDINGS"]
        lines += [f"  {finding_line(f)}" for f in self.findings] or ["  none"]
        return "\n".join(lines) + "\n"


def _with_place(finding: dict) -> dict:
    """``finding`` (``Finding.as_dict()``) with ``"place"``: where it is, as ``embroact check`` prints it."""
    return {**finding, "place": finding_place(finding)}


def operating_point(operation) -> dict | None:
    """The worksheet's operating point of a design's ``OperationSettings`` (None without a target pressure).

    Parameters
    ----------
    operation : OperationSettings or None
        The design's operation limits.

    Returns
    -------
    dict or None

    Examples
    --------
    >>> from embroact.patterns.design import OperationSettings
    >>> operating_point(OperationSettings(target_pressure_kpa=150.0, target_bend_deg=84.5))
    {'target_pressure_kpa': 150.0, 'target_bend_deg': 84.5, 'max_pressure_kpa': 300.0}
    >>> operating_point(OperationSettings()) is None
    True
    """
    if operation is None or operation.target_pressure_kpa is None:
        return None
    return {"target_pressure_kpa": operation.target_pressure_kpa, "target_bend_deg": operation.target_bend_deg,
            "max_pressure_kpa": operation.max_pressure_kpa}


def _operating_lines(point: dict | None) -> list[str]:
    """``operating point  84.5 deg at 150 kPa (...)`` or nothing."""
    if point is None:
        return []
    bend = "" if point["target_bend_deg"] is None else f"{point['target_bend_deg']:g} deg at "
    return [f"operating point  {bend}{point['target_pressure_kpa']:g} kPa (the design's target; the rules judge "
            f"up to {point['max_pressure_kpa']:g} kPa)"]


def _derived_lines(derived: dict, indent: str = "  ") -> list[str]:
    return [f"{indent}{k:<24} {_fmt(v)}" for k, v in derived.items() if k != "name"]


def _model_lines(model: dict | None, indent: str = "  ") -> list[str]:
    """The model block of one actuator: G, P0 with their sources, tube law, tube, notes."""
    if model is None:
        return []
    t = model["tube"]
    return [f"{indent}model G                  {model['g_mpa']:.6g} MPa ({model['g_source']})",
            f"{indent}model P0                 {model['p0_kpa']:.6g} kPa ({model['p0_source']})",
            f"{indent}tube-law P0 at r0        {model['tube_law_p0_kpa']:.6g} kPa (tube law {model['tube_law']})",
            f"{indent}model tube law           {model['tube_law']}",
            f"{indent}model tube               r_f {t['outer_radius_mm']:g} mm, d_f {t['inner_radius_mm']:g} mm, "
            f"G_e {t['g_e_mpa']:g} MPa"] + [f"{indent}model note: {n}" for n in model["notes"]]


def _segment_lines(k: int, seg: dict) -> list[str]:
    """One segment's block: where it lies and its legs, the transition to the next, what was sewn, its model."""
    legs_end = seg["first_leg_mm"] + seg["derived"]["length_mm"]
    lines = [f"  SEGMENT {k} ({seg['pattern']}): path {seg['start_mm']:.2f} to {seg['start_mm'] + seg['length_mm']:.2f} mm,"
             f" legs {seg['first_leg_mm']:.2f} to {legs_end:.2f} mm"]
    if seg["transition_mm"] > 0.0 or seg["join_run_mm"] > 0.0:
        lines.append(f"    transition to segment {k + 1}: {seg['transition_mm']:.2f} mm unbent, thread runs "
                     f"{seg['join_run_mm']:.2f} mm along a rail")
    lines += _derived_lines(seg["derived"], "    ")
    lines += _model_lines(seg["model"], "    ")
    if seg.get("model_error"):
        lines.append(f"    no model: {seg['model_error']}")
    return lines + [f"    adjustment: {s}" for s in seg["adjustments"]]


def _fmt(v) -> str:
    return f"{v:.4g}" if isinstance(v, float) else str(v)


def _legs(plan: StitchPlan, k: int):
    """Needle points of actuator ``k``, the index pairs of consecutive stitches (legs) and
    which legs belong to a placement line (sewn before the tube: they cross nothing)."""
    m = (plan.actuator == k) & (plan.commands == Command.STITCH)
    idx = np.flatnonzero(m)
    # a leg joins two needle points with no trim, stop or jump between them
    legs = np.flatnonzero(np.diff(idx) == 1)
    return plan.xy_mm[idx], legs, plan.roles[idx[legs + 1]] == Role.PLACEMENT


def _actuator_sheet(plan: StitchPlan, k: int, act: ActuatorPlan | None, t_fabric: float, analysed=None) -> ActuatorSheet:
    pts, legs, placement = _legs(plan, k)
    seg = pts[legs + 1] - pts[legs]
    lengths = np.hypot(seg[:, 0], seg[:, 1])
    extra = np.zeros(0)
    if act is not None:
        _, off = act.centerline.project(pts)
        crossing = (np.sign(off[legs]) * np.sign(off[legs + 1]) < 0) & ~placement
        extra = over_tube_extra_mm(lengths[crossing] / 2.0, act.tube.outer_radius_mm)
    n = len(pts)
    tails = 1 + int(np.count_nonzero((plan.actuator == k) & (plan.commands == Command.TRIM)))
    top = float(lengths.sum() + extra.sum() + n * t_fabric + tails * TAIL_MM)
    bobbin = float(lengths.sum() + n * t_fabric)
    if act is None:
        return ActuatorSheet(f"A{k + 1}", "unknown", 0.0, 0.0, 0.0, n, top, bobbin, 0, {})
    if analysed is None:
        from ...predict.analysis import SegmentAnalysis, segment_plans
        from ...predict.derived import derive
        from ...predict.strip import strip_geometry

        parts = [derive(part) for part in segment_plans(act)]
        derived, model = strip_geometry(act.name, parts, act.tube), None
        segments = tuple(SegmentAnalysis(seg, d, None).as_dict() for seg, d in zip(act.segments, parts))
    else:
        derived, model = analysed.derived, (analysed.choice.as_dict() if analysed.choice is not None else None)
        segments = tuple(s.as_dict() for s in analysed.segments)
    path = act.centerline.length_mm
    margin = act.tube.end_margin_mm
    return ActuatorSheet(act.name, derived.pattern, path, margin, path + 2 * margin, n, top, bobbin,
                         len(extra), derived.as_dict(), tuple(act.adjustments), model, segments)


def _side(dx: float, dy: float) -> str:
    """'3.5 mm right, 1.0 mm up' (plan frame, y up) for a vector from the needle."""
    parts = [f"{abs(dx):.1f} mm {'right' if dx > 0 else 'left'}" if abs(dx) >= 0.05 else "",
             f"{abs(dy):.1f} mm {'up' if dy > 0 else 'down'}" if abs(dy) >= 0.05 else ""]
    return ", ".join(p for p in parts if p) or "at the needle"


def _lay_line(a: ActuatorSheet, act: ActuatorPlan | None, needle) -> str:
    """Where the tube goes relative to the waiting needle, which end takes the connector."""
    if act is None:
        return f"lay the tube for actuator {a.name}"
    pts = act.centerline.points_mm
    (x0, y0), (x1, y1) = pts[0], pts[-1]
    d = pts[1] - pts[0]
    heading = math.degrees(math.atan2(d[1], d[0]))
    where = f"; from the needle at ({needle[0]:.1f}, {needle[1]:.1f}) mm its start is {_side(x0 - needle[0], y0 - needle[1])}" \
        if needle is not None else ""
    return (f"lay tube for actuator {a.name} ({a.tube_cut_mm:.0f} mm cut): its axis runs from ({x0:.1f}, {y0:.1f}) "
            f"to ({x1:.1f}, {y1:.1f}) mm, leaving the start at {heading:.0f} deg{where}; "
            f"{a.end_margin_mm:g} mm free at each end, the connector on the start end, the far end sealed; "
            f"tape both ends")


def _placed(plan: StitchPlan) -> set[int]:
    """Actuators with a placement line."""
    return set(plan.actuator[plan.roles == Role.PLACEMENT].tolist())


def _stop_lines(plan: StitchPlan, sheets: dict[int, ActuatorSheet], machine) -> tuple[str, ...]:
    """One line per pause: a tube laid before start or at the pause the machine file makes for it
    (after its placement line, if it has one), or a pause before a placement line."""
    ids = sorted(sheets)
    if machine is None:  # no machine file: the plan's STOP records
        stops = np.flatnonzero(plan.commands == Command.STOP)
        pauses = [tuple(plan.xy_mm[i]) for i in stops]
    else:
        pauses = list(machine.pauses_mm)
    line = [False] * len(pauses) if machine is None else [not tube for tube in machine.tube_pauses()]
    tube_pauses = [p for p, is_line in zip(pauses, line) if not is_line]
    before = len(ids) - len(tube_pauses)  # actuators whose tube is laid before start
    placed = _placed(plan)
    out = [f"before start: {_lay_line(sheets[k], _act(plan, k), None)}; then press start" for k in ids[:before]]
    later = iter(ids[before:])
    for n, (p, is_line) in enumerate(zip(pauses, line)):
        if is_line:
            out.append(f"stop {n + 1}: a colour change before the placement line of the next actuator, not a tube: "
                       "keep the same thread and press start")
            continue
        k = next(later)
        first = (f"the machine sews the placement line of {sheets[k].name} along its tube axis and stops; "
                 "lay the tube over that line: ") if k in placed else ""
        out.append(f"stop {n + 1}: {first}{_lay_line(sheets[k], _act(plan, k), p)}; press start")
    return tuple(out)


def _act(plan: StitchPlan, k: int) -> ActuatorPlan | None:
    return plan.actuators[k] if k < len(plan.actuators) else None


def machine_setup(machine, *, placement: bool = False) -> tuple[str, ...]:
    """Plain-words machine set-up for the machine file ``machine`` (a WriteResult), or none;
    ``placement``: the actuators have placement lines (sewn first, then the machine stops for
    each tube).

    Parameters
    ----------
    machine : WriteResult or None
        The machine file written.
    placement : bool, optional
        The actuators have placement lines.

    Returns
    -------
    tuple of str

    Examples
    --------
    >>> from embroact.export.machine.formats import WriteResult
    >>> res = WriteResult(None, "dst", 0, 10, 0, 3, 6, 0, 0, "double", ((0, 0),) * 3)
    >>> print(machine_setup(res)[1])
    multi-needle machine (automatic needle mode is fine): set all 7 entries of the needle sequence to needle 1; each cord-in is two stop codes in a row, which stops the machine even in automatic mode
    """
    first = ("hoop the fabric without any tube: each actuator's placement line is sewn first (a running stitch "
             "along its tube axis) and the machine then stops for its tube",) if placement else ()
    if machine is None:
        return ("no machine file: counts and stops are those of the stitch plan",) + first
    fmt, pauses = machine.format, machine.pauses
    if fmt in ("dst", "exp"):
        return _stop_code_setup(machine) + first
    if fmt in ("tbf", "u01"):
        return (f"{fmt.upper()} file: needle 1 for every actuator, and the format's own stop code at each of the "
                f"{pauses} cord-in stops: the machine stops there in any needle mode",) + first
    if placement:
        lines = pauses - sum(machine.tube_pauses())
        before = (f", and {lines} before the placement lines of later actuators ({fmt.upper()} has no jump: the "
                  "travel there begins a colour block): press start there") if lines else ""
        return (f"{fmt.upper()} file for a home machine: no stop code; the machine pauses at each of its "
                f"{machine.color_changes} colour changes ({pauses - lines} after the placement lines: keep the same "
                f"thread and lay that actuator's tube there{before})",) + first
    return (f"{fmt.upper()} file for a home machine: no stop code; the machine pauses at each of its "
            f"{machine.color_changes} colour changes (one per actuator after the first): keep the same thread and "
            "lay the next tube there",
            "lay tube 1 before pressing start: the machine starts sewing actuator 1 at once")


def _stop_code_setup(machine) -> tuple[str, ...]:
    """DST/EXP: one code for stop and colour change; what each kind of machine does with the file's."""
    fmt, pauses, codes = machine.format.upper(), machine.pauses, machine.stops
    head = f"{fmt} file with {codes} stop code(s) for {pauses} cord-in stop(s)"
    if codes == 0:
        return (head, "no stop to set up: every tube is laid before start (one needle, needle 1)")
    entries = codes + 1
    later = f"entry {entries}" if entries == 2 else f"entries 2 to {entries}"
    if machine.cord_stop == "double":
        multi = (f"multi-needle machine (automatic needle mode is fine): set all {entries} entries of the needle "
                 "sequence to needle 1; each cord-in is two stop codes in a row, which stops the machine even in "
                 "automatic mode")
        single = (f"single-needle machine: it stops at each of the {codes} stop codes, twice at each of the "
                  f"{pauses} cord-in stops: lay the tube at the first, press start again at the second; keep the "
                  "same thread when it asks for a colour")
    else:
        multi = (f"multi-needle machine: switch to manual needle mode, or set all {entries} entries of the needle "
                 f"sequence to needle 1 and programme a stop at {later}: in automatic mode a single stop code "
                 "only changes needle and sews on (cord_stop = \"double\" stops it anyway)")
        single = (f"single-needle machine: it stops at each of the {pauses} cord-in stops; keep the same thread "
                  "when it asks for a colour")
    return (head, multi, single)


def _start_line(plan: StitchPlan, machine) -> str:
    """Where the machine's start point goes in the hoop (the hoop is centred on the design)."""
    home = (" (a home machine that centres the design in the hoop itself needs no move)"
            if machine is not None and machine.format in COLOR_FORMATS else "")
    ox, oy = plan.origin_mm
    where = (f"; it is the design's ({ox:.1f}, {oy:.1f}) mm (plan frame; check the file against the drawing with "
             f"--origin-mm {ox:g},{-oy + 0.0:g})") if (ox, oy) != (0.0, 0.0) else ""
    return (f"start point (the 'start' cross on the template): {start_from_centre(plan)} of the hoop centre; "
            f"move the needle there first, or the design is sewn off the hoop's centre{home}{where}")


def check_speed_spm(speed_spm: float) -> float:
    """The worksheet's machine speed [stitches/min] if in [1, 2000]; commands call it before any work.

    Parameters
    ----------
    speed_spm : float
        The speed given.

    Returns
    -------
    float

    Examples
    --------
    >>> check_speed_spm(600)
    600.0
    """
    return check_range("speed_spm", speed_spm, low=1.0, low_inclusive=True, high=2000.0, high_inclusive=True)


def worksheet(
    plan: StitchPlan,
    design=None,
    *,
    speed_spm: float = DEFAULT_SPEED_SPM,
    fabric_thickness_mm: float = FABRIC_THICKNESS_MM,
    findings=(),
    machine=None,
    analysis=None,
) -> Worksheet:
    """Build the production worksheet of ``plan``.

    Parameters
    ----------
    plan : StitchPlan
        The design's plan.
    design : optional
        The design the plan came from; its ``name`` (if any) titles the sheet, its
        ``machine`` hoop sizes the fabric (default 200 x 200 mm).
    speed_spm : float
        Machine speed [stitches/min], in [1, 2000] (:func:`check_speed_spm`).
    fabric_thickness_mm : float
        For the per-penetration thread allowance [mm], in [0, 10].
    findings : iterable of Finding or dict
        Design-rule findings to list (``Finding.as_dict()`` is called when present).
    machine : WriteResult, optional
        The machine file written from ``plan``: counts, pauses and set-up are that file's.
    analysis : DesignAnalysis, optional
        The analysis the plan came from: its derived geometry and models (G, P0, tube, tube
        law and their sources) go on the sheet instead of a second derivation.

    Returns
    -------
    Worksheet

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> sheet = worksheet(analysis.plan, analysis.design, analysis=analysis)
    >>> round(sheet.sewing_time_s, 1), sheet.stops[0].split(":")[0]
    (18.6, 'stop 1')
    """
    spm = check_speed_spm(speed_spm)
    t_f = check_range("fabric_thickness_mm", fabric_thickness_mm, low=0.0, high=10.0, low_inclusive=True,
                      high_inclusive=True)
    ids = sorted({int(a) for a in plan.actuator.tolist() if a >= 0})
    analysed = {a.name: a for a in analysis.actuators} if analysis is not None else {}
    sheets = {}
    for k in ids:
        act = plan.actuators[k] if k < len(plan.actuators) else None
        sheets[k] = _actuator_sheet(plan, k, act, t_f, analysed.get(act.name) if act is not None else None)
    needles = plan.xy_mm[plan.commands == Command.STITCH]
    size = (float(np.ptp(needles[:, 0])), float(np.ptp(needles[:, 1]))) if len(needles) else (0.0, 0.0)
    if machine is None:
        n_st, n_j, n_tr, n_sp = (plan.count(c) for c in (Command.STITCH, Command.JUMP, Command.TRIM, Command.STOP))
        n_cc, n_wait = 0, n_sp
    else:
        n_st, n_j, n_tr, n_sp, n_cc = (machine.stitches, machine.jumps, machine.trims, machine.stops,
                                       machine.color_changes)
        n_wait = machine.pauses
    sewing = 60.0 * (n_st + n_j) / spm + n_tr * TRIM_TIME_S + n_wait * STOP_RESTART_S
    name = getattr(design, "name", None) or plan.name
    return Worksheet(
        name=name,
        size_mm=size,
        stitch_count=n_st,
        jump_count=n_j,
        trim_count=n_tr,
        stop_count=n_sp,
        stops=_stop_lines(plan, sheets, machine),
        actuators=tuple(sheets[k] for k in ids),
        top_thread_mm=math.fsum(s.top_thread_mm for s in sheets.values()),
        bobbin_thread_mm=math.fsum(s.bobbin_thread_mm for s in sheets.values()),
        speed_spm=spm,
        sewing_time_s=sewing,
        handling_time_s=len(ids) * LAY_TUBE_S,
        findings=tuple(_with_place(f.as_dict() if hasattr(f, "as_dict") else dict(f)) for f in findings),
        color_change_count=n_cc,
        machine_format=None if machine is None else machine.format,
        setup=machine_setup(machine, placement=bool(_placed(plan))) + (_start_line(plan, machine),),
        notes=() if machine is None else tuple(machine.notes),
        fabric_mm=_fabric_mm(plan, getattr(design, "machine", None)),
        operating_point=operating_point(getattr(design, "operation", None)),
    )


def _fabric_mm(plan: StitchPlan, machine) -> tuple[float, float]:
    """Hoop field plus the clamping border, at least the tubes with their free ends plus the border."""
    w, h = (getattr(machine, "hoop_width_mm", 200.0), getattr(machine, "hoop_height_mm", 200.0))
    spans = [np.zeros((0, 2))]
    for act in plan.actuators:
        pts = act.centerline.points_mm
        m = act.tube.end_margin_mm
        ends = [pts[0] - m * _unit(pts[1] - pts[0]), pts[-1] + m * _unit(pts[-1] - pts[-2])]
        spans.append(np.vstack([pts, ends]))
    allp = np.vstack(spans)
    tw, th = (np.ptp(allp, axis=0) if len(allp) else (0.0, 0.0))
    return (float(max(w, tw)) + 2 * FABRIC_BORDER_MM, float(max(h, th)) + 2 * FABRIC_BORDER_MM)


def _unit(v: np.ndarray) -> np.ndarray:
    n = float(np.hypot(v[0], v[1]))
    return v / n if n > 0 else v
