"""`feedtherm calibrate --workers N | --scheduler ADDRESS`: the runs of each evaluation on one Dask
cluster kept for the whole calibration, the serial calibration's files to the last digit."""

import json
import os
import subprocess
import sys

import pytest

# One parameter fitted to two conditions' final values, and the leave-one-out folds: a few dozen
# runs, of half an hour each (SHORT_DESCRIPTION): what the test compares, the serial files against
# the parallel ones to the last digit, does not depend on how long each run lasts.
ARGS = ["--fit", "I,II", "--params", "screw_nut_preload", "--cross-validate", "--no-equilibrium"]
SHORT_DESCRIPTION = "paper_short.toml"


@pytest.fixture
def short_paper(tmp_path):
    """The paper's bench, every condition run for 30 min, as a description file in ``tmp_path``."""
    from feedtherm.benches import bench

    text = bench("paper").description.read_text(encoding="utf-8")
    conditions = [line for line in text.splitlines() if line.startswith("[conditions.")]
    assert len(conditions) == 5
    for header in conditions:
        text = text.replace(header + "\n", header + '\nduration = "30 min"\n', 1)
    (tmp_path / SHORT_DESCRIPTION).write_text(text, encoding="utf-8")
    return SHORT_DESCRIPTION


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


def test_two_workers_give_the_serial_calibration_exactly(tmp_path, short_paper):
    serial = calibrate(tmp_path, short_paper, *ARGS, "--workers", "1", "--out", "serial")
    assert serial.returncode == 0, serial.stderr
    parallel = calibrate(tmp_path, short_paper, *ARGS, "--workers", "2", "--out", "parallel")
    assert parallel.returncode == 0, parallel.stderr
    assert parallel.stderr == ""  # no Dask chatter
    expected = files(tmp_path / "serial")
    assert {"calibration.json", "calibrated.toml", "heldout.csv"} <= set(expected)
    assert expected["calibration.json"]["model_runs"] > 10
    assert files(tmp_path / "parallel") == expected  # every number, to the last digit
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["parallel", "serial", SHORT_DESCRIPTION])  # no dask scratch


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
