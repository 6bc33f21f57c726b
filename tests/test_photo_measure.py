"""``embroact measure``: synthetic photos (tests/photo_renderer.py: a bent strip from known segment
curvatures, fins at the layout's positions, a pinhole camera tilted 5-25 deg, blur, uneven light, noise)
are read within 1 deg of the true marker reading and 0.5 mm of the true centreline; bad photos are
refused in one line naming the marker."""
import csv
import os

import numpy as np
import pytest

cv2 = pytest.importorskip("cv2")

import photo_renderer as pr  # noqa: E402  (after the OpenCV skip)
from embroact.export.cli.main import main  # noqa: E402  (after the OpenCV skip)
from embroact.export.photo.detect import PhotoRefused, measure_image  # noqa: E402  (after the OpenCV skip)
from embroact.predict.photomarkers import COUPON_LAYOUT  # noqa: E402  (after the OpenCV skip)


def _photo(seed, **kw):
    rng = np.random.default_rng(seed)
    theta = kw.pop("theta_deg", rng.uniform(-200.0, 280.0))
    side = kw.pop("side", "thread" if theta >= 0 else "fabric")  # outside the bend, as the fin sheet says
    truth = pr.strip(theta, rng, side=side)
    img = pr.render(truth, rng, side=side, tilt_deg=kw.pop("tilt_deg", rng.uniform(5.0, 25.0)), **kw)
    return truth, img, side


@pytest.mark.parametrize("seed", range(6))
def test_reading_and_centreline_within_limits(seed):
    truth, img, side = _photo(seed, noise_px=0.5)
    r = measure_image(img, COUPON_LAYOUT, {0: side})
    (b,) = r.blocks
    assert abs(b.strip.reading_deg - truth.reading_deg) < 1.0
    s = np.linspace(0.0, 100.0, 201)
    assert np.linalg.norm(b.strip.centreline_at(s) - truth.line(s), axis=1).max() < 0.5
    assert 4.0 < r.tilt_deg < 27.0


def test_straight_strip_reads_zero():
    truth, img, side = _photo(11, theta_deg=0.0, noise_px=0.0)
    (b,) = measure_image(img, COUPON_LAYOUT, {0: side}).blocks
    assert truth.reading_deg == pytest.approx(0.0, abs=1e-9)
    assert abs(b.strip.reading_deg) < 0.3


def _refusal(img, side="fabric"):
    with pytest.raises(PhotoRefused) as exc:
        measure_image(img, COUPON_LAYOUT, {0: side})
    msg = str(exc.value)
    assert "\n" not in msg
    return msg


def test_hidden_marker_refused_naming_it():
    _, img, side = _photo(3, hide=4)
    msg = _refusal(img, side)
    assert "marker id(s) 12 not found" in msg and "fin 4 of 11" in msg


def test_twisted_fin_refused_naming_it():
    _, img, side = _photo(4, twist=7, twist_deg=55.0)
    msg = _refusal(img, side)
    assert "marker id 15 (fin 7) too oblique" in msg


def test_oblique_photo_refused():
    _, img, side = _photo(5, tilt_deg=52.0)
    msg = _refusal(img, side)
    assert msg.startswith("too oblique: the board is seen 5") and "(at most 45 deg)" in msg


def test_duplicate_marker_refused():
    _, img, side = _photo(6, duplicate=True)
    assert _refusal(img, side).startswith("ambiguous: marker id 8 found 2 times")


def test_measure_fills_the_coupon_sheet(tmp_path, capsys):
    coupon = tmp_path / "coupon"
    coupon.mkdir()
    assert main(["calibrate", "coupon", "--patterns", "zigzag", "--width-count", "2", "--out", str(coupon)]) == 0
    photos = tmp_path / "photos"
    photos.mkdir()
    truths = {}
    for name, seed, bend in (("w5_100kPa.png", 21, 110.0), ("w5_100kPa_down.png", 22, 95.0)):
        truth, img, _ = _photo(seed, theta_deg=bend)  # block 0: the coupon's first zigzag, fins on the thread side
        cv2.imwrite(str(photos / name), img)
        truths[name] = truth.reading_deg
    _, bad, _ = _photo(23, theta_deg=150.0, hide=0)
    cv2.imwrite(str(photos / "w5_150kPa.png"), bad)
    out = tmp_path / "measured.csv"
    capsys.readouterr()
    code = main(["measure", *sorted(str(p) for p in photos.iterdir()), "--sheet", str(coupon / "measurements.csv"),
                 "-o", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "w5_150kPa.png" in err[0] and "marker id(s) 8 not found" in err[0]
    with open(out, newline="") as fh:
        rows = list(csv.DictReader(fh))
    done = {(r["branch"], r["photo"]): float(r["bend_deg"]) for r in rows if r["bend_deg"]}
    assert set(done) == {("loading", "w5_100kPa.png"), ("unloading", "w5_100kPa_down.png")}
    for (_, name), bend in done.items():
        assert abs(bend - truths[name]) < 1.0
    assert all(r["actuator"] == "01 zigzag w5.0" and r["pressure_kpa"] == "100" for r in rows if r["bend_deg"])
    assert sorted(os.listdir(tmp_path / "annotated")) == ["w5_100kPa.measured.jpg", "w5_100kPa_down.measured.jpg"]
    assert (tmp_path / "measured.centrelines.json").exists()


def test_no_pressure_in_the_name_is_refused(tmp_path, capsys):
    _, img, side = _photo(1)
    cv2.imwrite(str(tmp_path / "strip.png"), img)
    assert main(["measure", str(tmp_path / "strip.png"), "-o", str(tmp_path / "m.csv")]) == 2
    err = capsys.readouterr().err
    assert "no pressure" in err and not (tmp_path / "m.csv").exists()
