"""The ``embroact`` command line: parse, call the public API, print, return a code.

Each subcommand lives in its own module ``embroact.export.cmd_<name>`` with two
functions, ``add_arguments(parser)`` and ``run(args) -> int``; it is imported only
when that subcommand runs, so ``embroact --help`` imports nothing heavy.

Exit codes
----------
0  success
1  design-rule errors found (``check``), or ``build`` refused to write because of them
2  unusable input: bad parameter, unreadable or invalid design / embroidery file, usage
3  an output file could not be written
4  a numerical method failed (a bug or a design far outside the model; message says which), or the
   command ran past its time limit (``embroact --time-limit-s S COMMAND``, default an hour)
5  ``design``: no sewable design meets the target (the answer says why and names the nearest design,
   written only with ``--write-nearest``)
130, 143  interrupted (Ctrl-C) or terminated (SIGTERM), within a second whatever the command is
          computing (:mod:`embroact.export.cli.signals`); no partial output is left
141  standard output was closed by its reader (``| head``); the program ends quietly

Examples
--------
>>> from embroact.export.cli.main import main
>>> main(["zigzag", "--width-mm", "-1", "-o", "x.dst"])  # doctest: +SKIP
embroact: error: width_mm must be in (0, 200), got -1
2
"""
from __future__ import annotations

import argparse
import gc
import importlib
import io
import os
import re
import sys
import warnings

from .. import __version__
from .args import DEFAULT_TIME_LIMIT_S

__all__ = ["main", "COMMANDS", "commands"]

#: name -> (module, one-line help) of the commands after the quick commands (see :func:`commands`).
COMMANDS: dict[str, tuple[str, str]] = {
    "build": ("cmd_build", "build a design file: machine files, worksheet, previews, report"),
    "check": ("cmd_check", "run the design-rule checks on a design or any embroidery file"),
    "predict": ("cmd_predict", "predict pressure-to-bend curves for a design or quick parameters"),
    "fit": ("cmd_fit", "fit G and P0 to measured (pressure, angle) data"),
    "preview": ("cmd_preview", "render a single preview (stitches, bend chart, side view, 3D)"),
    "design": ("cmd_design", "inverse design: the design that bends as wanted (a bend or a shape at a pressure)"),
    "calibrate": ("cmd_calibrate", "calibration coupon: test actuators to sew, marker sheets, a measurement sheet"),
    "measure": ("cmd_measure", "bend from photos: markers found with OpenCV, one row per photo (extra: measure)"),
    "studio": ("cmd_studio", "designer in the browser: edit a design, see stitches and predicted bend live"),
}



def commands() -> dict[str, tuple[str, str]]:
    """name -> (module, one-line help) of every command, in the order ``--help`` shows them.

    First one quick command per registered pattern kind (``embroact zigzag``, ...), then
    :data:`COMMANDS`.

    Returns
    -------
    dict of str to tuple of str

    Examples
    --------
    >>> list(commands())[:2], commands()["cross"][1]
    (['zigzag', 'cross'], 'generate one cross-pattern actuator and write its machine file')
    """
    from ...patterns.kindnames import kind_descriptions  # not the registry: --help needs no parameter classes

    quick = {name: ("cmd_generate", f"generate {text or f'one {name} actuator'} and write its machine file")
             for name, text in kind_descriptions().items()}
    return {**quick, **COMMANDS}


EXIT_OK, EXIT_RULES, EXIT_INPUT, EXIT_OUTPUT, EXIT_SOLVER, EXIT_NOT_MET = 0, 1, 2, 3, 4, 5
#: Ended by Ctrl-C, SIGTERM, or a closed pipe: the shell's 128 + signal number.
EXIT_INTERRUPTED, EXIT_TERMINATED, EXIT_BROKEN_PIPE = 130, 143, 141


def _help_width() -> int:
    """The width argparse wraps help to (``COLUMNS``, else the terminal's, else 80 columns; less 2).

    What argparse gets from ``shutil.get_terminal_size``, without importing shutil (with
    bz2 and lzma: ~1.6 ms, a tenth of ``embroact --help`` over a bare interpreter).
    """
    try:
        columns = int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(sys.__stdout__.fileno()).columns if sys.__stdout__ else 0
        except (ValueError, OSError):
            columns = 0
    return (columns if columns > 0 else 80) - 2


