"""A study's laws and measurements: the regression laws adapted to a measurement file
(``feedtherm compensate --adapt``) and the leave-one-condition-out check on the bench's own.

- :func:`check_adaptation_file`: before the long run, the file holds D and, where the sensors were
  named, every one of them (one-line errors, :func:`.pairs.measured_pairs`);
- :func:`adapt_study`: the chosen regression laws (static and with lags, the ``law*.json`` a
  controller reads) updated on the file (:func:`.adapt.adapt_law`), each feature scaled by its
  spread over the study's training cycles;
- :func:`loco_study`: the static law on the description's own sensors, left one condition out on
  the bench's measurements (:mod:`.leave_one_out`), from their final values.

The Kalman estimator is not adapted: its weights are not coefficients to update but the reduced
physics model, and a measured mismatch enters it as a state (each source's heat error) that the
filter learns online (:mod:`.kalman`).
"""

from __future__ import annotations

import numpy as np

from ...system.load import LoadedSystem
from ...system.measurements import ELONGATION_QUANTITY, MeasurementSet
from .adapt import AdaptedLaw, adapt_law, feature_scale
from .leave_one_out import LeaveOneOut, leave_one_condition_out
from .pairs import elongation_sigma, measured_pairs
from .regression import RegressionLaw

#: Laws adapted by ``--adapt`` (kinds of :data:`.study.LAWS`) and the file each is written to.
ADAPTED_FILES = {"regression_lags": "law_adapted.json", "regression": "law_adapted_static.json"}
#: What compensation.json says of the Kalman estimator under ``--adapt``.
KALMAN_NOTE = ("not adapted: its weights are the reduced physics model, not fitted coefficients; a measured "
               "mismatch enters it as the sources' heat errors, which the filter estimates online")


def _ambients(loaded: LoadedSystem) -> dict[str, float]:
    """Condition -> its stated ambient [K] (what the ambient sensor reads where a file does not measure it)."""
    return {name: float(c.ambient) for name, c in loaded.system.conditions.items()}


def pairs_of(law: RegressionLaw, loaded: LoadedSystem, data: MeasurementSet, series: bool = True):
    """The measured pairs of ``law`` in ``data`` (:func:`.pairs.measured_pairs`) with the description's
    ambient sensor, conditions' ambients and σ of D."""
    return measured_pairs(law, data, ambient_sensor=loaded.system.room.ambient_sensor, ambients=_ambients(loaded),
                          sigma=elongation_sigma(loaded.system), series=series)


def check_adaptation_file(loaded: LoadedSystem, data: MeasurementSet, sensors: tuple[str, ...] | None) -> None:
    """Fail in one line before the study runs: no D in ``data``, or one of ``sensors`` (when named) not measured."""
    probe = RegressionLaw(tuple(sensors or ()), (), np.zeros((len(sensors or ()), 1)), 0.0)
    pairs_of(probe, loaded, data)


def adapt_study(result, loaded: LoadedSystem, data: MeasurementSet) -> dict[str, AdaptedLaw]:
    """Each law of :data:`ADAPTED_FILES` among ``result.chosen`` (a :class:`.study.StudyResult`) updated on ``data``."""
    train = result.sets["train"]
    out = {}
    for kind in ADAPTED_FILES:
        law = result.chosen[kind].law
        out[kind] = adapt_law(law, pairs_of(law, loaded, data), feature_scale(law, train.cycles, train.names),
                              reference=train.reference)
    return out


def loco_study(result, loaded: LoadedSystem, data: MeasurementSet | None) -> LeaveOneOut | None:
    """The static law on the description's own sensors, left one condition out on ``data``'s final
    values; None without such a law, without at least 3 conditions with all its inputs and D."""
    declared = result.declared.get("regression")
    if data is None or declared is None:
        return None
    law = declared.law
    # equilibrium pairs: the conditions' final values (a test's end is no equilibrium)
    usable = [c for c in data.conditions() if c in loaded.system.conditions and _complete(law, loaded, data, c)]
    if len(usable) < 3:  # two conditions leave one to adapt on: a line through one point says nothing
        return None
    subset = MeasurementSet([r for r in data.rows if r.condition in usable], data.source, data.equilibrium_min)
    train = result.sets["train"]
    return leave_one_condition_out(law, pairs_of(law, loaded, subset, series=False), subset,
                                   feature_scale(law, train.cycles, train.names), reference=train.reference)


def _complete(law: RegressionLaw, loaded: LoadedSystem, data: MeasurementSet, condition: str) -> bool:
    measured = {r.quantity for r in data.for_condition(condition)}
    ambient = loaded.system.room.ambient_sensor
    return ELONGATION_QUANTITY in measured and all(n in measured or (n == ambient and condition in loaded.system.conditions)
                                      for n in law.sensors)


def adaptation_block(adapted: dict[str, AdaptedLaw], data: MeasurementSet, loaded: LoadedSystem) -> dict:
    """compensation.json's ``adaptation``: per law its file, prior width, noise, and the residuals on
    the adaptation data before and after [µm] (in-sample: a fit's own data, not a held-out figure)."""
    laws = {}
    for kind, a in adapted.items():
        pairs = pairs_of(a.law, loaded, data)
        before = a.prior.bias + pairs.features @ a.prior.weights.ravel() - pairs.elongation
        after = a.law.bias + pairs.features @ a.law.weights.ravel() - pairs.elongation
        laws[kind] = {"file": ADAPTED_FILES[kind], "sensors": list(a.law.sensors), "samples": a.samples,
                      "conditions": list(dict.fromkeys(pairs.conditions)),
                      "prior_width_um": a.width * 1e6, "prior_width_at_search_edge": a.width_at_bound,
                      "noise_sigma_um": a.noise_sigma * 1e6, "log_evidence": a.log_evidence,
                      "in_sample_rms_before_um": _rms(before), "in_sample_rms_after_um": _rms(after)}
    return {"file": data.source, "laws": laws, "kalman": KALMAN_NOTE}


def _rms(values: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.square(values)))) * 1e6

