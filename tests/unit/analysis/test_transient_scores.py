"""Scores of a measured series against its run, checked by hand on straight-line runs."""

import math

import numpy as np
import pytest

from feedtherm.system.measurement_series import Series
from feedtherm.system.measurements import Measurement
from feedtherm.analysis.transient_scores import TransientComparison, compare_series
from feedtherm.errors import FeedthermError
from feedtherm.solution import EnergyBalance, Solution


def line_run(end_s=1000.0) -> Solution:
    """Sensor A rises 1 K per 100 s from 20 °C; D grows 1 µm per 100 s from 0; samples every 100 s."""
    times = np.arange(0.0, end_s + 1.0, 100.0)
    a = 293.15 + times / 100.0  # K
    d = times / 100.0 * 1e-6  # m
    empty = np.zeros((len(times), 0))
    return Solution(times=times, sensors={"A": a}, elongation=d, screw_x=np.zeros(0), screw_temperature=empty,
                    screw_displacement=empty, table_x=np.zeros(0), positioning_error=empty, nut_offset=0 * times,
                    part_temperatures={}, cycle_times=times, cycle_sensors={"A": a}, cycle_elongation=d,
                    final={"A": a[-1], "D": d[-1]}, steady={"A": a[-1], "D": d[-1]}, equilibrium_time=None,
                    energy=EnergyBalance(0.0, 0.0, 0.0))


def measured(quantity, unit, times, values, uncertainties=None) -> Measurement:
    series = Series(np.array(times, float), np.array(values, float),
                    None if uncertainties is None else np.array(uncertainties, float))
    return Measurement("c", quantity, unit, values[-1], None, series)


def test_scores_by_hand():
    # the run reads 20.5, 22.5, 30 °C at 50, 250, 1000 s (between its samples: interpolated)
    rows = [measured("A", "C", [50, 250, 1000], [20.5 - 3.0, 22.5 + 4.0, 30.0], [0.1, 0.1, 0.2])]
    (c,) = compare_series("c", line_run(), rows)
    np.testing.assert_allclose(c.simulated, [20.5, 22.5, 30.0])
    np.testing.assert_allclose(c.deviation, [3.0, -4.0, 0.0])
    assert c.rms == pytest.approx(math.sqrt((9.0 + 16.0 + 0.0) / 3.0))
    assert c.max_abs == pytest.approx(4.0)
    assert c.time_of_max == 250.0
    assert c.mean == pytest.approx(-1.0 / 3.0)
    np.testing.assert_allclose(c.uncertainty, [0.1, 0.1, 0.2])
    assert c.inside_two_sigma == pytest.approx(1.0 / 3.0)  # only |0| <= 0.4; 3 > 0.2, 4 > 0.2


def test_inside_two_sigma_counts_the_boundary():
    c = TransientComparison("c", "A", "C", np.arange(4.0), np.zeros(4), np.array([0.2, -0.2, 0.21, 0.0]),
                            np.full(4, 0.1))
    assert c.inside_two_sigma == 0.75


def test_elongation_in_micrometres_and_finals_skipped():
    rows = [measured("D_um", "um", [0, 500], [1.0, 5.0]),
            Measurement("c", "A", "C", 30.0)]  # a final value only: nothing to score over time
    (c,) = compare_series("c", line_run(), rows)
    assert (c.quantity, c.unit) == ("D_um", "um")
    np.testing.assert_allclose(c.simulated, [0.0, 5.0], atol=1e-9)
    assert c.rms == pytest.approx(math.sqrt(0.5))
    assert c.max_abs == pytest.approx(1.0)
    assert c.time_of_max == 0.0
    assert c.inside_two_sigma is None  # no uncertainties given


def test_a_series_beyond_the_run_is_an_error():
    with pytest.raises(FeedthermError, match="the run only 0–1000 s"):
        compare_series("c", line_run(), [measured("A", "C", [0, 1200], [20.0, 32.0])])


def test_a_sensor_the_run_lacks_is_an_error():
    with pytest.raises(FeedthermError, match="no sensor 'B'"):
        compare_series("c", line_run(), [measured("B", "C", [0], [20.0])])


def test_one_sample():
    c = TransientComparison("c", "A", "C", np.array([10.0]), np.array([21.0]), np.array([20.0]))
    assert (c.rms, c.max_abs, c.mean, c.time_of_max) == (1.0, 1.0, -1.0, 10.0)
