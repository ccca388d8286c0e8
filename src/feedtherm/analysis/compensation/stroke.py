"""The error along the stroke: a law that predicts the positioning error E(x, t) at any table position.

A law of D (:mod:`.regression`) corrects the axis by the same -D everywhere; the screw's error
changes along the stroke (the nut reads the screw's displacement under it, and the screw is
warmest where the nut runs most).  The stroke law gives each regressor of the lagged (or static)
regression a few coefficients over a basis in the normalised table position:

.. math::

    \\xi = 2\\,\\frac{x - x_\\min}{x_\\max - x_\\min} - 1 \\in [-1, 1], \\qquad
    \\hat E(x, t) = \\sum_{m=0}^{q} P_m(\\xi)\\Big( b_m + \\sum_{f} w_{f,m}\\,\\varphi_f(t) \\Big)

with ``P_m`` the Legendre polynomials (orthogonal on [-1, 1], so the coefficients of a low order
do not change much when the order grows), ``φ_f`` the regression's features (each sensor's reading
then its lags, [K]), weights ``w`` [m/K] and biases ``b`` [m].  ``x_min``, ``x_max`` [m]: the first
and last table positions of the runs (the nut's centre along x, the frame of ``positioning_error.csv``).
``q = 0`` is a law of the stroke-mean error, the same for every x.

**Fit.** Jointly over the recorded positions x_j (:data:`.data.STROKE_POSITIONS`) and every sample
of the training cycles: one least-squares problem in all ``(k (1 + lags) + 1)(q + 1)`` coefficients,
whose rows are the samples × positions.  The biases are not penalised (their columns are projected
out first); the weights take the ridge of :mod:`.regression`, ``α`` [K²] per regressor.  The order
``q`` (from :data:`ORDERS`) and ``α`` (from :data:`~.regression.RIDGE_GRID_K`) are chosen on the
validation cycles' RMS over positions and time, never on the test cycles: each order at its best
ridge, then the lowest order whose RMS is within :data:`ORDER_TOLERANCE` of the best order's (a
higher order costs the controller ``k (1 + lags) + 1`` multiply-adds more per order; on the paper
bench orders 1-3 differ by about 1 % on validation).

**A controller's cost** per sample (:func:`controller_cost`): the lags, 2 multiply-adds each per
sensor (``L = a L + (1 - a) T``, ``a`` fixed for a fixed sample interval); the q + 1 coefficients,
``(q + 1) · k (1 + lags)`` multiply-adds (plus q + 1 additions of the biases); the basis at x by the
Legendre recurrence, about 3 multiply-adds per order above 1; the sum ``Σ P_m c_m``, q + 1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import legendre

from ...errors import FeedthermError
from .data import CycleRecord, CycleSet
from .metrics import Residuals, summarise
from .regression import RIDGE_GRID_K, features, ridge_weights

#: The basis orders tried on the validation cycles: constant, linear, quadratic, cubic in x.
ORDERS: tuple[int, ...] = (0, 1, 2, 3)
#: A higher order is taken only if it lowers the validation RMS by more than this fraction of the
#: best (or by more than :data:`ORDER_FLOOR_M`): a declared parsimony rule, not a fitted one.
ORDER_TOLERANCE = 0.02
#: Validation RMS differences below 1 nm are not told apart [m].
ORDER_FLOOR_M = 1e-9


def normalised(x, x_min: float, x_max: float) -> np.ndarray:
    """ξ = 2 (x - x_min) / (x_max - x_min) - 1 of table positions ``x`` [m] (module notes)."""
    return 2.0 * (np.asarray(x, dtype=float) - x_min) / (x_max - x_min) - 1.0


def basis(xi, order: int) -> np.ndarray:
    """Legendre polynomials P_0 … P_order at ``xi``: ``(len(xi), order + 1)``."""
    return legendre.legvander(np.atleast_1d(np.asarray(xi, dtype=float)), order)


def check_positions(x, x_min: float, x_max: float, field: str = "x") -> np.ndarray:
    """``x`` [m] as a 1-D array, each finite and within [x_min, x_max] (to 1 nm).

    Raises
    ------
    FeedthermError
        One line naming ``field``: a value that is not a number, not finite, or outside the stroke.
    """
    try:
        values = np.atleast_1d(np.asarray(x, dtype=float)).ravel()
    except (TypeError, ValueError):
        raise FeedthermError(f"{field}: {x!r} is not a table position in metres") from None
    bad = ~np.isfinite(values)
    if bad.any():
        raise FeedthermError(f"{field}: {values[bad][0]} is not a finite table position [m]")
    outside = (values < x_min - 1e-9) | (values > x_max + 1e-9)
    if outside.any():
        raise FeedthermError(f"{field}: {values[outside][0]:.6g} m is outside the stroke, "
                             f"[{x_min:.6g}, {x_max:.6g}] m")
    return values


def controller_cost(sensors: int, lags: int, order: int) -> dict:
    """Multiply-adds per sample of a stroke law on a controller (module notes), by step and in total."""
    q = order + 1
    lag_updates = 2 * sensors * lags
    coefficients = q * sensors * (1 + lags) + q
    basis_eval = 0 if order < 2 else 3 * (order - 1)  # P0 = 1, P1 = ξ (one multiply-add from x), then the recurrence
    basis_eval += 1 if order >= 1 else 0
    total_sum = q
    return {"lag_updates": lag_updates, "coefficients": coefficients, "basis": basis_eval, "sum": total_sum,
            "total": lag_updates + coefficients + basis_eval + total_sum,
            "how": "per sample: 2 per lag per sensor; (order + 1) x (sensors x (1 + lags) + 1) for the "
                   "coefficients with their biases; ξ from x and the Legendre recurrence; (order + 1) for "
                   "the sum over the basis"}


@dataclass(frozen=True)
class StrokeLaw:
    """A fitted stroke law (module notes): ``weights`` ``(k (1 + lags), order + 1)`` [m/K], ``bias``
    ``(order + 1,)`` [m], the stroke's ends ``x_min``, ``x_max`` [m], the ridge ``α`` [K²]."""

    sensors: tuple[str, ...]
    lags: tuple[float, ...]
    order: int
    weights: np.ndarray
    bias: np.ndarray
    x_min: float
    x_max: float
    ridge: float = 0.0

    def coefficients(self, times: np.ndarray, readings: np.ndarray) -> np.ndarray:
        """The basis coefficients c_m(t) [m] ``(n, order + 1)`` from ``readings`` ``(n, k)`` [K]."""
        return self.bias + features(times, readings, self.lags) @ self.weights

    def predict(self, times: np.ndarray, readings: np.ndarray, x) -> np.ndarray:
        """E [m] ``(n, len(x))`` at the table positions ``x`` [m] (checked: inside the stroke, finite)."""
        x = check_positions(x, self.x_min, self.x_max)
        return self.coefficients(times, readings) @ basis(normalised(x, self.x_min, self.x_max), self.order).T

    def predict_record(self, record: CycleRecord, names: list[str]) -> np.ndarray:
        """E [m] at every sample and recorded position of a cycle whose sensor columns are ``names``."""
        return self.predict(record.times, record.sensors[:, [names.index(s) for s in self.sensors]],
                            np.clip(record.positions, self.x_min, self.x_max))

    @property
    def cost(self) -> dict:
        return controller_cost(len(self.sensors), len(self.lags), self.order)


