"""The whole strip's validity: the bent line with its sealed stub against itself, the clamp and the fixed fabric.

Independent values: the contact angle of one arc with a straight stub, from equations derived by hand
(the stub's corner on the fixed band's edge), solved with scipy; random chains of arcs checked with
shapely (the strip's body as the union of its cross-sections, the fixed band behind the clamp as a box);
and the issue's three reproductions, through every command that reports a status.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq
from shapely.geometry import Polygon, box
from shapely.ops import unary_union

from embroact.export.cli.main import main
from embroact.export.files.designfile import save_design
from embroact.patterns.design import design_from_dict
from embroact.predict.analysis import analyse
from embroact.predict.rules import check_design
from embroact.predict.validity import strip_coil_angle_deg, strip_contact

R_TUBE = 2.58  # the paper's zigzag sleeve radius, the tube's radius once it fills the sleeve [mm]


# -- one arc with a straight stub: contact angles derived by hand ----------------------------------------
# The arc of length L bending by theta has radius R = L / theta. Frame: clamp at the origin, heading +x,
# positive bends toward +y (centre (0, R)); the tube lies on the right of the fabric line, 2 r thick; the
# fixed band behind the clamp is x <= 0, -2r <= y <= 0 (fabric on top, supply tube below).
def _positive(theta, length, r, stub):
    """Tube outside the bend: the lower of the stub end's two corners, minus the band's top (y = 0).

    Fabric corner: tip + stub T, T = (cos, sin), y_F = R (1 - cos theta) + stub sin theta; tube-side corner:
    2 r further along the right normal (sin, -cos), y_O = y_F - 2 r cos theta (lower past 270 deg).
    """
    y_fabric = length / theta * (1.0 - math.cos(theta)) + stub * math.sin(theta)
    return min(y_fabric, y_fabric - 2.0 * r * math.cos(theta))


def _negative(theta, length, r, stub):
    """Mirror image of a negative bend (tube inside, band 0 <= y <= 2 r): the lower corner minus 2 r.

    Fabric corner as above; the inner corner 2 r toward the centre: y_I = y_F + 2 r cos theta (lower below 270 deg).
    """
    y_fabric = length / theta * (1.0 - math.cos(theta)) + stub * math.sin(theta)
    return min(y_fabric, y_fabric + 2.0 * r * math.cos(theta)) - 2.0 * r


def _root_deg(f, *args):
    return math.degrees(brentq(f, math.pi * 1.01, math.pi * 1.999, args=args, xtol=1e-14))


@pytest.mark.parametrize("length, r, stub", [(100.0, R_TUBE, 30.0), (100.0, R_TUBE, 0.0), (60.0, 2.0, 15.0),
                                             (200.0, 3.1, 30.0), (150.0, 2.2, 45.0)])
def test_one_arc_touches_where_the_hand_derived_corner_does(length, r, stub):
    pos, neg = _root_deg(_positive, length, r, stub), _root_deg(_negative, length, r, stub)
    assert strip_coil_angle_deg([length], [1.0], r, stub) == pytest.approx(pos, abs=1e-6)
    assert strip_coil_angle_deg([length], [-1.0], r, stub) == pytest.approx(-neg, abs=1e-6)
    for sign, limit in ((1.0, pos), (-1.0, neg)):
        below, above = sign * (limit - 0.01), sign * (limit + 0.01)
        assert strip_contact([length], [[below], [above], [sign * 359.0]], r, stub).tolist() == [False, True, True]


def test_the_issues_numbers_for_the_default_actuator():
    """100 mm, r 2.58 mm: the 30 mm stub meets the fixed part at 243 / 254 deg, not 315.7 / 360."""
    assert round(-strip_coil_angle_deg([100.0], [-1.0], R_TUBE, 30.0), 1) == 243.1
    assert round(strip_coil_angle_deg([100.0], [1.0], R_TUBE, 30.0), 1) == 253.9
    assert round(-strip_coil_angle_deg([100.0], [-1.0], R_TUBE), 2) == 315.70  # the stub-free limit of before


def test_unbent_pieces_lengthen_the_stub_and_move_the_clamp():
    """A straight tail of t mm before the stub is the same as a stub t mm longer (it is straight tube either way)."""
    a = strip_coil_angle_deg([100.0, 10.0], [1.0, 0.0], R_TUBE, 20.0)
    assert a == pytest.approx(strip_coil_angle_deg([100.0], [1.0], R_TUBE, 30.0), abs=1e-6)


def test_one_arc_between_straight_pieces_takes_the_closed_form_of_the_outline_test():
    """A straight lead-in continues the fixed band (it moves the clamp), a straight tail lengthens the stub: the
    closed form strip_contact takes for one bent piece agrees with the general outline test."""
    from embroact.predict.validity import _touches

    rng = np.random.default_rng(11)
    for _ in range(300):
        lead, length, tail = rng.uniform(0.5, 30.0), rng.uniform(40.0, 150.0), rng.uniform(0.5, 30.0)
        r, stub = float(rng.uniform(1.5, 3.2)), float(rng.choice([0.0, 15.0, 30.0]))
        theta = float(rng.uniform(-1.0, 1.0) * min(359.0, math.degrees(length / (2.1 * r))))
        fast = bool(strip_contact([lead, length, tail], [0.0, theta, 0.0], r, stub))
        assert fast == _touches(np.array([lead, length, tail]), np.array([0.0, theta, 0.0]), r, stub)
        assert fast == bool(strip_contact([length], [theta], r, stub + tail))


def test_small_turning_never_touches_and_arrays_broadcast():
    rng = np.random.default_rng(7)
    bends = rng.uniform(-1.0, 1.0, (200, 3))
    bends *= 90.0 / np.abs(bends).sum(axis=1, keepdims=True)
    assert not strip_contact([30.0, 40.0, 30.0], bends, R_TUBE, 30.0).any()
    assert strip_contact([100.0], [300.0], R_TUBE, 30.0).shape == ()


# -- chains of arcs against shapely ---------------------------------------------------------------------
def _band(lengths, theta_deg, r, stub, step=0.1):
    """Cross-sections of the strip (fabric point, tube edge 2 r to the right) sampled every ``step`` mm, by hand."""
    z, phi, fabric, heads = 0j, 0.0, [0j], [0.0]
    for length, t in zip(lengths, np.radians(theta_deg)):
        k = t / length
        n = max(2, int(math.ceil(length / step)))
        for h in np.linspace(0.0, length, n + 1)[1:]:
            if k:
                centre = z + 1j * np.exp(1j * phi) / k
                p = centre + (z - centre) * np.exp(1j * k * h)
            else:
                p = z + h * np.exp(1j * phi)
            fabric.append(p)
            heads.append(phi + k * h)
        z, phi = fabric[-1], heads[-1]
    if stub:
        for h in np.linspace(0.0, stub, max(2, int(stub / step)) + 1)[1:]:
            fabric.append(z + h * np.exp(1j * phi))
            heads.append(phi)
    fabric, heads = np.array(fabric), np.array(heads)
    return fabric, fabric - 2j * r * np.exp(1j * heads)


def _shapely_contact(lengths, theta_deg, r, stub):
    """(overlap area of the strip with itself, with the fixed band) [mm^2] from shapely's union of quads."""
    f, e = _band(lengths, theta_deg, r, stub)
    quads = [Polygon([(f[i].real, f[i].imag), (f[i + 1].real, f[i + 1].imag), (e[i + 1].real, e[i + 1].imag),
                      (e[i].real, e[i].imag)]) for i in range(len(f) - 1)]
    quads = [q.buffer(0) for q in quads]
    body = unary_union(quads)
    fixed = box(-1e4, -2.0 * r, 0.0, 0.0)  # neighbouring quads share an edge only: the sum less the union overlaps
    return sum(q.area for q in quads) - body.area, body.intersection(fixed).area


