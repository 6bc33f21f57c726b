"""The studio's web server: a Starlette app over a :class:`~embroact.export.studio.session.Studio`.

Routes (every one needs the run's token, as ``?token=`` or the ``X-Embroact-Token`` header,
and a ``Host`` of ``127.0.0.1:PORT`` or ``localhost:PORT``; anything else is answered 403
before a route runs):

==============================  ============================================================
``GET /``                       the page (``static/index.html``, the token written into it)
``GET /static/NAME``            the page's script and style sheet (package data; no CDN)
``GET /api/views``              fields and views at ``?pressure_kpa=`` (stitches, chart, side
                                view, numbers, findings, worksheet figures)
``GET /api/shape3d``            the 3D picture at ``?pressure_kpa=``
``POST /api/edit``              ``{"values": {key: value}, "pressure_kpa": p}``: the new views, or
                                ``{"applied": false, "error", "key"}`` (the design file's message)
``POST /api/save``              ``{"name": "x.toml"}``: the design file, in the output directory
``POST /api/build``             ``{"force": false}``: ``embroact build`` into the output directory
``POST /api/inverse``           ``{"bend_deg", "pressure_kpa", "pattern", "actuator"}``: a target
                                bend, kept as a proposal (pattern and start)
``POST /api/inverse-shape``     ``{"path_d", "pressure_kpa", "max_segments", "actuator"}``: a
                                target shape, kept as a proposal
``POST /api/apply-proposal``    ``{"pressure_kpa"}``: the proposal in the design; the new views
==============================  ============================================================

Errors are JSON ``{"error": "one line"}``: 400 bad input (also a query that is not UTF-8, a
body nested deeper than ``MAX_JSON_DEPTH``, numbers longer than ``MAX_NUMBER_CHARS``, NaN, lone
surrogates), 403 refused (token, host, a write outside the output directory), 409 design-rule
errors (nothing written) or an inverse search already running, 500 an output that could not be
written, 503 an inverse search that took longer than ``SEARCH_SECONDS`` (30 s; a target-shape
search stops itself at ``SHAPE_SEARCH_S``, 20 s, with the best design found). Inverse searches
run without the session lock, one at a time: the views, edits and saves of the page go on meanwhile. An invalid field is an answer (200, ``applied`` false), not an error.

Examples
--------
>>> import tempfile
>>> from starlette.testclient import TestClient
>>> from embroact.patterns.design import default_design
>>> from embroact.export.studio.session import Studio
>>> app = create_app(Studio(default_design(), tempfile.mkdtemp()), token="t0k", port=8000)
>>> client = TestClient(app, base_url="http://127.0.0.1:8000")
>>> client.get("/api/views").status_code, client.get("/api/views?token=t0k").status_code
(403, 200)
"""
from __future__ import annotations

import asyncio
import json
import math
import secrets
from importlib import resources
from urllib.parse import parse_qs

from starlette.applications import Starlette
from starlette.middleware import Middleware
from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, Response
from starlette.routing import Route

from ...patterns.base.errors import EmbroactError, ExportError, ParameterError
from ...patterns.base.validate import shown
from .form import FieldError
from .outputs import OutsideOutputError
from .session import SEARCH_SECONDS, BusyError

__all__ = ["create_app", "TOKEN_HEADER", "STATIC"]

TOKEN_HEADER = "x-embroact-token"
#: The page's assets: file name -> media type.
STATIC = {"studio.js": "text/javascript; charset=utf-8", "studio.css": "text/css; charset=utf-8"}
#: Largest request body read [bytes].
MAX_BODY_BYTES = 256 * 1024
#: Deepest nesting of a request's JSON (the page sends 3 levels).
MAX_JSON_DEPTH = 16
#: Longest number in a request's JSON [characters] (a double needs 24).
MAX_NUMBER_CHARS = 40
_SECURITY_HEADERS = [(b"cache-control", b"no-store"), (b"x-content-type-options", b"nosniff"),
                     (b"referrer-policy", b"no-referrer"),
                     (b"content-security-policy",
                      b"default-src 'self'; img-src 'self' data:; style-src 'self' 'unsafe-inline'; "
                      b"connect-src 'self'; frame-ancestors 'none'")]


def _asset(name: str) -> str:
    return resources.files(__package__).joinpath("static", name).read_text(encoding="utf-8")


