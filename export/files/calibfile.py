"""Measured data and calibration sets on disk: CSV readers, calibration TOML read/write.

Bend CSV (one row per measurement, in the order taken; ``#`` lines are comments;
other columns are ignored)::

    pressure_kpa,angle_deg,branch
    0,0,loading
    10,0.2,loading
    ...

``branch`` is optional (``loading`` / ``unloading``); without it the loop is split at
the maximum pressure.  Marker CSV: ``pressure_kpa[,branch]`` plus ``m1_x,m1_y,m1_z``
... for every marker (``m1``-``m7`` side 1 from base to tip, ``m8``-``m14`` side 2 for
the paper's layout; ``_z`` columns may be left out for 2-D data).

Calibration TOML (what the set was fitted with, then one table per fitted point)::

    name = "mylab"
    description = "..."
    tube_law = "paper"               # inflation-phase tube law of the fit
    measurement = "markers: 2 rows of 7, 10 mm apart, ..."   # how the angles were measured
    # covers: zigzag width_mm 7
    [tube]                           # the tube of the fitted samples (left out: unknown)
    outer_radius_mm = 1.5
    inner_radius_mm = 1.0
    g_e_mpa = 0.13
    [marker_layout]                  # the marker layout the data were compared through
    markers_per_side = 7             # (left out: whole-strip angles)
    spacing_mm = 10.0
    offset_mm = 0.0
    rows = 2
    side = "fabric"
    [materials]
    tube = "silicone"
    [[points]]
    pattern = "zigzag"
    coordinate = "width_mm"          # the key interpolated over for this pattern
    width_mm = 7.0                   # as the sample's needle points realise it (embroact fit)
    g_mpa = 2.7
    p0_kpa = 85.0
    branch = "loading"
    fitted = ["g_mpa", "p0_kpa"]     # the fitted parameters, the order of covariance
    covariance = [[4e-4, 0.05], [0.05, 1.2]]   # [MPa, kPa units]: uncertainty bands
    [points.tube_law_parameters]     # the tube law's parameters in the fit
    outer_radius_mm = 1.5
    g_e_mpa = 0.13

Files written before ``tube``, ``tube_law``, ``measurement``, ``marker_layout``,
``coordinate``, ``fitted``, ``covariance`` and ``tube_law_parameters`` existed are read with
the defaults (tube unknown, paper law, whole-strip angles, no covariance).

Every problem is one line naming the file, the line or point, the column or key and
the value; files are written atomically and byte-for-byte reproducibly.

Examples
--------
>>> import os, tempfile
>>> from embroact.predict.calibration import PAPER_2025
>>> from embroact.export.files.calibfile import write_calibration, read_calibration
>>> path = os.path.join(tempfile.mkdtemp(), "paper.toml")
>>> write_calibration(path, PAPER_2025)
>>> read_calibration(path) == PAPER_2025
True
"""
from __future__ import annotations

import csv
import dataclasses
import io
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...patterns.base.arrays import frozen_array
from ...patterns.base.errors import DesignFileError, EmbroactError
from ...patterns.base.validate import (COORD_MM, CSV_COLUMNS, CSV_FIELD_CHARS, CSV_FILE_BYTES, CSV_ROWS, check_count,
                                       read_input)
from ...patterns.design import Design, names_calibration_file
from ...patterns.kinds import pattern_kind
from ...predict.calibration import CalibrationPoint, CalibrationSet, CalibrationTube
from ...predict.layoutchoice import LAYOUT_FIELDS
from ...predict.markers import MarkerLayout
from .atomic import write_text_atomic
from .tomltext import dumps, load_toml

__all__ = [
    "BendData",
    "MarkerData",
    "read_bend_csv",
    "read_csv_table",
    "check_csv_coordinates",
    "read_marker_csv",
    "read_calibration",
    "write_calibration",
    "calibration_toml",
    "calibration_reference",
    "resolve_calibration_files",
]

_SET_KEYS = ("name", "description", "tube_law", "measurement", "tube", "marker_layout", "materials", "points")
_POINT_KEYS = tuple(f.name for f in dataclasses.fields(CalibrationPoint))
_TUBE_KEYS = tuple(f.name for f in dataclasses.fields(CalibrationTube))
_AXES = ("x", "y", "z")