def test_random_chains_agree_with_shapely():
    rng = np.random.default_rng(20261202)
    compared = touching = 0
    for _ in range(120):
        n = int(rng.integers(1, 4))
        lengths = rng.uniform(25.0, 70.0, n).round(1)
        r = float(rng.uniform(1.8, 3.2))
        top = np.minimum(300.0, np.degrees(lengths / (2.2 * r)))  # not kinked: radius above 2.2 r
        theta = (rng.uniform(-1.0, 1.0, n) * top).round(1)
        lengths = lengths.tolist()
        stub = float(rng.choice([0.0, 15.0, 30.0]))
        self_area, fixed_area = _shapely_contact(lengths, theta, r, stub)
        over = max(self_area, fixed_area)
        if 1e-6 < over < 0.05:
            continue  # grazing: within the sampling of either outline
        want = over >= 0.05
        assert bool(strip_contact(lengths, theta, r, stub)) == want, (lengths, theta.tolist(), r, stub, over)
        compared += 1
        touching += want
    assert compared >= 80 and 15 <= touching <= compared - 15, (compared, touching)


# -- the issue's reproductions ---------------------------------------------------------------------------
def _segmented(*segments, max_kpa=300.0):
    return design_from_dict({"operation": {"max_pressure_kpa": max_kpa},
                             "actuator": [{"name": "S", "segment": list(segments)}]})


