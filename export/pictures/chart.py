"""Pressure-bend chart: bend angle [deg] against pressure [kPa], drawn with :mod:`.svgdoc`.

One or many designs on one chart; each design's transition pressure P0 is a dashed
vertical mark, the model's status regions are shaded (a full-height band for a
single design, a thin ribbon per design under the plot for several), measured points
are overlaid as open circles, axes carry 1-2-5 ticks.  The data-to-SVG mapping is
the small frozen :class:`Scale` value, so callers and tests can locate any point.

Valid and invalid states: only the points whose angle is a state the model describes
(:data:`~embroact.predict.status.MODEL_STATES`: inflation, bending, lock-up, unstable)
are drawn as the curve and set the angle axis.  Past a validity limit (coiled, kinked,
over-stretched) the formula's angle is drawn as a thin dashed line clipped to the plot
box and its pressures are shaded as "beyond validity"; fill values (outside the model,
method failed) are not drawn.  A series with a band (``theta_low_deg``,
``theta_high_deg``, e.g. the 1-sigma band of a fitted calibration) gets it shaded in
its colour over the valid points::

     angle [deg]
       |             _____ locked
       |           /
       |  infl.  /  bending
       0 -------'.................> pressure [kPa]
                 P0

Examples
--------
>>> from embroact.export.pictures.chart import Series, bend_chart_svg, chart_scale, nice_ticks
>>> nice_ticks(0.0, 290.0)
(0.0, 50.0, 100.0, 150.0, 200.0, 250.0, 300.0)
>>> s = Series("w = 7 mm", [0, 100, 200], [0.0, 20.0, 60.0],
...            status=("inflation", "bending", "bending"), p0_kpa=84.5)
>>> sc = chart_scale([s])
>>> sc.x_px(0.0) == sc.left_px, sc.y_px(0.0) == sc.top_px + sc.height_px
(True, True)
>>> bend_chart_svg([s]).startswith('<svg')
True
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ...patterns.base.arrays import frozen_array
from ...patterns.base.errors import ParameterError
from .labels import Box, Placer
from .titles import fit_title, text_width_px

__all__ = ["STATUS_STYLE", "DRAWN_STATES", "BEYOND_VALIDITY", "Scale", "Series", "nice_ticks", "chart_scale",
           "bend_chart_svg"]

#: status name -> (fill colour, legend text).  Names are the lower-case members of
#: ``embroact.predict.status.Status``.
STATUS_STYLE: dict[str, tuple[str, str]] = {
    "inflation": ("#dbe9f6", "inflation (no bend)"),
    "bending": ("#e3f2df", "bending"),
    "locked": ("#fde7c8", "lock-up"),
    "unstable": ("#f9d4d4", "unstable"),
    "out_of_domain": ("#e6e6e6", "outside model"),
    "failed": ("#cccccc", "no answer (method failed)"),
    "coiled": ("#f2c4e0", "beyond validity: coiled"),
    "kinked": ("#e9c8f5", "beyond validity: kinked"),
    "overstretched": ("#f7d9c4", "beyond validity: over-stretched"),
}
#: Statuses whose angle is a state the model describes (the lower-case names of
#: ``embroact.predict.status.MODEL_STATES``): drawn as the curve, they set the angle axis.
DRAWN_STATES = frozenset(("inflation", "bending", "locked", "unstable"))
#: Statuses past a validity limit: the formula's angle is drawn dashed and clipped.
BEYOND_VALIDITY = frozenset(("coiled", "kinked", "overstretched"))
_BAND_OPACITY = 0.22

#: Line colours of successive series (colour-blind safe, Okabe-Ito).
PALETTE = ("#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#000000")

_DECIMALS = 2  # SVG coordinates are rounded to 0.01 user unit: stable bytes, small files
_TICK_STEPS = (1.0, 2.0, 5.0, 10.0, 20.0, 50.0)  # two decades: rounding can push past the first
_FONT = "font-family:Helvetica,Arial,sans-serif"
_TITLE_RIGHT_PX = 10.0  # the title's margin to the chart's right edge
_RIBBON_PX = 9.0
_RIBBON_FONT_PX = 8.0
_P0_FONT_PX = 10.0
_RIGHT_MIN_PX = 16.0
_LEGEND_ROW_PX = 18.0
_LEGEND_FONT_PX = 11.0
_KEY_PX = 22.0


def _frozen(values) -> np.ndarray:
    return frozen_array(values).reshape(-1)


def _scalar(a: np.ndarray):
    """Plain float for 0-d results, the array otherwise."""
    return float(a) if np.ndim(a) == 0 else a


def _status_names(status) -> tuple[str, ...]:
    """Status values (strings, Status members or their integer values) as lower-case names."""
    out = []
    for v in status:
        if isinstance(v, str):
            name = v.lower()
        elif hasattr(v, "name"):
            name = v.name.lower()
        else:
            from ...predict.status import Status  # lazy: only integer codes need the enum

            name = Status(int(v)).name.lower()
        if name not in STATUS_STYLE:
            raise ParameterError(f"status must be one of {', '.join(STATUS_STYLE)}, got {v!r}")
        out.append(name)
    return tuple(out)


@dataclass(frozen=True, slots=True)
class Series:
    """One design's predicted curve (and optional measurements) for the chart.

    Parameters
    ----------
    label : str
        Legend text.
    pressure_kpa, theta_deg : array-like
        Curve samples [kPa], [deg]; NaN angles (no answer) break the line.
    status : sequence, optional
        Per-sample status: names (``"bending"``), ``Status`` members or their codes.
    p0_kpa : float, optional
        Transition pressure to mark [kPa].
    measured_pressure_kpa, measured_theta_deg : array-like, optional
        Measured points to overlay [kPa], [deg].
    theta_low_deg, theta_high_deg : array-like, optional
        An uncertainty band, one value per pressure [deg] (given together).
    operating_point : (float, float), optional
        The design's operating point (pressure [kPa], bend [deg]): the target a design was made
        for, drawn as a diamond.

    Examples
    --------
    >>> s = Series("A1", [0.0, 100.0, 200.0], [0.0, 11.5, 102.9], status=("INFLATION", "BENDING", "COILED"), p0_kpa=85.0)
    >>> s.status, s.drawn().tolist()
    (('inflation', 'bending', 'coiled'), [True, True, False])
    """

    label: str
    pressure_kpa: np.ndarray
    theta_deg: np.ndarray
    status: tuple[str, ...] | None = None
    p0_kpa: float | None = None
    measured_pressure_kpa: np.ndarray | None = None
    measured_theta_deg: np.ndarray | None = None
    theta_low_deg: np.ndarray | None = None
    theta_high_deg: np.ndarray | None = None
    operating_point: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        p = _frozen(self.pressure_kpa)
        t = _frozen(self.theta_deg)
        if len(p) != len(t):
            raise ParameterError(f"theta_deg must have one value per pressure ({len(p)}), got {len(t)}")
        if not np.all(np.isfinite(p)):
            raise ParameterError("pressure_kpa must be finite numbers")
        object.__setattr__(self, "pressure_kpa", p)
        object.__setattr__(self, "theta_deg", t)
        if self.status is not None:
            names = _status_names(self.status)
            if len(names) != len(p):
                raise ParameterError(f"status must have one value per pressure ({len(p)}), got {len(names)}")
            object.__setattr__(self, "status", names)
        mp, mt = self.measured_pressure_kpa, self.measured_theta_deg
        if (mp is None) != (mt is None):
            raise ParameterError("measured_pressure_kpa and measured_theta_deg must be given together")
        if mp is not None:
            mp, mt = _frozen(mp), _frozen(mt)
            if len(mp) != len(mt):
                raise ParameterError(
                    f"measured_theta_deg must have one value per measured pressure ({len(mp)}), got {len(mt)}"
                )
            object.__setattr__(self, "measured_pressure_kpa", mp)
            object.__setattr__(self, "measured_theta_deg", mt)
        lo, hi = self.theta_low_deg, self.theta_high_deg
        if (lo is None) != (hi is None):
            raise ParameterError("theta_low_deg and theta_high_deg must be given together")
        if lo is not None:
            lo, hi = _frozen(lo), _frozen(hi)
            if len(lo) != len(p) or len(hi) != len(p):
                raise ParameterError(f"theta_low_deg and theta_high_deg must have one value per pressure ({len(p)}), "
                                     f"got {len(lo)} and {len(hi)}")
            object.__setattr__(self, "theta_low_deg", lo)
            object.__setattr__(self, "theta_high_deg", hi)
        if self.operating_point is not None:
            point = tuple(float(v) for v in self.operating_point)
            if len(point) != 2 or not all(math.isfinite(v) for v in point):
                raise ParameterError(f"operating_point must be two finite numbers (pressure_kpa, theta_deg), got "
                                     f"{self.operating_point!r:.60}")
            object.__setattr__(self, "operating_point", point)

    @classmethod
    def from_curve(cls, curve, *, label: str, p0_kpa: float | None = None, measured=None, band=None,
                   operating_point: tuple[float, float] | None = None) -> "Series":
        """Series from a ``predict`` curve (``pressure_kpa``, ``theta_deg``, ``status``).

        ``measured`` is an optional pair (pressure_kpa, theta_deg) of arrays; ``band`` an
        optional object with ``theta_low_deg`` and ``theta_high_deg`` at the curve's pressures
        (:class:`embroact.predict.uncertainty.Band`); ``operating_point`` the design's target
        (pressure_kpa, theta_deg).

        Parameters
        ----------
        curve : Curve
            A predicted curve.
        label : str
            Legend text.
        p0_kpa : float or None, optional
            P0 to mark [kPa].
        measured : tuple of array_like, optional
            (pressure_kpa, theta_deg) of measured points.
        band : Band, optional
            An uncertainty band at the curve's pressures.
        operating_point : (float, float), optional
            The design's target (pressure_kpa, theta_deg).

        Returns
        -------
        Series

        Examples
        --------
        >>> from embroact.predict.curve import ActuatorModel, curve
        >>> m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.5814, beta0_deg=0, outer_radius_mm=1.5,
        ...                   inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
        >>> s = Series.from_curve(curve(m, [0.0, 100.0, 200.0]), label="A1", p0_kpa=85.0)
        >>> s.status, s.theta_deg.round(2).tolist()
        (('inflation', 'bending', 'bending'), [0.0, 11.54, 102.93])
        """
        mp, mt = (None, None) if measured is None else measured
        lo, hi = (None, None) if band is None else (band.theta_low_deg, band.theta_high_deg)
        return cls(label, curve.pressure_kpa, curve.theta_deg, status=tuple(curve.status), p0_kpa=p0_kpa,
                   measured_pressure_kpa=mp, measured_theta_deg=mt, theta_low_deg=lo, theta_high_deg=hi,
                   operating_point=operating_point)

    def drawn(self) -> np.ndarray:
        """True where the angle is a state to draw as the curve (all points without statuses).

        Returns
        -------
        numpy.ndarray of bool

        Examples
        --------
        >>> s = Series("A1", [0.0, 100.0, 200.0], [0.0, 11.5, 102.9], status=("INFLATION", "BENDING", "COILED"), p0_kpa=85.0)
        >>> s.drawn().tolist(), Series("x", [0.0, 1.0], [0.0, 1.0]).drawn().tolist()
        ([True, True, False], [True, True])
        """
        if self.status is None:
            return np.ones(len(self.pressure_kpa), dtype=bool)
        return np.array([name in DRAWN_STATES for name in self.status], dtype=bool)

    def beyond_validity(self) -> np.ndarray:
        """True where the angle is the formula's, past a validity limit.

        Returns
        -------
        numpy.ndarray of bool

        Examples
        --------
        >>> s = Series("A1", [0.0, 100.0, 200.0], [0.0, 11.5, 102.9], status=("INFLATION", "BENDING", "COILED"), p0_kpa=85.0)
        >>> s.beyond_validity().tolist()
        [False, False, True]
        """
        if self.status is None:
            return np.zeros(len(self.pressure_kpa), dtype=bool)
        return np.array([name in BEYOND_VALIDITY for name in self.status], dtype=bool)


@dataclass(frozen=True, slots=True)
class Scale:
    """Linear map from (pressure [kPa], angle [deg]) to SVG user units (y down).

    Attributes
    ----------
    x_min_kpa, x_max_kpa, y_min_deg, y_max_deg : float
        Data range shown, equal to the first and last tick.
    left_px, top_px, width_px, height_px : float
        Plot box in SVG user units.

    Examples
    --------
    >>> sc = Scale(0.0, 200.0, 0.0, 100.0, 64.0, 46.0, 640.0, 340.0)
    >>> sc.x_px(100.0), sc.y_px(100.0), sc.y_px([0.0, 50.0]).tolist()
    (384.0, 46.0, [386.0, 216.0])
    """

    x_min_kpa: float
    x_max_kpa: float
    y_min_deg: float
    y_max_deg: float
    left_px: float
    top_px: float
    width_px: float
    height_px: float

    def x_px(self, pressure_kpa):
        """SVG x of a pressure [kPa] (scalar or array).

        Parameters
        ----------
        pressure_kpa : float or array_like
            [kPa].

        Returns
        -------
        float or numpy.ndarray

        Examples
        --------
        >>> sc = Scale(0.0, 200.0, 0.0, 100.0, 64.0, 46.0, 640.0, 340.0)
        >>> sc.x_px(0.0), sc.x_px([100.0, 200.0]).tolist()
        (64.0, [384.0, 704.0])
        """
        p = np.asarray(pressure_kpa, dtype=np.float64)
        return _scalar(self.left_px + (p - self.x_min_kpa) / (self.x_max_kpa - self.x_min_kpa) * self.width_px)

    def y_px(self, angle_deg):
        """SVG y of an angle [deg] (scalar or array); larger angles are higher up.

        Parameters
        ----------
        angle_deg : float or array_like
            [deg].

        Returns
        -------
        float or numpy.ndarray

        Examples
        --------
        >>> sc = Scale(0.0, 200.0, 0.0, 100.0, 64.0, 46.0, 640.0, 340.0)
        >>> sc.y_px(0.0), sc.y_px(100.0)
        (386.0, 46.0)
        """
        a = np.asarray(angle_deg, dtype=np.float64)
        return _scalar(self.top_px + (self.y_max_deg - a) / (self.y_max_deg - self.y_min_deg) * self.height_px)


def nice_ticks(low: float, high: float, *, max_ticks: int = 8) -> tuple[float, ...]:
    """Ticks with a 1-2-5 step covering [low, high], first <= low and last >= high.

    Parameters
    ----------
    low, high : float
        Data range (low <= high; an empty range is widened to one unit).
    max_ticks : int
        Upper bound on the number of ticks (>= 2).

    Returns
    -------
    tuple of float

    Raises
    ------
    ParameterError
        A range that is not finite, or low > high.

    Examples
    --------
    >>> nice_ticks(0.0, 287.0), nice_ticks(-3.0, 47.0, max_ticks=5)
    ((0.0, 50.0, 100.0, 150.0, 200.0, 250.0, 300.0), (-20.0, 0.0, 20.0, 40.0, 60.0))
    """
    if not (math.isfinite(low) and math.isfinite(high)) or high < low:
        raise ParameterError(f"tick range must be finite with low <= high, got ({low!r}, {high!r})")
    if high == low:
        low, high = low - 0.5, high + 0.5
    raw = (high - low) / (max_ticks - 1)
    decade = 10.0 ** math.floor(math.log10(raw))
    for m in _TICK_STEPS:
        step = m * decade
        first, last = math.floor(low / step), math.ceil(high / step)
        if last - first + 1 <= max_ticks:
            break
    return tuple(float(k * step) + 0.0 for k in range(first, last + 1))


def _finite(values: Sequence[np.ndarray]) -> np.ndarray:
    cat = np.concatenate([np.asarray(v, dtype=np.float64) for v in values]) if values else np.zeros(0)
    return cat[np.isfinite(cat)]


def _ribbons_px(series: Sequence[Series]) -> float:
    with_status = sum(s.status is not None for s in series)
    return _RIBBON_PX * with_status if len(series) > 1 else 0.0


def _right_px(series: Sequence[Series]) -> float:
    """Room right of the plot: the status strips' names when there are several curves."""
    if len(series) < 2:
        return _RIGHT_MIN_PX
    names = [_strip_name(s.label) for s in series if s.status is not None]
    return max([_RIGHT_MIN_PX] + [8.0 + text_width_px(n, _RIBBON_FONT_PX) for n in names])


