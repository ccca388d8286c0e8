"""Every bad description ends in one DescriptionError line naming the file, field and reason."""

import pytest

from feedtherm.benches import bench
from feedtherm.errors import DescriptionError
from feedtherm.system.load import load_system

BENCH = bench("paper").description.read_text(encoding="utf-8")


def write_variant(tmp_path, old: str, new: str) -> str:
    assert old in BENCH, f"test fixture out of date: {old!r} not in the bench file"
    path = tmp_path / "variant.toml"
    path.write_text(BENCH.replace(old, new, 1))
    return str(path)


def load_error(spec: str) -> str:
    with pytest.raises(DescriptionError) as info:
        load_system(spec)
    message = str(info.value)
    assert "\n" not in message
    return message


# The screw motor's declared loss model (the bench's nut motor declares the same line; the
# anchor's `into = { screw_motor` picks the screw motor's).
SCREW_MOTOR_LOSSES = (
    'losses = { model = "datasheet", torque_constant = "0.39 N*m/A", terminal_resistance = "5.70 ohm", '
    'resistance_temperature = "20 degC", friction_torque = "0.02 N*m", viscous_damping = "2e-5 N*m*s/rad" }\n'
    'into = { screw_motor'
)
SCREW = 'cylinders = [{ origin = ["-60 mm", "0 mm", "0 mm"], length = "510 mm", outer_diameter = "32 mm" }]'


@pytest.mark.parametrize(
    "old, new, fragments",
    [
        (SCREW, SCREW.replace('"32 mm"', '"-32 mm"'), ["parts.screw.cylinders[0].outer_diameter", "must be positive", "-32 mm"]),
        (SCREW, SCREW.replace('"32 mm"', '"0 mm"'), ["parts.screw.cylinders[0].outer_diameter", "must be positive"]),
        ('conductivity = "46 W/(m*K)"', 'conductivity = "-46 W/(m*K)"', ["materials.q345b.conductivity", "must be positive"]),
        ('outer_diameter = "32 mm"', 'outer_diamter = "32 mm"', ["unknown key 'outer_diamter'", "did you mean 'outer_diameter'"]),
        ('into = { front_bearing = 1.0 }', 'into = { front_bearng = 1.0 }', ["sources.front_bearing.into", "no part named 'front_bearng'", "did you mean 'front_bearing'"]),
        ('between = ["nut", "screw"]', 'between = ["nut", "scew"]', ["joints[6].between", "no part named 'scew'"]),
        ('screw = "screw"\nnut = "nut"', 'screw = "spindle"\nnut = "nut"', ["kinematics.screw", "no part named 'spindle'"]),
        ('lead = "10 mm"', 'lead = "10"', ["kinematics.lead", "has no unit"]),
        ('lead = "10 mm"', 'lead = "10 kg"', ["kinematics.lead", "not convertible to m"]),
        ('[kinematics]\ndrive = "dual"', '[kinematics]\ndrive = "triple"', ["kinematics.drive", "'dual' or 'single'"]),
        (SCREW_MOTOR_LOSSES, 'efficiency = 1.5\ninto = { screw_motor', ["sources.screw_motor.efficiency", "less than or equal to 1"]),
        ('into = { nut = 0.5, screw = 0.5 }', 'into = { nut = 0.5, screw = 0.6 }', ["sources.screw_nut.into", "add up to 1"]),
        ('[temperatures]\n', '[temperatures]\ninital = "20 degC"\n', ["unknown key 'inital' in temperatures", "did you mean 'initial'"]),
        ('[conditions.I]\nfeed_speed', '[conditions.I]\nscrew_sped = "1 rpm"\nfeed_speed', ["unknown key 'screw_sped'", "did you mean 'screw_speed'"]),
    ],
)
def test_bad_values_name_the_field_and_reason(tmp_path, old, new, fragments):
    message = load_error(write_variant(tmp_path, old, new))
    assert message.startswith(str(tmp_path / "variant.toml") + ": ")
    for fragment in fragments:
        assert fragment in message, message


