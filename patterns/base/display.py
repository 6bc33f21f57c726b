"""Rich display in Jupyter: value classes look their renderer up here, by type, on first use.

The value classes live in :mod:`embroact.patterns` and :mod:`embroact.predict`; the pictures
that show them are drawn by :mod:`embroact.export`, which those packages never import. So a
class only declares ``_repr_svg_ = repr_svg`` (or ``_repr_html_ = repr_html``), and the
top-level package ``embroact`` registers, on import, which ``"module:function"`` renders
each class. Importing a renderer is deferred until a notebook asks for a picture: nothing
here loads numpy, and importing any ``embroact`` module imports the top-level package first,
so the registrations are always in place.

A renderer that raises an :class:`~embroact.patterns.base.errors.EmbroactError` (a design
that cannot be generated, an actuator without a model) gives ``None``: the notebook then
shows the plain-text ``repr`` instead of a traceback.

Examples
--------
>>> from embroact.patterns.base.display import register, render, repr_svg
>>> class Box:
...     _repr_svg_ = repr_svg
...     def __repr__(self):
...         return '<svg xmlns="http://www.w3.org/2000/svg"/>'
>>> register(Box, "image/svg+xml", "builtins:repr")
>>> Box()._repr_svg_()
'<svg xmlns="http://www.w3.org/2000/svg"/>'
>>> render(Box(), "text/html") is None   # no HTML renderer registered for Box
True
"""
from __future__ import annotations

from importlib import import_module

from .errors import EmbroactError, ParameterError

TYPE_CHECKING = False
if TYPE_CHECKING:  # annotations only: importing typing is ~2 ms of `embroact --help`
    from typing import Any, Callable

__all__ = ["MIME_TYPES", "register", "renderer", "render", "repr_svg", "repr_html"]

#: The MIME types a renderer can be registered for.
MIME_TYPES = ("image/svg+xml", "text/html")

_RENDERERS: dict[tuple[str, str], str] = {}


def _key(cls: type | str) -> str:
    return cls if isinstance(cls, str) else f"{cls.__module__}.{cls.__qualname__}"


def register(cls: type | str, mime: str, target: str) -> None:
    """Name the function that renders instances of ``cls`` as ``mime``.

    Parameters
    ----------
    cls : type or str
        The class, or its dotted ``module.QualName`` (registering by name imports nothing).
    mime : str
        One of :data:`MIME_TYPES`.
    target : str
        ``"package.module:function"``; the function takes the instance and returns the text.

    Returns
    -------
    None

    Raises
    ------
    ParameterError
        An unknown MIME type or a target without ``:``.

    Examples
    --------
    >>> register("demo.Thing", "text/html", "html:escape")
    >>> renderer("demo.Thing", "text/html").__name__
    'escape'
    """
    if mime not in MIME_TYPES:
        raise ParameterError(f"mime must be one of {', '.join(MIME_TYPES)}, got {mime!r}")
    if target.count(":") != 1:
        raise ParameterError(f"target must be 'module:function', got {target!r}")
    _RENDERERS[(_key(cls), mime)] = target


def renderer(cls: type | str, mime: str) -> Callable[[Any], str] | None:
    """The function registered for ``cls`` and ``mime`` (imported now), or ``None``.

    Parameters
    ----------
    cls : type or str
        The class or its dotted name; a class without its own registration uses its bases'.
    mime : str
        One of :data:`MIME_TYPES`.

    Returns
    -------
    callable or None

    Examples
    --------
    >>> renderer(int, "image/svg+xml") is None
    True
    """
    names = [_key(c) for c in cls.__mro__] if isinstance(cls, type) else [cls]
    for name in names:
        target = _RENDERERS.get((name, mime))
        if target is not None:
            module, function = target.split(":")
            return getattr(import_module(module), function)
    return None


def render(obj: object, mime: str) -> str | None:
    """``obj`` rendered as ``mime`` by its registered function; ``None`` if none or it cannot be drawn.

    Parameters
    ----------
    obj : object
        The value to show.
    mime : str
        One of :data:`MIME_TYPES`.

    Returns
    -------
    str or None
        The SVG or HTML text; ``None`` when nothing is registered or the renderer raised an
        :class:`~embroact.patterns.base.errors.EmbroactError`.

    Examples
    --------
    >>> render(3, "text/html") is None
    True
    """
    function = renderer(type(obj), mime)
    if function is None:
        return None
    try:
        return function(obj)
    except EmbroactError:
        return None


def repr_svg(self: object) -> str | None:
    """``_repr_svg_`` of the value classes: :func:`render` as SVG.

    Parameters
    ----------
    self : object
        The instance (this function is used as a method).

    Returns
    -------
    str or None

    Examples
    --------
    >>> repr_svg(3) is None
    True
    """
    return render(self, "image/svg+xml")


def repr_html(self: object) -> str | None:
    """``_repr_html_`` of the value classes: :func:`render` as HTML.

    Parameters
    ----------
    self : object
        The instance (this function is used as a method).

    Returns
    -------
    str or None

    Examples
    --------
    >>> repr_html(3) is None
    True
    """
    return render(self, "text/html")

