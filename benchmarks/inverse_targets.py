"""Seeded target shapes for the inverse-design round trip: shapes predicted for known segmented designs.

Each target is generated from a random segmented design (2-6 segments, zigzag and cross
mixed, both bend directions, 80-200 mm long) by the forward model: the fabric line
embroact predicts for that design at the target pressure, sampled every 0.25 mm. A
design found for it can therefore match it exactly; the round trip measures how close
``design_shape`` gets.
"""
from __future__ import annotations

import math

import numpy as np

from embroact.patterns.design import ActuatorSpec, Design, MachineSettings, OperationSettings
from embroact.patterns.params import CrossParams, Tube, ZigzagParams
from embroact.patterns.segments import SegmentSpec
from embroact.predict.analysis import analyse

PRESSURE_KPA = 200.0
_ZIGZAG_WIDTH_MM = (6.6, 8.8)
_CROSS_NEG_DEG = (38.0, 52.0)
_CROSS_WIDTH_MM, _CROSS_INTERVAL_MM = 7.0, 1.4


def _segment(rng, kind: str):
    if kind == "zigzag":
        return ZigzagParams(round(float(rng.uniform(*_ZIGZAG_WIDTH_MM)), 3), 1.0), 12.0
    a = round(float(rng.uniform(*_CROSS_NEG_DEG)), 3)
    return CrossParams(_CROSS_WIDTH_MM, _CROSS_INTERVAL_MM, a), 4.0 * _CROSS_WIDTH_MM * math.tan(math.radians(a)) + 3.0


def target_design(seed: int) -> Design:
    """A random segmented design (the same for the same seed)."""
    rng = np.random.default_rng(seed)
    while True:
        n = int(rng.integers(2, 7))
        kinds = ["zigzag" if rng.random() < 0.55 else "cross" for _ in range(n)]
        if "zigzag" not in kinds or "cross" not in kinds:
            kinds[int(rng.integers(0, n))] = "cross" if "cross" not in kinds else "zigzag"
        parts = [_segment(rng, k) for k in kinds]
        low = sum(m for _, m in parts)
        if low <= 195.0:
            break
    total = float(rng.uniform(max(80.0, low), 200.0))
    extra = rng.dirichlet(np.ones(n)) * (total - low)
    lengths = [round(m + e, 2) for (_, m), e in zip(parts, extra)]
    segs = tuple(SegmentSpec(p, length, adjust="interval") for (p, _), length in zip(parts, lengths))
    spec = ActuatorSpec.segmented("T", segs)
    return Design(f"target-{seed}", Tube(), MachineSettings(), OperationSettings(max_pressure_kpa=PRESSURE_KPA),
                  (spec,))


def target_shape(seed: int, step_mm: float = 0.25) -> tuple[Design, np.ndarray]:
    """The design and its predicted fabric line at PRESSURE_KPA, points every ``step_mm`` (profile frame)."""
    design = target_design(seed)
    shape, _ = analyse(design).shapes("T", [PRESSURE_KPA])[0]
    s = np.linspace(0.0, shape.length_mm, int(round(shape.length_mm / step_mm)) + 1)
    return design, shape.profile_mm(s)


#: Seeded target bends (bend_deg, pressure_kpa, pattern): both patterns and directions, 10-300 deg, 80-300 kPa.
def target_bends(count: int = 30, seed: int = 23) -> list[tuple[float, float, str]]:
    """``count`` seeded target bends, the same for the same seed."""
    rng = np.random.default_rng(seed)
    return [(float(rng.choice([-1.0, 1.0]) * rng.uniform(10.0, 300.0)), float(rng.uniform(80.0, 300.0)),
             str(rng.choice(["zigzag", "cross"]))) for _ in range(count)]


def pystitch_needle_points_mm(data: bytes, origin_mm) -> np.ndarray:
    """Needle points [mm, plan frame] of a DST file's bytes as pystitch's reader decodes them."""
    import io

    import pystitch
    from pystitch import DstReader

    pattern = pystitch.EmbPattern.read_embroidery(DstReader, io.BytesIO(data), {"trim_at": None, "clipping": False})
    xy = [(x, -y) for x, y, c in pattern.stitches if c & pystitch.COMMAND_MASK == pystitch.STITCH]
    return np.asarray(xy, dtype=np.float64) / 10.0 + np.asarray(origin_mm, dtype=np.float64)


def sewn_bend_deg(design, pressure_kpa: float, decode=pystitch_needle_points_mm) -> tuple[float, object]:
    """(bend [deg], model) of a one-actuator design recomputed from its DST's decoded needle points.

    The DST is written from the design's plan and decoded by ``decode(bytes, origin_mm)``; the
    pattern geometry is measured on the decoded points (the plan's roles give which are legs),
    the sleeve derived from it and G and P0 looked up as ``embroact predict`` does for the
    design file.
    """
    from embroact.export.machine.formats import encode
    from embroact.patterns.design import build_plan
    from embroact.patterns.kinds import pattern_kind
    from embroact.patterns.measure import measure
    from embroact.patterns.plan import Command
    from embroact.predict.calibration import model_for
    from embroact.predict.curve import curve
    from embroact.predict.derived import derive_from_values

    plan = build_plan(design)
    data, res = encode(plan, "dst")
    xy = decode(data, res.origin_mm)
    roles = plan.roles[plan.commands == Command.STITCH]
    if len(xy) != len(roles):
        raise AssertionError(f"the DST holds {len(xy)} needle points, the plan {len(roles)}")
    spec = design.actuators[0]
    r = measure(xy, roles, plan.actuators[0].centerline, spec.pattern)  # the path as placed on the fabric
    p = spec.params
    angle = pattern_kind(spec.pattern).has_angle
    d = derive_from_values(spec.pattern, width_mm=r.width_mm, interval_mm=r.interval_mm,
                           angle_deg=r.angle_deg if angle else 0.0, length_mm=r.length_mm, tube=design.tube,
                           requested=(p.width_mm, p.interval_mm, p.angle_deg if angle else 0.0))
    model = model_for(d, spec.model).model
    return float(curve(model, [pressure_kpa]).theta_deg[0]), model
