"""embroact studio driven in a real headless Chromium (Debian's chromium, through Playwright).

The page loads the default design; changing the width and the pressure must show the
stitch preview, the chart and the predicted angle the API gives for those parameters
(and ``analyse`` of an independently written design); an invalid width shows the design
file's message and keeps the last good views; saving writes a design file ``embroact
build`` accepts; the page logs no console errors. Playwright never downloads a browser
here: it drives /usr/bin/chromium.
"""
import shutil
import xml.etree.ElementTree as ET

import pytest

sync_api = pytest.importorskip("playwright.sync_api", reason="playwright is not installed (pip install '.[test]')")
pytest.importorskip("uvicorn")
CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
if shutil.which(CHROMIUM) is None:
    pytest.skip("no headless Chromium at /usr/bin/chromium (apt-get install chromium)", allow_module_level=True)

import httpx2  # noqa: E402

from embroact.export.cli.main import main  # noqa: E402
from embroact.export.studio.serve import background  # noqa: E402
from embroact.export.studio.session import Studio  # noqa: E402
from embroact.patterns.base.errors import DesignFileError  # noqa: E402
from embroact.patterns.design import default_design, design_from_dict  # noqa: E402
from embroact.predict.analysis import analyse  # noqa: E402

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync"]
SVG = "{http://www.w3.org/2000/svg}"


def paper_dict(**actuator):
    return {"name": "paper-zigzag", "actuator": [{"name": "A1", "pattern": "zigzag", "width_mm": 7.0,
                                                  "interval_mm": 1.0, "length_mm": 100.0, **actuator}]}


def curve_points(svg_text: str) -> list[str]:
    """The ``points`` of the chart's curves, read with ElementTree (not the code that drew them)."""
    root = ET.fromstring(svg_text)
    return [e.get("points") for e in root.iter(f"{SVG}polyline") if e.get("class") == "curve"]


def marker_dot(svg_text: str) -> tuple[float, float]:
    root = ET.fromstring(svg_text)
    dot = next(e for e in root.iter(f"{SVG}circle") if e.get("class") == "pressure-dot")
    return float(dot.get("cx")), float(dot.get("cy"))


@pytest.fixture(scope="module")
def studio_page(tmp_path_factory):
    out = tmp_path_factory.mktemp("studio-out")
    with background(Studio(default_design(), out)) as url, sync_api.sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=FLAGS, headless=True)
        page = browser.new_page(viewport={"width": 1400, "height": 1000})
        problems = []
        page.on("console", lambda m: problems.append(f"{m.type}: {m.text}") if m.type in ("error", "warning")
                else None)
        page.on("pageerror", lambda e: problems.append(f"page error: {e}"))
        page.goto(url)
        page.wait_for_selector("body[data-ready='1']", timeout=30_000)
        yield page, url, out, problems
        browser.close()


def wait_for_update(page, before: str) -> None:
    page.wait_for_function("v => document.body.dataset.version !== v", arg=before, timeout=30_000)


def api_views(url: str, pressure_kpa: float) -> dict:
    base, token = url.split("/?token=")
    return httpx2.get(f"{base}/api/views", params={"pressure_kpa": pressure_kpa, "token": token}).json()


def test_the_page_follows_width_and_pressure_edits(studio_page):
    page, url, out, problems = studio_page
    start = {k: page.inner_html(f"#{k}") for k in ("stitches", "chart")}
    start_angle = page.inner_text("#angle-0")
    assert float(start_angle) == pytest.approx(float(analyse(default_design()).curves([200.0])[0].theta_deg[0]),
                                               abs=0.005)
    version = page.get_attribute("body", "data-version")
    page.fill("#f-actuator-0--width_mm", "8.5")
    page.press("#f-actuator-0--width_mm", "Enter")
    wait_for_update(page, version)
    version = page.get_attribute("body", "data-version")
    page.eval_on_selector("#pressure", "el => { el.value = '180'; el.dispatchEvent(new Event('input')); }")
    wait_for_update(page, version)
    assert page.inner_text("#pressure-value") == "180"

    api = api_views(url, 180.0)
    expected = float(analyse(design_from_dict(paper_dict(width_mm=8.5))).curves([180.0])[0].theta_deg[0])
    assert api["actuators"][0]["theta_deg"] == pytest.approx(expected, rel=1e-12)
    assert page.inner_text("#angle-0") == f"{api['actuators'][0]['theta_deg']:.2f}" != start_angle
    assert page.inner_text("#width-0") == "8.400"  # rails at +-4.25 mm sewn at +-4.2 on the 0.1 mm grid
    # the stitch preview is the API's: same layers and needle points, the new width in its caption
    shown = page.inner_html("#stitches")
    assert shown != start["stitches"]
    svg = ET.fromstring(api["stitches_svg"])
    needles = [c for g in svg.iter(f"{SVG}g") if g.get("id") == "needle-points" for c in g]
    assert page.locator("#stitches g#needle-points > *").count() == len(needles)
    assert "w 8.40 mm" in page.text_content("#stitches g#params")
    # the chart is the API's: same curve points, the marker at 180 kPa
    assert page.inner_html("#chart") != start["chart"]
    dom_points = page.eval_on_selector_all("#chart polyline.curve", "els => els.map(e => e.getAttribute('points'))")
    assert dom_points == curve_points(api["chart_svg"]) and dom_points
    assert page.get_attribute("#chart g#pressure-marker", "data-pressure-kpa") == "180"
    cx, cy = marker_dot(api["chart_svg"])
    assert float(page.get_attribute("#chart circle.pressure-dot", "cy")) == pytest.approx(cy)
    assert page.locator("#shape3d svg polygon").count() > 100
    assert problems == []


