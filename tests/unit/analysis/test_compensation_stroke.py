"""The error along the stroke (issue 34, item 3): E(x, t) linear in x and the sensors recovered, the
exported JSON evaluated at several x equal to the fitted law, bad x refused, D-only files still read."""

import json

import numpy as np
import pytest

from feedtherm.analysis.candidates import Candidate
from feedtherm.analysis.compensation.data import CycleRecord, CycleSet, stroke_positions
from feedtherm.analysis.compensation.evaluator import CompensationLaw, evaluate
from feedtherm.analysis.compensation.law import law_document, stroke_law_document
from feedtherm.analysis.compensation.regression import fit_regression, lagged
from feedtherm.analysis.compensation.stroke import (controller_cost, fit_stroke, fit_stroke_validated, normalised,
                                                     stroke_residuals)
from feedtherm.errors import FeedthermError

LAGS = (900.0, 3600.0)
NAMES = ["a", "b", "c"]
X_MIN, X_MAX = 0.1135, 0.3635  # [m], a 250 mm stroke
POSITIONS = stroke_positions(np.linspace(X_MIN, X_MAX, 51))
# E = B0 + B1 ξ + Σ (reading, lag 900, lag 3600) · (W0 + W1 ξ) on sensors a and c; [m], [m/K]
B0, B1 = -4.0e-4, 1.2e-4
W0 = {"a": (3e-6, -1.5e-6, 0.5e-6), "c": (1e-6, 0.0, 2e-6)}
W1 = {"a": (1e-6, 0.4e-6, 0.0), "c": (-0.5e-6, 0.0, -0.8e-6)}


def _error(times, readings):
    """E(x_j, t) [m] ``(n, 9)``: the known function of the module's constants."""
    xi = normalised(POSITIONS, X_MIN, X_MAX)
    c0, c1 = np.full(len(times), B0), np.full(len(times), B1)
    for name in W0:
        column = readings[:, NAMES.index(name)]
        terms = [column, *(lagged(times, column[:, None], tau)[:, 0] for tau in LAGS)]
        c0 = c0 + sum(w * t for w, t in zip(W0[name], terms))
        c1 = c1 + sum(w * t for w, t in zip(W1[name], terms))
    return c0[:, None] + c1[:, None] * xi[None, :]


def _set(name, seed, n_cycles=3, n=200):
    rng = np.random.default_rng(seed)
    records = []
    for i in range(n_cycles):
        times = np.cumsum(rng.uniform(30.0, 90.0, n)) - 30.0
        readings = 293.15 + 5 * lagged(times, np.cumsum(rng.normal(0, 0.3, (n, len(NAMES))), axis=0), 600.0)
        E = _error(times, readings)
        records.append(CycleRecord(f"{name}-{i}", times, readings, E[:, 4], np.zeros(n), np.zeros(n),
                                   positions=POSITIONS.copy(), stroke_error=E))
    return CycleSet(name, list(NAMES), records)


def _weights(order):
    """The module's known weights as the law's ``(features, order + 1)`` matrix (sensors a, c)."""
    rows = [[W0[s][f], W1[s][f]] + [0.0] * (order - 1) for s in ("a", "c") for f in range(3)]
    return np.array(rows)


def test_stroke_law_recovers_a_known_linear_function_of_x_and_the_sensors():
    law = fit_stroke(_set("train", 1), ("a", "c"), LAGS, order=1)
    np.testing.assert_allclose(law.weights, _weights(1), rtol=1e-6, atol=1e-13)
    np.testing.assert_allclose(law.bias, [B0, B1], rtol=1e-6, atol=1e-12)
    test = _set("test", 2)
    result = stroke_residuals(lambda r: law.predict_record(r, NAMES), test)
    assert result.max < 1e-12 and result.uncompensated_rms > 1e-6
    # a higher order finds nothing more: its extra coefficients are zero
    cubic = fit_stroke(_set("train", 1), ("a", "c"), LAGS, order=3)
    np.testing.assert_allclose(cubic.weights, _weights(3), atol=1e-12)
    np.testing.assert_allclose(cubic.bias, [B0, B1, 0.0, 0.0], atol=1e-10)


def test_order_chosen_on_validation_fits_the_known_function():
    choice = fit_stroke_validated(_set("train", 1), _set("validation", 3), ("a", "c"), LAGS)
    assert choice.law.order == 1 and choice.validation_rms < 1e-11  # higher orders gain nothing: the lowest that fits
    assert choice.as_dict()["validation_rms_um_by_order"]["0"]["rms_um"] > 1.0  # constant in x cannot


def test_a_law_of_d_over_the_stroke_leaves_the_error_that_varies_with_x():
    train = _set("train", 1)
    d_law = fit_regression([(c.times, c.sensors[:, [0, 2]], c.elongation) for c in train.cycles], ("a", "c"), LAGS)
    over = stroke_residuals(lambda r: d_law.predict(r.times, r.sensors[:, [0, 2]]), _set("test", 2))
    assert over.rms > 10e-6  # B1 ξ alone: 120 µm at the ends


def _candidates():
    return {n: Candidate(n, "part", (0.1, 0.0, 0.0), "top") for n in NAMES}