def chart_scale(series: Sequence[Series], *, width_px: float = 720.0, height_px: float = 440.0) -> Scale:
    """The :class:`Scale` that :func:`bend_chart_svg` uses for these series and sizes.

    The pressure axis starts at 0 kPa and the angle axis always includes 0 deg; it spans
    the drawn states (and their band) and the measured points only, never the formula's
    angles past a validity limit or fill values. The legend sits below the plot, so the
    plot keeps the chart's width (less the status strips' names on its right).

    Parameters
    ----------
    series : sequence of Series
        The chart's series.
    width_px, height_px : float, optional
        The chart's size [px].

    Returns
    -------
    Scale

    Examples
    --------
    >>> s = Series("A1", [0.0, 100.0, 200.0], [0.0, 11.5, 102.9], status=("INFLATION", "BENDING", "COILED"), p0_kpa=85.0)
    >>> sc = chart_scale([s])
    >>> sc.x_min_kpa, sc.x_max_kpa, sc.y_max_deg  # the coiled point is not drawn: the axis ends at 12 deg
    (0.0, 200.0, 12.0)
    """
    xs = _finite([s.pressure_kpa for s in series] + [s.measured_pressure_kpa for s in series
                                                     if s.measured_pressure_kpa is not None])
    ys = _finite([s.theta_deg[s.drawn()] for s in series]
                 + [b[s.drawn()] for s in series if s.theta_low_deg is not None and s.theta_high_deg is not None
                    for b in (s.theta_low_deg, s.theta_high_deg)]
                 + [s.measured_theta_deg for s in series if s.measured_theta_deg is not None])
    xt = nice_ticks(0.0, float(xs.max()) if xs.size else 1.0)
    yt = nice_ticks(min(0.0, float(ys.min()) if ys.size else 0.0), max(0.0, float(ys.max()) if ys.size else 1.0))
    left, top, bottom = 64.0, 46.0, 52.0 + _ribbons_px(series)
    return Scale(xt[0], xt[-1], yt[0], yt[-1], left, top, width_px - left - _right_px(series),
                 height_px - top - bottom)


