"""The room's air over a run: a measured series, and boundary conditions at another air temperature.

A test whose room is measured (system/thermal_tests.py) runs in the air its log gives: the
integrator moves the sinks of the surfaces that exchange heat with the air to the logged
temperature at every time step, while the surfaces' coefficients stay those of the run's
boundary conditions (taken at the log's mean).  A coefficient's dependence on the air temperature
is that of the air's properties, about 0.3 % per kelvin; the sink's is the whole driving
difference.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..system.schema import FeedSystem


@dataclass(frozen=True, eq=False)
class RoomAir:
    """The air temperature [K] at times [s], linear between samples and held beyond the first and last."""

    times: np.ndarray
    values: np.ndarray

    def __post_init__(self) -> None:
        times, values = np.asarray(self.times, dtype=float), np.asarray(self.values, dtype=float)
        if times.ndim != 1 or times.shape != values.shape or times.size == 0:
            raise ValueError("a room's air needs one value per time, at one time at least")
        if times.size > 1 and not np.all(np.diff(times) > 0):
            raise ValueError("the room's air times must increase")
        if not (np.all(np.isfinite(times)) and np.all(np.isfinite(values))):
            raise ValueError("the room's air must be finite")
        object.__setattr__(self, "times", times)
        object.__setattr__(self, "values", values)

    def at(self, t):
        """The air temperature [K] at ``t`` [s] (a float or an array)."""
        value = np.interp(t, self.times, self.values)
        return float(value) if np.ndim(value) == 0 else value

    def mean(self, t0: float, t1: float) -> float:
        """The time-mean air temperature [K] over [t0, t1] (exact for the piecewise-linear air)."""
        if t1 <= t0:
            return self.at(t0)
        inner = self.times[(self.times > t0) & (self.times < t1)]
        knots = np.concatenate([[t0], inner, [t1]])
        values = self.at(knots)
        return float(np.sum(0.5 * (values[1:] + values[:-1]) * np.diff(knots)) / (t1 - t0))


def air_surfaces(system: FeedSystem) -> list[str]:
    """The surfaces that exchange heat with the room's air (not with a sink of their own)."""
    return [name for name, surface in system.surfaces.items() if surface.sink_temperature is None]


def at_air(bc, system: FeedSystem, air: float):
    """``bc`` with the room's air at ``air`` [K]: the operating point's ambient and every air surface's sink
    moved there, every coefficient and heat as in ``bc``."""
    shift = air - bc.point.ambient
    if shift == 0.0:
        return bc
    surfaces = dict(bc.surfaces)
    for name in air_surfaces(system):
        if name in surfaces:
            surfaces[name] = replace(surfaces[name], sink=surfaces[name].sink + shift)
    return replace(bc, point=replace(bc.point, ambient=air), surfaces=surfaces)
