"""The coupled steady iteration's pieces, by hand: the signed step ratio and the range guard."""

from __future__ import annotations

import math

import numpy as np
import pytest

from feedtherm.boundary import LocalTemperatures
from feedtherm.errors import ModelError
from feedtherm.models.integrator import _step_ratio, _within_accepted_temperatures


def test_an_oscillation_has_a_negative_ratio_and_a_one_way_contraction_a_positive_one():
    last = np.array([1.0, 2.0])
    # (-0.5*1 - 1*2) / (1 + 4) = -2.5/5
    assert _step_ratio(np.array([-0.5, -1.0]), last) == pytest.approx(-0.5)
    # (0.8*1 + 1.6*2) / 5 = 4/5
    assert _step_ratio(np.array([0.8, 1.6]), last) == pytest.approx(0.8)


def test_the_first_step_and_a_zero_step_have_no_ratio():
    assert math.isinf(_step_ratio(np.ones(2), None))
    assert math.isinf(_step_ratio(np.ones(2), np.zeros(2)))


def test_a_reading_outside_the_accepted_temperatures_names_the_source_and_the_range():
    _within_accepted_temperatures(LocalTemperatures({"slider": 293.15}, {"screw_nut": 1273.0}))  # 999.85 degC
    with pytest.raises(ModelError, match=r"^temperatures.coupling = nonlinear: screw_nut reaches 1010 degC, "
                                         r"outside -150 to 1000 degC .*thermal runaway"):
        _within_accepted_temperatures(LocalTemperatures({"slider": 293.15}, {"screw_nut": 1283.15}))
    with pytest.raises(ModelError, match="slider reaches -160 degC"):
        _within_accepted_temperatures(LocalTemperatures({"slider": 113.15}, {}))
    with pytest.raises(ModelError, match="slider reaches nan degC"):
        _within_accepted_temperatures(LocalTemperatures({"slider": math.nan}, {}))