def _fmt(v: float) -> str:
    return f"{round(float(v), _DECIMALS):g}"


def _tick_label(v: float) -> str:
    return f"{v:g}"


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """(start, stop) index pairs of consecutive True entries."""
    idx = np.flatnonzero(np.diff(np.concatenate([[0], mask.astype(np.int8), [0]])))
    return list(zip(idx[::2].tolist(), idx[1::2].tolist()))


def _status_spans(s: Series) -> list[tuple[str, float, float]]:
    """(status, p_from, p_to) spans; boundaries halfway between samples of different status, except at a
    sample at the series' P0 (a breakpoint: the state changes there)."""
    p, status = s.pressure_kpa, s.status or ()
    order = np.argsort(p, kind="stable")
    p, names = p[order], [status[i] for i in order]
    edges = np.concatenate([[p[0]], (p[1:] + p[:-1]) / 2.0, [p[-1]]])
    if s.p0_kpa is not None:
        at = np.flatnonzero(p[:-1] == s.p0_kpa)
        edges[at + 1] = s.p0_kpa
    spans: list[tuple[str, float, float]] = []
    for i, name in enumerate(names):
        if spans and spans[-1][0] == name:
            spans[-1] = (name, spans[-1][1], float(edges[i + 1]))
        else:
            spans.append((name, float(edges[i]), float(edges[i + 1])))
    return spans