ZIGZAG_5 = {"pattern": "zigzag", "width_mm": 5, "interval_mm": 1, "length_mm": 50}
CROSS_45 = {"pattern": "cross", "width_mm": 7, "interval_mm": 1.4, "angle_deg": 45, "length_mm": 50}
CROSS_52 = {"pattern": "cross", "width_mm": 7, "interval_mm": 1.4, "angle_deg": 52, "length_mm": 50}


def _shape_touches(analysis, pressure_kpa):
    """shapely on the bent line the analysis draws at that pressure (its pieces and bends, the tube's stub)."""
    act = analysis.actuators[0]
    (shape, bends), = analysis.shapes(act.name, [pressure_kpa])
    lengths = [length for length, _ in act.bend_pieces()]
    radius = max(float(c.radius_mm[0]) for c in analysis.segment_curves([pressure_kpa])[0])
    return max(_shapely_contact(lengths, np.array(bends), radius, act.plan.tube.end_margin_mm)) > 0.05


def test_zigzag_and_cross_strip_is_coiled_where_its_stub_passes_the_clamp():
    """Zigzag 5 mm + cross 45 deg, 50 mm each: 243-276 deg at 190-200 kPa read BENDING before."""
    a = analyse(_segmented(ZIGZAG_5, CROSS_45))
    strip = a.curves([150.0, 190.0, 200.0])[0]
    assert all(set(s.as_dict()["status"]) <= {"INFLATION", "BENDING"} for s in strip.segments)  # each is valid
    assert strip.as_dict()["status"] == ["BENDING", "COILED", "COILED"]
    assert [_shape_touches(a, p) for p in (150.0, 190.0, 200.0)] == [False, True, True]
    codes = [(f.code, f.message) for f in check_design(a)]
    assert any(code == "EA405" and "whole strip COILED" in text for code, text in codes)


def test_two_cross_segments_coil_like_one_actuator_of_their_length():
    """Two -52 deg cross segments read BENDING at -331 deg (2000 kPa) while one 100 mm actuator is COILED."""
    two = analyse(_segmented(CROSS_52, CROSS_52)).curves([1000.0, 2000.0])[0]
    one = analyse(design_from_dict({"actuator": [dict(CROSS_52, name="X", length_mm=100)]})).curves([1000.0, 2000.0])[0]
    assert two.as_dict()["status"] == one.as_dict()["status"] == ["COILED", "COILED"]
    assert -340.0 < float(two.theta_deg[1]) < -300.0


@pytest.fixture(scope="module")
def spiral_target(tmp_path_factory):
    """The predicted line of three zigzags (6, 5.4, 5 mm, 40 mm each) at 200 kPa: 419 deg, a spiral."""
    a = analyse(_segmented(*({"pattern": "zigzag", "width_mm": w, "interval_mm": 1, "length_mm": 40}
                             for w in (6.0, 5.4, 5.0)), max_kpa=200.0))
    (shape, _), = a.shapes("S", [200.0])
    xy = shape.profile_mm(np.linspace(0.0, shape.length_mm, 241))
    path = tmp_path_factory.mktemp("spiral") / "spiral.csv"
    path.write_text("x_mm,y_mm\n" + "".join(f"{x:.4f},{y:.4f}\n" for x, y in xy))
    return path


