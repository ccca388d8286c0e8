"""Every command on the second bench, ballscrew_example, and the recovery of its synthetic truth.

The bench's measurements are a synthetic time series (scripts/make_ballscrew_measurements.py):
its description with the ball nut's drag torque and the front bearings' preload perturbed, run
with the fast model, plus seeded sensor noise.  So calibration must find the perturbed values,
and inference the heats they give, within the intervals each reports.
"""

from __future__ import annotations

import importlib.util
import json
import subprocess
from dataclasses import replace
import sys
from pathlib import Path

import numpy as np
import pytest

from feedtherm.analysis.calibration import calibrate
from feedtherm.analysis.inverse import Noise, infer_conditions
from feedtherm.system.measurements import MeasurementSet
from feedtherm.analysis.validation import measurements_of
from feedtherm.boundary import boundary_conditions
from feedtherm.system.load import load_system

NAME = "ballscrew_example"
ROOT = Path(__file__).parents[2]


def _script():
    spec = importlib.util.spec_from_file_location("make_ballscrew_measurements",
                                                  ROOT / "scripts" / "make_ballscrew_measurements.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


MAKER = _script()


def feedtherm(cwd: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "feedtherm", *args], cwd=cwd, capture_output=True, text=True,
                          timeout=900)


@pytest.fixture(scope="module")
def loaded():
    return load_system(NAME)


@pytest.fixture(scope="module")
def data(loaded):
    return measurements_of(loaded, None)


def test_the_bench_files_say_the_measurements_are_synthetic(loaded):
    folder = ROOT / "src" / "feedtherm" / "benches" / NAME
    first = (folder / "measurements.csv").read_text(encoding="utf-8").splitlines()[0]
    assert first.startswith("# SYNTHETIC")
    assert "SYNTHETIC" in (folder / "SOURCES.md").read_text(encoding="utf-8")


def test_the_committed_measurements_are_what_the_script_writes():
    """Generated once, and reproducible: the script rewrites the file byte for byte."""
    committed = MAKER.TARGET.read_text(encoding="utf-8")
    assert MAKER.measurements() == committed


def test_calibration_finds_the_perturbed_values_within_their_intervals(loaded, data):
    names = ["ball_nut_torque", "front_bearing_preload", "chtc_screw"]
    result = calibrate(loaded, data, ["v5", "v10", "v20"], names)
    truth = {"ball_nut_torque": MAKER.TRUTH["sources.ball_nut.torque"],
             "front_bearing_preload": MAKER.TRUTH["sources.front_bearing.axial_load"],
             "chtc_screw": MAKER.TRUTH["surfaces.screw_shaft.chtc_factor"]}
    for parameter, fitted, error in zip(result.parameters, result.fitted, result.standard_errors):
        assert abs(fitted - truth[parameter.name]) <= 1.96 * error, (parameter.name, fitted, error)
        assert error < 0.1 * truth[parameter.name]  # and the data pin each one down
    original = {p.name: p.originals[0] for p in result.parameters}
    assert abs(original["ball_nut_torque"] - truth["ball_nut_torque"]) > 10 * result.standard_errors[0]


def test_inference_finds_the_heats_of_the_truth_within_their_intervals(loaded, data):
    """From the series' last samples (8 h, within 0.3 K of the steady state), the steady inference.

    The whole-transient inference of these series (what `infer` does with a series file) puts 15
    of the 20 heats within their 95 % intervals, the guideways' at v5 4 standard errors off: its
    intervals are too narrow for this test to hold (docs/inverse.md)."""
    truth = MAKER.truth().system
    conditions = list(MAKER.CONDITIONS)
    finals = MeasurementSet([replace(row, series=None) for row in data.rows], data.source, data.equilibrium_min)
    inferred = infer_conditions(loaded, finals, conditions, noise=Noise(0.3, 1e-6))
    found = 0
    for inference in inferred:
        heats = boundary_conditions(truth, inference.condition).heats
        for estimate in inference.estimates:
            true = sum(heats[s].power for s in estimate.sources)
            assert estimate.low <= true <= estimate.high, (inference.condition, estimate.group, true)
            found += 1
    assert found == 5 * len(conditions)
    # the ball nut's heat is measured, not taken from the prior: its interval is narrow
    nut = next(e for e in inferred[0].estimates if e.group == "ball_nut")
    assert nut.high - nut.low < 0.2 * nut.inferred and nut.resolution > 0.9


@pytest.mark.parametrize("args, made", [
    (["check"], []),
    (["heat", "--condition", "v10", "--json"], []),
    (["run", "--condition", "v10", "--duration", "1800", "--motion", "averaged", "--no-plots"], ["summary.json"]),
    (["run", "--condition", "v10", "--model", "fem", "--mesh", "coarse", "--duration", "600", "--motion",
      "averaged", "--no-plots"], ["summary.json"]),
    # the reduced model's basis is built from the coarse FE model on the way (about 85 s)
    (["run", "--condition", "v10", "--model", "reduced", "--mesh", "coarse", "--duration", "600", "--motion",
      "averaged", "--no-plots"], ["summary.json"]),
    (["sweep", "--screw-rpm", "500,1500", "--nut-rpm", "0", "--ambient", "20", "--duration", "1800"],
     ["sweep.csv"]),
    # compensate: tests/integration/test_compensation_reference.py runs it on this bench (and checks its laws)
    (["uncertainty", "--samples", "4", "--no-sobol"], ["uncertainty.json"]),
])
def test_every_command_runs_on_the_bench(tmp_path, args, made):
    command = [args[0], NAME, *args[1:]]
    if made:
        command += ["--out", "out"]
    result = feedtherm(tmp_path, *command)
    assert result.returncode == 0, result.stderr[-2000:]
    for name in made:
        assert (tmp_path / "out" / name).is_file(), sorted(p.name for p in (tmp_path / "out").iterdir())


def test_validate_shows_the_measured_series_beside_the_runs(tmp_path, data):
    """One condition of the bench's series (a long file of one condition), validated as a user would."""
    text = MAKER.TARGET.read_text(encoding="utf-8").splitlines()
    one = [line for line in text if line.startswith(("#", "condition,", "v5,"))]
    (tmp_path / "v5.csv").write_text("\n".join(one) + "\n", encoding="utf-8")
    result = feedtherm(tmp_path, "validate", NAME, "--motion", "averaged", "--measured", "v5.csv", "--out", "out")
    assert result.returncode == 0, result.stderr[-2000:]
    summary = json.loads((tmp_path / "out" / "validation.json").read_text(encoding="utf-8"))
    scored = {(t["condition"], t["quantity"]) for t in summary["transients"]}
    assert scored == {("v5", q) for q in ("T1", "T2", "T3", "T4", "T5", "D_um")}
    report = (tmp_path / "out" / "report.html").read_text(encoding="utf-8")
    assert "Measured time series" in report
    assert np.isfinite([t["rms_deviation"] for t in summary["transients"]]).all()
