#!/usr/bin/env bash
# Regenerates the README's pictures with the installed embroact:
# the built-in default design (the paper's zigzag actuator) and the paper's cross design.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
embroact build --out "$tmp" > /dev/null
cp "$tmp"/preview.svg "$tmp"/bend.svg "$tmp"/shape.svg "$tmp"/shape3d.svg docs/img/
embroact preview stitches examples/paper_cross.toml -o docs/img/cross_preview.svg > /dev/null
embroact preview stitches examples/three_actuators.toml -o docs/img/three_preview.svg > /dev/null
embroact design --target-shape examples/data/target_hook.csv --at-kpa 250 --write-nearest -o examples/designed_hook.toml \
    --svg docs/img/design_shape.svg > /dev/null
embroact preview stitches examples/designed_hook.toml -o docs/img/design_stitches.svg > /dev/null
embroact preview bend examples/designed_hook.toml -o docs/img/design_bend.svg > /dev/null
embroact preview shape examples/designed_hook.toml -o docs/img/design_side.svg > /dev/null
# the README's calibration pictures: one synthetic photo (the tests' renderer) and what measure made of it
embroact calibrate coupon --out "$tmp" > /dev/null
PYTHONPATH=tests python -c "
import cv2, numpy as np, photo_renderer as pr
rng = np.random.default_rng(42)
img = pr.render(pr.strip(120.0, rng, side='thread'), rng, side='thread', tilt_deg=18.0)
cv2.imwrite('$tmp/w5_150kPa.jpg', img, [cv2.IMWRITE_JPEG_QUALITY, 90])"
embroact measure "$tmp"/w5_150kPa.jpg --sheet "$tmp"/measurements.csv -o "$tmp"/measured.csv > /dev/null
python -c "
import cv2
for src, dst in (('$tmp/w5_150kPa.jpg', 'measure_photo'), ('$tmp/annotated/w5_150kPa.measured.jpg', 'measure_annotated')):
    im = cv2.imread(src)
    im = cv2.resize(im, (900, round(im.shape[0] * 900 / im.shape[1])), interpolation=cv2.INTER_AREA)
    cv2.imwrite(f'docs/img/{dst}.jpg', im, [cv2.IMWRITE_JPEG_QUALITY, 85])"
echo "figures written to docs/img"
