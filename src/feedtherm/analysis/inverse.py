"""Inverse heat-source estimation: which heats explain the measured steady temperatures.

At frozen coefficients the steady state is linear in the heats.  For every group of sources
the model's own operators give a column of the transfer matrix ``R`` (the sensors' and D's
response to 1 W of that group, placed as the loss models place it), so the observations are

.. math:: y = y_0 + R\\,q + e, \\qquad e \\sim N(0, \\Sigma),

with ``y_0`` the observations at zero heat (every part at its sink temperature).  The heats are
estimated by non-negative, regularised least squares, the regularisation a Gaussian prior
centred on the loss models' heats with a declared relative width:

.. math:: \\hat q = \\arg\\min_{q \\ge 0} \\|\\Sigma^{-1/2}(y - y_0 - Rq)\\|^2
          + \\|T^{-1}(q - q_{prior})\\|^2 .

The posterior covariance ``(RᵀΣ⁻¹R + T⁻²)⁻¹`` gives each heat's interval, its resolution
(the share of the estimate that comes from the data rather than the prior: the diagonal of
``(RᵀΣ⁻¹R + T⁻²)⁻¹ RᵀΣ⁻¹R``) and the correlations that say which groups the sensors cannot tell
apart (only their sum or difference is measured).  An estimate that ends at its bound of 0 W
is flagged; its interval is then the unconstrained one cut at zero.

``Σ`` is diagonal: each observation's standard uncertainty is the one the measurement file
declares (a series' ``uncertainty`` column) where it gives one, else the uniform ``Noise``
(final values declare none).

Where a condition's measurements are time series, the heats are fitted to every sample
(:func:`transient_transfer`): at frozen coefficients the implicit-Euler run is linear in the
heats as well, ``y(t) = y_0(t) + R(t) q`` with ``y_0(t)`` the run at zero heat from the initial
state and the column ``R_g(t)`` the run with 1 W of group ``g`` less ``y_0(t)`` (superposition),
each interpolated to the measured times; the same estimator then takes one row per sample.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Mapping

import numpy as np
from scipy.special import ndtri

from ..constants import ELONGATION_PROBE, KELVIN_OFFSET
from ..errors import FeedthermError
from ..models.integrator import Integrator
from ..models.interface import cycle_weights, weighted_sum
from ..models.options import ModelOptions
from ..plan import plan_run
from ..simulate import initial_state, steady_solve
from ..solution.pack import sample_times
from ..system.load import LoadedSystem
from ..system.variants import with_values
from ..system.measurement_series import ELONGATION_QUANTITY
from ..system.measurements import MeasurementSet

#: Groups whose estimates correlate beyond this are reported as not told apart.
CORRELATION_LIMIT = 0.8
#: Below this resolution an estimate is said to come from the prior, not the measurements.
RESOLVED = 0.5
#: Time step of the transient responses [s]: the step ``validate`` scores a series with, and
#: calibration's runs of series (60 s steps lag a transient by up to 0.16 K, 1 µm on the
#: synthetic ballscrew series; docs/calibration.md).
TRANSIENT_STEP_S = 10.0


@dataclass(frozen=True)
class Noise:
    """Standard uncertainty of one measurement: temperatures [K], elongation [m]."""

    temperature: float
    elongation: float

    def __post_init__(self) -> None:
        for name in ("temperature", "elongation"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value > 0):
                raise FeedthermError(f"--sigma-{name}: must be a positive number, got {value!r}")


@dataclass(frozen=True)
class Transfer:
    """The linear steady response of one condition: ``y = baseline + matrix @ q``."""

    condition: str
    observations: list[str]  # sensor names, then "D"
    groups: dict[str, tuple[str, ...]]  # group -> its sources
    matrix: np.ndarray  # (observations, groups): [K/W], and [m/W] for D
    baseline: np.ndarray  # observations at zero heat [K], [m]
    prior: np.ndarray  # the loss models' heat of each group [W]

    def predict(self, heats: np.ndarray) -> np.ndarray:
        return self.baseline + self.matrix @ heats


@dataclass(frozen=True, eq=False)
class TransientTransfer:
    """The linear transient response of one condition at its measured samples: ``y = baseline + matrix @ q``.

    One row per sample: ``observations[i]`` (a sensor, or ``"D"``) at ``times[i]`` [s].
    """

    condition: str
    observations: list[str]
    times: np.ndarray
    groups: dict[str, tuple[str, ...]]
    matrix: np.ndarray  # (samples, groups): [K/W], and [m/W] for D
    baseline: np.ndarray  # the run at zero heat at each sample [K], [m]
    prior: np.ndarray  # the loss models' heat of each group [W]

    def predict(self, heats: np.ndarray) -> np.ndarray:
        return self.baseline + self.matrix @ heats


@dataclass(frozen=True)
class GroupEstimate:
    group: str
    sources: tuple[str, ...]
    loss_model: float  # [W]
    inferred: float  # [W]
    low: float  # 95 % interval [W]
    high: float
    resolution: float  # 0 = all prior, 1 = all measurements
    at_bound: bool


@dataclass(frozen=True)
class Inference:
    """The heats of one condition inferred from its measurements."""

    condition: str
    estimates: list[GroupEstimate]
    observations: list[str]
    measured: np.ndarray
    fitted: np.ndarray
    loss_model_prediction: np.ndarray
    covariance: np.ndarray
    correlation: np.ndarray
    not_told_apart: list[tuple[str, str, float]]
    chi2: float  # Σ (residual/σ)² of the fit to the measurements
    noise: Noise
    prior_width: float
    sigma: np.ndarray | None = None  # each observation's standard uncertainty [K], [m]
    declared: np.ndarray | None = None  # per observation: True where ``sigma`` is the file's, not ``noise``
    times: np.ndarray | None = None  # per observation, for a transient inference [s]; None: steady

    @property
    def transient(self) -> bool:
        """Whether the heats were fitted to the samples of measured series (else to final values)."""
        return self.times is not None

    @property
    def groups(self) -> list[str]:
        return [e.group for e in self.estimates]


def parse_groups(text: str | None, sources: list[str]) -> dict[str, tuple[str, ...]]:
    """``"motors=screw_motor,nut_motor;bearings=front_bearing,rear_bearing"`` → groups.

    Sources not named form a group of their own each; ``None`` gives one group per source.
    """
    groups: dict[str, tuple[str, ...]] = {}
    named: set[str] = set()
    for part in (text or "").split(";"):
        if not part.strip():
            continue
        name, sep, members = part.partition("=")
        name = name.strip()
        listed = tuple(m.strip() for m in members.split(",") if m.strip())
        if not sep or not name or not listed:
            raise FeedthermError(f"--groups: {part.strip()!r} is not NAME=SOURCE,SOURCE,...")
        for source in listed:
            if source not in sources:
                raise FeedthermError(f"--groups: no heat source {source!r}; sources: {', '.join(sources)}")
            if source in named:
                raise FeedthermError(f"--groups: source {source!r} is in two groups")
            named.add(source)
        if name in groups:
            raise FeedthermError(f"--groups: group name {name!r} is used twice")
        groups[name] = listed
    for source in sources:
        if source not in named:
            if source in groups:
                raise FeedthermError(f"--groups: group {source!r} is named like a source it does not hold")
            groups[source] = (source,)
    return groups


def transfer(loaded: LoadedSystem, condition: str, groups: dict[str, tuple[str, ...]], *,
             model: str = "fast") -> Transfer:
    """The steady response of ``condition``'s observations to 1 W of each group (cycle-averaged motion).

    Within a group the watt is shared as the loss models share the group's heat (equally if they
    give none), and each source's share enters where that source's heat enters.  The
    coefficients are those of the model's own steady state (evaluated there under
    ``temperatures.coupling = "nonlinear"``, frozen otherwise).
    """
    steady = steady_solve(loaded, condition, model=model)
    disc, integrator, k = steady.model, steady.integrator, steady.k
    bc = integrator.steady_boundary_conditions(0, steady.segment.bc, steady.state)
    k_probe = steady.probe_position
    positions = list(range(len(disc.positions))) if k is None else [k]
    weights = cycle_weights(len(disc.positions)) if k is None else np.ones(1)
    loads = integrator.loads(0, bc, k)
    names = disc.probe_names
    zero = disc.probe(np.zeros(disc.n_nodes), k_probe)
    baseline = disc.probe(integrator.steady(0, bc, k, rhs=loads.ambient.source), k_probe)
    columns, prior = [], []
    for members in groups.values():
        powers = np.array([bc.heats[s].power for s in members])
        total = float(powers.sum())
        shares = powers / total if total > 0 else np.full(len(members), 1.0 / len(members))
        unit = replace(bc, heats={s: replace(bc.heats[s], power=float(share)) for s, share in zip(members, shares)})
        q = weighted_sum(weights, [disc.heat_vector(unit, k) for k in positions])
        columns.append(disc.probe(integrator.steady(0, bc, k, rhs=q), k_probe) - zero)
        prior.append(total)
    return Transfer(condition, list(names), dict(groups), np.column_stack(columns), baseline, np.array(prior))


def transient_transfer(loaded: LoadedSystem, condition: str, groups: dict[str, tuple[str, ...]],
                       times: Mapping[str, np.ndarray], *, model: str = "fast",
                       measured: MeasurementSet | None = None) -> TransientTransfer:
    """The response of ``condition``'s measured series to 1 W of each group, at the measured times.

    Parameters
    ----------
    loaded : LoadedSystem
        The description and the overlay it runs in.
    condition : str
        The condition, run from its initial state over its duration with the cycle-averaged
        motion in :data:`TRANSIENT_STEP_S` steps.
    groups : dict of str to tuple of str
        Group → its sources; within a group the watt is shared as the loss models share the
        group's heat (equally if they give none), as in :func:`transfer`.
    times : mapping of str to ndarray
        Observation (a sensor, or ``"D"``) → its sample times [s].
    model : str
        The model of the registry to run.
    measured : MeasurementSet, optional
        The measurements a test's measured room or start reads (:func:`feedtherm.plan.plan_run`).

    Notes
    -----
    The coefficients (CHTCs, radiation, contact) are held at the run's first evaluation, so
    that the run is linear in the heats; under ``temperatures.coupling = "nonlinear"`` that is
    the frozen evaluation (the ambient plus ``convection_delta_t``), a linearisation.  The cost
    is one run per group and one at zero heat.

    A test runs as declared: from its start, in its room.  Where its duty changes the operating
    point (a cycle, its measuring stops) each group's heat keeps the loss models' shape over the
    segments, and the unknown is its heat at the *reference segment*, the one of most heat (the
    running duty): a segment where the loss models give a source no heat (a standstill) gives it
    none whatever the estimate.  For a condition (one segment) this is the heat itself.
    """
    frozen = loaded if loaded.system.temperatures.coupling == "frozen" else \
        with_values(loaded, {"temperatures.coupling": "frozen"}, origin_suffix="frozen coefficients")
    options = ModelOptions(motion="averaged", averaged_step=TRANSIENT_STEP_S, max_step=TRANSIENT_STEP_S, fields=False)
    plan = plan_run(frozen, condition=condition, model=model, motion="averaged", options=options,
                    sample_interval=TRANSIENT_STEP_S, allow_overload=True, measured=measured)  # heats are what is asked
    disc = plan.model.build(frozen.system, plan.options)
    grid = sample_times(plan.end, TRANSIENT_STEP_S)
    T0 = initial_state(plan, disc, Integrator(disc, plan.options, None))
    reference = max(plan.segments, key=lambda seg: seg.bc.total_heat).bc.heats
    names = list(disc.probe_names)
    for name, at in times.items():
        if name not in names:
            raise FeedthermError(f"condition {condition}: the model has no observation {name!r} ({', '.join(names)})")
        if at[-1] > grid[-1] * (1 + 1e-9):
            raise FeedthermError(f"condition {condition}: the measured {name} ends at {at[-1]:g} s, after the run "
                                 f"({grid[-1]:g} s)")

    def shape(seg, source: str) -> float:
        """The source's heat in ``seg`` relative to the reference segment's (1 where that has none)."""
        at_reference = reference[source].power
        return seg.bc.heats[source].power / at_reference if at_reference > 0 else 1.0

    def response(power) -> np.ndarray:
        """Every observation at every measured sample, each source's heat at the reference segment set to
        ``power(source)`` [W], the other segments' in the loss models' proportion."""
        segments = [replace(seg, bc=replace(seg.bc, heats={s: replace(h, power=float(power(s)) * shape(seg, s))
                                                           for s, h in seg.bc.heats.items()}))
                    for seg in plan.segments]
        # a fresh integrator: its caches are keyed by the boundary conditions' identity
        probes = np.array(Integrator(disc, plan.options, None).run(segments, T0, grid, air=plan.air).sample_probe)
        return np.concatenate([np.interp(at, grid, probes[:, names.index(name)]) for name, at in times.items()])

    baseline = response(lambda source: 0.0)
    heats = reference
    columns, prior = [], []
    for members in groups.values():
        powers = np.array([heats[s].power for s in members])
        total = float(powers.sum())
        shares = dict(zip(members, powers / total if total > 0 else np.full(len(members), 1.0 / len(members))))
        columns.append(response(lambda source: shares.get(source, 0.0)) - baseline)
        prior.append(total)
    observations = [name for name, at in times.items() for _ in at]
    return TransientTransfer(condition, observations, np.concatenate([np.asarray(at, dtype=float) for at in times.values()]),
                             dict(groups), np.column_stack(columns), baseline, np.array(prior))


def _default_sigma(name: str, noise: Noise) -> float:
    return noise.elongation if name == ELONGATION_PROBE else noise.temperature


def infer(transfer_: Transfer, measured: dict[str, float], noise: Noise, prior_width: float = 1.0) -> Inference:
    """Heats of ``transfer_``'s groups from the measured observations (sensors [K], ``D`` [m]).

    ``prior_width`` is the prior's standard deviation relative to each group's loss-model heat
    (with a floor of 1 W, so that a source the loss models put at zero can still be found).
    Final values declare no uncertainty: each takes ``noise``.
    """
    used = [i for i, name in enumerate(transfer_.observations) if name in measured]
    if not used:
        raise FeedthermError(f"condition {transfer_.condition}: no measurement of {', '.join(transfer_.observations)}")
    names = [transfer_.observations[i] for i in used]
    sigma = np.array([_default_sigma(n, noise) for n in names])
    return _estimate(transfer_, names, np.array([measured[n] for n in names]), transfer_.baseline[used],
                     transfer_.matrix[used], sigma, np.zeros(len(names), dtype=bool), noise, prior_width)


def infer_transient(transfer_: TransientTransfer, measured: np.ndarray, noise: Noise, prior_width: float = 1.0,
                    uncertainties: np.ndarray | None = None) -> Inference:
    """Heats of ``transfer_``'s groups from every measured sample (``measured`` in its row order, [K], [m]).

    ``uncertainties``: each sample's standard uncertainty, NaN where the file declares none
    (``noise`` then applies).  Otherwise as :func:`infer`.
    """
    names = transfer_.observations
    default = np.array([_default_sigma(n, noise) for n in names])
    given = np.full(len(names), np.nan) if uncertainties is None else np.asarray(uncertainties, dtype=float)
    declared = np.isfinite(given)
    return _estimate(transfer_, list(names), np.asarray(measured, dtype=float), transfer_.baseline, transfer_.matrix,
                     np.where(declared, given, default), declared, noise, prior_width, times=transfer_.times)


def _estimate(transfer_: Transfer | TransientTransfer, names: list[str], y: np.ndarray, y0: np.ndarray, R: np.ndarray,
              sigma: np.ndarray, declared: np.ndarray, noise: Noise, prior_width: float,
              times: np.ndarray | None = None) -> Inference:
    """The regularised non-negative estimate of the module's docstring, one row per observation."""
    if not (np.isfinite(prior_width) and prior_width > 0):
        raise FeedthermError(f"--prior-width: must be a positive number, got {prior_width!r}")
    prior = transfer_.prior
    tau = np.maximum(prior_width * prior, prior_width * 1.0)
    A = np.vstack([R / sigma[:, None], np.diag(1.0 / tau)])
    b = np.concatenate([(y - y0) / sigma, prior / tau])
    from scipy.optimize import lsq_linear  # imported where an estimate runs (module notes of :mod:`.calibration`)

    result = lsq_linear(A, b, bounds=(0.0, np.inf), method="bvls")
    q = np.maximum(result.x, 0.0)
    information = (R / sigma[:, None]).T @ (R / sigma[:, None])
    covariance = np.linalg.inv(information + np.diag(1.0 / tau**2))
    resolution = np.diag(covariance @ information)
    sd = np.sqrt(np.diag(covariance))
    z = ndtri(0.975)  # the normal's 97.5 % quantile (scipy.stats.norm.ppf is this function)
    correlation = covariance / np.outer(sd, sd)
    groups = list(transfer_.groups)
    estimates = [GroupEstimate(g, transfer_.groups[g], float(prior[i]), float(q[i]), max(0.0, float(q[i] - z * sd[i])),
                               float(q[i] + z * sd[i]), float(resolution[i]), bool(q[i] <= 1e-12))
                 for i, g in enumerate(groups)]
    pairs = [(groups[i], groups[j], float(correlation[i, j])) for i in range(len(groups)) for j in range(i + 1, len(groups))
             if abs(correlation[i, j]) > CORRELATION_LIMIT]
    fitted = y0 + R @ q
    return Inference(transfer_.condition, estimates, names, y, fitted, y0 + R @ prior, covariance, correlation, pairs,
                     float(np.sum(((y - fitted) / sigma) ** 2)), noise, prior_width, sigma, np.asarray(declared, bool),
                     times)


