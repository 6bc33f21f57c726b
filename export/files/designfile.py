"""Design files: TOML in (:func:`load_design`), TOML out (:func:`dumps_design`, :func:`save_design`).

The schema is documented in :mod:`embroact.patterns.design`. An actuator's
``path = "drawing.svg#tube1"`` takes its tube path from an SVG drawing (resolved relative
to the design file; :mod:`embroact.export.files.svgfile`). Every problem with a file
(missing, unreadable, not UTF-8, TOML syntax with its line, schema, SVG) is one
:class:`DesignFileError` line that starts with the file name.

Examples
--------
>>> import os, tempfile
>>> from embroact.export.files.designfile import load_design, save_design
>>> from embroact.patterns.design import default_design
>>> path = os.path.join(tempfile.mkdtemp(), "d.toml")
>>> save_design(default_design(), path)
>>> load_design(path) == default_design()
True
>>> with open(path, "w") as fh:
...     _ = fh.write("name = 'x'\\n[[actuator]]\\nwidht_mm = 7\\n")
>>> try:
...     load_design(path)
... except Exception as exc:
...     print(str(exc).replace(path, "d.toml").split(";")[0])
d.toml: actuator[0].widht_mm: unknown key
"""
from __future__ import annotations

import os
from pathlib import Path

from ...patterns.design import Design, design_from_dict, design_to_dict, names_calibration_file
from ...patterns.base.errors import DesignFileError, PathError
from ...patterns.base.validate import TEXT_FILE_BYTES, read_input
from .atomic import write_text_atomic
from .tomltext import dumps, loads_toml

__all__ = ["load_design", "loads_design", "dumps_design", "save_design"]


def _svg_drawings(data) -> dict[str, int]:
    """Every SVG file the actuators' ``path`` values name -> the first actuator drawn in it."""
    from .svgfile import is_svg_ref, split_ref

    acts = data.get("actuator") if isinstance(data, dict) else None
    drawings: dict[str, int] = {}
    for i, a in enumerate(acts if isinstance(acts, list) else ()):
        if isinstance(a, dict) and is_svg_ref(a.get("path")):
            drawings.setdefault(split_ref(a["path"])[0], i)
    return drawings


def _svg_paths(data, base_dir) -> object:
    """``data`` with every actuator ``path = "FILE.svg#name"`` replaced by its points (plan frame),
    and, without ``[machine] origin``, the origin a drawing marks (:func:`~.svgfile.svg_origin_mm`)."""
    from ...patterns.svgpath import to_plan
    from .svgfile import is_svg_ref, read_svg_path, svg_origin_mm

    drawings = _svg_drawings(data)  # file -> the first actuator drawn in it
    if not drawings:
        return data
    out = []
    for i, a in enumerate(data["actuator"]):
        if isinstance(a, dict) and is_svg_ref(a.get("path")):
            try:
                a = {**a, "path": to_plan(read_svg_path(a["path"], base_dir=base_dir).points_mm).tolist()}
            except PathError as exc:
                raise DesignFileError(f"actuator[{i}].path: {exc}") from None
        out.append(a)
    machine = data.get("machine", {})
    if not (isinstance(machine, dict) and "origin" not in machine):
        return {**data, "actuator": out}
    marks: dict[tuple[float, float], str] = {}
    for file, i in drawings.items():
        try:
            mark = svg_origin_mm(file, base_dir=base_dir)
        except PathError as exc:
            raise DesignFileError(f"actuator[{i}].path: {exc}") from None
        if mark is not None:
            marks.setdefault((mark[0], -mark[1] + 0.0), file)
    if marks:
        if len(marks) > 1:
            raise DesignFileError(f"machine.origin: the drawings mark {len(marks)} different origins "
                                  f"({', '.join(sorted(set(marks.values())))}); mark one, or set [machine] origin")
        machine = {**machine, "origin": list(next(iter(marks)))}
        return {**data, "actuator": out, "machine": machine}
    return {**data, "actuator": out}


