"""`feedtherm calibrate --workers N | --scheduler ADDRESS`: the runs of each evaluation on one Dask
cluster kept for the whole calibration, the serial calibration's files to the last digit."""

import json
import os
import subprocess
import sys

import pytest

# One parameter fitted to two conditions, and the leave-one-out folds: a few dozen runs.
ARGS = ["--fit", "I,II", "--params", "screw_nut_preload", "--cross-validate"]


def calibrate(cwd, *args):
    environ = {k: v for k, v in os.environ.items() if k != "DASK_SCHEDULER_ADDRESS"}
    return subprocess.run([sys.executable, "-m", "feedtherm", "calibrate", *args], capture_output=True, text=True,
                          timeout=600, cwd=cwd, env=environ)


def without_wall_times(value):
    """``value`` with every ``wall_time_s`` (the fit's and each fold's) left out."""
    if isinstance(value, dict):
        return {k: without_wall_times(v) for k, v in value.items() if k != "wall_time_s"}
    if isinstance(value, list):
        return [without_wall_times(v) for v in value]
    return value


def files(folder):
    """Every file of a calibration's folder; calibration.json without its wall times."""
    out = {}
    for path in sorted(folder.iterdir()):
        if path.name == "calibration.json":
            document = json.loads(path.read_text())
            assert document["wall_time_s"] > 0
            out[path.name] = without_wall_times(document)
        else:
            out[path.name] = path.read_bytes()
    return out


def test_two_workers_give_the_serial_calibration_exactly(tmp_path):
    serial = calibrate(tmp_path, *ARGS, "--workers", "1", "--out", "serial")
    assert serial.returncode == 0, serial.stderr
    parallel = calibrate(tmp_path, *ARGS, "--workers", "2", "--out", "parallel")
    assert parallel.returncode == 0, parallel.stderr
    assert parallel.stderr == ""  # no Dask chatter
    expected = files(tmp_path / "serial")
    assert {"calibration.json", "calibrated.toml", "heldout.csv"} <= set(expected)
    assert expected["calibration.json"]["model_runs"] > 10
    assert files(tmp_path / "parallel") == expected  # every number, to the last digit
    assert sorted(p.name for p in tmp_path.iterdir()) == ["parallel", "serial"]  # no dask scratch space


@pytest.mark.parametrize("args, fragment", [
    (["--workers", "0"], "--workers"),
    (["--workers", "2", "--scheduler", "127.0.0.1:8786"], "--scheduler: not allowed with argument --workers"),
    (["--scheduler", "localhost"], "--scheduler: 'localhost' is not a scheduler address"),
])
def test_bad_execution_choices_are_one_line(tmp_path, args, fragment):
    result = calibrate(tmp_path, *ARGS, *args, "--out", "out")
    assert result.returncode == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0], result.stderr
    assert list(tmp_path.iterdir()) == []
