"""The calibration is read where the machine sews: at the coordinate the needle points realise.

A quick ``--width-mm 6.1`` zigzag on a straight path sews rails 6.0 mm apart (every format holds
0.1 mm units); its prediction must be the one of the decoded file, whose needle points say 6.0 mm,
not one from G and P0 interpolated at the 6.1 mm nobody sews. A cross asked for 30 deg at s = 1.4 mm
sews tan(alpha0) = 3/5; its G and P0 are the calibration's monotone cubic at atan(3/5), computed here
by hand from the paper's table. A sewn coupon's fitted point is keyed by the coupon's realised
geometry, so a design sewn like it is that point exactly, float noise included.
"""
import io
import json
import math

import numpy as np
import pytest
import pyembroidery
from paper_sewn import A30_DEG, SEWN_FIT

from embroact.export.cli.main import main
from embroact.export.machine.formats import encode
from embroact.patterns.design import ActuatorSpec, Design, MachineSettings, OperationSettings, build_plan
from embroact.patterns.centerline import Centerline
from embroact.patterns.measure import measure
from embroact.patterns.params import CrossParams, Tube, ZigzagParams
from embroact.patterns.plan import Command
from embroact.predict.calibration import CalibrationSet, lookup, lookup_design, model_for
from embroact.predict.curve import curve
from embroact.predict.derived import derive, derive_from_values
from embroact.predict.fit import fit_design, model_predictor


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def _pyembroidery_points_mm(data: bytes, origin_mm) -> np.ndarray:
    """Needle points [mm, plan frame] of DST bytes as pyembroidery reads them (y down in its frame)."""
    pattern = pyembroidery.read_dst(io.BytesIO(data))
    xy = [(x, -y) for x, y, c in pattern.stitches if c & pyembroidery.COMMAND_MASK == pyembroidery.STITCH]
    return np.asarray(xy, dtype=np.float64) / 10.0 + np.asarray(origin_mm, dtype=np.float64)


def _quick(params) -> Design:
    """One 100 mm actuator on a straight path along +x from the origin (the quick commands move it half a grid unit
    across for an odd width)."""
    return Design("quick", Tube(), MachineSettings(), OperationSettings(),
                  (ActuatorSpec("A1", params, Centerline.straight(100.0)),))


def _decoded_derived(design: Design):
    """Derived geometry measured on the needle points pyembroidery decodes from the design's DST (which does not
    know what the design asked for: its requested values are the measured ones)."""
    plan = build_plan(design)
    data, res = encode(plan, "dst")
    xy = _pyembroidery_points_mm(data, res.origin_mm)
    roles = plan.roles[plan.commands == Command.STITCH]
    assert len(xy) == len(roles)
    spec = design.actuators[0]
    r = measure(xy, roles, plan.actuators[0].centerline, spec.pattern)
    angle = r.angle_deg if hasattr(spec.params, "angle_deg") else 0.0
    return derive_from_values(spec.pattern, width_mm=r.width_mm, interval_mm=r.interval_mm, angle_deg=angle,
                              length_mm=r.length_mm, tube=design.tube), xy


def test_quick_prediction_is_the_decoded_files(capsys):
    """predict on a design file asking 6.1 mm on the path y = 0 = the bend predicted from the decoded DST's needle
    points, to 1e-9 deg; the rails the file holds are 6.0 mm apart (+-3.05 rounds to +-3.0 on the 0.1 mm grid), so G
    and P0 are the calibration's at 6.0 mm, and JSON says both. The quick command lays its path half a grid unit
    across and sews 6.1 (tests/test_rules.py)."""
    import tempfile
    from pathlib import Path

    from embroact.export.files.tomltext import dumps

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "w61.toml"
        path.write_text(dumps({"name": "quick", "actuator": [{"name": "A1", "pattern": "zigzag", "width_mm": 6.1,
                                                             "interval_mm": 1.0, "length_mm": 100.0}]}))
        got = _json(capsys, ["predict", str(path), "--pressure-kpa", "100,150,200", "--json"])
    a = got["actuators"][0]
    d, xy = _decoded_derived(_quick(ZigzagParams(6.1, 1.0)))
    assert xy[:, 1].max() - xy[:, 1].min() == pytest.approx(6.0, abs=1e-12)  # the rails the file holds
    assert d.width_mm == pytest.approx(6.0, abs=1e-12)
    theta = curve(model_for(d).model, [100.0, 150.0, 200.0]).theta_deg
    assert np.asarray(a["theta_deg"]) == pytest.approx(np.asarray(theta), abs=1e-9)
    cal = a["model"]["calibration"]
    assert (cal["parameter"], cal["value"], cal["requested_value"]) == ("width_mm", pytest.approx(6.0), 6.1)
    assert "width_mm=6, requested 6.1" in a["model"]["g_source"]
    six = _json(capsys, ["predict", "zigzag", "--width-mm", "6.0", "--pressure-kpa", "100,150,200", "--json"])
    assert six["actuators"][0]["theta_deg"] == pytest.approx(a["theta_deg"], abs=1e-9)
    assert six["actuators"][0]["model"]["calibration"]["requested_value"] is None
    assert a["theta_deg"][1] == pytest.approx(96.571, abs=5e-4)  # was 88.938 with G, P0 at 6.1 mm


