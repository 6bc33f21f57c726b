"""Markers in a photo: found with OpenCV's ArUco module, mapped to the board's plane, read as bends.

Needs the ``measure`` extra (``pip install embroact[measure]``: opencv-python-headless, whose
``cv2.aruco`` detects the markers); OpenCV is imported when a photo is measured, never by
``embroact --help`` or any other command.

For one photo, :func:`measure_image`

1. detects the 4x4 ArUco markers (250-id dictionary) on a copy of the photo halved until it is
   under 1400 px wide, then refines every corner to subpixel on the full photo;
2. refuses the photo when an id is seen twice (ambiguous), when fewer than 4 board markers
   are found, or when the board is seen more than :data:`MAX_TILT_DEG` from face on;
3. maps pixels to board millimetres with the homography of every found board corner
   (least squares): the perspective correction, exact for points in the board's plane;
4. per actuator whose markers appear: refuses it when one of its markers is missing, or
   when a marker's square, mapped to the plane, is foreshortened past
   :data:`MAX_MARKER_TILT_DEG` (its fin is twisted out of the board's plane), naming the marker;
5. reads each actuator's bend and centreline with :func:`embroact.predict.photomarkers.read_strip`.

Every refusal is a :class:`PhotoRefused` with a one-line reason.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...patterns.base.errors import ParameterError
from ...predict.markers import MarkerSide
from ...predict.photomarkers import PhotoLayout, StripReading, read_strip

__all__ = [
    "MAX_MARKER_TILT_DEG",
    "MAX_TILT_DEG",
    "BlockReading",
    "PhotoReading",
    "PhotoRefused",
    "load_gray",
    "measure_image",
    "require_cv2",
]

#: A board seen more obliquely than this is refused [deg] (its far side is then resolved a
#: third less finely than its near side, and depth errors grow with the tangent of the tilt).
MAX_TILT_DEG = 45.0
#: A marker whose square maps to the plane foreshortened by more than this angle is refused [deg].
MAX_MARKER_TILT_DEG = 35.0
#: A marker whose mapped side differs from the printed one by more than this fraction is not in the plane.
_SIZE_TOLERANCE = 0.25
_MIN_BOARD_MARKERS = 4
#: Markers are found on a copy of the photo halved until it is narrower than this [px].
_DETECT_PX = 1400


class PhotoRefused(ParameterError):
    """A photo that cannot be measured; the message says why, in one line."""


def require_cv2():
    """OpenCV's module, or a one-line error naming the extra to install.

    Returns
    -------
    module
        ``cv2``, with the aruco detector.

    Raises
    ------
    ParameterError
        OpenCV is missing or older than 4.7.

    Examples
    --------
    >>> hasattr(require_cv2().aruco, "ArucoDetector")
    True
    """
    try:
        import cv2
    except ImportError:
        raise ParameterError("embroact measure needs OpenCV: pip install 'embroact[measure]' "
                             "(opencv-python-headless >= 4.7)") from None
    if not hasattr(cv2, "aruco") or not hasattr(cv2.aruco, "ArucoDetector"):
        raise ParameterError(f"embroact measure needs OpenCV >= 4.7 with the aruco module, found {cv2.__version__}")
    return cv2


@dataclass(frozen=True, slots=True)
class BlockReading:
    """One actuator in a photo: its marker block, fin side, reading, and its markers' image corners.

    Attributes
    ----------
    block : int
        The actuator's marker-id block.
    side : str
        The face its fins are on (``"fabric"`` or ``"thread"``).
    strip : StripReading
        The bend the markers read.
    corners_px : numpy.ndarray (n, 4, 2)
        Each marker's corners in the image [px].

    Examples
    --------
    >>> import numpy as np
    >>> from embroact.predict.photomarkers import COUPON_LAYOUT, read_strip
    >>> s = np.arange(11) * 10.0
    >>> up = np.tile([0.0, 1.0], (11, 1))
    >>> strip = read_strip(np.column_stack([s, np.full(11, COUPON_LAYOUT.fin_offset_mm)]), np.tile([1.0, 0.0], (11, 1)), up)
    >>> BlockReading(0, "fabric", strip, np.zeros((11, 4, 2))).strip.reading_deg
    0.0
    """

    block: int
    side: str
    strip: StripReading
    corners_px: np.ndarray  # (n, 4, 2)


@dataclass(frozen=True, slots=True)
class PhotoReading:
    """What one photo says: the board's homography and tilt, and each actuator's reading.

    Attributes
    ----------
    homography : numpy.ndarray (3, 3)
        Pixels -> board millimetres.
    tilt_deg : float
        The board's tilt against the camera [deg].
    board_found : tuple of int
        The board's marker ids found.
    blocks : tuple of BlockReading
        Each actuator found.
    board_corners_px : numpy.ndarray (k, 4, 2)
        The board markers' corners in the image [px].

    Examples
    --------
    >>> import numpy as np
    >>> r = PhotoReading(np.diag([0.1, 0.1, 1.0]), 0.0, (0, 1, 2, 3), (), np.zeros((0, 4, 2)))
    >>> r.to_pixels([[1.0, 2.0]]).tolist()
    [[10.0, 20.0]]
    """

    homography: np.ndarray  # pixels -> board mm
    tilt_deg: float
    board_found: tuple[int, ...]
    blocks: tuple[BlockReading, ...]
    board_corners_px: np.ndarray  # (k, 4, 2)

    def to_pixels(self, points_mm) -> np.ndarray:
        """Board-plane points [mm] back to pixels.

        Parameters
        ----------
        points_mm : array_like (n, 2)
            Points on the board's plane [mm].

        Returns
        -------
        numpy.ndarray (n, 2)
            [px].

        Examples
        --------
        >>> import numpy as np
        >>> PhotoReading(np.eye(3), 0.0, (), (), np.zeros((0, 4, 2))).to_pixels([[1.0, 2.0]]).tolist()
        [[1.0, 2.0]]
        """
        return _apply(np.linalg.inv(self.homography), np.asarray(points_mm, dtype=np.float64))


def load_gray(path: str):
    """The photo as an 8-bit grey image (OpenCV), or a one-line error.

    Parameters
    ----------
    path : str
        An image file (JPEG, PNG, TIFF, ...).

    Returns
    -------
    numpy.ndarray of uint8 (height, width)

    Raises
    ------
    ParameterError
        Not an image OpenCV can read.

    Examples
    --------
    >>> import os, tempfile
    >>> import numpy as np
    >>> cv2 = require_cv2()
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = cv2.imwrite(os.path.join(tmp, "a.png"), np.zeros((4, 5, 3), np.uint8))
    ...     load_gray(os.path.join(tmp, "a.png")).shape
    (4, 5)
    """
    cv2 = require_cv2()
    data = np.fromfile(path, dtype=np.uint8)  # also for names OpenCV's imread cannot open
    img = cv2.imdecode(data, cv2.IMREAD_GRAYSCALE) if data.size else None
    if img is None:
        raise ParameterError(f"{path}: not an image OpenCV can read (JPEG, PNG, TIFF, ...)")
    return img


def _apply(h: np.ndarray, pts: np.ndarray) -> np.ndarray:
    p = np.concatenate([pts.reshape(-1, 2), np.ones((pts.reshape(-1, 2).shape[0], 1))], axis=1) @ h.T
    return (p[:, :2] / p[:, 2:3]).reshape(pts.shape)


def _detect(cv2, gray) -> dict[int, list[np.ndarray]]:
    """Marker corners by id: found on a copy at most :data:`_DETECT_PX` wide (a quarter of the work on
    a phone photo), then refined to subpixel on the full image."""
    scale = 1
    while gray.shape[1] / (2 * scale) >= _DETECT_PX:
        scale *= 2
    small = gray if scale == 1 else cv2.resize(gray, (gray.shape[1] // scale, gray.shape[0] // scale),
                                               interpolation=cv2.INTER_AREA)
    params = cv2.aruco.DetectorParameters()
    params.cornerRefinementMethod = cv2.aruco.CORNER_REFINE_SUBPIX if scale == 1 else cv2.aruco.CORNER_REFINE_NONE
    # two adaptive-threshold windows (7 and 17 px) instead of OpenCV's three (3, 13, 23): a marker cell is
    # 3-8 px on the reduced copy; a third of the detection time
    params.adaptiveThreshWinSizeMin, params.adaptiveThreshWinSizeMax, params.adaptiveThreshWinSizeStep = 7, 17, 10
    detector = cv2.aruco.ArucoDetector(cv2.aruco.getPredefinedDictionary(cv2.aruco.DICT_4X4_250), params)
    corners, ids, _ = detector.detectMarkers(small)
    found: dict[int, list[np.ndarray]] = {}
    if ids is None or len(ids) == 0:  # OpenCV 4 gives None, OpenCV 5 an empty array
        return found
    pts = np.concatenate([np.asarray(c, dtype=np.float32).reshape(4, 2) for c in corners])
    if scale > 1:  # pixel centres: full = scale * small + (scale - 1) / 2
        pts = pts * scale + (scale - 1) / 2.0
    side = float(np.median(np.linalg.norm(pts.reshape(-1, 4, 2) - np.roll(pts.reshape(-1, 4, 2), 1, axis=1), axis=2)))
    win = int(max(2, min(6, round(side / 12))))
    criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 50, 0.01)
    pts = cv2.cornerSubPix(gray, pts.reshape(-1, 1, 2), (win, win), (-1, -1), criteria).reshape(-1, 4, 2)
    for c, i in zip(pts, ids.ravel().tolist()):
        found.setdefault(int(i), []).append(np.asarray(c, dtype=np.float64))
    return found


def _tilt_deg(h: np.ndarray, at_mm: np.ndarray) -> float:
    """How far from face on the plane is seen at ``at_mm``: arccos of the plane-to-image map's singular-value ratio."""
    inv = np.linalg.inv(h)
    eps = 1.0
    u0 = _apply(inv, at_mm)
    jac = np.stack([(_apply(inv, at_mm + [eps, 0.0]) - u0) / eps, (_apply(inv, at_mm + [0.0, eps]) - u0) / eps], axis=1)
    s = np.linalg.svd(jac, compute_uv=False)
    return float(np.degrees(np.arccos(np.clip(s[1] / s[0], 0.0, 1.0))))


