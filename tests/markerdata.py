"""Marker coordinates on a bent strip, built by hand for the tests (independent of predict/markers.py).

A uniform bend of the fabric line over l0 (straight beyond), clamped at the origin with its
tangent along +x, turning toward +y for positive angles; rows of markers beside the
embroidery lie at z = -+ ``lateral``.
"""
import math

import numpy as np


def strip_points(theta_deg, offsets_mm, l0=100.0):
    """Points at arc lengths s on a uniform bend of l0 (straight beyond), by hand: base at 0, tangent +x."""
    t = math.radians(theta_deg)
    out = []
    for s in offsets_mm:
        on = min(s, l0)
        if t == 0.0:
            x, y = on, 0.0
        else:
            R = l0 / t
            x, y = R * math.sin(on / R), R * (1 - math.cos(on / R))
        out.append((x + (s - on) * math.cos(t), y + (s - on) * math.sin(t)))
    return np.array(out)


def chord_turning_deg(theta_deg, offsets_mm, l0=100.0):
    """Turning between the first and last chord of markers at arc lengths ``offsets_mm`` on a uniform bend
    of ``l0`` by ``theta_deg`` [deg], by hand: what a marker layout with those offsets reads."""
    d = np.diff(strip_points(theta_deg, offsets_mm, l0), axis=0)
    turn = np.arctan2(d[:-1, 0] * d[1:, 1] - d[:-1, 1] * d[1:, 0], np.einsum("ij,ij->i", d[:-1], d[1:]))
    return math.degrees(turn.sum())


def paper_frame(theta_deg, offset=0.0, rot=np.eye(3), lateral=8.0, l0=100.0):
    """The paper's layout (2 rows of 7 markers, 10 mm apart, the first ``offset`` mm from the clamp), rotated."""
    s = offset + 10.0 * np.arange(7)
    xy = strip_points(theta_deg, s, l0)
    row = np.concatenate([xy, np.zeros((7, 1))], axis=1)
    return np.concatenate([row + [0, 0, -lateral], row + [0, 0, lateral]]) @ rot.T
