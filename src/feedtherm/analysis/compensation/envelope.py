"""The training envelope of a law: the readings and the rates it was fitted on, and the samples outside.

A regression law is an interpolation: fitted on readings within some range and changing at
some rates, it has no evidence beyond them.  :func:`training_envelope` records, for each of a
law's inputs, the smallest and largest reading of its training cycles and the fastest change
over :data:`RATE_WINDOW_S`; the law's file carries it (``envelope``), and ``feedtherm correct``
flags every logged sample whose reading or rate lies outside it (:func:`envelope_flags`), naming
the input and by how much.  A flag is a warning to look, not a refusal: the law still gives its
number.
"""

from __future__ import annotations

import numpy as np

#: The span over which a rate is taken [s]: the training's sample interval (a study samples every
#: 60 s), so that a log sampled more often does not read its sensors' noise as rates.
RATE_WINDOW_S = 60.0


def training_envelope(times_and_readings, sensors, window: float = RATE_WINDOW_S) -> dict:
    """The envelope of ``sensors`` over the training cycles ``times_and_readings``: an iterable of
    ``(times [s], readings (n, k) [K])`` whose columns are ``sensors``.  JSON-able (kelvin, K/s)."""
    lo = np.full(len(sensors), np.inf)
    hi = np.full(len(sensors), -np.inf)
    rate = np.zeros(len(sensors))
    for times, readings in times_and_readings:
        readings = np.atleast_2d(np.asarray(readings, float).T).T
        lo = np.minimum(lo, readings.min(axis=0))
        hi = np.maximum(hi, readings.max(axis=0))
        rate = np.maximum(rate, np.max(np.abs(windowed_rates(np.asarray(times, float), readings, window)), axis=0))
    return {"inputs": {name: {"min_K": float(a), "max_K": float(b), "max_rate_K_per_s": float(r)}
                       for name, a, b, r in zip(sensors, lo, hi, rate)},
            "rate_window_s": float(window),
            "meaning": "the readings and rates of the law's training cycles: a reading outside min_K..max_K, or a "
                       "change faster than max_rate_K_per_s over rate_window_s, lies where the law has no evidence"}


def windowed_rates(times: np.ndarray, readings: np.ndarray, window: float) -> np.ndarray:
    """Each sample's rate [K/s]: the change since the latest sample at least ``window`` [s] before it (0
    for the samples of the first window), per column of ``readings`` ``(n, k)``."""
    readings = np.atleast_2d(np.asarray(readings, float).T).T
    out = np.zeros_like(readings)
    # a sample never pairs with itself: a window below the times' rounding (5e-324 s) would divide 0 by 0
    earlier = np.minimum(np.searchsorted(times, times - window, side="right") - 1, np.arange(len(times)) - 1)
    has = earlier >= 0
    j = np.flatnonzero(has)
    if j.size:
        i = earlier[has]
        out[j] = (readings[j] - readings[i]) / (times[j] - times[i])[:, None]
    return out


def envelope_flags(envelope: dict, times: np.ndarray, columns: dict[str, np.ndarray]) -> list[str]:
    """Per sample, why it lies outside the law's training ``envelope`` (:func:`training_envelope`), or an
    empty string: each input whose reading [K] or rate leaves it, by how much."""
    times = np.asarray(times, float)
    reasons = [[] for _ in times]
    window = float(envelope["rate_window_s"])
    for name, values in columns.items():
        entry = envelope["inputs"][name]
        values = np.asarray(values, float)
        rates = windowed_rates(times, values[:, None], window)[:, 0]
        for j, (v, r) in enumerate(zip(values, rates)):
            if v < entry["min_K"]:
                reasons[j].append(f"{name} {entry['min_K'] - v:.2g} K below its training range")
            elif v > entry["max_K"]:
                reasons[j].append(f"{name} {v - entry['max_K']:.2g} K above its training range")
            if abs(r) > entry["max_rate_K_per_s"]:
                reasons[j].append(f"{name} changing at {abs(r) * 60.0:.2g} K/min, faster than its training's "
                                  f"{entry['max_rate_K_per_s'] * 60.0:.2g} K/min")
    return ["; ".join(r) for r in reasons]
