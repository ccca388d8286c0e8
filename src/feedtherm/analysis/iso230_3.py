"""ISO 230-3 thermal tests evaluated from measured displacement series.

Every quantity here is a pure function of numpy arrays, in SI units: times [s], displacements
[m], temperatures [K].  A positive deviation or displacement points along +x, the sign of the
package's thermal positioning error E(x, t).

Thermal drift at a target
    The positioning deviation at a target position, measured again at every stop of a test
    (an interferometer's reading minus the commanded position), less the deviation at that
    target's first measurement.  The first reading includes the axis's geometric positioning
    error (the pitch error of the screw, the scale's error), which is there cold and is not
    thermal; what the heat does is change it.  So ISO 230-3 takes the drift relative to the
    first measurement, which is zero by construction and makes the drift's range include 0.
    Its figures are the drift of largest magnitude (signed) and when it occurred.

Thermal expansion of the axis
    The drift of the distance between the two outer targets of a linear-axis test: the last
    target's drift less the first's.  The table visits the targets one after another at each
    stop, so the two are never measured at the same instant; the first target's drift is
    interpolated linearly in time to the last target's measurement times, within the first
    target's measured span, and held at its first and last value for up to half its shortest
    interval beyond it: the other targets of the same stop.  Divided by the distance between the
    targets it is an apparent expansion per length [m/m], comparable to α ΔT of the screw.

Environmental temperature variation error (ETVE)
    With the machine idle and the room's air varying, the range (max − min) of a displacement
    over the test is the ETVE figure for that direction; the range of the air temperature over
    the same time, and their ratio [m/K], say how strongly the machine follows its room.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np


@dataclass(frozen=True, eq=False)
class TargetDrift:
    """The thermal drift at one target position of an ISO 230-3 test.

    Attributes
    ----------
    target : float
        The axis coordinate of the target [m].
    times : ndarray
        The target's measurement times [s], strictly increasing.
    deviation : ndarray
        The positioning deviation measured at each time [m], as given.
    drift : ndarray
        ``deviation - deviation[0]`` [m]: the change since the target's first measurement.
    largest : float
        The drift of largest magnitude [m], signed (the first such sample).
    time_of_largest : float
        When it occurred [s].
    """

    target: float
    times: np.ndarray
    deviation: np.ndarray
    drift: np.ndarray
    largest: float
    time_of_largest: float

    @property
    def range(self) -> float:
        """``max(drift) - min(drift)`` [m], which includes the first measurement's 0."""
        return float(np.max(self.drift) - np.min(self.drift))


@dataclass(frozen=True, eq=False)
class ExpansionDrift:
    """The drift of the distance between two targets: the thermal expansion of a linear axis.

    Attributes
    ----------
    first_target, last_target : float
        The two targets' coordinates [m], ``first_target < last_target``.
    times : ndarray
        The last target's measurement times within the first target's measured span [s].
    drift : ndarray
        The last target's drift less the first's (interpolated to ``times``) [m].
    largest : float
        The drift of largest magnitude [m], signed (the first such sample).
    time_of_largest : float
        When it occurred [s].
    """

    first_target: float
    last_target: float
    times: np.ndarray
    drift: np.ndarray
    largest: float
    time_of_largest: float

    @property
    def per_length(self) -> float:
        """``largest / (last_target - first_target)`` [m/m]."""
        return self.largest / (self.last_target - self.first_target)


@dataclass(frozen=True, eq=False)
class Etve:
    """The environmental temperature variation error of one displacement (ISO 230-3).

    Attributes
    ----------
    quantity : str
        The displacement's name, such as ``"D"`` or ``"E@150mm"``.
    range : float
        ``max - min`` of the displacement over the test [m]: the ETVE figure.
    time_of_max, time_of_min : float
        When the displacement was largest and smallest [s] (the first such samples).
    air_range : float
        ``max - min`` of the air temperature over the displacement's time span [K].
    sensitivity : float
        ``range / air_range`` [m/K], NaN when ``air_range`` is 0.
    """

    quantity: str
    range: float
    time_of_max: float
    time_of_min: float
    air_range: float
    sensitivity: float


