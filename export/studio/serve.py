"""Run the studio: listen on 127.0.0.1, print the address with the run's token, open a browser.

The socket is bound before the server starts, so ``port=0`` (any free port) is known when
the address is printed and the Host check is set up. uvicorn serves the app; Ctrl-C stops
it cleanly. The browser is opened on a private launcher page (:func:`launcher_page`), so
the token never appears on a command line.

Examples
--------
>>> studio_url(8765, "abc")
'http://127.0.0.1:8765/?token=abc'
"""
from __future__ import annotations

import contextlib
import html
import os
import secrets
import shutil
import socket
import sys
import tempfile
import threading
import time
from pathlib import Path

from ...patterns.base.errors import ParameterError
from ...patterns.base.validate import shown

__all__ = ["studio_url", "check_port", "listen", "launcher_page", "serve", "background", "HOST"]

HOST = "127.0.0.1"


def studio_url(port: int, token: str) -> str:
    """The address the studio prints (and opens).

    Parameters
    ----------
    port : int
        The port it listens on.
    token : str
        The secret every request carries.

    Returns
    -------
    str

    Examples
    --------
    >>> studio_url(8765, "abc")
    'http://127.0.0.1:8765/?token=abc'
    """
    return f"http://{HOST}:{port}/?token={token}"


def check_port(port: object) -> int:
    """``port`` if it is an integer in [0, 65535] (0: any free port); checked before anything starts.

    Parameters
    ----------
    port : object
        The port given.

    Returns
    -------
    int

    Examples
    --------
    >>> check_port(8765)
    8765
    >>> check_port(-1)
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.ParameterError: port must be an integer in [0, 65535], got -1
    """
    if isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535:
        raise ParameterError(f"port must be an integer in [0, 65535], got {shown(port)}")
    return port


def listen(port: int) -> socket.socket:
    """A socket bound to ``127.0.0.1:port`` (0: a free port); a one-line error if it cannot be.

    Parameters
    ----------
    port : int
        In [0, 65535].

    Returns
    -------
    socket.socket
        Listening.

    Raises
    ------
    ParameterError
        A bad port, or one that cannot be bound.

    Examples
    --------
    >>> sock = listen(0)
    >>> sock.getsockname()[0], sock.getsockname()[1] > 0
    ('127.0.0.1', True)
    >>> sock.close()
    """
    check_port(port)
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


def launcher_page(url: str, folder: str | os.PathLike) -> Path:
    """A page only its owner can read that forwards the browser to ``url``.

    The browser is started with this file's name, not the address: a command line is visible
    to every user of the machine (``ps``), the token must not be.

    Parameters
    ----------
    url : str
        The studio's address (with its token).
    folder : str or os.PathLike
        Where the page is made (a private temporary folder).

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import os, tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     page = launcher_page("http://127.0.0.1:8765/?token=abc", tmp)
    ...     page.suffix, oct(os.stat(page).st_mode & 0o777), "refresh" in page.read_text()
    ('.html', '0o600', True)
    """
    fd, name = tempfile.mkstemp(prefix="embroact-studio-", suffix=".html", dir=folder)  # mode 0600
    with os.fdopen(fd, "w", encoding="utf-8") as fh:
        fh.write(f'<!DOCTYPE html><meta charset="utf-8"><meta http-equiv="refresh" content="0;url={html.escape(url)}">'
                 f'<title>embroact studio</title><a href="{html.escape(url)}">embroact studio</a>\n')
    return Path(name)


def _open_browser(server, page: Path) -> None:
    import webbrowser

    while not server.started and not server.should_exit:
        time.sleep(0.05)
    if server.started:
        webbrowser.open(page.as_uri())


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
    """Serve ``studio`` until interrupted; print its address first. Returns 0.

    Parameters
    ----------
    studio : Studio
        The session to serve.
    port : int, optional
        The port (0: a free one).
    browser : bool, optional
        Open the page in the browser.
    stream : file, optional
        Where the address is printed (default: stdout).

    Returns
    -------
    int
        0, once stopped (Ctrl-C or SIGTERM).

    Raises
    ------
    ParameterError
        A bad port, or one that cannot be bound: before anything is served.

    Examples
    --------
    >>> import tempfile
    >>> from embroact.patterns.design import default_design
    >>> from embroact.export.studio.session import Studio
    >>> out = tempfile.TemporaryDirectory()
    >>> studio = Studio(default_design(), out.name, (), None)
    >>> try:
    ...     serve(studio, port=-1)
    ... except ValueError as exc:
    ...     print(exc)
    port must be an integer in [0, 65535], got -1
    >>> out.cleanup()
    """
    server, sock, url = _server(studio, port)
    stream = sys.stdout if stream is None else stream
    print(f"embroact studio: {url}\nwrites into {studio.out_dir}; Ctrl-C stops it", file=stream, flush=True)
    folder = tempfile.mkdtemp(prefix="embroact-studio-")  # mode 0700
    try:
        if browser:
            threading.Thread(target=_open_browser, args=(server, launcher_page(url, folder)), daemon=True).start()
        server.run(sockets=[sock])
    finally:
        sock.close()
        shutil.rmtree(folder, ignore_errors=True)
    return 0


@contextlib.contextmanager
def background(studio, *, port: int = 0, timeout_s: float = 20.0):
    """Serve ``studio`` from a thread while the block runs (tests, benchmarks, screenshots); yields the address.

    Parameters
    ----------
    studio : Studio
        The session to serve.
    port : int, optional
        The port (0: a free one).
    timeout_s : float, optional
        Longest wait for the server to start, and to stop [s].

    Yields
    ------
    str
        The studio's address, with its token.

    Raises
    ------
    RuntimeError
        The server did not start within ``timeout_s``.

    Examples
    --------
    >>> import urllib.request
    >>> import tempfile
    >>> from embroact.patterns.design import default_design
    >>> from embroact.export.studio.session import Studio
    >>> out = tempfile.TemporaryDirectory()
    >>> studio = Studio(default_design(), out.name, (), None)
    >>> with background(studio) as url:
    ...     urllib.request.urlopen(url).read()[:15]
    b'<!DOCTYPE html>'
    >>> out.cleanup()
    """
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
