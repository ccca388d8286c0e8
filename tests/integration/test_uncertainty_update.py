"""The Bayesian update on the paper's bench, kept tiny (condition I, the noise scale fixed at 1,
two least-squares evaluations): serial against two Dask workers, the update as the study's
second set, the predictive set, and a condition without measurements (the command's other bad input
is in test_uncertainty_study.py)."""

import numpy as np
import pytest

from feedtherm import cli
from feedtherm.analysis.consistency import check_description_measurements
from feedtherm.analysis.execution import resolve_execution
from feedtherm.analysis.uncertainty.study import run_uncertainty
from feedtherm.analysis.uncertainty.update import bayesian_update
from feedtherm.analysis.validation import measurements_of

TINY = {"s2": 1.0, "max_nfev": 2}


@pytest.fixture(scope="module")
def data(paper):
    return measurements_of(paper, None)


@pytest.fixture(scope="module")
def serial(paper, data):
    return bayesian_update(paper, data, ["I"], consistency=check_description_measurements(paper.system, data), **TINY)


def test_two_workers_give_the_serial_update(paper_short, data):
    consistency = check_description_measurements(paper_short.system, data)
    serial = bayesian_update(paper_short, data, ["I"], consistency=consistency, **TINY)
    parallel = bayesian_update(paper_short, data, ["I"], consistency=consistency, execution=resolve_execution(2),
                               **TINY)
    assert np.array_equal(serial.fit.z, parallel.fit.z)
    assert np.array_equal(serial.fit.covariance, parallel.fit.covariance)
    assert np.array_equal(serial.x_map, parallel.x_map)
    timeless = [{k: v for k, v in u.summary.items() if k != "wall_time_s"} for u in (serial, parallel)]
    assert timeless[0] == timeless[1]  # everything but the wall time


def test_the_update_fits_the_measured_finals_of_its_conditions(paper, data, serial):
    rows = serial.summary["residuals"]
    measured = {r.quantity: r.measured for r in data.for_condition("I")}
    assert {r["quantity"] for r in rows} <= set(measured) and all(r["condition"] == "I" for r in rows)
    # the weights are the description's calibration weights: 0.5 K and 2 µm on the paper's bench
    sigma = {r["quantity"]: r["sigma"] for r in rows}
    assert sigma["T1"] == paper.system.calibration.temperature_sigma
    assert sigma["D_um"] == pytest.approx(paper.system.calibration.elongation_sigma * 1e6)
    assert (serial.fit.sd <= 1.0).all()
    assert serial.summary["model_runs"] == serial.fit.evaluations  # one condition per point
    for p, x in zip(serial.parameters, serial.x_map):
        assert p.declared == x and p.low <= x <= p.high
        assert p.distribution == "posterior (Bayesian update on I)"
        assert p.reason.startswith("prior: ") and "updated with the measured finals of I" in p.reason


@pytest.fixture(scope="module")
def study(paper, serial):
    return run_uncertainty(paper, samples=2, sobol_base=None, conditions=["I"], posterior=serial)


def test_the_update_is_the_studys_second_set(paper, serial, study):
    prior, after, _ = study.sets
    assert after.label == "calibrated" and after.calibration["fit_conditions"] == ["I"]
    assert after.parameters == serial.parameters
    # its nominal run is the run at the posterior mode
    from feedtherm.analysis.uncertainty.runs import SampleRun, run_sample

    at_map = run_sample(SampleRun(serial.nominal, ("I",), "map")).finals["I"]
    for f in after.finals:
        assert f.nominal == pytest.approx(at_map[f.quantity], abs=1e-9)


def test_the_predictive_set_widens_the_updated_finals_by_the_model_error(serial, study):
    _, after, predictive = study.sets
    assert predictive.label == "predictive" and predictive.runs == 0 and predictive.bands == {}
    # s² is fixed at 1 here, so the model error is the weights themselves: 0.5 K and 2 µm
    fitted = {r["quantity"] for r in serial.summary["residuals"]}
    assert predictive.model_error["noise_scale_s2"] == 1.0
    assert predictive.model_error["sd"] == {q: (2.0 if q == "D_um" else 0.5) for q in fitted}
    for f, g in zip(after.finals, predictive.finals):
        assert (f.condition, f.quantity, f.nominal, f.measured) == (g.condition, g.quantity, g.nominal, g.measured)
        if f.quantity in fitted:
            # two sampled points y1 < y2: the mixture's CDF at y1 is at least 1/4, so its 5 % quantile
            # lies below y1, while the samples' 5 % quantile, y1 + 0.05 (y2 − y1), is not below y1
            assert g.p05 < f.p05 and g.p95 > f.p95
        else:
            assert (g.p05, g.p50, g.p95) == (f.p05, f.p50, f.p95)  # the ambient: an input, not fitted


def exit_code(argv):
    try:
        return cli.main(argv)
    except SystemExit as exc:
        return exc.code


def test_a_condition_without_measurements_is_refused(capsys, tmp_path, monkeypatch):
    # the paper's measurements without condition V
    from importlib.resources import files

    monkeypatch.chdir(tmp_path)
    lines = (files("feedtherm") / "benches" / "paper" / "measurements.csv").read_text(encoding="utf-8").splitlines()
    kept = [line for line in lines if not line.startswith("V,")]
    assert len(kept) < len(lines)
    (tmp_path / "m.csv").write_text("\n".join(kept) + "\n", encoding="utf-8")
    code = exit_code(["uncertainty", "--update-with", "IV,V", "--measured", "m.csv", "--out", "out"])
    captured = capsys.readouterr()
    assert code == 2, captured
    line = captured.err.strip()
    assert line.startswith("feedtherm: error: --update-with: no measurements for V"), line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.csv"]
