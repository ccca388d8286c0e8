"""A test's ISO 230-3 figures, measured and simulated side by side.

For every test whose measurements hold positioning deviations at target positions: the drift at
each target since its first measurement, measured and as the run has it at the same instants,
the drift of the distance between the outer targets (the axis's thermal expansion), and for a
test with every motor at rest (its measuring stops aside) in a room whose air varies, the ETVE of
each measured displacement (:mod:`.iso230_3`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..constants import KELVIN_OFFSET
from ..solution import Solution
from ..system.measurement_series import ELONGATION_QUANTITY
from ..system.measurements import MeasurementSet
from .iso230_3 import Etve, ExpansionDrift, TargetDrift, etve, outer_targets, target_drift
from .transient_scores import positioning_at

_UM = 1e-6


@dataclass(frozen=True, eq=False)
class DriftTest:
    """One test's ISO 230-3 figures (SI: m, s, K), measured and simulated at the measured instants."""

    run: str
    measured: list[TargetDrift]
    simulated: list[TargetDrift]
    expansion_measured: ExpansionDrift | None
    expansion_simulated: ExpansionDrift | None
    etve: list[tuple[Etve, Etve]]  # (measured, simulated) per displacement, idle tests with a varying room only

    @property
    def residual(self) -> list[tuple[float, float]]:
        """Per target: (RMS, largest |·|) [m] of simulated − measured drift."""
        out = []
        for m, s in zip(self.measured, self.simulated):
            d = s.drift[1:] - m.drift[1:]
            out.append((float(np.sqrt(np.mean(d ** 2))) if d.size else 0.0, float(np.max(np.abs(d))) if d.size else 0.0))
        return out


def drift_test(run: str, solution: Solution, data: MeasurementSet, idle: bool = False) -> DriftTest | None:
    """The ISO 230-3 figures of ``run`` from its measurements and its run; None without positioning
    deviations or ETVE to evaluate."""
    rows = data.positioning_of(run)
    measured, simulated = [], []
    for row in rows:
        s = row.series
        measured.append(target_drift(row.target, s.times, s.values * _UM))
        simulated.append(target_drift(row.target, s.times,
                                      np.interp(s.times, solution.times, positioning_at(solution, row.target)) * _UM))
    etves = _etves(run, solution, data, rows) if idle and run in data.air else []
    if not measured and not etves:
        return None
    return DriftTest(run, measured, simulated, _outer(measured), _outer(simulated), etves)


def _outer(drifts: list[TargetDrift]) -> ExpansionDrift | None:
    try:
        return outer_targets(drifts)
    except ValueError:  # the outer targets never measured within each other's reach
        return None


def _etves(run: str, solution: Solution, data: MeasurementSet, rows) -> list[tuple[Etve, Etve]]:
    air = data.air[run]
    air_sim_t, air_sim = solution.times, solution.sensors[solution.ambient_sensor]
    out = []
    displacements = [(row.quantity, row.series, positioning_at(solution, row.target)) for row in rows]
    for row in data.for_condition(run):
        if row.quantity == ELONGATION_QUANTITY and row.series is not None:
            displacements.insert(0, ("D", row.series, solution.elongation_um))
    for name, series, simulated in displacements:
        if len(series.times) < 2:
            continue
        measured = etve(name, series.times, series.values * _UM, air.times, air.values + KELVIN_OFFSET)
        at = np.interp(series.times, solution.times, simulated) * _UM
        out.append((measured, etve(name, series.times, at, air_sim_t, air_sim)))
    return out
