"""The one analysis: every number computed once, policy applied once, bands from a fitted covariance."""
import dataclasses

import numpy as np
import pytest
from paper_sewn import A30_DEG, SEWN_FIT

from embroact.patterns.design import ModelSettings, default_design, design_from_dict
from embroact.patterns.params import Tube
from embroact.predict.analysis import analyse, pressure_grid_kpa, with_model_overrides
from embroact.predict.calibration import CalibrationPoint, CalibrationSet, CalibrationTube
from embroact.predict.curve import ActuatorModel, curve
from embroact.predict.derived import derive


def _lab_set(cov=((0.01, 0.05), (0.05, 4.0))):
    point = CalibrationPoint("zigzag", 7.0, 2.7, 85.0, interval_mm=1.0, fitted=("g_mpa", "p0_kpa"), covariance=cov)
    return CalibrationSet("lab", (point,), tube=CalibrationTube.of(Tube()), measurement="whole-strip")


def test_analysis_models_the_realised_geometry_with_the_set_pair():
    a = analyse(default_design()).actuators[0]
    assert a.segments[0].derived == derive(a.plan)  # measured on the generated stitches
    assert a.derived.as_dict() == a.segments[0].derived.as_dict()  # a chain of one: the whole strip is its segment
    assert (a.model.g_mpa, a.model.p0_kpa) == (2.7, 85.0)  # the paper's fitted pair for w = 7 mm
    assert a.model.r0_mm == a.derived.r0_mm and a.model.length_mm == a.derived.length_mm


def test_cross_calibration_is_looked_up_at_the_realised_angle():
    d = design_from_dict({"actuator": [{"name": "X", "pattern": "cross", "width_mm": 7, "interval_mm": 1.4,
                                        "angle_deg": 30, "length_mm": 100, "adjust": "angle"}]})
    x = analyse(d).actuators[0]
    assert x.derived.angle_deg == pytest.approx(A30_DEG, abs=1e-9)  # the generator closed the pattern
    # the paper's table read at the sewn angle, by hand (tests/paper_sewn.py), not its alpha0 = 30 point
    assert (x.model.g_mpa, x.model.p0_kpa) == pytest.approx(SEWN_FIT["cross a30"], rel=1e-12)
    assert x.model.beta0_deg == pytest.approx(x.derived.beta0_deg)  # model of what was sewn


def test_curves_are_computed_once_and_equal_the_api():
    a = analyse(default_design())
    c = a.curves()
    assert a.curves() is c
    ref = curve(a.actuators[0].segments[0].model, pressure_grid_kpa(300.0))
    np.testing.assert_array_equal(c[0].theta_deg, ref.theta_deg)
    assert c[0].pressure_kpa.tolist() == [10.0 * k for k in range(31)]


def test_overrides_follow_flag_over_design_over_default():
    d = with_model_overrides(default_design(), g_mpa=1.0, p0_source="geometry")
    a = analyse(d).actuators[0]
    x = a.derived.r0_mm / 1.5
    assert a.model.g_mpa == 1.0 and a.choice.g_source == "given"
    assert a.model.p0_kpa == pytest.approx(0.13 / 2.0 * (x - 1.0 / x) ** 2 * 1000.0, rel=1e-12)  # tube law at r0
    with pytest.raises(ValueError, match="model override must be a ModelSettings field"):
        with_model_overrides(default_design(), g=1.0)


def test_no_sleeve_is_refused_by_the_model_not_predicted_as_bending():
    from embroact.predict.derived import derive_from_values

    # r0 <= r_f when w <= (pi^2 - 4)/pi r_f = 2.80 mm for r_f = 1.5 mm (a generator cannot make it: it needs
    # w/2 > r_f + clearance, but the API takes any values)
    d = derive_from_values("zigzag", width_mm=2.5, interval_mm=1.0, angle_deg=0.0, length_mm=100.0, tube=Tube())
    assert not d.has_sleeve
    with pytest.raises(ValueError, match="no sleeve"):
        ActuatorModel.from_derived(d, g_mpa=1.0)


def test_band_only_from_a_fitted_covariance_and_equal_to_linear_propagation():
    paper = analyse(default_design())
    assert paper.bands([150.0]) == (None,)  # the paper set carries no covariance: no band claimed
    design = with_model_overrides(default_design(), calibration="lab")
    cov = np.array([[0.01, 0.05], [0.05, 4.0]])
    a = analyse(design, calibration_sets=[_lab_set()])
    p = np.array([120.0, 200.0, 260.0])
    band = a.bands(p)[0]
    # independent check: central differences of the curve in (G, P0), sd^2 = J C J^T
    m = a.actuators[0].segments[0].model
    def theta(g, p0):
        return curve(dataclasses.replace(m, g_mpa=g, p0_kpa=p0), p).theta_deg
    hg, hp = 1e-4, 1e-3
    jac = np.stack([(theta(m.g_mpa + hg, m.p0_kpa) - theta(m.g_mpa - hg, m.p0_kpa)) / (2 * hg),
                    (theta(m.g_mpa, m.p0_kpa + hp) - theta(m.g_mpa, m.p0_kpa - hp)) / (2 * hp)], axis=1)
    sd = np.sqrt(np.einsum("ij,jk,ik->i", jac, cov, jac))
    np.testing.assert_allclose(band.theta_sd_deg, sd, rtol=1e-4)
    given = analyse(with_model_overrides(design, g_mpa=2.7), calibration_sets=[_lab_set()])
    assert given.bands(p) == (None,)  # a given G is not the fitted pair: its covariance does not apply


def test_covariance_is_validated():
    with pytest.raises(ValueError, match="covariance must be 2 x 2"):
        CalibrationPoint("zigzag", 7.0, 2.7, 85.0, fitted=("g_mpa", "p0_kpa"), covariance=((1.0,),))
    with pytest.raises(ValueError, match="symmetric"):
        CalibrationPoint("zigzag", 7.0, 2.7, 85.0, fitted=("g_mpa", "p0_kpa"), covariance=((1.0, 0.1), (0.2, 1.0)))


def test_tube_other_than_the_calibrated_one_is_noted():
    design = with_model_overrides(dataclasses.replace(default_design(), tube=Tube(outer_radius_mm=1.6)),
                                  calibration="lab")
    a = analyse(design, calibration_sets=[_lab_set()]).actuators[0]
    assert a.choice.notes == ("tube outer_radius_mm 1.6 (calibrated with 1.5)",)
    assert ModelSettings().p0_source.value == "calibration"


def test_first_leg_is_where_the_projected_legs_start():
    """The analysis takes the legs' start from the measurement of the generated stitches; it is the
    smallest arc length of both ends of every leg, projected again here on a curved, moved path."""
    from embroact.patterns.plan import Role

    d = design_from_dict({"name": "s", "actuator": [{"name": "A", "pattern": "cross", "width_mm": 7.0,
                                                      "interval_mm": 1.4, "angle_deg": 30.0, "origin_mm": [40, -20],
                                                      "path": [[60.0 * np.sin(t), 60.0 * (1.0 - np.cos(t))]
                                                               for t in np.linspace(0.0, 1.2, 40)]}]})
    a = analyse(d)
    plan = a.plan
    legs = np.flatnonzero((plan.actuator == 0) & (plan.roles == Role.LEG))
    s, _ = plan.actuators[0].centerline.project(plan.xy_mm[np.concatenate([legs - 1, legs])])
    (link,) = a.actuators[0].segments  # a single-pattern actuator: a chain of one
    assert link.plan.first_leg_mm == pytest.approx(float(s.min()), abs=1e-9)
    assert 0.0 < link.plan.first_leg_mm < 10.0
