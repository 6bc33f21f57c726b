"""Coupon files: ``coupon.json`` (the coupon's actuators and marker layout) and the measurement sheet.

``embroact calibrate coupon`` writes both; ``embroact measure`` reads the layout and fills
the sheet's ``bend_deg`` column; ``embroact fit --sheet`` reads the sheet.

The measurement sheet is a CSV with one row per actuator, pressure step and branch::

    design,actuator,pattern,coordinate,block,fin_side,step,branch,pressure_kpa,bend_deg,photo
    coupon-hoop1.toml,01 zigzag w5.0,zigzag,5,0,thread,0,loading,0,,

``design`` is the hoop's design file (relative to the sheet), ``actuator`` the actuator's
name in it, ``block`` its marker-id block; ``bend_deg`` is the layout's marker reading
(empty until measured), ``photo`` the picture it came from.

Examples
--------
>>> rows = sheet_rows([{"design": "d.toml", "actuator": "A", "pattern": "zigzag", "coordinate": 5.0, "block": 0,
...                     "fin_side": "thread"}], [0.0, 100.0])
>>> [(r["branch"], r["pressure_kpa"]) for r in rows]
[('loading', 0.0), ('loading', 100.0), ('unloading', 0.0)]
>>> print(sheet_text(rows).splitlines()[1])
d.toml,A,zigzag,5,0,thread,0,loading,0,,
"""
from __future__ import annotations

import csv
import io
import json
import math
import os
from dataclasses import dataclass

from ...patterns.base.errors import ParameterError
from ...predict.markers import MarkerLayout
from ...predict.photomarkers import PhotoLayout, ReferenceBoard

__all__ = [
    "SHEET_COLUMNS",
    "SheetRow",
    "layout_as_dict",
    "layout_from_dict",
    "read_coupon_layout",
    "read_sheet",
    "sheet_rows",
    "sheet_text",
]

SHEET_COLUMNS = ("design", "actuator", "pattern", "coordinate", "block", "fin_side", "step", "branch",
                 "pressure_kpa", "bend_deg", "photo")
#: Largest measurement sheet read [rows] (a coupon of 22 actuators with 100 steps is 4,400).
_MAX_ROWS = 100_000


def _num(value: float) -> str:
    return f"{value:.10g}"


def sheet_rows(actuators, pressures_kpa) -> list[dict]:
    """Empty sheet rows: per actuator (mappings with the first six columns), loading up then unloading down.

    Parameters
    ----------
    actuators : iterable of mapping
        Per actuator: ``design``, ``actuator``, ``pattern``, ``coordinate``, ``block``, ``fin_side``.
    pressures_kpa : sequence of float
        The loading steps, ascending [kPa].

    Returns
    -------
    list of dict

    Examples
    --------
    >>> acts = [{"design": "coupon", "actuator": "01 zigzag w7.0", "pattern": "zigzag", "coordinate": 7.0, "block": 0,
    ...          "fin_side": "fabric"}]
    >>> rows = sheet_rows(acts, [0.0, 100.0])
    >>> [(r["branch"], r["pressure_kpa"]) for r in rows]
    [('loading', 0.0), ('loading', 100.0), ('unloading', 0.0)]
    """
    up = [float(p) for p in pressures_kpa]
    steps = [("loading", p) for p in up] + [("unloading", p) for p in reversed(up[:-1])]
    return [{**a, "step": k, "branch": b, "pressure_kpa": p, "bend_deg": None, "photo": ""}
            for a in actuators for k, (b, p) in enumerate(steps)]


def sheet_text(rows) -> str:
    """CSV text of sheet rows (numbers in shortest exact-enough form, empty for a missing bend).

    Parameters
    ----------
    rows : iterable of mapping
        :func:`sheet_rows`' rows, filled or not.

    Returns
    -------
    str

    Examples
    --------
    >>> acts = [{"design": "coupon", "actuator": "01 zigzag w7.0", "pattern": "zigzag", "coordinate": 7.0, "block": 0,
    ...          "fin_side": "fabric"}]
    >>> rows = sheet_rows(acts, [0.0, 100.0])
    >>> print(sheet_text(rows).splitlines()[2])
    coupon,01 zigzag w7.0,zigzag,7,0,fabric,1,loading,100,,
    """
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(SHEET_COLUMNS)
    for r in rows:
        w.writerow([_num(r[c]) if isinstance(r[c], float) else ("" if r[c] is None else r[c]) for c in SHEET_COLUMNS])
    return out.getvalue()


