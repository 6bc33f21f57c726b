"""One rule gate: every command and the studio judge a design by ``embroact.predict.rules.check_design``.

Each caller is run with ``check_design`` wrapped to record the designs it saw; a caller
that judged a design some other way (the geometry rules alone, as inverse shape design
once did) records nothing.
"""
from pathlib import Path

import pytest

import embroact.predict.rules as rules
from embroact.export.cli.main import main

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@pytest.fixture
def seen(monkeypatch):
    calls = []
    real = rules.check_design

    def wrapped(analysis, **kw):
        calls.append(analysis.design.name)
        return real(analysis, **kw)

    monkeypatch.setattr(rules, "check_design", wrapped)
    return calls


@pytest.mark.parametrize("argv", [
    ["build", "--out", "{tmp}"],
    ["check", str(EXAMPLES / "three_actuators.toml")],
    ["zigzag", "--width-mm", "7", "-o", "{tmp}/z.dst"],
    ["cross", "--width-mm", "7", "--angle-deg", "45", "-o", "{tmp}/c.dst"],
    ["design", "--bend-deg", "60", "--at-kpa", "150", "--pattern", "zigzag", "-o", "{tmp}/b.toml"],
    ["design", "--target-shape", str(EXAMPLES / "data" / "target_hook.csv"), "--at-kpa", "250", "-o", "{tmp}/s.toml"],
])
def test_every_command_runs_the_one_gate(argv, seen, tmp_path, capsys):
    assert main([a.format(tmp=tmp_path) for a in argv]) in (0, 1, 5)  # 5: a target not met, judged all the same
    assert seen, f"{argv[0]} judged its design without check_design"


def test_the_studio_runs_the_one_gate(seen, tmp_path):
    from embroact.export.studio.session import Studio
    from embroact.patterns.design import default_design

    Studio(default_design(), tmp_path).views(100.0)
    assert seen == ["paper-zigzag"]
