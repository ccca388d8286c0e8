"""Lubricant viscosity: ISO 3448 grades, Walther / ASTM D341.

Every expected value is printed in a source named beside it or worked out by hand in the
comments; none is the code's own output.  Logarithms are decimal.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from feedtherm.physics.lubricant import (
    coefficients_viscosity_temperature_Walther,
    kinematic_viscosity_iso_vg,
    kinematic_viscosity_lubricant,
    kinematic_viscosity_Walther,
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
    # Hand-made example, not from a data sheet: a VG 100 oil stated as 11 mm²/s at 100 °C.
    T = np.array([293.15, 313.15, 333.15, 373.15, 393.15])
    nu = kinematic_viscosity_lubricant(T, 100 * MM2_S, 11 * MM2_S)
    assert nu[1] == pytest.approx(100 * MM2_S, rel=1e-10)
    assert nu[3] == pytest.approx(11 * MM2_S, rel=1e-10)
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
        (lambda: kinematic_viscosity_lubricant(313.15, 100 * MM2_S, 0.0), "positive"),
    ],
)
def test_bad_input_is_one_clear_error(call, match):
    with pytest.raises(ValueError, match=match):
        call()
