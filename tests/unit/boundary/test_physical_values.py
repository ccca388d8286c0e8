"""Heats, coefficients and viscosities evaluated at an operating point are finite and physical, or a
ModelError names the value, never a RuntimeWarning (issue 35, item 2).

The values here bypass the description's declared ranges (``with_values`` sets them as a study
would): what the boundary-condition step itself guarantees, whatever reaches it.
"""

import warnings

import pytest

from feedtherm.boundary.physical import check_heat, check_viscosity
from feedtherm.errors import ModelError
from feedtherm.plan import boundary_of
from feedtherm.system.variants import with_values


def refused(loaded, changes: dict, condition: str = "I") -> str:
    variant = with_values(loaded, changes)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a warning of any kind fails the test
        with pytest.raises(ModelError) as info:
            boundary_of(variant, condition)
    message = str(info.value)
    assert "\n" not in message
    return message


def test_an_overflowing_copper_loss_names_the_motor_without_a_runtime_warning(paper):
    # 0.7 N m / 1e-300 N m/A: the current's square overflows (numpy's scalar power)
    message = refused(paper, {"sources.screw_motor.losses.torque_constant": 1e-300})
    assert message.startswith("sources.screw_motor: ")


def test_a_heat_beyond_a_megawatt_names_the_heat_factor_that_made_it(paper):
    message = refused(paper, {"sources.front_bearing.heat_factor": 1e300})
    assert message.startswith("sources.front_bearing.heat_factor: its heat here is ")
    assert "outside 0 to 1e+06 W" in message


def test_a_heat_beyond_a_megawatt_from_the_physics_names_the_source(paper):
    message = refused(paper, {"sources.screw_motor.losses.torque_constant": 1e-4})
    assert message.startswith("sources.screw_motor: its heat here is ") and "beyond what a feed drive has" in message


def test_an_infinite_coefficient_names_the_surface(paper):
    message = refused(paper, {"surfaces.screw_shaft.chtc_factor": 1e308 * 10})
    assert message.startswith("surfaces.screw_shaft: ")


def test_a_coefficient_beyond_its_range_names_the_surface(paper):
    message = refused(paper, {"surfaces.screw_shaft.chtc_factor": 1e300})
    assert message.startswith("surfaces.screw_shaft: its convective coefficient here is ")


def test_an_oil_below_its_pour_point_names_the_lubricant_and_the_temperature(paper):
    cold = with_values(paper, {"conditions.I.ambient": 273.15 - 100.0})
    with pytest.raises(ModelError) as info:
        boundary_of(cold, "I")
    message = str(info.value)
    assert message.startswith("sources.rear_bearing.lubricant: the oil's viscosity at -90 degC (the ambient -100 degC "
                              "plus temperatures.convection_delta_t 10 K) is ")
    assert message.endswith("the oil is too cold there; state a warmer ambient, or an oil for this cold")


def test_the_checks_pass_what_a_machine_has():
    check_heat("sources.x", 12.5, {"torque_Nm": 0.3, "held_by_brake": True})
    check_viscosity("sources.x.lubricant", 1e-4, 313.15, "the ambient")


@pytest.mark.parametrize("power, details", [(float("nan"), {}), (-1.0, {}), (2e6, {}), (1.0, {"current_A": float("inf")})])
def test_the_heat_check_refuses_what_no_machine_has(power, details):
    with pytest.raises(ModelError, match=r"^sources\.x: its heat here is "):
        check_heat("sources.x", power, details)
