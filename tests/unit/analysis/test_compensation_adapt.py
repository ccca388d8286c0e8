"""The Bayesian update of a regression law against hand calculations; its limits (a tight prior
keeps the prior, a loose one with many points is least squares); pairs read from measurement files."""

import numpy as np
import pytest

from feedtherm.analysis.compensation.adapt import (
    adapt_law, evidence_width, gaussian_posterior, log_evidence, minimum_norm_fit)
from feedtherm.analysis.compensation.pairs import Pairs, measured_pairs
from feedtherm.analysis.compensation.evaluator import CompensationLaw
from feedtherm.analysis.compensation.law import adapted_law_document
from feedtherm.analysis.compensation.regression import RegressionLaw
from feedtherm.system.measurements import read_measurements
from feedtherm.errors import FeedthermError


def one_input_law(bias=0.0, weight=1.0, lags=()):
    return RegressionLaw(("a",), lags, np.array([[weight] * (1 + len(lags))]), bias)


def test_one_input_posterior_and_predictive_sd_by_hand():
    """D = b + w x, prior b ~ N(0, 1), w ~ N(1, 1) (τ = 1, centre 0, scale 1), σ = 1, one pair x = 1, D = 3.

    S_N⁻¹ = I + φφᵀ = [[2, 1], [1, 2]], S_N = [[2, −1], [−1, 2]]/3;
    μ_N = S_N (μ₀ + φ y) = S_N [3, 4] = [2/3, 5/3];
    at x = 1: D = 7/3, variance φᵀ S_N φ + σ² = 2/3 + 1 = 5/3.
    """
    pairs = Pairs(np.array([[1.0]]), np.array([3.0]), np.array([1.0]), ("c1",))
    adapted = adapt_law(one_input_law(), pairs, np.array([1.0]), width=1.0, centre=np.array([0.0]))
    assert adapted.law.bias == pytest.approx(2 / 3)
    assert adapted.law.weights[0, 0] == pytest.approx(5 / 3)
    np.testing.assert_allclose(adapted.covariance, np.array([[2, -1], [-1, 2]]) / 3, atol=1e-12)
    mean, sd = adapted.predict_features(np.array([[1.0]]))
    assert mean[0] == pytest.approx(7 / 3)
    assert sd[0] == pytest.approx(np.sqrt(5 / 3))
    # log p(y) = log N(3; 1, τ²|φ|² + σ² = 3) = −(2²/3)/2 − log(3)/2 − log(2π)/2
    assert adapted.log_evidence == pytest.approx(-2 / 3 - 0.5 * np.log(3) - 0.5 * np.log(2 * np.pi))


def test_the_evidence_width_by_hand():
    """One pair, φ = [1, 1], residual r = 2, σ = 1: the evidence N(r; 0, 2τ² + 1) is largest at
    2τ² + 1 = r², τ² = 3/2."""
    width, at_bound = evidence_width(np.array([[1.0, 1.0]]), np.array([3.0]), np.array([1.0]), np.array([0.0, 1.0]))
    assert not at_bound
    assert width ** 2 == pytest.approx(1.5, rel=1e-4)


def test_residuals_within_the_noise_keep_the_prior():
    """Data that agree with the prior drive the evidence's width to its lower edge: the posterior is the prior."""
    rng = np.random.default_rng(3)
    x = rng.uniform(0, 10, (8, 1))
    law = one_input_law(1.0, 2.0)
    pairs = Pairs(x, 1.0 + 2.0 * x[:, 0], np.full(8, 0.5), tuple(f"c{i}" for i in range(8)))
    adapted = adapt_law(law, pairs)
    assert adapted.width_at_bound and adapted.width < 1e-3
    assert adapted.law.bias == pytest.approx(1.0, abs=1e-6)
    assert adapted.law.weights[0, 0] == pytest.approx(2.0, abs=1e-6)


def test_a_tight_prior_is_the_prior_and_a_loose_one_with_many_points_is_least_squares():
    rng = np.random.default_rng(7)
    x = rng.uniform(290, 310, (200, 2))
    y = 3e-6 + x @ np.array([2e-6, -1e-6]) + rng.normal(0, 1e-6, 200)
    prior = RegressionLaw(("a", "b"), (), np.array([[1e-6], [1e-6]]), -5e-4)
    pairs = Pairs(x, y, np.full(200, 1e-6), tuple(f"c{i}" for i in range(200)))
    tight = adapt_law(prior, pairs, np.array([5.0, 5.0]), width=1e-15)
    np.testing.assert_allclose(tight.law.weights, prior.weights, rtol=1e-6)
    assert tight.law.bias == pytest.approx(prior.bias, rel=1e-6)
    loose = adapt_law(prior, pairs, np.array([5.0, 5.0]), width=1.0)
    design = np.column_stack([np.ones(200), x])
    ols, *_ = np.linalg.lstsq(design, y, rcond=None)
    np.testing.assert_allclose(loose.law.weights.ravel(), ols[1:], rtol=1e-6)
    assert loose.law.bias == pytest.approx(ols[0], rel=1e-6)


