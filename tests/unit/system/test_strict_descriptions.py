"""Booleans only as booleans, names matched to their end, parameter paths that name numbers:
each refused in one line naming the field (issue 35, item 3)."""

import pytest

from feedtherm.benches import bench
from feedtherm.cli import main
from feedtherm.errors import DescriptionError
from feedtherm.system.load import load_system

BENCH = bench("paper").description.read_text(encoding="utf-8")


def load_error(tmp_path, *changes: tuple[str, str]) -> str:
    text = BENCH
    for old, new in changes:
        assert old in text, f"test fixture out of date: {old!r}"
        text = text.replace(old, new, 1)
    path = tmp_path / "variant.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(DescriptionError) as info:
        load_system(str(path))
    message = str(info.value)
    assert "\n" not in message and message.startswith(f"{path}: ")
    return message[len(f"{path}: "):]


TABLE = '[parts.worktable]\nmaterial = "q345b"\nmoving = true'


@pytest.mark.parametrize("value", ['"yes"', '"off"', "1", '"true"'])
def test_moving_takes_a_boolean_only(tmp_path, value):
    shown = value.strip('"')
    message = load_error(tmp_path, (TABLE, TABLE.replace("true", value)))
    assert message == f"parts.worktable.moving: {shown if value == '1' else repr(shown)} is not a boolean; " \
                      "write true or false"


def test_sliding_takes_a_boolean_only(tmp_path):
    message = load_error(tmp_path, ("sliding = true", "sliding = 1"))
    assert message.endswith(".sliding: 1 is not a boolean; write true or false")


def test_fit_takes_a_boolean_only(tmp_path):
    message = load_error(tmp_path, ("sliding = true", 'sliding = true\nfit = "no"'))
    assert message.endswith(".fit: 'no' is not a boolean; write true or false")


def test_a_name_with_a_trailing_newline_is_refused(tmp_path):
    message = load_error(tmp_path, ("[sensors.T5]", '[sensors."T5\\n"]'))
    assert message == "sensors: 'T5\\n' is not a valid name (letters, digits, underscores)"


def test_an_ambient_sensor_with_a_trailing_newline_is_refused(tmp_path):
    message = load_error(tmp_path, ('ambient_sensor = "T6"', 'ambient_sensor = "T6\\n"'))
    assert message.startswith("room.ambient_sensor: String should match pattern")


def test_a_calibration_path_that_names_no_value_is_an_error_with_the_closest(tmp_path):
    message = load_error(tmp_path, ('paths = ["sources.screw_nut.preload"]', 'paths = ["sources.screw_nut.preloda"]'))
    assert message == ("calibration.parameters.screw_nut_preload.paths: 'sources.screw_nut.preloda' does not name a "
                       "value of the description; did you mean 'sources.screw_nut.preload'?")


def test_a_calibration_path_to_a_word_is_an_error(tmp_path):
    message = load_error(tmp_path, ('paths = ["sources.screw_nut.preload"]', 'paths = ["sources.screw_nut.model"]'))
    assert message == "calibration.parameters.screw_nut_preload.paths: 'sources.screw_nut.model' does not name a number"


def test_check_refuses_a_calibration_typo_in_one_line(tmp_path, capsys):
    path = tmp_path / "variant.toml"
    path.write_text(BENCH.replace('paths = ["sources.screw_nut.preload"]', 'paths = ["sources.screw_nut.prelod"]', 1),
                    encoding="utf-8")
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "calibration.parameters.screw_nut_preload.paths: 'sources.screw_nut.prelod'" in err
