"""One report per build: ``report.json`` (machine-readable) and a self-contained ``report.html``.

The HTML file needs nothing but itself: the pictures are inline SVG (a picture larger than
:data:`REPORT_FIGURE_MAX_BYTES`, a thousand actuators' stitches, is named by its file beside the report instead), the style is an
inline ``<style>``, there is no script, and a Content-Security-Policy forbids any
external load.  Both files are built from the same plain dict (:func:`report_data`),
so they always agree.  Same input, same bytes: no time stamps, keys in a fixed order.

Examples
--------
>>> from embroact.export.report.report import report_data, report_html, report_json
>>> data = report_data(title="demo", actuators=[{"name": "A1", "derived": {"r0_mm": 2.58}}],
...                    findings=[{"code": "E1", "severity": "error", "message": "too close",
...                               "actuator": "A1", "stitch_index": 3, "xy_mm": [1.0, 2.0], "fix": "widen"}])
>>> '"r0_mm": 2.58' in report_json(data)
True
>>> html = report_html(data, figures={"bend": "<svg></svg>"})
>>> html.startswith("<!DOCTYPE html>") and "too close" in html and "<script" not in html
True
"""
from __future__ import annotations

import html
import json
import math
from typing import Mapping, Sequence

from .. import __version__
from ...patterns.base.findings import finding_place
from ...patterns.chain import Chain

__all__ = ["FIGURES", "report_data", "report_json", "report_html", "finding_dict"]

#: Figure keys report_html knows, in page order, with their headings.
FIGURES = {
    "stitches": "Stitch preview",
    "bend": "Pressure-bend chart",
    "side": "Bent shape, side view",
    "shape3d": "3D shape",
}

_FINDING_KEYS = ("code", "severity", "message", "actuator", "stitch_index", "xy_mm", "fix")
_CSP = "default-src 'none'; style-src 'unsafe-inline'; img-src data:"
_STYLE = """
body{font-family:Helvetica,Arial,sans-serif;margin:24px auto;max-width:1100px;color:#222;padding:0 16px}
h1{font-size:24px;margin-bottom:4px}h2{font-size:18px;border-bottom:1px solid #ccc;padding-bottom:3px;margin-top:28px}
.sub{color:#666;margin-top:0}
figure{margin:8px 0;overflow-x:auto}figure svg{max-width:100%;height:auto;border:1px solid #eee;box-sizing:border-box}
summary{cursor:pointer;font-size:14px;margin:6px 0}
table{border-collapse:collapse;font-size:13px;margin:8px 0}
th,td{border:1px solid #ddd;padding:3px 8px;text-align:left;vertical-align:top}
th{background:#f4f4f4}td.num{text-align:right;font-variant-numeric:tabular-nums}
table.sub{margin:0;font-size:12px}table.sub th{background:#fafafa;font-weight:normal}td ul{margin:0;padding-left:16px}
.error{background:#fde2e2}.warning{background:#fff4d6}.info{background:#e8f1fb}
.ok{color:#2a7a2a}.note{color:#666;font-size:12px}
ul.stops{font-size:13px}
"""


