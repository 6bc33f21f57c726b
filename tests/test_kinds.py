"""The two pattern-kind tables (geometry in patterns, model in predict) describe the same kinds."""
import math

import pytest

from embroact.patterns.base.errors import ParameterError
from embroact.patterns.kinds import PATTERN_KINDS, pattern_kind
from embroact.predict.kinds import MODEL_KINDS, Constraint, model_kind


def test_every_registered_kind_has_one_model_row():
    assert tuple(MODEL_KINDS) == PATTERN_KINDS.names()


@pytest.mark.parametrize("name", PATTERN_KINDS.names())
def test_thread_angle_exactly_when_the_pattern_has_an_angle(name):
    # the fixed-radius constraint has beta0 = 0; a pantograph's threads cross at the sewing angle
    assert model_kind(name).has_thread_angle == pattern_kind(name).has_angle
    assert model_kind(name).has_thread_angle == (model_kind(name).constraint is Constraint.PANTOGRAPH)


def test_beta0_against_the_hand_formula():
    # sin(beta0) = (w/2) tan(alpha0) / sqrt((2 r_f)^2 + (w/2)^2 (1 + tan^2 alpha0)); w 7, alpha0 45, r_f 1.5:
    # 3.5 / sqrt(9 + 24.5) = 3.5 / sqrt(33.5)
    assert model_kind("cross").beta0_deg(7.0, 45.0, 1.5) == pytest.approx(math.degrees(math.asin(3.5 / math.sqrt(33.5))),
                                                                            rel=1e-12)
    assert model_kind("zigzag").beta0_deg(7.0, 45.0, 1.5) == 0.0


def test_initial_direction_turns_at_tan_beta0_one_half():
    edge = math.degrees(math.atan(0.5))  # 26.565 deg
    cross = model_kind("cross")
    assert cross.bends_positive(edge - 1e-6) and not cross.bends_positive(edge + 1e-6)
    assert model_kind("zigzag").bends_positive(0.0)


def test_unknown_kind_is_one_line_naming_the_valid_ones():
    with pytest.raises(ParameterError, match="pattern must be one of 'zigzag', 'cross'(, '[a-z]+')*, got 'satin'"):
        model_kind("satin")
