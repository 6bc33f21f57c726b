"""Tube paths from SVG drawings (Inkscape's included): ``FILE.svg#name`` -> points in mm.

A reference ``drawing.svg#tube1`` names a file and, after ``#``, one drawn path: the
element whose ``id`` is ``tube1``; else the one whose Inkscape label
(``inkscape:label``, the name in Inkscape's Objects panel) is ``tube1``; a group or layer
so named must hold exactly one path. Without ``#name`` the drawing must hold exactly one
path. Every shape counts as a path (``path``, ``line``, ``polyline``, ...), read as Inkscape
draws it:

* hidden ones (``display:none``: a hidden Inkscape layer or object) do not count; locked
  layers (``sodipodi:insensitive``) are drawn, so they count;
* clones (``<use>``, Edit > Clone) are followed with their transforms, a clone of a group
  and a clone of a clone included; a clone is named by its own id or label (the copy it
  draws keeps the original's id, which names the original only). Clones are counted
  first and bounded (:mod:`embroact.export.files.svgclones`);
* Ink/Stitch commands are no tubes: their symbols (``<use>`` of ``#inkstitch_*``) and
  connector lines (paths with ``inkscape:connection-start`` / ``-end`` /
  ``connector-type``) are left out; Ink/Stitch's origin command marks the machine origin
  (:func:`svg_origin_mm`), as does a shape with id or label ``embroact-origin``;
* malformed path data is refused naming the element and the character offset
  (:func:`embroact.patterns.svgpath.check_d`), where a renderer would draw up to the error.

The drawing is read with svgelements in its real units: the document's ``width`` /
``height`` units and ``viewBox`` and every transform (layers, nested groups, the path's
own) are applied, user units without a unit are CSS px (96 per inch), and the points come
out in mm in the drawing's own frame: origin at the page's top-left corner, **y down**.
(svgelements converts mm and cm with 1/25.4 rounded to 0.0393701; its ``ppi`` is set so
that mm, cm and px are exact, which leaves inches 5.4e-7 too short: 0.16 um on an A4 page.)
That is the frame of ``embroact check FILE --tube-path`` (an embroidery file's frame);
:func:`svg_centerline` flips y into the plan frame (y up) for designs and the quick
commands, exactly as a path ``d`` string is flipped. Curves are flattened by
:mod:`embroact.patterns.svgpath` in the path's own coordinates and the points then mapped
through the whole transform, so an elliptical arc under a non-uniform scale or a skew stays
exact (subpaths joined when each starts where the last ended). Lengths and points agree with
Inkscape 1.2 to 0.01 mm (tests/test_svg_inkscape.py); a polyline is shorter than its curve
by about L h / (3 r) (h = ``curve_flatness_mm``, 0.005 mm): 0.006 mm over 100 mm at r = 30 mm.

Examples
--------
>>> import os, tempfile
>>> from embroact.export.files.svgfile import read_svg_path, svg_centerline
>>> path = os.path.join(tempfile.mkdtemp(), "d.svg")
>>> with open(path, "w") as fh:
...     _ = fh.write('<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="50mm" '
...                  'viewBox="0 0 200 100"><g transform="translate(10,0)">'
...                  '<path id="tube1" d="M 0 20 H 100"/></g></svg>')
>>> read_svg_path(path + "#tube1").points_mm.round(4).tolist()   # 2 user units per mm; y down
[[5.0, 10.0], [55.0, 10.0]]
>>> svg_centerline(path).points_mm.round(4).tolist()              # plan frame, y up
[[5.0, -10.0], [55.0, -10.0]]
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ...patterns.base.arrays import frozen_array
from ...patterns.base.errors import PathError
from ...patterns.base.validate import PATH_SEGMENTS, TEXT_FILE_BYTES, read_input, shown
from ...patterns.centerline import Centerline

if TYPE_CHECKING:
    import svgelements

__all__ = ["SvgPath", "is_svg_ref", "split_ref", "read_svg_path", "svg_centerline", "svg_origin_mm", "ORIGIN_MARKER"]

#: CSS px per inch: the unit of user coordinates without a unit (SVG 1.1, CSS 2.1).
PX_PER_INCH = 96.0
MM_PER_PX = 25.4 / PX_PER_INCH
#: The ``ppi`` handed to svgelements: it converts mm as ``mm * ppi * 0.0393701``, so this
#: value makes 1 mm exactly 96 / 25.4 px.
_SVGELEMENTS_PPI = PX_PER_INCH / (25.4 * 0.0393701)
_LABEL = "{http://www.inkscape.org/namespaces/inkscape}label"
_GROUPMODE = "{http://www.inkscape.org/namespaces/inkscape}groupmode"
_XLINK_HREF = "{http://www.w3.org/1999/xlink}href"
#: Attributes of an Inkscape connector (Ink/Stitch draws one from a command symbol to its object).
_CONNECTOR_KEYS = tuple("{http://www.inkscape.org/namespaces/inkscape}" + k
                        for k in ("connection-start", "connection-end", "connector-type"))
#: Ink/Stitch's command symbols are ``<use>`` of ``#inkstitch_<command>``.
_INKSTITCH_SYMBOL = "#inkstitch_"
#: id or Inkscape label of a shape marking the machine origin (its bounding-box centre).
ORIGIN_MARKER = "embroact-origin"


@dataclass(frozen=True, slots=True, eq=False)
class SvgPath:
    """One path read from a drawing.

    Attributes
    ----------
    file : str
        The SVG file as given (resolved against ``base_dir``).
    element_id : str or None
        The path element's ``id``.
    label : str or None
        Its Inkscape label.
    layer : str or None
        The label (or id) of the innermost Inkscape layer holding it.
    points_mm : ndarray, shape (n, 2)
        Flattened points [mm], drawing frame (page top-left, y down), read-only.

    Examples
    --------
    >>> import numpy as np
    >>> SvgPath("a.svg", "tube1", "Tube 1", "Layer 1", np.array([[0.0, 0.0], [10.0, 0.0]]))
    SvgPath(file='a.svg', element_id='tube1', layer='Layer 1', n_points=2)
    """

    file: str
    element_id: str | None
    label: str | None
    layer: str | None
    points_mm: np.ndarray

    def __repr__(self) -> str:
        return (f"SvgPath(file={self.file!r}, element_id={self.element_id!r}, layer={self.layer!r}, "
                f"n_points={len(self.points_mm)})")


@dataclass(frozen=True, slots=True)
class _Found:
    shape: Any
    element_id: str | None
    label: str | None
    layer: str | None
    groups: tuple[tuple[str | None, str | None], ...]  # (id, label) of every enclosing group or clone
    in_clone: bool  # drawn by a clone (<use>): found by the clone's id or label, not the original's


def is_svg_ref(text: object) -> bool:
    """True if ``text`` names an SVG file (``FILE.svg`` or ``FILE.svg#name``), not path data.

    Parameters
    ----------
    text : object
        A design file's ``path`` value or a ``--path`` / ``--tube-path`` argument.

    Returns
    -------
    bool

    Examples
    --------
    >>> is_svg_ref("drawing.svg#tube1"), is_svg_ref("Tubes.SVG"), is_svg_ref("M 0 0 L 10 0")
    (True, True, False)
    """
    return isinstance(text, str) and split_ref(text)[0].lower().endswith(".svg")


def split_ref(ref: str) -> tuple[str, str | None]:
    """``"drawing.svg#tube1"`` -> ``("drawing.svg", "tube1")``; no ``#``: name None.

    Parameters
    ----------
    ref : str
        ``FILE.svg`` or ``FILE.svg#name`` (the last ``#`` separates the name).

    Returns
    -------
    tuple of (str, str or None)

    Examples
    --------
    >>> split_ref("a/b.svg#tube 1"), split_ref("b.svg")
    (('a/b.svg', 'tube 1'), ('b.svg', None))
    """
    file, sep, name = ref.strip().rpartition("#")
    return (file, name) if sep else (ref.strip(), None)


def _attributes(e) -> dict:
    return e.values.get("attributes", {}) if hasattr(e, "values") else {}


def _href(own: dict) -> str:
    return (own.get(_XLINK_HREF) or own.get("href") or "").strip()


def _walk(group, layer: str | None, groups: tuple, clone: bool, marks: list) -> list[_Found]:
    """Drawn shapes under ``group``; origin markers (as matrices) appended to ``marks``."""
    import svgelements

    found = []
    for e in group:
        own = _attributes(e)
        if isinstance(e, svgelements.Use) and _href(own).startswith(_INKSTITCH_SYMBOL):
            if _href(own) == _INKSTITCH_SYMBOL + "origin":
                marks.append(("inkstitch_origin", e.transform.point_in_matrix_space((0.0, 0.0))))
            continue  # an Ink/Stitch command symbol: no tube
        if isinstance(e, (svgelements.Group, svgelements.Use)):
            is_layer = own.get(_GROUPMODE) == "layer"
            name = own.get(_LABEL) or e.id
            named = (None, None) if clone else (e.id, own.get(_LABEL))  # a clone's insides are copies: unnamed
            found += _walk(e, name if is_layer else layer, groups + (named,), clone or isinstance(e, svgelements.Use),
                           marks)
        elif isinstance(e, svgelements.Shape) and not isinstance(e, svgelements.Text):
            if any(key in own for key in _CONNECTOR_KEYS):
                continue  # an Ink/Stitch command's connector line (or any Inkscape connector)
            if ORIGIN_MARKER in (e.id, own.get(_LABEL)):
                box = e.bbox(transformed=True)
                if box is not None:
                    marks.append((ORIGIN_MARKER, svgelements.Point((box[0] + box[2]) / 2, (box[1] + box[3]) / 2)))
                continue
            found.append(_Found(e, e.id, own.get(_LABEL), layer, groups, clone))
    return found


def _describe(f: _Found) -> str:
    bits = [f"label {f.label!r}"] if f.label else []
    bits += [f"layer {f.layer!r}"] if f.layer else []
    return f"{f.element_id or '(no id)'}" + (f" ({', '.join(bits)})" if bits else "")


def _choose(found: list[_Found], name: str | None, file: str) -> _Found:
    listing = "; paths: " + (", ".join(_describe(f) for f in found[:12]) + (" ..." if len(found) > 12 else "")
                             if found else "none")
    if name is None:
        if len(found) != 1:
            raise PathError(f"{file}: holds {len(found)} visible paths, name one with {file}#ID (id or label){listing}")
        return found[0]
    for key in ("id", "label"):
        own = [f for f in found if not f.in_clone and (f.element_id if key == "id" else f.label) == name]
        inside = [f for f in found if any((g[0] if key == "id" else g[1]) == name for g in f.groups)]
        if len(own) + len(inside) == 0:
            continue
        if len(own) == 1 and not inside:
            return own[0]
        if not own and len(inside) == 1:
            return inside[0]
        what = "paths" if own else "paths in the group or layer"
        many = ", ".join(_describe(f) for f in (own or inside)[:12])
        raise PathError(f"{file}#{name}: {len(own) or len(inside)} {what} with {key} {name!r} ({many}); "
                        f"a tube is one path: name a single path by its id")
    raise PathError(f"{file}#{name}: no visible path, group or layer with id or label {name!r}{listing}")


def _check_root(svg, data: bytes, p: Path) -> None:
    """Refuse a document whose root is no ``<svg>`` (an HTML page, an ``svg`` in another namespace).

    svgelements reads any XML, and hands back a plain element for a root it does not know.
    """
    import svgelements

    if isinstance(svg, svgelements.SVG):
        return
    import io
    import xml.etree.ElementTree as ET

    try:  # the XML parsed already: its first start tag is the root's
        tag = next(ET.iterparse(io.BytesIO(data), events=("start",)))[1].tag
    except (ET.ParseError, StopIteration):
        tag = "?"
    raise PathError(f"{p}: not an SVG drawing: the root element is {shown(tag)}, expected "
                    f"'{{http://www.w3.org/2000/svg}}svg' (an SVG file saved by a drawing program)")


def read_svg_path(ref: str | os.PathLike, *, base_dir: str | os.PathLike | None = None) -> SvgPath:
    """Read one tube path from an SVG drawing, in mm, the drawing's frame (y down).

    Parameters
    ----------
    ref : str or os.PathLike
        ``FILE.svg`` (the drawing's only path) or ``FILE.svg#name`` (id, label, or the
        group / layer holding one path).
    base_dir : str or os.PathLike, optional
        Directory a relative ``FILE`` is resolved against (a design file's folder);
        default: the working directory.

    Returns
    -------
    SvgPath
        The chosen path's id, label, layer and flattened points [mm].

    Raises
    ------
    PathError
        One line naming the file: cannot read, not SVG, no such path (listing the paths it
        holds), several candidates, or a path that is no single open tube.

    Examples
    --------
    >>> read_svg_path("missing.svg#t1")
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.PathError: missing.svg: cannot read SVG file: No such file or directory
    """
    from ...patterns.svgpath import check_d, flatten

    drawing = _read_drawing(ref, base_dir)
    found = _choose(drawing.found, drawing.name, drawing.file)
    try:
        d = _attributes(found.shape).get("d")
        if d is not None:
            try:
                check_d(d)
            except PathError as exc:
                raise PathError(f"path data d: {exc}") from None
        pts = flatten(_untransformed(found.shape), _mm_matrix(found.shape))
    except PathError as exc:
        raise PathError(f"{drawing.file}#{found.element_id or drawing.name}: {exc}") from None
    return SvgPath(drawing.file, found.element_id, found.label, found.layer, frozen_array(pts + 0.0))


def svg_origin_mm(ref: str | os.PathLike, *, base_dir: str | os.PathLike | None = None) -> tuple[float, float] | None:
    """The machine origin a drawing marks [mm, drawing frame, y down], or None without a marker.

    A marker is Ink/Stitch's origin command (a ``<use>`` of its ``inkstitch_origin``
    symbol: the point it is placed at) or a shape whose id or Inkscape label is
    ``embroact-origin`` (its bounding-box centre: draw a small circle or cross).

    Parameters
    ----------
    ref : str or os.PathLike
        ``FILE.svg`` (a ``#name`` after it is ignored).
    base_dir : str or os.PathLike, optional
        Directory a relative ``FILE`` is resolved against.

    Returns
    -------
    tuple of float or None

    Raises
    ------
    PathError
        As :func:`read_svg_path`, or for a drawing with more than one marker.

    Examples
    --------
    >>> svg_origin_mm("missing.svg")
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.PathError: missing.svg: cannot read SVG file: No such file or directory
    """
    drawing = _read_drawing(ref, base_dir)
    if not drawing.marks:
        return None
    if len(drawing.marks) > 1:
        raise PathError(f"{drawing.file}: {len(drawing.marks)} origin markers ({', '.join(m[0] for m in drawing.marks)}); "
                        "mark the machine origin once")
    point = drawing.marks[0][1]
    return (float(point.x) * MM_PER_PX + 0.0, float(point.y) * MM_PER_PX + 0.0)


@dataclass(frozen=True, slots=True)
class _Drawing:
    file: str
    name: str | None
    found: list
    marks: list


def _read_drawing(ref: str | os.PathLike, base_dir) -> _Drawing:
    """Parse the drawing ``ref`` names (clones checked first): its shapes and origin markers."""
    import io

    import svgelements

    from .svgclones import check_clones

    file, name = split_ref(os.fspath(ref))
    p = Path(file) if base_dir is None else Path(base_dir) / file
    data = read_input(p, TEXT_FILE_BYTES, "SVG file", error=PathError)
    check_clones(data, str(p))
    try:
        svg = svgelements.SVG.parse(io.BytesIO(data), ppi=_SVGELEMENTS_PPI, reify=False)
    except Exception as exc:  # svgelements raises whatever its XML parser or number parsing raises
        raise PathError(f"{p}: not a readable SVG file ({type(exc).__name__}: {str(exc)[:80]})") from None
    _check_root(svg, data, p)
    marks: list = []
    found = _walk(svg, None, (), False, marks)
    return _Drawing(str(p), name, found, marks)


def _untransformed(shape) -> "svgelements.Path":
    """The shape as a path in its own coordinates (its transform left out)."""
    import svgelements

    path = svgelements.Path(shape)
    if len(path) > PATH_SEGMENTS:
        raise PathError(f"SVG path must have at most {PATH_SEGMENTS:,} segments, got {len(path):,}")
    path.transform = svgelements.Matrix()
    return path


def _mm_matrix(shape) -> tuple[float, float, float, float, float, float]:
    """The shape's whole transform (document units, layers, groups, clones, its own) to mm."""
    m, k = shape.transform, MM_PER_PX
    return (float(m.a) * k, float(m.b) * k, float(m.c) * k, float(m.d) * k, float(m.e) * k, float(m.f) * k)


def svg_centerline(ref: str | os.PathLike, *, base_dir: str | os.PathLike | None = None) -> Centerline:
    """The tube path ``ref`` names, as a :class:`Centerline` in the plan frame (y up).

    Parameters
    ----------
    ref : str or os.PathLike
        ``FILE.svg`` or ``FILE.svg#name``, as for :func:`read_svg_path`.
    base_dir : str or os.PathLike, optional
        Directory a relative ``FILE`` is resolved against.

    Returns
    -------
    Centerline
        The drawn path in mm, y flipped (SVG y down -> plan y up).

    Raises
    ------
    PathError
        As :func:`read_svg_path`, and for a path that is no valid tube (closed, crossing
        itself), prefixed with the file and element.

    Examples
    --------
    >>> svg_centerline("missing.svg")
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.PathError: missing.svg: cannot read SVG file: No such file or directory
    """
    from ...patterns.svgpath import to_plan

    found = read_svg_path(ref, base_dir=base_dir)
    try:
        return Centerline.from_points(to_plan(found.points_mm))
    except PathError as exc:
        raise PathError(f"{found.file}#{found.element_id or split_ref(os.fspath(ref))[1]}: {exc}") from None