class _Guard:
    """ASGI middleware: the Host must be this server's loopback address and the token must match."""

    def __init__(self, app, *, token: str, port: int) -> None:
        self.app, self.token = app, token.encode("ascii")
        self.hosts = {f"127.0.0.1:{port}".encode(), f"localhost:{port}".encode()}

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        headers = dict(scope.get("headers") or [])
        reason = None
        if headers.get(b"host") not in self.hosts:
            reason = "refused: the Host header must be this studio's address (127.0.0.1 or localhost with its port)"
        else:
            given = headers.get(TOKEN_HEADER.encode()) or _query_token(scope.get("query_string", b""))
            origin = headers.get(b"origin")
            if not secrets.compare_digest(given, self.token):
                reason = "refused: this studio's token is missing or wrong (use the address the studio printed)"
            elif origin is not None and origin.split(b"//", 1)[-1] not in self.hosts:
                reason = "refused: request from another site"
        if reason is not None:
            return await JSONResponse({"error": reason}, status_code=403)(scope, receive, send)

        async def secured(message):
            if message["type"] == "http.response.start":
                message = {**message, "headers": list(message.get("headers", [])) + _SECURITY_HEADERS}
            await send(message)

        return await self.app(scope, receive, secured)


def _query_token(query: bytes) -> bytes:
    """The ``token`` of a query string as bytes, percent-decoded byte for byte (``%FF`` is the byte 0xFF).

    Decoded as Latin-1, every byte stands for itself: nothing undecodable can fail here, and
    a wrong token is then a wrong token (403), whatever bytes it holds.
    """
    values = parse_qs(query.decode("latin-1"), encoding="latin-1", errors="strict").get("token") or [""]
    return values[0].encode("latin-1")


def _error(exc: Exception) -> JSONResponse:
    from ..report.build import DesignRuleError

    if isinstance(exc, FieldError):  # an answer, not a failed request: the page shows it by the field
        return JSONResponse({"applied": False, "error": str(exc), "key": exc.key})
    if isinstance(exc, OutsideOutputError):
        return JSONResponse({"error": str(exc)}, status_code=403)
    if isinstance(exc, BusyError):
        return JSONResponse({"error": str(exc)}, status_code=409)
    if isinstance(exc, DesignRuleError):
        return JSONResponse({"error": str(exc), "findings": [f.as_dict() for f in exc.findings]}, status_code=409)
    if isinstance(exc, ExportError):
        return JSONResponse({"error": str(exc)}, status_code=500)
    return JSONResponse({"error": str(exc)}, status_code=400)