def test_the_whitened_form_equals_the_information_form():
    """Bishop's eq. 3.50–3.51 (inverse covariances) and the whitened form used, on a random case."""
    rng = np.random.default_rng(1)
    phi, y, sigma = rng.normal(size=(5, 3)), rng.normal(size=5), rng.uniform(0.5, 2, 5)
    mu0, s0 = rng.normal(size=3), np.diag(rng.uniform(0.5, 2, 3))
    mean, cov = gaussian_posterior(phi, y, sigma, mu0, s0)
    lam = np.diag(sigma ** -2)
    cov_ref = np.linalg.inv(np.linalg.inv(s0) + phi.T @ lam @ phi)
    np.testing.assert_allclose(cov, cov_ref, atol=1e-12)
    np.testing.assert_allclose(mean, cov_ref @ (np.linalg.inv(s0) @ mu0 + phi.T @ lam @ y), atol=1e-12)
    assert np.isfinite(log_evidence(phi, y, sigma, mu0, s0))


def test_minimum_norm_fit_passes_through_fewer_points_than_coefficients():
    x = np.array([[300.0, 301.0, 299.0], [302.0, 300.0, 301.0]])
    y = np.array([1e-5, 2e-5])
    law = RegressionLaw(("a", "b", "c"), (), np.zeros((3, 1)), 0.0)
    fit = minimum_norm_fit(law, Pairs(x, y, np.ones(2), ("I", "II")), np.ones(3))
    np.testing.assert_allclose(fit.bias + x @ fit.weights.ravel(), y, atol=1e-15)


def test_minimum_norm_fit_drops_the_null_direction_of_centring():
    # The paper bench's measured T1-T5 and ambient [degC] of I, II, IV and V (Table 6, Table 5) and D [um]:
    # centred, the 4 x 6 design has rank 3; its fourth singular value is rounding (about 3e-15 of the
    # largest), which numpy's default cutoff (6 x 2.2e-16 = 1.3e-15) would keep.
    celsius = np.array([[27.1, 24.5, 34.5, 33.2, 31.9, 20.0], [29.6, 26.2, 37.1, 35.8, 34.2, 20.0],
                        [23.6, 20.9, 31.8, 29.5, 28.5, 15.0], [33.2, 30.5, 40.8, 38.8, 37.9, 25.0]])
    x = celsius + 273.15
    y = np.array([29.9, 35.5, 20.3, 71.5]) * 1e-6
    law = RegressionLaw(tuple("abcdef"), (), np.zeros((6, 1)), 0.0)
    fit = minimum_norm_fit(law, Pairs(x, y, np.ones(4), ("I", "II", "IV", "V")), np.ones(6))
    # the minimum-norm solution by hand: the pseudo-inverse on the three real singular values
    u, sv, vt = np.linalg.svd(x - x.mean(axis=0), full_matrices=False)
    w = vt[:3].T @ ((u[:, :3].T @ (y - y.mean())) / sv[:3])
    np.testing.assert_allclose(fit.weights.ravel(), w, rtol=1e-9)
    # and rounding-sized changes of the readings do not move it
    nudged = minimum_norm_fit(law, Pairs(x + 1e-12, y, np.ones(4), ("I", "II", "IV", "V")), np.ones(6))
    np.testing.assert_allclose(nudged.weights.ravel(), w, rtol=1e-6)


def test_the_adapted_document_gives_the_posterior_mean_and_sd():
    rng = np.random.default_rng(2)
    x = rng.uniform(295, 305, (4, 1))
    law = one_input_law(-3e-4, 1e-6, lags=(900.0,))
    pairs = Pairs(np.repeat(x, 2, axis=1), 2e-5 + 1.5e-6 * (x[:, 0] - 300), np.full(4, 2e-6), ("a", "b", "c", "d"))
    adapted = adapt_law(law, pairs, np.array([3.0, 2.0]))
    evaluator = CompensationLaw(adapted_law_document(adapted, {}))
    d, sd = evaluator.update_with_sd(0.0, {"a": 301.0})
    mean, sd_ref = adapted.predict_features(np.array([[301.0, 301.0]]))
    assert d == pytest.approx(mean[0], rel=1e-12)
    assert sd == pytest.approx(sd_ref[0], rel=1e-9)


