"""embroact studio: server work per edit of the default design, and the page's first load.

Measured in one run, medians over ``--repeats`` samples:

* ``edit_ms``: one width edit of the default design through the studio's session
  (validate as the design file is, generate, analyse, design rules, worksheet, stitch
  preview with the findings, bend chart, side view, numbers; every width new, so nothing
  comes from the session's cache). Target < 50 ms.
* ``shape3d_ms``: the 3D picture at the slider's pressure, which the page fetches right
  after the other views (the mesh picture of :mod:`embroact.export.pictures.meshview`).
* ``slider_ms``: a pressure change (views of an analysed design at a new pressure).
* ``http_edit_ms``: the same edit as the page sends it to the running server (``fetch`` in
  Chromium, until the JSON answer is parsed).
* ``baseline_ms``: ``analyse`` + ``check_design`` of the same designs alone, the physics
  and rules any edit needs; ``edit_over_baseline`` is what the studio adds on top.
* ``first_load_ms``: a fresh headless Chromium page from navigation until every view is
  drawn (``body[data-ready]``, 3D included); ``blank_load_ms`` is the style sheet alone from
  the same server in the same browser, the floor. Target < 1000 ms. The page timings run
  ``embroact studio --no-browser`` in its own process, as a user starts it.

Run: ``python benchmarks/studio_bench.py [--repeats 15] [--screenshot docs/img/studio.png]``;
prints one JSON object (needs the studio extra, and /usr/bin/chromium for the page load).
"""
from __future__ import annotations

import argparse
import contextlib
import json
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time

CHROMIUM = "/usr/bin/chromium"
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync"]
TARGET_EDIT_MS, TARGET_LOAD_MS = 50.0, 1000.0


def _ms(fn) -> float:
    t = time.perf_counter()
    fn()
    return (time.perf_counter() - t) * 1000.0


def _median(xs) -> float:
    return float(statistics.median(xs))


def server_work(repeats: int) -> dict:
    """Medians of the session's work per edit, 3D picture, slider move and the baseline [ms].

    The four are sampled in turn, one of each per round, so that a change in the shared
    machine's load moves them together and their ratios stay comparable.
    """
    from embroact.export.studio.session import Studio
    from embroact.patterns.design import default_design, design_from_dict
    from embroact.predict.analysis import analyse
    from embroact.predict.rules import check_design

    studio = Studio(default_design(), tempfile.mkdtemp())
    studio.views(200.0)
    studio.shape3d(200.0)  # warm-up: imports, first meshes
    samples: dict[str, list[float]] = {"edit_ms": [], "shape3d_ms": [], "slider_ms": [], "baseline_ms": []}
    for k in range(repeats):
        w = 6.0 + 0.05 * k  # every edit a new design (nothing from the session's cache)
        d = design_from_dict({"actuator": [{"name": "A1", "pattern": "zigzag", "width_mm": w + 0.01,
                                            "interval_mm": 1.0, "length_mm": 100.0}]})
        samples["baseline_ms"].append(_ms(lambda: check_design(analyse(d))))
        samples["edit_ms"].append(_ms(lambda: studio.edit({"actuator[0].width_mm": w}, 200.0)))
        samples["shape3d_ms"].append(_ms(lambda: studio.shape3d(200.0)))
        samples["slider_ms"].append(_ms(lambda: studio.views(100.0 + 7 * k)))
    return {name: _median(xs) for name, xs in samples.items()}


@contextlib.contextmanager
def studio_command():
    """``embroact studio --out out --no-browser`` in its own process and a new folder (as a user runs
    it); yields its address."""
    work = tempfile.mkdtemp()
    os.mkdir(os.path.join(work, "out"))
    proc = subprocess.Popen([sys.executable, "-m", "embroact.export", "studio", "--out", "out", "--no-browser"],
                            cwd=work, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        line = proc.stdout.readline()
        if not line.startswith("embroact studio: http://"):
            raise RuntimeError(f"embroact studio did not start: {line!r}")
        yield line.split(": ", 1)[1].strip()
    finally:
        proc.send_signal(signal.SIGINT)  # Ctrl-C: the server's own clean shutdown
        proc.wait(10)


_FETCH_EDITS = """async ([token, n]) => {
  const times = [];
  for (let k = 0; k < n; k++) {
    const body = JSON.stringify({values: {"actuator[0].width_mm": 6.02 + 0.05 * k}, pressure_kpa: 200});
    const t = performance.now();
    const r = await fetch("api/edit", {method: "POST", body,
                                       headers: {"X-Embroact-Token": token, "Content-Type": "application/json"}});
    await r.json();
    times.push(performance.now() - t);
  }
  return times;
}"""


def page_timings(repeats: int, screenshot: str | None) -> dict:
    """Median first load of the page and of a blank page, and of an edit fetched by the page [ms]."""
    from playwright.sync_api import sync_playwright

    out: dict = {}
    with studio_command() as url, sync_playwright() as pw:
        base, token = url.split("/?token=")
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=FLAGS, headless=True)
        loads, blanks = [], []
        for _ in range(max(3, repeats // 3)):
            context = browser.new_context(viewport={"width": 1400, "height": 1000})
            page = context.new_page()
            loads.append(_ms(lambda: (page.goto(url), page.wait_for_selector("body[data-ready='1']", timeout=30_000))))
            blanks.append(_ms(lambda: page.goto(f"{base}/static/studio.css?token={token}")))
            context.close()
        out["first_load_ms"], out["blank_load_ms"] = _median(loads), _median(blanks)
        page = browser.new_page(viewport={"width": 1440, "height": 1250})
        page.goto(url)
        page.wait_for_selector("body[data-ready='1']", timeout=30_000)
        out["http_edit_ms"] = _median(page.evaluate(_FETCH_EDITS, [token, repeats]))
        if screenshot:
            page.evaluate("""async ([token]) => { await fetch("api/edit", {method: "POST",
                headers: {"X-Embroact-Token": token}, body: JSON.stringify({values: {"actuator[0].width_mm": 7}})}); }""",
                          [token])
            page.reload()
            page.wait_for_selector("body[data-ready='1']", timeout=30_000)
            page.screenshot(path=screenshot)
        browser.close()
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=15)
    ap.add_argument("--screenshot", help="also save a screenshot of the page (PNG)")
    args = ap.parse_args(argv)
    res = server_work(args.repeats)
    if shutil.which(CHROMIUM) is not None:
        res.update(page_timings(args.repeats, args.screenshot))
    res["edit_over_target"] = res["edit_ms"] / TARGET_EDIT_MS
    res["edit_over_baseline"] = res["edit_ms"] / res["baseline_ms"]
    res["edit_and_3d_over_target"] = (res["edit_ms"] + res["shape3d_ms"]) / TARGET_EDIT_MS
    if res.get("first_load_ms") is not None:
        res["first_load_over_target"] = res["first_load_ms"] / TARGET_LOAD_MS
        res["first_load_over_blank"] = res["first_load_ms"] / res["blank_load_ms"]
    print(json.dumps({k: round(v, 4) if isinstance(v, float) else v for k, v in res.items()}, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
