"""The pictures a build attaches to its machine files: bend chart, side view, 3D shape.

:func:`embroact.export.report.stage.previews_stage` gives the build stage that predicts every
actuator's curve and renders, in memory, with the functions of this module:

================ =========================================================
``bend.svg``     pressure-bend chart of every actuator (:mod:`.chart`)
``shape.svg``    side views at a few pressures (:mod:`.sideview`)
``shape.glb``    3D shape at the shape pressure (:mod:`.mesh`; suffix selectable)
``shape3d.svg``  flat-shaded picture of the 3D shape (:mod:`.meshview`)
``report.json``  all of it as data, with the worksheet and the findings
``report.html``  the same, self-contained, with the stitch preview
================ =========================================================

:func:`~embroact.export.report.stage.render_previews` renders an analysed design (:func:`embroact.predict.analysis.analyse`)
with its curves: every picture and the report use the analysis's derived geometry, model and
memoised curves, so they agree with ``embroact predict`` and the model rules to the last digit.

Examples
--------
>>> from embroact.export.pictures.previews import side_pressures
>>> side_pressures([0.0, 50.0, 100.0, 150.0, 200.0, 250.0, 300.0], [0, 0, 5, 20, 40, 60, 80], count=4)
(0.0, 100.0, 200.0, 300.0)
"""
from __future__ import annotations

import dataclasses
from typing import Mapping, Sequence

import numpy as np

from ...patterns.base.errors import ParameterError
from .chart import Series, bend_chart_svg, chart_scale
from .sideview import SidePanel

__all__ = [
    "OUTPUT_NAMES",
    "side_pressures",
    "shape_theta_deg",
    "shape_state",
    "described_kpa",
    "not_drawn_note",
    "piece_lengths_mm",
    "piece_theta_deg",
    "sleeve_mm",
    "segment_boundaries_mm",
    "model_caption",
    "actuator_series",
    "bend_series",
    "operating_points",
    "breakpoints_kpa",
    "chart_curves",
    "bend_chart",
    "bend_chart_width_px",
    "side_panels",
    "side_panel",
    "actuator_shape",
    "shape_meshes",
    "shape3d_title",
    "check_side_states",
    "curve_bands",
]

#: Output kind -> file name (the mesh's suffix follows ``mesh_suffix``).
OUTPUT_NAMES = {
    "bend": "bend.svg",
    "side": "shape.svg",
    "mesh": "shape",
    "shape3d": "shape3d.svg",
    "json": "report.json",
    "html": "report.html",
}
DEFAULT_SIDE_STATES = 5
#: Width of the bend chart [px], and the least width of its plot box [px] (a wider legend widens the chart).
CHART_WIDTH_PX = 720.0
CHART_MIN_PLOT_PX = 300.0
#: Most series a bend chart draws one by one; past them identical ones are drawn once (:func:`merged_series`).
CHART_MAX_SERIES = 12
MAX_SIDE_STATES = 12


def side_pressures(pressure_kpa, theta_deg, *, count: int = DEFAULT_SIDE_STATES) -> tuple[float, ...]:
    """Up to ``count`` sampled pressures, evenly spread over the range, with a finite angle.

    The nearest sample to each of ``count`` evenly spaced targets is taken (no repeats).

    Parameters
    ----------
    pressure_kpa, theta_deg : array_like (n,)
        A curve's samples [kPa, deg]; NaN angles are skipped.
    count : int, optional
        Most pressures.

    Returns
    -------
    tuple of float
        Ascending [kPa].

    Examples
    --------
    >>> side_pressures([0, 10, 20, 30, 40], [0, 1, 2, float("nan"), 4], count=3)
    (0.0, 20.0, 40.0)
    """
    p = np.asarray(pressure_kpa, dtype=np.float64)[np.isfinite(np.asarray(theta_deg, dtype=np.float64))]
    if len(p) == 0:
        return ()
    targets = np.linspace(p.min(), p.max(), max(1, int(count)))
    return tuple(sorted({float(p[np.argmin(np.abs(p - t))]) for t in targets}))


def _valid(curve) -> np.ndarray:
    """States a view may draw as the actuator's shape (all, for a curve without statuses)."""
    from ...predict.validity import valid_mask

    if getattr(curve, "status", None) is None:
        return np.ones(len(curve.pressure_kpa), dtype=bool)
    return valid_mask(curve)


