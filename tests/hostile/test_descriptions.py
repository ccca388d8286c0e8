"""Descriptions with careless values: refused in one line that says what is wrong with the value and
what is allowed, or, where the value is possible but suspect, warned of by the field; and the spellings
data sheets use read as they mean."""

from __future__ import annotations

import math

import pytest

from feedtherm.benches import bench
from feedtherm.system.load import load_system
from bench_text import paper_text  # tests/: the paper bench with changes made

OVERLAY = (bench("paper").folder / "overlay.toml").read_text(encoding="utf-8")


def variant(folder, *changes: tuple[str, str], name: str = "variant.toml") -> str:
    """The paper bench's description with ``changes`` (old, new) made, written to ``folder/name``."""
    (folder / name).write_text(paper_text(*changes), encoding="utf-8")
    return name


# --------------------------------------------------------------------------- temperatures.initial

@pytest.mark.parametrize("initial, says", [
    # a temperature outside the range: what is wrong with it, and the word allowed instead
    ('"0 K"', ("temperatures.initial: '0 K' lies outside the accepted range, -150 to 1000 degC",
               "Allowed instead: 'ambient'")),
    ('"5000 degC"', ("temperatures.initial: '5000 degC' lies outside the accepted range", "'ambient'")),
    ('"inf degC"', ("temperatures.initial: must be a finite number, got 'inf degC'", "'ambient'")),
    ("20", ('temperatures.initial: 20 has no unit; write it with one, e.g. "20 degC"', "'ambient'")),
    # a misspelt word: the words allowed, and that a quantity is allowed too
    ('"ambiant"', ("temperatures.initial: 'ambiant' is not allowed; allowed values: 'ambient', or a quantity",)),
])
def test_an_initial_temperature_is_refused_with_what_is_wrong_and_what_is_allowed(refused, tmp_path, initial,
                                                                                   says):
    path = variant(tmp_path, ('initial = "ambient"', f"initial = {initial}"))
    line = refused("check", path, says=says)
    assert "literal[" not in line and "function-before" not in line


def test_a_tests_start_outside_the_range_says_so(refused, tmp_path):
    path = variant(tmp_path, ('start = "20 degC"', 'start = "0 K"'))
    refused("check", path, says=("tests.IV_lab_start.start: '0 K' lies outside the accepted range",
                                 "Allowed instead: 'ambient' or 'measured'"))


def test_a_soak_without_a_name_names_its_field(refused, tmp_path):
    path = variant(tmp_path, ('start = "20 degC"', 'start = { soaked = "" }'))
    refused("check", path, says=("tests.IV_lab_start.start.soaked:",))


# --------------------------------------------------------------------------- calibration bounds

@pytest.mark.parametrize("bounds, says", [
    ("[0.2, inf]", ("calibration.parameters.motor_no_load.bounds[1]: must be a finite number, got inf",)),
    ("[-inf, 5.0]", ("calibration.parameters.motor_no_load.bounds[0]: must be a finite number, got -inf",)),
    ("[0.2, nan]", ("calibration.parameters.motor_no_load.bounds[1]: must be a finite number, got nan",)),
    ("[0.2, 1e400]", ("calibration.parameters.motor_no_load.bounds[1]: must be a finite number, got inf",)),
    ('[0.2, "inf"]', ("calibration.parameters.motor_no_load.bounds:", "must be a finite number, got 'inf'")),
])
def test_an_infinite_calibration_bound_is_refused_as_not_finite(refused, tmp_path, bounds, says):
    # the first [0.2, 5.0] is motor_no_load's
    path = variant(tmp_path, ("bounds = [0.2, 5.0]", f"bounds = {bounds}"))
    line = refused("check", path, says=says)
    assert ".str:" not in line and "valid string" not in line


def test_an_infinite_bound_with_a_unit_is_refused_as_not_finite(refused, tmp_path):
    path = variant(tmp_path, ('bounds = ["50 N", "365 N"]', 'bounds = ["50 N", "inf N"]'))
    refused("check", path, says=("calibration.parameters.screw_nut_preload.bounds: must be a finite number, "
                                 "got 'inf N'",))


def test_an_infinite_uncertainty_range_is_refused_as_not_finite(refused, tmp_path):
    path = variant(tmp_path, ("range = [0.08, 0.15]", "range = [0.08, inf]"))
    refused("check", path, says=("uncertainty.parameters.screw_nut_friction.range[1]: must be a finite number, "
                                 "got inf",))


