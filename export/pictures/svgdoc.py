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

    Parameters
    ----------
    name : str
        The layer's name (an XML id, :func:`svg_id`).

    Returns
    -------
    dict of str to str

    Examples
    --------
    >>> layer("tubes")
    {'id': 'tubes', 'inkscape:groupmode': 'layer', 'inkscape:label': 'tubes'}
    """
    return {"id": name, "inkscape:groupmode": "layer", "inkscape:label": name}


def svg_id(text: str) -> str:
    """``text`` as an XML id (letters, digits, ``-``, ``_``, ``.``; others become ``_``).

    Parameters
    ----------
    text : str
        Any name.

    Returns
    -------
    str
        Starting with a letter or ``_``.

    Examples
    --------
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
    """An ElementTree element that can add children and write itself.

    Examples
    --------
    >>> dwg = Drawing(size=("10mm", "10mm"))
    >>> g = dwg.g(id="marks")
    >>> _ = g.add(dwg.circle((0, 0), 1))
    >>> g.tostring()
    '<g id="marks"><circle cx="0" cy="0" r="1" /></g>'
    """

    def add(self, element: Element) -> Element:
        """Append ``element`` as the last child and return it.

        Parameters
        ----------
        element : Element
            The child.

        Returns
        -------
        Element
            ``element``.

        Examples
        --------
        >>> dwg = Drawing(size=("10mm", "10mm"))
        >>> g = dwg.g()
        >>> g.add(dwg.circle((0, 0), 1)) is g[0]
        True
        """
        self.append(element)
        return element

    @property
    def attribs(self) -> dict:
        """The element's attributes (svgwrite's name for them): the live dict, so setting a key sets it.

        Examples
        --------
        >>> c = Drawing(size=("10mm", "10mm")).circle((0, 0), 1)
        >>> c.attribs["fill"] = "red"
        >>> c.tostring()
        '<circle cx="0" cy="0" r="1" fill="red" />'
        """
        return self.attrib

    def update(self, attribs: dict) -> None:
        """Set attributes (svgwrite's ``update``), written in name order as every element's are.

        Parameters
        ----------
        attribs : dict
            Names (``_`` for ``-``) and values.

        Examples
        --------
        >>> g = Drawing(size=("10mm", "10mm")).g(id="legs")
        >>> g.update({"fill": "none"})
        >>> g.tostring()
        '<g fill="none" id="legs" />'
        """
        merged = {**self.attrib, **_attributes(attribs)}
        self.attrib.clear()
        self.attrib.update(sorted(merged.items()))

    @property
    def elements(self) -> list:
        """The children, in order (svgwrite's name for them).

        Examples
        --------
        >>> dwg = Drawing(size=("10mm", "10mm"))
        >>> g = dwg.g()
        >>> g.add(dwg.circle((0, 0), 1)) is g.elements[0]
        True
        """
        return list(self)

    def set_desc(self, title: str) -> None:
        """Insert a ``<title>`` (a tooltip in browsers) as the first child.

        Parameters
        ----------
        title : str
            The tooltip.

        Examples
        --------
        >>> dwg = Drawing(size=("10mm", "10mm"))
        >>> g = dwg.g()
        >>> _ = g.add(dwg.circle((0, 0), 1))
        >>> g.set_desc("needle point 7")
        >>> g.tostring()
        '<g><title>needle point 7</title><circle cx="0" cy="0" r="1" /></g>'
        """
        self.insert(0, _element("title", {}, title))

    def tostring(self) -> str:
        """The element and its children as SVG text.

        Returns
        -------
        str

        Examples
        --------
        >>> Drawing(size=("10mm", "10mm")).path("M 0 0 L 3 4").tostring()
        '<path d="M 0 0 L 3 4" />'
        """
        return ET.tostring(self, encoding="unicode")


def _element(tag: str, extra: dict, text: str | None = None) -> Element:
    el = Element(tag, _attributes(extra))
    if text is not None:
        el.text = text
    return el


