"""A picture of the 3D shape without a GL context: orthographic projection, painter's algorithm, SVG.

Triangles facing away from the camera are dropped (the bodies are closed), the rest
are flat-shaded (ambient + Lambert) and drawn far to near.  Good enough for a report
or a README; the GLB file is the real 3D output.

The picture is modelled only as finely as it can show: shapes meshed finer than
``PICTURE_TOLERANCE_PX`` of a pixel at the picture's width are meshed again at that
tolerance (the GLB keeps the chordal tolerance asked for), and long triangles are
split for depth sorting to a fraction of the whole drawing.  A scene that would still
need more than ``PICTURE_MAX_TRIANGLES`` (a long path coiled into a small picture, many
actuators) is meshed coarser until it fits. Where the bodies' least triangles are still
more than the pixels show (a thousand small actuators), the triangles' corners are moved to
the centres of ``PICTURE_CELL_PX`` screen cells: those left with fewer than three distinct
corners, and those under a later one on the same three cells, are not drawn, so the picture
holds no more polygons than its pixels resolve; and past ``PICTURE_MAX_POLYGONS`` polygons (a tall picture
of many actuators) the cells are widened until it holds at most that many, so the picture's size is bounded
by what it shows, not by the number of actuators. Past ``PICTURE_MAX_NAMES`` shapes they are
not named (the names would cover each other); the key says how many there are.

The camera turns the plan frame by ``azimuth_deg`` about +z, then tilts it by
``elevation_deg`` about the screen's horizontal axis; the view is along -z' (x' right,
y' up on screen)::

        y' (up)
        |
        +---- x' (right)      camera looks along -z'
       /
      z' (toward the viewer)

Examples
--------
>>> from embroact.export.pictures.mesh import PlanarPath, actuator_mesh
>>> from embroact.export.pictures.meshview import mesh_svg, view_rotation
>>> import numpy as np
>>> view_rotation(0.0, 90.0).round(6).tolist() == np.eye(3).tolist()  # from the top: plan x right, y up
True
>>> m = actuator_mesh(PlanarPath.straight(50.0), 45.0, width_mm=7.0, r0_mm=2.58, tolerance_mm=0.5)
>>> mesh_svg(m).startswith('<svg')
True
"""
from __future__ import annotations

import math

import numpy as np

from ...patterns.base.errors import check_range
from ...patterns.base.tolerances import DEFAULT_TOLERANCES
from .labels import Box, Placer, text_box
from .titles import fit_title, text_width_px

__all__ = ["view_rotation", "mesh_svg", "picture_tolerance_mm", "PICTURE_TOLERANCE_PX"]

#: Chordal tolerance of the picture's mesh, in pixels at the rendered width.
PICTURE_TOLERANCE_PX = 0.25
#: Triangles the picture's mesh may have (about 1 MB of SVG once back faces are dropped).
PICTURE_MAX_TRIANGLES = 24_000
#: Most shapes the picture names (beyond, the names would cover each other and the shapes).
PICTURE_MAX_NAMES = 100
#: Width of the screen cells [px] the picture's triangle corners are moved to the centres of (what its pixels
#: resolve: triangles left with fewer than three distinct cells are not drawn).
PICTURE_CELL_PX = 1.0
#: Most polygons the picture draws (about 1.3 MB of SVG): past it the screen cells are widened.
PICTURE_MAX_POLYGONS = 16_000
#: Coarsest picture mesh [mm] (the mesh's own upper limit).
_MAX_TOLERANCE_MM = 10.0

_AMBIENT = 0.45
_LIGHT = np.array([-0.35, 0.55, 0.75]) / np.linalg.norm([-0.35, 0.55, 0.75])
_MARGIN_PX = 12.0
_NAME_PX = 12.0
_KEY_ROW_PX = 20.0
# Each triangle is stroked in its own fill this wide: adjacent triangles overlap, no background shows through the
# anti-aliased shared edges (0.4 px left faint seams across the fabric in Chromium)
_SEAM_PX = 0.9
_FONT = "font-family:Helvetica,Arial,sans-serif"
_SPLIT_FRACTION = 0.04
_HANGING = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])


