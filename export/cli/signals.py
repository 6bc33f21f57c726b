"""Ctrl-C, SIGTERM and the time limit end a command within a second, whatever it is computing.

Python runs a signal handler in the main thread between two bytecodes, so a command inside
one long call into a C library (shapely's nearest-segment query over a 5,000-arc path runs
20 s in one call) would notice SIGTERM only when that call returns: 20 s late. The
:func:`watchdog` closes that gap. The C-level signal handler writes the signal's number to
a pipe (``signal.set_wakeup_fd``) at once, and a thread waiting on the pipe (the C libraries
release the GIL while they work, so it runs) gives the main thread :data:`GRACE_S` to end
the usual way (the handler raises, staged files are removed, the exit code is returned); if
it has not, the thread removes the staged files itself
(:func:`embroact.export.files.atomic.abandon_staged`, which waits for a rename in progress)
and ends the process with the same message and exit code. The message is written once
(:func:`last_line`): a main thread that writes it just past the grace gets as long again to
end by itself.

The time limit (``embroact --time-limit-s S COMMAND``, default :data:`DEFAULT_TIME_LIMIT_S`)
is a SIGALRM handled the same way: the command ends with ``embroact: error: the command took
longer than its time limit of S s (--time-limit-s)`` and exit code 4.

Examples
--------
>>> import signal, time
>>> from embroact.export.cli.signals import watchdog, TimeLimitError
>>> try:
...     with watchdog(time_limit_s=0.05):
...         while True:
...             time.sleep(0.01)
... except TimeLimitError as exc:
...     print(exc)
the command took longer than its time limit of 0.05 s (--time-limit-s)
"""
from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
from typing import Iterator

from .args import DEFAULT_TIME_LIMIT_S

__all__ = ["watchdog", "serving", "TimeLimitError", "Terminated", "GRACE_S", "DEFAULT_TIME_LIMIT_S",
           "time_limit_message", "interrupted_by", "last_line"]