# --------------------------------------------------------------------------- standstill

def test_a_standstill_with_a_stated_feed_implies_no_lead(warned, tmp_path):
    # both motors at 360 rpm: the table stands still whatever the lead, not "a lead of inf mm"
    path = variant(tmp_path, ('screw_speed = "396 rpm"', 'screw_speed = "360 rpm"'))
    text = warned("check", path, says=("conditions.I.feed_speed", "stated 0.18 m/min", "= 0 m/min",
                                       "the table stands still"))
    line = next(line for line in text.splitlines() if "conditions.I.feed_speed" in line)
    assert "inf" not in line and "implies a lead" not in line


def test_a_stated_standstill_of_turning_motors_implies_no_lead(warned, tmp_path):
    path = variant(tmp_path, ('feed_speed = "0.18 m/min"', 'feed_speed = "0 m/min"'))
    text = warned("check", path, says=("conditions.I.feed_speed", "stated 0 m/min", "is a standstill"))
    line = next(line for line in text.splitlines() if "conditions.I.feed_speed" in line)
    assert "implies a lead of 0 mm" not in line and "lead of" not in line


# --------------------------------------------------------------------------- overlays

def with_overlay(tmp_path, overlay: str | None, *changes: tuple[str, str]) -> str:
    """A description in ``tmp_path`` whose meta.overlay names ``printed.toml``, holding ``overlay`` with
    ``changes`` made (None: no such file)."""
    if overlay is not None:
        for old, new in changes:
            assert old in overlay, f"test fixture out of date: {old!r} not in the overlay"
            overlay = overlay.replace(old, new, 1)
        (tmp_path / "printed.toml").write_text(overlay, encoding="utf-8")
    return variant(tmp_path, ('measurements = "bundled:paper"',
                              'measurements = "bundled:paper"\noverlay = "printed.toml"'))


@pytest.mark.parametrize("changes, says", [
    ([('source = "guideways"', 'source = "guideway"')],
     ("printed.toml: heat[0].source: no heat source named 'guideway'; did you mean 'guideways'?",)),
    ([('reference_condition = "I"', 'reference_condition = "VI"')],
     ("printed.toml: reference_condition: no condition named 'VI'",)),
    ([('value = "0.39 W"', 'value = "-0.39 W"')], ("printed.toml: heat[0].value: must not be negative",)),
    ([('name = "paper"', 'name = "physics"')], ("printed.toml: name: 'physics' is the mode without an overlay",)),
    ([('name = "paper"', 'name = "../../elsewhere"')], ("printed.toml: name: '../../elsewhere' is not a mode name",)),
    ([('source = "screw_motor"', 'source = "guideways"')],
     ("printed.toml: heat[1].source: 'guideways' is printed already, in heat[0]",)),
])
def test_check_refuses_a_bad_overlay_in_one_line_naming_it(refused, tmp_path, changes, says):
    refused("check", with_overlay(tmp_path, OVERLAY, *changes), says=says)


def test_check_refuses_a_missing_overlay(refused, tmp_path):
    refused("check", with_overlay(tmp_path, None), says=("printed.toml: no such overlay file",))


def test_check_lists_a_good_overlay(tmp_path, monkeypatch, capsys):
    from feedtherm.cli import main

    monkeypatch.chdir(tmp_path)
    assert main(["check", with_overlay(tmp_path, OVERLAY)]) == 0
    assert "overlay 'paper' (printed.toml, --mode paper): 6 printed heats and 6 CHTCs at condition I" in \
        capsys.readouterr().out


# --------------------------------------------------------------------------- units

@pytest.mark.parametrize("spelling", ["396 rev/min", "396 r/min", "396 1/min"])
def test_revolutions_per_minute_in_every_spelling_give_the_same_speed(tmp_path, spelling):
    path = tmp_path / variant(tmp_path, ('screw_speed = "396 rpm"', f'screw_speed = "{spelling}"'))
    speed = load_system(str(path)).system.conditions["I"].screw_speed
    assert speed == load_system("paper").system.conditions["I"].screw_speed
    assert speed == pytest.approx(396 * 2 * math.pi / 60, rel=1e-12)
