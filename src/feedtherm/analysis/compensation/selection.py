"""Sensor placement: greedy forward selection of K sensors on held-out error.

Starting from no sensor, each step adds the candidate whose law, refitted on the training
cycles, gives the smallest RMS residual on the *validation* cycles (machine variants the law
was not fitted on); the sets for K = 1, 2, ... are nested.  The figures a study reports come
from a third set of cycles (:mod:`.data`), so the choice itself is not judged on the data it
was made on.

Why greedy forward selection on held-out error rather than an information criterion (D-optimal
design on the model's sensitivities): the question is which sensors make the *law* accurate on
another machine, and the held-out residual measures exactly that, including the model mismatch
of the variants; a D-optimal criterion measures how well the sensors identify the nominal
model's states and says nothing of the law's error under mismatch.  Greedy selection is the
usual approach of thermal-error studies (Mayr et al. 2012, §4.1 [1]_); it is not guaranteed to
find the best set of K, and the report shows the error against K so its steps can be judged.

Every trial set is judged at its best ridge strength (:mod:`.regression`, :data:`RIDGE_GRID_K`),
chosen on the same validation cycles, and on the sensors' noisy readings (:mod:`.noise`): a pair of
nearly collinear sensors that fits the noise-free training cycles exactly by the difference of two
large weights is judged with the noise and offsets that difference amplifies, or with the bias the
ridge puts in its place, so the selection prefers a well-conditioned set.

References
----------
.. [1] J. Mayr et al., "Thermal issues in machine tools", CIRP Annals 61(2), 771-791 (2012).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...errors import FeedthermError
from .data import CycleSet
from .regression import RIDGE_GRID_K, RegressionLaw, features, fit_regression, solve_weights


@dataclass(frozen=True)
class SelectionStep:
    """The sensors chosen for K = len(sensors), the law fitted on them (at the ridge chosen) and its validation RMS [m]."""

    sensors: tuple[str, ...]
    law: RegressionLaw
    validation_rms: float


def _feature_cube(cycles: CycleSet, lags: tuple[float, ...]) -> list[np.ndarray]:
    """Per cycle, the regressors of every candidate: ``(n, candidates, 1 + len(lags))``."""
    m = 1 + len(lags)
    return [features(c.times, c.sensors, lags).reshape(len(c.times), len(cycles.names), m) for c in cycles.cycles]


def _fit(cube: list[np.ndarray], targets: list[np.ndarray], chosen: list[int], alphas, reference: float | None):
    """``[(weights, bias), ...]``, one per ridge ``α`` [K²] of ``alphas`` (through ``reference`` [K], :mod:`.regression`)."""
    X = np.vstack([f[:, chosen, :].reshape(len(f), -1) for f in cube])
    return solve_weights(X, np.concatenate(targets), alphas, reference)


def _best_ridge(train_cube, train_y, val_cube, val_all, trial, alphas, reference=None) -> tuple[float, float]:
    """(validation RMS [m], α [K²]) of the ridge strength of ``alphas`` with the smallest validation RMS."""
    best = None
    regressors = [f[:, trial, :].reshape(len(f), -1) for f in val_cube]  # the trial's, once for every α
    for alpha, (w, b) in zip(alphas, _fit(train_cube, train_y, trial, alphas, reference)):
        pred = np.concatenate([X @ w + b for X in regressors])
        rms = float(np.sqrt(np.mean((val_all - pred) ** 2)))
        if best is None or rms < best[0]:
            best = (rms, float(alpha))
    return best


def greedy_selection(train: CycleSet, validation: CycleSet, max_sensors: int, lags: tuple[float, ...] = (),
                     allowed: list[str] | None = None, start: tuple[str, ...] = (),
                     ridge_grid: tuple[float, ...] = RIDGE_GRID_K) -> list[SelectionStep]:
    """Nested sensor sets for K = 1 … ``max_sensors`` (see the module's notes).

    Parameters
    ----------
    train, validation : CycleSet
        The same candidates (columns) in both.
    max_sensors : int
    lags : tuple of float
        The lags of every law (:mod:`.regression`).
    allowed : list of str, optional
        Candidates to choose from (default: all).
    start : tuple of str
        Sensors every set contains (counted in K).
    ridge_grid : tuple of float
        Ridge strengths tried, as the equivalent reading noise ``√α`` [K] (:mod:`.regression`);
        ``(0.0,)``: ordinary least squares.
    """
    names = train.names
    if validation.names != names:
        raise FeedthermError("the training and validation sets have different candidates")
    pool = list(names if allowed is None else allowed)
    if not 1 <= max_sensors <= len(pool):
        raise FeedthermError(f"--sensors: K = {max_sensors} but there are {len(pool)} candidates")
    train_cube, val_cube = _feature_cube(train, lags), _feature_cube(validation, lags)
    train_y = [c.elongation for c in train.cycles]
    val_y = [c.elongation for c in validation.cycles]
    val_all = np.concatenate(val_y)
    alphas = [float(g) ** 2 for g in ridge_grid]
    chosen = [names.index(s) for s in start]
    steps = []
    while len(chosen) < max_sensors:
        best = None
        for name in pool:
            j = names.index(name)
            if j in chosen:
                continue
            rms, alpha = _best_ridge(train_cube, train_y, val_cube, val_all, [*chosen, j], alphas, train.reference)
            if best is None or rms < best[0]:
                best = (rms, j, alpha)
        chosen.append(best[1])
        sensors = tuple(names[j] for j in chosen)
        steps.append(SelectionStep(sensors, fit_on(train, sensors, lags, best[2]), best[0]))
    return steps


def fit_on(train: CycleSet, sensors: tuple[str, ...], lags: tuple[float, ...] = (), ridge: float = 0.0) -> RegressionLaw:
    """The regression law on the named sensors, fitted on ``train`` with the ridge ``α`` [K²]."""
    unknown = [s for s in sensors if s not in train.names]
    if unknown:
        raise FeedthermError(f"--sensors: no candidate {unknown[0]!r}")
    columns = [train.names.index(s) for s in sensors]
    return fit_regression([(c.times, c.sensors[:, columns], c.elongation) for c in train.cycles], tuple(sensors), lags,
                          ridge, train.reference)


def fit_validated(train: CycleSet, validation: CycleSet, sensors: tuple[str, ...], lags: tuple[float, ...] = (),
                  ridge_grid: tuple[float, ...] = RIDGE_GRID_K) -> RegressionLaw:
    """The law on the named sensors, its ridge chosen on ``validation`` from ``ridge_grid`` [K]."""
    unknown = [s for s in sensors if s not in train.names]
    if unknown:
        raise FeedthermError(f"--sensors: no candidate {unknown[0]!r}")
    trial = [train.names.index(s) for s in sensors]
    alphas = [float(g) ** 2 for g in ridge_grid]
    _, alpha = _best_ridge(_feature_cube(train, lags), [c.elongation for c in train.cycles],
                           _feature_cube(validation, lags), np.concatenate([c.elongation for c in validation.cycles]),
                           trial, alphas, train.reference)
    return fit_on(train, sensors, lags, alpha)


def predictor(law: RegressionLaw, names: list[str]):
    """``record -> D̂`` of ``law`` for cycles whose columns are ``names``."""
    columns = [names.index(s) for s in law.sensors]
    return lambda record: law.predict(record.times, record.sensors[:, columns])
