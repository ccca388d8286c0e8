"""A law's conditioning: how much a small fixed error of one sensor costs in D.

A law that reads the difference of two nearly equal temperatures through two large weights of
opposite sign fits its training data and fails on a machine whose sensors are off by a tenth of a
kelvin.  Reported for every law (issue 34):

- ``max_abs_weight_um_per_K``: the largest |weight| [µm/K] of a regression law (a reading's or a
  lag's);
- ``offset_error_um``: per sensor, the error [µm] a constant offset of :data:`OFFSET_K` on that
  sensor alone causes.  A static law: ``|w_s| · 0.1 K``.  A lagged law: a constant offset passes
  each first-order lag with gain 1, so at steady state the cost is ``|Σ_τ w_s,τ| · 0.1 K``
  (the sum of the sensor's reading and lag weights; while the lags settle after an offset appears,
  up to ``Σ_τ |w_s,τ| · 0.1 K``, given as ``offset_transient_um``).  The Kalman estimator has no
  weights: its cost is found by running it on a test cycle with and without the offset, the largest
  |ΔD̂| over the cycle;
- ``within_limit``: every sensor's cost at most :data:`LIMIT_UM` (the issue's aim).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

#: The offset a sensor's cost is stated for [K].
OFFSET_K = 0.1
#: The cost the issue accepts for it [µm].
LIMIT_UM = 2.0


def regression_conditioning(law) -> dict:
    """The conditioning block of a :class:`.regression.RegressionLaw` (module notes)."""
    w = np.atleast_2d(np.asarray(law.weights, dtype=float))
    steady = np.abs(w.sum(axis=1)) * OFFSET_K * 1e6
    transient = np.abs(w).sum(axis=1) * OFFSET_K * 1e6
    worst = float(steady.max()) if steady.size else 0.0
    return {"max_abs_weight_um_per_K": float(np.abs(w).max() * 1e6) if w.size else 0.0,
            "offset_K": OFFSET_K,
            "offset_error_um": {s: float(v) for s, v in zip(law.sensors, steady)},
            "offset_transient_um": {s: float(v) for s, v in zip(law.sensors, transient)},
            "max_offset_error_um": worst, "limit_um": LIMIT_UM, "within_limit": bool(worst <= LIMIT_UM),
            "ridge_K": float(np.sqrt(getattr(law, "ridge", 0.0))),
            "how": "|sum of a sensor's weights| x 0.1 K: a constant offset passes every lag with gain 1"}


def kalman_conditioning(law, record, names: list[str]) -> dict:
    """The conditioning block of a :class:`.kalman.KalmanLaw`: the largest |ΔD̂| [µm] over ``record``
    (a cycle whose columns are ``names``) when one input (a sensor or the ambient) reads
    :data:`OFFSET_K` high throughout."""
    shifted = {}
    for name in dict.fromkeys((*law.sensors, law.model.ambient)):
        readings = record.sensors.copy()
        readings[:, names.index(name)] += OFFSET_K
        shifted[name] = replace(record, sensors=readings)
    law.filter_records([record, *shifted.values()], names)  # the runs side by side
    base = law.predict_record(record, names)
    costs = {name: float(np.abs(law.predict_record(moved, names) - base).max() * 1e6)
             for name, moved in shifted.items()}
    worst = max(costs.values()) if costs else 0.0
    return {"max_abs_gain_um_per_K": worst / OFFSET_K, "offset_K": OFFSET_K, "offset_error_um": costs,
            "max_offset_error_um": worst, "limit_um": LIMIT_UM, "within_limit": bool(worst <= LIMIT_UM),
            "cycle": record.label,
            "how": "the filter run on the cycle with and without 0.1 K on one input; the largest |change of D|"}
