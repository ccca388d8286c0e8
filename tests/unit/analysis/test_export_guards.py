"""The exported law's guards and a stroke law's offset-and-slope bound (issue 58), by hand."""

import pytest

from feedtherm.analysis.compensation.guards import DEFAULT_MARGIN_K, resolve_guards
from feedtherm.analysis.compensation.offset_slope import reduction_bound
from feedtherm.errors import FeedthermError


def _stroke(bias, weights):
    return {"inputs": [{"name": "T1"}], "bias_m": bias, "weights_m_per_K": weights}


def test_the_bound_is_the_largest_magnitude_of_the_terms_beyond_the_line():
    """b2 = -3 µm, w2 = 0.01 µm/K, T1 in 290…300 K: |c2| is largest at a corner of the range,
    max(|-3 + 0.01·290|, |-3 + 0.01·300|) µm = max(0.1, 0) µm = 0.1 µm, which the centred form gives as
    |-3e-6 + 1e-8·295| + 1e-8·5 = 5e-8 + 5e-8 = 1e-7 m."""
    document = _stroke([1e-6, 2e-6, -3e-6], [[[1e-7, 1e-7, 1e-8]]])
    assert reduction_bound(document, {"T1": (290.0, 300.0)}) == pytest.approx(1e-7, rel=1e-12)


def test_a_lag_counts_as_a_feature_within_the_same_range():
    """One lag with w2 = -0.02 µm/K beside the reading's +0.01 µm/K: |c2| ≤ |b2 + (0.01 - 0.02)·295e-6| +
    (0.01 + 0.02)·5 µm = |1 - 2.95| + 0.15 = 2.1 µm, with b2 = 1 µm."""
    document = _stroke([0.0, 0.0, 1e-6], [[[0.0, 0.0, 1e-8], [0.0, 0.0, -2e-8]]])
    assert reduction_bound(document, {"T1": (290.0, 300.0)}) == pytest.approx(2.1e-6, rel=1e-12)


def test_a_line_is_its_own_offset_and_slope():
    assert reduction_bound(_stroke([1e-6, 2e-6], [[[1e-7, 1e-7]]]), {"T1": (290.0, 300.0)}) == 0.0


def test_the_default_valid_range_is_the_envelope_widened_by_the_margin():
    document = {"inputs": [{"name": "T1"}, {"name": "T2"}],
                "envelope": {"inputs": {"T1": {"min_K": 293.0, "max_K": 301.0}, "T2": {"min_K": 290.0, "max_K": 295.0}}}}
    guards = resolve_guards(document)
    assert guards.valid_K == ((293.0 - DEFAULT_MARGIN_K, 301.0 + DEFAULT_MARGIN_K),
                              (290.0 - DEFAULT_MARGIN_K, 295.0 + DEFAULT_MARGIN_K))
    assert guards.max_rate == 1e-6 and guards.start == "first-sample" and guards.reference_K is None
    assert resolve_guards(document, (280.0, 320.0)).valid_K == ((280.0, 320.0), (280.0, 320.0))


@pytest.mark.parametrize("kwargs, field", [({"max_rate": 0.0}, "--max-rate"), ({"margin_K": -1.0}, "--margin"),
                                           ({"margin_K": 283.15}, "--margin"),
                                           ({"start": "warm"}, "--start"), ({"start": "reference"}, "--start"),
                                           ({"valid_range_K": (300.0, 290.0)}, "--valid-range")])
def test_each_bad_option_is_named(kwargs, field):
    document = {"inputs": [{"name": "T1"}], "envelope": {"inputs": {"T1": {"min_K": 293.0, "max_K": 301.0}}}}
    with pytest.raises(FeedthermError, match=f"^{field}"):
        resolve_guards(document, **kwargs)


def test_without_an_envelope_the_range_must_be_declared():
    with pytest.raises(FeedthermError, match="^--valid-range: the law carries no training envelope"):
        resolve_guards({"inputs": [{"name": "T1"}]})