@dataclass(frozen=True, slots=True)
class BendData:
    """Measured bend angles.

    Attributes
    ----------
    pressure_kpa, angle_deg : ndarray, shape (n,)
        Pressures [kPa] and signed bend angles [deg], read-only.
    branch : tuple of str or None
        ``"loading"`` / ``"unloading"`` per row when the file has a ``branch`` column.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "b.csv").write_text("pressure_kpa,angle_deg,branch\\n0,0,loading\\n200,95,loading\\n")
    ...     data = read_bend_csv(Path(tmp, "b.csv"))
    >>> data.pressure_kpa.tolist(), data.angle_deg.tolist(), data.branch
    ([0.0, 200.0], [0.0, 95.0], ('loading', 'loading'))
    """

    pressure_kpa: np.ndarray
    angle_deg: np.ndarray
    branch: tuple[str, ...] | None


@dataclass(frozen=True, slots=True)
class MarkerData:
    """Marker positions per frame.

    Attributes
    ----------
    pressure_kpa : ndarray, shape (frames,)
        Pressure of each frame [kPa].
    markers_mm : ndarray, shape (frames, n_markers, 2 or 3)
        Marker positions [mm].
    branch : tuple of str or None
        ``"loading"`` / ``"unloading"`` per frame when the file says.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "m.csv").write_text("pressure_kpa,m1_x,m1_y,m2_x,m2_y\\n0,0,0,10,0\\n")
    ...     data = read_marker_csv(Path(tmp, "m.csv"), n_markers=2)
    >>> data.markers_mm.shape, data.branch
    ((1, 2, 2), None)
    """

    pressure_kpa: np.ndarray
    markers_mm: np.ndarray
    branch: tuple[str, ...] | None


def read_csv_table(path) -> tuple[dict[str, int], list[tuple[int, list[str]]]]:
    """Header -> column index, and (line number, cells) of each data row: the one CSV reader of the
    commands (measurements, markers, target shapes); blank lines and ``#`` comments are skipped.

    The limits of :mod:`embroact.patterns.base.validate` hold before anything is parsed:
    file size (``CSV_FILE_BYTES``, read no further), data rows (``CSV_ROWS``), columns
    (``CSV_COLUMNS``) and characters per field (``CSV_FIELD_CHARS``).

    Parameters
    ----------
    path : str or os.PathLike
        The CSV file.

    Returns
    -------
    columns : dict of str to int
        Header name -> column index.
    rows : list of (int, list of str)
        Line number and cells of each data row.

    Raises
    ------
    DesignFileError
        Unreadable, empty, or beyond a limit (naming the line).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "t.csv").write_text("# a comment\\nx_mm,y_mm\\n0,1\\n\\n2,3\\n")
    ...     read_csv_table(Path(tmp, "t.csv"))
    ({'x_mm': 0, 'y_mm': 1}, [(3, ['0', '1']), (5, ['2', '3'])])
    """
    text = read_input(path, CSV_FILE_BYTES, "CSV file", encoding="utf-8-sig")
    lines: list[tuple[int, str]] = []
    for i, line in enumerate(io.StringIO(text, newline=""), start=1):
        if line.strip() and not line.lstrip().startswith("#"):
            lines.append((i, line))
            if len(lines) > CSV_ROWS + 1:  # stop here: 16 MiB of "0\n" would be 8 million rows
                raise DesignFileError(f"{path} must have at most {CSV_ROWS:,} data rows, got more "
                                      f"(line {i} is data row {CSV_ROWS + 1:,})")
    if not lines:
        raise DesignFileError(f"{path} is empty: expected a header line and data rows")
    rows: list[list[str]] = []
    old_limit = csv.field_size_limit(CSV_FIELD_CHARS)
    try:
        for row in csv.reader(line for _, line in lines):
            if len(row) > CSV_COLUMNS:
                raise DesignFileError(f"{path} line {lines[len(rows)][0]}: a row must have at most "
                                      f"{CSV_COLUMNS:,} columns, got {len(row):,}")
            rows.append(row)
    except csv.Error as exc:
        raise DesignFileError(f"{path} line {lines[min(len(rows), len(lines) - 1)][0]}: not CSV: {exc} "
                              f"(at most {CSV_FIELD_CHARS:,} characters per field)") from None
    finally:
        csv.field_size_limit(old_limit)
    header = [h.strip().lower() for h in rows[0]]
    dup = next((h for i, h in enumerate(header) if h in header[:i]), None)
    if dup is not None:
        raise DesignFileError(f"{path}: column {dup!r} appears more than once in the header")
    if len(rows) == 1:
        raise DesignFileError(f"{path} has a header but no data rows")
    return {h: i for i, h in enumerate(header)}, [(n, r) for (n, _), r in zip(lines[1:], rows[1:])]


