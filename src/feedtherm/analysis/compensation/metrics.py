"""Residual thermal error of a compensation law over cycles: RMS, maximum, reduction."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass

import numpy as np

from .data import CycleRecord, CycleSet


@dataclass(frozen=True)
class Residuals:
    """Residual error over every sample of a set of cycles [m], and without compensation.

    Without compensation the error is D itself (the axis is positioned as if the screw were at
    its reference temperature); ``reduction`` is ``1 - rms / uncompensated_rms``.
    """

    rms: float
    max: float
    uncompensated_rms: float
    uncompensated_max: float
    per_cycle: tuple[tuple[str, float, float], ...]  # label, RMS [m], max |residual| [m]

    @property
    def reduction(self) -> float:
        return 1.0 - self.rms / self.uncompensated_rms if self.uncompensated_rms > 0 else float("nan")

    def as_dict(self, per_cycle: bool = True) -> dict:
        """µm and %, for files (``per_cycle``: with each cycle's RMS and max)."""
        out = {"rms_um": self.rms * 1e6, "max_um": self.max * 1e6,
               "uncompensated_rms_um": self.uncompensated_rms * 1e6,
               "uncompensated_max_um": self.uncompensated_max * 1e6,
               "reduction_percent": 100.0 * self.reduction}
        if per_cycle:
            out["per_cycle"] = [{"cycle": label, "rms_um": r * 1e6, "max_um": m * 1e6} for label, r, m in self.per_cycle]
        return out


def residuals(predict: Callable[[CycleRecord], np.ndarray], cycles: CycleSet) -> Residuals:
    """The residuals ``D - predict(cycle)`` over every cycle of ``cycles``."""
    return summarise((record.label, record.elongation, np.asarray(predict(record), dtype=float))
                     for record in cycles.cycles)


def summarise(cycles: Iterable[tuple[str, np.ndarray, np.ndarray]]) -> Residuals:
    """:class:`Residuals` of ``(label, truth, prediction)`` per cycle [m], over every entry of all of them
    (a prediction of one value per sample is applied to every column of a 2-D truth)."""
    errors, truth, per_cycle = [], [], []
    for label, actual, predicted in cycles:
        actual = np.asarray(actual, dtype=float)
        if predicted.ndim < actual.ndim:
            predicted = predicted[:, None]
        error = (actual - predicted).ravel()
        errors.append(error)
        truth.append(actual.ravel())
        per_cycle.append((label, float(np.sqrt(np.mean(error ** 2))), float(np.abs(error).max())))
    e, d = np.concatenate(errors), np.concatenate(truth)
    return Residuals(float(np.sqrt(np.mean(e ** 2))), float(np.abs(e).max()),
                     float(np.sqrt(np.mean(d ** 2))), float(np.abs(d).max()), tuple(per_cycle))
