"""The industry baseline: D from a few sensor temperatures by multiple linear regression.

.. math:: \\hat D(t) = b + \\sum_{s} \\Big( w_s\\,T_s(t) + \\sum_{\\tau} w_{s,\\tau}\\,L_\\tau[T_s](t) \\Big)

with a bias ``b`` [m], weights [m/K] and, optionally, first-order lags ``L_τ`` of each sensor
(time constants declared, :data:`DEFAULT_LAGS`).  The lags give the law a memory: the screw
heats within minutes of a speed change while a housing sensor follows over an hour, so the
present readings alone cannot tell a warming machine from a cooling one at the same
temperatures [1]_ [2]_.  The weights are the ordinary least-squares fit over every sample of the
training cycles (columns centred, so the fit does not depend on the temperatures' origin).

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


def lagged(times: np.ndarray, readings: np.ndarray, tau: float) -> np.ndarray:
    """The first-order lag of each column of ``readings`` (time along axis 0) with time constant ``tau`` [s]."""
    readings = np.asarray(readings, dtype=float)
    out = np.empty_like(readings)
    out[0] = readings[0]
    decay = np.exp(-np.diff(np.asarray(times, dtype=float)) / tau)
    for n in range(1, len(readings)):
        out[n] = decay[n - 1] * out[n - 1] + (1.0 - decay[n - 1]) * readings[n]
    return out


def features(times: np.ndarray, readings: np.ndarray, lags: tuple[float, ...]) -> np.ndarray:
    """Regressors of one cycle, ``(n, k·(1 + len(lags)))``: per sensor, its reading then its lags."""
    readings = np.atleast_2d(np.asarray(readings, dtype=float).T).T
    blocks = [readings[:, :, None], *(lagged(times, readings, tau)[:, :, None] for tau in lags)]
    return np.concatenate(blocks, axis=2).reshape(len(readings), -1)


@dataclass(frozen=True)
class RegressionLaw:
    """A fitted law: ``D = bias + features · weights`` (weights ``(k, 1 + len(lags))``, [m/K])."""

    sensors: tuple[str, ...]
    lags: tuple[float, ...]
    weights: np.ndarray
    bias: float

    def predict(self, times: np.ndarray, readings: np.ndarray) -> np.ndarray:
        """D [m] at ``times`` from ``readings`` ``(n, k)`` [K] of :attr:`sensors`, in order."""
        return self.bias + features(times, readings, self.lags) @ self.weights.ravel()

    def predict_record(self, record, names: list[str]) -> np.ndarray:
        """D [m] at every sample of a recorded cycle whose sensor columns are ``names``."""
        return self.predict(record.times, record.sensors[:, [names.index(s) for s in self.sensors]])


def fit_regression(cycles: list[tuple[np.ndarray, np.ndarray, np.ndarray]], sensors: tuple[str, ...],
                   lags: tuple[float, ...] = ()) -> RegressionLaw:
    """Least-squares weights over every sample of ``cycles``.

    Parameters
    ----------
    cycles : list of (times [s], readings (n, k) [K], D (n,) [m])
        One entry per cycle (the lags restart at each cycle's first sample).
    sensors : tuple of str
        Names of the readings' columns.
    lags : tuple of float
        Time constants [s] of the lagged regressors; empty for the static law.
    """
    if not cycles:
        raise FeedthermError("a regression needs at least one cycle")
    X = np.vstack([features(t, r, lags) for t, r, _ in cycles])
    y = np.concatenate([np.asarray(d, dtype=float) for _, _, d in cycles])
    if X.shape[1] != len(sensors) * (1 + len(lags)):
        raise FeedthermError(f"{X.shape[1]} regressors for {len(sensors)} sensors and {len(lags)} lags")
    mean_x, mean_y = X.mean(axis=0), y.mean()
    weights, *_ = np.linalg.lstsq(X - mean_x, y - mean_y, rcond=None)
    return RegressionLaw(tuple(sensors), tuple(float(t) for t in lags), weights.reshape(len(sensors), 1 + len(lags)),
                         float(mean_y - mean_x @ weights))
