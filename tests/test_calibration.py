"""Calibration sets: the paper's numbers, interpolation, extrapolation flags, user sets.

Expected values are the paper's tables (docs/model.md section 7) and linear interpolation done by hand.
"""
import dataclasses

import numpy as np
import pytest

from embroact.patterns.base.errors import ModelDomainError, ParameterError
from embroact.predict.calibration import (
    PAPER_2025,
    CalibrationPoint,
    CalibrationSet,
    get_set,
    lookup,
    register,
    set_names,
    unregister,
)

# the paper's tables (docs/model.md section 7), typed by hand
PAPER_ZIGZAG = {5.0: (0.8, 50.0), 7.0: (2.7, 85.0), 9.0: (3.4, 180.0)}
PAPER_CROSS = {15.0: (2.9, 150.0), 30.0: (12.0, 160.0), 45.0: (1.3, 170.0), 60.0: (2.9, 200.0)}


@pytest.mark.parametrize("w", sorted(PAPER_ZIGZAG))
def test_paper_zigzag_points_exact(w):
    c = lookup("zigzag", width_mm=w)
    assert (c.g_mpa, c.p0_kpa) == PAPER_ZIGZAG[w]
    assert not c.interpolated and not c.extrapolated
    assert c.name == "paper-2025" and c.parameter == "width_mm"
    assert (c.range_low, c.range_high) == (5.0, 9.0)


@pytest.mark.parametrize("a", sorted(PAPER_CROSS))
def test_paper_cross_points_exact(a):
    c = lookup("cross", width_mm=7.0, angle_deg=a)
    assert (c.g_mpa, c.p0_kpa) == PAPER_CROSS[a]
    assert c.notes == () and not c.interpolated and c.parameter == "angle_deg"


def test_paper_set_metadata():
    assert "paper-2025" in set_names()
    mats = dict(PAPER_2025.materials)
    assert "natural rubber" in mats["tube"] and mats["thread"] == "polyester" and mats["fabric"] == "cotton"
    assert len(PAPER_2025.points) == 7


def test_interpolation_is_monotone_cubic_in_the_parameter():
    """PCHIP (Fritsch-Carlson) by hand at w = 6 mm: secants 0.95, 0.35 /mm; slopes 1.25 (end, three-point) and
    12 / (6 / 0.95 + 6 / 0.35) (middle); the Hermite cubic at t = 1/2."""
    m0, m1 = 1.25, 12.0 / (6.0 / 0.95 + 6.0 / 0.35)
    c = lookup("zigzag", width_mm=6.0)
    assert c.g_mpa == pytest.approx(0.5 * 0.8 + 0.125 * 2 * m0 + 0.5 * 2.7 - 0.125 * 2 * m1, rel=1e-14)
    assert c.interpolated and not c.extrapolated
    assert lookup("zigzag", width_mm=7.0).g_mpa == 2.7  # the calibrated value at a calibrated point
    scipy = pytest.importorskip("scipy.interpolate")
    for pattern, xs, g, p0 in [("zigzag", [5, 7, 9], [0.8, 2.7, 3.4], [50, 85, 180]),
                               ("cross", [15, 30, 45, 60], [2.9, 12.0, 1.3, 2.9], [150, 160, 170, 200])]:
        for x in np.linspace(xs[0], xs[-1], 37):
            c = lookup(pattern, width_mm=7.0 if pattern == "cross" else x, angle_deg=x if pattern == "cross" else None)
            assert c.g_mpa == pytest.approx(float(scipy.PchipInterpolator(xs, g)(x)), rel=1e-12)
            assert c.p0_kpa == pytest.approx(float(scipy.PchipInterpolator(xs, p0)(x)), rel=1e-12)
            k = int(np.clip(np.searchsorted(xs, x, side="right") - 1, 0, len(xs) - 2))
            assert min(g[k], g[k + 1]) - 1e-12 <= c.g_mpa <= max(g[k], g[k + 1]) + 1e-12  # monotone between points


def test_no_snap_band_around_a_calibrated_point():
    """0.6 um either side of 7 mm: G moves by the slope times the step, not to the calibrated value."""
    a, b, c = (lookup("zigzag", width_mm=w).g_mpa for w in (6.9994, 7.0, 7.0006))
    assert b == 2.7 and a < b < c and (c - a) == pytest.approx(2 * 0.0006 * 12.0 / (6.0 / 0.95 + 6.0 / 0.35), rel=1e-3)


