"""Points of the unit hypercube (scrambled Sobol' sequences) and their map to the parameters.

One map serves every use: the bands' quasi-Monte Carlo points and Saltelli's matrices for
the Sobol indices are drawn in [0, 1)^d and each column goes through its parameter's inverse
cumulative distribution function (:func:`ppf`).  Parameters fitted by a calibration are
correlated: their columns go through a Gaussian copula (:func:`to_values`).
"""

from __future__ import annotations

import numpy as np
from scipy.special import ndtri

from ...errors import FeedthermError
from .types import UncertainParameter

#: The distribution of a parameter fitted by a calibration: normal around the fit, clipped to
#: the fit's bounds (see :func:`to_values`).
POSTERIOR = "posterior normal"
#: Points this close to 0 or 1 are moved inward, so that an unbounded normal stays finite.
EDGE = 1e-12


def is_power_of_two(n: int) -> bool:
    return n > 0 and n & (n - 1) == 0


def unit_points(n: int, d: int, seed: int) -> np.ndarray:
    """``n`` scrambled Sobol' points in [0, 1)^d (``n`` a power of 2: only such sets are balanced)."""
    if not is_power_of_two(n):
        raise FeedthermError(f"--samples: must be a power of 2 (Sobol' points are balanced only in such sets), got {n}")
    from scipy.stats import qmc  # scipy.stats takes 0.35 s to import: only where a study samples

    return qmc.Sobol(d, scramble=True, seed=seed).random_base2(int(np.log2(n)))


def ppf(parameter: UncertainParameter, u) -> np.ndarray:
    """The parameter's quantiles at the probabilities ``u`` (its inverse CDF) [SI or factor].

    uniform: on [low, high]; triangular: on [low, high] with its mode at the declared value;
    normal: mean the declared value, standard deviation ``sigma``, truncated to [low, high]
    where a range is given; lognormal: median the declared value, ``sigma`` of ln x, truncated
    likewise (in ln x).
    """
    u = np.clip(np.asarray(u, dtype=float), EDGE, 1.0 - EDGE)
    p = parameter
    if p.distribution == "uniform":
        return p.low + u * (p.high - p.low)
    if p.distribution == "triangular":
        from scipy import stats  # 0.35 s to import: only for the distributions scipy.special lacks

        c = (p.declared - p.low) / (p.high - p.low)
        return stats.triang.ppf(u, c, loc=p.low, scale=p.high - p.low)
    if p.distribution in ("normal", "lognormal"):
        log = p.distribution == "lognormal"
        centre = np.log(p.declared) if log else p.declared
        if p.low is None:
            z = ndtri(u)  # Φ⁻¹ (scipy.stats.norm.ppf is this function)
        else:
            from scipy import stats

            a, b = ((np.log(v) if log else v) for v in (p.low, p.high))
            z = stats.truncnorm.ppf(u, (a - centre) / p.sigma, (b - centre) / p.sigma)
        x = centre + p.sigma * z
        return np.exp(x) if log else x
    raise ValueError(f"{p.name}: no distribution {p.distribution!r}")  # the schema admits none other


def to_values(parameters: list[UncertainParameter], u: np.ndarray, correlation: np.ndarray | None = None) -> np.ndarray:
    """Map points ``u`` (n, d) of the unit hypercube to parameter values (n, d).

    Parameters whose distribution is :data:`POSTERIOR` are jointly normal with the given
    ``correlation`` (a matrix over them, in their order): z = L·Φ⁻¹(u) with L Lᵀ the
    correlation (a Gaussian copula), x = mean + σ z, clipped to [low, high] (the fit's bounds:
    a fitted value cannot leave them, and clipping keeps the mean and spread of a posterior
    well inside them).  Every other column goes through :func:`ppf`.
    """
    u = np.atleast_2d(np.asarray(u, dtype=float))
    x = np.empty_like(u)
    posterior = [i for i, p in enumerate(parameters) if p.distribution == POSTERIOR]
    for i, p in enumerate(parameters):
        if i not in posterior:
            x[:, i] = ppf(p, u[:, i])
    if posterior:
        z = ndtri(np.clip(u[:, posterior], EDGE, 1.0 - EDGE))
        if correlation is not None:
            z = z @ correlation_root(correlation).T
        for j, i in enumerate(posterior):
            p = parameters[i]
            x[:, i] = np.clip(p.declared + p.sigma * z[:, j], p.low, p.high)
    return x


def correlation_root(correlation: np.ndarray) -> np.ndarray:
    """L with L Lᵀ = the correlation; a fit's matrix may be singular, so the symmetric root of
    its eigen-decomposition (negative rounding eigenvalues set to 0) rather than Cholesky."""
    c = 0.5 * (np.asarray(correlation, dtype=float) + np.asarray(correlation, dtype=float).T)
    w, v = np.linalg.eigh(c)
    return v @ np.diag(np.sqrt(np.clip(w, 0.0, None))) @ v.T
