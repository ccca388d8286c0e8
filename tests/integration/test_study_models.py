"""`feedtherm calibrate` and `feedtherm uncertainty` run any model of the registry (`--model`, `--mesh`).

An unknown model is one line naming --model, before any run, and nothing is written.  The chosen
model reaches every run: a model registered under a test name, the fast model wrapped to count its
builds (one per run) and record each one's mesh, runs the whole fit, every leave-one-out fold, the
study's points and the Bayesian update's, and gives the fast model's numbers to the last digit (it
is the fast model); the results and the files say which model and mesh made them.  Kept small:
the paper's bench with half-hour conditions (``paper_short``), one parameter, two samples,
serial runs.
"""

import json

import numpy as np
import pytest

from feedtherm import cli
from feedtherm.analysis.calibration import RunCache, calibrate, cross_validate
from feedtherm.analysis.consistency import check_description_measurements
from feedtherm.system.measurements import MeasurementSet
from feedtherm.analysis.uncertainty.study import run_uncertainty
from feedtherm.analysis.uncertainty.update import bayesian_update
from feedtherm.analysis.validation import measurements_of
from feedtherm.models.fast.discretization import FastDiscretization
from feedtherm.models.registry import ModelEntry, register_model, unregister_model
from feedtherm.outputs.calibration_files import calibration_summary

#: The test's model: the fast one, counted.
COUNTING = "counting"
PARAMS = ["screw_nut_preload"]


@pytest.fixture
def counting():
    """The mesh of every build of the registered model "counting" (the fast model), in order."""
    meshes = []

    def factory(system, options):
        meshes.append(options.mesh)
        return FastDiscretization(system, options)

    register_model(ModelEntry(COUNTING, "the fast model, its builds counted (a test's)", factory, uses_mesh=True))
    try:
        yield meshes
    finally:
        unregister_model(COUNTING)


@pytest.fixture(autouse=True)
def no_scheduler(monkeypatch):
    """The commands run here, never on a scheduler the environment names."""
    monkeypatch.delenv("DASK_SCHEDULER_ADDRESS", raising=False)


def exit_code(args):
    try:
        return cli.main(args)
    except SystemExit as stop:  # argparse's own errors
        return stop.code


def measured(loaded, conditions) -> MeasurementSet:
    """The bench's own measured final values and equilibrium times at ``conditions``."""
    data = measurements_of(loaded, None)
    return MeasurementSet([r for r in data.rows if r.condition in conditions], data.source,
                          {c: t for c, t in data.equilibrium_min.items() if c in conditions})


# ---------------------------------------------------------------------------- the command line


@pytest.mark.parametrize("command", [
    ["calibrate", "--fit", "I,II,IV", "--params", "screw_nut_preload", "--cross-validate", "--workers", "1"],
    ["uncertainty", "--samples", "2"],
])
@pytest.mark.parametrize("name, fragments", [
    ("nonsense", ["--model: no model 'nonsense'", "models: fast, fem, reduced"]),
    ("reduce", ["--model: no model 'reduce'", "did you mean 'reduced'?"]),
])
def test_an_unknown_model_is_one_line_and_writes_nothing(capsys, tmp_path, monkeypatch, command, name, fragments):
    monkeypatch.chdir(tmp_path)  # where the default output folder would go
    code = exit_code([command[0], "paper", *command[1:], "--model", name, "--mesh", "medium"])
    captured = capsys.readouterr()
    assert code == 2, captured
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("feedtherm: error: --model"), captured.err
    for fragment in fragments:
        assert fragment in lines[0], lines[0]
    assert captured.out == ""
    assert list(tmp_path.iterdir()) == []


def test_the_commands_run_the_chosen_model_and_say_so(capsys, tmp_path, monkeypatch, paper, counting):
    monkeypatch.chdir(tmp_path)
    rows = measurements_of(paper, None).for_condition("I")  # the bench's measured finals of I alone
    (tmp_path / "I.csv").write_text("condition,quantity,unit,measured\n"
                                    + "".join(f"I,{r.quantity},{r.unit},{r.measured!r}\n" for r in rows))
    code = exit_code(["calibrate", "paper", "--fit", "I", "--params", "screw_nut_preload", "--measured", "I.csv",
                      "--no-equilibrium", "--workers", "1", "--model", COUNTING, "--mesh", "fine", "--out", "cal"])
    assert code == 0, capsys.readouterr().err
    summary = json.loads((tmp_path / "cal" / "calibration.json").read_text())
    assert (summary["model"], summary["mesh"]) == (f"{COUNTING}, cycle-averaged motion", "fine")
    assert len(counting) == summary["model_runs"] > 0 and set(counting) == {"fine"}

    counting.clear()
    code = exit_code(["uncertainty", "paper", "--samples", "2", "--no-sobol", "--model", COUNTING, "--mesh", "fine",
                      "--out", "unc"])
    assert code == 0, capsys.readouterr().err
    settings = json.loads((tmp_path / "unc" / "uncertainty.json").read_text())["settings"]
    assert (settings["model"], settings["mesh"]) == (COUNTING, "fine")
    assert len(counting) == settings["runs"] == 3 * 5 and set(counting) == {"fine"}  # 3 points × 5 conditions