def view_rotation(azimuth_deg: float, elevation_deg: float) -> np.ndarray:
    """World-to-view rotation (3, 3): rows are the screen x', y' and the toward-viewer z' axes.

    ``elevation_deg = 90`` looks straight down on the plan; ``0`` looks along the plan
    from the side (plan +z up on screen).

    Parameters
    ----------
    azimuth_deg : float
        Camera direction around the plan's z axis [deg], in [-360, 360].
    elevation_deg : float
        Camera height above the plan [deg], in [-90, 90].

    Returns
    -------
    numpy.ndarray (3, 3)

    Examples
    --------
    >>> (view_rotation(0.0, 0.0).round(6) + 0.0).tolist()  # from the side: plan +z is up on screen
    [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]]
    """
    az = math.radians(check_range("azimuth_deg", azimuth_deg, low=-360.0, high=360.0, low_inclusive=True,
                                  high_inclusive=True))
    el = math.radians(check_range("elevation_deg", elevation_deg, low=-90.0, high=90.0, low_inclusive=True,
                                  high_inclusive=True))
    ca, sa, ce, se = math.cos(az), math.sin(az), math.cos(el), math.sin(el)
    right = np.array([ca, sa, 0.0])
    toward = np.array([sa * ce, -ca * ce, se])  # el = 90: +z (top view); el = 0: horizontal
    up = np.cross(toward, right)
    return np.vstack([right, up, toward])


def _extent_mm(shapes, rot: np.ndarray) -> np.ndarray:
    """Screen extent (x', y') [mm] of the shapes' vertices seen through ``rot``."""
    pts = np.concatenate([np.asarray(b.vertices) for s in shapes for b in s.bodies]) @ rot[:2].T
    return pts.max(axis=0) - pts.min(axis=0)


def _scale_px_per_mm(extent_mm: np.ndarray, width_px: float) -> float:
    return (width_px - 2 * _MARGIN_PX) / max(float(extent_mm[0]), DEFAULT_TOLERANCES.length_mm)


def picture_tolerance_mm(shapes, rot: np.ndarray, width_px: float) -> float:
    """Chordal tolerance [mm] that is ``PICTURE_TOLERANCE_PX`` at the picture's scale.

    Parameters
    ----------
    shapes : sequence of ShapeMesh
        What the picture shows.
    rot : numpy.ndarray (3, 3)
        The view (:func:`view_rotation`).
    width_px : float
        The picture's width [px].

    Returns
    -------
    float
        [mm].

    Examples
    --------
    >>> from embroact.export.pictures.mesh import PlanarPath, actuator_mesh
    >>> m = actuator_mesh(PlanarPath.straight(1000.0), 0.0, width_mm=7.0, r0_mm=2.58, tolerance_mm=1.0)
    >>> round(picture_tolerance_mm([m], np.eye(3), 468.0), 3)  # 1000 mm on 444 px: 0.25 px = 0.563 mm
    0.563
    """
    return PICTURE_TOLERANCE_PX / _scale_px_per_mm(_extent_mm(shapes, rot), width_px)


def _picture_shapes(shapes, tol: float):
    """The shapes meshed at ``tol`` or coarser (identical ones once, :func:`~.mesh.remeshed_all`), within ``PICTURE_MAX_TRIANGLES`` (when the
    mesh's own limit allows): the triangle count goes as 1/tol (rings along the path and
    segments round the tube each as 1/sqrt(tol)), so each retry scales tol by the excess."""
    from .mesh import remeshed_all

    finer = iter(remeshed_all([s for s in shapes if s.tolerance_mm < tol], tol))
    out = tuple(s if s.tolerance_mm >= tol else next(finer) for s in shapes)
    n = sum(s.triangle_count for s in out)
    for _ in range(4):
        if n <= PICTURE_MAX_TRIANGLES or tol >= _MAX_TOLERANCE_MM:
            break
        tol = min(_MAX_TOLERANCE_MM, tol * 1.1 * n / PICTURE_MAX_TRIANGLES)
        coarser = remeshed_all(shapes, tol)
        n, before = sum(s.triangle_count for s in coarser), n
        out = coarser
        if n > 0.9 * before:  # at the bodies' least triangles (many small shapes): coarser cannot help
            break
    return out


