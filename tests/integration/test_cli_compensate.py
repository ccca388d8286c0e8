"""`feedtherm compensate` as a user runs it: a small study, its files, and bad input (issue 16)."""

import json
import subprocess
import sys

import numpy as np
import pytest

from feedtherm.analysis.compensation.evaluator import CompensationLaw

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def run(cwd, *args):
    return subprocess.run([sys.executable, "-m", "feedtherm", "compensate", *args], capture_output=True, text=True,
                          timeout=300, cwd=cwd)


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    """One 1-hour cycle per set: the whole path, not the figures of docs/compensation.md."""
    cwd = tmp_path_factory.mktemp("compensate")
    return cwd, run(cwd, "--cycles", "1", "--duration", "3600", "--seed", "4", "--sensors", "2")


def test_two_workers_give_the_serial_study(study, tmp_path):
    """The cycles on a local Dask cluster: the same laws, to the byte."""
    cwd, serial = study
    assert serial.returncode == 0, serial.stderr
    parallel = run(tmp_path, "--cycles", "1", "--duration", "3600", "--seed", "4", "--sensors", "2", "--workers", "2")
    assert parallel.returncode == 0, parallel.stderr
    for name in ("law.json", "law_static.json", "compensation.csv"):
        assert (tmp_path / "out" / "paper_compensation_physics" / name).read_bytes() == \
            (cwd / "out" / "paper_compensation_physics" / name).read_bytes(), name


def test_a_study_writes_its_files_and_one_line(study):
    cwd, result = study
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert len(lines) == 1 and lines[0].startswith("out/paper_compensation_physics: law on "), lines
    out = cwd / "out" / "paper_compensation_physics"
    assert sorted(p.name for p in out.iterdir()) == sorted(
        ["law.json", "law_static.json", "law_kalman.json", "compensation.json", "compensation.csv", "error_vs_k.png",
         "sensor_map.png", "test_cycle.png", "compensation.html"])
    for name in ("error_vs_k.png", "sensor_map.png", "test_cycle.png"):
        assert (out / name).read_bytes()[:8] == PNG_MAGIC
    summary = json.loads((out / "compensation.json").read_text())
    assert [len(e["sensors"]) for e in summary["curves"]["regression_lags"]] == [1, 2, 3, 4, 5, 6]
    assert summary["declared"]["regression"]["sensors"] == ["T1", "T2", "T3", "T4", "T5"]
    assert [m["condition"] for m in summary["measured"]["regression"]["conditions"]] == ["I", "II", "III", "IV", "V"]
    law = CompensationLaw.from_file(out / "law.json")
    assert len(law.inputs) == 2 and law.inputs == summary["chosen"]["regression_lags"]["sensors"]
    assert np.isfinite(law.update(0.0, {name: 300.0 for name in law.inputs}))
    html = (out / "compensation.html").read_text()
    assert 'id="compensation"' in html and "data:image/png;base64" in html


@pytest.mark.parametrize("args, message", [
    (["--sensors", "500"], "--sensors: K = 500 but there are "),
    (["--sensors", "0"], "--sensors: K must be at least 1"),
    (["--sensors", "T1,T9"], "--sensors: no candidate sensor 'T9'"),
    (["--sensors", "T1,T1"], "--sensors: a sensor is listed twice"),
    (["--seed", "1.5"], "argument --seed: must be a whole number, got '1.5'"),
    (["--seed", "one"], "argument --seed: must be a whole number, got 'one'"),
    (["--cycles", "0"], "argument --cycles: must be a positive whole number"),
    (["--mode", "paper", "ballscrew_example"], "--mode paper"),
])
def test_bad_input_is_one_line_exit_2_and_nothing_written(tmp_path, args, message):
    result = run(tmp_path, *args, "--out", "study")
    assert result.returncode == 2
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and message in lines[0], result.stderr
    assert list(tmp_path.iterdir()) == []


def test_validate_refuses_a_folder_without_a_study_in_one_line(tmp_path):
    result = subprocess.run([sys.executable, "-m", "feedtherm", "validate", "--compensation", str(tmp_path / "none"),
                             "--out", "report"], capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.splitlines() == [f"feedtherm: error: --compensation: {tmp_path / 'none' / 'compensation.json'} "
                                          "not found (give the output folder of `feedtherm compensate`)"]
    assert list(tmp_path.iterdir()) == []


def test_the_study_reads_back_as_a_report_section(study):
    from feedtherm.outputs.compensation_files import read_compensation_summary
    from feedtherm.outputs.report.compensation import compensation_section

    cwd, _ = study
    read = read_compensation_summary(cwd / "out" / "paper_compensation_physics")
    assert sorted(read["figures"]) == ["error_vs_k.png", "sensor_map.png", "test_cycle.png"]
    html = compensation_section(read["summary"], read["figures"])
    assert html.count("data:image/png;base64") == 3 and "Kalman filter" in html
