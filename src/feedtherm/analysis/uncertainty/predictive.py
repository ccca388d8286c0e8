"""Posterior predictive quantiles: the parameters' spread widened by the model error.

A Bayesian update (:mod:`.update`) fits the measured finals with residuals
r = (y − y_measured)/σ ~ N(0, s² I): the noise scale s² measures how far the model misses the
measurements at its best parameters, in the weights σ.  The band of the sampled parameters says
where the *model's* prediction can go; a prediction of a *measured* value also carries that
misfit.  The posterior predictive distribution of a measured final value is then (Gelman et al.
2013, §1.3, Eq. 1.4, with the normal likelihood of the update)

    p(ỹ | data) = ∫ N(ỹ; y(x), s²σ²) p(x | data) dx
                ≈ (1/n) Σ_i N(ỹ; y_i, s²σ²),

the sampled parameter points x_i standing in for the posterior (each with weight 1/n), y_i the
model's final value at x_i.  Its cumulative distribution is F(ỹ) = (1/n) Σ_i Φ((ỹ − y_i)/(sσ)),
monotone and continuous, so each quantile is the one root of F(ỹ) = p
(:func:`scipy.optimize.brentq`), bracketed by min y_i − 9 sσ and max y_i + 9 sσ, where F is
within 1e-18 of 0 and 1.

Reference
---------
.. [1] Gelman, A., Carlin, J. B., Stern, H. S., Dunson, D. B., Vehtari, A., Rubin, D. B. (2013).
   *Bayesian Data Analysis*, 3rd ed., CRC Press. §1.3 (posterior predictive distribution),
   §6.3 (posterior predictive checks).
"""

from __future__ import annotations

import numpy as np
from scipy.special import ndtr

#: Half-width of the bracket of a quantile's root, in model-error standard deviations.
BRACKET_SD = 9.0
#: Absolute tolerance of a quantile [°C or µm]: 1e-6 of the value's unit, far below any band's width.
QUANTILE_TOLERANCE = 1e-6


def predictive_quantiles(values, error_sd: float, probabilities) -> np.ndarray:
    """Quantiles of the equal-weight normal mixture (1/n) Σ_i N(y_i, error_sd²).

    Parameters
    ----------
    values : array_like, shape (n,)
        The model's final value y_i at each sampled parameter point [°C or µm].
    error_sd : float
        The model error's standard deviation s·σ [same unit as ``values``], ≥ 0.  Zero gives
        the plain sample quantiles (``numpy.quantile``, linear interpolation), the band of the
        parameters alone.
    probabilities : sequence of float
        The probabilities p in (0, 1) of the quantiles.

    Returns
    -------
    numpy.ndarray, shape (len(probabilities),)
        ỹ_p with (1/n) Σ_i Φ((ỹ_p − y_i)/error_sd) = p, to :data:`QUANTILE_TOLERANCE`.

    Notes
    -----
    Valid for any n ≥ 1; with n = 1 the quantiles are those of N(y_1, error_sd²),
    y_1 + error_sd Φ⁻¹(p). Source: Gelman et al. (2013), §1.3.
    """
    y = np.asarray(values, dtype=float).ravel()
    p = np.asarray(probabilities, dtype=float)
    if y.size == 0:
        raise ValueError("predictive_quantiles: no sampled values")
    if error_sd < 0 or not np.isfinite(error_sd):
        raise ValueError(f"predictive_quantiles: error_sd must be finite and >= 0, got {error_sd}")
    if np.any((p <= 0) | (p >= 1)):
        raise ValueError(f"predictive_quantiles: probabilities must lie in (0, 1), got {p.tolist()}")
    if error_sd == 0.0:
        return np.quantile(y, p)
    low, high = y.min() - BRACKET_SD * error_sd, y.max() + BRACKET_SD * error_sd

    def excess(x: float, target: float) -> float:
        return float(np.mean(ndtr((x - y) / error_sd))) - target  # Φ (scipy.stats.norm.cdf is this function)

    from scipy.optimize import brentq  # 0.1 s to import: only where a band is computed

    return np.array([brentq(excess, low, high, args=(float(q),), xtol=QUANTILE_TOLERANCE) for q in p])
