"""Sleeve geometry derived from the generated stitches: r0, beta0 and gamma.

The numbers come from what the generator realised (rail spacing and leg angle
measured on the stitches), not from the request; both are kept for reports. The tube law's
P0 at r0 depends on the tube law in force, a model setting: it is
:attr:`embroact.predict.calibration.ModelChoice.tube_law_p0_kpa`
(:func:`embroact.predict.tubelaws.transition_pressure_kpa`).

Examples
--------
>>> from embroact.patterns.params import Tube
>>> from embroact.predict.derived import derive_from_values
>>> g = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0,
...                        length_mm=100.0, tube=Tube())
>>> round(g.r0_mm, 4), g.beta0_deg
(2.5814, 0.0)
>>> c = derive_from_values("cross", width_mm=7.0, interval_mm=1.4, angle_deg=45.0,
...                        length_mm=100.0, tube=Tube())
>>> round(c.beta0_deg, 3), c.bends_positive
(37.208, False)
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

from ..patterns.base.errors import check_range
from ..patterns.base.records import quick_init
from ..patterns.kinds import pattern_kind
from ..patterns.params import Tube
from ..patterns.plan import ActuatorPlan
from .kinds import model_kind
from .sleeve import gamma, min_sleeve_width_mm, neutral_angle_deg, sleeve_radius_mm

__all__ = ["DerivedGeometry", "derive", "derive_from_values", "geometry_dict", "GEOMETRY_KEYS"]


@quick_init
@dataclass(frozen=True, slots=True)
class DerivedGeometry:
    """Realised pattern parameters and the sleeve they make (docs/model.md sections 2-3).

    Attributes
    ----------
    name, pattern : str
        The actuator's name and pattern kind.
    length_mm : float
        l0, embroidered (fabric-side) length [mm].
    width_mm, interval_mm, angle_deg : float
        Realised rail spacing, stitch interval, leg angle alpha0 (0 for zigzag) [mm, mm, deg].
    requested_width_mm, requested_interval_mm, requested_angle_deg : float
        What the user asked for.
    r0_mm : float
        Sleeve radius [mm].
    beta0_deg : float
        Thread angle to the circumferential direction at r0 [deg] (0 for zigzag).
    gamma : float
        2 r0 / (l0 cos beta0) [1/rad].
    neutral_angle_deg : float
        alpha0 with tan(beta0) = 1/2 for this width and tube [deg].
    tube : Tube
        The tube.

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> d = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
    >>> round(d.r0_mm, 4), d.beta0_deg, round(d.gamma, 5), d.has_sleeve
    (2.5814, 0.0, 0.05163, True)
    """

    name: str
    pattern: str
    length_mm: float
    width_mm: float
    interval_mm: float
    angle_deg: float
    requested_width_mm: float
    requested_interval_mm: float
    requested_angle_deg: float
    r0_mm: float
    beta0_deg: float
    gamma: float
    neutral_angle_deg: float
    tube: Tube

    @property
    def has_sleeve(self) -> bool:
        """True when r0 > r_f, i.e. an inflation phase exists."""
        return self.r0_mm > self.tube.outer_radius_mm

    @property
    def bends_positive(self) -> bool:
        """Initial bending direction: dV/dl > 0 at theta = 0 (zigzag always; cross if tan beta0 < 1/2)."""
        return model_kind(self.pattern).bends_positive(self.beta0_deg)

    def as_dict(self) -> dict:
        """Plain dict with unit-suffixed keys (for JSON and reports).

        Returns
        -------
        dict
            Every field but the tube, and ``min_sleeve_width_mm``, ``has_sleeve``, ``bends_positive``.

        Examples
        --------
        >>> from embroact.patterns.params import Tube
        >>> d = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
        >>> d.as_dict()["min_sleeve_width_mm"] == float(min_sleeve_width_mm(1.5)), "tube" in d.as_dict()
        (True, False)
        """
        return geometry_dict(self)


#: The fields of a sleeve geometry in its dict, in order (a segment's and the whole strip's alike).
GEOMETRY_KEYS = ("name", "pattern", "length_mm", "width_mm", "interval_mm", "angle_deg", "requested_width_mm",
                 "requested_interval_mm", "requested_angle_deg", "r0_mm", "beta0_deg", "gamma", "neutral_angle_deg")


def geometry_dict(geometry) -> dict:
    """The dict of a segment's or a whole strip's sleeve geometry: :data:`GEOMETRY_KEYS`, then
    ``min_sleeve_width_mm``, ``has_sleeve`` and ``bends_positive``.

    Parameters
    ----------
    geometry : DerivedGeometry or StripGeometry
        Anything with those fields and a ``tube``.

    Returns
    -------
    dict

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> d = derive_from_values("zigzag", width_mm=7.0, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
    >>> list(geometry_dict(d))[-3:]
    ['min_sleeve_width_mm', 'has_sleeve', 'bends_positive']
    """
    d = {k: getattr(geometry, k) for k in GEOMETRY_KEYS}
    d["min_sleeve_width_mm"] = float(min_sleeve_width_mm(geometry.tube.outer_radius_mm))
    d["has_sleeve"] = geometry.has_sleeve
    bends = geometry.bends_positive
    d["bends_positive"] = None if bends is None else bool(bends)
    return d


def derive_from_values(
    pattern: str,
    *,
    width_mm: float,
    interval_mm: float,
    angle_deg: float,
    length_mm: float,
    tube: Tube,
    name: str = "actuator",
    requested: tuple[float, float, float] | None = None,
) -> DerivedGeometry:
    """Derived geometry from realised values (used directly by quick commands).

    Parameters
    ----------
    pattern : str
        A registered pattern kind.
    width_mm, interval_mm, length_mm : float
        Realised rail spacing, stitch interval and length [mm], > 0.
    angle_deg : float
        Realised embroidery angle [deg], in (0, 90) for a kind with an angle.
    tube : Tube
        The tube.
    name : str, optional
        The actuator's name.
    requested : tuple of float or None, optional
        What was asked for: (width_mm, interval_mm, angle_deg); None: the realised values.

    Returns
    -------
    DerivedGeometry

    Examples
    --------
    >>> from embroact.patterns.params import Tube
    >>> d = derive_from_values("cross", width_mm=7.0, interval_mm=1.4, angle_deg=45.0, length_mm=100.0, tube=Tube())
    >>> round(d.r0_mm, 4), round(d.beta0_deg, 4), d.requested_angle_deg
    (2.5814, 37.2078, 45.0)
    """
    kind = model_kind(pattern)
    w = check_range("width_mm", width_mm, low=0.0)
    s = check_range("interval_mm", interval_mm, low=0.0)
    l0 = check_range("length_mm", length_mm, low=0.0)
    a = check_range("angle_deg", angle_deg, low=0.0, high=90.0) if pattern_kind(pattern).has_angle else float(angle_deg)
    beta0 = kind.beta0_deg(w, a, tube.outer_radius_mm)
    r0, neutral = _sleeve_of_width(w, float(tube.outer_radius_mm))
    req = requested if requested is not None else (w, s, a)
    return DerivedGeometry(
        name=name,
        pattern=pattern,
        length_mm=l0,
        width_mm=w,
        interval_mm=s,
        angle_deg=a,
        requested_width_mm=float(req[0]),
        requested_interval_mm=float(req[1]),
        requested_angle_deg=float(req[2]),
        r0_mm=r0,
        beta0_deg=beta0,
        gamma=float(gamma(r0, beta0, l0)),
        neutral_angle_deg=neutral,
        tube=tube,
    )


@functools.lru_cache(maxsize=256)
def _sleeve_of_width(width_mm: float, outer_radius_mm: float) -> tuple[float, float]:
    """(sleeve radius r0 [mm], neutral angle [deg]) of a width on a tube: kept, as a search over a cross pattern's
    angle derives hundreds of designs of one width."""
    return float(sleeve_radius_mm(width_mm, outer_radius_mm)), float(neutral_angle_deg(width_mm, outer_radius_mm))


def derive(actuator: ActuatorPlan) -> DerivedGeometry:
    """Derived geometry of one generated single-pattern actuator (a chain of one), from its realised parameters.

    Parameters
    ----------
    actuator : ActuatorPlan
        A generated actuator of one segment (a longer chain: :class:`ParameterError`; each segment is
        derived from :func:`~embroact.predict.analysis.segment_plans`).

    Returns
    -------
    DerivedGeometry

    Examples
    --------
    >>> from embroact.patterns.zigzag import zigzag
    >>> from embroact.patterns.params import ZigzagParams
    >>> d = derive(zigzag([[0.0, 0.0], [100.0, 0.0]], ZigzagParams(7.0, 1.0), name="A1").actuators[0])
    >>> d.name, d.width_mm, d.length_mm
    ('A1', 7.0, 100.0)
    """
    seg = actuator.segments.single(f"actuator {actuator.name!r} has {len(actuator.segments)} segments: derive each "
                                   "(embroact.predict.analysis.segment_plans), the whole strip is "
                                   "embroact.predict.strip.strip_geometry of them")
    r, p = seg.realised, seg.params
    return derive_from_values(
        seg.pattern,
        width_mm=r.width_mm,
        interval_mm=r.interval_mm,
        angle_deg=r.angle_deg if pattern_kind(seg.pattern).has_angle else 0.0,
        length_mm=r.length_mm,
        tube=actuator.tube,
        name=actuator.name,
        requested=(p.width_mm, p.interval_mm, seg.requested_angle_deg),
    )
