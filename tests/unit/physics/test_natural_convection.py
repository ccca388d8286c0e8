"""Tests of feedtherm.physics.natural_convection (Eq. 25, h_natural).

Expected values are numbers printed in the sources (correlation constants, docs/paper-audit.md §4
CHTCs) or hand calculations written out below. Hand calculations of surface-level h use
Incropera (2007) Table A.4 air at 300 K (nu = 15.89e-6 m²/s, k = 26.3e-3 W/mK,
alpha = 22.5e-6 m²/s, Pr = 0.707, Pr^(1/3) = 0.89085), so the comparison with the
CoolProp-based code is made with a stated 3 % tolerance (Table A.4 vs CoolProp ~1-1.5 %
on nu, k at 1 atm, plus the 298.15 K vs 300 K property difference).
"""

import warnings

import numpy as np
import pytest

from feedtherm.physics import natural_convection as cv
from feedtherm.physics.validity import CorrelationRangeWarning

RTOL_HAND = 0.03


@pytest.fixture
def no_warnings():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        yield


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
    assert cv.Nu_natural_vertical_plate_McAdams(1e8) == pytest.approx(59.0, rel=1e-12)
    assert cv.Nu_natural_vertical_plate_McAdams(1e12) == pytest.approx(1000.0, rel=1e-12)
    # boundary 1e9: laminar side 0.59 * 177.83 = 104.92, turbulent side 0.10 * 1000 = 100
    assert cv.Nu_natural_vertical_plate_McAdams(1e9 * (1 - 1e-12)) == pytest.approx(104.918, rel=1e-5)
    assert cv.Nu_natural_vertical_plate_McAdams(1e9) == pytest.approx(100.0, rel=1e-12)


def test_vertical_plate_below_1e4_still_laminar_form_but_warns():
    # 0.59 * (1e3)^0.25 = 0.59 * 5.6234 = 3.3178
    with pytest.warns(CorrelationRangeWarning, match="vertical_plate"):
        assert cv.Nu_natural_vertical_plate_McAdams(1e3) == pytest.approx(3.3178, rel=1e-4)
    with pytest.warns(CorrelationRangeWarning):
        cv.Nu_natural_vertical_plate_McAdams(1e14)


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
                               cv.Nu_natural_vertical_plate_McAdams,
                               cv.Nu_natural_horizontal_plate_up,
                               cv.Nu_natural_horizontal_plate_down])
def test_natural_zero_rayleigh_limit_and_negative_rejected(f, no_warnings):
    assert f(0.0) == 0.0
    with pytest.raises(ValueError):
        f(-1.0)

# --------------------------------------------------------------- surface-level helpers
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