@dataclass(frozen=True, slots=True)
class SheetRow:
    """One measured row of a sheet: which actuator, at which pressure and branch, what it read.

    Attributes
    ----------
    design, actuator, pattern : str
        The coupon, the actuator's label and its pattern kind.
    block : int
        Its marker-id block.
    fin_side : str
        Face its fins are on.
    branch : str
        ``"loading"`` or ``"unloading"``.
    pressure_kpa : float
        [kPa].
    bend_deg : float or None
        The reading [deg]; None: not measured yet.
    photo : str
        The photo it was read from.
    line : int
        The sheet's line.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> acts = [{"design": "coupon", "actuator": "01 zigzag w7.0", "pattern": "zigzag", "coordinate": 7.0, "block": 0,
    ...          "fin_side": "fabric"}]
    >>> rows = sheet_rows(acts, [0.0, 100.0])
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "s.csv").write_text(sheet_text(rows).replace("loading,100,,", "loading,100,42.5,"))
    ...     row = read_sheet(Path(tmp, "s.csv"))[1]
    >>> row.actuator, row.pressure_kpa, row.bend_deg, row.line
    ('01 zigzag w7.0', 100.0, 42.5, 3)
    """

    design: str
    actuator: str
    pattern: str
    block: int
    fin_side: str
    branch: str
    pressure_kpa: float
    bend_deg: float | None
    photo: str
    line: int


def _float(text: str, where: str, column: str, empty_ok: bool = False) -> float | None:
    if empty_ok and not text.strip():
        return None
    try:
        v = float(text)
    except ValueError:
        v = math.nan
    if not math.isfinite(v):
        raise ParameterError(f"{where}: {column} must be a finite number, got {text!r}")
    return v


def read_sheet(path: str | os.PathLike) -> tuple[SheetRow, ...]:
    """The rows of a measurement sheet (every row, measured or not); one-line errors name the line.

    Parameters
    ----------
    path : str or os.PathLike
        The sheet (CSV).

    Returns
    -------
    tuple of SheetRow

    Raises
    ------
    ParameterError
        A missing column, a bad number or branch, more than 100,000 rows.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> acts = [{"design": "coupon", "actuator": "01 zigzag w7.0", "pattern": "zigzag", "coordinate": 7.0, "block": 0,
    ...          "fin_side": "fabric"}]
    >>> rows = sheet_rows(acts, [0.0, 100.0])
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "s.csv").write_text(sheet_text(rows))
    ...     [r.bend_deg for r in read_sheet(Path(tmp, "s.csv"))]
    [None, None, None]
    """
    with open(path, newline="", encoding="utf-8") as fh:
        reader = csv.DictReader(fh)
        missing = [c for c in ("design", "actuator", "pattern", "block", "branch", "pressure_kpa", "bend_deg")
                   if c not in (reader.fieldnames or ())]
        if missing:
            raise ParameterError(f"{path}: measurement sheet needs the column(s) {', '.join(missing)} "
                                 f"(see embroact calibrate coupon)")
        rows: list[SheetRow] = []
        for i, r in enumerate(reader, start=2):
            if len(rows) >= _MAX_ROWS:
                raise ParameterError(f"{path}: a measurement sheet holds at most {_MAX_ROWS:,} rows")
            where = f"{path} line {i}"
            if r["branch"] not in ("loading", "unloading"):
                raise ParameterError(f"{where}: branch must be 'loading' or 'unloading', got {r['branch']!r}")
            block = _float(r["block"], where, "block")
            if block is None or block < 0 or block != int(block):
                raise ParameterError(f"{where}: block must be a whole number >= 0, got {r['block']!r}")
            rows.append(SheetRow(r["design"], r["actuator"], r["pattern"], int(block), r.get("fin_side") or "fabric",
                                 r["branch"], float(_float(r["pressure_kpa"], where, "pressure_kpa")),  # type: ignore[arg-type]
                                 _float(r["bend_deg"] or "", where, "bend_deg", empty_ok=True), r.get("photo") or "", i))
    return tuple(rows)


