"""``embroact predict``: pressure-to-bend curves for quick parameters or a design file.

``embroact predict KIND --width-mm W ...`` (KIND a pattern kind) generates the actuator (so that r0
and beta0 come from the realised stitches) and predicts theta(P);
``embroact predict DESIGN.toml`` does the same for every actuator of a design file.
Both go through :func:`embroact.export.cli.target.load_target` and the one analysis
(:func:`embroact.predict.analysis.analyse`), so ``build``, ``check`` and the API give the
same numbers. G and P0 follow the calibration policy (docs/model.md): flags > the design's
``[actuator.model]`` > the calibration set (G and P0 fitted as a pair). Pressures are
``start:stop:step`` (stop included when it lies on the grid) or a comma-separated list, in kPa.

Examples
--------
>>> from embroact.export.cli.main import main
>>> main(["predict", "zigzag", "--width-mm", "7", "--g-mpa", "2.7", "--p0-kpa", "85",
...       "--pressure-kpa", "0,100,200"])
A1: zigzag w=7 mm s=1 mm l0=100 mm; r0 2.581 mm; G 2.7 MPa (given), P0 85 kPa (given); tube r_f 1.5 mm, d_f 1 mm, G_e 0.13 MPa; tube law paper; method stable-analytic-trace
pressure_kpa  theta_deg  status       l_mm     r_mm    beta_deg  d_mm    beyond validity
     0.000       0.000   INFLATION     100.000  1.5000  0.000     1.0000
   100.000      11.539   BENDING       101.040  2.5814  0.000     2.3281
   200.000     102.930   BENDING       109.275  2.5814  0.000     2.3386
0
>>> main(["predict", "zigzag", "--width-mm", "7", "--pressure-kpa", "0:300:-10"])  # one line on stderr
2
"""
from __future__ import annotations

import argparse
import json
import math
import sys

from ...patterns.kinds import PATTERN_KINDS
from .args import parse_pressures
from .markerargs import add_layout_arguments, given_layout, wants_markers
from .target import add_model_arguments, add_quick_arguments, analyse_target, load_target

__all__ = ["add_arguments", "run", "parse_pressures"]

def add_arguments(parser: argparse.ArgumentParser, name: str) -> None:
    """Options of ``embroact predict``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    name : str
        The command's name (``"predict"``).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact predict")
    >>> add_arguments(parser, "predict")
    >>> args = parser.parse_args(["zigzag", "--width-mm", "7", "--pressure-kpa", "0,100"])
    >>> args.target, args.width_mm, args.pressure_kpa, args.method
    ('zigzag', 7.0, '0,100', 'auto')
    """
    parser.add_argument("target", metavar="KIND|DESIGN.toml",
                        help="a pattern kind with quick parameters ("
                        + ", ".join(PATTERN_KINDS.names()) + "), or a design file")
    g = parser.add_argument_group("quick parameters (a pattern kind)")
    add_quick_arguments(g, pattern=None, tube_fields=("outer_radius_mm", "inner_radius_mm", "g_e_mpa"))
    m = parser.add_argument_group("model")
    m.add_argument("--actuator", metavar="NAME", help="design file: only this actuator")
    add_model_arguments(m)
    m.add_argument("--method", default="auto", help="model method, e.g. stable-analytic-trace (default auto)")
    o = parser.add_argument_group("output")
    o.add_argument("--pressure-kpa", metavar="START:STOP:STEP|P1,P2,...",
                   help="pressures [kPa] (default 0 to MAX in 10 kPa steps and MAX itself, MAX = the design's "
                        "max_pressure_kpa, 300 for quick parameters)")
    o.add_argument("--json", action="store_true", help="print machine-readable JSON (units in the keys)")
    add_layout_arguments(parser.add_argument_group("measurement (the marker reading next to theta)"),
                         recorded="the layout the actuator's calibration set records, if any",
                         measurement_help="markers: also give what the layout's marker sum reads on each predicted "
                                          "bent line, a segmented actuator's chain of arcs included (reading_deg; "
                                          "default whole-strip: theta only)")


def _finite(x: float):
    return x if math.isfinite(x) else None


def _limits(pieces, c) -> list[list[str]]:
    """Every validity limit each point exceeds (its status names only the first), for the ``(model, curve)``
    pieces of a strip (one segment, or every segment of the whole strip: the limits any of them exceeds there);
    a whole strip that touches itself or the clamp (status COILED, ``embroact.predict.validity.strip_status``)
    is COILED."""
    import numpy as np

    from ...predict.status import Status
    from ...predict.validity import limit_flags

    per_piece = [limit_flags(np.radians(pc.theta_deg), pc.length_mm, pc.radius_mm, m.length_mm, m.stub_mm).names()
                 for m, pc in pieces]
    names = [list(dict.fromkeys(n for piece in at for n in piece)) for at in zip(*per_piece)]
    return [["COILED"] + n if s == Status.COILED and "COILED" not in n else n for n, s in zip(names, c.status)]


