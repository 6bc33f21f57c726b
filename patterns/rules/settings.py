"""Thresholds of the design rules: :class:`RuleSettings`.

Examples
--------
>>> from embroact.patterns.rules.settings import RuleSettings
>>> s = RuleSettings(hoop_width_mm=200.0, hoop_height_mm=200.0)
>>> s.trim_jump_count, s.couching_gap_mm(1.5)
(3, 9.0)
"""
from __future__ import annotations

from dataclasses import dataclass, field

from ..base.errors import ParameterError, check_range
from ..base.tolerances import DEFAULT_TOLERANCES, Tolerances
from ..limits import MAX_STITCH_MM, MIN_STITCH_MM, TRIM_JUMP_RUN, format_limit

__all__ = ["RuleSettings"]


@dataclass(frozen=True, slots=True)
class RuleSettings:
    """Thresholds of the geometric, sleeve and file-level rules.

    Parameters
    ----------
    format : str
        Target machine format (per-record limits from ``patterns/limits.py``).
    min_stitch_mm, max_stitch_mm : float
        Machine stitch-length limits [mm] (EA104, EA103).
    hoop_width_mm, hoop_height_mm : float or None
        Sewing field [mm]; None skips the hoop rules (EA306, EA305's hoop part).
    density_radius_mm : float
        Radius of the density count [mm] (Ink/Stitch: 0.5).
    density_warning_count, density_error_count : int
        Needle points within the radius, the point itself included, for a warning (3) / error (6).
    min_sleeve_gap_mm : float
        Smallest r0 - r_f without a warning [mm] (EA202).
    turning_radius_factor : float
        Minimum tube turning radius in tube outer diameters (EA301).
    neutral_band_deg : float
        Half width of the band around the neutral angle that is flagged [deg] (EA206).
    actuator_clearance_mm : float
        Smallest gap between two actuators' stitched bands [mm] (EA304).
    couching_gap_factor : float
        Longest stretch of a tube that no leg holds, in tube outer diameters (EA307; default 3:
        9 mm for r_f = 1.5 mm, three times the spacing at which EA203 warns).
    trim_jump_count : int
        Consecutive jump records the machine reads as a trim (EA501).
    max_records : int or None
        Machine memory limit on records; None uses the format's limit (EA504).
    max_findings_per_rule : int
        Findings listed per rule; the rest are summarised in one more finding.
    tolerances : Tolerances
        Shared thresholds (:data:`~embroact.patterns.base.tolerances.DEFAULT_TOLERANCES`).

    Examples
    --------
    >>> s = RuleSettings(format="pes", hoop_width_mm=100.0, hoop_height_mm=100.0)
    >>> s.format, s.max_stitch_mm, s.couching_gap_mm(1.5)
    ('pes', 12.1, 9.0)
    """

    format: str = "dst"
    min_stitch_mm: float = MIN_STITCH_MM
    max_stitch_mm: float = MAX_STITCH_MM
    hoop_width_mm: float | None = None
    hoop_height_mm: float | None = None
    density_radius_mm: float = 0.5
    density_warning_count: int = 3
    density_error_count: int = 6
    min_sleeve_gap_mm: float = 0.1
    turning_radius_factor: float = 3.0
    neutral_band_deg: float = 3.0
    actuator_clearance_mm: float = 1.0
    couching_gap_factor: float = 3.0
    trim_jump_count: int = TRIM_JUMP_RUN
    max_records: int | None = None
    max_findings_per_rule: int = 10
    tolerances: Tolerances = field(default_factory=lambda: DEFAULT_TOLERANCES)

    def __post_init__(self) -> None:
        format_limit(self.format)
        check_range("min_stitch_mm", self.min_stitch_mm, low=0.0, low_inclusive=True, high=100.0)
        check_range("max_stitch_mm", self.max_stitch_mm, low=self.min_stitch_mm, high=1000.0)
        for name in ("hoop_width_mm", "hoop_height_mm"):
            if getattr(self, name) is not None:
                check_range(name, getattr(self, name), low=0.0, high=1e4)
        check_range("density_radius_mm", self.density_radius_mm, low=0.0, high=100.0)
        check_range("min_sleeve_gap_mm", self.min_sleeve_gap_mm, low=0.0, low_inclusive=True, high=100.0)
        check_range("turning_radius_factor", self.turning_radius_factor, low=0.0, low_inclusive=True, high=1e3)
        check_range("neutral_band_deg", self.neutral_band_deg, low=0.0, low_inclusive=True, high=90.0)
        check_range("actuator_clearance_mm", self.actuator_clearance_mm, low=0.0, low_inclusive=True, high=1e3)
        check_range("couching_gap_factor", self.couching_gap_factor, low=0.0, high=1e3)
        for name in ("density_warning_count", "density_error_count", "trim_jump_count", "max_findings_per_rule"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < 1:
                raise ParameterError(f"{name} must be an integer >= 1, got {v!r}")

    @classmethod
    def for_machine(cls, machine, *, format: str | None = None, **overrides) -> "RuleSettings":
        """Settings from a design's machine settings (``format``, hoop and stitch limits).

        Parameters
        ----------
        machine : MachineSettings or alike
            Any object with the attributes of ``MachineSettings`` (``format``,
            ``hoop_width_mm``, ``hoop_height_mm``, ``min_stitch_mm``, ``max_stitch_mm``).
        format : str or None, optional
            Check for this format instead of ``machine.format``.
        **overrides
            Any other field.

        Returns
        -------
        RuleSettings

        Examples
        --------
        >>> from types import SimpleNamespace
        >>> m = SimpleNamespace(format="dst", min_stitch_mm=0.3, max_stitch_mm=12.1, hoop_width_mm=130.0,
        ...                     hoop_height_mm=180.0)
        >>> s = RuleSettings.for_machine(m, format="exp", max_findings_per_rule=3)
        >>> s.format, s.hoop_height_mm, s.max_findings_per_rule
        ('exp', 180.0, 3)
        """
        base = dict(
            format=format or machine.format,
            min_stitch_mm=machine.min_stitch_mm,
            max_stitch_mm=machine.max_stitch_mm,
            hoop_width_mm=machine.hoop_width_mm,
            hoop_height_mm=machine.hoop_height_mm,
        )
        base.update(overrides)
        return cls(**base)

    def couching_gap_mm(self, outer_radius_mm: float) -> float:
        """Longest unheld stretch allowed for a tube of radius ``outer_radius_mm`` [mm] (EA307).

        Parameters
        ----------
        outer_radius_mm : float
            The tube's outer radius r_f [mm].

        Returns
        -------
        float
            ``couching_gap_factor`` outer diameters [mm].

        Examples
        --------
        >>> RuleSettings(couching_gap_factor=2.0).couching_gap_mm(1.5)
        6.0
        """
        return self.couching_gap_factor * 2.0 * outer_radius_mm
