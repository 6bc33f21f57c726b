"""The marker reading of a chain of arcs (segmented actuators), against geometry written out by hand.

Every expected value here comes from point coordinates built in this file with math.cos and
math.sin (circle arcs joined end to end, a straight line past the last one), chord by chord,
or from the hand formula ``(n - 2) h kappa`` of a uniform bend; none from the package.
"""
import json
import math

import numpy as np
import pytest

from embroact.export.cli.main import main
from embroact.patterns.base.errors import ParameterError
from embroact.patterns.design import design_from_dict
from embroact.predict.analysis import analyse
from embroact.predict.markers import (PAPER_LAYOUT, MarkerLayout, chain_marker_positions_mm, chain_reading_deg,
                                      reading_deg)


def _chain_point(lengths_mm, theta_deg, s_mm):
    """(x, y) at arc length s on arcs joined end to end (straight past the last), by hand."""
    x = y = phi = 0.0
    for length, theta in zip(lengths_mm, theta_deg):
        h = min(s_mm, length)
        k = math.radians(theta) / length
        if k == 0.0:
            x, y = x + h * math.cos(phi), y + h * math.sin(phi)
        else:  # centre of curvature at distance 1/k left of the heading
            x, y = x + (math.sin(phi + k * h) - math.sin(phi)) / k, y - (math.cos(phi + k * h) - math.cos(phi)) / k
        phi += k * h
        s_mm -= h
        if s_mm <= 0.0:
            return x, y
    return x + s_mm * math.cos(phi), y + s_mm * math.sin(phi)


def _hand_reading(lengths_mm, theta_deg, s_mm):
    """Sum of the signed turning angles between consecutive chords of the hand-built points [deg]."""
    p = [_chain_point(lengths_mm, theta_deg, s) for s in s_mm]
    d = [(b[0] - a[0], b[1] - a[1]) for a, b in zip(p, p[1:])]
    return math.degrees(sum(math.atan2(u[0] * v[1] - u[1] * v[0], u[0] * v[0] + u[1] * v[1]) for u, v in zip(d, d[1:])))


def _s(layout):
    return [layout.offset_mm + layout.spacing_mm * j for j in range(layout.markers_per_side)]


def test_a_uniform_chain_reads_n_minus_2_h_kappa():
    # three arcs of one curvature, 1.2 deg/mm: the paper's layout reads (7 - 2) * 10 mm * kappa = 60 deg
    kappa = 1.2
    lengths = [30.0, 45.0, 25.0]
    assert chain_reading_deg(lengths, [kappa * L for L in lengths]) == pytest.approx(5 * 10.0 * kappa, abs=1e-9)
    # 5 markers 8 mm apart from 12 mm on: 3 * 8 * kappa; and the one-arc case is reading_deg
    lay = MarkerLayout(markers_per_side=5, spacing_mm=8.0, offset_mm=12.0, rows=1)
    assert chain_reading_deg(lengths, [kappa * L for L in lengths], lay) == pytest.approx(3 * 8.0 * kappa, abs=1e-9)
    assert chain_reading_deg([100.0], [120.0], lay) == pytest.approx(reading_deg(120.0, 100.0, lay), abs=1e-12)


def test_two_arcs_with_markers_on_both_and_a_chord_across_the_boundary():
    lengths, theta = [40.0, 50.0], [60.0, -90.0]
    # markers at 0..60 mm: the first chord (0-10) lies on arc 1, the last (50-60) on arc 2, so the reading is
    # the curvature between their middles, 5 and 55 mm: 35 mm of 1.5 deg/mm and 15 mm of -1.8 deg/mm
    assert _hand_reading(lengths, theta, _s(PAPER_LAYOUT)) == pytest.approx(35 * 1.5 - 15 * 1.8, abs=1e-9)
    assert chain_reading_deg(lengths, theta) == pytest.approx(35 * 1.5 - 15 * 1.8, abs=1e-9)
    # markers at 35..75 mm: the first chord (35-45) straddles the boundary at 40 mm, so the curvature between the
    # chord middles (40 to 70 mm: 30 mm of arc 2, -54 deg) is not what the chords read
    lay = MarkerLayout(markers_per_side=5, spacing_mm=10.0, offset_mm=35.0, rows=1)
    want = _hand_reading(lengths, theta, _s(lay))
    assert chain_reading_deg(lengths, theta, lay) == pytest.approx(want, abs=1e-9)
    assert abs(want - (-30 * 1.8)) > 0.1  # the straddling chord turns otherwise than its middle's tangent
    # the positions themselves, point by point
    np.testing.assert_allclose(chain_marker_positions_mm(lengths, theta, lay),
                               [_chain_point(lengths, theta, s) for s in _s(lay)], atol=1e-12)


