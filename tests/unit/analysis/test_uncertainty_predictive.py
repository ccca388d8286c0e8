"""Posterior predictive quantiles: the normal mixture (1/n) Σ N(y_i, sd²), by hand and by property."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from feedtherm.analysis.uncertainty.predictive import QUANTILE_TOLERANCE, predictive_quantiles


def mixture_cdf(x: float, values, sd: float) -> float:
    """(1/n) Σ Φ((x − y_i)/sd), Φ(t) = (1 + erf(t/√2))/2: written out apart from the module."""
    return sum(0.5 * (1.0 + math.erf((x - y) / (sd * math.sqrt(2.0)))) for y in values) / len(values)


def test_one_value_gives_the_normal_quantiles():
    # N(10, 2²): the 5 % and 95 % quantiles are 10 ∓ 2 × 1.6448536 (Φ⁻¹(0.95) = 1.6448536, a
    # standard normal table), the median 10.
    q = predictive_quantiles([10.0], 2.0, [0.05, 0.5, 0.95])
    assert q == pytest.approx([10.0 - 3.2897073, 10.0, 10.0 + 3.2897073], abs=1e-5)


def test_two_far_values_put_the_five_percent_quantile_below_the_lower_one():
    # y = 0 and 100, sd 1: below 50 the mixture's CDF is Φ(x)/2, so the 5 % quantile solves
    # Φ(x) = 0.1: x = −1.2815516 (table); by symmetry the 95 % one is 100 + 1.2815516.
    q = predictive_quantiles([0.0, 100.0], 1.0, [0.05, 0.95])
    assert q == pytest.approx([-1.2815516, 101.2815516], abs=1e-5)


def test_no_model_error_gives_the_samples_quantiles():
    y = [3.0, 1.0, 4.0, 1.5, 9.0]
    assert np.array_equal(predictive_quantiles(y, 0.0, [0.05, 0.5, 0.95]), np.quantile(y, [0.05, 0.5, 0.95]))


@settings(max_examples=60, deadline=None)
@given(values=st.lists(st.floats(-200.0, 200.0), min_size=1, max_size=40),
       sd=st.floats(0.01, 50.0), p=st.floats(0.01, 0.99))
def test_each_quantile_solves_the_mixture_cdf(values, sd, p):
    (q,) = predictive_quantiles(values, sd, [p])
    # F(q) = p to the root's tolerance: F changes by at most φ(0)/sd per unit of q
    assert mixture_cdf(q, values, sd) == pytest.approx(p, abs=QUANTILE_TOLERANCE / (sd * math.sqrt(2 * math.pi)) + 1e-9)


def test_a_symmetric_sample_has_its_centre_as_median():
    q = predictive_quantiles([-3.0, -1.0, 1.0, 3.0], 0.7, [0.5])
    assert q[0] == pytest.approx(0.0, abs=1e-6)


@pytest.mark.parametrize("values, sd, p, fragment", [
    ([], 1.0, [0.5], "no sampled values"),
    ([1.0], -1.0, [0.5], "error_sd"),
    ([1.0], float("nan"), [0.5], "error_sd"),
    ([1.0], 1.0, [0.0], "probabilities"),
    ([1.0], 1.0, [1.0], "probabilities"),
])
def test_bad_arguments_are_refused(values, sd, p, fragment):
    with pytest.raises(ValueError, match=fragment):
        predictive_quantiles(values, sd, p)
