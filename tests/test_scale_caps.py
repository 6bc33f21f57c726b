"""Outputs bounded whatever the number of actuators: the side view, the summary line."""
import re

import numpy as np
import xml.etree.ElementTree as ET

import pytest

from embroact.export.pictures.sideview import SIDE_VIEW_MAX_PANELS, SidePanel, side_view_svg

_SVG = "{http://www.w3.org/2000/svg}"


def _panels(n):
    return [SidePanel(f"A{k}", length_mm=20.0, r0_mm=2.3, pressure_kpa=[0.0, 100.0], theta_deg=[0.0, 40.0])
            for k in range(n)]


def _drawn(svg):
    root = ET.fromstring(svg)
    labels = [t.text for g in root.iter(f"{_SVG}g") if g.get("class") == "panel" for t in g.iter(f"{_SVG}text")
              if t.get("font-weight") == "bold"]
    title = next(t.text for t in root.iter(f"{_SVG}text"))
    return labels, title


@pytest.mark.parametrize("n", [1, SIDE_VIEW_MAX_PANELS])
def test_side_view_draws_every_panel_up_to_the_cap(n):
    labels, title = _drawn(side_view_svg(_panels(n)))
    assert labels == [f"A{k}" for k in range(n)] and "of" not in title


def test_side_view_past_the_cap_draws_the_first_and_says_so():
    labels, title = _drawn(side_view_svg(_panels(SIDE_VIEW_MAX_PANELS + 7)))
    assert labels == [f"A{k}" for k in range(SIDE_VIEW_MAX_PANELS)]
    assert title.endswith(f"the first {SIDE_VIEW_MAX_PANELS} of {SIDE_VIEW_MAX_PANELS + 7} actuators")


