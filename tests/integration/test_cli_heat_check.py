"""`feedtherm heat` and `feedtherm check` as a user runs them (a subprocess each)."""

import json
import os
import subprocess
import sys

import pytest

from feedtherm.benches import bench

BENCH = bench("paper").description.read_text(encoding="utf-8")


def run(*args):
    return subprocess.run([sys.executable, "-m", "feedtherm", *args], capture_output=True, text=True, timeout=120)


def assert_one_line_error(result, *fragments):
    assert result.returncode != 0
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert "Traceback" not in result.stderr
    for fragment in fragments:
        assert fragment in lines[0], lines[0]


def test_heat_paper_mode_reproduces_table_1():
    result = run("heat", "--condition", "I", "--mode", "paper", "--json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["condition"] == "I" and data["mode"] == "paper"
    assert data["heat_W"]["front_bearing"] == pytest.approx(4.95)
    assert data["printed"]["overlay"] == "paper" and data["printed"]["condition"] == "I"
    for source, value in data["printed"]["heat_W"].items():
        assert data["heat_W"][source] == pytest.approx(value)
    assert set(data["heat_W"]) == {"guideways", "screw_motor", "nut_motor", "front_bearing", "nut_bearing",
                                   "rear_bearing", "screw_nut"}
    assert data["chtc_W_per_m2K"]["screw_shaft"] == pytest.approx(56.3)


def test_heat_physics_mode_prints_computed_values_beside_the_papers():
    result = run("heat", "paper", "--condition", "I")
    assert result.returncode == 0, result.stderr
    out = result.stdout
    for name in ("front_bearing", "screw_nut", "screw_shaft", "worktable", "4.95", "56.30"):
        assert name in out
    data = json.loads(run("heat", "--condition", "I", "--json").stdout)
    assert data["mode"] == "physics"
    assert data["heat_W"]["front_bearing"] != pytest.approx(4.95)  # computed, not copied
    from feedtherm.system.load import load_system

    surfaces = load_system("paper").system.surfaces
    # a surface radiates exactly when it has an emissivity (base_bottom: a covered face, 0)
    assert all((v > 0) == (surfaces[name].emissivity > 0) for name, v in data["radiation_W_per_m2K"].items())


def test_check_flags_condition_I_only():
    result = run("check")
    assert result.returncode == 0, result.stderr
    warnings = [line for line in result.stdout.splitlines() if line.startswith("warning:")]
    assert len(warnings) == 1
    assert "conditions.I.feed_speed" in warnings[0] and "0.36 m/min" in warnings[0]


def test_check_states_what_its_run_costs_scale_with(tmp_path):
    """The models' sizes once, then each run's steps and times; --duration sets the runs' length."""
    env_cache = {"FEEDTHERM_CACHE": str(tmp_path)}  # an empty cache: no mesh made yet
    result = subprocess.run([sys.executable, "-m", "feedtherm", "check", "paper", "--duration", "600"],
                            capture_output=True, text=True, timeout=120, env={**os.environ, **env_cache})
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert "fast 1,474 nodes; fem coarse ~13,000 nodes (not meshed yet); fem medium ~44,000 nodes (not meshed yet)" in out
    assert "41 grid positions of the moving group" in out
    assert "run cost of conditions.I (10.0 min simulated):" in out
    # 600 s in steps of 1.667 s; the FE and reduced models' windows in steps of 8.333 s
    assert "--motion resolved: 360 steps (72 in the FE and reduced models, window by window); about fast" in out
    assert "estimated times:" in out and "power law in the model's nodes" in out


def test_check_refuses_a_duration_shorter_than_a_step():
    assert_one_line_error(run("check", "paper", "--duration", "0.5"), "--duration", "shorter than one time step")


def test_check_accepts_a_file(tmp_path):
    path = tmp_path / "bench.toml"
    path.write_text(BENCH)
    result = run("check", str(path))
    assert result.returncode == 0 and str(path) in result.stdout


@pytest.mark.parametrize(
    "content, fragments",
    [
        (BENCH.replace('outer_diameter = "32 mm" }]', 'outer_diameter = "-32 mm" }]', 1), ["outer_diameter", "must be positive"]),
        (BENCH.replace('[parts.screw]', '[parts.screww]', 1), ["no part named 'screw'", "did you mean 'screww'"]),
        (BENCH.replace('lead = "10 mm"', 'leed = "10 mm"', 1), ["unknown key 'leed'", "did you mean 'lead'"]),
        (BENCH.replace('conductivity = "48 W/(m*K)"', 'conductivity = "-48 W/(m*K)"', 1), ["materials.gcr15.conductivity", "must be positive"]),
        ("[meta\n", ["invalid TOML"]),
        ("", ["empty"]),
    ],
)
@pytest.mark.parametrize("command", [["check"], ["heat", "--condition", "I"]])
def test_bad_descriptions_get_one_line(tmp_path, content, fragments, command):
    path = tmp_path / "bad.toml"
    path.write_text(content)
    result = run(command[0], str(path), *command[1:])
    assert_one_line_error(result, str(path), *fragments)


def test_missing_file_gets_one_line(tmp_path):
    assert_one_line_error(run("check", str(tmp_path / "missing.toml")), "no such file")


def test_unknown_condition_and_bad_mode_get_one_line():
    assert_one_line_error(run("heat", "--condition", "VI"), "--condition", "no condition 'VI'", "I, II, III, IV, V")
    assert_one_line_error(run("heat", "--condition", "I", "--mode", "exact"), "--mode: must be physics or paper",
                          "got 'exact'")
    assert_one_line_error(run("heat"), "--condition")


def test_modes_name_the_slow_mass_and_add_up():
    data = json.loads(run("modes", "--condition", "I", "--count", "4", "--json").stdout)
    taus = [m["time_constant_s"] for m in data["modes"]]
    assert taus == sorted(taus, reverse=True)  # slowest first
    for mode in data["modes"]:
        assert sum(mode["part_shares"].values()) == pytest.approx(1.0)
        assert mode["settling_95_s"] == pytest.approx(mode["time_constant_s"] * 2.9957, rel=1e-4)
    assert set(data["modes"][0]["sensor_amplitude_K"]) == {"T1", "T2", "T3", "T4", "T5"}
    assert data["capacity_J_per_K"]["base"] > data["capacity_J_per_K"]["screw"] > 0


def test_modes_refuse_an_unknown_condition():
    assert_one_line_error(run("modes", "--condition", "IX"), "--condition", "IX")


def test_a_reader_that_goes_away_gets_no_traceback():
    """`feedtherm check | head`: the pipe closed before the output is written ends quietly."""
    import subprocess
    import sys

    proc = subprocess.Popen([sys.executable, "-m", "feedtherm", "check", "paper"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE)
    proc.stdout.close()  # nobody reads: the first flush of stdout meets a broken pipe
    _, err = proc.communicate(timeout=120)
    assert b"Traceback" not in err and b"BrokenPipeError" not in err, err.decode()
    assert proc.returncode == 1
