"""Measured series in validate's outputs: the CSVs, the JSON entry and the report section, from
synthetic Solutions; with final values only, none of them appears."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from feedtherm.system.measurement_series import Series
from feedtherm.system.measurements import Measurement
from feedtherm.analysis.transient_scores import compare_series
from feedtherm.outputs.report import render_report
from feedtherm.outputs.transient_files import transient_lines, write_transient_files
from feedtherm.outputs.validation_files import validation_summary, write_validation

# synthetic Solutions and a whole Validation live beside this file (pytest puts it on sys.path)
from test_report_html import synthetic_validation


def series_validation():
    validation = synthetic_validation()
    run = validation.solutions["I"]
    times = np.array([0.0, 1800.0, 3600.0])
    t2 = np.interp(times, run.times, run.sensors_celsius()["T2"]) + np.array([0.0, 1.0, -2.0])
    d = np.interp(times, run.times, run.elongation_um) + 3.0
    rows = [Measurement("I", "T2", "C", t2[-1], None, Series(times, t2, np.full(3, 0.2))),
            Measurement("I", "D_um", "um", d[-1], None, Series(times, d))]
    return synthetic_validation(transients=compare_series("I", run, rows))


def test_scores_and_samples_are_written(tmp_path):
    validation = series_validation()
    paths = write_transient_files(validation.transients, tmp_path)
    assert [p.name for p in paths] == ["transients.csv", "transient_samples.csv"]
    with open(paths[0], newline="") as handle:
        scores = {row["quantity"]: row for row in csv.DictReader(handle)}
    # deviations simulated − measured: (0, −1, +2) K and −3 µm throughout
    assert float(scores["T2"]["rms_deviation"]) == pytest.approx(np.sqrt(5.0 / 3.0), abs=1e-4)
    assert float(scores["T2"]["max_abs_deviation"]) == pytest.approx(2.0, abs=1e-4)
    assert float(scores["T2"]["time_of_max_s"]) == 3600.0
    assert float(scores["T2"]["mean_deviation"]) == pytest.approx(1.0 / 3.0, abs=1e-4)
    assert scores["T2"]["unit"] == "K"
    assert scores["T2"]["inside_two_sigma"] == "0.333"  # u = 0.2 K: only the 0 K deviation
    assert scores["D_um"]["inside_two_sigma"] == ""  # no uncertainties
    assert float(scores["D_um"]["rms_deviation"]) == pytest.approx(3.0, abs=1e-4)
    assert scores["D_um"]["unit"] == "um"
    with open(paths[1], newline="") as handle:
        samples = list(csv.DictReader(handle))
    assert len(samples) == 6
    assert [r["uncertainty"] for r in samples] == ["0.2"] * 3 + [""] * 3
    lines = transient_lines(validation.transients)
    assert lines == ["measured series, condition I: temperature RMS 1.3 K (T2), max |Δ| 2.0 K at 60 min; "
                     "elongation RMS 3.0 µm (D), max |Δ| 3.0 µm at 0 min"]


def test_the_report_and_the_summary_show_the_series():
    validation = series_validation()
    html = render_report(validation)
    assert 'id="measured-series"' in html
    assert "Condition I: 2 measured series, bars ±1 standard uncertainty." in html
    assert '<a href="#measured-series">' in html  # in the contents too
    summary = validation_summary(validation)
    assert [e["quantity"] for e in summary["transients"]] == ["T2", "D_um"]
    json.dumps(summary)  # JSON-able: plain floats


def test_final_values_only_change_nothing(tmp_path):
    validation = synthetic_validation()
    assert write_transient_files(validation.transients, tmp_path) == []
    assert "measured-series" not in render_report(validation)  # neither section nor contents entry
    assert "transients" not in validation_summary(validation)
    written = write_validation(validation, tmp_path / "out")
    assert sorted(p.name for p in written) == ["report.html", "validation.csv", "validation.json"]