class _Help(argparse.HelpFormatter):
    """argparse's help layout at :func:`_help_width`."""

    def __init__(self, prog: str, **kwargs) -> None:
        kwargs.setdefault("width", _help_width())
        super().__init__(prog, **kwargs)


class _RawDescriptionHelp(_Help, argparse.RawDescriptionHelpFormatter):
    """:class:`_Help` with the description kept as written (the command table)."""


class _Parser(argparse.ArgumentParser):
    """argparse whose usage errors are one line (no usage block), like every other error.

    Options must be spelled out (no abbreviations: ``--wid`` is not ``--width-mm``), and an
    unknown option is reported before a missing required one (``--widht-mm 7`` names the
    typo, with the nearest known option).
    """

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("formatter_class", _Help)
        super().__init__(*args, allow_abbrev=False, **kwargs)

    def error(self, message: str):
        self.exit(EXIT_INPUT, f"{self.prog}: error: {_error_line(message)} (see '{self.prog} --help')\n")

    def parse_args(self, args=None, namespace=None):
        required = [a for a in self._actions if a.required]
        for action in required:  # first pass: unknown options only
            action.required = False
        try:
            _, extras = self.parse_known_args(args, namespace)
        finally:
            for action in required:
                action.required = True
        if extras:
            self.error(f"unrecognized arguments: {' '.join(extras)}{self._nearest(extras[0])}")
        return super().parse_args(args, namespace)

    def _nearest(self, token: str) -> str:
        import difflib

        known = [s for a in self._actions for s in a.option_strings if s.startswith("--")]
        flag = token.split("=", 1)[0]
        close = [k for k in known if k.startswith(flag)][:1] or difflib.get_close_matches(flag, known, n=1, cutoff=0.75)
        return f" (did you mean {close[0]}?)" if close else ""


def _printable(text: str) -> str:
    """``text`` with control characters and undecodable bytes escaped: one safe terminal line."""
    return "".join(c if c.isprintable() else c.encode("unicode_escape", "backslashreplace").decode("ascii")
                   for c in str(text))


def _option_like_value(argv: list[str]) -> str | None:
    """The first ``--flag=--``: argparse drops a bare ``--`` value and hands the command an empty list."""
    for token in argv:
        if token == "--":
            return None
        if token.startswith("-") and token.endswith("=--") and token.count("=") == 1:
            return token
    return None


#: Longest time limit [s] (a day; setitimer takes any float, a typo of 1e300 is no limit).
MAX_TIME_LIMIT_S = 86400.0


def _time_limit(text: str) -> float:
    """``--time-limit-s``: seconds in [0, MAX_TIME_LIMIT_S] (argparse words a ValueError as an invalid value)."""
    value = float(text)
    if not 0.0 <= value <= MAX_TIME_LIMIT_S:
        raise argparse.ArgumentTypeError(f"must be in [0, {MAX_TIME_LIMIT_S:g}] seconds, got {text[:40]!r}")
    return value


def _top_parser() -> argparse.ArgumentParser:
    every = commands()
    width = max(len(n) for n in every)
    lines = "\n".join(f"  {n:<{width}}  {h}" for n, (_, h) in every.items())
    p = _Parser(
        prog="embroact",
        description="CAD tool and stitch generator for embroidery actuators.\n\ncommands:\n" + lines,
        epilog="Units: mm, kPa, MPa, deg. 'embroact COMMAND --help' shows a command's options. "
        "Exit codes: 0 ok, 1 design-rule errors, 2 bad input, 3 cannot write, 4 solver failure, "
        "5 design target not met.",
        formatter_class=_RawDescriptionHelp,
    )
    p.add_argument("--version", action="version", version=f"embroact {__version__}")
    p.add_argument("--debug", action="store_true", help="show tracebacks for errors")
    p.add_argument("--time-limit-s", type=_time_limit, default=DEFAULT_TIME_LIMIT_S, metavar="S",
                   help=f"end the command after S seconds with exit code 4 (default {DEFAULT_TIME_LIMIT_S:g}; 0: none)")
    p.add_argument("command", choices=list(every), metavar="COMMAND", help="one of the commands above")
    p.add_argument("args", nargs=argparse.REMAINDER, help=argparse.SUPPRESS)
    return p


