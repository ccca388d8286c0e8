"""Uncertainty studies on the paper's bench, kept tiny (a few 3 h runs of the fast model, ~0.2 s
each): the runs, serial against two Dask workers, Sobol' indices that must vanish where a
parameter cannot act, a failed run, the calibrated set and the command's bad input."""

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from feedtherm import cli
from feedtherm.analysis.calibration import CalibrationResult, _final_values, resolve_parameters
from feedtherm.analysis.execution import resolve_execution
from feedtherm.analysis.uncertainty import study as study_module
from feedtherm.analysis.uncertainty.posterior import read_posterior
from feedtherm.analysis.uncertainty.sampling import POSTERIOR
from feedtherm.analysis.uncertainty.study import run_uncertainty
from feedtherm.errors import FeedthermError
from feedtherm.outputs.calibration_files import calibrated_toml
from feedtherm.benches import bench
from feedtherm.system.load import load_system, parse_toml, validate_description

#: A description that declares no uncertainties: what `feedtherm new` writes.
TEMPLATE = Path(cli.__file__).parent / "benches" / "_template" / "description.toml"

TINY = {"samples": 2, "sobol_base": None, "conditions": ["I"]}


@pytest.fixture(scope="module")
def serial(paper):
    return run_uncertainty(paper, **TINY)


def test_a_tiny_study_has_bands_around_the_declared_run(paper, serial):
    (prior,) = serial.sets
    assert prior.label == "prior" and prior.runs == 3 and serial.settings["runs"] == 3
    band = prior.bands["I"]
    assert band.time_s[0] == 0.0 and band.time_s[-1] == 10800.0 and len(band.time_s) == 181
    assert set(band.quantiles) == {"T1", "T2", "T3", "T4", "T5", "T6", "D_um"}
    for q, values in band.quantiles.items():
        assert values.shape == (3, 181)
        assert (values[0] <= values[1]).all() and (values[1] <= values[2]).all()
    # the nominal run is the run at the declared values, as calibration makes it
    declared = _final_values(paper, "I")
    for f in prior.finals:
        assert f.nominal == pytest.approx(declared[f.quantity], abs=1e-9)
    assert prior.coverage == (0, 0)  # no measurements passed


def test_the_final_values_are_judged_against_the_measurements(paper):
    from feedtherm.analysis.consistency import check_description_measurements
    from feedtherm.analysis.validation import measurements_of

    data = measurements_of(paper, None)
    found = run_uncertainty(paper, **TINY, data=data, consistency=check_description_measurements(paper.system, data))
    (prior,) = found.sets
    judged = {f.quantity: f for f in prior.finals if f.measured is not None}
    assert sorted(judged) == ["D_um", "T1", "T2", "T3", "T4", "T5"]  # T6, the ambient, is not measured
    for f in judged.values():
        row = next(r for r in data.for_condition("I") if r.quantity == f.quantity)
        assert f.measured == row.measured
        assert f.inside == (f.p05 <= row.measured <= f.p95)
    assert prior.coverage[1] == 6


def test_two_workers_give_the_serial_study(paper_short):
    tiny = {**TINY, "sobol_base": 2}
    serial = run_uncertainty(paper_short, **tiny)
    parallel = run_uncertainty(paper_short, **tiny, execution=resolve_execution(2))
    assert parallel.settings["execution"] == "a local Dask cluster of 2 worker processes"
    a, b = serial.sets[0], parallel.sets[0]
    assert a.finals == b.finals
    assert a.sobol and a.sobol == b.sobol  # the bootstrap intervals too
    for q in a.bands["I"].quantiles:
        assert np.array_equal(a.bands["I"].quantiles[q], b.bands["I"].quantiles[q])
        assert np.array_equal(a.bands["I"].nominal[q], b.bands["I"].nominal[q])


