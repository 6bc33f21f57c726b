"""report.json / report.html: content, self-containment, the build stage, and a real headless browser."""
import json
import math
import os
import re
import shutil
import subprocess
from html.parser import HTMLParser

import numpy as np
import pytest

from embroact.export.report.build import build
from embroact.export.pictures.previews import shape_theta_deg, side_pressures
from embroact.export.report.stage import Previews, previews_stage, render_previews
from embroact.export.report.report import FIGURES, finding_dict, report_data, report_html, report_json
from embroact.patterns.design import default_design
from embroact.patterns.base.errors import ParameterError
from embroact.patterns.base.findings import Finding, Severity


class _Tags(HTMLParser):
    def __init__(self):
        super().__init__()
        self.tags, self.refs = [], []

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        self.refs += [(tag, k, v) for k, v in attrs if k in ("src", "href", "xlink:href", "data", "action")]


def _scan(html):
    p = _Tags()
    p.feed(html)
    return p


FINDING = Finding("EA104", Severity.WARNING, "stitch 0.2 mm < 0.3 mm <b>&</b>", actuator="A1", stitch_index=7,
                  xy_mm=(1.0, -3.5), fix="increase the interval")


# ----------------------------------------------------------------------------- report.py
def test_finding_objects_and_dicts_give_the_same_keys():
    d = finding_dict(FINDING)
    assert (d["code"], d["severity"], d["stitch_index"], d["xy_mm"]) == ("EA104", "warning", 7, [1.0, -3.5])
    plain = finding_dict({"code": "X1", "severity": "error", "message": "m"})
    assert plain["fix"] is None and plain["actuator"] is None


def test_json_is_strict_and_keeps_numbers():
    data = report_data(title="t", actuators=[{"name": "A", "curve": {"theta_deg": np.array([0.0, np.nan, 2.5])}}])
    text = report_json(data)
    back = json.loads(text)
    assert back["actuators"][0]["curve"]["theta_deg"] == [0.0, None, 2.5]
    assert "NaN" not in text and back["findings"] == [] and back["worksheet"] is None


def test_html_escapes_text_and_loads_nothing():
    data = report_data(title="<design & co>", actuators=[{"name": "A1", "derived": {"r0_mm": 2.5}}],
                       findings=[FINDING])
    html = report_html(data, figures={"bend": '<?xml version="1.0"?><svg xmlns="http://www.w3.org/2000/svg"/>'})
    assert "&lt;design &amp; co&gt;" in html and "&lt;b&gt;&amp;&lt;/b&gt;" in html
    assert "<?xml" not in html
    scan = _scan(html)
    assert not {"script", "link", "iframe", "object", "embed", "img"} & set(scan.tags)
    assert scan.refs == []
    assert "Content-Security-Policy" in html and "default-src 'none'" in html
    assert 'class="warning"' in html and "A1, stitch 7 at (1.00, -3.50) mm" in html  # as embroact check prints it


def test_unknown_figure_rejected():
    with pytest.raises(ParameterError, match="figure names must be among"):
        report_html(report_data(title="t", actuators=[]), figures={"movie": "<svg/>"})


# ----------------------------------------------------------------------------- previews helpers
def test_side_pressures_and_shape_theta():
    assert side_pressures([0, 10, 20, 30], [0, float("nan"), 1, 2], count=3) == (0.0, 20.0, 30.0)

    class C:
        pressure_kpa = np.array([0.0, 100.0, 200.0])
        theta_deg = np.array([0.0, 10.0, 30.0])
        segments = ()  # a curve-like object with no segment curves

    assert shape_theta_deg(C, None) == (200.0, 30.0)
    assert shape_theta_deg(C, 150.0) == (150.0, 20.0)
    with pytest.raises(ParameterError, match=r"shape_pressure_kpa must be in \[0, 200\]"):
        shape_theta_deg(C, 250.0)


def test_pressures_follow_the_design():
    from embroact.predict.analysis import analyse

    assert analyse(default_design()).pressures_kpa == tuple(float(p) for p in range(0, 301, 10))


# ----------------------------------------------------------------------------- the build stage
@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("build")
    res = build(default_design(), out, stages=[previews_stage()])
    return out, res


def test_build_writes_every_output(built):
    out, res = built
    expected = {"paper-zigzag.dst", "preview.svg", "template.svg", "worksheet.json", "worksheet.txt", "bend.svg", "shape.svg",
                "template-a4.html", "template-letter.html",
                "shape.glb", "shape3d.svg", "report.json", "report.html"}
    assert set(res.files) == expected == set(os.listdir(out))


