"""Tests of feedtherm.physics.air against Incropera et al. (2007), Table A.4."""

import dataclasses
import subprocess
import sys
import math
import warnings

import numpy as np
import pytest

from feedtherm.physics.air import AirProperties, film_temperature, properties_air
from feedtherm.physics.validity import CorrelationRangeWarning

# Incropera, DeWitt, Bergman, Lavine, Fundamentals of Heat and Mass Transfer, 6th ed.
# (2007), Table A.4, air at atmospheric pressure (values as printed, SI units).
TABLE_A4 = {
    300.0: dict(density=1.1614, specific_heat=1007.0, dynamic_viscosity=184.6e-7,
                kinematic_viscosity=15.89e-6, conductivity=26.3e-3, diffusivity=22.5e-6,
                prandtl=0.707),
    350.0: dict(density=0.9950, specific_heat=1009.0, dynamic_viscosity=208.2e-7,
                kinematic_viscosity=20.92e-6, conductivity=30.0e-3, diffusivity=29.9e-6,
                prandtl=0.700),
}

# Tolerance 2 %: CoolProp (Lemmon 2000 EOS, Lemmon & Jacobsen 2004 transport) and the
# older table differ by ~1 % in the transport properties; at 1 atm the density (and
# hence ν and α) differs by a further 1.3 % because the table's densities are for 1 bar
# (see test_table_density_is_for_one_bar).
RTOL_TABLE = 0.02


@pytest.mark.parametrize("T", sorted(TABLE_A4))
@pytest.mark.parametrize("field", sorted(TABLE_A4[300.0]))
def test_matches_incropera_table_A4_at_1_atm(T, field):
    assert getattr(properties_air(T), field) == pytest.approx(TABLE_A4[T][field], rel=RTOL_TABLE)


@pytest.mark.parametrize("T", sorted(TABLE_A4))
def test_table_density_is_for_one_bar(T):
    # Ideal gas at 1e5 Pa: rho = p M / (R T) = 1e5 * 0.0289586 / (8.314462618 * 300)
    # = 1.16096 kg/m^3 at 300 K, i.e. the table's 1.1614; at 101325 Pa it is 1.1763.
    # So at p = 1e5 Pa CoolProp should match the table density within 0.2 %.
    assert properties_air(T, p=1e5).density == pytest.approx(TABLE_A4[T]["density"], rel=2e-3)


def test_density_close_to_ideal_gas_at_1_atm():
    # rho = 101325 * 0.0289586 / (8.314462618 * 300) = 1.17635 kg/m^3; air at 1 atm and
    # 300 K has a compressibility factor within 0.1 % of 1.
    rho_ideal = 101325.0 * 0.0289586 / (8.314462618 * 300.0)
    assert rho_ideal == pytest.approx(1.17635, rel=1e-5)
    assert properties_air(300.0).density == pytest.approx(rho_ideal, rel=1e-3)


def test_derived_properties_are_consistent():
    a = properties_air(310.0)
    assert a.kinematic_viscosity == pytest.approx(a.dynamic_viscosity / a.density, rel=1e-12)
    assert a.prandtl == pytest.approx(
        a.specific_heat * a.dynamic_viscosity / a.conductivity, rel=1e-12)
    assert a.diffusivity == pytest.approx(
        a.conductivity / (a.density * a.specific_heat), rel=1e-12)
    assert a.prandtl == pytest.approx(a.kinematic_viscosity / a.diffusivity, rel=1e-12)


def test_expansion_coefficient_is_ideal_gas_inverse_temperature():
    # docs/paper-audit.md Eq. 26: beta = 1/T_f in 1/K, e.g. 1/298.15 = 3.35402e-3 1/K.
    a = properties_air(298.15)
    assert a.expansion_coefficient == pytest.approx(3.35402e-3, rel=1e-5)
    assert a.temperature == 298.15


def test_properties_rise_with_temperature():
    cold, warm = properties_air(280.0), properties_air(340.0)
    assert warm.conductivity > cold.conductivity
    assert warm.kinematic_viscosity > cold.kinematic_viscosity
    assert warm.density < cold.density


def test_result_is_frozen_dataclass():
    a = properties_air(300.0)
    assert isinstance(a, AirProperties)
    with pytest.raises(dataclasses.FrozenInstanceError):
        a.density = 1.0