FINALS = "condition,quantity,unit,measured\nI,a,C,27.0\nI,D_um,um,30.0\nII,a,C,30.0\nII,D_um,um,40.0\n"


def test_pairs_from_final_values_are_settled_readings(tmp_path):
    path = tmp_path / "m.csv"
    path.write_text(FINALS)
    pairs = measured_pairs(one_input_law(lags=(900.0, 3600.0)), read_measurements(str(path)), ambient_sensor="T6",
                           ambients={}, sigma=2e-6)
    np.testing.assert_allclose(pairs.features, [[300.15] * 3, [303.15] * 3])
    np.testing.assert_allclose(pairs.elongation, [30e-6, 40e-6])
    assert pairs.conditions == ("I", "II") and list(pairs.sigma) == [2e-6, 2e-6]


def test_pairs_from_a_series_run_the_lags_and_take_its_uncertainty(tmp_path):
    path = tmp_path / "s.csv"
    path.write_text("condition,time [s],quantity,value,unit,uncertainty\n"
                    "v,0,a,20,degC,0.1\nv,0,D,0,um,1\nv,900,a,30,degC,0.1\nv,900,D,10,um,1.5\n")
    pairs = measured_pairs(one_input_law(lags=(900.0,)), read_measurements(str(path)), ambient_sensor="T6",
                           ambients={}, sigma=2e-6)
    a = np.exp(-1.0)
    np.testing.assert_allclose(pairs.features[:, 1], [293.15, a * 293.15 + (1 - a) * 303.15])
    np.testing.assert_allclose(pairs.sigma, [1e-6, 1.5e-6])


def test_the_ambient_sensor_reads_a_declared_conditions_ambient(tmp_path):
    path = tmp_path / "m.csv"
    path.write_text(FINALS)
    law = RegressionLaw(("a", "T6"), (), np.zeros((2, 1)), 0.0)
    pairs = measured_pairs(law, read_measurements(str(path)), ambient_sensor="T6", ambients={"I": 293.15, "II": 298.15},
                           sigma=2e-6)
    np.testing.assert_allclose(pairs.features[:, 1], [293.15, 298.15])


@pytest.mark.parametrize("text, message", [
    ("condition,quantity,unit,measured\nI,a,C,27.0\n", "no measured D"),
    ("condition,quantity,unit,measured\nI,b,C,27.0\nI,D_um,um,30.0\n", "condition I does not measure a, an input"),
])
def test_pairs_refuse_a_file_without_d_or_an_input(tmp_path, text, message):
    path = tmp_path / "m.csv"
    path.write_text(text)
    with pytest.raises(FeedthermError, match=message):
        measured_pairs(one_input_law(), read_measurements(str(path)), ambient_sensor="T6", ambients={}, sigma=2e-6)


def test_leave_one_condition_out_corrects_an_offset_the_model_got_wrong(tmp_path):
    """Five conditions on the line D = 10 µm + 2 µm/K (T − 293.15 K); the prior law is right in slope
    but 30 µm high.  Held out in turn: the prior misses by +30 µm, the adapted law (τ by evidence on
    the other four) and the least-squares line on them by far less; no reference column, no reference."""
    from feedtherm.analysis.compensation.leave_one_out import leave_one_condition_out

    temperatures = [22.0, 25.0, 28.0, 31.0, 35.0]
    lines = ["condition,quantity,unit,measured"]
    for i, t in enumerate(temperatures):
        lines += [f"c{i},a,C,{t}", f"c{i},D_um,um,{10 + 2 * (t - 20):.6f}"]
    path = tmp_path / "m.csv"
    path.write_text("\n".join(lines) + "\n")
    data = read_measurements(str(path))
    prior = RegressionLaw(("a",), (), np.array([[2e-6]]), 40e-6 - 2e-6 * 293.15)
    pairs = measured_pairs(prior, data, ambient_sensor="T6", ambients={}, sigma=2e-6)
    loco = leave_one_condition_out(prior, pairs, data, np.array([4.0]))
    assert [h.condition for h in loco.held_out] == ["c0", "c1", "c2", "c3", "c4"]
    assert loco.summary("model_only")["rms_um"] == pytest.approx(30.0)
    assert loco.summary("regression")["max_um"] < 1e-6
    assert loco.summary("adapted")["max_um"] < 3.0
    assert loco.summary("reference_model") is None
    assert loco.as_dict()["within_2sd"] == 5
