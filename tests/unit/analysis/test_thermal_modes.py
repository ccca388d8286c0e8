"""The thermal modes of a linear network, checked against hand calculations."""

import math

import numpy as np
import pytest

from feedtherm.analysis.thermal_modes import mode_table, settling_time, slow_modes


def test_one_body_to_air_has_the_time_constant_c_over_ha():
    # A 2 kg steel block (c = 460 J/(kg K)): C = 920 J/K; h A = 10 W/(m^2 K) * 0.1 m^2 = 1 W/K.
    # tau = C / (h A) = 920 s.
    lam, v = slow_modes(np.array([920.0]), np.array([[1.0]]), 1)
    assert 1.0 / lam[0] == pytest.approx(920.0)
    assert v[0, 0] ** 2 * 920.0 == pytest.approx(1.0)  # C-normalised


def test_two_equal_bodies_joined_and_cooled_alike():
    # Two bodies of C = 1000 J/K, each a = 2 W/K to the air, joined by g = 5 W/K.
    # Uniform mode: lambda_1 = a / C = 2e-3 1/s (tau 500 s), v = (1, 1)/sqrt(2C): each holds half.
    # Antisymmetric mode: lambda_2 = (a + 2 g) / C = 12e-3 1/s (tau 83.3 s).
    # Start 1 K below the steady state everywhere: c_1 = v^T C e0 = -2C/sqrt(2C) = -sqrt(2C);
    # the amplitude at body 1 is v_1 c_1 = -1 K from mode 1 and 0 from mode 2.
    C = np.array([1000.0, 1000.0])
    M = np.array([[2.0 + 5.0, -5.0], [-5.0, 2.0 + 5.0]])
    modes = mode_table(C, M, np.array([-1.0, -1.0]), {"S1": np.array([1.0, 0.0])},
                       {"a": np.array([0]), "b": np.array([1])}, count=2)
    assert [m.time_constant for m in modes] == pytest.approx([500.0, 1000.0 / 12.0])
    assert modes[0].part_shares == pytest.approx({"a": 0.5, "b": 0.5})
    assert modes[0].sensor_amplitudes["S1"] == pytest.approx(-1.0)
    assert modes[1].sensor_amplitudes["S1"] == pytest.approx(0.0, abs=1e-12)


def test_all_modes_add_up_to_the_start_deviation():
    rng = np.random.default_rng(3)
    n = 6
    C = rng.uniform(100.0, 900.0, n)
    K = np.zeros((n, n))
    for i in range(n - 1):  # a chain of contacts
        g = rng.uniform(0.5, 5.0)
        K[i, i] += g
        K[i + 1, i + 1] += g
        K[i, i + 1] -= g
        K[i + 1, i] -= g
    K += np.diag(rng.uniform(0.1, 1.0, n))
    e0 = rng.normal(size=n)
    rows = {f"S{i}": np.eye(n)[i] for i in range(n)}
    modes = mode_table(C, K, e0, rows, {"all": np.arange(n)}, count=n)
    for i in range(n):
        assert sum(m.sensor_amplitudes[f"S{i}"] for m in modes) == pytest.approx(e0[i])
    assert all(m.part_shares["all"] == pytest.approx(1.0) for m in modes)


def test_settling_to_95_percent_takes_three_time_constants():
    # -ln(1 - 0.95) = ln 20 = 2.9957
    assert settling_time(600.0) == pytest.approx(600.0 * math.log(20.0))
    with pytest.raises(ValueError):
        settling_time(600.0, 1.0)