def measured_observations(data: MeasurementSet, condition: str, ambient: str) -> dict[str, float]:
    """A condition's measurements in SI: sensors [K] (``ambient``, the air's, left out), ``D`` [m]."""
    out = {}
    for row in data.for_condition(condition):
        if row.quantity == ambient:
            continue
        if row.quantity == ELONGATION_QUANTITY:
            out[ELONGATION_PROBE] = row.measured * 1e-6
        elif row.unit == "C":
            out[row.quantity] = row.measured + KELVIN_OFFSET
    return out


def _observed_series(data: MeasurementSet, condition: str, ambient: str):
    """A condition's measured series by observation name (``ambient`` left out), in SI:
    name → (times [s], values [K] or [m], standard uncertainties [K] or [m], or None)."""
    out = {}
    for row in data.for_condition(condition):
        if row.series is None or row.quantity == ambient:
            continue
        u = row.series.uncertainties
        at = row.series.zero_uncertainty_at()
        if at is not None:
            raise FeedthermError(f"{data.source}: condition {condition} {row.quantity}: the uncertainty at {at:g} s "
                                 "is 0, which would weigh it infinitely; give the standard uncertainty, or no "
                                 "uncertainty column (--sigma-temperature and --sigma-elongation then apply)")
        if row.quantity == ELONGATION_QUANTITY:
            out[ELONGATION_PROBE] = (row.series.times, row.series.values * 1e-6, None if u is None else u * 1e-6)
        else:
            out[row.quantity] = (row.series.times, row.series.values + KELVIN_OFFSET, u)
    return out



