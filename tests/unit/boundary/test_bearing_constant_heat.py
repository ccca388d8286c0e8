"""A bearing source with the catalogue's constant coefficient of friction (``friction_model = "constant"``)."""

from __future__ import annotations

import math

import pytest

from feedtherm.boundary import operating_point
from feedtherm.boundary.heat import source_heats
from feedtherm.system.sources import BearingSource
from feedtherm.system.load import load_system
from feedtherm.system.variants import with_values

PAIR = {"model": "bearing", "shaft": "screw", "bearing_type": "angular_contact", "friction_model": "constant",
        "bore_diameter": "25 mm", "outer_diameter": "62 mm", "bearings_in_set": 2, "static_load_rating": "40.5 kN",
        "axial_load": "3150 N", "radial_load": "50 N", "friction_coefficient": 0.0020, "into": {"front_bearing": 1.0}}


def heats(source, condition):
    loaded = load_system("paper")
    system = with_values(loaded, {"sources": {**loaded.system.sources, "front_bearing": source}}).system
    return source_heats(system, operating_point(system, system.conditions[condition]))


def test_a_support_pair_by_hand_at_two_speeds():
    source = BearingSource.model_validate(PAIR)
    # each bearing: P = 3150 + 50/2 = 3175 N, M = 0.5 * 0.0020 * 3175 * 0.025 = 0.079375 N m; the pair 0.15875 N m.
    # At 396 rpm: 0.15875 * 396 * 2 pi / 60 = 0.15875 * 41.46902 = 6.58321 W; at 2214 rpm 0.15875 * 231.8495 = 36.8061 W.
    low, high = heats(source, "I")["front_bearing"], heats(source, "III")["front_bearing"]
    assert low.details["friction_torque_Nm"] == pytest.approx(0.15875, rel=1e-12)
    assert low.power == pytest.approx(6.58321, rel=1e-5)
    assert high.power == pytest.approx(36.8061, rel=1e-5)
    assert high.power / low.power == pytest.approx(2214 / 396)  # the torque does not depend on the speed
    assert math.isclose(high.details["friction_torque_Nm"], low.details["friction_torque_Nm"])


def test_the_screw_motor_carries_the_pairs_drag():
    constant = heats(BearingSource.model_validate(PAIR), "I")
    lighter = heats(BearingSource.model_validate({**PAIR, "axial_load": "1000 N"}), "I")
    # 0.5 * 0.0020 * (3175 - 1025) N * 0.025 m = 0.05375 N m per bearing, 0.1075 N m less on the screw motor
    drop = constant["screw_motor"].details["torque_Nm"] - lighter["screw_motor"].details["torque_Nm"]
    assert drop == pytest.approx(0.1075, rel=1e-6)


@pytest.mark.parametrize("change, message", [
    ({"friction_coefficient": None}, "friction_coefficient: needed by friction_model = 'constant'"),
    ({"friction_coefficient": 0.3}, "not a rolling bearing's constant coefficient of friction"),
    ({"series": "single_row"}, "series: not used by friction_model = 'constant'"),
    ({"lubricant": {"grade": "ISO VG 100", "viscosity_100C": "11 mm^2/s"}}, "lubricant, lubricant_viscosity: not used"),
    ({"friction_model": "skf", "series": "single_row", "lubricant_viscosity": "100 mm^2/s"},
     "friction_coefficient: used only by friction_model = 'constant'"),
])
def test_the_fields_of_the_constant_model(change, message):
    data = {**PAIR, **change}
    data = {k: v for k, v in data.items() if v is not None}
    with pytest.raises(ValueError, match=message):
        BearingSource.model_validate(data)
