"""A third pattern kind, "parallel" (straight couching), registered from this one module.

This is what the README's "Adding a pattern kind" section describes, step by step: a frozen
parameter class, a layout (the needle stations on a stretch of the path) with its station bound
and realised parameters, the pattern kind (:func:`embroact.patterns.kinds.register`) and one model row
(:func:`embroact.predict.kinds.register_model`). Nothing else in embroact changes.

Parallel couching: legs straight across the tube (perpendicular to the path), one every
``interval_mm``, joined alternately along the left and the right rail; the threads run
around the tube, so the model's constraint is the fixed sleeve radius (as for the zigzag).
No calibration set holds parallel points, so ``embroact design`` skips it with a note.

``tests/conftest.py`` imports this module when ``EMBROACT_TEST_KINDS=1`` is set, so the
whole suite can run with the kind registered (``EMBROACT_TEST_KINDS=1 python -m pytest``).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from embroact.patterns.assemble import Layout, check_record_count
from embroact.patterns.base.errors import check_range
from embroact.patterns.kinds import PATTERN_KINDS, PatternKind, register
from embroact.patterns.params import StitchOptions, whole_intervals
from embroact.patterns.plan import Role
from embroact.predict.kinds import MODEL_KINDS, Constraint, ModelKind, register_model

NAME = "parallel"


@dataclass(frozen=True, slots=True)
class ParallelParams:
    """Straight couching: legs across the tube every ``interval_mm``, ``width_mm`` wide."""

    pattern: ClassVar[str] = NAME
    width_mm: float
    interval_mm: float

    def __post_init__(self) -> None:
        check_range("width_mm", self.width_mm, low=0.0, high=200.0)
        check_range("interval_mm", self.interval_mm, low=0.0, high=100.0)


def parallel_stations(length_mm: float, params: ParallelParams) -> int:
    """Two needle stations per leg (no allocation)."""
    return 2 * (whole_intervals(length_mm, params.interval_mm) + 1)


def parallel_realised_params(params: ParallelParams) -> ParallelParams:
    """Parallel couching sews its request as given."""
    return params


def parallel_interval_mm(sa, oa, sb, ob) -> float:
    """Realised interval: the median spacing of the legs' positions along the path [mm]."""
    pos = np.unique(np.round(0.5 * (np.asarray(sa) + np.asarray(sb)), 6))
    return float(np.median(np.diff(pos))) if pos.size > 1 else 0.0


def parallel_layout(cl, params: ParallelParams, start_mm: float, length_mm: float, *,
                    options: StitchOptions = StitchOptions()) -> Layout:
    """Parallel couching on ``[start_mm, start_mm + length_mm]`` of ``cl``: legs across, edge stitches along the
    rails, the legs centred on the stretch."""
    s = params.interval_mm
    n = whole_intervals(length_mm, s)
    check_record_count(2 * (n + 1), options)
    leg = np.arange(n + 1)
    at = start_mm + 0.5 * max(length_mm - n * s, 0.0) + leg * s
    first = np.where(leg % 2 == 0, 1, -1)  # each leg starts on the rail the previous one ended on
    return Layout(np.repeat(at, 2), np.column_stack([first, -first]).ravel(), np.tile([Role.EDGE, Role.LEG], n + 1))


def parallel_design(x: float, width_mm: float, interval_mm: float) -> ParallelParams:
    """Inverse design's free parameter: the width ``x`` at the nominal interval."""
    return ParallelParams(float(x), interval_mm)


KIND = PatternKind(NAME, ParallelParams, __name__, "width_mm", interval=parallel_interval_mm,
                   description="one parallel-couching actuator (legs straight across the tube)",
                   design_params=parallel_design)
MODEL_ROW = ModelKind(NAME, Constraint.FIXED_RADIUS, (4.0, 14.0))


def register_parallel() -> bool:
    """Register the kind and its model row (once); True when this call registered them."""
    if NAME in PATTERN_KINDS.names():
        return False
    register(KIND)
    register_model(MODEL_ROW)
    return True


def unregister_parallel() -> None:
    """Take the kind out again (a test that registered it leaves the registries as it found them)."""
    PATTERN_KINDS.remove(NAME)
    del MODEL_KINDS[NAME]