def _band_dict(band):
    # 1-sigma band from the calibration's covariance; None when the calibration carries none
    return None if band is None else band.summary()


def _piece(pieces, c) -> dict:
    """The curve ``c`` of a segment or a whole strip with its branch end and validity limits, from the
    ``(model, curve)`` of each of its segments (a whole strip's branch end: the one every segment has, else None)."""
    from ...patterns.chain import common
    from ...predict.branch import branch_end

    # lock-up, fold (zigzag), tracing cap or none
    out: dict[str, object] = {"branch_end": common(branch_end(m).as_dict() for m, _ in pieces)}
    out.update(c.as_dict())
    out["limits"] = _limits(pieces, c)
    return out


def _measured(out: dict, reading) -> dict:
    """``out`` with the marker reading (a (LayoutChoice, readings) pair, or None for whole-strip angles)."""
    if reading is not None:
        choice, values = reading
        out["measurement"] = choice.layout.as_dict()
        out["measurement_source"] = choice.source
        out["reading_deg"] = values.tolist()
    return out


def _result(act, c, band, segment_curves, reading=None) -> dict:
    out = act.as_dict()
    pieces = [(s.model, sc) for s, sc in zip(act.segments, segment_curves)]
    out["segment_curves"] = [_piece([piece], piece[1]) for piece in pieces]
    out.update(_piece(pieces, c))  # the whole strip, in the same keys (a chain of one: its segment's numbers)
    out["band"] = _band_dict(band)
    return _measured(out, reading)  # the reading of the whole chain of arcs


def _reading_head(reading) -> list[str]:
    """The line naming the layout of the reading column and where it came from (none without one)."""
    if reading is None:
        return []
    choice = reading[0]
    return [f"reading_deg: what the marker sum reads ({choice.layout.label}; layout: {choice.source})"]


_COLUMNS = ("pressure_kpa", "theta_deg", "status", "length_mm", "radius_mm", "beta_deg", "inner_radius_mm")


def _piece_table(title, derived, choice, c, band, reading=None) -> str:
    from ...patterns.kinds import pattern_kind
    from ...predict.status import is_model_state

    model = choice.model
    angle = (f" alpha0={derived.angle_deg:.4g} deg beta0={derived.beta0_deg:.4g} deg"
             if pattern_kind(derived.pattern).has_angle else "")
    head = (f"{title}: {derived.pattern} w={derived.width_mm:.4g} mm s={derived.interval_mm:.4g} mm "
            f"l0={derived.length_mm:.4g} mm{angle}; r0 {derived.r0_mm:.4g} mm; G {model.g_mpa:.4g} MPa "
            f"({choice.g_source}), P0 {model.p0_kpa:.4g} kPa ({choice.p0_source}); tube r_f {model.outer_radius_mm:g} mm, "
            f"d_f {model.inner_radius_mm:g} mm, G_e {model.g_e_mpa:g} MPa; tube law {model.tube_law}; "
            f"method {c.method}")
    rows = [head + "".join(f"; note: {n}" for n in choice.notes)]
    if band is not None:
        rows.append("1-sigma band of theta from the calibration's covariance: "
                    + ", ".join(f"{p:g} kPa +-{s:.3g} deg" for p, s in zip(band.pressure_kpa, band.theta_sd_deg)
                                if s > 0.0))
    d = c.as_dict()
    rows += _reading_head(reading)
    described = is_model_state(c.status).tolist()
    column = _reading_column(reading, described)
    rows.append("pressure_kpa  theta_deg " + ("reading_deg " if reading is not None else "")
                + " status       l_mm     r_mm    beta_deg  d_mm    beyond validity")
    for (p, t, s, l, r, b, di), rd, lim, ok in zip(zip(*(d[k] for k in _COLUMNS)), column, _limits([(model, c)], c),
                                                  described):
        state = (f"{t:10.3f} {rd}  {s:<13s}{l:8.3f}  {r:6.4f}  {b:<8.3f}  {di:6.4f}" if ok else
                 f"{'-':>10s} {rd}  {s:<13s}{'-':>8s}  {'-':>6s}  {'-':<8s}  {'-':>6s}")
        rows.append(f"{p:10.3f}  {state}  {'+'.join(lim)}".rstrip())
    return "\n".join(rows)


def _reading_column(reading, described: list[bool]) -> list[str]:
    """The reading_deg cells of a table (none without a reading; '-' where the model describes no state)."""
    if reading is None:
        return [""] * len(described)
    return [f"{v:10.3f} " if ok else f"{'-':>10s} " for v, ok in zip(reading[1], described)]