def infer_conditions(loaded: LoadedSystem, data: MeasurementSet, conditions: list[str], *, groups: str | None = None,
                     noise: Noise, prior_width: float = 1.0,
                     model: str = "fast") -> list[Inference]:
    """The heats of each of ``conditions`` from ``data``: from the final values (:func:`infer`), or,
    where the condition's measurements are time series, from every sample (:func:`infer_transient`),
    each weighted by its declared uncertainty where the file gives one, else by ``noise``."""
    measured = data.conditions()
    for condition in conditions:
        if condition not in measured:
            raise FeedthermError(f"--conditions: no measurements of {condition!r} in {data.source}; "
                                 f"measured: {', '.join(measured)}")
    grouping = parse_groups(groups, list(loaded.system.sources))
    ambient = loaded.system.room.ambient_sensor
    observed = {c: _observed_series(data, c, ambient) for c in conditions}  # a bad series fails before any run
    out = []
    for c in conditions:
        series = observed[c]
        if series:  # every sample, each with its declared uncertainty (NaN: the uniform noise)
            response = transient_transfer(loaded, c, grouping, {n: t for n, (t, _, _) in series.items()}, model=model,
                                          measured=data)
            values = np.concatenate([v for _, v, _ in series.values()])
            u = np.concatenate([np.full(len(t), np.nan) if u is None else u for t, _, u in series.values()])
            out.append(infer_transient(response, values, noise, prior_width, u))
        else:
            out.append(infer(transfer(loaded, c, grouping, model=model), measured_observations(data, c, ambient),
                             noise, prior_width))
    return out
