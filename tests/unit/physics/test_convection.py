"""Tests of feedtherm.physics.convection.

Expected values are numbers printed in the sources (correlation constants, AUDIT §4
CHTCs) or hand calculations written out below. Hand calculations of surface-level h use
Incropera (2007) Table A.4 air at 300 K (nu = 15.89e-6 m²/s, k = 26.3e-3 W/mK,
alpha = 22.5e-6 m²/s, Pr = 0.707, Pr^(1/3) = 0.89085), so the comparison with the
CoolProp-based code is made with a stated 3 % tolerance (Table A.4 vs CoolProp ~1-1.5 %
on nu, k at 1 atm, plus the 298.15 K vs 300 K property difference).
"""

import math
import warnings

import numpy as np
import pytest

from feedtherm.physics import convection as cv
from feedtherm.physics.air import air_properties
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
    # Correction (AUDIT Eq. 24): the paper's L in mm (32) would give 1000x less.
    assert cv.h_from_nusselt(22.817, 0.0263, 32.0) == pytest.approx(18.753e-3, rel=1e-4)


@pytest.mark.parametrize("args", [(10.0, 0.026, -0.1), (10.0, 0.0, 0.1), (-1.0, 0.026, 0.1)])
def test_h_from_nusselt_rejects_bad_input(args):
    with pytest.raises(ValueError):
        cv.h_from_nusselt(*args)


# ------------------------------------------------------------- natural convection (Eq. 25)
@pytest.mark.parametrize("Ra, expected", [
    (1e-6, 0.675 * 10 ** (-6 * 0.058)),   # = 0.675 * 0.44875 = 0.30290
    (1.0, 1.02),                          # 1.02 * 1^0.148
    (1e3, 0.850 * 10 ** (3 * 0.188)),     # = 0.850 * 3.6644 = 3.1147
    (1e5, 0.480 * 10 ** 1.25),            # = 0.480 * 17.783 = 8.5357
    (1e10, 0.125 * 10 ** 3.33),           # = 0.125 * 2138.0 = 267.25
])
def test_morgan_each_regime(Ra, expected, no_warnings):
    # Incropera Table 9.1 constants, one point inside each of the five Ra ranges.
    assert cv.Nu_natural_horizontal_cylinder_Morgan(Ra) == pytest.approx(expected, rel=1e-12)


def test_morgan_regime_boundaries_nearly_continuous():
    for Ra in (1e-2, 1e2, 1e4, 1e7):
        below = cv.Nu_natural_horizontal_cylinder_Morgan(Ra * (1 - 1e-12))
        at = cv.Nu_natural_horizontal_cylinder_Morgan(Ra)
        assert at == pytest.approx(below, rel=0.01)
    # at 1e4 the upper regime is used: 0.48 * (1e4)^0.25 = 4.80
    assert cv.Nu_natural_horizontal_cylinder_Morgan(1e4) == pytest.approx(4.80, rel=1e-12)


def test_morgan_arrays_and_range_warnings():
    Nu = cv.Nu_natural_horizontal_cylinder_Morgan(np.array([1.0, 1e5]))
    np.testing.assert_allclose(Nu, [1.02, 8.53574], rtol=1e-5)
    with pytest.warns(CorrelationRangeWarning, match="Ra_D"):
        cv.Nu_natural_horizontal_cylinder_Morgan(1e-11)
    with pytest.warns(CorrelationRangeWarning):
        cv.Nu_natural_horizontal_cylinder_Morgan(1e13)


def test_vertical_plate_regimes(no_warnings):
    # 0.59 * (1e8)^0.25 = 0.59 * 100 = 59.0 ; 0.10 * (1e12)^(1/3) = 0.10 * 1e4 = 1000
    assert cv.Nu_natural_vertical_plate(1e8) == pytest.approx(59.0, rel=1e-12)
    assert cv.Nu_natural_vertical_plate(1e12) == pytest.approx(1000.0, rel=1e-12)
    # boundary 1e9: laminar side 0.59 * 177.83 = 104.92, turbulent side 0.10 * 1000 = 100
    assert cv.Nu_natural_vertical_plate(1e9 * (1 - 1e-12)) == pytest.approx(104.918, rel=1e-5)
    assert cv.Nu_natural_vertical_plate(1e9) == pytest.approx(100.0, rel=1e-12)


