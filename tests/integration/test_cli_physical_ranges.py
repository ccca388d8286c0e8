"""Every number `check` evaluates is finite and physical, or one line names the field (issue 35,
item 2): out-of-range values refused by their declared range, heats and viscosities that leave
what a machine can be refused where they are evaluated, by `heat`, `check` and `run` alike, with
exit 2, nothing written, no traceback and no RuntimeWarning."""

import subprocess
import sys
from pathlib import Path

import pytest

from feedtherm.benches import bench
from feedtherm.cli import main

TEXTS = {name: bench(name).description.read_text(encoding="utf-8") for name in ("paper", "ballscrew_example")}
CONDITION = {"paper": "I", "ballscrew_example": "v5"}

# (bench, the text replaced, its replacement, what the one line must say)
CASES = {
    "tiny torque constant": ("paper", 'torque_constant = "0.39 N*m/A"', 'torque_constant = "1e-300 N*m/A"',
                             ["sources.screw_motor.losses.torque_constant: '1e-300 N*m/A' lies outside the accepted "
                              "range, 0.0001 to 1000 N*m/A"]),
    "huge grease viscosity": ("paper", 'grease_viscosity = "1 Pa*s"', 'grease_viscosity = "1e300 Pa*s"',
                              ["sources.screw_nut.grease_viscosity: '1e300 Pa*s' lies outside the accepted range"]),
    "huge oil viscosity": ("ballscrew_example", 'lubricant_viscosity = "100 mm^2/s"',
                           'lubricant_viscosity = "1e300 mm^2/s"',
                           ["sources.front_bearing.lubricant_viscosity: '1e300 mm^2/s' lies outside the accepted "
                            "range, 0 to 100000 mm^2/s"]),
    "tiny efficiency": ("ballscrew_example", "efficiency = 0.80", "efficiency = 1e-300",
                        ["sources.servo_motor.efficiency: 1e-300 is below 0.1"]),
    "huge heat factor": ("paper", "into = { screw_motor = 1.0 }", "into = { screw_motor = 1.0 }\nheat_factor = 1e300",
                         ["sources.screw_motor.heat_factor: 1e+300 lies outside the accepted range, 0.01 to 100"]),
    "flank at 90 deg": ("paper", 'flank_half_angle = "15 deg"', 'flank_half_angle = "90 deg"',
                        ["sources.screw_nut.flank_half_angle: must lie from 0 to under 45 deg", "got 90 deg"]),
    "flank at 1000 deg": ("paper", 'flank_half_angle = "15 deg"', 'flank_half_angle = "1000 deg"',
                          ["sources.screw_nut.flank_half_angle: '1000 deg' lies outside the accepted range, "
                           "0 to 90 deg"]),
    "tiny contact resistance": ("paper", 'tcr = "1.25e-3 m^2*K/W"', 'tcr = "1e-300 m^2*K/W"',
                                ["joints[0].tcr: '1e-300 m^2*K/W' lies outside the accepted range, "
                                 "1e-07 to 10000 m^2*K/W"]),
    # In range, but the copper loss of 0.7 N m at 1e-4 N m/A (7,000 A) is 4e8 W: found where it is evaluated.
    "heat beyond a megawatt": ("paper", 'torque_constant = "0.39 N*m/A"', 'torque_constant = "1e-4 N*m/A"',
                               ["sources.screw_motor: its heat here is", "outside 0 to 1e+06 W"]),
    # An oil far below its pour point: the real problem named, not advice about units.
    "ambient too cold for the oil": ("paper", 'ambient = "20 degC"', 'ambient = "-150 degC"',
                                     ["sources.rear_bearing.lubricant: the oil's viscosity at -140 degC (the ambient "
                                      "-150 degC plus temperatures.convection_delta_t 10 K)", "the oil is too cold"]),
}


def variant(tmp_path, case: str):
    name, old, new, _ = CASES[case]
    text = TEXTS[name]
    assert old in text, f"test fixture out of date: {old!r}"
    path = tmp_path / "variant.toml"
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    return path, CONDITION[name]


def one_line(capsys, path, fragments) -> str:
    captured = capsys.readouterr()
    assert captured.out == ""
    lines = captured.err.splitlines()
    assert len(lines) == 1, captured.err
    assert lines[0].startswith(f"feedtherm: error: {path}: "), lines[0]
    for fragment in fragments:
        assert fragment in lines[0], lines[0]
    assert "Traceback" not in captured.err and "RuntimeWarning" not in captured.err
    assert "pass m²/s" not in captured.err  # the advice for a value given in mm²/s as m²/s
    return lines[0]


@pytest.mark.filterwarnings("error::RuntimeWarning")  # a RuntimeWarning anywhere fails the test
@pytest.mark.parametrize("command", ["heat", "check", "run"])
@pytest.mark.parametrize("case", sorted(CASES))
def test_each_case_is_one_line_naming_the_field(tmp_path, capsys, monkeypatch, case, command):
    path, condition = variant(tmp_path, case)
    monkeypatch.chdir(tmp_path)  # where run's default out/ would go
    args = {"heat": ["heat", str(path), "--condition", condition],
            "check": ["check", str(path)],
            "run": ["run", str(path), "--condition", condition, "--duration", "60", "--no-plots"]}[command]
    assert main(args) == 2
    one_line(capsys, path, CASES[case][3])
    assert [p.name for p in tmp_path.iterdir()] == ["variant.toml"]  # nothing written


def test_check_names_the_condition_of_an_evaluated_heat(tmp_path, capsys):
    path, _ = variant(tmp_path, "heat beyond a megawatt")
    assert main(["check", str(path)]) == 2
    assert one_line(capsys, path, []).startswith(f"feedtherm: error: {path}: conditions.I: sources.screw_motor: ")


def test_a_run_in_a_child_process_writes_no_runtime_warning(tmp_path):
    # The warnings module of a child process prints to its stderr: what a user would see.
    path, condition = variant(tmp_path, "heat beyond a megawatt")
    result = subprocess.run([sys.executable, "-m", "feedtherm", "run", str(path), "--condition", condition,
                             "--duration", "60"], capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr.startswith(f"feedtherm: error: {path}: sources.screw_motor: its heat here is ")
    assert result.stderr.count("\n") == 1, result.stderr
    assert [p.name for p in tmp_path.iterdir()] == ["variant.toml"]


def test_the_bundled_benches_and_the_template_stay_within_every_range(capsys):
    from feedtherm.benches import template

    for spec in [*TEXTS, str(Path(template.__file__).parent / "_template" / "description.toml")]:
        assert main(["check", spec]) == 0, capsys.readouterr().err
