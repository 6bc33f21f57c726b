"""The command reference (docs/commands.md), generated from the argparse parsers themselves.

``python -m embroact.export.cli.reference > docs/commands.md`` rewrites the page; a test
asserts that the committed page equals :func:`commands_markdown`, so the page cannot drift
from the options the program really takes.

Examples
--------
>>> from embroact.export.cli.reference import commands_markdown
>>> text = commands_markdown()
>>> text.splitlines()[0], "## embroact zigzag" in text, "`--width-mm WIDTH_MM`" in text
('# Command reference', True, True)
"""
from __future__ import annotations

import argparse

__all__ = ["commands_markdown"]

_HEADER = """# Command reference

Generated from the program's own argument parsers by
`python -m embroact.export.cli.reference > docs/commands.md` (a test checks that this page
matches them). Every command also prints its options with `--help`. Units: mm, kPa, MPa,
degrees; `--json` output names the unit in every key.

Exit codes: 0 success; 1 design-rule errors found (`check`, or `build` refused);
2 unusable input; 3 an output file could not be written; 4 a numerical method failed or the
command ran past its time limit; 5 `design` found no sewable design meeting the target (it says
why and names the nearest, written only with `--write-nearest`); 130 / 143 interrupted (Ctrl-C) /
terminated (SIGTERM).

Options of every command, given before its name: `embroact --time-limit-s S COMMAND ...` ends
the command after S seconds (default 3600; 0: none) with exit code 4 and one line;
`--debug` shows tracebacks. Ctrl-C, SIGTERM and the time limit take effect within a second,
whatever the command is computing.
"""


def _cell(text: object) -> str:
    return " ".join(str(text).split()).replace("|", "\\|")


def _flag(action: argparse.Action) -> str:
    if not action.option_strings:
        return _cell(f"`{action.metavar or action.dest}`")
    names = ", ".join(action.option_strings)
    if action.nargs == 0:
        return f"`{names}`"
    metavar = action.metavar or (("{" + ",".join(map(str, action.choices)) + "}") if action.choices
                                 else action.dest.upper())
    return _cell(f"`{names} {metavar}`")


def _default(action: argparse.Action) -> str:
    if action.nargs == 0 or action.default in (None, [], argparse.SUPPRESS) or action.required:
        return "required" if action.required else ""
    return f"`{action.default}`"


def _parser_markdown(name: str, parser: argparse.ArgumentParser) -> list[str]:
    out = [f"## embroact {name}", "", _cell(parser.description or ""), ""]
    for group in parser._action_groups:  # argparse keeps groups in definition order
        actions = [a for a in group._group_actions if a.help != argparse.SUPPRESS
                   and not isinstance(a, argparse._HelpAction)]
        if not actions:
            continue
        out += [f"**{group.title}**", "", "| option | default | meaning |", "|---|---|---|"]
        out += [f"| {_flag(a)} | {_default(a)} | {_cell(a.help or '')} |" for a in actions]
        out.append("")
    return out


def commands_markdown() -> str:
    """The command reference as Markdown: every command, every option, its default and help.

    Returns
    -------
    str
        The text of docs/commands.md.

    Examples
    --------
    >>> "| `--tube-path 'x1,y1 x2,y2 ...'\\\\|SVG_D\\\\|FILE.svg#ID` |" in commands_markdown()  # | escaped in a table
    True
    """
    from .main import _command_parser, commands

    out = [_HEADER, "| command | does |", "|---|---|"]
    out += [f"| [`embroact {n}`](#embroact-{n}) | {_cell(h)} |" for n, (_, h) in commands().items()]
    out.append("")
    for name in commands():
        out += _parser_markdown(name, _command_parser(name)[1])
    return "\n".join(out).rstrip() + "\n"


if __name__ == "__main__":
    print(commands_markdown(), end="")