def shape_theta_deg(curve, pressure_kpa: float | None) -> tuple[float, float]:
    """(pressure, theta) for a drawn shape: the highest sampled pressure whose state the model
    describes (not coiled, kinked or over-stretched: :func:`embroact.predict.validity.valid_mask`),
    or the curve interpolated linearly at ``pressure_kpa`` (which must lie in that valid range).

    Parameters
    ----------
    curve : Curve or StripCurve
        A predicted curve.
    pressure_kpa : float or None
        The pressure wanted [kPa]; None: the highest drawable one.

    Returns
    -------
    tuple of float
        [kPa, deg].

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> curves = analysis.curves()
    >>> [round(v, 2) for v in shape_theta_deg(curves[0], None)], [round(v, 2) for v in shape_theta_deg(curves[0], 150.0)]
    ([300.0, 234.19], [150.0, 53.71])
    """
    p, theta, _ = shape_state(curve, pressure_kpa)
    return p, theta


def _drawable(curve) -> np.ndarray:
    """True where a curve's sample may be drawn as the actuator's shape: a finite angle the model describes."""
    return np.isfinite(np.asarray(curve.theta_deg, dtype=np.float64)) & _valid(curve)


def described_kpa(curve) -> tuple[float, float] | None:
    """The range of pressures [kPa] a shape may be drawn at: from the lowest to the highest sampled
    pressure whose state the model describes (:func:`shape_state` draws only in it; the studio too).

    Parameters
    ----------
    curve : Curve or StripCurve
        A predicted curve.

    Returns
    -------
    tuple of float or None
        (lowest, highest) [kPa]; None when the model describes none of its states.

    Examples
    --------
    >>> from embroact.patterns.design import design_from_dict
    >>> from embroact.predict.analysis import analyse
    >>> narrow = analyse(design_from_dict({"operation": {"max_pressure_kpa": 250.0}, "actuator": [
    ...     {"name": "N", "pattern": "zigzag", "width_mm": 5, "interval_mm": 1, "length_mm": 80}]}))
    >>> described_kpa(narrow.curves()[0])   # it coils past 150 kPa
    (0.0, 150.0)
    """
    p = np.asarray(curve.pressure_kpa, dtype=np.float64)[_drawable(curve)]
    return (float(p.min()), float(p.max())) if len(p) else None


def not_drawn_note(pressures_kpa: Sequence[float], statuses: Sequence[str],
                   described: tuple[float, float] | None) -> str:
    """The one line a view writes where it does not draw an actuator's states: at which pressures, why, and
    the range the model describes (:func:`described_kpa`).

    Parameters
    ----------
    pressures_kpa : sequence of float
        The pressures not drawn [kPa], at least one.
    statuses : sequence of str
        Their states' status names (each named once, in order).
    described : tuple of float or None
        :func:`described_kpa` of the actuator's curve.

    Returns
    -------
    str

    Examples
    --------
    >>> not_drawn_note([167.0], ["COILED"], (0.0, 150.0))
    'not drawn at 167 kPa: COILED; the model describes 0-150 kPa'
    >>> not_drawn_note([160.0, 250.0], ["COILED", "COILED"], None)
    'not drawn at 160-250 kPa: COILED; the model describes none of its states'
    """
    lo, hi = min(pressures_kpa), max(pressures_kpa)
    at = f"{lo:g} kPa" if lo == hi else f"{lo:g}-{hi:g} kPa"
    why = "/".join(dict.fromkeys(statuses)) or "no state"
    rng = f"{described[0]:g}-{described[1]:g} kPa" if described else "none of its states"
    return f"not drawn at {at}: {why}; the model describes {rng}"


