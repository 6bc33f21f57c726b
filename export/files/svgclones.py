"""Clones (``<use>``) in an SVG drawing, counted and bounded before the drawing is read.

Inkscape's clones (Edit > Clone) are ``<use>`` elements naming another element by
``href``; a reader draws the named element again under the clone's transform. A clone
may name a group holding clones, so a small file can name very many copies (or itself):
:func:`check_clones` counts what following every clone would draw, without drawing it,
and refuses a drawing whose clones nest deeper than :data:`MAX_CLONE_DEPTH`, would make
more than :data:`MAX_CLONES` copies of an element or more than :data:`MAX_CLONE_ELEMENTS`
elements in all, or name themselves.

Examples
--------
>>> from embroact.export.files.svgclones import check_clones
>>> svg = (b'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink">'
...        b'<path id="p" d="M 0 0 H 10"/><use xlink:href="#p"/><use href="#p"/></svg>')
>>> check_clones(svg, "d.svg")
2
>>> check_clones(b'<svg xmlns="http://www.w3.org/2000/svg"><g id="g"><use href="#g"/></g></svg>', "d.svg")
Traceback (most recent call last):
...
embroact.patterns.base.errors.PathError: d.svg: the clone (<use>) of '#g' names an element holding it: a clone cannot draw itself
"""
from __future__ import annotations

import xml.etree.ElementTree as ET

from ...patterns.base.errors import PathError

__all__ = ["check_clones", "MAX_CLONES", "MAX_CLONE_DEPTH", "MAX_CLONE_ELEMENTS"]

#: Most copies the clones of one drawing may make (a clone inside a cloned group counts once per copy).
MAX_CLONES = 10_000
#: Deepest chain of clones of clones.
MAX_CLONE_DEPTH = 16
#: Most elements a drawing may hold with every clone followed.
MAX_CLONE_ELEMENTS = 200_000
_HREFS = ("href", "{http://www.w3.org/1999/xlink}href")


def _href(el: ET.Element) -> str | None:
    for key in _HREFS:
        value = el.get(key)
        if value is not None:
            return value.strip()
    return None


def check_clones(data: bytes, file: str) -> int:
    """The number of copies following every clone of the drawing ``data`` makes (checked).

    Parameters
    ----------
    data : bytes
        The SVG file's bytes.
    file : str
        The file's name, for messages.

    Returns
    -------
    int
        Copies made by clones (0 without ``<use>``).

    Raises
    ------
    PathError
        One line naming the file: not XML, a clone of itself, or clones beyond the limits.

    Examples
    --------
    >>> svg = (b'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink">'
    ...        b'<path id="p" d="M0,0 L10,0"/><use xlink:href="#p"/><use xlink:href="#p"/></svg>')
    >>> check_clones(svg, "a.svg")
    2
    """
    try:
        root = ET.fromstring(data)
    except ET.ParseError as exc:
        raise PathError(f"{file}: not a readable SVG file (XML: {exc})") from None
    by_id = {el.get("id"): el for el in root.iter() if el.get("id") is not None}
    memo: dict[int, tuple[int, int, int]] = {}  # id(element) -> (clones, elements, depth) below it
    visiting: set[int] = set()

    def tally(el: ET.Element) -> tuple[int, int, int]:
        key = id(el)
        if key in memo:
            return memo[key]
        if key in visiting:
            raise PathError(f"{file}: the clone (<use>) of {_href(el)!r} names an element holding it: "
                            "a clone cannot draw itself")
        visiting.add(key)
        clones, elements, depth = 0, 1, 0
        for child in el:
            c, e, d = tally(child)
            clones, elements, depth = clones + c, elements + e, max(depth, d)
        ref = _href(el) if el.tag.rpartition("}")[2] == "use" else None
        target = by_id.get(ref[1:]) if ref and ref.startswith("#") else None
        if target is not None:
            if id(target) in visiting:
                raise PathError(f"{file}: the clone (<use>) of {ref!r} names an element holding it: "
                                "a clone cannot draw itself")
            c, e, d = tally(target)
            clones, elements, depth = clones + c + 1, elements + e, max(depth, d + 1)
        visiting.discard(key)
        if depth > MAX_CLONE_DEPTH:
            raise PathError(f"{file}: clones (<use>) nest {depth} deep (a clone of a clone ...); at most "
                            f"{MAX_CLONE_DEPTH} allowed")
        if clones > MAX_CLONES or elements > MAX_CLONE_ELEMENTS:
            raise PathError(f"{file}: following its clones (<use>) would draw more than {MAX_CLONES:,} copies or "
                            f"{MAX_CLONE_ELEMENTS:,} elements; at most that many allowed (Inkscape: Edit > Clone > "
                            "Unlink Clone on what need not be a clone)")
        memo[key] = (clones, elements, depth)
        return memo[key]

    try:
        return tally(root)[0]
    except RecursionError:
        raise PathError(f"{file}: elements nest too deeply to read") from None
