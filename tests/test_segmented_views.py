"""Segmented actuators in every view: build, preview bend|shape|mesh, report, worksheet, stitch caption, rules.

The reference numbers are independent of the views: each segment's curve from the analysis
(the model, tested elsewhere), the chain of arcs summed here by hand in complex numbers, the
target hook the design was made for (examples/data/target_hook.csv), and the sleeve radius
from its formula (docs/model.md).
"""
from __future__ import annotations

import cmath
import csv
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from embroact.export.cli.main import main
from embroact.export.files.designfile import load_design
from embroact.export.pictures import previews as pv
from embroact.export.report.stage import render_previews
from embroact.patterns.design import design_from_dict
from embroact.predict.analysis import analyse
from embroact.predict.rules import check_design

ROOT = Path(__file__).resolve().parent.parent
HOOK = ROOT / "examples" / "designed_hook.toml"
TARGET = ROOT / "examples" / "data" / "target_hook.csv"
AT_KPA = 250.0  # the pressure the hook was designed for


def _hand_tip(lengths, theta_deg) -> complex:
    """Tip of a chain of circular arcs (profile frame: x along the clamped tangent, y toward positive bends)."""
    z, phi = 0j, 0.0
    for length, t in zip(lengths, np.radians(theta_deg)):
        z += length * cmath.exp(1j * phi) if t == 0.0 else length / t * (cmath.exp(1j * (phi + t)) - cmath.exp(1j * phi)) / 1j
        phi += t
    return z


@pytest.fixture(scope="module")
def hook():
    return analyse(load_design(HOOK))


def test_side_view_draws_the_chain_of_arcs_at_each_segments_bend(hook):
    act = hook.actuators[0]
    strip = hook.curves()[0]
    (panel,) = pv.side_panels(hook, hook.curves())
    k = len(panel.pressure_kpa) - 1  # the last state drawn
    top = panel.pressure_kpa[k]
    at = hook.segment_curves([top])[0]  # each segment alone at that pressure
    pieces = act.bend_pieces()
    want = [float(at[i].theta_deg[0]) if i >= 0 else 0.0 for _, i in pieces]
    assert panel.segment_lengths_mm == pytest.approx([length for length, _ in pieces], abs=1e-12)
    assert panel.segment_theta_deg[k] == pytest.approx(want, abs=1e-9)
    assert panel.theta_deg[k] == pytest.approx(sum(want), abs=1e-9)
    assert float(strip.theta_deg[list(strip.pressure_kpa).index(top)]) == pytest.approx(sum(want), abs=1e-9)
    tip = _hand_tip([length for length, _ in pieces], want)
    shape = panel.shape(k)
    assert shape.profile_mm([shape.length_mm])[0] == pytest.approx([tip.real, tip.imag], abs=1e-9)
    # the shape the hook was designed for: at its design pressure its end lies near the target's (the README: 0.3 mm)
    at = hook.segment_curves([AT_KPA])[0]
    tip = _hand_tip([length for length, _ in pieces], [float(at[i].theta_deg[0]) if i >= 0 else 0.0 for _, i in pieces])
    with TARGET.open() as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))][1:]
    end = complex(*map(float, rows[-1]))
    assert abs(tip - end) < 0.5


def test_side_view_svg_states_carry_the_whole_strips_bend(tmp_path, capsys, hook):
    out = tmp_path / "shape.svg"
    assert main(["preview", "shape", str(HOOK), "-o", str(out), "--states", "3"]) == 0
    capsys.readouterr()
    svg = out.read_text()
    states = re.findall(r'data-pressure-kpa="([^"]+)" data-theta-deg="([^"]+)"', svg)
    strip = hook.curves()[0]
    theta = dict(zip(strip.pressure_kpa.tolist(), strip.theta_deg.tolist()))
    top = load_design(HOOK).operation.max_pressure_kpa
    assert [float(p) for p, _ in states] == [0.0, top / 2.0, top]
    for p, t in states:
        assert float(t) == pytest.approx(theta[float(p)], rel=1e-5)
    n = len(hook.actuators[0].segments)
    assert f"A1 ({n} segments)" in svg
    assert svg.count('class="mark"') == (n - 1) * len(states)  # where one segment meets the next, in every state
    starts = np.cumsum([0.0] + [length for length, _ in hook.actuators[0].bend_pieces()])
    for m in pv.segment_boundaries_mm(hook.actuators[0]):  # each mark lies in an unbent transition
        i = int(np.searchsorted(starts, m)) - 1
        assert hook.actuators[0].bend_pieces()[i][1] == -1