def test_vertical_plate_below_1e4_still_laminar_form_but_warns():
    # 0.59 * (1e3)^0.25 = 0.59 * 5.6234 = 3.3178
    with pytest.warns(CorrelationRangeWarning, match="vertical_plate"):
        assert cv.Nu_natural_vertical_plate(1e3) == pytest.approx(3.3178, rel=1e-4)
    with pytest.warns(CorrelationRangeWarning):
        cv.Nu_natural_vertical_plate(1e14)


def test_horizontal_plate_up_regimes(no_warnings):
    # 0.54 * (1e6)^0.25 = 0.54 * 31.623 = 17.076 ; 0.15 * (1e9)^(1/3) = 150
    assert cv.Nu_natural_horizontal_plate_up(1e6) == pytest.approx(17.0763, rel=1e-5)
    assert cv.Nu_natural_horizontal_plate_up(1e9) == pytest.approx(150.0, rel=1e-12)
    # at 1e7: 0.54 * 56.234 = 30.37 vs 0.15 * 215.44 = 32.32; the upper form is used
    assert cv.Nu_natural_horizontal_plate_up(1e7) == pytest.approx(32.316, rel=1e-4)


@pytest.mark.parametrize("Ra", [1e3, 1e12])
def test_horizontal_plate_up_warns_outside(Ra):
    with pytest.warns(CorrelationRangeWarning, match="plate_up"):
        cv.Nu_natural_horizontal_plate_up(Ra)


def test_horizontal_plate_down(no_warnings):
    # 0.27 * (1e8)^0.25 = 27.0
    assert cv.Nu_natural_horizontal_plate_down(1e8) == pytest.approx(27.0, rel=1e-12)


@pytest.mark.parametrize("Ra", [1e4, 1e11])
def test_horizontal_plate_down_warns_outside(Ra):
    with pytest.warns(CorrelationRangeWarning, match="plate_down"):
        cv.Nu_natural_horizontal_plate_down(Ra)


@pytest.mark.parametrize("f", [cv.Nu_natural_horizontal_cylinder_Morgan,
                               cv.Nu_natural_vertical_plate,
                               cv.Nu_natural_horizontal_plate_up,
                               cv.Nu_natural_horizontal_plate_down])
def test_natural_zero_rayleigh_limit_and_negative_rejected(f, no_warnings):
    assert f(0.0) == 0.0
    with pytest.raises(ValueError):
        f(-1.0)


# -------------------------------------------------------------------- forced convection
def test_rotating_cylinder_constant():
    # Eq. 27: 0.133 * (1000)^(2/3) * 0.7^(1/3) = 0.133 * 100 * 0.887904 = 11.8091
    assert cv.Nu_rotating_cylinder(1000.0, 0.7) == pytest.approx(11.8091, rel=1e-5)


@pytest.mark.parametrize("Re, Pr", [(5e5, 0.71), (1e4, 0.65), (1e4, 1000.0)])
def test_rotating_cylinder_warns_outside_range(Re, Pr):
    with pytest.warns(CorrelationRangeWarning, match="Eq. 27"):
        cv.Nu_rotating_cylinder(Re, Pr)


def test_flat_plate_average_is_twice_the_printed_local_eq_28(no_warnings):
    # Correction AUDIT Eq. 28: 0.664 * sqrt(1e4) * 0.7^(1/3) = 0.664*100*0.887904 = 58.957
    avg = cv.Nu_flat_plate_laminar_average(1e4, 0.7)
    local = cv.Nu_flat_plate_laminar_local(1e4, 0.7)
    assert avg == pytest.approx(58.9569, rel=1e-5)
    assert local == pytest.approx(29.4785, rel=1e-5)
    assert avg == pytest.approx(2.0 * local, rel=1e-12)


@pytest.mark.parametrize("f", [cv.Nu_flat_plate_laminar_average, cv.Nu_flat_plate_laminar_local])
@pytest.mark.parametrize("Re, Pr", [(1e6, 0.7), (1e4, 0.5)])
def test_flat_plate_warns_outside_laminar_range(f, Re, Pr):
    with pytest.warns(CorrelationRangeWarning):
        f(Re, Pr)


def test_plate_normal_to_flow_inside_range(no_warnings):
    # Eq. 29: 0.228 * (1e4)^0.731 * 0.7^(1/3) = 0.228 * 839.46 * 0.887904 = 169.94
    assert cv.Nu_plate_normal_to_flow(1e4, 0.7) == pytest.approx(169.94, rel=1e-4)


