"""ballscrew_example's ISO 230-3 drift tests (issue 56): measured by the FE model on a machine with two
declared values changed (scripts/make_ballscrew_drift_tests.py), they go through validate, calibrate
(fit on one test, predict another), infer, compensate --adapt and correct.

Calibrating the fast model on FE data meets an error of form: the fitted values are not the truth's
within their standard errors (the note of issue 56 gives them), but the held-out test's drift at
every target is within 3 µm RMS of the measured (the interferometer's noise: 1 µm)."""

import csv
import importlib.util
import json
from pathlib import Path

import numpy as np
import pytest

from feedtherm.cli import main

ROOT = Path(__file__).parents[2]
NAME = "ballscrew_example"
DRIFT_CSV = ROOT / "src" / "feedtherm" / "benches" / NAME / "drift_tests.csv"
_spec = importlib.util.spec_from_file_location("make_ballscrew_drift_tests", ROOT / "scripts" / "make_ballscrew_drift_tests.py")
MAKER = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(MAKER)


@pytest.fixture(scope="module")
def calibrated(tmp_path_factory):
    out = tmp_path_factory.mktemp("drift") / "calibration"
    # serial: the same fit to the bit as on a cluster (test_cli_calibrate_parallel.py), and the default
    # local cluster of one worker per core gains nothing here (40 s against 37 s serial, idle) and loses
    # to the other pytest-xdist worker on the same two cores (106 s against 63 s beside a busy process)
    assert main(["calibrate", NAME, "--fit", "drift", "--params", "ball_nut_torque,front_bearing_preload,chtc_screw",
                 "--workers", "1", "--out", str(out)]) == 0
    return out


def test_the_held_out_test_is_predicted_within_3_um_rms_at_every_target(calibrated):
    document = json.loads((calibrated / "calibration.json").read_text())
    held = [s for s in document["series"]["held_out"] if s["condition"] == "drift_fast"]
    targets = [s for s in held if s["quantity"].startswith("E@")]
    assert [s["quantity"] for s in targets] == ["E@110mm", "E@200mm", "E@300mm", "E@400mm", "E@490mm"]
    assert max(s["rms_deviation"] for s in targets) <= 3.0
    assert all(s["quantity"] != "ambient" for s in held)  # the room's air drives the run; it is not scored


def test_the_fit_moves_the_changed_values_toward_the_truth(calibrated):
    """Both changed values move from the description's toward the truth's; the FE model's form keeps
    them short of it (issue 56's note: the fast model against the FE model on the truth)."""
    document = json.loads((calibrated / "calibration.json").read_text())
    fitted = document["parameters"]
    for name, path in (("ball_nut_torque", "sources.ball_nut.torque"),
                       ("front_bearing_preload", "sources.front_bearing.axial_load")):
        original, value, truth = fitted[name]["original"], fitted[name]["fitted"], MAKER.TRUTH[path]
        assert abs(value - truth) < abs(original - truth), (name, original, value, truth)


def test_infer_and_correct_take_the_tests(tmp_path):
    assert main(["infer", NAME, "--conditions", "drift", "--out", str(tmp_path / "infer")]) == 0
    inferred = json.loads((tmp_path / "infer" / "inference.json").read_text())
    assert inferred


def test_compensate_adapts_on_the_drift_tests_and_correct_runs_the_law_on_them(tmp_path):
    out = tmp_path / "compensation"
    assert main(["compensate", NAME, "--sensors", "declared", "--cycles", "1", "--duration", "3600",
                 "--adapt", str(DRIFT_CSV), "--out", str(out)]) == 0
    summary = json.loads((out / "compensation.json").read_text())
    assert set(summary["adaptation"]["laws"]["regression_lags"]["conditions"]) == {"drift", "drift_fast", "etve"}
    assert {t["test"] for t in summary["drift_tests"]} == {"drift", "drift_fast", "etve"}
    assert main(["correct", str(out / "law_adapted.json"), str(DRIFT_CSV), "--out", str(tmp_path / "correction")]) == 0
    with open(tmp_path / "correction" / "correction.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert {r["condition"] for r in rows} == {"drift", "drift_fast", "etve"}
    assert "outside_envelope" in rows[0]
