"""A regression law trained on simulated cycles, updated on measured pairs of its machine.

The law :math:`D = b + \\mathbf f^{\\mathsf T}\\mathbf w` (:mod:`.regression`; features
:math:`\\mathbf f` [K]: each input's reading, then its lags) carries the model's relation between
temperatures and elongation.  A measured machine differs from its model (on the paper's bench the
law on the declared sensors misses the measured D by −14 … +45 µm, docs/compensation.md §4), and a few measured
pairs (temperatures, D) can correct it.  Few: a bench measures a handful of conditions, fewer than
the law's coefficients, so a least-squares fit on them alone is underdetermined.  The simulated
law is the prior and the measurements update it, the conjugate Gaussian linear model [1]_ §3.3.

**Coordinates.**  The coefficients are updated in scaled, centred coordinates

.. math:: D = c + \\sum_j \\theta_j\\,\\frac{f_j - m_j}{s_j},
   \\qquad \\theta_j = w_j s_j, \\quad c = b + \\mathbf m^{\\mathsf T}\\mathbf w,

with :math:`\\mathbf m` [K] the mean of the adaptation features (so :math:`c` [m] is the law's D at
the measured operating region) and :math:`s_j` [K] the spread (standard deviation) of feature
:math:`j` over the law's *training* cycles (the range the law was built for; independent of the
measurements).  Every :math:`\\theta_j` [m] is then the change of D over one typical swing of its
feature, and :math:`c` the level of D: all in metres, comparable.

**Prior.**  :math:`\\boldsymbol\\theta \\sim \\mathcal N(\\boldsymbol\\theta_0, \\tau^2 I)`, with
:math:`\\boldsymbol\\theta_0` the simulation-trained law's coefficients: the measured machine's level
and each feature's contribution are those of the model, give or take :math:`\\tau` [m], one width
for all, because nothing says beforehand which coefficient the mismatch sits in.

**Width** :math:`\\tau`: maximum marginal likelihood (type-2 maximum likelihood, the evidence
[1]_ §3.5) on the adaptation data only,

.. math:: \\hat\\tau = \\arg\\max_\\tau\\; \\log \\mathcal N\\big(\\mathbf y;\\ \\Phi\\boldsymbol\\theta_0,\\
   \\tau^2 \\Phi\\Phi^{\\mathsf T} + \\operatorname{diag}\\boldsymbol\\sigma^2\\big),

a one-dimensional search on :math:`\\log\\tau`.  The data say how far the machine is from its model:
residuals within the noise drive :math:`\\tau \\to 0` (the posterior is the prior), large
residuals widen it.  Nothing of a held-out condition enters (leave-one-condition-out chooses
:math:`\\tau` on the others).

**Noise.**  Each measured D has a Gaussian error of standard deviation :math:`\\sigma_i` [m]: the
file's ``uncertainty`` column where it gives one, else the description's
``calibration.elongation_sigma``, else 2 µm, the value calibration and inference use
(:mod:`.pairs`).  The measured temperatures' own
uncertainty is not propagated (errors in variables): at 0.5 K through weights of norm
11 µm/K (the paper bench's static law on its declared sensors) it would add about 6 µm in
quadrature; left out, it is part of what :math:`\\tau` absorbs, and the predictive standard
deviation below is short of it.

**Posterior** ([1]_ eqs. 3.49–3.51, with :math:`\\Lambda = \\operatorname{diag}\\boldsymbol\\sigma^{-2}`):

.. math:: S_N = \\big(\\tau^{-2} I + \\Phi^{\\mathsf T}\\Lambda\\Phi\\big)^{-1}, \\qquad
   \\boldsymbol\\theta_N = S_N\\big(\\tau^{-2}\\boldsymbol\\theta_0 + \\Phi^{\\mathsf T}\\Lambda\\mathbf y\\big),

and the predictive standard deviation of a measured D at features :math:`\\mathbf f` ([1]_ eq. 3.59)
:math:`\\sqrt{\\boldsymbol\\varphi^{\\mathsf T} \\Sigma \\boldsymbol\\varphi + \\sigma^2}` with
:math:`\\boldsymbol\\varphi = [1, \\mathbf f - \\mathbf m]` and :math:`\\Sigma` the posterior covariance of
:math:`[c, \\mathbf w]` [m², m²/K, m²/K²]; :math:`\\sigma` [m] is the median of the adaptation
samples' (a new reading's noise).

**Pairs** (:mod:`.pairs`): from final values one per condition, each lag settled at its reading;
from a time series every sample of D, the lags run over the series.

References
----------
.. [1] C. M. Bishop, *Pattern Recognition and Machine Learning*, Springer (2006): §3.3 Bayesian
   linear regression; §3.5 the evidence approximation.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...errors import FeedthermError
from .pairs import Pairs
from .regression import RegressionLaw, features

#: A feature that does not vary over the training cycles is scaled by 1 K (its coefficient's width
#: is then τ per kelvin).
UNIT_SCALE = 1.0
#: A singular value of a least-squares design below this fraction of the largest is rounding (the
#: null direction centring creates is about 1e-15; the measured bench's real ones are above 1e-2) [-].
RANK_TOLERANCE = 1e-10
#: Search range of the prior width, relative to the data: from far below the smallest noise to far
#: above the largest residual [-].
_WIDTH_RANGE = 1e-4


@dataclass(frozen=True)
class AdaptedLaw:
    """The posterior of a law's coefficients after measured pairs.

    Attributes
    ----------
    law : RegressionLaw
        The posterior mean, a law like any other (``predict`` gives D [m]).
    prior : RegressionLaw
        The simulation-trained law it started from.
    centre : ndarray, shape (p,)
        The features' centre m [K] (the adaptation features' mean).
    covariance : ndarray, shape (1 + p, 1 + p)
        Posterior covariance of [c, w]: the law's D at the centre [m], the weights [m/K].
    noise_sigma : float
        σ [m] of a new measured D, added to the predictive variance.
    width : float
        The prior width τ [m] (scaled coordinates).
    log_evidence : float
        log p(y | τ) at that width [-].
    samples : int
        Number of measured pairs.
    width_at_bound : bool
        True when the evidence's maximum lies at the search's edge (at the lower one: the data are
        within their noise of the prior, the posterior is the prior).
    scale : ndarray, shape (p,), or None
        The features' scale s [K] of the prior's coordinates.
    """

    law: RegressionLaw
    prior: RegressionLaw
    centre: np.ndarray
    covariance: np.ndarray
    noise_sigma: float
    width: float
    log_evidence: float
    samples: int
    width_at_bound: bool = False
    scale: np.ndarray | None = None

    def sd(self, feature_rows: np.ndarray) -> np.ndarray:
        """Predictive standard deviation [m] of a measured D at each row of features ``(n, p)`` [K]."""
        phi = np.column_stack([np.ones(len(feature_rows)), np.asarray(feature_rows, float) - self.centre])
        variance = np.einsum("ij,jk,ik->i", phi, self.covariance, phi) + self.noise_sigma ** 2
        return np.sqrt(np.maximum(variance, 0.0))

    def predict(self, times: np.ndarray, readings: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """D [m] and its predictive standard deviation [m] at ``times`` [s] from ``readings`` ``(n, k)`` [K]."""
        rows = features(times, readings, self.law.lags)
        return self.law.bias + rows @ self.law.weights.ravel(), self.sd(rows)

    def predict_features(self, feature_rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """D [m] and its predictive standard deviation [m] at rows of features ``(n, p)`` [K]."""
        rows = np.atleast_2d(np.asarray(feature_rows, float))
        return self.law.bias + rows @ self.law.weights.ravel(), self.sd(rows)


# ------------------------------------------------------------------ the conjugate update


def gaussian_posterior(phi: np.ndarray, y: np.ndarray, sigma: np.ndarray, prior_mean: np.ndarray,
                       prior_covariance: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Posterior mean and covariance of θ in ``y = Φθ + ε``, ``ε ~ N(0, diag σ²)``, ``θ ~ N(μ₀, S₀)``.

    .. math:: S_N = (S_0^{-1} + \\Phi^{\\mathsf T}\\Lambda\\Phi)^{-1}, \\quad
       \\mu_N = S_N (S_0^{-1}\\mu_0 + \\Phi^{\\mathsf T}\\Lambda y)

    Bishop (2006) eqs. 3.49–3.51, computed in whitened form so that it stays exact from a prior of
    zero width to one far wider than the data: with :math:`S_0 = L L^{\\mathsf T}` and the singular
    values :math:`B = \\Lambda^{1/2}\\Phi L = U S V^{\\mathsf T}`,
    :math:`S_N = L V (I + S^{\\mathsf T} S)^{-1} V^{\\mathsf T} L^{\\mathsf T}` and
    :math:`\\mu_N = \\mu_0 + L V (I + S^{\\mathsf T} S)^{-1} S^{\\mathsf T} U^{\\mathsf T}\\Lambda^{1/2}(y - \\Phi\\mu_0)`.
    """
    root, u, s, vt, white = _whitened(phi, y, sigma, prior_mean, prior_covariance)
    p = vt.shape[0]
    s_full = np.zeros(p)
    s_full[:len(s)] = s
    shrink = 1.0 / (1.0 + s_full ** 2)
    lv = root @ vt.T
    projected = np.zeros(p)
    projected[:len(s)] = s * (u[:, :len(s)].T @ white)
    mean = prior_mean + lv @ (shrink * projected)
    covariance = (lv * shrink) @ lv.T
    return mean, 0.5 * (covariance + covariance.T)


