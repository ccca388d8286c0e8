"""`feedtherm run` with bad input: one line, exit 2, no traceback, nothing written.

Every case here fails before the model is imported, so these tests hold whether or not
`feedtherm.simulate` exists yet.
"""

import subprocess
import sys
import types

import numpy as np
import pytest

from feedtherm import cli

BAD_HEADER = "time,screw_rpm,nut_rpm,ambient_C\n0,396,360,20\n"


def run(tmp_path, *args):
    """`python -m feedtherm run ...` in an empty working directory (where `out/` would go)."""
    return subprocess.run([sys.executable, "-m", "feedtherm", "run", *args], capture_output=True, text=True,
                          timeout=120, cwd=tmp_path)


def assert_one_line_error_and_nothing_written(result, tmp_path, *fragments, inputs=()):
    assert result.returncode == 2, result.stderr
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("feedtherm: error: ") and "Traceback" not in result.stderr
    for fragment in fragments:
        assert fragment in lines[0], lines[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(inputs)  # no out/, no staging directory


@pytest.mark.parametrize(
    "args, fragments",
    [
        (["--condition", "I", "--duration", "-5"], ["--duration", "positive", "'-5'"]),
        (["--condition", "I", "--duration", "nan"], ["--duration", "positive"]),
        (["--condition", "I", "--sample-interval", "0"], ["--sample-interval", "positive", "'0'"]),
        (["--condition", "I", "--sample-interval", "ten"], ["--sample-interval", "'ten'"]),
        (["--condition", "I", "--cycle", "I_then_standstill"], ["--cycle", "not allowed with", "--condition"]),
        ([], ["one of the arguments --condition --test --cycle is required"]),
        (["--condition", "IX"], ["no condition or test 'IX'", "I, II, III, IV, V"]),
        (["--cycle", "I_then_standstil"], ["'I_then_standstil'", "I_then_standstill"]),
        (["--cycle", "missing.csv"], ["'missing.csv'", "nor an existing CSV file"]),
        (["--condition", "I", "--model", "ansys"], ["--model", "no model 'ansys'", "fast, fem"]),
        (["--condition", "I", "--model", "fem", "--mesh", "huge"], ["--mesh", "invalid choice: 'huge'"]),
        (["--condition", "I", "--model", "fem", "--factor-memory", "-2"], ["--factor-memory", "positive", "GB", "'-2'"]),
        (["--condition", "I", "--model", "fem", "--factor-memory", "0"], ["--factor-memory", "positive", "'0'"]),
        (["ballscrew_example", "--condition", "v10", "--mode", "paper"], ["--mode paper", "no overlay of printed values"]),
        (["no_such_bench.toml", "--condition", "I"], ["no_such_bench.toml: no such file"]),
    ],
)
def test_bad_arguments(tmp_path, args, fragments):
    assert_one_line_error_and_nothing_written(run(tmp_path, *args), tmp_path, *fragments)


def test_a_cycle_csv_with_a_wrong_header(tmp_path):
    (tmp_path / "cycle.csv").write_text(BAD_HEADER)
    result = run(tmp_path, "--cycle", "cycle.csv", "--duration", "3600")
    assert_one_line_error_and_nothing_written(result, tmp_path, "cycle.csv: line 1: header must be",
                                              "got time,screw_rpm", inputs=["cycle.csv"])


def test_a_cycle_csv_with_a_bad_row_fails_without_a_duration_too(tmp_path):
    (tmp_path / "cycle.csv").write_text("time_s,screw_rpm,nut_rpm,ambient_C\n0,396,360,20\n60,fast,0,20\n")
    result = run(tmp_path, "--cycle", "cycle.csv")
    assert_one_line_error_and_nothing_written(result, tmp_path, "cycle.csv: line 3", "must be numbers",
                                              inputs=["cycle.csv"])


def test_an_out_path_that_is_a_file(tmp_path):
    (tmp_path / "results").write_text("not a directory")
    result = run(tmp_path, "--condition", "I", "--out", "results")
    assert_one_line_error_and_nothing_written(result, tmp_path, "results", "not a directory", inputs=["results"])


def test_an_out_path_below_a_file(tmp_path):
    (tmp_path / "results").write_text("not a directory")
    result = run(tmp_path, "--condition", "I", "--out", "results/run1")
    assert_one_line_error_and_nothing_written(result, tmp_path, "is a file", inputs=["results"])


# --------------------------------------------------------------------------- the hand-over to simulate


def fake_solution():
    """Just enough of a Solution for the files and the final line (2 samples, 2 cells)."""
    from feedtherm.solution import EnergyBalance, Solution

    times = np.array([0.0, 10.0])
    sensors = {"T1": np.array([293.15, 294.15]), "T6": np.array([293.15, 293.15])}
    field = np.full((2, 2), 293.65)
    return Solution(
        times=times, sensors=sensors, elongation=np.array([0.0, 1e-6]), screw_x=np.array([0.0, 0.1]),
        screw_temperature=field, screw_displacement=np.zeros((2, 2)), table_x=np.array([0.02, 0.05, 0.08]),
        positioning_error=np.array([[0.0, 0.0, 0.0], [0.2e-6, 0.5e-6, 0.8e-6]]), nut_offset=np.zeros(2),
        part_temperatures={}, cycle_times=times, cycle_sensors=sensors, cycle_elongation=np.zeros(2),
        final={"T1": 294.15, "T6": 293.15, "D": 1e-6}, steady={"T1": 295.15, "T6": 293.15, "D": 2e-6},
        equilibrium_time=None, energy=EnergyBalance(10.0, 5.0, 5.0),
        info={"condition": "I", "model": "fast", "mode": "physics", "wall_time_s": 0.0, "time_step_s": 10.0,
              "unknowns": 4, "provenance": {}, "ambient_sensor": "T6"},
    )


def test_valid_arguments_reach_the_plan_and_the_files_appear(tmp_path, monkeypatch, capsys):
    calls = []

    def execute(plan, progress):
        calls.append(plan)
        progress(0.5)
        return fake_solution()

    monkeypatch.setitem(sys.modules, "feedtherm.simulate", types.SimpleNamespace(execute=execute))
    monkeypatch.chdir(tmp_path)
    assert cli.main(["run", "--condition", "I", "--duration", "60", "--sample-interval", "5"]) == 0
    (plan,) = calls
    assert plan.loaded.origin == "bundled:paper" and plan.label == "I" and plan.mode == "physics"
    assert plan.model.name == "fast" and not plan.single_drive and plan.sample_interval == 5.0
    assert (plan.options.motion, plan.options.mesh, plan.options.solver) == ("resolved", "coarse", "auto")
    (segment,) = plan.segments
    assert (segment.t0, segment.t1) == (0.0, 60.0)
    # Table 5, condition I: 396 and 360 rpm at 20 °C
    point = segment.bc.point
    assert (point.screw_rpm, point.nut_rpm, point.ambient) == (pytest.approx(396.0), pytest.approx(360.0),
                                                               pytest.approx(293.15))
    out = capsys.readouterr().out
    assert out == "out/paper_I_physics: T1 21.00 °C, D 1.00 µm, energy balance error 0 %\n"
    assert len(list((tmp_path / "out" / "paper_I_physics").iterdir())) == 9  # 5 tables, 4 plots


def test_the_progress_bar_waits_for_a_slow_run():
    clock = iter([100.0, 100.5, 101.5, 102.0]).__next__
    with cli._LazyProgress(enabled=True, delay=1.0, clock=clock) as progress:  # started at 100.0
        progress(0.1)  # 0.5 s in: nothing shown
        assert progress._bar is None
        progress(0.6)  # 1.5 s in: the bar appears at 60 %
        assert progress._bar.tasks[0].completed == pytest.approx(0.6)
        progress(1.0)
        assert progress._bar.tasks[0].completed == pytest.approx(1.0)


def test_no_progress_bar_when_stdout_is_not_a_terminal():
    with cli._LazyProgress(enabled=False, delay=0.0) as progress:
        progress(0.5)
        assert progress._bar is None


def test_a_run_of_too_many_steps_is_refused_before_it_starts(tmp_path):
    """99,000 rpm against 0 rpm: the table at 990 m/min, 20 steps per 200 mm stroke, 600 s:
    600 s / (0.2 m / (20 * 16.5 m/s)) = 990,000 steps > 500,000 (the run hung before the limit)."""
    from feedtherm.benches import bench

    text = bench("paper").description.read_text(encoding="utf-8")
    (tmp_path / "fast.toml").write_text(text.replace('screw_speed = "396 rpm"\nnut_speed = "360 rpm"',
                                                     'screw_speed = "99000 rpm"\nnut_speed = "0 rpm"', 1))
    result = run(tmp_path, "fast.toml", "--condition", "I", "--duration", "600", "--out", "out")
    assert_one_line_error_and_nothing_written(result, tmp_path, "990,000 time steps", "more than the 500,000",
                                              "--motion averaged", inputs=["fast.toml"])


#: [s] CPU time of a run past its imports, loading and build, inside the integration (about 0.8 s
#: gets there; a 300,000 s run takes far longer than this in all).
INTEGRATING_CPU_S = 2.0


def cpu_seconds(pid: int) -> float | None:
    """The CPU time [s] process ``pid`` has used, from Linux's /proc (fields 14 and 15 of its
    stat line, utime and stime in clock ticks); None where there is no /proc."""
    import os
    from pathlib import Path

    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except (OSError, IndexError):
        return None
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def test_sigterm_stops_a_run_cleanly(tmp_path):
    """SIGTERM mid-run: exit 128 + 15, one line, no output directory and no staging folder."""
    import signal
    import time

    process = subprocess.Popen([sys.executable, "-m", "feedtherm", "run", "paper", "--condition", "III",
                                "--duration", "300000", "--out", "out"], cwd=tmp_path, text=True,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    # sent once the run has used the CPU time that takes it inside the integration (on a loaded
    # machine that is later in wall time, not sooner); without /proc, after a generous 6 s
    deadline = time.monotonic() + 60.0
    while process.poll() is None and time.monotonic() < deadline:
        used = cpu_seconds(process.pid)
        if used is None:
            time.sleep(6.0)
            break
        if used >= INTEGRATING_CPU_S:
            break
        time.sleep(0.05)
    assert process.poll() is None, process.communicate()
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=60)
    assert process.returncode == 128 + signal.SIGTERM, err
    assert err.strip() == "feedtherm: terminated"
    assert list(tmp_path.iterdir()) == []


def test_the_fe_model_refuses_a_material_without_elastic_constants(tmp_path):
    # the fast model needs only the expansion; the FE model solves the displacements in 3D
    from feedtherm.benches import bench

    text = bench("paper").description.read_text(encoding="utf-8")
    old = 'youngs_modulus = "0.05 GPa"\n'
    assert old in text
    (tmp_path / "no_modulus.toml").write_text(text.replace(old, "", 1), encoding="utf-8")
    result = run(tmp_path, "no_modulus.toml", "--condition", "I", "--model", "fem", "--duration", "600")
    assert_one_line_error_and_nothing_written(result, tmp_path, "materials.belt_rubber.youngs_modulus",
                                              "needs it for every part's material", inputs=["no_modulus.toml"])
