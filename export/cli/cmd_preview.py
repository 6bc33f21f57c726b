"""``embroact preview KIND [DESIGN.toml] -o FILE``: render one view of a design.

KIND is one of

- ``stitches``: the stitch plan to scale (SVG);
- ``bend``: the pressure-bend chart of every actuator (SVG);
- ``shape``: side views of the bent strip at a few pressures (SVG);
- ``mesh``: the 3D shape at one pressure; the suffix of FILE picks the format
  (``.glb``, ``.stl``, ``.obj``, ``.ply``, or ``.svg`` for a flat-shaded picture).
  Only this kind with ``.stl``, ``.obj`` or ``.ply`` imports trimesh.

Without DESIGN the built-in default design is used (the paper's zigzag actuator).
``stitches`` also takes any embroidery file embroact reads (``preview stitches x.dst``): its
records drawn to scale in its own frame (y flipped to the plan's), before sewing.
Pressures are given as ``START:STOP:STEP`` (inclusive) or a comma list, in kPa.

Examples
--------
>>> import os, tempfile
>>> from embroact.export.cli.main import main
>>> out = os.path.join(tempfile.mkdtemp(), "bend.svg")
>>> main(["preview", "bend", "-o", out, "--pressure-kpa", "0:300:50"])
wrote ...bend.svg: bend chart, 1 actuator(s), 7 pressures
0
"""
from __future__ import annotations

import argparse
import json
from pathlib import Path

from .args import parse_pressures
from .target import add_model_arguments

__all__ = ["KINDS", "add_arguments", "run", "measured_points"]

#: kind -> one-line description.
KINDS = {
    "stitches": "stitch plan to scale (SVG)",
    "bend": "pressure-bend chart (SVG)",
    "shape": "bent-shape side views (SVG)",
    "mesh": "3D shape: .glb .stl .obj .ply, or .svg for a picture",
}


def add_arguments(parser: argparse.ArgumentParser, name: str) -> None:
    """Options of ``embroact preview``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    name : str
        The command's name (``"preview"``).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact preview")
    >>> add_arguments(parser, "preview")
    >>> args = parser.parse_args(["bend", "design.toml", "-o", "bend.svg"])
    >>> args.kind, args.design, args.output
    ('bend', 'design.toml', 'bend.svg')
    """
    parser.add_argument("kind", choices=list(KINDS), metavar="KIND",
                        help="; ".join(f"{k}: {v}" for k, v in KINDS.items()))
    parser.add_argument("design", nargs="?", help="design file (TOML); default: the built-in paper zigzag design; "
                                                  "for stitches also an embroidery file (x.dst, x.pes, ...)")
    add_model_arguments(parser.add_argument_group("model (overrides the design's [actuator.model])"))
    parser.add_argument("-o", "--output", required=True, help="output file")
    parser.add_argument("--pressure-kpa", default=None,
                        help="pressures for bend/shape, START:STOP:STEP or a list [kPa] "
                             "(default 0 to the design's max_pressure_kpa in 10 kPa steps)")
    parser.add_argument("--shape-pressure-kpa", type=float, default=None,
                        help="pressure of the 3D shape [kPa] (default: the highest pressure)")
    parser.add_argument("--states", type=int, default=5, help="pressures drawn in the side view, 1..12 (default 5)")
    parser.add_argument("--tolerance-mm", type=float, default=None,
                        help="chordal tolerance of the 3D mesh [mm] (default 0.05)")
    parser.add_argument("--measured", action="append", default=[], metavar="[ACTUATOR=]CSV",
                        help="bend chart: overlay measured points from a bend CSV (pressure_kpa,angle_deg), "
                             "on the named actuator or the first one; repeatable")
    parser.add_argument("--json", action="store_true", help="print machine-readable JSON (units in the keys)")


def measured_points(specs, names) -> dict:
    """``["A1=loop.csv", "other.csv"]`` -> {actuator name: (pressure_kpa, angle_deg)}.

    A spec without a known ``NAME=`` prefix belongs to the first actuator.

    Parameters
    ----------
    specs : sequence of str
        ``NAME=FILE.csv`` or ``FILE.csv``, each a bend CSV.
    names : sequence of str
        The design's actuator names.

    Returns
    -------
    dict of str to tuple of numpy.ndarray
        Pressures [kPa] and angles [deg] by actuator.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = Path(tmp, "b.csv").write_text("pressure_kpa,angle_deg\\n0,0\\n200,95\\n")
    ...     points = measured_points([f"B={tmp}/b.csv", f"{tmp}/b.csv"], ["A", "B"])
    >>> sorted(points), points["B"][1].tolist()
    (['A', 'B'], [0.0, 95.0])
    """
    from ..files.calibfile import read_bend_csv

    out = {}
    for spec in specs:
        name, _, rest = spec.partition("=")
        name, path = (name, rest) if rest and name in names else (names[0], spec)
        data = read_bend_csv(path)
        out[name] = (data.pressure_kpa, data.angle_deg)
    return out


def _svg_only(kind: str, out: Path) -> None:
    from ...patterns.base.errors import ParameterError

    if out.suffix.lower() != ".svg":
        raise ParameterError(f"output of preview {kind} must end in .svg, got {out.name!r}")