@pytest.mark.parametrize("pattern", ["zigzag", "cross"])
def test_bend_is_continuous_over_a_dense_scan(pattern):
    """10,000 widths (zigzag) / angles (cross) across the calibrated range, at a pressure where most bend: no step
    of the bend larger than 1.5 x the local slope (the larger neighbouring step) x the step. The embroidered length is
    held at 100 mm (a cross pattern's whole leg pitches change it in steps, a separate parameter)."""
    from embroact.patterns.design import ModelSettings
    from embroact.patterns.params import Tube
    from embroact.predict.curve import sweep
    from embroact.predict.inverse import _Model, design_space
    from embroact.predict.status import Status

    space = design_space(pattern)
    pressure = 200.0 if pattern == "zigzag" else 260.0
    model = _Model(pressure, Tube(), ModelSettings(), ())
    x = np.linspace(space.low, space.high, 10_000)
    params = [space.params(v) for v in x]
    c = sweep([model.model(q, 100.0) for q in params], [pressure])
    th, st = np.asarray(c.theta_deg)[:, 0], np.asarray(c.status)[:, 0]
    ok = st == int(Status.BENDING)
    d = np.abs(np.diff(th))
    both = ok[:-1] & ok[1:]
    assert both.sum() > 5000
    local = np.maximum(np.concatenate([[0.0], d[:-1]]), np.concatenate([d[1:], [0.0]]))
    jumps = both & (d > 1.5 * local + 1e-9)
    assert not jumps.any(), [(float(x[i]), float(th[i]), float(th[i + 1])) for i in np.flatnonzero(jumps)[:5]]


def test_clamp_outside_range_is_flagged():
    lo = lookup("zigzag", width_mm=4.0)
    hi = lookup("zigzag", width_mm=12.0)
    assert (lo.g_mpa, lo.p0_kpa, lo.extrapolated) == (0.8, 50.0, True)
    assert (hi.g_mpa, hi.p0_kpa, hi.extrapolated) == (3.4, 180.0, True)
    assert not hi.interpolated
    assert "clamped to [5, 9]" in hi.label


def test_linear_extrapolation_extends_end_segment():
    c = lookup("zigzag", width_mm=10.0, extrapolation="linear")
    assert c.g_mpa == pytest.approx(3.4 + (3.4 - 2.7) / 2, rel=1e-14)
    assert c.p0_kpa == pytest.approx(180.0 + (180.0 - 85.0) / 2, rel=1e-14)
    assert c.extrapolated and "extrapolated beyond [5, 9]" in c.label


def test_linear_extrapolation_to_negative_modulus_is_refused():
    # cross 15 -> 30 deg: G rises 2.9 -> 12.0, so at 5 deg it would be 2.9 - 9.1*10/15 < 0
    with pytest.raises(ModelDomainError, match=r"g_mpa=-") as exc:
        lookup("cross", width_mm=7.0, angle_deg=5.0, extrapolation="linear")
    assert "\n" not in str(exc.value)
    assert lookup("cross", width_mm=7.0, angle_deg=5.0).g_mpa == 2.9


def test_cross_width_mismatch_noted():
    c = lookup("cross", width_mm=9.0, angle_deg=45.0)
    assert c.g_mpa == 1.3 and any("width_mm 9" in n for n in c.notes)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(pattern="cross", width_mm=7.0), "angle_deg is required"),
        (dict(pattern="spiral", width_mm=7.0), "pattern must be one of"),
        (dict(pattern="zigzag", width_mm=-1.0), "width_mm must be in"),
        (dict(pattern="zigzag", width_mm=7.0, name="nope"), "'paper-2025'"),
        (dict(pattern="zigzag", width_mm=7.0, extrapolation="cubic"), "'clamp', 'linear'"),
        (dict(pattern="zigzag", width_mm=7.0, branch="up"), "branch must be one of"),
        (dict(pattern="cross", width_mm=7.0, angle_deg=90.0), r"angle_deg must be in \(0, 90\)"),
    ],
)
def test_bad_lookup_arguments(kwargs, match):
    pattern = kwargs.pop("pattern")
    with pytest.raises(ParameterError, match=match):
        lookup(pattern, **kwargs)


def _user_set(name="lab-a"):
    return CalibrationSet(
        name,
        (
            CalibrationPoint("zigzag", 6.0, 1.0, 60.0, branch="loading"),
            CalibrationPoint("zigzag", 6.0, 2.0, 40.0, branch="unloading"),
            CalibrationPoint("zigzag", 8.0, 3.0, 100.0, branch="both"),
        ),
        "synthetic",
        {"tube": "silicone"},
    )