def _table(act, c, band, segment_curves, reading=None) -> str:
    """The actuator's text table: a chain of one as one table, a longer chain one per segment and the whole strip;
    a line saying what COILED means when the whole strip reads it."""
    from ...predict.status import Status, is_model_state

    table = act.segments.one_or_all(lambda: _piece_table(act.name, act.derived, act.choice, c, band, reading),
                                    lambda: _strip_table(act, c, segment_curves, reading))
    if is_model_state(c.status).all():
        return table
    table += ("\n-: past a validity limit the model describes no state (the formula's values, which mean nothing "
              "there, are in --json)")
    if not (c.status == Status.COILED).any():
        return table
    return (table + f"\nCOILED: the strip, with the {act.plan.tube.end_margin_mm:g} mm sealed tube beyond its tip, "
            "touches itself, the clamp or the fixed fabric (docs/model.md, where the model stops)")


def _strip_table(act, c, segment_curves, reading) -> str:
    from ...predict.status import is_model_state

    parts = [_piece_table(act.segments.part_name(act.name, k), s.derived, s.choice, sc, None)
             for k, (s, sc) in enumerate(zip(act.segments, segment_curves))]
    total = c.as_dict()  # the whole strip (embroact.predict.analysis.whole_strip)
    rows = [f"{act.name}: whole strip, {len(act.segments)} segments (sum of the segments' bends"
            + ("; the reading is the marker sum on their chain of arcs)" if reading is not None else ")")]
    rows += _reading_head(reading)
    rows.append("pressure_kpa  theta_deg " + ("reading_deg " if reading is not None else "") + " status")
    described = is_model_state(c.status).tolist()
    rows += [f"{p:10.3f}  {t:10.3f} {rd}  {s}" if ok else f"{p:10.3f}  {'-':>10s} {rd}  {s}"
             for p, t, rd, s, ok in zip(total["pressure_kpa"], total["theta_deg"], _reading_column(reading, described),
                                        total["status"], described)]
    return "\n\n".join(parts + ["\n".join(rows)])


def run(args) -> int:
    """Predict and print; return the exit code.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options (:func:`add_arguments`), with ``command`` set to ``"predict"``.

    Returns
    -------
    int
        The exit code (:mod:`embroact.export.cli.main`).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="embroact predict")
    >>> add_arguments(parser, "predict")
    >>> args = parser.parse_args(["zigzag", "--width-mm", "7", "--g-mpa", "2.7", "--p0-kpa", "85", "--pressure-kpa", "200"])
    >>> args.command = "predict"
    >>> run(args)  # doctest: +ELLIPSIS
    A1: zigzag w=7 mm s=1 mm l0=100 mm; r0 2.581 mm; G 2.7 MPa (given), P0 85 kPa (given); ...
    pressure_kpa  theta_deg  status ...
       200.000     102.930   BENDING ...
    0
    """
    from ...patterns.base.errors import ParameterError

    quick = args.target in PATTERN_KINDS.names()
    given = given_layout(args)  # checked even when the angles are whole-strip ones
    target = load_target(args, pattern=args.target if quick else None, design_path=None if quick else args.target)
    analysis = analyse_target(target)
    # default: the design's standard grid, the one build, check and preview use (working pressure included)
    pressures = parse_pressures(args.pressure_kpa) if args.pressure_kpa is not None else analysis.pressures_kpa
    acts = analysis.actuators
    if args.actuator is not None:
        acts = tuple(a for a in acts if a.name == args.actuator)
        if not acts:
            valid = ", ".join(a.name for a in analysis.actuators)
            raise ParameterError(f"--actuator must be one of {valid}, got {args.actuator!r}")
    names = [a.name for a in analysis.actuators]
    curves = dict(zip(names, analysis.curves(pressures, method=args.method)))  # segmented: the whole strip
    pieces = {name: c.segments for name, c in curves.items()}  # a chain of one: the whole strip's own curve
    readings, bands = {}, {}
    for a in acts:  # the marker reading: the actuator's layout (flags > its calibration set's > the paper's)
        choice = analysis.marker_layout(a.name, **given) if wants_markers(args) else None
        layout = None if choice is None else choice.layout
        readings[a.name] = None if choice is None else (
            choice, analysis.marker_reading_deg(a.name, layout, pressures, method=args.method))
        bands[a.name] = analysis.bands(pressures, method=args.method, measurement=layout)[names.index(a.name)]
    results = [_result(a, curves[a.name], bands[a.name], pieces[a.name], readings[a.name]) for a in acts]
    if args.json:
        payload = {"design": target.design.name, "actuators": results}  # one schema, quick or design file
        json.dump(payload, sys.stdout, indent=1, allow_nan=False)
        print()
    else:
        print("\n\n".join(_table(a, curves[a.name], bands[a.name], pieces[a.name], readings[a.name]) for a in acts))
    return 0
