"""SVG documents on the standard library's ElementTree: the few shapes the pictures draw.

A picture makes a :class:`Drawing`, adds the elements its factory methods make (``rect``,
``circle``, ``line``, ``polyline``, ``polygon``, ``path``, ``text``, ``g``, ``clipPath``)
and takes the text with ``tostring()``. Calls and text are those of svgwrite's
``Drawing(profile="full", debug=False)``, which the pictures were first drawn with:
keyword names take ``_`` for ``-`` (``stroke_width``; a trailing ``_`` is dropped, for
``class_``), values are written with ``str``, ``None`` and empty values are left out,
attributes are written in name order and the document starts with an empty ``<defs />``.
ElementTree (which svgwrite also serialises with) escapes and writes the text. svgwrite
itself is not imported: its package loads ``urllib.request`` (http, ssl, email) and
compiles its validation tables on import, whatever the profile or debug setting, about
40 ms of every build.

Examples
--------
>>> from embroact.export.pictures.svgdoc import Drawing
>>> dwg = Drawing(size=("20mm", "10mm"), viewBox="0 0 20 10")
>>> g = dwg.add(dwg.g(id="marks", stroke_width=0.5))
>>> _ = g.add(dwg.circle((5, 5), 1.5, fill="#c51b7d"))
>>> _ = g.add(dwg.text("A & B", insert=(8, 6), font_size=3))
>>> print(dwg.tostring())  # doctest: +NORMALIZE_WHITESPACE
<svg baseProfile="full" height="10mm" version="1.1" viewBox="0 0 20 10" width="20mm"
 xmlns="http://www.w3.org/2000/svg" xmlns:ev="http://www.w3.org/2001/xml-events"
 xmlns:xlink="http://www.w3.org/1999/xlink"><defs /><g id="marks" stroke-width="0.5"><circle cx="5" cy="5"
 fill="#c51b7d" r="1.5" /><text font-size="3" x="8" y="6">A &amp; B</text></g></svg>
"""
from __future__ import annotations

import xml.etree.ElementTree as ET

__all__ = ["Element", "Drawing", "INKSCAPE", "layer", "svg_id"]

#: Attribute of an ``<svg>`` declaring Inkscape's namespace: ``Drawing(size, **INKSCAPE)``.
INKSCAPE = {"xmlns:inkscape": "http://www.inkscape.org/namespaces/inkscape"}


def layer(name: str) -> dict[str, str]:
    """Attributes of a group that Inkscape shows as a layer named ``name`` (its id too):
    ``dwg.g(**layer("tubes"))`` in a drawing made with ``**INKSCAPE``; other readers see a plain ``<g>``.

    >>> layer("tubes")
    {'id': 'tubes', 'inkscape:groupmode': 'layer', 'inkscape:label': 'tubes'}
    """
    return {"id": name, "inkscape:groupmode": "layer", "inkscape:label": name}


def svg_id(text: str) -> str:
    """``text`` as an XML id (letters, digits, ``-``, ``_``, ``.``; others become ``_``).

    >>> svg_id("S-curve 2"), svg_id("1st")
    ('S-curve_2', '_1st')
    """
    out = "".join(c if c.isascii() and (c.isalnum() or c in "-_.") else "_" for c in text)
    return out if out[:1].isalpha() or out[:1] == "_" else "_" + out

_NAMESPACES = {"xmlns": "http://www.w3.org/2000/svg", "xmlns:xlink": "http://www.w3.org/1999/xlink",
               "xmlns:ev": "http://www.w3.org/2001/xml-events"}


def _attributes(extra: dict) -> dict[str, str]:
    """SVG attributes from keyword arguments: names with ``-`` for ``_``, values as text, in name order."""
    out = {}
    for key, value in extra.items():
        text = "" if value is None else str(value)
        if text:
            out[key.rstrip("_").replace("_", "-")] = text
    return dict(sorted(out.items()))


def _points(points) -> str:
    return " ".join(f"{x},{y}" for x, y in points)


class Element(ET.Element):
    """An ElementTree element that can add children and write itself."""

    def add(self, element: Element) -> Element:
        """Append ``element`` as the last child and return it."""
        self.append(element)
        return element

    def set_desc(self, title: str) -> None:
        """Insert a ``<title>`` (a tooltip in browsers) as the first child."""
        self.insert(0, _element("title", {}, title))

    def tostring(self) -> str:
        """The element and its children as SVG text."""
        return ET.tostring(self, encoding="unicode")


def _element(tag: str, extra: dict, text: str | None = None) -> Element:
    el = Element(tag, _attributes(extra))
    if text is not None:
        el.text = text
    return el


class Drawing:
    """An ``<svg>`` document of ``size`` (width, height, with units) and the shapes' factory.

    Parameters
    ----------
    size : (str, str)
        Width and height as written (``"120mm"``, ``"480"``).
    **extra
        Further attributes of ``<svg>`` (``viewBox``).
    """

    def __init__(self, size, **extra) -> None:
        width, height = size
        self.root = _element("svg", {**extra, "width": width, "height": height, **_NAMESPACES, "baseProfile": "full",
                                     "version": "1.1"})
        self.defs = self.root.add(_element("defs", {}))

    def add(self, element: Element) -> Element:
        """Append ``element`` to the document and return it."""
        return self.root.add(element)

    def tostring(self) -> str:
        """The document as SVG text."""
        return self.root.tostring()

    def g(self, **extra) -> Element:
        return _element("g", extra)

    def clipPath(self, **extra) -> Element:  # noqa: N802  (the SVG element's name)
        return _element("clipPath", extra)

    def rect(self, insert, size, **extra) -> Element:
        return _element("rect", {**extra, "x": insert[0], "y": insert[1], "width": size[0], "height": size[1]})

    def circle(self, center, r, **extra) -> Element:
        return _element("circle", {**extra, "cx": center[0], "cy": center[1], "r": r})

    def line(self, start, end, **extra) -> Element:
        return _element("line", {**extra, "x1": start[0], "y1": start[1], "x2": end[0], "y2": end[1]})

    def polyline(self, points, **extra) -> Element:
        return _element("polyline", {**extra, "points": _points(points)})

    def polygon(self, points, **extra) -> Element:
        return _element("polygon", {**extra, "points": _points(points)})

    def path(self, d: str, **extra) -> Element:
        return _element("path", {**extra, "d": d})

    def text(self, text: str, insert, **extra) -> Element:
        return _element("text", {**extra, "x": insert[0], "y": insert[1]}, str(text))
