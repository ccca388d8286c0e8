"""`feedtherm validate` with measured time series: bad files fail in one line before any run;
a good one is scored over the whole transient.

The good file is tests/data/ballscrew_v10_series.csv, SYNTHETIC (the fast model's v10 run of
ballscrew_example over 20 min plus seeded noise of 0.1 K and 0.5 µm; see
tests/data/make_ballscrew_series.py), validated against that bench with v10 cut to 20 min.
"""

from __future__ import annotations

import csv
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from feedtherm import cli
from feedtherm.benches import bench

SERIES = Path(__file__).parents[1] / "data" / "ballscrew_v10_series.csv"
HEADER = "condition,time [min],quantity,value,unit,uncertainty\n"
GOOD = "v10,0,T1,20.0,degC,0.2\n"


#: v10's duration in the bench's description, the line that a 20-min copy shortens.
V10_DURATION = 'duration = "8 h"\ndescription = "10 m/min"\n'


def short_description(tmp_path: Path) -> Path:
    """ballscrew_example with its condition v10 lasting 20 min, the span of the synthetic series."""
    text = (bench("ballscrew_example").folder / "description.toml").read_text(encoding="utf-8")
    assert V10_DURATION in text
    path = tmp_path / "short.toml"
    path.write_text(text.replace(V10_DURATION, V10_DURATION.replace('"8 h"', '"20 min"'), 1), encoding="utf-8")
    return path


def assert_fails_in_one_line(capsys, system, bad: Path, out: Path, *fragments):
    assert cli.main(["validate", str(system), "--measured", str(bad), "--out", str(out)]) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, captured.err
    assert "Traceback" not in captured.err
    assert str(bad) in lines[0]
    for fragment in fragments:
        assert fragment in lines[0], lines[0]
    assert not out.exists()
    assert not [p for p in out.parent.iterdir() if p.name.startswith(out.name)]  # no staging directory either


@pytest.mark.parametrize(
    "body, fragments",
    [
        (GOOD + "v10,2,T9,21.0,degC,0.2\n", ["line 3", "unknown quantity 'T9'"]),
        (GOOD + "v99,2,T1,21.0,degC,0.2\n", ["line 3", "unknown test 'v99'"]),
        (GOOD + "v10,2,T1,nan,degC,0.2\n", ["line 3", "the value must be a finite number"]),
        (GOOD + "v10,nan,T1,21.0,degC,0.2\n", ["line 3", "the time must be a finite number"]),
        (GOOD + "v10,2,T1,21.0,mm,0.2\n", ["line 3", "'mm' is not a temperature's unit"]),
        (GOOD + "v10,2,D,21.0,degC,0.2\n", ["line 3", "'degC' is not a length's unit"]),
        (GOOD + "v10,0,T1,21.0,degC,0.2\n", ["line 3", "time 0 s twice"]),
        ("v10,5,T1,20.0,degC,0.2\nv10,2,T1,21.0,degC,0.2\n", ["line 3", "out of order"]),
        (GOOD + "v10,2,T1,,degC,0.2\n", ["line 3", "the value is missing"]),
        (GOOD + "v10,2,T1,21.0,degC,-0.2\n", ["line 3", "must not be negative"]),
        (GOOD + "v10,500,T1,21.0,degC,0.2\n", ["line 3", "after the end of v10's run (28800 s)"]),
    ],
)
def test_a_bad_series_file_fails_before_any_run(tmp_path, capsys, body, fragments):
    bad = tmp_path / "bad.csv"
    bad.write_text(HEADER + body)
    assert_fails_in_one_line(capsys, "ballscrew_example", bad, tmp_path / "out", *fragments)