def shape_state(curve, pressure_kpa: float | None) -> tuple[float, float, tuple[float, ...]]:
    """As :func:`shape_theta_deg`, with each segment's bend there (``curve.segments``: a segmented
    actuator's whole strip, :class:`~embroact.predict.analysis.StripCurve`, holds one curve per
    segment; a single-pattern actuator's curve is its one segment's).

    A strip's state is drawable only where every segment's is and the strip has not coiled
    (its status); each segment's bend is interpolated over the same drawable pressures, so the
    segments' bends add up to the strip's.

    Parameters
    ----------
    curve : Curve or StripCurve
        A predicted curve.
    pressure_kpa : float or None
        The pressure wanted [kPa]; None: the highest drawable one.

    Returns
    -------
    pressure, theta : float
        [kPa, deg].
    parts : tuple of float
        Each segment's bend there [deg].

    Examples
    --------
    >>> from embroact.patterns.design import design_from_dict
    >>> from embroact.predict.analysis import analyse
    >>> strip = analyse(design_from_dict({"actuator": [{"name": "S", "segment": [
    ...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
    ...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]})).curves([0.0, 250.0])[0]
    >>> p, theta, parts = shape_state(strip, 250.0)
    >>> p, round(theta, 2), [round(t, 2) for t in parts], abs(sum(parts) - theta) < 1e-9
    (250.0, 109.4, [80.86, 28.54], True)
    """
    p = np.asarray(curve.pressure_kpa, dtype=np.float64)
    t = np.asarray(curve.theta_deg, dtype=np.float64)
    ok = _drawable(curve)
    described = described_kpa(curve)
    if described is None:
        raise ParameterError("the curve has no state the model describes to draw a shape from")
    order = np.argsort(p[ok], kind="stable")
    p, t = p[ok][order], t[ok][order]
    parts = [np.asarray(c.theta_deg, dtype=np.float64)[ok][order] for c in curve.segments]
    if pressure_kpa is None:
        return float(p[-1]), float(t[-1]), tuple(float(v[-1]) for v in parts)
    if not described[0] <= pressure_kpa <= described[1]:
        raise ParameterError(f"shape_pressure_kpa must be in [{described[0]:g}, {described[1]:g}] (the predicted "
                             f"range the model describes), got {pressure_kpa:g}")
    at = float(pressure_kpa)
    return at, float(np.interp(at, p, t)), tuple(float(np.interp(at, p, v)) for v in parts)


def piece_lengths_mm(act) -> tuple[float, ...]:
    """The length of each of ``act.bend_pieces()`` [mm]: the chain of arcs, transitions unbent.

    Parameters
    ----------
    act : ActuatorAnalysis
        An analysed actuator.

    Returns
    -------
    tuple of float

    Examples
    --------
    >>> from embroact.patterns.design import design_from_dict
    >>> from embroact.predict.analysis import analyse
    >>> seg = analyse(design_from_dict({"actuator": [{"name": "S", "segment": [
    ...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
    ...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]}))
    >>> act = seg.actuators[0]
    >>> piece_lengths_mm(act)
    (50.0, 50.0)
    """
    return tuple(length for length, _ in act.bend_pieces())


def piece_theta_deg(act, segment_theta_deg: Sequence[float]) -> tuple[float, ...]:
    """The bend of each of ``act.bend_pieces()`` given each segment's bend [deg] (0 for the unbent pieces).

    Parameters
    ----------
    act : ActuatorAnalysis
        An analysed actuator.
    segment_theta_deg : sequence of float
        Each segment's bend [deg].

    Returns
    -------
    tuple of float

    Examples
    --------
    >>> from embroact.patterns.design import design_from_dict
    >>> from embroact.predict.analysis import analyse
    >>> seg = analyse(design_from_dict({"actuator": [{"name": "S", "segment": [
    ...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
    ...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]}))
    >>> act = seg.actuators[0]
    >>> piece_theta_deg(act, [30.0, 10.0])
    (30.0, 10.0)
    """
    return tuple(float(segment_theta_deg[k]) if k >= 0 else 0.0 for _, k in act.bend_pieces())


def segment_boundaries_mm(act) -> tuple[float, ...]:
    """Arc lengths where one segment gives way to the next [mm]: the middle of the unbent transition
    between one segment's legs and the next's (``()`` for a chain of one).

    Parameters
    ----------
    act : ActuatorAnalysis
        An analysed actuator.

    Returns
    -------
    tuple of float

    Examples
    --------
    >>> from embroact.patterns.design import design_from_dict
    >>> from embroact.predict.analysis import analyse
    >>> seg = analyse(design_from_dict({"actuator": [{"name": "S", "segment": [
    ...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
    ...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]}))
    >>> act = seg.actuators[0]
    >>> segment_boundaries_mm(act)
    (50.0,)
    """
    segs = act.segments
    return tuple((a.plan.first_leg_mm + a.derived.length_mm + b.plan.first_leg_mm) / 2.0
                 for a, b in zip(segs, segs[1:]))


def sleeve_mm(act) -> tuple[float, float]:
    """(width w, sleeve radius r0) [mm] a view draws an actuator with: a segmented one's widest
    segment and largest r0 (the views draw one tube and one pair of rails per actuator).

    Parameters
    ----------
    act : ActuatorAnalysis
        An analysed actuator.

    Returns
    -------
    tuple of float

    Examples
    --------
    >>> from embroact.patterns.design import design_from_dict
    >>> from embroact.predict.analysis import analyse
    >>> seg = analyse(design_from_dict({"actuator": [{"name": "S", "segment": [
    ...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
    ...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]}))
    >>> act = seg.actuators[0]
    >>> [round(v, 4) for v in sleeve_mm(act)]
    [9.0, 3.1539]
    """
    parts = [s.derived for s in act.segments]
    return max(d.width_mm for d in parts), max(d.r0_mm for d in parts)


