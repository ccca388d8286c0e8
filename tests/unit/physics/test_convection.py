"""Tests of feedtherm.physics.convection: dimensionless groups, mixed convection,
and the re-exports of the natural and forced modules.

Expected values are numbers printed in the sources (correlation constants, docs/paper-audit.md §4
CHTCs) or hand calculations written out below. Hand calculations of surface-level h use
Incropera (2007) Table A.4 air at 300 K (nu = 15.89e-6 m²/s, k = 26.3e-3 W/mK,
alpha = 22.5e-6 m²/s, Pr = 0.707, Pr^(1/3) = 0.89085), so the comparison with the
CoolProp-based code is made with a stated 3 % tolerance (Table A.4 vs CoolProp ~1-1.5 %
on nu, k at 1 atm, plus the 298.15 K vs 300 K property difference).
"""

import inspect
import math
import warnings

import pytest

from feedtherm.physics import convection as cv
from feedtherm.physics import dimensionless, forced_convection, natural_convection
from feedtherm.physics.air import properties_air
from feedtherm.physics.validity import CorrelationRangeWarning

RTOL_HAND = 0.03


@pytest.fixture
def no_warnings():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        yield


# ------------------------------------------------------------------ dimensionless groups
def test_grashof_hand_calculation():
    # L = 0.1 m, dT = 10 K, nu = 15.89e-6 m²/s, beta = 1/300 1/K:
    # g beta = 9.80665/300 = 0.0326888; * dT * L^3 = 3.26888e-4; nu^2 = 2.52492e-10;
    # Gr = 3.26888e-4 / 2.52492e-10 = 1.29465e6.
    assert cv.grashof(0.1, 310.0, 300.0, 15.89e-6, 1 / 300) == pytest.approx(1.29465e6, rel=1e-5)


def test_grashof_uses_magnitude_and_si_viscosity():
    a = cv.grashof(0.1, 310.0, 300.0, 15.89e-6, 1 / 300)
    assert cv.grashof(0.1, 300.0, 310.0, 15.89e-6, 1 / 300) == a
    # Eq. 26 correction: nu entered in mm²/s (15.89) would make Gr 1e12 times too small.
    assert cv.grashof(0.1, 310.0, 300.0, 15.89, 1 / 300) == pytest.approx(a * 1e-12)


def test_rayleigh_and_reynolds():
    assert cv.rayleigh(1.29465e6, 0.707) == pytest.approx(9.1532e5, rel=1e-4)
    # 3 mm/s feed over 0.3 m: Re = 0.003 * 0.3 / 15.89e-6 = 56.64
    assert cv.reynolds(-0.003, 0.3, 15.89e-6) == pytest.approx(56.64, rel=1e-4)


def test_reynolds_rotating_hand_calculation():
    # Re = omega d^2 / nu = 41.469 * 0.032^2 / 15.89e-6 = 41.469 * 1.024e-3 / 15.89e-6 = 2672.4
    assert cv.reynolds_rotating(-41.469, 0.032, 15.89e-6) == pytest.approx(2672.4, rel=1e-4)


def test_h_from_nusselt_length_in_metres():
    # Eq. 24: h = Nu k / L = 22.817 * 0.0263 / 0.032 = 18.753 W/m²K.
    assert cv.h_from_nusselt(22.817, 0.0263, 0.032) == pytest.approx(18.753, rel=1e-4)
    # Correction (docs/paper-audit.md Eq. 24): the paper's L in mm (32) would give 1000x less.
    assert cv.h_from_nusselt(22.817, 0.0263, 32.0) == pytest.approx(18.753e-3, rel=1e-4)


@pytest.mark.parametrize("args", [(10.0, 0.026, -0.1), (10.0, 0.0, 0.1), (-1.0, 0.026, 0.1)])
def test_h_from_nusselt_rejects_bad_input(args):
    with pytest.raises(ValueError):
        cv.h_from_nusselt(*args)

def test_nu_mixed_churchill(no_warnings):
    # assisting: (3^3 + 4^3)^(1/3) = 91^(1/3) = 4.49794; opposing: (64 - 27)^(1/3) = 3.33222
    assert cv.Nu_mixed(3.0, 4.0) == pytest.approx(4.49794, rel=1e-5)
    assert cv.Nu_mixed(4.0, 3.0, assisting=False) == pytest.approx(3.33222, rel=1e-5)
    assert cv.Nu_mixed(3.0, 4.0, n=1.0) == pytest.approx(7.0)
    # limits: one mode absent -> the other
    assert cv.Nu_mixed(0.0, 5.0) == pytest.approx(5.0)
    assert cv.Nu_mixed(5.0, 0.0) == pytest.approx(5.0)
    with pytest.raises(ValueError):
        cv.Nu_mixed(3.0, 4.0, n=0.0)