def test_exported_json_evaluated_at_several_x_equals_the_fitted_model(tmp_path):
    rng = np.random.default_rng(7)
    train = _set("train", 1)
    for record in train.cycles:  # noise on E so that every coefficient of the cubic is non-trivial
        record.stroke_error[:] += rng.normal(0, 1e-6, record.stroke_error.shape)
    law = fit_stroke(train, ("a", "b", "c"), LAGS, order=3, ridge=0.05 ** 2)
    path = tmp_path / "law_stroke.json"
    path.write_text(json.dumps(stroke_law_document(law, _candidates())))
    document = json.loads(path.read_text())
    assert document["version"] == 2 and document["basis"] == {**document["basis"], "kind": "legendre", "order": 3}
    assert document["controller_cost"]["multiply_adds_per_sample"] == controller_cost(3, 2, 3)["total"]
    record = _set("test", 2).cycles[0]
    xs = [X_MIN, 0.15, 0.2384, 0.3, X_MAX]
    expected = law.predict(record.times, record.sensors, xs)
    stream = {n: record.sensors[:, NAMES.index(n)].tolist() for n in NAMES}
    got = np.array(evaluate(document, record.times.tolist(), stream, xs))
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-12)
    one = CompensationLaw.from_file(path)  # one x per sample, as a controller moving the table
    for n, t in enumerate(record.times[:20]):
        value = one.update(t, {s: stream[s][n] for s in NAMES}, xs[n % 5])
        assert value == pytest.approx(expected[n, n % 5], abs=1e-12)
        assert one.at(0.2384) == pytest.approx(expected[n, 2], abs=1e-12)


@pytest.mark.parametrize("x, words", [(0.5, "outside the stroke"), (0.1, "outside the stroke"),
                                      (float("nan"), "not a finite"), (float("inf"), "not a finite"),
                                      ("left", "not a table position"), (None, "needs the table position")])
def test_bad_x_is_refused_with_one_line_naming_x(x, words):
    law = fit_stroke(_set("train", 1), ("a", "c"), LAGS, order=1)
    evaluator = CompensationLaw(json.loads(json.dumps(stroke_law_document(law, _candidates()))))
    with pytest.raises(ValueError, match=words) as caught:
        evaluator.update(0.0, {"a": 300.0, "c": 300.0}, x)
    assert str(caught.value).startswith("x:") and "\n" not in str(caught.value)
    if x is not None and not isinstance(x, str):
        with pytest.raises(FeedthermError, match=words):
            law.predict(np.zeros(1), np.full((1, 2), 300.0), [0.2, x])


def test_d_only_documents_stay_version_1_and_take_no_x():
    train = _set("train", 1)
    d_law = fit_regression([(c.times, c.sensors[:, [0, 2]], c.elongation) for c in train.cycles], ("a", "c"), LAGS)
    document = json.loads(json.dumps(law_document(d_law, _candidates())))
    assert document["version"] == 1
    law = CompensationLaw(document)
    assert law.update(0.0, {"a": 300.0, "c": 301.0}) == pytest.approx(float(d_law.predict(np.zeros(1), np.array([[300.0, 301.0]]))[0]), abs=1e-15)
    with pytest.raises(ValueError, match="^x: this law predicts D"):
        law.update(60.0, {"a": 300.0, "c": 301.0}, 0.2)
    with pytest.raises(ValueError, match="needs version 2"):
        CompensationLaw({**document, "kind": "linear_regression_stroke", "version": 1})


def test_stroke_conditioning_is_the_worst_offset_cost_over_the_stroke():
    from feedtherm.analysis.compensation.stroke import stroke_conditioning

    law = fit_stroke(_set("train", 1), ("a", "c"), LAGS, order=1)
    block = stroke_conditioning(law)
    # a: Σ_f W0 = 2.0e-6, Σ_f W1 = 1.4e-6 -> |2.0 ± 1.4| µm/K, worst at ξ = 1: 3.4 µm/K, 0.34 µm for 0.1 K
    assert block["offset_error_um"]["a"] == pytest.approx(0.34, rel=1e-5)
    assert block["offset_error_um"]["c"] == pytest.approx(0.1 * (3.0 + 1.3), rel=1e-5)
    assert block["max_abs_weight_um_per_K"] == pytest.approx(4.0, rel=1e-5)  # a's reading at ξ = 1


def test_a_higher_order_is_chosen_when_it_lowers_the_validation_error_by_more_than_the_tolerance():
    def quadratic(cycles):
        for record in cycles.cycles:  # + 20 µm (3 ξ² - 1)/2 times a reading's swing: order 2 needed
            xi = normalised(record.positions, X_MIN, X_MAX)
            record.stroke_error[:] += 20e-6 * (record.sensors[:, [1]] - 293.15) / 5 * (1.5 * xi ** 2 - 0.5)
        return cycles

    choice = fit_stroke_validated(quadratic(_set("train", 1)), quadratic(_set("validation", 3)), ("a", "b", "c"), LAGS)
    assert choice.law.order == 2 and choice.validation_rms < 1e-11