def _draw_status(dwg, g, series: Sequence[Series], sc: Scale) -> None:
    rows = [s for s in series if s.status is not None]
    for k, s in enumerate(rows):
        if len(series) == 1:
            y0, h = sc.top_px, sc.height_px
        else:
            y0, h = sc.top_px + sc.height_px + 2.0 + k * _RIBBON_PX, _RIBBON_PX - 1.0
        for name, a, b in _status_spans(s):
            x0, x1 = float(sc.x_px(a)), float(sc.x_px(b))
            g.add(dwg.rect((_fmt(x0), _fmt(y0)), (_fmt(x1 - x0), _fmt(h)), fill=STATUS_STYLE[name][0],
                           **{"class": f"status {name}", "data-series": str(series.index(s))}))


def _draw_axes(dwg, g, sc: Scale, xt, yt, ribbons_px: float) -> None:
    right, bottom = sc.left_px + sc.width_px, sc.top_px + sc.height_px
    below = bottom + ribbons_px
    for v in xt:
        x = _fmt(sc.x_px(v))
        g.add(dwg.line((x, _fmt(sc.top_px)), (x, _fmt(bottom)), stroke="#d0d0d0", stroke_width=0.5))
        g.add(dwg.text(_tick_label(v), insert=(x, _fmt(below + 16)), text_anchor="middle", font_size=11,
                       **{"class": "xtick"}))
    for v in yt:
        y = _fmt(sc.y_px(v))
        g.add(dwg.line((_fmt(sc.left_px), y), (_fmt(right), y), stroke="#000" if v == 0 else "#d0d0d0",
                       stroke_width=0.8 if v == 0 else 0.5))
        g.add(dwg.text(_tick_label(v), insert=(_fmt(sc.left_px - 6), _fmt(sc.y_px(v) + 4)), text_anchor="end",
                       font_size=11, **{"class": "ytick"}))
    g.add(dwg.rect((_fmt(sc.left_px), _fmt(sc.top_px)), (_fmt(sc.width_px), _fmt(sc.height_px)),
                   fill="none", stroke="#333", stroke_width=1))
    g.add(dwg.text("pressure [kPa]", insert=(_fmt(sc.left_px + sc.width_px / 2), _fmt(below + 36)),
                   text_anchor="middle", font_size=12))
    cy = sc.top_px + sc.height_px / 2
    g.add(dwg.text("bend angle [deg]", insert=(16, _fmt(cy)), text_anchor="middle", font_size=12,
                   transform=f"rotate(-90 16 {_fmt(cy)})"))