def stroke_range(cycles: CycleSet) -> tuple[float, float]:
    """The first and last recorded table positions [m] over every cycle of ``cycles``."""
    positions = [c.positions for c in cycles.cycles if c.positions is not None and len(c.positions)]
    if not positions or any(c.stroke_error is None for c in cycles.cycles):
        raise FeedthermError("the cycles carry no positioning error along a stroke (no table)")
    lo, hi = min(float(p.min()) for p in positions), max(float(p.max()) for p in positions)
    if not hi > lo:
        raise FeedthermError("the cycles' table positions span no stroke")
    return lo, hi


def _design(cycles: CycleSet, sensors: tuple[str, ...], lags, order: int, x_min: float, x_max: float):
    """``(X, Z, y)``: the weights' columns ``kron(features, P)``, the biases' ``kron(1, P)``, E [m];
    one row per sample and position.  With the set's reference temperature the features are taken
    from it (``T − T_ref``; :func:`_fit` then leaves the biases out)."""
    columns = [cycles.names.index(s) for s in sensors]
    origin = 0.0 if cycles.reference is None else cycles.reference
    X, Z, y = [], [], []
    for record in cycles.cycles:
        F = features(record.times, record.sensors[:, columns], lags) - origin
        B = basis(normalised(record.positions, x_min, x_max), order)
        X.append(np.kron(F, B))
        Z.append(np.kron(np.ones((len(F), 1)), B))
        y.append(np.asarray(record.stroke_error, dtype=float).ravel())
    return np.vstack(X), np.vstack(Z), np.concatenate(y)


