"""Calibration: fit declared parameters to measured conditions, then predict the others.

The parameters, their kinds and bounds are declared in the description's ``[calibration]``
section.  The fit is bounded nonlinear least squares (scipy ``least_squares``, trust region
reflective) on residuals ``(simulated - measured) / sigma`` of the final values of the fitted
conditions, with ``sigma`` the declared temperature and elongation weights.  Each model
evaluation is a full transient run of the fast model with the cycle-averaged motion.

What a calibration is worth is how it predicts conditions it was not fitted to: the result
carries a held-out table, and :func:`cross_validate` leaves each condition out in turn.
"""

from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from scipy.optimize import least_squares

from ..errors import FeedthermError
from ..simulate import simulate
from ..system.load import LoadedSystem
from ..system.quantities import to_base_si
from ..system.references import closest
from ..system.variants import get_path, with_values
from .measurements import MeasurementSet
from .validation_types import ELONGATION_QUANTITY

#: Condition number of the Jacobian above which the fit cannot separate the parameters.
SINGULAR_CONDITION_NUMBER = 1e8


@dataclass(frozen=True)
class FitParameter:
    name: str
    kind: str  # "value" or "scale"
    paths: list[str]  # concrete paths (wildcards expanded)
    originals: list[float]  # SI values at the paths before the fit
    lower: float
    upper: float

    @property
    def start(self) -> float:
        x0 = self.originals[0] if self.kind == "value" else 1.0
        return float(min(max(x0, self.lower), self.upper))

    def values(self, x: float) -> dict[str, float]:
        """The description values this parameter sets when it equals ``x``."""
        if self.kind == "value":
            return {p: x for p in self.paths}
        return {p: o * x for p, o in zip(self.paths, self.originals)}


@dataclass(frozen=True)
class Prediction:
    condition: str
    quantity: str
    unit: str
    predicted: float
    measured: float

    @property
    def deviation(self) -> float:
        return self.predicted - self.measured


@dataclass
class CalibrationResult:
    parameters: list[FitParameter]
    fitted: np.ndarray
    standard_errors: np.ndarray
    correlation: np.ndarray
    identifiable: list[str]  # "" when identifiable, else the reason
    at_bound: list[str]  # "lower", "upper" or "" per parameter: the data push past the declared range
    fit_conditions: list[str]
    residuals: list[Prediction]  # at the fitted conditions, after the fit
    held_out: list[Prediction]
    cost: float
    model_runs: int
    wall_time_s: float
    measurement_source: str
    calibrated: LoadedSystem
    status: str = ""
    extra: dict = field(default_factory=dict)


# ---------------------------------------------------------------------------- parameters


def expand(loaded: LoadedSystem, path: str) -> list[str]:
    """Concrete paths for a path with ``[*]`` wildcards."""
    if "[*]" not in path:
        return [path]
    head, tail = path.split("[*]", 1)
    items = get_path(loaded.system, head)
    return [p for i in range(len(items)) for p in expand(loaded, f"{head}[{i}]{tail}")]


def resolve_parameters(loaded: LoadedSystem, names: list[str]) -> list[FitParameter]:
    """The declared parameters ``names``; one-line errors for anything undeclared."""
    declared = loaded.system.calibration.parameters if loaded.system.calibration else {}
    out = []
    for name in names:
        if name not in declared:
            if re.search(r"[.\[]", name):
                raise FeedthermError(f"--params: {name!r} has no declared bounds; declare it under "
                                     f"[calibration.parameters] with kind, paths and bounds")
            known = ", ".join(declared) or "none declared"
            raise FeedthermError(f"--params: unknown parameter {name!r}{closest(name, declared)} (declared: {known})")
        spec = declared[name]
        paths = [p for path in spec.paths for p in expand(loaded, path)]
        try:
            originals = [float(get_path(loaded.system, p)) for p in paths]
        except (KeyError, IndexError, AttributeError, TypeError):
            raise FeedthermError(f"calibration.parameters.{name}.paths: a path does not name a value") from None
        try:
            lower, upper = (to_base_si(b) for b in spec.bounds)
        except ValueError as exc:
            raise FeedthermError(f"calibration.parameters.{name}.bounds: {exc}") from None
        if not lower < upper:
            raise FeedthermError(f"calibration.parameters.{name}.bounds: the lower bound must be below the upper")
        out.append(FitParameter(name, spec.kind, paths, originals, lower, upper))
    if not out:
        raise FeedthermError("--params: name at least one parameter")
    return out


def apply(loaded: LoadedSystem, parameters: list[FitParameter], x) -> LoadedSystem:
    changes: dict[str, float] = {}
    for p, value in zip(parameters, x):
        changes.update(p.values(float(value)))
    return with_values(loaded, changes, origin_suffix="calibrated")


# ---------------------------------------------------------------------------- model


class _Model:
    """Final values of conditions for parameter vectors, counting the runs."""

    def __init__(self, loaded: LoadedSystem, parameters: list[FitParameter], mode: str):
        self.loaded, self.parameters, self.mode = loaded, parameters, mode
        self.runs = 0

    def finals(self, x, conditions: list[str]) -> dict[str, dict[str, float]]:
        variant = apply(self.loaded, self.parameters, x)
        out = {}
        for condition in conditions:
            run = simulate(variant, condition=condition, mode=self.mode, motion="averaged")
            self.runs += 1
            out[condition] = {k: float(v) for k, v in run.summary_values("final").items()}
        return out


