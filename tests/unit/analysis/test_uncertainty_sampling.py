"""The uncertainty study's mathematics against hand calculations: inverse CDFs, quantile
bands, a fit's posterior through the Gaussian copula, and Sobol' indices of analytic functions
through the same map and SALib wrapper the study uses."""

import math

import numpy as np
import pytest
from scipy import stats

from feedtherm.analysis.uncertainty.sampling import POSTERIOR, ppf, to_values, unit_points
from feedtherm.analysis.uncertainty.sobol import saltelli_points, sobol_indices
from feedtherm.analysis.uncertainty.study import quantile_bands
from feedtherm.analysis.uncertainty.types import UncertainParameter
from feedtherm.errors import FeedthermError


def parameter(name="x", distribution="uniform", declared=1.0, low=None, high=None, sigma=None, kind="value"):
    return UncertainParameter(name, "", kind, (f"a.{name}",), declared, distribution, low, high, sigma, "", "why", "")


def test_uniform_quantiles_are_linear_in_the_probability():
    p = parameter(distribution="uniform", declared=3.0, low=2.0, high=6.0)
    # F^-1(u) = 2 + 4 u
    assert ppf(p, [0.25, 0.5, 0.9]) == pytest.approx([3.0, 4.0, 5.6])


def test_triangular_mode_is_the_declared_value():
    # mode at the lower end of [0, 1]: F(x) = 1 - (1 - x)^2, so F^-1(u) = 1 - sqrt(1 - u)
    p = parameter(distribution="triangular", declared=0.0, low=0.0, high=1.0)
    u = np.array([0.1, 0.5, 0.75])
    assert ppf(p, u) == pytest.approx(1 - np.sqrt(1 - u))
    # mode inside: F(mode) = (mode - low) / (high - low)
    q = parameter(distribution="triangular", declared=150.0, low=50.0, high=365.0)
    assert ppf(q, [(150 - 50) / (365 - 50)]) == pytest.approx([150.0])


def test_a_truncated_normal_stays_in_its_range_and_is_centred_on_the_declared_value():
    p = parameter(distribution="normal", declared=1.0, low=0.9, high=1.1, sigma=0.2)
    x = ppf(p, np.linspace(0.0, 1.0, 101))
    assert x.min() >= 0.9 and x.max() <= 1.1
    assert ppf(p, [0.5]) == pytest.approx([1.0])  # symmetric truncation: the median is the mean
    # untruncated: Phi^-1(0.8413) = 1 standard deviation
    free = parameter(distribution="normal", declared=10.0, sigma=2.0)
    assert ppf(free, [stats.norm.cdf(1.0)]) == pytest.approx([12.0])
    assert np.isfinite(ppf(free, [0.0, 1.0])).all()  # the edges are moved inward, not infinite


def test_a_lognormal_has_the_declared_median_and_sigma_of_ln_x():
    p = parameter(distribution="lognormal", declared=800.0, sigma=1.0)
    assert ppf(p, [0.5, stats.norm.cdf(1.0)]) == pytest.approx([800.0, 800.0 * math.e])
    truncated = parameter(distribution="lognormal", declared=1.0, low=0.5, high=2.0, sigma=0.3)
    x = ppf(truncated, np.linspace(0, 1, 51))
    assert x.min() >= 0.5 - 1e-12 and x.max() <= 2.0 + 1e-12
    assert ppf(truncated, [0.5]) == pytest.approx([1.0])  # symmetric in ln x


def test_points_must_be_a_power_of_two():
    assert unit_points(8, 3, seed=1).shape == (8, 3)
    with pytest.raises(FeedthermError, match="--samples: must be a power of 2"):
        unit_points(100, 3, seed=1)
    with pytest.raises(FeedthermError, match="--sobol-base: must be a power of 2"):
        saltelli_points(["a", "b"], 48, seed=1)


def test_the_bands_of_a_monotone_model_are_its_quantile_mapping():
    # y = x^2 with x uniform on [1, 3]: the q-quantile of y is (1 + 2 q)^2
    p = parameter(distribution="uniform", declared=2.0, low=1.0, high=3.0)
    x = to_values([p], unit_points(1024, 1, seed=3))[:, 0]
    t = np.array([0.0, 1.0, 2.0])  # a "series": y(t) = t * x^2, monotone in x at every t > 0
    series = t[None, :] * (x ** 2)[:, None]
    bands = quantile_bands(series)
    assert bands.shape == (3, 3)
    expected = np.array([(1 + 2 * q) ** 2 for q in (0.05, 0.5, 0.95)])
    assert bands[:, 2] == pytest.approx(2 * expected, rel=5e-3)
    assert bands[:, 1] == pytest.approx(expected, rel=5e-3)
    assert bands[:, 0] == pytest.approx([0.0, 0.0, 0.0])


