"""Unit tests of feedtherm.physics.screw_nut (sliding trapezoidal-thread model).

Every expected value is a number printed in a source (Shigley Example 8-1, docs/paper-audit.md §1/§5)
or a hand calculation written out step by step below (calculator arithmetic, 8+
significant digits).  None is the code's own output.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest

from feedtherm.physics import screw_nut as sn
from feedtherm.physics.validity import CorrelationRangeWarning

HAND = 1e-6  # rel tolerance for hand calculations

# Default Tr32x10(P5) nut of docs/paper-audit.md §4/§5.
D2 = 0.0295  # pitch diameter [m]
LEAD = 0.010  # lead [m]
BETA = math.radians(15.0)  # flank half angle [rad]
MU = 0.10
FP = 500.0  # split-nut preload [N]
F_LOAD = 25.0  # guideway friction as axial load [N]


# --------------------------------------------------------------------------------------
# Sliding model (docs/paper-audit.md §5, Shigley §8-2)
# --------------------------------------------------------------------------------------

PHI = 0.10748580  # atan(10 / (pi * 29.5)) = atan(0.10790166) rad
RHO = 0.10316011  # atan(0.1 / cos 15°) = atan(0.10352762) rad


def test_helix_angle_tr32x10():
    # pi * d2 = 92.676983 mm; tan(phi) = 10 / 92.676983 = 0.10790166
    # phi = 0.10748580 rad = 6.1584827 deg  (docs/paper-audit.md §4: 6.16 deg)
    phi = sn.helix_angle(LEAD, D2)
    assert phi == pytest.approx(PHI, rel=HAND)
    assert math.degrees(phi) == pytest.approx(6.16, abs=0.005)


def test_helix_angle_accepts_arrays():
    # lead 5 mm: tan(phi) = 5/92.676983 = 0.053950828 -> 0.053898570 rad
    phi = sn.helix_angle(np.array([0.005, 0.010]), D2)
    assert phi == pytest.approx([0.053898570, PHI], rel=HAND)


def test_thread_friction_angle():
    # cos 15° = 0.96592583; 0.1 / 0.96592583 = 0.10352762; atan -> 0.10316011 rad (5.9106°)
    assert sn.friction_angle_thread(MU, BETA) == pytest.approx(RHO, rel=HAND)
    # square thread: rho' = atan(mu) = atan(0.1) = 0.099668652 rad
    assert sn.friction_angle_thread(MU, 0.0) == pytest.approx(0.099668652, rel=HAND)


def test_shigley_example_8_1_square_thread():
    # Shigley Ex. 8-1: d_m = 30 mm, l = 8 mm (double thread, p = 4), f = 0.08, F = 6.4 kN.
    # Printed: T_R = 15.94 N·m (raise), T_L = -0.466 N·m (lower, not self-locking).
    # torque_thread_load is T_R minus the useful F l/(2 pi) = 6400*0.008/(2 pi) = 8.1487331
    F, dm, lead, f = 6400.0, 0.030, 0.008, 0.08
    useful = F * lead / (2.0 * math.pi)
    assert sn.torque_thread_load(F, dm, lead, f, 0.0) + useful == pytest.approx(15.94, rel=1e-3)
    # Split nut: T_R + T_L = 15.94 - 0.466 = 15.474 N·m
    assert sn.torque_thread_preload(F, dm, lead, f, 0.0) == pytest.approx(15.474, rel=1e-3)


def test_load_friction_torque_tr32_hand_and_shigley_rational_form():
    # tan(phi + rho') = tan(0.21064591) = 0.21381779;  tan(phi) = 0.10790166
    # F r2 = 25 * 0.01475 = 0.36875 N·m; [..] = 0.10591613 -> M = 0.039056575 N·m
    M = sn.torque_thread_load(F_LOAD, D2, LEAD, MU, BETA)
    assert M == pytest.approx(0.039056575, rel=HAND)
    # Shigley Eq. 8-1 with sec(alpha): T_R = F d/2 (l + pi f d sec b)/(pi d - f l sec b)
    sec = 1.0 / math.cos(BETA)
    T_R = F_LOAD * D2 / 2 * (LEAD + math.pi * MU * D2 * sec) / (math.pi * D2 - MU * LEAD * sec)
    assert M == pytest.approx(T_R - F_LOAD * LEAD / (2 * math.pi), rel=1e-12)
    # direction of the load is ignored
    assert sn.torque_thread_load(-F_LOAD, D2, LEAD, MU, BETA) == pytest.approx(M, rel=1e-12)


def test_preload_friction_torque_tr32_audit():
    # tan(phi + rho') = 0.21381779; tan(phi - rho') = tan(0.0043256896) = 0.0043257166
    # difference 0.20949207; F_p r2 = 500 * 0.01475 = 7.375 N·m
    # M_p = 7.375 * 0.20949207 = 1.5450040 N·m  (docs/paper-audit.md §5: ~1.55 N·m)
    M = sn.torque_thread_preload(FP, D2, LEAD, MU, BETA)
    assert M == pytest.approx(1.5450040, rel=HAND)
    assert M == pytest.approx(1.55, abs=0.005)


def test_flank_normal_load():
    # sigma cos(b) cos(phi) = 12 * 0.96592583 * 0.99422896 = 11.524217
    # Q_j = 500 / 11.524217 = 43.386895 N
    assert sn.normal_load_flank(500.0, 12, BETA, PHI) == pytest.approx(43.386895, rel=HAND)
    assert sn.normal_load_flank(-500.0, 12, BETA, PHI) == pytest.approx(43.386895, rel=HAND)


def test_grease_shear_torque_petroff():
    # omega at 36 rpm = 2 pi 36/60 = 3.7699112 rad/s; r2^2 = 2.175625e-4 m^2
    # A = pi d2 L = pi * 0.0295 * 0.060 = 5.5606190e-3 m^2; h = 0.3 mm, eta = 1 Pa·s
    # M = 1 * 3.7699112 * 2.175625e-4 * 5.5606190e-3 / 3e-4 = 0.015202571 N·m
    omega = 2 * math.pi * 36 / 60
    M = sn.torque_grease_shear(1.0, omega, D2 / 2, 5.5606190e-3, 3e-4)
    assert M == pytest.approx(0.015202571, rel=HAND)
    M_reverse = sn.torque_grease_shear(1.0, -omega, D2 / 2, 5.5606190e-3, 3e-4)
    assert M_reverse == pytest.approx(M, rel=1e-12)


def test_sliding_screw_torque_audit_default_condition_I():
    # load 0.039056575 + preload 1.5450040 + grease 0.015202571 (eta 1 Pa·s, h 0.3 mm,
    # L 60 mm, 36 rpm, values above) = 1.5992632 N·m
    t = sn.torque_screw_nut_sliding(F_LOAD, FP, D2, LEAD, MU, BETA, 1.0, 3e-4, 0.060, 36.0)
    assert t.load == pytest.approx(0.039056575, rel=HAND)
    assert t.preload == pytest.approx(1.5450040, rel=HAND)
    assert t.grease == pytest.approx(0.015202571, rel=HAND)
    assert t.total == pytest.approx(1.5992632, rel=HAND)
    with pytest.raises(dataclasses.FrozenInstanceError):
        t.total = 0.0


def test_sliding_heat_matches_audit_table_6W_at_36rpm():
    # Coulomb only (eta = 0): M_T = 0.039056575 + 1.5450040 = 1.5840606 N·m (docs/paper-audit.md: 1.58)
    # H = 1.5840606 * 3.7699112 = 5.9717678 W (docs/paper-audit.md: 6.0 W); preload only: 5.8245280 W
    t = sn.torque_screw_nut_sliding(F_LOAD, FP, D2, LEAD, MU, BETA, 0.0, 3e-4, 0.060, 36.0)
    assert t.total == pytest.approx(1.5840606, rel=HAND)
    H = sn.heat_screw_nut(t.total, 396.0, 360.0)
    assert H == pytest.approx(5.9717678, rel=HAND)
    assert H == pytest.approx(6.0, abs=0.05)
    assert sn.heat_screw_nut(t.preload, 396.0, 360.0) == pytest.approx(5.8245280, rel=HAND)
    # condition III, n_T = 54 rpm: 1.5840606 * 5.6548668 = 8.9576518 W (docs/paper-audit.md: 9.0 W)
    assert sn.heat_screw_nut(t.total, 2214.0, 2160.0) == pytest.approx(8.9576518, rel=HAND)


@pytest.mark.parametrize(
    "mu, expected_W",
    [
        # mu 0.08: rho' = 0.082633497, tan(phi+rho') = 0.19244355, tan(phi-rho') = 0.024857420
        # M = 7.375*0.16758613 + 0.36875*0.084541893 = 1.2359477 + 0.031174823 = 1.2671225
        # H = 1.2671225 * 3.7699112 = 4.7769394 W (docs/paper-audit.md: 4.8)
        (0.08, 4.7769394),
        # mu 0.15: rho' = 0.15406088, tan(..+) = 0.26767836, tan(..-) = -0.046608785
        # M = 7.375*0.31428714 + 0.36875*0.15977670 = 2.3178677 + 0.058917658 = 2.3767853
        # H = 2.3767853 * 3.7699112 = 8.9602696 W (docs/paper-audit.md: 9.0)
        (0.15, 8.9602696),
    ],
)
def test_sliding_heat_audit_mu_range(mu, expected_W):
    t = sn.torque_screw_nut_sliding(F_LOAD, FP, D2, LEAD, mu, BETA, 0.0, 3e-4, 0.060, 36.0)
    assert sn.heat_screw_nut(t.total, 396.0, 360.0) == pytest.approx(expected_W, rel=HAND)


def test_screw_nut_heat_uses_relative_speed():
    # Eq. 23 as printed, M in N·mm: 1584.0606 * 36 / 9550 = 5.9713280 W (1/9550 vs 2pi/60e3)
    assert sn.heat_screw_nut(1.5840606, 396.0, 360.0) == pytest.approx(5.9713280, rel=1e-4)
    assert sn.heat_screw_nut(1.5840606, 360.0, 396.0) == pytest.approx(5.9717678, rel=HAND)
    assert sn.heat_screw_nut(1.5840606, 360.0, 360.0) == 0.0
    # opposite senses add: |300 - (-60)| = 360 rpm -> 1.5840606 * 37.699112 = 59.717678 W
    assert sn.heat_screw_nut(1.5840606, 300.0, -60.0) == pytest.approx(59.717678, rel=HAND)


# --------------------------------------------------------------------------------------
# Validity and argument errors
# --------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "call",
    [
        lambda: sn.helix_angle(0.0, D2),
        lambda: sn.helix_angle(LEAD, -D2),
        lambda: sn.torque_thread_load(25.0, 0.0, LEAD, MU, BETA),
        lambda: sn.torque_grease_shear(1.0, 3.0, D2 / 2, 5e-3, 0.0),
        lambda: sn.torque_screw_nut_sliding(25.0, FP, D2, LEAD, MU, BETA, 1.0, 3e-4, 0.0, 36.0),
        lambda: sn.torque_thread_preload(-10.0, D2, LEAD, MU, BETA),
        lambda: sn.friction_angle_thread(-0.1, BETA),
    ],
)
def test_nonpositive_sizes_and_negative_loads_raise(call):
    with pytest.raises(ValueError, match="must"):
        call()


@pytest.mark.parametrize(
    "mu, beta",
    [(0.6, BETA), (0.0, BETA), (MU, math.radians(45.0)), (MU, math.radians(-5.0))],
)
def test_out_of_range_friction_and_flank_angle_warn(mu, beta):
    with pytest.warns(CorrelationRangeWarning):
        sn.friction_angle_thread(mu, beta)


def test_in_range_inputs_do_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sn.torque_screw_nut_sliding(
            F_LOAD, FP, D2, LEAD, 0.5, math.radians(44.9), 1.0, 3e-4, 0.06, 36.0)


def test_frictionless_limit_is_zero_but_warns():
    with pytest.warns(CorrelationRangeWarning, match="mu"):
        assert sn.torque_thread_preload(FP, D2, LEAD, 0.0, BETA) == 0.0
