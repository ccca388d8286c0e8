"""A law's conditioning: how much a small fixed error of one sensor costs in D.

A law that reads the difference of two nearly equal temperatures through two large weights of
opposite sign fits its training data and fails on a machine whose sensors are off by a tenth of a
kelvin.  Reported for every law (issue 34):

- ``offset_K``: per input, the offset its cost is priced at: the declared offset of its kind
  (:mod:`.noise`: a contact sensor 0.1 K, an infrared one 0.5 K by default, or the description's
  ``[compensation]`` values), :data:`OFFSET_K` for an input whose kind is not known;
- ``max_abs_weight_um_per_K``: the largest |weight| [µm/K] of a regression law (a reading's or a
  lag's);
- ``offset_error_um``: per sensor, the error [µm] its offset ``δ_s`` on that sensor alone causes.
  A static law: ``|w_s| · δ_s``.  A lagged law: a constant offset passes each first-order lag with
  gain 1, so at steady state the cost is ``|Σ_τ w_s,τ| · δ_s`` (the sum of the sensor's reading and
  lag weights; while the lags settle after an offset appears, up to ``Σ_τ |w_s,τ| · δ_s``, given as
  ``offset_transient_um``).  The Kalman estimator has no weights: its cost is found by running it
  on a test cycle with and without the offset, the largest |ΔD̂| over the cycle;
- ``within_limit``: every sensor's cost at most :data:`LIMIT_UM` (the issue's aim).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace

import numpy as np

#: The offset a sensor's cost is stated for where its kind's declared offset is not given [K]
#: (a contact sensor's default, :data:`.noise.DEFAULT_NOISE`).
OFFSET_K = 0.1
#: The cost the issue accepts for it [µm].
LIMIT_UM = 2.0


def input_offsets(sensors, offsets: Mapping[str, float] | None = None) -> np.ndarray:
    """Each of ``sensors``' offset [K]: its entry in ``offsets`` (name -> its kind's declared offset,
    :meth:`.noise.SensorNoise.offsets`), :data:`OFFSET_K` where it has none."""
    offsets = offsets or {}
    return np.array([float(offsets.get(s, OFFSET_K)) for s in sensors])


def regression_conditioning(law, offsets: Mapping[str, float] | None = None) -> dict:
    """The conditioning block of a :class:`.regression.RegressionLaw` (module notes); ``offsets``:
    each input's declared offset [K] (:func:`input_offsets`)."""
    w = np.atleast_2d(np.asarray(law.weights, dtype=float))
    delta = input_offsets(law.sensors, offsets)
    steady = np.abs(w.sum(axis=1)) * delta * 1e6
    transient = np.abs(w).sum(axis=1) * delta * 1e6
    worst = float(steady.max()) if steady.size else 0.0
    return {"max_abs_weight_um_per_K": float(np.abs(w).max() * 1e6) if w.size else 0.0,
            "offset_K": {s: float(v) for s, v in zip(law.sensors, delta)},
            "offset_error_um": {s: float(v) for s, v in zip(law.sensors, steady)},
            "offset_transient_um": {s: float(v) for s, v in zip(law.sensors, transient)},
            "max_offset_error_um": worst, "limit_um": LIMIT_UM, "within_limit": bool(worst <= LIMIT_UM),
            "ridge_K": float(np.sqrt(getattr(law, "ridge", 0.0))),
            "how": "|sum of a sensor's weights| x its kind's declared offset (offset_K): a constant offset passes "
                   "every lag with gain 1"}


def kalman_conditioning(law, record, names: list[str], offsets: Mapping[str, float] | None = None) -> dict:
    """The conditioning block of a :class:`.kalman.KalmanLaw`: the largest |ΔD̂| [µm] over ``record``
    (a cycle whose columns are ``names``) when one input (a sensor or the ambient) reads its declared
    offset (:func:`input_offsets`) high throughout."""
    inputs = list(dict.fromkeys((*law.sensors, law.model.ambient)))
    delta = dict(zip(inputs, input_offsets(inputs, offsets)))
    shifted = {}
    for name in inputs:
        readings = record.sensors.copy()
        readings[:, names.index(name)] += delta[name]
        shifted[name] = replace(record, sensors=readings)
    law.filter_records([record, *shifted.values()], names)  # the runs side by side
    base = law.predict_record(record, names)
    costs = {name: float(np.abs(law.predict_record(moved, names) - base).max() * 1e6)
             for name, moved in shifted.items()}
    worst = max(costs.values()) if costs else 0.0
    gains = [costs[name] / delta[name] for name in inputs if delta[name] > 0]
    return {"max_abs_gain_um_per_K": max(gains, default=0.0), "offset_K": {n: float(v) for n, v in delta.items()},
            "offset_error_um": costs, "max_offset_error_um": worst, "limit_um": LIMIT_UM,
            "within_limit": bool(worst <= LIMIT_UM), "cycle": record.label,
            "how": "the filter run on the cycle with and without one input's declared offset (offset_K); the largest "
                   "|change of D|"}
