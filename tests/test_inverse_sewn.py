"""Inverse design over what a machine sews: the bend `design` reports is the one recomputed from the
needle points an independent DST decoder reads from the written file; verdicts agree with a dense scan
of the calibrated range; the sensitivity is what `predict` gives one grid step off."""
import dataclasses
import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

import dst_decoder

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import inverse_targets  # noqa: E402
from embroact.export.cli.main import main
from embroact.predict.curve import curve, sweep
from embroact.predict.inverse import design_bend, design_space
from embroact.predict.status import Status

VALID = (int(Status.BENDING), int(Status.INFLATION))


def _decoded(data, origin_mm):
    """Needle points of DST bytes read by the suite's own decoder (not pystitch's, not embroact's)."""
    recs = [r for r in dst_decoder.decode(data).records if r.kind == "stitch"]
    return np.array([(r.x, r.y) for r in recs], dtype=np.float64) / 10.0 + np.array(origin_mm)


def sewn_bend_deg(design, pressure_kpa):
    """The bend recomputed from the decoded DST's needle points (benchmarks/inverse_targets.py)."""
    return inverse_targets.sewn_bend_deg(design, pressure_kpa, decode=_decoded)


def dense_range(pattern, pressure_kpa, length_mm=100.0, points=2001, zooms=3):
    """(lowest, highest) bend in a valid state over a dense scan of the calibrated parameter (requested values),
    each extreme then scanned again as densely between its neighbours (a steep approach to a limit)."""
    from embroact.predict.inverse import _legs, _Model
    from embroact.patterns.params import Tube
    from embroact.patterns.design import ModelSettings

    space = design_space(pattern)
    model = _Model(pressure_kpa, Tube(), ModelSettings(), (), Tube().end_margin_mm)  # a whole strip with its stub

    def scan(x):
        params = [space.params(float(v)) for v in x]
        c = sweep([model.model(q, _legs(q, length_mm)[1]) for q in params], [pressure_kpa])
        th, st = np.asarray(c.theta_deg)[:, 0], np.asarray(c.status)[:, 0]
        return th, np.isin(st, VALID)

    out = []
    for sign in (-1.0, 1.0):
        x = np.linspace(space.low, space.high, points)
        best = -np.inf
        for _ in range(zooms + 1):
            th, ok = scan(x)
            if not ok.any():
                break
            i = int(np.argmax(np.where(ok, sign * th, -np.inf)))
            best = max(best, float(sign * th[i]))
            x = np.linspace(x[max(i - 1, 0)], x[min(i + 1, len(x) - 1)], 201)
        out.append(sign * best)
    return out[0], out[1]


TARGETS = inverse_targets.target_bends(30)
RNG = np.random.default_rng(23)


@pytest.mark.parametrize("length_tolerance_mm", [0.0, 5.0])
@pytest.mark.parametrize("bend, pressure, pattern", TARGETS)
def test_reported_bend_is_the_decoded_files(bend, pressure, pattern, length_tolerance_mm, tmp_path, capsys):
    """All 30 seeded targets, with the length kept and with 5 mm of length allowed: the reported bend is the one
    of the decoded DST; met within the tolerance, or the answer names the nearest design and a pressure at which
    that design reaches the target exactly; `check` on the written design gives the findings the answer lists."""
    try:
        r = design_bend(bend, pressure, pattern=pattern, length_tolerance_mm=length_tolerance_mm)
    except Exception as exc:  # no valid sewable design of this pattern at all: a one-line refusal
        assert "no valid sewable design" in str(exc)
        return
    from embroact.export.files.designfile import save_design

    save_design(r.best.design, tmp_path / "d.toml")
    assert list(r.best.findings) == _check_findings(capsys, tmp_path / "d.toml")
    theta, m = sewn_bend_deg(r.best.design, pressure)
    assert theta == pytest.approx(r.best.theta_deg, abs=1e-6)
    assert abs(r.best.design.actuators[0].centerline.length_mm - 100.0) <= length_tolerance_mm + 1e-9
    if r.reached:
        assert abs(theta - bend) <= 0.5
    else:
        assert "not met" in r.statement and "Nearest" in r.statement
        if r.best.exact_pressure_kpa is not None:
            assert float(curve(m, [r.best.exact_pressure_kpa]).theta_deg[0]) == pytest.approx(bend, abs=1e-4)
            assert f"{r.best.exact_pressure_kpa:.1f} kPa" in r.statement