def _draw_band(dwg, g, k: int, s: Series, sc: Scale) -> None:
    """The band as one polygon per run of drawn points (low edge forward, high edge back)."""
    if s.theta_low_deg is None or s.theta_high_deg is None:
        return
    order = np.argsort(s.pressure_kpa, kind="stable")
    p, lo, hi = s.pressure_kpa[order], s.theta_low_deg[order], s.theta_high_deg[order]
    ok = s.drawn()[order] & np.isfinite(lo) & np.isfinite(hi)
    for a, b in _runs(ok):
        xs = np.concatenate([p[a:b], p[a:b][::-1]])
        ys = np.concatenate([lo[a:b], hi[a:b][::-1]])
        pts = [(_fmt(x), _fmt(y)) for x, y in zip(sc.x_px(xs), sc.y_px(ys))]
        g.add(dwg.polygon(pts, fill=PALETTE[k % len(PALETTE)], fill_opacity=_BAND_OPACITY, stroke="none",
                          **{"class": "band", "data-series": str(k)}))


def _draw_series(dwg, g, k: int, s: Series, sc: Scale) -> None:
    colour = PALETTE[k % len(PALETTE)]
    order = np.argsort(s.pressure_kpa, kind="stable")
    p, t = s.pressure_kpa[order], s.theta_deg[order]
    finite = np.isfinite(t)
    for a, b in _runs(finite & s.drawn()[order]):
        pts = [(_fmt(x), _fmt(y)) for x, y in zip(sc.x_px(p[a:b]), sc.y_px(t[a:b]))]
        g.add(dwg.polyline(pts, fill="none", stroke=colour, stroke_width=2, stroke_linejoin="round",
                           **{"class": "curve", "data-series": str(k)}))
    beyond = finite & s.beyond_validity()[order]
    for a, b in _runs(beyond):  # from the last drawn point before the run, so the line continues
        a0 = a - 1 if a > 0 and finite[a - 1] and s.drawn()[order][a - 1] else a
        pts = [(_fmt(x), _fmt(y)) for x, y in zip(sc.x_px(p[a0:b]), sc.y_px(t[a0:b]))]
        g.add(dwg.polyline(pts, fill="none", stroke=colour, stroke_width=1, stroke_dasharray="2,3",
                           clip_path="url(#plot-box)", **{"class": "beyond", "data-series": str(k)}))
    if s.p0_kpa is not None and sc.x_min_kpa <= s.p0_kpa <= sc.x_max_kpa:
        x = _fmt(sc.x_px(s.p0_kpa))
        g.add(dwg.line((x, _fmt(sc.top_px)), (x, _fmt(sc.top_px + sc.height_px)), stroke=colour,
                       stroke_width=1.2, stroke_dasharray="5,3", **{"class": "p0", "data-series": str(k)}))
    if s.operating_point is not None and sc.x_min_kpa <= s.operating_point[0] <= sc.x_max_kpa:
        g.add(_diamond(dwg, float(sc.x_px(s.operating_point[0])), float(sc.y_px(s.operating_point[1])), colour,
                       **{"class": "operating-point", "data-series": str(k),
                          "data-pressure-kpa": f"{s.operating_point[0]:g}", "data-theta-deg": f"{s.operating_point[1]:g}"}))
    if s.measured_pressure_kpa is not None:
        for x, y in zip(sc.x_px(s.measured_pressure_kpa), sc.y_px(s.measured_theta_deg)):
            g.add(dwg.circle((_fmt(x), _fmt(y)), 3.2, fill="#fff", stroke=colour, stroke_width=1.5,
                             **{"class": "measured", "data-series": str(k)}))


