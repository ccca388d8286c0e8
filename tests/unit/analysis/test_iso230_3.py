"""ISO 230-3 drift, expansion and ETVE, checked against hand calculations.

The test of a linear axis: targets at 50, 200 and 350 mm, measured at stops 0, 600 and 1200 s,
the table reaching each target 2 s after the one before (50 mm at 0 s, 200 mm at 2 s, 350 mm at
4 s, and so on).  Deviations are written in µm and converted to m.
"""

import math

import numpy as np
import pytest

from feedtherm.analysis.iso230_3 import (Etve, ExpansionDrift, TargetDrift, etve, expansion_drift, outer_targets,
                                         target_drift)

UM = 1e-6
MM = 1e-3
STOPS = np.array([0.0, 600.0, 1200.0])


def the_three_targets() -> list[TargetDrift]:
    return [target_drift(50 * MM, STOPS + 0.0, np.array([1.0, 3.0, 2.0]) * UM),
            target_drift(200 * MM, STOPS + 2.0, np.array([-2.0, -6.0, 1.0]) * UM),
            target_drift(350 * MM, STOPS + 4.0, np.array([0.5, 6.5, 9.5]) * UM)]


def test_drift_at_each_target_by_hand():
    t50, t200, t350 = the_three_targets()
    # 50 mm: deviations 1, 3, 2 µm -> drift 0, 2, 1 µm; largest +2 µm at 600 s; range 2 - 0 = 2 µm
    assert isinstance(t50, TargetDrift)
    assert t50.target == pytest.approx(0.050)
    np.testing.assert_allclose(t50.times, [0.0, 600.0, 1200.0])
    np.testing.assert_allclose(t50.deviation, [1.0e-6, 3.0e-6, 2.0e-6])  # as given
    np.testing.assert_allclose(t50.drift, [0.0, 2.0e-6, 1.0e-6], atol=1e-15)
    assert t50.largest == pytest.approx(2.0e-6)
    assert t50.time_of_largest == 600.0
    assert t50.range == pytest.approx(2.0e-6)
    # 200 mm: deviations -2, -6, 1 µm -> drift 0, -4, +3 µm; largest -4 µm (|-4| > |3|) at 602 s;
    # range 3 - (-4) = 7 µm
    np.testing.assert_allclose(t200.drift, [0.0, -4.0e-6, 3.0e-6], atol=1e-15)
    assert t200.largest == pytest.approx(-4.0e-6)
    assert t200.time_of_largest == 602.0
    assert t200.range == pytest.approx(7.0e-6)
    # 350 mm: deviations 0.5, 6.5, 9.5 µm -> drift 0, 6, 9 µm; largest +9 µm at 1204 s; range 9 µm
    np.testing.assert_allclose(t350.drift, [0.0, 6.0e-6, 9.0e-6], atol=1e-15)
    assert t350.largest == pytest.approx(9.0e-6)
    assert t350.time_of_largest == 1204.0
    assert t350.range == pytest.approx(9.0e-6)


def test_the_range_includes_the_first_measurement():
    # deviations 5, 7, 8 µm -> drift 0, 2, 3 µm: the range is 3 - 0 = 3 µm (not 3 - 2 = 1 µm)
    d = target_drift(0.1, [0.0, 1.0, 2.0], np.array([5.0, 7.0, 8.0]) * UM)
    assert d.range == pytest.approx(3.0e-6)
    # all drifts negative: -1, -4 µm -> range 0 - (-4) = 4 µm, largest -4 µm
    d = target_drift(0.1, [0.0, 1.0, 2.0], np.array([5.0, 4.0, 1.0]) * UM)
    assert (d.range, d.largest) == (pytest.approx(4.0e-6), pytest.approx(-4.0e-6))


def test_one_sample_has_no_drift():
    d = target_drift(0.2, [30.0], [4.0e-6])
    np.testing.assert_array_equal(d.drift, [0.0])
    assert (d.largest, d.time_of_largest, d.range) == (0.0, 30.0, 0.0)


