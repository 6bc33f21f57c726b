"""The studio's design form: the design as editable fields, and edits validated as the design file is.

A design is held in its design-file form (the dict :func:`~embroact.patterns.design.design_from_dict`
reads), with straight tube paths written as ``length_mm`` (plus ``origin_mm`` and
``rotation_deg``) so that their length can be edited. Every field is named by its key
path in that dict, the same path a design-file error message starts with:
``actuator[0].width_mm``, ``actuator[0].model.g_mpa``, ``tube.outer_radius_mm``,
``actuator[1].segment[0].length_mm``. An edit names only such keys (any other is refused);
the edited dict is validated by ``design_from_dict`` itself, so an invalid value gets the
design file's own one-line message, and the key it belongs to.

Examples
--------
>>> from embroact.patterns.design import default_design
>>> form = design_form(default_design())
>>> form["actuator"][0]["length_mm"], "path" in form["actuator"][0]
(100.0, False)
>>> [f.key for f in fields(form)][:4]
['name', 'operation.max_pressure_kpa', 'operation.max_bend_deg', 'tube.outer_radius_mm']
>>> form2, design = apply_edits(form, {"actuator[0].width_mm": "7.5"})
>>> design.actuators[0].params.width_mm
7.5
>>> try:
...     apply_edits(form, {"actuator[0].width_mm": -1})
... except FieldError as exc:
...     print(exc.key, "|", exc)
actuator[0].width_mm | actuator[0]: width_mm must be in (0, 200), got -1
"""
from __future__ import annotations

import copy
import math
import re
from dataclasses import dataclass
from typing import Mapping

from ...patterns.base.choices import choice_values
from ...patterns.base.errors import DesignFileError, ParameterError
from ...patterns.design import Design, P0Source, TubeLaw, design_from_dict, design_to_dict
from ...patterns.kinds import PATTERN_KINDS, pattern_kind

__all__ = ["Field", "FieldError", "design_form", "fields", "apply_edits", "MAX_EDITS"]

#: Most fields one edit may change.
MAX_EDITS = 64
#: Angle a cross pattern starts from when an actuator is switched to it [deg] (the paper's).
DEFAULT_CROSS_ANGLE_DEG = 45.0
_KEY = re.compile(r"^[a-z_0-9]+(\[\d{1,4}\])?(\.[a-z_0-9]+(\[\d{1,4}\])?){0,3}$")
_TOKEN = re.compile(r"([a-z_0-9]+)(?:\[(\d+)\])?")


@dataclass(frozen=True, slots=True)
class Field:
    """One editable value of the design.

    Attributes
    ----------
    key : str
        Key path in the design-file dict (``actuator[0].width_mm``).
    group : str
        Where the page shows it (``"design"``, ``"tube"``, ``"actuator A1"``, ...).
    value : object
        Current value (None: unset optional value).
    kind : str
        ``"number"``, ``"choice"``, ``"bool"`` (choices ``"true"``, ``"false"``) or ``"text"``.
    choices : tuple of str
        The allowed values of a choice.
    optional : bool
        May be left empty (model values taken from the calibration set).

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> form = design_form(default_design())
    >>> fields(form)[0]
    Field(key='name', group='design', value='paper-zigzag', kind='text', choices=(), optional=False)
    """

    key: str
    group: str
    value: object
    kind: str = "number"
    choices: tuple[str, ...] = ()
    optional: bool = False

    def as_dict(self) -> dict:
        """JSON-ready.

        Returns
        -------
        dict

        Examples
        --------
        >>> Field("actuator[0].width_mm", "actuator A1", 7.0).as_dict()
        {'key': 'actuator[0].width_mm', 'group': 'actuator A1', 'value': 7.0, 'kind': 'number', 'choices': [], 'optional': False}
        """
        return {"key": self.key, "group": self.group, "value": self.value, "kind": self.kind,
                "choices": list(self.choices), "optional": self.optional}


class FieldError(DesignFileError):
    """An edit the design file would refuse; ``key`` is the field it belongs to."""

    def __init__(self, key: str, message: str) -> None:
        super().__init__(message)
        self.key = key


