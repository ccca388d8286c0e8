"""The room's draught (room.air_speed) on every correlated surface, as mixed convection."""

from __future__ import annotations

import pytest

from feedtherm.boundary import boundary_conditions
from feedtherm.errors import DescriptionError
from feedtherm.physics import convection
from feedtherm.physics.air import film_temperature
from feedtherm.system.load import parse_toml, read_text, validate_data
from feedtherm.system.variants import with_values

U = 0.2  # m/s


@pytest.fixture(scope="module")
def still_and_draughty(paper):
    draughty = with_values(paper, {"room.air_speed": U})
    return boundary_conditions(paper.system, "I"), boundary_conditions(draughty.system, "I"), draughty.system


@pytest.mark.parametrize("name, flow", [
    ("nut_housing", "plate"),  # a moving plate: parallel flow on its natural length
    ("screw_shaft", "cross flow"),  # the rotating screw: cross flow on its diameter
])
def test_the_draught_mixes_in_on_the_surface_s_own_length(still_and_draughty, name, flow):
    still, draughty, system = still_and_draughty
    conv = system.surfaces[name].convection
    t_film = film_temperature(still.point.ambient + 10.0, still.point.ambient)
    room = (convection.h_flat_plate_laminar_average(conv.natural_length, U, t_film) if flow == "plate"
            else convection.h_cylinder_crossflow(conv.diameter, U, t_film))
    h_still = still.surfaces[name].convection
    assert draughty.surfaces[name].convection == pytest.approx((h_still**3 + room**3) ** (1 / 3), rel=1e-12)
    assert f"room air at 0.2 m/s ({flow})" in draughty.surfaces[name].correlation


def test_a_declared_coefficient_and_still_air_are_left_alone(still_and_draughty, paper):
    still, draughty, _ = still_and_draughty
    assert draughty.surfaces["base_bottom"].convection == still.surfaces["base_bottom"].convection == 800.0
    assert paper.system.room.air_speed == 0.0
    assert all(draughty.surfaces[n].convection > still.surfaces[n].convection
               for n in still.surfaces if n != "base_bottom")


def test_a_negative_air_speed_is_one_line():
    text, origin = read_text("paper")
    data = parse_toml(text, origin)
    data["room"] = {"air_speed": "-0.1 m/s"}
    with pytest.raises(DescriptionError, match="room.air_speed") as info:
        validate_data(data, "variant")
    assert "\n" not in str(info.value)
