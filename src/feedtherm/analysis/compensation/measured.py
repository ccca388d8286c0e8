"""A law trained on simulated cycles, applied to the measured bench.

For each measured condition the law reads the measured equilibrium temperatures of its inputs
(the ambient sensor reads the condition's stated ambient) and predicts D, which is compared with
the measured D and beside the deviation of the reference model where the measurements carry it
(its simulated D − measured D).  The measurements are
equilibrium values, so each is one reading of a machine in its thermal equilibrium: a regression
law's lags start settled at the first reading (:mod:`.evaluator`), as on a machine that has run
at that state for long; the Kalman estimator reads the same values every :data:`STEP` for
:data:`HOLD` at the condition's motor speeds, from a machine at the ambient (the paper's runs
last 3 h), and gives its last estimate.  Nothing of the measurements enters the fit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...constants import KELVIN_OFFSET
from ...system.load import LoadedSystem
from ...system.measurements import ELONGATION_QUANTITY, MeasurementSet
from ...constants import RPM_PER_RAD_S
from .kalman import KalmanLaw
from .regression import RegressionLaw

#: How long [s] and how often [s] the Kalman estimator reads a condition's equilibrium values.
HOLD = 3 * 3600.0
STEP = 60.0


@dataclass(frozen=True)
class MeasuredPrediction:
    """One condition: the law's D and the measured D [m]; the paper's model's D [m] where known."""

    condition: str
    predicted: float
    measured: float
    paper_simulated: float | None

    @property
    def deviation(self) -> float:
        return self.predicted - self.measured

    @property
    def paper_deviation(self) -> float | None:
        return None if self.paper_simulated is None else self.paper_simulated - self.measured

    def as_dict(self) -> dict:
        return {"condition": self.condition, "predicted_um": self.predicted * 1e6, "measured_um": self.measured * 1e6,
                "deviation_um": self.deviation * 1e6,
                "paper_simulated_um": None if self.paper_simulated is None else self.paper_simulated * 1e6,
                "paper_deviation_um": None if self.paper_deviation is None else self.paper_deviation * 1e6}


def measured_inputs(loaded: LoadedSystem, data: MeasurementSet, condition: str) -> dict[str, float]:
    """The measured temperatures [K] of one condition, and the ambient sensor from the condition's ambient."""
    values = {r.quantity: r.measured + KELVIN_OFFSET for r in data.for_condition(condition)
              if r.quantity != ELONGATION_QUANTITY}
    values.setdefault(loaded.system.room.ambient_sensor, loaded.system.conditions[condition].ambient)
    return values


def predict_measured(law: RegressionLaw | KalmanLaw, loaded: LoadedSystem,
                     data: MeasurementSet) -> list[MeasuredPrediction]:
    """The law's D at every measured condition whose measurements hold all its inputs and D (its final
    values: a test's series are judged over time, :mod:`.drift_judge`)."""
    out = []
    for condition in [c for c in data.conditions() if c in loaded.system.conditions]:
        inputs = measured_inputs(loaded, data, condition)
        elongation = [r for r in data.for_condition(condition) if r.quantity == ELONGATION_QUANTITY]
        if not elongation or any(name not in inputs for name in law.sensors):
            continue
        if isinstance(law, KalmanLaw):
            predicted = _held(law, inputs, loaded.system.conditions[condition])
        else:
            predicted = float(law.predict([0.0], [[inputs[name] for name in law.sensors]])[0])
        row = elongation[0]
        paper = None if row.reference_simulated is None else row.reference_simulated * 1e-6
        out.append(MeasuredPrediction(condition, predicted, row.measured * 1e-6, paper))
    return out


def _held(law: KalmanLaw, inputs: dict[str, float], condition) -> float:
    """The estimator's D after reading ``inputs`` every STEP for HOLD at the condition's speeds."""
    estimator = law.estimator()
    screw, nut = condition.screw_speed * RPM_PER_RAD_S, condition.nut_speed * RPM_PER_RAD_S
    readings = {name: inputs[name] for name in (*law.sensors, law.model.ambient)}
    d = 0.0
    for t in np.arange(0.0, HOLD + STEP / 2, STEP):
        d, _ = estimator.update(float(t), readings, screw, nut)
    return d