def _ids_text(ids) -> str:
    return ", ".join(str(i) for i in ids)


def measure_image(gray, layout: PhotoLayout, sides: dict[int, str] | None = None, *, expect=None) -> PhotoReading:
    """Measure one grey image (module docstring).

    Parameters
    ----------
    gray : ndarray
        8-bit grey image.
    layout : PhotoLayout
        The board's and the fins' layout.
    sides : dict of block -> ``"fabric"`` or ``"thread"``, optional
        Fin side of each actuator block (default fabric).
    expect : iterable of int, optional
        Blocks that must be in the picture (a missing one is refused).

    Returns
    -------
    PhotoReading

    Raises
    ------
    PhotoRefused
        The photo cannot be measured (too few board markers, a marker twice, a block missing);
        the message says why.

    Examples
    --------
    >>> import numpy as np
    >>> from embroact.predict.photomarkers import COUPON_LAYOUT
    >>> try:
    ...     measure_image(np.full((200, 300), 255, np.uint8), COUPON_LAYOUT)
    ... except PhotoRefused as exc:
    ...     print(exc)
    reference board: 0 of its 8 markers found, at least 4 needed (not found: ids 0, 1, 2, 3, 4, 5, 6, 7)
    """
    cv2 = require_cv2()
    found = _detect(cv2, gray)
    twice = sorted(i for i, v in found.items() if len(v) > 1)
    if twice:
        raise PhotoRefused(f"ambiguous: marker id {twice[0]} found {len(found[twice[0]])} times (two prints of one "
                           "marker in the picture)")
    board = layout.board
    on_board = [k for k, i in enumerate(board.ids) if i in found]
    if len(on_board) < _MIN_BOARD_MARKERS:
        missing = [i for i in board.ids if i not in found]
        raise PhotoRefused(f"reference board: {len(on_board)} of its {len(board.ids)} markers found, at least "
                           f"{_MIN_BOARD_MARKERS} needed (not found: ids {_ids_text(missing)})")
    img_pts = np.concatenate([found[board.ids[k]][0] for k in on_board])
    mm_pts = np.concatenate([board.corners_mm(k) for k in on_board])
    h, _ = cv2.findHomography(img_pts, mm_pts, 0)
    if h is None or not np.all(np.isfinite(h)):
        raise PhotoRefused("reference board: its markers give no perspective (are they all on one line?)")
    centre = np.mean(np.asarray(board.centres_mm), axis=0)
    tilt = _tilt_deg(h, centre)
    if tilt > MAX_TILT_DEG:
        raise PhotoRefused(f"too oblique: the board is seen {tilt:.0f} deg from face on (at most {MAX_TILT_DEG:g} deg); "
                           "photograph it more squarely")
    blocks: dict[int, dict[int, np.ndarray]] = {}
    for i, c in found.items():
        where = layout.block_of(i)
        if where is not None:
            blocks.setdefault(where[0], {})[where[1]] = c[0]
    wanted = sorted(set(blocks) | set(expect or ()))
    if not wanted:
        raise PhotoRefused("no actuator markers found (ids from "
                           f"{layout.first_id}); is the strip in the picture and in focus?")
    n = layout.markers.markers_per_side
    out = []
    for b in wanted:
        ids = layout.ids(b)
        have = blocks.get(b, {})
        missing = [ids[j] for j in range(n) if j not in have]
        if missing:
            raise PhotoRefused(f"actuator block {b}: marker id(s) {_ids_text(missing)} not found (fin "
                               f"{_ids_text(ids.index(i) for i in missing)} of {n}: hidden, out of the picture or "
                               "out of focus)")
        corners_px = np.stack([have[j] for j in range(n)])
        corners = _apply(h, corners_px)
        sides_mm = np.linalg.norm(np.roll(corners, -1, axis=1) - corners, axis=2)  # (n, 4)
        for j in range(n):
            ratio = sides_mm[j].min() / sides_mm[j].max()
            seen = float(np.degrees(np.arccos(np.clip(ratio, 0.0, 1.0))))
            if seen > MAX_MARKER_TILT_DEG:
                raise PhotoRefused(f"actuator block {b}: marker id {ids[j]} (fin {j}) too oblique: seen {seen:.0f} deg "
                                   f"out of the board's plane (at most {MAX_MARKER_TILT_DEG:g} deg); straighten its fin")
            size = float(sides_mm[j].mean())
            if abs(size / layout.marker_size_mm - 1.0) > _SIZE_TOLERANCE:
                raise PhotoRefused(f"actuator block {b}: marker id {ids[j]} (fin {j}) measures {size:.1f} mm on the "
                                   f"board's scale, printed {layout.marker_size_mm:g} mm: it is not in the board's "
                                   "plane (or printed at another scale)")
        x_axes = (corners[:, 1] - corners[:, 0] + corners[:, 2] - corners[:, 3]) / 2.0
        up_axes = (corners[:, 0] - corners[:, 3] + corners[:, 1] - corners[:, 2]) / 2.0
        side = (sides or {}).get(b, MarkerSide.FABRIC.value)
        strip = read_strip(corners.mean(axis=1), x_axes, up_axes, layout, side=side)
        out.append(BlockReading(b, side, strip, corners_px))
    board_px = np.stack([found[board.ids[k]][0] for k in on_board])
    return PhotoReading(h, tilt, tuple(board.ids[k] for k in on_board), tuple(out), board_px)