def layout_as_dict(layout: PhotoLayout) -> dict:
    """JSON-ready dict of a photo layout (unit-suffixed keys).

    Parameters
    ----------
    layout : PhotoLayout
        The layout.

    Returns
    -------
    dict

    Examples
    --------
    >>> from embroact.predict.photomarkers import COUPON_LAYOUT
    >>> sorted(layout_as_dict(COUPON_LAYOUT))
    ['board', 'fin_offset_mm', 'first_id', 'marker_size_mm', 'markers']
    """
    b = layout.board
    return {"markers": layout.markers.as_dict(), "marker_size_mm": layout.marker_size_mm,
            "fin_offset_mm": layout.fin_offset_mm, "first_id": layout.first_id,
            "board": {"ids": list(b.ids), "centres_mm": [list(c) for c in b.centres_mm], "size_mm": b.size_mm}}


def layout_from_dict(d, where: str = "layout") -> PhotoLayout:
    """The :class:`PhotoLayout` of :func:`layout_as_dict`'s dict; one-line errors name ``where``.

    Parameters
    ----------
    d : mapping
        :func:`layout_as_dict`'s dict.
    where : str, optional
        Where it came from, for the messages.

    Returns
    -------
    PhotoLayout

    Raises
    ------
    ParameterError
        A missing or bad field.

    Examples
    --------
    >>> from embroact.predict.photomarkers import COUPON_LAYOUT
    >>> layout_from_dict(layout_as_dict(COUPON_LAYOUT)) == COUPON_LAYOUT
    True
    """
    try:
        b = d["board"]
        return PhotoLayout(MarkerLayout(**d["markers"]), float(d["marker_size_mm"]), float(d["fin_offset_mm"]),
                           int(d["first_id"]), ReferenceBoard(tuple(b["ids"]), tuple(tuple(c) for c in b["centres_mm"]),
                                                              float(b["size_mm"])))
    except (KeyError, TypeError, ValueError) as exc:
        if isinstance(exc, ParameterError):
            raise ParameterError(f"{where}: {exc}") from None
        raise ParameterError(f"{where}: not a marker layout (missing or bad {exc})") from None


def read_coupon_layout(path: str | os.PathLike) -> tuple[PhotoLayout, dict]:
    """The layout of a ``coupon.json`` and its actuators by block (``{block: actuator dict}``).

    Parameters
    ----------
    path : str or os.PathLike
        The ``coupon.json`` ``embroact calibrate coupon`` wrote.

    Returns
    -------
    layout : PhotoLayout
    actuators : dict of int to dict

    Raises
    ------
    ParameterError
        Not JSON, or no layout in it.

    Examples
    --------
    >>> import json, tempfile
    >>> from pathlib import Path
    >>> from embroact.predict.photomarkers import COUPON_LAYOUT
    >>> doc = {"layout": layout_as_dict(COUPON_LAYOUT), "actuators": [{"block": 0, "label": "01 zigzag w5.0"}]}
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "coupon.json").write_text(json.dumps(doc))
    ...     layout, acts = read_coupon_layout(Path(tmp, "coupon.json"))
    >>> layout == COUPON_LAYOUT, acts[0]["label"]
    (True, '01 zigzag w5.0')
    """
    try:
        with open(path, encoding="utf-8") as fh:
            doc = json.load(fh)
    except json.JSONDecodeError as exc:
        raise ParameterError(f"{path}: not a coupon file (JSON error at line {exc.lineno})") from None
    if not isinstance(doc, dict) or "layout" not in doc:
        raise ParameterError(f"{path}: not a coupon file (no 'layout')")
    acts = {int(a["block"]): a for a in doc.get("actuators", []) if isinstance(a, dict) and "block" in a}
    return layout_from_dict(doc["layout"], str(path)), acts