def _predictions(finals, data: MeasurementSet, conditions: list[str]) -> list[Prediction]:
    return [Prediction(r.condition, r.quantity, r.unit, finals[r.condition][r.quantity], r.measured)
            for c in conditions for r in data.for_condition(c)]


def _sigma(loaded: LoadedSystem, unit: str) -> float:
    cal = loaded.system.calibration
    if unit == "um":
        return (cal.elongation_sigma if cal else 2e-6) * 1e6
    return cal.temperature_sigma if cal else 0.5


# ---------------------------------------------------------------------------- fit


def calibrate(loaded: LoadedSystem, data: MeasurementSet, fit: list[str], names: list[str], *,
              mode: str = "physics", progress: Callable[[float], None] | None = None) -> CalibrationResult:
    """Fit the parameters ``names`` to the conditions ``fit``; predict every other condition."""
    started = time.perf_counter()
    measured = data.conditions()
    missing = [c for c in fit if c not in measured]
    if missing:
        raise FeedthermError(f"--fit: no measurements for {', '.join(missing)} in {data.source} (measured: {', '.join(measured)})")
    unknown = [c for c in fit if c not in loaded.system.conditions]
    if unknown:
        raise FeedthermError(f"--fit: no condition {', '.join(unknown)} in {loaded.origin}")
    parameters = resolve_parameters(loaded, names)
    rows = [r for c in fit for r in data.for_condition(c)]
    if len(rows) < len(parameters):
        raise FeedthermError(f"--fit: {len(rows)} measured values cannot determine {len(parameters)} parameters")
    model = _Model(loaded, parameters, mode)
    sigma = np.array([_sigma(loaded, r.unit) for r in rows])
    target = np.array([r.measured for r in rows])
    lower = np.array([p.lower for p in parameters])
    upper = np.array([p.upper for p in parameters])
    span = upper - lower

    def residuals(u):  # u: parameters scaled to [0, 1] within their bounds
        finals = model.finals(lower + u * span, fit)
        if progress is not None:
            progress(min(0.95, model.runs / (len(fit) * (len(parameters) + 1) * 8)))
        return (np.array([finals[r.condition][r.quantity] for r in rows]) - target) / sigma

    u0 = (np.array([p.start for p in parameters]) - lower) / span
    result = least_squares(residuals, u0, bounds=(0.0, 1.0), diff_step=1e-3, x_scale=1.0, xtol=1e-6, ftol=1e-8)
    x = lower + result.x * span
    se, corr, identifiable = _uncertainty(result.jac / span[None, :], result.fun, x, len(rows))
    at_bound = ["lower" if u <= 1e-6 else "upper" if u >= 1 - 1e-6 else "" for u in result.x]
    finals = model.finals(x, measured)
    held_out = [c for c in measured if c not in fit and c in loaded.system.conditions]
    calibrated = apply(loaded, parameters, x)
    if progress is not None:
        progress(1.0)
    return CalibrationResult(
        parameters=parameters, fitted=x, standard_errors=se, correlation=corr, identifiable=identifiable,
        at_bound=at_bound,
        fit_conditions=list(fit), residuals=_predictions(finals, data, fit), held_out=_predictions(finals, data, held_out),
        cost=float(result.cost), model_runs=model.runs, wall_time_s=time.perf_counter() - started,
        measurement_source=data.source, calibrated=calibrated, status=result.message,
    )


def _uncertainty(jac: np.ndarray, fun: np.ndarray, x: np.ndarray, m: int):
    """Standard errors, correlation and identifiability from the Jacobian at the optimum.

    cov = s² (JᵀJ)⁻¹ with s² = Σr² / (m − n), the residual variance of the weighted fit
    (1 when there are no degrees of freedom left).
    """
    n = len(x)
    dof = m - n
    s2 = float(fun @ fun) / dof if dof > 0 else 1.0
    singular = np.linalg.svd(jac, compute_uv=False)
    cond = singular[0] / singular[-1] if singular[-1] > 0 else math.inf
    cov = s2 * np.linalg.pinv(jac.T @ jac)
    se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(se, se)
    corr = np.nan_to_num(corr)
    reasons = []
    for i in range(n):
        if cond > SINGULAR_CONDITION_NUMBER or not np.isfinite(cond):
            reasons.append(f"not identifiable: near-singular Jacobian (condition number {cond:.2g})")
        elif se[i] > abs(x[i]):
            reasons.append("not identifiable: standard error larger than the value")
        elif singular[-1] == 0 or np.all(jac[:, i] == 0):
            reasons.append("not identifiable: the measurements do not depend on it")
        else:
            reasons.append("")
    return se, corr, reasons


def cross_validate(loaded: LoadedSystem, data: MeasurementSet, names: list[str], *, mode: str = "physics",
                   progress: Callable[[float], None] | None = None) -> list[tuple[str, CalibrationResult]]:
    """Leave each measured condition out in turn: fit on the rest, predict the one left out."""
    conditions = [c for c in data.conditions() if c in loaded.system.conditions]
    out = []
    for i, left_out in enumerate(conditions):
        fit = [c for c in conditions if c != left_out]
        out.append((left_out, calibrate(loaded, data, fit, names, mode=mode)))
        if progress is not None:
            progress((i + 1) / len(conditions))
    return out


__all__ = ["calibrate", "cross_validate", "resolve_parameters", "CalibrationResult", "Prediction", "ELONGATION_QUANTITY"]
