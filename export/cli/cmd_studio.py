"""``embroact studio [DESIGN.toml] --out DIR``: the designer in the browser.

Starts a local web server on 127.0.0.1 only, prints its address with a secret token made
for this run and opens a browser (unless ``--no-browser``). The page edits the design
(default: the paper's zigzag actuator) and shows the stitches, the bend chart, the side and
3D views at a pressure, the design-rule findings and the worksheet figures; it saves the
design and builds machine files into DIR only. Needs the optional web server:
``pip install 'embroact[studio]'``.

Exit codes: 130 stopped with Ctrl-C (143 by SIGTERM), like every command interrupted;
2 bad design or option, port in use, extra not installed; 3 output directory missing or
not writable.

Examples
--------
>>> from embroact.export.cli.main import main
>>> main(["studio", "--out", "out", "--port", "99999"])  # doctest: +SKIP
embroact: error: port must be an integer in [0, 65535], got 99999
2
"""
from __future__ import annotations

import argparse
from pathlib import Path

from .target import add_model_arguments

__all__ = ["add_arguments", "run", "EXTRA_HINT"]

EXTRA_HINT = "embroact studio needs the web server of the studio extra: pip install 'embroact[studio]'"


def add_arguments(parser: argparse.ArgumentParser, name: str) -> None:
    """Options of ``embroact studio``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    name : str
        The command's name (``"studio"``).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact studio")
    >>> add_arguments(parser, "studio")
    >>> args = parser.parse_args(["--out", "out"])
    >>> args.out, args.port, args.no_browser
    ('out', 0, False)
    """
    parser.add_argument("design", nargs="?", help="design file (TOML); default: the built-in paper zigzag design")
    add_model_arguments(parser.add_argument_group("model (overrides the design's [actuator.model])"))
    parser.add_argument("--out", required=True, help="existing output directory: the only place the studio writes")
    parser.add_argument("--port", type=int, default=0, help="port on 127.0.0.1 (default 0: any free port)")
    parser.add_argument("--no-browser", action="store_true", help="print the address only; open no browser")


def run(args) -> int:
    """Check the options and the extra, load the design, serve until Ctrl-C (then main's exit code 130).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options (:func:`add_arguments`), with ``command`` set to the command's name.

    Returns
    -------
    int
        The exit code (:mod:`embroact.export.cli.main`).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact studio")
    >>> add_arguments(parser, "studio")
    >>> args = parser.parse_args(["--out", ".", "--port", "70000"])
    >>> args.command = "studio"
    >>> try:
    ...     run(args)
    ... except ValueError as exc:
    ...     print(exc)
    port must be an integer in [0, 65535], got 70000
    """
    import importlib.util

    from ...patterns.base.errors import ParameterError
    from ...patterns.base.validate import check_output_name
    from ..files.atomic import check_writable_dir
    from ..studio.serve import check_port
    from .signals import serving
    from .target import load_target, note_demo_calibration

    check_port(args.port)  # before the extra is looked for and the design read
    out = check_writable_dir(check_output_name("--out", args.out))
    if any(importlib.util.find_spec(m) is None for m in ("starlette", "uvicorn", "tomlkit")):
        raise ParameterError(EXTRA_HINT)
    from ..studio.serve import serve
    from ..studio.session import Studio

    target = load_target(args, design_path=args.design)
    note_demo_calibration({a.model.calibration for a in target.design.actuators}, now=True)
    source = None
    if args.design is not None:  # the file's own design (no overrides): the save changes only what differs
        from ..files.calibfile import resolve_calibration_files
        from ..files.designfile import load_design

        source = (args.design, resolve_calibration_files(load_design(args.design), Path(args.design).parent)[0])
    studio = Studio(target.design, out, target.calibration_sets, source)
    with serving():  # until stopped: no time limit; Ctrl-C and SIGTERM end it gracefully
        return serve(studio, port=args.port, browser=not args.no_browser)
