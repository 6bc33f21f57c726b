"""``embroact measure PHOTO... -o measured.csv``: bend readings from photos of marker fins and a board.

Needs the ``measure`` extra (OpenCV). Per photo: the markers found, the board's
perspective corrected, each actuator's bend read as its layout's marker sum, its
centreline fitted (:mod:`embroact.export.photo.detect`); an annotated picture per photo
(``--annotated DIR``, default ``annotated/`` beside the output) and the centrelines in
``<output stem>.centrelines.json``.

Pressure and branch of each photo come from ``--pressures TABLE.csv`` (columns ``photo``,
``pressure_kpa`` and optionally ``branch``; ``photo`` is the file name) or from the file
name: a number before ``kPa`` (``w5_150kPa.jpg``, ``150kpa-down.png``) and ``down`` or
``unload`` for the unloading branch.

With ``--sheet SHEET.csv`` (the coupon's measurement sheet) the output is that sheet with
``bend_deg`` and ``photo`` filled in where a photo matched an actuator's marker block,
branch and pressure step (within 0.5 kPa); the layout and the fins' sides come from the
``coupon.json`` beside it (or ``--coupon``). Without a sheet the output lists one row per
actuator and photo.

A photo that cannot be measured is refused in one line (which photo, which marker, why);
the others are measured and written, and the exit code is then 2.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import sys

__all__ = ["add_arguments", "run"]

_PRESSURE = re.compile(r"(\d+(?:\.\d+)?)\s*kpa", re.IGNORECASE)
_UNLOADING = re.compile(r"(down|unload)", re.IGNORECASE)
#: A sheet row matches a photo's pressure within this [kPa].
_PRESSURE_MATCH_KPA = 0.5


def add_arguments(parser: argparse.ArgumentParser, name: str) -> None:
    """Options of ``embroact measure``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    name : str
        The command's name (``"measure"``).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact measure")
    >>> add_arguments(parser, "measure")
    >>> args = parser.parse_args(["p1.jpg", "p2.jpg", "-o", "m.csv"])
    >>> args.photos, args.output
    (['p1.jpg', 'p2.jpg'], 'm.csv')
    """
    parser.add_argument("photos", nargs="+", metavar="PHOTO", help="photos (JPEG, PNG, ...) of the strip and the board")
    parser.add_argument("-o", "--output", required=True, metavar="OUT.csv", help="measurements (CSV)")
    parser.add_argument("--sheet", metavar="SHEET.csv", help="the coupon's measurement sheet to fill in")
    parser.add_argument("--coupon", metavar="coupon.json",
                        help="the coupon's layout and actuators (default: coupon.json beside --sheet, else the "
                             "coupon's default layout)")
    parser.add_argument("--pressures", metavar="TABLE.csv", help="photo,pressure_kpa[,branch] per photo file name")
    parser.add_argument("--annotated", metavar="DIR", help="directory of the annotated pictures (default: annotated/ "
                                                            "beside the output; created)")
    parser.add_argument("--json", action="store_true", help="print machine-readable JSON")


def _pressure_table(path):
    import csv

    from ...patterns.base.errors import ParameterError

    out = {}
    with open(path, newline="", encoding="utf-8") as fh:
        reader = csv.DictReader(fh)
        if not {"photo", "pressure_kpa"} <= set(reader.fieldnames or ()):
            raise ParameterError(f"{path}: --pressures needs the columns photo and pressure_kpa")
        for i, r in enumerate(reader, start=2):
            try:
                p = float(r["pressure_kpa"])
            except ValueError:
                raise ParameterError(f"{path} line {i}: pressure_kpa must be a number, got {r['pressure_kpa']!r}") from None
            branch = (r.get("branch") or "loading").strip()
            if branch not in ("loading", "unloading"):
                raise ParameterError(f"{path} line {i}: branch must be 'loading' or 'unloading', got {branch!r}")
            out[os.path.basename(r["photo"].strip())] = (p, branch)
    return out


def _pressure_of(photo: str, table):
    """(pressure_kpa, branch) of a photo, or None."""
    name = os.path.basename(photo)
    if table is not None:
        return table.get(name)
    m = _PRESSURE.search(name)
    if m is None:
        return None
    return float(m.group(1)), "unloading" if _UNLOADING.search(name) else "loading"


def _setup(args):
    """(layout, {block: side}, {block: label}, sheet rows or None)."""
    from ...predict.photomarkers import COUPON_LAYOUT
    from ..files.couponfile import read_coupon_layout, read_sheet

    rows = read_sheet(args.sheet) if args.sheet else None
    coupon = args.coupon or (os.path.join(os.path.dirname(args.sheet) or ".", "coupon.json") if args.sheet else None)
    layout, acts = COUPON_LAYOUT, {}
    if coupon and (args.coupon or os.path.exists(coupon)):
        layout, acts = read_coupon_layout(coupon)
    sides = {b: a.get("fin_side", "fabric") for b, a in acts.items()}
    labels = {b: a.get("actuator", f"block {b}") for b, a in acts.items()}
    for r in rows or ():
        sides.setdefault(r.block, r.fin_side)
        labels.setdefault(r.block, r.actuator)
    return layout, sides, labels, rows


def run(args) -> int:
    """Measure every photo; write the measurements, the pictures and the centrelines; return the exit code.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options (:func:`add_arguments`), with ``command`` set to the command's name.

    Returns
    -------
    int
        The exit code (:mod:`embroact.export.cli.main`).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact measure")
    >>> add_arguments(parser, "measure")
    >>> args = parser.parse_args(["p.jpg", "-o", "no-such-dir/m.csv"])
    >>> args.command = "measure"
    >>> from embroact.patterns.base.errors import ExportError
    >>> try:
    ...     run(args)
    ... except ExportError as exc:
    ...     print(exc)
    output directory 'no-such-dir' does not exist
    """
    from ...patterns.base.errors import ParameterError
    from ...patterns.base.validate import check_output_name
    from ..files.atomic import check_output_dir, write_files_atomic
    from ..files.couponfile import sheet_text
    from ..photo.detect import PhotoRefused, load_gray, measure_image, require_cv2

    out_path = check_output_name("--output", args.output)
    check_output_dir(out_path)
    require_cv2()
    layout, sides, labels, rows = _setup(args)
    table = _pressure_table(args.pressures) if args.pressures else None
    out_dir = os.path.dirname(os.path.abspath(out_path))
    pic_dir = args.annotated or os.path.join(out_dir, "annotated")
    results, refused = [], []
    for photo in args.photos:
        pb = _pressure_of(photo, table)
        if pb is None:
            refused.append((photo, "no pressure: put it in the name (w5_150kPa.jpg) or give --pressures"))
            continue
        try:
            gray = load_gray(photo)
            reading = measure_image(gray, layout, sides)
        except PhotoRefused as exc:
            refused.append((photo, str(exc)))
            continue
        results.append((photo, pb, reading, gray))
    measured = [(photo, p, branch, b, reading) for photo, (p, branch), reading, _ in results for b in reading.blocks]
    if rows is not None:
        filled = {}
        for photo, p, branch, b, _ in measured:
            match = [r for r in rows if r.block == b.block and r.branch == branch
                     and abs(r.pressure_kpa - p) <= _PRESSURE_MATCH_KPA]
            if not match:
                refused.append((photo, (f"actuator block {b.block} ({labels.get(b.block, '?')}) at {p:g} kPa {branch} "
                                        "matches no row of the sheet")))
                continue
            filled[match[0].line] = (round(b.strip.reading_deg, 4), os.path.basename(photo))
        out_rows = []
        for r in rows:
            bend, photo_name = filled.get(r.line, (r.bend_deg, r.photo))
            out_rows.append({"design": r.design, "actuator": r.actuator, "pattern": r.pattern,
                             "coordinate": "", "block": r.block, "fin_side": r.fin_side, "step": "",
                             "branch": r.branch, "pressure_kpa": r.pressure_kpa, "bend_deg": bend, "photo": photo_name})
        _copy_columns(args.sheet, out_rows)
        text = sheet_text(out_rows)
    else:
        import csv
        import io

        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(("photo", "actuator", "block", "branch", "pressure_kpa", "bend_deg", "rms_mm", "tilt_deg"))
        for photo, p, branch, b, reading in measured:
            w.writerow((os.path.basename(photo), labels.get(b.block, f"block {b.block}"), b.block, branch, f"{p:g}",
                        f"{b.strip.reading_deg:.4f}", f"{b.strip.rms_mm:.4f}", f"{reading.tilt_deg:.2f}"))
        text = buf.getvalue()
    for photo, reason in refused:
        print(f"embroact: refused {photo}: {reason}", file=sys.stderr)
    if not measured:
        raise ParameterError(f"no photo could be measured ({len(refused)} refused)")
    from ..photo.annotate import annotated_jpeg

    os.makedirs(pic_dir, exist_ok=True)
    files: dict[str | os.PathLike, bytes] = {out_path: text.encode("utf-8")}
    lines = {}
    for photo, (p, branch), reading, gray in results:
        stem = os.path.splitext(os.path.basename(photo))[0]
        files[os.path.join(pic_dir, f"{stem}.measured.jpg")] = annotated_jpeg(
            gray, reading, f"{os.path.basename(photo)}: {p:g} kPa {branch}; board tilt {reading.tilt_deg:.0f} deg", labels)
        lines[os.path.basename(photo)] = [{"block": b.block, "actuator": labels.get(b.block, ""),
                                           "reading_deg": b.strip.reading_deg, "rms_mm": b.strip.rms_mm,
                                           "centreline_mm": [[round(x, 4), round(y, 4)] for x, y in b.strip.centreline_mm.tolist()]}
                                          for b in reading.blocks]
    stem = os.path.splitext(out_path)[0]
    files[stem + ".centrelines.json"] = (json.dumps(lines, indent=1, sort_keys=True) + "\n").encode("utf-8")
    write_files_atomic(files)
    if args.json:
        print(json.dumps({"measured": [{"photo": os.path.basename(ph), "block": b.block, "pressure_kpa": p,
                                        "branch": br, "bend_deg": b.strip.reading_deg, "rms_mm": b.strip.rms_mm,
                                        "tilt_deg": r.tilt_deg} for ph, p, br, b, r in measured],
                          "refused": [{"photo": ph, "reason": why} for ph, why in refused], "output": out_path},
                         indent=1, sort_keys=True))
    else:
        for photo, p, branch, b, reading in measured:
            print(f"{os.path.basename(photo)}: {labels.get(b.block, f'block {b.block}')} {b.strip.reading_deg:.2f} deg "
                  f"at {p:g} kPa {branch} (fit rms {b.strip.rms_mm:.2f} mm, board tilt {reading.tilt_deg:.0f} deg)")
        print(f"wrote {out_path} ({len(measured)} reading(s) from {len(results)} photo(s)), pictures in {pic_dir}")
    return 2 if refused else 0


def _copy_columns(sheet: str, out_rows: list) -> None:
    """Keep the sheet's coordinate and step columns as written (they are not read back)."""
    import csv

    with open(sheet, newline="", encoding="utf-8") as fh:
        original = list(csv.DictReader(fh))
    for r, o in zip(out_rows, original):
        r["coordinate"], r["step"] = o.get("coordinate", ""), o.get("step", "")
