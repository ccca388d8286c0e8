"""Measured pairs of a regression law: its features and the measured D, with D's uncertainty.

From final values (one pair per condition) the readings are equilibrium values: a lag equals its
reading (settled, as :mod:`.measured` reads them).  From a time series the lags run over the
series from its first sample (the machine at rest) and every sample of D is a pair; the inputs are
interpolated linearly to the union of their and D's sample times, held at their first and last
values outside their own.  A law's input the file does not measure is an error, except the ambient
sensor of a declared condition, which reads the condition's ambient (as :mod:`.measured`).

Each D's standard uncertainty σ [m]: the file's ``uncertainty`` column where it gives one, else
the description's ``calibration.elongation_sigma``, else :data:`DEFAULT_ELONGATION_SIGMA` — the
order and the default of calibration's residual weights (:mod:`~feedtherm.analysis.calibration`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ...constants import KELVIN_OFFSET
from ...errors import FeedthermError
from ...system.measurements import ELONGATION_QUANTITY, MeasurementSet
from .regression import RegressionLaw, features

#: Standard uncertainty of a measured D [m] where neither the file nor the description gives one
#: (calibration's and inference's default, :mod:`~feedtherm.analysis.calibration`).
DEFAULT_ELONGATION_SIGMA = 2e-6


@dataclass(frozen=True)
class Pairs:
    """Measured pairs of one law: its features ``(n, p)`` [K], measured D ``(n,)`` [m], the
    standard uncertainty of each D ``(n,)`` [m], and each sample's condition."""

    features: np.ndarray
    elongation: np.ndarray
    sigma: np.ndarray
    conditions: tuple[str, ...]

    def without(self, condition: str) -> "Pairs":
        keep = np.array([c != condition for c in self.conditions])
        return Pairs(self.features[keep], self.elongation[keep], self.sigma[keep],
                     tuple(c for c in self.conditions if c != condition))

    def only(self, condition: str) -> "Pairs":
        keep = np.array([c == condition for c in self.conditions])
        return Pairs(self.features[keep], self.elongation[keep], self.sigma[keep],
                     tuple(c for c in self.conditions if c == condition))


def elongation_sigma(system) -> float:
    """σ [m] of a measured D without its own uncertainty: ``calibration.elongation_sigma``, else the default."""
    cal = system.calibration
    return float(cal.elongation_sigma) if cal else DEFAULT_ELONGATION_SIGMA


def measured_pairs(law: RegressionLaw, data: MeasurementSet, *, ambient_sensor: str,
                   ambients: Mapping[str, float], sigma: float, series: bool = True) -> Pairs:
    """The pairs (features, D) of ``law`` in ``data``: one per condition from final values, every
    D sample from a series (``series=False``: the final values of a series too).

    Parameters
    ----------
    ambient_sensor : str
        The description's ambient sensor; where the file does not measure it, it reads the
        condition's ambient from ``ambients`` (condition -> [K]).
    sigma : float
        σ [m] of a D without a declared uncertainty (:func:`elongation_sigma`).

    Raises
    ------
    FeedthermError
        One line: no D in the file; an input of the law not measured at a condition with D; a
        declared uncertainty of 0.
    """
    rows, values, sigmas, conditions = [], [], [], []
    with_d = [c for c in data.conditions()
              if any(r.quantity == ELONGATION_QUANTITY for r in data.for_condition(c))]
    if not with_d:
        raise FeedthermError(f"{data.source}: no measured D (quantity {ELONGATION_QUANTITY} in final values, "
                             "D in a time series); adaptation needs the elongation")
    for condition in with_d:
        measured = {r.quantity: r for r in data.for_condition(condition)}
        for name in law.sensors:
            if name not in measured and not (name == ambient_sensor and condition in ambients):
                raise FeedthermError(f"{data.source}: condition {condition} does not measure {name}, an input of "
                                     f"the law on {', '.join(law.sensors)}")
        d = measured[ELONGATION_QUANTITY]
        if series and d.series is not None:
            f, y, u = _series_pairs(law, measured, condition, ambients, sigma)
        else:
            readings = [[_final(measured, name, condition, ambients) for name in law.sensors]]
            f = features(np.zeros(1), np.array(readings), law.lags)
            u = np.array([sigma if d.series is None or d.series.uncertainties is None
                          else float(d.series.uncertainties[-1]) * 1e-6])
            y = np.array([d.measured * 1e-6])
        if np.any(u <= 0):
            raise FeedthermError(f"{data.source}: condition {condition} D: an uncertainty of 0 would weigh it "
                                 "infinitely; give the standard uncertainty, or no uncertainty column")
        rows.append(f)
        values.append(y)
        sigmas.append(u)
        conditions += [condition] * len(y)
    return Pairs(np.vstack(rows), np.concatenate(values), np.concatenate(sigmas), tuple(conditions))


def _final(measured: dict, name: str, condition: str, ambients: Mapping[str, float]) -> float:
    if name in measured:
        return measured[name].measured + KELVIN_OFFSET
    return float(ambients[condition])  # the ambient sensor of a declared condition (checked by the caller)


def union_times(rows) -> np.ndarray:
    """The sorted union of the sample times [s] of measurements ``rows`` (final values: time 0)."""
    return np.unique(np.concatenate([r.series.times if r.series is not None else np.zeros(1) for r in rows]))


def values_at(row, times: np.ndarray) -> np.ndarray:
    """A measurement's values (°C or µm) at ``times`` [s]: linear between its samples and held at its
    first and last outside them; final values: the same value at every time."""
    if row.series is None:
        return np.full(len(times), float(row.measured))
    return np.interp(times, row.series.times, row.series.values)


def _series_pairs(law: RegressionLaw, measured: dict, condition: str, ambients: Mapping[str, float], sigma: float):
    """Features at every D sample of a condition: the inputs interpolated on the union of their and
    D's sample times (held at their first and last values outside), the lags run over it."""
    d = measured[ELONGATION_QUANTITY].series
    times = union_times([measured[ELONGATION_QUANTITY], *(measured[n] for n in law.sensors if n in measured)])
    columns = [values_at(measured[name], times) + KELVIN_OFFSET if name in measured
               else np.full(len(times), float(ambients[condition])) for name in law.sensors]
    rows = features(times, np.column_stack(columns), law.lags)
    at = np.searchsorted(times, d.times)
    u = np.full(len(d.times), sigma) if d.uncertainties is None else np.asarray(d.uncertainties, float) * 1e-6
    return rows[at], np.asarray(d.values, float) * 1e-6, u