def loads_design(text: str, *, source: str = "<string>", base_dir: str | os.PathLike | None = None) -> Design:
    """Parse TOML text into a :class:`Design`; errors start with ``source``.

    Parameters
    ----------
    text : str
        The design file's TOML text.
    source : str
        Name that starts every error message (the file name).
    base_dir : str or os.PathLike, optional
        Folder that ``path = "FILE.svg#name"`` and ``calibration = "FILE.toml"`` references
        are resolved against (the design file's folder); default: the working directory.

    Returns
    -------
    Design
        The validated design; SVG file paths are read into point lists (plan frame), and
        calibration files into :attr:`Design.calibration_sets` (each actuator's setting then
        names its file's absolute path), exactly as the command line reads them; the files
        read are its :attr:`Design.source_files`.

    Examples
    --------
    >>> loads_design('[[actuator]]\\nname = "A"\\npattern = "zigzag"\\nwidth_mm = 7\\ninterval_mm = 1\\n'
    ...              'length_mm = 50').actuators[0].centerline.length_mm
    50.0
    """
    data = loads_toml(text, source=source)
    try:
        design = design_from_dict(_svg_paths(data, base_dir))
    except DesignFileError as exc:
        raise DesignFileError(f"{source}: {exc}") from None
    folder = Path(base_dir) if base_dir is not None else Path.cwd()
    design = _with_calibration_files(design, folder)
    return _with_source_files(design, data, source, folder)


def _with_source_files(design: Design, data: dict, source: str, base_dir: Path) -> Design:
    """``design`` with :attr:`Design.source_files`: the drawings and calibration files ``data`` names, by key."""
    import dataclasses

    files = [(f"drawing of {source} actuator[{i}].path", os.fspath(base_dir / file))
             for file, i in _svg_drawings(data).items()]
    for i, a in enumerate(data.get("actuator", ())):  # validated: a list of tables
        named = a.get("model", {}).get("calibration")
        if isinstance(named, str) and names_calibration_file(named):
            files.append((f"calibration file of {source} actuator[{i}].model.calibration", os.fspath(base_dir / named)))
    return dataclasses.replace(design, source_files=tuple(files)) if files else design


def _with_calibration_files(design: Design, base_dir: Path) -> Design:
    """``design`` with the calibration files its actuators name read (relative to ``base_dir``)."""
    named = [spec.model.calibration for spec in design.actuators]
    if not any(isinstance(n, str) and names_calibration_file(n) for n in named):
        return design  # set names only: no calibration reader (and no numpy) needed
    import dataclasses

    from .calibfile import resolve_calibration_files

    resolved, sets = resolve_calibration_files(design, base_dir)
    return dataclasses.replace(resolved, calibration_sets=sets)


def load_design(path: str | os.PathLike) -> Design:
    """Read and validate a TOML design file.

    Parameters
    ----------
    path : path-like
        The file; relative paths inside it (SVG drawings, calibration files) are read from
        its folder.

    Returns
    -------
    Design

    Examples
    --------
    >>> load_design("examples/paper_cross.toml").actuators[0].params.angle_deg
    45.0

    Raises
    ------
    DesignFileError
        One line naming the file: cannot read, larger than
        :data:`~embroact.patterns.base.validate.TEXT_FILE_BYTES`, not UTF-8, TOML syntax
        error (with line and column), or a schema error (with the key path).
    """
    p = Path(path)
    text = read_input(p, TEXT_FILE_BYTES, "design file", encoding="utf-8")
    return loads_design(text, source=str(p), base_dir=p.parent)


def dumps_design(design: Design) -> str:
    """TOML text of ``design`` (paths as point lists), readable by :func:`loads_design`.

    Parameters
    ----------
    design : Design

    Returns
    -------
    str

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> text = dumps_design(default_design())
    >>> text.splitlines()[0], loads_design(text) == default_design()
    ('name = "paper-zigzag"', True)
    """
    return dumps(design_to_dict(design))


def save_design(design: Design, path: str | os.PathLike) -> None:
    """Write ``design`` as TOML to ``path`` atomically.

    Parameters
    ----------
    design : Design
    path : path-like
        The file to write (replaced whole, or left as it was on an error).

    Returns
    -------
    None

    Examples
    --------
    >>> import os, tempfile
    >>> from embroact.patterns.design import default_design
    >>> path = os.path.join(tempfile.mkdtemp(), "zigzag.toml")
    >>> save_design(default_design(), path)
    >>> load_design(path) == default_design()
    True
    """
    write_text_atomic(path, dumps_design(design))