def test_markers_past_the_bent_length_sit_on_the_straight_continuation():
    lengths, theta = [40.0, 50.0], [60.0, -90.0]  # 90 mm bent; markers at 70..110 mm
    lay = MarkerLayout(markers_per_side=5, spacing_mm=10.0, offset_mm=70.0, rows=1)
    want = _hand_reading(lengths, theta, _s(lay))
    assert chain_reading_deg(lengths, theta, lay) == pytest.approx(want, abs=1e-9)
    assert want == pytest.approx(-1.8 * (90.0 - 75.0), abs=1e-9)  # tangent from 75 mm (first chord) to the tip
    # the chords 70-80 and 80-90 lie on arc 2, 90-100 and 100-110 on the straight part: those two point along
    # the tip's tangent, 60 - 90 = -30 deg
    d = np.diff(chain_marker_positions_mm(lengths, theta, lay), axis=0)
    assert math.atan2(d[-1][1], d[-1][0]) == pytest.approx(math.atan2(d[-2][1], d[-2][0]), abs=1e-12)
    assert math.degrees(math.atan2(d[-1][1], d[-1][0])) == pytest.approx(60.0 - 90.0, abs=1e-9)
    # all markers past the end read nothing
    assert chain_reading_deg(lengths, theta, MarkerLayout(offset_mm=90.0)) == pytest.approx(0.0, abs=1e-12)


def test_many_chains_at_once_and_bad_input():
    theta = np.array([[60.0, -90.0], [0.0, 0.0], [-20.0, 200.0]])
    got = chain_reading_deg([40.0, 50.0], theta)
    assert got.shape == (3,)
    for row, g in zip(theta, got):
        assert g == pytest.approx(_hand_reading([40.0, 50.0], row, _s(PAPER_LAYOUT)), abs=1e-9)
    with pytest.raises(ParameterError, match=r"theta_deg must have one bend per arc length \(2\)"):
        chain_reading_deg([40.0, 50.0], [10.0])
    with pytest.raises(ParameterError, match=r"lengths_mm\[1\] must be in \(0"):
        chain_reading_deg([40.0, 0.0], [10.0, 5.0])
    with pytest.raises(ParameterError, match="theta_deg must be finite"):
        chain_reading_deg([40.0], [math.nan])


# ----------------------------------------------------------------------------- a segmented design
SEGMENTED = {"name": "two", "actuator": [{"name": "S", "segment": [
    {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 35},
    {"pattern": "zigzag", "width_mm": 9, "interval_mm": 1, "length_mm": 45}]}]}
PRESSURES = [0.0, 150.0, 200.0, 250.0]


def _design_file(tmp_path):
    from embroact.export.files.designfile import save_design

    path = tmp_path / "two.toml"
    save_design(design_from_dict(SEGMENTED), path)
    return str(path)


