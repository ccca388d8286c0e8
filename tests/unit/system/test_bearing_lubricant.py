"""A bearing's lubricant: a fixed viscosity or an ISO VG grade; every bad value named in one line."""

from __future__ import annotations

import pytest

from feedtherm.benches import bench
from feedtherm.errors import DescriptionError
from feedtherm.system.load import load_system

PAPER = bench("paper").description.read_text(encoding="utf-8")
DECLARED = 'lubricant = { grade = "ISO VG 100", viscosity_100C = "11 mm^2/s" }\ninto = { rear_bearing = 1.0 }'


def write_variant(tmp_path, lubricant_lines: str) -> str:
    """The paper bench with the rear bearing's declared lubricant replaced by ``lubricant_lines``."""
    assert PAPER.count(DECLARED) == 1, "test fixture out of date: the paper bench's rear bearing changed"
    path = tmp_path / "lubricant_variant.toml"
    path.write_text(PAPER.replace(DECLARED, f"{lubricant_lines}\ninto = {{ rear_bearing = 1.0 }}", 1), encoding="utf-8")
    return str(path)


def load_error(tmp_path, lubricant_lines: str) -> str:
    with pytest.raises(DescriptionError) as info:
        load_system(write_variant(tmp_path, lubricant_lines))
    message = str(info.value)
    assert "\n" not in message
    return message


def test_grade_with_viscosity_100c_loads_with_units(tmp_path):
    # Hand-made example, not from a data sheet: a VG 100 oil stated as 11 mm²/s at 100 °C.
    source = load_system(write_variant(tmp_path, 'lubricant = { grade = "VG 100", viscosity_100C = "11 cSt" }')).system.sources["rear_bearing"]
    assert source.lubricant_viscosity is None
    assert source.lubricant.viscosity_100C == pytest.approx(11e-6, rel=1e-12)
    # ISO 3448 midpoint of VG 100 at 40 °C, the stated value at 100 °C, and Walther between:
    # 177.2454 mm²/s at 30 °C (hand calculation in tests/unit/boundary/test_bearing_lubricant_heat.py).
    assert source.viscosity_at(313.15) == pytest.approx(100e-6, rel=1e-9)
    assert source.viscosity_at(373.15) == pytest.approx(11e-6, rel=1e-9)
    assert source.viscosity_at(303.15) == pytest.approx(177.2454e-6, rel=1e-6)


def test_a_fixed_viscosity_does_not_depend_on_temperature(tmp_path):
    # The bench's bearings declare an ISO VG grade; a variant declares the fixed viscosity.
    source = load_system(write_variant(tmp_path, 'lubricant_viscosity = "100 mm^2/s"')).system.sources["rear_bearing"]
    assert source.lubricant is None
    assert source.viscosity_at(250.0) == source.viscosity_at(400.0) == pytest.approx(100e-6, rel=1e-12)


@pytest.mark.parametrize(
    ("lines", "field", "reason"),
    [
        ('lubricant = { grade = "ISO VG 90", viscosity_100C = "11 mm^2/s" }', "sources.rear_bearing.lubricant.grade", "not an ISO 3448 grade"),
        ('lubricant = { grade = "ISO VG 100" }', "sources.rear_bearing.lubricant.viscosity_100C", "missing (required)"),
        ('lubricant = { grade = "ISO VG 100", viscosity_100C = "-11 mm^2/s" }', "sources.rear_bearing.lubricant.viscosity_100C", "must be positive"),
        ('lubricant = { grade = "ISO VG 100", viscosity_100C = "120 mm^2/s" }', "sources.rear_bearing.lubricant", "smaller"),
        ('lubricant = { grade = "ISO VG 100", viscosity_100C = "11 mm^2/s", colour = "red" }', "sources.rear_bearing.lubricant", "colour"),
        ('lubricant_viscosity = "100 mm^2/s"\nlubricant = { grade = "ISO VG 100", viscosity_100C = "11 mm^2/s" }',
         "sources.rear_bearing", "give one"),
        ("", "sources.rear_bearing", "lubricant_viscosity or lubricant"),
    ],
)
def test_bad_lubricant_is_named(tmp_path, lines, field, reason):
    message = load_error(tmp_path, lines)
    assert field in message and reason in message, message
