"""Calibration recovers known parameters, reports what it cannot identify, and predicts held-out data."""

import subprocess
import sys

import numpy as np
import pytest

from feedtherm.analysis.calibration import calibrate, cross_validate, resolve_parameters
from feedtherm.analysis.measurements import read_measurements
from feedtherm.analysis.validation import calibrated_values
from feedtherm.errors import FeedthermError
from feedtherm.outputs.calibration_files import write_calibration
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system

SENSORS = ["T1", "T2", "T3", "T4", "T5"]


def synthetic_measurements(loaded, path, conditions, seed=7):
    """Measurements made by the model itself, with noise of 0.1 K and 0.5 µm."""
    rng = np.random.default_rng(seed)
    lines = ["condition,quantity,unit,measured"]
    for c in conditions:
        final = simulate(loaded, condition=c, motion="averaged").summary_values("final")
        for q in SENSORS:
            lines.append(f"{c},{q},C,{final[q] + rng.normal(0, 0.1):.4f}")
        lines.append(f"{c},D_um,um,{final['D_um'] + rng.normal(0, 0.5):.4f}")
    path.write_text("\n".join(lines) + "\n")
    return read_measurements(str(path), sensors=SENSORS)


def test_known_parameters_are_recovered_within_their_standard_errors(paper, tmp_path):
    names = ["screw_nut_preload", "chtc_moving"]
    truth = {"screw_nut_preload": 1200.0, "chtc_moving": 1.8}
    params = resolve_parameters(paper, names)
    from feedtherm.analysis.calibration import apply

    generating = apply(paper, params, [truth[n] for n in names])
    data = synthetic_measurements(generating, tmp_path / "synthetic.csv", ["I", "II", "IV"])
    result = calibrate(paper, data, ["I", "II", "IV"], names)
    for p, x, se, why in zip(result.parameters, result.fitted, result.standard_errors, result.identifiable):
        assert why == "", why
        assert 0 < se < abs(x)
        assert abs(x - truth[p.name]) <= 2.0 * se, (p.name, x, se)
    # the calibrated description carries the fitted values and says so
    assert result.calibrated.system.sources["screw_nut"].preload == pytest.approx(result.fitted[0])
    out = write_calibration(paper, result, tmp_path / "cal")
    reloaded = load_system(str(tmp_path / "cal" / "calibrated.toml"))
    assert reloaded.system.sources["screw_nut"].preload == pytest.approx(result.fitted[0], rel=1e-5)
    assert reloaded.system.surfaces["worktable"].chtc_factor == pytest.approx(result.fitted[1], rel=1e-5)
    entries = calibrated_values(reloaded)
    assert len(entries) == 2 and "I, II, IV" in entries[0]["source"]
    assert {p.name for p in out} == {"calibrated.toml", "calibration.json", "heldout.csv"}


def test_parameters_the_data_cannot_separate_are_reported(paper, tmp_path):
    # The thread's friction coefficient and its preload act only through one friction torque:
    # two temperatures cannot tell them apart, and the fit must say so instead of returning
    # two confident numbers.
    data_path = tmp_path / "two.csv"
    data_path.write_text("condition,quantity,unit,measured\nI,T3,C,30.0\nI,T4,C,30.5\n")
    data = read_measurements(str(data_path), sensors=SENSORS)
    result = calibrate(paper, data, ["I"], ["screw_nut_friction", "screw_nut_preload"])
    assert all("not identifiable" in why for why in result.identifiable), result.identifiable


def test_cross_validation_predicts_each_left_out_condition(paper, tmp_path):
    data = synthetic_measurements(paper, tmp_path / "m.csv", ["I", "II", "IV"])
    folds = cross_validate(paper, data, ["screw_nut_preload"])
    assert [left for left, _ in folds] == ["I", "II", "IV"]
    for left, result in folds:
        assert {r.condition for r in result.held_out} == {left}
        assert max(abs(r.deviation) for r in result.held_out if r.unit == "C") < 0.5  # model-made data


@pytest.mark.parametrize(
    "args, fragment",
    [
        (["--fit", "I,II", "--params", "screw_nut_frction"], "unknown parameter 'screw_nut_frction'; did you mean 'screw_nut_friction'"),
        (["--fit", "I,II", "--params", "sources.screw_nut.preload"], "has no declared bounds"),
        (["--fit", "I,VI", "--params", "screw_nut_preload"], "--fit: no measurements for VI"),
        (["--fit", "I", "--params", "screw_nut_preload", "--measured", "BADHEADER"], "header must be"),
    ],
)
def test_bad_calibration_input_is_one_line(tmp_path, args, fragment):
    bad = tmp_path / "bad.csv"
    bad.write_text("cond,q,u,m\nI,T1,C,1\n")
    args = [str(bad) if a == "BADHEADER" else a for a in args]
    out = tmp_path / "out"
    result = subprocess.run([sys.executable, "-m", "feedtherm", "calibrate", *args, "--out", str(out)],
                            capture_output=True, text=True, timeout=300)
    assert result.returncode == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0] and "Traceback" not in result.stderr, result.stderr
    assert not out.exists()


def test_unknown_parameter_raises_before_any_run(paper):
    with pytest.raises(FeedthermError, match="unknown parameter"):
        resolve_parameters(paper, ["nope"])


def test_a_parameter_pushed_to_its_bound_is_flagged(paper, tmp_path):
    # Measurements far hotter than any preload within [50, 3000] N can make: the fit ends at
    # the upper bound, and says so.
    lines = ["condition,quantity,unit,measured"] + [f"I,{q},C,60.0" for q in SENSORS]
    path = tmp_path / "hot.csv"
    path.write_text("\n".join(lines) + "\n")
    result = calibrate(paper, read_measurements(str(path), sensors=SENSORS), ["I"], ["screw_nut_preload"])
    assert result.at_bound == ["upper"]
    assert result.fitted[0] == pytest.approx(3000.0)
