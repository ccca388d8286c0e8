"""Unit tests of feedtherm.physics.screw_nut_rolling (the paper's Eqs. 1-12, corrected).

Every expected value is a number printed in a source (Hamrock & Dowson, Heathcote,
docs/paper-audit.md §1/§5) or a hand calculation written out step by step below (calculator
arithmetic, 8+ significant digits).  None is the code's own output.
"""

from __future__ import annotations

import math

import pytest

from feedtherm.physics import screw_nut_rolling as sn
from feedtherm.physics.validity import CorrelationRangeWarning

HAND = 1e-6  # rel tolerance for hand calculations

# Default Tr32x10(P5) nut of docs/paper-audit.md §4/§5.
D2 = 0.0295  # pitch diameter [m]
BETA = math.radians(15.0)  # flank half angle [rad]


# --------------------------------------------------------------------------------------
# Moduli (Eq. 10, Hamrock E')
# --------------------------------------------------------------------------------------


def test_effective_modulus_steel_on_steel():
    # E* = E / (2 (1 - nu^2)) = 2.1e11 / (2 * 0.91) = 2.1e11 / 1.82 = 1.1538461538e11 Pa
    E_star = sn.effective_modulus_Hertz(2.1e11, 0.3, 2.1e11, 0.3)
    assert E_star == pytest.approx(1.1538461538e11, rel=HAND)


def test_effective_modulus_steel_on_bronze():
    # (1 - 0.3^2)/2.1e11  = 0.91/2.1e11   = 4.3333333e-12
    # (1 - 0.34^2)/1.1e11 = 0.8844/1.1e11 = 8.0400000e-12
    # sum = 1.23733333e-11  ->  E* = 1/sum = 8.0818966e10 Pa
    assert sn.effective_modulus_Hertz(2.1e11, 0.3, 1.1e11, 0.34) == pytest.approx(8.0818966e10, rel=HAND)


def test_hamrock_modulus_is_twice_hertz_modulus_and_matches_hamrock_dowson():
    # Hamrock & Dowson quote E' = 2.28e11 Pa for bearing steel (E = 2.075e11 Pa, nu = 0.3):
    # E' = 2 / (2 * 0.91 / 2.075e11) = 2.075e11 / 0.91 = 2.2802198e11 Pa
    E_prime = sn.effective_modulus_Hamrock_Dowson(2.075e11, 0.3, 2.075e11, 0.3)
    assert E_prime == pytest.approx(2.2802198e11, rel=HAND)
    assert E_prime == pytest.approx(2.28e11, rel=1e-3)  # printed value
    assert E_prime == pytest.approx(2.0 * 1.1401099e11, rel=HAND)  # = 2 E*


def test_poisson_ratio_outside_physical_range_warns():
    with pytest.warns(CorrelationRangeWarning, match="nu"):
        sn.effective_modulus_Hertz(2.1e11, 0.6, 2.1e11, 0.3)


# --------------------------------------------------------------------------------------
# Differential sliding (Eqs. 3-5)
# --------------------------------------------------------------------------------------


def test_heathcote_bracket_audit_value():
    # int_{-1}^{1} (X^2 - X^4) dX = 2 (1/3 - 1/5) = 4/15 = 0.26666667
    # X = 0.347: X^3 = 0.041781923, X^5 = 0.0050309196
    #   X^3/3 - X^5/5 = 0.013927308 - 0.0010061839 = 0.012921124
    #   int_{-0.347}^{0.347} = 2 * 0.012921124 = 0.025842248
    # bracket = 0.26666667 - 2 * 0.025842248 = 0.21498217   (docs/paper-audit.md §1: "0.2149")
    b = sn.bracket_differential_sliding(-0.347, 0.347)
    assert b == pytest.approx(0.21498217, rel=HAND)
    assert b == pytest.approx(0.2149, rel=1e-3)


def test_heathcote_rolling_lines_give_zero_net_tangential_force():
    # Zero net force: int (1 - X^2) outside = int inside  ->  c^3 - 3c + 1 = 0,
    # c = 2 cos 80 deg = 0.34729636.  X^3 = 0.041889066, X^5 = 0.0050524396
    #   X^3/3 - X^5/5 = 0.013963022 - 0.0010104879 = 0.012952534
    # bracket = 4/15 - 4 * 0.012952534 = 0.26666667 - 0.051810136 = 0.21485653
    c = 2.0 * math.cos(math.radians(80.0))
    assert c**3 - 3.0 * c + 1.0 == pytest.approx(0.0, abs=1e-12)
    assert sn.bracket_differential_sliding(-c, c) == pytest.approx(0.21485653, rel=HAND)


