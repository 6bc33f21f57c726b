"""Shared command-line pieces: tube flag defaults agree with Tube, pressure lists by hand."""
import argparse

import pytest

from embroact.export.cli.args import TUBE_FLAGS, add_tube_arguments, parse_pressures, tube_from_args
from embroact.patterns.base.errors import ParameterError
from embroact.patterns.params import Tube


@pytest.mark.parametrize("flag, field, text, default", TUBE_FLAGS)
def test_flag_defaults_are_tube_defaults(flag, field, text, default):
    assert getattr(Tube(), field) == default


def test_tube_from_args_round_trip():
    p = argparse.ArgumentParser()
    add_tube_arguments(p, fields=[f[1] for f in TUBE_FLAGS])
    tube = tube_from_args(p.parse_args(["--tube-radius-mm", "2", "--clearance-mm", "0.5"]))
    assert tube == Tube(outer_radius_mm=2.0, clearance_mm=0.5)


def test_bad_tube_value_names_the_field():
    p = argparse.ArgumentParser()
    add_tube_arguments(p)
    with pytest.raises(ParameterError, match=r"inner_radius_mm must be in \[0, outer_radius_mm=1.5\), got 2"):
        tube_from_args(p.parse_args(["--tube-inner-radius-mm", "2"]))


@pytest.mark.parametrize("text, expected", [
    ("0:300:100", [0.0, 100.0, 200.0, 300.0]),
    ("0:290:100", [0.0, 100.0, 200.0]),
    ("120", [120.0]),
    ("10, 20 ,35", [10.0, 20.0, 35.0]),
])
def test_parse_pressures_by_hand(text, expected):
    assert parse_pressures(text).tolist() == pytest.approx(expected)


def test_a_tube_error_names_the_flags_and_the_default_left(capsys):
    """--tube-radius-mm 1.0 with the inner radius left at its default 1.0: the error says the inner radius it names is
    --tube-inner-radius-mm's default (it said only 'inner_radius_mm must be in [0, outer_radius_mm=1)', a value the
    user never typed)."""
    from embroact.export.cli.main import main

    assert main(["zigzag", "--width-mm", "7", "--tube-radius-mm", "1.0", "-o", "never.dst"]) == 2
    assert capsys.readouterr().err == ("embroact: error: inner_radius_mm must be in [0, outer_radius_mm=1), got 1 "
                                       "(--tube-inner-radius-mm 1: its default)\n")