def _short_source(source: str, choice) -> str:
    """'given', 'geometry', or the calibration set's name (flagged when extrapolated)."""
    if source.startswith("calibration") and choice.calibration is not None:
        cal = choice.calibration
        return cal.name + (" extrapolated" if cal.extrapolated else "")
    return source.split(" ", 1)[0]


def _label(name: str, d, choice) -> str:
    """Legend of one actuator (or segment): name, width, and the model's G and P0 with where they came from."""
    if choice is None:
        return f"{name} ({d.pattern}, w {d.width_mm:.1f} mm; no model)"
    m, c = choice.model, choice
    g_src, p0_src = _short_source(c.g_source, c), _short_source(c.p0_source, c)
    values = (f"G {m.g_mpa:.4g} MPa, P0 {m.p0_kpa:.4g} kPa ({g_src})" if g_src == p0_src
              else f"G {m.g_mpa:.4g} MPa ({g_src}), P0 {m.p0_kpa:.4g} kPa ({p0_src})")
    return f"{name}, w {d.width_mm:.1f} mm: {values}"


def model_caption(analysis) -> str:
    """The tube law(s) and tube(s) of the models, for the chart title (the legend names G and P0).

    Parameters
    ----------
    analysis : DesignAnalysis
        The analysed design.

    Returns
    -------
    str
        Empty when no actuator has a model.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> model_caption(analyse(default_design()))
    'paper law, r_f 1.5, d_f 1 mm, G_e 0.13 MPa'
    """
    parts: list[str] = []
    for choice in (p.choice for act in analysis.actuators for p in act.segments):
        if choice is None:
            continue
        m = choice.model
        text = f"{m.tube_law} law, r_f {m.outer_radius_mm:g}, d_f {m.inner_radius_mm:g} mm, G_e {m.g_e_mpa:g} MPa"
        if text not in parts:
            parts.append(text)
    return "; ".join(parts)


def actuator_series(act, curve, measured: tuple | None = None, band=None,
                    operating_point: tuple[float, float] | None = None) -> list[Series]:
    """Chart series of one analysed actuator and its curve.

    The whole strip (the sum of its segments' bends, which measurements of the tip angle are
    compared with) and then, for a chain of more than one, one series per segment, each with its
    own pattern, G and P0 (a chain of one: its segment is the whole strip).

    Parameters
    ----------
    act : ActuatorAnalysis
        The actuator.
    curve : Curve or StripCurve
        Its curve.
    measured : tuple or None, optional
        (pressure_kpa, theta_deg) of measured points.
    band : Band or None, optional
        The 1-sigma band of its fitted calibration at the curve's pressures
        (:meth:`~embroact.predict.analysis.DesignAnalysis.bands`).
    operating_point : (float, float) or None, optional
        The design's target (pressure_kpa, theta_deg) marked on the curve (:func:`operating_points`).

    Returns
    -------
    list of Series

    Examples
    --------
    >>> from embroact.patterns.design import design_from_dict
    >>> from embroact.predict.analysis import analyse
    >>> seg = analyse(design_from_dict({"actuator": [{"name": "S", "segment": [
    ...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
    ...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]}))
    >>> act = seg.actuators[0]
    >>> [s.label.split(":")[0] for s in actuator_series(act, seg.curves()[0])]
    ['S whole strip', 'S segment 0 (zigzag), w 7.0 mm', 'S segment 1 (zigzag), w 9.0 mm']
    """
    segs = act.segments
    whole = segs.one_or_all(lambda: _label(act.name, act.derived, act.choice),
                            lambda: f"{act.name} whole strip: sum of its {len(segs)} segments")
    return [Series.from_curve(curve, label=whole, p0_kpa=act.choice.model.p0_kpa if act.choice is not None else None,
                              measured=measured, band=band, operating_point=operating_point)] + [
        Series.from_curve(c, label=_label(f"{segs.part_name(act.name, k)} ({seg.derived.pattern})", seg.derived,
                                          seg.choice), p0_kpa=seg.model.p0_kpa)
        for k, (seg, c) in enumerate(zip(segs.listed, curve.segments))]