def test_bend_chart_has_the_whole_strip_and_one_series_per_segment(tmp_path, capsys, hook):
    out = tmp_path / "bend.svg"
    assert main(["preview", "bend", str(HOOK), "-o", str(out)]) == 0
    capsys.readouterr()
    svg = out.read_text()
    n = len(hook.actuators[0].segments)
    assert sorted(set(re.findall(r'class="curve" data-series="(\d)"', svg))) == [str(k) for k in range(n + 1)]
    assert f"A1 whole strip: sum of its {n} segments" in svg
    for k, seg in enumerate(hook.actuators[0].segments):
        assert f"A1 segment {k} ({seg.derived.pattern}), w {seg.derived.width_mm:.1f} mm: G {seg.model.g_mpa:.4g}" in svg
    assert len(re.findall(r'class="p0"', svg)) == n  # each segment's own transition pressure
    assert svg == pv.bend_chart(hook, hook.curves())


def test_mesh_bends_each_segment_by_its_own_angle(hook):
    shapes, pressures = pv.shape_meshes(hook, hook.curves(), pressure_kpa=AT_KPA, tolerance_mm=0.2)
    (mesh,) = shapes
    act = hook.actuators[0]
    at = hook.segment_curves([AT_KPA])[0]
    want = [float(at[i].theta_deg[0]) if i >= 0 else 0.0 for _, i in act.bend_pieces()]
    assert pressures == {"A1": AT_KPA}
    assert mesh.bent.segment_theta_deg == pytest.approx(want, abs=1e-9)
    assert mesh.theta_deg == pytest.approx(sum(want), abs=1e-9)
    assert sum(mesh.bent.segment_lengths_mm) == pytest.approx(act.plan.centerline.length_mm, abs=1e-9)


@pytest.mark.parametrize("example", ["paper_cross.toml", "designed_hook.toml"])
def test_a_chain_of_one_and_of_many_are_drawn_by_their_bend_pieces(example):
    """The side view, the 3D shape and the studio draw any chain by its pieces: the cross (a chain of one whose
    legs start 0.3 mm in) with its lead-in and tail unbent, the hook with its transitions unbent too."""
    from embroact.export.studio.views import bend_at, side_svg

    a = analyse(load_design(ROOT / "examples" / example))
    act = a.actuators[0]
    pieces = act.bend_pieces()
    assert [k for _, k in pieces].count(-1) >= 2  # a lead-in and a tail in both
    lengths = [length for length, _ in pieces]
    at = a.segment_curves([200.0])[0]
    want = [float(at[i].theta_deg[0]) if i >= 0 else 0.0 for _, i in pieces]
    (panel,) = pv.side_panels(a, a.curves([0.0, 200.0]))
    assert panel.segment_lengths_mm == pytest.approx(lengths, abs=1e-12)
    assert panel.segment_theta_deg[-1] == pytest.approx(want, abs=1e-9)
    tip = _hand_tip(lengths, want)
    shape = panel.shape(1)
    assert shape.profile_mm([shape.length_mm])[0] == pytest.approx([tip.real, tip.imag], abs=1e-9)
    (mesh,), _ = pv.shape_meshes(a, a.curves([0.0, 200.0]), pressure_kpa=200.0, tolerance_mm=0.2)
    assert mesh.bent.segment_lengths_mm == pytest.approx(lengths, abs=1e-12)
    assert mesh.bent.segment_theta_deg == pytest.approx(want, abs=1e-9)
    svg = side_svg(a, bend_at(a, 200.0), 200.0)
    assert svg.count('class="mark"') == 2 * (len(act.segments) - 1)  # segment boundaries, none in a chain of one