def test_every_side_view_caller_draws_at_most_the_cap():
    """The build's report, the notebook display and the studio all draw through side_view_svg's one cap."""
    from embroact.export.pictures.display import analysis_html
    from embroact.export.report.stage import render_previews
    from embroact.export.studio.views import bend_at, side_svg
    from embroact.patterns.design import design_from_dict
    from embroact.predict.analysis import analyse

    n = SIDE_VIEW_MAX_PANELS + 2
    analysis = analyse(design_from_dict({"machine": {"hoop_width_mm": 400, "hoop_height_mm": 400}, "actuator": [
        {"name": f"A{k}", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 20,
         "origin_mm": [-150.0 + 40.0 * (k % 8), -150.0 + 25.0 * (k // 8)]} for k in range(n)]}))
    note = f"the first {SIDE_VIEW_MAX_PANELS} of {n} actuators"
    build = render_previews(analysis, mesh_suffix=None).files["shape.svg"]
    studio = side_svg(analysis, bend_at(analysis, 150.0), 150.0)
    html = analysis_html(analysis)
    shown = next(svg for svg in re.findall(r"<svg.*?</svg>", html, flags=re.S) if "Bent shape" in svg)
    for svg in (build, studio, shown):
        assert _drawn(svg)[0] == [f"A{k}" for k in range(SIDE_VIEW_MAX_PANELS)]
    assert _drawn(build)[1].endswith(note) and _drawn(shown)[1].endswith(note)
    assert _drawn(studio)[1] == f"Side view at 150 kPa: {note}"


def test_summary_line_names_five_actuators_per_code_and_counts_the_rest():
    import embroact.predict.rules  # noqa: F401  (declares the model rules)
    from embroact.patterns.base.findings import SUMMARY_NAMES, summary_line
    from embroact.patterns.base.findings import RULES

    fs = [RULES.finding("EA403", "x", actuator=f"A{k}") for k in range(1000)] + [
        RULES.finding("EA405", "y", actuator="B"), RULES.finding("EA405", "y", actuator="B")]
    line = summary_line(fs)
    assert SUMMARY_NAMES == 5 and "\n" not in line and len(line) < 200
    assert line.endswith("EA403 (A0, A1, A2, A3, A4 and 995 more), EA405 (B)")


def test_a_path_longer_than_the_hoop_is_refused_before_anything_is_generated(tmp_path, monkeypatch, capsys):
    """EA306 from the paths alone: a 3 m straight zigzag in a 1 m hoop is refused with the rule's code, no
    stitch generated and nothing written; --force still builds (the rule then reports it on the records)."""
    from embroact.export.cli.main import main
    from embroact.patterns import design as design_module

    src = tmp_path / "long.toml"
    src.write_text('name = "long"\n[machine]\nhoop_width_mm = 1000.0\nhoop_height_mm = 1000.0\n[[actuator]]\n'
                   'name = "A"\npattern = "zigzag"\nwidth_mm = 7.0\ninterval_mm = 2.0\nlength_mm = 3000.0\n')
    out = tmp_path / "out"
    out.mkdir()
    generated = []
    real = design_module.generate_actuator
    monkeypatch.setattr(design_module, "generate_actuator", lambda *a, **k: generated.append(1) or real(*a, **k))
    assert main(["build", str(src), "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert "EA306 the actuator paths alone span 3000.0 x 0.0 mm, more than the 1000 x 1000 mm hoop" in err
    assert generated == [] and list(out.iterdir()) == []
    assert main(["build", str(src), "--out", str(out), "--force", "--no-previews", "--mesh-format", "none"]) == 0
    assert generated and any(p.suffix == ".dst" for p in out.iterdir())


def test_report_tables_show_identical_actuators_once_and_at_most_the_column_cap():
    """150 identical actuators and one other: two columns and a note; 150 distinct ones: the first 100 and
    a note naming report.json (which keeps every actuator)."""
    from embroact.export.report.report import REPORT_MAX_COLUMNS, report_data, report_html, report_json

    same = [{"name": f"A{k}", "derived": {"r0_mm": 2.58}, "model": {"g_mpa": 2.7}} for k in range(150)]
    other = [{"name": "B", "derived": {"r0_mm": 3.1}, "model": {"g_mpa": 2.7}}]
    html = report_html(report_data(title="t", actuators=same + other))
    assert "<th>A0 and 149 identical</th>" in html and "<th>B</th>" in html and "<th>A1</th>" not in html
    assert "151 columns, identical ones shown once" in html
    distinct = [{"name": f"A{k}", "derived": {"r0_mm": 2.0 + k / 1000}} for k in range(150)]
    data = report_data(title="t", actuators=distinct)
    html = report_html(data)
    assert f"<th>A{REPORT_MAX_COLUMNS - 1}</th>" in html and f"<th>A{REPORT_MAX_COLUMNS}</th>" not in html
    assert f"the first {REPORT_MAX_COLUMNS} of 150 shown (report.json has every one)" in html
    assert '"name": "A149"' in report_json(data)


def test_label_placer_index_counts_what_a_full_scan_counts():
    """The placer's obstacle index (cells over the frame) answers every query as a scan of every obstacle
    does: random boxes, polylines (long and short, some wider than the index's cells) and placed labels."""
    import numpy as np

    from embroact.export.pictures.labels import Box, Placer, _segments_hit

    rng = np.random.default_rng(7)
    placer = Placer(Box(0.0, 0.0, 400.0, 300.0), margin=0.5)
    boxes, polylines = [], []
    for _ in range(60):
        x, y = rng.uniform(-20, 420), rng.uniform(-20, 320)
        b = Box(x, y, x + rng.uniform(0, 30), y + rng.uniform(0, 10))
        placer.block_box(b)
        boxes.append(b.grown(0.5))
    for k in range(40):
        pts = np.cumsum(rng.normal(0.0, 40.0 if k % 4 == 0 else 3.0, (int(rng.integers(1, 60)), 2)), axis=0) + 150
        placer.block_polyline(pts)
        polylines.append(np.vstack([pts, pts]) if len(pts) == 1 else pts)
    for k in range(80):
        placer.place(f"L{k}", tuple(rng.uniform(0, 400, 2)), 6.0, gap=1.0)
    segs = np.vstack([np.hstack([p[:-1], p[1:]]) for p in polylines])
    for _ in range(300):
        x, y = rng.uniform(-30, 430), rng.uniform(-30, 330)
        q = Box(x, y, x + rng.uniform(0, 60), y + rng.uniform(0, 20))
        scan = sum(q.overlaps(b) for b in boxes) + 10_000 * sum(q.overlaps(lab.box.grown(0.5)) for lab in placer.labels)
        scan += _segments_hit(segs, q.grown(0.5)) + (0 if placer.frame.contains(q) else 100_000_000)
        assert placer.collisions(q) == scan


def test_report_findings_past_the_cap_are_one_row_per_kind_errors_first():
    """150 alike warnings and one error: two rows, the error first, the warning counted (150) with the first five
    actuators named; report.json keeps all 151. At the cap, every finding has its own row."""
    from embroact.export.report.report import REPORT_MAX_FINDINGS, report_data, report_html, report_json

    warn = [{"code": "EA403", "severity": "warning", "message": "bend beyond limit", "actuator": f"A{k}",
             "fix": "shorten"} for k in range(150)]
    err = [{"code": "EA101", "severity": "error", "message": "needle in the tube", "actuator": "B", "fix": "widen"}]
    data = report_data(title="t", actuators=[], findings=warn + err)
    html = report_html(data)
    section = html.split('<section id="findings">', 1)[1]
    rows = section.split("<tr")[2:]
    assert len(rows) == 2 and "EA101" in rows[0] and "EA403" in rows[1]
    assert '<td class="num">150</td><td>A0, A1, A2, A3, A4 and 145 more</td>' in rows[1]
    assert "151 findings in 2 kinds" in section and report_json(data).count('"code"') == 151
    few = report_html(report_data(title="t", actuators=[], findings=warn[:REPORT_MAX_FINDINGS]))
    assert few.split('<section id="findings">', 1)[1].count("<tr") == REPORT_MAX_FINDINGS + 1


def test_a_figure_past_the_report_budget_is_linked_to_its_file(monkeypatch):
    """A figure larger than REPORT_FIGURE_MAX_BYTES is named by its file (a link, the report stays small); one
    without a file, or within the budget, is inline."""
    from embroact.export.report import report as report_module
    from embroact.export.report.report import report_data, report_html

    big = "<svg>" + "<g/>" * 1000 + "</svg>"
    monkeypatch.setattr(report_module, "REPORT_FIGURE_MAX_BYTES", 1000)
    data = report_data(title="t", actuators=[])
    linked = report_html(data, figures={"stitches": big, "bend": "<svg></svg>"}, figure_files={
        "stitches": "preview.svg", "bend": "bend.svg"})
    assert '<a href="preview.svg">preview.svg</a>' in linked and big not in linked and "<svg></svg>" in linked
    assert big in report_html(data, figures={"stitches": big})


def test_the_3d_picture_holds_at_most_its_polygon_budget(monkeypatch):
    """Past PICTURE_MAX_POLYGONS the screen cells widen until the picture holds at most that many polygons;
    within it the picture is unchanged."""
    import xml.etree.ElementTree as ET

    from embroact.export.pictures import meshview
    from embroact.export.pictures.mesh import PlanarPath, actuator_mesh
    from embroact.patterns.centerline import Centerline

    shapes = [actuator_mesh(PlanarPath.from_centerline(Centerline([[0.0, 30.0 * k], [20.0, 30.0 * k]])), 60.0,
                            width_mm=5.0, r0_mm=2.0, measure=False, name=f"A{k}") for k in range(6)]

    def polygons(svg):
        return sum(1 for e in ET.fromstring(svg).iter(f"{_SVG}polygon"))

    free = polygons(meshview.mesh_svg(shapes))
    monkeypatch.setattr(meshview, "PICTURE_MAX_POLYGONS", free // 4)
    capped = polygons(meshview.mesh_svg(shapes))
    assert 0 < capped <= free // 4 < free
    monkeypatch.setattr(meshview, "PICTURE_MAX_POLYGONS", free)
    assert polygons(meshview.mesh_svg(shapes)) == free


def test_the_stitch_preview_text_lists_alike_actuators_once():
    """Past PREVIEW_MAX_LINES segment lines, actuators sewn alike share one line (and the picture's height
    stops growing with their number); within it, every actuator has its own line."""
    from embroact.export.pictures.stitches import PREVIEW_MAX_LINES, plan_svg
    from embroact.patterns.design import build_plan, design_from_dict

    def texts(n):
        d = design_from_dict({"machine": {"hoop_width_mm": 400, "hoop_height_mm": 400}, "actuator": [
            {"name": f"A{k}", "pattern": "zigzag", "width_mm": 5, "interval_mm": 1, "length_mm": 10,
             "origin_mm": [-150.0 + 40.0 * (k % 8), -150.0 + 20.0 * (k // 8)]} for k in range(n)]})
        root = ET.fromstring(plan_svg(build_plan(d)))
        g = next(g for g in root.iter(f"{_SVG}g") if g.get("id") == "params")
        return [t.text for t in g.iter(f"{_SVG}text")]

    few, many = texts(PREVIEW_MAX_LINES), texts(PREVIEW_MAX_LINES + 5)
    assert [t.split()[0] for t in few[1:]] == [f"A{k}" for k in range(PREVIEW_MAX_LINES)]
    assert len(many) == 2 and many[1].startswith(f"A0 (and {PREVIEW_MAX_LINES + 4} alike) zigzag: w 5.00 mm")


def test_identical_actuators_are_meshed_once_and_moved():
    """MovedMeshes makes one mesh for paths that differ only in their start; the moved copies hold what meshing
    each path directly gives (same triangles, vertices to 1e-9 mm, same deviation), and a different bend is its
    own mesh."""
    from dataclasses import replace

    from embroact.export.pictures.mesh import MovedMeshes, PlanarPath, actuator_mesh
    from embroact.patterns.centerline import Centerline

    path = PlanarPath.from_centerline(Centerline([[0.0, 0.0], [30.0, 10.0], [60.0, 0.0]]))
    starts = [(0.0, 0.0), (100.0, 0.0), (-40.0, 250.0)]
    meshes = MovedMeshes()
    made = [meshes.mesh(replace(path, start_mm=s), 70.0, width_mm=5.0, r0_mm=2.0, name=f"A{k}")
            for k, s in enumerate(starts)]
    other = meshes.mesh(path, 71.0, width_mm=5.0, r0_mm=2.0, name="B")
    assert meshes.made == 2 and other.theta_deg == 71.0
    for k, (m, s) in enumerate(zip(made, starts)):
        direct = actuator_mesh(replace(path, start_mm=s), 70.0, width_mm=5.0, r0_mm=2.0, name=f"A{k}")
        assert m.name == direct.name and m.bent.path.start_mm == direct.bent.path.start_mm
        for a, b in zip(m.bodies, direct.bodies):
            assert np.array_equal(a.faces, b.faces) and np.abs(a.vertices - b.vertices).max() < 1e-9
        assert abs(m.max_deviation_mm - direct.max_deviation_mm) < 1e-12
        got, want = m.bent.frames([0.0, 35.0, 60.0]), direct.bent.frames([0.0, 35.0, 60.0])
        assert np.abs(got[0] - want[0]).max() < 1e-9 and np.abs(got[1] - want[1]).max() < 1e-12


def test_derived_geometry_past_the_cap_is_ranges_then_columns_findings_first():
    """Past REPORT_MAX_COLUMNS actuators the derived geometry opens with each quantity's count, least and
    greatest value and number of distinct values (by hand: r0 2.0 x 120, 2.5 x 30), and the collapsed columns
    put the actuators with findings first."""
    from embroact.export.report.report import REPORT_MAX_COLUMNS, report_data, report_html

    acts = [{"name": f"A{k}", "derived": {"r0_mm": 2.0 if k < 120 else 2.5, "has_sleeve": True}} for k in range(150)]
    finding = {"code": "EA101", "severity": "error", "message": "m", "actuator": "A130", "fix": "f"}
    html = report_html(report_data(title="t", actuators=acts, findings=[finding]))
    derived = html.split('<section id="derived">', 1)[1].split("</section>", 1)[0]
    ranges, columns = derived.split("<details>", 1)
    assert ('<tr><th>r0 [mm]</th><td class="num">150</td><td class="num">2</td><td class="num">2.5</td>'
            '<td class="num">2</td></tr>') in ranges and "has sleeve" not in ranges
    heads = [h.split("</th>")[0] for h in columns.split("<th>")[2:4]]
    assert heads == ["A120 and 29 identical", "A0 and 119 identical"] and "those with findings first" in columns
    small = report_html(report_data(title="t", actuators=acts[:REPORT_MAX_COLUMNS], findings=[finding]))
    assert "<details><summary>Per actuator" not in small
