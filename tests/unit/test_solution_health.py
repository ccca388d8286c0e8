"""A run's results are checked before they are written: each way of failing is named."""

import dataclasses

import numpy as np
import pytest

from feedtherm.errors import ModelError
from feedtherm.simulate import simulate
from feedtherm.solution import EnergyBalance
from feedtherm.solution.health import ENERGY_TOLERANCE, check_health, problems
from feedtherm.system.load import load_system


@pytest.fixture(scope="module")
def healthy():
    return simulate(load_system("paper"), condition="I", duration=1200.0)


def test_a_model_run_is_healthy(healthy):
    assert problems(healthy) == []
    check_health(healthy)


def _with_sensor(solution, name, values):
    return dataclasses.replace(solution, sensors={**solution.sensors, name: values})


def test_nan_temperatures_are_named(healthy):
    bad = _with_sensor(healthy, "T3", np.full_like(healthy.sensors["T3"], np.nan))
    with pytest.raises(ModelError, match="sensor T3: the temperatures are not finite"):
        check_health(bad)


def test_temperatures_at_or_below_absolute_zero_are_named(healthy):
    bad = _with_sensor(healthy, "T1", healthy.sensors["T1"] - 400.0)  # ~ -380 °C
    assert any(p.startswith("sensor T1: a temperature of") and "absolute zero" in p for p in problems(bad))


def test_an_energy_balance_that_does_not_close_is_named(healthy):
    # heat in 1000 J, lost 500 J, stored 499 J: residual 1 J of 1000 J = 1e-3 > 1e-4
    bad = dataclasses.replace(healthy, energy=EnergyBalance(heat_in=1000.0, heat_lost=500.0, heat_stored=499.0))
    assert ENERGY_TOLERANCE == 1e-4
    assert problems(bad) == ["energy balance: heat in, lost and stored differ by 0.001 of the heat, more than 0.0001"]
    # 0.05 J of 1000 J = 5e-5 passes
    fine = dataclasses.replace(healthy, energy=EnergyBalance(heat_in=1000.0, heat_lost=500.0, heat_stored=499.95))
    assert problems(fine) == []


def test_a_summary_that_is_not_finite_or_incomplete_is_named(healthy):
    bad = dataclasses.replace(healthy, final={**healthy.final, "T2": float("nan")})
    assert problems(bad) == ["summary: the final value of T2 is not finite"]
    partial = dict(healthy.steady)
    del partial["D"]
    assert problems(dataclasses.replace(healthy, steady=partial)) == ["summary: no steady value of D, which the series have"]


def test_the_message_is_one_line_and_counts_the_rest(healthy):
    bad = _with_sensor(_with_sensor(healthy, "T1", healthy.sensors["T1"] * np.nan), "T2", healthy.sensors["T2"] * np.nan)
    with pytest.raises(ModelError) as info:
        check_health(bad)
    message = str(info.value)
    assert "\n" not in message and "nothing written" in message and "more)" in message
