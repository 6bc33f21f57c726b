"""Hypothesis properties on hostile values, run under the memory ceiling by tests/test_hostile_generated.py.

Not collected by pytest itself (no ``test_`` prefix): ``test_hostile_properties_under_the_ceiling``
runs ``python hostile_props.py`` in a process whose address space is capped, and each
``@given`` function below runs all its examples when called.

* :func:`extreme_floats`: the generator of hostile doubles: subnormals, the largest finite
  values, the smallest normals, both zeros, infinities, NaN, values around 1e+-150 (whose
  squares over- or underflow) and the doubles next to each of a set of bounds;
* :func:`check_range_property`: check_range accepts exactly the finite, non-subnormal values
  inside its bounds, and refuses every other with one line naming the parameter;
* :func:`svg_arc_property`: an SVG arc with any radii, rotation, flags and end point either
  becomes a centerline of finite points inside the coordinate range or is one PathError /
  ParameterError line, never another exception;
* :func:`output_name_property`: any string is a usable output name or one ParameterError line
  that shows it escaped (printable only).
"""
from __future__ import annotations

import math
import sys

from hypothesis import HealthCheck, given, settings, strategies as st

#: Bounds the commands use (mm, kPa, MPa, deg, counts): the doubles next to them are generated.
BOUNDS = (0.0, 1.0, 10.0, 50.0, 90.0, 100.0, 200.0, 1e4, 1e5, 1e6, 1e7)
SPECIAL = (5e-324, -5e-324, sys.float_info.min, -sys.float_info.min, sys.float_info.max, -sys.float_info.max,
           1e308, -1e308, 1e150, 1e-150, 1e-300, 0.0, -0.0, math.inf, -math.inf, math.nan)
EXAMPLES = 300
_SETTINGS = settings(max_examples=EXAMPLES, derandomize=True, deadline=None,
                     suppress_health_check=[HealthCheck.too_slow])


def extreme_floats() -> st.SearchStrategy[float]:
    """Hostile doubles: specials, the neighbours of common bounds, and any double at all."""
    near = [f(b) for b in BOUNDS for f in (lambda b: math.nextafter(b, math.inf), lambda b: math.nextafter(b, -math.inf),
                                           lambda b: b, lambda b: -b)]
    return st.one_of(st.sampled_from(SPECIAL + tuple(near)), st.floats(allow_nan=True, allow_infinity=True),
                     st.floats(min_value=-1e-300, max_value=1e-300))


@_SETTINGS
@given(extreme_floats(), st.sampled_from(BOUNDS), st.sampled_from(BOUNDS), st.booleans(), st.booleans())
def check_range_property(v, a, b, lo_in, hi_in):
    from embroact.patterns.base.errors import ParameterError, check_range

    lo, hi = min(a, b), max(a, b)
    inside = (lo < v < hi) or (lo_in and v == lo) or (hi_in and v == hi)
    ok = math.isfinite(v) and inside and (v == 0.0 or abs(v) >= sys.float_info.min)
    try:
        got = check_range("x_mm", v, low=lo, high=hi, low_inclusive=lo_in, high_inclusive=hi_in)
    except ParameterError as exc:
        assert not ok, (v, lo, hi, exc)
        assert str(exc).startswith("x_mm must ") and "\n" not in str(exc), exc
    else:
        assert ok and got == v, (v, lo, hi)


@_SETTINGS
@given(extreme_floats(), extreme_floats(), extreme_floats(), st.sampled_from("0 1".split()),
       st.sampled_from("0 1".split()), extreme_floats(), extreme_floats(), st.booleans())
def svg_arc_property(rx, ry, rotation, large, sweep, x, y, relative):
    import numpy as np

    from embroact.patterns.base.errors import EmbroactError
    from embroact.patterns.centerline import Centerline

    d = f"M 0 0 {'a' if relative else 'A'} {rx!r} {ry!r} {rotation!r} {large} {sweep} {x!r} {y!r}"
    d = d.replace("inf", "1e999").replace("nan", "0")  # the numbers as a user could type them
    try:
        c = Centerline.from_svg_path(d)
    except EmbroactError as exc:
        assert "\n" not in str(exc), exc
        return
    pts = c.points_mm
    assert np.all(np.isfinite(pts)) and np.all(np.abs(pts) <= 1e7), d


@_SETTINGS
@given(st.text(min_size=0, max_size=40) | st.sampled_from(["", ".", "-", "--", "-o", "\x00", "\udcff", "a\x1b[2J"]))
def output_name_property(name):
    from embroact.patterns.base.errors import ParameterError
    from embroact.patterns.base.validate import check_output_name

    try:
        assert check_output_name("--out", name) == name
    except ParameterError as exc:
        text = str(exc)
        assert text.startswith("--out must ") and text.isprintable(), text
        assert "\n" not in text and "\x1b" not in text and "\x00" not in text, text


def main() -> None:
    for prop in (check_range_property, svg_arc_property, output_name_property):
        prop()
        print(f"{prop.__name__}: {EXAMPLES} examples", flush=True)


if __name__ == "__main__":
    import resource

    ceiling = int(sys.argv[1])
    resource.setrlimit(resource.RLIMIT_AS, (ceiling, ceiling))
    main()