def test_quick_cross_prediction_is_the_decoded_files(capsys):
    """The same for a cross asked for 30 deg: the decoded legs sew tan(alpha0) = 3/5, and predict agrees to 1e-9 deg."""
    got = _json(capsys, ["predict", "cross", "--width-mm", "7", "--angle-deg", "30", "--pressure-kpa", "200,300",
                         "--json"])["actuators"][0]
    d, _ = _decoded_derived(_quick(CrossParams(7.0, 1.4, 30.0)))
    assert math.tan(math.radians(d.angle_deg)) == pytest.approx(0.6, abs=1e-12)
    theta = curve(model_for(d).model, [200.0, 300.0]).theta_deg
    assert np.asarray(got["theta_deg"]) == pytest.approx(np.asarray(theta), abs=1e-9)


def test_cross_calibration_is_interpolated_at_the_realised_angle(capsys):
    """cross w 7, s 1.4, alpha0 30 sews tan(alpha0) = 3/5 (30.96 deg); G and P0 are the paper's table read by hand
    there (tests/paper_sewn.py), in the lookup, the model and predict's JSON."""
    alpha = A30_DEG
    g, p0 = SEWN_FIT["cross a30"]
    d = derive(build_plan(_quick(CrossParams(7.0, 1.4, 30.0))).actuators[0])
    assert d.angle_deg == pytest.approx(alpha, abs=1e-9) and d.requested_angle_deg == 30.0
    c = lookup_design(d)
    assert (c.g_mpa, c.p0_kpa) == (pytest.approx(g, rel=1e-12), pytest.approx(p0, rel=1e-12))
    assert c.interpolated and c.requested_value == 30.0 and c.value == pytest.approx(alpha, abs=1e-9)
    got = _json(capsys, ["predict", "cross", "--width-mm", "7", "--angle-deg", "30", "--pressure-kpa", "250",
                         "--json"])["actuators"][0]["model"]
    assert (got["g_mpa"], got["p0_kpa"]) == (pytest.approx(g, rel=1e-12), pytest.approx(p0, rel=1e-12))
    assert got["calibration"]["requested_value"] == 30.0
    assert f"angle_deg={alpha:g}, requested 30, interpolated in [15, 60]" in got["g_source"]


def test_float_noise_hits_a_calibrated_point():
    """A width a float's last bit off a calibrated one is that point: its G and P0 exactly, not interpolated."""
    for w in (7.0 + 2**-50, 7.0 - 2**-50, 8.600000000000001 - 1.6):
        c = lookup("zigzag", width_mm=w)
        assert (c.g_mpa, c.p0_kpa, c.interpolated, c.extrapolated) == (2.7, 85.0, False, False)


def test_a_fitted_point_is_keyed_by_the_coupons_realised_geometry():
    """A coupon asked for 30 deg sews atan(3/5): the fitted point sits at the realised angle, and a design sewn
    like the coupon (asked for 30.5 deg, which sews the same legs) gets that point's G and P0 exactly."""
    d = derive(build_plan(_quick(CrossParams(7.0, 1.4, 30.0))).actuators[0])
    p = np.arange(0.0, 301.0, 25.0)
    (r,) = fit_design(d, p, model_predictor(d)(p, 6.0, 120.0, None), branch="loading")
    pt = r.to_point()
    assert pt.angle_deg == pytest.approx(math.degrees(math.atan(0.6)), abs=1e-9) and pt.interval_mm == 1.4
    other = derive(build_plan(_quick(CrossParams(7.0, 1.4, 30.5))).actuators[0])
    assert other.requested_angle_deg == 30.5 and other.angle_deg == pytest.approx(d.angle_deg, abs=1e-12)
    c = lookup_design(other, name="lab", sets=[CalibrationSet("lab", (pt,))])
    assert (c.g_mpa, c.p0_kpa, c.interpolated, c.extrapolated) == (pt.g_mpa, pt.p0_kpa, False, False)
    assert c.requested_value == 30.5
