"""The ball_screw source in a description: units converted, and every bad value named in one line."""

from __future__ import annotations

import math

import pytest

from feedtherm.benches import bench
from feedtherm.errors import DescriptionError
from feedtherm.system.load import load_system
from feedtherm.system.sources import BallScrewSource

EXAMPLE = bench("ballscrew_example").description.read_text(encoding="utf-8")
CATALOGUE_NUT = '''[sources.ball_nut]
model = "torque"
shaft = "relative"
torque = "0.291 N*m"
'''
BALL_NUT = '''[sources.ball_nut]
model = "ball_screw"
pitch_diameter = "26 mm"
ball_diameter = "4.7625 mm"
contact_angle = "45 deg"
screw_conformity = 0.55
nut_conformity = 0.55
loaded_balls = 40
preload = "1.28 kN"
slip_friction_coefficient = 0.1
hysteresis_loss_fraction = 0.01
lubricant_dynamic_viscosity = "87 mPa*s"
pressure_viscosity_coefficient = "20 1/GPa"
youngs_modulus = "210 GPa"
poisson_ratio = 0.3
'''


def _without_table(text: str, header: str) -> str:
    """``text`` without the TOML table ``header`` (up to the blank line after it)."""
    start = text.index(header)
    return text[:start] + text[text.index("\n\n", start) + 2:]


def write_example(tmp_path, source: str) -> str:
    assert CATALOGUE_NUT in EXAMPLE, "test fixture out of date: the example's ball nut changed"
    text = EXAMPLE.replace(CATALOGUE_NUT, source, 1)
    if source != CATALOGUE_NUT:  # the catalogue torque that calibration and uncertainty vary is gone with it
        for section in ("calibration", "uncertainty"):
            text = _without_table(text, f"[{section}.parameters.ball_nut_torque]")
    path = tmp_path / "ball_screw_variant.toml"
    path.write_text(text, encoding="utf-8")
    return str(path)


def load_error(tmp_path, source: str) -> str:
    with pytest.raises(DescriptionError) as info:
        load_system(write_example(tmp_path, source))
    message = str(info.value)
    assert "\n" not in message
    return message


def test_a_ball_screw_source_loads_in_si_units(tmp_path):
    source = load_system(write_example(tmp_path, BALL_NUT)).system.sources["ball_nut"]
    assert isinstance(source, BallScrewSource)
    assert source.pitch_diameter == pytest.approx(0.026, rel=1e-12)
    assert source.ball_diameter == pytest.approx(4.7625e-3, rel=1e-12)
    assert source.contact_angle == pytest.approx(math.pi / 4.0, rel=1e-12)  # 45 deg
    assert source.preload == pytest.approx(1280.0, rel=1e-12)
    assert source.external_axial_load == 0.0  # default: the guideways' friction only
    assert source.lubricant_dynamic_viscosity == pytest.approx(0.087, rel=1e-12)  # 87 mPa s
    assert source.pressure_viscosity_coefficient == pytest.approx(2e-8, rel=1e-12)  # 20 1/GPa
    assert source.youngs_modulus == pytest.approx(2.1e11, rel=1e-12)


@pytest.mark.parametrize("field", ["ball_diameter", "contact_angle", "loaded_balls", "pressure_viscosity_coefficient"])
def test_a_missing_field_is_named(tmp_path, field):
    lines = [line for line in BALL_NUT.splitlines(keepends=True) if not line.startswith(f"{field} =")]
    assert len(lines) == len(BALL_NUT.splitlines()) - 1
    message = load_error(tmp_path, "".join(lines))
    assert message.endswith(f"sources.ball_nut.{field}: missing (required)"), message


@pytest.mark.parametrize(
    "old, new, fragments",
    [
        ('contact_angle = "45 deg"', 'contact_angle = "90 deg"', ["sources.ball_nut.contact_angle", "between 0 and 90 deg"]),
        ('contact_angle = "45 deg"', 'contact_angle = "45"', ["sources.ball_nut.contact_angle", "has no unit"]),
        ("screw_conformity = 0.55", "screw_conformity = 0.5", ["sources.ball_nut.screw_conformity", "greater than 0.5"]),
        ('ball_diameter = "4.7625 mm"', 'ball_diameter = "30 mm"', ["sources.ball_nut", "ball_diameter must be smaller than pitch_diameter"]),
        ('pressure_viscosity_coefficient = "20 1/GPa"', 'pressure_viscosity_coefficient = "20 GPa"',
         ["sources.ball_nut.pressure_viscosity_coefficient", "not convertible to 1/Pa"]),
        ('lubricant_dynamic_viscosity = "87 mPa*s"', 'lubricant_dynamic_viscosity = "100 mm^2/s"',
         ["sources.ball_nut.lubricant_dynamic_viscosity", "not convertible to Pa*s"]),
        ("loaded_balls = 40", "loaded_balls = 0", ["sources.ball_nut.loaded_balls", "greater than or equal to 1"]),
        ("loaded_balls = 40", "loaded_bals = 40", ["unknown key 'loaded_bals'", "did you mean 'loaded_balls'"]),
    ],
)
def test_a_bad_value_is_named_with_its_reason(tmp_path, old, new, fragments):
    assert old in BALL_NUT
    message = load_error(tmp_path, BALL_NUT.replace(old, new, 1))
    for fragment in fragments:
        assert fragment in message, message
