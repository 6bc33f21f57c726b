"""The annotated picture of a measured photo: what ``embroact measure`` found and read.

Board markers outlined in green, fin markers in blue, the fabric-line points the fins give
as red dots, the fitted centreline in red, and per actuator its reading; a header line
with the pressure, the branch and the board's tilt, then one line per actuator. The picture is scaled to at most
:data:`MAX_WIDTH_PX` wide and encoded as JPEG (OpenCV).
"""
from __future__ import annotations

import numpy as np

from .detect import PhotoReading, require_cv2

__all__ = ["MAX_WIDTH_PX", "annotated_jpeg"]

MAX_WIDTH_PX = 1600
_GREEN, _BLUE, _RED, _WHITE, _BLACK = (40, 170, 40), (200, 90, 20), (30, 30, 220), (255, 255, 255), (0, 0, 0)


def _text(cv2, img, text: str, org, scale: float) -> None:
    for colour, width in ((_WHITE, 5), (_BLACK, 2)):
        cv2.putText(img, text, (int(org[0]), int(org[1])), cv2.FONT_HERSHEY_SIMPLEX, scale, colour, width, cv2.LINE_AA)


def annotated_jpeg(image, reading: PhotoReading, header: str, labels: dict[int, str]) -> bytes:
    """JPEG bytes of ``image`` (grey or colour) with ``reading`` drawn on it; ``labels``: block -> name.

    Parameters
    ----------
    image : numpy.ndarray
        The photo (grey or BGR), as read.
    reading : PhotoReading
        What :func:`~embroact.export.photo.detect.measure_image` found in it.
    header : str
        The first line written on the picture.
    labels : dict of int to str
        Actuator names by marker block.

    Returns
    -------
    bytes
        A JPEG, at most ``MAX_WIDTH_PX`` wide (empty if OpenCV cannot encode it).

    Examples
    --------
    >>> import numpy as np
    >>> reading = PhotoReading(np.eye(3), 0.0, (), (), np.zeros((0, 4, 2)))
    >>> annotated_jpeg(np.full((100, 200), 255, np.uint8), reading, "photo 1", {})[:3]
    b'\\xff\\xd8\\xff'
    """
    cv2 = require_cv2()
    scale = min(1.0, MAX_WIDTH_PX / image.shape[1])
    img = image if scale == 1.0 else cv2.resize(image, (round(image.shape[1] * scale), round(image.shape[0] * scale)),
                                                interpolation=cv2.INTER_AREA)
    img = cv2.cvtColor(img, cv2.COLOR_GRAY2BGR) if img.ndim == 2 else img.copy()
    width = max(1, round(2 * img.shape[1] / 1200))

    def px(points) -> np.ndarray:
        return np.round(np.asarray(points) * scale).astype(np.int32)

    for quad in reading.board_corners_px:
        cv2.polylines(img, [px(quad)], True, _GREEN, width + 1, cv2.LINE_AA)
    for b in reading.blocks:
        for quad in b.corners_px:
            cv2.polylines(img, [px(quad)], True, _BLUE, width, cv2.LINE_AA)
        line = px(reading.to_pixels(b.strip.centreline_mm))
        cv2.polylines(img, [line], False, _RED, width + 1, cv2.LINE_AA)
        for p in px(reading.to_pixels(b.strip.points_mm)):
            cv2.circle(img, (int(p[0]), int(p[1])), width + 2, _RED, -1, cv2.LINE_AA)
    size = 0.7 * img.shape[1] / 1200
    _text(cv2, img, header, (12, 30 * size / 0.7), size)
    for k, b in enumerate(reading.blocks):  # one line per actuator under the header, clear of the fins
        _text(cv2, img, f"{labels.get(b.block, f'block {b.block}')}: {b.strip.reading_deg:.1f} deg "
                        f"(centreline fit rms {b.strip.rms_mm:.2f} mm)", (12, (62 + 30 * k) * size / 0.7), size)
    ok, data = cv2.imencode(".jpg", img, [cv2.IMWRITE_JPEG_QUALITY, 90])
    return bytes(data) if ok else b""