VERDICT_TARGETS = [(float(RNG.uniform(-150, 360)), float(RNG.uniform(80, 300)), str(RNG.choice(["zigzag", "cross"])))
                   for _ in range(40)]


@pytest.mark.parametrize("bend, pressure, pattern", VERDICT_TARGETS + [(67.5, 80.0, "zigzag"),
                                                                          (355.0, 200.0, "zigzag"),
                                                                          (-127.0, 300.0, "cross")])
def test_verdicts_agree_with_a_dense_scan(bend, pressure, pattern):
    """All 40 seeded targets and the issue's three: in the dense scan's range an in-range verdict; outside it
    refused, the quoted extreme the scan's (about 0.7 s each)."""
    if bend == 0.0:
        return
    lo, hi = dense_range(pattern, pressure)
    if min(abs(bend - lo), abs(bend - hi)) < 0.05:  # too close to an extreme for a 4001-point reference
        return
    try:
        r = design_bend(bend, pressure, pattern=pattern)
    except Exception as exc:
        assert not lo <= bend <= hi, exc
        return
    if r.range_deg is None:  # below every design's P0: nothing bends
        assert lo == hi == 0.0 and not r.in_range and "below the transition pressure P0" in r.statement
        return
    assert r.in_range == (lo <= bend <= hi)
    assert r.range_deg[0] == pytest.approx(lo, abs=0.05) and r.range_deg[1] == pytest.approx(hi, abs=0.05)
    if not r.in_range:
        assert not r.reached
        assert f"{(hi if bend > hi else lo):+.2f} deg" in r.statement


def test_every_zigzag_width_in_grid_units_is_sewn_and_a_length_meets_what_the_widths_miss():
    """A 6.1 mm zigzag is sewn 6.1 mm wide (the path moved half a grid unit: the decoded file's needle points lie on
    two rails 6.1 mm apart, on the grid); 88 deg at 150 kPa lies between the 6.1 and 6.2 mm designs (90.22, 84.53 deg) and is met by 6.1 mm over
    97.5 mm (90.22 x 97.5 / 100 = 87.96 deg) when the length may move."""
    from embroact.export.machine.formats import encode
    from embroact.patterns.design import build_plan

    r = design_bend(90.0, 150.0, pattern="zigzag")
    assert r.reached and r.best.params.width_mm == 6.1
    plan = build_plan(r.best.design)
    data, res = encode(plan, "dst")
    rails = np.unique(np.round(_decoded(data, res.origin_mm)[:, 1], 6))
    assert len(rails) == 2 and rails[1] - rails[0] == pytest.approx(6.1, abs=1e-9)
    assert sewn_bend_deg(r.best.design, 150.0)[0] == pytest.approx(90.22, abs=0.01)
    r = design_bend(88.0, 150.0, pattern="zigzag")
    assert not r.reached and "a length of 97.5 mm would meet it" in r.statement
    r = design_bend(88.0, 150.0, pattern="zigzag", length_tolerance_mm=3.0)
    assert r.reached and r.best.params.width_mm == 6.1 and r.best.length_mm == 97.5
    assert r.best.theta_deg == pytest.approx(90.22 * 97.5 / 100.0, abs=0.01)
    assert sewn_bend_deg(r.best.design, 150.0)[0] == pytest.approx(r.best.theta_deg, abs=1e-6)


def test_the_issues_examples():
    """67.5 deg at 80 kPa is beyond the zigzag's 67.21 deg; -127 deg at 300 kPa is met by a cross."""
    r = design_bend(67.5, 80.0, pattern="zigzag")
    assert not r.reached and not r.in_range and "at most +67.21 deg" in r.statement
    r = design_bend(-127.0, 300.0, pattern="cross")
    assert r.reached and abs(r.best.theta_deg + 127.0) <= 0.5
    r = design_bend(355.0, 200.0, pattern="zigzag")  # a 5.289 mm zigzag bends 355 deg, but its stub is on the clamp
    assert not r.in_range and not r.reached and "at most +253.90 deg" in r.statement