def _finite(value):
    """``value`` with every non-finite float as None (JSON has no NaN or infinity)."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    if hasattr(value, "item") and callable(value.item):  # numpy scalars
        return _finite(value.item())
    return value


def _json_number(text: str) -> float | int:
    """A JSON number of at most :data:`MAX_NUMBER_CHARS` characters (a 309-digit integer is no float)."""
    if len(text) > MAX_NUMBER_CHARS:
        raise ParameterError(f"request body: numbers must have at most {MAX_NUMBER_CHARS} characters, "
                             f"got {len(text)}")
    return float(text) if any(c in text for c in ".eE") else int(text)


def _no_constant(name: str):
    raise ParameterError(f"request body: {name} is no JSON number (numbers must be finite)")


def _checked(value, depth: int = 0):
    """``value`` if it nests at most :data:`MAX_JSON_DEPTH` deep and every string is valid Unicode."""
    if depth > MAX_JSON_DEPTH:
        raise ParameterError(f"request body must nest at most {MAX_JSON_DEPTH} deep")
    if isinstance(value, str):
        try:
            value.encode("utf-8")
        except UnicodeEncodeError:  # "\ud800" in JSON: a lone surrogate, no character
            raise ParameterError(f"request body: strings must be valid Unicode, got a lone surrogate in "
                                 f"{shown(value)}") from None
    elif isinstance(value, dict):
        for k, v in value.items():
            _checked(k, depth + 1)
            _checked(v, depth + 1)
    elif isinstance(value, list):
        for v in value:
            _checked(v, depth + 1)
    return value


def _nesting(raw: bytes) -> int:
    """Deepest bracket nesting of JSON text, counted without parsing (brackets inside strings count too:
    an over-count only refuses a body that is absurd anyway)."""
    depth = deepest = 0
    for byte in raw:
        if byte in b"[{":
            depth += 1
            deepest = max(deepest, depth)
        elif byte in b"]}":
            depth -= 1
    return deepest


async def _body(request: Request) -> dict:
    raw = await request.body()
    if len(raw) > MAX_BODY_BYTES:
        raise EmbroactError(f"request body must be at most {MAX_BODY_BYTES} bytes, got {len(raw)}")
    if _nesting(raw) > MAX_JSON_DEPTH:  # json.loads recurses per level: 1,000 deep is a RecursionError
        raise ParameterError(f"request body must nest at most {MAX_JSON_DEPTH} deep")
    try:
        data = json.loads(raw or b"{}", parse_int=_json_number, parse_float=_json_number,
                          parse_constant=_no_constant)
    except (ValueError, UnicodeDecodeError) as exc:
        if isinstance(exc, EmbroactError):
            raise
        raise EmbroactError("request body must be a JSON object") from None
    if not isinstance(data, dict):
        raise EmbroactError("request body must be a JSON object")
    return _checked(data)


def _query(request: Request) -> dict:
    """The query parameters (the last of each name), each UTF-8 text: ``%FF`` is refused, not replaced."""
    out = {}
    for key, values in parse_qs(request.scope.get("query_string", b"").decode("latin-1"), encoding="latin-1",
                                keep_blank_values=True).items():
        try:
            out[key.encode("latin-1").decode("utf-8")] = values[-1].encode("latin-1").decode("utf-8")
        except UnicodeDecodeError:
            raise ParameterError(f"query parameter {shown(key)} must be UTF-8 text, got {shown(values[-1])}") from None
    return out


def create_app(studio, *, token: str, port: int) -> Starlette:
    """The Starlette app serving ``studio`` to requests that carry ``token`` on ``127.0.0.1:port``.

    Parameters
    ----------
    studio : Studio
        The session the app edits.
    token : str
        The secret every request must carry.
    port : int
        The port it is served on (requests naming another host or port are refused).

    Returns
    -------
    starlette.applications.Starlette

    Examples
    --------
    >>> import tempfile
    >>> from embroact.patterns.design import default_design
    >>> from embroact.export.studio.session import Studio
    >>> out = tempfile.TemporaryDirectory()
    >>> studio = Studio(default_design(), out.name, (), None)
    >>> from starlette.testclient import TestClient
    >>> client = TestClient(create_app(studio, token="abc", port=8000), base_url="http://127.0.0.1:8000")
    >>> client.get("/?token=abc").status_code, client.get("/?token=wrong").status_code
    (200, 403)
    >>> out.cleanup()
    """
    from starlette.concurrency import run_in_threadpool

    page = _asset("index.html")

    def call(fn, seconds: float | None = None):
        """An endpoint running ``fn(request data)`` in a worker thread, errors as JSON; with ``seconds``,
        answered 503 when ``fn`` takes longer (it finishes in the background; nothing is kept from it)."""
        async def endpoint(request: Request) -> Response:
            try:
                data = await _body(request) if request.method == "POST" else _query(request)
                work = run_in_threadpool(fn, data)
                return JSONResponse(_finite(await (work if seconds is None else asyncio.wait_for(work, seconds))))
            except EmbroactError as exc:
                return _error(exc)
            except TimeoutError:  # asyncio.wait_for (Python 3.11: the built-in)
                return JSONResponse({"error": f"the search took longer than {seconds:g} s: try a simpler target or "
                                              "fewer segments"}, status_code=503)
        return endpoint

    async def index(request: Request) -> Response:
        return HTMLResponse(page.replace("__TOKEN__", token))

    async def static(request: Request) -> Response:
        name = request.path_params["name"]
        if name not in STATIC:
            return JSONResponse({"error": f"no such asset {name!r:.60}"}, status_code=404)
        return Response(_asset(name), media_type=STATIC[name])

    routes = [
        Route("/", index),
        Route("/static/{name}", static),
        Route("/api/views", call(lambda d: studio.views(d.get("pressure_kpa")))),
        Route("/api/shape3d", call(lambda d: studio.shape3d(d.get("pressure_kpa")))),
        Route("/api/edit", call(lambda d: studio.edit(d.get("values"), d.get("pressure_kpa"))), methods=["POST"]),
        Route("/api/save", call(lambda d: studio.save(d.get("name"))), methods=["POST"]),
        Route("/api/build", call(lambda d: studio.build(force=d.get("force", False))), methods=["POST"]),
        Route("/api/inverse", call(lambda d: studio.inverse(d.get("bend_deg"), d.get("pressure_kpa"),
                                                            pattern=d.get("pattern", "any"),
                                                            actuator=d.get("actuator", 0)), SEARCH_SECONDS),
              methods=["POST"]),
        Route("/api/inverse-shape", call(lambda d: studio.inverse_shape(d.get("path_d"), d.get("pressure_kpa"),
                                                                        max_segments=d.get("max_segments", 6),
                                                                        actuator=d.get("actuator", 0)),
                   SEARCH_SECONDS), methods=["POST"]),
        Route("/api/apply-proposal", call(lambda d: studio.apply_proposal(d.get("pressure_kpa"))), methods=["POST"]),
    ]
    return Starlette(routes=routes, middleware=[Middleware(_Guard, token=token, port=port)])
