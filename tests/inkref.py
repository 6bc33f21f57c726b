"""Reference geometry of SVG path data, written from the SVG 1.1 specification alone (mpmath).

Independent of ``embroact.patterns.svgpath`` and of svgelements: path data is tokenised
here, elliptical arcs are converted from endpoint to centre parameterisation as SVG 1.1
appendix F.6.5-F.6.6 states it (radii scaled up when too small), and lengths are
mpmath quadratures of |B'(t)|. Used with the drawings Inkscape flattened
(tests/data/inkscape/*.inkscape.svg) as the reference of tests/test_svg_inkscape.py.

Examples
--------
>>> segs = segments("M 0 0 A 10 10 0 0 1 20 0")  # half circle, radius 10
>>> round(float(length(segs)), 12) == round(float(mp.pi * 10), 12)
True
"""
from __future__ import annotations

import re

import mpmath as mp
import numpy as np

_TOKEN = re.compile(r"[MmLlHhVvCcSsQqTtAaZz]|[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_ARITY = {"M": 2, "L": 2, "T": 2, "H": 1, "V": 1, "C": 6, "S": 4, "Q": 4, "A": 7, "Z": 0}


def segments(d: str) -> list[tuple]:
    """Path data -> absolute segments: ("L", p0, p1), ("C", p0, c1, c2, p1), ("A", centre, rx, ry, phi, t0, dt)."""
    tokens = _TOKEN.findall(d)
    out, i = [], 0
    cur = start = mp.matrix([0, 0])
    cmd, last_ctrl, last_cmd = None, None, None
    while i < len(tokens):
        if tokens[i].isalpha():
            cmd = tokens[i]
            i += 1
            if cmd in "Zz":
                if mp.norm(cur - start) > 0:
                    out.append(("L", cur, start))
                cur, last_cmd = start, "Z"
                continue
        n = _ARITY[cmd.upper()]
        args = [mp.mpf(t) for t in tokens[i:i + n]]
        i += n
        rel = cmd.islower()
        base = cur if rel else mp.matrix([0, 0])

        def pt(x, y, base=base):
            return mp.matrix([x + base[0], y + base[1]])

        up = cmd.upper()
        if up == "M":
            cur = start = pt(*args)
            cmd = "l" if rel else "L"  # further pairs are line-tos
            last_cmd = "M"
            continue
        if up in "LHV":
            end = pt(*args) if up == "L" else (mp.matrix([args[0] + (cur[0] if rel else 0), cur[1]]) if up == "H"
                                               else mp.matrix([cur[0], args[0] + (cur[1] if rel else 0)]))
            out.append(("L", cur, end))
            cur, last_ctrl = end, None
        elif up in "CS":
            if up == "C":
                c1, c2, end = pt(*args[0:2]), pt(*args[2:4]), pt(*args[4:6])
            else:
                c1 = 2 * cur - last_ctrl if last_cmd in "CS" else cur
                c2, end = pt(*args[0:2]), pt(*args[2:4])
            out.append(("C", cur, c1, c2, end))
            cur, last_ctrl = end, c2
        elif up in "QT":
            if up == "Q":
                q, end = pt(*args[0:2]), pt(*args[2:4])
            else:
                q = 2 * cur - last_ctrl if last_cmd in "QT" else cur
                end = pt(*args[0:2])
            out.append(("C", cur, cur + 2 * (q - cur) / 3, end + 2 * (q - end) / 3, end))  # exact degree raise
            cur, last_ctrl = end, q
        elif up == "A":
            end = pt(*args[5:7])
            out.append(_arc(cur, args[0], args[1], args[2], args[3] != 0, args[4] != 0, end))
            cur, last_ctrl = end, None
        last_cmd = up
    return out


def _arc(p0, rx, ry, phi_deg, large, sweep, p1) -> tuple:
    """SVG 1.1 F.6.5: endpoint -> centre parameterisation (radii corrected per F.6.6)."""
    rx, ry = abs(rx), abs(ry)
    if rx == 0 or ry == 0 or mp.norm(p1 - p0) == 0:
        return ("L", p0, p1)
    phi = mp.radians(phi_deg)
    c, s = mp.cos(phi), mp.sin(phi)
    dx, dy = (p0[0] - p1[0]) / 2, (p0[1] - p1[1]) / 2
    x1, y1 = c * dx + s * dy, -s * dx + c * dy
    lam = x1 ** 2 / rx ** 2 + y1 ** 2 / ry ** 2
    if lam > 1:
        rx, ry = rx * mp.sqrt(lam), ry * mp.sqrt(lam)
    num = rx ** 2 * ry ** 2 - rx ** 2 * y1 ** 2 - ry ** 2 * x1 ** 2
    coef = mp.sqrt(max(num, 0) / (rx ** 2 * y1 ** 2 + ry ** 2 * x1 ** 2)) * (-1 if large == sweep else 1)
    cx1, cy1 = coef * rx * y1 / ry, -coef * ry * x1 / rx
    centre = mp.matrix([c * cx1 - s * cy1 + (p0[0] + p1[0]) / 2, s * cx1 + c * cy1 + (p0[1] + p1[1]) / 2])

    def angle(ux, uy, vx, vy):
        return mp.atan2(ux * vy - uy * vx, ux * vx + uy * vy)

    t0 = angle(1, 0, (x1 - cx1) / rx, (y1 - cy1) / ry)
    dt = angle((x1 - cx1) / rx, (y1 - cy1) / ry, (-x1 - cx1) / rx, (-y1 - cy1) / ry)
    if not sweep and dt > 0:
        dt -= 2 * mp.pi
    elif sweep and dt < 0:
        dt += 2 * mp.pi
    return ("A", centre, rx, ry, phi, t0, dt)


def _point(seg, t):
    kind = seg[0]
    if kind == "L":
        return seg[1] + (seg[2] - seg[1]) * t
    if kind == "C":
        p0, c1, c2, p1 = seg[1:]
        u = 1 - t
        return u ** 3 * p0 + 3 * u ** 2 * t * c1 + 3 * u * t ** 2 * c2 + t ** 3 * p1
    centre, rx, ry, phi, t0, dt = seg[1:]
    a = t0 + dt * t
    x, y = rx * mp.cos(a), ry * mp.sin(a)
    return mp.matrix([mp.cos(phi) * x - mp.sin(phi) * y + centre[0], mp.sin(phi) * x + mp.cos(phi) * y + centre[1]])


def _speed(seg, t):
    kind = seg[0]
    if kind == "L":
        return mp.norm(seg[2] - seg[1])
    if kind == "C":
        p0, c1, c2, p1 = seg[1:]
        u = 1 - t
        v = 3 * u ** 2 * (c1 - p0) + 6 * u * t * (c2 - c1) + 3 * t ** 2 * (p1 - c2)
        return mp.norm(v)
    _, rx, ry, _, t0, dt = seg[1:]
    a = t0 + dt * t
    return abs(dt) * mp.sqrt((rx * mp.sin(a)) ** 2 + (ry * mp.cos(a)) ** 2)


def length(segs, scale=1) -> mp.mpf:
    """Total length of ``segs`` (times ``scale``), by mpmath quadrature (15 digits)."""
    with mp.workdps(20):
        return scale * mp.fsum(mp.quad(lambda t, s=s: _speed(s, t), [0, 0.25, 0.5, 0.75, 1]) for s in segs)


def sample(segs, per_segment=2000, scale=1.0) -> np.ndarray:
    """Points along ``segs`` (numpy, times ``scale``), ``per_segment`` steps each, ends included."""
    ts = np.linspace(0.0, 1.0, per_segment + 1)
    pts = [np.array([[float(v) for v in _point(s, mp.mpf(t))] for t in (ts if k == 0 else ts[1:])])
           for k, s in enumerate(segs)]
    return np.vstack(pts) * scale


def distances_to_polyline(points: np.ndarray, polyline: np.ndarray) -> np.ndarray:
    """Distance of each point to the polyline (its segments)."""
    a, b = polyline[:-1], polyline[1:]
    ab = b - a
    out = np.empty(len(points))
    for i, p in enumerate(points):
        t = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0.0, 1.0)
        out[i] = np.min(np.hypot(*(a + ab * t[:, None] - p).T))
    return out
