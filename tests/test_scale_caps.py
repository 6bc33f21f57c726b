"""Outputs bounded whatever the number of actuators: the side view, the summary line."""
import xml.etree.ElementTree as ET

import pytest

from embroact.export.pictures.previews import SIDE_VIEW_MAX_PANELS, _side_view
from embroact.export.pictures.sideview import SidePanel

_SVG = "{http://www.w3.org/2000/svg}"


def _panels(n):
    return [SidePanel(f"A{k}", length_mm=20.0, r0_mm=2.3, pressure_kpa=[0.0, 100.0], theta_deg=[0.0, 40.0])
            for k in range(n)]


def _drawn(svg):
    root = ET.fromstring(svg)
    labels = [t.text for g in root.iter(f"{_SVG}g") if g.get("class") == "panel" for t in g.iter(f"{_SVG}text")
              if t.get("font-weight") == "bold"]
    title = next(t.text for t in root.iter(f"{_SVG}text"))
    return labels, title


@pytest.mark.parametrize("n", [1, SIDE_VIEW_MAX_PANELS])
def test_side_view_draws_every_panel_up_to_the_cap(n):
    labels, title = _drawn(_side_view(_panels(n)))
    assert labels == [f"A{k}" for k in range(n)] and "of" not in title


def test_side_view_past_the_cap_draws_the_first_and_says_so():
    labels, title = _drawn(_side_view(_panels(SIDE_VIEW_MAX_PANELS + 7)))
    assert labels == [f"A{k}" for k in range(SIDE_VIEW_MAX_PANELS)]
    assert title.endswith(f"the first {SIDE_VIEW_MAX_PANELS} of {SIDE_VIEW_MAX_PANELS + 7} actuators")


def test_summary_line_names_five_actuators_per_code_and_counts_the_rest():
    import embroact.predict.rules  # noqa: F401  (declares the model rules)
    from embroact.export.cli.target import SUMMARY_NAMES, summary_line
    from embroact.patterns.base.findings import RULES

    fs = [RULES.finding("EA403", "x", actuator=f"A{k}") for k in range(1000)] + [
        RULES.finding("EA405", "y", actuator="B"), RULES.finding("EA405", "y", actuator="B")]
    line = summary_line(fs)
    assert SUMMARY_NAMES == 5 and "\n" not in line and len(line) < 200
    assert line.endswith("EA403 (A0, A1, A2, A3, A4 and 995 more), EA405 (B)")
