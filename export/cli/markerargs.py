"""Marker-layout flags shared by ``embroact fit`` and ``embroact predict``.

``--measurement markers`` says the angles are marker sums (docs/model.md section 11):
``fit`` compares the data with the layout's reading of the model's bend, ``predict``
prints that reading next to theta. The layout flags have no parser defaults, so a flag
not given can be told from one given its default value: each given flag sets its field,
the others come from the layout a calibration set records (``predict``: the actuator's;
``fit --append``: the set it merges into), else from the paper's layout: 2 rows
(``--sides``) of 7 markers 10 mm apart, the first at the clamped end, on the fabric
(:func:`embroact.predict.layoutchoice.layout_for`).

Examples
--------
>>> import argparse
>>> from embroact.export.cli.markerargs import add_layout_arguments, layout_from_args
>>> p = argparse.ArgumentParser()
>>> add_layout_arguments(p)
>>> c = layout_from_args(p.parse_args(["--measurement", "markers", "--marker-spacing-mm", "8"]))
>>> c.layout.label, c.source
('markers: 2 rows of 7, 8 mm apart, first 0 mm from the clamped end, fabric side', "given spacing_mm; the rest the paper's")
>>> layout_from_args(p.parse_args([])) is None   # whole-strip angles
True
"""
from __future__ import annotations

__all__ = ["MEASUREMENTS", "MAX_MARKERS_PER_SIDE", "MAX_MARKER_ROWS", "add_layout_arguments", "given_layout",
           "wants_markers", "layout_from_args"]

#: Values of ``--measurement``: the angle between the strip's two ends, or a marker sum.
MEASUREMENTS = ("whole-strip", "markers")
#: Layout bounds: a marker CSV then has at most 3 rows * 100 markers * 3 axes coordinate
#: columns (within :data:`embroact.patterns.base.validate.CSV_COLUMNS`).
MAX_MARKERS_PER_SIDE, MAX_MARKER_ROWS = 100, 3
#: Largest marker spacing and offset [mm] (MarkerLayout's bounds).
_MAX_SPACING_MM, _MAX_OFFSET_MM = 1e4, 1e5


def add_layout_arguments(group, *, measurement_help: str = "",
                         recorded: str = "the layout the calibration set records") -> None:
    """``--measurement`` and the layout flags (no numpy: ``--help`` stays fast).

    Parameters
    ----------
    group : argparse.ArgumentParser or argument group
        Where the flags go.
    measurement_help : str, optional
        Help of ``--measurement`` (a default text when empty).
    recorded : str, optional
        Where, in the help, a flag not given takes its value from before falling back to the
        paper's layout.

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser()
    >>> add_layout_arguments(parser)
    >>> args = parser.parse_args(["--measurement", "markers", "--markers-per-side", "5"])
    >>> args.measurement, args.markers_per_side, args.sides
    ('markers', 5, None)
    """
    group.add_argument("--measurement", choices=MEASUREMENTS, default="whole-strip",
                       help=measurement_help or "how the angles are measured: whole-strip (the angle between the "
                                                "strip's two ends, default) or markers (the layout's marker sum)")

    def default(paper: str) -> str:
        return f"(default: {recorded}, else {paper})"

    group.add_argument("--markers-per-side", type=int, help=f"markers in each row {default('7')}")
    group.add_argument("--sides", type=int, help=f"marker rows, one per side of the embroidery {default('2')}")
    group.add_argument("--marker-spacing-mm", type=float,
                       help=f"distance between neighbouring markers along the fabric at rest [mm] {default('10')}")
    group.add_argument("--marker-offset-mm", type=float,
                       help=f"distance from the clamped end of the bent length to the first marker [mm] {default('0')}")
    group.add_argument("--marker-side", choices=("fabric", "thread"),
                       help=f"face the markers are on {default('fabric')}; recorded, the reading does not depend on it")


def given_layout(args) -> dict:
    """The layout fields the flags give, checked (``MarkerLayout`` field names; flags not given are absent).

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options (:func:`add_layout_arguments`).

    Returns
    -------
    dict

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser()
    >>> add_layout_arguments(parser)
    >>> args = parser.parse_args(["--measurement", "markers", "--markers-per-side", "5"])
    >>> given_layout(args)
    {'markers_per_side': 5}
    """
    from ...patterns.base.errors import check_range
    from ...patterns.base.validate import check_count

    out: dict[str, object] = {}
    if args.markers_per_side is not None:
        out["markers_per_side"] = check_count("markers_per_side", args.markers_per_side, low=3,
                                              high=MAX_MARKERS_PER_SIDE)
    if args.sides is not None:
        out["rows"] = check_count("sides", args.sides, low=1, high=MAX_MARKER_ROWS)
    if args.marker_spacing_mm is not None:
        out["spacing_mm"] = check_range("marker_spacing_mm", args.marker_spacing_mm, low=0.0, high=_MAX_SPACING_MM)
    if args.marker_offset_mm is not None:
        out["offset_mm"] = check_range("marker_offset_mm", args.marker_offset_mm, low=0.0, low_inclusive=True,
                                       high=_MAX_OFFSET_MM)
    if args.marker_side is not None:
        out["side"] = args.marker_side
    return out


def wants_markers(args, *, markers: bool = False) -> bool:
    """True when the angles are marker sums: ``--measurement markers``, or marker coordinates (``markers``).

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options.
    markers : bool, optional
        Marker coordinates were given.

    Returns
    -------
    bool

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser()
    >>> add_layout_arguments(parser)
    >>> args = parser.parse_args(["--measurement", "markers", "--markers-per-side", "5"])
    >>> wants_markers(args), wants_markers(parser.parse_args([])), wants_markers(parser.parse_args([]), markers=True)
    (True, False, True)
    """
    return markers or args.measurement == "markers"


def layout_from_args(args, *, markers: bool = False, recorded=None, calibration: str = ""):
    """The :class:`~embroact.predict.layoutchoice.LayoutChoice` of the flags, or None for whole-strip angles.

    Flags not given take ``recorded``'s fields (the layout calibration set ``calibration``
    records), else the paper's. ``markers=True`` (marker coordinates given) implies
    ``--measurement markers``. The flags are checked either way.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options.
    markers : bool, optional
        Marker coordinates were given.
    recorded : MarkerLayout or None, optional
        The layout the calibration set records.
    calibration : str, optional
        That set's name, for the source text.

    Returns
    -------
    LayoutChoice or None

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser()
    >>> add_layout_arguments(parser)
    >>> args = parser.parse_args(["--measurement", "markers", "--markers-per-side", "5"])
    >>> choice = layout_from_args(args)
    >>> choice.layout.markers_per_side, choice.source
    (5, "given markers_per_side; the rest the paper's")
    >>> layout_from_args(parser.parse_args([])) is None
    True
    """
    from ...predict.layoutchoice import layout_for

    given = given_layout(args)
    if not wants_markers(args, markers=markers):
        return None
    return layout_for(recorded, calibration=calibration, given=given)
