"""``embroact measure`` on synthetic photos: error distribution and the time of a 12-photo set.

Photos come from the tests' renderer (``tests/photo_renderer.py``: a 100 mm strip bent by
a seeded total of -200..280 deg over 3 uneven arcs, 11 fins, the reference board, a
pinhole camera tilted 5-25 deg about a random axis, blur, uneven light, pixel noise, and
each marker displaced by 0.5 px rms), 2400 x 1800 px (about 10 px per mm on the board).

* **Accuracy**: over ``--photos`` seeded photos (default 120), the error of the bend
  reading against the true marker reading [deg] and the largest distance between the
  measured and the true centreline [mm]: median, 95th percentile, maximum; and how many
  photos were refused (none should be). Targets: every reading within 1 deg, every
  centreline within 0.5 mm.
* **Speed**: ``embroact measure`` on 12 photos (JPEG, as a phone writes them; annotated
  pictures and the centrelines written) in a subprocess pinned to one core
  (``taskset -c 0``), against the floor measured in the same run: a subprocess that only
  decodes the 12 JPEGs and runs OpenCV's ArUco detector on them, pinned the same way.
  Median of 3 runs. Target: under 5 s.

Run: ``python benchmarks/photo_bench.py [--photos N] [--quick]``.
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests"))

READING_LIMIT_DEG, CENTRELINE_LIMIT_MM, TIME_LIMIT_S = 1.0, 0.5, 5.0

_FLOOR = """
import sys, cv2, numpy as np
det = cv2.aruco.ArucoDetector(cv2.aruco.getPredefinedDictionary(cv2.aruco.DICT_4X4_250), cv2.aruco.DetectorParameters())
for p in sys.argv[1:]:
    det.detectMarkers(cv2.imdecode(np.fromfile(p, np.uint8), cv2.IMREAD_GRAYSCALE))
"""


def _photo(seed: int):
    import photo_renderer as pr

    rng = np.random.default_rng(seed)
    theta = rng.uniform(-200.0, 280.0)
    side = "thread" if theta >= 0 else "fabric"  # the fins outside the bend, as the fin sheet says
    truth = pr.strip(theta, rng, side=side)
    return truth, pr.render(truth, rng, side=side, tilt_deg=rng.uniform(5.0, 25.0), noise_px=0.5), side


def accuracy(n: int) -> dict:
    """Reading and centreline errors over ``n`` seeded photos."""
    from embroact.export.photo.detect import PhotoRefused, measure_image
    from embroact.predict.photomarkers import COUPON_LAYOUT

    reading, line, refused = [], [], []
    s = np.linspace(0.0, 100.0, 201)
    for seed in range(n):
        truth, img, side = _photo(1000 + seed)
        try:
            (b,) = measure_image(img, COUPON_LAYOUT, {0: side}).blocks
        except PhotoRefused as exc:
            refused.append((seed, str(exc)))
            continue
        reading.append(abs(b.strip.reading_deg - truth.reading_deg))
        line.append(float(np.linalg.norm(b.strip.centreline_at(s) - truth.line(s), axis=1).max()))
    return {"photos": n, "refused": refused, "reading_err_deg": reading, "centreline_err_mm": line}


def _timed(cmd: list[str], runs: int) -> float:
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def speed(runs: int, count: int = 12) -> dict:
    """``embroact measure`` on ``count`` JPEG photos against the decode-and-detect floor, one core."""
    import cv2

    with tempfile.TemporaryDirectory() as d:
        paths = []
        for k in range(count):
            _, img, _ = _photo(2000 + k)
            p = os.path.join(d, f"strip_{25 * k}kPa.jpg")
            cv2.imwrite(p, img, [cv2.IMWRITE_JPEG_QUALITY, 92])
            paths.append(p)
        pin = ["taskset", "-c", "0"] if os.path.exists("/usr/bin/taskset") else []
        env_cmd = [sys.executable, "-m", "embroact", "measure", *paths, "-o", os.path.join(d, "m.csv")]
        floor = _timed(pin + [sys.executable, "-c", _FLOOR, *paths], runs)
        full = _timed(pin + env_cmd, runs)
    return {"photos": count, "measure_s": full, "floor_s": floor, "ratio": full / floor, "one_core": bool(pin)}


def _dist(values, unit: str) -> str:
    v = np.asarray(values)
    return (f"median {np.median(v):.3f} {unit}, 95th percentile {np.percentile(v, 95):.3f} {unit}, "
            f"max {v.max():.3f} {unit}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--photos", type=int, default=120)
    ap.add_argument("--quick", action="store_true", help="3 photos, 1 timing run of 2 photos (smoke test)")
    args = ap.parse_args(argv)
    n, runs, count = (3, 1, 2) if args.quick else (args.photos, 3, 12)
    acc = accuracy(n)
    ok_read = bool(acc["reading_err_deg"]) and max(acc["reading_err_deg"]) < READING_LIMIT_DEG
    ok_line = bool(acc["centreline_err_mm"]) and max(acc["centreline_err_mm"]) < CENTRELINE_LIMIT_MM
    print(f"accuracy over {n} seeded photos (tilt 5-25 deg, 0.5 px marker noise), {len(acc['refused'])} refused")
    print(f"  reading error:     {_dist(acc['reading_err_deg'], 'deg')}  "
          f"[{'PASS' if ok_read else 'FAIL'} < {READING_LIMIT_DEG:g} deg]")
    print(f"  centreline error:  {_dist(acc['centreline_err_mm'], 'mm')}  "
          f"[{'PASS' if ok_line else 'FAIL'} < {CENTRELINE_LIMIT_MM:g} mm]")
    for seed, why in acc["refused"]:
        print(f"  refused seed {seed}: {why}")
    sp = speed(runs, count)
    ok_time = sp["measure_s"] < TIME_LIMIT_S * sp["photos"] / 12
    print(f"speed: embroact measure on {sp['photos']} photos {sp['measure_s']:.2f} s "
          f"({'one core' if sp['one_core'] else 'all cores'}), decode+detect floor {sp['floor_s']:.2f} s, "
          f"ratio {sp['ratio']:.2f}  [{'PASS' if ok_time else 'FAIL'} < {TIME_LIMIT_S:g} s for 12]")
    return 0 if (ok_read and ok_line and not acc["refused"]) or args.quick else 1


if __name__ == "__main__":
    sys.exit(main())
