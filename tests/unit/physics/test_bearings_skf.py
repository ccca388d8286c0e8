"""SKF bearing friction model: every constant from its catalogue table, every number by hand.

Source of every constant: SKF General Catalogue 6000 (2006 edition; Russian edition
"Общий каталог SKF", pp. 88-101): Table 2a (G_rr, G_sl formulas), Table 3 (angular contact
ball bearings, single row: R1 = 5.03e-7, R2 = 1.97, R3 = 1.90e-12, S1 = 1.30e-2, S2 = 0.68,
S3 = 1.91e-12), Table 3a (deep groove series 62: R1 = 3.9e-7, R2 = 1.7, S1 = 3.23e-3,
S2 = 36.5), Table 4 (seals), Table 5 (K_Z: deep groove 3.1, angular contact single row 4.4),
K_rs = 6e-8 for grease, mu_bl = 0.15, mu_EHL = 0.05 for mineral oil.  Bearing dimensions from
ISO 15 (7010: d = 50, D = 80 mm; 6205: d = 25, D = 52 mm).  No worked example of the
catalogue's friction model was found in a source, so the calculations below are done by hand
(natural logarithms, 7 significant digits); none is the code's output.
"""

from __future__ import annotations

import math

import pytest

from feedtherm.physics.bearings_skf import (
    GEOMETRIC_CONSTANTS_SKF,
    K_RS_SKF,
    K_Z_SKF,
    MU_BL_SKF,
    MU_EHL_SKF,
    mu_sl,
    phi_bl,
    phi_ish,
    phi_rs,
    seal_constants_SKF,
    torque_bearing_rolling_angular_contact_SKF,
    torque_bearing_rolling_deep_groove_SKF,
    torque_bearing_seal_SKF,
    torque_bearing_sliding_angular_contact_SKF,
    torque_bearing_sliding_deep_groove_SKF,
    torque_bearing_SKF,
)

NU = 100e-6  # 100 mm²/s


def test_constants_are_the_catalogue_tables():
    # Table 3 (angular contact, single row), Table 3a (series 62 and 60), Table 5, K_rs, mu.
    assert GEOMETRIC_CONSTANTS_SKF["angular_contact"]["single_row"] == (5.03e-7, 1.97, 1.90e-12, 1.30e-2, 0.68, 1.91e-12)
    assert GEOMETRIC_CONSTANTS_SKF["deep_groove"]["62"] == (3.9e-7, 1.7, 0.0, 3.23e-3, 36.5, 0.0)
    assert GEOMETRIC_CONSTANTS_SKF["deep_groove"]["60"] == (4.1e-7, 1.7, 0.0, 3.73e-3, 14.6, 0.0)
    assert K_Z_SKF["angular_contact"]["single_row"] == 4.4 and K_Z_SKF["deep_groove"]["62"] == 3.1
    assert K_RS_SKF["grease"] == 6e-8 and K_RS_SKF["oil_jet"] == 3e-8
    assert MU_BL_SKF == 0.15 and MU_EHL_SKF["mineral"] == 0.05


def test_full_hand_calculation_7010_single_row_on_grease():
    # One bearing of a 7010 pair: d = 50, D = 80, d_m = 65 mm; F_r = 25 N (half the pair's
    # 50 N), F_a = 300 N; n = 1080 rpm; base oil nu = 100 mm²/s; grease; mineral oil.
    dm, d, D, n = 0.065, 0.050, 0.080, 1080.0
    R1, R2, R3, S1, S2, S3 = GEOMETRIC_CONSTANTS_SKF["angular_contact"]["single_row"]

    # Rolling: F_g = R3 d_m^4 n^2 = 1.90e-12·17850625·1166400 = 39.5598 N;
    # F_r + F_g + R2 F_a = 25 + 39.5598 + 591 = 655.5598 N; ^0.54 = e^(0.54·6.485490) = 33.1872;
    # d_m^1.97 = e^(1.97·4.174387) = 3727.686; G_rr = 5.03e-7·3727.686·33.1872 = 0.0622269;
    # (nu n)^0.6 = 108000^0.6 = e^(0.6·11.589887) = 1047.259; M_rr = 65.1677 N·mm.
    m_rr = torque_bearing_rolling_angular_contact_SKF(R1, R2, R3, dm, 25.0, 300.0, NU, n)
    assert m_rr == pytest.approx(65.1677e-3, rel=2e-6)

    # phi_ish = 1/(1 + 1.84e-9 (n d_m)^1.28 nu^0.64): 70200^1.28 = e^(1.28·11.159104)
    # = 1.597024e6, 100^0.64 = 19.054607; 1.84e-9·1.597024e6·19.054607 = 0.0559924;
    # phi_ish = 0.946976.
    f_ish = phi_ish(n, dm, NU)
    assert f_ish == pytest.approx(0.946976, abs=1e-6)

    # phi_rs = exp(-K_rs nu n (d + D) sqrt(K_Z/(2(D - d)))): sqrt(4.4/60) = 0.270801;
    # 6e-8·100·1080·130·0.270801 = 0.228123; phi_rs = e^-0.228123 = 0.796026.
    f_rs = phi_rs(K_RS_SKF["grease"], K_Z_SKF["angular_contact"]["single_row"], NU, n, d, D)
    assert f_rs == pytest.approx(0.796026, abs=1e-6)

    # phi_bl = exp(-2.6e-8 (n nu)^1.4 d_m): 108000^1.4 = e^(1.4·11.589887) = 1.113764e7;
    # 2.6e-8·1.113764e7·65 = 18.8226; phi_bl = 6.69e-9: a full film, mu_sl = mu_EHL = 0.05.
    f_bl = phi_bl(n, NU, dm)
    assert f_bl == pytest.approx(6.690e-9, rel=1e-3)
    mu = mu_sl(f_bl, MU_BL_SKF, MU_EHL_SKF["mineral"])
    assert mu == pytest.approx(0.05, abs=1e-9)

    # Sliding: F_g = S3 d_m^4 n^2 = 1.91e-12·17850625·1166400 = 39.7681 N;
    # (25 + 39.7681)^(4/3) = e^(4/3·4.170812) = 260.104; S2 F_a^(4/3) = 0.68·2008.299 = 1365.643;
    # d_m^0.26 = 2.960448; G_sl = 1.30e-2·2.960448·1625.748 = 62.5682 N·mm; M_sl = 3.12841 N·mm.
    m_sl = torque_bearing_sliding_angular_contact_SKF(S1, S2, S3, dm, 25.0, 300.0, n, mu)
    assert m_sl == pytest.approx(3.12841e-3, rel=2e-6)

    # M = phi_ish phi_rs M_rr + M_sl = 0.946976·0.796026·65.1677 + 3.12841 = 49.1246 + 3.12841
    # = 52.2530 N·mm; the pair: 104.506 N·mm, heat 0.104506·2π·1080/60 = 11.819 W.
    total = torque_bearing_SKF(m_rr, f_ish, f_rs, m_sl)
    assert total.total == pytest.approx(52.2530e-3, rel=2e-6)
    assert 2 * total.total * 2 * math.pi * n / 60 == pytest.approx(11.819, abs=1e-3)