def _clean(value):
    """JSON-safe copy: numpy scalars/arrays to Python, non-finite floats to None, tuples to lists."""
    kind = type(value)  # the plain types first, by exact type (a numpy float or an enum is a subclass: below)
    if kind is float:
        return value if math.isfinite(value) else None
    if value is None or kind is str or kind is int or kind is bool:
        return value
    if kind is dict:
        return {str(k): _clean(v) for k, v in value.items()}
    if kind is list:
        return [_clean(v) for v in value]
    if isinstance(value, Mapping):
        return {str(k): _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    if hasattr(value, "tolist"):
        return _clean(value.tolist())
    if hasattr(value, "value") and hasattr(value, "name"):  # enums
        return _clean(value.value)
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    return value


def finding_dict(finding) -> dict:
    """A design-rule finding (``Finding`` object or dict) as a dict with the standard keys.

    Parameters
    ----------
    finding : Finding or mapping
        The finding.

    Returns
    -------
    dict
        Missing keys are None.

    Examples
    --------
    >>> finding_dict({"code": "EA101", "message": "needle in the tube"})["severity"] is None
    True
    """
    if hasattr(finding, "as_dict"):
        d = dict(finding.as_dict())
    elif isinstance(finding, Mapping):
        d = dict(finding)
    else:
        d = {k: getattr(finding, k, None) for k in _FINDING_KEYS}
    for k in _FINDING_KEYS:
        d.setdefault(k, None)
    d["place"] = finding_place(d)
    return _clean(d)


def report_data(
    *,
    title: str,
    actuators: Sequence[Mapping],
    findings=(),
    worksheet: Mapping | None = None,
    mesh: Mapping | None = None,
    generator: str = f"embroact {__version__}",
) -> dict:
    """The report as one plain, JSON-ready dict.

    Parameters
    ----------
    title : str
        Design name.
    actuators : sequence of mapping
        Per actuator: ``name``, ``derived`` (``DerivedGeometry.as_dict()``), optionally
        ``model`` (``ModelChoice.as_dict()``: G, P0, tube, tube law and their sources),
        ``curve`` (``Curve.as_dict()``: ``pressure_kpa``, ``theta_deg``, ``status`` lists,
        ``method``) and ``side_view`` (list of ``{"pressure_kpa", "theta_deg"}``).
    findings : iterable
        ``Finding`` objects or dicts (code, severity, message, actuator, stitch_index, xy_mm, fix).
    worksheet : mapping, optional
        ``Worksheet.as_dict()``.
    mesh : mapping, optional
        3D output facts: file name, pressure, triangle count, tolerance, realised deviation.
    generator : str, optional
        What made the report.

    Returns
    -------
    dict

    Examples
    --------
    >>> data = report_data(title="demo", actuators=[{"name": "A1"}])
    >>> data["title"], data["findings"], data["generator"].startswith("embroact")
    ('demo', [], True)
    """
    return _clean({
        "title": str(title),
        "generator": generator,
        "actuators": [dict(a) for a in actuators],
        "findings": [finding_dict(f) for f in findings],
        "worksheet": dict(worksheet) if worksheet is not None else None,
        "mesh": dict(mesh) if mesh is not None else None,
    })


def report_json(data: Mapping) -> str:
    """``report.json`` text: indented, keys in insertion order, no NaN (strict JSON).

    Parameters
    ----------
    data : mapping
        From :func:`report_data`.

    Returns
    -------
    str
        Ending in a newline.

    Examples
    --------
    >>> print(report_json({"title": "demo", "r0_mm": 2.581}), end="")
    {
      "title": "demo",
      "r0_mm": 2.581
    }
    """
    return json.dumps(_clean(data), indent=2, allow_nan=False) + "\n"


def _e(v) -> str:
    return html.escape("" if v is None else str(v), quote=True)


def _num(v) -> str:
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return _e(v)
    return _e(f"{v:.6g}" if isinstance(v, float) else v)


#: Name endings and the unit they stand for: ``size_mm`` is written "size [mm]".
_UNITS = (("_kpa", "kPa"), ("_mpa", "MPa"), ("_deg", "deg"), ("_mm", "mm"), ("_spm", "stitches/min"),
          ("_m", "m"), ("_s", "s"))


def _label(key) -> str:
    """A key as a heading: underscores as spaces, a unit ending as the unit in brackets."""
    key = str(key)
    for end, unit in _UNITS:
        if key.endswith(end) and len(key) > len(end):
            return f"{key[:-len(end)].replace('_', ' ')} [{unit}]"
    return key.replace("_", " ")


def _value(v) -> str:
    """HTML of one value: numbers to 6 digits, yes/no, lists of numbers in one line, lists of text as a
    list, a mapping as a sub-table of its keys, a list of mappings as a sub-table with a row each."""
    if isinstance(v, bool):
        return "yes" if v else "no"
    if v is None or isinstance(v, (int, float, str)):
        return _num(v)
    if isinstance(v, Mapping):
        if not v:
            return ""
        rows = "".join(f"<tr><th>{_e(_label(k))}</th>{_cell(x)}</tr>" for k, x in v.items())
        return f'<table class="sub">{rows}</table>'
    items = list(v)
    if not items:
        return ""
    if all(isinstance(x, Mapping) for x in items):
        keys = list(dict.fromkeys(k for x in items for k in x))
        head = "".join(f"<th>{_e(_label(k))}</th>" for k in keys)
        rows = "".join(f"<tr>{''.join(_cell(x.get(k)) for k in keys)}</tr>" for x in items)
        return f'<table class="sub"><tr>{head}</tr>{rows}</table>'
    if all(isinstance(x, str) for x in items) and len(items) > 1:
        return "<ul>" + "".join(f"<li>{_e(x)}</li>" for x in items) + "</ul>"
    return ", ".join(_value(x) for x in items)  # each item escaped once


def _cell(v) -> str:
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        return f'<td class="num">{_num(v)}</td>'
    return f"<td>{_value(v)}</td>"


def _named_segments(actuator: Mapping) -> list[Mapping]:
    """The actuator's segments, each named as the chain names its parts (:meth:`Chain.part_name
    <embroact.patterns.chain.Chain.part_name>`): ``A1`` in a chain of one, ``A1 segment 0``, ``A1 segment 1``
    ... in a longer one; an entry without segments (read from a machine file) is its own one."""
    segs = list(actuator.get("segments") or [actuator])
    chain = Chain(segs)
    return [{**s, "name": chain.part_name(str(actuator.get("name")), k)} for k, s in enumerate(segs)]


def _parts(actuators: Sequence[Mapping]) -> list[Mapping]:
    """One entry per segment of every actuator (:func:`_named_segments`), with its ``derived`` and ``model``."""
    return [s for a in actuators for s in _named_segments(a)]


#: Columns (actuators, segments) a per-actuator table shows at most; beyond it identical entries share one
#: column, and past that the first ones are shown with a note (``report.json`` holds every actuator).
REPORT_MAX_COLUMNS = 100


def _unnamed(value, name):
    """``value`` without its ``name`` entries that repeat ``name`` (at any depth: a part's derived geometry names
    its actuator), so that two actuators alike but for their names compare equal.

    Examples
    --------
    >>> _unnamed({"name": "A1", "derived": {"name": "A1", "r0_mm": 2.0}, "other": {"name": "B"}}, "A1")
    {'derived': {'r0_mm': 2.0}, 'other': {'name': 'B'}}
    """
    if isinstance(value, Mapping):
        return {k: _unnamed(v, name) for k, v in value.items() if not (k == "name" and v == name)}
    if isinstance(value, list):
        return [_unnamed(v, name) for v in value]
    return value


def _summarised(entries: Sequence[Mapping], first=frozenset()) -> tuple[list[Mapping], str]:
    """``entries`` as a table shows them (at most :data:`REPORT_MAX_COLUMNS`) and the note saying what was
    merged or left out ("" when all are shown as they are). Past the cap, the columns holding an entry named in
    ``first`` (the actuators with findings) come first.

    Examples
    --------
    >>> few, note = _summarised([{"name": f"A{k}", "x": 1} for k in range(150)])
    >>> [e["name"] for e in few], note
    (['A0 and 149 identical'], '150 columns, identical ones shown once')
    >>> few, note = _summarised([{"name": f"A{k}", "x": k % 2} for k in range(150)], first={"A7"})
    >>> [e["name"] for e in few], note
    (['A1 and 74 identical', 'A0 and 74 identical'], '150 columns, identical ones shown once, those with findings first')
    """
    if len(entries) <= REPORT_MAX_COLUMNS:
        return list(entries), ""
    groups: dict[str, list[Mapping]] = {}
    for e in entries:
        key = json.dumps(_unnamed(e, e.get("name")), sort_keys=True, default=str)
        groups.setdefault(key, []).append(e)
    flagged = [any(str(e.get("name")) in first for e in g) for g in groups.values()]
    ordered = [g for f, g in zip(flagged, groups.values()) if f] + [g for f, g in zip(flagged, groups.values()) if not f]
    shown = [{**g[0], "name": f"{g[0].get('name')} and {len(g) - 1} identical"} if len(g) > 1 else g[0]
             for g in ordered]
    note = f"{len(entries)} columns, identical ones shown once" + (", those with findings first" if any(flagged)
                                                                   and not all(flagged) else "")
    if len(shown) > REPORT_MAX_COLUMNS:
        note += f"; the first {REPORT_MAX_COLUMNS} of {len(shown)} shown (report.json has every one)"
        shown = shown[:REPORT_MAX_COLUMNS]
    return shown, note


def _noted(note: str) -> str:
    return f'<p class="note">{_e(note)}</p>' if note else ""


def _ranges_table(parts: Sequence[Mapping]) -> str:
    """Per numeric derived quantity over every part: how many have it, its least and greatest value and how many
    distinct values it takes (the summary above a table of more than :data:`REPORT_MAX_COLUMNS` columns)."""
    values: dict[str, list[float]] = {}
    for p in parts:
        for k, v in (p.get("derived") or {}).items():
            if isinstance(v, (int, float)) and not isinstance(v, bool):
                values.setdefault(k, []).append(v)
    rows = "".join(f"<tr><th>{_e(_label(k))}</th>{_cell(len(v))}{_cell(min(v))}{_cell(max(v))}{_cell(len(set(v)))}"
                   "</tr>" for k, v in values.items())
    head = "".join(f"<th>{h}</th>" for h in ("quantity", "count", "least", "greatest", "distinct values"))
    return f'<table class="ranges"><tr>{head}</tr>{rows}</table>' if rows else ""


def _derived_table(actuators: Sequence[Mapping], with_findings=frozenset()) -> str:
    all_parts = _parts(actuators)
    parts, note = _summarised(all_parts, with_findings)
    rows: list[str] = []
    for a in parts:
        for k in a.get("derived") or {}:
            if k not in rows:
                rows.append(k)
    if not rows:
        return '<p class="note">no actuators</p>'
    head = "".join(f"<th>{_e(a.get('name'))}</th>" for a in parts)
    body = "".join(
        f"<tr><th>{_e(_label(k))}</th>{''.join(_cell((a.get('derived') or {}).get(k)) for a in parts)}</tr>"
        for k in rows
    )
    table = f"<table><tr><th>quantity</th>{head}</tr>{body}</table>"
    if len(all_parts) > REPORT_MAX_COLUMNS:  # a summary of the ranges, the columns collapsed under it
        table = (_ranges_table(all_parts) + f"<details><summary>Per actuator ({len(parts)} column{'s' * (len(parts) != 1)})</summary>"
                 f"{_noted(note)}{table}</details>")
        note = ""
    return _noted(note) + table + _segments_table(actuators)


def _segments_table(actuators: Sequence[Mapping]) -> str:
    """Where each segment lies (named as :func:`_named_segments` names it: a chain of one as its actuator): its
    share of the path, its legs (the part that bends), the unbent transition to the next segment and the
    thread's run along a rail there [mm]."""
    rows = []
    for s in (s for s in _parts(actuators) if "start_mm" in s):
        legs = s["first_leg_mm"] + (s.get("derived") or {}).get("length_mm", 0.0)
        rows.append(f"<tr><th>{_e(s['name'])}</th><td>{_e(s.get('pattern'))}</td>"
                    f"{_cell(s['start_mm'])}{_cell(s['start_mm'] + s['length_mm'])}{_cell(s['first_leg_mm'])}"
                    f"{_cell(legs)}{_cell(s['transition_mm'])}{_cell(s['join_run_mm'])}</tr>")
    if not rows:
        return ""
    head = "".join(f"<th>{h}</th>" for h in ("segment", "pattern", "path from [mm]", "path to [mm]", "legs from [mm]",
                                               "legs to [mm]", "transition [mm]", "thread run [mm]"))
    table = f"<table><tr>{head}</tr>{''.join(rows)}</table>"
    if len(rows) > REPORT_MAX_COLUMNS:
        table = f"<details><summary>{len(rows)} segments</summary>{table}</details>"
    return f"<h3>Segments along the path</h3>{table}"


def _model_table(actuators: Sequence[Mapping]) -> str:
    """G, P0, tube and tube law per actuator (per segment of a segmented one), each with where it came from."""
    with_model, note = _summarised([a for a in _parts(actuators) if a.get("model")])
    if not with_model:
        return '<p class="note">no model</p>'
    rows = []
    for a in with_model:
        m, t = a["model"], a["model"].get("tube") or {}
        tube = (f"r_f {_num(t.get('outer_radius_mm'))} mm, d_f {_num(t.get('inner_radius_mm'))} mm, "
                f"G_e {_num(t.get('g_e_mpa'))} MPa")
        rows.append(f"<tr><th>{_e(a.get('name'))}</th>{_cell(m.get('g_mpa'))}<td>{_e(m.get('g_source'))}</td>"
                    f"{_cell(m.get('p0_kpa'))}<td>{_e(m.get('p0_source'))}</td>{_cell(m.get('tube_law_p0_kpa'))}"
                    f"<td>{_e(m.get('tube_law'))}</td>"
                    f"<td>{_e(tube)}</td><td>{_e('; '.join(m.get('notes') or []))}</td></tr>")
    head = "".join(f"<th>{h}</th>" for h in ("actuator", "G [MPa]", "G from", "P0 [kPa]", "P0 from", "tube-law P0 [kPa]", "tube law",
                                               "tube", "notes"))
    return _noted(note) + f"<table><tr>{head}</tr>{''.join(rows)}</table>"


#: Findings the report's table lists one by one at most; past it, one row per kind of finding (severity, code,
#: message and fix alike) with its count and the actuators it names, errors first (report.json lists every one).
REPORT_MAX_FINDINGS = 100
#: Largest figure [bytes] the report holds inline; a larger one is named by its file beside the report.
REPORT_FIGURE_MAX_BYTES = 1_500_000
_SEVERITY_ORDER = {"error": 0, "warning": 1, "info": 2}


def _findings_summary(findings: Sequence[Mapping]) -> str:
    """One row per kind of finding (severity, code, message, fix), errors first: how many, and where (the first
    five actuators named and how many more)."""
    groups: dict[tuple, list[Mapping]] = {}
    for f in findings:
        groups.setdefault(tuple(str(f.get(k) or "") for k in ("severity", "code", "message", "fix")), []).append(f)
    order = sorted(groups, key=lambda k: (_SEVERITY_ORDER.get(k[0], 3), k[1]))
    head = "".join(f"<th>{h}</th>" for h in ("severity", "code", "message", "count", "where", "fix"))
    rows = []
    for key in order:
        fs = groups[key]
        names = list(dict.fromkeys(str(f["actuator"]) for f in fs if f.get("actuator") is not None))
        where = ", ".join(names[:5]) + (f" and {len(names) - 5} more" if len(names) > 5 else "")
        sev, code, message, fix = key
        rows.append(f'<tr class="{_e(sev)}"><td>{_e(sev)}</td><td>{_e(code)}</td><td>{_e(message)}</td>'
                    f'{_cell(sum(f.get("count") or 1 for f in fs))}<td>{_e(where)}</td><td>{_e(fix)}</td></tr>')
    note = (f"{len(findings)} findings in {len(groups)} kinds (alike severity, code, message and fix), errors first; "
            "report.json lists every one")
    return _noted(note) + f"<table><tr>{head}</tr>{''.join(rows)}</table>"


def _findings_table(findings: Sequence[Mapping]) -> str:
    if not findings:
        return '<p class="ok">No design-rule findings.</p>'
    if len(findings) > REPORT_MAX_FINDINGS:
        return _findings_summary(findings)
    head = "".join(f"<th>{h}</th>" for h in ("severity", "code", "message", "where", "fix"))
    rows = []
    for f in findings:
        sev = str(f.get("severity") or "")
        rows.append(f'<tr class="{_e(sev)}"><td>{_e(sev)}</td><td>{_e(f.get("code"))}</td><td>{_e(f.get("message"))}'
                    f'</td><td>{_e(finding_place(f))}</td><td>{_e(f.get("fix"))}</td></tr>')
    return f"<table><tr>{head}</tr>{''.join(rows)}</table>"


#: Worksheet entries shown elsewhere in the report (the findings) or as their own list (the stops).
_WORKSHEET_APART = ("actuators", "stops", "findings")


def _worksheet_html(ws: Mapping | None) -> str:
    """The worksheet as tables of values with units: the whole design, then one column per actuator
    (nested values, a segment's geometry, as sub-tables)."""
    if not ws:
        return '<p class="note">no worksheet</p>'
    table = "".join(f"<tr><th>{_e(_label(k))}</th>{_cell(v)}</tr>" for k, v in ws.items() if k not in _WORKSHEET_APART)
    out = [f"<table>{table}</table>"]
    if ws.get("stops"):
        stops = list(ws["stops"])
        more = (f'<p class="note">the first {REPORT_MAX_COLUMNS} of {len(stops)} stops shown (worksheet.txt lists '
                "every one)</p>" if len(stops) > REPORT_MAX_COLUMNS else "")
        out.append("<h3>Stop sequence</h3><ul class=\"stops\">"
                   + "".join(f"<li>{_e(s)}</li>" for s in stops[:REPORT_MAX_COLUMNS]) + "</ul>" + more)
    acts, note = _summarised(ws.get("actuators") or [])
    if acts:
        keys = [k for k in dict.fromkeys(k for a in acts for k in a) if k != "name"]
        head = "".join(f"<th>{_e(a.get('name'))}</th>" for a in acts)
        rows = "".join(f"<tr><th>{_e(_label(k))}</th>{''.join(_cell(a.get(k)) for a in acts)}</tr>" for k in keys
                       if any(a.get(k) not in (None, [], {}) for a in acts))
        out.append(f"<h3>Per actuator</h3>{_noted(note)}<table><tr><th>actuator</th>{head}</tr>{rows}</table>")
    return "".join(out)


def _curve_columns(actuator: Mapping) -> list[Mapping]:
    """The curves of one actuator in the table: a chain of one its own (named as the actuator), a longer one its
    whole strip and each segment's (named as the chain names them, :func:`_named_segments`)."""
    curves = actuator.get("segment_curves") or []
    name = actuator.get("name")
    return Chain.shown(curves, lambda: [actuator], lambda: [{**actuator, "name": f"{name} whole strip"}] + [
        {"name": Chain(curves).part_name(str(name), k), "curve": c} for k, c in enumerate(curves)])


def _curve_table(actuators: Sequence[Mapping]) -> str:
    with_curves, note = _summarised([c for a in actuators if a.get("curve") for c in _curve_columns(a)])
    if not with_curves:
        return ""
    pressures = with_curves[0]["curve"]["pressure_kpa"]
    if any(a["curve"]["pressure_kpa"] != pressures for a in with_curves):
        return ""
    head = "".join(f"<th>{_e(a.get('name'))} theta [deg]</th><th>status</th>" for a in with_curves)
    rows = []
    for i, p in enumerate(pressures):
        cells = "".join(_theta_cell(a, i) + _cell((a["curve"].get("status") or [""] * (i + 1))[i])
                        for a in with_curves)
        rows.append(f"<tr>{_cell(p)}{cells}</tr>")
    banded = any(a.get("band") for a in with_curves)
    banded_note = " (+- the 1-sigma band of the fitted calibration's covariance)" if banded else ""
    return (f"<details><summary>Predicted curve ({len(pressures)} pressures){banded_note}</summary>{_noted(note)}<table>"
            f"<tr><th>pressure [kPa]</th>{head}</tr>{''.join(rows)}</table></details>")


def _theta_cell(actuator: Mapping, i: int) -> str:
    """theta at point i, with the band's 1-sigma half-width where it has one (``theta +- sd``)."""
    theta, band = actuator["curve"]["theta_deg"][i], actuator.get("band")
    sd = band["theta_sd_deg"][i] if band else 0.0
    if not isinstance(theta, (int, float)) or not sd:
        return _cell(theta)
    return f'<td class="num">{_num(theta)} +- {_e(f"{sd:.3g}")}</td>'


def _mesh_note(mesh: Mapping | None) -> str:
    if not mesh:
        return ""
    parts = [f"{k.replace('_', ' ')}: {_num(v)}" for k, v in mesh.items() if not isinstance(v, (dict, list))]
    return f'<p class="note">{_e("; ".join(parts))}</p>'


def _inline_svg(svg: str) -> str:
    """SVG text ready to sit inside HTML: any XML declaration or doctype dropped."""
    start = svg.find("<svg")
    return svg[start:] if start >= 0 else svg


def _figure(svg: str, file: str | None) -> str:
    """The figure inline, or past :data:`REPORT_FIGURE_MAX_BYTES` (when it has a file) a link to its file."""
    size = len(svg.encode("utf-8"))
    if file is None or size <= REPORT_FIGURE_MAX_BYTES:
        return f"<figure>{_inline_svg(svg)}</figure>"
    return (f'<p class="note">This picture is {size / 1e6:.1f} MB, more than a page holds inline '
            f'(at most {REPORT_FIGURE_MAX_BYTES / 1e6:.1f} MB): open <a href="{_e(file)}">{_e(file)}</a>, written '
            "beside this report.</p>")


def report_html(data: Mapping, *, figures: Mapping[str, str] | None = None,
                figure_files: Mapping[str, str] | None = None) -> str:
    """The self-contained ``report.html`` text.

    Parameters
    ----------
    data : mapping
        From :func:`report_data`.
    figures : mapping, optional
        SVG texts keyed by the names in :data:`FIGURES`; missing ones are left out.
    figure_files : mapping, optional
        The file each figure is written to beside the report (keyed as ``figures``): a figure larger than
        :data:`REPORT_FIGURE_MAX_BYTES` is linked there instead of inlined. Without one, every figure is inline.

    Returns
    -------
    str
        One HTML page, no external resources.

    Raises
    ------
    ParameterError
        A figure name not in :data:`FIGURES`.

    Examples
    --------
    >>> html = report_html(report_data(title="demo", actuators=[{"name": "A1"}]))
    >>> html.startswith("<!DOCTYPE html>"), "<h1>demo</h1>" in html
    (True, True)
    """
    figures = dict(figures or {})
    unknown = sorted(set(figures) - set(FIGURES))
    if unknown:
        from ...patterns.base.errors import ParameterError

        raise ParameterError(f"figure names must be among {', '.join(FIGURES)}, got {', '.join(unknown)}")
    acts = data.get("actuators") or []
    findings = data.get("findings") or []
    n_all = sum(f.get("count") or 1 for f in findings)  # a capped rule's last finding counts the rest
    n_err = sum(f.get("count") or 1 for f in findings if f.get("severity") == "error")
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        f'<meta http-equiv="Content-Security-Policy" content="{_CSP}">',
        '<meta name="viewport" content="width=device-width, initial-scale=1">',
        f"<title>{_e(data.get('title'))} - embroact report</title>",
        f"<style>{_STYLE}</style></head><body>",
        f"<h1>{_e(data.get('title'))}</h1>",
        f'<p class="sub">{len(acts)} actuator(s); {n_all} design-rule finding(s), {n_err} error(s); '
        f"{_e(data.get('generator'))}</p>",
    ]
    for key, heading in FIGURES.items():
        if key in figures:
            parts.append(f'<section id="{key}"><h2>{heading}</h2>'
                         + _figure(figures[key], (figure_files or {}).get(key)))
            if key == "bend":
                parts.append(_curve_table(acts))
            if key == "shape3d":
                parts.append(_mesh_note(data.get("mesh")))
            parts.append("</section>")
    parts += [
        '<section id="model"><h2>Model</h2>', _model_table(acts), "</section>",
        '<section id="derived"><h2>Derived geometry</h2>',
        _derived_table(acts, frozenset(str(f["actuator"]) for f in findings if f.get("actuator") is not None)),
        "</section>",
        '<section id="worksheet"><h2>Worksheet</h2>', _worksheet_html(data.get("worksheet")), "</section>",
        '<section id="findings"><h2>Design-rule findings</h2>', _findings_table(findings), "</section>",
        "</body></html>",
    ]
    return "\n".join(parts) + "\n"
