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


def test_each_quantity_has_its_own_equilibrium_time_and_D_its_own_bounds():
    from feedtherm.solution.equilibrium import equilibrium_times

    # T1 = 10 K (1 - e^{-t/1800}) reaches 95 % at 1800 ln 20 = 5392 s (the first test's case);
    # T2 = 4 K (1 - e^{-t/600}) at 600 ln 20 = 1797 s, its 600 s window then spans
    # 4 (e^{-1197/600} - e^{-1797/600}) = 0.35 K < 0.5 K.
    # D = 50 µm (1 - e^{-t/900}): 95 % at 900 ln 20 = 2696 s; its window then spans
    # 50 (e^{-2096/900} - e^{-2696/900}) = 2.4 µm > 1 µm, quiet only from t with
    # 50 e^{-t/900} (e^{600/900} - 1) < 1: t > 900 ln(50 * 0.9477) = 3477 s.
    t = np.arange(0.0, 20000.0, 10.0)
    sensors = {"T1": 10.0 * (1 - np.exp(-t / 1800.0)), "T2": 4.0 * (1 - np.exp(-t / 600.0))}
    d = 50e-6 * (1 - np.exp(-t / 900.0))
    initial = {"T1": 0.0, "T2": 0.0, "D": 0.0}
    steady = {"T1": 10.0, "T2": 4.0, "D": 50e-6}
    each = equilibrium_times(t, sensors, d, initial, steady, "D")
    assert 5390.0 <= each["T1"] <= 5400.0
    assert 1790.0 <= each["T2"] <= 1810.0
    assert 3470.0 <= each["D"] <= 3490.0  # the 1 µm bound, not the 95 % rise, decides D
    # Held to the temperatures' bounds, D in metres (a rise below 0.1, swings below 0.5) would
    # count as settled from the first instant the 600 s window allows:
    assert equilibrium_time(t, {"D": d}, initial, steady) == 600.0


def test_a_quantity_that_never_settles_has_none():
    from feedtherm.solution.equilibrium import equilibrium_times

    t = np.arange(0.0, 3600.0, 10.0)
    each = equilibrium_times(t, {"T1": t / 3600.0}, 20e-6 * t / 3600.0, {"T1": 0.0, "D": 0.0},
                             {"T1": 10.0, "D": 50e-6}, "D")
    assert each == {"T1": None, "D": None}


@pytest.mark.parametrize("spacing", ["uniform", "uneven"])
def test_the_trailing_range_is_each_windows_max_less_its_min(spacing):
    """Against the windows taken one by one: [t - WINDOW_S, t] at every sample, both ends included."""
    from feedtherm.solution.equilibrium import WINDOW_S, _trailing_range

    rng = np.random.default_rng(3)
    for n in (1, 2, 7, 64, 500):
        step = WINDOW_S / 13
        times = (np.arange(n) * step if spacing == "uniform" else np.cumsum(rng.uniform(0.0, 2.5 * step, n)))
        values = rng.normal(size=n).cumsum()
        expected = [np.ptp(values[(times >= t - WINDOW_S) & (times <= t)]) for t in times]
        assert np.array_equal(_trailing_range(times, values), expected)
