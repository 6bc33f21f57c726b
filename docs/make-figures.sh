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
embroact design --target-shape examples/data/target_hook.csv --at-kpa 250 -o examples/designed_hook.toml \
    --svg docs/img/design_shape.svg > /dev/null
embroact preview stitches examples/designed_hook.toml -o docs/img/design_stitches.svg > /dev/null
embroact preview bend examples/designed_hook.toml -o docs/img/design_bend.svg > /dev/null
embroact preview shape examples/designed_hook.toml -o docs/img/design_side.svg > /dev/null
echo "figures written to docs/img"