def _coiling(max_kpa: float = 300.0):
    """Two 100 mm zigzags of the paper's width: each about 234 deg at 300 kPa, together past a full turn."""
    return design_from_dict({"operation": {"max_pressure_kpa": max_kpa}, "actuator": [{"name": "C", "segment": [
        {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 100},
        {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 100}]}]})


def test_a_strip_that_coils_is_drawn_only_where_it_has_not(tmp_path, capsys):
    a = analyse(_coiling())
    strip = a.curves()[0]
    seg = a.segment_curves()[0]
    names = strip.as_dict()["status"]
    assert names[-1] == "COILED"
    assert all(s == "BENDING" for s in (seg[0].as_dict()["status"][-1], seg[1].as_dict()["status"][-1]))
    first_coiled = names.index("COILED")
    # one uniform 200 mm arc: its 30 mm square-cut stub's fabric corner reaches the fabric behind the clamp
    # where R (1 - cos theta) + 30 sin theta = 0, R = 200 mm / theta (before a full turn)
    limit = math.degrees(brentq(lambda t: 200.0 / t * (1.0 - math.cos(t)) + 30.0 * math.sin(t), math.pi * 1.1,
                                math.pi * 1.99))
    assert 280.0 < limit < 300.0
    assert abs(float(seg[0].theta_deg[first_coiled] + seg[1].theta_deg[first_coiled])) >= limit
    assert abs(float(seg[0].theta_deg[first_coiled - 1] + seg[1].theta_deg[first_coiled - 1])) < limit
    (panel,) = pv.side_panels(a, a.curves())
    last_valid = float(strip.pressure_kpa[first_coiled - 1])
    assert max(panel.pressure_kpa) == last_valid
    design = tmp_path / "c.toml"
    from embroact.export.files.designfile import save_design

    save_design(_coiling(), design)
    assert main(["preview", "mesh", str(design), "-o", str(tmp_path / "m.svg"), "--shape-pressure-kpa", "300"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"shape_pressure_kpa must be in [0, {last_valid:g}]" in err[0] and "got 300" in err[0]


def test_build_writes_every_view_with_per_segment_numbers(tmp_path, capsys, hook):
    out = tmp_path / "out"
    out.mkdir()
    assert main(["build", str(HOOK), "--out", str(out), "--shape-pressure-kpa", str(AT_KPA)]) == 0
    lines = capsys.readouterr().out.splitlines()
    for k, seg in enumerate(hook.actuators[0].segments):
        assert any(line.startswith(f"A1 segment {k}: G {seg.model.g_mpa:.4g} MPa") for line in lines)
    report = json.loads((out / "report.json").read_text())
    (entry,) = report["actuators"]
    assert [s["derived"]["width_mm"] for s in entry["segments"]] == [s.derived.width_mm
                                                                     for s in hook.actuators[0].segments]
    n = len(hook.actuators[0].segments)
    assert len(entry["segment_curves"]) == n
    total = [math.fsum(t) for t in zip(*(c["theta_deg"] for c in entry["segment_curves"]))]
    assert entry["curve"]["theta_deg"] == pytest.approx(total, abs=1e-9)
    mesh = report["mesh"]
    assert mesh["pressure_kpa"] == {"A1": AT_KPA}
    assert math.fsum(mesh["segment_theta_deg"]["A1"]) == pytest.approx(mesh["theta_deg"]["A1"], abs=1e-9)
    html = (out / "report.html").read_text()
    for k in range(n):
        assert f"<th>A1 segment {k}</th>" in html
        assert f"<th>A1 segment {k} theta [deg]</th>" in html
    assert "<th>A1 whole strip theta [deg]</th>" in html and "Segments along the path" in html
    assert (out / "shape.glb").stat().st_size > 0 and "<svg" in (out / "shape3d.svg").read_text()


def test_worksheet_lists_each_segment_and_its_transition(tmp_path, capsys, hook):
    out = tmp_path / "out"
    out.mkdir()
    assert main(["build", str(HOOK), "--out", str(out), "--no-previews"]) == 0
    capsys.readouterr()
    sheet = json.loads((out / "worksheet.json").read_text())
    segs = sheet["actuators"][0]["segments"]
    kinds = [s.derived.pattern for s in hook.actuators[0].segments]
    assert [s["pattern"] for s in segs] == kinds and kinds[-1] == "cross"
    for a, b in zip(segs, segs[1:]):  # the transition is the unbent gap between one segment's legs and the next's
        assert a["transition_mm"] == pytest.approx(b["first_leg_mm"] - a["first_leg_mm"] - a["derived"]["length_mm"],
                                                   abs=1e-9)
        assert a["start_mm"] + a["length_mm"] == pytest.approx(b["start_mm"], abs=1e-9)
    assert segs[-1]["transition_mm"] == 0.0
    text = (out / "worksheet.txt").read_text()
    assert f"ACTUATOR A1 ({len(kinds)} segments: {', '.join(kinds)})" in text
    assert f"SEGMENT {len(kinds) - 1} (cross)" in text and text.count("model G ") == len(kinds)
    assert f"transition to segment 1: {segs[0]['transition_mm']:.2f} mm unbent" in text


def test_stitch_preview_caption_lists_every_segment(tmp_path, capsys, hook):
    out = tmp_path / "st.svg"
    assert main(["preview", "stitches", str(HOOK), "-o", str(out)]) == 0
    capsys.readouterr()
    svg = out.read_text()
    for k, seg in enumerate(hook.actuators[0].segments):  # measured on the needle points
        d = seg.derived
        extra = f", s {d.interval_mm:.3f} mm, alpha0 {d.angle_deg:.2f} deg" if d.pattern == "cross" else ""
        assert f"A1 segment {k} {d.pattern}: w {d.width_mm:.2f} mm{extra}" in svg


def _r0(w: float, rf: float = 1.5) -> float:
    """Sleeve radius r0 = (w + 2 sqrt((w/2)^2 + (2 r_f)^2)) / (2 pi) (docs/model.md)."""
    return (w + 2.0 * math.sqrt((w / 2.0) ** 2 + (2.0 * rf) ** 2)) / (2.0 * math.pi)


def test_tight_sleeve_is_checked_on_every_segment():
    d = design_from_dict({"tube": {"clearance_mm": 0.0}, "actuator": [{"name": "S", "segment": [
        {"pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 40},
        {"pattern": "zigzag", "width_mm": 3.05, "interval_mm": 1, "length_mm": 30},
        {"pattern": "zigzag", "width_mm": 3.2, "interval_mm": 1, "length_mm": 30}]}]})
    a = analyse(d)
    found = [f for f in check_design(a) if f.code == "EA202"]
    assert [f.message.split(":")[0] for f in found] == ["segment 1", "segment 2"]  # w 7 mm: r0 - r_f = 1.08 mm
    for f, w in zip(found, (3.0, 3.2)):  # 3.05 mm: rails at +-1.525 mm, on the 0.1 mm grid +-1.5 mm
        assert f"by only {_r0(w) - 1.5:.3f} mm" in f.message
    starts = [s.plan.first_leg_mm for s in a.actuators[0].segments[1:]]
    x0 = a.plan.origin_mm[0]  # findings are placed in the machine frame; the path starts at the design's x = 0
    assert [float(f.xy_mm[0]) + x0 for f in found] == pytest.approx(starts, abs=1e-9)  # where each segment's legs start


def test_preview_mesh_json_gives_each_segments_bend(tmp_path, capsys, hook):
    out = tmp_path / "m.glb"
    assert main(["preview", "mesh", str(HOOK), "-o", str(out), "--shape-pressure-kpa", str(AT_KPA), "--json"]) == 0
    (shape,) = json.loads(capsys.readouterr().out)["shapes"]
    want = [float(c.theta_deg[0]) for c in hook.segment_curves([AT_KPA])[0]]
    assert shape["segment_theta_deg"] == pytest.approx(want, abs=1e-9)
    assert shape["theta_deg"] == pytest.approx(sum(want), abs=1e-9) and shape["pressure_kpa"] == AT_KPA


def test_a_segmented_actuator_needs_its_whole_strip_curve(hook):
    n = len(hook.actuators[0].segments)
    with pytest.raises(Exception, match=rf"actuator 'A1' has {n} segments: its curve must be its whole strip"):
        render_previews(hook, [hook.segment_curves()[0][0]], mesh_suffix=None)