@pytest.mark.parametrize("Re", [100.0, 2e4])
def test_plate_normal_to_flow_warns_outside_4e3_1p5e4(Re):
    # Correction AUDIT Eq. 29: at feed speeds Re ~ 20-170, far below 4e3.
    with pytest.warns(CorrelationRangeWarning, match="Eq. 29"):
        cv.Nu_plate_normal_to_flow(Re, 0.707)


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
def test_h_rotating_cylinder_screw_shaft_audit_18_8():
    # AUDIT §4: screw shaft, Eq. 27 at 396 rpm, d = 32 mm -> 18.8 W/m²K.
    # omega = 2 pi 396/60 = 41.469 rad/s; Re = 41.469 * 0.032^2 / 15.89e-6 = 2672.4;
    # Re^(2/3) = 192.58; Nu = 0.133 * 192.58 * 0.89085 = 22.817;
    # h = 22.817 * 0.0263 / 0.032 = 18.753 W/m²K (CoolProp at 298.15 K gives ~18.97).
    h = cv.h_rotating_cylinder(0.032, 396.0, 298.15)
    assert h == pytest.approx(18.753, rel=RTOL_HAND)
    assert h == pytest.approx(18.8, rel=RTOL_HAND)
    assert cv.h_rotating_cylinder(0.032, -396.0, 298.15) == h


def test_h_rotating_cylinder_diameter_range_audit_17_20():
    # h ∝ d^(1/3): 18.753*(25/32)^(1/3) = 17.27 and 18.753*(40/32)^(1/3) = 20.20 -> "17-20"
    assert round(cv.h_rotating_cylinder(0.025, 396.0, 298.15)) == 17
    assert round(cv.h_rotating_cylinder(0.040, 396.0, 298.15)) == 20


def test_h_rotating_cylinder_nut_audit_20_5():
    # AUDIT §4: Ø50 rotating nut at 360 rpm -> 20.5 W/m²K.
    # omega = 37.699 rad/s; Re = 37.699 * 0.0025 / 15.89e-6 = 5931.3; Re^(2/3) = 327.67;
    # Nu = 0.133 * 327.67 * 0.89085 = 38.823; h = 38.823 * 0.0263 / 0.05 = 20.42 W/m²K.
    h = cv.h_rotating_cylinder(0.05, 360.0, 298.15)
    assert h == pytest.approx(20.42, rel=RTOL_HAND)
    assert h == pytest.approx(20.5, rel=RTOL_HAND)


def test_h_rotating_cylinder_standstill(no_warnings):
    assert cv.h_rotating_cylinder(0.032, 0.0, 298.15) == 0.0


def test_h_rotating_cylinder_warns_above_re_4p3e5():
    # d = 0.5 m at 3000 rpm: Re = 314.16 * 0.25 / 1.56e-5 ≈ 5e6 > 4.3e5
    with pytest.warns(CorrelationRangeWarning, match="Re"):
        cv.h_rotating_cylinder(0.5, 3000.0, 298.15)


def test_h_flat_plate_forced_table_at_3_mm_per_s():
    # AUDIT §4 "table or slider, forced, 3 mm/s: 0.2-0.7". Hand, L = 0.3 m, 300 K:
    # Re = 0.003*0.3/15.89e-6 = 56.64; sqrt = 7.5259; Nu = 0.664*7.5259*0.89085 = 4.4518;
    # h = 4.4518 * 0.0263 / 0.3 = 0.3903 W/m²K (the printed 0.332 would give 0.195).
    h = cv.h_flat_plate_forced(0.3, 0.003, 300.0)
    assert h == pytest.approx(0.3903, rel=RTOL_HAND)
    assert 0.2 <= h <= 0.7


def test_table_2_worktable_needs_21_m_per_s_with_printed_eq_28():
    # AUDIT §4: worktable 16.23 W/m²K "needs u ≈ 21 m/s in Eq. 28" (0.332, L = 0.3 m).
    # Hand: Re = (16.23*0.3/(0.0263*0.332*0.89085))^2 = 625.95^2 = 3.918e5;
    # u = 3.918e5 * 15.89e-6 / 0.3 = 20.75 m/s.
    air = air_properties(300.0)
    Re = cv.reynolds(20.75, 0.3, air.kinematic_viscosity)
    h = cv.h_from_nusselt(cv.Nu_flat_plate_laminar_local(Re, air.prandtl), air.conductivity, 0.3)
    assert h == pytest.approx(16.23, rel=RTOL_HAND)