def _behind_fabric(shape, body, rot: np.ndarray) -> np.ndarray:
    """Per face: True where a thread-side body sits on a stretch of fabric whose thread side faces away.

    Such faces lie behind the (opaque, thin) fabric; drawing them first keeps depth sorting
    of large fabric triangles from letting them show through.
    """
    if body.name == "fabric":
        return np.zeros(len(body.faces), dtype=bool)
    s = np.asarray(body.ring_s_mm)[np.asarray(body.faces) // body.ring_size].mean(axis=1)
    # the faces of one ring-to-ring cell share a few arc lengths: one frame for each distinct one
    s_once, face = np.unique(s, return_inverse=True)
    _, frames = shape.bent.frames(s_once)
    return ((frames[:, :, 2] @ rot[2]) < 0.0)[face.reshape(-1)]


def mesh_svg(shape, *, azimuth_deg: float = 60.0, elevation_deg: float = 20.0, width_px: float = 480.0,
             hanging: bool = True, title: str | None = None) -> str:
    """The shape as a flat-shaded SVG picture (string).

    Parameters
    ----------
    shape : ShapeMesh or sequence of ShapeMesh
        From :func:`embroact.export.pictures.mesh.actuator_mesh` (several: drawn together).
    azimuth_deg, elevation_deg : float
        Camera direction [deg] (see :func:`view_rotation`).
    width_px : float
        Picture width [px], >= 100; the height follows the shape's aspect.
    hanging : bool
        Turn the plan frame first so that the strip hangs from its clamped start, as in
        the paper's photographs: plan +x -> down, plan +z (thread side) -> world +x.
    title : str, optional
        Caption drawn in the top-left corner (wrapped onto up to 3 lines, shortened past them:
        :func:`embroact.export.pictures.titles.fit_title`).

    Returns
    -------
    str
        SVG.

    Examples
    --------
    >>> from embroact.export.pictures.mesh import PlanarPath, actuator_mesh
    >>> m = actuator_mesh(PlanarPath.straight(100.0), 90.0, width_mm=7.0, r0_mm=2.58, measure=False)
    >>> svg = mesh_svg(m, title="A1 at 300 kPa")
    >>> svg.startswith("<svg"), "A1 at 300 kPa" in svg
    (True, True)
    """
    from .svgdoc import Drawing

    from .mesh import shapes_of
    from .triangles import subdivide_to_size

    width = check_range("width_px", width_px, low=100.0, low_inclusive=True, high=10000.0)
    rot = view_rotation(azimuth_deg, elevation_deg) @ (_HANGING if hanging else np.eye(3))
    shapes = shapes_of(shape)
    shapes = _picture_shapes(shapes, min(picture_tolerance_mm(shapes, rot, width), _MAX_TOLERANCE_MM))
    # long thin triangles defeat depth sorting: split them to a fraction of the shape's
    # size, or of the whole drawing when it holds many shapes
    split = _SPLIT_FRACTION * max(max(s.bent.path.length_mm for s in shapes), float(_extent_mm(shapes, rot).max()))
    tris, cols, hidden, owner = [], [], [], []
    for k, s in enumerate(shapes):
        for b in s.bodies:
            v, f, parent = subdivide_to_size(b.vertices, b.faces, split)
            tris.append(v[f] @ rot.T)
            cols.append(np.tile(np.array(b.colour[:3], dtype=float), (len(f), 1)))
            hidden.append(_behind_fabric(s, b, rot)[parent])
            owner.append(np.full(len(f), k))
    tri, col, behind, who = np.concatenate(tris), np.concatenate(cols), np.concatenate(hidden), np.concatenate(owner)
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    norm = np.linalg.norm(n, axis=1)
    keep = (n[:, 2] > 0) & (norm > 0)
    tri, col, behind, who, n = tri[keep], col[keep], behind[keep], who[keep], n[keep] / norm[keep, None]
    shade = _AMBIENT + (1.0 - _AMBIENT) * np.clip(n @ _LIGHT, 0.0, 1.0)
    rgb = np.clip(col * shade[:, None], 0, 255).round().astype(int)
    # parts behind the fabric first, then everything far to near
    order = np.lexsort((tri[:, :, 2].mean(axis=1), ~behind))
    lo, hi = tri[:, :, :2].reshape(-1, 2).min(axis=0), tri[:, :, :2].reshape(-1, 2).max(axis=0)
    scale = _scale_px_per_mm(hi - lo, width)
    fitted = fit_title(title, width - 2 * _MARGIN_PX, font_px=14.0, small_px=12.0, max_lines=3) if title else None
    top = (15.0 + 15.0 * len(fitted.lines) if fitted else _MARGIN_PX) + _NAME_PX * 1.6
    height = (hi[1] - lo[1]) * scale + top + _MARGIN_PX + _KEY_ROW_PX
    dwg = Drawing(size=(f"{width:.0f}", f"{height:.0f}"), viewBox=f"0 0 {width:.0f} {height:.0f}")
    dwg.add(dwg.rect((0, 0), (f"{width:.0f}", f"{height:.0f}"), fill="#fff"))
    g = dwg.g(stroke_width=_SEAM_PX, stroke_linejoin="round", **{"class": "mesh"})
    dwg.add(g)
    px = np.empty_like(tri[:, :, :2])
    px[:, :, 0] = _MARGIN_PX + (tri[:, :, 0] - lo[0]) * scale
    px[:, :, 1] = top + (hi[1] - tri[:, :, 1]) * scale
    lines, font_px = (fitted.lines, fitted.font_px) if fitted else ((), 0.0)
    placer = Placer(Box(0.0, 0.0, width, height), margin=2.0)
    for k, line in enumerate(lines):
        dwg.add(dwg.text(line, insert=(_MARGIN_PX, 20 + 15 * k), font_size=f"{font_px:g}", font_weight="bold",
                         style=_FONT))
        placer.block_box(text_box(line, _MARGIN_PX, 20 + 15 * k, font_px))
    _draw_names(dwg, placer, [s.name for s in shapes], px, who)
    _draw_key(dwg, shapes, height - _MARGIN_PX, width)
    shown, snapped = _budget_polygons(px[order])
    return _with_polygons(dwg.tostring(), g.tostring(), snapped.reshape(-1, 6), rgb[order][shown])


def _budget_polygons(px: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_pixel_polygons` on ``PICTURE_CELL_PX`` cells, widened (each time by the root of the excess, the
    polygons a picture of a given area holds going as 1 / cell area) until at most ``PICTURE_MAX_POLYGONS`` are
    left.

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> px = rng.uniform(0.0, 400.0, (3000, 1, 2)) + rng.uniform(0.0, 4.0, (3000, 3, 2))
    >>> len(_budget_polygons(px)[0]) == len(_pixel_polygons(px)[0])  # within the budget: unchanged
    True
    """
    cell = PICTURE_CELL_PX
    shown, snapped = _pixel_polygons(px, cell)
    for _ in range(8):
        if len(shown) <= PICTURE_MAX_POLYGONS:
            break
        cell *= 1.05 * math.sqrt(len(shown) / PICTURE_MAX_POLYGONS)
        shown, snapped = _pixel_polygons(px, cell)
    return shown, snapped


def _pixel_polygons(px: np.ndarray, cell_px: float = PICTURE_CELL_PX) -> tuple[np.ndarray, np.ndarray]:
    """The triangles (in drawing order, (n, 3, 2) [px]) a picture shows at its pixel size: corners moved to the
    centres of cells ``cell_px`` wide (vertex clustering on the screen), those left with fewer than three
    distinct corners dropped, and of triangles on the same three cells only the last drawn (it covers the others).
    Returns the indices kept (ascending) and their corners.

    Examples
    --------
    >>> px = np.array([[[0.1, 0.1], [9.9, 0.2], [0.2, 9.9]], [[0.1, 0.1], [0.3, 0.2], [0.2, 9.9]],
    ...                [[0.2, 0.2], [9.8, 0.1], [0.1, 9.8]]])
    >>> kept, corners = _pixel_polygons(px)
    >>> kept.tolist(), corners[0].tolist()
    ([2], [[0.5, 0.5], [9.5, 0.5], [0.5, 9.5]])
    """
    cell = np.floor(px / cell_px).astype(np.int64)
    key = (cell[:, :, 0] - cell[:, :, 0].min()) * (int(cell[:, :, 1].max() - cell[:, :, 1].min()) + 1) \
        + (cell[:, :, 1] - cell[:, :, 1].min()) if len(px) else np.zeros((0, 3), dtype=np.int64)
    distinct = (key[:, 0] != key[:, 1]) & (key[:, 1] != key[:, 2]) & (key[:, 0] != key[:, 2])
    corners = np.sort(key, axis=1)[::-1]  # reversed: the first of equal rows is the last drawn
    # the first of each run of equal rows in a stable sort (np.unique(axis=0, return_index=True) finds the same
    # rows through a sort of the rows as bytes: 3.5 times as long)
    order = np.lexsort(corners.T[::-1])
    ranked = corners[order]
    first = np.ones(len(px), dtype=bool)
    first[1:] = np.any(ranked[1:] != ranked[:-1], axis=1)
    kept = np.zeros(len(px), dtype=bool)
    kept[len(px) - 1 - order[first]] = True
    kept = np.flatnonzero(kept & distinct)
    return kept, (cell[kept] + 0.5) * cell_px


_KEY_TEXT = (("fabric", "fabric"), ("tube", "tube (thread side)"), ("rail", "rails (leg ends)"))


def _draw_key(dwg, shapes, y: float, width_px: float) -> None:
    """Which colour is which part: the fabric strip, the tube on the thread side, the rails; and how many shapes
    there are when they are too many to name (where the row has room)."""
    colours: dict[str, tuple] = {}
    for s in shapes:
        for b in s.bodies:
            colours.setdefault(b.name.split("_")[0], b.colour[:3])
    x = _MARGIN_PX
    for part, text in _KEY_TEXT:
        if part not in colours:
            continue
        dwg.add(dwg.rect((f"{x:.1f}", f"{y - 9:.1f}"), (12, 10), fill="#%02x%02x%02x" % tuple(colours[part]),
                         stroke="#555", stroke_width=0.5))
        dwg.add(dwg.text(text, insert=(f"{x + 16:.1f}", f"{y:.1f}"), font_size=f"{_NAME_PX - 1:g}", style=_FONT,
                         **{"class": "key"}))
        x += 16 + text_width_px(text, _NAME_PX - 1) + 14
    count = f"{len(shapes)} actuators (unnamed)"
    if len(shapes) > PICTURE_MAX_NAMES and x + text_width_px(count, _NAME_PX - 1) <= width_px - _MARGIN_PX:
        dwg.add(dwg.text(count, insert=(f"{x:.1f}", f"{y:.1f}"), font_size=f"{_NAME_PX - 1:g}", style=_FONT,
                         **{"class": "key"}))


def _draw_names(dwg, placer: Placer, names, px: np.ndarray, who: np.ndarray) -> None:
    """Each shape's name above its highest point (the clamp of a hanging strip), clear of the other names; past
    ``PICTURE_MAX_NAMES`` shapes none (they could not be read), and the key says how many there are."""
    if len(names) > PICTURE_MAX_NAMES:
        return
    for k, name in enumerate(names):
        pts = px[who == k].reshape(-1, 2)
        if not len(pts):
            continue
        top = pts[np.argmin(pts[:, 1])]
        lab = placer.place(name, (float(top[0]), float(top[1])), _NAME_PX, gap=3.0,
                           directions=((0, -1), (1, -1), (-1, -1), (1, 0), (-1, 0), (0, 1)))
        dwg.add(dwg.text(name, insert=(f"{lab.x:.1f}", f"{lab.y:.1f}"), font_size=f"{_NAME_PX:g}", style=_FONT,
                         text_anchor=lab.anchor, fill="#222", **{"class": "name"}))


#: The text of one polygon around its 8 values (colour, three corners x,y, colour), as svgdoc writes it.
_POLYGON_TEXT = ('<polygon fill="', '" points="', ",", " ", ",", " ", ",", '" stroke="', '" />')


def _with_polygons(svg: str, group: str, points: np.ndarray, colours: np.ndarray) -> str:
    """``svg`` with the empty group ``group`` filled by one polygon per triangle, written as svgdoc writes them.

    An element object per polygon would be most of the picture's time (a few thousand triangles); the
    text is the same: attributes in name order, points as the coordinates rounded to 0.1 px (``%.1f``
    gives the digits of ``str(round(x, 1))`` for every coordinate a picture can have), colours as
    ``#rrggbb``. The corners lie on screen cells, so few coordinates are distinct: each is written once
    and the polygons are put together from those pieces (a format per polygon took three times as long).

    Parameters
    ----------
    svg, group : str
        The document and the empty group's text in it (once).
    points : numpy.ndarray (n, 6)
        Each polygon's corners x0, y0, x1, y1, x2, y2 [px].
    colours : numpy.ndarray of int (n, 3)
        Each polygon's colour, 0-255 per channel.

    Returns
    -------
    str

    Examples
    --------
    >>> _with_polygons('<svg><g class="mesh" /></svg>', '<g class="mesh" />', np.array([[0.5, 1.5, 2.5, 1.5, 0.5, 0.5]]),
    ...                np.array([[255, 0, 16]]))
    '<svg><g class="mesh"><polygon fill="#ff0010" points="0.5,1.5 2.5,1.5 0.5,0.5" stroke="#ff0010" /></g></svg>'
    """
    if not len(points):
        return svg
    values, which = np.unique(points, return_inverse=True)
    coordinates = np.array(["%.1f" % v for v in values.tolist()], dtype=object)
    rgb = (colours[:, 0] << 16) | (colours[:, 1] << 8) | colours[:, 2]
    shades, shade = np.unique(rgb, return_inverse=True)
    colour = np.array(["#%06x" % c for c in shades.tolist()], dtype=object)[shade.reshape(-1)]
    pieces = np.empty((len(points), 2 * len(_POLYGON_TEXT) - 1), dtype=object)
    pieces[:, 0::2] = _POLYGON_TEXT
    pieces[:, 1], pieces[:, 3:15:2], pieces[:, 15] = colour, coordinates[which.reshape(-1, 6)], colour
    assert svg.count(group) == 1 and group.endswith(" />")
    return svg.replace(group, group[:-3] + ">" + "".join(pieces.reshape(-1).tolist()) + "</g>")