def _diamond(dwg, x: float, y: float, colour: str, **extra):
    """The operating point's mark: a filled diamond 10 px across centred on (x, y)."""
    return dwg.polygon([(_fmt(cx), _fmt(cy)) for cx, cy in _diamond_corners(x, y)],
                       fill=colour, stroke="#fff", stroke_width=1.0, **extra)


def _diamond_corners(x: float, y: float) -> list[tuple[float, float]]:
    """Top, right, bottom and left corner of the operating point's diamond centred on (x, y) [px]."""
    r = 5.0
    return [(x, y - r), (x + r, y), (x, y + r), (x - r, y)]


def _curve_points_px(s: Series, sc: Scale) -> list[np.ndarray]:
    """The drawn runs of a series in SVG units (what the P0 labels keep off)."""
    order = np.argsort(s.pressure_kpa, kind="stable")
    p, t = s.pressure_kpa[order], s.theta_deg[order]
    shown = np.isfinite(t) & (s.drawn()[order] | s.beyond_validity()[order])
    return [np.column_stack([sc.x_px(p[a:b]), np.clip(sc.y_px(t[a:b]), sc.top_px, sc.top_px + sc.height_px)])
            for a, b in _runs(shown)]


def _draw_p0_labels(dwg, g, series: Sequence[Series], sc: Scale) -> None:
    """Each P0 mark's value beside its line, placed clear of every curve and of the other P0 labels."""
    placer = Placer(Box(sc.left_px + 1.0, sc.top_px + 1.0, sc.left_px + sc.width_px - 1.0,
                        sc.top_px + sc.height_px - 1.0), margin=1.0)
    for s in series:
        for pts in _curve_points_px(s, sc):
            placer.block_polyline(pts)
        if s.operating_point is not None:  # the diamond's outline
            x, y = float(sc.x_px(s.operating_point[0])), float(sc.y_px(s.operating_point[1]))
            corners = _diamond_corners(x, y)
            placer.block_polyline(corners + corners[:1])
    marked = [s for s in series if s.p0_kpa is not None and sc.x_min_kpa <= s.p0_kpa <= sc.x_max_kpa]
    for s in marked:  # the dashed P0 lines: a label sits beside its own line, never across another
        placer.block_polyline([(sc.x_px(s.p0_kpa), sc.top_px), (sc.x_px(s.p0_kpa), sc.top_px + sc.height_px)])
    rows = np.arange(sc.top_px + 12.0, sc.top_px + sc.height_px - 4.0, 12.0)
    if not len(rows):  # no row of text fits in the plot: the dashed lines alone mark P0
        return
    for k, s in enumerate(series):
        if s.p0_kpa is None or not sc.x_min_kpa <= s.p0_kpa <= sc.x_max_kpa:
            continue
        x = float(sc.x_px(s.p0_kpa))
        text = f"P0 {s.p0_kpa:.0f}"
        lab = placer.place_along(text, [(x, float(y)) for y in rows], _P0_FONT_PX, gap=3.0)
        if lab.collisions:  # no free spot beside its line (P0s a few kPa apart): the dashed line alone marks it
            continue
        g.add(dwg.text(text, insert=(_fmt(lab.x), _fmt(lab.y)), font_size=_P0_FONT_PX, fill=PALETTE[k % len(PALETTE)],
                       text_anchor=lab.anchor, **{"class": "p0-label", "data-series": str(k)}))


