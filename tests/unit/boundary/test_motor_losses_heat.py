"""Motor heats of the paper bench with the data-sheet loss model, at conditions I and III.

The bench keeps its efficiency model (its assumptions are frozen); here both motors of a variant
are an example motor declared for this test only, not a choice for the bench:
- copper: WITTENSTEIN alpha premo 320 V, stator 2C (operating manual rev. 02, Tbl-16),
  K_t = 0.39 N·m/A, R_tt = 5.70 Ω (a 1.17 N·m servo, the class of the bench's 400 W motors);
- drag: AMETEK Pittman 14204S004 data sheet, T_F = 1.1e-2 N·m, D = 1.2e-5 N·m·s.

The torques come from the torque balance, which the loss model does not change:
docs/paper-audit.md §5 works out 0.121 + 0.010 + 1.595 + 0.028 = 1.754 N·m for the screw motor and
0.127 − 1.595 − 0.028 = −1.497 N·m (braking) for the nut motor at condition I.
"""

from __future__ import annotations

import math

import pytest

from feedtherm.boundary import operating_point
from feedtherm.boundary.heat import source_heats
from feedtherm.system.sources import MotorSource
from feedtherm.system.variants import with_values

K_T, R_TT, T_F, D = 0.39, 5.70, 1.1e-2, 1.2e-5
DATASHEET = {"model": "datasheet", "torque_constant": "0.39 N*m/A", "terminal_resistance": "5.70 ohm",
             "friction_torque": "1.1e-2 N*m", "viscous_damping": "1.2e-5 N*m*s/rad"}
# The same copper law stated at one torque: 1.5 (1.17/0.39)^2 5.70 = 1.5 * 9 * 5.70 = 76.95 W.
RATED = {"model": "rated", "rated_torque": "1.17 N*m", "rated_copper_loss": "76.95 W",
         "friction_torque": "1.1e-2 N*m", "viscous_damping": "1.2e-5 N*m*s/rad"}


@pytest.fixture(scope="module")
def bench(paper_equations):
    """The torque balance of docs/paper-audit.md §5 is the one of the paper's equation models (500 N preload)."""
    return paper_equations


def with_motor_losses(loaded, losses):
    sources = dict(loaded.system.sources)
    for name in ("screw_motor", "nut_motor"):
        motor = sources[name]
        assert motor.extra_torque == 0.0  # so the variant differs in its loss model only
        sources[name] = MotorSource.model_validate(
            {"model": "motor", "shaft": motor.shaft, "into": dict(motor.into), "losses": losses})
    return with_values(loaded, {"sources": sources}).system


def heats_at(system, condition):
    return source_heats(system, operating_point(system, system.conditions[condition]))


def omega(n_rpm):
    return n_rpm * 2 * math.pi / 60


def test_screw_and_nut_motor_heats_at_condition_I_by_hand(bench):
    heats = heats_at(with_motor_losses(bench, DATASHEET), "I")
    screw, nut = heats["screw_motor"], heats["nut_motor"]
    # screw motor, 1.754 N m at 396 rpm: I = 1.754/0.39 = 4.4974 A,
    # copper 1.5 * 4.4974^2 * 5.70 = 1.5 * 20.2272 * 5.70 = 172.94 W;
    # no-load 0.011 * 41.469023 + 1.2e-5 * 41.469023^2 = 0.45615925 + 0.02063616 = 0.47679541 W.
    assert screw.details["torque_Nm"] == pytest.approx(1.754, abs=6e-4)  # the audit rounds to 1 mN m
    assert screw.details["copper_loss_W"] == pytest.approx(172.94, rel=1e-3)
    assert screw.details["no_load_loss_W"] == pytest.approx(0.47679541, rel=1e-7)
    assert screw.power == pytest.approx(172.94 + 0.4768, rel=1e-3)
    # nut motor, braking by 1.497 N m at 360 rpm: copper 1.5 (1.497/0.39)^2 5.70 = 1.5 * 14.7339
    # * 5.70 = 125.97 W; no-load 0.011 * 37.699112 + 1.2e-5 * 1421.2230 = 0.41469023 + 0.01705468
    # = 0.43174491 W.  Its shaft takes in 1.497 * 37.699 = 56.4 W, which goes to the amplifier's
    # DC bus: the motor's heat is its losses only.
    assert nut.details["shaft_power_W"] == pytest.approx(-56.4, rel=2e-3)
    assert nut.details["copper_loss_W"] == pytest.approx(125.97, rel=1e-3)
    assert nut.details["no_load_loss_W"] == pytest.approx(0.43174491, rel=1e-7)
    assert nut.power == pytest.approx(nut.details["copper_loss_W"] + nut.details["no_load_loss_W"], rel=1e-12)


