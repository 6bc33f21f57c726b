"""SVG path data -> polyline points, with the svgelements library (no file I/O).

:func:`parse_d` reads a path ``d`` string (every SVG 1.1 command, absolute and relative,
compact arc flags such as ``a5,5 0 01 10,0`` included; :func:`check_d` refuses malformed
data naming the character offset); :func:`flatten` turns a parsed path into polyline
points (in mm, through an optional transform matrix applied to the points): lines exactly,
Bezier curves and elliptical arcs to a chordal error of at most
``DEFAULT_TOLERANCES.curve_flatness_mm``.
Points stay in SVG's frame (y down); :func:`to_plan` flips them into the plan frame (y up).

Several subpaths: a tube is one piece, so subpaths are joined into one polyline when each
starts where the one before it ended (within ``DEFAULT_TOLERANCES.length_mm``); a gap
between them is a :class:`PathError` naming it. Subpaths that draw nothing (a lone move)
are dropped. Reading SVG *files* (units, viewBox, transforms, choosing a path by id,
label or layer) is I/O and lives in :mod:`embroact.export.files.svgfile`.

svgelements is imported on first use, so importing this module stays cheap.

Examples
--------
>>> from embroact.patterns.svgpath import flatten, parse_d, to_plan
>>> flatten(parse_d("M 0 0 H 10 V 10")).tolist()
[[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]
>>> pts = flatten(parse_d("M0 0 a5,5 0 01 10,0"))  # compact arc flags; over the top (y < 0)
>>> round(float(pts[:, 1].min()), 9), pts[-1].tolist()
(-5.0, [10.0, 0.0])
>>> to_plan(flatten(parse_d("M 0 0 L 3 4 M 3 4 L 6 4"))).tolist()  # joined; y flipped
[[0.0, 0.0], [3.0, -4.0], [6.0, -4.0]]
"""
from __future__ import annotations

import math
import re
from typing import TYPE_CHECKING, Any

import numpy as np

from .base.errors import PathError
from .base.tolerances import DEFAULT_TOLERANCES
from .base.validate import COORD_MM, PATH_CHARS, PATH_POINTS, PATH_SEGMENTS, check_coordinates

if TYPE_CHECKING:
    import svgelements

__all__ = ["parse_d", "check_d", "flatten", "to_plan"]

_D_COMMANDS = "MmLlHhVvCcSsQqTtAaZz"
#: Characters an SVG path d string may hold (svgelements silently skips unknown commands).
_D_BAD_CHAR = re.compile(rf"[^{_D_COMMANDS}0-9eE+\-.,\s]")
_D_FIRST = re.compile(r"^\s*[Mm]")
_D_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
#: Most numbers one drawing command takes (an arc: rx ry rotation flags x y; flags may be compact).
_NUMBERS_PER_SEGMENT = 7
#: Arc radii beyond these are handled by :func:`_arc_radii` (their squares over- or underflow).
_HUGE_RADIUS_MM, _TINY_RADIUS_MM = 1e150, 1e-150
_PATH_CLASS = None
#: Numbers each path command takes (an arc's 4th and 5th are flags, one character each).
_ARITY = {"M": 2, "L": 2, "T": 2, "H": 1, "V": 1, "C": 6, "S": 4, "Q": 4, "A": 7, "Z": 0}
_D_NUMBER_AT = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_D_SEPARATORS = " \t\r\n\f,"


def check_d(d: str) -> None:
    """Refuse path data that does not follow SVG's path grammar, naming the character offset.

    SVG renderers (and svgelements) stop drawing at the first error and keep what came
    before it, so a typo would silently shorten a tube; this scan finds the error instead.

    Parameters
    ----------
    d : str
        Path data.

    Raises
    ------
    PathError
        One line: what is wrong and its character offset (0-based) in ``d`` (callers prefix
        the path or element).

    Examples
    --------
    >>> check_d("M 0 0 a5,5 0 01 10,0 Z")
    >>> check_d("M 0 0 L 10 0 L 20")
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.PathError: 'L' at character 13 needs numbers in groups of 2, got 1 (ends at character 17)
    """
    i, n = 0, len(d)
    command: str | None = None
    start = count = 0

    def close_command(at: int) -> None:
        assert command is not None
        arity = _ARITY[command.upper()]
        if (arity == 0 and count) or (arity and (count == 0 or count % arity)):
            got = f"got {count}" + (f" (ends at character {at})" if count else "")
            need = "takes no numbers" if arity == 0 else f"needs numbers in groups of {arity}"
            raise PathError(f"{command!r} at character {start} {need}, {got}")

    while i < n:
        ch = d[i]
        if ch in _D_SEPARATORS:
            i += 1
            continue
        if ch.upper() in _ARITY:
            if command is None and ch not in "Mm":
                raise PathError(f"must start with a move-to (M), got {ch!r} at character {i}")
            if command is not None:
                close_command(i)
            command, start, count = ch, i, 0
            i += 1
            continue
        if command is None:
            raise PathError(f"must start with a move-to (M), got {ch!r} at character {i}")
        if command.upper() == "A" and count % 7 in (3, 4):  # arc flags: one character, 0 or 1
            if ch not in "01":
                raise PathError(f"arc flag at character {i} must be 0 or 1, got {ch!r}")
            i, count = i + 1, count + 1
            continue
        m = _D_NUMBER_AT.match(d, i)
        if m is None:
            raise PathError(f"unexpected {ch!r} at character {i} (expected a number or a command)")
        i, count = m.end(), count + 1
    if command is None:
        raise PathError("no path data")
    close_command(n)