def run(args) -> int:
    """Load (or default) the design, analyse it once, render the view, write it atomically, report.

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
    >>> import argparse, tempfile
    >>> parser = argparse.ArgumentParser(prog="embroact preview")
    >>> add_arguments(parser, "preview")
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     args = parser.parse_args(["stitches", "-o", f"{tmp}/p.svg"])
    ...     args.command = "preview"
    ...     run(args)  # doctest: +ELLIPSIS
    wrote .../p.svg: stitch plan, 106 stitches
    0
    """
    from .args import check_shape_flags, input_files
    from ..files.atomic import check_command_files
    from .target import analyse_target, load_target

    out = check_command_files([("--output", args.output)], input_files(args))[0]
    check_shape_flags(args)
    if args.kind != "mesh":
        _svg_only(args.kind, out)
    if _is_machine_file(args.design):
        text, info = _machine_file_stitches(args, out)
    else:
        target = load_target(args, design_path=args.design)
        check_command_files([("--output", args.output)], input_files(args, target.design))  # its drawings, calibrations
        text, info = _render(args, out, analyse_target(target))
    if args.json:
        print(json.dumps({"file": str(out), "kind": args.kind, **info}, indent=2, sort_keys=True))
    else:
        print(f"wrote {out}: {text}")
    return 0


def _is_machine_file(path: str | None) -> bool:
    """True for a file name with an embroidery suffix embroact reads (``x.dst``, ``x.PES``, ...)."""
    from ..machine.filecheck import readable_suffixes

    return path is not None and Path(path).suffix.lower().lstrip(".") in readable_suffixes()


def _machine_file_stitches(args, out: Path) -> tuple[str, dict]:
    """``preview stitches FILE.dst``: the file's records to scale (no design: no tubes, no model)."""
    from ...patterns.base.errors import ParameterError
    from ..files.atomic import write_text_atomic
    from ...patterns.base.validate import MACHINE_FILE_BYTES, read_input
    from ..machine.filecheck import read_records, records_plan
    from ..machine.formats import read_result
    from ..pictures.stitches import plan_svg

    if args.kind != "stitches":
        raise ParameterError(f"preview {args.kind} needs a design file (TOML); of an embroidery file "
                             f"({Path(args.design).name}) embroact previews the stitches only")
    from .target import model_flags_given

    flags = model_flags_given(args)
    if flags:
        raise ParameterError(f"{flags[0]} applies to design files; an embroidery file is previewed without a model")
    records = read_records(args.design)
    plan = records_plan(records)
    machine = read_result(read_input(args.design, MACHINE_FILE_BYTES, "embroidery file"), records.suffix, args.design)
    write_text_atomic(out, plan_svg(plan, machine=machine))
    return (f"stitches of {Path(args.design).name}, {machine.counts_text()}",
            {"stitch_count": machine.stitches, "stop_count": machine.stops, "trim_count": machine.trims,
             "input": args.design})


def _render(args, out: Path, analysis) -> tuple[str, dict]:
    """Write the view; return a one-line summary and its JSON fields."""
    from ..files.atomic import write_text_atomic

    plan = analysis.plan
    if args.kind == "stitches":
        from ..pictures.stitches import plan_svg

        write_text_atomic(out, plan_svg(plan))
        return f"stitch plan, {plan.stitch_count} stitches", {"stitch_count": plan.stitch_count}
    from ..pictures import previews as pv
    from ..report.stage import actuator_entry

    pressures = parse_pressures(args.pressure_kpa) if args.pressure_kpa is not None else analysis.pressures_kpa
    curves = analysis.curves(pressures)
    info = {"actuators": [actuator_entry(a, c) for a, c in zip(analysis.actuators, curves)],
            "pressure_kpa": [float(p) for p in pressures]}
    if args.kind == "bend":
        measured = measured_points(args.measured, [a.name for a in plan.actuators])
        write_text_atomic(out, pv.bend_chart(analysis, curves, measured))
        return f"bend chart, {len(curves)} actuator(s), {len(pressures)} pressures", info
    if args.kind == "shape":
        from ..pictures.sideview import side_view_svg

        pv.check_side_states(args.states, name="states")
        write_text_atomic(out, side_view_svg(pv.side_panels(analysis, curves, count=args.states)))
        return f"side views, {len(curves)} actuator(s)", info
    text, mesh_info = _write_mesh(out, analysis, curves, args)
    return text, {**info, **mesh_info}


def _write_mesh(out: Path, analysis, curves, args) -> tuple[str, dict]:
    from ...patterns.base.errors import ParameterError
    from ..files.atomic import write_text_atomic
    from ..pictures.mesh import MESH_FORMATS, write_mesh

    suffix = out.suffix.lower()
    if suffix != ".svg" and suffix not in MESH_FORMATS:
        raise ParameterError(f"output of preview mesh must end in one of {', '.join(MESH_FORMATS)}, .svg, "
                             f"got {out.name!r}")
    from ..pictures.previews import shape3d_title, shape_meshes, shape_state

    shapes, pressures = shape_meshes(analysis, curves, pressure_kpa=args.shape_pressure_kpa,
                                     tolerance_mm=args.tolerance_mm)
    if suffix == ".svg":
        from ..pictures.meshview import mesh_svg

        write_text_atomic(out, mesh_svg(shapes, title=shape3d_title(pressures)))
    else:
        write_mesh(shapes, out)
    tri = sum(s.triangle_count for s in shapes)
    dev = max(s.max_deviation_mm for s in shapes)
    angles = ", ".join(f"{s.name} {s.theta_deg:.1f} deg at {pressures[s.name]:g} kPa" for s in shapes)
    parts = {a.name: list(shape_state(c, args.shape_pressure_kpa)[2])  # each segment's bend in the shape
             for a, c in zip(analysis.actuators, curves)}
    info = {"triangle_count": tri, "max_deviation_mm": dev, "tolerance_mm": shapes[0].tolerance_mm,
            "shapes": [{"name": s.name, "theta_deg": s.theta_deg, "pressure_kpa": pressures[s.name],
                        "segment_theta_deg": parts[s.name]} for s in shapes]}
    return (f"3D shape ({angles}); {tri} triangles, max deviation {dev:.4f} mm "
            f"(tolerance {shapes[0].tolerance_mm:g} mm)"), info
