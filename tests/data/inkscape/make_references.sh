#!/usr/bin/env bash
# Reference values from Inkscape itself (1.2, the Debian package) for tests/test_svg_inkscape.py:
#   NAME.query.csv    inkscape --query-all: id, x, y, width, height of every element [px, 96/in]
#   NAME.inkscape.svg the drawing as Inkscape flattens it: clones unlinked, groups ungrouped
#                     (transforms pushed into the path data by Inkscape), shapes turned to paths
# Run from this folder after editing a drawing: bash make_references.sh
set -euo pipefail
cd "$(dirname "$0")"
flatten="select-all:all;object-unlink-clones;select-all:all;object-to-path"
for _ in 1 2 3 4; do flatten+=";select-all:all;selection-ungroup"; done
for svg in arcs clones inkstitch units_in units_mm units_pt units_px; do
  inkscape --query-all "$svg.svg" 2>/dev/null > "$svg.query.csv"
  inkscape "$svg.svg" --actions="$flatten" --export-plain-svg --export-type=svg \
    --export-filename="$svg.inkscape.svg" 2>/dev/null
done
