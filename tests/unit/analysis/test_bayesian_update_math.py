"""The Bayesian update's mathematics against hand calculations: on a linear model with normal
priors the Laplace posterior is exact, so it must equal the conjugate Gaussian formulas; the
noise scale's fixed point on a toy whose misfit is known; posterior samples of bounded priors
stay inside them; the posterior is never wider than the prior."""

import numpy as np
import pytest
from scipy import stats

from feedtherm.analysis.uncertainty.sampling import unit_points
from feedtherm.analysis.uncertainty.types import UncertainParameter
from feedtherm.analysis.uncertainty.update import (
    S2_RTOL, BayesianUpdate, effective_parameters, laplace_update, noise_scale, to_x)


def parameter(name, distribution, declared, low=None, high=None, sigma=None):
    return UncertainParameter(name, "", "value", (f"a.{name}",), declared, distribution, low, high, sigma, "", "why", "")


class LinearModel:
    """y = G x + g0 with normal priors x_i ~ N(μ_i, τ_i²): residuals (y(x(z)) − y_measured)/σ_e."""

    def __init__(self, G, g0, measured, sigma_e, mu, tau):
        self.G, self.g0, self.y, self.se = (np.asarray(a, dtype=float) for a in (G, g0, measured, sigma_e))
        self.prior = [parameter(f"x{i}", "normal", m, sigma=t) for i, (m, t) in enumerate(zip(mu, tau))]
        self.batches = []

    def __call__(self, z):
        self.batches.append(len(z))
        x = to_x(self.prior, z)
        return ((x @ self.G.T + self.g0) - self.y) / self.se


def conjugate(model: LinearModel, mu, tau):
    """The textbook posterior of a linear-Gaussian model in x (e.g. Gelman et al., BDA §14):
    P = Gᵀ Σe⁻¹ G + Σ0⁻¹, mean = P⁻¹ (Gᵀ Σe⁻¹ (y − g0) + Σ0⁻¹ μ), covariance P⁻¹."""
    inv_e = np.diag(1.0 / model.se ** 2)
    inv_0 = np.diag(1.0 / np.asarray(tau) ** 2)
    precision = model.G.T @ inv_e @ model.G + inv_0
    cov = np.linalg.inv(precision)
    mean = cov @ (model.G.T @ inv_e @ (model.y - model.g0) + inv_0 @ np.asarray(mu))
    return mean, cov


MU, TAU = [2.0, -1.0], [0.5, 0.2]
G = [[1.0, 2.0], [0.5, -1.0], [2.0, 0.0], [0.0, 3.0], [1.0, 1.0]]
G0 = [0.1, 0.0, -0.2, 0.3, 0.0]


def toy(measured):
    return LinearModel(G, G0, measured, [0.4, 0.3, 0.5, 0.4, 0.3], MU, TAU)


#: Measurements the model reproduces closely at x = (2.3, −1.1): the residual variance stays below 1.
CLOSE = np.array(G) @ [2.3, -1.1] + G0 + [0.05, -0.04, 0.06, -0.03, 0.02]


@pytest.mark.parametrize("s2", [1.0, None])  # forced, and the fixed point (which stays at its floor 1 here)
def test_a_linear_model_gives_the_conjugate_gaussian_posterior(s2):
    model = toy(CLOSE)
    fit = laplace_update(model, 2, s2=s2)
    assert fit.s2 == 1.0
    mean, cov = conjugate(model, MU, TAU)
    tau = np.asarray(TAU)
    # x = μ + τ z for an untruncated normal prior
    assert MU + tau * fit.z == pytest.approx(mean, abs=1e-6)
    assert np.outer(tau, tau) * fit.covariance == pytest.approx(cov, rel=1e-6, abs=1e-12)
    # every Jacobian is one batch of at most d + 1 points
    assert max(model.batches) <= 3