def test_expansion_between_the_outer_targets_by_hand():
    t50, _, t350 = the_three_targets()
    e = expansion_drift(t50, t350)
    assert isinstance(e, ExpansionDrift)
    assert (e.first_target, e.last_target) == (pytest.approx(0.050), pytest.approx(0.350))
    # 350 mm is measured at 4, 604 and 1204 s; 50 mm spans 0-1200 s, held for half its shortest
    # interval (300 s) beyond: 1204 s, the last stop's, is in.
    np.testing.assert_allclose(e.times, [4.0, 604.0, 1204.0])
    # 50 mm's drift interpolated in time (0 s: 0, 600 s: 2 µm, 1200 s: 1 µm), held after 1200 s:
    #   at    4 s: 0 + (2 - 0) * 4 / 600           = 1/75  µm = 0.013333 µm
    #   at  604 s: 2 + (1 - 2) * 4 / 600 = 2 - 1/150   µm = 1.993333 µm
    #   at 1204 s: 1 µm (held)
    # expansion drift = drift(350 mm) - drift(50 mm):
    #   at    4 s: 0 - 1/75          = -0.013333 µm
    #   at  604 s: 6 - (2 - 1/150)   = 4 + 1/150 = 4.006667 µm
    #   at 1204 s: 9 - 1             = 8 µm
    np.testing.assert_allclose(e.drift, np.array([-1.0 / 75.0, 4.0 + 1.0 / 150.0, 8.0]) * UM, rtol=1e-12)
    assert e.largest == pytest.approx(8.0 * UM)
    assert e.time_of_largest == 1204.0
    # per length: 8 µm / (350 - 50) mm = 8e-6 / 0.3 = 26.667e-6 m/m
    assert e.per_length == pytest.approx(8.0 * UM / 0.3)
    assert e.per_length == pytest.approx(26.6667e-6, rel=1e-5)
    # without the reach, the last stop is left out
    e = expansion_drift(t50, t350, reach=0.0)
    np.testing.assert_allclose(e.times, [4.0, 604.0])
    assert e.largest == pytest.approx((4.0 + 1.0 / 150.0) * UM)


def test_expansion_when_the_last_target_is_measured_first():
    # the table runs backwards: 350 mm at 0, 600, 1200 s; 50 mm at 4, 604, 1204 s.  The first
    # (50 mm) target spans 4-1204 s, held 300 s before: 0 s takes its first drift, 0.
    first = target_drift(0.050, STOPS + 4.0, np.array([0.0, 3.0, 6.0]) * UM)  # drift 0, 3, 6 µm
    last = target_drift(0.350, STOPS, np.array([1.0, 9.0, 11.0]) * UM)  # drift 0, 8, 10 µm
    e = expansion_drift(first, last)
    np.testing.assert_allclose(e.times, [0.0, 600.0, 1200.0])
    # first's drift at 0 s: 0 (held); at 600 s: 0 + 3 * (600 - 4) / 600 = 2.98 µm; at 1200 s:
    # 3 + 3 * 596 / 600 = 5.98 µm.  Expansion: 0 - 0 = 0; 8 - 2.98 = 5.02 µm; 10 - 5.98 = 4.02 µm
    # -> largest 5.02 µm at 600 s
    np.testing.assert_allclose(e.drift, np.array([0.0, 5.02, 4.02]) * UM, rtol=1e-12, atol=1e-18)
    assert e.largest == pytest.approx(5.02e-6)
    assert e.time_of_largest == 600.0
    assert e.per_length == pytest.approx(5.02e-6 / 0.3)


def test_outer_targets_takes_the_smallest_and_largest_in_any_order():
    t50, t200, t350 = the_three_targets()
    e = outer_targets([t200, t350, t50])
    assert (e.first_target, e.last_target) == (t50.target, t350.target)
    np.testing.assert_allclose(e.drift, expansion_drift(t50, t350).drift)
    assert outer_targets([t200]) is None
    assert outer_targets([]) is None


