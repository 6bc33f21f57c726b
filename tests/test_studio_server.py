"""embroact studio's server, through Starlette's test client: refusals, validation, agreement with the CLI.

Expected values come from outside the studio: design-file messages from
``design_from_dict`` on hand-written dicts, bends from ``analyse`` of independently built
designs and from ``embroact predict --json``, written files through ``load_design`` and
``embroact build``.
"""
import json
import os
import subprocess
import sys

import pytest

pytest.importorskip("starlette")
pytest.importorskip("httpx2")

from starlette.testclient import TestClient  # noqa: E402

from embroact.export.cli.main import main  # noqa: E402
from embroact.export.files.designfile import load_design  # noqa: E402
from embroact.export.studio.app import create_app  # noqa: E402
from embroact.export.studio.session import Studio  # noqa: E402
from embroact.patterns.base.errors import DesignFileError  # noqa: E402
from embroact.patterns.design import default_design, design_from_dict  # noqa: E402
from embroact.predict.analysis import analyse  # noqa: E402

TOKEN = "test-token-123"
PORT = 8123
BASE = f"http://127.0.0.1:{PORT}"
AUTH = {"X-Embroact-Token": TOKEN}


def paper_dict(**actuator) -> dict:
    """The default design written out by hand (the paper's zigzag), with actuator keys replaced."""
    a = {"name": "A1", "pattern": "zigzag", "width_mm": 7.0, "interval_mm": 1.0, "length_mm": 100.0, **actuator}
    return {"name": "paper-zigzag", "actuator": [a]}


def design_file_message(d: dict) -> str:
    with pytest.raises(DesignFileError) as exc:
        design_from_dict(d)
    return str(exc.value)


@pytest.fixture
def out_dir(tmp_path):
    d = tmp_path / "out"
    d.mkdir()
    return d


@pytest.fixture
def client(out_dir):
    app = create_app(Studio(default_design(), out_dir), token=TOKEN, port=PORT)
    return TestClient(app, base_url=BASE)


def edit(client, values, pressure_kpa=None):
    body = {"values": values} if pressure_kpa is None else {"values": values, "pressure_kpa": pressure_kpa}
    return client.post("/api/edit", json=body, headers=AUTH)


# ------------------------------------------------------------------ refusals
@pytest.mark.parametrize("method,path", [("GET", "/"), ("GET", "/api/views"), ("GET", "/static/studio.js"),
                                         ("GET", "/api/shape3d"), ("POST", "/api/save"), ("POST", "/api/build")])
def test_a_request_without_the_token_is_refused(client, out_dir, method, path):
    r = client.request(method, path, json={"name": "x.toml"} if method == "POST" else None)
    assert r.status_code == 403
    assert "token" in r.json()["error"]
    r = client.request(method, path + "?token=wrong-token", json={"name": "x.toml"} if method == "POST" else None)
    assert r.status_code == 403
    assert list(out_dir.iterdir()) == []


def test_the_token_is_accepted_in_the_query_or_the_header(client):
    assert client.get(f"/api/views?token={TOKEN}").status_code == 200
    assert client.get("/api/views", headers=AUTH).status_code == 200
    page = client.get(f"/?token={TOKEN}")
    assert page.status_code == 200 and f"static/studio.js?token={TOKEN}" in page.text
    assert client.get(f"/static/studio.js?token={TOKEN}").headers["content-type"].startswith("text/javascript")


@pytest.mark.parametrize("host", ["evil.example", f"evil.example:{PORT}", "127.0.0.1:9999", "127.0.0.1",
                                  f"192.168.1.5:{PORT}", f"localhost.evil.example:{PORT}"])
def test_a_request_for_another_host_is_refused(client, host):
    r = client.get("/api/views", headers={**AUTH, "Host": host})
    assert r.status_code == 403
    assert "Host" in r.json()["error"]


def test_localhost_with_the_port_is_this_host(client):
    assert client.get("/api/views", headers={**AUTH, "Host": f"localhost:{PORT}"}).status_code == 200


def test_a_post_from_another_site_is_refused(client, out_dir):
    r = client.post("/api/save", json={"name": "x.toml"}, headers={**AUTH, "Origin": "http://evil.example"})
    assert r.status_code == 403
    assert list(out_dir.iterdir()) == []