def test_the_noise_scale_reaches_its_fixed_point_on_a_known_misfit():
    # one parameter acting on four values alike, which scatter ±3 about 0.5: the misfit is known.
    # MAP z = Σc / (m + s²) = 2 / (4 + s²); p_eff = 4 / (4 + s²); s² = Σ (z − c_k)² / (4 − p_eff)
    c = np.array([3.5, -2.5, 3.5, -2.5])

    def residuals(z):
        return z[:, :1] - c[None, :]

    s2 = 1.0
    for _ in range(200):  # the hand iteration, to convergence
        z = 2.0 / (4.0 + s2)
        s2 = np.sum((z - c) ** 2) / (4.0 - 4.0 / (4.0 + s2))
    assert s2 > 9.0  # the scatter is far beyond the weights
    fit = laplace_update(residuals, 1)
    assert fit.converged and 2 <= fit.passes <= 4
    assert fit.s2 == pytest.approx(s2, rel=S2_RTOL)
    assert fit.z[0] == pytest.approx(2.0 / (4.0 + fit.s2), abs=1e-6)  # the MAP at the s² it reports
    assert fit.p_eff == pytest.approx(4.0 / (4.0 + fit.s2), rel=1e-9)
    assert fit.covariance[0, 0] == pytest.approx(1.0 / (4.0 / fit.s2 + 1.0), rel=1e-9)


def test_effective_parameters_and_noise_scale_by_hand():
    J = np.array([[3.0, 0.0], [0.0, 1.0], [0.0, 0.0]])  # JᵀJ = diag(9, 1)
    assert effective_parameters(J, 1.0) == pytest.approx(9 / 10 + 1 / 2)
    assert noise_scale(np.array([2.0, 2.0, 2.0]), 1.4) == pytest.approx(12.0 / 1.6)
    assert noise_scale(np.array([0.1, 0.1, 0.1]), 1.4) == 1.0  # never below the weights
    assert noise_scale(np.array([2.0]), 1.4) == 1.0  # no degrees of freedom left


@pytest.mark.parametrize("measured", [CLOSE, CLOSE + [3.0, -2.0, 4.0, 1.0, -3.0]])
def test_the_posterior_is_never_wider_than_the_prior(measured):
    fit = laplace_update(toy(measured), 2)
    assert (fit.sd <= 1.0).all() and (fit.sd < 0.999).any()
    assert np.linalg.eigvalsh(np.eye(2) - fit.covariance).min() >= -1e-12  # Σ ≤ I in every direction


def test_samples_of_bounded_priors_stay_inside_them():
    prior = [parameter("u", "uniform", 1.0, low=0.5, high=1.5),
             parameter("t", "triangular", 150.0, low=50.0, high=365.0)]

    def residuals(z):  # measured close to both upper ends, precisely
        x = to_x(prior, z)
        return np.column_stack([(x[:, 0] - 1.45) / 0.01, (x[:, 1] - 355.0) / 1.0])

    fit = laplace_update(residuals, 2, s2=1.0)
    update = BayesianUpdate(loaded=None, nominal=None, prior=prior, parameters=[], fit=fit, x_map=to_x(prior, fit.z)[0],
                            fit_conditions=[], rows=[], excluded=[], conditions_runs=0)
    x = update.values(unit_points(256, 2, 0))
    assert (x[:, 0] >= 0.5).all() and (x[:, 0] <= 1.5).all()
    assert (x[:, 1] >= 50.0).all() and (x[:, 1] <= 365.0).all()
    assert np.median(x[:, 0]) > 1.4 and np.median(x[:, 1]) > 340.0  # moved to the data, yet inside


def test_posterior_points_have_the_posterior_moments():
    fit = laplace_update(toy(CLOSE), 2, s2=1.0)
    z = fit.z_points(unit_points(4096, 2, 0))
    assert z.mean(axis=0) == pytest.approx(fit.z, abs=0.01)
    assert np.cov(z.T) == pytest.approx(fit.covariance, abs=0.01)
    # the point u = ½ is the mode
    assert fit.z_points(np.full((1, 2), 0.5))[0] == pytest.approx(fit.z)
    assert stats.norm.cdf(0.0) == 0.5