def _command_parser(name: str):
    module_name, description = commands()[name]
    module = importlib.import_module(f".{module_name}", __package__)
    parser = _Parser(prog=f"embroact {name}", description=description)
    parser.add_argument("--debug", action="store_true", help="show tracebacks for errors")
    module.add_arguments(parser, name)
    return module, parser


_OUT_OF_MEMORY = "out of memory: the input is too large for this machine"
#: Longest error line printed [characters]; a longer one (a message repeating a huge value) is cut.
ERROR_CHARS = 1000
#: Control characters other than newline and tab: escaped on stdout (an input file name
#: with ESC [2J in it must not clear the terminal).
_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f]")


class _EscapingStdout(io.TextIOBase):
    """Standard output with control characters written as escapes (``\x1b``), all else passed on."""

    def __init__(self, inner):
        self._inner = inner

    def write(self, text: str) -> int:
        self._inner.write(_CONTROL.sub(lambda m: m.group().encode("unicode_escape").decode("ascii"), text))
        return len(text)

    def flush(self) -> None:
        self._inner.flush()

    def fileno(self) -> int:
        return self._inner.fileno()

    def isatty(self) -> bool:
        return self._inner.isatty()

    def writable(self) -> bool:
        return True


def _quiet_stdout() -> None:
    """After a broken pipe: point stdout at /dev/null so the exit-time flush stays silent."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError, io.UnsupportedOperation):
        pass


def main(argv: list[str] | None = None) -> int:
    """Run the command line; return the exit code (see the module docstring).

    Also: SIGTERM cleans up like Ctrl-C (exit 143, no staged ``.part`` file left), and either
    ends the process within a second (:mod:`embroact.export.cli.signals`; run as the program,
    ``argv`` None, the process then ends without the interpreter's shutdown); a reader
    that goes away (``embroact predict ... | head -1``) ends the program quietly with 141,
    the shell's code for a broken pipe; floating-point RuntimeWarnings are not shown (every
    result is checked for finiteness where it leaves the model, and a non-finite one
    becomes a status or a one-line error, so the warning tells a user nothing; ``--debug``
    shows them); stdout escapes control characters (a file name holding ESC sequences) and
    what it cannot encode instead of failing. Run as the program, it ends by moving every object
    to the garbage collector's permanent generation (``gc.freeze``), so that the interpreter's
    exit skips the cycle search over the loaded modules (atexit handlers and the streams' flush
    still run; the process's memory is returned whole).

    Parameters
    ----------
    argv : list of str or None, optional
        The arguments after the program's name; None: ``sys.argv[1:]``.

    Returns
    -------
    int
        The exit code.

    Examples
    --------
    >>> main(["--version"])  # doctest: +ELLIPSIS
    embroact ...
    0
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     main(["cross", "--width-mm", "7", "--angle-deg", "45", "-o", f"{tmp}/c.dst"])  # doctest: +ELLIPSIS
    wrote .../c.dst (dst): 148 stitches, 1 stop, 1 trim; w 7 mm, s 1.4 mm, alpha0 45 deg, ...
    0
    """
    program = argv is None  # the process's own command line: it may end the process (a call from Python may not)
    argv = list(sys.argv[1:] if argv is None else argv)
    if isinstance(sys.stdout, io.TextIOWrapper):
        sys.stdout.reconfigure(errors="backslashreplace")
    try:
        top = _top_parser().parse_args(argv)
        module, parser = _command_parser(top.command)
        bad = _option_like_value(top.args)
        if bad is not None:
            flag = bad[:-3]
            parser.error(f"argument {flag}: expected a value, got '--' (an option, not a value)")
        args = parser.parse_args(top.args)
    except SystemExit as exc:  # argparse: --help (0) or usage error (2)
        return int(exc.code or 0)
    args.command = top.command
    debug = top.debug or args.debug
    from .signals import Terminated, last_line, watchdog  # here: `embroact --help` needs neither it nor threads

    real_stdout = sys.stdout
    if real_stdout is not None:  # None when started with stdout closed (>&-)
        sys.stdout = _EscapingStdout(real_stdout)
    try:
        with watchdog(time_limit_s=top.time_limit_s):
            code = _run(module, args, debug)
    except KeyboardInterrupt as exc:  # a signal as the block was left (Terminated is a KeyboardInterrupt)
        code = EXIT_TERMINATED if isinstance(exc, Terminated) else EXIT_INTERRUPTED
        last_line(f"embroact: {'terminated' if code == EXIT_TERMINATED else 'interrupted'}")
    finally:
        sys.stdout = real_stdout
    if program and code in (EXIT_INTERRUPTED, EXIT_TERMINATED):
        _exit_now(code)  # freeing a large computation's memory at shutdown can take longer than the signal may
    if program:  # the process ends next: the interpreter's last collections need not search what is loaded
        gc.freeze()  # for cycles (20 ms of `embroact build`'s exit; the memory goes back with the process)
    return code


def _exit_now(code: int) -> None:
    """End the process at once with ``code`` (streams flushed, no interpreter shutdown)."""
    for stream in (sys.stdout, sys.stderr):
        try:
            if stream is not None:
                stream.flush()
        except (OSError, ValueError):
            pass
    os._exit(code)


def _run(module, args, debug: bool) -> int:
    """``module.run(args)`` with every failure turned into its exit code and one stderr line."""
    from ...patterns.base.errors import EmbroactError, ExportError, SolverError
    from .signals import Terminated, TimeLimitError, interrupted_by, last_line

    err: EmbroactError | str
    timed_out = False
    try:
        with warnings.catch_warnings():
            if not debug:
                warnings.simplefilter("ignore", RuntimeWarning)
            from .target import print_notes, reset_notes

            reset_notes()
            code = int(module.run(args))
            if not getattr(args, "json", False):  # machine-readable runs keep stderr for errors
                print_notes()  # the demonstration-calibration note, once, after the command's own output
            if sys.stdout is not None:
                sys.stdout.flush()
        return code
    except BrokenPipeError:
        _quiet_stdout()
        return EXIT_BROKEN_PIPE
    except ExportError as exc:
        code, err = EXIT_OUTPUT, exc
    except SolverError as exc:
        code, err = EXIT_SOLVER, exc
    except TimeLimitError as exc:  # no Exception: raised wherever the command was (the watchdog may end it too)
        code, err, timed_out = EXIT_SOLVER, str(exc), True
    except EmbroactError as exc:
        code, err = EXIT_INPUT, exc
    except OSError as exc:
        code, err = EXIT_INPUT, f"{exc.filename or ''}: {exc.strerror or exc}".lstrip(": ")
    except MemoryError:  # past the documented input limits; one line, not a traceback
        code, err = EXIT_INPUT, _OUT_OF_MEMORY
    except Exception as exc:  # C++ libraries (GEOS via shapely) report exhausted memory as their own error
        signum = interrupted_by()
        if signum is not None:  # a library made the signal's exception its own (an import it interrupted)
            import signal

            last_line(f"embroact: {'terminated' if signum == signal.SIGTERM else 'interrupted'}")
            return EXIT_TERMINATED if signum == signal.SIGTERM else EXIT_INTERRUPTED
        if "bad_alloc" not in str(exc):
            raise
        code, err = EXIT_INPUT, _OUT_OF_MEMORY
    except Terminated:
        last_line("embroact: terminated")
        return EXIT_TERMINATED
    except KeyboardInterrupt:
        last_line("embroact: interrupted")
        return EXIT_INTERRUPTED
    if debug:
        raise err if isinstance(err, BaseException) else RuntimeError(err)
    (last_line if timed_out else _stderr_line)(f"embroact: error: {_error_line(str(err))}")
    return code


def _stderr_line(line: str) -> None:
    print(line, file=sys.stderr)


def _error_line(text: str) -> str:
    """``text`` printable and at most :data:`ERROR_CHARS` characters (a message echoing a 200,000-character value)."""
    line = _printable(text)
    if len(line) <= ERROR_CHARS:
        return line
    return f"{line[:ERROR_CHARS]}... ({len(line) - ERROR_CHARS:,} more characters cut)"
