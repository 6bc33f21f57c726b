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
                                bend, answered with the field edits that meet it
``POST /api/inverse-shape``     ``{"path_d", "pressure_kpa", "max_segments", "actuator"}``: a
                                target shape, kept as a proposal
``POST /api/apply-proposal``    ``{"pressure_kpa"}``: the proposal in the design; the new views
==============================  ============================================================

Errors are JSON ``{"error": "one line"}``: 400 bad input, 403 refused (token, host, a write
outside the output directory), 409 design-rule errors (nothing written), 500 an output that
could not be written. An invalid field is an answer (200, ``applied`` false), not an error.

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

from ...patterns.base.errors import EmbroactError, ExportError
from .form import FieldError
from .outputs import OutsideOutputError

__all__ = ["create_app", "TOKEN_HEADER", "STATIC"]

TOKEN_HEADER = "x-embroact-token"
#: The page's assets: file name -> media type.
STATIC = {"studio.js": "text/javascript; charset=utf-8", "studio.css": "text/css; charset=utf-8"}
#: Largest request body read [bytes].
MAX_BODY_BYTES = 256 * 1024
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
            given = headers.get(TOKEN_HEADER.encode()) or \
                (parse_qs(scope.get("query_string", b"").decode("latin-1")).get("token") or [""])[0].encode("latin-1")
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


def _error(exc: Exception) -> JSONResponse:
    from ..report.build import DesignRuleError

    if isinstance(exc, FieldError):  # an answer, not a failed request: the page shows it by the field
        return JSONResponse({"applied": False, "error": str(exc), "key": exc.key})
    if isinstance(exc, OutsideOutputError):
        return JSONResponse({"error": str(exc)}, status_code=403)
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


async def _body(request: Request) -> dict:
    raw = await request.body()
    if len(raw) > MAX_BODY_BYTES:
        raise EmbroactError(f"request body must be at most {MAX_BODY_BYTES} bytes, got {len(raw)}")
    try:
        data = json.loads(raw or b"{}")
    except (ValueError, UnicodeDecodeError):
        raise EmbroactError("request body must be a JSON object") from None
    if not isinstance(data, dict):
        raise EmbroactError("request body must be a JSON object")
    return data


def create_app(studio, *, token: str, port: int) -> Starlette:
    """The Starlette app serving ``studio`` to requests that carry ``token`` on ``127.0.0.1:port``."""
    from starlette.concurrency import run_in_threadpool

    page = _asset("index.html")

    def call(fn):
        """An endpoint running ``fn(request data)`` in a worker thread, errors as JSON."""
        async def endpoint(request: Request) -> Response:
            try:
                data = await _body(request) if request.method == "POST" else dict(request.query_params)
                return JSONResponse(_finite(await run_in_threadpool(fn, data)))
            except EmbroactError as exc:
                return _error(exc)
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
                                                            actuator=d.get("actuator", 0))), methods=["POST"]),
        Route("/api/inverse-shape", call(lambda d: studio.inverse_shape(d.get("path_d"), d.get("pressure_kpa"),
                                                                        max_segments=d.get("max_segments", 6),
                                                                        actuator=d.get("actuator", 0))),
              methods=["POST"]),
        Route("/api/apply-proposal", call(lambda d: studio.apply_proposal(d.get("pressure_kpa"))), methods=["POST"]),
    ]
    return Starlette(routes=routes, middleware=[Middleware(_Guard, token=token, port=port)])