@pytest.mark.parametrize("name", ["../escape.toml", "/tmp/escape.toml", "sub/escape.toml", "..\\escape.toml",
                                  ".hidden.toml", "..", "", "escape.dst", "a\x00.toml", " x.toml", 7, None])
def test_a_write_outside_the_output_directory_is_refused(client, out_dir, name):
    before = sorted(os.listdir(out_dir.parent))
    r = client.post("/api/save", json={"name": name}, headers=AUTH)
    assert r.status_code == 403, r.text
    assert "name must" in r.json()["error"]
    assert sorted(os.listdir(out_dir.parent)) == before and list(out_dir.iterdir()) == []


def test_a_symbolic_link_out_of_the_output_directory_is_refused(client, out_dir, tmp_path):
    outside = tmp_path / "outside.toml"
    (out_dir / "link.toml").symlink_to(outside)
    r = client.post("/api/save", json={"name": "link.toml"}, headers=AUTH)
    assert r.status_code == 403
    assert not outside.exists()


# ------------------------------------------------------------------ validation
@pytest.mark.parametrize("key,value,actuator", [
    ("actuator[0].width_mm", -1, {"width_mm": -1}),
    ("actuator[0].width_mm", "abc", {"width_mm": "abc"}),
    ("actuator[0].interval_mm", 0, {"interval_mm": 0}),
    ("actuator[0].length_mm", 1e7, {"length_mm": 1e7}),
    ("actuator[0].pattern", "spiral", {"pattern": "spiral"}),
    ("actuator[0].model.g_mpa", -2, {"model": {"g_mpa": -2}}),
])
def test_an_invalid_value_gets_the_design_files_message_and_changes_nothing(client, key, value, actuator):
    before = client.get("/api/views?pressure_kpa=150", headers=AUTH).json()
    r = edit(client, {key: value}, 150)
    assert r.status_code == 200
    body = r.json()
    assert body["applied"] is False
    assert body["error"] == design_file_message(paper_dict(**actuator))
    assert "\n" not in body["error"]
    assert body["key"] == key
    after = client.get("/api/views?pressure_kpa=150", headers=AUTH).json()
    assert after == before


def test_a_tube_value_names_its_field(client):
    body = edit(client, {"tube.outer_radius_mm": 0}).json()
    d = paper_dict()
    d["tube"] = {"outer_radius_mm": 0}
    assert (body["key"], body["error"]) == ("tube.outer_radius_mm", design_file_message(d))


@pytest.mark.parametrize("key", ["actuator[0].colour_mm", "actuator[3].width_mm", "actuator[0].path", "__class__",
                                 "tube", "actuator[0].model.calibration.name", "actuator[0].angle_deg"])
def test_an_unknown_parameter_is_refused(client, key):
    r = edit(client, {key: 1.0})
    assert r.status_code == 400
    assert "unknown design parameter" in r.json()["error"]


def test_bad_request_bodies_are_one_line_errors(client):
    for body in (b"not json", b"[1, 2]", b'{"values": []}', b'{"values": {}}'):
        r = client.post("/api/edit", content=body, headers=AUTH)
        assert r.status_code == 400 and "\n" not in r.json()["error"]
    r = client.get("/api/views?pressure_kpa=900", headers=AUTH)
    assert r.status_code == 400 and "pressure_kpa must be in [0, 300]" in r.json()["error"]


# ------------------------------------------------------------------ agreement with the CLI
def test_an_edit_shows_what_analyse_and_embroact_predict_give(client, capsys, tmp_path):
    v = edit(client, {"actuator[0].width_mm": "8.5"}, 180).json()
    a = analyse(design_from_dict(paper_dict(width_mm=8.5)))
    expected = float(a.curves([180.0])[0].theta_deg[0])
    act = v["actuators"][0]
    assert act["theta_deg"] == pytest.approx(expected, rel=1e-12)
    assert act["derived"]["width_mm"] == pytest.approx(8.4)  # rails at +-4.25 mm sewn at +-4.2 (0.1 mm grid, half to even)
    assert act["model"]["p0_kpa"] == pytest.approx(a.actuators[0].model.p0_kpa)
    from embroact.export.files.tomltext import dumps

    design_file = tmp_path / "edited.toml"  # the edited design, as the studio saves it (the path where it was)
    design_file.write_text(dumps(paper_dict(width_mm=8.5)))
    assert main(["predict", str(design_file), "--pressure-kpa", "180", "--json"]) == 0
    (cli,) = json.loads(capsys.readouterr().out)["actuators"]
    assert cli["pressure_kpa"] == [180.0]
    assert cli["theta_deg"][0] == pytest.approx(act["theta_deg"], rel=1e-12)
    # the stitch preview is the build's plan_svg of the same plan, with the findings circled on top
    from embroact.export.pictures.stitches import plan_svg

    plain = plan_svg(a.plan)
    assert v["stitches_svg"].startswith(plain[: plain.rfind("</svg>")])
    assert v["stitches_svg"].count('class="finding') == sum(f["xy_mm"] is not None for f in v["findings"])


