"""Calibration on measured time series: every sample a residual, weighted by its own uncertainty.

The thermal model is replaced by analytic transients (``fake_run``), so the tests check the
fit's arithmetic against hand calculations without running the model; the paper's bench only
supplies the declared parameters, their bounds and the calibration weights (0.5 K, 2 µm).
"""

import numpy as np
import pytest
from rich.console import Console

from feedtherm.analysis import calibration
from feedtherm.analysis.calibration import RunCache, calibrate, cross_validate, series_key
from feedtherm.system.measurements import read_measurements
from feedtherm.errors import FeedthermError
from feedtherm.outputs.calibration_files import calibration_summary, cross_summary, print_calibration
from feedtherm.system.paths import get_path
from feedtherm.system.variants import with_values

PRELOAD, CHTC = "sources.screw_nut.preload", "surfaces.screw_shaft.chtc_factor"
SENSORS = ["T1", "T2"]
#: Per condition: T1's and T2's steady rise per newton of preload [K/N], and the time constant
#: of the rise at a CHTC factor of 1 [s] (a higher factor cools faster and lower).
GAINS = {"I": (0.02, 0.01, 900.0), "II": (0.03, 0.012, 700.0), "III": (0.025, 0.02, 1100.0)}


def fake_transient(loaded, condition: str, t: np.ndarray) -> dict[str, np.ndarray]:
    """T1 and T2 [°C] at times ``t`` [s]: a first-order rise whose height grows with the preload
    and whose height and time constant fall with the CHTC factor."""
    preload = float(get_path(loaded.system, PRELOAD))
    chtc = float(get_path(loaded.system, CHTC))
    g1, g2, tau = GAINS[condition]
    shape = 1.0 - np.exp(-np.asarray(t, dtype=float) * chtc / tau)
    return {"T1": 20.0 + g1 * preload / np.sqrt(chtc) * shape, "T2": 20.0 + g2 * preload / chtc * shape}


@pytest.fixture
def runs(monkeypatch):
    """The fake model in place of the thermal model; the list of (condition, series asked for)."""
    made = []

    def run(loaded, condition, series=None, *, model="fast", mesh=None):
        made.append((condition, series))
        end = float(loaded.system.conditions[condition].duration)
        values = {q: float(v[0]) for q, v in fake_transient(loaded, condition, np.array([end])).items()}
        values[calibration.EQUILIBRIUM_QUANTITY] = 30.0
        if series:  # on a 10 s grid, as the model's runs: every measured time below lies on it
            grid = np.arange(0.0, end + 1.0, 10.0)
            values[calibration.SERIES_TIMES] = grid
            for quantity in series:
                values[series_key(quantity)] = fake_transient(loaded, condition, grid)[quantity]
        return values

    monkeypatch.setattr(calibration, "_final_values", run)
    return made


def write_series(path, rows, uncertainty=True):
    """A long-format file of (condition, minutes, quantity, value, uncertainty or None) rows."""
    lines = ["condition,time [min],quantity,value,unit" + (",uncertainty" if uncertainty else "")]
    for c, minutes, q, v, u in rows:
        cell = "" if u is None else repr(float(u))
        lines.append(f"{c},{float(minutes)!r},{q},{float(v)!r},degC" + (f",{cell}" if uncertainty else ""))
    path.write_text("\n".join(lines) + "\n")
    return read_measurements(str(path), sensors=SENSORS)