def parse_d(d: str) -> "svgelements.Path":
    """Parse an SVG path ``d`` string (coordinates as they stand) into an svgelements Path.

    Parameters
    ----------
    d : str
        Path data: ``M L H V C S Q T A Z`` and their relative forms, starting with a move-to.

    Returns
    -------
    svgelements.Path
        The parsed path, untransformed.

    Raises
    ------
    PathError
        One line: not a string, empty, an unsupported character (with its position), not
        starting with M, a command missing numbers, an arc flag other than 0 or 1, or a
        non-finite number.

    Examples
    --------
    >>> [type(s).__name__ for s in parse_d("M 0 0 C 1 1 2 1 3 0 a 2 2 0 0 0 4 0")]
    ['Move', 'CubicBezier', 'Arc']
    """
    if not isinstance(d, str) or not d.strip():
        raise PathError(f"SVG path must be a non-empty string, got {d!r}")
    if ".svg" in d.lower():
        raise PathError(
            f"SVG path {d!r:.60} looks like an SVG file reference (FILE.svg#id): files are read by "
            "embroact.export.files.svgfile (design files, --path and --tube-path accept them), not as path data"
        )
    bad = _D_BAD_CHAR.search(d)
    if bad:
        raise PathError(
            f"SVG path: unsupported character {bad.group()!r} at position {bad.start()}; "
            f"supported commands: {' '.join(_D_COMMANDS)}"
        )
    if not _D_FIRST.match(d):
        raise PathError(f"SVG path must start with a move-to (M), got {d.strip()[:1]!r}")
    if len(d) > PATH_CHARS:
        raise PathError(f"SVG path must be at most {PATH_CHARS:,} characters, got {len(d):,}")
    try:
        check_d(d)
    except PathError as exc:
        raise PathError(f"SVG path {d!r:.60}: {exc}") from None
    numbers = len(_D_NUMBER.findall(d))
    if numbers > _NUMBERS_PER_SEGMENT * PATH_SEGMENTS:
        raise PathError(f"SVG path must have at most {PATH_SEGMENTS:,} segments, got {numbers:,} numbers "
                        f"(at least {-(-numbers // _NUMBERS_PER_SEGMENT):,} segments)")
    try:
        path = _path_class()(d)
    except PathError:
        raise
    except (ValueError, TypeError, AttributeError, IndexError):
        raise PathError(
            f"SVG path {d!r:.60}: a command is missing numbers or an arc flag is not 0 or 1 "
            "(arc: a rx ry rotation large-arc-flag sweep-flag x y)"
        ) from None
    if len(path) > PATH_SEGMENTS:
        raise PathError(f"SVG path must have at most {PATH_SEGMENTS:,} segments, got {len(path):,}")
    ends = [s.end for s in path if s.end is not None]
    if not ends or not all(math.isfinite(p.x) and math.isfinite(p.y) for p in ends):
        raise PathError(f"SVG path {d!r:.60}: coordinates must be finite numbers")
    return path


def _arc_radii(rx: float, ry: float, chord: float, large: bool) -> tuple[float, float] | None:
    """Radii svgelements can compute with, for the same arc; None where the arc is a straight line.

    SVG scales radii too small for the chord up until they fit; only the ratio rx/ry matters
    then, so radii whose squares would underflow (1e-300) are scaled to a quarter of the
    chord, still too small, giving the same arc. An ellipse with a radius of 0 is a straight
    line (SVG's rule), and so are an arc between points closer than
    ``DEFAULT_TOLERANCES.length_mm`` and, to far below a nanometre, the short arc of a radius
    whose square overflows (1e308: sagitta chord^2 / (8 r)); the long way round on such a
    radius leaves the coordinate range (a PathError).
    """
    big, small = max(rx, ry), min(rx, ry)
    if small == 0.0 or chord < DEFAULT_TOLERANCES.length_mm:
        return None
    if big > _HUGE_RADIUS_MM:
        if large:
            raise PathError(f"SVG path: an arc of radius {big:g} mm taking the large way round (large-arc-flag 1) "
                            f"leaves the coordinate range [-{COORD_MM:g}, {COORD_MM:g}] mm")
        return None
    if small < _TINY_RADIUS_MM and big <= chord / 4.0:
        scale = chord / 4.0 / big
        rx, ry = rx * scale, ry * scale
    return (rx, ry) if min(rx, ry) >= _TINY_RADIUS_MM else None