def test_deep_groove_with_axial_load_hand():
    # 6205 (series 62, d_m = 38.5 mm, C0 = 7.8 kN), F_r = 50 N, F_a = 300 N, 1116 rpm,
    # nu = 100 mm²/s. alpha_F = 24.6 (300/7800)^0.24 = 24.6·e^(0.24·(-3.258097)) = 24.6·0.457516
    # = 11.254896 deg; sin alpha_F = 0.1951741.
    R1, R2, _, S1, S2, _ = GEOMETRIC_CONSTANTS_SKF["deep_groove"]["62"]
    # G_rr = R1 d_m^1.96 (F_r + R2/sin alpha_F · F_a)^0.54: 1.7/0.1951741 = 8.710170;
    # 50 + 2613.051 = 2663.051 N, ^0.54 = e^(0.54·7.887228) = 70.74650;
    # G_rr = 3.9e-7·1280.864·70.74650 = 0.0353405; ·111600^0.6 (1068.067) = 37.7460 N·mm.
    m_rr = torque_bearing_rolling_deep_groove_SKF(R1, R2, 0.0385, 50.0, 300.0, 7800.0, NU, 1116.0)
    assert m_rr == pytest.approx(37.7460e-3, rel=2e-6)
    # G_sl = S1 d_m^-0.145 (F_r^5 + S2 d_m^1.5/sin alpha_F · F_a^4)^(1/3):
    # 50^5 = 3.125e8; 36.5·238.8862/0.1951741·8.1e9 = 3.618651e14; sum 3.618654e14,
    # ^(1/3) = e^11.174098 = 71260.53; 38.5^-0.145 = e^-0.529345 = 0.588990;
    # G_sl = 3.23e-3·0.588990·71260.53 = 135.5688 N·mm; mu_sl = 0.05: M_sl = 6.77844 N·mm.
    m_sl = torque_bearing_sliding_deep_groove_SKF(S1, S2, 0.0385, 50.0, 300.0, 7800.0, 0.05)
    assert m_sl == pytest.approx(6.77844e-3, rel=2e-6)


def test_deep_groove_without_axial_load_hand():
    # 6205, F_r = 50 N, F_a = 0, 1116 rpm: G_rr = 3.9e-7·38.5^1.96·50^0.54 = 3.9e-7·1280.864·8.268825
    # = 4.130584e-3, M_rr = 4.130584e-3·1068.067 = 4.41174 N·mm; G_sl = 3.23e-3·38.5^-0.26·50^(5/3)
    # = 3.23e-3·0.387062·678.6044 = 0.848398 N·mm.
    R1, R2, _, S1, S2, _ = GEOMETRIC_CONSTANTS_SKF["deep_groove"]["62"]
    assert torque_bearing_rolling_deep_groove_SKF(R1, R2, 0.0385, 50.0, 0.0, 7800.0, NU, 1116.0) == pytest.approx(4.41174e-3, rel=2e-6)
    assert torque_bearing_sliding_deep_groove_SKF(S1, S2, 0.0385, 50.0, 0.0, 7800.0, 1.0) == pytest.approx(0.848398e-3, rel=2e-6)


