"""Text boxes of an SVG document read from its geometry, independent of the code that placed them.

Each ``<text>`` (and each ``<tspan>`` line) becomes an axis-aligned box in the root's user units:
its width from the Helvetica advances of :func:`embroact.export.pictures.titles.text_width_px`
(the bold widths, a little wider than regular text), its height from the font size (ascent
0.75 em above the baseline, descent 0.22 em below), shifted by ``text-anchor`` and mapped through
every ``transform`` of the element and its ancestors (``translate``, ``scale``, ``rotate``,
``matrix``). The canvas is the root's ``viewBox``.
"""
from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass

from embroact.export.pictures.titles import text_width_px

_NS = "{http://www.w3.org/2000/svg}"
_ASCENT, _DESCENT = 0.75, 0.22


@dataclass(frozen=True)
class Box:
    text: str
    x0: float
    y0: float
    x1: float
    y1: float

    def overlap(self, other: "Box", tol: float = 0.0) -> bool:
        return (min(self.x1, other.x1) - max(self.x0, other.x0) > tol
                and min(self.y1, other.y1) - max(self.y0, other.y0) > tol)


def _num(v, default=0.0) -> float:
    if v is None or v == "":
        return default
    return float(re.match(r"-?[\d.eE+-]+", str(v).strip()).group(0))


def _matrix(transform: str | None):
    m = (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)
    if not transform:
        return m
    for name, args in re.findall(r"(\w+)\s*\(([^)]*)\)", transform):
        a = [float(v) for v in re.split(r"[\s,]+", args.strip()) if v]
        if name == "translate":
            t = (1, 0, 0, 1, a[0], a[1] if len(a) > 1 else 0.0)
        elif name == "scale":
            t = (a[0], 0, 0, a[1] if len(a) > 1 else a[0], 0, 0)
        elif name == "rotate":
            c, s = math.cos(math.radians(a[0])), math.sin(math.radians(a[0]))
            cx, cy = (a[1], a[2]) if len(a) == 3 else (0.0, 0.0)
            t = (c, s, -s, c, cx - c * cx + s * cy, cy - s * cx - c * cy)
        elif name == "matrix":
            t = tuple(a)
        else:
            raise ValueError(f"transform {name} not handled")
        m = _mul(m, t)
    return m


def _mul(m, t):
    a, b, c, d, e, f = m
    A, B, C, D, E, F = t
    return (a * A + c * B, b * A + d * B, a * C + c * D, b * C + d * D, a * E + c * F + e, b * E + d * F + f)


def _apply(m, x, y):
    a, b, c, d, e, f = m
    return a * x + c * y + e, b * x + d * y + f


def _style(el) -> dict:
    out = {}
    for part in (el.get("style") or "").split(";"):
        if ":" in part:
            k, v = part.split(":", 1)
            out[k.strip()] = v.strip()
    return out


def _inherited(el, parents, name, default=None):
    node = el
    while node is not None:
        v = node.get(name) or _style(node).get(name)
        if v:
            return v
        node = parents.get(node)
    return default


def viewbox(root) -> tuple[float, float, float, float]:
    x, y, w, h = (float(v) for v in root.get("viewBox").split())
    return x, y, x + w, y + h


def text_boxes(svg: str) -> tuple[list[Box], tuple[float, float, float, float]]:
    """Every text line's box (root user units) and the canvas (x0, y0, x1, y1)."""
    root = ET.fromstring(svg)
    parents = {child: parent for parent in root.iter() for child in parent}
    boxes = []
    for el in root.iter(f"{_NS}text"):
        lines = [el] if not list(el.iter(f"{_NS}tspan")) else list(el.iter(f"{_NS}tspan"))
        for line in lines:
            text = "".join(line.itertext()) if line is not el else (el.text or "")
            if not text.strip():
                continue
            fs = _num(_inherited(line, parents, "font-size"), 16.0)
            anchor = _inherited(line, parents, "text-anchor", "start")
            x = _num(line.get("x") if line.get("x") is not None else el.get("x"))
            y = _num(line.get("y") if line.get("y") is not None else el.get("y"))
            w = text_width_px(text, fs)
            x0 = x - {"start": 0.0, "middle": w / 2, "end": w}[anchor]
            m = (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)
            chain, node = [], el
            while node is not None:
                chain.append(node)
                node = parents.get(node)
            for node in reversed(chain):
                m = _mul(m, _matrix(node.get("transform")))
            corners = [_apply(m, px, py) for px in (x0, x0 + w) for py in (y - _ASCENT * fs, y + _DESCENT * fs)]
            xs, ys = [c[0] for c in corners], [c[1] for c in corners]
            boxes.append(Box(text, min(xs), min(ys), max(xs), max(ys)))
    return boxes, viewbox(root)


def label_problems(svg: str, *, tol_frac: float = 0.0) -> list[str]:
    """Pairs of overlapping text boxes and boxes that leave the canvas, as sentences (empty: none)."""
    boxes, (cx0, cy0, cx1, cy1) = text_boxes(svg)
    problems = []
    for i, a in enumerate(boxes):
        eps = 1e-6 * max(cx1 - cx0, cy1 - cy0)
        if a.x0 < cx0 - eps or a.y0 < cy0 - eps or a.x1 > cx1 + eps or a.y1 > cy1 + eps:
            problems.append(f"{a.text!r} leaves the canvas: {a} vs {(cx0, cy0, cx1, cy1)}")
        for b in boxes[i + 1:]:
            tol = tol_frac * min(a.y1 - a.y0, b.y1 - b.y0)
            if a.overlap(b, tol):
                problems.append(f"{a.text!r} overlaps {b.text!r}")
    return problems