def _strip_name(label: str) -> str:
    """A status strip's name: the series label up to its first ``,`` or ``:`` (the actuator's name)."""
    for sep in (":", ","):
        label = label.split(sep)[0]
    return label


def _draw_strip_names(dwg, g, series: Sequence[Series], sc: Scale) -> None:
    """Under several curves each status strip is named at its right end."""
    if len(series) < 2:
        return
    rows = [s for s in series if s.status is not None]
    for k, s in enumerate(rows):
        y = sc.top_px + sc.height_px + 2.0 + k * _RIBBON_PX + _RIBBON_PX - 1.5
        g.add(dwg.text(_strip_name(s.label), insert=(_fmt(sc.left_px + sc.width_px + 4.0), _fmt(y)),
                       font_size=_RIBBON_FONT_PX, fill=PALETTE[series.index(s) % len(PALETTE)],
                       **{"class": "strip-name"}))


def _legend_items(series: Sequence[Series], used: list[str]) -> list[tuple[str, object, str]]:
    """(kind, key, text) of every legend entry: each series, then the marks and the shaded states drawn."""
    items: list[tuple[str, object, str]] = [("series", k, s.label) for k, s in enumerate(series)]
    marks = (("measured", any(s.measured_pressure_kpa is not None for s in series), "measured"),
             ("p0", any(s.p0_kpa is not None for s in series), "P0 (transition)"),
             ("band", any(s.theta_low_deg is not None for s in series), "1-sigma band"),
             ("operating", any(s.operating_point is not None for s in series), _operating_text(series)),
             ("beyond", any(s.beyond_validity().any() for s in series), "formula past validity"))
    items += [("mark", kind, text) for kind, present, text in marks if present]
    if len(series) > 1 and used:
        items.append(("note", None, "each curve's state, in its strip under the plot:"))
    items += [("state", name, STATUS_STYLE[name][1]) for name in used]
    return items


def _operating_text(series: Sequence[Series]) -> str:
    """The operating point's legend entry: its pressure and bend when one series has it."""
    points = [s.operating_point for s in series if s.operating_point is not None]
    if len(points) == 1:
        return f"operating point (design target): {points[0][1]:.1f} deg at {points[0][0]:g} kPa"
    return "operating point (design target)"


def _legend_rows(items, width_px: float) -> list[list[tuple[str, object, str, float]]]:
    """Items flowed into rows of ``width_px``: each series on a row of its own (shortened to fit), the rest side by side."""
    rows: list[list] = []
    used = width_px
    for kind, key, text in items:
        if kind == "series":
            text = fit_title(text, width_px - _KEY_PX - 6.0, font_px=_LEGEND_FONT_PX, small_px=_LEGEND_FONT_PX,
                             max_lines=1).lines[0]
        w = _key_px(kind) + text_width_px(text, _LEGEND_FONT_PX) + 16.0
        if kind in ("series", "note") or used + w > width_px or (rows and rows[-1][0][0] in ("series", "note")):
            rows.append([])
            used = 0.0
        rows[-1].append((kind, key, text, used))
        used += w
    return rows


def _key_px(kind: str) -> float:
    """Width of an entry's symbol and the space after it (a note has none)."""
    return 0.0 if kind == "note" else _KEY_PX + 6.0


def _legend_height_px(series: Sequence[Series], used: list[str], width_px: float) -> float:
    return _LEGEND_ROW_PX * len(_legend_rows(_legend_items(series, used), width_px)) + 8.0


def _draw_key(dwg, g, kind: str, key, x: float, y: float) -> None:
    """The symbol of a legend entry, ``_KEY_PX`` wide, centred on height ``y``."""
    if kind == "series":
        g.add(dwg.line((_fmt(x), _fmt(y)), (_fmt(x + _KEY_PX), _fmt(y)), stroke=PALETTE[key % len(PALETTE)],
                       stroke_width=2))
    elif kind == "state":
        g.add(dwg.rect((_fmt(x), _fmt(y - 6)), (_KEY_PX, 12), fill=STATUS_STYLE[key][0], stroke="#999",
                       stroke_width=0.5))
    elif key == "measured":
        g.add(dwg.circle((_fmt(x + _KEY_PX / 2), _fmt(y)), 3.2, fill="#fff", stroke="#333", stroke_width=1.5))
    elif key == "p0":
        g.add(dwg.line((_fmt(x + _KEY_PX / 2), _fmt(y - 7)), (_fmt(x + _KEY_PX / 2), _fmt(y + 7)), stroke="#333",
                       stroke_dasharray="5,3"))
    elif key == "band":
        g.add(dwg.rect((_fmt(x), _fmt(y - 6)), (_KEY_PX, 12), fill="#333", fill_opacity=_BAND_OPACITY))
    elif key == "operating":
        g.add(_diamond(dwg, x + _KEY_PX / 2, y, "#333"))
    else:  # beyond validity
        g.add(dwg.line((_fmt(x), _fmt(y)), (_fmt(x + _KEY_PX), _fmt(y)), stroke="#333", stroke_width=1,
                       stroke_dasharray="2,3"))