def test_segmented_reading_is_the_marker_sum_on_the_chain_of_arcs():
    """The analysis' reading of a segmented actuator against the hand-built chain of its pieces (lead-in
    dropped: the offset counts from where the legs start), with its own segments' bends."""
    a = analyse(design_from_dict(SEGMENTED))
    act = a.actuator("S")
    pieces = act.bend_pieces()
    curves = a.segment_curves(PRESSURES)[0]
    lay = MarkerLayout(markers_per_side=6, spacing_mm=15.0, offset_mm=2.0)  # last marker at 77 of ~80 mm
    got = a.marker_reading_deg("S", lay, PRESSURES)
    first = next(j for j, (_, k) in enumerate(pieces) if k >= 0)
    for j, r in enumerate(got):
        lengths = [length for length, _ in pieces[first:]]
        bends = [float(curves[k].theta_deg[j]) if k >= 0 else 0.0 for _, k in pieces[first:]]
        assert r == pytest.approx(_hand_reading(lengths, bends, _s(lay)), abs=1e-9)
    assert got[0] == 0.0 and got[-1] > 0.0
    assert a.marker_reading_deg("S", lay, PRESSURES) is got  # memoised


def test_predict_gives_a_segmented_reading_the_api_agrees(capsys, tmp_path):
    path = _design_file(tmp_path)
    grid = ",".join(f"{p:g}" for p in PRESSURES)
    assert main(["predict", path, "--pressure-kpa", grid, "--measurement", "markers", "--json"]) == 0
    (doc,) = json.loads(capsys.readouterr().out)["actuators"]
    a = analyse(design_from_dict(SEGMENTED))
    assert doc["reading_deg"] == a.marker_reading_deg("S", PAPER_LAYOUT, PRESSURES).tolist()
    assert doc["measurement"] == PAPER_LAYOUT.as_dict()
    assert doc["measurement_source"] == "the paper's (calibration set 'paper-2025' records none)"
    # the bent shape the side view draws (BentShape, Rodrigues frames) read by hand: the same numbers
    lead = a.actuator("S").bend_pieces()[0]
    start = lead[0] if lead[1] < 0 else 0.0
    for r, (shape, _) in zip(doc["reading_deg"], a.shapes("S", PRESSURES)):
        p = shape.profile_mm([start + s for s in _s(PAPER_LAYOUT)])
        d = np.diff(p, axis=0)
        want = math.degrees(sum(math.atan2(u[0] * v[1] - u[1] * v[0], u @ v) for u, v in zip(d, d[1:])))
        assert r == pytest.approx(want, abs=1e-9)
    # the text table prints the column for the whole strip, and no longer says there is none
    assert main(["predict", path, "--pressure-kpa", grid, "--measurement", "markers"]) == 0
    out = capsys.readouterr().out
    assert "no marker reading" not in out
    block = out.split("S: whole strip")[1].splitlines()
    assert block[1].startswith("reading_deg: what the marker sum reads (markers: 2 rows of 7, 10 mm apart")
    assert block[2].split() == ["pressure_kpa", "theta_deg", "reading_deg", "status"]
    assert [float(row.split()[2]) for row in block[3:]] == pytest.approx(doc["reading_deg"], abs=5e-4)


def test_plain_actuator_reading_cli_api_and_band_agree(capsys, tmp_path):
    """One concept: predict's column, the analysis' reading and the uncertainty band's reading are one number."""
    from embroact.patterns.design import default_design

    a = analyse(default_design())
    lay = MarkerLayout(markers_per_side=5, spacing_mm=12.0, offset_mm=60.0)  # the last two past l0 = 100 mm
    got = a.marker_reading_deg("A1", lay, PRESSURES)
    theta = a.curves(PRESSURES)[0].theta_deg
    np.testing.assert_allclose(got, [_hand_reading([100.0], [t], _s(lay)) for t in theta], atol=1e-9)
    np.testing.assert_allclose(got, reading_deg(theta, 100.0, lay), atol=1e-12)
    assert main(["predict", "zigzag", "--width-mm", "7", "--pressure-kpa", ",".join(map(str, PRESSURES)),
                 "--measurement", "markers", "--markers-per-side", "5", "--marker-spacing-mm", "12",
                 "--marker-offset-mm", "60", "--json"]) == 0
    (doc,) = json.loads(capsys.readouterr().out)["actuators"]
    assert doc["reading_deg"] == got.tolist()