def log_evidence(phi: np.ndarray, y: np.ndarray, sigma: np.ndarray, prior_mean: np.ndarray,
                 prior_covariance: np.ndarray) -> float:
    """log p(y) [-] under the prior: ``y ~ N(Φμ₀, Φ S₀ Φᵀ + diag σ²)`` (Bishop 2006, eq. 3.86 in general form),
    through the whitened singular values of :func:`gaussian_posterior`."""
    _, u, s, _, white = _whitened(phi, y, sigma, prior_mean, prior_covariance)
    along = u[:, :len(s)].T @ white
    quadratic = white @ white - np.sum(s ** 2 / (1.0 + s ** 2) * along ** 2)
    logdet = 2.0 * np.sum(np.log(np.asarray(sigma, float))) + np.sum(np.log1p(s ** 2))
    return float(-0.5 * (quadratic + logdet + len(white) * np.log(2 * np.pi)))


def _whitened(phi, y, sigma, prior_mean, prior_covariance):
    """L with S₀ = L Lᵀ (symmetric square root, exact for a singular S₀), the SVD of
    B = Λ^½ Φ L, and the whitened residual Λ^½ (y − Φμ₀)."""
    phi = np.atleast_2d(np.asarray(phi, float))
    sigma = np.asarray(sigma, float)
    values, vectors = np.linalg.eigh(np.asarray(prior_covariance, float))
    root = vectors * np.sqrt(np.clip(values, 0.0, None))
    u, s, vt = np.linalg.svd(phi @ root / sigma[:, None], full_matrices=True)
    white = (np.asarray(y, float) - phi @ prior_mean) / sigma
    return root, u, s, vt, white


