import pytest

from feedtherm.physics.contact import conductance_contact, temperature_jump


def test_nut_screw_joint_conductance_by_hand():
    # Table 3 nut-screw TCR 1.65e-4 m^2K/W over pi * 0.032 m * 0.060 m = 6.0319e-3 m^2
    # G = 6.0319e-3 / 1.65e-4 = 36.557 W/K
    assert conductance_contact(1.65e-4, 3.141592653589793 * 0.032 * 0.060) == pytest.approx(36.557, rel=1e-4)


def test_temperature_jump_is_flux_times_resistance():
    # 1000 W/m^2 through a bearing seat of 1.25e-3 m^2K/W drops 1.25 K
    assert temperature_jump(1000.0, 1.25e-3) == pytest.approx(1.25, rel=1e-12)
    assert temperature_jump(-1000.0, 1.25e-3) == pytest.approx(-1.25, rel=1e-12)


@pytest.mark.parametrize("tcr, area", [(0.0, 1.0), (-1e-3, 1.0), (1e-3, 0.0)])
def test_non_physical_inputs_are_rejected(tcr, area):
    with pytest.raises(ValueError):
        conductance_contact(tcr, area)
