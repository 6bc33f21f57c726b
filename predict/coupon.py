"""The calibration coupon: which test actuators to sew, and how they share hoops.

A material profile gives G and P0 along each pattern's calibration coordinate (its kind's
``calibration_axis``; docs/calibration.md). The coupon samples that coordinate for every
registered pattern kind (:data:`~embroact.patterns.kinds.PATTERN_KINDS`) it can sample
(:func:`coupon_kinds`), each at its kind's default stitch interval:

* a kind calibrated along **width** (``width_mm``): ``width_count`` widths evenly over
  ``width_range_mm``. The default range is the paper's prototypes' relative to the tube,
  10/3 to 6 tube radii (5 to 9 mm for r_f = 1.5 mm), raised where needed so that the sleeve
  clears the tube by 3 times the EA202 gap (a narrower sleeve makes P0 tiny and steep in the width);
* a kind calibrated along **angle** (``angle_deg``): ``angle_count`` angles at one width
  (``angle_width_mm``, default the middle of the width range), evenly over ``angle_range_deg``;
  where the kind's threads lie at an angle (a pantograph, :mod:`embroact.predict.kinds`) half of
  them below and half above the neutral angle (where the bending direction flips), at least
  ``neutral_band_deg + 2`` away from it (EA206 warns within the band).

Widths are on a 0.2 mm grid (each rail at +-w/2 on the machine formats' 0.1 mm grid),
angles on 1 deg. Each actuator is 100 mm long by default, sewn straight along +x; the
actuators of one hoop sit one above the other ``pitch_mm`` apart, numbered in sewing
order, and take as many hoops as they need. Each has its own block of marker ids
(:class:`~embroact.predict.photomarkers.PhotoLayout`) and a fin side: outside its bend
(the thread side for a bend toward the back, the fabric side for one toward the front), so
the fins fan out as it bends.

Examples
--------
>>> from embroact.patterns.params import Tube
>>> c = plan_coupon(("zigzag", "cross"), tube=Tube())
>>> [a.label for a in c.actuators][:2], [round(a.coordinate, 1) for a in c.actuators]
(['01 zigzag w5.0', '02 zigzag w6.0'], [5.0, 6.0, 7.0, 8.0, 9.0, 16.7, 21.8, 26.6, 38.7, 45.0, 52.4])
>>> c.hoops, [a.hoop for a in c.actuators].count(0)
(2, 8)
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..patterns.base.errors import ParameterError, check_range
from ..patterns.kinds import PATTERN_KINDS, pattern_kind
from ..patterns.params import Tube
from ..patterns.rules.settings import RuleSettings
from .kinds import model_kind
from .markers import MarkerSide
from .photomarkers import COUPON_LAYOUT, PhotoLayout
from .sleeve import neutral_angle_deg, sleeve_radius_mm

__all__ = ["COUPON_AXES", "Coupon", "CouponActuator", "coupon_kinds", "default_width_range_mm", "plan_coupon"]

#: The calibration axes the coupon samples: a kind's widths, or its angles at one width.
COUPON_AXES = ("width_mm", "angle_deg")
#: Width grid [mm]: both rails on the formats' 0.1 mm grid.
_WIDTH_STEP_MM = 0.2
#: The paper's prototypes span these widths in tube radii (5 and 9 mm on r_f = 1.5 mm).
_PAPER_WIDTH_RADII = (10.0 / 3.0, 6.0)
#: The default range keeps r0 - r_f at least this many EA202 gaps.
_GAP_FACTOR = 3.0
#: A cross leg stays this much shorter than the machine's longest stitch [mm].
_LEG_MARGIN_MM = 0.5
#: Fabric kept beside the hoop's edge [mm].
_HOOP_MARGIN_MM = 10.0


@dataclass(frozen=True, slots=True)
class CouponActuator:
    """One test actuator of the coupon.

    Attributes
    ----------
    order : int
        Sewing order, from 1.
    label : str
        Name in the design and on every sheet, e.g. ``"03 zigzag w7.0"``.
    pattern : str
        Its pattern kind.
    width_mm, interval_mm, angle_deg, length_mm : float
        The design values (angle 0 for zigzag).
    hoop : int
        Hoop index, from 0.
    origin_mm : (float, float)
        Start of its straight path in the hoop's frame [mm].
    block : int
        Its marker-id block (ids ``layout.ids(block)``).
    fin_side : MarkerSide
        Face its marker fins go on (outside the expected bend).

    Examples
    --------
    >>> c = plan_coupon(("zigzag", "cross"), tube=Tube())
    >>> a = c.actuators[2]
    >>> a.order, a.label, a.coordinate, a.hoop
    (3, '03 zigzag w7.0', 7.0, 0)
    """

    order: int
    label: str
    pattern: str
    width_mm: float
    interval_mm: float
    angle_deg: float
    length_mm: float
    hoop: int
    origin_mm: tuple[float, float]
    block: int
    fin_side: MarkerSide

    @property
    def coordinate(self) -> float:
        """Its calibration coordinate: the value of its kind's calibration axis (the zigzag's width, say)."""
        return getattr(self, pattern_kind(self.pattern).calibration_axis)

    def design_table(self) -> dict:
        """The ``[[actuator]]`` table of a design file.

        Returns
        -------
        dict

        Examples
        --------
        >>> c = plan_coupon(("zigzag", "cross"), tube=Tube())
        >>> c.actuators[0].design_table()
        {'name': '01 zigzag w5.0', 'pattern': 'zigzag', 'width_mm': 5.0, 'interval_mm': 1.0, 'length_mm': 100.0, 'origin_mm': [-50.0, 87.5]}
        """
        d: dict[str, object] = {"name": self.label, "pattern": self.pattern, "width_mm": self.width_mm,
                                "interval_mm": self.interval_mm, "length_mm": self.length_mm,
                                "origin_mm": list(self.origin_mm)}
        if pattern_kind(self.pattern).has_angle:
            d["angle_deg"] = self.angle_deg
        return d


@dataclass(frozen=True, slots=True)
class Coupon:
    """The coupon's actuators, their hoops and the marker layout they are measured with.

    Attributes
    ----------
    actuators : tuple of CouponActuator
        In sewing order.
    hoops : int
        Hoops needed.
    hoop_mm : (float, float)
        Sewing field, width and height [mm].
    layout : PhotoLayout
        The marker layout.
    neutral_angle_deg : float or None
        The neutral angle of the angle-sampled actuators whose threads lie at an angle [deg], when there are any.

    Examples
    --------
    >>> c = plan_coupon(("zigzag", "cross"), tube=Tube())
    >>> c.hoops, c.hoop_mm, len(c.actuators)
    (2, (200.0, 200.0), 11)
    """

    actuators: tuple[CouponActuator, ...]
    hoops: int
    hoop_mm: tuple[float, float]
    layout: PhotoLayout = field(default=COUPON_LAYOUT)
    neutral_angle_deg: float | None = None

    def on_hoop(self, hoop: int) -> tuple[CouponActuator, ...]:
        """The actuators sewn in hoop ``hoop``, in order.

        Parameters
        ----------
        hoop : int
            Hoop index, from 0.

        Returns
        -------
        tuple of CouponActuator

        Examples
        --------
        >>> c = plan_coupon(("zigzag", "cross"), tube=Tube())
        >>> [a.order for a in c.on_hoop(1)]
        [9, 10, 11]
        """
        return tuple(a for a in self.actuators if a.hoop == hoop)


def _sleeve_clear_width_mm(tube: Tube, gap_mm: float) -> float:
    """Smallest width whose sleeve radius exceeds r_f by ``gap_mm`` (bisection; r0 grows with w)."""
    lo, hi = 0.0, 100.0 * tube.outer_radius_mm
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if float(sleeve_radius_mm(mid, tube.outer_radius_mm)) - tube.outer_radius_mm < gap_mm else (lo, mid)
    return hi


def _grid(value: float, step: float, up: bool) -> float:
    n = value / step
    return round((math.ceil(n - 1e-9) if up else math.floor(n + 1e-9)) * step, 6)


#: The rule thresholds the coupon's values keep clear of (EA202's gap, EA206's band, the longest stitch).
_RULES = RuleSettings()


def default_width_range_mm(tube: Tube, min_sleeve_gap_mm: float = _RULES.min_sleeve_gap_mm) -> tuple[float, float]:
    """The default zigzag widths' range for ``tube`` [mm] (module docstring).

    Parameters
    ----------
    tube : Tube
        The coupon's tube.
    min_sleeve_gap_mm : float, optional
        Smallest sleeve gap r0 - r_f to keep clear of [mm].

    Returns
    -------
    tuple of float
        Narrowest and widest width [mm].

    Examples
    --------
    >>> default_width_range_mm(Tube())
    (5.0, 9.0)
    """
    rf = tube.outer_radius_mm
    lo = max(_PAPER_WIDTH_RADII[0] * rf, _sleeve_clear_width_mm(tube, _GAP_FACTOR * min_sleeve_gap_mm))
    return _grid(lo, _WIDTH_STEP_MM, up=True), _grid(_PAPER_WIDTH_RADII[1] * rf, _WIDTH_STEP_MM, up=False)


def _sewn_angle_deg(target: float, width_mm: float, interval_mm: float, neutral: float, keep: float) -> float:
    """The angle nearest ``target`` that a pattern of two crossing leg families sews exactly, outside the
    neutral band.

    Such a pattern closes after ``n`` passes where ``tan(alpha0) = n s / (2 w)`` (the cross pattern,
    :mod:`embroact.patterns.cross`); any other request is adjusted by the generator, so the coupon asks
    for one of these, rounded to 1e-4 deg.
    """
    n = max(round(2.0 * width_mm * math.tan(math.radians(target)) / interval_mm), 1)
    for cand in (n, n + 1, n - 1, n + 2, n - 2):
        a = math.degrees(math.atan(cand * interval_mm / (2.0 * width_mm)))
        if cand >= 1 and abs(a - neutral) >= keep and (a < neutral) == (target < neutral):
            return round(a, 4)
    return round(target, 4)


def _spread(lo: float, hi: float, n: int) -> list[float]:
    return [lo] if n == 1 else [lo + (hi - lo) * i / (n - 1) for i in range(n)]


def _count(name: str, n, high: int = 40) -> int:
    if isinstance(n, bool) or not isinstance(n, int) or not 0 <= n <= high:
        raise ParameterError(f"{name} must be an integer in [0, {high}], got {n!r}")
    return n


def coupon_kinds() -> tuple[str, ...]:
    """The registered pattern kinds the coupon samples: those calibrated along an axis of :data:`COUPON_AXES`.

    Returns
    -------
    tuple of str
        In registration order.

    Examples
    --------
    >>> coupon_kinds()[:2]
    ('zigzag', 'cross')
    """
    return tuple(k.name for k in PATTERN_KINDS if k.calibration_axis in COUPON_AXES)


def _angles(name: str, count: int, angle_range_deg, cw: float, tube: Tube, neutral_band_deg: float,
            max_stitch_mm: float) -> tuple[list[float], float | None]:
    """The angles of an angle-sampled kind at width ``cw`` and its neutral angle (None without a thread angle)."""
    kind = pattern_kind(name)
    a_lo, a_hi = angle_range_deg
    check_range("angle_range_deg low", a_lo, low=0.0, high=90.0)
    check_range("angle_range_deg high", a_hi, low=a_lo, high=90.0)
    a_hi = min(a_hi, math.degrees(math.acos(min(cw / (max_stitch_mm - _LEG_MARGIN_MM), 1.0))))
    if not model_kind(name).has_thread_angle:
        return _spread(a_lo, a_hi, count), None
    if count < 2:
        raise ParameterError(f"angle_count must be at least 2 (one angle on each side of the neutral angle), "
                             f"got {count}")
    neutral = float(neutral_angle_deg(cw, tube.outer_radius_mm))
    keep = neutral_band_deg + 2.0
    below, above = count // 2, count - count // 2
    if not a_lo < neutral - keep or not neutral + keep < a_hi:
        raise ParameterError(f"angle_range_deg must reach past the neutral angle {neutral:.1f} deg by more than "
                             f"{keep:g} deg on both sides, got [{a_lo:g}, {a_hi:g}]")
    angles = _spread(a_lo, neutral - keep, below) if below > 1 else [a_lo]
    angles += _spread(neutral + keep, a_hi, above) if above > 1 else [a_hi]
    return [_sewn_angle_deg(a, cw, kind.default_interval_mm, neutral, keep) for a in angles], neutral


def plan_coupon(
    patterns=None,
    *,
    tube: Tube | None = None,
    width_count: int = 5,
    angle_count: int = 6,
    width_range_mm: tuple[float, float] | None = None,
    angle_range_deg: tuple[float, float] = (15.0, 60.0),
    angle_width_mm: float | None = None,
    length_mm: float = 100.0,
    hoop_mm: tuple[float, float] = (200.0, 200.0),
    pitch_mm: float = 25.0,
    neutral_band_deg: float = _RULES.neutral_band_deg,
    min_sleeve_gap_mm: float = _RULES.min_sleeve_gap_mm,
    max_stitch_mm: float = _RULES.max_stitch_mm,
    layout: PhotoLayout = COUPON_LAYOUT,
) -> Coupon:
    """The coupon's actuators and hoops (module docstring).

    Parameters
    ----------
    patterns : sequence of str, optional
        Patterns to calibrate, from :func:`coupon_kinds`; default all of them, in registration order.
    tube : Tube, optional
        Default: the paper's tube.
    width_count, angle_count : int
        Widths per width-sampled kind, angles per angle-sampled kind (with a thread angle: at least 2,
        half on each side of the neutral angle).
    width_range_mm : (float, float), optional
        The widths' range [mm]; default :func:`default_width_range_mm`.
    angle_range_deg : (float, float)
        The angles' range [deg], within (0, 90).
    angle_width_mm : float, optional
        Width of the angle-sampled actuators [mm]; default the middle of the width range.
    length_mm : float
        Bent length [mm] (each kind sewn at its default stitch interval).
    hoop_mm : (float, float)
        Sewing field, width and height [mm].
    pitch_mm : float
        Distance between neighbouring actuators' tubes [mm] (each strip is cut out with this much fabric).
    neutral_band_deg, min_sleeve_gap_mm : float
        The EA206 band and the EA202 gap the values keep clear of.
    max_stitch_mm : float
        The machine's longest stitch [mm]: a leg ``w / cos(alpha0)`` stays 0.5 mm below it
        (which lowers the top of ``angle_range_deg``: 54 deg for w = 7 mm).
    layout : PhotoLayout
        How the actuators are measured; its marker span must cover ``length_mm``.

    Returns
    -------
    Coupon

    Examples
    --------
    >>> c = plan_coupon(("zigzag",), tube=Tube(), width_count=3)
    >>> [a.label for a in c.actuators], c.hoops
    (['01 zigzag w5.0', '02 zigzag w7.0', '03 zigzag w9.0'], 1)
    >>> try:
    ...     plan_coupon(("satin",))
    ... except ValueError as exc:
    ...     print(exc)  # doctest: +ELLIPSIS
    patterns must list distinct names from zigzag, cross..., got 'satin'
    """
    tube = Tube() if tube is None else tube
    kinds = coupon_kinds()
    pats = kinds if patterns is None else tuple(patterns)
    bad = [p for p in pats if p not in kinds]
    if bad or not pats or len(set(pats)) != len(pats):
        raise ParameterError(f"patterns must list distinct names from {', '.join(kinds)}, got {','.join(pats)!r}")
    width_count = _count("width_count", width_count)
    angle_count = _count("angle_count", angle_count)
    check_range("length_mm", length_mm, low=10.0, high=1000.0, high_inclusive=True)
    check_range("pitch_mm", pitch_mm, low=2.0 * tube.outer_radius_mm, high=1000.0)
    hoop_w = check_range("hoop_width_mm", hoop_mm[0], low=0.0, high=10_000.0)
    hoop_h = check_range("hoop_height_mm", hoop_mm[1], low=0.0, high=10_000.0)
    lo_w, hi_w = width_range_mm if width_range_mm is not None else default_width_range_mm(tube, min_sleeve_gap_mm)
    check_range("width_range_mm low", lo_w, low=0.0, high=200.0)
    check_range("width_range_mm high", hi_w, low=lo_w, low_inclusive=True, high=200.0)
    cw = angle_width_mm if angle_width_mm is not None else _grid(0.5 * (lo_w + hi_w), _WIDTH_STEP_MM, up=False)
    values: list[tuple[str, float, float]] = []  # (pattern, width, angle)
    neutral = None
    for name in pats:
        if pattern_kind(name).calibration_axis == "width_mm":
            values += [(name, _grid(w, _WIDTH_STEP_MM, up=not i), 0.0)
                       for i, w in enumerate(_spread(lo_w, hi_w, width_count) if width_count else [])]
        elif angle_count:
            check_range("angle_width_mm", cw, low=0.0, high=200.0)
            angles, at = _angles(name, angle_count, angle_range_deg, cw, tube, neutral_band_deg, max_stitch_mm)
            neutral = at if at is not None else neutral
            values += [(name, cw, a) for a in angles]
    if not values:
        raise ParameterError("the coupon needs at least one actuator: width_count or angle_count above 0")
    if len(values) > layout.blocks:
        raise ParameterError(f"a coupon has at most {layout.blocks} actuators (marker ids), got {len(values)}")
    span = layout.positions_mm()
    if span[-1] > length_mm + 1e-9:
        raise ParameterError(f"the marker layout reaches {span[-1]:g} mm along the strip, past length_mm {length_mm:g}")
    if length_mm + 2 * _HOOP_MARGIN_MM > hoop_w:
        raise ParameterError(f"hoop_width_mm must hold length_mm {length_mm:g} plus {2 * _HOOP_MARGIN_MM:g} mm, "
                             f"got {hoop_w:g}")
    per_hoop = max(int((hoop_h - 2 * _HOOP_MARGIN_MM) // pitch_mm) + 1, 1)
    acts = []
    for i, (pattern, w, a) in enumerate(values):
        hoop, row = divmod(i, per_hoop)
        n_here = min(per_hoop, len(values) - hoop * per_hoop)
        y = ((n_here - 1) / 2.0 - row) * pitch_mm
        kind, model = pattern_kind(pattern), model_kind(pattern)
        bends_back = model.bends_positive(model.beta0_deg(w, a, tube.outer_radius_mm))  # fins outside the bend
        label = f"{i + 1:02d} {pattern} " + (f"w{w:.1f}" if kind.calibration_axis == "width_mm" else f"a{a:.1f} w{w:.1f}")
        acts.append(CouponActuator(i + 1, label, pattern, w, kind.default_interval_mm, a, float(length_mm), hoop,
                                   (-length_mm / 2.0, round(y, 6)), i,
                                   MarkerSide.THREAD if bends_back else MarkerSide.FABRIC))
    return Coupon(tuple(acts), acts[-1].hoop + 1, (hoop_w, hoop_h), layout, neutral)
