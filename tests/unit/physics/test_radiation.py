"""Tests of feedtherm.physics.radiation (hand calculations, Incropera Example 1.2)."""

import math

import numpy as np
import pytest

from feedtherm.physics.radiation import SIGMA, h_radiation, heat_flux_radiation


def test_sigma_follows_from_the_defined_si_constants():
    # σ = 2π⁵ k⁴ / (15 h³ c²) with the exact k = 1.380649e-23 J/K, h = 6.62607015e-34 J·s,
    # c = 299792458 m/s (SI 2019); scipy.constants holds the same CODATA value
    from scipy.constants import Stefan_Boltzmann

    k, h, c = 1.380649e-23, 6.62607015e-34, 299792458.0
    assert SIGMA == pytest.approx(2.0 * math.pi ** 5 * k ** 4 / (15.0 * h ** 3 * c ** 2), rel=1e-9)
    assert SIGMA == pytest.approx(Stefan_Boltzmann, rel=1e-12)


def test_incropera_example_1_2_steam_pipe():
    # Incropera 6th ed., Example 1.2: pipe D = 70 mm, Ts = 200 C = 473 K,
    # Tsur = 25 C = 298 K, eps = 0.8; radiation loss printed as q' = 421 W/m.
    # Hand: 473^4 = 5.00547e10, 298^4 = 7.88615e9, difference 4.21685e10;
    # q'' = 0.8 * 5.670374e-8 * 4.21685e10 = 1912.9 W/m^2; q' = q'' * pi * 0.07 = 420.7 W/m.
    q_per_m = heat_flux_radiation(0.8, 473.0, 298.0) * math.pi * 0.07
    assert q_per_m == pytest.approx(421.0, abs=0.5)


def test_audit_h_r_at_20_to_30_C():
    # docs/paper-audit.md §1 "missing": h_r ≈ 1.8 (eps 0.3) and 4.9 (eps 0.8) near 20-30 C.
    # Hand, Ts = 30 C, Ta = 20 C: Ts^2 + Ta^2 = 91899.92 + 85936.92 = 177836.84 K^2,
    # Ts + Ta = 596.3 K, sigma * product = 5.670374e-8 * 1.060441e8 = 6.01310 W/m^2K;
    # eps 0.3 -> 1.8039, eps 0.8 -> 4.8105.
    assert h_radiation(0.3, 303.15, 293.15) == pytest.approx(1.8039, rel=1e-4)
    assert h_radiation(0.8, 303.15, 293.15) == pytest.approx(4.8105, rel=1e-4)
    # Both at 300 K (27 C): 4 sigma T^3 = 4 * 5.670374e-8 * 2.7e7 = 6.12400;
    # eps 0.8 -> 4.8992 (the docs/paper-audit.md's 4.9), eps 0.3 -> 1.8372.
    assert h_radiation(0.8, 300.0, 300.0) == pytest.approx(4.8992, rel=1e-4)
    assert h_radiation(0.3, 300.0, 300.0) == pytest.approx(1.8372, rel=1e-4)


def test_linearisation_is_exact():
    Ts, Ta, eps = 320.0, 291.0, 0.6
    q = heat_flux_radiation(eps, Ts, Ta)
    assert h_radiation(eps, Ts, Ta) * (Ts - Ta) == pytest.approx(q, rel=1e-12)


def test_colder_surface_gains_heat_and_equal_temperatures_give_zero_flux():
    assert heat_flux_radiation(0.5, 290.0, 300.0) < 0.0
    assert heat_flux_radiation(0.5, 300.0, 300.0) == 0.0
    # h_r is symmetric in Ts and Ta
    assert h_radiation(0.5, 290.0, 300.0) == pytest.approx(h_radiation(0.5, 300.0, 290.0))


def test_arrays_broadcast():
    h = h_radiation(np.array([0.3, 0.8]), 300.0, 300.0)
    np.testing.assert_allclose(h, [1.8372, 4.8992], rtol=1e-4)


@pytest.mark.parametrize("eps", [0.0, -0.1, 1.01, float("nan")])
def test_rejects_emissivity_outside_0_1(eps):
    with pytest.raises(ValueError, match="emissivity"):
        h_radiation(eps, 300.0, 290.0)
    with pytest.raises(ValueError, match="emissivity"):
        heat_flux_radiation(eps, 300.0, 290.0)


def test_emissivity_one_is_allowed():
    # black body, both at 300 K: 4 sigma T^3 = 6.12400 W/m^2K
    assert h_radiation(1.0, 300.0, 300.0) == pytest.approx(6.12400, rel=1e-5)


@pytest.mark.parametrize("T", [0.0, -5.0])
def test_rejects_non_absolute_temperatures(T):
    with pytest.raises(ValueError):
        h_radiation(0.5, T, 293.15)
    with pytest.raises(ValueError):
        heat_flux_radiation(0.5, 293.15, T)


def test_a_call_with_floats_gives_the_arrays_numbers_to_the_last_bit():
    # the boundary conditions call with Python floats, which take a path without arrays: the same
    # products, T_s·T_s where numpy squares an array (Python's T_s ** 2 differs in the last bit at times)
    rng = np.random.default_rng(3)
    for eps, Ts, Ta in zip(rng.uniform(0.01, 1.0, 2000), rng.uniform(250.0, 900.0, 2000), rng.uniform(250.0, 400.0, 2000)):
        scalar = h_radiation(float(eps), float(Ts), float(Ta))
        assert type(scalar) is float
        assert scalar == h_radiation(np.array([eps]), np.array([Ts]), np.array([Ta]))[0]
    for bad in (float("inf"), float("nan")):
        with pytest.raises(ValueError, match="T_surface must be an absolute temperature"):
            h_radiation(0.5, bad, 293.15)
