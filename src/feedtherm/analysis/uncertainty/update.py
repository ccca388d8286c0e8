"""A Bayesian update of every declared uncertainty with measured final values (Laplace approximation).

The declared priors are the prior; the measured final values of the sensors and D at chosen
conditions are the data.  The update works in standard-normal coordinates, one per declared
parameter,

    x_i = F_i⁻¹(Φ(z_i)),

with F_i⁻¹ the parameter's inverse CDF (:func:`.sampling.ppf`) and Φ the standard normal CDF.
The prior is then exactly z ~ N(0, I), whatever each declared distribution is, and every z maps
inside every prior's support (a bounded prior needs no clipping).

Likelihood: the weighted residuals r(z) = (y(x(z)) − y_measured) / σ of the measured finals,
σ the description's calibration weights (:func:`..calibration._sigma`, the weights
``feedtherm calibrate`` uses), with noise scale s²: r ~ N(0, s² I).  The posterior mode (MAP)
minimises

    ‖r(z)‖² / s² + ‖z‖²,

found by :func:`scipy.optimize.least_squares` on the stacked vector [r/s; z] (the prior as d
pseudo-observations).  Around the mode the model is linearised, r(z) ≈ r(z*) + J (z − z*)
(Laplace's approximation; exact for a linear model and normal priors), so the posterior is

    z ~ N(z*, Σ),   Σ = (JᵀJ / s² + I)⁻¹.

Since JᵀJ/s² is positive semi-definite, Σ ≤ I in the Loewner order: in no direction is the
posterior wider than the prior.  Posterior samples are z = z* + L Φ⁻¹(u) with L Lᵀ = Σ
(Cholesky) and u the study's scrambled Sobol' points, mapped back by x = F⁻¹(Φ(z)).

Noise scale.  The weights σ describe the measurement alone; the model's structural misfit
(a sensor a few K off at every condition) is not measurement noise, and a posterior that
treated it as information would be over-confident.  As the calibration scales its covariance
by the residual variance s² = Σr² / (m − n) (:func:`..calibration._uncertainty`), the update
takes s² = max(1, ‖r(z*)‖² / (m − p_eff)), where p_eff = tr H, H = J (JᵀJ + s² I)⁻¹ Jᵀ, is the
effective number of parameters the data determine (the prior pins the rest; MacKay 1992,
"Bayesian interpolation", Neural Computation 4:415–447, Eq. 4.6 ff.; Gelman et al., *Bayesian
Data Analysis*, 3rd ed. 2013, §7.2, p_eff of a ridge/hierarchical regression).  s² never drops
below 1: the weights are the floor of the measurement's own uncertainty.  s² and the MAP are
iterated to a fixed point (:data:`MAX_PASSES`, :data:`S2_RTOL`).

The core (:func:`laplace_update`) takes any function from a batch of z to residual vectors, so
a linear toy checks it against the conjugate Gaussian formulas; :func:`bayesian_update` builds
that function from the description: one batch of runs per call, through the execution layer.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from scipy.special import ndtr, ndtri

from ...errors import FeedthermError
from ...models.registry import model_entry
from ...simulate import prepare
from ...system.load import LoadedSystem
from ..calibration import FTOL, XTOL, _data, _sigma
from ..consistency import ConsistencyReport
from ..execution import Execution, TaskFailure, kept_open, run_ordered
from ...system.measurements import MeasurementSet
from .declared import resolve_uncertainties, variant
from .runs import SampleRun, run_sample
from .sampling import ppf
from .types import BAND, UncertainParameter

#: Forward-difference step of the Jacobian in z (prior standard deviations).  At the prior's
#: centre a step of 0.05 moves a parameter's probability by φ(0)·0.05 ≈ 2 % of its prior mass
#: (2 % of the range of a uniform prior), the order of the calibration's step (1 % of the
#: bound span, ``calibration.SENSITIVITY_STEP``): small against the prior width the posterior
#: is resolved on, yet large enough that the fast model's 60 s steps do not dominate the
#: difference quotient.
JACOBIAN_STEP = 0.05
#: At most this many rounds of (MAP at s², new s²) — the fixed point of the noise scale.
MAX_PASSES = 4
#: The fixed point is reached when s² changes by less than this fraction: the posterior
#: standard deviations then move by under half of it (2.5 %), below what the 5–95 % quantiles
#: of a few hundred sampled runs resolve.
S2_RTOL = 0.05

#: A batch of points z (k, d) -> their weighted residual vectors (k, m).
ResidualBatch = Callable[[np.ndarray], np.ndarray]


@dataclass
class LaplaceFit:
    """The linearised posterior in standard-normal coordinates."""

    z: np.ndarray  # (d,) the posterior mode
    covariance: np.ndarray  # (d, d) Σ = (JᵀJ/s² + I)⁻¹
    jacobian: np.ndarray  # (m, d) of r at the mode
    residuals: np.ndarray  # (m,) r(z*) (weighted, not divided by s)
    s2: float  # the noise scale the mode and Σ use
    p_eff: float  # tr H at the mode and s²
    passes: int  # rounds of the s² fixed point
    converged: bool  # s² changed by under S2_RTOL in the last pass
    evaluations: int  # points z evaluated (each runs every fit condition)
    jacobians: int
    status: str  # the last least-squares message

    @property
    def sd(self) -> np.ndarray:
        """Posterior standard deviation of each z (≤ 1: never wider than the prior)."""
        return np.sqrt(np.clip(np.diag(self.covariance), 0.0, None))

    def z_points(self, u: np.ndarray) -> np.ndarray:
        """Posterior points z = z* + L Φ⁻¹(u), L Lᵀ = Σ (Cholesky), for ``u`` (n, d) in (0, 1)."""
        from .sampling import EDGE

        normal = ndtri(np.clip(np.atleast_2d(np.asarray(u, dtype=float)), EDGE, 1.0 - EDGE))
        return self.z[None, :] + normal @ np.linalg.cholesky(self.covariance).T


def effective_parameters(jacobian: np.ndarray, s2: float) -> float:
    """p_eff = tr(J (JᵀJ + s² I)⁻¹ Jᵀ) = Σ λ_k / (λ_k + s²) over the eigenvalues λ_k of JᵀJ."""
    eigen = np.linalg.eigvalsh(jacobian.T @ jacobian)
    return float(np.sum(np.clip(eigen, 0.0, None) / (np.clip(eigen, 0.0, None) + s2)))


def noise_scale(residuals: np.ndarray, p_eff: float) -> float:
    """s² = max(1, ‖r‖² / (m − p_eff)); 1 when no degrees of freedom are left (as calibration)."""
    dof = len(residuals) - p_eff
    return max(1.0, float(residuals @ residuals) / dof) if dof > 0 else 1.0


def laplace_update(residuals: ResidualBatch, d: int, *, s2: float | None = None, step: float = JACOBIAN_STEP,
                   max_passes: int = MAX_PASSES, max_nfev: int | None = None) -> LaplaceFit:
    """The Laplace posterior of z ~ N(0, I) given residuals r(z) ~ N(0, s² I).

    ``residuals``: a batch of points (k, d) to their residual vectors (k, m); every Jacobian is
    one batch of (up to) d + 1 points (forward differences of ``step`` in z).  ``s2``: a fixed
    noise scale; None: the fixed point of :func:`noise_scale`.  ``max_nfev``: caps each
    least-squares pass (a small test; None: scipy's default).
    """
    cache: dict[bytes, np.ndarray] = {}
    counts = {"evaluations": 0, "jacobians": 0}

    def evaluate(points: np.ndarray) -> list[np.ndarray]:
        points = np.atleast_2d(np.asarray(points, dtype=float))
        todo = [p for p in points if p.tobytes() not in cache]
        if todo:
            found = np.atleast_2d(np.asarray(residuals(np.array(todo)), dtype=float))
            counts["evaluations"] += len(todo)
            for p, r in zip(todo, found):
                cache[p.tobytes()] = r
        return [cache[p.tobytes()] for p in points]

    def jac_r(z: np.ndarray) -> np.ndarray:
        counts["jacobians"] += 1
        points = np.vstack([z, z + step * np.eye(d)])  # one batch: the point and its d neighbours
        base, *moved = evaluate(points)
        return np.column_stack([(m - base) / step for m in moved])

    from scipy.optimize import least_squares  # 0.1 s to import: only where an update fits

    z = np.zeros(d)
    scale = 1.0 if s2 is None else float(s2)
    passes, converged, status = 0, s2 is not None, ""
    while True:
        passes += 1
        root = np.sqrt(scale)
        result = least_squares(lambda v: np.concatenate([evaluate(v[None, :])[0] / root, v]), z,
                               jac=lambda v: np.vstack([jac_r(v) / root, np.eye(d)]), method="trf",
                               xtol=XTOL, ftol=FTOL, max_nfev=max_nfev)
        z, status = result.x, result.message
        jacobian = jac_r(z)
        r = evaluate(z[None, :])[0]
        if s2 is not None:
            break
        updated = noise_scale(r, effective_parameters(jacobian, scale))
        converged = abs(updated - scale) <= S2_RTOL * scale
        if converged or passes >= max_passes:
            break
        scale = updated
    covariance = np.linalg.inv(jacobian.T @ jacobian / scale + np.eye(d))
    covariance = 0.5 * (covariance + covariance.T)  # exactly symmetric for the Cholesky factor
    return LaplaceFit(z=z, covariance=covariance, jacobian=jacobian, residuals=r, s2=scale,
                      p_eff=effective_parameters(jacobian, scale), passes=passes, converged=converged,
                      evaluations=counts["evaluations"], jacobians=counts["jacobians"], status=status)


# ------------------------------------------------------------------------------ on a description


def to_x(parameters: list[UncertainParameter], z: np.ndarray) -> np.ndarray:
    """x_i = F_i⁻¹(Φ(z_i)) for points z (n, d) [SI or factors]."""
    z = np.atleast_2d(np.asarray(z, dtype=float))
    u = ndtr(z)  # Φ (scipy.stats.norm.cdf is this function)
    return np.column_stack([ppf(p, u[:, i]) for i, p in enumerate(parameters)])


@dataclass(frozen=True)
class _Row:
    condition: str
    quantity: str
    unit: str
    measured: float
    sigma: float


@dataclass
class _ModelResiduals:
    """The weighted residuals of the fit rows for a batch of z: one batch of runs per call."""

    loaded: LoadedSystem
    prior: list[UncertainParameter]
    rows: list[_Row]
    conditions: tuple[str, ...]
    execution: Execution
    runs: int = 0
    model: str = "fast"  # the model of the registry every run takes
    mesh: str | None = None  # its FE mesh (None: the options' own)

    def __call__(self, z: np.ndarray) -> np.ndarray:
        x = to_x(self.prior, z)
        items = [SampleRun(variant(self.loaded, self.prior, xi, f"update point {self.runs + k}"), self.conditions,
                           f"update point {self.runs + k}",
                           tuple((p.name, float(v)) for p, v in zip(self.prior, xi)), self.model, self.mesh)
                 for k, xi in enumerate(x)]
        self.runs += len(items)
        out, failures = [], []
        for _, result in run_ordered(run_sample, items, execution=self.execution, describe=SampleRun.describe):
            if isinstance(result, TaskFailure):
                failures.append(result)
            else:
                out.append([(result.finals[r.condition][r.quantity] - r.measured) / r.sigma for r in self.rows])
        if failures:
            raise FeedthermError(f"--update-with: {len(failures)} of {len(items)} runs of the update failed; "
                                 f"the first: {failures[0]}")
        return np.array(out)


@dataclass
class BayesianUpdate:
    """The declared priors updated with the measured finals of ``fit_conditions``."""

    loaded: LoadedSystem  # the description the sampled values apply to (the original)
    nominal: LoadedSystem  # the description at the posterior mode
    prior: list[UncertainParameter]
    parameters: list[UncertainParameter]  # for the record: MAP as declared, the 5–95 % range as low/high
    fit: LaplaceFit
    x_map: np.ndarray
    fit_conditions: list[str]
    rows: list[_Row]
    excluded: list[dict]
    conditions_runs: int  # model runs (points × fit conditions)
    summary: dict = field(default_factory=dict)
    model: str = "fast"  # the model of the registry the update's runs took
    mesh: str | None = None  # its FE mesh (None: the options' own)

    def values(self, u: np.ndarray) -> np.ndarray:
        """The posterior's parameter values (n, d) at the unit points ``u`` (n, d)."""
        return to_x(self.prior, self.fit.z_points(u))

    def model_error(self) -> dict[str, float]:
        """Quantity -> the standard deviation s·σ of the model error N(0, s²σ²) the update
        assumed for its measured values [°C or µm] (the fitted quantities only)."""
        return {r.quantity: float(np.sqrt(self.fit.s2) * r.sigma) for r in self.rows}


def bayesian_update(loaded: LoadedSystem, data: MeasurementSet, fit_conditions: list[str], *,
                    consistency: ConsistencyReport | None = None,
                    execution: Execution = Execution(), s2: float | None = None,
                    max_nfev: int | None = None, model: str = "fast", mesh: str | None = None) -> BayesianUpdate:
    """Update every declared uncertainty of ``loaded`` with the measured finals of ``fit_conditions``.

    The data: the sensors' and D_um finals (whatever ``data`` measures at those conditions) but the
    values ``consistency`` flags, as calibration leaves them out (:func:`..calibration._data`,
    without the equilibrium times, which the fast runs of a study do not give).  The runs:
    ``model`` (a model of the registry, default the fast one; ``mesh`` its FE mesh) with the
    cycle-averaged motion in 60 s steps (:func:`.runs.run_sample`), each Jacobian one batch
    through ``execution``.  Raises :class:`FeedthermError` (one line) for an unknown condition
    or model, or a condition without measurements.
    """
    started = time.perf_counter()
    model_entry(model)  # an unknown model fails before any run
    prepare(loaded.system, model, mesh)
    prior = resolve_uncertainties(loaded)
    unknown = [c for c in fit_conditions if c not in loaded.system.conditions]
    if unknown:
        raise FeedthermError(f"--update-with: no condition {unknown[0]!r} in {loaded.origin}; conditions: "
                             f"{', '.join(loaded.system.conditions)}")
    measured = data.conditions()
    missing = [c for c in fit_conditions if c not in measured]
    if missing:
        raise FeedthermError(f"--update-with: no measurements for {', '.join(missing)} in {data.source} "
                             f"(measured: {', '.join(measured)})")
    every = _data(data, list(fit_conditions), consistency, equilibrium=False)
    rows = [_Row(r.condition, r.quantity, r.unit, r.measured, _sigma(loaded, r.unit)) for r in every if not r.flag]
    excluded = [{"condition": r.condition, "quantity": r.quantity, "measured": r.measured, "reason": r.flag}
                for r in every if r.flag]
    with kept_open(execution) as where:  # one cluster for every Jacobian
        residuals = _ModelResiduals(loaded, prior, rows, tuple(fit_conditions), where, model=model, mesh=mesh)
        fit = laplace_update(residuals, len(prior), s2=s2, max_nfev=max_nfev)
    x_map = to_x(prior, fit.z)[0]
    k = ndtri(BAND[1])  # the band's quantile in z: a one-dimensional normal's 5–95 % range
    low = to_x(prior, fit.z - k * fit.sd)[0]
    high = to_x(prior, fit.z + k * fit.sd)[0]
    on = ", ".join(fit_conditions)
    parameters = [UncertainParameter(
        name=p.name, description=p.description, kind=p.kind, paths=p.paths, declared=float(x_map[i]),
        distribution=f"posterior (Bayesian update on {on})", low=float(low[i]), high=float(high[i]), sigma=None,
        unit=p.unit,
        reason=(f"prior: {_prior_text(p)}; updated with the measured finals of {on}: posterior mode "
                f"{x_map[i]:.4g}, {round(100 * BAND[0])}–{round(100 * BAND[1])} % {low[i]:.4g} … {high[i]:.4g}, "
                f"posterior sd {fit.sd[i]:.2f} of the prior's in standard-normal coordinates"),
        provenance=p.provenance) for i, p in enumerate(prior)]
    nominal = variant(loaded, prior, x_map, f"posterior mode ({on})")
    update = BayesianUpdate(loaded=loaded, nominal=nominal, prior=prior, parameters=parameters, fit=fit,
                            x_map=x_map, fit_conditions=list(fit_conditions), rows=rows, excluded=excluded,
                            conditions_runs=residuals.runs * len(fit_conditions), model=model, mesh=mesh)
    update.summary = _summary(update) | {"wall_time_s": time.perf_counter() - started}
    return update


def _prior_text(p: UncertainParameter) -> str:
    unit = "× declared" if p.kind == "scale" else p.unit
    parts = [p.distribution]
    if p.sigma is not None:
        parts.append(f"σ {'of ln x ' if p.distribution == 'lognormal' else ''}{p.sigma:.4g}")
    if p.low is not None:
        parts.append(f"{p.low:.4g} … {p.high:.4g}")
    return " ".join(parts) + (f" {unit}" if unit else "") + f", declared {p.declared:.4g}"


def _summary(update: BayesianUpdate) -> dict:
    fit = update.fit
    model = fit.residuals
    return {
        "method": "Bayesian update of the declared priors, Laplace approximation in standard-normal coordinates",
        "fit_conditions": update.fit_conditions,
        "noise_scale_s2": fit.s2,
        "effective_parameters": fit.p_eff,
        "measured_values": len(update.rows),
        "passes": fit.passes,
        "converged": fit.converged,
        "least_squares": fit.status,
        "jacobians": fit.jacobians,
        "points": fit.evaluations,
        "model_runs": update.conditions_runs,
        "model": update.model,
        "mesh": update.mesh,
        "jacobian_step_z": JACOBIAN_STEP,
        "parameters": {p.name: {"prior": _prior_text(p), "map": float(update.x_map[i]), "z_map": float(fit.z[i]),
                                "sd_z": float(fit.sd[i]), "p05": update.parameters[i].low,
                                "p95": update.parameters[i].high, "kind": p.kind, "unit": p.unit}
                       for i, p in enumerate(update.prior)},
        "correlation_z": {"parameters": [p.name for p in update.prior],
                          "matrix": (fit.covariance / np.outer(fit.sd, fit.sd)).tolist()},
        "residuals": [{"condition": r.condition, "quantity": r.quantity, "unit": r.unit, "measured": r.measured,
                       "sigma": r.sigma, "model": r.measured + r.sigma * float(model[j]),
                       "weighted": float(model[j])} for j, r in enumerate(update.rows)],
        "excluded": update.excluded,
    }
