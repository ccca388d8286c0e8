import numpy as np
import pytest

from feedtherm.solution.equilibrium import equilibrium_time


def test_first_order_rise_reaches_equilibrium_after_95_percent_and_a_quiet_window():
    # T = 10 K * (1 - exp(-t / 1800 s)): 95 % of the rise at t = 1800 ln 20 = 5392 s.
    t = np.arange(0.0, 20000.0, 10.0)
    T = 10.0 * (1 - np.exp(-t / 1800.0))
    teq = equilibrium_time(t, {"T1": T}, {"T1": 0.0}, {"T1": 10.0})
    # by 5392 s the 600 s window varies by 10 (e^{-4792/1800} - e^{-5392/1800}) = 0.20 K < 0.5 K
    assert 5390.0 <= teq <= 5400.0


def test_fluctuation_criterion_delays_equilibrium():
    t = np.arange(0.0, 20000.0, 10.0)
    T = 10.0 + 0.6 * np.sin(2 * np.pi * t / 400.0) * (t < 10000)  # 1.2 K swings until 10,000 s
    teq = equilibrium_time(t, {"T1": T}, {"T1": 0.0}, {"T1": 10.0})
    assert 10000.0 <= teq <= 10600.0


def test_no_equilibrium_within_the_run():
    t = np.arange(0.0, 3600.0, 10.0)
    assert equilibrium_time(t, {"T1": t / 3600.0}, {"T1": 0.0}, {"T1": 10.0}) is None


def test_rise_time_examples_hold():
    """The doctest examples of rise_time: an exponential rise with τ = 1000 s reaches 95 % at
    τ ln 20 = 2995.7 s, whether the run covers it (interpolated) or ends at 1000 s (extrapolated)."""
    import doctest

    from feedtherm.solution import equilibrium

    finder = doctest.DocTestFinder()
    (test,) = [t for t in finder.find(equilibrium) if t.name.endswith("rise_time")]
    assert doctest.DocTestRunner().run(test).failed == 0


def test_rise_time_is_the_slowest_sensor_and_ignores_flat_ones():
    import numpy as np

    from feedtherm.solution.equilibrium import rise_time

    t = np.arange(0.0, 20001.0, 50.0)
    series = {"fast": 1 - np.exp(-t / 500), "slow": 2 * (1 - np.exp(-t / 2000)), "flat": 0.01 * t / t[-1]}
    initial = {"fast": 0.0, "slow": 0.0, "flat": 0.0}
    steady = {"fast": 1.0, "slow": 2.0, "flat": 0.01}
    assert rise_time(t, series, initial, steady) == pytest.approx(2000 * np.log(20), abs=2.0)