def test_the_findings_are_check_designs(client):
    from embroact.predict.rules import check_design

    v = edit(client, {"actuator[0].width_mm": 4.0, "actuator[0].interval_mm": 0.4}).json()
    expected = check_design(analyse(design_from_dict(paper_dict(width_mm=4.0, interval_mm=0.4))))
    assert [(f["code"], f["xy_mm"]) for f in v["findings"]] == [(f.code, list(f.xy_mm) if f.xy_mm else None)
                                                                 for f in expected]
    assert "EA105" in v["summary"]  # needle points dense: placed, so circled on the preview
    assert v["stitches_svg"].count('class="finding warning"') == sum(f.code == "EA105" for f in expected)


def test_switching_the_pattern_brings_the_cross_keys(client):
    v = edit(client, {"actuator[0].pattern": "cross", "actuator[0].interval_mm": 1.4}).json()
    keys = [f["key"] for f in v["fields"]]
    assert "actuator[0].angle_deg" in keys and "actuator[0].adjust" in keys
    expected = analyse(design_from_dict(paper_dict(pattern="cross", interval_mm=1.4, angle_deg=45.0)))
    assert v["actuators"][0]["derived"]["angle_deg"] == pytest.approx(expected.actuators[0].derived.angle_deg)
    v = edit(client, {"actuator[0].pattern": "zigzag"}).json()
    assert "actuator[0].angle_deg" not in [f["key"] for f in v["fields"]]


def test_a_lower_working_pressure_pulls_the_slider_down(client):
    v = edit(client, {"operation.max_pressure_kpa": 120}, 250).json()
    assert v["pressure_kpa"] == 120 and v["max_pressure_kpa"] == 120


# ------------------------------------------------------------------ outputs
def test_save_writes_a_design_that_embroact_build_accepts(client, out_dir, tmp_path):
    edit(client, {"actuator[0].width_mm": 8.0, "name": "wide one"})
    r = client.post("/api/save", json={"name": "wide.toml"}, headers=AUTH)
    assert r.status_code == 200 and r.json()["file"] == "wide.toml"
    saved = load_design(out_dir / "wide.toml")
    assert saved == design_from_dict({**paper_dict(width_mm=8.0), "name": "wide one"})
    other = tmp_path / "built"
    other.mkdir()
    assert main(["build", str(out_dir / "wide.toml"), "--out", str(other), "--no-previews"]) == 0
    assert (other / "wide_one.dst").exists()


def test_build_writes_what_embroact_build_writes(client, out_dir, tmp_path):
    r = client.post("/api/build", json={}, headers=AUTH)
    assert r.status_code == 200, r.text
    other = tmp_path / "cli"
    other.mkdir()
    assert main(["build", "--out", str(other)]) == 0
    assert sorted(r.json()["files"]) == sorted(os.listdir(other)) == sorted(os.listdir(out_dir))
    assert (out_dir / "paper-zigzag.dst").read_bytes() == (other / "paper-zigzag.dst").read_bytes()


def test_build_refuses_on_rule_errors_and_writes_nothing(client, out_dir):
    edit(client, {"machine.max_stitch_mm": 5.0})  # 7 mm legs: EA103 stitch over machine maximum (error)
    r = client.post("/api/build", json={"force": False}, headers=AUTH)
    assert r.status_code == 409 and r.json()["error"].startswith("design-rule error EA103")
    assert list(out_dir.iterdir()) == []
    assert client.post("/api/build", json={"force": True}, headers=AUTH).status_code == 200
    assert (out_dir / "paper-zigzag.dst").exists()


