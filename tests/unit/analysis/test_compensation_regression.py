"""The regression law: known coefficients recovered, the exported JSON evaluated the same, greedy choice."""

import json

import numpy as np
import pytest

from feedtherm.analysis.candidates import Candidate
from feedtherm.analysis.compensation.data import CycleRecord, CycleSet
from feedtherm.analysis.compensation.evaluator import CompensationLaw, evaluate
from feedtherm.analysis.compensation.law import law_document
from feedtherm.analysis.compensation.metrics import residuals
from feedtherm.analysis.compensation.regression import fit_regression, lagged
from feedtherm.analysis.compensation.selection import greedy_selection, predictor
from feedtherm.errors import FeedthermError

LAGS = (900.0, 3600.0)


def _synthetic(rng, n_cycles=4, n=300, names=("a", "b", "c", "d")):
    """Smooth random temperatures [K] on uneven times; D from known weights on a, c and their lags."""
    cycles = []
    for i in range(n_cycles):
        times = np.cumsum(rng.uniform(30.0, 90.0, n)) - 30.0
        drive = np.cumsum(rng.normal(0, 0.3, (n, len(names))), axis=0)
        readings = 293.15 + lagged(times, drive, 600.0) * 5
        cycles.append((times, readings))
    return cycles


# weights [m/K] of a (reading, lag 900 s, lag 3600 s) and c; bias [m]
TRUE = {"a": (4e-6, -2.5e-6, 1.0e-6), "c": (1.5e-6, 0.0, 3e-6)}
BIAS = -7.3e-4


def _target(times, readings, names):
    d = np.full(len(times), BIAS)
    for name, w in TRUE.items():
        column = readings[:, names.index(name)]
        terms = [column, *(lagged(times, column[:, None], tau)[:, 0] for tau in LAGS)]
        d += sum(wi * ti for wi, ti in zip(w, terms))
    return d


def test_regression_recovers_known_coefficients():
    names = ["a", "b", "c", "d"]
    cycles = [(t, r[:, [0, 2]], _target(t, r, names)) for t, r in _synthetic(np.random.default_rng(5))]
    law = fit_regression(cycles, ("a", "c"), LAGS)
    np.testing.assert_allclose(law.weights, np.array([TRUE["a"], TRUE["c"]]), rtol=1e-6, atol=1e-12)
    assert law.bias == pytest.approx(BIAS, rel=1e-6)


def test_regression_with_noise_recovers_coefficients_within_their_spread():
    rng = np.random.default_rng(6)
    names = ["a", "b", "c", "d"]
    cycles = [(t, r[:, [0, 2]], _target(t, r, names) + rng.normal(0, 0.2e-6, len(t)))
              for t, r in _synthetic(rng, n_cycles=8)]
    law = fit_regression(cycles, ("a", "c"), LAGS)
    np.testing.assert_allclose(law.weights, np.array([TRUE["a"], TRUE["c"]]), atol=2e-7)
    assert fit_regression(cycles, ("a", "c"), ()).weights.shape == (2, 1)  # the static law: no lag columns


def _set(name, rng, names):
    records = []
    for i, (t, r) in enumerate(_synthetic(rng, names=tuple(names))):
        records.append(CycleRecord(f"{name}-{i}", t, r, _target(t, r, names), np.zeros(len(t)), np.zeros(len(t))))
    return CycleSet(name, list(names), records)


def test_exported_json_evaluated_on_a_stream_equals_the_fitted_law():
    names = ["a", "b", "c", "d"]
    train = _set("train", np.random.default_rng(1), names)
    law = fit_regression([(c.times, c.sensors[:, [0, 1, 2]], c.elongation) for c in train.cycles], ("a", "b", "c"), LAGS)
    candidates = {n: Candidate(n, "part", (0.1, 0.0, 0.0), "top") for n in names}
    document = json.loads(json.dumps(law_document(law, candidates)))  # through text, as a file
    record = _set("test", np.random.default_rng(2), names).cycles[0]
    expected = law.predict(record.times, record.sensors[:, [0, 1, 2]])
    stream = {n: record.sensors[:, names.index(n)].tolist() for n in ("a", "b", "c")}
    np.testing.assert_allclose(evaluate(document, record.times.tolist(), stream), expected, rtol=0, atol=1e-12)
    one = CompensationLaw(document)
    first = one.update(record.times[0], {n: stream[n][0] for n in stream})
    assert first == pytest.approx(expected[0], abs=1e-12)
    with pytest.raises(ValueError, match="increasing time"):
        one.update(record.times[0], {n: stream[n][0] for n in stream})


def test_greedy_selection_finds_the_informative_sensors_and_refuses_too_many():
    names = ["a", "b", "c", "d"]
    train = _set("train", np.random.default_rng(11), names)
    validation = _set("validation", np.random.default_rng(12), names)
    steps = greedy_selection(train, validation, 2, LAGS)
    assert set(steps[-1].sensors) == {"a", "c"}
    assert steps[-1].validation_rms < 1e-12 < steps[0].validation_rms
    result = residuals(predictor(steps[-1].law, names), validation)
    assert result.rms < 1e-12 and result.reduction == pytest.approx(1.0)
    with pytest.raises(FeedthermError, match="K = 5 but there are 4 candidates"):
        greedy_selection(train, validation, 5)


def test_the_lag_is_the_first_order_filter_written_out():
    # by hand: a step from 0 to 1 K at t = 10 s, τ = 10 s, samples every 10 s: a = e^-1,
    # L = 0, (1 - e^-1) = 0.63212, e^-1·0.63212 + (1 - e^-1) = 0.86466
    lag = lagged(np.array([0.0, 10.0, 20.0]), np.array([[0.0], [1.0], [1.0]]), 10.0)[:, 0]
    np.testing.assert_allclose(lag, [0.0, 0.632120558828558, 0.864664716763387], rtol=1e-12)
    # the recurrence sample by sample, on even stretches (the filter's runs), uneven steps between
    # them, a step at the end and temperatures of either sign: the same floats, not merely close ones
    rng = np.random.default_rng(11)
    times = np.concatenate([np.arange(50) * 10.0, 495.0 + np.cumsum(rng.uniform(1.0, 20.0, 30)),
                            1000.0 + np.arange(40) * 7.5])
    times[-1] += 2.0
    readings = rng.normal(0.0, 50.0, (len(times), 3))
    for tau in (5.0, 900.0):
        decay = np.exp(-np.diff(times) / tau)
        expected = np.empty_like(readings)
        expected[0] = readings[0]
        for n in range(1, len(times)):
            expected[n] = decay[n - 1] * expected[n - 1] + (1.0 - decay[n - 1]) * readings[n]
        np.testing.assert_array_equal(lagged(times, readings, tau), expected)
        np.testing.assert_array_equal(lagged(times, readings[:, 1], tau), expected[:, 1])
    np.testing.assert_array_equal(lagged(np.array([3.0]), np.array([[290.0, 291.0]]), 900.0), [[290.0, 291.0]])
