"""Servo-motor losses from data-sheet values: copper loss from the torque, no-load loss from the speed.

The motors and their numbers:
- WITTENSTEIN alpha premo 320 V (operating manual rev. 02, 4022-D045530, Tbl-16), stator 2C:
  K_t = 0.39 N·m/A r.m.s., K_e = 23.7 V r.m.s./krpm (line to line), connection resistance
  R_tt = 5.70 Ω, continuous stall torque T_0 = 1.17 N·m at I_0 = 2.96 A; stator 1C: K_t = 0.35,
  K_e = 21.0, R_tt = 15.1 Ω, T_0 = 0.60 N·m, I_0 = 1.73 A.
- AMETEK Pittman 14204S004: friction torque T_F = 1.1e-2 N·m, viscous damping D = 1.2e-5 N·m·s,
  no-load speed 3702 rpm (388 rad/s).
Every expected value is worked out by hand below.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from feedtherm.physics.servo_motor import (
    resistance_winding_copper,
    heat_motor_copper,
    heat_motor_copper_rated,
    heat_motor_no_load,
)
from feedtherm.physics.validity import CorrelationRangeWarning


def test_premo_torque_constant_is_per_amp_rms_of_a_sinusoidal_three_phase_motor():
    # The formula's I is the r.m.s. line current: a sinusoidal motor has k_T = sqrt(3) K_e,LL,rms
    # in V s/rad.  2C: 23.7 V/krpm = 23.7/104.71976 = 0.226318 V s/rad, x 1.7320508 = 0.39199;
    # 1C: 21.0/104.71976 = 0.200535, x 1.7320508 = 0.34734 (data sheet: 0.39 and 0.35).
    assert math.sqrt(3) * 23.7 / (1000 * 2 * math.pi / 60) == pytest.approx(0.39, abs=0.005)
    assert math.sqrt(3) * 21.0 / (1000 * 2 * math.pi / 60) == pytest.approx(0.35, abs=0.005)


def test_copper_loss_of_premo_2c_at_its_continuous_stall_torque():
    # I = 1.17/0.39 = 3.0 A; P = 1.5 * 3.0^2 * 5.70 = 76.95 W.
    assert heat_motor_copper(1.17, 0.39, 5.70) == pytest.approx(76.95, rel=1e-12)
    # From the data sheet's stall current instead: 1.5 * 2.96^2 * 5.70 = 1.5 * 8.7616 * 5.70
    # = 74.9117 W: the two agree within the rounding of K_t (2.96 * 0.39 = 1.154 vs 1.17 N m).
    assert heat_motor_copper(2.96 * 0.39, 0.39, 5.70) == pytest.approx(74.9117, rel=1e-5)


def test_copper_loss_of_premo_1c_at_its_continuous_stall_torque():
    # I = 0.60/0.35 = 1.7142857 A, I^2 = 2.9387755; P = 1.5 * 2.9387755 * 15.1 = 66.563265 W.
    assert heat_motor_copper(0.60, 0.35, 15.1) == pytest.approx(66.563265, rel=1e-7)


def test_copper_loss_grows_with_the_square_of_the_torque_and_ignores_its_sign():
    # A braking motor carries the same current in the same windings.
    base = heat_motor_copper(1.17, 0.39, 5.70)
    assert heat_motor_copper(-1.17, 0.39, 5.70) == pytest.approx(base, rel=1e-12)
    assert heat_motor_copper(2 * 1.17, 0.39, 5.70) == pytest.approx(4 * 76.95, rel=1e-12)
    np.testing.assert_allclose(heat_motor_copper(np.array([0.0, 0.39, 0.78]), 0.39, 5.70),
                               [0.0, 1.5 * 5.70, 1.5 * 4 * 5.70], rtol=1e-12)  # I = 0, 1, 2 A


def test_rated_form_matches_the_torque_constant_form():
    # P_cu,N = 76.95 W at M_N = 1.17 N m (premo 2C).  At 0.585 N m: 76.95 / 4 = 19.2375 W; at
    # 1.5 N m: 76.95 * (1.5/1.17)^2 = 76.95 * 1.6436555 = 126.47929 W = 1.5 (1.5/0.39)^2 5.70.
    assert heat_motor_copper_rated(0.585, 1.17, 76.95) == pytest.approx(19.2375, rel=1e-12)
    assert heat_motor_copper_rated(-1.5, 1.17, 76.95) == pytest.approx(126.47929, rel=1e-7)
    assert heat_motor_copper(1.5, 0.39, 5.70) == pytest.approx(126.47929, rel=1e-7)


def test_rated_form_warns_beyond_twice_the_rated_torque():
    # Kollmorgen: M = I K_T holds up to I = 2 I_0; 2.5 M_N is outside.
    with pytest.warns(CorrelationRangeWarning, match="heat_motor_copper_rated"):
        heat_motor_copper_rated(2.5 * 1.17, 1.17, 76.95)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        heat_motor_copper_rated(2.0 * 1.17, 1.17, 76.95)  # the edge of the range is valid


def test_no_load_loss_of_the_pittman_motor_at_its_no_load_speed():
    # 3702 rpm: omega = 3702 * 2 pi/60 = 387.67253 rad/s (data sheet: 388);
    # T_F omega = 0.011 * 387.67253 = 4.2643978 W; D omega^2 = 1.2e-5 * 150290.00 = 1.8034800 W;
    # P_0 = 6.0678778 W.
    assert heat_motor_no_load(3702.0, 1.1e-2, 1.2e-5) == pytest.approx(6.0678778, rel=1e-6)


def test_no_load_loss_grows_with_speed_and_with_its_square():
    # Friction part x k, viscous part x k^2 when the speed grows k times: I -> III of the paper
    # bench's screw, 396 -> 2214 rpm, k = 5.5909091.  At 396 rpm: omega = 41.469023;
    # T_F part 0.45615925 W, D part 1.2e-5 * 1719.6799 = 0.020636159 W.
    k = 2214.0 / 396.0
    assert heat_motor_no_load(396.0, 1.1e-2, 0.0) == pytest.approx(0.45615925, rel=1e-7)
    assert heat_motor_no_load(396.0, 0.0, 1.2e-5) == pytest.approx(0.020636159, rel=1e-7)
    assert heat_motor_no_load(2214.0, 1.1e-2, 0.0) == pytest.approx(0.45615925 * k, rel=1e-7)
    assert heat_motor_no_load(2214.0, 0.0, 1.2e-5) == pytest.approx(0.020636159 * k**2, rel=1e-7)
    assert heat_motor_no_load(-396.0, 1.1e-2, 1.2e-5) == heat_motor_no_load(396.0, 1.1e-2, 1.2e-5)
    assert heat_motor_no_load(0.0, 1.1e-2, 1.2e-5) == 0.0


def test_no_load_loss_from_a_measured_loss_and_its_hysteresis_share():
    # The Modelica core-loss form: P_0 = P_ref [x w/w_ref + (1 - x)(w/w_ref)^2].  With
    # P_ref = 20 W at 3000 rpm (314.15927 rad/s) and x = 0.4: T_F = 0.4 * 20/314.15927
    # = 0.025464791 N m, D = 0.6 * 20/314.15927^2 = 1.2158542e-4 N m s.  At 1500 rpm:
    # 20 (0.4 * 0.5 + 0.6 * 0.25) = 20 * 0.35 = 7.0 W.
    w_ref = 3000 * 2 * math.pi / 60
    t_f, d = 0.4 * 20 / w_ref, 0.6 * 20 / w_ref**2
    assert t_f == pytest.approx(0.025464791, rel=1e-7)
    assert d == pytest.approx(1.2158542e-4, rel=1e-7)
    assert heat_motor_no_load(3000.0, t_f, d) == pytest.approx(20.0, rel=1e-12)
    assert heat_motor_no_load(1500.0, t_f, d) == pytest.approx(7.0, rel=1e-12)


@pytest.mark.parametrize(("call", "name"), [
    (lambda: heat_motor_copper(1.0, 0.0, 5.7), "torque_constant"),
    (lambda: heat_motor_copper(1.0, 0.39, -1.0), "terminal_resistance"),
    (lambda: heat_motor_copper(float("nan"), 0.39, 5.7), "torque"),
    (lambda: heat_motor_copper_rated(1.0, 0.0, 76.95), "rated_torque"),
    (lambda: heat_motor_copper_rated(1.0, 1.17, -1.0), "rated_copper_loss"),
    (lambda: heat_motor_no_load(3000.0, -0.01, 0.0), "friction_torque"),
    (lambda: heat_motor_no_load(3000.0, 0.01, -1e-5), "viscous_damping"),
    (lambda: heat_motor_no_load(float("inf"), 0.01, 1e-5), "n_rpm"),
])
def test_bad_arguments_are_named(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_winding_resistance_reproduces_the_iec_resistance_method():
    # IEC 60034-1 §8.6.2.3.1 by hand: a winding of R1 = 2.0 Ω cold at θ1 = 20 °C that measures
    # R2 = 2.4 Ω hot is at θ2 = (R2/R1)(235 + θ1) − 235 = 1.2·255 − 235 = 71 °C; going the other
    # way, R(71 °C) = 2.0·(235 + 71)/(235 + 20) = 2.0·306/255 = 2.4 Ω.
    assert resistance_winding_copper(2.0, 293.15, 344.15) == pytest.approx(2.4, rel=1e-12)
    # copper's 20 °C coefficient 1/255 = 3.92e-3 1/K: +1 K at 20 °C adds 0.392 %
    assert resistance_winding_copper(1.0, 293.15, 294.15) == pytest.approx(1.0 + 1.0 / 255.0, rel=1e-12)
    np.testing.assert_allclose(resistance_winding_copper(5.7, 293.15, np.array([293.15, 333.15])),
                               [5.7, 5.7 * 295.0 / 255.0], rtol=1e-12)


def test_winding_resistance_refuses_temperatures_below_the_inferred_zero_and_warns_outside_its_range():
    with pytest.raises(ValueError, match="temperature must be above -235 degC"):
        resistance_winding_copper(1.0, 293.15, 30.0)
    with pytest.warns(CorrelationRangeWarning, match="resistance_winding_copper"):
        resistance_winding_copper(1.0, 293.15, 573.15)