def _rails_on_grid_path(spec, width_mm):
    """The straight path of ``spec`` moved so that rails +-w/2 lie on the 0.1 mm grid: y = 0 for an even number of
    0.1 mm units of width, y = 0.05 mm for an odd one (3.05 + 0.05 = 3.1, -3.05 + 0.05 = -3.0)."""
    from embroact.patterns.centerline import Centerline

    y = 0.05 if round(width_mm * 10) % 2 else 0.0
    return Centerline.straight(spec.centerline.length_mm, origin_mm=(0.0, y))


def test_sensitivity_is_predict_one_grid_step_off(tmp_path, capsys):
    """The printed change for +-1 grid step agrees in sign and within 10 % with predict on the stepped file
    (a zigzag width steps by one 0.1 mm unit, its straight path placed so both rails lie on the grid; a cross
    angle turns by one step with the interval closing the same number of passes, so that the file sews the turned
    legs: the generator would turn a lone angle back to close the pattern, and the step would change nothing)."""
    from embroact.export.files.designfile import dumps_design

    for bend, pressure, pattern in [(120.0, 200.0, "zigzag"), (130.0, 150.0, "zigzag"), (-40.0, 250.0, "cross")]:
        r = design_bend(bend, pressure, pattern=pattern)
        spec = r.best.design.actuators[0]
        steps = {s.parameter: s.step for s in r.best.sensitivity}
        assert steps["width_mm"] == pytest.approx(0.1)
        for s in r.best.sensitivity:
            for sign, want in ((-1, s.minus_deg), (1, s.plus_deg)):
                value = round(getattr(spec.params, s.parameter) + sign * s.step, 10)
                params = dataclasses.replace(spec.params, **{s.parameter: value})
                if s.parameter == "angle_deg":
                    w, a = spec.params.width_mm, math.radians(spec.params.angle_deg)
                    passes = round(2.0 * w * math.tan(a) / spec.params.interval_mm)
                    params = dataclasses.replace(params, interval_mm=2.0 * w * math.tan(math.radians(value)) / passes)
                moved = dataclasses.replace(spec, params=params)
                if s.parameter == "width_mm":
                    moved = dataclasses.replace(moved, centerline=_rails_on_grid_path(spec, value))
                out = tmp_path / "moved.toml"
                out.write_text(dumps_design(dataclasses.replace(r.best.design, actuators=(moved,))))
                capsys.readouterr()
                assert main(["predict", str(out), "--pressure-kpa", str(pressure), "--json"]) == 0
                act = json.loads(capsys.readouterr().out)["actuators"][0]
                if s.parameter == "width_mm":  # the stepped width is the one sewn
                    assert act["derived"]["width_mm"] == pytest.approx(value, abs=1e-9)
                else:  # the legs turn by about the step (the sewn angle is measured on the 0.1 mm grid)
                    assert act["derived"]["angle_deg"] - r.best.params.angle_deg == pytest.approx(sign * s.step,
                                                                                                rel=0.5)
                got = act["theta_deg"][0] - r.best.theta_deg
                assert abs(want) > 0.05 and np.sign(got) == np.sign(want) and got == pytest.approx(want, rel=0.1)


def test_unreachable_targets_exit_5_for_every_pattern_and_write_only_when_asked(tmp_path, capsys):
    out = tmp_path / "d.toml"
    for pattern in ("zigzag", "cross", "any"):
        assert main(["design", "--bend-deg", "60", "--at-kpa", "50", "--pattern", pattern, "-o", str(out)]) == 5
        text = capsys.readouterr().out
        assert "below the transition pressure P0" in text and "nothing written" in text
        assert not out.exists()
    assert main(["design", "--bend-deg", "60", "--at-kpa", "50", "--pattern", "zigzag", "-o", str(out),
                 "--write-nearest"]) == 5
    assert out.exists()


def _check_findings(capsys, path):
    capsys.readouterr()
    main(["check", str(path), "--json"])
    found = json.loads(capsys.readouterr().out)["findings"]
    return [f"{f['code']} {f['severity']}: {f['message']}" for f in found]