def _require(path, columns: dict[str, int], names) -> None:
    missing = [n for n in names if n not in columns]
    if missing:
        raise DesignFileError(
            f"{path}: missing column {missing[0]!r} (header has: {', '.join(columns) or 'nothing'})"
        )


def _cell(path, line: int, row: list[str], columns: dict[str, int], name: str) -> str:
    i = columns[name]
    if i >= len(row) or not row[i].strip():
        raise DesignFileError(f"{path} line {line}: column {name!r} is empty")
    return row[i].strip()


def _number(path, line, row, columns, name) -> float:
    text = _cell(path, line, row, columns, name)
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not np.isfinite(value):
        raise DesignFileError(f"{path} line {line}: {name} must be a finite number, got {text!r}")
    return value


def _branches(path, columns, rows) -> tuple[str, ...] | None:
    if "branch" not in columns:
        return None
    out = []
    for line, row in rows:
        b = _cell(path, line, row, columns, "branch").lower()
        if b not in ("loading", "unloading"):
            raise DesignFileError(f"{path} line {line}: branch must be 'loading' or 'unloading', got {b!r}")
        out.append(b)
    return tuple(out)


def _columns(path, columns, rows, names) -> np.ndarray:
    """Numbers of the named columns, row by row; the first column is a gauge pressure (>= 0)."""
    _require(path, columns, names)
    values = np.array([[_number(path, line, row, columns, n) for n in names] for line, row in rows])
    negative = np.flatnonzero(values[:, 0] < 0.0)
    if negative.size:
        line = rows[negative[0]][0]
        raise DesignFileError(f"{path} line {line}: {names[0]} must be >= 0 (gauge pressure), got {values[negative[0], 0]:g}")
    return values


def check_csv_coordinates(path, rows, values: np.ndarray, names) -> None:
    """Refuse a coordinate [mm] beyond ``COORD_MM``, naming the line and column: the bound of every path point.

    Parameters
    ----------
    path : str or os.PathLike
        The file, for the message.
    rows : list of (int, list of str)
        :func:`read_csv_table`'s rows.
    values : numpy.ndarray (n, k)
        One row of numbers per row [mm].
    names : sequence of str
        The columns of ``values``.

    Raises
    ------
    DesignFileError
        A coordinate beyond the bound.

    Examples
    --------
    >>> import numpy as np
    >>> try:
    ...     check_csv_coordinates("t.csv", [(2, ["0", "3e9"])], np.array([[0.0, 3e9]]), ["x_mm", "y_mm"])
    ... except ValueError as exc:
    ...     print(exc)
    t.csv line 2: y_mm must be in [-1e+07, 1e+07] mm, got 3e+09
    """
    far = np.argwhere(np.abs(values) > COORD_MM)
    if far.size:
        i, j = far[0]
        raise DesignFileError(f"{path} line {rows[i][0]}: {names[j]} must be in [-{COORD_MM:g}, {COORD_MM:g}] mm, "
                              f"got {values[i, j]:g}")


def read_bend_csv(path) -> BendData:
    """Read ``pressure_kpa,angle_deg[,branch]`` rows (module docstring).

    Parameters
    ----------
    path : str or os.PathLike
        The CSV file.

    Returns
    -------
    BendData

    Raises
    ------
    DesignFileError
        Unreadable or empty file, missing column, empty or non-numeric cell, bad branch.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "b.csv").write_text("pressure_kpa,angle_deg\\n0,0\\n100,x\\n")
    ...     try:
    ...         read_bend_csv(Path(tmp, "b.csv"))
    ...     except ValueError as exc:
    ...         print(str(exc).replace(tmp, "TMP"))  # doctest: +ELLIPSIS
    TMP/b.csv line 3: angle_deg ...
    """
    columns, rows = read_csv_table(path)
    values = _columns(path, columns, rows, ("pressure_kpa", "angle_deg"))
    return BendData(frozen_array(values[:, 0]), frozen_array(values[:, 1]), _branches(path, columns, rows))


