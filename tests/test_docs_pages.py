"""docs/commands.md is generated from the parsers and must match them; docs/api.md's examples run."""
import doctest
from pathlib import Path

import pytest

from embroact.export.cli.reference import commands_markdown
from embroact.patterns.kinds import PATTERN_KINDS

DOCS = Path(__file__).resolve().parent.parent / "docs"
#: Pattern kinds registered by tests (EMBROACT_TEST_KINDS=1): the page documents the kinds embroact ships.
_TEST_KINDS = [k.name for k in PATTERN_KINDS if not k.module.startswith("embroact.")]
shipped_kinds_only = pytest.mark.skipif(bool(_TEST_KINDS), reason=f"test pattern kinds registered: {_TEST_KINDS}")


@shipped_kinds_only
def test_command_reference_matches_the_parsers():
    page = (DOCS / "commands.md").read_text(encoding="utf-8")
    assert page == commands_markdown(), (
        "docs/commands.md is out of date: python -m embroact.export.cli.reference > docs/commands.md")


@shipped_kinds_only
def test_every_command_and_option_is_on_the_page():
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