def test_each_sample_is_weighted_by_its_own_uncertainty_else_by_the_descriptions(paper, runs, tmp_path):
    # T1 = 20 + p·g(t) and T2 = 20 + p·g(t)/2 at the CHTC factor 1 of the description, with
    # g = 0.02·(1 − exp(−t/900 s)) at condition I: linear in the preload p, so the weighted least
    # squares estimate is p̂ = Σ gᵢ yᵢ / σᵢ² / Σ gᵢ² / σᵢ² (yᵢ the rise over 20 °C)
    g = 0.02 * (1.0 - np.exp(-np.array([600.0, 1200.0]) / 900.0))
    rows = [("I", 10.0, "T1", 20.0 + 300.0 * g[0], 0.1), ("I", 20.0, "T1", 20.0 + 100.0 * g[1], 0.4),
            ("I", 10.0, "T2", 20.0 + 150.0 * g[0] / 2, None), ("I", 20.0, "T2", 20.0 + 150.0 * g[1] / 2, None)]
    data = write_series(tmp_path / "series.csv", rows)
    assert data.rows[1].series.uncertainties is None  # T2: the description's 0.5 K applies
    result = calibrate(paper, data, ["I"], ["screw_nut_preload"], equilibrium=False)

    gain = np.concatenate([g, g / 2])
    rise = np.array([300.0 * g[0], 100.0 * g[1], 150.0 * g[0] / 2, 150.0 * g[1] / 2])
    sigma = np.array([0.1, 0.4, 0.5, 0.5])
    expected = np.sum(gain * rise / sigma**2) / np.sum(gain**2 / sigma**2)
    unweighted = np.sum(gain * rise) / np.sum(gain**2)
    assert abs(expected - unweighted) > 30.0  # the weights decide the answer
    assert result.fitted[0] == pytest.approx(expected, abs=0.05)
    cost = 0.5 * np.sum(((expected * gain - rise) / sigma) ** 2)
    assert result.cost == pytest.approx(cost, rel=1e-4)
    # every run of a fitted series was asked for the measured quantities' series
    assert runs and all(list(series) == SENSORS for _, series in runs)

    scores = {s.quantity: s for s in result.series_fit}
    assert result.series_conditions == ["I"] and set(scores) == set(SENSORS)
    deviation = expected * g - rise[:2]
    assert scores["T1"].rms == pytest.approx(np.sqrt(np.mean(deviation**2)), rel=1e-4)
    assert scores["T1"].max_abs == pytest.approx(np.max(np.abs(deviation)), rel=1e-4)
    # the final value's residual is the run at the last sample's time, not the run's end
    final = {(r.condition, r.quantity): r for r in result.residuals}
    assert final[("I", "T1")].predicted == pytest.approx(20.0 + result.fitted[0] * g[1], rel=1e-12)
    summary = calibration_summary(result)["series"]
    assert [s["quantity"] for s in summary["fitted"]] == SENSORS
    assert summary["fitted"][0]["weights"] == "declared uncertainties"
    assert summary["fitted"][1]["weights"] == "calibration sigma of the description"
    console = Console(record=True, width=120)
    print_calibration(result, tmp_path, console=console)
    text = console.export_text()
    assert "fitted as series" in text and f"{scores['T1'].rms:.2f} K" in text


def test_a_fit_to_a_synthetic_series_recovers_the_parameters_within_their_intervals(paper, runs, tmp_path):
    truth = with_values(paper, {PRELOAD: 220.0, CHTC: 1.6})
    rng = np.random.default_rng(7)
    minutes = np.arange(0.0, 61.0, 2.0)
    noise = 0.1
    rows = []
    for c in GAINS:
        clean = fake_transient(truth, c, minutes * 60.0)
        for q in SENSORS:
            rows += [(c, float(m), q, float(v + rng.normal(0.0, noise)), noise) for m, v in zip(minutes, clean[q])]
    data = write_series(tmp_path / "series.csv", rows)
    result = calibrate(paper, data, ["I", "II"], ["screw_nut_preload", "chtc_screw"], equilibrium=False)
    half = 1.96 * result.standard_errors
    for fitted, se, true in zip(result.fitted, half, [220.0, 1.6]):
        assert abs(fitted - true) <= se, (fitted, true, se)
        assert se < 0.05 * true  # an interval narrow enough for the check above to mean something
    # the held-out condition's series is predicted to within the noise
    held = {s.quantity: s for s in result.series_held_out}
    assert set(held) == set(SENSORS) and all(s.condition == "III" for s in held.values())
    for s in held.values():
        assert 0.5 * noise < s.rms < 2.0 * noise
        assert s.inside_two_sigma > 0.85