def read_marker_csv(path, *, n_markers: int = 14) -> MarkerData:
    """Read ``pressure_kpa[,branch]`` and marker columns ``m1_x, m1_y[, m1_z]`` ... ``m{n}_*``.

    Parameters
    ----------
    path : str or os.PathLike
        The CSV file.
    n_markers : int, optional
        Markers per frame (the paper's: 2 rows of 7).

    Returns
    -------
    MarkerData

    Raises
    ------
    DesignFileError
        As :func:`read_bend_csv`, naming the first missing marker column.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "m.csv").write_text("pressure_kpa,m1_x,m1_y,m1_z\\n50,1,2,3\\n")
    ...     read_marker_csv(Path(tmp, "m.csv"), n_markers=1).markers_mm.tolist()
    [[[1.0, 2.0, 3.0]]]
    """
    check_count("n_markers", n_markers, low=1, high=CSV_COLUMNS // len(_AXES))
    columns, rows = read_csv_table(path)
    axes = _AXES if "m1_z" in columns else _AXES[:2]
    names = [f"m{i}_{ax}" for i in range(1, n_markers + 1) for ax in axes]
    values = _columns(path, columns, rows, ["pressure_kpa", *names])
    check_csv_coordinates(path, rows, values[:, 1:], names)
    markers = values[:, 1:].reshape(len(rows), n_markers, len(axes))
    return MarkerData(frozen_array(values[:, 0]), frozen_array(markers), _branches(path, columns, rows))


def _coverage_comment(cset: CalibrationSet) -> str:
    parts = []
    for pattern, (lo, hi) in cset.coverage().items():
        span = f"{lo:g}" if lo == hi else f"{lo:g}-{hi:g}"
        parts.append(f"{pattern} {pattern_kind(pattern).calibration_axis} {span}")
    return "# covers: " + ", ".join(parts)


def calibration_toml(cset: CalibrationSet) -> str:
    """The TOML text of a calibration set (stable key order, shortest round-trip floats).

    Parameters
    ----------
    cset : CalibrationSet
        The set.

    Returns
    -------
    str
        A comment naming the coverage, then the set.

    Examples
    --------
    >>> from embroact.predict.calibration import CalibrationPoint, CalibrationSet
    >>> lab = CalibrationSet("lab", (CalibrationPoint("zigzag", 7.0, 2.0, 90.0),))
    >>> print(calibration_toml(lab).splitlines()[1])
    # covers: zigzag width_mm 7
    """
    doc: dict = {"name": cset.name, "description": cset.description, "tube_law": cset.tube_law,
                 "measurement": cset.measurement}
    if cset.tube is not None:
        doc["tube"] = {k: getattr(cset.tube, k) for k in _TUBE_KEYS}
    if cset.marker_layout is not None:
        doc["marker_layout"] = cset.marker_layout.as_dict()
    if cset.materials:
        doc["materials"] = dict(cset.materials)
    doc["points"] = [{"pattern": p.pattern, "coordinate": pattern_kind(p.pattern).calibration_axis,
                      **{k: v for k, v in p.as_dict().items() if k != "pattern"}} for p in cset.points]
    return f"# embroact calibration set\n{_coverage_comment(cset)}\n{dumps(doc)}"


def calibration_reference(value: str | None, base_dir) -> tuple[str | None, tuple[CalibrationSet, ...]]:
    """(reference, (set,)) for a calibration setting that names a file (read relative to ``base_dir``):
    the reference is the file's absolute path, by which the set is found (``CalibrationSet.source``) and
    which a design saved anywhere still resolves; (value, ()) for a set name or None.

    Parameters
    ----------
    value : str or None
        The setting: a set name or a ``.toml`` file.
    base_dir : str or os.PathLike
        Where a relative file name is read from.

    Returns
    -------
    tuple
        The reference and the sets read.

    Examples
    --------
    >>> calibration_reference("paper-2025", ".")
    ('paper-2025', ())
    >>> from embroact.predict.calibration import CalibrationPoint, CalibrationSet
    >>> lab = CalibrationSet("lab", (CalibrationPoint("zigzag", 7.0, 2.0, 90.0),))
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write_calibration(f"{tmp}/lab.toml", lab)
    ...     ref, (found,) = calibration_reference("lab.toml", tmp)
    >>> found.name, ref.endswith("lab.toml")
    ('lab', True)
    """
    if value is None or not names_calibration_file(value):
        return value, ()
    cset = read_calibration(Path(base_dir) / value)
    return cset.source, (cset,)


def resolve_calibration_files(design: Design, base_dir) -> tuple[Design, tuple[CalibrationSet, ...]]:
    """``design`` with every calibration file its actuators name replaced by its absolute path, and the sets.

    What ``embroact predict/build/check DESIGN.toml`` do with ``[actuator.model] calibration =
    "lab.toml"`` (``base_dir``: the design file's folder); pass the sets on to
    :func:`embroact.predict.analysis.analyse`.

    Parameters
    ----------
    design : Design
        A design.
    base_dir : str or os.PathLike
        The design file's folder.

    Returns
    -------
    design : Design
        With absolute calibration references.
    sets : tuple of CalibrationSet
        The sets read.

    Examples
    --------
    >>> import os, tempfile
    >>> from embroact.patterns.design import design_from_dict
    >>> from embroact.predict.analysis import analyse
    >>> from embroact.predict.calibration import CalibrationPoint, CalibrationSet
    >>> folder = tempfile.mkdtemp()
    >>> write_calibration(os.path.join(folder, "lab.toml"),
    ...                   CalibrationSet("lab", (CalibrationPoint("zigzag", 7.0, 2.0, 90.0),)))
    >>> d = design_from_dict({"actuator": [{"name": "A1", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1,
    ...                                     "length_mm": 100, "model": {"calibration": "lab.toml"}}]})
    >>> d, sets = resolve_calibration_files(d, folder)
    >>> d.actuators[0].model.calibration == os.path.realpath(os.path.join(folder, "lab.toml")), [s.name for s in sets]
    (True, ['lab'])
    >>> m = analyse(d, calibration_sets=sets).actuators[0].model
    >>> m.g_mpa, m.p0_kpa
    (2.0, 90.0)
    """
    sets: dict[str, CalibrationSet] = {}
    specs = []
    for spec in design.actuators:
        name, found = calibration_reference(spec.model.calibration, base_dir)
        sets.update({s.name: s for s in found})
        model = dataclasses.replace(spec.model, calibration=name or spec.model.calibration)
        specs.append(dataclasses.replace(spec, model=model))
    return dataclasses.replace(design, actuators=tuple(specs)), tuple(sets.values())


def write_calibration(path, cset: CalibrationSet) -> None:
    """Write ``cset`` as TOML to ``path`` atomically (an existing file is replaced whole).

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    cset : CalibrationSet
        The set.

    Examples
    --------
    >>> from embroact.predict.calibration import CalibrationPoint, CalibrationSet
    >>> lab = CalibrationSet("lab", (CalibrationPoint("zigzag", 7.0, 2.0, 90.0),))
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write_calibration(f"{tmp}/lab.toml", lab)
    ...     read_calibration(f"{tmp}/lab.toml").points == lab.points
    True
    """
    write_text_atomic(path, calibration_toml(cset))


def _unknown(path, where: str, keys, allowed) -> None:
    extra = sorted(set(keys) - set(allowed))
    if extra:
        raise DesignFileError(f"{path}: unknown key {extra[0]!r} in {where} (allowed: {', '.join(allowed)})")


def read_calibration(path) -> CalibrationSet:
    """Read a calibration set written by :func:`write_calibration` (or by hand).

    Parameters
    ----------
    path : str or os.PathLike
        The TOML file.

    Returns
    -------
    CalibrationSet
        Its ``source`` is the file's absolute path.

    Raises
    ------
    DesignFileError
        Unreadable file, TOML syntax, unknown keys, wrong types or out-of-range values.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "lab.toml").write_text('name = "lab"\\n[[points]]\\npattern = "zigzag"\\nwidth_mm = 7.0\\n'
    ...                                      'g_mpa = 2.0\\np0_kpa = 90.0\\n')
    ...     cset = read_calibration(Path(tmp, "lab.toml"))
    >>> cset.name, cset.points[0].g_mpa
    ('lab', 2.0)
    """
    doc = load_toml(path, "calibration file")
    _unknown(path, "the calibration set", doc, _SET_KEYS)
    points = doc.get("points")
    if not isinstance(points, list) or not all(isinstance(p, dict) for p in points):
        raise DesignFileError(f"{path}: expected [[points]] tables, got {type(points).__name__}")
    materials = doc.get("materials", {})
    if not isinstance(materials, dict) or not all(isinstance(v, str) for v in materials.values()):
        raise DesignFileError(f"{path}: [materials] must map names to strings")
    parsed = [_point(path, i, p) for i, p in enumerate(points)]
    try:
        return CalibrationSet(doc.get("name", ""), tuple(parsed), doc.get("description", ""), tuple(materials.items()),
                              tube=_tube(path, doc.get("tube")), tube_law=doc.get("tube_law", "paper"),
                              measurement=doc.get("measurement", "whole-strip"),
                              marker_layout=_layout(path, doc.get("marker_layout")),
                              source=str(Path(path).resolve()))
    except EmbroactError as exc:
        raise DesignFileError(f"{path}: {exc}") from None


def _tube(path, table) -> CalibrationTube | None:
    if table is None:
        return None
    if not isinstance(table, dict):
        raise DesignFileError(f"{path}: [tube] must be a table of {', '.join(_TUBE_KEYS)}")
    _unknown(path, "[tube]", table, _TUBE_KEYS)
    missing = [k for k in _TUBE_KEYS if k not in table]
    if missing:
        raise DesignFileError(f"{path}: [tube] is missing key {missing[0]!r}")
    try:
        return CalibrationTube(**table)
    except EmbroactError as exc:
        raise DesignFileError(f"{path}: [tube]: {exc}") from None


def _layout(path, table) -> MarkerLayout | None:
    if table is None:
        return None
    if not isinstance(table, dict):
        raise DesignFileError(f"{path}: [marker_layout] must be a table of {', '.join(LAYOUT_FIELDS)}")
    _unknown(path, "[marker_layout]", table, LAYOUT_FIELDS)
    try:
        return MarkerLayout(**table)
    except EmbroactError as exc:
        raise DesignFileError(f"{path}: [marker_layout]: {exc}") from None


def _check_shapes(path, i: int, table: dict) -> None:
    """``fitted`` a list of names, ``covariance`` a list of lists of numbers, ``tube_law_parameters`` a table."""
    where = f"{path}: points[{i}]"
    fitted = table.get("fitted", [])
    if not isinstance(fitted, list) or not all(isinstance(f, str) for f in fitted):
        raise DesignFileError(f"{where}: fitted must be a list of parameter names, got {fitted!r}")
    cov = table.get("covariance", [])
    if not isinstance(cov, list) or not all(
            isinstance(row, list) and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in row)
            for row in cov):
        raise DesignFileError(f"{where}: covariance must be a list of rows of numbers, got {cov!r}")
    law = table.get("tube_law_parameters", {})
    if not isinstance(law, dict):
        raise DesignFileError(f"{where}: tube_law_parameters must be a table of numbers, got {law!r}")


def _point(path, i: int, table: dict) -> CalibrationPoint:
    _unknown(path, f"points[{i}]", table, ("coordinate",) + _POINT_KEYS)
    _check_shapes(path, i, table)
    fields = {k: v for k, v in table.items() if k != "coordinate"}
    try:
        point = CalibrationPoint(**fields)
    except TypeError:
        missing = [k for k in ("pattern", "width_mm", "g_mpa", "p0_kpa") if k not in table]
        raise DesignFileError(f"{path}: points[{i}] is missing key {missing[0]!r}") from None
    except EmbroactError as exc:
        raise DesignFileError(f"{path}: points[{i}]: {exc}") from None
    axis = pattern_kind(point.pattern).calibration_axis
    if table.get("coordinate", axis) != axis:
        raise DesignFileError(f"{path}: points[{i}]: coordinate must be {axis!r} for the {point.pattern} "
                              f"pattern, got {table['coordinate']!r}")
    return point
