"""Evaluate an exported compensation law on a stream of readings, as a controller would.

This module needs nothing but the standard library: copy it beside a controller's code, load
the law's JSON file (:func:`~feedtherm.analysis.compensation.law.law_document` writes it) and
feed it readings as they arrive::

    law = CompensationLaw.from_file("law.json")
    for t, readings in stream:                 # readings: {sensor: 301.2, ...} in kelvin
        correction = -law.update(t, readings)  # D [m]; the axis moves by -D

The document (``format = "feedtherm-compensation-law"``, ``version = 1``) holds the inputs'
names and units, the bias [m], the weights [m/K] of each input and of its first-order lags, and
the lags' time constants [s].  A lag starts settled at the first reading and then follows
``L = a L + (1 - a) T`` with ``a = exp(-Δt/τ)`` at each reading, Δt the time since the previous one.

A law adapted to measurements (``feedtherm compensate --adapt``, ``law_adapted*.json``) carries a
``posterior`` block as well: the features' centre ``m`` [K], the covariance ``Σ`` of (the law's D at
the centre [m], the weights [m/K]) and the noise ``σ`` [m] of a measured D;
:meth:`CompensationLaw.update_with_sd` then gives D and its predictive standard deviation
``sqrt(φᵀ Σ φ + σ²)`` with ``φ = [1, features − m]`` (features: each input's reading, then its lags)::

    law = CompensationLaw.from_file("law_adapted.json")
    D, sd = law.update_with_sd(t, readings)   # [m], [m]
"""

from __future__ import annotations

import json
import math
from pathlib import Path

FORMAT = "feedtherm-compensation-law"
VERSION = 1


class CompensationLaw:
    """A linear-regression law read from its document; :meth:`update` gives D [m] reading by reading."""

    def __init__(self, document: dict):
        if document.get("format") != FORMAT or document.get("version") != VERSION:
            raise ValueError(f"not a {FORMAT} document of version {VERSION}")
        if document.get("kind") != "linear_regression":
            raise ValueError(f"cannot evaluate a law of kind {document.get('kind')!r}")
        self.inputs = [item["name"] for item in document["inputs"]]
        self.lags = [float(tau) for tau in document["lags_s"]]
        self.bias = float(document["bias_m"])
        self.weights = [[float(w) for w in row] for row in document["weights_m_per_K"]]
        if len(self.weights) != len(self.inputs) or any(len(row) != 1 + len(self.lags) for row in self.weights):
            raise ValueError("weights_m_per_K must have one row per input and 1 + len(lags_s) columns")
        self.posterior = _posterior(document.get("posterior"), len(self.inputs) * (1 + len(self.lags)))
        self.reset()

    @classmethod
    def from_file(cls, path: str | Path) -> "CompensationLaw":
        return cls(json.loads(Path(path).read_text(encoding="utf-8")))

    def reset(self) -> None:
        """Forget the past readings (the next one restarts the lags)."""
        self._time: float | None = None
        self._lagged: list[list[float]] = []

    def update(self, time: float, readings: dict[str, float]) -> float:
        """D [m] after the readings [K] taken at ``time`` [s] (times must increase)."""
        return self._step(time, readings)[0]

    def update_with_sd(self, time: float, readings: dict[str, float]) -> tuple[float, float]:
        """D [m] and its predictive standard deviation [m] after the readings [K] taken at ``time`` [s];
        only for an adapted law (a document with a ``posterior`` block)."""
        if self.posterior is None:
            raise ValueError("this law has no posterior block (only law_adapted*.json has); use update()")
        total, row = self._step(time, readings)
        centre, covariance, noise = self.posterior
        phi = [1.0] + [f - c for f, c in zip(row, centre)]
        variance = sum(phi[i] * covariance[i][j] * phi[j] for i in range(len(phi)) for j in range(len(phi)))
        return total, math.sqrt(max(variance, 0.0) + noise ** 2)

    def _step(self, time: float, readings: dict[str, float]) -> tuple[float, list[float]]:
        """D [m] and the features (per input: reading, then lags) [K] after one reading."""
        values = [float(readings[name]) for name in self.inputs]
        if self._time is None:
            self._lagged = [[v] * len(self.lags) for v in values]
        else:
            dt = float(time) - self._time
            if not dt > 0:
                raise ValueError(f"readings must come in increasing time, got {time} after {self._time}")
            for state, value in zip(self._lagged, values):
                for i, tau in enumerate(self.lags):
                    a = math.exp(-dt / tau)
                    state[i] = a * state[i] + (1.0 - a) * value
        self._time = float(time)
        total, features = self.bias, []
        for row, value, state in zip(self.weights, values, self._lagged):
            total += row[0] * value + sum(w * s for w, s in zip(row[1:], state))
            features += [value, *state]
        return total, features


def _posterior(block: dict | None, n_features: int):
    """(centre [K], covariance, noise σ [m]) of a ``posterior`` block, checked; None without one."""
    if block is None:
        return None
    centre = [float(c) for c in block["centre_K"]]
    covariance = [[float(v) for v in row] for row in block["covariance"]]
    if len(centre) != n_features or len(covariance) != n_features + 1 or \
            any(len(row) != n_features + 1 for row in covariance):
        raise ValueError(f"posterior: centre_K must have {n_features} entries and covariance "
                         f"{n_features + 1} x {n_features + 1}")
    return centre, covariance, float(block["noise_sigma_m"])


def evaluate(document: dict, times, readings: dict[str, list[float]]) -> list[float]:
    """D [m] at every time of a recorded stream: ``readings[name][n]`` [K] at ``times[n]`` [s]."""
    law = CompensationLaw(document)
    return [law.update(t, {name: readings[name][n] for name in law.inputs}) for n, t in enumerate(times)]


def evaluate_with_sd(document: dict, times, readings: dict[str, list[float]]) -> list[tuple[float, float]]:
    """(D [m], predictive sd [m]) at every time of a recorded stream, for an adapted law's document."""
    law = CompensationLaw(document)
    return [law.update_with_sd(t, {name: readings[name][n] for name in law.inputs}) for n, t in enumerate(times)]