def evidence_width(phi: np.ndarray, y: np.ndarray, sigma: np.ndarray, prior_mean: np.ndarray) -> tuple[float, bool]:
    """The prior width τ [y's unit] of ``θ ~ N(μ₀, τ² I)`` that maximises the evidence, and whether
    the maximum lies at the search's edge.

    A log-spaced scan then a bounded Brent search on log τ, between :data:`_WIDTH_RANGE` times the
    smallest σ and 1/:data:`_WIDTH_RANGE` times the largest of σ and the prior's residuals.
    """
    phi = np.atleast_2d(np.asarray(phi, float))
    residual = np.abs(np.asarray(y, float) - phi @ prior_mean)
    low = np.log(_WIDTH_RANGE * float(np.min(sigma)))
    high = np.log(max(float(np.max(sigma)), float(np.max(residual))) / _WIDTH_RANGE)
    eye = np.eye(phi.shape[1])

    def negative(log_width: float) -> float:
        return -log_evidence(phi, y, sigma, prior_mean, np.exp(2 * log_width) * eye)

    grid = np.linspace(low, high, 121)
    values = [negative(g) for g in grid]
    best = int(np.argmin(values))
    if best in (0, len(grid) - 1):
        return float(np.exp(grid[best])), True
    from scipy.optimize import minimize_scalar  # 0.1 s to import: only where a width is refined

    found = minimize_scalar(negative, bounds=(grid[best - 1], grid[best + 1]), method="bounded",
                            options={"xatol": 1e-6})
    return float(np.exp(found.x)), False


