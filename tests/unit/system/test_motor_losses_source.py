"""A motor source's loss model in a description: units converted, and every bad value named in one line."""

from __future__ import annotations

import pytest

from feedtherm.benches import bench
from feedtherm.errors import DescriptionError
from feedtherm.system.load import load_system
from feedtherm.system.sources import DatasheetMotorLosses, RatedMotorLosses

PAPER = bench("paper").description.read_text(encoding="utf-8")
# The bench's screw motor as declared (its nut motor declares the same losses line).
BENCH_LOSSES = ('losses = { model = "datasheet", torque_constant = "0.39 N*m/A", terminal_resistance = "5.70 ohm", '
                'resistance_temperature = "20 degC", friction_torque = "0.02 N*m", viscous_damping = "2e-5 N*m*s/rad" }\n'
                'into = { screw_motor = 1.0 }')
EFFICIENCY = 'efficiency = 0.85\ninto = { screw_motor = 1.0 }'
DATASHEET = ('losses = { model = "datasheet", torque_constant = "0.39 N*m/A", terminal_resistance = "5.70 ohm", '
             'friction_torque = "11 mN*m", viscous_damping = "1.2566371e-3 N*m/krpm" }\n'
             'into = { screw_motor = 1.0 }')
RATED = ('losses = { model = "rated", rated_torque = "1.17 N*m", rated_copper_loss = "76.95 W", '
         'friction_torque = "0 N*m", viscous_damping = "0 N*m*s/rad" }\ninto = { screw_motor = 1.0 }')


def write_variant(tmp_path, motor: str) -> str:
    """The paper bench with its screw motor's loss model (``BENCH_LOSSES``) replaced by ``motor``."""
    assert PAPER.count(BENCH_LOSSES) == 1, "test fixture out of date: the bench's screw motor changed"
    text = PAPER.replace(BENCH_LOSSES, motor, 1)
    # calibration and uncertainty vary the screw motor's datasheet losses: with another loss
    # model those paths name no value (an error), so only the nut motor's are kept
    for paths in (["terminal_resistance"], ["friction_torque", "viscous_damping"]):
        both = ", ".join(f'"sources.{m}_motor.losses.{p}"' for p in paths for m in ("screw", "nut"))
        if len(paths) == 2:
            both = both.replace('torque", "sources.screw', 'torque",\n         "sources.screw', 1)
        assert both in text, f"test fixture out of date: {both!r}"
        text = text.replace(both, ", ".join(f'"sources.nut_motor.losses.{p}"' for p in paths))
    path = tmp_path / "motor_variant.toml"
    path.write_text(text, encoding="utf-8")
    return str(path)


def load_error(tmp_path, motor: str) -> str:
    with pytest.raises(DescriptionError) as info:
        load_system(write_variant(tmp_path, motor))
    message = str(info.value)
    assert "\n" not in message
    return message


def test_datasheet_losses_load_in_si_units(tmp_path):
    motor = load_system(write_variant(tmp_path, DATASHEET)).system.sources["screw_motor"]
    assert motor.efficiency is None
    losses = motor.losses
    assert isinstance(losses, DatasheetMotorLosses)
    assert losses.torque_constant == pytest.approx(0.39, rel=1e-12)
    assert losses.terminal_resistance == pytest.approx(5.70, rel=1e-12)
    assert losses.friction_torque == pytest.approx(0.011, rel=1e-12)
    # 1 krpm = 1000 * 2 pi/60 = 104.71976 rad/s: 1.2566371e-3 N m/krpm = 1.2e-5 N m s/rad
    assert losses.viscous_damping == pytest.approx(1.2e-5, rel=1e-7)


def test_rated_losses_load_in_si_units(tmp_path):
    losses = load_system(write_variant(tmp_path, RATED)).system.sources["screw_motor"].losses
    assert isinstance(losses, RatedMotorLosses)
    assert (losses.rated_torque, losses.rated_copper_loss) == (pytest.approx(1.17), pytest.approx(76.95))


def test_the_bench_uses_the_datasheet_loss_model(paper):
    # Both motors: the declared data sheet values in SI units; the loss model not chosen
    # (efficiency) is left out of the serialised form, and hash.
    for name in ("screw_motor", "nut_motor"):
        motor = paper.system.sources[name]
        assert motor.efficiency is None
        losses = motor.losses
        assert isinstance(losses, DatasheetMotorLosses)
        assert losses.torque_constant == pytest.approx(0.39, rel=1e-12)
        assert losses.terminal_resistance == pytest.approx(5.70, rel=1e-12)
        assert losses.resistance_temperature == pytest.approx(293.15, rel=1e-12)  # 20 degC
        assert losses.friction_torque == pytest.approx(0.02, rel=1e-12)
        assert losses.viscous_damping == pytest.approx(2e-5, rel=1e-12)
        assert "efficiency" not in motor.model_dump(mode="json")


def test_an_efficiency_motor_serialises_without_losses(tmp_path):
    # A motor declared with an efficiency keeps the serialised form, and hash, it had before
    # `losses` existed.
    motor = load_system(write_variant(tmp_path, EFFICIENCY)).system.sources["screw_motor"]
    assert motor.efficiency == 0.85 and motor.losses is None
    assert "losses" not in motor.model_dump(mode="json")


def test_a_motor_needs_a_loss_model(tmp_path):
    message = load_error(tmp_path, "into = { screw_motor = 1.0 }")
    assert message.endswith("sources.screw_motor: efficiency or losses: give one (efficiency = 0.85, "
                            "or losses = { model = \"datasheet\", ... })")


def test_a_motor_takes_one_loss_model_only(tmp_path):
    message = load_error(tmp_path, "efficiency = 0.85\n" + DATASHEET)
    assert message.endswith("sources.screw_motor: efficiency and losses: give one loss model, not both")


@pytest.mark.parametrize(("change", "expected"), [
    (("terminal_resistance = \"5.70 ohm\"", "terminal_resistance = \"5.70 N\""),
     "sources.screw_motor.losses.terminal_resistance: '5.70 N' is not convertible to ohm"),
    (("torque_constant = \"0.39 N*m/A\"", "torque_constant = \"-0.39 N*m/A\""),
     "sources.screw_motor.losses.torque_constant: must be positive, got '-0.39 N*m/A'"),
    ((", viscous_damping = \"1.2566371e-3 N*m/krpm\"", ""),
     "sources.screw_motor.losses.viscous_damping: missing (required)"),
    (("torque_constant =", "torque_const ="),
     "unknown key 'torque_const' in sources.screw_motor.losses; did you mean 'torque_constant'?"),
    (("friction_torque = \"11 mN*m\"", "friction_torque = 0.011"),
     "sources.screw_motor.losses.friction_torque: 0.011 has no unit; write it with one, e.g. \"0.011 N*m\""),
])
def test_bad_datasheet_values_are_named(tmp_path, change, expected):
    old, new = change
    assert old in DATASHEET
    assert load_error(tmp_path, DATASHEET.replace(old, new)).endswith(expected)


def test_an_unknown_loss_model_is_named(tmp_path):
    message = load_error(tmp_path, DATASHEET.replace('model = "datasheet"', 'model = "catalogue"'))
    assert "sources.screw_motor.losses" in message
    assert "datasheet" in message and "rated" in message
