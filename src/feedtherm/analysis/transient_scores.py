"""How well a run follows a measured series: the whole transient, not only its end.

The simulated series is interpolated linearly to the measured times (a run samples every
10 s, far closer than a thermal transient bends), and the deviations simulated − measured are
summarised by their root mean square, their largest magnitude and when it occurred, their
mean (the bias) and, where the file gives uncertainties, the share of samples within two of them.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..errors import FeedthermError
from ..solution import Solution
from ..system.measurement_series import ELONGATION_QUANTITY, Series, target_of
from ..system.measurements import Measurement

#: Slack on the run's time span [s]: a sample at the run's end is not rounded out of it.
_TIME_SLACK = 1e-6


@dataclass(frozen=True, eq=False)
class TransientComparison:
    """One measured series against its run (°C or µm; deviations in K or µm).

    Attributes
    ----------
    condition, quantity : str
        The condition and the measured quantity (a sensor name, or ``D_um``).
    unit : str
        ``"C"`` for a temperature, ``"um"`` for the elongation.
    times : ndarray
        Measured sample times [s].
    measured, simulated : ndarray
        The measured values and the run's values at ``times``.
    uncertainty : ndarray or None
        The measured values' standard uncertainties, where given.
    """

    condition: str
    quantity: str
    unit: str
    times: np.ndarray
    measured: np.ndarray
    simulated: np.ndarray
    uncertainty: np.ndarray | None = None

    @property
    def deviation(self) -> np.ndarray:
        return self.simulated - self.measured

    @property
    def rms(self) -> float:
        """Root mean square of the deviations."""
        return float(np.sqrt(np.mean(self.deviation ** 2)))

    @property
    def max_abs(self) -> float:
        """Largest |deviation|."""
        return float(np.max(np.abs(self.deviation)))

    @property
    def time_of_max(self) -> float:
        """When the largest |deviation| occurred [s] (the first such sample)."""
        return float(self.times[int(np.argmax(np.abs(self.deviation)))])

    @property
    def mean(self) -> float:
        """Mean deviation (the bias)."""
        return float(np.mean(self.deviation))

    @property
    def inside_two_sigma(self) -> float | None:
        """Share of the samples within two standard uncertainties of the run, None without them.

        The run's own uncertainty is not counted: this says whether the measurement's scatter
        alone could explain the deviations (about 95 % of the samples if it did).
        """
        if self.uncertainty is None:
            return None
        return float(np.mean(np.abs(self.deviation) <= 2.0 * self.uncertainty))


def simulated_series(solution: Solution, quantity: str) -> np.ndarray:
    """The run's series of a measured quantity: a sensor [°C], ``D_um`` [µm], or the positioning error E
    at a target (``E@150mm``, :func:`~feedtherm.system.measurement_series.target_key`) [µm]."""
    if quantity == ELONGATION_QUANTITY:
        return solution.elongation_um
    target = target_of(quantity)
    if target is not None:
        return positioning_at(solution, target)
    celsius = solution.sensors_celsius()
    if quantity not in celsius:
        raise FeedthermError(f"the run has no sensor {quantity!r} to compare with its measured series")
    return celsius[quantity]


def positioning_at(solution: Solution, target: float) -> np.ndarray:
    """The thermal positioning error E [µm] at the table position ``target`` [m] over the run's times,
    linear between the run's table positions."""
    if solution.table_x.size == 0:
        raise FeedthermError("the run has no table (no feed drive), so no positioning error at a target")
    return np.array([np.interp(target, solution.table_x, row) for row in solution.positioning_error]) * 1e6


def drift(row: Measurement) -> Measurement:
    """A positioning deviation's series as its drift since its first sample (ISO 230-3): the values less
    the first, the first sample left out (0 by construction), each uncertainty combined with the first's.

    An interferometer's deviation holds the axis's geometric error, which the model does not: its
    change is what the heat does (:mod:`feedtherm.analysis.iso230_3`).
    """
    series = row.series
    if series is None or len(series.times) < 2:
        raise FeedthermError(f"{row.condition} {row.quantity}: a drift needs two measurements at the target or more")
    u = series.uncertainties
    values = series.values[1:] - series.values[0]
    combined = None if u is None else np.sqrt(u[1:] ** 2 + u[0] ** 2)
    return replace(row, measured=float(values[-1]), series=Series(series.times[1:], values, combined),
                   since=float(series.times[0]))


def compare_series(condition: str, solution: Solution, rows: list[Measurement]) -> list[TransientComparison]:
    """Every measured series among ``rows`` (one condition's) against ``solution``, its run.

    Raises
    ------
    FeedthermError
        A measured time lies outside the run, which can then say nothing about it.
    """
    out = []
    start, end = float(solution.times[0]), float(solution.times[-1])
    for row in rows:
        series = row.series
        if series is None:
            continue
        if series.times[0] < start - _TIME_SLACK or series.times[-1] > end + _TIME_SLACK:
            raise FeedthermError(f"condition {condition}: the measured {row.quantity} spans {series.times[0]:g}–"
                                 f"{series.times[-1]:g} s, the run only {start:g}–{end:g} s")
        simulated = np.interp(series.times, solution.times, simulated_series(solution, row.quantity))
        if row.since is not None:  # a drift: the run's change since the same instant
            simulated = simulated - np.interp(row.since, solution.times, simulated_series(solution, row.quantity))
        out.append(TransientComparison(condition, row.quantity, row.unit, series.times, series.values, simulated,
                                       series.uncertainties))
    return out