def test_heats_scale_with_the_square_of_the_torque_and_with_the_speed(bench):
    system = with_motor_losses(bench, DATASHEET)
    one, three = heats_at(system, "I"), heats_at(system, "III")
    for name, n_one, n_three in (("screw_motor", 396.0, 2214.0), ("nut_motor", 360.0, 2160.0)):
        m_one, m_three = one[name].details["torque_Nm"], three[name].details["torque_Nm"]
        # copper: 1.5 (M/k_T)^2 R_tt at each condition's own torque, so the ratio is (M_III/M_I)^2
        for heat, m in ((one[name], m_one), (three[name], m_three)):
            assert heat.details["copper_loss_W"] == pytest.approx(1.5 * (m / K_T) ** 2 * R_TT, rel=1e-12)
            assert heat.details["current_A"] == pytest.approx(abs(m) / K_T, rel=1e-12)
        ratio = three[name].details["copper_loss_W"] / one[name].details["copper_loss_W"]
        assert ratio == pytest.approx((m_three / m_one) ** 2, rel=1e-12)
        # no-load: (T_F + D w) w at each condition's own speed
        for heat, n in ((one[name], n_one), (three[name], n_three)):
            assert heat.details["no_load_loss_W"] == pytest.approx((T_F + D * omega(n)) * omega(n), rel=1e-12)
    # screw motor, III: 0.011 * 231.84953 + 1.2e-5 * 231.84953^2 = 2.5503448 + 0.6450506 = 3.1953954 W
    assert three["screw_motor"].details["no_load_loss_W"] == pytest.approx(3.1953954, rel=1e-7)


def test_the_circulating_torque_no_longer_makes_the_heat_grow_with_the_shaft_power(bench):
    # The efficiency model's loss is proportional to M*omega: the screw motor's heat grows like the
    # speed, 2214/396 = 5.59, times the small change of its torque.  With the data-sheet model the
    # copper loss follows M^2 only, and the no-load loss (a few W) is small beside it.
    system = with_motor_losses(bench, DATASHEET)
    new = heats_at(system, "III")["screw_motor"].power / heats_at(system, "I")["screw_motor"].power
    old = heats_at(bench.system, "III")["screw_motor"].power / heats_at(bench.system, "I")["screw_motor"].power
    assert old > 2214.0 / 396.0
    assert new < 1.3


def test_rated_loss_form_gives_the_same_heats_as_the_torque_constant_form(bench):
    datasheet = with_motor_losses(bench, DATASHEET)
    rated = with_motor_losses(bench, RATED)
    for condition in ("I", "III"):
        a, b = heats_at(datasheet, condition), heats_at(rated, condition)
        for name in ("screw_motor", "nut_motor"):
            assert b[name].power == pytest.approx(a[name].power, rel=1e-12)


def test_the_torque_balance_is_the_same_for_both_loss_models(bench):
    new, old = heats_at(with_motor_losses(bench, DATASHEET), "II"), heats_at(bench.system, "II")
    for name in ("screw_motor", "nut_motor"):
        assert new[name].details["torque_Nm"] == old[name].details["torque_Nm"]
    for name in old:
        if name not in ("screw_motor", "nut_motor"):
            assert new[name].power == old[name].power
