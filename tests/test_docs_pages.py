"""docs/commands.md is generated from the parsers and must match them; docs/api.md's examples run."""
import doctest
from pathlib import Path

import pytest

from embroact.export.cli.reference import commands_markdown
from embroact.patterns.kinds import PATTERN_KINDS

DOCS = Path(__file__).resolve().parent.parent / "docs"


def _shipped_kinds_only():
    """Skip when a test has registered a pattern kind (EMBROACT_TEST_KINDS=1): the page documents the shipped ones."""
    extra = [k.name for k in PATTERN_KINDS if not k.module.startswith("embroact.")]
    if extra:
        pytest.skip(f"test pattern kinds registered: {extra}")


def test_command_reference_matches_the_parsers():
    _shipped_kinds_only()
    page = (DOCS / "commands.md").read_text(encoding="utf-8")
    assert page == commands_markdown(), (
        "docs/commands.md is out of date: python -m embroact.export.cli.reference > docs/commands.md")


def test_every_command_and_option_is_on_the_page():
    _shipped_kinds_only()
    from embroact.export.cli.main import _command_parser, commands

    page = (DOCS / "commands.md").read_text(encoding="utf-8")
    for name in commands():
        assert f"## embroact {name}" in page
        for action in _command_parser(name)[1]._actions:
            for flag in action.option_strings:
                if flag not in ("-h", "--help"):
                    assert f"`{flag}" in page or f", {flag}" in page, (name, flag)


def test_api_page_examples_run(monkeypatch):
    monkeypatch.chdir(DOCS.parent)  # the page's paths are relative to the repository
    result = doctest.testfile(str(DOCS / "api.md"), module_relative=False,
                              optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 10 and result.failed == 0