def test_the_posterior_reproduces_the_fit_mean_standard_errors_and_correlation():
    fitted = [parameter("a", POSTERIOR, declared=150.0, low=0.0, high=1000.0, sigma=20.0),
              parameter("b", POSTERIOR, declared=1.2, low=0.0, high=10.0, sigma=0.1, kind="scale"),
              parameter("c", "uniform", declared=0.1, low=0.0, high=1.0)]
    correlation = np.array([[1.0, -0.7], [-0.7, 1.0]])
    x = to_values(fitted, unit_points(4096, 3, seed=5), correlation)
    assert x[:, :2].mean(axis=0) == pytest.approx([150.0, 1.2], rel=2e-3)
    assert x[:, :2].std(axis=0) == pytest.approx([20.0, 0.1], rel=2e-2)
    assert np.corrcoef(x[:, 0], x[:, 1])[0, 1] == pytest.approx(-0.7, abs=0.02)
    assert x[:, 2].mean() == pytest.approx(0.5, abs=1e-3)  # the prior column keeps its own map
    assert abs(np.corrcoef(x[:, 0], x[:, 2])[0, 1]) < 0.05


def test_a_posterior_is_clipped_to_the_fit_bounds():
    p = parameter("a", POSTERIOR, declared=0.95, low=0.0, high=1.0, sigma=0.1)
    x = to_values([p], unit_points(1024, 1, seed=0))[:, 0]
    assert x.max() == 1.0 and x.min() >= 0.0
    # the mass above the bound sits on it: P(x > 1) = 1 - Phi(0.5)
    assert np.mean(x == 1.0) == pytest.approx(1 - stats.norm.cdf(0.5), abs=0.01)


def _indices_of(function, parameters, base):
    names = [p.name for p in parameters]
    x = to_values(parameters, saltelli_points(names, base, seed=11))
    return sobol_indices(names, function(x), seed=11)


def test_sobol_indices_of_a_linear_model():
    # y = a x1 + b x2, x uniform on [0, 1]: V_i = c_i^2 / 12, so S1_i = ST_i = c_i^2 / (a^2 + b^2)
    a, b = 1.0, 2.0
    parameters = [parameter("x1", low=0.0, high=1.0, declared=0.5), parameter("x2", low=0.0, high=1.0, declared=0.5)]
    found = _indices_of(lambda x: a * x[:, 0] + b * x[:, 1], parameters, 1024)
    expected = [a ** 2 / (a ** 2 + b ** 2), b ** 2 / (a ** 2 + b ** 2)]  # 0.2, 0.8
    assert found["S1"] == pytest.approx(expected, abs=0.02)
    assert found["ST"] == pytest.approx(expected, abs=0.02)
    assert (found["S1_conf"] > 0).all()


def test_sobol_indices_of_the_ishigami_function():
    # y = sin x1 + a sin^2 x2 + b x3^4 sin x1, x_i uniform on [-pi, pi] (Ishigami & Homma 1990):
    # V = a^2/8 + b pi^4/5 + b^2 pi^8/18 + 1/2, V1 = (1 + b pi^4/5)^2 / 2, V2 = a^2/8,
    # V13 = 8 b^2 pi^8 / 225, V3 = 0; ST1 = (V1 + V13)/V, ST2 = V2/V, ST3 = V13/V.
    a, b, pi = 7.0, 0.1, math.pi
    v = a ** 2 / 8 + b * pi ** 4 / 5 + b ** 2 * pi ** 8 / 18 + 0.5
    v1, v2, v13 = (1 + b * pi ** 4 / 5) ** 2 / 2, a ** 2 / 8, 8 * b ** 2 * pi ** 8 / 225
    parameters = [parameter(n, low=-pi, high=pi, declared=0.0) for n in ("x1", "x2", "x3")]
    found = _indices_of(lambda x: np.sin(x[:, 0]) + a * np.sin(x[:, 1]) ** 2 + b * x[:, 2] ** 4 * np.sin(x[:, 0]),
                        parameters, 4096)
    assert found["S1"] == pytest.approx([v1 / v, v2 / v, 0.0], abs=0.03)  # 0.314, 0.442, 0
    assert found["ST"] == pytest.approx([(v1 + v13) / v, v2 / v, v13 / v], abs=0.03)  # 0.558, 0.442, 0.244


def test_an_output_that_does_not_vary_has_no_indices():
    found = sobol_indices(["x1", "x2"], np.full(8, 20.0), seed=0)
    assert list(found["ST"]) == [0.0, 0.0]


def test_the_bootstrap_intervals_are_reproducible_with_seed_zero():
    # SALib seeds its bootstrap only for a truthy seed: the study's default seed 0 must still
    # give the same intervals on every call, whatever numpy's global state
    parameters = [parameter("x1", low=0.0, high=1.0, declared=0.5), parameter("x2", low=0.0, high=1.0, declared=0.5)]
    names = [p.name for p in parameters]
    x = to_values(parameters, saltelli_points(names, 64, seed=0))
    y = x[:, 0] + 2 * x[:, 1] ** 2
    first = sobol_indices(names, y, seed=0)
    np.random.seed(12345)  # another state of the global generator
    second = sobol_indices(names, y, seed=0)
    assert first["S1_conf"].tolist() == second["S1_conf"].tolist()
    assert first["ST_conf"].tolist() == second["ST_conf"].tolist()