def test_user_set_via_sets_and_branches():
    s = _user_set()
    load = lookup("zigzag", width_mm=7.0, name="lab-a", sets=[s])
    unload = lookup("zigzag", width_mm=7.0, name="lab-a", sets=[s], branch="unloading")
    assert (load.g_mpa, load.p0_kpa) == pytest.approx((2.0, 80.0))
    assert (unload.g_mpa, unload.p0_kpa) == pytest.approx((2.5, 70.0))
    with pytest.raises(ModelDomainError, match="no cross points"):
        lookup("cross", width_mm=7.0, angle_deg=30.0, name="lab-a", sets=[s])


def test_exact_branch_wins_over_both():
    s = CalibrationSet(
        "dup",
        (
            CalibrationPoint("zigzag", 7.0, 9.0, 90.0, branch="both"),
            CalibrationPoint("zigzag", 7.0, 2.0, 20.0, branch="loading"),
            CalibrationPoint("zigzag", 7.0, 2.0, 20.0, branch="loading"),  # an identical copy is harmless
        ),
    )
    c = lookup("zigzag", width_mm=7.0, name="dup", sets=[s])
    assert (c.g_mpa, c.p0_kpa) == (2.0, 20.0)
    assert lookup("zigzag", width_mm=7.0, name="dup", sets=[s], branch="unloading").g_mpa == 9.0


def test_sets_of_one_name_keep_their_own_points():
    """The interpolation tables a process keeps are per set, not per name: a second set called "lab" with other
    points (a calibration file edited and read again) interpolates its own (hand values: the straight line
    through two points at the midpoint)."""
    def lab(g_high):
        return CalibrationSet("lab", (CalibrationPoint("zigzag", 5.0, 1.0, 50.0),
                                      CalibrationPoint("zigzag", 9.0, g_high, 150.0)))

    assert lookup("zigzag", width_mm=7.0, name="lab", sets=[lab(3.0)]).g_mpa == pytest.approx(2.0, rel=1e-15)
    assert lookup("zigzag", width_mm=7.0, name="lab", sets=[lab(5.0)]).g_mpa == pytest.approx(3.0, rel=1e-15)
    assert lookup("zigzag", width_mm=6.0, name="lab", sets=[lab(3.0)]).g_mpa == pytest.approx(1.5, rel=1e-15)


def test_conflicting_duplicates_are_refused_not_averaged():
    """G 2.70 and 9.0 for one design and branch would have become 5.85: the set names both points."""
    pts = (CalibrationPoint("zigzag", 5.0, 1.0, 50.0), CalibrationPoint("zigzag", 7.0, 2.7, 85.0),
           CalibrationPoint("zigzag", 7.0, 9.0, 85.0))
    with pytest.raises(ValueError, match=r"^points\[1\] and points\[2\] are one design \(zigzag width_mm 7, both\) "
                                         r"with different values \(g_mpa 2.7 and 9.0\): keep one$"):
        CalibrationSet("dup", pts)
    cross = (CalibrationPoint("cross", 7.0, 2.0, 80.0, angle_deg=45.0),
             CalibrationPoint("cross", 7.0, 2.0, 95.0, angle_deg=45.0))
    with pytest.raises(ValueError, match=r"\(cross width_mm 7 angle_deg 45, both\) .*\(p0_kpa 80.0 and 95.0\)"):
        CalibrationSet("dup", cross)


def test_g_e_interpolated_only_when_all_points_have_it():
    pts = (
        CalibrationPoint("zigzag", 5.0, 1.0, 50.0, g_e_mpa=0.1),
        CalibrationPoint("zigzag", 9.0, 3.0, 150.0, g_e_mpa=0.2),
    )
    c = lookup("zigzag", width_mm=6.0, name="ge", sets=[CalibrationSet("ge", pts)])
    assert c.g_e_mpa == pytest.approx(0.125)
    assert lookup("zigzag", width_mm=6.0).g_e_mpa is None