def test_etve_by_hand():
    # D over a 4 h idle test: 0, 2, 5, 3, -1 µm at 0, 1, 2, 3, 4 h
    times = [0.0, 3600.0, 7200.0, 10800.0, 14400.0]
    d = np.array([0.0, 2.0, 5.0, 3.0, -1.0]) * UM
    # air at -600 s and 15000 s lies outside the test's 0-14400 s and is left out (290 K, 299 K)
    air_times = [-600.0, 0.0, 3600.0, 7200.0, 10800.0, 14400.0, 15000.0]
    air = [290.0, 293.15, 293.65, 294.65, 294.15, 293.40, 299.0]
    e = etve("D", times, d, air_times, air)
    assert isinstance(e, Etve)
    assert e.quantity == "D"
    # range: max 5 µm at 7200 s, min -1 µm at 14400 s -> 6 µm
    assert e.range == pytest.approx(6.0e-6)
    assert (e.time_of_max, e.time_of_min) == (7200.0, 14400.0)
    # air within 0-14400 s: max 294.65 K, min 293.15 K -> 1.5 K
    assert e.air_range == pytest.approx(1.5)
    # sensitivity: 6 µm / 1.5 K = 4 µm/K
    assert e.sensitivity == pytest.approx(4.0e-6)


def test_etve_with_constant_air_has_no_sensitivity():
    e = etve("E@150mm", [0.0, 10.0, 20.0], [1.0e-6, -2.0e-6, 0.5e-6], [0.0, 20.0], [293.15, 293.15])
    assert e.range == pytest.approx(3.0e-6)  # 1 - (-2) µm
    assert (e.time_of_max, e.time_of_min) == (0.0, 10.0)
    assert e.air_range == 0.0
    assert math.isnan(e.sensitivity)


@pytest.mark.parametrize("times, deviation, message", [
    ([], [], "no samples"),
    ([0.0, 1.0], [0.0], "2 times but 1 values"),
    ([0.0, 1.0], [0.0, float("nan")], "finite"),
    ([0.0, float("inf")], [0.0, 1.0e-6], "finite"),
    ([0.0, 1.0, 1.0], [0.0, 1.0e-6, 2.0e-6], "strictly increasing"),
    ([0.0, 2.0, 1.0], [0.0, 1.0e-6, 2.0e-6], "strictly increasing"),
])
def test_target_drift_rejects_bad_series(times, deviation, message):
    with pytest.raises(ValueError, match=message):
        target_drift(0.05, times, deviation)


def test_target_drift_rejects_a_non_finite_target():
    with pytest.raises(ValueError, match="finite"):
        target_drift(float("nan"), [0.0], [0.0])


def test_expansion_rejects_targets_not_distinct_or_ordered():
    t50, _, t350 = the_three_targets()
    with pytest.raises(ValueError, match="distinct targets in order"):
        expansion_drift(t350, t50)
    with pytest.raises(ValueError, match="distinct targets in order"):
        expansion_drift(t50, t50)
    with pytest.raises(ValueError, match="distinct targets in order"):  # two drifts of one target
        outer_targets([t50, target_drift(0.050, [0.0], [0.0])])


def test_expansion_rejects_when_no_time_is_left():
    first = target_drift(0.05, [0.0, 600.0], [0.0, 1.0e-6])
    last = target_drift(0.35, [1000.0, 1300.0], [0.0, 2.0e-6])  # after the first's span and its reach
    with pytest.raises(ValueError, match="lies within -300–900 s"):
        expansion_drift(first, last)


@pytest.mark.parametrize("times, d, air_times, air, message", [
    ([], [], [0.0], [293.0], "no samples"),
    ([0.0, 1.0], [0.0], [0.0], [293.0], "2 times but 1 values"),
    ([0.0, 1.0], [0.0, float("nan")], [0.0], [293.0], "finite"),
    ([1.0, 0.0], [0.0, 0.0], [0.0], [293.0], "strictly increasing"),
    ([0.0, 1.0], [0.0, 0.0], [0.0, 1.0], [293.0], "air: 2 times but 1 values"),
    ([0.0, 1.0], [0.0, 0.0], [0.0, 1.0], [293.0, float("inf")], "air: the times and values must be finite"),
    ([0.0, 1.0], [0.0, 0.0], [1.0, 0.0], [293.0, 293.0], "air: the times must be strictly increasing"),
    ([0.0, 1.0], [0.0, 0.0], [2.0, 3.0], [293.0, 293.0], "no air temperature lies within"),
])
def test_etve_rejects_bad_series(times, d, air_times, air, message):
    with pytest.raises(ValueError, match=message):
        etve("D", times, d, air_times, air)