def _series(what: str, times, values) -> tuple[np.ndarray, np.ndarray]:
    """``times`` and ``values`` as float arrays, checked: 1-D, equal lengths, at least one sample,
    finite, times strictly increasing."""
    t = np.asarray(times, dtype=float)
    v = np.asarray(values, dtype=float)
    if t.ndim != 1 or v.ndim != 1:
        raise ValueError(f"{what}: times and values must be 1-D, got shapes {t.shape} and {v.shape}")
    if len(t) != len(v):
        raise ValueError(f"{what}: {len(t)} times but {len(v)} values")
    if len(t) < 1:
        raise ValueError(f"{what}: no samples")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(v))):
        raise ValueError(f"{what}: the times and values must be finite")
    if np.any(np.diff(t) <= 0.0):
        raise ValueError(f"{what}: the times must be strictly increasing")
    return t, v


def _largest(times: np.ndarray, drift: np.ndarray) -> tuple[float, float]:
    """The drift of largest magnitude, signed, and its time (the first such sample)."""
    i = int(np.argmax(np.abs(drift)))
    return float(drift[i]), float(times[i])


def target_drift(target: float, times, deviation) -> TargetDrift:
    """The thermal drift at ``target`` [m] from its deviations [m] measured at ``times`` [s].

    Raises
    ------
    ValueError
        No sample, non-finite values, mismatched lengths or times not strictly increasing.
    """
    if not np.isfinite(target):
        raise ValueError(f"target {target!r}: the target coordinate must be finite")
    t, d = _series(f"target {float(target) * 1e3:g} mm", times, deviation)
    drift = d - d[0]
    largest, when = _largest(t, drift)
    return TargetDrift(float(target), t, d, drift, largest, when)


def expansion_drift(first: TargetDrift, last: TargetDrift, reach: float | None = None) -> ExpansionDrift:
    """The drift of the distance from ``first`` to ``last``: ``last.drift - first.drift``.

    Evaluated at ``last.times`` within ``[first.times[0] - reach, first.times[-1] + reach]``, the
    first target's drift interpolated linearly in time there and held beyond its ends.  ``reach``
    [s] defaults to half the first target's shortest interval between measurements (0 with one
    measurement): the last stop's other targets, never the next stop's.

    Raises
    ------
    ValueError
        The targets are not distinct and ordered (``first.target < last.target``), or none of
        the last target's times lies within the first target's measured span.
    """
    if not first.target < last.target:
        raise ValueError(f"the expansion needs two distinct targets in order, got first "
                         f"{first.target * 1e3:g} mm and last {last.target * 1e3:g} mm")
    if reach is None:
        reach = 0.5 * float(np.min(np.diff(first.times))) if len(first.times) > 1 else 0.0
    start, end = first.times[0] - reach, first.times[-1] + reach
    inside = (last.times >= start) & (last.times <= end)
    if not np.any(inside):
        raise ValueError(f"no measurement of the target at {last.target * 1e3:g} mm lies within "
                         f"{start:g}–{end:g} s, the span of the target at {first.target * 1e3:g} mm")
    t = last.times[inside]
    drift = last.drift[inside] - np.interp(t, first.times, first.drift)
    largest, when = _largest(t, drift)
    return ExpansionDrift(first.target, last.target, t, drift, largest, when)


def outer_targets(drifts: Sequence[TargetDrift]) -> ExpansionDrift | None:
    """The expansion drift between the smallest and the largest target, None for fewer than two."""
    if len(drifts) < 2:
        return None
    first = min(drifts, key=lambda d: d.target)
    last = max(drifts, key=lambda d: d.target)
    return expansion_drift(first, last)


def etve(quantity: str, times, displacement, air_times, air) -> Etve:
    """The ETVE of a displacement [m] measured at ``times`` [s], against the air [K] at ``air_times``.

    The air's range is taken over its samples within the displacement's time span
    ``[times[0], times[-1]]``, the test's.

    Raises
    ------
    ValueError
        Either series has no sample, non-finite values, mismatched lengths or times not
        strictly increasing; or no air sample lies within the displacement's span.
    """
    t, x = _series(f"ETVE {quantity}", times, displacement)
    ta, a = _series(f"ETVE {quantity} air", air_times, air)
    inside = (ta >= t[0]) & (ta <= t[-1])
    if not np.any(inside):
        raise ValueError(f"ETVE {quantity}: no air temperature lies within the test's {t[0]:g}–{t[-1]:g} s")
    a = a[inside]
    i_max, i_min = int(np.argmax(x)), int(np.argmin(x))
    span = float(x[i_max] - x[i_min])
    air_range = float(np.max(a) - np.min(a))
    sensitivity = span / air_range if air_range > 0.0 else float("nan")
    return Etve(quantity, span, float(t[i_max]), float(t[i_min]), air_range, sensitivity)
