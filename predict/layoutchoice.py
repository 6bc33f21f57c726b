"""Which marker layout a reading uses, and where it came from.

A calibration set fitted to marker sums records the layout its data were measured with
(:attr:`~embroact.predict.calibration.CalibrationSet.marker_layout`). A marker reading
of a prediction made with that set should use the same layout unless the caller says
otherwise, so the policy, field by field, is:

    given field > the layout the calibration set records > the paper's layout

(:data:`~embroact.predict.markers.PAPER_LAYOUT`: 2 rows of 7 markers 10 mm apart, the
first at the clamped end). :func:`layout_for` applies it and says where the result came
from, as :class:`~embroact.predict.calibration.ModelChoice` says where G and P0 came from.

Examples
--------
>>> from embroact.predict.markers import MarkerLayout
>>> lab = MarkerLayout(markers_per_side=5, spacing_mm=12.0)
>>> layout_for(lab, calibration="lab").source
"recorded by calibration set 'lab'"
>>> c = layout_for(lab, calibration="lab", given={"offset_mm": 4.0})
>>> c.layout.label, c.source
('markers: 2 rows of 5, 12 mm apart, first 4 mm from the clamped end, fabric side', "given offset_mm; the rest recorded by calibration set 'lab'")
>>> layout_for(None, calibration="paper-2025").source
"the paper's (calibration set 'paper-2025' records none)"
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Mapping

from ..patterns.base.errors import ParameterError
from .markers import PAPER_LAYOUT, MarkerLayout

__all__ = ["LAYOUT_FIELDS", "LayoutChoice", "layout_for"]

#: The fields of a :class:`MarkerLayout` a caller may give.
LAYOUT_FIELDS = tuple(f.name for f in dataclasses.fields(MarkerLayout))


@dataclass(frozen=True, slots=True)
class LayoutChoice:
    """A marker layout and the source of its fields.

    Attributes
    ----------
    layout : MarkerLayout
        The layout.
    source : str
        Where it came from, e.g. ``"recorded by calibration set 'lab'"``, ``"the paper's"``,
        ``"given"`` or ``"given spacing_mm; the rest ..."``.
    given : tuple of str
        The fields the caller gave (the others are the recorded or the paper's).

    Examples
    --------
    >>> layout_for().as_dict()["source"]
    "the paper's"
    """

    layout: MarkerLayout
    source: str
    given: tuple[str, ...] = ()

    def as_dict(self) -> dict:
        """JSON-ready: ``layout`` (unit-suffixed keys), ``label``, ``source`` and ``given``.

        Returns
        -------
        dict

        Examples
        --------
        >>> sorted(layout_for().as_dict())
        ['given', 'label', 'layout', 'source']
        """
        return {"layout": self.layout.as_dict(), "label": self.layout.label, "source": self.source,
                "given": list(self.given)}


def layout_for(recorded: MarkerLayout | None = None, *, calibration: str = "",
               given: Mapping[str, Any] | None = None) -> LayoutChoice:
    """The layout of a marker reading: given fields over the recorded layout over the paper's.

    Parameters
    ----------
    recorded : MarkerLayout, optional
        The layout the calibration set records (``None``: it records none, or there is no set).
    calibration : str
        Name of that calibration set, for the source (empty: no set was used).
    given : mapping of field name -> value, optional
        Fields the caller set (``None`` values count as not given); names from :data:`LAYOUT_FIELDS`.

    Returns
    -------
    LayoutChoice

    Raises
    ------
    ParameterError
        An unknown field, or a given value :class:`MarkerLayout` refuses.

    Examples
    --------
    >>> layout_for(given={"spacing_mm": 8.0}).source
    "given spacing_mm; the rest the paper's"
    """
    fields = {k: v for k, v in (given or {}).items() if v is not None}
    unknown = sorted(set(fields) - set(LAYOUT_FIELDS))
    if unknown:
        raise ParameterError(f"marker layout field must be one of {', '.join(LAYOUT_FIELDS)}, got {unknown[0]!r}")
    if recorded is not None:
        base, origin = recorded, f"recorded by calibration set {calibration!r}"
    else:
        base = PAPER_LAYOUT
        origin = "the paper's" + (f" (calibration set {calibration!r} records none)" if calibration else "")
    names = tuple(k for k in LAYOUT_FIELDS if k in fields)
    if not names:
        source = origin
    elif len(names) == len(LAYOUT_FIELDS):
        source = "given"
    else:
        source = f"given {', '.join(names)}; the rest {origin}"
    return LayoutChoice(dataclasses.replace(base, **fields), source, names)
