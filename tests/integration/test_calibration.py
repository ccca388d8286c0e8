"""Calibration recovers known parameters, reports what it cannot identify, and predicts held-out data."""

import subprocess
import sys

import numpy as np
import pytest

from feedtherm.analysis.calibration import calibrate, cross_validate, resolve_parameters
from feedtherm.system.measurements import read_measurements
from feedtherm.analysis.validation import calibrated_values
from feedtherm.errors import FeedthermError
from feedtherm.outputs.calibration_files import write_calibration
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system

SENSORS = ["T1", "T2", "T3", "T4", "T5"]


def synthetic_measurements(loaded, path, conditions, seed=7, options=None):
    """Measurements made by the model itself, with noise of 0.1 K and 0.5 µm (``options``: its time stepping)."""
    rng = np.random.default_rng(seed)
    lines = ["condition,quantity,unit,measured"]
    for c in conditions:
        final = simulate(loaded, condition=c, motion="averaged", options=options).summary_values("final")
        for q in SENSORS:
            lines.append(f"{c},{q},C,{final[q] + rng.normal(0, 0.1):.4f}")
        lines.append(f"{c},D_um,um,{final['D_um'] + rng.normal(0, 0.5):.4f}")
    path.write_text("\n".join(lines) + "\n")
    return read_measurements(str(path), sensors=SENSORS)


def test_known_parameters_are_recovered_within_their_standard_errors(paper, tmp_path):
    names = ["screw_nut_preload", "chtc_moving"]
    truth = {"screw_nut_preload": 220.0, "chtc_moving": 1.8}  # a machine its motors can run (under 240 N)
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


def test_the_rotating_screws_film_is_recovered_from_two_conditions_and_predicts_a_third(paper, tmp_path):
    """A factor on the screw's CHTC acts on T4 and D most: two conditions' finals find it."""
    params = resolve_parameters(paper, ["chtc_screw"])
    from feedtherm.analysis.calibration import apply

    from feedtherm.analysis.calibration import CALIBRATION_OPTIONS

    generating = apply(paper, params, [1.6])
    # the fit's own time stepping: what is left to find is the film, not a time step's bias
    data = synthetic_measurements(generating, tmp_path / "synthetic.csv", ["I", "II", "III"],
                                  options=CALIBRATION_OPTIONS)
    result = calibrate(paper, data, ["I", "II"], ["chtc_screw"], equilibrium=False)
    se = result.standard_errors[0]
    assert 0 < se < 0.2 and abs(result.fitted[0] - 1.6) <= 2.0 * se
    held = {(p.condition, p.quantity): p for p in result.held_out}
    assert abs(held[("III", "D_um")].deviation) < 1.5  # 0.5 µm of noise on D, carried to III
    write_calibration(paper, result, tmp_path / "cal")
    reloaded = load_system(str(tmp_path / "cal" / "calibrated.toml"))
    assert reloaded.system.surfaces["screw_shaft"].chtc_factor == pytest.approx(result.fitted[0], rel=1e-5)


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


def test_held_out_predictions_fall_in_their_intervals_and_flagged_values_are_not_fitted(paper, tmp_path):
    """Model-made data at I, II, IV (noise 0.1 K, 0.5 µm), the model's own equilibrium times
    stated for them, and IV's elongation spoiled by 30 µm and flagged as inconsistent: the fit
    must ignore the spoiled value (reporting it with its reason), fit the equilibrium times, and
    predict the held-out condition inside its 95 % intervals."""
    from feedtherm.analysis.calibration import EQUILIBRIUM_QUANTITY, _Model
    from feedtherm.analysis.consistency import ConsistencyReport, Flag
    from feedtherm.system.measurements import Measurement, MeasurementSet

    names = ["screw_nut_preload"]
    truth = apply_values(paper, names, [220.0])  # a machine its motors can run (under 240 N)
    data = synthetic_measurements(truth, tmp_path / "m.csv", ["I", "II", "IV"])
    own = _Model(truth, []).finals([], ["I", "II"])
    spoiled = [Measurement(r.condition, r.quantity, r.unit, r.measured + (30.0 if (r.condition, r.quantity) == ("IV", "D_um") else 0.0))
               for r in data.rows]
    stated = {c: own[c][EQUILIBRIUM_QUANTITY] for c in ("I", "II")}
    data = MeasurementSet(spoiled, data.source, stated)
    flags = ConsistencyReport([Flag("IV", "D_um", "elongation_law", "spoiled on purpose", 20.0)], None, [])
    result = calibrate(paper, data, ["I", "IV"], names, consistency=flags)
    assert [(r.condition, r.quantity, r.flag) for r in result.excluded] == [("IV", "D_um", "spoiled on purpose")]
    assert abs(result.excluded[0].deviation + 30.0) < 2.0  # the fit did not bend towards the spoiled value
    assert abs(result.fitted[0] - 220.0) < 3 * result.standard_errors[0]
    fitted_eq = [r for r in result.residuals if r.quantity == EQUILIBRIUM_QUANTITY]
    assert [r.condition for r in fitted_eq] == ["I"] and abs(fitted_eq[0].deviation) < 1.0  # minutes
    held = result.held_out
    assert {r.condition for r in held} == {"II"} and any(r.quantity == EQUILIBRIUM_QUANTITY for r in held)
    assert all(r.interval is not None and r.interval > 0 for r in held)
    outside = [(r.quantity, r.deviation, r.interval) for r in held if abs(r.deviation) > r.interval]
    assert len(outside) <= 1, outside  # 95 % intervals: of 7 values, two outside has probability 4 %