def operating_points(analysis) -> tuple:
    """Each actuator's operating point (pressure_kpa, theta_deg) from the design's ``[operation]``, or None each.

    The pressure is ``target_pressure_kpa``; the bend is ``target_bend_deg`` where the design
    names one (a target-bend design: the mark shows the target against the curve), else the
    actuator's predicted bend there (a target-shape design). None for every actuator when the design has no
    target pressure, and for one without a bend there.

    Parameters
    ----------
    analysis : DesignAnalysis
        The analysed design.

    Returns
    -------
    tuple
        One (pressure_kpa, theta_deg) or None per actuator.

    Examples
    --------
    >>> import dataclasses
    >>> from embroact.patterns.design import OperationSettings, default_design
    >>> from embroact.predict.analysis import analyse
    >>> d = default_design()
    >>> operating_points(analyse(d))
    (None,)
    >>> d = dataclasses.replace(d, operation=OperationSettings(target_pressure_kpa=150.0, target_bend_deg=90.0))
    >>> operating_points(analyse(d))
    ((150.0, 90.0),)
    """
    op = analysis.design.operation
    if op.target_pressure_kpa is None:
        return (None,) * len(analysis.actuators)
    p = float(op.target_pressure_kpa)
    if op.target_bend_deg is not None:
        return ((p, float(op.target_bend_deg)),) * len(analysis.actuators)
    curves = analysis.curves([p])
    return tuple((p, float(c.theta_deg[0])) if np.isfinite(c.theta_deg[0]) else None for c in curves)


def curve_bands(analysis, curves) -> tuple:
    """The 1-sigma band of each actuator at its curve's pressures, None where its calibration has no
    covariance (:meth:`~embroact.predict.analysis.DesignAnalysis.bands`) or the curves' pressures differ.

    Parameters
    ----------
    analysis : DesignAnalysis
        The analysed design.
    curves : sequence of Curve
        One per actuator.

    Returns
    -------
    tuple of Band or None

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> curves = analysis.curves()
    >>> curve_bands(analysis, curves)  # the paper's set records no covariance
    (None,)
    """
    grids = {tuple(float(p) for p in c.pressure_kpa) for c in curves}
    if len(grids) != 1:
        return (None,) * len(curves)
    return analysis.bands(grids.pop())


def bend_series(analysis, curves, measured: Mapping[str, tuple] | None = None, bands=None) -> list[Series]:
    """Chart series of every actuator (:func:`actuator_series`).

    Parameters
    ----------
    analysis : DesignAnalysis
        The analysed design.
    curves : sequence of Curve
        One per actuator.
    measured : mapping, optional
        Actuator name -> (pressure_kpa, theta_deg) of measured points.
    bands : sequence, optional
        One band (or None) per actuator (default :func:`curve_bands`).

    Returns
    -------
    list of Series

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> curves = analysis.curves()
    >>> [s.label for s in bend_series(analysis, curves)]
    ['A1, w 7.0 mm: G 2.7 MPa, P0 85 kPa (paper-2025)']
    """
    measured = dict(measured or {})
    bands = curve_bands(analysis, curves) if bands is None else bands
    series = [s for a, c, b, op in zip(analysis.actuators, curves, bands, operating_points(analysis))
              for s in actuator_series(a, c, measured.get(a.name), b, op)]
    return series if len(series) <= CHART_MAX_SERIES else merged_series(series)


def merged_series(series: Sequence[Series]) -> list[Series]:
    """Series with the same curve, status, P0, measurements, band and operating point as one, labelled by the
    first with how many more it stands for (in the order they first appear): a chart of many identical actuators
    draws one curve and one status strip, not one each.

    Parameters
    ----------
    series : sequence of Series

    Returns
    -------
    list of Series

    Examples
    --------
    >>> same = [Series(f"A{k}", [0.0, 100.0], [0.0, 20.0], p0_kpa=50.0) for k in range(3)]
    >>> [s.label for s in merged_series(same + [Series("B", [0.0, 100.0], [0.0, 30.0])])]
    ['A0 (and 2 identical)', 'B']
    """
    groups: dict[tuple, list[Series]] = {}
    for s in series:
        values = (getattr(s, f.name) for f in dataclasses.fields(s) if f.name != "label")
        key = tuple(v.tobytes() if isinstance(v, np.ndarray) else v for v in values)
        groups.setdefault(key, []).append(s)
    return [g[0] if len(g) == 1 else dataclasses.replace(g[0], label=f"{g[0].label} (and {len(g) - 1} identical)")
            for g in groups.values()]