def _draw_legend(dwg, g, series: Sequence[Series], used: list[str], x0: float, y0: float, width_px: float) -> None:
    for r, row in enumerate(_legend_rows(_legend_items(series, used), width_px)):
        y = y0 + r * _LEGEND_ROW_PX
        for kind, key, text, dx in row:
            if kind != "note":
                _draw_key(dwg, g, kind, key, x0 + dx, y)
            g.add(dwg.text(text, insert=(_fmt(x0 + dx + _key_px(kind)), _fmt(y + 4)), font_size=_LEGEND_FONT_PX,
                           **{"class": "legend"}))


def bend_chart_svg(
    series: Sequence[Series],
    *,
    title: str = "Predicted bend angle",
    width_px: float = 720.0,
    height_px: float = 440.0,
) -> str:
    """The pressure-bend chart as an SVG document string.

    Parameters
    ----------
    series : sequence of Series
        One per design (at least one, each with at least one sample).
    title : str
        Chart title.
    width_px, height_px : float
        Size of the chart in SVG user units (px), at least 320 x 240; the legend is drawn
        below it, one row per series and rows of marks and states, and adds to the height.

    Returns
    -------
    str
        SVG text; polylines carry ``class="curve"`` (valid states) or ``class="beyond"`` (the
        formula past a validity limit) and ``data-series="k"``; bands are polygons of
        ``class="band"``.

    Examples
    --------
    >>> s = Series("A1", [0.0, 100.0, 200.0], [0.0, 11.5, 102.9], status=("INFLATION", "BENDING", "COILED"), p0_kpa=85.0)
    >>> svg = bend_chart_svg([s], title="A1")
    >>> svg.startswith("<svg"), "A1" in svg
    (True, True)
    """
    from .svgdoc import Drawing

    if not series or any(len(s.pressure_kpa) == 0 for s in series):
        raise ParameterError("series must hold at least one curve with at least one sample")
    if width_px < 320 or height_px < 240:
        raise ParameterError(f"chart size must be at least 320 x 240 px, got {width_px:g} x {height_px:g}")
    sc = chart_scale(series, width_px=width_px, height_px=height_px)
    xt = nice_ticks(sc.x_min_kpa, sc.x_max_kpa)
    yt = nice_ticks(sc.y_min_deg, sc.y_max_deg)
    used = [name for name in STATUS_STYLE if any(s.status is not None and name in s.status for s in series)]
    legend_w = width_px - 16.0 - _TITLE_RIGHT_PX
    total_px = height_px + _legend_height_px(series, used, legend_w)
    dwg = Drawing(size=(_fmt(width_px), _fmt(total_px)), viewBox=f"0 0 {_fmt(width_px)} {_fmt(total_px)}")
    dwg.add(dwg.rect((0, 0), (_fmt(width_px), _fmt(total_px)), fill="#fff"))
    clip = dwg.defs.add(dwg.clipPath(id="plot-box"))
    clip.add(dwg.rect((_fmt(sc.left_px), _fmt(sc.top_px)), (_fmt(sc.width_px), _fmt(sc.height_px))))
    g = dwg.g(style=_FONT)
    dwg.add(g)
    _draw_status(dwg, g, series, sc)
    for k, s in enumerate(series):
        _draw_band(dwg, g, k, s, sc)
    _draw_axes(dwg, g, sc, xt, yt, _ribbons_px(series))
    for k, s in enumerate(series):
        _draw_series(dwg, g, k, s, sc)
    _draw_p0_labels(dwg, g, series, sc)
    _draw_strip_names(dwg, g, series, sc)
    _draw_legend(dwg, g, series, used, 16.0, height_px + 6.0, legend_w)
    fitted = fit_title(title, width_px - sc.left_px - _TITLE_RIGHT_PX)  # two lines of 12 px above the plot at most
    for k, line in enumerate(fitted.lines):
        y = 22 if len(fitted.lines) == 1 else 17 + 15 * k
        g.add(dwg.text(line, insert=(_fmt(sc.left_px), y), font_size=_fmt(fitted.font_px), font_weight="bold",
                       **{"class": "title"}))
    return dwg.tostring()
