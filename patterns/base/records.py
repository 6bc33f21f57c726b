"""A quicker ``__init__`` for the frozen dataclasses a first curve builds.

A frozen dataclass writes each field through ``object.__setattr__``, looked up by name per field, and a first
one-pressure curve builds five such values (the geometry, the rates, the lean table, the branch and the curve).
:func:`quick_init` gives such a class (frozen, with slots) an ``__init__`` with the same signature, defaults and
``__post_init__`` call that sets each slot through its descriptor instead, which is quicker; the instances stay
frozen.

Examples
--------
>>> from dataclasses import FrozenInstanceError, dataclass
>>> from embroact.patterns.base.records import quick_init
>>> @quick_init
... @dataclass(frozen=True, slots=True)
... class Point:
...     x: float
...     y: float = 0.0
>>> p = Point(1.0)
>>> p, p == Point(1.0, y=0.0)
(Point(x=1.0, y=0.0), True)
>>> try:
...     p.x = 2.0
... except FrozenInstanceError:
...     print("frozen")
frozen
"""
from __future__ import annotations

import dataclasses

__all__ = ["quick_init"]


def quick_init(cls):
    """Give the frozen slots dataclass ``cls`` the quicker ``__init__`` (module docstring).

    Parameters
    ----------
    cls : type
        A ``@dataclass(frozen=True, slots=True)`` class whose fields all take part in ``__init__`` by position, none
        with a default factory.

    Returns
    -------
    type
        ``cls``, its ``__init__`` replaced.

    Raises
    ------
    TypeError
        ``cls`` is not such a class.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> quick_init(dataclass(frozen=True, slots=True)(type("Pair", (), {"__annotations__": {"a": int}})))(3)
    Pair(a=3)
    """
    params = getattr(cls, "__dataclass_params__", None)
    fields = dataclasses.fields(cls) if params is not None else ()
    if not (params is not None and params.frozen and "__slots__" in cls.__dict__
            and all(f.init and f.kw_only is not True and f.default_factory is dataclasses.MISSING for f in fields)):
        raise TypeError(f"quick_init takes a frozen dataclass with slots and plain fields, got {cls.__name__}")
    names = [f.name for f in fields]
    scope = {f"_set_{n}": cls.__dict__[n].__set__ for n in names}
    scope.update({f"_default_{f.name}": f.default for f in fields if f.default is not dataclasses.MISSING})
    signature = ", ".join(n if f"_default_{n}" not in scope else f"{n}=_default_{n}" for n in names)
    body = "".join(f"    _set_{n}(self, {n})\n" for n in names)
    if hasattr(cls, "__post_init__"):
        body += "    self.__post_init__()\n"
    exec(f"def __init__(self, {signature}):\n{body}", scope)  # noqa: S102 - names from the class's own fields
    init = scope["__init__"]
    init.__qualname__, init.__module__ = f"{cls.__qualname__}.__init__", cls.__module__
    cls.__init__ = init
    return cls