def breakpoints_kpa(analysis) -> tuple[float, ...]:
    """Where a curve of the design changes branch: the transition pressure P0 of every actuator and
    segment with a model, ascending, each once.

    Parameters
    ----------
    analysis : DesignAnalysis
        The analysed design.

    Returns
    -------
    tuple of float
        [kPa].

    Examples
    --------
    >>> from embroact.patterns.design import design_from_dict
    >>> from embroact.predict.analysis import analyse
    >>> seg = analyse(design_from_dict({"actuator": [{"name": "S", "segment": [
    ...     {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 50},
    ...     {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 50}]}]}))
    >>> act = seg.actuators[0]
    >>> breakpoints_kpa(seg)
    (85.0, 180.0)
    """
    models = [p.model for a in analysis.actuators for p in a.segments if p.choice is not None]
    return tuple(sorted({float(m.p0_kpa) for m in models}))


def chart_curves(analysis, curves) -> tuple:
    """``curves`` at their own pressures and at every breakpoint among them (:func:`breakpoints_kpa`).

    Sampled there, each drawn curve's inflation part ends exactly at its P0 and its bending branch
    starts there, instead of a chord from the last inflation sample to the first bending one.

    Parameters
    ----------
    analysis : DesignAnalysis
        The analysed design.
    curves : sequence of Curve
        One per actuator, at one set of pressures.

    Returns
    -------
    tuple of Curve

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> curves = analysis.curves()
    >>> drawn = chart_curves(analysis, curves)
    >>> len(curves[0].pressure_kpa), len(drawn[0].pressure_kpa), 85.0 in drawn[0].pressure_kpa
    (31, 32, True)
    """
    grids = {tuple(float(p) for p in c.pressure_kpa) for c in curves}
    if len(grids) != 1:
        return tuple(curves)
    grid = grids.pop()
    extra = [p for p in breakpoints_kpa(analysis) if grid[0] < p < grid[-1] and p not in grid]
    return tuple(curves) if not extra else analysis.curves(sorted(grid + tuple(extra)))


def bend_chart(analysis, curves, measured: Mapping[str, tuple] | None = None, bands=None) -> str:
    """The bend chart SVG of an analysed design: the legend gives each actuator's G and P0 and where they
    came from, the title the tube law and tube; a fitted calibration's 1-sigma band is shaded.

    The curves are drawn at their pressures and breakpoints (:func:`chart_curves`); ``bands``, when
    given for other pressures, are taken again at those.

    Parameters
    ----------
    analysis : DesignAnalysis
        The analysed design.
    curves : sequence of Curve
        One per actuator.
    measured : mapping, optional
        Actuator name -> (pressure_kpa, theta_deg) of measured points.
    bands : sequence, optional
        One band (or None) per actuator.

    Returns
    -------
    str
        SVG.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> curves = analysis.curves()
    >>> svg = bend_chart(analysis, curves)
    >>> svg.startswith("<svg"), "paper-zigzag: predicted bend" in svg
    (True, True)
    """
    caption = model_caption(analysis)
    title = f"{analysis.plan.name}: predicted bend" + (f"; tube {caption}" if caption else "")
    drawn = chart_curves(analysis, curves)
    if len(drawn[0].pressure_kpa) != len(curves[0].pressure_kpa):  # bands at the new pressures
        bands = None
    series = bend_series(analysis, drawn, measured, bands)
    return bend_chart_svg(series, title=title, width_px=bend_chart_width_px(series))


def bend_chart_width_px(series) -> float:
    """Width [px] of :func:`bend_chart` for these series: long legends (a segment's pattern, G and P0)
    widen the chart rather than narrow its plot below ``CHART_MIN_PLOT_PX``.

    Parameters
    ----------
    series : sequence of Series
        The chart's series.

    Returns
    -------
    float

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> curves = analysis.curves()
    >>> bend_chart_width_px(bend_series(analysis, curves))
    720.0
    """
    return CHART_WIDTH_PX + max(0.0, CHART_MIN_PLOT_PX - chart_scale(series, width_px=CHART_WIDTH_PX).width_px)