def test_h_face_normal_to_motion():
    # Inside the range: L = 0.1 m, u = 1e4 * 15.89e-6 / 0.1 = 1.589 m/s -> Re = 1e4;
    # Nu = 0.228 * 839.46 * 0.89085 = 170.51; h = 170.51 * 0.0263 / 0.1 = 44.84 W/m²K.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert cv.h_face_normal_to_motion(0.1, 1.589, 300.0) == pytest.approx(44.84, rel=RTOL_HAND)
    with pytest.warns(CorrelationRangeWarning, match="Eq. 29"):
        cv.h_face_normal_to_motion(0.1, 0.003, 300.0)


def test_h_natural_vertical_plate_hand_calculation(no_warnings):
    # L = 0.1 m, Ts = 30 C, Ta = 20 C, Tf = 298.15 K, beta = 1/298.15;
    # Ra = 9.80665/298.15 * 10 * 1e-3 / (15.89e-6 * 22.5e-6) = 9.1998e5 (laminar);
    # Nu = 0.59 * 9.1998e5^0.25 = 0.59 * 30.970 = 18.272; h = 18.272*0.0263/0.1 = 4.806.
    h = cv.h_natural("vertical_plate", 0.1, 303.15, 293.15)
    assert h == pytest.approx(4.806, rel=RTOL_HAND)


def test_h_natural_horizontal_cylinder_hand_calculation(no_warnings):
    # d = 0.05 m, dT = 10 K at Tf = 298.15 K: g beta dT d^3 = 9.80665/298.15*10*1.25e-4
    # = 4.1116e-5 m^3/s^2; nu alpha = 15.89e-6*22.5e-6 = 3.5753e-10; Ra = 1.1500e5;
    # Morgan 1e4-1e7: Nu = 0.48 * 1.15e5^0.25 = 0.48 * 18.415 = 8.839;
    # h = 8.839 * 0.0263 / 0.05 = 4.649 W/m²K.
    h = cv.h_natural("horizontal_cylinder", 0.05, 303.15, 293.15)
    assert h == pytest.approx(4.649, rel=RTOL_HAND)


def test_h_natural_cold_face_up_behaves_as_hot_face_down():
    # Same film temperature (293.15 K) and |dT| = 10 K in both cases.
    cold_up = cv.h_natural("horizontal_plate_up", 0.1, 288.15, 298.15)
    hot_down = cv.h_natural("horizontal_plate_down", 0.1, 298.15, 288.15)
    cold_down = cv.h_natural("horizontal_plate_down", 0.1, 288.15, 298.15)
    hot_up = cv.h_natural("horizontal_plate_up", 0.1, 298.15, 288.15)
    assert cold_up == pytest.approx(hot_down, rel=1e-12)
    assert cold_down == pytest.approx(hot_up, rel=1e-12)
    assert hot_up > hot_down  # 0.54 vs 0.27 prefactor


@pytest.mark.parametrize("orientation", cv.NATURAL_ORIENTATIONS)
def test_h_natural_zero_temperature_difference(orientation, no_warnings):
    assert cv.h_natural(orientation, 0.1, 293.15, 293.15) == 0.0


def test_h_natural_warns_below_plate_down_range():
    # L = A/P = 0.02 m, dT = 5 K: Ra ≈ 9.8/295.65*5*8e-6/(1.56e-5*2.2e-5) ≈ 3.9e3 < 1e5
    with pytest.warns(CorrelationRangeWarning, match="plate_down"):
        cv.h_natural("horizontal_plate_down", 0.02, 298.15, 293.15)


def test_h_natural_rejects_unknown_orientation():
    with pytest.raises(ValueError, match="vertical_plate.*horizontal_plate_down"):
        cv.h_natural("vertical", 0.1, 303.15, 293.15)


@pytest.mark.parametrize("L, Ts, Ta", [(0.0, 303.15, 293.15), (0.1, 30.0, -20.0)])
def test_h_natural_rejects_bad_geometry_or_temperature(L, Ts, Ta):
    with pytest.raises(ValueError):
        cv.h_natural("vertical_plate", L, Ts, Ta)


def test_mixed_convection_at_feed_speed_is_natural_dominated():
    # Replacement for Eq. 29 at 3 mm/s (AUDIT): h_F ≈ 0.39 vs h_N ≈ 3-5, so the blend
    # is within 0.3 % of natural convection: (0.39^3 + 4.8^3)^(1/3) = 4.8021.
    hF = cv.h_flat_plate_forced(0.3, 0.003, 298.15)
    hN = cv.h_natural("vertical_plate", 0.1, 303.15, 293.15)
    assert cv.h_mixed(hF, hN) == pytest.approx(hN, rel=3e-3)
    assert cv.h_mixed(hF, hN) > hN
    assert math.isfinite(cv.h_mixed(hF, hN))