def test_design_refuses_a_spiral_target_that_touches_itself(spiral_target, tmp_path, capsys):
    """The target itself, as a strip with the 30 mm stub, reaches the clamp: refused before any search."""
    assert main(["design", "--target-shape", str(spiral_target), "--at-kpa", "200", "-o", str(tmp_path / "s.toml")]) == 2
    err = capsys.readouterr().err
    assert "not reachable by any design" in err and "touches itself or the clamp" in err and "30 mm" in err


def test_design_does_not_call_a_coiled_spiral_met(spiral_target, tmp_path, capsys, monkeypatch):
    """Past the up-front check (switched off here), the search's answer is judged on its whole strip: the
    nearest design follows the spiral within 0.1 mm yet is COILED, so it is not met; predict and check agree."""
    from embroact.predict import inverse

    monkeypatch.setattr(inverse, "_target_touches", lambda sj, xy, tube: None)
    out = tmp_path / "spiral.toml"
    code = main(["design", "--target-shape", str(spiral_target), "--at-kpa", "200", "-o", str(out), "--json",
                 "--write-nearest"])
    result = json.loads(capsys.readouterr().out)
    assert code == 5 and not result["reached"] and result["rmse_mm"] < 0.5
    assert "whole strip is COILED at 200 kPa" in result["statement"]
    assert main(["predict", str(out), "--pressure-kpa", "200", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["actuators"][0]["status"] == ["COILED"]
    assert main(["check", str(out), "--json"]) in (0, 1)
    assert any(f["code"] == "EA405" and "whole strip COILED" in f["message"]
               for f in json.loads(capsys.readouterr().out)["findings"])


def test_design_bend_refuses_a_bend_past_the_stub_limit_and_meets_one_below(tmp_path, capsys):
    """A 100 mm zigzag's stub reaches the clamp at 253.9 deg: 260 deg is refused, 234 deg (w 7 mm) met, BENDING."""
    assert main(["design", "--bend-deg", "260", "--at-kpa", "250", "--pattern", "zigzag", "--json",
                 "-o", str(tmp_path / "a.toml")]) == 5
    assert not json.loads(capsys.readouterr().out)["reached"]
    out = tmp_path / "b.toml"
    assert main(["design", "--bend-deg", "234", "--at-kpa", "300", "--pattern", "zigzag", "--json", "-o", str(out)]) == 0
    assert json.loads(capsys.readouterr().out)["reached"]
    assert main(["predict", str(out), "--pressure-kpa", "300", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["actuators"][0]["status"] == ["BENDING"]


def test_every_view_reads_the_same_strip_status(tmp_path, capsys):
    """predict --json, check, build's report and chart data and the studio's views agree on the coiled strip."""
    from embroact.export.studio.views import bend_at

    design = _segmented(ZIGZAG_5, CROSS_45, max_kpa=200.0)
    path = tmp_path / "zc.toml"
    save_design(design, path)
    want = analyse(design).curves()[0].as_dict()["status"]
    assert want[-4:] == ["BENDING", "COILED", "COILED", "COILED"]  # 170 kPa 195 deg; 180 kPa 216 deg
    assert main(["predict", str(path), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["actuators"][0]["status"] == want
    (tmp_path / "out").mkdir()
    assert main(["build", str(path), "--out", str(tmp_path / "out"), "--force", "--mesh-format", "none"]) == 0
    capsys.readouterr()
    report = json.loads((tmp_path / "out" / "report.json").read_text())
    assert report["actuators"][0]["curve"]["status"] == want
    assert any(f["code"] == "EA405" for f in report["findings"])
    assert main(["check", str(path), "--json"]) in (0, 1)
    assert any(f["code"] == "EA405" and "whole strip" in f["message"]
               for f in json.loads(capsys.readouterr().out)["findings"])
    (view,) = bend_at(analyse(design), 200.0)
    assert view["status"] == "COILED"


def test_predict_text_says_what_a_coiled_strip_means(tmp_path, capsys):
    path = tmp_path / "zc.toml"
    save_design(_segmented(ZIGZAG_5, CROSS_45, max_kpa=200.0), path)
    assert main(["predict", str(path), "--pressure-kpa", "170,180"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[-4].split()[-1] == "BENDING" and lines[-3].split()[-2:] == ["-", "COILED"]  # no state: no bend
    assert lines[-2].startswith("-: past a validity limit the model describes no state")
    assert lines[-1].startswith("COILED: the strip, with the 30 mm sealed tube beyond its tip, touches itself")


def test_the_whole_strip_finding_stands_beside_an_actuator_without_a_model():
    """The whole-strip EA405 of one actuator was read from every actuator's strips at once, so a second actuator
    without a model (its calibration has no points of its kind) dropped it for the whole design."""
    from embroact.predict.calibration import CalibrationPoint, CalibrationSet

    only_zigzag = CalibrationSet("zigzag-only", (CalibrationPoint("zigzag", 6.0, 2.0, 60.0, branch="both"),),
                                 "synthetic", {})
    lone = {"name": "N", "origin_mm": [0.0, 40.0], "model": {"calibration": "zigzag-only"}, **CROSS_45}
    d = design_from_dict({"operation": {"max_pressure_kpa": 300.0},
                          "actuator": [{"name": "S", "segment": [ZIGZAG_5, CROSS_45]}, lone]})
    a = analyse(d, calibration_sets=[only_zigzag])
    assert a.actuators[1].choice is None
    assert any(f.code == "EA405" and f.actuator == "S" and "whole strip COILED from 180 kPa" in f.message
               for f in check_design(a))


def test_a_single_pattern_strip_counts_its_unbent_ends_and_ea405_follows_it():
    """A 100 mm zigzag of 2.9 mm interval is sewn with 0.7 mm unbent at each end (legs over 98.6 mm). Its model's
    own limit (the legs' arc with the 30 mm stub: 253.3 deg) leaves out the tail, which is straight tube before the
    stub: the whole strip (bend_pieces) coils at the angle of one 98.6 mm arc with a 30.7 mm stub (the hand-derived
    corner), earlier than the model alone; every view reads that status, and EA405 names the first working-grid
    pressure at which it is not valid."""
    from embroact.predict.analysis import pressure_grid_kpa
    from embroact.predict.rules import ModelRuleSettings, check_model
    from embroact.predict.status import Status

    d = design_from_dict({"operation": {"max_pressure_kpa": 300.0},
                          "actuator": [{"name": "A", "pattern": "zigzag", "width_mm": 5.3, "interval_mm": 2.9,
                                        "length_mm": 100.0}]})
    a = analyse(d)
    act = a.actuators[0]
    (lead, _), (l0, k), (tail, _) = act.bend_pieces()
    assert k == 0 and lead == pytest.approx(0.7, abs=1e-6) and tail == pytest.approx(0.7, abs=1e-6)
    p = np.linspace(100.0, 250.0, 15001)  # the rails sew 5.2 mm (G 1.05 MPa there): the strip coils near 166 kPa
    theta = np.asarray(a.model_curve(act.segments[0].model, p).theta_deg)
    status = np.asarray(a.curves(p)[0].status)
    first = int(np.flatnonzero(status == int(Status.COILED))[0])
    assert 0 < first
    r = float(a.model_curve(act.segments[0].model, [p[first]]).radius_mm[0])
    alone = _root_deg(_positive, l0, r, 30.0)
    whole = _root_deg(_positive, l0, r, 30.0 + tail)
    assert whole < alone - 0.5
    assert theta[first - 1] < whole <= theta[first] + 0.01  # the strip coils where the tail counts (r where it coils)
    grid = pressure_grid_kpa(300.0)
    bad = np.flatnonzero(~np.isin(a.curves(grid)[0].status, [int(Status.BENDING), int(Status.INFLATION)]))
    (ea405,) = [f for f in check_model(a, ModelRuleSettings(max_pressure_kpa=300.0)) if f.code == "EA405"]
    assert f"from {grid[bad[0]]:.0f} kPa on" in ea405.message
