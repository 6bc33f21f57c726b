"""quick_init: the same construction as the dataclass's own __init__, frozen instances, and refusals."""
import dataclasses

import numpy as np
import pytest

from embroact.patterns.base.records import quick_init
from embroact.predict.curve import ActuatorModel, Curve, curve
from embroact.predict.model import Geometry


def test_a_quick_init_builds_what_the_dataclass_init_builds():
    @dataclasses.dataclass(frozen=True, slots=True)
    class Plain:
        a: int
        b: str = "b"
        seen: tuple = ()

        def __post_init__(self):
            object.__setattr__(self, "seen", (self.a, self.b))

    Quick = quick_init(dataclasses.make_dataclass("Quick", [("a", int), ("b", str, "b"), ("seen", tuple, ())],
                                                  frozen=True, slots=True, namespace={
                                                      "__post_init__": Plain.__post_init__}))
    for args, kwargs in (((1,), {}), ((1, "x"), {}), ((), {"a": 2, "b": "y"})):
        plain, quick = Plain(*args, **kwargs), Quick(*args, **kwargs)
        assert dataclasses.astuple(plain) == dataclasses.astuple(quick)
    with pytest.raises(TypeError):
        Quick()
    with pytest.raises(TypeError):
        Quick(1, "x", (), 4)
    with pytest.raises(dataclasses.FrozenInstanceError):
        Quick(1).a = 2


@pytest.mark.parametrize("kind", [dict(), dict(frozen=True), dict(slots=True)])
def test_only_frozen_slots_dataclasses_take_it(kind):
    cls = dataclasses.make_dataclass("C", [("a", int)], **kind)
    with pytest.raises(TypeError, match="frozen dataclass with slots"):
        quick_init(cls)
    with pytest.raises(TypeError):
        quick_init(int)


def test_factories_and_keyword_only_fields_are_refused():
    for field in (dataclasses.field(default_factory=list), dataclasses.field(kw_only=True)):
        cls = dataclasses.make_dataclass("C", [("a", list, field)], frozen=True, slots=True)
        with pytest.raises(TypeError):
            quick_init(cls)


def test_the_values_a_curve_returns_stay_frozen():
    geo = Geometry.from_values(beta0_rad=0.3, l0_mm=100.0, r0_mm=2.6, c_mm2=1.25, g_mpa=1.3, p0_mpa=0.17)
    with pytest.raises(dataclasses.FrozenInstanceError):
        geo.l0 = np.ones((1, 1))
    m = ActuatorModel("zigzag", length_mm=100, r0_mm=2.58, beta0_deg=0, outer_radius_mm=1.5, inner_radius_mm=1.0,
                      g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85)
    c = curve(m, [200.0])
    assert isinstance(c, Curve) and c.calibration == "given"
    with pytest.raises(dataclasses.FrozenInstanceError):
        c.method = "x"