def test_h_mixed_equals_nu_mixed_rebased_to_common_length():
    # forced: Nu_F = 4.452 on L1 = 0.3 m; natural: Nu_N = 18.27 on L2 = 0.1 m; k = 0.0263.
    # h_F = 4.452*0.0263/0.3 = 0.39029; h_N = 18.27*0.0263/0.1 = 4.80501.
    # Rebase both to L = 0.3: Nu_F' = 4.452, Nu_N' = 4.80501*0.3/0.0263 = 54.810;
    # Nu = (4.452^3 + 54.810^3)^(1/3) = (88.24 + 164657)^(1/3) = 54.8198 -> h = 54.8198 *
    # 0.0263/0.3 = 4.80587, the same as (h_F^3 + h_N^3)^(1/3) = (0.05945 + 110.9387)^(1/3).
    hF, hN = 4.452 * 0.0263 / 0.3, 18.27 * 0.0263 / 0.1
    h = cv.h_mixed(hF, hN)
    assert h == pytest.approx(cv.Nu_mixed(hF * 0.3 / 0.0263, hN * 0.3 / 0.0263) * 0.0263 / 0.3)
    assert h == pytest.approx(4.80587, rel=1e-5)
    # ...whereas blending the Nusselt numbers on different lengths would be wrong:
    assert cv.Nu_mixed(4.452, 18.27) * 0.0263 / 0.3 != pytest.approx(h, rel=0.1)
    with pytest.raises(ValueError):
        cv.h_mixed(1.0, 1.0, n=-3.0)

# --------------------------------------------------------------- surface-level helpers
def test_table_2_worktable_needs_21_m_per_s_with_printed_eq_28():
    # docs/paper-audit.md §4: worktable 16.23 W/m²K "needs u ≈ 21 m/s in Eq. 28" (0.332, L = 0.3 m).
    # Hand: Re = (16.23*0.3/(0.0263*0.332*0.89085))^2 = 625.95^2 = 3.918e5;
    # u = 3.918e5 * 15.89e-6 / 0.3 = 20.75 m/s.
    air = properties_air(300.0)
    Re = cv.reynolds(20.75, 0.3, air.kinematic_viscosity)
    h = cv.h_from_nusselt(cv.Nu_flat_plate_laminar_local(Re, air.prandtl), air.conductivity, 0.3)
    assert h == pytest.approx(16.23, rel=RTOL_HAND)

def test_mixed_convection_at_feed_speed_is_natural_dominated():
    # Replacement for Eq. 29 at 3 mm/s (docs/paper-audit.md §1, Eq. 29): h_F ≈ 0.39 vs h_N ≈ 3-5,
    # so the blend is within 0.3 % of natural convection: (0.39^3 + 4.8^3)^(1/3) = 4.8009.
    hF = cv.h_flat_plate_laminar_average(0.3, 0.003, 298.15)
    hN = cv.h_natural("vertical_plate", 0.1, 303.15, 293.15)
    assert cv.h_mixed(hF, hN) == pytest.approx(hN, rel=3e-3)
    assert cv.h_mixed(hF, hN) > hN
    assert math.isfinite(cv.h_mixed(hF, hN))


# ------------------------------------------------------------------------- re-exports
@pytest.mark.parametrize("module", [dimensionless, natural_convection, forced_convection])
def test_convection_reexports_every_public_function_of_the_split_modules(module):
    own = [name for name, f in inspect.getmembers(module, inspect.isfunction)
           if f.__module__ == module.__name__ and not name.startswith("_")]
    assert own
    for name in own:
        assert name in cv.__all__
        assert getattr(cv, name) is getattr(module, name)


def test_convection_all_resolves_and_keeps_the_names_boundary_uses():
    assert len(cv.__all__) == len(set(cv.__all__))
    assert all(hasattr(cv, name) for name in cv.__all__)
    assert cv.G_STANDARD is dimensionless.G_STANDARD
    assert cv.NATURAL_ORIENTATIONS is natural_convection.NATURAL_ORIENTATIONS
    for name in ("h_natural", "h_rotating_cylinder", "h_flat_plate_laminar_average",
                 "h_plate_normal_to_flow", "h_mixed"):
        assert name in cv.__all__


def test_calls_with_floats_give_the_arrays_numbers_to_the_last_bit():
    # the boundary conditions call Grashof, the film temperature and the air's properties with Python
    # floats, which take paths without arrays (and the air's properties a small cache): the same numbers
    import numpy as np

    from feedtherm.physics import air as air_module
    from feedtherm.physics.air import film_temperature

    rng = np.random.default_rng(4)
    for Ts, Ta, L in zip(rng.uniform(250.0, 450.0, 2000), rng.uniform(250.0, 320.0, 2000), rng.uniform(0.01, 2.0, 2000)):
        Ts, Ta, L = float(Ts), float(Ta), float(L)
        film = film_temperature(Ts, Ta)
        assert type(film) is float and film == film_temperature(np.array([Ts]), np.array([Ta]))[0]
        air = properties_air(film)
        assert properties_air(film) is air  # kept
        air_module._properties.cache_clear()
        assert properties_air(film) == air  # and what it keeps is what a fresh evaluation gives
        gr = cv.grashof(L, Ts, Ta, air.kinematic_viscosity, air.expansion_coefficient)
        assert type(gr) is float
        assert gr == cv.grashof(L, np.array([Ts]), np.array([Ta]), air.kinematic_viscosity, air.expansion_coefficient)[0]
    # a kept value still warns outside the range the properties are checked for, at every call
    for _ in range(2):
        with pytest.warns(CorrelationRangeWarning, match="properties_air"):
            properties_air(650.0)
