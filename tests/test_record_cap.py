"""Every record the machine will read counts against the record cap, travel jumps included."""
import math

import pytest

from embroact.patterns.assemble import MAX_RECORDS
from embroact.patterns.base.errors import PatternError
from embroact.patterns.design import build_plan, design_from_dict

SPREAD_MM = 999_999.0


def _far_apart(n: int, spread_mm: float = SPREAD_MM) -> dict:
    acts = [{"name": f"T{k}", "pattern": "zigzag", "width_mm": 5.0, "interval_mm": 1.0, "length_mm": 10.0,
             "origin_mm": [spread_mm * (-1) ** k, 0.0]} for k in range(n)]
    return {"name": "far-apart", "machine": {"hoop_width_mm": 9_000.0, "hoop_height_mm": 9_000.0}, "actuator": acts}


def test_travel_jumps_count_against_the_cap():
    """100 tiny actuators +-999,999 mm apart: ~40 stitches each, but 99 hops of 2e6 mm at
    12.0 mm per jump (DST 12.1 mm less the 0.1 mm grid) are 16.5 million jump records."""
    hop_jumps = math.ceil(2 * SPREAD_MM / 12.0)
    assert 99 * hop_jumps > MAX_RECORDS  # the hand count: the design is over the cap by travel alone
    with pytest.raises(PatternError) as err:
        build_plan(design_from_dict(_far_apart(100)))
    msg = str(err.value)
    assert "\n" not in msg and "travel jumps" in msg and f"{MAX_RECORDS:,}" in msg
    assert "1.65e+07" in msg or "1.66e+07" in msg  # about 16.5 million, counted before generating


def test_travel_jumps_within_the_cap_are_written_as_counted():
    """Two actuators 100 mm apart: the plan's jump records match the count the cap uses, within its bound."""
    from embroact.patterns.design import _travel_records
    from embroact.patterns.plan import Command, Role

    design = design_from_dict(_far_apart(2, spread_mm=50.0))
    plan = build_plan(design)
    travel = int(((plan.commands == Command.JUMP) & (plan.roles == Role.TRAVEL)).sum())
    # the bound also counts the move from the machine's start point (50 mm: 5 jumps) to the first actuator
    assert travel <= _travel_records(design) <= travel + math.ceil((50.0 + 2.5) / 12.0) + 1
