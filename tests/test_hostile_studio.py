"""Generated hostile requests to every studio route, through Starlette's test client.

Every case must be answered (no exception escapes the app, no 500) with a 4xx JSON
``{"error": "one line"}`` where the request is bad, and leave the session usable: a later
views request answers 200. Classes: undecodable query strings (``?token=%FF`` before the
token is checked, and in parameters after it), JSON nested 1,000 deep, 309-digit and
4,301-digit numbers, NaN and Infinity, lone surrogates in every string, save names over
255 bytes; inverse searches run without the session lock and under ``SEARCH_SECONDS``.
"""
import threading
import time

import pytest

pytest.importorskip("starlette")
pytest.importorskip("httpx2")

from starlette.testclient import TestClient  # noqa: E402

from embroact.export.studio import app as studio_app  # noqa: E402
from embroact.export.studio.session import Studio  # noqa: E402
from embroact.patterns.design import default_design  # noqa: E402

TOKEN = "test-token-123"
PORT = 8123
AUTH = {"X-Embroact-Token": TOKEN}
GET_ROUTES = ["/", "/static/studio.js", "/static/studio.css", "/api/views", "/api/shape3d"]
POST_ROUTES = ["/api/edit", "/api/save", "/api/build", "/api/inverse", "/api/inverse-shape", "/api/apply-proposal"]
#: Query bytes no UTF-8 decoder accepts, and Latin-1 look-alikes of the token.
BAD_QUERY = ["%FF", "%FF%FE", "%C3", "%ED%A0%80", "%00", "%C0%AF", "t%FFest", "%" , "%G0", TOKEN + "%FF"]


def _client(out_dir, **kwargs) -> TestClient:
    app = studio_app.create_app(Studio(default_design(), out_dir), token=TOKEN, port=PORT, **kwargs)
    return TestClient(app, base_url=f"http://127.0.0.1:{PORT}", raise_server_exceptions=False)


def _one_line_error(r, status: int) -> str:
    assert r.status_code == status, (r.status_code, r.text[:300])
    error = r.json()["error"]
    assert "\n" not in error and "Traceback" not in error and len(error) < 400, error
    return error


@pytest.fixture
def client(tmp_path):
    return _client(tmp_path)


def test_undecodable_tokens_are_refused_on_every_route(client):
    """``?token=%FF`` gave 500 with a traceback on all 11 routes, before the token was checked: now 403."""
    n = 0
    for route in GET_ROUTES + POST_ROUTES:
        for q in BAD_QUERY:
            method = client.get if route in GET_ROUTES else client.post
            r = method(f"{route}?token={q}")
            assert _one_line_error(r, 403).startswith("refused: this studio's token"), (route, q)
            n += 1
    assert n == 110
    assert client.get("/api/views", headers=AUTH).status_code == 200


def test_undecodable_parameters_after_the_token_are_400(client):
    for route in ("/api/views", "/api/shape3d"):
        for q in BAD_QUERY[:5]:
            r = client.get(f"{route}?token={TOKEN}&pressure_kpa={q}")
            error = _one_line_error(r, 400)
            assert error.startswith("query parameter 'pressure_kpa' must be UTF-8 text, got ") or \
                error.startswith("pressure_kpa must be"), (route, q, error)
    assert client.get(f"/api/views?token={TOKEN}&pressure_kpa=100").status_code == 200


#: (body text, the error it must give) for every POST route.
BAD_BODIES = {
    "arrays-1000": ("[" * 1000 + "]" * 1000, "request body must nest at most 16 deep"),
    "objects-1000": ('{"a":' * 1000 + "1" + "}" * 1000, "request body must nest at most 16 deep"),
    "values-17": ('{"values": ' + "[" * 16 + "]" * 16 + "}", "request body must nest at most 16 deep"),
    "int-309": ('{"values": {"actuator[0].width_mm": ' + "9" * 309 + '}, "pressure_kpa": 1, "bend_deg": 1}',
                "request body: numbers must have at most 40 characters, got 309"),
    "int-4301": ('{"pressure_kpa": ' + "1" * 4301 + "}", "request body: numbers must have at most 40 characters, "
                 "got 4301"),
    "float-400": ('{"pressure_kpa": 1.' + "0" * 400 + "}", "request body: numbers must have at most 40 characters, "
                  "got 402"),
    "nan": ('{"pressure_kpa": NaN}', "request body: NaN is no JSON number (numbers must be finite)"),
    "infinity": ('{"bend_deg": -Infinity}', "request body: -Infinity is no JSON number (numbers must be finite)"),
    "surrogate-value": ('{"values": {"actuator[0].model.calibration": "\\ud800"}, "name": "\\udfff.toml"}',
                        "request body: strings must be valid Unicode, got a lone surrogate in '\\ud800'"),
    "surrogate-key": ('{"\\ud83d": 1}', "request body: strings must be valid Unicode, got a lone surrogate in "
                      "'\\ud83d'"),
    "surrogate-name": ('{"name": "a\\udcff.toml", "path_d": "M 0 0 \\ud800"}', None),
    "not-utf8": (b'{"name": "\xff.toml"}', "request body must be a JSON object"),
}


