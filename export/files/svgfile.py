"""Tube paths from SVG drawings (Inkscape's included): ``FILE.svg#name`` -> points in mm.

A reference ``drawing.svg#tube1`` names a file and, after ``#``, one drawn path: the
element whose ``id`` is ``tube1``; else the one whose Inkscape label
(``inkscape:label``, the name in Inkscape's Objects panel) is ``tube1``; a group or layer
so named must hold exactly one path. Without ``#name`` the drawing must hold exactly one
path. Every shape counts as a path (``path``, ``line``, ``polyline``, ...); hidden ones
(``display:none``) do not.

The drawing is read with svgelements in its real units: the document's ``width`` /
``height`` units and ``viewBox`` and every transform (layers, nested groups, the path's
own) are applied, user units without a unit are CSS px (96 per inch), and the points come
out in mm in the drawing's own frame: origin at the page's top-left corner, **y down**.
(svgelements converts mm and cm with 1/25.4 rounded to 0.0393701; its ``ppi`` is set so
that mm, cm and px are exact, which leaves inches 5.4e-7 too short: 0.16 um on an A4 page.)
That is the frame of ``embroact check FILE --tube-path`` (an embroidery file's frame);
:func:`svg_centerline` flips y into the plan frame (y up) for designs and the quick
commands, exactly as a path ``d`` string is flipped. Curves are flattened by
:mod:`embroact.patterns.svgpath` (subpaths joined when each starts where the last ended).

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
from typing import Any

import numpy as np

from ...patterns.base.arrays import frozen_array
from ...patterns.base.errors import PathError
from ...patterns.base.validate import PATH_SEGMENTS, TEXT_FILE_BYTES, read_input
from ...patterns.centerline import Centerline

__all__ = ["SvgPath", "is_svg_ref", "split_ref", "read_svg_path", "svg_centerline"]

#: CSS px per inch: the unit of user coordinates without a unit (SVG 1.1, CSS 2.1).
PX_PER_INCH = 96.0
MM_PER_PX = 25.4 / PX_PER_INCH
#: The ``ppi`` handed to svgelements: it converts mm as ``mm * ppi * 0.0393701``, so this
#: value makes 1 mm exactly 96 / 25.4 px.
_SVGELEMENTS_PPI = PX_PER_INCH / (25.4 * 0.0393701)
_LABEL = "{http://www.inkscape.org/namespaces/inkscape}label"
_GROUPMODE = "{http://www.inkscape.org/namespaces/inkscape}groupmode"


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
    groups: tuple[tuple[str | None, str | None], ...]  # (id, label) of every enclosing group


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


def _walk(group, layer: str | None, groups: tuple) -> list[_Found]:
    import svgelements

    found = []
    for e in group:
        own = e.values.get("attributes", {}) if hasattr(e, "values") else {}
        if isinstance(e, svgelements.Group):
            is_layer = own.get(_GROUPMODE) == "layer"
            name = own.get(_LABEL) or e.id
            found += _walk(e, name if is_layer else layer, groups + ((e.id, own.get(_LABEL)),))
        elif isinstance(e, svgelements.Shape) and not isinstance(e, svgelements.Text):
            found.append(_Found(e, e.id, own.get(_LABEL), layer, groups))
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
        own = [f for f in found if (f.element_id if key == "id" else f.label) == name]
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
    import svgelements

    file, name = split_ref(os.fspath(ref))
    p = Path(file) if base_dir is None else Path(base_dir) / file
    data = read_input(p, TEXT_FILE_BYTES, "SVG file", error=PathError)
    try:
        import io

        svg = svgelements.SVG.parse(io.BytesIO(data), ppi=_SVGELEMENTS_PPI)
    except Exception as exc:  # svgelements raises whatever its XML parser or number parsing raises
        raise PathError(f"{p}: not a readable SVG file ({type(exc).__name__}: {str(exc)[:80]})") from None
    found = _choose(_walk(svg, None, ()), name, str(p))
    try:
        from ...patterns.svgpath import flatten

        shape = svgelements.Path(found.shape) * svgelements.Matrix.scale(MM_PER_PX)
        if len(shape) > PATH_SEGMENTS:
            raise PathError(f"SVG path must have at most {PATH_SEGMENTS:,} segments, got {len(shape):,}")
        shape.reify()
        pts = flatten(shape)
    except PathError as exc:
        raise PathError(f"{p}#{found.element_id or name}: {exc}") from None
    return SvgPath(str(p), found.element_id, found.label, found.layer, frozen_array(pts + 0.0))


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
