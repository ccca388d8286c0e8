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
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import lsq_linear
from scipy.stats import norm

from ..constants import ELONGATION_PROBE, KELVIN_OFFSET
from ..errors import FeedthermError
from ..models.interface import cycle_weights, weighted_sum
from ..simulate import steady_solve
from ..system.load import LoadedSystem
from .measurements import MeasurementSet

#: Groups whose estimates correlate beyond this are reported as not told apart.
CORRELATION_LIMIT = 0.8
#: Below this resolution an estimate is said to come from the prior, not the measurements.
RESOLVED = 0.5


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


def infer(transfer_: Transfer, measured: dict[str, float], noise: Noise, prior_width: float = 1.0) -> Inference:
    """Heats of ``transfer_``'s groups from the measured observations (sensors [K], ``D`` [m]).

    ``prior_width`` is the prior's standard deviation relative to each group's loss-model heat
    (with a floor of 1 W, so that a source the loss models put at zero can still be found).
    """
    if not (np.isfinite(prior_width) and prior_width > 0):
        raise FeedthermError(f"--prior-width: must be a positive number, got {prior_width!r}")
    used = [i for i, name in enumerate(transfer_.observations) if name in measured]
    if not used:
        raise FeedthermError(f"condition {transfer_.condition}: no measurement of {', '.join(transfer_.observations)}")
    names = [transfer_.observations[i] for i in used]
    y = np.array([measured[n] for n in names])
    R = transfer_.matrix[used]
    y0 = transfer_.baseline[used]
    sigma = np.array([noise.elongation if n == ELONGATION_PROBE else noise.temperature for n in names])
    prior = transfer_.prior
    tau = np.maximum(prior_width * prior, prior_width * 1.0)
    A = np.vstack([R / sigma[:, None], np.diag(1.0 / tau)])
    b = np.concatenate([(y - y0) / sigma, prior / tau])
    result = lsq_linear(A, b, bounds=(0.0, np.inf), method="bvls")
    q = np.maximum(result.x, 0.0)
    information = (R / sigma[:, None]).T @ (R / sigma[:, None])
    covariance = np.linalg.inv(information + np.diag(1.0 / tau**2))
    resolution = np.diag(covariance @ information)
    sd = np.sqrt(np.diag(covariance))
    z = norm.ppf(0.975)
    correlation = covariance / np.outer(sd, sd)
    groups = list(transfer_.groups)
    estimates = [GroupEstimate(g, transfer_.groups[g], float(prior[i]), float(q[i]), max(0.0, float(q[i] - z * sd[i])),
                               float(q[i] + z * sd[i]), float(resolution[i]), bool(q[i] <= 1e-12))
                 for i, g in enumerate(groups)]
    pairs = [(groups[i], groups[j], float(correlation[i, j])) for i in range(len(groups)) for j in range(i + 1, len(groups))
             if abs(correlation[i, j]) > CORRELATION_LIMIT]
    fitted = y0 + R @ q
    return Inference(transfer_.condition, estimates, names, y, fitted, y0 + R @ prior, covariance, correlation, pairs,
                     float(np.sum(((y - fitted) / sigma) ** 2)), noise, prior_width)


def measured_observations(data: MeasurementSet, condition: str, ambient: str) -> dict[str, float]:
    """A condition's measurements in SI: sensors [K] (``ambient``, the air's, left out), ``D`` [m]."""
    out = {}
    for row in data.for_condition(condition):
        if row.quantity == ambient:
            continue
        if row.quantity == "D_um":
            out[ELONGATION_PROBE] = row.measured * 1e-6
        elif row.unit == "C":
            out[row.quantity] = row.measured + KELVIN_OFFSET
    return out


def infer_conditions(loaded: LoadedSystem, data: MeasurementSet, conditions: list[str], *, groups: str | None = None,
                     noise: Noise, prior_width: float = 1.0,
                     model: str = "fast") -> list[Inference]:
    """:func:`infer` at each of ``conditions`` from ``data``."""
    measured = data.conditions()
    for condition in conditions:
        if condition not in measured:
            raise FeedthermError(f"--conditions: no measurements of condition {condition!r} in {data.source}; "
                                 f"measured: {', '.join(measured)}")
    grouping = parse_groups(groups, list(loaded.system.sources))
    return [infer(transfer(loaded, c, grouping, model=model), measured_observations(data, c, loaded.system.room.ambient_sensor), noise,
                  prior_width)
            for c in conditions]
