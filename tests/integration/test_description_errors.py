"""Descriptions that pass the schema but that no model can run as meant (issue 15's cases).

Each gets one line naming the field and the reason, exit 2, no traceback and nothing written,
from `check` and from every command that would run it (`heat`, `run`); a valid spelling of a
value (a speed in 1/min or Hz) gives the same result as the bench's own.
"""

import json
import subprocess
import sys

import pytest

from feedtherm import cli
from feedtherm.benches import bench
from bench_text import paper_text  # tests/: the paper bench with changes made

COMMANDS = (["check"], ["heat", "--condition", "I"], ["run", "--condition", "I", "--duration", "600", "--out", "out"])


def variant(tmp_path, *changes: tuple[str, str]) -> str:
    path = tmp_path / "variant.toml"
    path.write_text(paper_text(*changes), encoding="utf-8")
    return str(path)


def feedtherm(tmp_path, *args):
    """The command in a child process, as a user runs it."""
    return subprocess.run([sys.executable, "-m", "feedtherm", *args], capture_output=True, text=True,
                          timeout=300, cwd=tmp_path)


def feedtherm_here(tmp_path, monkeypatch, capsys, *args):
    """The command in this process (an uncaught exception fails the test as a traceback would)."""
    monkeypatch.chdir(tmp_path)
    code = cli.main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


JOINT_0 = '[[joints]]\nbetween = ["front_bearing", "front_housing"]\ntcr = "1.25e-3 m^2*K/W"'