def test_an_invalid_width_shows_its_message_and_keeps_the_views(studio_page):
    page, url, out, problems = studio_page
    before = {k: page.inner_html(f"#{k}") for k in ("stitches", "chart", "side", "numbers")}
    page.fill("#f-actuator-0--width_mm", "-1")
    page.press("#f-actuator-0--width_mm", "Enter")
    page.wait_for_function("() => document.getElementById('m-actuator-0--width_mm').textContent !== ''",
                           timeout=30_000)
    with pytest.raises(DesignFileError) as exc:
        design_from_dict(paper_dict(width_mm=-1))
    assert page.inner_text("#m-actuator-0--width_mm") == str(exc.value)
    assert "invalid" in page.get_attribute("#f-actuator-0--width_mm", "class")
    assert {k: page.inner_html(f"#{k}") for k in before} == before
    assert problems == []


def test_saving_writes_a_design_embroact_build_accepts(studio_page, tmp_path):
    page, url, out, problems = studio_page
    page.fill("#save-name", "from-browser.toml")
    page.click("#save")
    page.wait_for_function("() => document.getElementById('output-result').textContent.startsWith('saved')",
                           timeout=30_000)
    saved = out / "from-browser.toml"
    assert saved.exists()
    assert main(["build", str(saved), "--out", str(tmp_path), "--no-previews"]) == 0
    assert (tmp_path / "paper-zigzag.dst").exists()
    page.fill("#save-name", "../outside.toml")
    page.click("#save")
    page.wait_for_function("() => document.getElementById('output-result').classList.contains('error')",
                           timeout=30_000)
    assert not (out.parent / "outside.toml").exists()
    # a refused save is a 403 answer; the browser reports that resource status, nothing else went wrong
    assert [p for p in problems if "status of 403" not in p] == []


def test_findings_are_marked_on_the_preview_and_inverse_design_applies(studio_page):
    page, url, out, problems = studio_page
    version = page.get_attribute("body", "data-version")
    page.fill("#f-actuator-0--interval_mm", "0.4")
    page.press("#f-actuator-0--interval_mm", "Enter")
    wait_for_update(page, version)
    placed = page.locator("#stitches circle.finding")
    assert placed.count() > 0  # EA105: needle points dense, each circled where it is
    k = placed.first.get_attribute("data-finding")
    page.click(f"#finding-list li[data-finding='{k}']")
    assert "active" in placed.first.get_attribute("class")
    assert page.inner_text(f"#finding-list li[data-finding='{k}']").startswith("EA105")
    # inverse design: 84.5 deg at 150 kPa with a zigzag (the sewable 6.2 mm bends 84.53), applied as its proposal
    page.fill("#inv-bend", "84.5")
    page.fill("#inv-pressure", "150")
    page.select_option("#inv-pattern", "zigzag")
    page.click("#inv-run")
    page.wait_for_selector("#inv-apply:not([hidden])", timeout=60_000)
    text = page.inner_text("#inv-result")
    assert text.startswith("met: zigzag bends 84.53 deg at 150 kPa")
    assert "one machine-grid step (sewn again, G, P0 and geometry following): width_mm -0.100 mm: 5.68 deg" in text
    version = page.get_attribute("body", "data-version")
    page.click("#inv-apply")
    wait_for_update(page, version)
    from embroact.predict.inverse import design_bend

    width = design_bend(84.5, 150.0, pattern="zigzag").best.params.width_mm
    # the field shows 6 significant digits; the design keeps every digit (the saved file reads back the width)
    assert page.input_value("#f-actuator-0--width_mm") == repr(float(f"{width:.6g}"))
    assert page.input_value("#f-actuator-0--interval_mm") == "1"
    page.fill("#save-name", "applied.toml")
    page.click("#save")
    page.wait_for_function("() => document.getElementById('output-result').textContent.startsWith('saved')",
                           timeout=30_000)
    from embroact.export.files.designfile import load_design

    assert load_design(out / "applied.toml").actuators[0].params.width_mm == pytest.approx(width, rel=1e-15)
    assert [p for p in problems if "status of 403" not in p] == []


