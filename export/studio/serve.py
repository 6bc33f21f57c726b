"""Run the studio: listen on 127.0.0.1, print the address with the run's token, open a browser.

The socket is bound before the server starts, so ``port=0`` (any free port) is known when
the address is printed and the Host check is set up. uvicorn serves the app; Ctrl-C stops
it cleanly.

Examples
--------
>>> studio_url(8765, "abc")
'http://127.0.0.1:8765/?token=abc'
"""
from __future__ import annotations

import contextlib
import secrets
import socket
import sys
import threading
import time

from ...patterns.base.errors import ParameterError

__all__ = ["studio_url", "listen", "serve", "background", "HOST"]

HOST = "127.0.0.1"


def studio_url(port: int, token: str) -> str:
    """The address the studio prints (and opens)."""
    return f"http://{HOST}:{port}/?token={token}"


def listen(port: int) -> socket.socket:
    """A socket bound to ``127.0.0.1:port`` (0: a free port); a one-line error if it cannot be."""
    if isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535:
        raise ParameterError(f"port must be an integer in [0, 65535], got {port!r}")
    # proto IPPROTO_TCP: asyncio then sets TCP_NODELAY on each connection (with proto 0 it does not,
    # and a response written in two parts waits ~40 ms for the browser's delayed ACK)
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM, socket.IPPROTO_TCP)
    try:
        sock.bind((HOST, port))
    except OSError as exc:
        sock.close()
        raise ParameterError(f"port {port}: cannot listen on {HOST}:{port}: {exc.strerror or exc}") from None
    sock.listen(64)
    return sock


def _open_browser(server, url: str) -> None:
    import webbrowser

    while not server.started and not server.should_exit:
        time.sleep(0.05)
    if server.started:
        webbrowser.open(url)


def _server(studio, port: int):
    """(uvicorn server, bound socket, address) for ``studio`` on ``127.0.0.1:port``, with a new token."""
    import uvicorn

    from .app import create_app

    sock = listen(port)
    port = sock.getsockname()[1]
    token = secrets.token_urlsafe(24)
    config = uvicorn.Config(create_app(studio, token=token, port=port), log_level="warning", lifespan="off",
                            access_log=False)
    return uvicorn.Server(config), sock, studio_url(port, token)


def serve(studio, *, port: int = 0, browser: bool = True, stream=None) -> int:
    """Serve ``studio`` until interrupted; print its address first. Returns 0."""
    server, sock, url = _server(studio, port)
    stream = sys.stdout if stream is None else stream
    print(f"embroact studio: {url}\nwrites into {studio.out_dir}; Ctrl-C stops it", file=stream, flush=True)
    if browser:
        threading.Thread(target=_open_browser, args=(server, url), daemon=True).start()
    try:
        server.run(sockets=[sock])
    finally:
        sock.close()
    return 0


@contextlib.contextmanager
def background(studio, *, port: int = 0, timeout_s: float = 20.0):
    """Serve ``studio`` from a thread while the block runs (tests, benchmarks, screenshots); yields the address."""
    server, sock, url = _server(studio, port)
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    deadline = time.monotonic() + timeout_s
    while not server.started:
        if not thread.is_alive() or time.monotonic() > deadline:
            raise RuntimeError("the studio server did not start")
        time.sleep(0.02)
    try:
        yield url
    finally:
        server.should_exit = True
        thread.join(timeout_s)
        sock.close()