def test_no_warning_inside_range():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        properties_air(200.0)
        properties_air(500.0)


@pytest.mark.parametrize("T", [150.0, 600.0])
def test_warns_outside_200_500_K(T):
    with pytest.warns(CorrelationRangeWarning, match="properties_air"):
        a = properties_air(T)
    assert math.isfinite(a.density)


@pytest.mark.parametrize("T", [0.0, -20.0, float("nan"), float("inf")])
def test_rejects_non_absolute_temperature(T):
    with pytest.raises(ValueError):
        properties_air(T)


def test_rejects_non_positive_pressure():
    with pytest.raises(ValueError):
        properties_air(300.0, p=0.0)


def test_film_temperature():
    # (303.15 + 293.15) / 2 = 298.15
    assert film_temperature(303.15, 293.15) == pytest.approx(298.15)
    assert film_temperature(293.15, 303.15) == pytest.approx(298.15)


def test_film_temperature_adds_arrays_elementwise():
    # (300 + 290)/2 = 295 K and (310 + 290)/2 = 300 K; lists must not be concatenated
    from feedtherm.physics.air import film_temperature

    assert list(film_temperature([300.0, 310.0], [290.0, 290.0])) == [295.0, 300.0]
    assert film_temperature(303.15, 293.15) == pytest.approx(298.15)


# --- the table of CoolProp's values at one atmosphere (feedtherm.physics.air_table) ---------

def test_table_interpolation_stays_within_5e6_of_coolprop():
    # Linear interpolation between whole kelvins of ρT, c_p, μ and k: the largest deviation
    # measured over 110-1400 K is 4.7e-6 (c_p near 110 K, where it curves most).
    from feedtherm.physics.air import _coolprop_state, _tabulated

    for T in np.random.default_rng(7).uniform(110.0, 1400.0, 200):
        tabulated, exact = np.array(_tabulated(T)), np.array(_coolprop_state(T, 101325.0))
        assert np.all(np.abs(tabulated / exact - 1.0) <= 5e-6), T


def test_table_rows_are_coolprops_values():
    from feedtherm.physics.air_table import read_table, table_rows

    table = read_table()
    assert table[0, 0] == 110.0 and table[-1, 0] == 1400.0 and np.all(np.diff(table[:, 0]) == 1.0)
    picked = table[[0, 190, 1290]]  # 110, 300 and 1400 K
    assert np.allclose(table_rows(picked[:, 0]), picked, rtol=1e-9, atol=0.0)


def test_outside_the_table_coolprop_answers():
    # 1e5 Pa is not the table's pressure: ρ from CoolProp, ≈ p/(R_air T) = 1e5/(287.05 · 300) = 1.1612
    assert properties_air(300.0, p=1e5).density == pytest.approx(1.1612, rel=2e-3)
    # 1500 K is past the table's last row (with the range warning)
    with pytest.warns(CorrelationRangeWarning):
        hot = properties_air(1500.0)
    assert hot.density == pytest.approx(101325.0 / (287.05 * 1500.0), rel=2e-3)


def test_importing_the_air_properties_does_not_import_coolprop():
    # CoolProp takes seconds to import; a command's start-up must not pay it (issue 13)
    code = ("import sys, feedtherm.physics.air as a; a.properties_air(300.0); "
            "import feedtherm.cli; print('CoolProp' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_the_table_interpolation_is_numpys_to_the_last_bit():
    """properties_air's tabulated path interpolates on Python floats; it must give numpy.interp's
    floats exactly (rows, the table's ends and random temperatures between them)."""
    from feedtherm.physics import air
    from feedtherm.physics.air_table import T_FIRST, T_LAST

    grid, rho_T, cp, mu, k = air._table()
    temperatures = np.concatenate([grid, np.random.default_rng(7).uniform(T_FIRST, T_LAST, 20000),
                                   np.random.default_rng(8).uniform(280.0, 330.0, 20000)])
    for T in temperatures.tolist():
        expected = (float(np.interp(T, grid, rho_T)) / T, float(np.interp(T, grid, cp)),
                    float(np.interp(T, grid, mu)), float(np.interp(T, grid, k)))
        assert air._tabulated(T) == expected, T