def _fit(X: np.ndarray, Z: np.ndarray, y: np.ndarray, alphas, reference: float | None = None,
         order: int = 0) -> list[tuple[np.ndarray, np.ndarray]]:
    """``[(w, b), ...]`` per ``α``: through ``reference`` [K] (``X`` from it, no free biases: each
    ``b_m = −reference Σ_f w_fm``, so that a machine at the reference reads E = 0 at every x); else
    ridge on the weights with the biases' columns projected out, then the biases by least squares on
    what the weights leave."""
    if reference is not None:
        return [(w, -reference * w.reshape(-1, order + 1).sum(axis=0)) for w in ridge_weights(X, y, alphas)]
    Zp = np.linalg.pinv(Z)
    Xc, yc = X - Z @ (Zp @ X), y - Z @ (Zp @ y)
    return [(w, Zp @ (y - X @ w)) for w in ridge_weights(Xc, yc, alphas)]


def fit_stroke(train: CycleSet, sensors: tuple[str, ...], lags: tuple[float, ...] = (), order: int = 1,
               ridge: float = 0.0, stroke: tuple[float, float] | None = None) -> StrokeLaw:
    """The stroke law on the named sensors, fitted on ``train`` (module notes).

    Parameters
    ----------
    train : CycleSet
        Cycles whose records carry ``positions`` [m] and ``stroke_error`` [m].
    sensors : tuple of str
        Candidates (columns of ``train``) the law reads.
    lags : tuple of float
        Time constants [s] of the lagged regressors (:mod:`.regression`).
    order : int
        Highest Legendre order in x (0 … 3 usually).
    ridge : float
        The penalty ``α`` [K²] on the weights.
    stroke : (float, float), optional
        The stroke's ends [m]; default: the recorded positions' (:func:`stroke_range`).
    """
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 0:
        raise FeedthermError(f"order: {order!r} is not a whole number ≥ 0")
    unknown = [s for s in sensors if s not in train.names]
    if unknown:
        raise FeedthermError(f"--sensors: no candidate {unknown[0]!r}")
    x_min, x_max = stroke or stroke_range(train)
    X, Z, y = _design(train, tuple(sensors), lags, order, x_min, x_max)
    w, b = _fit(X, Z, y, [ridge], train.reference, order)[0]
    return StrokeLaw(tuple(sensors), tuple(float(t) for t in lags), int(order),
                     w.reshape(len(sensors) * (1 + len(lags)), order + 1), np.asarray(b, dtype=float),
                     float(x_min), float(x_max), float(ridge))