def test_inverse_design_is_a_proposal_that_reaches_the_target(client):
    r = client.post("/api/inverse", json={"bend_deg": 84.5, "pressure_kpa": 150, "pattern": "zigzag"}, headers=AUTH)
    assert r.status_code == 200, r.text
    res = r.json()
    assert res["reached"] is True and res["origin_mm"] == [0.0, 0.0]  # 6.2 mm: both rails on the grid at y = 0
    v = client.post("/api/apply-proposal", json={"pressure_kpa": 150}, headers=AUTH).json()
    width = res["values"]["actuator[0].width_mm"]
    theta = float(analyse(design_from_dict(paper_dict(width_mm=width))).curves([150.0])[0].theta_deg[0])
    assert v["actuators"][0]["theta_deg"] == pytest.approx(theta, rel=1e-12)
    assert theta == pytest.approx(res["best"]["theta_deg"], abs=1e-9) and abs(theta - 84.5) <= 0.5
    bad = client.post("/api/inverse", json={"bend_deg": "x", "pressure_kpa": 150}, headers=AUTH)
    assert bad.status_code == 400 and bad.json()["error"] == "bend_deg must be a number, got 'x'"


def test_the_3d_view_is_the_mesh_picture(client):
    r = client.get("/api/shape3d?pressure_kpa=200", headers=AUTH).json()
    assert r["svg"].startswith("<svg") and 'class="mesh"' in r["svg"] and "3D shape at 200 kPa" in r["svg"]


