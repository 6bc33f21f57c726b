"""Stitch plans for the export tests: hand-built ones and, when present, generated ones.

Hand-built plans follow the record convention of the generators (STOP at the first
needle point, tie-in, legs, tie-off, TRIM; JUMP travel between actuators; one END)
with numbers chosen by hand, so the export tests do not depend on the generators.
"""
from __future__ import annotations

import importlib.util

import numpy as np

from embroact.patterns.centerline import Centerline
from embroact.patterns.params import CrossParams, Tube, ZigzagParams
from embroact.patterns.plan import ActuatorPlan, Command as C, Realised, Role as R, StitchPlan

def _have(module: str) -> bool:
    return importlib.util.find_spec(module) is not None


HAVE_GENERATORS = _have("embroact.patterns.zigzag") and _have("embroact.patterns.design")
HAVE_CROSS = _have("embroact.patterns.cross")


def _zigzag_records(k, origin, width, interval, length):
    """Straight zigzag along +x from ``origin``: legs rail to rail every ``interval``."""
    ox, oy = origin
    n = int(round(length / interval))
    pts = [(ox + i * interval, oy + (width / 2 if i % 2 == 0 else -width / 2)) for i in range(n + 1)]
    recs = [(pts[0][0], pts[0][1], C.STOP, R.CONTROL, k)]
    tie = [(pts[0][0] + d, pts[0][1]) for d in (0.0, 0.7, 0.0)]
    recs += [(x, y, C.STITCH, R.TIE_IN, k) for x, y in tie]
    recs += [(x, y, C.STITCH, R.LEG, k) for x, y in pts[1:]]
    end = pts[-1]
    recs += [(end[0] - d, end[1], C.STITCH, R.TIE_OFF, k) for d in (0.7, 0.0)]
    recs.append((end[0], end[1], C.TRIM, R.CONTROL, k))
    return recs


def actuator(name, origin, width, length, pattern="zigzag", interval=1.0):
    params = ZigzagParams(width, interval) if pattern == "zigzag" else CrossParams(width, interval, 45.0)
    return ActuatorPlan(
        name, params, Tube(), Centerline.straight(length, origin_mm=origin), Realised(width, interval, 0.0, length)
    )


def hand_plan(n_actuators=1, *, width=7.0, interval=1.0, length=40.0, gap=20.0, name="hand"):
    """``n_actuators`` straight zigzags stacked in y, ``gap`` mm apart."""
    recs, acts = [], []
    for k in range(n_actuators):
        origin = (5.0, -k * gap - 3.0)
        if k:
            recs.append((origin[0], origin[1] + width / 2, C.JUMP, R.TRAVEL, k))
        recs += _zigzag_records(k, origin, width, interval, length)
        acts.append(actuator(f"A{k + 1}", origin, width, length, interval=interval))
    last = recs[-1]
    recs.append((last[0], last[1], C.END, R.CONTROL, -1))
    return StitchPlan.from_records(recs, actuators=tuple(acts), name=name)


def generated_plans():
    """(label, plan) pairs from the generators: zigzag and cross, straight and curved, 1 and 3 actuators."""
    if not HAVE_GENERATORS:
        return []
    from embroact.patterns.design import build_plan, default_design, design_from_dict
    from embroact.patterns.zigzag import zigzag

    d = "M 0 0 C 30 -25 60 25 90 0"
    curve = Centerline.from_svg_path(d)
    three = design_from_dict({"name": "three", "actuator": [
        {"name": "A1", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 60},
        {"name": "A2", "pattern": "zigzag", "width_mm": 9, "interval_mm": 1.5, "path": d, "origin_mm": [0, 30]},
        {"name": "A3", "pattern": "zigzag", "width_mm": 5, "interval_mm": 0.8, "length_mm": 40,
         "origin_mm": [20, 60], "rotation_deg": 90}]})
    plans = [
        ("zigzag-straight", zigzag(Centerline.straight(100.0), ZigzagParams(7.0, 1.0))),
        ("zigzag-curved", zigzag(curve, ZigzagParams(7.0, 1.0))),
        ("default-design", build_plan(default_design())),
        ("three-zigzags", build_plan(three)),
    ]
    if HAVE_CROSS:
        from embroact.patterns.cross import cross

        plans += [
            ("cross-straight", cross(Centerline.straight(100.0), CrossParams(7.0, 1.4, 45.0))),
            ("cross-curved", cross(curve, CrossParams(7.0, 1.4, 45.0))),
        ]
        from embroact.patterns.design import join_plans

        three_cross = join_plans(
            [cross(Centerline.straight(50.0, origin_mm=(0.0, 20.0 * k)), CrossParams(7.0, 1.4, 45.0), name=f"C{k + 1}")
             for k in range(3)], name="three-cross")
        plans.append(("three-cross", three_cross))
        plans.append(("segmented-curved", build_plan(design_from_dict({"name": "seg", "actuator": [{
            "name": "S", "path": d, "segment": [
                {"pattern": "zigzag", "width_mm": 6.1529, "interval_mm": 1, "length_mm": 45},
                {"pattern": "cross", "width_mm": 7, "interval_mm": 1.4, "angle_deg": 46.92,
                 "length_mm": curve.length_mm - 45}]}]}))))
    return plans


def needle_points(plan):
    return np.asarray(plan.xy_mm[plan.commands == C.STITCH])