def _straight(table: dict) -> dict:
    """A table's two-point ``path`` as ``length_mm``, ``origin_mm``, ``rotation_deg`` (others unchanged)."""
    pts = table.get("path")
    if not isinstance(pts, list) or len(pts) != 2:
        return table
    (x0, y0), (x1, y1) = pts
    out = {k: v for k, v in table.items() if k != "path"}
    out["length_mm"] = round(math.hypot(x1 - x0, y1 - y0), 9)
    if (x0, y0) != (0.0, 0.0):
        out["origin_mm"] = [x0, y0]
    rotation = round(math.degrees(math.atan2(y1 - y0, x1 - x0)), 9)
    if rotation:
        out["rotation_deg"] = rotation
    return out


def design_form(design: Design) -> dict:
    """The design-file dict of ``design``, straight paths as ``length_mm`` (editable).

    Parameters
    ----------
    design : Design
        The design.

    Returns
    -------
    dict

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> form = design_form(default_design())
    >>> sorted(form), form["actuator"][0]["length_mm"]
    (['actuator', 'machine', 'name', 'operation', 'tube'], 100.0)
    """
    d = design_to_dict(design)
    d["actuator"] = [_straight(a) for a in d["actuator"]]
    return d


def _typed(key: str, group: str, value, choices: Mapping) -> Field:
    """A settings field, its kind from its value (true/false, text, number) or a known choice."""
    if key in choices:
        return Field(key, group, value, "choice", choices[key])
    if isinstance(value, bool):
        return Field(key, group, value, "bool", ("true", "false"))
    return Field(key, group, value, "text" if isinstance(value, str) else "number")


def _pattern_fields(table: dict, path: str, group: str) -> list[Field]:
    kind = pattern_kind(table["pattern"])
    out = [Field(f"{path}.pattern", group, table["pattern"], "choice", PATTERN_KINDS.names())]
    out += [Field(f"{path}.{k}", group, table.get(k)) for k in kind.param_keys]
    out += [Field(f"{path}.{k}", group, table.get(k, values[0]), "choice", values)
            for k, values in zip(kind.options, kind.option_values)]
    return out


def fields(form: Mapping, calibrations: tuple[str, ...] = ()) -> tuple[Field, ...]:
    """Every editable field of a design form, in page order.

    Parameters
    ----------
    form : mapping
        :func:`design_form`'s dict.
    calibrations : tuple of str, optional
        The set names a model may choose besides the built-in ones and the one it names.

    Returns
    -------
    tuple of Field

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> form = design_form(default_design())
    >>> [f.key for f in fields(form)][:4]
    ['name', 'operation.max_pressure_kpa', 'operation.max_bend_deg', 'tube.outer_radius_mm']
    """
    from ..machine.formats import FORMATS
    from ...predict.calibration import set_names

    from ...patterns.stops import CordStop

    choices = {"machine.format": tuple(FORMATS), "machine.cord_stop": choice_values(CordStop)}
    out = [Field("name", "design", form.get("name", "design"), "text")]
    for table in ("operation", "tube", "machine"):
        out += [_typed(f"{table}.{k}", table, v, choices) for k, v in form.get(table, {}).items()]
    for i, a in enumerate(form["actuator"]):
        path, group = f"actuator[{i}]", f"actuator {a.get('name', i)}"
        if "segment" in a:
            for k, seg in enumerate(a["segment"]):
                out += _pattern_fields(seg, f"{path}.segment[{k}]", f"{group}, segment {k}")
                out.append(Field(f"{path}.segment[{k}].length_mm", f"{group}, segment {k}", seg.get("length_mm")))
        else:
            out += _pattern_fields(a, path, group)
        if "length_mm" in a and "segment" not in a:
            out.append(Field(f"{path}.length_mm", group, a["length_mm"]))
        model = a.get("model", {})
        names = tuple(dict.fromkeys((*set_names(), *calibrations, model.get("calibration", "paper-2025"))))
        out.append(Field(f"{path}.model.calibration", f"{group}, model", model.get("calibration", "paper-2025"),
                         "choice", names))
        out += [Field(f"{path}.model.{k}", f"{group}, model", model.get(k), optional=True) for k in ("g_mpa", "p0_kpa")]
        out.append(Field(f"{path}.model.p0_source", f"{group}, model", model.get("p0_source", "calibration"), "choice",
                         choice_values(P0Source)))
        out.append(Field(f"{path}.model.tube_law", f"{group}, model", model.get("tube_law", "paper"), "choice",
                         choice_values(TubeLaw)))
    return tuple(out)