#: How long the main thread has to end by itself after a signal before the watchdog ends the process [s].
GRACE_S = 0.25
#: Exit codes: the shell's 128 + signal number, and the solver's code for a time limit.
_EXIT = {signal.SIGINT: (130, "interrupted"), signal.SIGTERM: (143, "terminated")}
_EXIT_TIME_LIMIT = 4
#: Stack of the watchdog thread [bytes] (the smallest most systems allow is 32 KiB; its calls are shallow).
_STACK_BYTES = 256 * 1024


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised like an interrupt so that staged files are removed on the way out."""


class TimeLimitError(BaseException):
    """The command ran past its time limit (a one-line error, exit code 4).

    Raised by the SIGALRM handler wherever the main thread is: like KeyboardInterrupt it is
    no ``Exception``, so none of the handlers that re-word a library error with a file or
    key name (``except EmbroactError``, ``except Exception``) takes it for one (``check
    arcs.toml`` said ``actuator[1].path: the command took longer ...``, exit 2); cleanups
    still run.
    """


def time_limit_message(seconds: float) -> str:
    """The one line a command past its time limit ends with.

    Parameters
    ----------
    seconds : float
        The time limit [s].

    Returns
    -------
    str

    Examples
    --------
    >>> time_limit_message(60.0)
    'the command took longer than its time limit of 60 s (--time-limit-s)'
    """
    return f"the command took longer than its time limit of {seconds:g} s (--time-limit-s)"


#: The signals the handlers met in the running block, in order (a library may turn the exception a handler
#: raised into an error of its own: numpy, imported while SIGTERM arrives, raises ImportError).
_RECEIVED: list[signal.Signals] = []


def interrupted_by() -> signal.Signals | None:
    """The signal (SIGINT or SIGTERM) that interrupted the running :func:`watchdog` block, if one did.

    An error a command ends with is the signal's doing when this is set: the handler's
    exception was turned into another one on the way out (an import that fails because the
    signal interrupted it), and the command ends as the signal asks, not with a traceback.

    Returns
    -------
    signal.Signals or None

    Examples
    --------
    >>> with watchdog(time_limit_s=0):
    ...     interrupted_by() is None
    True
    """
    return _RECEIVED[0] if _RECEIVED else None


#: Taken by whichever of the main thread and the watchdog thread writes the line a signal or the time limit ends
#: the running :func:`watchdog` block with (a main thread that ends just past :data:`GRACE_S` and the watchdog
#: both reached theirs: ``embroact: terminated`` twice); a new one for each block.
_LAST_LINE = threading.Lock()


def last_line(line: str) -> None:
    """Write ``line`` to stderr as the command's last, unless it has been written: the line a signal or the time limit
    ends a command with, written once whether the main thread or the watchdog thread ends it.

    Parameters
    ----------
    line : str
        The line, without its newline.

    Examples
    --------
    >>> import contextlib, io
    >>> err = io.StringIO()
    >>> with watchdog(time_limit_s=0), contextlib.redirect_stderr(err):
    ...     last_line("embroact: terminated")
    ...     last_line("embroact: interrupted")
    >>> err.getvalue().splitlines()
    ['embroact: terminated']
    """
    if _LAST_LINE.acquire(blocking=False):
        print(line, file=sys.stderr)


def _on_sigterm(signum, frame):
    _RECEIVED.append(signal.SIGTERM)
    raise Terminated()


def _on_sigint(signum, frame):
    _RECEIVED.append(signal.SIGINT)
    raise KeyboardInterrupt()


#: Set while a server runs (:func:`serving`): its event loop answers signals itself, and it has no time limit.
_SERVING = threading.Event()


@contextlib.contextmanager
def serving() -> Iterator[None]:
    """Run a server in the block: no time limit, and signals left to the server's own handlers.

    ``embroact studio`` runs until stopped; uvicorn ends it gracefully on Ctrl-C or SIGTERM
    (closing connections, removing the launcher page), which the watchdog must not cut short.

    Yields
    ------
    None

    Examples
    --------
    >>> with serving():
    ...     _SERVING.is_set()
    True
    >>> _SERVING.is_set()
    False
    """
    if threading.current_thread() is threading.main_thread():
        signal.setitimer(signal.ITIMER_REAL, 0)
    _SERVING.set()
    try:
        yield
    finally:
        _SERVING.clear()


def _guard(read_fd: int, done: threading.Event, time_limit_s: float, said: threading.Lock) -> None:
    """The watchdog thread: wait for a signal byte; give the main thread GRACE_S; then end the process (with the
    block's last line unless the main thread has written it: it then gets GRACE_S more to end by itself)."""
    from ..files.atomic import abandon_staged

    wanted = {int(signal.SIGINT), int(signal.SIGTERM), int(signal.SIGALRM)}
    while True:
        try:
            data = os.read(read_fd, 64)
        except OSError:
            return
        if not data or done.is_set():
            return
        hits = [b for b in data if b in wanted]
        if not hits or _SERVING.is_set():
            continue
        if done.wait(GRACE_S):
            return  # the main thread handled it
        signum = signal.Signals(hits[0])
        if signum == signal.SIGALRM:
            code, line = _EXIT_TIME_LIMIT, f"embroact: error: {time_limit_message(time_limit_s)}"
        else:
            code, word = _EXIT[signum]
            line = f"embroact: {word}"
        wrote = said.acquire(blocking=False)
        if not wrote and done.wait(GRACE_S):
            return  # the main thread wrote the line and ended by itself
        abandon_staged()
        if wrote:
            with contextlib.suppress(OSError):
                os.write(2, (line + "\n").encode())
        os._exit(code)


@contextlib.contextmanager
def watchdog(*, time_limit_s: float = DEFAULT_TIME_LIMIT_S) -> Iterator[None]:
    """Run the block with SIGTERM raising :class:`Terminated`, the time limit, and the watchdog thread.

    Outside the main thread (where no signal handler can be set) the block runs as it is.

    Parameters
    ----------
    time_limit_s : float, optional
        Longest time the block may take [s]; 0: no limit.

    Yields
    ------
    None

    Raises
    ------
    TimeLimitError
        The block ran past ``time_limit_s``.

    Examples
    --------
    >>> with watchdog(time_limit_s=60.0):
    ...     sum(range(10))
    45
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    global _LAST_LINE
    read_fd, write_fd = os.pipe()
    os.set_blocking(write_fd, False)
    done, said = threading.Event(), threading.Lock()
    _LAST_LINE = said

    def on_alarm(signum, frame):
        raise TimeLimitError(time_limit_message(time_limit_s))

    try:
        old_fd = signal.set_wakeup_fd(write_fd, warn_on_full_buffer=False)
    except ValueError:  # not possible here (an embedding that forbids it): signals as Python handles them
        old_fd = None
    thread = None
    if old_fd is not None:
        thread = threading.Thread(target=_guard, args=(read_fd, done, time_limit_s, said), name="embroact-watchdog",
                                  daemon=True)
        stack = threading.stack_size(_STACK_BYTES)  # it reads a pipe: no 8 MB stack under a memory ceiling
        try:
            thread.start()
        except RuntimeError:  # no thread to be had (address space exhausted): Python's handlers alone
            thread = None
        finally:
            threading.stack_size(stack)
    # the handlers last in and first out: a signal outside the block meets the handler the caller had
    _RECEIVED.clear()
    old_term = signal.signal(signal.SIGTERM, _on_sigterm)
    old_int = signal.getsignal(signal.SIGINT)
    if old_int is signal.default_int_handler:  # Python's own (an ignored SIGINT stays ignored)
        signal.signal(signal.SIGINT, _on_sigint)
    old_alarm = signal.signal(signal.SIGALRM, on_alarm) if time_limit_s > 0 else None
    if time_limit_s > 0:
        signal.setitimer(signal.ITIMER_REAL, time_limit_s)
    try:
        yield
    finally:
        if time_limit_s > 0:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, old_alarm)
        signal.signal(signal.SIGTERM, old_term)
        if old_int is signal.default_int_handler:
            signal.signal(signal.SIGINT, old_int)
        done.set()
        if old_fd is not None:
            signal.set_wakeup_fd(old_fd)
        os.close(write_fd)  # the thread's read returns b"": it ends
        if thread is not None:
            thread.join(1.0)
        os.close(read_fd)
        sys.stderr.flush()
