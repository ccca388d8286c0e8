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

**The error along the stroke** (``law_stroke*.json``, ``version = 2``, ``kind =
"linear_regression_stroke"``): the law gives the positioning error E [m] at a table position x [m]
inside the stroke declared in its ``position`` block; each input's reading and lags get ``order + 1``
weights over Legendre polynomials of ``ξ = 2 (x - x_min)/(x_max - x_min) - 1``::

    law = CompensationLaw.from_file("law_stroke.json")
    for t, readings, x in stream:                  # x: where the table is [m]
        correction = -law.update(t, readings, x)   # E(x) [m]; the axis at x moves by -E(x)
        elsewhere = law.at(0.2)                    # E at another x from the same readings

An x outside the stroke, or not finite, raises ValueError naming x.  A law of D (version 1) takes
no x: D is the same at every position.  The ``controller_cost`` block counts the multiply-adds per
sample.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

FORMAT = "feedtherm-compensation-law"
#: Laws of D (one number): version 1, unchanged since the first release.
VERSION = 1
#: Laws of E(x, t) along the stroke (kind ``linear_regression_stroke``).
STROKE_VERSION = 2
KINDS = {"linear_regression": (VERSION, STROKE_VERSION), "linear_regression_stroke": (STROKE_VERSION,)}


class CompensationLaw:
    """A linear-regression law read from its document; :meth:`update` gives D [m] (a law of D) or
    E(x) [m] (a stroke law) reading by reading."""

    def __init__(self, document: dict):
        if document.get("format") != FORMAT or document.get("version") not in (VERSION, STROKE_VERSION):
            raise ValueError(f"not a {FORMAT} document of version {VERSION} or {STROKE_VERSION}")
        kind = document.get("kind")
        if kind not in KINDS:
            raise ValueError(f"cannot evaluate a law of kind {kind!r}")
        if document["version"] not in KINDS[kind]:
            raise ValueError(f"a law of kind {kind!r} needs version {KINDS[kind][0]}")
        self.inputs = [item["name"] for item in document["inputs"]]
        self.lags = [float(tau) for tau in document["lags_s"]]
        self.stroke = kind == "linear_regression_stroke"
        if self.stroke:
            position = document["position"]
            self.x_min, self.x_max = float(position["x_min_m"]), float(position["x_max_m"])
            if not (math.isfinite(self.x_min) and math.isfinite(self.x_max) and self.x_max > self.x_min):
                raise ValueError("position: x_max_m must be finite and above x_min_m")
            if document["basis"]["kind"] != "legendre":
                raise ValueError(f"cannot evaluate a basis of kind {document['basis']['kind']!r}")
            self.order = int(document["basis"]["order"])
            self.bias_coefficients = [float(b) for b in document["bias_m"]]
            # per input, per feature (reading, lags), per basis order [m/K]
            self.weight_blocks = [[[float(w) for w in row] for row in block] for block in document["weights_m_per_K"]]
            q = self.order + 1
            if len(self.bias_coefficients) != q or len(self.weight_blocks) != len(self.inputs) or any(
                    len(block) != 1 + len(self.lags) or any(len(row) != q for row in block)
                    for block in self.weight_blocks):
                raise ValueError("weights_m_per_K must be inputs x (1 + len(lags_s)) x (order + 1) and bias_m "
                                 "have order + 1 entries")
            self.posterior = None
        else:
            self.bias = float(document["bias_m"])
            self.weights = [[float(w) for w in row] for row in document["weights_m_per_K"]]
            if len(self.weights) != len(self.inputs) or any(len(row) != 1 + len(self.lags) for row in self.weights):
                raise ValueError("weights_m_per_K must have one row per input and 1 + len(lags_s) columns")
            self.posterior = _posterior(document.get("posterior"), len(self.inputs) * (1 + len(self.lags)))
        self.reset()

    @classmethod
    def from_file(cls, path: str | Path) -> "CompensationLaw":
        """The law of the file ``path``.  Inside feedtherm the file is checked first
        (:func:`feedtherm.analysis.compensation.law_files.read_law_document`: a one-line
        ``FeedthermError`` naming the key and the reason for anything that is not a law); this
        module copied beside a controller's code reads it with the standard library alone."""
        try:
            from .law_files import read_law_document
        except ImportError:  # the standalone copy: no package around it
            return cls(json.loads(Path(path).read_text(encoding="utf-8")))
        return cls(read_law_document(path)[0])

    def reset(self) -> None:
        """Forget the past readings (the next one restarts the lags)."""
        self._time: float | None = None
        self._lagged: list[list[float]] = []
        self._coefficients: list[float] | None = None

    def update(self, time: float, readings: dict[str, float], x: float | None = None) -> float:
        """After the readings [K] taken at ``time`` [s] (times must increase): D [m] for a law of D
        (``x`` not given), E(x) [m] at the table position ``x`` [m] for a stroke law."""
        if not self.stroke:
            if x is not None:
                raise ValueError("x: this law predicts D, the same at every table position; call update(time, readings)")
            return self._step(time, readings)[0]
        xi = self._xi(x)  # checked before the state moves
        self._step(time, readings)
        return self._at(xi)

    def at(self, x: float) -> float:
        """E(x) [m] at the table position ``x`` [m] from the last readings (a stroke law, after an update)."""
        if not self.stroke:
            raise ValueError("x: this law predicts D, the same at every table position")
        if self._coefficients is None:
            raise ValueError("no readings yet: call update() first")
        return self._at(self._xi(x))

    def _xi(self, x) -> float:
        """The normalised position ξ of ``x`` [m]; ValueError naming x when x is missing, not finite or outside the stroke."""
        if x is None:
            raise ValueError("x: a stroke law needs the table position x [m]")
        x = table_position(x, self.x_min, self.x_max)
        return min(1.0, max(-1.0, 2.0 * (x - self.x_min) / (self.x_max - self.x_min) - 1.0))

    def _at(self, xi: float) -> float:
        """Σ_m P_m(ξ) c_m with the Legendre recurrence (m P_m = (2m - 1) ξ P_{m-1} - (m - 1) P_{m-2})."""
        total, previous, current = 0.0, 0.0, 1.0
        for m, c in enumerate(self._coefficients):
            if m == 1:
                previous, current = current, xi
            elif m > 1:
                previous, current = current, ((2 * m - 1) * xi * current - (m - 1) * previous) / m
            total += c * current
        return total

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
        if self.stroke:
            coefficients = list(self.bias_coefficients)
            for block, value, state in zip(self.weight_blocks, values, self._lagged):
                for row, feature in zip(block, [value, *state]):
                    for m, w in enumerate(row):
                        coefficients[m] += w * feature
            self._coefficients = coefficients
            return float("nan"), []
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


