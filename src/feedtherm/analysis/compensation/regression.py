"""The industry baseline: D from a few sensor temperatures by multiple linear regression.

.. math:: \\hat D(t) = b + \\sum_{s} \\Big( w_s\\,T_s(t) + \\sum_{\\tau} w_{s,\\tau}\\,L_\\tau[T_s](t) \\Big)

with a bias ``b`` [m], weights [m/K] and, optionally, first-order lags ``L_τ`` of each sensor
(time constants declared, :data:`DEFAULT_LAGS`).  The lags give the law a memory: the screw
heats within minutes of a speed change while a housing sensor follows over an hour, so the
present readings alone cannot tell a warming machine from a cooling one at the same
temperatures [1]_ [2]_.  The weights are the least-squares fit over every sample of the training
cycles, with a ridge penalty (Tikhonov regularisation [3]_ [4]_):

.. math:: \\min_w \\frac{1}{n} \\lVert y - X w \\rVert^2 + \\alpha \\lVert w \\rVert^2,
          \\qquad w = (X^T X + n \\alpha I)^{-1} X^T y .

Every regressor is a temperature [K], so one isotropic ``α`` [K²] is physical: it is the penalty
that white noise of variance ``α`` added to every regressor gives in expectation (Bishop 1995 [4]_),
and it is stated as that noise, ``σ_r = √α`` [K].  A pair of nearly collinear sensors fitted
without it takes weights of hundreds of µm/K of opposite sign (their difference carries the
signal), which turns a 0.1 K offset into tens of µm; the ridge trades that for a small bias.
``α`` is chosen on the validation cycles from :data:`RIDGE_GRID_K` (:mod:`.selection`), never on
the test cycles.

**Through the reference state.** Every displacement is zero with every part at the description's
reference temperature ``T_ref`` (``temperatures.reference``): so is the law's, by construction.
Its regressors are taken from ``T_ref`` (``T_s − T_ref`` and their lags) with no free intercept, and
the bias it exports is ``b = −T_ref Σ w``: a machine uniformly at ``T_ref`` (every reading and every
lag there) reads ``D̂ = 0`` exactly.  A free intercept (the columns centred, ``reference`` None) fits
the training cycles' mean and predicted +23 to +39 µm for a cold machine at the reference (issue 56),
more error than no compensation for the first minutes.

A lag is the discrete first-order filter a controller runs on each new reading:
``L_n = a L_{n-1} + (1 - a) T_n`` with ``a = exp(-Δt/τ)`` and ``L_0 = T_0`` (the machine starts
at rest: the filter starts settled at the first reading).

References
----------
.. [1] J. Mayr et al., "Thermal issues in machine tools", CIRP Annals 61(2), 771-791 (2012),
   §4.2: multiple linear regression on a few temperatures is the industrial standard of
   thermal error compensation; its weakness is the missing dynamics.
.. [2] J. Yang, J. Yuan, J. Ni, "Thermal error mode analysis and robust modeling for error
   compensation on a CNC turning center", Int. J. Mach. Tools Manuf. 39 (1999) 1367-1381:
   temperatures and their first-order lagged values as regressors of the thermal error.
.. [3] A. E. Hoerl, R. W. Kennard, "Ridge regression: biased estimation for nonorthogonal
   problems", Technometrics 12(1) (1970) 55-67.
.. [4] C. M. Bishop, "Training with noise is equivalent to Tikhonov regularization", Neural
   Computation 7(1) (1995) 108-116.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...errors import FeedthermError

#: Time constants of the lags [s].  900 s: the screw's own time constant, ρ c r / (2 h) with
#: GCr15 (7800 kg/m³, 729 J/(kg K)), r = 16 mm and the paper's printed screw CHTC, 56.3 W/(m² K), is 810 s.  3600 s: the
#: slow mode of the housings, base and table (the bench reaches equilibrium in 2-3 h, paper §4.2,
#: about three time constants).  Declared from the physics, not chosen on the held-out error.
DEFAULT_LAGS: tuple[float, ...] = (900.0, 3600.0)

#: The ridge strengths tried on the validation cycles, as the equivalent reading noise
#: ``σ_r = √α`` [K]: from none, through the declared sensors' noise (0.1-0.3 K) and offsets
#: (0.1-0.5 K), to 2 K, beyond which a law on readings that swing by a few kelvin is all bias.
RIDGE_GRID_K: tuple[float, ...] = (0.0, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0)


def ridge_weights(X: np.ndarray, y: np.ndarray, alphas) -> list[np.ndarray]:
    """Ridge weights of the centred ``X`` ``(n, p)`` [K] and ``y`` ``(n,)`` for each ``α`` [K²]
    (module notes), from one SVD; ``α = 0`` is the least-squares solution of least norm."""
    n = len(X)
    U, s, Vt = np.linalg.svd(X, full_matrices=False)
    uy = U.T @ y
    keep = s > (s.max() if s.size else 0.0) * max(X.shape) * np.finfo(float).eps
    out = []
    for alpha in alphas:
        if alpha > 0:
            factor = s / (s ** 2 + n * alpha)
        else:
            factor = np.where(keep, 1.0 / np.where(keep, s, 1.0), 0.0)
        out.append(Vt.T @ (factor * uy))
    return out


def lagged(times: np.ndarray, readings: np.ndarray, tau: float) -> np.ndarray:
    """The first-order lag of each column of ``readings`` (time along axis 0) with time constant ``tau`` [s].

    ``L_n = a L_{n-1} + (1 - a) T_n``, ``a = exp(-Δt_n/τ)``, ``L_0 = T_0`` (module notes).  Over each
    run of samples at one spacing the recurrence is a first-order IIR filter, run by
    ``scipy.signal.lfilter`` (in its transposed direct form each value is ``a·L_{n-1} + (1 − a)·T_n``,
    the same two products and one sum as the recurrence written out, so the same floats).
    """
    from scipy.signal import lfilter  # here: importing scipy.signal takes half a second, and `correct` imports this module

    readings = np.asarray(readings, dtype=float)
    out = np.empty_like(readings)
    out[0] = readings[0]
    decay = np.exp(-np.diff(np.asarray(times, dtype=float)) / tau)
    starts = [0, *(np.flatnonzero(decay[1:] != decay[:-1]) + 1).tolist()] if decay.size else []
    for start, end in zip(starts, [*starts[1:], decay.size]):
        a = decay[start]
        state = (a * out[start])[None]  # the filter's delay before sample start + 1: a·L_start
        out[start + 1:end + 1] = lfilter([1.0 - a, 0.0], [1.0, -a], readings[start + 1:end + 1], axis=0, zi=state)[0]
    return out


def features(times: np.ndarray, readings: np.ndarray, lags: tuple[float, ...]) -> np.ndarray:
    """Regressors of one cycle, ``(n, k·(1 + len(lags)))``: per sensor, its reading then its lags."""
    readings = np.atleast_2d(np.asarray(readings, dtype=float).T).T
    blocks = [readings[:, :, None], *(lagged(times, readings, tau)[:, :, None] for tau in lags)]
    return np.concatenate(blocks, axis=2).reshape(len(readings), -1)


@dataclass(frozen=True)
class RegressionLaw:
    """A fitted law: ``D = bias + features · weights`` (weights ``(k, 1 + len(lags))``, [m/K]);
    ``ridge``: the penalty ``α`` [K²] it was fitted with (module notes)."""

    sensors: tuple[str, ...]
    lags: tuple[float, ...]
    weights: np.ndarray
    bias: float
    ridge: float = 0.0

    def predict(self, times: np.ndarray, readings: np.ndarray) -> np.ndarray:
        """D [m] at ``times`` from ``readings`` ``(n, k)`` [K] of :attr:`sensors`, in order."""
        return self.bias + features(times, readings, self.lags) @ self.weights.ravel()

    def predict_record(self, record, names: list[str]) -> np.ndarray:
        """D [m] at every sample of a recorded cycle whose sensor columns are ``names``."""
        return self.predict(record.times, record.sensors[:, [names.index(s) for s in self.sensors]])


def fit_regression(cycles: list[tuple[np.ndarray, np.ndarray, np.ndarray]], sensors: tuple[str, ...],
                   lags: tuple[float, ...] = (), ridge: float = 0.0, reference: float | None = None) -> RegressionLaw:
    """Least-squares weights over every sample of ``cycles``, with the ridge penalty ``ridge``.

    Parameters
    ----------
    cycles : list of (times [s], readings (n, k) [K], D (n,) [m])
        One entry per cycle (the lags restart at each cycle's first sample).
    sensors : tuple of str
        Names of the readings' columns.
    lags : tuple of float
        Time constants [s] of the lagged regressors; empty for the static law.
    ridge : float
        The penalty ``α`` [K²] (module notes); 0: ordinary least squares.
    reference : float, optional
        The reference temperature [K] the law passes through (module notes); None: a free intercept.
    """
    if not cycles:
        raise FeedthermError("a regression needs at least one cycle")
    X = np.vstack([features(t, r, lags) for t, r, _ in cycles])
    y = np.concatenate([np.asarray(d, dtype=float) for _, _, d in cycles])
    if X.shape[1] != len(sensors) * (1 + len(lags)):
        raise FeedthermError(f"{X.shape[1]} regressors for {len(sensors)} sensors and {len(lags)} lags")
    weights, bias = solve_weights(X, y, [ridge], reference)[0]
    return RegressionLaw(tuple(sensors), tuple(float(t) for t in lags), weights.reshape(len(sensors), 1 + len(lags)),
                         bias, float(ridge))


def solve_weights(X: np.ndarray, y: np.ndarray, alphas, reference: float | None) -> list[tuple[np.ndarray, float]]:
    """``[(weights, bias), ...]`` per ridge ``α`` of ``alphas`` [K²] for regressors ``X`` [K] and ``y``:
    through ``reference`` [K] (``bias = −reference Σ w``), or with a free intercept (columns centred)."""
    if reference is not None:
        return [(w, float(-reference * w.sum())) for w in ridge_weights(X - reference, y, alphas)]
    mean_x, mean_y = X.mean(axis=0), y.mean()
    return [(w, float(mean_y - mean_x @ w)) for w in ridge_weights(X - mean_x, y - mean_y, alphas)]