def test_a_finals_file_runs_as_before_and_matches_a_series_of_its_final_samples(paper, runs, tmp_path):
    truth = with_values(paper, {PRELOAD: 180.0, CHTC: 1.2})
    end = float(paper.system.conditions["I"].duration)
    lines = ["condition,quantity,unit,measured"]
    series_rows = []
    for c in ("I", "II"):
        for q, v in fake_transient(truth, c, np.array([end])).items():
            lines.append(f"{c},{q},C,{float(v[0]) + 0.3!r}")  # off the truth, so the cost is not 0
            series_rows.append((c, end / 60.0, q, float(v[0]) + 0.3, None))
    (tmp_path / "finals.csv").write_text("\n".join(lines) + "\n")
    finals = read_measurements(str(tmp_path / "finals.csv"), sensors=SENSORS)
    from_finals = calibrate(paper, finals, ["I"], ["screw_nut_preload", "chtc_screw"], equilibrium=False,
                            cache=RunCache())
    # the finals take today's runs: no series asked for, none scored or written
    assert runs and all(series is None for _, series in runs)
    assert from_finals.series_fit == [] and from_finals.series_held_out == []
    assert "series" not in calibration_summary(from_finals)

    runs.clear()
    one_sample = write_series(tmp_path / "series.csv", series_rows, uncertainty=False)
    from_series = calibrate(paper, one_sample, ["I"], ["screw_nut_preload", "chtc_screw"], equilibrium=False)
    assert all(series for _, series in runs)
    np.testing.assert_allclose(from_series.fitted, from_finals.fitted, rtol=1e-9)
    assert from_series.cost == pytest.approx(from_finals.cost, rel=1e-9)
    for a, b in zip(from_series.held_out, from_finals.held_out):
        assert (a.condition, a.quantity) == (b.condition, b.quantity)
        assert a.predicted == pytest.approx(b.predicted, rel=1e-9)
        assert a.interval == pytest.approx(b.interval, rel=1e-6)


def test_a_zero_uncertainty_fails_in_one_line_before_any_run(paper, runs, tmp_path):
    data = write_series(tmp_path / "series.csv", [("I", 0.0, "T1", 20.0, 0.2), ("I", 10.0, "T1", 21.0, 0.0)])
    with pytest.raises(FeedthermError) as failure:
        calibrate(paper, data, ["I"], ["screw_nut_preload"])
    message = str(failure.value)
    assert "\n" not in message and "series.csv" in message and "I T1" in message and "600 s is 0" in message
    assert runs == []


def test_cross_validation_scores_each_left_out_series(paper, runs, tmp_path):
    truth = with_values(paper, {PRELOAD: 200.0, CHTC: 1.3})
    rows = []
    for c in GAINS:
        clean = fake_transient(truth, c, np.arange(0.0, 3601.0, 600.0))
        rows += [(c, m, q, float(v), 0.2) for q in SENSORS for m, v in zip(range(0, 61, 10), clean[q])]
    data = write_series(tmp_path / "series.csv", rows)
    cache = RunCache()
    result = calibrate(paper, data, list(GAINS), ["screw_nut_preload"], equilibrium=False, cache=cache)
    assert result.series_held_out == [] and result.series_conditions == list(GAINS)
    folds = cross_validate(paper, data, ["screw_nut_preload"], equilibrium=False, start=result.fitted, cache=cache)
    summary = cross_summary(folds)["held_out_series"]
    assert sorted({(s["left_out"], s["condition"]) for s in summary}) == [(c, c) for c in sorted(GAINS)]
    assert all(s["samples"] == 7 and s["weights"] == "declared uncertainties" for s in summary)
    # one parameter cannot follow the CHTC's 1.3 instead of the description's 1: the folds miss
    assert max(s["rms_deviation"] for s in summary) > 0.05


def test_a_series_request_keys_and_travels_apart_from_a_finals_request(paper, runs):
    import pickle

    params = calibration.resolve_parameters(paper, ["screw_nut_preload"])
    x = np.array([200.0])
    with calibration._Model(paper, params, cache=RunCache(), series={"I": ["T2", "T1"]}) as model:
        finals_key, series_key_ = model._key(x, "II"), model._key(x, "I")
        assert len(finals_key) == 4  # as before: mode, condition, parameters, values
        assert series_key_[4] == ("T1", "T2") and series_key_[:4] == (finals_key[0], "I", *finals_key[2:])
        values = model.finals(x, ["I", "II"])
    assert runs == [("I", ("T1", "T2")), ("II", None)]
    assert calibration.SERIES_TIMES in values["I"] and calibration.SERIES_TIMES not in values["II"]
    # what a Dask worker receives and runs: the request pickles whole, quantities included
    request = pickle.loads(pickle.dumps(calibration._CalibrationRun(paper, "I", ("T1",))))
    assert request.series == ("T1",)
    assert set(calibration._calibration_run(request)) >= {series_key("T1"), calibration.SERIES_TIMES}