def table_position(x, x_min: float, x_max: float) -> float:
    """``x`` [m] as a float inside the stroke [x_min, x_max] (to 1 nm).

    Raises
    ------
    ValueError
        One line naming x: not a number, not finite, or outside the stroke.
    """
    try:
        x = float(x)
    except (TypeError, ValueError):
        raise ValueError(f"x: {x!r} is not a table position in metres") from None
    if not math.isfinite(x):
        raise ValueError(f"x: {x} is not a finite table position [m]")
    if not x_min - 1e-9 <= x <= x_max + 1e-9:
        raise ValueError(f"x: {x:.6g} m is outside the stroke, [{x_min:.6g}, {x_max:.6g}] m")
    return x


def evaluate(document: dict, times, readings: dict[str, list[float]], x=None) -> list:
    """The law's output at every time of a recorded stream: ``readings[name][n]`` [K] at ``times[n]`` [s].

    A law of D: D [m] per time (no ``x``).  A stroke law: ``x`` [m] a table position (E(x) [m] per
    time) or a list of them (per time, the list of E at each x).
    """
    law = CompensationLaw(document)
    if not law.stroke or x is None or not isinstance(x, (list, tuple)):
        return [law.update(t, {name: readings[name][n] for name in law.inputs}, x) for n, t in enumerate(times)]
    positions = [float(v) for v in x]
    for v in positions:
        law._xi(v)  # every x checked before any reading
    out = []
    for n, t in enumerate(times):
        law.update(t, {name: readings[name][n] for name in law.inputs}, positions[0] if positions else None)
        out.append([law.at(v) for v in positions])
    return out


def evaluate_with_sd(document: dict, times, readings: dict[str, list[float]]) -> list[tuple[float, float]]:
    """(D [m], predictive sd [m]) at every time of a recorded stream, for an adapted law's document."""
    law = CompensationLaw(document)
    return [law.update_with_sd(t, {name: readings[name][n] for name in law.inputs}) for n, t in enumerate(times)]