@pytest.mark.parametrize(
    "X1, X2, expected",
    [
        (0.0, 0.0, 4.0 / 15.0),  # no reversed zone: +int over the whole contact
        (-1.0, 1.0, -4.0 / 15.0),  # all reversed: 4/15 - 2*4/15
        # asymmetric: [X^3/3 - X^5/5] from 0 to 0.5 = 0.041666667 - 0.00625 = 0.035416667
        # bracket = 0.26666667 - 2*0.035416667 = 0.19583333
        (0.0, 0.5, 0.19583333),
    ],
)
def test_heathcote_bracket_closed_form_limits(X1, X2, expected):
    assert sn.bracket_differential_sliding(X1, X2) == pytest.approx(expected, rel=HAND)


def test_heathcote_bracket_rejects_lines_outside_contact():
    with pytest.raises(ValueError, match="X1"):
        sn.bracket_differential_sliding(0.5, 0.2)
    with pytest.raises(ValueError):
        sn.bracket_differential_sliding(-1.2, 0.3)


def test_differential_sliding_torque_contact_is_heathcote_0p0806():
    # mu = 0.1, Q = 100 N, a = 1 mm, R = 15 mm, X = +-0.347
    # 0.75 * mu * Q * a^2/(2R) = 0.75 * 0.1 * 100 * 1e-6 / 0.030 = 2.5e-4 N·m
    # * bracket 0.21498217 = 5.3745543e-5 N·m
    # Heathcote form: 0.375 * 0.21498217 = 0.080618314 -> 0.080618314 * mu Q a^2/R
    M = sn.torque_differential_sliding_contact(0.1, 100.0, 1e-3, 0.015, -0.347, 0.347)
    assert M == pytest.approx(5.3745543e-5, rel=HAND)
    assert M / (0.1 * 100.0 * 1e-6 / 0.015) == pytest.approx(0.0806, rel=1e-3)


def test_eq3_printed_prefactor_is_7p5_times_too_small():
    # Printed Eq. 3: 0.1 * mu * Q * a^2/(2R) * bracket, computed by hand here.
    mu, Q, a, R = 0.1, 100.0, 1e-3, 0.015
    bracket = 0.21498217  # hand value above
    printed = 0.1 * mu * Q * a**2 / (2.0 * R) * bracket  # = 7.1660723e-6 N·m
    assert printed == pytest.approx(7.1660723e-6, rel=HAND)
    corrected = sn.torque_differential_sliding_contact(mu, Q, a, R, -0.347, 0.347)
    assert printed / corrected == pytest.approx(0.1 / 0.75, rel=HAND)  # 1/7.5


def test_rolling_analogy_is_three_orders_below_coulomb_sliding():
    # docs/paper-audit.md §5: Q = 100 N, a = 1 mm, R = 15 mm, 12 flanks, mu = 0.1, X = +-2cos80:
    # M_dj = 2.5e-4 * 0.21485653 = 5.3714133e-5; M_d = 12 * 5.3714133e-5 * cos 15
    #      = 6.4456959e-4 * 0.96592583 = 6.2260641e-4 N·m  (~0.6 N·mm)
    # Coulomb: mu * Q * r2 * 12 = 0.1 * 100 * 0.01475 * 12 = 1.77 N·m (~1.8 N·m)
    c = 2.0 * math.cos(math.radians(80.0))
    Mdj = sn.torque_differential_sliding_contact(0.1, 100.0, 1e-3, 0.015, -c, c)
    Md = sn.torque_differential_sliding([Mdj] * 12, BETA)
    assert Md == pytest.approx(6.2260641e-4, rel=HAND)
    assert 1.77 / Md == pytest.approx(2843, rel=1e-3)  # docs/paper-audit.md: "~3000x"


def test_differential_sliding_torque_sums_with_cos_alpha():
    # (1e-4 + 2e-4 + 3e-4) * cos 15 deg = 6e-4 * 0.96592583 = 5.7955550e-4 N·m
    Md = sn.torque_differential_sliding([1e-4, 2e-4, 3e-4], BETA)
    assert Md == pytest.approx(5.7955550e-4, rel=HAND)
    # per-contact angles 0 and 60 deg: 1e-4 * 1 + 2e-4 * 0.5 = 2e-4 N·m
    Md = sn.torque_differential_sliding([1e-4, 2e-4], [0.0, math.pi / 3])
    assert Md == pytest.approx(2e-4, rel=HAND)


# --------------------------------------------------------------------------------------
# Hertz and hysteresis (Eqs. 6-8)
# --------------------------------------------------------------------------------------

E_STAR_STEEL = 1.1538461538e11  # hand value above