def _path_class():
    """svgelements.Path whose arcs get :func:`_arc_radii` (made once, on first use)."""
    global _PATH_CLASS
    if _PATH_CLASS is None:
        import svgelements

        class _Path(svgelements.Path):
            def arc(self, *arc_args, relative=False, **kwargs):
                for i in range(0, len(arc_args), 6):
                    rx, ry, rotation, large, sweep, end = arc_args[i:i + 6]
                    start = self.current_point
                    if end in ("z", "Z"):
                        end = self.z_point
                    end = svgelements.Point(end)
                    absolute = end + start if relative and start is not None else end
                    check_coordinates("path", max(abs(absolute.x), abs(absolute.y)))
                    chord = abs(absolute - start) if start is not None else 0.0
                    radii = _arc_radii(abs(rx), abs(ry), chord, bool(large))
                    if radii is None:
                        self.append(svgelements.Line(start, end, relative=relative))
                    else:
                        self.append(svgelements.Arc(start, radii[0], radii[1], rotation, large, sweep, end,
                                                    relative=relative))
                return self

        _PATH_CLASS = _Path
    return _PATH_CLASS


def _segment_points(seg: Any, tol: float) -> np.ndarray:
    """Points of one drawing segment, its start excluded, to the chordal tolerance ``tol``."""
    import svgelements

    if isinstance(seg, (svgelements.Line, svgelements.Close)):
        return np.array([[seg.end.x, seg.end.y]], dtype=np.float64)
    if isinstance(seg, (svgelements.QuadraticBezier, svgelements.CubicBezier)):
        inner = (seg.control,) if isinstance(seg, svgelements.QuadraticBezier) else (seg.control1, seg.control2)
        ctrl = np.array([[p.x, p.y] for p in (seg.start, *inner, seg.end)], dtype=np.float64)
        deg = len(ctrl) - 1
        second = deg * (deg - 1) * np.diff(ctrl, n=2, axis=0)
        # uniform steps: n = ceil(sqrt(M / (8 tol))), M a bound on |B''|, keeps the chord error <= tol
        n = max(1, math.ceil(math.sqrt(float(np.max(np.hypot(second[:, 0], second[:, 1]))) / (8.0 * tol))))
    elif isinstance(seg, svgelements.Arc):
        r = max(seg.rx, seg.ry)
        step = 2.0 * math.acos(max(-1.0, 1.0 - tol / r)) if r > 0.0 else math.pi
        if not (math.isfinite(seg.sweep) and step > 0.0):
            raise PathError(f"SVG path: an arc of radii {seg.rx:g}, {seg.ry:g} mm cannot be computed "
                            "(radii or their ratio out of range)")
        n = max(1, math.ceil(abs(seg.sweep) / step))
    else:  # pragma: no cover - svgelements has no other drawing segment
        raise PathError(f"SVG path: unsupported segment {type(seg).__name__}")
    if n > PATH_POINTS:
        raise PathError(f"SVG path: curve too large to flatten ({n} points > {PATH_POINTS})")
    pts = np.asarray(seg.npoint(np.linspace(0.0, 1.0, n + 1)[1:]), dtype=np.float64)
    pts[-1] = (seg.end.x, seg.end.y)  # land exactly on the given end point
    return pts


def _affine(matrix: tuple[float, float, float, float, float, float] | None) -> tuple[np.ndarray, np.ndarray, float]:
    """(linear part, offset, largest stretch) of an SVG matrix (a, b, c, d, e, f)."""
    if matrix is None:
        return np.eye(2), np.zeros(2), 1.0
    a, b, c, d, e, f = (float(v) for v in matrix)
    linear = np.array([[a, c], [b, d]])
    stretch = float(np.linalg.svd(linear, compute_uv=False)[0]) if np.all(np.isfinite(linear)) else math.nan
    if not (math.isfinite(stretch) and stretch > 0.0 and math.isfinite(e) and math.isfinite(f)):
        raise PathError(f"SVG path: transform matrix({a:g}, {b:g}, {c:g}, {d:g}, {e:g}, {f:g}) draws nothing "
                        "(it must be finite, not of scale 0)")
    return linear, np.array([e, f]), stretch


