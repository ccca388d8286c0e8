"""`feedtherm sweep --workers N | --scheduler ADDRESS`: the same CSV as the serial sweep, bad
choices as one line, a failed point reported with its inputs beside the others' rows."""

import os
import socket
import subprocess
import sys

import pytest

from feedtherm import cli
from feedtherm.analysis import sweep as sweep_module

# 2 screw speeds × 1 nut speed × 2 ambients, 30 min each: four runs of ~0.3 s.
GRID = ["--screw-rpm", "396,1116", "--nut-rpm", "360", "--ambient", "20:25:5", "--duration", "1800"]


def run(cwd, *args, env=None):
    environ = {k: v for k, v in os.environ.items() if k != "DASK_SCHEDULER_ADDRESS"}
    environ.update(env or {})
    return subprocess.run([sys.executable, "-m", "feedtherm", "sweep", *args], capture_output=True, text=True,
                          timeout=180, cwd=cwd, env=environ)


@pytest.fixture(scope="module")
def serial_csv(tmp_path_factory):
    cwd = tmp_path_factory.mktemp("serial")
    result = run(cwd, *GRID, "--out", "serial")
    assert result.returncode == 0, result.stderr
    return (cwd / "serial" / "sweep.csv").read_bytes()


def test_two_local_workers_write_the_serial_csv_byte_for_byte(tmp_path, serial_csv):
    result = run(tmp_path, *GRID, "--out", "parallel", "--workers", "2")
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""  # no Dask chatter
    assert result.stdout.startswith("parallel: sweep of 4 points written in ")
    assert (tmp_path / "parallel" / "sweep.csv").read_bytes() == serial_csv
    assert sorted(p.name for p in tmp_path.iterdir()) == ["parallel"]  # no staging directory, no dask-scratch


def free_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def assert_one_line_and_nothing_written(result, cwd, *fragments):
    assert result.returncode == 2, result.stderr
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("feedtherm: error: "), result.stderr
    for fragment in fragments:
        assert fragment in lines[0], lines[0]
    assert list(cwd.iterdir()) == []


@pytest.mark.parametrize("args, env, fragments", [
    (["--workers", "0"], {}, ["--workers", "positive whole number", "'0'"]),
    (["--workers", "two"], {}, ["--workers", "'two'"]),
    (["--workers", "2", "--scheduler", "127.0.0.1:8786"], {}, ["--scheduler", "not allowed with argument --workers"]),
    (["--scheduler", "localhost"], {}, ["--scheduler: 'localhost' is not a scheduler address"]),
    ([], {"DASK_SCHEDULER_ADDRESS": "nowhere"}, ["DASK_SCHEDULER_ADDRESS: 'nowhere' is not a scheduler address"]),
])
def test_bad_execution_choices(tmp_path, args, env, fragments):
    assert_one_line_and_nothing_written(run(tmp_path, *GRID, *args, env=env), tmp_path, *fragments)


def test_an_unreachable_scheduler_is_one_line_and_writes_nothing(tmp_path):
    address = f"tcp://127.0.0.1:{free_port()}"  # nothing listens there
    result = run(tmp_path, *GRID, "--scheduler", address)
    assert_one_line_and_nothing_written(result, tmp_path, f"cannot reach the Dask scheduler at {address}")


def test_a_failed_point_is_named_and_the_others_are_written(tmp_path, monkeypatch, capsys):
    """One point of four raises inside its run: three rows are written, one line names the fourth."""
    real = sweep_module._simulate

    def failing(run, progress=None):
        if run.label.startswith("point screw 1116 rpm, nut 360 rpm, ambient 25"):
            raise RuntimeError("solver diverged")
        return real(run, progress)

    monkeypatch.setattr(sweep_module, "_simulate", failing)
    code = cli.main(["sweep", *GRID, "--out", str(tmp_path / "out")])
    captured = capsys.readouterr()
    assert code == 1
    assert captured.err.splitlines() == [
        "feedtherm: error: point screw 1116 rpm, nut 360 rpm, ambient 25 °C: RuntimeError: solver diverged"]
    assert "sweep of 3 points written" in captured.out
    lines = (tmp_path / "out" / "sweep.csv").read_text().splitlines()
    assert [line.split(",")[:3] for line in lines[1:]] == [["396", "360", "20"], ["396", "360", "25"],
                                                          ["1116", "360", "20"]]