def adapt_law(law: RegressionLaw, pairs: Pairs, scale: np.ndarray | None = None, *, width: float | None = None,
              centre: np.ndarray | None = None, reference: float | None = None) -> AdaptedLaw:
    """The posterior of ``law`` after ``pairs`` (see the module's notes).

    Parameters
    ----------
    law : RegressionLaw
        The prior mean (the simulation-trained law).
    pairs : Pairs
        Measured features [K], D [m] and σ [m] (:func:`.pairs.measured_pairs`).
    scale : ndarray, shape (p,), optional
        Each feature's spread s [K] over the law's training cycles (:func:`feature_scale`); default
        :data:`UNIT_SCALE`.
    width : float, optional
        The prior width τ [m]; default: maximum evidence on ``pairs`` (:func:`evidence_width`).
    centre : ndarray, shape (p,), optional
        The features' centre m [K]; default: the mean of ``pairs.features``.
    reference : float, optional
        The reference temperature [K] the law keeps passing through (:mod:`.regression`): no free
        level, ``c = (m − reference)·w``, so the adapted law reads 0 for a machine at the reference
        too.  None: the level ``c`` is a coefficient of its own.
    """
    x = np.atleast_2d(np.asarray(pairs.features, float))
    if len(x) == 0:
        raise FeedthermError("adaptation: no measured pairs")
    w0 = law.weights.ravel()
    p = len(w0)
    m = x.mean(axis=0) if centre is None else np.asarray(centre, float)
    s = np.full(p, UNIT_SCALE) if scale is None else np.asarray(scale, float)
    s = np.where(s > 0, s, UNIT_SCALE)
    if reference is not None:  # D = Σ θ_j (f_j − T_ref)/s_j: the weights alone, the level follows them
        phi = (x - reference) / s
        theta0 = w0 * s
    else:
        phi = np.column_stack([np.ones(len(x)), (x - m) / s])
        theta0 = np.concatenate([[law.bias + m @ w0], w0 * s])
    at_bound = False
    if width is None:
        width, at_bound = evidence_width(phi, pairs.elongation, pairs.sigma, theta0)
    prior = width ** 2 * np.eye(len(theta0))
    theta, cov_theta = gaussian_posterior(phi, pairs.elongation, pairs.sigma, theta0, prior)
    if reference is not None:  # [θ] -> [c, w] with c = (m − T_ref)·w, the law's D at the centre
        to_law = np.vstack([(m - reference) / s, np.diag(1.0 / s)])
        coefficients, covariance = to_law @ theta, to_law @ cov_theta @ to_law.T
    else:
        to_law = np.concatenate([[1.0], 1.0 / s])  # [c, θ] -> [c, w]
        coefficients = theta * to_law
        covariance = cov_theta * np.outer(to_law, to_law)
    weights = coefficients[1:]
    mean = RegressionLaw(law.sensors, law.lags, weights.reshape(law.weights.shape), float(coefficients[0] - m @ weights))
    return AdaptedLaw(mean, law, m, covariance, float(np.median(pairs.sigma)), float(width),
                      log_evidence(phi, pairs.elongation, pairs.sigma, theta0, prior), len(x), at_bound, s)


def minimum_norm_fit(law: RegressionLaw, pairs: Pairs, scale: np.ndarray | None = None) -> RegressionLaw:
    """Least squares on ``pairs`` alone, in the coordinates of :func:`adapt_law` (centred at the
    pairs' mean, scaled by ``scale``): with fewer pairs than coefficients, the solution of least
    norm of the scaled weights (``numpy.linalg.lstsq``, the Moore–Penrose pseudo-inverse).

    Singular values below :data:`RANK_TOLERANCE` of the largest count as zero.  Centring n pairs
    leaves a design of rank at most n − 1 whose last singular value is rounding (about 1e-15 of the
    largest), which numpy's default cutoff (machine epsilon times the larger dimension) can keep;
    kept, it divides rounding by rounding and moves the fit by an amount of the order of the data."""
    x = np.atleast_2d(np.asarray(pairs.features, float))
    m = x.mean(axis=0)
    s = np.full(x.shape[1], UNIT_SCALE) if scale is None else np.where(np.asarray(scale) > 0, scale, UNIT_SCALE)
    y = pairs.elongation
    theta, *_ = np.linalg.lstsq((x - m) / s, y - y.mean(), rcond=RANK_TOLERANCE)
    weights = theta / s
    return RegressionLaw(law.sensors, law.lags, weights.reshape(law.weights.shape), float(y.mean() - m @ weights))


def feature_scale(law: RegressionLaw, records, names: list[str]) -> np.ndarray:
    """Each feature's standard deviation [K] over every sample of ``records`` (the law's training
    cycles: ``times`` [s], ``sensors`` [K] with columns ``names``), the lags restarting per cycle."""
    index = [names.index(s) for s in law.sensors]
    rows = np.vstack([features(r.times, r.sensors[:, index], law.lags) for r in records])
    return rows.std(axis=0)