def test_hertz_semi_minor_axis_reduces_to_sphere_on_plane():
    # Johnson: a = (3 Q R / 4 E*)^(1/3). Q = 100 N, R = 10 mm, E* = 1.1538461538e11 Pa
    # 3*100*0.01 / (4 * 1.1538461538e11) = 3 / 4.6153846e11 = 6.5e-12 m^3
    # cube root: 1.8662556e-4 m.  Here gamma = 1, sum_rho = 1/R + 1/R = 200 1/m.
    b = sn.semi_minor_axis_Hertz(1.0, 100.0, E_STAR_STEEL, 200.0)
    assert b == pytest.approx(1.8662556e-4, rel=HAND)


def test_hysteresis_torque_contact_hand():
    # kappa * alpha * Q * b/R * r_m = (3/16) * 0.01 * 100 * (1.8662556e-4/0.01) * 0.015
    # = 0.1875 * 0.018662556 * 0.015 = 0.0034992293 * 0.015 = 5.2488439e-5 N·m
    M = sn.torque_hysteresis_contact(0.01, 100.0, 1.8662556e-4, 0.01, 0.015)
    assert M == pytest.approx(5.2488439e-5, rel=HAND)
    # The 3/32 convention of the paper/bearing texts gives half with the same alpha_h.
    M32 = sn.torque_hysteresis_contact(0.01, 100.0, 1.8662556e-4, 0.01, 0.015, kappa=3 / 32)
    assert M32 == pytest.approx(M / 2.0, rel=1e-12)


def test_corrected_eq8_scales_as_q_to_4_3_and_inverse_cube_root_of_e():
    # M_f = kappa alpha (gamma/R) (3/(2 E* sum_rho))^(1/3) Q^(4/3) r_m
    def chain(Q, E_star):
        b = sn.semi_minor_axis_Hertz(1.0, Q, E_star, 200.0)
        return sn.torque_hysteresis_contact(0.01, Q, b, 0.01, 0.015)

    base = chain(100.0, E_STAR_STEEL)
    assert base == pytest.approx(5.2488439e-5, rel=HAND)
    assert chain(200.0, E_STAR_STEEL) / base == pytest.approx(2.0 ** (4.0 / 3.0), rel=1e-12)
    # printed Eq. 8 has E^(+1/3): doubling E would raise M by 2^(1/3); corrected lowers it
    assert chain(100.0, 2.0 * E_STAR_STEEL) / base == pytest.approx(2.0 ** (-1.0 / 3.0), rel=1e-12)


def test_corrected_eq8_is_a_torque_but_printed_eq8_is_not():
    # Unit-rescaling test: inputs in N, mm, N/mm^2 must give N·mm = 1000 x the SI N·m.
    si = sn.torque_hysteresis_contact(
        0.01, 100.0, sn.semi_minor_axis_Hertz(1.0, 100.0, E_STAR_STEEL, 200.0), 0.01, 0.015)
    mm = sn.torque_hysteresis_contact(
        0.01, 100.0, sn.semi_minor_axis_Hertz(1.0, 100.0, E_STAR_STEEL * 1e-6, 0.2), 10.0, 15.0)
    assert mm / si == pytest.approx(1000.0, rel=1e-9)

    # Printed Eq. 8, by hand: (3/32) eta B gamma (3E/(2 sum_rho))^(1/3) P^(4/3), B = 2R.
    def printed(B, E, sum_rho):
        return 3 / 32 * 0.01 * B * (3 * E / (2 * sum_rho)) ** (1 / 3) * 100.0 ** (4 / 3)

    # B: x1000, (E/sum_rho)^(1/3): (1e-6/1e-3)^(1/3) = 0.1  ->  x100, not x1000
    ratio = printed(20.0, 2.1e5, 0.2) / printed(0.02, 2.1e11, 200.0)
    assert ratio == pytest.approx(100.0, rel=1e-9)


def test_hysteresis_loss_fraction_above_one_warns():
    with pytest.warns(CorrelationRangeWarning, match="alpha_h"):
        sn.torque_hysteresis_contact(1.5, 100.0, 1e-4, 0.01, 0.015)


# --------------------------------------------------------------------------------------
# EHL rolling resistance (Eqs. 9-12)
# --------------------------------------------------------------------------------------


def test_ellipticity_hamrock_brewe():
    # k(1) = 1.0339 (the fit, not the exact 1);  10^0.636 = 4.3251383 -> k = 4.4717605
    assert sn.ellipticity_Hamrock_Brewe(0.01, 0.01) == pytest.approx(1.0339, rel=HAND)
    assert sn.ellipticity_Hamrock_Brewe(0.05, 0.005) == pytest.approx(4.4717605, rel=HAND)
    with pytest.warns(CorrelationRangeWarning, match="Ry/Rx"):
        sn.ellipticity_Hamrock_Brewe(0.005, 0.01)


