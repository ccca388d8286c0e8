"""One sampled point of an uncertainty study: its runs, wherever they execute.

A :class:`SampleRun` carries the variant description as data, and the model that runs it by
name (a model of the registry, :mod:`feedtherm.models.registry`: the fast one by default, and
its FE mesh for the models that take one); :func:`run_sample` (module level, so a Dask worker
imports it by name) runs its conditions with that model and the cycle-averaged motion in 60 s
steps, as calibration does (``CALIBRATION_OPTIONS``), and returns the series of the sensors [°C]
and D [µm] on a fixed grid and the final values.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...system.load import LoadedSystem
from ...system.runs import run_duration
from ..calibration import CALIBRATION_OPTIONS, CALIBRATION_STEP_S
from ..validation_types import ELONGATION_QUANTITY

#: Spacing of the bands' time grid [s]: the calibration runs' own sampling.
GRID_STEP_S = CALIBRATION_STEP_S


@dataclass(frozen=True)
class SampleRun:
    """The runs of one point: ``loaded`` (the variant) at each of ``conditions``."""

    loaded: LoadedSystem  # with the overlay its runs take
    conditions: tuple[str, ...]
    label: str  # "prior sample 17", "Sobol point 3", "calibrated nominal"
    values: tuple[tuple[str, float], ...] = ()  # the parameters' values at this point [SI or factor]
    model: str = "fast"  # the model of the registry that runs it
    mesh: str | None = None  # its FE mesh (None: the options' own)

    def describe(self) -> str:
        shown = ", ".join(f"{name}={value:.4g}" for name, value in self.values)
        return f"{self.label}" + (f" ({shown})" if shown else "")


@dataclass(frozen=True)
class SampleResult:
    """Per condition: the series on :func:`grid` (quantity -> (n_t,)) and the final values."""

    series: dict[str, dict[str, np.ndarray]]
    finals: dict[str, dict[str, float]]


def grid(duration_s: float) -> np.ndarray:
    """The bands' time grid of a run of ``duration_s`` [s]."""
    return np.arange(0.0, duration_s + 0.5 * GRID_STEP_S, GRID_STEP_S)


def run_sample(run: SampleRun) -> SampleResult:
    """Run every condition of ``run`` (a worker imports this by name)."""
    from ...simulate import simulate  # the model is loaded only when a batch really runs

    series, finals = {}, {}
    for condition in run.conditions:
        solution = simulate(run.loaded, condition=condition, model=run.model, mesh=run.mesh, motion="averaged",
                            options=CALIBRATION_OPTIONS, sample_interval=GRID_STEP_S,
                            allow_overload=True)  # a sampled machine is run as declared, overloaded or not
        times = grid(run_duration(run.loaded.system, condition))
        values = {name: np.interp(times, solution.times, s) for name, s in solution.sensors_celsius().items()}
        values[ELONGATION_QUANTITY] = np.interp(times, solution.times, solution.elongation_um)
        series[condition] = values
        finals[condition] = {k: float(v) for k, v in solution.summary_values("final").items()}
    return SampleResult(series, finals)
