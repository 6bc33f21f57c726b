"""Worksheet lines for every stop mode and machine kind, held against the file's own bytes."""
import numpy as np

import dst_decoder
from embroact.export.machine.formats import encode
from embroact.export.pictures.template import template_svg
from embroact.export.report.worksheet import worksheet
from embroact.patterns.design import build_plan, default_design
from embroact.patterns.plan import Command as C, Role as R, StitchPlan


def _three():
    from embroact.export.files.designfile import load_design

    return build_plan(load_design("examples/three_actuators.toml"))


def test_double_cord_stop_single_needle_counts_the_stop_codes_the_file_holds():
    plan = _three()
    data, res = encode(plan, "dst", cord_stop="double")
    codes = sum(r.kind == "stop" for r in dst_decoder.decode(data).records)
    assert codes == 6 == res.stops  # 3 cord-in stops, two 0xC3 each
    single = next(line for line in worksheet(plan, machine=res).setup if line.startswith("single-needle"))
    assert "each of the 6 stop codes, twice at each of the 3 cord-in stops" in single


def _stop_at_origin(n_actuators: int) -> StitchPlan:
    """Actuators 10 mm apart, the first one's stop point at the origin (the file leaves that stop out)."""
    recs = []
    for k in range(n_actuators):
        y = 10.0 * k
        if k:
            recs.append((0, y, C.JUMP, R.TRAVEL, k))
        recs += [(0, y, C.STOP, R.CONTROL, k), (0, y, C.STITCH, R.TIE_IN, k), (1, y + 3, C.STITCH, R.LEG, k),
                 (1, y + 3, C.TRIM, R.CONTROL, k)]
    return StitchPlan.from_records(recs + [(1, 3, C.END, R.CONTROL, -1)])


def test_stop_at_the_origin_is_worded_for_the_stop_codes_left():
    res = encode(_stop_at_origin(1), "dst")[1]
    assert res.stops == 0
    setup = worksheet(_stop_at_origin(1), machine=res).setup
    assert setup[1].startswith("no stop to set up") and not any("entries 2 to 1" in s for s in setup)
    res2 = encode(_stop_at_origin(2), "dst")[1]
    assert res2.stops == 1
    assert "programme a stop at entry 2:" in worksheet(_stop_at_origin(2), machine=res2).setup[1]


def test_start_point_is_placed_from_the_hoop_centre_on_sheet_and_template():
    """The default design with its origin at its path's start: its records span x from the start point to
    100 mm right of it, so the hoop centred on them has the start point 50 mm left of its centre; with the
    default origin (the centre of the design's extent) the start point is the hoop's centre."""
    import dataclasses

    d = default_design()
    centred = build_plan(d)
    assert "start: 0.0 mm right, 0.0 mm up of the hoop centre" in template_svg(centred)
    plan = build_plan(dataclasses.replace(d, machine=dataclasses.replace(d.machine, origin=(0.0, 0.0))))
    xy = plan.xy_mm
    assert np.isclose(xy[:, 0].min(), 0.0, atol=0.05) and np.isclose(xy[:, 0].max(), 100.0, atol=0.05)
    sheet = worksheet(plan, machine=encode(plan, "dst")[1])
    assert any("start point (the 'start' cross on the template): 50.0 mm left, 0.0 mm up of the hoop centre" in s
               for s in sheet.setup)
    assert "start: 50.0 mm left, 0.0 mm up of the hoop centre" in template_svg(plan)