class Drawing:
    """An ``<svg>`` document of ``size`` (width, height, with units) and the shapes' factory.

    Each factory method (:meth:`g`, :meth:`clipPath`, :meth:`rect`, :meth:`circle`, :meth:`line`,
    :meth:`polyline`, :meth:`polygon`, :meth:`path`, :meth:`text`) makes one element; its
    ``**extra`` keywords are attributes (``_`` for ``-``, a trailing ``_`` dropped, None left out).

    Parameters
    ----------
    size : (str, str)
        Width and height as written (``"120mm"``, ``"480"``).
    **extra
        Further attributes of ``<svg>`` (``viewBox``).

    Examples
    --------
    >>> dwg = Drawing(size=("20mm", "10mm"), viewBox="0 0 20 10")
    >>> _ = dwg.add(dwg.rect((0, 0), (4, 2), fill="red"))
    >>> dwg.tostring().endswith('<defs /><rect fill="red" height="2" width="4" x="0" y="0" /></svg>')
    True
    """

    def __init__(self, size, **extra) -> None:
        width, height = size
        self.root = _element("svg", {**extra, "width": width, "height": height, **_NAMESPACES, "baseProfile": "full",
                                     "version": "1.1"})
        self.defs = self.root.add(_element("defs", {}))

    def add(self, element: Element) -> Element:
        """Append ``element`` to the document and return it.

        Parameters
        ----------
        element : Element
            A top-level element.

        Returns
        -------
        Element
            ``element``.

        Examples
        --------
        >>> dwg = Drawing(size=("20mm", "10mm"))
        >>> dwg.add(dwg.g(id="z")).tostring()
        '<g id="z" />'
        """
        return self.root.add(element)

    def tostring(self) -> str:
        """The document as SVG text.

        Returns
        -------
        str

        Examples
        --------
        >>> dwg = Drawing(size=("20mm", "10mm"))
        >>> dwg.tostring()[:40]
        '<svg baseProfile="full" height="10mm" ve'
        """
        return self.root.tostring()

    def g(self, **extra) -> Element:
        """A group ``<g>``.

        Parameters
        ----------
        **extra
            Attributes (``stroke_width`` for ``stroke-width``, ``class_`` for ``class``).

        Returns
        -------
        Element

        Examples
        --------
        >>> dwg = Drawing(size=("20mm", "10mm"))
        >>> dwg.g(id="a", stroke_width=0.5).tostring()
        '<g id="a" stroke-width="0.5" />'
        """
        return _element("g", extra)

    def clipPath(self, **extra) -> Element:  # noqa: N802  (the SVG element's name)
        """A ``<clipPath>`` (its children clip what names it).

        Parameters
        ----------
        **extra
            Attributes (``stroke_width`` for ``stroke-width``, ``class_`` for ``class``).

        Returns
        -------
        Element

        Examples
        --------
        >>> dwg = Drawing(size=("20mm", "10mm"))
        >>> dwg.clipPath(id="c").tostring()
        '<clipPath id="c" />'
        """
        return _element("clipPath", extra)

    def rect(self, insert, size, **extra) -> Element:
        """A rectangle ``<rect>``.

        Parameters
        ----------
        insert : (float, float)
            Top-left corner.
        size : (float, float)
            Width and height.
        **extra
            Attributes (``stroke_width`` for ``stroke-width``, ``class_`` for ``class``).

        Returns
        -------
        Element

        Examples
        --------
        >>> dwg = Drawing(size=("20mm", "10mm"))
        >>> dwg.rect((0, 0), (4, 2), fill="red").tostring()
        '<rect fill="red" height="2" width="4" x="0" y="0" />'
        """
        return _element("rect", {**extra, "x": insert[0], "y": insert[1], "width": size[0], "height": size[1]})

    def circle(self, center, r, **extra) -> Element:
        """A circle ``<circle>``.

        Parameters
        ----------
        center : (float, float)
            Centre.
        r : float
            Radius.
        **extra
            Attributes (``stroke_width`` for ``stroke-width``, ``class_`` for ``class``).

        Returns
        -------
        Element

        Examples
        --------
        >>> dwg = Drawing(size=("20mm", "10mm"))
        >>> dwg.circle((5, 5), 1.5).tostring()
        '<circle cx="5" cy="5" r="1.5" />'
        """
        return _element("circle", {**extra, "cx": center[0], "cy": center[1], "r": r})

    def line(self, start, end, **extra) -> Element:
        """A straight line ``<line>``.

        Parameters
        ----------
        start, end : (float, float)
            End points.
        **extra
            Attributes (``stroke_width`` for ``stroke-width``, ``class_`` for ``class``).

        Returns
        -------
        Element

        Examples
        --------
        >>> dwg = Drawing(size=("20mm", "10mm"))
        >>> dwg.line((0, 0), (3, 4), stroke="black").tostring()
        '<line stroke="black" x1="0" x2="3" y1="0" y2="4" />'
        """
        return _element("line", {**extra, "x1": start[0], "y1": start[1], "x2": end[0], "y2": end[1]})

    def polyline(self, points, **extra) -> Element:
        """An open polyline ``<polyline>``.

        Parameters
        ----------
        points : iterable of (float, float)
            Vertices.
        **extra
            Attributes (``stroke_width`` for ``stroke-width``, ``class_`` for ``class``).

        Returns
        -------
        Element

        Examples
        --------
        >>> dwg = Drawing(size=("20mm", "10mm"))
        >>> dwg.polyline([(0, 0), (1, 2)], fill="none").tostring()
        '<polyline fill="none" points="0,0 1,2" />'
        """
        return _element("polyline", {**extra, "points": _points(points)})

    def polygon(self, points, **extra) -> Element:
        """A closed polygon ``<polygon>``.

        Parameters
        ----------
        points : iterable of (float, float)
            Vertices.
        **extra
            Attributes (``stroke_width`` for ``stroke-width``, ``class_`` for ``class``).

        Returns
        -------
        Element

        Examples
        --------
        >>> dwg = Drawing(size=("20mm", "10mm"))
        >>> dwg.polygon([(0, 0), (1, 0), (0, 1)]).tostring()
        '<polygon points="0,0 1,0 0,1" />'
        """
        return _element("polygon", {**extra, "points": _points(points)})

    def path(self, d: str, **extra) -> Element:
        """A ``<path>``.

        Parameters
        ----------
        d : str
            Path data.
        **extra
            Attributes (``stroke_width`` for ``stroke-width``, ``class_`` for ``class``).

        Returns
        -------
        Element

        Examples
        --------
        >>> dwg = Drawing(size=("20mm", "10mm"))
        >>> dwg.path("M 0 0 L 3 4").tostring()
        '<path d="M 0 0 L 3 4" />'
        """
        return _element("path", {**extra, "d": d})

    def text(self, text: str, insert, **extra) -> Element:
        """A ``<text>``.

        Parameters
        ----------
        text : str
            The text (escaped when written).
        insert : (float, float)
            Its anchor.
        **extra
            Attributes (``stroke_width`` for ``stroke-width``, ``class_`` for ``class``).

        Returns
        -------
        Element

        Examples
        --------
        >>> dwg = Drawing(size=("20mm", "10mm"))
        >>> dwg.text("A & B", insert=(1, 2), font_size=3).tostring()
        '<text font-size="3" x="1" y="2">A &amp; B</text>'
        """
        return _element("text", {**extra, "x": insert[0], "y": insert[1]}, str(text))
