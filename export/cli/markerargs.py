"""Marker-layout flags shared by ``embroact fit`` and ``embroact predict``.

``--measurement markers`` says the angles are marker sums (docs/model.md section 11):
``fit`` compares the data with the layout's reading of the model's bend, ``predict``
prints that reading next to theta. The layout flags default to the paper's: 2 rows
(``--sides``) of 7 markers 10 mm apart, the first at the clamped end, on the fabric.

Examples
--------
>>> import argparse
>>> from embroact.export.cli.markerargs import add_layout_arguments, layout_from_args
>>> p = argparse.ArgumentParser()
>>> add_layout_arguments(p)
>>> layout_from_args(p.parse_args(["--measurement", "markers", "--marker-spacing-mm", "8"])).label
'markers: 2 rows of 7, 8 mm apart, first 0 mm from the clamped end, fabric side'
>>> layout_from_args(p.parse_args([])) is None   # whole-strip angles
True
"""
from __future__ import annotations

__all__ = ["MEASUREMENTS", "MAX_MARKERS_PER_SIDE", "MAX_MARKER_ROWS", "add_layout_arguments", "layout_from_args"]

#: Values of ``--measurement``: the angle between the strip's two ends, or a marker sum.
MEASUREMENTS = ("whole-strip", "markers")
#: Layout bounds: a marker CSV then has at most 3 rows * 100 markers * 3 axes coordinate
#: columns (within :data:`embroact.patterns.base.validate.CSV_COLUMNS`).
MAX_MARKERS_PER_SIDE, MAX_MARKER_ROWS = 100, 3
#: Largest marker spacing and offset [mm] (MarkerLayout's bounds).
_MAX_SPACING_MM, _MAX_OFFSET_MM = 1e4, 1e5


def add_layout_arguments(group, *, measurement_help: str = "") -> None:
    """``--measurement`` and the layout flags (no numpy: ``--help`` stays fast)."""
    group.add_argument("--measurement", choices=MEASUREMENTS, default="whole-strip",
                       help=measurement_help or "how the angles are measured: whole-strip (the angle between the "
                                                "strip's two ends, default) or markers (the layout's marker sum)")
    group.add_argument("--markers-per-side", type=int, default=7, help="markers in each row (default 7)")
    group.add_argument("--sides", type=int, default=2, help="marker rows, one per side of the embroidery (default 2)")
    group.add_argument("--marker-spacing-mm", type=float, default=10.0,
                       help="distance between neighbouring markers along the fabric at rest [mm] (default 10)")
    group.add_argument("--marker-offset-mm", type=float, default=0.0,
                       help="distance from the clamped end to the first marker [mm] (default 0)")
    group.add_argument("--marker-side", choices=("fabric", "thread"), default="fabric",
                       help="face the markers are on (default fabric; recorded, the reading does not depend on it)")


def layout_from_args(args, *, markers: bool = False):
    """The :class:`~embroact.predict.markers.MarkerLayout` of the flags, or None for whole-strip angles.

    ``markers=True`` (marker coordinates given) implies ``--measurement markers``.
    """
    from ...patterns.base.errors import check_range
    from ...patterns.base.validate import check_count
    from ...predict.markers import MarkerLayout

    per_side = check_count("markers_per_side", args.markers_per_side, low=3, high=MAX_MARKERS_PER_SIDE)
    rows = check_count("sides", args.sides, low=1, high=MAX_MARKER_ROWS)
    spacing = check_range("marker_spacing_mm", args.marker_spacing_mm, low=0.0, high=_MAX_SPACING_MM)
    offset = check_range("marker_offset_mm", args.marker_offset_mm, low=0.0, low_inclusive=True, high=_MAX_OFFSET_MM)
    if not markers and args.measurement != "markers":
        return None
    return MarkerLayout(markers_per_side=per_side, spacing_mm=spacing, offset_mm=offset, rows=rows,
                        side=args.marker_side)
