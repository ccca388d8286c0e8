"""Palmgren bearing friction (paper Eqs. 15–22, corrected).

Every expected value is either printed in the paper / docs/paper-audit.md or worked out by hand in
the comments next to it; none is the code's own output.  Notation in the comments:
ω(n) = 2π n / 60; ω(396) = 41.4690 rad/s, ω(360) = 37.6991, ω(1116) = 116.867,
ω(2214) = 231.850, ω(1080) = 113.097, ω(2160) = 226.195.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest

from feedtherm.physics.bearings import (
    F0_TYPICAL,
    BearingTorque,
    P1_angular_contact_Palmgren,
    P1_deep_groove_Palmgren,
    f1_angular_contact_Palmgren,
    f1_deep_groove_Palmgren,
    heat_bearing,
    torque_bearing_load_Palmgren,
    torque_bearing_Palmgren,
    torque_bearing_viscous_Palmgren,
)

NU_100 = 100e-6  # 100 mm²/s in m²/s
DM_25x62 = 0.0435  # (25 + 62)/2 mm
DM_7010 = 0.065  # (50 + 80)/2 mm
DM_6205 = 0.0385  # (25 + 52)/2 mm


def _no_warnings(func, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return func(*args, **kwargs)


# ----------------------------------------------------------------------- f1 (Eqs. 17, 19)


def test_f1_angular_contact_front_pair_audit():
    # docs/paper-audit.md §3 back-out, front 25x62 pair: P0 ≈ Fa = 3100 N, C0 = 40 kN -> f1 = 4.3e-4.
    # P0/C0 = 0.0775; ln 0.0775 = -2.5575; ×0.33 = -0.8440; e^-0.8440 = 0.4300.
    assert _no_warnings(f1_angular_contact_Palmgren, 3100.0, 40e3) == pytest.approx(
        4.300e-4, rel=1e-3
    )


def test_f1_angular_contact_rear_pair_audit():
    # docs/paper-audit.md §3: rear pair Fa = 2.7 kN -> f1 = 4.1e-4.
    # 2700/40000 = 0.0675; ln = -2.6956; ×0.33 = -0.8895; e^ = 0.4108.
    assert f1_angular_contact_Palmgren(2700.0, 40e3) == pytest.approx(4.108e-4, rel=1e-3)


def test_f1_deep_groove_default_z_hand():
    # P0/C0 = 0.25: 0.25^0.55 = e^(0.55 ln 0.25) = e^(-0.76246) = 0.46652; × 5e-4.
    assert f1_deep_groove_Palmgren(1950.0, 7800.0) == pytest.approx(2.3326e-4, rel=1e-4)


def test_f1_deep_groove_correction_vs_printed_eq19():
    # Printed Eq. 19: 9e-4 (P0/C0)^0.55. Corrected default: 5e-4 (same exponent).
    # 6205 (C0 = 7.8 kN) at P0 = 2500 N: (2500/7800)^0.55 = 0.32051^0.55 = 0.53483.
    printed = 9e-4 * (2500.0 / 7800.0) ** 0.55  # = 4.813e-4
    corrected = f1_deep_groove_Palmgren(2500.0, 7800.0)
    assert corrected == pytest.approx(2.674e-4, rel=1e-3)
    assert printed / corrected == pytest.approx(1.8, rel=1e-12)  # 9/5


def test_f1_deep_groove_printed_coefficient_is_outside_tabulated_range():
    with pytest.warns(UserWarning, match="z = 0.0009"):
        f1_deep_groove_Palmgren(2500.0, 7800.0, z=9e-4)
    for z in (4e-4, 6e-4):  # ends of Harris's range: no warning
        _no_warnings(f1_deep_groove_Palmgren, 2500.0, 7800.0, z=z)


def test_f1_ratio_outside_0_1_warns():
    with pytest.warns(UserWarning, match="P0/C0 = 1.5"):
        f1_angular_contact_Palmgren(60e3, 40e3)
    with pytest.warns(UserWarning, match="P0/C0 = 0 "):
        assert f1_angular_contact_Palmgren(0.0, 40e3) == 0.0
    _no_warnings(f1_angular_contact_Palmgren, 40e3, 40e3)  # P0/C0 = 1 is inside


@pytest.mark.parametrize(("P0", "C0"), [(100.0, 0.0), (100.0, -5.0), (-1.0, 40e3)])
def test_f1_rejects_bad_loads(P0, C0):
    with pytest.raises(ValueError, match="P0|C0"):
        f1_angular_contact_Palmgren(P0, C0)


def test_f1_deep_groove_rejects_nonpositive_z():
    with pytest.raises(ValueError, match="z"):
        f1_deep_groove_Palmgren(100.0, 7800.0, z=0.0)


# ----------------------------------------------------------------------- P1 (Eqs. 18, 20)


def test_P1_angular_contact_front_pair():
    # 1.4·3100 − 0.1·50 = 4340 − 5 = 4335 N (> Fr).
    assert P1_angular_contact_Palmgren(3100.0, 50.0) == pytest.approx(4335.0)


@pytest.mark.parametrize(
    ("Fa", "Fr", "printed", "expected"),
    [
        (0.0, 50.0, -5.0, 50.0),  # printed 1.4·0 − 0.1·50 = −5 N: a negative load
        (100.0, 1000.0, 40.0, 1000.0),  # printed 140 − 100 = 40 N < Fr
    ],
)
def test_P1_angular_contact_rule_P1_at_least_Fr(Fa, Fr, printed, expected):
    assert 1.4 * Fa - 0.1 * Fr == pytest.approx(printed)  # Eq. 18 as printed
    assert P1_angular_contact_Palmgren(Fa, Fr) == pytest.approx(expected)


def test_P1_deep_groove_loaded_and_floating():
    # docs/paper-audit.md 6205 row: 3·2500 − 0.1·50 = 7495 N.
    assert P1_deep_groove_Palmgren(2500.0, 50.0) == pytest.approx(7495.0)
    # Floating rear bearing, Fa = 0, Fr = 50 N: printed Eq. 20 gives −5 N; rule gives Fr.
    assert P1_deep_groove_Palmgren(0.0, 50.0) == pytest.approx(50.0)


def test_P1_vectorised_and_rejects_negative_load():
    np.testing.assert_allclose(
        P1_deep_groove_Palmgren([0.0, 2500.0], [50.0, 50.0]), [50.0, 7495.0]
    )
    with pytest.raises(ValueError, match="Fa"):
        P1_deep_groove_Palmgren(-1.0, 50.0)
    with pytest.raises(ValueError, match="Fr"):
        P1_angular_contact_Palmgren(1.0, float("nan"))


# ----------------------------------------------------------------------- M_l (Eq. 16)


def test_load_torque_front_pair_audit():
    # docs/paper-audit.md: M_l = 81 N·mm. f1 = 4.300e-4, P1 = 4335 N, dm = 43.5 mm:
    # 4.300e-4 · 4335 · 43.5 = 81.09 N·mm = 0.08109 N·m.
    assert torque_bearing_load_Palmgren(4.300e-4, 4335.0, DM_25x62) == pytest.approx(0.08109, rel=1e-3)


def test_load_torque_6205_given_audit_f1():
    # docs/paper-audit.md 6205 row: f1 = 3.3e-4, P1 = 7495 N, dm = 38.5 mm -> 3.3e-4·7495·38.5 = 95.2 N·mm.
    assert torque_bearing_load_Palmgren(3.3e-4, 7495.0, DM_6205) == pytest.approx(0.0952, rel=1e-3)


@pytest.mark.parametrize("dm", [0.0, -0.01, 43.5])
def test_load_torque_rejects_bad_dm(dm):
    # 43.5 is a mean diameter in mm passed as metres.
    with pytest.raises(ValueError, match="dm"):
        torque_bearing_load_Palmgren(4e-4, 4335.0, dm)


# ----------------------------------------------------------------------- M_v (Eqs. 21–22)


def test_viscous_torque_front_pair_audit():
    # docs/paper-audit.md: M_v = 38 N·mm. ν n = 100·396 = 39600; 39600^(2/3) = e^(2/3·10.58658) = 1161.80;
    # dm³ = 43.5³ = 82312.9; 1e-7 · 4 · 1161.80 · 82312.9 = 38.252 N·mm.
    assert torque_bearing_viscous_Palmgren(4.0, NU_100, 396.0, DM_25x62) == pytest.approx(
        0.038252, rel=1e-4
    )


def test_viscous_torque_eq21_printed_lacks_cube():
    # Printed Eq. 21 (dm, not dm³): 1e-7·4·1161.8·43.5 = 0.0202 N·mm (docs/paper-audit.md: "0.02").
    printed_Nmm = 1e-7 * 4.0 * (100.0 * 396.0) ** (2.0 / 3.0) * 43.5
    assert printed_Nmm == pytest.approx(0.0202, rel=2e-3)
    corrected_Nmm = torque_bearing_viscous_Palmgren(4.0, NU_100, 396.0, DM_25x62) * 1e3
    assert corrected_Nmm / printed_Nmm == pytest.approx(43.5**2)  # the missing dm²


def test_viscous_torque_low_regime_and_printed_eq22():
    # ν = 10 mm²/s, n = 100 rpm: ν n = 1000 < 2000 -> 160e-7 f0 dm³.
    # 6205, f0 = 2: 160e-7 · 2 · 38.5³ = 160e-7 · 2 · 57066.6 = 1.8261 N·mm.
    m_v = torque_bearing_viscous_Palmgren(2.0, 10e-6, 100.0, DM_6205)
    assert m_v == pytest.approx(1.8261e-3, rel=1e-4)
    printed_Nmm = 160.0 * 2.0 * 38.5**3  # Eq. 22 as printed: 1.83e7 N·mm (18 kN·m)
    assert printed_Nmm / (m_v * 1e3) == pytest.approx(1e7)


def test_viscous_torque_regime_boundary():
    # ν n = 2000 exactly (ν = 20 mm²/s, n = 100 rpm) belongs to Eq. 21:
    # 2000^(2/3) = 158.74, so M_v = 1e-7 · 1 · 158.74 · 1e6 (dm = 100 mm) = 15.874 N·mm.
    at = torque_bearing_viscous_Palmgren(1.0, 20e-6, 100.0, 0.1)
    assert at == pytest.approx(15.874e-3, rel=1e-4)
    # Just below: 160e-7 · 1e6 = 16.0 N·mm. The branches differ by only 0.8 %.
    below = torque_bearing_viscous_Palmgren(1.0, 20e-6, 99.99, 0.1)
    assert below == pytest.approx(16.0e-3, rel=1e-12)


def test_viscous_torque_speed_sign_and_array():
    # Direction does not matter; arrays evaluate element-wise (front pair at I and III):
    # III: 100·2214 = 221400; ^(2/3) = 3659.75; 4e-7·3659.75·82312.9 = 120.50 N·mm.
    m = torque_bearing_viscous_Palmgren(4.0, NU_100, np.array([-396.0, 2214.0]), DM_25x62)
    np.testing.assert_allclose(m, [0.038252, 0.12050], rtol=1e-4)


def test_viscous_torque_rejects_unit_slips():
    with pytest.raises(ValueError, match="m²/s"):
        torque_bearing_viscous_Palmgren(4.0, 100.0, 396.0, DM_25x62)  # 100 mm²/s passed as m²/s
    with pytest.raises(ValueError, match="nu"):
        torque_bearing_viscous_Palmgren(4.0, -1e-4, 396.0, DM_25x62)
    with pytest.raises(ValueError, match="f0"):
        torque_bearing_viscous_Palmgren(-1.0, NU_100, 396.0, DM_25x62)


# ----------------------------------------------------------------------- totals and heat


def test_bearing_torque_dataclass():
    t = torque_bearing_Palmgren(4.300e-4, 4335.0, DM_25x62, 4.0, NU_100, 396.0)
    assert isinstance(t, BearingTorque)
    assert t.total == pytest.approx(t.load + t.viscous)
    with pytest.raises(dataclasses.FrozenInstanceError):
        t.total = 0.0  # type: ignore[misc]


@pytest.mark.parametrize(
    ("heat_W", "n_rpm", "torque_Nmm"),
    [(4.95, 396.0, 119.4), (5.31, 360.0, 140.9), (4.36, 396.0, 105.1)],
)
def test_required_torques_from_table1(heat_W, n_rpm, torque_Nmm):
    # docs/paper-audit.md §3: M = H / ω. 4.95/41.4690 = 0.11937; 5.31/37.6991 = 0.14085;
    # 4.36/41.4690 = 0.10514 N·m. (docs/paper-audit.md §3: the review's 105.2 for the rear uses the
    # paper's rounded 1.047e-4, 4.36/(1.047e-4·396) = 105.16; exact 2π/60 gives 105.14.)
    assert heat_bearing(torque_Nmm * 1e-3, n_rpm) == pytest.approx(heat_W, rel=1e-3)


def test_front_pair_reproduces_table1_and_speed_scaling():
    # docs/paper-audit.md back-out, front 25x62 pair, Fa = 3.1 kN: M = 81.09 + 38.25 = 119.34 N·mm
    # -> H(I) = 0.11934 · 41.469 = 4.949 W (Table 1: 4.95).
    # II: M_v = 4e-7·(111600)^(2/3)·82312.9 = 4e-7·2317.98·82312.9 = 76.32;
    #     (81.09 + 76.32)·116.867e-3 = 18.40 W.  III: (81.09 + 120.50)·231.850e-3 = 46.74 W.
    f1 = f1_angular_contact_Palmgren(3100.0, 40e3)
    P1 = P1_angular_contact_Palmgren(3100.0, 50.0)
    t = torque_bearing_Palmgren(f1, P1, DM_25x62, 4.0, NU_100, 396.0)
    assert t.load == pytest.approx(0.081, abs=1e-3)  # docs/paper-audit.md 81 N·mm
    assert t.viscous == pytest.approx(0.038, abs=1e-3)  # docs/paper-audit.md 38 N·mm
    assert heat_bearing(t, 396.0) == pytest.approx(4.95, rel=2e-3)
    for n, expected in ((1116.0, 18.4), (2214.0, 46.7)):  # docs/paper-audit.md: 18.4 / 46.7 W
        tn = torque_bearing_Palmgren(f1, P1, DM_25x62, 4.0, NU_100, n)
        assert heat_bearing(tn.total, n) == pytest.approx(expected, rel=2e-3)


def test_rear_pair_reproduces_table1():
    # Fa = 2.7 kN: f1 = 4.108e-4, P1 = 3775 N, M_l = 4.108e-4·3775·43.5 = 67.46 N·mm;
    # H = (67.46 + 38.25)·41.469e-3 = 4.384 W (Table 1: 4.36; docs/paper-audit.md: 4.4).
    f1 = f1_angular_contact_Palmgren(2700.0, 40e3)
    t = torque_bearing_Palmgren(f1, P1_angular_contact_Palmgren(2700.0, 50.0), DM_25x62,
                                4.0, NU_100, 396.0)
    assert heat_bearing(t, 396.0) == pytest.approx(4.36, rel=1e-2)


def test_nut_pair_at_nut_speed_reproduces_table1():
    # docs/paper-audit.md nut 7010 DB pair, Fa = 0.84 kN, f1 = 2.8e-4 (implies C0 ≈ 39.8 kN):
    # P1 = 1.4·840 − 5 = 1171 N; M_l = 2.8e-4·1171·65 = 21.31 N·mm (docs/paper-audit.md 21).
    # M_v = 4e-7·(36000)^(2/3)·65³ = 4e-7·1090.3·274625 = 119.77 N·mm (docs/paper-audit.md 120).
    # At the nut speed 360 rpm: 141.08·37.6991e-3 = 5.319 W (Table 1: 5.31).
    # II (1080): M_v = 4e-7·2269.5·274625 = 249.3; (21.31 + 249.3)·113.097e-3 = 30.6 W.
    # III (2160): M_v = 4e-7·3603.0·274625 = 395.8; 417.1·226.195e-3 = 94.3 W
    # (docs/paper-audit.md §3; the review: 94.2).
    P1 = P1_angular_contact_Palmgren(840.0, 50.0)
    t = torque_bearing_Palmgren(2.8e-4, P1, DM_7010, 4.0, NU_100, 360.0)
    assert t.load == pytest.approx(0.021, abs=1e-3)
    assert t.viscous == pytest.approx(0.120, abs=1e-3)
    assert heat_bearing(t, 360.0) == pytest.approx(5.31, rel=3e-3)
    for n, expected in ((1080.0, 30.6), (2160.0, 94.2)):
        tn = torque_bearing_Palmgren(2.8e-4, P1, DM_7010, 4.0, NU_100, n)
        assert heat_bearing(tn, n) == pytest.approx(expected, rel=2e-3)


def test_rear_6205_audit_row_uses_printed_z():
    # docs/paper-audit.md row "Rear: 6205 via Eqs. 19–20": f1 = 3.3e-4, M_l 95 / M_v 10, H 4.4/13.4/29.3.
    # M_v = 1.5e-7·1161.8·38.5³ = 1.5e-7·1161.8·57066.6 = 9.945 N·mm.
    # H(I) = (95.22 + 9.945)·41.469e-3 = 4.361 W; II: M_v = 1.5e-7·2317.98·57066.6 = 19.84,
    # 115.07·116.867e-3 = 13.45 W; III: M_v = 31.33, 126.55·231.850e-3 = 29.34 W.
    for n, expected in ((396.0, 4.36), (1116.0, 13.45), (2214.0, 29.34)):
        t = torque_bearing_Palmgren(3.3e-4, 7495.0, DM_6205, 1.5, NU_100, n)
        assert heat_bearing(t, n) == pytest.approx(expected, rel=2e-3)
    # But f1 = 3.3e-4 is not the corrected Eq. 19: with z = 5e-4, C0 = 7.8 kN and P0 = Fa
    # it is 5e-4·0.53483 = 2.674e-4.  3.3e-4 follows from the *printed* z = 9e-4 with
    # P0 = 0.6Fr + 0.5Fa = 1280 N: 9e-4·(1280/7800)^0.55 = 9e-4·0.3701 = 3.331e-4.
    assert f1_deep_groove_Palmgren(2500.0, 7800.0) == pytest.approx(2.674e-4, rel=1e-3)
    with pytest.warns(UserWarning, match="z"):
        assert f1_deep_groove_Palmgren(1280.0, 7800.0, z=9e-4) == pytest.approx(
            3.331e-4, rel=1e-3
        )


@pytest.mark.parametrize(
    ("label", "Fa", "Fr", "C0", "dm", "f0", "n", "deep", "expected_W"),
    [
        # 25x62 pair, Fa = 2.15 kN: f1 = 1e-3·0.05375^0.33 = 3.811e-4, P1 = 3005 N,
        # M_l = 49.81, M_v = 38.25 -> 88.07 N·mm · 41.469e-3 = 3.652 W (docs/paper-audit.md 3.65).
        ("25x62 2.15 kN", 2150.0, 50.0, 40e3, DM_25x62, 4.0, 396.0, False, 3.65),
        # Fa = 3.15 kN: f1 = 4.323e-4, P1 = 4405, M_l = 82.83 -> 121.08 · 41.469e-3 = 5.02.
        ("25x62 3.15 kN", 3150.0, 50.0, 40e3, DM_25x62, 4.0, 396.0, False, 5.0),
        # 6205 floating, Fr = 50 N, P0 = Fr: f1 = 5e-4·(50/7800)^0.55 = 3.110e-5, P1 = 50,
        # M_l = 0.060, M_v = 9.945 -> 10.005 · 41.469e-3 = 0.415 W (docs/paper-audit.md 0.41).
        ("6205 floating", 0.0, 50.0, 7800.0, DM_6205, 1.5, 396.0, True, 0.41),
        # 7205 DB pair, 300 N preload, C0 = 2·10 kN (assumed catalogue value):
        # f1 = 1e-3·0.015^0.33 = 2.496e-4, P1 = 415, M_l = 3.99; M_v = 4e-7·1161.8·57066.6
        # = 26.52 -> 30.52 · 41.469e-3 = 1.265 W (docs/paper-audit.md 1.27).
        ("7205 DB", 300.0, 50.0, 20e3, DM_6205, 4.0, 396.0, False, 1.27),
        # 7010 single, 300 N, C0 ≈ 20 kN (assumed), f0 = 2, 360 rpm: M_l = 6.75,
        # M_v = 2e-7·1090.3·274625 = 59.88 -> 66.63 · 37.6991e-3 = 2.512 W (docs/paper-audit.md 2.5).
        ("7010 single", 300.0, 50.0, 20e3, DM_7010, 2.0, 360.0, False, 2.5),
    ],
)
def test_audit_typical_bearings(label, Fa, Fr, C0, dm, f0, n, deep, expected_W):
    P0 = max(Fa, Fr)  # docs/paper-audit.md's P0 ≈ Fa (≥ Fr for the floating bearing)
    if deep:
        f1, P1 = f1_deep_groove_Palmgren(P0, C0), P1_deep_groove_Palmgren(Fa, Fr)
    else:
        f1, P1 = f1_angular_contact_Palmgren(P0, C0), P1_angular_contact_Palmgren(Fa, Fr)
    t = torque_bearing_Palmgren(f1, P1, dm, f0, NU_100, n)
    assert heat_bearing(t, n) == pytest.approx(expected_W, rel=1.2e-2), label


def test_nut_pair_cannot_reach_table1_at_200_cst():
    # docs/paper-audit.md: "with ν = 200 mm²/s the required preloads fall by 15–25 %". For the nut pair
    # the viscous torque alone then exceeds the required 140.9 N·mm:
    # 4e-7·(200·360)^(2/3)·65³ = 4e-7·1730.8·274625 = 190.1 N·mm.
    m_v = torque_bearing_viscous_Palmgren(4.0, 200e-6, 360.0, DM_7010)
    assert m_v == pytest.approx(0.1901, rel=1e-3)
    assert m_v > 5.31 / (2 * math.pi * 360 / 60)


def test_bearing_heat_zero_at_standstill_and_sign():
    # 0.1 N·m at ±600 rpm: 0.1 · 62.832 = 6.2832 W either way; standstill: 0 W.
    assert heat_bearing(0.1, -600.0) == pytest.approx(6.2832, rel=1e-4)
    assert heat_bearing(torque_bearing_Palmgren(4e-4, 4335.0, DM_25x62, 4.0, NU_100, 0.0),
                        0.0) == 0.0


def test_f0_typical_values():
    # docs/paper-audit.md §3: f0 = 2 per angular-contact bearing, 4 per pair, 1.5 deep groove (grease);
    # Harris: deep groove with grease 0.7–2; a pair takes twice the single-row f0.
    assert F0_TYPICAL["angular_contact_single"]["grease"] == 2.0
    assert F0_TYPICAL["angular_contact_pair"]["grease"] == 4.0
    assert F0_TYPICAL["deep_groove"]["grease"] == 1.5
    assert 0.7 <= F0_TYPICAL["deep_groove"]["grease"] <= 2.0
    for lub, value in F0_TYPICAL["angular_contact_single"].items():
        assert F0_TYPICAL["angular_contact_pair"][lub] == pytest.approx(2 * value)


# --------------------------------------------------------------------------- constant coefficient of friction


def test_constant_friction_torque_by_hand():
    from feedtherm.physics.bearings import torque_bearing_constant_friction

    # SKF catalogue estimate M = 0.5 mu P d: a 25 mm bore angular contact bearing (mu = 0.0020,
    # the table's single-row value) at P = 3175 N: 0.5 * 0.0020 * 3175 * 0.025 = 0.079375 N m.
    assert torque_bearing_constant_friction(0.0020, 3175.0, 0.025) == pytest.approx(0.079375, rel=1e-12)
    # a 6205 (d = 25 mm, deep groove mu = 0.0010) at 1000 N: 0.5 * 0.001 * 1000 * 0.025 = 0.0125 N m
    assert torque_bearing_constant_friction(0.0010, 1000.0, 0.025) == pytest.approx(0.0125, rel=1e-12)
    # proportional to the load, independent of nothing else
    loads = np.array([0.0, 1000.0, 2000.0])
    assert np.allclose(torque_bearing_constant_friction(0.002, loads, 0.025), [0.0, 0.025, 0.05])


@pytest.mark.parametrize("args, match", [((0.0, 1000.0, 0.025), "mu"), ((0.002, -1.0, 0.025), "P"),
                                          ((0.002, 1000.0, 25.0), "bore"), ((0.5, 1000.0, 0.025), "coefficient")])
def test_constant_friction_refuses_what_is_not_a_bearing(args, match):
    from feedtherm.physics.bearings import torque_bearing_constant_friction

    with pytest.raises(ValueError, match=match):
        torque_bearing_constant_friction(*args)