def test_sobol_indices_vanish_where_a_parameter_cannot_act(tmp_path):
    # where the laser's stand sits on the base changes no temperature: Saltelli's differences are
    # exactly zero there, and not on D
    text = bench("paper").description.read_text(encoding="utf-8")
    stand = ('[uncertainty.parameters.laser_stand_x]\nkind = "value"\npaths = ["mechanics.elongation.mount.point[0]"]\n'
             'distribution = "uniform"\nrange = ["460 mm", "500 mm"]\nreason = "test: a value only D reads"\n\n')
    anchor = "[uncertainty.parameters.screw_nut_friction]"
    (tmp_path / "with_stand.toml").write_text(text.replace(anchor, stand + anchor, 1), encoding="utf-8")
    with_stand = load_system(str(tmp_path / "with_stand.toml"))
    found = run_uncertainty(with_stand, samples=2, sobol_base=2, conditions=["I"])
    prior = found.sets[0]
    assert prior.sobol_condition == "I"
    names = [p.name for p in prior.parameters]
    assert len(prior.sobol) == 6 * len(names)  # T1-T5 and D; the ambient T6 does not vary
    assert found.settings["sobol_runs"] == 2 * (len(names) + 2)
    for index in prior.sobol:
        if index.parameter == "laser_stand_x" and index.quantity != "D_um":
            assert index.S1 == 0.0 and index.ST == 0.0
    stand_on_d = next(i for i in prior.sobol if i.parameter == "laser_stand_x" and i.quantity == "D_um")
    assert stand_on_d.ST > 0.0


def test_a_failed_run_fails_the_study_naming_the_point(paper, monkeypatch):
    real = study_module.run_sample

    def flaky(run):
        if run.label == "prior sample 1":
            raise FeedthermError("the solver diverged")
        return real(run)

    monkeypatch.setattr(study_module, "run_sample", flaky)
    with pytest.raises(FeedthermError) as info:
        run_uncertainty(paper, **TINY)
    message = str(info.value)
    assert "\n" not in message
    assert "1 of 3 sampled points failed" in message
    assert "prior sample 1 (screw_nut_friction=" in message and "the solver diverged" in message


def fake_calibration(paper, folder, fitted: dict[str, float], errors: dict[str, float]):
    """A calibration folder as `feedtherm calibrate` writes it, for the fitted values given."""
    parameters = resolve_parameters(paper, list(fitted))
    x = np.array([fitted[p.name] for p in parameters])
    se = np.array([errors[p.name] for p in parameters])
    correlation = np.eye(len(parameters))
    if len(parameters) > 1:
        correlation[0, 1] = correlation[1, 0] = 0.5
    result = CalibrationResult(parameters, x, se, correlation, [""] * len(x), [""] * len(x), ["I", "II"], [], [],
                               0.0, 0, 0.0, "bundled:paper", paper)
    folder.mkdir()
    (folder / "calibrated.toml").write_text(calibrated_toml(paper, result), encoding="utf-8")
    summary = {"fit_conditions": ["I", "II"], "held_out": [],
               "parameters": {p.name: {"kind": p.kind, "fitted": float(v), "standard_error": float(s),
                                       "bounds": [p.lower, p.upper], "paths": p.paths}
                              for p, v, s in zip(parameters, x, se)},
               "correlation": {"parameters": [p.name for p in parameters], "matrix": correlation.tolist()}}
    (folder / "calibration.json").write_text(json.dumps(summary), encoding="utf-8")
    return summary


def test_a_calibrated_description_leaves_out_the_priors_of_fitted_values(paper, tmp_path):
    # a factor of 3 on the screw's film lies outside its declared prior (0.4-2.5): the calibrated
    # description must not carry that prior, or it would not load
    fake_calibration(paper, tmp_path / "cal", {"chtc_screw": 3.0, "screw_nut_preload": 200.0},
                     {"chtc_screw": 0.1, "screw_nut_preload": 20.0})
    text = (tmp_path / "cal" / "calibrated.toml").read_text(encoding="utf-8")
    calibrated = validate_description(parse_toml(text, "calibrated"), "calibrated")
    kept = set(calibrated.system.uncertainty.parameters)
    assert kept == set(paper.system.uncertainty.parameters) - {"chtc_screw", "screw_nut_preload"}
    assert calibrated.system.surfaces["screw_shaft"].chtc_factor == pytest.approx(3.0)


