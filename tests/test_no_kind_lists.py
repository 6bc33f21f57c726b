"""No annotation or message lists the pattern kinds: the registry is the one list (issue 22).

The source is read here (an AST walk over every module of the package) for a type annotation
naming two or more kinds' parameter classes (``ZigzagParams | CrossParams``: a third kind
would not fit it) and for a string that is no docstring (an error message, a help text, a
default) naming two or more kinds (``"pattern must be zigzag or cross"``). The kinds' own
modules and the registry that registers them are where the names live. Docstrings may
describe the shipped kinds' physics side by side; messages and annotations may not. A test of
the test feeds the finder each kind of listing and shows that it finds them.
"""
from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

from embroact.patterns.kinds import PATTERN_KINDS

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("api", "patterns", "predict", "export")
#: The shipped kinds (those of embroact's own modules; a kind a test registers is not counted).
SHIPPED = [k for k in PATTERN_KINDS if k.module.startswith("embroact.")]
#: Where the kinds' names belong: their own modules and the registry that registers them.
OWN = {ROOT / "patterns" / "kinds.py", *(ROOT / "patterns" / f"{k.module.rsplit('.', 1)[1]}.py" for k in SHIPPED)}


def _docstrings(tree: ast.AST) -> set[int]:
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
                out.add(id(first.value))
    return out


def kind_listings(source: str, names=None, classes=None) -> list[tuple[int, str]]:
    """``(line, text)`` of every annotation naming two or more kinds' parameter classes and every
    non-docstring string naming two or more kinds, in ``source``."""
    names = [k.name for k in SHIPPED] if names is None else names
    classes = [k.params.__name__ for k in SHIPPED] if classes is None else classes
    words = [re.compile(rf"(?i)\b{re.escape(n)}\b") for n in names]
    tree = ast.parse(source)
    docs = _docstrings(tree)
    found = []
    for node in ast.walk(tree):
        annotations = []
        if isinstance(node, ast.arg) and node.annotation is not None:
            annotations.append(node.annotation)
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.returns is not None:
            annotations.append(node.returns)
        elif isinstance(node, ast.AnnAssign):
            annotations.append(node.annotation)
        for a in annotations:
            text = a.value if isinstance(a, ast.Constant) and isinstance(a.value, str) else ast.unparse(a)
            if sum(bool(re.search(rf"\b{c}\b", text)) for c in classes) >= 2:
                found.append((a.lineno, text))
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs:
            if sum(bool(w.search(node.value)) for w in words) >= 2:
                found.append((node.lineno, node.value))
    return sorted(found)


def _modules() -> list[Path]:
    return sorted(p for pkg in PACKAGES for p in (ROOT / pkg).rglob("*.py") if p not in OWN)


def test_no_annotation_or_message_lists_the_kinds():
    assert len(SHIPPED) >= 2 and len(_modules()) > 100
    found = {rel: hits for p in _modules()
             if (hits := kind_listings(p.read_text(encoding="utf-8"))) and (rel := str(p.relative_to(ROOT)))}
    assert found == {}


@pytest.mark.parametrize("code", [
    "def f(p: ZigzagParams | CrossParams) -> None:\n    pass\n",
    "def f(p) -> 'Union[ZigzagParams, CrossParams]':\n    pass\n",
    "x: tuple[ZigzagParams, CrossParams] = ()\n",
    "raise ValueError('pattern must be zigzag or cross')\n",
    "def f(pattern):\n    raise ValueError(f'{pattern!r}: expected Zigzag, Cross')\n",
    "HELP = 'patterns to calibrate (default zigzag,cross)'\n",
])
def test_the_finder_finds_every_kind_of_listing(code):
    assert kind_listings(code, ["zigzag", "cross"], ["ZigzagParams", "CrossParams"]), code


def test_the_finder_lets_one_kind_and_docstrings_pass():
    code = ('"""Zigzag and cross patterns, side by side (a docstring)."""\n'
            "def f(p: ZigzagParams) -> CrossParams:\n    'zigzag: its width; cross: its angle'\n"
            "    raise ValueError('a zigzag must be wider than its tube')\n"
            "MSG = 'legs cross the tube'\n")
    assert kind_listings(code, ["zigzag", "cross"], ["ZigzagParams", "CrossParams"]) == []
