"""The import graph of the source tree, read from the AST, and the layering rules it must keep.

Every ``import`` and ``from ... import`` of every module counts, at any depth: inside
functions (lazy imports), under ``if TYPE_CHECKING:`` and in sub-packages. Relative imports
are resolved against the module's own package, so ``from ...export import x`` in
``patterns/rules/engine.py`` is ``embroact.export``. A string naming a module by its full
dotted name (``importlib.import_module("embroact.export.cli.main")``, or a ``"module:function"``
reference a registry loads later) counts as an import of that module too.

Rules (README, Architecture):

1. layers: ``export -> predict -> patterns``; patterns imports neither predict nor export,
   predict does not import export;
2. no import cycle inside a layer (imports under ``if TYPE_CHECKING:`` never run and are left
   out here), apart from :data:`CYCLE_EXEMPT`;
3. the export sub-packages in one direction (:data:`EXPORT_RANKS`): a sub-package imports only
   sub-packages of a lower rank, or its own.
"""
from __future__ import annotations

import ast
from pathlib import Path

#: Source folder -> package name it installs as (pyproject.toml's package-dir).
PACKAGE_DIRS = {"api": "embroact", "patterns": "embroact.patterns", "predict": "embroact.predict",
                "export": "embroact.export"}
#: Layer order: a layer imports only itself and the layers after it.
LAYERS = ("embroact.export", "embroact.predict", "embroact.patterns")
#: Export sub-packages by rank: each imports only lower ranks (and itself). The package's own
#: modules (``embroact.export``, ``__main__``) are the top.
EXPORT_RANKS = {"cli": 6, "studio": 5, "report": 4, "photo": 3, "pictures": 2, "machine": 1, "files": 0}
#: Import cycles allowed inside a layer (none today).
CYCLE_EXEMPT: frozenset[frozenset[str]] = frozenset()


def module_name(root: Path, path: Path) -> str:
    """``embroact.patterns.rules.engine`` for ``root/patterns/rules/engine.py``."""
    rel = path.relative_to(root)
    parts = list(rel.with_suffix("").parts)
    base = PACKAGE_DIRS[parts[0]]
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join([base, *parts[1:]])


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> list[str]:
    if node.level == 0:
        base = node.module or ""
    else:
        package = module.split(".") if is_package else module.split(".")[:-1]
        package = package[: len(package) - (node.level - 1)]
        base = ".".join(package + ([node.module] if node.module else []))
    if node.module is None:  # from . import a, b: each is a module of that package
        return [f"{base}.{a.name}" for a in node.names]
    return [base] + [f"{base}.{a.name}" for a in node.names]


def _typing_only(tree: ast.AST) -> set[int]:
    """ids of the import nodes under ``if TYPE_CHECKING:`` (they never run)."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            out.update(id(n) for body in node.body for n in ast.walk(body))
    return out


def _named_module(node: ast.AST) -> str | None:
    """The module a string constant names by its dotted name (``"embroact.x.y"`` or ``"embroact.x.y:f"``), if any."""
    if not (isinstance(node, ast.Constant) and isinstance(node.value, str)):
        return None
    module, _, attr = node.value.partition(":")
    if "." not in module or not all(p.isidentifier() for p in module.split(".")) or (attr and not attr.isidentifier()):
        return None
    return module


def import_graph(root: Path, *, typing: bool = True) -> dict[str, set[str]]:
    """Module -> the embroact modules it imports (names as installed), for every module under ``root``.

    ``typing=False`` leaves out the imports under ``if TYPE_CHECKING:`` (for the cycle check:
    they name a type and never run).
    """
    files = {module_name(root, p): p for d in PACKAGE_DIRS if (root / d).is_dir() for p in (root / d).rglob("*.py")}
    graph: dict[str, set[str]] = {}
    for name, path in files.items():
        is_package = path.name == "__init__.py"
        found: set[str] = set()
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        skip = set() if typing else _typing_only(tree)
        for node in ast.walk(tree):
            if id(node) in skip:
                continue
            if isinstance(node, ast.Import):
                found.update(a.name for a in node.names)
            elif isinstance(node, ast.ImportFrom):
                found.update(_resolve(name, is_package, node))
            elif (named := _named_module(node)) is not None:
                found.add(named)
        # keep the modules that exist (``from .x import func`` names x, not x.func)
        graph[name] = {m for m in found if m in files and m != name}
    return graph


def _layer(module: str) -> str | None:
    return next((layer for layer in LAYERS if module == layer or module.startswith(layer + ".")), None)


def layer_violations(graph: dict[str, set[str]]) -> list[str]:
    """``a -> b`` for every import from a lower layer into a higher one."""
    out = []
    for a, targets in sorted(graph.items()):
        la = _layer(a)
        if la is None:  # the API package sits on top
            continue
        for b in sorted(targets):
            lb = _layer(b)
            if lb is None or LAYERS.index(lb) < LAYERS.index(la):
                out.append(f"{a} -> {b}")
    return out


def _export_rank(module: str) -> tuple[str, float] | None:
    parts = module.split(".")
    if _layer(module) != "embroact.export":
        return None
    if len(parts) > 2 and parts[2] in EXPORT_RANKS:
        return parts[2], EXPORT_RANKS[parts[2]]
    return parts[2] if len(parts) > 2 else "", max(EXPORT_RANKS.values()) + 1.0


def export_direction_violations(graph: dict[str, set[str]]) -> list[str]:
    """``a -> b`` for every import of an export sub-package by one of the same or lower rank (but itself)."""
    out = []
    for a, targets in sorted(graph.items()):
        ra = _export_rank(a)
        if ra is None:
            continue
        for b in sorted(targets):
            rb = _export_rank(b)
            if rb is not None and rb[0] != ra[0] and rb[1] >= ra[1]:
                out.append(f"{a} -> {b}")
    return out


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Import cycles inside each layer (strongly connected components of more than one module), sorted.

    Package ``__init__`` modules that only re-export (lazily) are left out as targets: importing
    ``embroact.patterns.x`` runs ``embroact.patterns`` first by Python's rules, not by choice.
    """
    packages = {m for m in graph if any(o.startswith(m + ".") for o in graph)}
    edges = {a: {b for b in bs if b not in packages and _layer(a) == _layer(b)} for a, bs in graph.items()}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    found: list[list[str]] = []

    def strong(v: str) -> None:  # Tarjan, iterative enough for a package of ~150 modules
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1 and frozenset(comp) not in CYCLE_EXEMPT:
                found.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            strong(v)
    return sorted(found)