def side_panels(analysis, curves, *, count: int = DEFAULT_SIDE_STATES) -> list[SidePanel]:
    """Side-view panels, one per actuator, at up to ``count`` of the curve's pressures.

    Parameters
    ----------
    analysis : DesignAnalysis
        The analysed design.
    curves : sequence of Curve
        One per actuator.
    count : int, optional
        Most states per panel.

    Returns
    -------
    list of SidePanel

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> curves = analysis.curves()
    >>> panel, = side_panels(analysis, curves, count=3)
    >>> panel.label, panel.pressure_kpa, [round(t, 2) for t in panel.theta_deg], panel.note
    ('A1', (0.0, 150.0, 300.0), [0.0, 53.71, 234.19], '')

    An actuator whose states at the pressures asked are past a validity limit gets an empty panel
    and a note saying why (:func:`not_drawn_note`):

    >>> from embroact.patterns.design import design_from_dict
    >>> narrow = analyse(design_from_dict({"operation": {"max_pressure_kpa": 250.0}, "actuator": [
    ...     {"name": "N", "pattern": "zigzag", "width_mm": 5, "interval_mm": 1, "length_mm": 80}]}))
    >>> panel, = side_panels(narrow, narrow.curves([167.0]))
    >>> panel.pressure_kpa, panel.note
    ((), 'not drawn at 167 kPa: COILED; the model describes 0-150 kPa')
    """
    panels = []
    for a, c, whole in zip(analysis.actuators, curves, _default_curves(analysis, curves)):
        ok = _drawable(c)
        picks = side_pressures(c.pressure_kpa, np.where(ok, c.theta_deg, np.nan), count=count)
        panels.append(side_panel(a, [shape_state(c, p) for p in picks], note=_left_out(c, ok, whole)))
    return panels


def _left_out(curve, ok: np.ndarray, whole) -> str:
    """The note of a curve's samples not drawn (``~ok``): why, and where the model holds (``whole``'s range when
    the curve has no drawable sample); "" when every sample is drawn."""
    if ok.all():
        return ""
    from ...predict.status import status_names

    names = status_names(np.asarray(curve.status)[~ok]) if getattr(curve, "status", None) is not None else []
    return not_drawn_note(np.asarray(curve.pressure_kpa, dtype=np.float64)[~ok].tolist(), names,
                          described_kpa(curve if ok.any() else whole))


def _default_curves(analysis, curves) -> tuple:
    """The analysis's curves over its own pressures where one of ``curves`` has no drawable state (the range
    its note gives, as ``embroact preview mesh`` and the studio judge a pressure), else ``curves``."""
    return analysis.curves() if any(not _drawable(c).any() for c in curves) else tuple(curves)


def side_panel(act, states: Sequence[tuple[float, float, Sequence[float]]], *, note: str = "") -> SidePanel:
    """The side-view panel of one analysed actuator in ``states``, for a chain of one segment as for five.

    The fabric line is the chain of :meth:`~embroact.predict.analysis.ActuatorAnalysis.bend_pieces`:
    the unbent lead-in, each segment's legs bent by its own angle with the unbent transitions
    between them, and the unbent tail; the tube is drawn with the largest r0 (:func:`sleeve_mm`)
    and the segment boundaries are marked (:func:`segment_boundaries_mm`; none in a chain of one).

    Parameters
    ----------
    act : ActuatorAnalysis
        An analysed actuator.
    states : sequence of (float, float, sequence of float)
        Per state drawn its pressure [kPa], the whole strip's bend [deg] and each segment's bend [deg],
        as :func:`shape_state` gives them.
    note : str, optional
        The panel's one-line note (:func:`not_drawn_note`: the states it leaves out and why).

    Returns
    -------
    SidePanel

    Examples
    --------
    >>> from embroact.patterns.design import design_from_dict
    >>> from embroact.predict.analysis import analyse
    >>> act = analyse(design_from_dict({"actuator": [{"name": "A1", "pattern": "cross", "width_mm": 7,
    ...     "interval_mm": 1.4, "angle_deg": 45, "length_mm": 100}]})).actuators[0]   # legs 0.3 mm in from each end
    >>> panel = side_panel(act, [(0.0, 0.0, (0.0,)), (200.0, -40.0, (-40.0,))])
    >>> panel.label, [round(v, 3) for v in panel.segment_lengths_mm], panel.segment_theta_deg[1]
    ('A1', [0.3, 99.4, 0.3], (0.0, -40.0, 0.0))
    """
    lengths = piece_lengths_mm(act)
    return SidePanel(act.segments.one_or_all(act.name, lambda: f"{act.name} ({len(act.segments)} segments)"),
                     length_mm=sum(lengths), r0_mm=sleeve_mm(act)[1], pressure_kpa=tuple(p for p, _, _ in states),
                     theta_deg=tuple(t for _, t, _ in states), segment_lengths_mm=lengths,
                     segment_theta_deg=tuple(piece_theta_deg(act, parts) for _, _, parts in states),
                     marks_mm=segment_boundaries_mm(act), note=note)


