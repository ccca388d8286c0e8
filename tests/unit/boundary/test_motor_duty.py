"""The motors' duty: the torque their shaft needs against their rated continuous torque.

The paper bench declares both motors as WITTENSTEIN alpha premo stator 2C servos: k_T = 0.39 N·m/A,
1.17 N·m continuous, so 1.17 / 0.39 = 3.00 A continuous.
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from feedtherm.analysis.calibration import motor_duty
from feedtherm.benches import bench
from feedtherm.boundary import operating_point
from feedtherm.boundary.heat import motor_overloads, source_heats
from feedtherm.errors import FeedthermError
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system
from feedtherm.system.variants import with_values


def heats_at(system, condition):
    return source_heats(system, operating_point(system, system.conditions[condition]))


def test_the_screw_motor_carries_the_torques_on_its_shaft_against_its_rating():
    system = load_system("paper").system
    heats = heats_at(system, "I")
    screw = heats["screw_motor"].details
    # the screw motor drives the screw against the front and rear bearings' drag and the thread's torque
    on_shaft = (heats["front_bearing"].details["friction_torque_Nm"] + heats["rear_bearing"].details["friction_torque_Nm"]
                + heats["screw_nut"].details["friction_torque_Nm"])
    assert screw["torque_Nm"] == pytest.approx(on_shaft, rel=0.05)
    assert screw["continuous_torque_Nm"] == pytest.approx(1.17)
    assert screw["continuous_current_A"] == pytest.approx(3.0)  # 1.17 / 0.39
    assert screw["torque_to_continuous"] == pytest.approx(abs(screw["torque_Nm"]) / 1.17)
    assert screw["current_A"] == pytest.approx(abs(screw["torque_Nm"]) / 0.39)
    assert not motor_overloads(heats)


def test_a_preload_the_motors_cannot_hold_is_refused():
    loaded = load_system("paper")
    # 400 N of thread preload: its circulating torque alone, 3.2e-3 N m/N * 400 N = 1.28 N m, exceeds 1.17 N m
    heavy = with_values(loaded, {"sources.screw_nut.preload": 400.0})
    overloads = motor_overloads(heats_at(heavy.system, "I"))
    assert [o.source for o in overloads] == ["screw_motor", "nut_motor"]  # the thread's torque loads both
    assert overloads[0].torque > 1.17
    with pytest.raises(FeedthermError, match=r"^condition I: sources.screw_motor: .* continuous_torque 1.17"):
        simulate(heavy, condition="I", duration=60.0)
    # studies that vary the preloads run the point and report it
    simulate(heavy, condition="I", duration=60.0, allow_overload=True)
    assert max(motor_duty(heavy)["I"].values()) > 1.0


def test_check_refuses_an_overloaded_description_in_one_line(tmp_path):
    text = bench("paper").description.read_text(encoding="utf-8")
    assert 'preload = "150 N"' in text
    path = tmp_path / "heavy.toml"
    path.write_text(text.replace('preload = "150 N"', 'preload = "350 N"'), encoding="utf-8")
    result = subprocess.run([sys.executable, "-m", "feedtherm", "check", str(path)], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in result.stderr
    assert "sources.screw_motor" in lines[0] and "continuous_torque" in lines[0], lines[0]


def test_the_declared_bench_keeps_every_motor_within_its_rating():
    duty = motor_duty(load_system("paper"))
    assert set(duty) == {"I", "II", "III", "IV", "V"}
    assert all(0.3 < r < 1.0 for motors in duty.values() for r in motors.values())