# ---------------------------------------------------------------------------- calibration


def test_the_fit_runs_the_chosen_model_with_the_fast_models_numbers(paper_short, counting):
    data = measured(paper_short, ["I", "II"])
    cache = RunCache()  # shared: the second fit must not take the first model's runs from it
    fast = calibrate(paper_short, data, ["I"], PARAMS, cache=cache)
    assert counting == []
    chosen = calibrate(paper_short, data, ["I"], PARAMS, cache=cache, model=COUNTING, mesh="medium")
    assert len(counting) == chosen.model_runs == fast.model_runs > 0
    assert set(counting) == {"medium"}
    np.testing.assert_array_equal(chosen.fitted, fast.fitted)
    np.testing.assert_array_equal(chosen.standard_errors, fast.standard_errors)
    assert chosen.residuals == fast.residuals and chosen.held_out == fast.held_out and chosen.cost == fast.cost
    assert [r.condition for r in chosen.held_out][0] == "II"
    assert (fast.model, fast.mesh, chosen.model, chosen.mesh) == ("fast", None, COUNTING, "medium")
    a, b = calibration_summary(fast), calibration_summary(chosen)
    assert (a["model"], a["mesh"]) == ("fast, cycle-averaged motion", None)
    assert (b["model"], b["mesh"]) == (f"{COUNTING}, cycle-averaged motion", "medium")
    timeless = [{k: v for k, v in s.items() if k not in ("wall_time_s", "model", "mesh")} for s in (a, b)]
    assert timeless[0] == timeless[1]


def test_every_fold_runs_the_chosen_model(paper_short, counting):
    data = measured(paper_short, ["I", "II"])
    fast = cross_validate(paper_short, data, PARAMS, equilibrium=False)
    assert counting == []
    chosen = cross_validate(paper_short, data, PARAMS, equilibrium=False, model=COUNTING, mesh="coarse")
    assert len(counting) == sum(r.model_runs for _, r in chosen) == sum(r.model_runs for _, r in fast)
    assert set(counting) == {"coarse"}
    assert [left for left, _ in chosen] == [left for left, _ in fast] == ["I", "II"]
    for (_, a), (_, b) in zip(fast, chosen):
        np.testing.assert_array_equal(b.fitted, a.fitted)
        assert b.held_out == a.held_out and (b.model, b.mesh) == (COUNTING, "coarse")


# ---------------------------------------------------------------------------- uncertainty


def test_the_study_runs_the_chosen_model_with_the_fast_models_numbers(paper_short, counting):
    tiny = {"samples": 2, "sobol_base": 2, "conditions": ["I"]}
    fast = run_uncertainty(paper_short, **tiny)
    assert counting == []
    chosen = run_uncertainty(paper_short, **tiny, model=COUNTING, mesh="medium")
    assert len(counting) == chosen.settings["runs"] == fast.settings["runs"]
    assert set(counting) == {"medium"}
    assert (fast.settings["model"], fast.settings["mesh"]) == ("fast", None)
    assert (chosen.settings["model"], chosen.settings["mesh"]) == (COUNTING, "medium")
    timeless = [{k: v for k, v in s.settings.items() if k not in ("wall_time_s", "model", "mesh")}
                for s in (fast, chosen)]
    assert timeless[0] == timeless[1]
    (a,), (b,) = fast.sets, chosen.sets
    assert b.finals == a.finals and b.sobol and b.sobol == a.sobol
    for q in a.bands["I"].quantiles:
        np.testing.assert_array_equal(b.bands["I"].quantiles[q], a.bands["I"].quantiles[q])
        np.testing.assert_array_equal(b.bands["I"].nominal[q], a.bands["I"].nominal[q])


def test_the_bayesian_update_runs_the_chosen_model(paper_short, counting):
    data = measurements_of(paper_short, None)
    options = {"consistency": check_description_measurements(paper_short.system, data), "s2": 1.0, "max_nfev": 1}
    fast = bayesian_update(paper_short, data, ["I"], **options)
    assert counting == []
    chosen = bayesian_update(paper_short, data, ["I"], **options, model=COUNTING, mesh="fine")
    assert len(counting) == chosen.conditions_runs == fast.conditions_runs > 0
    assert set(counting) == {"fine"}
    np.testing.assert_array_equal(chosen.fit.z, fast.fit.z)
    np.testing.assert_array_equal(chosen.fit.covariance, fast.fit.covariance)
    assert (chosen.summary["model"], chosen.summary["mesh"]) == (COUNTING, "fine")
    assert (fast.summary["model"], fast.summary["mesh"]) == ("fast", None)
