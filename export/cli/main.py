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
4  a numerical method failed (a bug or a design far outside the model; message says which)

Examples
--------
>>> from embroact.export.cli.main import main
>>> main(["zigzag", "--width-mm", "-1", "-o", "x.dst"])  # doctest: +SKIP
embroact: error: width_mm must be in (0, 200), got -1
2
"""
from __future__ import annotations

import argparse
import importlib
import sys

from .. import __version__

__all__ = ["main", "COMMANDS"]

#: name -> (module, one-line help). Order is the order shown by ``--help``.
COMMANDS: dict[str, tuple[str, str]] = {
    "zigzag": ("cmd_generate", "generate one zigzag actuator and write its machine file"),
    "cross": ("cmd_generate", "generate one cross-pattern actuator and write its machine file"),
    "build": ("cmd_build", "build a design file: machine files, worksheet, previews, report"),
    "check": ("cmd_check", "run the design-rule checks on a design or any embroidery file"),
    "predict": ("cmd_predict", "predict pressure-to-bend curves for a design or quick parameters"),
    "fit": ("cmd_fit", "fit G and P0 to measured (pressure, angle) data"),
    "preview": ("cmd_preview", "render a single preview (stitches, bend chart, side view, 3D)"),
}

EXIT_OK, EXIT_RULES, EXIT_INPUT, EXIT_OUTPUT, EXIT_SOLVER = 0, 1, 2, 3, 4


class _Parser(argparse.ArgumentParser):
    """argparse whose usage errors are one line (no usage block), like every other error."""

    def error(self, message: str):
        self.exit(EXIT_INPUT, f"{self.prog}: error: {message} (see '{self.prog} --help')\n")


def _top_parser() -> argparse.ArgumentParser:
    width = max(len(n) for n in COMMANDS)
    lines = "\n".join(f"  {n:<{width}}  {h}" for n, (_, h) in COMMANDS.items())
    p = _Parser(
        prog="embroact",
        description="CAD tool and stitch generator for embroidery actuators.\n\ncommands:\n" + lines,
        epilog="Units: mm, kPa, MPa, deg. 'embroact COMMAND --help' shows a command's options. "
        "Exit codes: 0 ok, 1 design-rule errors, 2 bad input, 3 cannot write, 4 solver failure.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("--version", action="version", version=f"embroact {__version__}")
    p.add_argument("--debug", action="store_true", help="show tracebacks for errors")
    p.add_argument("command", choices=list(COMMANDS), metavar="COMMAND", help="one of the commands above")
    p.add_argument("args", nargs=argparse.REMAINDER, help=argparse.SUPPRESS)
    return p


def _command_parser(name: str):
    module = importlib.import_module(f".{COMMANDS[name][0]}", __package__)
    parser = _Parser(prog=f"embroact {name}", description=COMMANDS[name][1])
    parser.add_argument("--debug", action="store_true", help="show tracebacks for errors")
    module.add_arguments(parser, name)
    return module, parser


def main(argv: list[str] | None = None) -> int:
    """Run the command line; return the exit code (see the module docstring)."""
    argv = list(sys.argv[1:] if argv is None else argv)
    try:
        top = _top_parser().parse_args(argv)
        module, parser = _command_parser(top.command)
        args = parser.parse_args(top.args)
    except SystemExit as exc:  # argparse: --help (0) or usage error (2)
        return int(exc.code or 0)
    args.command = top.command
    debug = top.debug or args.debug
    from ...patterns.base.errors import EmbroactError, ExportError, SolverError

    try:
        return int(module.run(args))
    except ExportError as exc:
        code, err = EXIT_OUTPUT, exc
    except SolverError as exc:
        code, err = EXIT_SOLVER, exc
    except EmbroactError as exc:
        code, err = EXIT_INPUT, exc
    except OSError as exc:
        code, err = EXIT_INPUT, f"{exc.filename or ''}: {exc.strerror or exc}".lstrip(": ")
    except KeyboardInterrupt:
        print("embroact: interrupted", file=sys.stderr)
        return 130
    if debug:
        raise err if isinstance(err, BaseException) else RuntimeError(err)
    print(f"embroact: error: {err}", file=sys.stderr)
    return code
