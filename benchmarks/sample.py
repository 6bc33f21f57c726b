"""The benchmark's fixed, seeded design sample and its 50-digit reference answers.

Designs cover both patterns, widths 4-12 mm (stratified), cross angles 5-80 deg
(stratified) and effective moduli G 0.8-12 MPa (log-uniform, the paper's fitted
range), on the default tube; P0 comes from the paper's tube law. Each design's
pressures run from 0 to the pressure at ``END_FRACTION`` of its stable branch
(lock-up, fold or ``MAX_SAMPLE_BEND_DEG``), evenly spaced in angle, so every sampled
pressure above P0 has a stable equilibrium and the whole branch is covered.

The reference is ``tests/mpref.py`` (docs/model.md re-typed in mpmath, 50 digits), reused
here, not copied: each sampled pressure is ``P_ref`` at a grid angle, and its reference
angle is that grid angle Newton-corrected at 60 digits for the rounding of the pressure
to float64 (no embroact solver is involved).

Examples
--------
>>> from sample import sample_designs
>>> [d.pattern for d in sample_designs(4)]
['zigzag', 'cross', 'zigzag', 'cross']
"""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from pathlib import Path

import mpmath as mp
import numpy as np

from embroact.patterns.params import Tube
from embroact.predict.curve import ActuatorModel, lockup
from embroact.predict.derived import derive_from_values

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from mpref import DIGITS, Ref  # noqa: E402  (the tests' reference, reused)

__all__ = ["SEED", "Design", "sample_designs", "design", "branch_sample_end_deg", "reference_points",
           "reference_point"]

SEED = 20251027
WIDTH_RANGE_MM = (4.0, 12.0)
ANGLE_RANGE_DEG = (5.0, 80.0)
G_RANGE_MPA = (0.8, 12.0)
#: Fraction of the stable branch (in angle) that the sampled pressures reach.
END_FRACTION = 0.95
#: Largest bend sampled [deg] (one full roll of the strip; the model goes further).
MAX_SAMPLE_BEND_DEG = 360.0
#: Share of each design's pressures below P0 (inflation phase, angle 0).
INFLATION_SHARE = 0.1
#: Relative step of the secant slope used in the reference's Newton correction.
_SLOPE_STEP = mp.mpf(10) ** -25
_KPA_PER_MPA = 1000


@dataclass(frozen=True, slots=True)
class Design:
    """One sampled actuator: its parameters, the embroact model and the reference."""

    name: str
    pattern: str
    width_mm: float
    angle_deg: float
    g_mpa: float
    model: ActuatorModel

    def ref(self) -> Ref:
        """The 50-digit reference of exactly this model's float64 inputs."""
        m = self.model
        return Ref(m.pattern, l0=m.length_mm, r0=m.r0_mm, beta0=mp.radians(mp.mpf(m.beta0_deg)),
                   rf=m.outer_radius_mm, df=m.inner_radius_mm, g=m.g_mpa, p0=mp.mpf(m.p0_kpa) / _KPA_PER_MPA)

    def as_dict(self) -> dict:
        return {"name": self.name, "pattern": self.pattern, "width_mm": self.width_mm, "angle_deg": self.angle_deg,
                "g_mpa": self.g_mpa, "p0_kpa": self.model.p0_kpa, "beta0_deg": self.model.beta0_deg}


def design(pattern: str, width_mm: float, angle_deg: float, g_mpa: float, name: str = "") -> Design:
    """A design on the default tube, P0 from the paper's law (interval 1 mm: the model ignores it)."""
    derived = derive_from_values(pattern, width_mm=width_mm, interval_mm=1.0, angle_deg=angle_deg,
                                 length_mm=100.0, tube=Tube())
    model = ActuatorModel.from_derived(derived, g_mpa=g_mpa, calibration="benchmark")
    return Design(name or f"{pattern}-w{width_mm:.2f}-a{angle_deg:.1f}-G{g_mpa:.2f}", pattern,
                  float(width_mm), float(angle_deg), float(g_mpa), model)


def _stratified(rng, n: int, lo: float, hi: float) -> np.ndarray:
    return lo + (hi - lo) * (rng.permutation(n) + rng.uniform(size=n)) / n


def sample_designs(n: int, *, seed: int = SEED) -> list[Design]:
    """``n`` designs, alternately zigzag and cross, stratified over width and angle."""
    rng = np.random.default_rng(seed)
    widths = _stratified(rng, n, *WIDTH_RANGE_MM)
    angles = _stratified(rng, n, *ANGLE_RANGE_DEG)
    g = np.exp(rng.uniform(math.log(G_RANGE_MPA[0]), math.log(G_RANGE_MPA[1]), size=n))
    out = []
    for i in range(n):
        pattern = ("zigzag", "cross")[i % 2]
        out.append(design(pattern, round(float(widths[i]), 3), round(float(angles[i]), 2) if pattern == "cross"
                          else 0.0, round(float(g[i]), 3), name=f"{pattern[0]}{i:02d}"))
    return out


def branch_sample_end_deg(d: Design) -> float:
    """Largest sampled bend [deg]: ``END_FRACTION`` of the stable branch, at most ``MAX_SAMPLE_BEND_DEG``."""
    theta_end, _ = lockup(d.model)
    return math.copysign(min(END_FRACTION * abs(theta_end), MAX_SAMPLE_BEND_DEG), theta_end)


def reference_points(d: Design, n: int) -> tuple[np.ndarray, np.ndarray]:
    """``n`` ascending pressures [kPa] and their reference angles [deg].

    ``INFLATION_SHARE`` of the points lie below P0 (angle 0); the others are the
    reference pressures at angles evenly spaced over the sampled branch, rounded
    to float64, with their reference angles from :func:`reference_point`.
    """
    ref = d.ref()
    n_infl = max(1, int(round(n * INFLATION_SHARE)))
    theta_max = branch_sample_end_deg(d)
    pressures = np.empty(n)
    theta = np.zeros(n)
    pressures[:n_infl] = np.linspace(0.0, d.model.p0_kpa, n_infl, endpoint=False)
    for k, t in enumerate(np.linspace(0.0, theta_max, n - n_infl + 1)[1:], start=n_infl):
        pressures[k], theta[k], _ = reference_point(ref, t)
    return pressures, theta


def reference_point(ref: Ref, theta_deg: float) -> tuple[float, float, float]:
    """(P_ref(theta) rounded to float64 [kPa], the reference angle of that rounded pressure [deg],
    the slope dP/dtheta there [kPa/deg]).

    The angle is ``theta`` corrected by one Newton step at 60 digits for the rounding,
    ``(P - P_ref(theta)) / P_ref'(theta)``; the correction is ~1e-16 relative, so its own
    error is ~1e-32 (the slope is a secant over a relative step of 1e-25).
    """
    with mp.workdps(DIGITS + 10):
        t = mp.radians(mp.mpf(theta_deg))
        p_t = ref.pressure(t)
        slope = (ref.pressure(t * (1 + _SLOPE_STEP)) - p_t) / (t * _SLOPE_STEP)
        p = float(p_t * _KPA_PER_MPA)
        return p, float(mp.degrees(t + (mp.mpf(p) / _KPA_PER_MPA - p_t) / slope)), float(slope * _KPA_PER_MPA
                                                                                          / mp.degrees(1))