def stroke_conditioning(law: StrokeLaw, points: int = 101, offsets: dict[str, float] | None = None) -> dict:
    """A stroke law's conditioning (:mod:`.conditioning`): per sensor, the largest error [µm] over the
    stroke that its declared offset ``δ_s`` on that sensor alone causes once the lags settle,
    ``max_x |Σ_m P_m(ξ) Σ_f w_{s,f,m}| · δ_s`` on ``points`` positions (``offsets``: name -> δ [K],
    :func:`.conditioning.input_offsets`); the largest |weight| [µm/K] of a feature at any x,
    ``max_x |Σ_m P_m(ξ) w_{f,m}|``."""
    from .conditioning import LIMIT_UM, input_offsets

    B = basis(np.linspace(-1.0, 1.0, points), law.order)
    k, m = len(law.sensors), 1 + len(law.lags)
    along = law.weights @ B.T  # (features, points) [m/K]
    delta = input_offsets(law.sensors, offsets)
    steady = np.abs(along.reshape(k, m, points).sum(axis=1)).max(axis=1) * delta * 1e6
    worst = float(steady.max()) if steady.size else 0.0
    return {"max_abs_weight_um_per_K": float(np.abs(along).max() * 1e6) if along.size else 0.0,
            "offset_K": {s: float(v) for s, v in zip(law.sensors, delta)},
            "offset_error_um": {s: float(v) for s, v in zip(law.sensors, steady)},
            "max_offset_error_um": worst, "limit_um": LIMIT_UM, "within_limit": bool(worst <= LIMIT_UM),
            "ridge_K": math.sqrt(law.ridge),
            "how": "the largest over the stroke of |sum of a sensor's weights at x| x its kind's declared offset "
                   "(offset_K)"}


@dataclass(frozen=True)
class StrokeChoice:
    """The law chosen on validation and every (order, ridge [K]) tried with its validation RMS [m]."""

    law: StrokeLaw
    validation_rms: float
    tried: tuple[tuple[int, float, float], ...]  # order, √α [K], validation RMS [m]

    def as_dict(self) -> dict:
        best = {}
        for order, ridge_k, rms in self.tried:
            if order not in best or rms < best[order][1]:
                best[order] = (ridge_k, rms)
        return {"order": self.law.order, "ridge_K": math.sqrt(self.law.ridge),
                "validation_rms_um": self.validation_rms * 1e6,
                "validation_rms_um_by_order": {str(o): {"ridge_K": r, "rms_um": v * 1e6} for o, (r, v) in best.items()},
                "chosen_on": f"validation cycles, RMS over positions and time: the lowest order within "
                             f"{100 * ORDER_TOLERANCE:.0f} % of the best order's RMS, each order at its best ridge"}


def fit_stroke_validated(train: CycleSet, validation: CycleSet, sensors: tuple[str, ...], lags: tuple[float, ...] = (),
                         orders: tuple[int, ...] = ORDERS, ridge_grid: tuple[float, ...] = RIDGE_GRID_K) -> StrokeChoice:
    """The stroke law on ``sensors`` whose order and ridge give the smallest validation RMS over
    positions and time; the law is refitted on ``train`` at that order and ridge."""
    x_min, x_max = stroke_range(train)
    alphas = [float(g) ** 2 for g in ridge_grid]
    truth = np.concatenate([np.asarray(r.stroke_error, float).ravel() for r in validation.cycles])
    tried, best = [], {}
    for order in orders:
        X, Z, y = _design(train, tuple(sensors), lags, order, x_min, x_max)
        for alpha, (w, b) in zip(alphas, _fit(X, Z, y, alphas, train.reference, order)):
            law = StrokeLaw(tuple(sensors), tuple(lags), order, w.reshape(-1, order + 1), b, x_min, x_max, alpha)
            pred = np.concatenate([law.predict_record(r, validation.names).ravel() for r in validation.cycles])
            rms = float(np.sqrt(np.mean((truth - pred) ** 2)))
            tried.append((order, math.sqrt(alpha), rms))
            if order not in best or rms < best[order][1]:
                best[order] = (law, rms)
    smallest = min(rms for _, rms in best.values())
    order = min(o for o, (_, rms) in best.items() if rms <= smallest * (1.0 + ORDER_TOLERANCE) + ORDER_FLOOR_M)
    return StrokeChoice(best[order][0], best[order][1], tuple(tried))


def stroke_residuals(predict, cycles: CycleSet) -> Residuals:
    """The residuals ``E(x_j, t) - predict(record)`` over every sample and recorded position of
    ``cycles`` (``predict``: record -> ``(n, p)`` [m], or ``(n,)`` for a law of D applied at every x);
    without compensation the error is E itself."""
    return summarise((record.label, record.stroke_error, np.asarray(predict(record), dtype=float))
                     for record in cycles.cycles)
