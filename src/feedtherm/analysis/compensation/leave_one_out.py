"""Leave-one-condition-out: does a simulation-trained law, updated on a bench's other conditions,
predict the measured D of the one left out?

For each measured condition, with the pairs of every other condition (:func:`.pairs.measured_pairs`),
the held-out condition's D − measured D [m] of four predictors:

- ``model_only``: the simulation-trained law alone (no measurement enters);
- ``adapted``: its Bayesian update on the other conditions (:func:`.adapt.adapt_law`, the prior's
  width by maximum evidence on those conditions only), with its predictive standard deviation;
- ``regression``: a least-squares fit on the other conditions alone, in the same centred and
  scaled coordinates — with fewer conditions than coefficients (the paper's bench: 4 conditions,
  6 coefficients) the minimum-norm solution (:func:`.adapt.minimum_norm_fit`);
- ``reference_model``: the measurement file's ``reference_simulated`` D (another model's, for the
  paper's bench its own ANSYS results), where every condition carries one.

Nothing is chosen on the held-out condition: the prior width, the centre and the fit see the
others only; the features' scale comes from the simulated training cycles.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...system.measurements import ELONGATION_QUANTITY, MeasurementSet
from .adapt import adapt_law, minimum_norm_fit
from .pairs import Pairs
from .regression import RegressionLaw

#: The predictors compared, in the order they are shown.
PREDICTORS = ("model_only", "adapted", "regression", "reference_model")


@dataclass(frozen=True)
class HeldOut:
    """One held-out condition: measured D and each predictor's D − measured [m]; the adapted law's
    predictive standard deviation [m] and its prior width τ [m]."""

    condition: str
    measured: float
    residuals: dict[str, float | None]
    adapted_sd: float
    width: float

    def as_dict(self) -> dict:
        return {"condition": self.condition, "measured_um": self.measured * 1e6,
                **{f"{k}_um": None if v is None else v * 1e6 for k, v in self.residuals.items()},
                "adapted_sd_um": self.adapted_sd * 1e6, "prior_width_um": self.width * 1e6}


@dataclass(frozen=True)
class LeaveOneOut:
    law: RegressionLaw
    held_out: list[HeldOut]

    def summary(self, predictor: str) -> dict | None:
        """RMS and max |residual| [µm] of ``predictor`` over the held-out conditions (None if any lacks it)."""
        values = [h.residuals[predictor] for h in self.held_out]
        if not values or any(v is None for v in values):
            return None
        r = np.abs(np.array(values))
        return {"rms_um": float(np.sqrt(np.mean(r ** 2))) * 1e6, "max_um": float(r.max()) * 1e6,
                "conditions": len(values)}

    def as_dict(self) -> dict:
        return {"law": "regression", "sensors": list(self.law.sensors), "lags_s": list(self.law.lags),
                "conditions": [h.as_dict() for h in self.held_out],
                **{name: self.summary(name) for name in PREDICTORS},
                "within_2sd": sum(abs(h.residuals["adapted"]) <= 2 * h.adapted_sd for h in self.held_out)}


def leave_one_condition_out(law: RegressionLaw, pairs: Pairs, data: MeasurementSet,
                            scale: np.ndarray | None = None, reference: float | None = None) -> LeaveOneOut:
    """Every condition of ``pairs`` held out in turn (one pair per condition: equilibrium values).

    ``data``: the measurements the pairs come from, for the ``reference_simulated`` D; ``reference``: the
    temperature [K] the adapted law keeps passing through (:func:`.adapt.adapt_law`).
    """
    held = []
    for condition in dict.fromkeys(pairs.conditions):
        rest, test = pairs.without(condition), pairs.only(condition)
        x, measured = test.features, float(test.elongation[-1])
        adapted = adapt_law(law, rest, scale, reference=reference)
        mean, sd = adapted.predict_features(x)
        fit = minimum_norm_fit(law, rest, scale)
        residuals = {
            "model_only": float(law.bias + x[-1] @ law.weights.ravel()) - measured,
            "adapted": float(mean[-1]) - measured,
            "regression": float(fit.bias + x[-1] @ fit.weights.ravel()) - measured,
            "reference_model": _reference(data, condition, measured),
        }
        held.append(HeldOut(condition, measured, residuals, float(sd[-1]), adapted.width))
    return LeaveOneOut(law, held)


def _reference(data: MeasurementSet, condition: str, measured: float) -> float | None:
    rows = [r for r in data.for_condition(condition) if r.quantity == ELONGATION_QUANTITY]
    if not rows or rows[0].reference_simulated is None:
        return None
    return rows[0].reference_simulated * 1e-6 - measured