def test_design_and_check_give_the_same_findings(tmp_path, capsys):
    """The findings `design` lists for the written file are the ones `check` gives for it (one gate)."""
    for bend, pressure, pattern in [(84.5, 150.0, "zigzag"), (-40.0, 250.0, "cross"), (25.0, 220.0, "cross")]:
        out = tmp_path / "b.toml"
        capsys.readouterr()
        assert main(["design", "--bend-deg", str(bend), "--at-kpa", str(pressure), "--pattern", pattern, "-o",
                     str(out), "--json"]) == 0
        res = json.loads(capsys.readouterr().out)
        assert res["best"]["findings"] == _check_findings(capsys, out)
    _, xy = inverse_targets.target_shape(1, step_mm=0.5)
    csv = tmp_path / "shape.csv"
    csv.write_text("x_mm,y_mm\n" + "".join(f"{x:.5f},{y:.5f}\n" for x, y in xy))
    out = tmp_path / "s.toml"
    capsys.readouterr()
    assert main(["design", "--target-shape", str(csv), "--at-kpa", "200", "-o", str(out), "--json"]) == 0
    res = json.loads(capsys.readouterr().out)
    assert res["findings"] == _check_findings(capsys, out)


@pytest.mark.parametrize("place", [((0.0, 0.0), 0.0), ((10.0, 20.03), 90.0)])
def test_the_studio_searches_the_designs_design_searches(place, tmp_path, capsys):
    """The studio's target bend searched 0.2 mm width steps (the path kept on its grid line) where `design` searches
    0.1 mm ones: 88 deg at 150 kPa got 6.2 mm (84.53 deg) in the studio and 6.1 mm (90.22 deg) from `design`. Both now
    give the same answer, for an actuator at the origin and one elsewhere along +y; the studio's proposal starts the
    actuator half a grid unit across its path, so the applied design is sewn 6.1 mm wide and bends as answered."""
    from embroact.export.studio.session import Studio
    from embroact.patterns.centerline import Centerline
    from embroact.patterns.design import default_design

    base = default_design()
    origin, rotation = place
    spec = dataclasses.replace(base.actuators[0], centerline=Centerline.straight(100.0, origin_mm=origin,
                                                                                 rotation_deg=rotation))
    studio = Studio(dataclasses.replace(base, actuators=(spec,)), str(tmp_path))
    for bend, pressure, pattern in [(90.0, 150.0, "zigzag"), (88.0, 150.0, "zigzag"), (-40.0, 250.0, "cross")]:
        capsys.readouterr()
        main(["design", "--bend-deg", str(bend), "--at-kpa", str(pressure), "--pattern", pattern, "-o",
              str(tmp_path / "d.toml"), "--write-nearest", "--json"])
        cli = json.loads(capsys.readouterr().out)
        answer = studio.inverse(bend, pressure, pattern=pattern)
        for key in ("reached", "statement"):
            assert answer[key] == cli[key]
        # a cross's angle and interval are asked continuously and many requests sew the same needle points: the
        # rotated actuator's search settles on another request (41.4596 vs 41.4665 deg) that sews the same legs
        # (the same bend to 1e-9 deg below); the width is a grid value and agrees exactly
        assert answer["best"]["params"] == pytest.approx(cli["best"]["params"], abs=0.01)
        assert answer["best"]["params"]["width_mm"] == cli["best"]["params"]["width_mm"]
        assert answer["best"]["theta_deg"] == pytest.approx(cli["best"]["theta_deg"], abs=1e-9)
        width = cli["best"]["params"]["width_mm"]
        across = answer["origin_mm"][1 if rotation == 0.0 else 0]
        assert (across * 10 + width * 10 / 2) % 1 == pytest.approx(0.0, abs=1e-6)  # both rails on the 0.1 mm grid
        if answer["reached"]:
            views = studio.apply_proposal(pressure)
            act = views["actuators"][0]
            assert act["derived"]["width_mm"] == pytest.approx(width, abs=1e-9)
            assert act["theta_deg"] == pytest.approx(answer["best"]["theta_deg"], abs=1e-9)
            assert sewn_bend_deg(studio.design, pressure)[0] == pytest.approx(answer["best"]["theta_deg"], abs=1e-6)