def test_a_finals_file_with_an_unknown_condition_names_its_line(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text("condition,quantity,unit,measured\nv10,T1,C,25.0\nv99,T1,C,25.0\n")
    assert_fails_in_one_line(capsys, "ballscrew_example", bad, tmp_path / "out", "line 3", "unknown test 'v99'")


def test_the_process_exits_2_with_one_line_and_writes_nothing(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text(HEADER + GOOD + "v10,2,T1,21.0,mm,0.2\n")
    result = subprocess.run([sys.executable, "-m", "feedtherm", "validate", "ballscrew_example", "--measured",
                             str(bad), "--out", str(tmp_path / "out")], capture_output=True, text=True, timeout=120,
                            cwd=tmp_path)
    assert result.returncode == 2
    assert result.stdout == ""
    assert len(result.stderr.strip().splitlines()) == 1 and "line 3" in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.csv"]


def test_a_series_longer_than_the_shortened_run_is_refused(tmp_path, capsys):
    rows = SERIES.read_text(encoding="utf-8").replace("v10,20,T1,", "v10,21,T1,")
    bad = tmp_path / "long.csv"
    bad.write_text(rows)
    assert_fails_in_one_line(capsys, short_description(tmp_path), bad, tmp_path / "out",
                             "after the end of v10's run (1200 s)")


def test_a_synthetic_series_is_scored_over_the_whole_transient(tmp_path, capsys, monkeypatch):
    # The one-at-a-time sensitivities (45 s of steady states) do not read the measurements; they
    # are tested elsewhere and left out here to keep this test short.
    monkeypatch.setattr("feedtherm.analysis.validation.sensitivities", lambda *args, **kwargs: [])
    out = tmp_path / "out"
    assert cli.main(["validate", str(short_description(tmp_path)), "--measured", str(SERIES), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "measured series, condition v10" in printed and "transients.csv" in printed
    with open(out / "transients.csv", newline="") as handle:
        scores = {row["quantity"]: row for row in csv.DictReader(handle)}
    assert set(scores) == {"T1", "T3", "T4", "D_um"}
    with open(out / "transient_samples.csv", newline="") as handle:
        samples = list(csv.DictReader(handle))
    assert len(samples) == 44
    for quantity, row in scores.items():
        assert row["condition"] == "v10" and int(row["samples"]) == 11
        assert (float(row["start_s"]), float(row["end_s"])) == (0.0, 1200.0)
        assert row["unit"] == ("um" if quantity == "D_um" else "K")
        deviations = np.array([float(r["deviation"]) for r in samples if r["quantity"] == quantity])
        assert float(row["rms_deviation"]) == pytest.approx(np.sqrt(np.mean(deviations ** 2)), abs=1e-3)
        assert float(row["max_abs_deviation"]) == pytest.approx(np.max(np.abs(deviations)), abs=1e-3)
        # The file is this model's run plus noise of 0.1 K / 0.5 µm (RMS 0.08-0.12 K, 0.36 µm
        # when written). Bounds well above the noise leave room for later model changes, while a
        # unit read wrong (K as °C: 273 K; mm as µm: a factor of 1000) exceeds them by far.
        assert float(row["rms_deviation"]) < (5.0 if quantity == "D_um" else 0.8), row
        assert 0.0 <= float(row["inside_two_sigma"]) <= 1.0  # the file gives uncertainties
    t4 = [r for r in samples if r["quantity"] == "T4"]
    assert float(t4[0]["measured"]) == pytest.approx(293.209 - 273.15, abs=1e-3)  # written in K, read in °C
    assert all(r["uncertainty"] == "0.2" for r in t4)
    # the finals: each series' last sample against the run's end
    with open(out / "validation.csv", newline="") as handle:
        finals = {row["quantity"]: row for row in csv.DictReader(handle)}
    assert float(finals["T4"]["measured"]) == pytest.approx(float(t4[-1]["measured"]), abs=0.01)  # 4 digits
    summary = json.loads((out / "validation.json").read_text())
    assert {entry["quantity"] for entry in summary["transients"]} == set(scores)
    report = (out / "report.html").read_text(encoding="utf-8")
    assert 'id="measured-series"' in report and "Condition v10: 4 measured series" in report


TEST_HEADER = "test,time [s],quantity,value,unit,uncertainty,target [mm]\n"


@pytest.mark.parametrize(
    "body, fragments",
    [
        # the travel is 94..494 mm (the nut's centre, its flange included, at 294 mm; a 400 mm stroke)
        ("drift,19,E,8,um,1,90\n", ["line 2", "target 90 mm lies outside the table's travel, 94..494 mm"]),
        ("drift,19,E,8,um,1,250\n", ["line 2", "drift never visits target 250 mm"]),
        ("drift,99,E,8,um,1,490\ndrift,19,E,9,um,1,490\n", ["line 3", "drift E@490mm is out of order"]),
        ("drift,19,E,nan,um,1,110\n", ["line 2", "the value must be a finite number"]),
        ("drift,20000,T1,21.0,degC,0.1,\n", ["line 2", "after the end of drift's run"]),
        ("v10,19,E,8,um,1,110\n", ["line 2", "v10 never visits target 110 mm (it has no measuring stops)"]),
    ],
)
def test_a_bad_test_log_fails_before_any_run(tmp_path, capsys, body, fragments):
    bad = tmp_path / "bad.csv"
    bad.write_text(TEST_HEADER + body)
    assert_fails_in_one_line(capsys, "ballscrew_example", bad, tmp_path / "out", *fragments)


def test_a_target_column_without_its_unit_is_refused(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text(TEST_HEADER.replace("target [mm]", "target") + "drift,19,E,8,um,1,110\n")
    assert_fails_in_one_line(capsys, "ballscrew_example", bad, tmp_path / "out", "line 1",
                             "the target column names its unit")