def test_register_and_unregister():
    s = _user_set("lab-reg")
    register(s)
    try:
        assert "lab-reg" in set_names() and get_set("lab-reg") is s
        assert lookup("zigzag", width_mm=8.0, name="lab-reg").g_mpa == 3.0
        with pytest.raises(ParameterError, match="already registered"):
            register(s)
        register(s, replace=True)
    finally:
        unregister("lab-reg")
    assert "lab-reg" not in set_names()
    with pytest.raises(ParameterError, match="already registered"):
        register(dataclasses.replace(s, name="paper-2025"), replace=True)
    with pytest.raises(ParameterError, match="no user calibration set"):
        unregister("paper-2025")


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(g_mpa=0.0), "g_mpa must be in"),
        (dict(p0_kpa=-1.0), "p0_kpa must be in"),
        (dict(branch="sideways"), "branch must be one of"),
        (dict(pattern="cross", angle_deg=0.0), "angle_deg must be in"),
        (dict(n_points=0), "n_points must be a positive integer"),
        (dict(g_mpa=float("nan")), "g_mpa must be a finite number"),
    ],
)
def test_point_validation(kwargs, match):
    base = dict(pattern="zigzag", width_mm=7.0, g_mpa=1.0, p0_kpa=50.0)
    base.update(kwargs)
    with pytest.raises(ParameterError, match=match):
        CalibrationPoint(**base)


def test_set_validation_and_merge():
    with pytest.raises(ParameterError, match="calibration name"):
        CalibrationSet("bad name!", PAPER_2025.points)
    with pytest.raises(ParameterError, match="at least one"):
        CalibrationSet("empty", ())
    s = _user_set()
    new = CalibrationPoint("zigzag", 6.0, 5.0, 61.0, branch="loading")
    merged = s.with_points([new])
    assert len(merged.points) == 3 and new in merged.points
    assert CalibrationPoint("zigzag", 6.0, 1.0, 60.0, branch="loading") not in merged.points
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.name = "x"


# -- calibration TOML files (export.calibfile) ---------------------------------------------
from embroact.export.files.calibfile import calibration_toml, read_calibration, write_calibration  # noqa: E402
from embroact.patterns.base.errors import DesignFileError  # noqa: E402


def test_toml_round_trip_is_exact_and_stable(tmp_path):
    odd = CalibrationSet(
        "lab.odd_1",
        (
            CalibrationPoint("cross", 7.25, 0.1 + 0.2, 1e-300 + 170.0, angle_deg=33.37, branch="unloading",
                             g_mpa_se=1e-17, rmse_deg=0.0, n_points=12, g_e_mpa=0.13),
            CalibrationPoint("zigzag", 5.0, 123456789.0 / 1e4, 0.0),
        ),
        'quote " backslash \\ tab \t newline \n DEL \x7f unicode \u00b5m \U0001f9f5',
        {"tube": "silicone 'A'", "odd key =": "x"},
    )
    path = tmp_path / "odd.toml"
    write_calibration(path, odd)
    assert read_calibration(path) == odd
    first = path.read_bytes()
    write_calibration(path, read_calibration(path))
    assert path.read_bytes() == first
    assert calibration_toml(PAPER_2025).count("[[points]]") == 7


def test_provenance_round_trips_and_old_files_still_read(tmp_path):
    from embroact.predict.calibration import CalibrationTube

    fitted = CalibrationSet("lab", (CalibrationPoint("cross", 7.0, 2.0, 120.0, angle_deg=30.0, branch="loading"),),
                            tube=CalibrationTube(1.6, 0.9, 0.2), tube_law="thick-wall",
                            measurement="markers: 2 rows of 7, 10 mm apart")
    path = tmp_path / "lab.toml"
    write_calibration(path, fitted)
    text = path.read_text()
    assert "# covers: cross angle_deg 30\n" in text and 'coordinate = "angle_deg"' in text
    assert "[tube]\nouter_radius_mm = 1.6\ninner_radius_mm = 0.9\ng_e_mpa = 0.2\n" in text
    assert read_calibration(path) == fitted
    # a file written before the provenance keys: no tube, the paper's law, whole-strip angles
    old = tmp_path / "old.toml"
    old.write_text('name = "old"\ndescription = ""\n\n[[points]]\npattern = "zigzag"\nwidth_mm = 7.0\n'
                   'g_mpa = 2.7\np0_kpa = 85.0\nbranch = "loading"\n')
    back = read_calibration(old)
    assert (back.tube, back.tube_law, back.measurement) == (None, "paper", "whole-strip")
    assert back.points == (CalibrationPoint("zigzag", 7.0, 2.7, 85.0, branch="loading"),)
    wrong = tmp_path / "wrong.toml"
    wrong.write_text(text.replace('coordinate = "angle_deg"', 'coordinate = "width_mm"'))
    with pytest.raises(DesignFileError, match=r"points\[0\]: coordinate must be 'angle_deg' for the cross pattern"):
        read_calibration(wrong)
    (tmp_path / "notube.toml").write_text(text.replace("g_e_mpa = 0.2\n", ""))
    with pytest.raises(DesignFileError, match=r"\[tube\] is missing key 'g_e_mpa'"):
        read_calibration(tmp_path / "notube.toml")