def test_the_calibrated_set_samples_the_posterior_and_keeps_the_other_priors(paper, tmp_path):
    summary = fake_calibration(paper, tmp_path / "cal", {"screw_nut_preload": 300.0, "chtc_screw": 1.5},
                               {"screw_nut_preload": 20.0, "chtc_screw": 0.15})
    summary["parameters"]["chtc_screw"]["note"] = "not identifiable: standard error larger than the value"
    posterior = read_posterior(tmp_path / "cal", paper, summary)
    names = [p.name for p in posterior.parameters]
    assert names[:2] == ["screw_nut_preload", "chtc_screw"]
    assert set(names[2:]) == set(paper.system.uncertainty.parameters) - {"screw_nut_preload", "chtc_screw"}
    preload, chtc = posterior.parameters[:2]
    assert preload.distribution == POSTERIOR and preload.declared == 300.0 and preload.sigma == 20.0
    assert (preload.low, preload.high) == (50.0, 365.0) and preload.unit == "N"
    # a scale is relative to the calibrated values (which hold the fitted factor already)
    assert chtc.declared == 1.0 and chtc.sigma == pytest.approx(0.1) and chtc.high == pytest.approx(5.0 / 1.5)
    assert "fitted by calibration on I, II: 300 +- 20" in preload.reason
    assert "the calibration says" not in preload.reason
    assert chtc.reason.endswith("(the calibration says: not identifiable: standard error larger than the value)")
    assert posterior.summary["replaced"] == ["screw_nut_preload", "chtc_screw"]
    assert posterior.correlation.tolist() == [[1.0, 0.5], [0.5, 1.0]]
    found = run_uncertainty(paper, **TINY, posterior=posterior)
    prior, after = found.sets
    assert after.label == "calibrated" and after.calibration["fit_conditions"] == ["I", "II"]
    assert after.calibration["replaced"] == ["screw_nut_preload", "chtc_screw"]
    # the calibrated nominal run is the calibrated description's, not the declared one
    assert after.finals[0].nominal != prior.finals[0].nominal


# ----------------------------------------------------------------------------- the command


def exit_code(args):
    try:
        return cli.main(args)
    except SystemExit as stop:  # argparse's own errors
        return stop.code


@pytest.mark.parametrize("args, fragments", [
    ([str(TEMPLATE)], ["declares no uncertainties", "[uncertainty.parameters"]),
    (["--samples", "100"], ["--samples", "power of 2", "'100'"]),
    (["--sobol-base", "0"], ["--sobol-base", "'0'"]),
    (["--condition", "IX"], ["--condition: no condition 'IX'"]),
    (["--workers", "0"], ["--workers", "'0'"]),
    (["--calibration", "nowhere"], ["--calibration", "nowhere"]),
    (["--measured", "missing.csv"], ["missing.csv"]),
    (["--update-with", "I", "--calibration", "somewhere"], ["--update-with and --calibration"]),
    (["--update-with", "I,IX"], ["--update-with: no condition 'IX'"]),
    (["--update-with", "I,,II"], ["--update-with", "comma-separated"]),
])
def test_bad_input_is_one_line_and_writes_nothing(capsys, tmp_path, monkeypatch, args, fragments):
    monkeypatch.chdir(tmp_path)
    code = exit_code(["uncertainty", *args, "--out", "out"])
    captured = capsys.readouterr()
    assert code == 2, captured
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("feedtherm: error: "), captured.err
    for fragment in fragments:
        assert fragment in lines[0], lines[0]
    assert captured.out == ""
    assert list(tmp_path.iterdir()) == []


def test_the_command_writes_the_study(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code = cli.main(["uncertainty", "--samples", "2", "--sobol-base", "2", "--out", "unc"])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert (tmp_path / "unc").is_dir()
    assert [p.name for p in tmp_path.iterdir()] == ["unc"]
    shutil.rmtree(tmp_path / "unc")