CASES = {
    "an ambient of 20 K (a typo for 20 degC)": (
        [('ambient = "20 degC"', 'ambient = "20 K"')],
        ["conditions.I.ambient", "-150 to 1000 degC", 'did you mean "20 degC"?']),
    "a length of 1e400 mm (overflows to inf)": (
        [('lead = "10 mm"', 'lead = "1e400 mm"')], ["kinematics.lead", "must be a finite number"]),
    "a screw speed of 1e30 rpm (hung the run)": (
        [('screw_speed = "396 rpm"', 'screw_speed = "1e30 rpm"')],
        ["conditions.I.screw_speed", "|value| <= 100000 rpm"]),
    "an extra heat of 1e400 W": (
        [('[sources.rear_bearing]', '[sources.extra]\nmodel = "fixed"\npower = "1e400 W"\ninto = { worktable = 1.0 }\n\n'
                                    '[sources.rear_bearing]')],
        ["sources.extra.power", "finite"]),
    "a conductivity of 1e30 W/(m*K)": (
        [('conductivity = "46 W/(m*K)"', 'conductivity = "1e30 W/(m*K)"')],
        ["conductivity", "0 to 5000 W/(m*K)"]),
    "lateral faces on a box part": (
        [('faces = ["+z"]', 'faces = ["lateral"]')], ["surfaces.worktable.faces", "'lateral' does not exist on a box"]),
    "a sensor at x = 5000 mm": (
        [('position = ["245 mm", "0 mm", "45 mm"]', 'position = ["5000 mm", "0 mm", "45 mm"]')],
        ["sensors.T3.position", "outside part 'nut_housing'"]),
    "a joint listed twice": (
        [(JOINT_0, JOINT_0.replace("[[joints]]", '[[joints]]\nbetween = ["front_housing", "front_bearing"]\n'
                                   'tcr = "1.25e-3 m^2*K/W"\narea = "1e-3 m^2"\n\n[[joints]]', 1))],
        ["joints[1].between", "already joined by joints[0]"]),
    "calibration bounds upper before lower": (
        [('bounds = ["1000 N", "6300 N"]', 'bounds = ["6300 N", "1000 N"]')],
        ["calibration.parameters.front_bearing_preload.bounds", "lower bound (6300 N) must be below the upper"]),
    "a calibration bound in mm for a force": (
        [('bounds = ["1000 N", "6300 N"]', 'bounds = ["1 mm", "3 mm"]')],
        ["front_bearing_preload.bounds", "'1 mm' does not have the dimension of the values it bounds (N)"]),
    "a lead without its unit": (
        [('lead = "10 mm"', 'lead = 10')], ["kinematics.lead", 'write it with one, e.g. "10 mm"']),
    "-300 degC": (
        [('ambient = "20 degC"', 'ambient = "-300 degC"')], ["conditions.I.ambient", "outside the accepted range"]),
    "a stroke longer than the screw": (
        [('stroke = "200 mm"', 'stroke = "900 mm"')], ["kinematics.stroke", "longer than the screw"]),
    "the laser's mount outside its part": (
        [('mount = { part = "base", point = ["480 mm", "0 mm", "-60 mm"] }',
          'mount = { part = "base", point = ["480 mm", "0 mm", "60 mm"] }')],
        ["mechanics.elongation.mount.point", "lies outside part 'base'"]),
    "a zero sensing direction": (
        [('direction = [1, 0, 0]', 'direction = [0, 0, 0]')], ["mechanics.elongation.direction", "zero vector"]),
    "a support on an unknown part": (
        [('part = "base"\npoint = ["650 mm"', 'part = "bsae"\npoint = ["650 mm"')],
        ["mechanics.supports[1].part", "no part named 'bsae'", "did you mean 'base'"]),
    "a structure the supports do not hold": (
        [('fix = ["z"]', 'fix = ["y"]')], ["mechanics.supports", "free to move", "the whole structure: rotate about x"]),
}


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("command", COMMANDS, ids=lambda c: c[0])
def test_every_command_refuses_with_one_line(tmp_path, monkeypatch, capsys, case, command):
    changes, fragments = CASES[case]
    path = variant(tmp_path, *changes)
    code, out, err = feedtherm_here(tmp_path, monkeypatch, capsys, command[0], path, *command[1:])
    assert code == 2, (out, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    for fragment in fragments:
        assert fragment in lines[0], lines[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["variant.toml"]  # nothing written


def test_the_refusal_is_exit_2_without_a_traceback_in_a_real_process(tmp_path):
    path = variant(tmp_path, ('screw_speed = "396 rpm"', 'screw_speed = "1e30 rpm"'))
    result = feedtherm(tmp_path, "run", path, "--condition", "I", "--duration", "1", "--out", "out")
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert result.stderr.count("\n") == 1 and "conditions.I.screw_speed" in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["variant.toml"]


def test_a_part_that_reaches_no_ambient_is_an_error(tmp_path, monkeypatch, capsys):
    """A part with no surface and no joint has no steady state: found before any run."""
    path = variant(tmp_path, ("[parts.rear_bearing]", '[parts.loose]\nmaterial = "gcr15"\n'
                              'boxes = [{ origin = ["0 mm", "0 mm", "500 mm"], size = ["10 mm", "10 mm", "10 mm"] }]\n\n'
                              "[parts.rear_bearing]"))
    code, _, err = feedtherm_here(tmp_path, monkeypatch, capsys, "check", path)
    assert code == 2
    assert "parts.loose: no surface and no chain of joints connects it to the ambient" in err


@pytest.mark.parametrize("spelling", ["396 1/min", "6.6 Hz", "41.469023 rad/s"])
def test_a_speed_in_any_spelling_gives_the_benchs_heat(tmp_path, monkeypatch, capsys, spelling):
    path = variant(tmp_path, ('screw_speed = "396 rpm"', f'screw_speed = "{spelling}"'))
    heat = json.loads(feedtherm_here(tmp_path, monkeypatch, capsys, "heat", path, "--condition", "I", "--json")[1])
    reference = json.loads(feedtherm_here(tmp_path, monkeypatch, capsys, "heat", "paper", "--condition", "I", "--json")[1])
    assert heat["screw_rpm"] == pytest.approx(396.0, rel=1e-6)
    assert heat["heat_W"] == pytest.approx(reference["heat_W"], rel=1e-6)


@pytest.mark.parametrize(
    "bench_name, change, fragment",
    [
        # the f0 = inf (a Palmgren bearing of the ball-screw example)
        ("ballscrew_example", ("f0 = 4.0", "f0 = inf"), "sources.front_bearing.f0: must be a finite number, got inf"),
        # NaN where a plain number has an upper bound: named as not finite, not "should be less than 0.5"
        ("ballscrew_example", ("poisson_ratio = 0.29", "poisson_ratio = nan"), "poisson_ratio: must be a finite number, got nan"),
        # a temperature without its unit: the hint names degC, not K
        ("paper", ('reference = "20 degC"', "reference = 20"), 'temperatures.reference: 20 has no unit; write it with one, e.g. "20 degC"'),
    ],
)
def test_messages_name_what_is_wrong(tmp_path, monkeypatch, capsys, bench_name, change, fragment):
    text = bench(bench_name).description.read_text(encoding="utf-8")
    assert change[0] in text, f"test fixture out of date: {change[0]!r}"
    path = tmp_path / "variant.toml"
    path.write_text(text.replace(*change, 1), encoding="utf-8")
    code, _, err = feedtherm_here(tmp_path, monkeypatch, capsys, "check", str(path))
    assert code == 2 and err.count("\n") == 1 and fragment in err, err