def test_ehl_groups_and_rolling_resistance_hand():
    # eta0 = 0.1 Pa·s, alpha_p = 2e-8 1/Pa, u = 0.5 m/s, Q = 100 N, E' = 2.28e11 Pa,
    # Rx = 5 mm, Ry = 50 mm.
    # U = 0.1*0.5/(2.28e11*0.005) = 0.05/1.14e9 = 4.3859649e-11
    # G = 2e-8 * 2.28e11 = 4560
    # W = 100/(2.28e11 * 2.5e-5) = 100/5.7e6 = 1.7543860e-5
    U, G, W = sn.dimensionless_groups_ehl(0.1, 2e-8, 0.5, 100.0, 2.28e11, 0.005)
    assert U == pytest.approx(4.3859649e-11, rel=HAND)
    assert G == pytest.approx(4560.0, rel=HAND)
    assert W == pytest.approx(1.7543860e-5, rel=HAND)
    # k = 4.4717605; k^0.348 = 1.6840948; G^0.022 = 1.2036417;
    # U^0.66 = 1.4580184e-7; W^0.47 = 5.8175325e-3; E' Rx^2 = 5.7e6 N
    # F = 2.86 * 5.7e6 * 1.6840948 * 1.2036417 * 1.4580184e-7 * 5.8175325e-3
    #   = 1.6302e7 * 2.0270465 * 8.4822213e-10 = 2.8028926e-2 N
    F = sn.rolling_resistance_ehl(2.28e11, 0.005, 4.4717605, G, U, W)
    assert F == pytest.approx(2.8028926e-2, rel=HAND)
    assert sn.rolling_resistance_ehl(2.28e11, 0.005, 4.4717605, G, U, W, f_t=0.5) == pytest.approx(
        1.4014463e-2, rel=HAND)


def test_eq10_e_star_in_eq9_overestimates_by_2_to_0p108():
    # Same physics, E* instead of E' = 2E*: F ∝ E'^(1 - 0.66 + 0.022 - 0.47) = E'^-0.108,
    # so F(E*)/F(E') = 2^0.108 = 1.0777331
    def force(E):
        U, G, W = sn.dimensionless_groups_ehl(0.1, 2e-8, 0.5, 100.0, E, 0.005)
        return sn.rolling_resistance_ehl(E, 0.005, 4.4717605, G, U, W)

    E_star = sn.effective_modulus_Hertz(2.1e11, 0.3, 2.1e11, 0.3)
    E_prime = sn.effective_modulus_Hamrock_Dowson(2.1e11, 0.3, 2.1e11, 0.3)
    assert force(E_star) / force(E_prime) == pytest.approx(1.0777331, rel=HAND)


def test_viscous_torque_uses_pitch_radius_not_nominal():
    # F_l = 2 N at d2/2 = 14.75 mm: 0.0295 N·m. Printed Eq. 11 (R_s = d/2 = 16 mm):
    # 0.032 N·m; printed/corrected = 32/29.5 = 1.0847458
    M = sn.torque_viscous_contact(2.0, D2)
    assert M == pytest.approx(0.0295, rel=HAND)
    assert (2.0 * 0.032 / 2.0) / M == pytest.approx(1.0847458, rel=HAND)


def test_eq1_total_counts_each_contact_once():
    # sigma = 12 contacts of 1e-5 (slide), 2e-5 (hysteresis), 3e-5 (viscous) N·m each:
    # M_d = 12e-5, M_f = 24e-5, M_l = 36e-5 -> M_T = 72e-5 N·m.
    Md, Mf, Ml = 12 * 1e-5, 12 * 2e-5, 12 * 3e-5
    MT = sn.torque_screw_nut_rolling(Md, Mf, Ml)
    assert MT == pytest.approx(7.2e-4, rel=HAND)
    printed = sum(Md + Mf + Ml for _ in range(12))  # outer sum over threads as printed
    assert printed / MT == pytest.approx(12.0, rel=1e-12)


# --------------------------------------------------------------------------------------
# Validity and argument errors
# --------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "call",
    [
        lambda: sn.torque_differential_sliding_contact(0.1, 100.0, 0.0, 0.015, -0.3, 0.3),
        lambda: sn.semi_minor_axis_Hertz(1.0, 100.0, E_STAR_STEEL, -200.0),
        lambda: sn.torque_hysteresis_contact(0.01, 100.0, 1e-4, 0.01, 0.0),
        lambda: sn.torque_viscous_contact(2.0, 0.0),
    ],
)
def test_nonpositive_sizes_and_negative_loads_raise(call):
    with pytest.raises(ValueError, match="must"):
        call()
