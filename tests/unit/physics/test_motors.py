"""Servo-motor heat (paper Eq. 14, corrected and as printed).

Expected values are paper Table 1 numbers or hand calculations in the comments.
ω(396) = 2π·396/60 = 41.4690 rad/s; ω(360) = 37.6991 rad/s.
"""

from __future__ import annotations

import numpy as np
import pytest

from feedtherm.physics.motors import heat_motor, heat_motor_paper, power_motor_output


def test_output_power_hand():
    # 0.30 N·m · 41.4690 rad/s = 12.4407 W; sign of torque and speed ignored.
    assert power_motor_output(0.30, 396.0) == pytest.approx(12.4407, rel=1e-5)
    assert power_motor_output(-0.30, -396.0) == pytest.approx(12.4407, rel=1e-5)


def test_output_power_rated_servo():
    # docs/paper-audit.md §4 motor: 400 W servo, rated 1.27 N·m -> rated speed 400/1.27 = 315 rad/s
    # = 3008 rpm (a 3000-rpm servo). 1.27 · 2π·3000/60 = 1.27 · 314.159 = 398.98 W.
    assert power_motor_output(1.27, 3000.0) == pytest.approx(398.98, rel=1e-4)


@pytest.mark.parametrize(("n_rpm", "table1_W"), [(396.0, 1.87), (360.0, 1.70)])
def test_paper_form_reproduces_table1(n_rpm, table1_W):
    # docs/paper-audit.md §4: M_m = 0.30 N·m = 300 N·mm, δ = 0.85.
    # Screw motor: 300·396/9550·0.15 = 1.8660 W; nut motor: 300·360/9550·0.15 = 1.6963 W.
    assert heat_motor_paper(0.30, n_rpm, 0.85) == pytest.approx(table1_W, abs=5e-3)


def test_table1_implies_equal_Mm_times_1_minus_delta():
    # docs/paper-audit.md §1 row 14: 1.87·9550/396 = 45.10 N·mm and 1.70·9550/360 = 45.10 N·mm.
    assert 1.87 * 9550 / 396 == pytest.approx(45.10, abs=0.01)
    assert 1.70 * 9550 / 360 == pytest.approx(45.10, abs=0.01)
    # Heat ratio equals the speed ratio: 1.87/1.70 = 1.1 = 396/360.
    ratio = heat_motor_paper(0.30, 396.0, 0.85) / heat_motor_paper(0.30, 360.0, 0.85)
    assert ratio == pytest.approx(396 / 360, rel=1e-12)
    assert 1.87 / 1.70 == pytest.approx(396 / 360, rel=1e-3)


def test_corrected_loss_hand_and_vs_printed():
    # P_out = 12.4407 W; corrected loss = 12.4407·(1/0.85 − 1) = 12.4407·0.176471 = 2.1954 W,
    # printed (1 − δ) form = 12.4407·0.15 = 1.8661 W (with exact 2π/60; 1.8660 with 9550).
    corrected = heat_motor(0.30, 396.0, 0.85)
    assert corrected == pytest.approx(2.1954, rel=1e-4)
    printed = heat_motor_paper(0.30, 396.0, 0.85)
    # The two differ by the factor 1/η (up to the rounded 9550 vs 9549.3: 7e-5).
    assert corrected / printed == pytest.approx(1 / 0.85, rel=1e-4)


def test_corrected_loss_is_input_minus_output():
    # Energy balance: P_in = P_out/η = 12.4407/0.85 = 14.6361 W; loss = 14.6361 − 12.4407.
    assert heat_motor(0.30, 396.0, 0.85) == pytest.approx(14.6361 - 12.4407, rel=1e-4)


def test_efficiency_that_reproduces_table1_with_corrected_form():
    # 1/η − 1 = 0.15 -> η = 1/1.15 = 0.869565 gives 12.4407·0.15 = 1.866 W (Table 1: 1.87).
    assert heat_motor(0.30, 396.0, 1 / 1.15) == pytest.approx(1.87, abs=5e-3)


def test_unit_efficiency_gives_zero_loss():
    assert heat_motor(0.30, 396.0, 1.0) == 0.0
    assert heat_motor_paper(0.30, 396.0, 1.0) == 0.0


def test_arrays():
    np.testing.assert_allclose(
        heat_motor_paper(0.30, np.array([396.0, 360.0]), 0.85), [1.8660, 1.6963], rtol=1e-4
    )


@pytest.mark.parametrize("eta", [0.0, -0.1, 1.2, float("nan")])
@pytest.mark.parametrize("func", [heat_motor, heat_motor_paper])
def test_efficiency_outside_0_1_rejected(func, eta):
    with pytest.raises(ValueError, match="efficiency"):
        func(0.30, 396.0, eta)


def test_generator_loss_is_input_power_times_one_minus_eta():
    # Hand calculation: a nut motor braked by 1.5 N·m at 360 rpm.
    # omega = 360 * 2*pi/60 = 37.699 rad/s; P_in = 1.5 * 37.699 = 56.549 W
    # loss = 56.549 * (1 - 0.85) = 8.482 W
    from feedtherm.physics.motors import heat_motor_braking

    assert heat_motor_braking(-1.5, 360.0, 0.85) == pytest.approx(1.5 * 360 * 2 * 3.141592653589793 / 60 * 0.15, rel=1e-12)
    assert heat_motor_braking(1.5, 360.0, 0.85) == pytest.approx(8.4823, rel=1e-4)