def test_missing_part_section_is_named(tmp_path):
    start = BENCH.index("[parts.nut_bearing]")
    end = BENCH.index("[parts.nut]")
    path = tmp_path / "no_nut_bearing.toml"
    path.write_text(BENCH[:start] + BENCH[end:])
    message = load_error(str(path))
    assert "no part named 'nut_bearing'" in message


def test_missing_required_section(tmp_path):
    start = BENCH.index("[temperatures]")
    end = BENCH.index("\n[", start + 1)
    path = tmp_path / "no_temperatures.toml"
    path.write_text(BENCH[:start] + BENCH[end + 1:])
    assert "temperatures: missing (required)" in load_error(str(path))


def test_a_bench_without_its_kinematics_is_told_what_needs_a_feed_drive(tmp_path):
    start = BENCH.index("[kinematics]")
    end = BENCH.index("[[mechanics.supports]]")
    path = tmp_path / "no_kinematics.toml"
    path.write_text(BENCH[:start] + BENCH[end:])
    message = load_error(str(path))
    assert ".moving: the system has no feed drive ([kinematics] is left out)" in message, message


def test_broken_toml(tmp_path):
    path = tmp_path / "broken.toml"
    path.write_text('[meta\nname = "x"\n')
    message = load_error(str(path))
    assert "invalid TOML" in message and "line 1" in message


def test_empty_file(tmp_path):
    path = tmp_path / "empty.toml"
    path.write_text("\n  \n")
    assert "the file is empty" in load_error(str(path))


def test_missing_file(tmp_path):
    message = load_error(str(tmp_path / "nope.toml"))
    assert message.endswith("nope.toml: no such file")


def test_unknown_bundled_name_lists_the_bundled_ones():
    message = load_error("papr")
    assert "no such file" in message and "paper" in message


def test_signed_speeds_are_directions_not_errors(tmp_path):
    spec = write_variant(tmp_path, 'screw_speed = "396 rpm"\nnut_speed = "360 rpm"',
                         'screw_speed = "-396 rpm"\nnut_speed = "-360 rpm"')
    condition = load_system(spec).system.conditions["I"]
    assert condition.screw_speed < 0 and condition.nut_speed < 0


def test_unknown_key_inside_a_tagged_source_suggests_from_that_source_type(tmp_path):
    spec = write_variant(tmp_path, SCREW_MOTOR_LOSSES, 'eficiency = 0.85\ninto = { screw_motor')
    message = load_error(spec)
    assert "unknown key 'eficiency' in sources.screw_motor" in message
    assert "did you mean 'efficiency'" in message


@pytest.mark.parametrize(
    "old, new, fragments",
    [
        ('reversal = "both_reverse"', 'reversal = "nut_only"',
         ["kinematics.reversal: 'nut_only' is not allowed", "allowed values: 'both_reverse'"]),
        ('kind = "natural", orientation = "vertical_plate", length = "18 mm"',
         'kind = "natural", orientation = "vertical", length = "18 mm"',
         ["convection.orientation: 'vertical' is not allowed", "'horizontal_cylinder', 'vertical_plate', "
          "'horizontal_plate_up' or 'horizontal_plate_down'"]),
        ('faces = ["lateral"]', 'faces = ["side"]',
         ["faces[0]: 'side' is not allowed", "'+x', '-x', '+y', '-y', '+z', '-z', 'lateral', 'ends' or 'bore'"]),
        ('kind = "natural", orientation = "vertical_plate", length = "18 mm"',
         'kind = "forced", orientation = "vertical_plate", length = "18 mm"',
         ["convection.kind: 'forced' is not allowed", "'natural', 'rotating', 'moving_plate', 'moving_face', 'fixed'"]),
    ],
    ids=["reversal", "orientation", "faces", "convection kind"],
)
def test_a_value_outside_a_list_names_the_allowed_values(tmp_path, old, new, fragments):
    message = load_error(write_variant(tmp_path, old, new))
    for fragment in fragments:
        assert fragment in message, message
