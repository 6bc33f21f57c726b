"""Synthetic photos of a bent strip with marker fins and the reference board, for the measure tests.

Independent of ``embroact measure``: the strip is a chain of arcs from known segment
curvatures, integrated here; markers are OpenCV's own ArUco images, pasted on fins at the
printed layout (11 fins 10 mm apart from the clamp, 5 mm markers whose centres stand 5 mm
off the fabric line, up away from it; board markers of 12 mm at the board sheet's
positions); the plane is seen through a pinhole camera tilted by a chosen angle, then
blurred, lit unevenly and given pixel noise. Each marker is also displaced at random by
``noise_px`` (rms per axis, in pixels of the photo), the noise the measurement must stand.

The true reading is the sum of the turning angles between consecutive chords of the
markers' points on the fabric line, computed here from the analytic curve.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

cv2 = None  # imported by render(): the tests skip without OpenCV

SPACING_MM, N_FINS, FIN_MM, FIN_OFFSET_MM, FIRST_ID = 10.0, 11, 5.0, 5.0, 8
BOARD_IDS = (0, 1, 2, 3, 4, 5, 6, 7)
BOARD_CENTRES = ((-80.0, 55.0), (0.0, 55.0), (80.0, 55.0), (80.0, 0.0), (80.0, -55.0), (0.0, -55.0), (-80.0, -55.0),
                 (-80.0, 0.0))
BOARD_MM = 12.0
#: Plane texture: x in [-100, 100], y in [-75, 75] mm.
_X0, _Y1, _TEX_PX_MM = -100.0, 75.0, 20.0


@dataclass
class Truth:
    reading_deg: float
    lengths_mm: np.ndarray
    kappa_per_mm: np.ndarray
    start_mm: np.ndarray
    heading_rad: float
    back_sign: float  # +1: the back of the fabric is to the left of the tangent in the board frame

    def line(self, s):
        """Fabric-line points at arc lengths s [mm] (board frame)."""
        return _chain(self.start_mm, self.heading_rad, self.lengths_mm, self.kappa_per_mm, np.asarray(s, float))

    def tangent(self, s):
        return _heading(self.heading_rad, self.lengths_mm, self.kappa_per_mm, np.asarray(s, float))


def _heading(phi0, lengths, kappa, s):
    edges = np.concatenate([[0.0], np.cumsum(lengths)])
    i = np.clip(np.searchsorted(edges, s, side="right") - 1, 0, len(lengths) - 1)
    turn = np.concatenate([[0.0], np.cumsum(kappa * lengths)])
    return phi0 + turn[i] + kappa[i] * (s - edges[i])


def _chain(start, phi0, lengths, kappa, s, steps=4000):
    """Points by numerical integration of the heading (independent of closed forms)."""
    fine = np.linspace(0.0, lengths.sum() + 20.0, steps * 2 + 1)
    phi = _heading(phi0, np.append(lengths, 20.0), np.append(kappa, 0.0), fine)
    dx, dy = np.cos(phi), np.sin(phi)
    h = fine[1] - fine[0]
    x = start[0] + np.concatenate([[0.0], np.cumsum((dx[1:] + dx[:-1]) * h / 2)])
    y = start[1] + np.concatenate([[0.0], np.cumsum((dy[1:] + dy[:-1]) * h / 2)])
    return np.stack([np.interp(s, fine, x), np.interp(s, fine, y)], axis=-1)


def true_reading_deg(points):
    d = np.diff(points, axis=0)
    ang = np.arctan2(d[:-1, 0] * d[1:, 1] - d[:-1, 1] * d[1:, 0], (d[:-1] * d[1:]).sum(axis=1))
    return float(np.degrees(ang.sum()))


def strip(theta_deg, rng, *, side="thread", segments=3):
    """A 100 mm strip bending theta_deg in total, unevenly over ``segments`` arcs, placed in the board window."""
    lengths = np.full(segments, 100.0 / segments)
    w = rng.uniform(0.5, 1.5, segments)
    kappa = np.radians(theta_deg) * w / (w * lengths).sum()
    back_sign = 1.0 if rng.random() < 0.5 else -1.0  # which way the photo sees the back of the fabric
    # a positive bend turns toward the back: counter-clockwise when the back is to the left
    kappa = kappa * back_sign
    start = np.array([-50.0, -38.0 if kappa.sum() > 0 else 38.0]) + rng.normal(0, 2.0, 2)
    t = Truth(0.0, lengths, kappa, start, float(rng.normal(0, 0.05)), back_sign)
    t.reading_deg = true_reading_deg(t.line(np.arange(N_FINS) * SPACING_MM)) * back_sign
    return t


def _paste(tex, img, centre, xdir, ydir, size_mm, squash=1.0):
    """Paste marker image ``img`` (top row = up) with its centre at ``centre`` [mm] and axes xdir, ydir."""
    m = img.shape[0]
    a = xdir * size_mm * squash / m
    b = -ydir * size_mm / m  # image rows grow downward, away from up
    o = centre - (m / 2.0) * a - (m / 2.0) * b
    # plane mm -> texture px: u = (x - X0) R, v = (Y1 - y) R
    to_px = np.array([[_TEX_PX_MM, 0.0], [0.0, -_TEX_PX_MM]])
    A = np.column_stack([to_px @ a, to_px @ b, to_px @ o + [-_X0 * _TEX_PX_MM, _Y1 * _TEX_PX_MM]])
    corners = np.array([[0, 0, 1], [m, 0, 1], [m, m, 1], [0, m, 1]], float) @ A.T
    lo = np.floor(corners.min(axis=0)).astype(int) - 2
    hi = np.ceil(corners.max(axis=0)).astype(int) + 2
    lo = np.maximum(lo, 0)
    hi = np.minimum(hi, [tex.shape[1], tex.shape[0]])
    A2 = A.copy()
    A2[:, 2] -= lo
    size = (int(hi[0] - lo[0]), int(hi[1] - lo[1]))
    patch = cv2.warpAffine(img.astype(np.float32), A2, size, flags=cv2.INTER_LINEAR)
    mask = cv2.warpAffine(np.ones_like(img, dtype=np.float32), A2, size, flags=cv2.INTER_LINEAR)
    roi = tex[lo[1]:hi[1], lo[0]:hi[0]]
    roi[:] = roi * (1 - mask) + patch * mask


def _card(tex, centre, xdir, ydir, w_mm, h_mm, value):
    c = np.array([centre + sx * xdir * w_mm / 2 + sy * ydir * h_mm / 2 for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))])
    px = np.column_stack([(c[:, 0] - _X0) * _TEX_PX_MM, (_Y1 - c[:, 1]) * _TEX_PX_MM])
    cv2.fillConvexPoly(tex, np.round(px * 16).astype(np.int32), float(value), lineType=cv2.LINE_AA, shift=4)


def render(truth: Truth, rng, *, side="thread", block=0, tilt_deg=15.0, noise_px=0.5, blur_px=1.0,
           image_size=(2400, 1800), hide=None, twist=None, twist_deg=50.0, duplicate=False):
    """The photo (8-bit grey) of ``truth``'s strip with fins on ``side``; ``hide``/``twist``: a fin index."""
    global cv2
    import cv2 as _cv2

    cv2 = _cv2
    aruco = cv2.aruco.getPredefinedDictionary(cv2.aruco.DICT_4X4_250)
    W, H = image_size
    # camera: looks at the board centre from D mm, tilted by tilt_deg about a random in-plane axis
    D = 330.0
    f = W * D / 250.0  # the 250 mm field across the image width when face on
    px_per_mm = f / D
    jitter_mm = noise_px / px_per_mm
    tex = np.full((int(150 * _TEX_PX_MM), int(200 * _TEX_PX_MM)), 185.0, np.float32)
    for i, c in zip(BOARD_IDS, BOARD_CENTRES):
        m = cv2.aruco.generateImageMarker(aruco, i, 120)
        cc = np.array(c) + rng.normal(0, jitter_mm, 2)
        _card(tex, cc, np.array([1.0, 0]), np.array([0, 1.0]), BOARD_MM * 8 / 6, BOARD_MM * 8 / 6, 250)
        _paste(tex, m, cc, np.array([1.0, 0]), np.array([0, 1.0]), BOARD_MM)
    # the strip: fabric band and tube along the fabric line
    s_line = np.linspace(0, 100, 401)
    line = truth.line(s_line)
    px = np.column_stack([(line[:, 0] - _X0) * _TEX_PX_MM, (_Y1 - line[:, 1]) * _TEX_PX_MM])
    cv2.polylines(tex, [np.round(px * 16).astype(np.int32)], False, 90.0, thickness=int(3 * _TEX_PX_MM),
                  lineType=cv2.LINE_AA, shift=4)
    s_fins = np.arange(N_FINS) * SPACING_MM
    pts, phi = truth.line(s_fins), truth.tangent(s_fins)
    back = truth.back_sign * np.stack([-np.sin(phi), np.cos(phi)], axis=1)  # toward the back, in the plane
    up = back if side == "fabric" else -back
    for j in range(N_FINS):
        t = np.array([np.cos(phi[j]), np.sin(phi[j])])
        # the printed frame: x along the tangent, up away from the fabric; seen from the printed face,
        # (x, up) must be counter-clockwise: flip x when the photo sees the fin from its back... it cannot,
        # the marker would read mirrored: the renderer keeps the printed face to the camera
        xdir = t if (t[0] * up[j][1] - t[1] * up[j][0]) > 0 else -t
        centre = pts[j] + FIN_OFFSET_MM * up[j] + rng.normal(0, jitter_mm, 2)
        _card(tex, pts[j] + (FIN_OFFSET_MM - 0.5) * up[j], xdir, up[j], FIN_MM * 8 / 6, FIN_OFFSET_MM + FIN_MM, 245)
        if hide == j:
            continue
        m = cv2.aruco.generateImageMarker(aruco, FIRST_ID + block * N_FINS + j, 96)
        squash = np.cos(np.radians(twist_deg)) if twist == j else 1.0
        _paste(tex, m, centre, xdir, up[j], FIN_MM, squash)
    if duplicate:
        m = cv2.aruco.generateImageMarker(aruco, FIRST_ID + block * N_FINS, 96)
        _paste(tex, m, np.array([60.0, -40.0]), np.array([1.0, 0]), np.array([0, 1.0]), FIN_MM)
    tex = cv2.GaussianBlur(tex, (0, 0), 0.5 * _TEX_PX_MM / px_per_mm)
    # pinhole camera
    axis = rng.normal(size=2)
    axis /= np.linalg.norm(axis)
    rvec = np.array([axis[0], axis[1], 0.0]) * np.radians(tilt_deg)
    R, _ = cv2.Rodrigues(rvec)
    centre_w = np.array([0.0, 0.0, 0.0]) + np.append(rng.normal(0, 3.0, 2), 0)
    # camera looks along -z of the world at the board: world->camera flips y and z (image y down)
    flip = np.diag([1.0, -1.0, -1.0])
    Rc = R @ flip
    cam_pos = centre_w + Rc.T @ np.array([0.0, 0.0, -D])
    t = -Rc @ cam_pos
    K = np.array([[f, 0, W / 2], [0, f, H / 2], [0, 0, 1]])
    Hcam = K @ np.column_stack([Rc[:, 0], Rc[:, 1], t])  # plane (x, y, 1) -> image
    T = np.array([[1 / _TEX_PX_MM, 0, _X0], [0, -1 / _TEX_PX_MM, _Y1], [0, 0, 1]])  # texture px -> plane mm
    img = cv2.warpPerspective(tex, Hcam @ T, (W, H), flags=cv2.INTER_LINEAR, borderValue=120.0)
    if blur_px:
        img = cv2.GaussianBlur(img, (0, 0), blur_px)
    yy, xx = np.mgrid[0:H, 0:W]
    g = rng.normal(size=2)
    light = 0.85 + 0.25 * ((xx / W - 0.5) * g[0] + (yy / H - 0.5) * g[1])
    img = img * light + rng.normal(0, 3.0, img.shape)
    return np.clip(img, 0, 255).astype(np.uint8)