# ------------------------------------------------------------------ the command
def test_the_core_loads_no_web_framework():
    code = ("import sys, embroact.export.cli.main as m\n"
            "try:\n    m.main(['--help'])\nexcept SystemExit:\n    pass\n"
            "print(sorted(k for k in sys.modules if k.split('.')[0] in ('starlette', 'uvicorn', 'httpx', 'anyio')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip().splitlines()[-1] == "[]"
    out = subprocess.run([sys.executable, "-m", "embroact.export", "studio", "--help"], capture_output=True, text=True)
    assert out.returncode == 0 and "--no-browser" in out.stdout


def test_studio_options_are_checked_first(tmp_path, capsys):
    assert main(["studio", "--out", str(tmp_path / "missing"), "--no-browser"]) == 3
    assert "does not exist" in capsys.readouterr().err
    assert main(["studio", "--out", str(tmp_path), "--port", "70000", "--no-browser"]) == 2
    assert capsys.readouterr().err.strip() == "embroact: error: port must be an integer in [0, 65535], got 70000"


def test_a_design_that_cannot_be_sewn_is_refused_at_its_field(client):
    from embroact.patterns.base.errors import EmbroactError
    from embroact.patterns.design import build_plan

    with pytest.raises(EmbroactError) as exc:
        build_plan(design_from_dict(paper_dict(width_mm=3.0)))
    body = edit(client, {"actuator[0].width_mm": 3}).json()
    assert (body["applied"], body["key"], body["error"]) == (False, "actuator[0].width_mm", str(exc.value))


def test_a_true_false_setting_is_a_choice(client):
    v = edit(client, {"machine.placement_line": "true"}).json()
    field = next(f for f in v["fields"] if f["key"] == "machine.placement_line")
    assert (field["kind"], field["value"]) == ("bool", True)
    body = edit(client, {"machine.placement_line": "maybe"}).json()
    d = paper_dict()
    d["machine"] = {"placement_line": "maybe"}
    assert (body["key"], body["error"]) == ("machine.placement_line", design_file_message(d))


def test_the_command_prints_its_address_serves_it_and_stops_on_ctrl_c(tmp_path):
    import signal

    import httpx2

    proc = subprocess.Popen([sys.executable, "-m", "embroact.export", "studio", "--out", str(tmp_path),
                             "--no-browser"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        head, url = proc.stdout.readline().strip().split(": ", 1)
        assert head == "embroact studio" and url.startswith("http://127.0.0.1:") and "/?token=" in url
        base, token = url.split("/?token=")
        assert len(token) >= 32
        assert httpx2.get(url).status_code == 200
        assert httpx2.get(f"{base}/api/views").status_code == 403
        assert httpx2.get(f"{base}/api/views", headers={"X-Embroact-Token": token}).json()["design"] == "paper-zigzag"
    finally:
        proc.send_signal(signal.SIGINT)
        code = proc.wait(20)
    # the default design's calibration is the demonstration set: one note line, then the interruption
    err = proc.stderr.read().strip().splitlines()
    assert code == 130 and err[-1] == "embroact: interrupted"
    assert len(err) == 2 and "demonstration data" in err[0]


def test_a_segmented_actuator_shows_each_segments_bend(out_dir):
    import xml.etree.ElementTree as ET

    def seg_dict(w1):
        return {"name": "seg", "actuator": [{"name": "S", "segment": [
            {"pattern": "zigzag", "width_mm": 8.0, "interval_mm": 1.0, "length_mm": 40.0},
            {"pattern": "zigzag", "width_mm": w1, "interval_mm": 1.0, "length_mm": 50.0}]}]}

    client = TestClient(create_app(Studio(design_from_dict(seg_dict(6.0)), out_dir), token=TOKEN, port=PORT),
                        base_url=BASE)
    v = edit(client, {"actuator[0].segment[1].width_mm": 7.0}, 200)
    v = v.json()
    per = analyse(design_from_dict(seg_dict(7.0))).segment_curves([200.0])[0]
    expected = [float(c.theta_deg[0]) for c in per]
    act = v["actuators"][0]
    assert act["segment_theta_deg"] == pytest.approx(expected, rel=1e-12)
    assert act["theta_deg"] == pytest.approx(sum(expected), rel=1e-12)
    chart = ET.fromstring(v["chart_svg"])
    series = {e.get("data-series") for e in chart.iter("{http://www.w3.org/2000/svg}polyline")
              if e.get("class") == "curve"}
    assert series == {"0", "1", "2"}  # the build's chart: the whole strip, then one curve per segment
    assert "S whole strip" in v["chart_svg"] and "segment 1" in v["chart_svg"] and v["side_svg"].startswith("<svg")
    assert len(chart.findall(".//{http://www.w3.org/2000/svg}circle[@class='pressure-dot']")) == 3
    assert act["status"] == "BENDING"


HOSTILE = ["nan", "inf", "-inf", "1e999", "abc", "", "  ", "0x10", "\x00", "7" * 400, -1e308]


def test_hostile_values_in_every_field_are_one_line_answers(client):
    fields = client.get("/api/views", headers=AUTH).json()["fields"]
    before = client.get("/api/views", headers=AUTH).json()
    for f in fields:
        for value in HOSTILE:
            r = edit(client, {f["key"]: value})
            assert r.status_code in (200, 400), (f["key"], value, r.text)
            body = r.json()
            if body.get("applied") is False or r.status_code == 400:
                assert "\n" not in body["error"] and body["error"], (f["key"], value)
            else:  # accepted (a name, an empty optional value): put the design back
                edit(client, {f["key"]: f["value"] if f["value"] is not None else ""})
    assert client.get("/api/views", headers=AUTH).json() == before


def test_the_browser_is_given_a_private_launcher_page_not_the_token(tmp_path, monkeypatch):
    import stat
    import types
    import webbrowser

    from embroact.export.studio import serve

    opened = []
    monkeypatch.setattr(webbrowser, "open", opened.append)
    url = "http://127.0.0.1:4321/?token=SECRET-token"
    page = serve.launcher_page(url, tmp_path)
    assert stat.S_IMODE(page.stat().st_mode) == 0o600
    assert f'http-equiv="refresh" content="0;url={url}"' in page.read_text()
    serve._open_browser(types.SimpleNamespace(started=True, should_exit=False), page)
    assert opened == [page.as_uri()] and "SECRET" not in opened[0]


def test_a_target_shape_is_proposed_then_applied(client):
    r = client.post("/api/apply-proposal", json={}, headers=AUTH)
    assert r.status_code == 400 and r.json()["error"].startswith("no inverse-design proposal")
    bad = client.post("/api/inverse-shape", json={"path_d": "M 0 0 Q", "pressure_kpa": 150}, headers=AUTH)
    assert bad.status_code == 400 and "\n" not in bad.json()["error"]
    # a quarter circle 100 mm long from the clamp, bending toward the back of the fabric (up in SVG)
    arc = "M 0 0 A 63.662 63.662 0 0 0 63.662 -63.662"
    res = client.post("/api/inverse-shape", json={"path_d": arc, "pressure_kpa": 150}, headers=AUTH).json()
    assert res["reached"] is True and res["rmse_mm"] < 0.5  # sewable widths step by 0.2 mm: two segments mix them
    unchanged = client.get("/api/views?pressure_kpa=150", headers=AUTH).json()
    assert unchanged["actuators"][0]["derived"]["width_mm"] == 7.0  # a proposal changes nothing yet
    v = client.post("/api/apply-proposal", json={"pressure_kpa": 150}, headers=AUTH).json()
    widths = [s["derived"]["requested_width_mm"] for s in v["actuators"][0]["segments"]]
    assert widths == pytest.approx([s["params"]["width_mm"] for s in res["segments"]])
    whole = v["actuators"][0]["derived"]["requested_width_mm"]  # the whole strip's: common to its segments, or null
    assert whole == (widths[0] if len(set(widths)) == 1 else None)
    # the applied design bends as proposed (its segments' bends added)
    theta = sum(s["theta_deg"] for s in res["segments"])
    assert v["actuators"][0]["theta_deg"] == pytest.approx(theta, abs=1e-6)
    again = client.post("/api/apply-proposal", json={}, headers=AUTH)
    assert again.status_code == 400


def test_the_slider_marks_the_pressure_where_a_widened_chart_draws_it(out_dir):
    """The hook's long segment legends sit below the build's chart: the slider's dots sit on its curves."""
    import xml.etree.ElementTree as ET
    from pathlib import Path

    design = load_design(Path(__file__).resolve().parents[1] / "examples" / "designed_hook.toml")
    chart = ET.fromstring(Studio(design, out_dir).views(200.0)["chart_svg"])
    ns = "{http://www.w3.org/2000/svg}"
    assert float(chart.get("width")) == 720.0  # the legend below the plot: the plot keeps the chart's width
    vertices = [tuple(map(float, p.split(","))) for e in chart.iter(ns + "polyline") if e.get("class") == "curve"
                for p in e.get("points").split()]
    dots = chart.findall(f".//{ns}circle[@class='pressure-dot']")
    segments = len(design.actuators[0].segments)
    assert segments >= 2 and len(dots) == 1 + segments  # the whole strip and each segment, a vertex at 200 kPa
    for dot in dots:
        x, y = float(dot.get("cx")), float(dot.get("cy"))
        assert min(abs(vx - x) + abs(vy - y) for vx, vy in vertices) < 0.02


@pytest.mark.parametrize("example", ["three_actuators.toml", "designed_hook.toml", None])
def test_the_worksheet_panel_shows_the_numbers_build_writes(out_dir, tmp_path, example):
    """The studio's worksheet figures equal worksheet.json of 'embroact build' (its jumps were 0 where build's was 1)."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[1] / "examples"
    design = default_design() if example is None else load_design(root / example)
    panel = Studio(design, out_dir).views(100.0)["worksheet"]
    built = tmp_path / "built"
    built.mkdir()
    argv = ["build", "--out", str(built), "--no-previews", "--force"] + ([] if example is None else [str(root / example)])
    assert main(argv) in (0, 1)
    sheet = json.loads((built / "worksheet.json").read_text())
    for key, value in panel.items():
        if key == "actuators":
            for a, b in zip(value, sheet["actuators"]):
                assert {k: b[k] for k in a} == a
        else:
            assert sheet[key] == value, key
    assert panel["jump_count"] == sheet["jump_count"] and "jump_count" in panel


def test_an_unreachable_shape_is_drawn_over_its_target_but_never_applied(client, monkeypatch):
    # the search's own answer for a quarter circle, marked not reached (a shape the rules let it only approach)
    import dataclasses

    import embroact.predict.inverse as inverse

    real = inverse.design_shape
    monkeypatch.setattr(inverse, "design_shape", lambda *a, **k: dataclasses.replace(real(*a, **k), reached=False))
    arc = "M 0 0 A 63.662 63.662 0 0 0 63.662 -63.662"
    res = client.post("/api/inverse-shape", json={"path_d": arc, "pressure_kpa": 150}, headers=AUTH).json()
    assert res["reached"] is False
    assert res["svg"].startswith("<svg") and 'class="target"' in res["svg"] and 'class="predicted"' in res["svg"]
    r = client.post("/api/apply-proposal", json={}, headers=AUTH)
    assert r.status_code == 400 and r.json()["error"].startswith("no inverse-design proposal")
