"""Package-level names that load their module on first use (PEP 562).

A package ``__init__`` lists ``name -> submodule`` and gets ``__getattr__`` and
``__dir__`` from :func:`lazy_exports`, so importing one small module of the package
(``embroact.patterns.base.errors``) does not load numpy, shapely and every generator.

Examples
--------
>>> from embroact.patterns.base.lazy import lazy_exports
>>> getattr_, dir_ = lazy_exports("embroact.patterns", {"Tube": "params"})
>>> getattr_("Tube").__name__
'Tube'
"""
from __future__ import annotations

import importlib

__all__ = ["lazy_exports"]


def lazy_exports(package: str, exports: dict[str, str]):
    """``(__getattr__, __dir__)`` for ``package`` resolving ``exports`` (name -> submodule)."""

    def __getattr__(name: str):
        if name in exports:
            return getattr(importlib.import_module(f"{package}.{exports[name]}"), name)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__():
        return sorted(set(vars(importlib.import_module(package))) | set(exports))

    return __getattr__, __dir__