def test_the_launcher_page_forwards_to_the_studio(studio_page, tmp_path):
    from embroact.export.studio.serve import launcher_page

    page, url, out, problems = studio_page
    page.goto(launcher_page(url, tmp_path).as_uri())
    page.wait_for_url(url, timeout=30_000)
    page.wait_for_selector("body[data-ready='1']", timeout=30_000)
    assert page.inner_text("#design-name") == "paper-zigzag"


def test_the_target_shape_panel_replaces_the_actuator(studio_page):
    page, url, out, problems = studio_page
    page.fill("#shape-d", "M 0 0 A 63.662 63.662 0 0 0 63.662 -63.662")
    page.fill("#shape-pressure", "150")
    page.click("#shape-run")
    page.wait_for_selector("#shape-apply:not([hidden])", timeout=60_000)
    assert page.inner_text("#shape-result").startswith("met with ")  # one 6.1 mm zigzag on y = 0.05 mm
    version = page.get_attribute("body", "data-version")
    page.click("#shape-apply")
    wait_for_update(page, version)
    from embroact.predict.inverse import design_shape
    from embroact.patterns.centerline import Centerline

    target = Centerline.from_svg_path("M 0 0 A 63.662 63.662 0 0 0 63.662 -63.662").points_mm
    proposed = design_shape(target, 150.0).design.actuators[0]
    segmented = len(proposed.segments) > 1  # a chain of one is edited as the actuator's own pattern
    width = (proposed.segments[0].params if segmented else proposed.params).width_mm
    assert float(page.input_value("#f-actuator-0--segment-0--width_mm" if segmented
                                  else "#f-actuator-0--width_mm")) == pytest.approx(width, rel=1e-12)
    assert [p for p in problems if "status of 403" not in p] == []


def test_a_segmented_actuator_shows_each_segments_numbers(studio_page, tmp_path):
    """The designed hook (three segments): the panel gives the whole strip's bend and, per segment, its bend,
    realised width and P0, as the analysis gives them (a page of its own in the module's browser)."""
    from embroact.export.files.designfile import load_design

    design = load_design("examples/designed_hook.toml")
    with background(Studio(design, tmp_path)) as url:
        page = studio_page[0].context.browser.new_page(viewport={"width": 1400, "height": 1000})
        page.goto(url)
        page.wait_for_selector("body[data-ready='1']", timeout=30_000)
        api = api_views(url, float(page.input_value("#pressure")))
        a = api["actuators"][0]
        assert page.inner_text("#angle-0") == f"{a['theta_deg']:.2f}"
        for k, seg in enumerate(analyse(design).actuators[0].segments):
            assert page.inner_text(f"#width-0-{k}") == f"{seg.derived.width_mm:.3f}"
            assert page.inner_text(f"#p0-0-{k}") == f"{seg.choice.model.p0_kpa:.2f}"
            assert page.inner_text(f"#angle-0-{k}") == f"{a['segment_theta_deg'][k]:.2f}"
        assert page.query_selector("#width-0") is None  # no whole-actuator geometry: it has none
        page.close()


def test_the_views_keep_their_size_across_edits_and_no_field_name_is_clipped(studio_page):
    """Fixed layout: the page and each view box keep their size whatever the views draw (a coil, a tall 3D shape)."""
    page, url, out, problems = studio_page
    boxes = "#stitches, #chart, #side, #shape3d, #numbers"

    def sizes():  # each view's place and size on the page (what follows them, findings and worksheet, may grow)
        page.wait_for_selector("#shape3d svg", timeout=60_000)
        return page.evaluate("sel => [...document.querySelectorAll(sel)].map(e => e.getBoundingClientRect())"
                             ".map(r => [r.left, r.top + window.scrollY, r.width, r.height])", boxes)

    before = sizes()
    # the module's page may hold a segmented actuator by now (the target-shape test applies its answer)
    if page.query_selector("#f-actuator-0--segment-0--width_mm"):
        edits = ({"actuator[0].segment[0].width_mm": "4"}, {"actuator[0].segment[1].width_mm": "9"})
    else:
        edits = ({"actuator[0].width_mm": "4"}, {"actuator[0].length_mm": "160"})
    for values in edits:
        version = page.get_attribute("body", "data-version")
        key, value = next(iter(values.items()))
        field = "#f-" + key.replace("[", "-").replace("].", "--")
        page.fill(field, value)
        page.press(field, "Enter")
        wait_for_update(page, version)
        assert sizes() == before, values
    clipped = page.evaluate("[...document.querySelectorAll('.field span.key')]"
                            ".filter(e => e.scrollWidth > e.clientWidth + 1).map(e => e.textContent)")
    assert clipped == []
