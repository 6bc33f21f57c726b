"""The paper's calibration read by hand where embroact sews the paper's 30 and 60 deg crosses.

w = 7 mm, s = 1.4 mm held: the legs close with tan(alpha0) = 3/5 (30.96 deg, asked 30) and 17/10
(59.53 deg, asked 60). The paper's points (15, 30, 45, 60 deg; G 2.9, 12, 1.3, 2.9 MPa; P0 150, 160,
170, 200 kPa) lie 15 deg apart, and the lookup is the monotone cubic of Fritsch and Carlson, whose
slopes here are: G' = 0 at 30 and 45 deg (G turns there); G' at 60 from the three-point end formula
(3 x 1.6/15 + 10.7/15) / 2 = 0.517, limited to three times the last secant, 3 x 1.6/15 = 0.32;
P0' = 2/3 at 30 (two secants of 2/3), 2 / (3/2 + 1/2) = 1 at 45 (harmonic mean of 2/3 and 2), and
(3 x 2 - 2/3) / 2 = 8/3 at 60 [kPa/deg].
"""
import math


def hermite(x, x0, x1, y0, y1, m0, m1):
    """The cubic Hermite piece on [x0, x1] with end values ``y0``, ``y1`` and end slopes ``m0``, ``m1``."""
    t, h = (x - x0) / (x1 - x0), x1 - x0
    return ((2 * t**3 - 3 * t**2 + 1) * y0 + (t**3 - 2 * t**2 + t) * h * m0 + (-2 * t**3 + 3 * t**2) * y1
            + (t**3 - t**2) * h * m1)


A30_DEG, A60_DEG = math.degrees(math.atan(0.6)), math.degrees(math.atan(1.7))
#: name: (G [MPa], P0 [kPa]) at the sewn angle.
SEWN_FIT = {
    "cross a30": (hermite(A30_DEG, 30.0, 45.0, 12.0, 1.3, 0.0, 0.0),
                  hermite(A30_DEG, 30.0, 45.0, 160.0, 170.0, 2.0 / 3.0, 1.0)),
    "cross a60": (hermite(A60_DEG, 45.0, 60.0, 1.3, 2.9, 0.0, 0.32),
                  hermite(A60_DEG, 45.0, 60.0, 170.0, 200.0, 1.0, 8.0 / 3.0)),
}
