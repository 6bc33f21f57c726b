"""``design`` with a calibration that records covariances prefers the design whose 1-sigma band is narrow.

A hand-made profile: zigzag widths 5-9 mm and cross angles on both sides of the neutral angle, G and
P0 smooth along each coordinate, every point with a diagonal covariance; the zigzag points and the
cross points get covariances that differ by a factor of 4. A target that a zigzag and a cross both
meet is then designed twice, the factor on one pattern and then on the other: the winner is the
candidate with the narrower band each time, and so changes pattern with the covariances alone.
"""
import pytest

from embroact.patterns.design import ModelSettings
from embroact.patterns.params import Tube
from embroact.predict.calibration import CalibrationPoint, CalibrationSet, CalibrationTube
from embroact.predict.inverse import design_bend

TARGET_DEG, AT_KPA, TOLERANCE_DEG = 60.0, 200.0, 3.0
CROSS_ANGLES_DEG = (16.6992, 21.8014, 26.5651, 38.6598, 45.0, 52.4314)


def _profile(zigzag_scale, cross_scale):
    def point(pattern, width_mm, g_mpa, p0_kpa, scale, **kw):
        return CalibrationPoint(pattern, width_mm, g_mpa, p0_kpa, branch="loading", fitted=("g_mpa", "p0_kpa"),
                                covariance=((scale * 1e-3, 0.0), (0.0, scale * 2.0)), **kw)

    pts = [point("zigzag", w, 3.0 + 0.4 * (w - 7.0), 40.0 + 25.0 * (w - 5.0), zigzag_scale)
           for w in (5.0, 6.0, 7.0, 8.0, 9.0)]
    pts += [point("cross", 7.0, 2.0 + 0.03 * abs(a - 33.4), 90.0 + a, cross_scale, angle_deg=a, interval_mm=1.4)
            for a in CROSS_ANGLES_DEG]
    return CalibrationSet("banded", tuple(pts), tube=CalibrationTube.of(Tube()))


def _design(pattern, zigzag_scale, cross_scale):
    return design_bend(TARGET_DEG, AT_KPA, pattern=pattern, settings=ModelSettings(calibration="banded"),
                       sets=[_profile(zigzag_scale, cross_scale)], tolerance_deg=TOLERANCE_DEG)


@pytest.mark.parametrize(("zigzag_scale", "cross_scale", "winner"), [(1.0, 4.0, "zigzag"), (4.0, 1.0, "cross")])
def test_the_narrower_band_wins_among_designs_that_meet_the_target(zigzag_scale, cross_scale, winner):
    each = {pattern: _design(pattern, zigzag_scale, cross_scale).best for pattern in ("zigzag", "cross")}
    for c in each.values():  # both meet the target, cleanly, with a band
        assert abs(c.theta_deg - TARGET_DEG) <= TOLERANCE_DEG and c.warning_count == 0 and c.theta_sd_deg > 0
    loser = "cross" if winner == "zigzag" else "zigzag"
    assert each[loser].theta_sd_deg > 1.5 * each[winner].theta_sd_deg
    r = _design("any", zigzag_scale, cross_scale)
    assert r.reached and r.best.pattern == winner and r.best.theta_sd_deg == each[winner].theta_sd_deg
    assert f"bends {r.best.theta_deg:.2f} deg (+- {r.best.theta_sd_deg:.2f} deg, 1 sigma of the calibration) at" in r.statement
    # the cross meets it more closely either way: the band, not the distance to the target, decides
    assert abs(each["cross"].theta_deg - TARGET_DEG) < abs(each["zigzag"].theta_deg - TARGET_DEG)