@pytest.mark.parametrize(
    "text, match",
    [
        ('name = "x"\n[[points]]\npattern = "zigzag"\nwidth_mm = 7.0\ng_mpa = 1.0\np0_kpa = 50.0\ncolour = 1\n',
         r"unknown key 'colour' in points\[0\]"),
        ('name = "x"\n[[points]]\npattern = "zigzag"\nwidth_mm = 7.0\ng_mpa = 1.0\n', r"points\[0\] is missing key 'p0_kpa'"),
        ('name = "x"\n[[points]]\npattern = "zigzag"\nwidth_mm = "7"\ng_mpa = 1.0\np0_kpa = 5.0\n',
         r"points\[0\]: width_mm must be a number"),
        ('name = "x"\nversion = 2\n[[points]]\n', "unknown key 'version' in the calibration set"),
        ('name = "x"\n', r"expected \[\[points\]\] tables"),
        ('name = "bad name"\n[[points]]\npattern = "zigzag"\nwidth_mm = 7.0\ng_mpa = 1.0\np0_kpa = 5.0\n',
         "calibration name must be"),
        ("name = \n", "TOML syntax error"),
        ('name = "x"\n[materials]\ntube = 3\n[[points]]\n', r"\[materials\] must map names to strings"),
    ],
)
def test_bad_calibration_files(tmp_path, text, match):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(DesignFileError, match=match) as exc:
        read_calibration(path)
    assert "\n" not in str(exc.value)


def test_missing_calibration_file(tmp_path):
    with pytest.raises(DesignFileError, match="cannot read"):
        read_calibration(tmp_path / "nope.toml")


# -- model_for: the one model factory; every prediction names where G and P0 came from --------
from embroact.patterns.design import ModelSettings  # noqa: E402
from embroact.patterns.params import Tube  # noqa: E402
from embroact.predict.calibration import model_for  # noqa: E402
from embroact.predict.derived import derive_from_values  # noqa: E402


def _derived(pattern="zigzag", width_mm=7.0, angle_deg=0.0):
    return derive_from_values(pattern, width_mm=width_mm, interval_mm=1.0, angle_deg=angle_deg, length_mm=100.0,
                              tube=Tube())


def test_model_for_sources():
    c = model_for(_derived())
    m = c.model
    assert (m.g_mpa, m.p0_kpa, m.calibration) == (2.7, 85.0, "calibration paper-2025 (zigzag, width_mm=7)")
    assert c.g_source == c.p0_source == "calibration paper-2025 (zigzag, width_mm=7)"
    c = model_for(_derived(width_mm=11.0))
    assert c.calibration.extrapolated and c.model.g_mpa == 3.4 and "clamped to [5, 9]" in c.g_source
    d = _derived()
    c = model_for(d, ModelSettings(p0_source="geometry"))
    # the paper's tube law at r0 (hand check: (G_e/2)(x - 1/x)^2 with x = r0/r_f)
    x = d.r0_mm / 1.5
    assert c.model.p0_kpa == pytest.approx(0.13 / 2 * (x - 1 / x) ** 2 * 1000, rel=1e-12)
    assert c.p0_source.startswith("geometry (tube law paper") and c.model.g_mpa == 2.7
    c = model_for(d, ModelSettings(g_mpa=1.5, p0_kpa=60.0))
    assert c.calibration is None and (c.model.g_mpa, c.model.p0_kpa, c.model.calibration) == (1.5, 60.0, "given")
    c = model_for(_derived("cross", angle_deg=45.0), ModelSettings(p0_kpa=100.0))
    assert (c.model.g_mpa, c.model.p0_kpa) == (1.3, 100.0) and c.p0_source == "given"
    assert c.notes == ("calibration 'paper-2025' records no tube: its G may not carry over to this tube",)
    with pytest.raises(ParameterError, match="p0_source must be one of 'calibration', 'geometry'"):
        ModelSettings(p0_source="fitted")