def _walk(form: dict, key: str) -> tuple[dict, str]:
    """The table holding ``key``'s last part, and that part."""
    parts = key.split(".")
    node = form
    for part in parts[:-1]:
        match = _TOKEN.fullmatch(part)
        if match is None:
            raise FieldError(key, f"{key}: not a design-file key path")
        name, index = match.groups()
        node = node.setdefault(name, {}) if index is None else node[name][int(index)]
    return node, parts[-1]


def _value(f: Field, raw):
    """A page value as the design file would hold it: numbers from numeric text, true/false, None for an empty optional."""
    if f.kind == "bool":
        return {"true": True, "false": False}.get(raw, raw) if isinstance(raw, str) else raw
    if f.kind != "number":
        return raw
    if isinstance(raw, str):
        text = raw.strip()
        if not text and f.optional:
            return None
        try:
            number = float(text)
        except ValueError:
            return raw  # the design file's own message names it ("must be a number")
        return int(number) if number.is_integer() and isinstance(f.value, int) else number
    return raw


def _set(form: dict, f: Field, value) -> None:
    table, last = _walk(form, f.key)
    if value is None:
        table.pop(last, None)
        return
    table[last] = value
    if last == "pattern" and isinstance(value, str) and value in PATTERN_KINDS.names():
        kind = pattern_kind(value)
        for other in PATTERN_KINDS:  # keys only another kind takes go, this kind's missing keys come
            for k in (*other.param_keys, *other.options):
                if k not in (*kind.param_keys, *kind.options):
                    table.pop(k, None)
        if "angle_deg" in kind.param_keys:
            table.setdefault("angle_deg", DEFAULT_CROSS_ANGLE_DEG)


def _field_of(message: str, keys: set[str], fallback: str) -> str:
    """The field a design-file message is about: ``actuator[0]: width_mm must ...`` -> ``actuator[0].width_mm``."""
    head, _, rest = message.partition(": ")
    word = re.match(r"[a-z_0-9]+", rest)
    for key in ((f"{head}.{word.group(0)}" if word else None), head):
        if key in keys:
            return key
    return fallback


def apply_edits(form: Mapping, edits: Mapping, calibrations: tuple[str, ...] = ()) -> tuple[dict, Design]:
    """``form`` with ``edits`` (key path -> value) applied, and the design it validates to.

    Parameters
    ----------
    form : mapping
        :func:`design_form`'s dict.
    edits : mapping of str to object
        Field key -> new value (None: unset).
    calibrations : tuple of str, optional
        As for :func:`fields`.

    Returns
    -------
    form : dict
        The edited form (``form`` itself is not changed).
    design : Design

    Raises
    ------
    ParameterError
        An edit names a key that is not a field of the form, or too many.
    FieldError
        The edited design is invalid: the design file's message and the field's key.

    Examples
    --------
    >>> from embroact.patterns.design import default_design
    >>> form = design_form(default_design())
    >>> new, design = apply_edits(form, {"actuator[0].width_mm": 6.5})
    >>> design.actuators[0].params.width_mm, form["actuator"][0]["width_mm"]
    (6.5, 7.0)
    """
    if not isinstance(edits, Mapping) or not edits:
        raise ParameterError("values must be a non-empty object of field keys and values")
    if len(edits) > MAX_EDITS:
        raise ParameterError(f"values must change at most {MAX_EDITS} fields, got {len(edits)}")
    known = {f.key: f for f in fields(form, calibrations)}
    new = copy.deepcopy(dict(form))
    for key, raw in edits.items():
        if not isinstance(key, str) or not _KEY.match(key) or key not in known:
            shown = repr(key)[:80]
            raise ParameterError(f"{shown}: unknown design parameter; the fields are the design file's keys "
                                 f"(e.g. actuator[0].width_mm)")
        if not (raw is None or isinstance(raw, (str, int, float))):
            raise FieldError(key, f"{key}: must be a number or text, got {type(raw).__name__}")
        _set(new, known[key], _value(known[key], raw))
    try:
        design = design_from_dict(new)
    except DesignFileError as exc:
        raise FieldError(_field_of(str(exc), set(known), next(iter(edits))), str(exc)) from None
    return new, design