def shape_meshes(analysis, curves, *, pressure_kpa: float | None = None, tolerance_mm: float | None = None):
    """3D shape per actuator at ``pressure_kpa`` (default the highest predicted).

    Parameters
    ----------
    analysis : DesignAnalysis
        The analysed design.
    curves : sequence of Curve
        One per actuator.
    pressure_kpa : float or None, optional
        The pressure of the shapes [kPa].
    tolerance_mm : float or None, optional
        The meshes' chordal tolerance [mm]; None: the default, coarsened where the picture allows.

    Returns
    -------
    shapes : list of ShapeMesh
    pressures : dict of str to float
        Each actuator's shape's pressure [kPa].

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> analysis = analyse(default_design())
    >>> curves = analysis.curves()
    >>> shapes, pressures = shape_meshes(analysis, curves)
    >>> [s.name for s in shapes], pressures
    (['A1'], {'A1': 300.0})
    """
    from .mesh import DEFAULT_CHORD_TOLERANCE_MM, MovedMeshes

    tol = DEFAULT_CHORD_TOLERANCE_MM if tolerance_mm is None else tolerance_mm
    shapes, pressures, meshes = [], {}, MovedMeshes()  # identical actuators side by side meshed once
    for a, c in zip(analysis.actuators, curves):
        p, theta, parts = shape_state(c, pressure_kpa)
        shapes.append(actuator_shape(a, theta, parts, tolerance_mm=tol, coarsen=tolerance_mm is None, meshes=meshes))
        pressures[a.name] = p
    return shapes, pressures


def actuator_shape(act, theta_deg: float, segment_theta_deg: Sequence[float], *, meshes=None, **options):
    """The 3D shape of one analysed actuator: each segment's legs bent by its own bend, the lead-in, the
    transitions and the tail unbent (:meth:`~embroact.predict.analysis.ActuatorAnalysis.bend_pieces`, for a
    chain of one as for five), on its path and with the sleeve a view draws it with (:func:`sleeve_mm`).

    Parameters
    ----------
    act : ActuatorAnalysis
        An analysed actuator.
    theta_deg : float
        Its whole strip's bend [deg].
    segment_theta_deg : sequence of float
        Each segment's bend [deg] (adding up to ``theta_deg``).
    meshes : MovedMeshes, optional
        Where the mesh is made (:class:`~embroact.export.pictures.mesh.MovedMeshes`: an identical actuator's
        moved); default a fresh one.
    **options
        Further keywords of :func:`~embroact.export.pictures.mesh.actuator_mesh` (``tolerance_mm``, ``measure``...).

    Returns
    -------
    ShapeMesh

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> from embroact.predict.analysis import analyse
    >>> act = analyse(default_design()).actuators[0]
    >>> shape = actuator_shape(act, 90.0, [90.0], measure=False)
    >>> shape.name, shape.theta_deg
    ('A1', 90.0)
    """
    from .mesh import MovedMeshes, PlanarPath

    width, r0 = sleeve_mm(act)
    return (meshes or MovedMeshes()).mesh(
        PlanarPath.from_centerline(act.plan.centerline), theta_deg, width_mm=width, r0_mm=r0, name=act.name,
        segment_lengths_mm=piece_lengths_mm(act), segment_theta_deg=piece_theta_deg(act, segment_theta_deg), **options)


def shape3d_title(pressures: Mapping[str, float]) -> str:
    """Title of the 3D picture: the pressure of each actuator's shape (one pressure when they agree).

    Parameters
    ----------
    pressures : mapping of str to float
        Each actuator's shape's pressure [kPa].

    Returns
    -------
    str

    Examples
    --------
    >>> shape3d_title({"A1": 150.0, "A2": 87.5})
    '3D shape: A1 at 150 kPa, A2 at 87.5 kPa'
    >>> shape3d_title({"A1": 300.0})
    '3D shape at 300 kPa'
    """
    if len(set(pressures.values())) == 1:
        return f"3D shape at {next(iter(pressures.values())):g} kPa"
    return "3D shape: " + ", ".join(f"{n} at {p:g} kPa" for n, p in pressures.items())


def check_side_states(value, *, name: str = "side_states") -> int:
    """``value`` if it is an integer in [1, :data:`MAX_SIDE_STATES`], else :class:`ParameterError` naming ``name``.

    Parameters
    ----------
    value : object
        The count given.
    name : str, optional
        The parameter's name for the message.

    Returns
    -------
    int

    Examples
    --------
    >>> check_side_states(5)
    5
    """
    if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= MAX_SIDE_STATES:
        raise ParameterError(f"{name} must be an integer in [1, {MAX_SIDE_STATES}], got {value!r}")
    return value
