"""Calibration keeps the motors within their rated continuous torque (analysis/calibration.py)."""

import numpy as np
import pytest

from feedtherm.analysis.calibration import (DUTY_LIMIT, DUTY_SIGMA, _DutyPenalty, apply, calibrate,
                                            resolve_parameters)
from feedtherm.system.measurements import read_measurements
from feedtherm.boundary import boundary_conditions
from feedtherm.boundary.heat import motor_duties
from feedtherm.plan import with_mode
from feedtherm.simulate import simulate


def test_the_penalty_is_zero_within_the_rating_and_grows_with_the_overload(paper):
    params = resolve_parameters(paper, ["screw_nut_preload"])
    penalty = _DutyPenalty(paper, params, ["I", "III"])
    assert penalty.motors == ["nut_motor", "screw_motor"]
    assert np.all(penalty(np.array([150.0])) == 0.0)
    at_340 = penalty(np.array([340.0]))
    overloaded = apply(paper, params, [340.0]).system
    expected = [max(0.0, motor_duties(boundary_conditions(overloaded, c).heats)[m] - DUTY_LIMIT) / DUTY_SIGMA
                for c in ("I", "III") for m in ("nut_motor", "screw_motor")]
    assert at_340 == pytest.approx(expected)
    assert at_340[1] > 0.0 and at_340[3] > 0.0  # the screw motor passes its rating at both speeds
    # the declared limit and stiffness: a duty of d gives (d - 0.995) / 0.0005
    duty_i = motor_duties(boundary_conditions(overloaded, "I").heats)["screw_motor"]
    assert at_340[1] == pytest.approx((duty_i - 0.995) / 0.0005)


def test_paper_mode_has_no_duty_to_keep(paper):
    params = resolve_parameters(paper, ["screw_nut_preload"])
    in_paper_mode = with_mode(paper, "paper")
    assert _DutyPenalty(in_paper_mode, params, ["I"])(np.array([340.0])).size == 0


def test_a_fit_that_wants_an_overloaded_motor_stops_at_its_rating(paper, tmp_path):
    """Measurements at I made by a machine whose thread preload (340 N) overloads the screw motor:
    the fit follows them only up to the motor's rating at every declared condition, and reports a
    machine the motors can run."""
    params = resolve_parameters(paper, ["screw_nut_preload"])
    truth = apply(paper, params, [340.0])
    final = simulate(truth, condition="I", motion="averaged", allow_overload=True).summary_values("final")
    path = tmp_path / "overloaded.csv"
    sensors = ("T1", "T2", "T3", "T4", "T5")
    path.write_text("condition,quantity,unit,measured\n" + "".join(f"I,{q},C,{final[q]:.4f}\n" for q in sensors))
    result = calibrate(paper, read_measurements(str(path), sensors=list(sensors)), ["I"],
                       ["screw_nut_preload"], equilibrium=False)
    # every condition the machine runs counts, measured or not: III, the fastest, binds
    assert set(result.motor_duty) == {"I", "II", "III", "IV", "V"}
    assert result.overloads() == []
    worst = max(duties["screw_motor"] for duties in result.motor_duty.values())
    assert worst == result.motor_duty["III"]["screw_motor"]
    assert 250.0 < result.fitted[0] < 340.0  # pulled towards the data, held back by the rating
    assert DUTY_LIMIT - 0.01 < worst <= 1.0  # and it goes as far as it may
