"""Picture titles fit their pictures: widths from the Helvetica-Bold metrics, wrapped, shortened."""
import re

import pytest

from embroact.export.pictures.chart import bend_chart_svg
from embroact.export.pictures.meshview import mesh_svg
from embroact.export.pictures.previews import bend_series, shape3d_title, shape_meshes
from embroact.export.pictures.titles import ELLIPSIS, fit_title, text_width_px
from embroact.patterns.design import default_design
from embroact.predict.analysis import analyse

LONG = ("a rather long design name for the lab notebook: predicted bend; tube paper law, r_f 1.5, d_f 1 mm, "
        "G_e 0.13 MPa; thick-wall law, r_f 2, d_f 1.4 mm, G_e 0.2 MPa")


def test_widths_by_hand():
    # Helvetica-Bold advances: M 833, i 278, l 278, space 278, digits 556, degree sign 400 (1/1000 em)
    assert text_width_px("MMM", 10.0) == pytest.approx(24.99)
    assert text_width_px("il 0", 10.0) == pytest.approx((278 * 3 + 556) / 100)
    assert text_width_px("45\u00b0", 12.0) == pytest.approx((556 * 2 + 400) * 12 / 1000)


def test_a_short_title_stays_one_line_at_its_size():
    assert fit_title("Predicted bend angle", 300.0).lines == ("Predicted bend angle",)
    assert fit_title("Predicted bend angle", 300.0).font_px == 15.0
    # too wide at 15 px for 140 px (151.7 px), fits at 12 px (121.4 px)
    assert fit_title("Predicted bend angle", 140.0).font_px == 12.0


def test_long_titles_wrap_at_separators_and_keep_every_word():
    f = fit_title(LONG, 600.0, max_lines=3)
    assert len(f.lines) > 1 and all(text_width_px(line, f.font_px) <= 600.0 for line in f.lines)
    assert " ".join(f.lines) == LONG  # wrapped after "; " or ", " or a space, nothing dropped
    assert f.lines[0].endswith(";")  # the coarsest separator first


def test_titles_past_the_lines_are_shortened_with_an_ellipsis():
    f = fit_title(LONG, 200.0, max_lines=2)
    assert len(f.lines) == 2 and f.lines[-1].endswith(ELLIPSIS)
    assert all(text_width_px(line, f.font_px) <= 200.0 for line in f.lines)
    one = fit_title("x" * 300, 100.0, max_lines=1)
    assert one.lines[0].endswith(ELLIPSIS) and text_width_px(one.lines[0], 12.0) <= 100.0


def _titles(svg):
    return [(float(size), text) for size, text in
            re.findall(r'<text[^>]*font-size="([\d.]+)"[^>]*font-weight="bold"[^>]*>([^<]*)</text>', svg)]


@pytest.fixture(scope="module")
def paper():
    a = analyse(default_design())
    return a, a.curves()


def test_chart_title_fits_the_chart(paper):
    a, curves = paper
    svg = bend_chart_svg(bend_series(a, curves), title=LONG, width_px=720)
    lines = [(s, t) for s, t in _titles(svg)]
    assert len(lines) == 2 and all(64 + text_width_px(t, s) <= 720 - 10 for s, t in lines)
    short = bend_chart_svg(bend_series(a, curves), title="A1: predicted bend", width_px=720)
    assert _titles(short) == [(15.0, "A1: predicted bend")]


def test_3d_title_of_many_actuators_fits_the_picture(paper):
    a, curves = paper
    shapes, _ = shape_meshes(a, curves)
    title = shape3d_title({f"actuator number {k}": 100.0 + 7.5 * k for k in range(40)})
    svg = mesh_svg(shapes, title=title, width_px=480)
    lines = _titles(svg)
    assert len(lines) == 3 and lines[-1][1].endswith(ELLIPSIS)
    assert all(12 + text_width_px(t, s) <= 480 - 12 for s, t in lines)
    assert lines[0][1].startswith("3D shape: actuator number 0 at 100 kPa")