def _check_extent(path: "svgelements.Path", linear: np.ndarray, offset: np.ndarray) -> None:
    """Refuse a path reaching beyond :data:`COORD_MM` (or not finite) in mm, before any point is computed.

    A Bezier curve lies inside the hull of its control points and an arc inside the box of
    its centre plus its larger radius, so mapping those corners through the transform bounds
    everything the flattening would compute: no coordinate of 1e308 or transform that
    overflows reaches its arithmetic (a quadratic to 1e308 raised OverflowError there).
    """
    corners = []
    for seg in path:
        for key in ("start", "end", "control", "control1", "control2"):
            q = getattr(seg, key, None)
            if q is not None:
                corners.append((q.x, q.y))
        center = getattr(seg, "center", None)
        if center is not None:
            r = max(abs(getattr(seg, "rx", 0.0) or 0.0), abs(getattr(seg, "ry", 0.0) or 0.0))
            corners += [(center.x + sx * r, center.y + sy * r) for sx in (-1.0, 1.0) for sy in (-1.0, 1.0)]
    if not corners:
        return
    with np.errstate(all="ignore"):
        pts = np.array(corners, dtype=np.float64) @ linear.T + offset
        worst = float(np.abs(pts).max()) if np.all(np.isfinite(pts)) else math.inf
    check_coordinates("path", worst)


def flatten(path: "svgelements.Path", matrix: tuple[float, float, float, float, float, float] | None = None) -> np.ndarray:
    """Polyline points of ``path`` (its units, SVG frame), subpaths joined end to start.

    Parameters
    ----------
    path : svgelements.Path
        A parsed path, its segments untransformed.
    matrix : tuple of 6 float, optional
        An SVG transform ``matrix(a, b, c, d, e, f)`` from the path's coordinates to mm:
        the path is flattened in its own coordinates (to the tolerance divided by the
        matrix's largest stretch) and the points are then mapped. An elliptical arc under a
        non-uniform scale or a skew stays exact this way (svgelements' reified arcs do not).
        Default: the coordinates are mm already.

    Returns
    -------
    ndarray, shape (n, 2)
        Points in the path's own frame (y down), first point the first move-to.

    Raises
    ------
    PathError
        If the path draws nothing, or a subpath does not start where the one before ended.

    Examples
    --------
    >>> flatten(parse_d("M 0 0 L 10 0 M 20 0 L 30 0"))
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.PathError: SVG path has 2 subpaths with a gap of 10 mm between them (subpath 2 starts at (20, 0), subpath 1 ends at (10, 0)); a tube is one piece: draw one subpath per tube (Inkscape: Path > Break Apart, one path per tube) or join them
    """
    import svgelements

    linear, offset, stretch = _affine(matrix)
    _check_extent(path, linear, offset)
    tol = DEFAULT_TOLERANCES.curve_flatness_mm / stretch
    subpaths: list[list[np.ndarray]] = []
    for seg in path:
        if isinstance(seg, svgelements.Move):
            subpaths.append([np.array([[seg.end.x, seg.end.y]], dtype=np.float64)])
        elif not subpaths:
            raise PathError("SVG path must start with a move-to (M)")
        else:
            subpaths[-1].append(_segment_points(seg, tol))
    drawn = [np.vstack(s) @ linear.T + offset if matrix is not None else np.vstack(s) for s in subpaths if len(s) > 1]
    if not drawn:
        raise PathError("SVG path draws nothing (only move-to commands)")
    for k in range(1, len(drawn)):
        gap = float(np.hypot(*(drawn[k][0] - drawn[k - 1][-1])))
        if gap > DEFAULT_TOLERANCES.length_mm:
            (x0, y0), (x1, y1) = drawn[k][0], drawn[k - 1][-1]
            raise PathError(
                f"SVG path has {len(drawn)} subpaths with a gap of {gap:.4g} mm between them (subpath {k + 1} "
                f"starts at ({x0:.4g}, {y0:.4g}), subpath {k} ends at ({x1:.4g}, {y1:.4g})); a tube is one piece: "
                "draw one subpath per tube (Inkscape: Path > Break Apart, one path per tube) or join them"
            )
        drawn[k] = drawn[k][1:]
    pts = np.vstack(drawn)
    if len(pts) > PATH_POINTS:
        raise PathError(f"SVG path: too many points after flattening ({len(pts)} > {PATH_POINTS})")
    return pts


def to_plan(points_svg: np.ndarray) -> np.ndarray:
    """SVG-frame points (y down) -> plan-frame points (y up), same units.

    Parameters
    ----------
    points_svg : array_like, shape (n, 2)
        Points with y pointing down.

    Returns
    -------
    ndarray, shape (n, 2)
        The same points with y negated (no negative zeros).

    Examples
    --------
    >>> to_plan([[1.0, 2.0], [3.0, 0.0]]).tolist()
    [[1.0, -2.0], [3.0, 0.0]]
    """
    return np.asarray(points_svg, dtype=np.float64) * np.array([1.0, -1.0]) + 0.0  # + 0.0: -0.0 -> 0.0
