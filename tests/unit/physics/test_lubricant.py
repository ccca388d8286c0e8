"""Lubricant viscosity: ISO 3448 grades, ASTM D2270 viscosity index, Walther / ASTM D341.

Every expected value is printed in a source named beside it or worked out by hand in the
comments; none is the code's own output.  Logarithms are decimal.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from feedtherm.physics.lubricant import (
    coefficients_viscosity_temperature_Walther,
    kinematic_viscosity_100C_from_index,
    kinematic_viscosity_iso_vg,
    kinematic_viscosity_lubricant,
    kinematic_viscosity_Walther,
    viscosity_index,
)
from feedtherm.physics.validity import CorrelationRangeWarning

MM2_S = 1e-6  # m²/s per mm²/s


# --------------------------------------------------------------------------- ISO 3448


@pytest.mark.parametrize(
    ("grade", "midpoint"),
    # ISO 3448:1992 Table 1, the 18 grades and their midpoints at 40 °C [mm²/s]
    [(2, 2.2), (3, 3.2), (5, 4.6), (7, 6.8), (10, 10), (15, 15), (22, 22), (32, 32), (46, 46),
     (68, 68), (100, 100), (150, 150), (220, 220), (320, 320), (460, 460), (680, 680),
     (1000, 1000), (1500, 1500)],
)
def test_iso_vg_midpoints(grade, midpoint):
    assert kinematic_viscosity_iso_vg(grade) == pytest.approx(midpoint * MM2_S, rel=1e-12)


@pytest.mark.parametrize("written", ["ISO VG 100", "iso vg 100", "VG 100", "VG100", " 100 "])
def test_iso_vg_written_forms(written):
    assert kinematic_viscosity_iso_vg(written) == pytest.approx(100 * MM2_S, rel=1e-12)


@pytest.mark.parametrize("bad", ["ISO VG 90", 90, "SAE 30", "", True, 100.0])
def test_iso_vg_rejects_what_iso_3448_does_not_define(bad):
    with pytest.raises(ValueError, match="ISO"):
        kinematic_viscosity_iso_vg(bad)


# ----------------------------------------------------------------------- ASTM D2270


def test_viscosity_index_d2270_example_below_100():
    # ASTM D2270 worked example: U = 73.30, Y = 8.86 mm²/s. Table 1 rows 8.8 / 8.9:
    # L = 118.5 + 0.6·2.4 = 119.94, H = 68.79 + 0.6·1.15 = 69.48;
    # VI = 100·(119.94 − 73.30)/(119.94 − 69.48) = 100·46.64/50.46 = 92.43 (reported 92).
    assert viscosity_index(73.30 * MM2_S, 8.86 * MM2_S) == pytest.approx(92.43, abs=0.01)


def test_viscosity_index_above_100():
    # U = 22.83, Y = 5.05: H = 28.49 + 0.5·(29.46 − 28.49) = 28.975 (Table 1 rows 5.0 / 5.1);
    # N = (log 28.975 − log 22.83)/log 5.05 = (1.462023 − 1.358506)/0.703291 = 0.147190;
    # 10^N = 1.403428; VI = 100 + 0.403428/0.00715 = 156.42 (reported 156).
    assert viscosity_index(22.83 * MM2_S, 5.05 * MM2_S) == pytest.approx(156.42, abs=0.01)


def test_viscosity_index_above_the_table_uses_the_d2270_formulas():
    # Y = 80 > 70: L = 0.8353·6400 + 14.67·80 − 216 = 5345.92 + 1173.6 − 216 = 6303.52,
    # H = 0.1684·6400 + 11.85·80 − 97 = 1077.76 + 948 − 97 = 1928.76;
    # U = 3000: VI = 100·3303.52/4374.76 = 75.513.
    assert viscosity_index(3000 * MM2_S, 80 * MM2_S) == pytest.approx(75.513, abs=1e-3)


def test_viscosity_index_is_100_on_the_reference_oil_of_index_100():
    # An oil with U = H(Y) is the VI-100 reference oil: Table 1 row Y = 10.0 has H = 82.87.
    assert viscosity_index(82.87 * MM2_S, 10.0 * MM2_S) == pytest.approx(100.0, abs=1e-9)
    # ... and U = L(Y) is the VI-0 reference oil (row 10.0: L = 147.7).
    assert viscosity_index(147.7 * MM2_S, 10.0 * MM2_S) == pytest.approx(0.0, abs=1e-9)


def test_viscosity_index_undefined_below_2_mm2_s():
    with pytest.raises(ValueError, match="2 mm²/s"):
        viscosity_index(10 * MM2_S, 1.9 * MM2_S)


def test_nu100_from_index_vg100_vi95_hand():
    # Table 1 rows 11.0 (L = 173.9, H = 95.19) and 11.1 (L = 176.6, H = 96.45), U = 100:
    # VI = 100·(73.9 + 2.7t)/(78.71 + 1.44t) = 95 -> 7390 + 270t = 7477.45 + 136.8t,
    # t = 87.45/133.2 = 0.656532 -> Y = 11.06565 mm²/s.
    nu100 = kinematic_viscosity_100C_from_index(100 * MM2_S, 95.0)
    assert nu100 == pytest.approx(11.06565 * MM2_S, rel=1e-6)


def test_nu100_from_index_inverts_the_d2270_examples():
    # The two examples above, read backwards: VI 92.43 at U = 73.30 -> Y = 8.86; VI 156.42 at
    # U = 22.83 -> Y = 5.05 (to the two decimals of the indices).
    assert kinematic_viscosity_100C_from_index(73.30 * MM2_S, 92.43) == pytest.approx(8.86 * MM2_S, abs=1e-3 * MM2_S)
    assert kinematic_viscosity_100C_from_index(22.83 * MM2_S, 156.42) == pytest.approx(5.05 * MM2_S, abs=1e-3 * MM2_S)


def test_nu100_from_index_rejects_an_oil_that_cannot_exist():
    # VG 1500 at Y = 2 (the smallest ν₁₀₀ D2270 defines; L = 7.994, H = 6.394) has
    # VI = 100·(7.994 − 1500)/(7.994 − 6.394) = −93250: an index of −1e6 needs Y < 2.
    with pytest.raises(ValueError, match="below 2 mm²/s"):
        kinematic_viscosity_100C_from_index(1500 * MM2_S, -1e6)
    with pytest.raises(ValueError, match="finite"):
        kinematic_viscosity_100C_from_index(100 * MM2_S, math.nan)


# ------------------------------------------------------------------ Walther / ASTM D341


def test_walther_constants_hand():
    # ν₄₀ = 32, ν₁₀₀ = 5.4 mm²/s: loglog 32.7 = 0.180283, loglog 6.1 = −0.104948,
    # log 313.15 = 2.495752, log 373.15 = 2.571883; B = 0.285231/0.076131 = 3.74658,
    # A = 0.180283 + 3.74658·2.495752 = 9.53082.
    A, B = coefficients_viscosity_temperature_Walther(32 * MM2_S, 313.15, 5.4 * MM2_S, 373.15)
    assert (A, B) == pytest.approx((9.53082, 3.74658), abs=2e-5)


def test_walther_constants_match_a_published_d341_spreadsheet():
    # "Viscosity vs Temperature Calculator" (ASTM D341 form, temperatures as °C + 273):
    # 32 cSt at 313 K and 5.4 cSt at 373 K give A = 9.5259, B = 3.7449 and 8.5 cSt at 353 K.
    A, B = coefficients_viscosity_temperature_Walther(32 * MM2_S, 313.0, 5.4 * MM2_S, 373.0)
    assert (A, B) == pytest.approx((9.5259, 3.7449), abs=1e-4)
    assert kinematic_viscosity_Walther(353.0, A, B) == pytest.approx(8.5 * MM2_S, abs=0.05 * MM2_S)


def test_walther_viscosity_at_80_c_hand():
    # A − B·log 353.15 = 9.530815 − 3.746578·2.547959 = −0.015312; 10^−0.015312 = 0.965353;
    # 10^0.965353 = 9.23321; ν = 8.533 mm²/s.
    assert kinematic_viscosity_lubricant(353.15, 32 * MM2_S, 5.4 * MM2_S) == pytest.approx(8.533 * MM2_S, abs=1e-3 * MM2_S)


def test_walther_line_passes_through_its_points_and_falls_with_temperature():
    T = np.array([293.15, 313.15, 333.15, 373.15, 393.15])
    nu = kinematic_viscosity_lubricant(T, 100 * MM2_S, 11.06565 * MM2_S)
    assert nu[1] == pytest.approx(100 * MM2_S, rel=1e-10)
    assert nu[3] == pytest.approx(11.06565 * MM2_S, rel=1e-10)
    assert np.all(np.diff(nu) < 0.0)


def test_walther_warns_below_2_mm2_s():
    # An ISO VG 2 oil (2.2 mm²/s at 40 °C) at 100 °C is below 2 mm²/s, where D341 adds terms.
    with pytest.warns(CorrelationRangeWarning, match="nu"):
        coefficients_viscosity_temperature_Walther(2.2 * MM2_S, 313.15, 1.0 * MM2_S, 373.15)


def test_walther_is_silent_inside_its_range():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        kinematic_viscosity_lubricant(343.15, 100 * MM2_S, 11 * MM2_S)


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: kinematic_viscosity_lubricant(313.15, 100.0, 11 * MM2_S), "mm²/s"),  # mm²/s passed
        (lambda: kinematic_viscosity_lubricant(313.15, 11 * MM2_S, 100 * MM2_S), "smaller"),
        (lambda: kinematic_viscosity_lubricant(-1.0, 100 * MM2_S, 11 * MM2_S), "absolute"),
        (lambda: coefficients_viscosity_temperature_Walther(32 * MM2_S, 313.15, 5 * MM2_S, 313.15), "differ"),
        (lambda: viscosity_index(0.0, 10 * MM2_S), "positive"),
    ],
)
def test_bad_input_is_one_clear_error(call, match):
    with pytest.raises(ValueError, match=match):
        call()