def test_hostile_bodies_on_every_post_route(client, tmp_path):
    """JSON 1,000 deep and 309-digit integers gave 500; a lone surrogate in the calibration field made every
    later views and save request 500 until edited. Each is now one 400 line, and the session stays usable."""
    for route in POST_ROUTES:
        for bid, (body, message) in BAD_BODIES.items():
            r = client.post(route, content=body if isinstance(body, bytes) else body.encode(), headers=AUTH)
            error = _one_line_error(r, 400)
            if message is not None:
                assert error == message, (route, bid, error)
            else:
                assert "lone surrogate" in error, (route, bid, error)
            assert client.get("/api/views", headers=AUTH).status_code == 200, (route, bid)
    assert client.post("/api/save", json={"name": "after.toml"}, headers=AUTH).status_code == 200
    assert sorted(p.name for p in tmp_path.iterdir()) == ["after.toml"]


@pytest.mark.parametrize("name, status", [
    ("a" * 115 + ".toml", 200), ("\u00e9" * 115 + ".toml", 200),                # 120 characters, 235 bytes
    ("\U0001F600" * 62 + ".toml", 200),                                        # 253 bytes
    ("\U0001F600" * 63 + ".toml", 400), ("\U0001F600" * 100 + ".toml", 400),   # 257 and 405 bytes
    ("\u4e2d" * 84 + ".toml", 400),                                            # 257 bytes
])
def test_save_names_are_bounded_in_bytes(client, tmp_path, name, status):
    """A name over 255 bytes gave 500 (ENAMETOOLONG); one that fits is written, its staged copy fitting too."""
    r = client.post("/api/save", json={"name": name}, headers=AUTH)
    size = len(name.encode())
    if status == 400:
        assert _one_line_error(r, 400) == f"name must be at most 255 bytes in UTF-8, got {size}"
        assert list(tmp_path.iterdir()) == []
    else:
        assert r.status_code == 200, r.text
        assert [p.name for p in tmp_path.iterdir()] == [name]


def test_an_inverse_search_holds_no_lock_and_has_a_time_limit(tmp_path, monkeypatch):
    """inverse-shape held the session lock 41.6 s, blocking a views request 40.6 s: views now answer while a
    search runs, a second search is refused (409), and the request is answered 503 at SEARCH_SECONDS."""
    import embroact.predict.inverse as inverse

    release, started = threading.Event(), threading.Event()
    real = inverse.design_shape

    def slow(*args, **kwargs):
        started.set()
        release.wait(10)
        return real(*args, **kwargs)

    monkeypatch.setattr(inverse, "design_shape", slow)
    monkeypatch.setattr(studio_app, "SEARCH_SECONDS", 1.0)
    client = _client(tmp_path)
    body = {"path_d": "M 0 0 A 60 60 0 0 0 60 -60", "pressure_kpa": 200, "max_segments": 2}
    answers = {}
    search = threading.Thread(target=lambda: answers.setdefault(
        "first", client.post("/api/inverse-shape", json=body, headers=AUTH)))
    search.start()
    assert started.wait(10)
    t = time.perf_counter()
    assert client.get("/api/views", headers=AUTH).status_code == 200
    assert time.perf_counter() - t < 5.0  # the analysis of the default design, not the search
    second = client.post("/api/inverse-shape", json=body, headers=AUTH)
    assert _one_line_error(second, 409).startswith("an inverse search is still running")
    search.join(10)
    assert _one_line_error(answers["first"], 503) == ("the search took longer than 1 s: try a simpler target or "
                                                      "fewer segments")
    release.set()
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:  # the abandoned search ends; then a search is accepted again
        r = client.post("/api/inverse-shape", json=body, headers=AUTH)
        if r.status_code != 409:
            break
        time.sleep(0.1)
    assert r.status_code in (200, 503), r.text


def test_the_studio_serves_past_the_time_limit_and_stops_on_sigterm(tmp_path):
    """A server runs until stopped: ``--time-limit-s`` does not end it, SIGTERM does (143, one line)."""
    import os
    import signal
    import subprocess
    import sys

    import httpx2

    proc = subprocess.Popen([sys.executable, "-m", "embroact.export", "--time-limit-s", "1", "studio", "--out",
                             str(tmp_path), "--no-browser"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})
    try:
        url = proc.stdout.readline().strip().split(": ", 1)[1]
        time.sleep(2.0)
        assert proc.poll() is None
        assert httpx2.get(url.replace("/?token=", "/api/views?token=")).status_code == 200
    finally:
        proc.send_signal(signal.SIGTERM)
        code = proc.wait(20)
    err = proc.stderr.read()
    assert code == 143 and ("\n" + err).endswith("\nembroact: terminated\n"), (code, err)
    assert "Traceback" not in err
    assert list(tmp_path.iterdir()) == []