def test_reductions_are_one_at_standstill_and_fall_with_speed():
    assert phi_ish(0.0, 0.065, NU) == 1.0
    assert phi_rs(6e-8, 4.4, NU, 0.0, 0.050, 0.080) == 1.0
    assert phi_bl(0.0, NU, 0.065) == 1.0  # boundary friction at standstill: mu_sl = mu_bl
    assert mu_sl(1.0) == pytest.approx(0.15)
    speeds = [360.0, 1080.0, 2160.0]
    assert phi_ish(speeds[0], 0.065, NU) > phi_ish(speeds[1], 0.065, NU) > phi_ish(speeds[2], 0.065, NU)
    assert phi_rs(6e-8, 4.4, NU, speeds[0], 0.05, 0.08) > phi_rs(6e-8, 4.4, NU, speeds[2], 0.05, 0.08)


def test_rolling_moment_grows_slower_than_palmgrens_viscous_term():
    # Palmgren's viscous torque grows as (nu n)^(2/3): x6 in speed -> 6^(2/3) = 3.3019.
    # SKF: M_rr ~ (nu n)^0.6 (6^0.6 = 2.9302) before the reductions, which fall with speed.
    R1, R2, R3, *_ = GEOMETRIC_CONSTANTS_SKF["angular_contact"]["single_row"]

    def reduced(n):
        m = torque_bearing_rolling_angular_contact_SKF(R1, R2, R3, 0.065, 25.0, 300.0, NU, n)
        return phi_ish(n, 0.065, NU) * phi_rs(6e-8, 4.4, NU, n, 0.05, 0.08) * m

    assert reduced(2160.0) / reduced(360.0) < 6 ** (2 / 3)


def test_seal_table_rows():
    # Table 4: RSL on deep groove up to 25 mm: no moment; 25-52 mm: 2.25, 0.0018, 0.
    assert seal_constants_SKF("RSL", "deep_groove", 0.022) == (0.0, 0.0, 0.0)
    assert seal_constants_SKF("RSL", "deep_groove", 0.047) == (2.25, 0.0018, 0.0)
    assert seal_constants_SKF("RSH", "deep_groove", 0.052) == (2.25, 0.028, 2.0)
    assert seal_constants_SKF("RS1", "deep_groove", 0.072) == (2.25, 0.018, 20.0)
    assert seal_constants_SKF("RS1", "deep_groove", 0.090) == (2.25, 0.018, 15.0)
    assert seal_constants_SKF("RS1", "angular_contact", 0.080) == (2.0, 0.014, 10.0)


@pytest.mark.parametrize(
    ("seal", "bearing_type", "D", "match"),
    [("RSH", "deep_groove", 0.062, "D = 62 mm"), ("RS1", "angular_contact", 0.026, "30 < D <= 120 mm"),
     ("RSH", "angular_contact", 0.062, "no constants"), ("2RS", "deep_groove", 0.052, "no constants")],
)
def test_seal_table_gaps_are_named(seal, bearing_type, D, match):
    with pytest.raises(ValueError, match=match):
        seal_constants_SKF(seal, bearing_type, D)


def test_seal_moment_hand():
    # RS1 on a 7010 (angular contact, D = 80 mm: beta 2, K_S1 0.014, K_S2 10), d_s = d1 = 57.6 mm
    # (an assumed counterface diameter): 0.014·57.6² + 10 = 0.014·3317.76 + 10 = 56.44864 N·mm.
    beta, k1, k2 = seal_constants_SKF("RS1", "angular_contact", 0.080)
    assert torque_bearing_seal_SKF(k1, beta, k2, 0.0576) == pytest.approx(56.44864e-3, rel=1e-9)
    assert torque_bearing_seal_SKF(k1, beta, k2, 0.0576, 1) == pytest.approx(28.22432e-3, rel=1e-9)
    # RSL above 25 mm outside diameter: the whole value whatever the number of seals.
    assert torque_bearing_seal_SKF(0.0018, 2.25, 0.0, 0.0302, 1, full_value=True) == pytest.approx(
        torque_bearing_seal_SKF(0.0018, 2.25, 0.0, 0.0302, 2))


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: phi_ish(1000.0, 65.0, NU), "metres"),
        (lambda: phi_ish(1000.0, 0.065, 100.0), "m²/s"),
        (lambda: phi_rs(6e-8, 4.4, NU, 1000.0, 0.08, 0.05), "exceed"),
        (lambda: mu_sl(1.5), r"\[0, 1\]"),
        (lambda: torque_bearing_SKF(0.01, 1.2, 0.9, 0.001), "phi_ish"),
        (lambda: torque_bearing_seal_SKF(0.014, 2.0, 10.0, 0.0576, 3), "1 or 2"),
        (lambda: torque_bearing_rolling_deep_groove_SKF(3.9e-7, 1.7, 0.0385, -1.0, 0.0, 7800.0, NU, 1000.0), "Fr"),
    ],
)
def test_bad_input_is_one_clear_error(call, match):
    with pytest.raises(ValueError, match=match):
        call()