def test_report_json_content_against_hand_values(built):
    out, _ = built
    data = json.loads((out / "report.json").read_text())
    (act,) = data["actuators"]
    # docs/model.md section 2: r0 = (w + 2 sqrt((w/2)^2 + (2 r_f)^2)) / (2 pi), w = 7, r_f = 1.5
    r0 = (7.0 + 2.0 * math.hypot(3.5, 3.0)) / (2.0 * math.pi)
    assert act["derived"]["r0_mm"] == pytest.approx(r0, rel=1e-12)
    # paper law P0 = (G_e/2) (x - 1/x)^2, x = r0 / r_f, G_e = 0.13 MPa
    x = r0 / 1.5
    assert act["model"]["tube_law_p0_kpa"] == pytest.approx(65.0 * (x - 1.0 / x) ** 2, rel=1e-12)
    curve = act["curve"]
    assert curve["pressure_kpa"][:3] == [0.0, 10.0, 20.0] and curve["status"][0] == "INFLATION"
    assert curve["theta_deg"][0] == 0.0 and curve["calibration"] == "calibration paper-2025 (zigzag, width_mm=7)"
    # the model and where each number came from: the paper's fitted pair for w = 7 mm
    model = act["model"]
    assert (model["g_mpa"], model["p0_kpa"], model["tube_law"]) == (2.7, 85.0, "paper")
    assert model["g_source"] == model["p0_source"] == "calibration paper-2025 (zigzag, width_mm=7)"
    assert model["tube"] == {"outer_radius_mm": 1.5, "inner_radius_mm": 1.0, "g_e_mpa": 0.13}
    assert data["mesh"]["theta_deg"]["A1"] == pytest.approx(curve["theta_deg"][-1])
    assert 0 < data["mesh"]["max_deviation_mm"] <= data["mesh"]["tolerance_mm"] == 0.05
    assert data["worksheet"]["stitch_count"] == 106


def test_report_html_holds_every_section(built):
    out, _ = built
    html = (out / "report.html").read_text()
    for key in list(FIGURES) + ["model", "derived", "worksheet", "findings"]:
        assert f'<section id="{key}">' in html
    model = html[html.index('<section id="model">'):html.index('<section id="derived">')]
    assert "<td>calibration paper-2025 (zigzag, width_mm=7)</td>" in model and ">2.7<" in model and ">85<" in model
    assert html.count("<svg") == 4
    assert (out / "preview.svg").read_text()[(out / "preview.svg").read_text().find("<svg"):] in html
    scan = _scan(html)
    assert "script" not in scan.tags and scan.refs == []


def test_report_names_a_chain_of_one_as_its_actuator(built):
    """A single-pattern actuator is one block named "A1" in every table (as in the worksheet, the bend chart's
    legend and embroact predict), never "A1 segment 0" or a whole strip beside itself."""
    out, _ = built
    html = (out / "report.html").read_text()
    assert "A1 segment" not in html and "whole strip" not in html
    derived = html[html.index('<section id="derived">'):html.index('<section id="worksheet">')]
    assert derived.count("<th>A1</th>") == 2  # the derived geometry's column and the segments-along-the-path row
    assert "<th>A1 theta [deg]</th>" in html
    assert "A1 segment" not in (out / "bend.svg").read_text()


def test_render_is_deterministic_and_mesh_optional(built):
    from embroact.predict.analysis import analyse

    analysis = analyse(default_design())
    curves = analysis.curves([0.0, 100.0, 200.0])
    a = render_previews(analysis, curves, stitch_svg="<svg/>", mesh_suffix=".stl")
    b = render_previews(analyse(default_design()), curves, stitch_svg="<svg/>", mesh_suffix=".stl")
    assert isinstance(a, Previews) and a.files == b.files and "shape.stl" in a.files
    none = render_previews(analysis, curves, stitch_svg="<svg/>", mesh_suffix=None)
    assert set(none.files) == {"bend.svg", "shape.svg", "report.json", "report.html"} and none.mesh is None
    with pytest.raises(ParameterError, match="need one curve per actuator"):
        render_previews(analysis, (), stitch_svg="<svg/>")


# ----------------------------------------------------------------------------- headless browser
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
          "--disable-component-update", "--disable-sync", "--no-first-run", "--enable-logging=stderr", "--v=0"]


def _browse(url, profile, *extra):
    return subprocess.run([CHROMIUM, *_FLAGS, f"--user-data-dir={profile}", *extra, url],
                          capture_output=True, text=True, timeout=120)


def _console(stderr):
    return [ln for ln in stderr.splitlines() if ":CONSOLE" in ln]


@pytest.mark.skipif(CHROMIUM is None, reason="no headless browser installed (apt-get install chromium)")
def test_report_renders_in_headless_chromium_without_console_errors(built, tmp_path):
    out, _ = built
    # control: the detector sees a blocked external load and a blocked script
    bad = tmp_path / "bad.html"
    bad.write_text(report_html(report_data(title="bad", actuators=[])).replace(
        "</body>", '<img src="http://example.invalid/x.png"><script>console.error("x")</script></body>'))
    assert len(_console(_browse(bad.as_uri(), tmp_path / "p0", "--dump-dom").stderr)) >= 2
    page = (out / "report.html").as_uri()
    dom = _browse(page, tmp_path / "p1", "--dump-dom")
    assert dom.returncode == 0 and _console(dom.stderr) == []
    assert dom.stdout.count("<svg") == 4 and "Design-rule findings" in dom.stdout
    assert re.search(r'<polyline[^>]*class="curve"', dom.stdout)
    shot = tmp_path / "report.png"
    run = _browse(page, tmp_path / "p2", f"--screenshot={shot}", "--window-size=1200,2400")
    assert run.returncode == 0 and _console(run.stderr) == []
    png = shot.read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert int.from_bytes(png[16:20], "big") == 1200 and int.from_bytes(png[20:24], "big") == 2400
