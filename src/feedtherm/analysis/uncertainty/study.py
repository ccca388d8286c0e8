"""An uncertainty study: prediction bands and Sobol' indices from the declared uncertainties.

For each state of knowledge (the declared priors; after a calibration, its posterior and the
priors it left, or the priors updated with measured finals, :mod:`.update`), ``samples``
scrambled Sobol' points of the unit hypercube are mapped through the parameters' inverse
distribution functions (:mod:`.sampling`; the update's through its posterior), and every point's variant of the
description runs every condition with the chosen model (``model``/``mesh``, a model of the
registry: by default the fast one; cycle-averaged motion, 60 s steps, as calibration runs).
The bands are the 5 %, 50 % and 95 % quantiles over the points, at each time of a 60 s grid and
of the final values, beside the run at the declared values and the measurements.  After a
Bayesian update a third set, "predictive", widens the updated finals' bands by the model error
N(0, s²σ²) the update measured (:mod:`.predictive`): the band a measured value is expected in,
where the calibrated set's is the model's prediction alone.
For one condition (default I), Saltelli's scheme gives the Sobol' indices of the final values
under the priors (:mod:`.sobol`).

Every run goes through the execution layer (:func:`~feedtherm.analysis.execution.run_ordered`),
serial or on a Dask cluster, with identical results.  A band needs all its points: if a run
fails, the study fails with one line naming the point and its parameter values (after the
batch, so every failure is counted).
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import Callable

import numpy as np

from ...errors import FeedthermError
from ...models.registry import model_entry
from ...simulate import prepare
from ...system.load import LoadedSystem
from ...system.overlay import mode_of
from ..consistency import ConsistencyReport
from ..execution import Execution, TaskFailure, run_ordered
from ...system.measurements import MeasurementSet
from ...system.runs import run_duration, run_names
from ..validation_types import ELONGATION_QUANTITY
from .declared import resolve_uncertainties, variant
from .posterior import Posterior
from .predictive import predictive_quantiles
from .runs import GRID_STEP_S, SampleResult, SampleRun, run_sample
from .sampling import to_values, unit_points
from .sobol import saltelli_points, sobol_indices
from .types import BAND, Band, FinalBand, SobolIndex, UncertainParameter, UncertaintySet, UncertaintyStudy
from .update import BayesianUpdate

#: Default points of the bands (a power of 2), and of Saltelli's base.
DEFAULT_SAMPLES = 128
DEFAULT_SOBOL_BASE = 64
#: The quantiles of a band: its lower edge, the median, its upper edge.
QUANTILES = (BAND[0], 0.5, BAND[1])


def run_uncertainty(loaded: LoadedSystem, *, samples: int = DEFAULT_SAMPLES, sobol_base: int | None = DEFAULT_SOBOL_BASE,
                    seed: int = 0, sobol_condition: str | None = None,
                    data: MeasurementSet | None = None, consistency: ConsistencyReport | None = None,
                    posterior: Posterior | BayesianUpdate | None = None, execution: Execution = Execution(),
                    progress: Callable[[float], None] | None = None,
                    conditions: list[str] | None = None, model: str = "fast",
                    mesh: str | None = None) -> UncertaintyStudy:
    """Bands of every condition (``conditions``, default all) under the priors and, with
    ``posterior``, after calibration (a calibration folder's :class:`~.posterior.Posterior`, or
    the declared priors updated with measurements, :class:`~.update.BayesianUpdate`; the set is
    labelled "calibrated" either way); Sobol' indices at ``sobol_condition`` (``sobol_base``
    None: none).

    ``data``/``consistency``: the measurements the final values are judged against, with the
    consistency check's flags.  ``model``/``mesh``: the model of the registry every run takes
    (default the fast one) and its FE mesh (``fem``, ``reduced``; None: the options' own); the
    settings record both.  Raises :class:`~feedtherm.errors.FeedthermError` (one line)
    for a system without declared uncertainties, an unknown condition or model, a sample count
    that is not a power of 2, or a failed run.
    """
    started = time.perf_counter()
    model_entry(model)  # an unknown model fails before any run
    prepare(loaded.system, model, mesh)
    prior = resolve_uncertainties(loaded)
    conditions = list(loaded.system.conditions) if conditions is None else list(conditions)
    if sobol_condition is None:
        sobol_condition = next(iter(loaded.system.conditions))
    runs = run_names(loaded.system)  # a test is run as declared: its start, its room
    for c in conditions + ([sobol_condition] if sobol_base is not None else []):
        if c not in runs:
            raise FeedthermError(f"--condition: no condition or test {c!r} in {loaded.origin}; conditions: "
                                 f"{', '.join(loaded.system.conditions)}"
                                 + (f"; tests: {', '.join(loaded.system.tests)}" if loaded.system.tests else ""))
    # (label, the description the values apply to, the nominal run's, the parameters, their sampler)
    states = [("prior", loaded, loaded, prior, lambda u: to_values(prior, u))]
    if posterior is not None:
        states.append(("calibrated", posterior.loaded, posterior.nominal, posterior.parameters, posterior.values))
    items: list[SampleRun] = []
    slices = {}
    for label, base, nominal, parameters, sampler in states:
        points = sampler(unit_points(samples, len(parameters), seed))
        start = len(items)
        items.append(SampleRun(nominal, tuple(conditions), f"{label} nominal", model=model, mesh=mesh))
        items.extend(_point(base, parameters, x, tuple(conditions), f"{label} sample {i}", model, mesh)
                     for i, x in enumerate(points))
        slices[label] = (start, len(items))
    sobol_points = None
    if sobol_base is not None:
        unit = saltelli_points([p.name for p in prior], sobol_base, seed)
        sobol_points = to_values(prior, unit)
        start = len(items)
        items.extend(_point(loaded, prior, x, (sobol_condition,), f"Sobol point {i}", model, mesh)
                     for i, x in enumerate(sobol_points))
        slices["sobol"] = (start, len(items))
    results = _run_all(items, execution, progress)
    sets = []
    for label, _, _, parameters, _ in states:
        a, b = slices[label]
        sets.append(_set(label, parameters, results[a], results[a + 1:b], conditions, data, consistency))
    if sobol_points is not None:
        a, b = slices["sobol"]
        sets[0].sobol_condition = sobol_condition
        sets[0].sobol = _indices(prior, [r.finals[sobol_condition] for r in results[a:b]], seed)
    if posterior is not None:
        sets[1].calibration = posterior.summary
    if isinstance(posterior, BayesianUpdate):
        a, b = slices["calibrated"]
        sets.append(_predictive(sets[1], results[a + 1:b], posterior.model_error(), posterior.fit.s2))
    settings = {
        "samples": samples, "seed": seed, "sampler": "scrambled Sobol' points (scipy.stats.qmc), inverse CDFs",
        "sobol_base": sobol_base, "sobol_runs": 0 if sobol_points is None else len(sobol_points),
        "sobol_scheme": None if sobol_points is None else "Saltelli 2010 (SALib), first-order and total, no second order",
        "model": model, "mesh": mesh, "motion": "averaged", "time_step_s": GRID_STEP_S, "mode": mode_of(loaded),
        "conditions": conditions, "ambient_sensor": loaded.system.room.ambient_sensor,
        "duration_s": {c: run_duration(loaded.system, c) for c in conditions},
        "band": list(BAND), "execution": execution.describe(),
        "runs": sum(len(item.conditions) for item in items),
        "failures": "a band needs every sampled point: a failed run fails the study",
        "wall_time_s": time.perf_counter() - started,
    }
    return UncertaintyStudy(system=loaded.origin, settings=settings, sets=sets)


def _point(base: LoadedSystem, parameters: list[UncertainParameter], x, conditions, label, model: str = "fast",
           mesh: str | None = None) -> SampleRun:
    values = tuple((p.name, float(v)) for p, v in zip(parameters, x))
    return SampleRun(variant(base, parameters, x, label), conditions, label, values, model, mesh)


def _run_all(items: list[SampleRun], execution: Execution, progress) -> list[SampleResult]:
    results, failures = [], []
    for _, result in run_ordered(run_sample, items, execution=execution, describe=SampleRun.describe,
                                 progress=progress):
        (failures if isinstance(result, TaskFailure) else results).append(result)
    if failures:
        more = f" (and {len(failures) - 1} more)" if len(failures) > 1 else ""
        raise FeedthermError(f"{len(failures)} of {len(items)} sampled points failed, and a band needs them all; "
                             f"the first: {failures[0]}{more}")
    return results


def quantile_bands(values: np.ndarray) -> np.ndarray:
    """The 5 %, 50 % and 95 % quantiles over the samples (axis 0) of ``values``."""
    return np.quantile(np.asarray(values, dtype=float), QUANTILES, axis=0)


def _set(label, parameters, nominal: SampleResult, samples: list[SampleResult], conditions, data, consistency) -> UncertaintySet:
    bands, finals = {}, []
    for c in conditions:
        quantities = list(nominal.series[c])
        bands[c] = Band(time_s=np.arange(len(nominal.series[c][quantities[0]])) * GRID_STEP_S,
                        quantiles={q: quantile_bands([s.series[c][q] for s in samples]) for q in quantities},
                        nominal={q: nominal.series[c][q] for q in quantities})
        measured = {r.quantity: r.measured for r in data.for_condition(c)} if data is not None else {}
        for q in quantities:
            p05, p50, p95 = quantile_bands([s.finals[c][q] for s in samples])
            flag = consistency.flag_for(c, q) if consistency is not None else None
            finals.append(FinalBand(c, q, "um" if q == ELONGATION_QUANTITY else "C", float(p05), float(p50),
                                    float(p95), nominal.finals[c][q], measured.get(q), flag.reason if flag else ""))
    return UncertaintySet(label=label, parameters=list(parameters), bands=bands, finals=finals,
                          runs=(len(samples) + 1) * len(conditions))


def _predictive(updated: UncertaintySet, samples: list[SampleResult], error_sd: dict[str, float],
                s2: float) -> UncertaintySet:
    """The updated set's final values with the model error added: each fitted quantity's band is
    the 5–95 % of the posterior predictive mixture (:func:`.predictive.predictive_quantiles`).

    A quantity the update did not fit (the ambient, the condition's input) keeps its band.
    There are no bands over time: s² is measured on the final values only, and how the misfit
    grows from zero at the start is not known.
    """
    finals = []
    for f in updated.finals:
        sd = error_sd.get(f.quantity)
        if sd is None:
            finals.append(f)
            continue
        p05, p50, p95 = predictive_quantiles([s.finals[f.condition][f.quantity] for s in samples], sd, QUANTILES)
        finals.append(replace(f, p05=float(p05), p50=float(p50), p95=float(p95)))
    return UncertaintySet(label="predictive", parameters=updated.parameters, bands={}, finals=finals, runs=0,
                          model_error={"noise_scale_s2": s2, "sd": error_sd})


def _indices(parameters: list[UncertainParameter], finals: list[dict[str, float]], seed: int) -> list[SobolIndex]:
    out = []
    names = [p.name for p in parameters]
    for q in finals[0]:
        y = np.array([f[q] for f in finals])
        if np.ptp(y) == 0.0:
            continue  # the ambient sensor: nothing to apportion
        found = sobol_indices(names, y, seed)
        out.extend(SobolIndex(q, name, float(found["S1"][j]), float(found["S1_conf"][j]), float(found["ST"][j]),
                              float(found["ST_conf"][j])) for j, name in enumerate(names))
    return out