def apply_values(loaded, names, values):
    from feedtherm.analysis.calibration import apply

    return apply(loaded, resolve_parameters(loaded, names), values)


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


def test_a_parameter_pushed_to_its_bound_is_flagged(paper_equations, tmp_path):
    # Measurements far hotter than any preload within the declared [50, 365] N can make under the
    # paper's equation loss models: the fit ends at the upper bound, and says so.
    paper = paper_equations
    upper = resolve_parameters(paper, ["screw_nut_preload"])[0].upper
    assert upper == pytest.approx(365.0)
    lines = ["condition,quantity,unit,measured"] + [f"I,{q},C,60.0" for q in SENSORS]
    path = tmp_path / "hot.csv"
    path.write_text("\n".join(lines) + "\n")
    result = calibrate(paper, read_measurements(str(path), sensors=SENSORS), ["I"], ["screw_nut_preload"])
    assert result.at_bound == ["upper"]
    assert result.fitted[0] == pytest.approx(upper)


def test_parallel_conditions_give_the_serial_values(paper):
    """workers > 1 runs the conditions of an evaluation in processes: same numbers, same count."""
    from feedtherm.analysis.calibration import _Model

    params = resolve_parameters(paper, ["screw_nut_preload"])
    with _Model(paper, params, workers=1) as serial, _Model(paper, params, workers=2) as parallel:
        a = serial.finals([700.0], ["I", "III"])
        b = parallel.finals([700.0], ["I", "III"])
        assert serial.runs == parallel.runs == 2
    assert a == b


@pytest.mark.parametrize("content, fragment", [
    (None, "calibration.json not found"),
    ("{not json", "is not readable JSON"),
    ('{"fit_conditions": ["I"]}', "lacks parameters, held_out"),
])
def test_validate_with_a_bad_calibration_folder_is_one_line(tmp_path, content, fragment):
    folder = tmp_path / "cal"
    folder.mkdir()
    if content is not None:
        (folder / "calibration.json").write_text(content)
    out = tmp_path / "out"
    result = subprocess.run([sys.executable, "-m", "feedtherm", "validate", "--calibration", str(folder),
                             "--out", str(out)], capture_output=True, text=True, timeout=300)
    assert result.returncode == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0] and "Traceback" not in result.stderr, result.stderr
    assert not out.exists()


def test_a_calibration_folder_reaches_the_validation_headline(paper, tmp_path):
    """calibrate writes calibration.json with the cross-validation; validate --calibration reads it back."""
    from feedtherm.outputs.calibration_files import read_calibration_summary

    data = synthetic_measurements(paper, tmp_path / "m.csv", ["I", "II"])
    result = calibrate(paper, data, ["I"], ["screw_nut_preload"])
    folds = cross_validate(paper, data, ["screw_nut_preload"], start=result.fitted)
    write_calibration(paper, result, tmp_path / "cal", folds)
    summary = read_calibration_summary(tmp_path / "cal")
    assert summary["fit_conditions"] == ["I"]
    assert {r["condition"] for r in summary["held_out"]} == {"II"}
    assert all(r["interval95"] > 0 for r in summary["held_out"])
    cross = summary["cross_validation"]
    assert cross["largest_temperature_deviation_C"]["condition"] in ("I", "II")
    assert cross["model_runs"] == sum(r.model_runs for _, r in folds)


@pytest.mark.parametrize("condition", ["I", "III"])
def test_calibration_runs_with_60_s_steps_agree_with_the_default_steps(paper, condition):
    """Calibration's runs take 60 s steps; against `feedtherm run --motion averaged` (10 s) the
    final values differ by under 0.02 K and 0.05 µm, the time to 95 % of the rise by under 1.5 min."""
    from feedtherm.analysis.calibration import EQUILIBRIUM_QUANTITY, _final_values
    from feedtherm.solution.equilibrium import rise_time

    coarse = _final_values(paper, condition)
    run = simulate(paper, condition=condition, motion="averaged")
    fine = run.summary_values("final")
    initial = {n: float(s[0]) for n, s in run.sensors.items()}
    sensors = {n: v for n, v in run.cycle_sensors.items() if n in initial}
    for q in SENSORS:
        assert abs(coarse[q] - fine[q]) < 0.02, q
    assert abs(coarse["D_um"] - fine["D_um"]) < 0.05
    assert abs(coarse[EQUILIBRIUM_QUANTITY] - rise_time(run.cycle_times, sensors, initial, run.steady) / 60) < 1.5


def test_a_value_left_at_its_default_is_calibrated_and_written_in_its_bounds_unit(paper, tmp_path):
    """room.air_speed is absent from the bench (still air): a draught of 0.3 m/s is recovered from
    measurements the model made with it, and the calibrated description's [room] table gains it."""
    names = ["room_air_speed"]
    params = resolve_parameters(paper, names)
    from feedtherm.analysis.calibration import apply

    data = synthetic_measurements(apply(paper, params, [0.3]), tmp_path / "draught.csv", ["I", "II", "IV"])
    result = calibrate(paper, data, ["I", "II", "IV"], names)
    assert abs(result.fitted[0] - 0.3) <= 2.0 * result.standard_errors[0] < 0.3
    write_calibration(paper, result, tmp_path / "cal")
    text = (tmp_path / "cal" / "calibrated.toml").read_text(encoding="utf-8")
    room = text.split("[room]")[1].split("\n[")[0]
    assert next(line for line in room.splitlines() if line.startswith("air_speed")).endswith(" m/s\"")
    reloaded = load_system(str(tmp_path / "cal" / "calibrated.toml"))
    assert reloaded.system.room.air_speed == pytest.approx(result.fitted[0], rel=1e-5)
