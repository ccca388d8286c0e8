"""Calibration: fit declared parameters to measured conditions, then predict the others.

The parameters, their kinds and bounds are declared in the description's ``[calibration]``
section.  The fit is bounded nonlinear least squares (scipy ``least_squares``, trust region
reflective) on residuals ``(simulated - measured) / sigma`` of the final values of the fitted
conditions, with ``sigma`` the declared temperature and elongation weights.  Where the
measurements state equilibrium times, the simulated time to 95 % of the steady rise is fitted
too (the transient information; weight ``equilibrium_sigma``).  Each model evaluation is a full
transient run with the cycle-averaged motion (60 s steps, see ``CALIBRATION_OPTIONS``) of the
model the caller chooses (``model``/``mesh``: a model of the registry,
:mod:`feedtherm.models.registry`; by default the fast one, whose runs are cheap enough for the
hundreds a fit takes).

Where a condition's measurements are time series (:mod:`.measurement_series`), every sample is a
residual instead of the final value: the run, in 10 s steps (``SERIES_OPTIONS``), interpolated
linearly to the measured times as ``validate`` does, minus the sample, over the sample's own
standard uncertainty where the file gives one, else over the declared weight of its kind.
Every sample is used, however long the series: the cost of a fit is in its runs (one per
condition and point, whatever the number of samples), not in the residuals.

Where a motor declares a continuous torque, the fit is held within it at every declared
condition (their speeds, not their measurements) by a penalty residual (:data:`DUTY_LIMIT`);
the cost and the standard errors are the data's.

Measured values that the consistency check (:mod:`feedtherm.analysis.consistency`) flags are
left out of the fit and kept in the tables with their reason.

What a calibration is worth is how it predicts conditions it was not fitted to: the result
carries a held-out table with 95 % prediction intervals (the parameter covariance carried
through the model's sensitivities, plus the measurement's own scatter), and
:func:`cross_validate` leaves each condition out in turn.

scipy.optimize is imported where a fit runs, and Student's t is scipy.special's ``stdtrit`` (the
function scipy.stats' ``t.ppf`` calls): the two packages take 0.1 s and 0.35 s to import, which
every command that reads this module (``validate``, ``compensate``, ``calibrate``) paid at its
start, a command refused on bad input too.
"""

from __future__ import annotations

import contextlib
import math
import re
import time
from dataclasses import dataclass, field
from typing import Callable, Mapping, Sequence

import numpy as np
from scipy.special import stdtrit

from ..boundary import boundary_conditions
from ..boundary.heat import motor_duties
from ..errors import ArgumentError, FeedthermError
from ..models.options import ModelOptions
from ..models.registry import model_entry
from ..simulate import prepare, simulate
from ..solution.equilibrium import rise_time
from ..system.load import LoadedSystem
from ..system.overlay import mode_of
from ..system.paths import expand_path, get_path
from ..system.quantities import to_base_si
from ..system.references import closest
from ..system.variants import with_values
from .consistency import ConsistencyReport
from .execution import Execution, TaskFailure, kept_open, run_ordered
from ..system.measurement_series import Series
from ..system.measurements import MeasurementSet
from ..system.runs import run_duration, run_names
from .transient_scores import TransientComparison, drift, simulated_series
from .validation_types import ELONGATION_QUANTITY

#: The equilibrium time among the predicted quantities: time to 95 % of the steady rise [min].
EQUILIBRIUM_QUANTITY = "t_eq"
#: Two-sided 95 % coverage factor of a normal distribution.
Z95 = 1.959964

#: Condition number of the Jacobian above which the fit cannot separate the parameters.
SINGULAR_CONDITION_NUMBER = 1e8
#: Correlation of two estimates beyond which the data determine only their combination.  The
#: condition number above is in the parameters' units, so two parameters that act through one
#: quantity (a thread's friction coefficient and its preload, through one torque) can stay below
#: it when their units differ little; their estimates' correlation is ±1 to within the forward
#: differences' second-order terms (1 − 5e-9 on the paper bench), whatever the units.
COLLINEAR_CORRELATION = 0.9999


@dataclass(frozen=True)
class FitParameter:
    name: str
    kind: str  # "value" or "scale"
    paths: list[str]  # concrete paths (wildcards expanded)
    originals: list[float]  # SI values at the paths before the fit
    lower: float
    upper: float

    @property
    def start(self) -> float:
        """The declared value, or, where that lies on or beyond a bound, a tenth of the range inside.

        A value declared at a bound (a still room's air speed, 0) may have no slope there
        (forced convection mixes in as u^(3/2)), and a fit started on it would never move.
        """
        x0 = self.originals[0] if self.kind == "value" else 1.0
        inset = 0.1 * (self.upper - self.lower)
        if x0 <= self.lower:
            return float(self.lower + inset)
        if x0 >= self.upper:
            return float(self.upper - inset)
        return float(x0)

    def values(self, x: float) -> dict[str, float]:
        """The description values this parameter sets when it equals ``x``."""
        if self.kind == "value":
            return {p: x for p in self.paths}
        return {p: o * x for p, o in zip(self.paths, self.originals)}


@dataclass(frozen=True)
class Prediction:
    condition: str
    quantity: str
    unit: str  # "C", "um" or "min"
    predicted: float
    measured: float
    interval: float | None = None  # half-width of the 95 % prediction interval
    flag: str = ""  # why the consistency check flags the measured value ("" if it does not)

    @property
    def deviation(self) -> float:
        return self.predicted - self.measured


@dataclass
class CalibrationResult:
    """What a calibration found: the fitted parameters, how well the data determine them, the
    fit's residuals, the predictions of the conditions it did not fit, and the calibrated
    description.

    Attributes
    ----------
    parameters : list of FitParameter
        The parameters fitted, with the description paths each sets and its bounds.
    fitted : ndarray
        The fitted value of each parameter, in SI units (a factor for a ``"scale"`` parameter).
    standard_errors : ndarray
        The standard error of each fitted value, in its unit.
    correlation : ndarray
        The fitted values' correlation matrix.
    identifiable : list of str
        Per parameter, ``""`` when the data determine it, else the reason they do not.
    at_bound : list of str
        Per parameter, ``"lower"`` or ``"upper"`` where the data push it against a declared bound,
        else ``""``.
    fit_conditions : list of str
        The conditions (or tests) fitted.
    residuals : list of Prediction
        The fitted conditions' values, simulated after the fit beside the measured ones.
    held_out : list of Prediction
        The measured conditions not fitted, predicted by the calibrated model, with their 95 %
        prediction intervals.
    cost : float
        Half the sum of the squared weighted residuals at the fitted values.
    model_runs : int
        The model runs the fit took.
    wall_time_s : float
        The fit's wall time [s].
    measurement_source : str
        Where the measurements came from.
    calibrated : LoadedSystem
        The description with the fitted values, to simulate.
    status : str
        The least-squares solver's message at its end.
    excluded : list of Prediction
        Measured values of the fitted conditions that the consistency check flags, left out of
        the fit (each with its flag).
    motor_duty : dict
        Condition -> motor -> its torque over its declared continuous torque at the fitted values.
    series_fit, series_held_out : list of TransientComparison
        The measured series of the fitted and of the held-out conditions against the calibrated runs.
    model, mesh : str
        The model the runs took and its FE mesh (``None``: the model takes none).
    """

    parameters: list[FitParameter]
    fitted: np.ndarray
    standard_errors: np.ndarray
    correlation: np.ndarray
    identifiable: list[str]  # "" when identifiable, else the reason
    at_bound: list[str]  # "lower", "upper" or "" per parameter: the data push past the declared range
    fit_conditions: list[str]
    residuals: list[Prediction]  # at the fitted conditions, after the fit
    held_out: list[Prediction]
    cost: float
    model_runs: int
    wall_time_s: float
    measurement_source: str
    calibrated: LoadedSystem
    status: str = ""
    excluded: list[Prediction] = field(default_factory=list)  # flagged values left out of the fit
    # condition -> motor -> torque over its declared continuous torque, at the fitted values (> 1:
    # the motor could not run there, so the fitted preloads are implausible)
    motor_duty: dict[str, dict[str, float]] = field(default_factory=dict)
    # the measured series of the fitted conditions against the calibrated runs (their samples were
    # the residuals), and those of the held-out conditions against their predictions
    series_fit: list[TransientComparison] = field(default_factory=list)
    series_held_out: list[TransientComparison] = field(default_factory=list)
    model: str = "fast"  # the model of the registry the runs took
    mesh: str | None = None  # its FE mesh (None: the model takes none, or the options' own)

    @property
    def series_conditions(self) -> list[str]:
        """The fitted conditions whose residuals were series samples."""
        return list(dict.fromkeys(s.condition for s in self.series_fit))

    def overloads(self) -> list[tuple[str, str, float]]:
        """(condition, motor, torque ratio) where the fitted machine needs more than a motor's rating."""
        return [(c, m, r) for c, motors in self.motor_duty.items() for m, r in motors.items() if r > 1.0]


# ---------------------------------------------------------------------------- parameters


def expand(loaded: LoadedSystem, path: str) -> list[str]:
    """Concrete paths for a path with ``[*]`` wildcards."""
    return expand_path(loaded.system, path)


def resolve_parameters(loaded: LoadedSystem, names: list[str]) -> list[FitParameter]:
    """The declared parameters ``names``; one-line errors for anything undeclared."""
    declared = loaded.system.calibration.parameters if loaded.system.calibration else {}
    out = []
    for name in names:
        if name not in declared:
            if re.search(r"[.\[]", name):
                raise ArgumentError("params", f"{name!r} has no declared bounds; declare it under "
                                              f"[calibration.parameters] with kind, paths and bounds")
            known = ", ".join(declared) or "none declared"
            raise ArgumentError("params", f"unknown parameter {name!r}{closest(name, declared)} (declared: {known})")
        spec = declared[name]
        paths = [p for path in spec.paths for p in expand(loaded, path)]
        try:
            originals = [float(get_path(loaded.system, p)) for p in paths]
        except (KeyError, IndexError, AttributeError, TypeError):
            raise FeedthermError(f"calibration.parameters.{name}.paths: a path does not name a value") from None
        try:
            lower, upper = (to_base_si(b) for b in spec.bounds)
        except ValueError as exc:
            raise FeedthermError(f"calibration.parameters.{name}.bounds: {exc}") from None
        if not lower < upper:
            raise FeedthermError(f"calibration.parameters.{name}.bounds: the lower bound must be below the upper")
        out.append(FitParameter(name, spec.kind, paths, originals, lower, upper))
    if not out:
        raise ArgumentError("params", "name at least one parameter")
    return out


def apply(loaded: LoadedSystem, parameters: list[FitParameter], x) -> LoadedSystem:
    changes: dict[str, float] = {}
    for p, value in zip(parameters, x):
        changes.update(p.values(float(value)))
    return with_values(loaded, changes, origin_suffix="calibrated")


# ---------------------------------------------------------------------------- model


#: Time stepping of calibration's runs: the cycle-averaged motion with 60 s steps and samples.
#: Their difference from the default 10 s steps is below 0.02 K, 0.05 µm and 1.5 min of
#: the equilibrium time on the paper's bench (tests/integration/test_calibration.py); six times
#: fewer steps make the hundreds of runs of a fit affordable.
CALIBRATION_STEP_S = 60.0
CALIBRATION_OPTIONS = ModelOptions(motion="averaged", averaged_step=CALIBRATION_STEP_S,
                                   max_step=CALIBRATION_STEP_S, fields=False)
#: Time stepping of the runs of conditions fitted as series.  Implicit Euler lags a transient by
#: about half a step: on ballscrew_example's v10 (tests/data/ballscrew_v10_series.csv) 60 s steps
#: differ from 10 s steps by up to 0.16 K and 1.0 µm within the first 20 min, as much as the
#: samples' own uncertainties (0.2 K, 1 µm), where the finals differ by hundredths.  10 s steps
#: are what ``validate`` scores a series with; a run costs 1.3 to 2.5 times a 60 s one.
SERIES_STEP_S = 10.0
SERIES_OPTIONS = ModelOptions(motion="averaged", averaged_step=SERIES_STEP_S, max_step=SERIES_STEP_S, fields=False)


def series_key(quantity: str) -> tuple[str, str]:
    """Where a run's values hold its series of ``quantity`` (a tuple, so that it cannot be taken
    for a quantity's name)."""
    return ("series", quantity)


#: Where a run's values hold the times [s] of its series.
SERIES_TIMES = ("series times",)


def _final_values(loaded: LoadedSystem, condition: str, series: Sequence[str] | None = None, *,
                  model: str = "fast", mesh: str | None = None) -> dict:
    """One condition's final values, its time to 95 % of the steady rise [min] and its series.

    Parameters
    ----------
    loaded : LoadedSystem
        The description (with the parameters applied) and the overlay it runs in.
    condition : str
        The condition to run over its duration.
    series : sequence of str, optional
        Measured quantities (sensors, or ``D_um``) whose series to return: the run is then
        stepped and sampled every :data:`SERIES_STEP_S`.  Without it the run takes 60 s steps and
        returns finals only.
    model : str
        The model of the registry that runs it (default ``"fast"``).
    mesh : {"coarse", "medium", "fine"}, optional
        The FE mesh of a model that takes one (``fem``, ``reduced``); None: the options' own
        (``ModelOptions.mesh``, coarse).

    Returns
    -------
    dict
        Quantity → final value (°C, µm), :data:`EQUILIBRIUM_QUANTITY` → minutes and, for each
        quantity of ``series``, ``series_key(quantity)`` → the run's series (°C, µm) at the times
        under :data:`SERIES_TIMES` [s].  The series stay on the run's own samples, so what a run
        returns and the cache holds grows with the run's duration, not with the number of
        measured samples; the fit interpolates them to the measured times.
    """
    step, options = (SERIES_STEP_S, SERIES_OPTIONS) if series else (CALIBRATION_STEP_S, CALIBRATION_OPTIONS)
    run = simulate(loaded, condition=condition, model=model, mesh=mesh, motion="averaged", options=options,
                   sample_interval=step, allow_overload=True)  # the fit reports overloads
    values: dict = {k: float(v) for k, v in run.summary_values("final").items()}
    initial = {name: float(trace[0]) for name, trace in run.sensors.items()}
    sensors = {n: v for n, v in run.cycle_sensors.items() if n in initial}
    values[EQUILIBRIUM_QUANTITY] = rise_time(run.cycle_times, sensors, initial, run.steady) / 60.0
    if series:
        values[SERIES_TIMES] = np.array(run.times, dtype=float)
        for quantity in series:
            values[series_key(quantity)] = np.array(simulated_series(run, quantity), dtype=float)
    return values


@dataclass(frozen=True)
class _CalibrationRun:
    """One run of a calibration request: a description with the parameters applied, a condition."""

    loaded: LoadedSystem  # with the overlay the fit runs in
    condition: str
    series: tuple[str, ...] = ()  # the measured quantities whose series the run returns
    model: str = "fast"  # the model of the registry that runs it
    mesh: str | None = None  # its FE mesh (None: the options' own)

    def describe(self) -> str:
        return f"condition {self.condition} of {self.loaded.origin}"


def _calibration_run(run: _CalibrationRun) -> dict:
    """One run, wherever it executes (a worker imports this by name)."""
    how = {"model": run.model, "mesh": run.mesh}
    if run.series:
        return _final_values(run.loaded, run.condition, run.series, **how)
    return _final_values(run.loaded, run.condition, **how)


def _value(result):
    """A run's values; a run that failed on a worker fails the calibration, as it would serially."""
    if isinstance(result, TaskFailure):
        raise FeedthermError(f"a calibration run failed: {result}")
    return result


class RunCache:
    """Final values of runs already made, by parameter values, condition and model (and mesh).

    A calibration evaluates the same points more than once: the prediction intervals start
    from the optimum the fit has just evaluated, and every leave-one-out fold starts from the
    first fit's optimum, where its values and sensitivities are known.  Pass one cache to
    :func:`calibrate` and :func:`cross_validate` of one system (and overlay) to run each point once.
    The runs are deterministic, so a cached value is the value the run would give.
    """

    def __init__(self) -> None:
        self._finals: dict[tuple, dict[str, float]] = {}

    def get(self, key: tuple) -> dict[str, float] | None:
        return self._finals.get(key)

    def put(self, key: tuple, finals: dict[str, float]) -> None:
        self._finals[key] = finals


#: Finite-difference step of the sensitivities, as a fraction of each parameter's range.  One
#: step serves the fit's Jacobian and the prediction intervals, so that the points of one are
#: reused by the other.  1 % (the intervals' step before) keeps the differences well above the
#: jitter the coupling tolerance leaves in the values (re-evaluations at 0.2 K thresholds).
SENSITIVITY_STEP = 0.01


class _Model:
    """Final values (and the time to 95 % of the steady rise) of conditions, counting the runs.

    ``execution`` says where the runs of one request go (:mod:`.execution`): serially, or side by
    side on a Dask cluster, which is started (or reached) at the first request that has more than
    one run and kept until the model is closed; pass one already kept open
    (:func:`~feedtherm.analysis.execution.kept_open`) to share it between calibrations.
    ``workers`` > 1 without ``execution`` is a local cluster of that many processes.  The values
    are the same wherever the runs go.  ``cache`` keeps every run's values for later requests of
    the same point.  ``series``: condition → the measured quantities whose series its runs also
    return (:func:`_final_values`, in 10 s steps); their cache keys name them, so a finals-only
    request never gets a series run's values, nor the reverse.  ``model``/``mesh``: the model of
    the registry the runs take (default the fast one) and its FE mesh; the cache keys name them
    too, so one cache never hands one model's values to another.
    """

    def __init__(self, loaded: LoadedSystem, parameters: list[FitParameter], workers: int = 1,
                 cache: RunCache | None = None, execution: Execution | None = None,
                 series: Mapping[str, Sequence[str]] | None = None, *, model: str = "fast",
                 mesh: str | None = None):
        self.loaded, self.parameters = loaded, parameters
        self.model, self.mesh = model, mesh
        self.series = {c: tuple(sorted(quantities)) for c, quantities in (series or {}).items() if quantities}
        self.runs = 0
        if execution is None:
            execution = Execution(workers=workers) if workers > 1 else Execution()
        self.execution = execution
        self.cache = cache if cache is not None else RunCache()
        self._open = contextlib.ExitStack()
        self._running: Execution | None = None

    def __enter__(self) -> "_Model":
        return self

    def __exit__(self, *exc) -> None:
        self._open.close()  # the cluster this model started, if any
        self._running = None

    def _key(self, x, condition: str) -> tuple:
        # 12 significant digits: a point that went through the fit's [0, 1] scaling and back
        # differs from itself in the last bit
        names = tuple(p.name for p in self.parameters)
        how = (mode_of(self.loaded), self.model, self.mesh)  # the overlay, the model and its mesh
        key = (how, condition, names, tuple(float(f"{float(v):.12g}") for v in x))
        quantities = self.series.get(condition)
        return key if quantities is None else (*key, quantities)  # a finals-only run keys as it always did

    def finals(self, x, conditions: list[str]) -> dict[str, dict[str, float]]:
        return self.finals_many([x], conditions)[0]

    def finals_many(self, points: list, conditions: list[str]) -> list[dict[str, dict[str, float]]]:
        """Values of every condition at every point; the runs not cached run side by side."""
        missing = [(i, c) for i, x in enumerate(points) for c in conditions
                   if self.cache.get(self._key(x, c)) is None]
        missing = list(dict.fromkeys(missing))
        if missing:
            variants = {i: apply(self.loaded, self.parameters, points[i]) for i in {i for i, _ in missing}}
            self.runs += len(missing)
            runs = [_CalibrationRun(variants[i], c, self.series.get(c, ()), self.model, self.mesh)
                    for i, c in missing]
            if self.execution.serial or len(runs) == 1:
                values = [_calibration_run(run) for run in runs]
            else:
                values = [_value(result) for _, result in
                          run_ordered(_calibration_run, runs, execution=self._cluster(),
                                      describe=_CalibrationRun.describe)]
            for (i, c), v in zip(missing, values):
                self.cache.put(self._key(points[i], c), v)
        return [{c: self.cache.get(self._key(x, c)) for c in conditions} for x in points]

    def _cluster(self) -> Execution:
        if self._running is None:
            self._running = self._open.enter_context(kept_open(self.execution))
        return self._running

    def sensitivities(self, x, lower, upper, conditions: list[str]):
        """Values at ``x`` and their forward differences per parameter, all runs side by side.

        The step is :data:`SENSITIVITY_STEP` of each range, towards the farther bound.
        Returns ``(base, steps, moved)``: the values at ``x``, the step per parameter and the
        values at each shifted point.
        """
        x = np.asarray(x, dtype=float)
        span = upper - lower
        steps, points = [], [x]
        for j in range(len(x)):
            h = SENSITIVITY_STEP * span[j] * (1.0 if x[j] + SENSITIVITY_STEP * span[j] <= upper[j] else -1.0)
            shifted = x.copy()
            shifted[j] += h
            steps.append(h)
            points.append(shifted)
        values = self.finals_many(points, conditions)
        return values[0], steps, values[1:]


@dataclass(frozen=True, eq=False)
class _Datum:
    """One fitted or predicted value: a measurement row, or a stated equilibrium time.

    ``measured`` is the final value (a series' last sample); ``series``, where the file gives
    one, holds every sample, and each of them is a residual of the fit.
    """

    condition: str
    quantity: str
    unit: str
    measured: float
    flag: str = ""
    series: Series | None = None
    since: float | None = None  # a drift's origin [s]: the series is the change since then (E at a target)


def _data(data: MeasurementSet, conditions: list[str], consistency: ConsistencyReport | None,
          equilibrium: bool) -> list[_Datum]:
    out = []
    for c in conditions:
        for r in data.for_condition(c):
            flag = consistency.flag_for(c, r.quantity) if consistency else None
            out.append(_Datum(c, r.quantity, r.unit, r.measured, flag.reason if flag else "", r.series))
        for r in data.positioning_of(c):  # E at each target, as its drift since its first measurement
            d = drift(r)
            out.append(_Datum(c, d.quantity, d.unit, d.measured, "", d.series, d.since))
        if equilibrium and c in data.equilibrium_min:
            out.append(_Datum(c, EQUILIBRIUM_QUANTITY, "min", data.equilibrium_min[c]))
    return out


def _simulated(values: dict, r: _Datum):
    """The run's counterpart of ``r``: its series interpolated linearly to the measured times
    (as ``validate`` scores a series), or its final value."""
    if r.series is None:
        return values[r.quantity]
    simulated = np.interp(r.series.times, values[SERIES_TIMES], values[series_key(r.quantity)])
    if r.since is not None:  # a drift: the run's change since the same instant
        simulated = simulated - np.interp(r.since, values[SERIES_TIMES], values[series_key(r.quantity)])
    return simulated


def _point(values: dict, r: _Datum) -> float:
    """The run's counterpart of ``r``'s final value: at a series' last sample time, or the run's final value."""
    if r.series is None:
        return values[r.quantity]
    return float(_simulated(values, r)[-1])


def _weights(loaded: LoadedSystem, r: _Datum) -> np.ndarray:
    """The standard uncertainty of each residual of ``r``: a sample's own where the file gives
    it, else the description's weight of its kind (:func:`_sigma`)."""
    if r.series is None:
        return np.array([_sigma(loaded, r.unit)])
    if r.series.uncertainties is not None:
        return np.asarray(r.series.uncertainties, dtype=float)
    return np.full(len(r.series.times), _sigma(loaded, r.unit))


def _point_sigma(loaded: LoadedSystem, r: _Datum) -> float:
    """The standard uncertainty of ``r``'s final value (a series' last sample's, where given)."""
    return float(_weights(loaded, r)[-1])


def _series_quantities(rows: list[_Datum]) -> dict[str, list[str]]:
    """Condition → the quantities measured as series among ``rows``."""
    out: dict[str, list[str]] = {}
    for r in rows:
        if r.series is not None:
            out.setdefault(r.condition, []).append(r.quantity)
    return out


def _check_series(loaded: LoadedSystem, rows: list[_Datum], source: str) -> None:
    """A series the fit cannot use fails before any run: one that outlasts its condition's run
    (interpolation would hold the run's last value), or a sample whose uncertainty is 0 (its
    residual would weigh infinitely)."""
    for r in rows:
        if r.series is None:
            continue
        duration = run_duration(loaded.system, r.condition)
        if r.series.times[-1] > duration * (1 + 1e-9):
            raise FeedthermError(f"{source}: {r.condition} {r.quantity}: the series ends at "
                                 f"{r.series.times[-1]:g} s, after the run ({duration:g} s)")
        at = r.series.zero_uncertainty_at()
        if at is not None:
            raise FeedthermError(f"{source}: condition {r.condition} {r.quantity}: the uncertainty at {at:g} s is 0, "
                                 "which would weigh its residual infinitely; give the standard uncertainty, or no "
                                 "uncertainty column (the description's calibration weights then apply)")


def _predictions(finals, rows: list[_Datum], intervals: dict | None = None) -> list[Prediction]:
    return [Prediction(r.condition, r.quantity, r.unit, _point(finals[r.condition], r), r.measured,
                       None if intervals is None else intervals.get((r.condition, r.quantity)), r.flag)
            for r in rows]


def _series_scores(finals, rows: list[_Datum]) -> list[TransientComparison]:
    """Every unflagged measured series among ``rows`` against the runs ``finals`` hold."""
    return [TransientComparison(r.condition, r.quantity, r.unit, r.series.times, r.series.values,
                                np.asarray(_simulated(finals[r.condition], r)), r.series.uncertainties)
            for r in rows if r.series is not None and not r.flag]


def _sigma(loaded: LoadedSystem, unit: str) -> float:
    cal = loaded.system.calibration
    if unit == "um":
        return (cal.elongation_sigma if cal else 2e-6) * 1e6
    if unit == "min":
        return (cal.equilibrium_sigma if cal else 600.0) / 60.0
    return cal.temperature_sigma if cal else 0.5


# ---------------------------------------------------------------------------- fit


def calibrate(loaded: LoadedSystem, data: MeasurementSet, fit: list[str], names: list[str], *,
              progress: Callable[[float], None] | None = None,
              consistency: ConsistencyReport | None = None, equilibrium: bool = True,
              start: np.ndarray | None = None, workers: int = 1, cache: RunCache | None = None,
              execution: Execution | None = None, model: str = "fast",
              mesh: str | None = None) -> CalibrationResult:
    """Fit the parameters ``names`` to the conditions ``fit``; predict every other condition.

    ``consistency``: values it flags are left out of the fit (and reported with their reason).
    ``equilibrium``: also fit the stated equilibrium times of the fitted conditions.
    Where ``data`` holds time series, every sample of a fitted condition's series is a residual,
    over its own uncertainty where the file gives one (see the module's docstring); the result's
    ``series_fit`` and ``series_held_out`` score each series against its run.
    ``start``: the parameter values to start from (default: the description's, clipped to the bounds).
    ``execution``: where the runs of one evaluation go, side by side (:mod:`.execution`; serial by
    default; pass one kept open, :func:`~feedtherm.analysis.execution.kept_open`, to start a
    cluster once for many calibrations); ``workers`` > 1 without it: a local cluster of that many
    processes for this calibration.  The numbers are the same either way.
    ``cache``: runs already made (shared with a later :func:`cross_validate`).
    ``model``: the model of the registry every run takes (default the fast one; an unknown name
    fails before any run), ``mesh`` its FE mesh (``fem``, ``reduced``; None: the options' own).
    The runs take the overlay ``loaded`` carries (:func:`feedtherm.plan.with_mode`).
    """
    started = time.perf_counter()
    model_entry(model)  # an unknown model fails before any run
    prepare(loaded.system, model, mesh)
    measured = data.runs()
    missing = [c for c in fit if c not in measured]
    if missing:
        raise ArgumentError("fit", f"no measurements for {', '.join(missing)} in {data.source} "
                                   f"(measured: {', '.join(measured)})")
    runs = run_names(loaded.system)
    unknown = [c for c in fit if c not in runs]
    if unknown:
        raise ArgumentError("fit", f"no condition or test {', '.join(unknown)} in {loaded.origin}")
    parameters = resolve_parameters(loaded, names)
    fitted_data = _data(data, fit, consistency, equilibrium)
    rows = [r for r in fitted_data if not r.flag]
    held_out = [c for c in measured if c not in fit and c in runs]
    every = _data(data, list(fit) + held_out, consistency, equilibrium)
    _check_series(loaded, every, data.source)
    # one residual per final value, and one per sample of a series
    sigma = np.concatenate([_weights(loaded, r) for r in rows]) if rows else np.zeros(0)
    target = np.concatenate([np.atleast_1d(r.series.values if r.series is not None else r.measured)
                             for r in rows]) if rows else np.zeros(0)
    if len(target) < len(parameters):
        raise ArgumentError("fit", f"{len(target)} measured values cannot determine {len(parameters)} parameters")
    with _Model(loaded, parameters, workers, cache, execution, series=_series_quantities(every), model=model,
                mesh=mesh) as runner:
        lower = np.array([p.lower for p in parameters])
        upper = np.array([p.upper for p in parameters])
        span = upper - lower

        # every condition the machine ran, fitted or not: its motors carried them all
        duty = _DutyPenalty(loaded, parameters, list(loaded.system.conditions))

        def values(finals) -> np.ndarray:
            simulated = np.concatenate([np.atleast_1d(_simulated(finals[r.condition], r)) for r in rows])
            return (simulated - target) / sigma

        def report_progress() -> None:
            if progress is not None:
                progress(min(0.9, runner.runs / (len(fit) * (len(parameters) + 1) * 8)))

        def residuals(u):  # u: parameters scaled to [0, 1] within their bounds
            x = lower + u * span
            out = np.concatenate([values(runner.finals(x, fit)), duty(x)])
            report_progress()
            return out

        def jacobian(u):  # the same forward differences as the prediction intervals', in u
            x = lower + u * span
            base, steps, moved = runner.sensitivities(x, lower, upper, fit)
            report_progress()
            f0 = np.concatenate([values(base), duty(x)])
            columns = []
            for j, (m, h, s) in enumerate(zip(moved, steps, span)):
                shifted = x.copy()
                shifted[j] += h
                columns.append((np.concatenate([values(m), duty(shifted)]) - f0) / (h / s))
            return np.column_stack(columns)

        x_start = np.array([p.start for p in parameters]) if start is None else np.clip(start, lower, upper)
        u = (x_start - lower) / span
        jac = jacobian(u)
        from scipy.optimize import least_squares  # imported where a fit runs (module notes)

        for _ in range(MAX_FIT_ROUNDS):
            result = least_squares(residuals, u, jac=_Broyden(residuals, u, jac), bounds=(0.0, 1.0), x_scale=1.0,
                                   xtol=XTOL, ftol=FTOL)
            u, jac = result.x, jacobian(result.x)
            if _converged(jac, result.fun, u):
                break
        x = lower + u * span
        n = len(target)  # the data's residuals; the motors' duty penalties follow them
        se, corr, identifiable, cov, s2, dof = _uncertainty(jac[:n] / span[None, :], result.fun[:n], x, n,
                                                            [p.name for p in parameters])
        # scipy's trust-region reflective fit keeps its iterates strictly inside the bounds, so a
        # parameter the data push against one ends a little inside it: its active mask marks it
        # (within XTOL of the scaled range, 0.1 %)
        active = result.active_mask
        at_bound = ["lower" if ui <= 1e-6 or a < 0 else "upper" if ui >= 1 - 1e-6 or a > 0 else ""
                    for ui, a in zip(u, active)]
        finals, intervals = _prediction_intervals(runner, x, lower, upper, every, cov, s2, dof, loaded)
        calibrated = apply(loaded, parameters, x)
        if progress is not None:
            progress(1.0)
        fitted_rows = [r for r in every if r.condition in fit]
        return CalibrationResult(
            parameters=parameters, fitted=x, standard_errors=se, correlation=corr, identifiable=identifiable,
            at_bound=at_bound, fit_conditions=list(fit),
            residuals=_predictions(finals, [r for r in fitted_rows if not r.flag], intervals),
            held_out=_predictions(finals, [r for r in every if r.condition not in fit], intervals),
            cost=0.5 * float(result.fun[:n] @ result.fun[:n]), model_runs=runner.runs,
            wall_time_s=time.perf_counter() - started,
            measurement_source=data.source, calibrated=calibrated, status=result.message,
            excluded=_predictions(finals, [r for r in fitted_rows if r.flag], intervals),
            motor_duty=motor_duty(calibrated),
            series_fit=_series_scores(finals, fitted_rows),
            series_held_out=_series_scores(finals, [r for r in every if r.condition not in fit]),
            model=model, mesh=mesh,
        )


#: The fit keeps every motor within its rated continuous torque at every declared condition: a
#: motor's duty above ``DUTY_LIMIT`` adds the residual (duty - DUTY_LIMIT) / ``DUTY_SIGMA`` (an
#: exterior penalty, Nocedal & Wright 2006, §17.1).  A 1 % overload adds (0.015 / 0.0005)² = 900
#: to the sum of squares, as much as 36 data missed by five sigma each; the penalty starts 0.5 %
#: below the rating so that the point where it balances the data stays within the rating.
DUTY_LIMIT, DUTY_SIGMA = 0.995, 0.0005


class _DutyPenalty:
    """The motors' duty penalties at a parameter point (see :data:`DUTY_LIMIT`): one residual per
    condition and motor with a declared continuous torque; none under an overlay, whose heats are
    printed values, not a mechanism.  The conditions' speeds are all it needs of them, so a
    held-out condition constrains the fit without its measurements entering it."""

    def __init__(self, loaded: LoadedSystem, parameters: list[FitParameter], conditions: list[str]):
        self.loaded, self.parameters = loaded, parameters
        self.conditions = conditions if loaded.overlay is None else []
        self.motors = sorted(motor_duties(boundary_conditions(loaded.system, conditions[0]).heats)) \
            if self.conditions else []

    def __call__(self, x) -> np.ndarray:
        if not self.motors:
            return np.zeros(0)
        system = apply(self.loaded, self.parameters, x).system
        out = []
        for condition in self.conditions:
            duties = motor_duties(boundary_conditions(system, condition).heats)
            out.extend(max(0.0, duties[m] - DUTY_LIMIT) / DUTY_SIGMA for m in self.motors)
        return np.array(out)


def motor_duty(loaded: LoadedSystem) -> dict[str, dict[str, float]]:
    """Each condition's motors' torque over their declared continuous torque (those that declare
    one); none under an overlay, whose printed heats carry no torques."""
    if loaded.overlay is not None:
        return {}
    duties = {condition: motor_duties(boundary_conditions(loaded.system, condition).heats)
              for condition in loaded.system.conditions}
    return {condition: ratios for condition, ratios in duties.items() if ratios}


#: Tolerances of the fit, on the parameters scaled to [0, 1] and on the relative cost reduction.
#: On the paper's bench a cost tolerance of 1e-3 instead of 1e-4 moves the held-out and
#: leave-one-out predictions by under 0.01 K, 0.1 µm and 0.1 min, with a fifth fewer runs
#: (benchmarks/README.md).
XTOL, FTOL = 1e-3, 1e-3
#: Rounds of least squares, each ended by a full finite-difference Jacobian (see :class:`_Broyden`).
MAX_FIT_ROUNDS = 4


class _Broyden:
    """The fit's Jacobian: finite differences where a round starts, Broyden's updates after.

    A forward-difference Jacobian costs one run per parameter and condition; a least-squares
    step costs one run per condition.  Within a round the Jacobian is updated from the steps
    the fit takes anyway (Broyden's rank-one secant update, Dennis & Schnabel 1996, §8.1), and
    each round ends with a finite-difference Jacobian at the point reached: it is the one the
    covariance and the prediction intervals use, and :func:`_converged` checks on it that the
    point is a minimum; if not, a new round starts there.
    """

    def __init__(self, residuals: Callable, u0: np.ndarray, jac0: np.ndarray):
        self.residuals = residuals
        self.u, self.f, self.jac = np.array(u0, dtype=float), residuals(u0), np.array(jac0, dtype=float)

    def __call__(self, u) -> np.ndarray:
        u = np.asarray(u, dtype=float)
        du = u - self.u
        if np.any(du != 0.0):
            f = self.residuals(u)  # evaluated by the fit already: a cached run
            self.jac = self.jac + np.outer(f - self.f - self.jac @ du, du) / float(du @ du)
            self.u, self.f = u.copy(), f
        return self.jac.copy()


def _converged(jac: np.ndarray, fun: np.ndarray, u: np.ndarray) -> bool:
    """Whether the bounded Gauss-Newton step from ``u`` with the exact Jacobian is negligible.

    The step solves min |J·d + f| with 0 ≤ u + d ≤ 1 (scipy ``lsq_linear``); it is negligible
    when it moves no scaled parameter by more than ``XTOL`` or promises a cost reduction below
    ``FTOL`` of the cost, the tolerances ``least_squares`` stops on.
    """
    from scipy.optimize import lsq_linear

    step = lsq_linear(jac, -fun, bounds=(-u, 1.0 - u)).x
    cost = 0.5 * float(fun @ fun)
    predicted = cost - 0.5 * float(np.sum((jac @ step + fun) ** 2))
    return float(np.max(np.abs(step), initial=0.0)) <= XTOL or predicted <= FTOL * cost


def _prediction_intervals(model: _Model, x, lower, upper, rows: list[_Datum], cov: np.ndarray, s2: float, dof: int,
                          loaded: LoadedSystem):
    """Values at ``x`` of every condition in ``rows`` and the 95 % half-width of each.

    Var = g·Cov·gᵀ + s²·σ²: ``g`` the value's sensitivity to the parameters (one-sided
    differences of :data:`SENSITIVITY_STEP` of each range, away from the nearer bound), ``Cov`` the parameter
    covariance of the fit, ``σ`` the declared weight of a measurement of that kind (a series' last
    sample's own uncertainty where the file gives one; the value is then the run at that sample's
    time) and ``s²``
    the residual variance per degree of freedom (1 when none is left), and the coverage factor
    Student's t with those degrees of freedom (s² is itself estimated from few residuals): the
    interval a new measurement at that condition should fall in if the model's misfit is like
    the fit's.
    """
    conditions = list(dict.fromkeys(r.condition for r in rows))
    base, steps, moved = model.sensitivities(x, lower, upper, conditions)
    coverage = float(stdtrit(dof, 0.975)) if dof > 0 else Z95  # Student's t quantile (module notes)
    intervals = {}
    for r in rows:
        c = r.condition
        g = np.array([(_point(m[c], r) - _point(base[c], r)) / h for m, h in zip(moved, steps)])
        variance = float(g @ cov @ g) + s2 * _point_sigma(loaded, r) ** 2
        intervals[(c, r.quantity)] = coverage * math.sqrt(max(variance, 0.0))
    return base, intervals


def _uncertainty(jac: np.ndarray, fun: np.ndarray, x: np.ndarray, m: int, names: list[str] | None = None):
    """Standard errors, correlation and identifiability from the Jacobian at the optimum, and
    the covariance, residual variance and degrees of freedom they come from.

    cov = s² (JᵀJ)⁻¹ with s² = Σr² / (m − n), the residual variance of the weighted fit
    (1 when there are no degrees of freedom left).
    """
    n = len(x)
    dof = m - n
    s2 = float(fun @ fun) / dof if dof > 0 else 1.0
    singular = np.linalg.svd(jac, compute_uv=False)
    cond = singular[0] / singular[-1] if singular[-1] > 0 else math.inf
    cov = s2 * np.linalg.pinv(jac.T @ jac)
    se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(se, se)
    corr = np.nan_to_num(corr)
    reasons = []
    for i in range(n):
        if cond > SINGULAR_CONDITION_NUMBER or not np.isfinite(cond):
            reasons.append(f"not identifiable: near-singular Jacobian (condition number {cond:.2g})")
        elif (partner := _collinear_with(corr, i)) is not None:
            other = names[partner] if names is not None else f"parameter {partner + 1}"
            reasons.append(f"not identifiable: the data fix only its combination with {other} "
                           f"(correlation {corr[i, partner]:+.6f})")
        elif se[i] > abs(x[i]):
            reasons.append("not identifiable: standard error larger than the value")
        elif singular[-1] == 0 or np.all(jac[:, i] == 0):
            reasons.append("not identifiable: the measurements do not depend on it")
        else:
            reasons.append("")
    return se, corr, reasons, cov, s2, dof


def _collinear_with(corr: np.ndarray, i: int) -> int | None:
    """The parameter whose estimate is correlated with parameter i's beyond :data:`COLLINEAR_CORRELATION`."""
    others = [j for j in range(len(corr)) if j != i and abs(corr[i, j]) > COLLINEAR_CORRELATION]
    return max(others, key=lambda j: abs(corr[i, j])) if others else None


def cross_validate(loaded: LoadedSystem, data: MeasurementSet, names: list[str], *,
                   progress: Callable[[float], None] | None = None, consistency: ConsistencyReport | None = None,
                   equilibrium: bool = True, start: np.ndarray | None = None,
                   workers: int = 1, cache: RunCache | None = None,
                   execution: Execution | None = None, model: str = "fast",
                   mesh: str | None = None) -> list[tuple[str, CalibrationResult]]:
    """Leave each measured condition out in turn: fit on the rest, predict the one left out.

    ``start``: where every fold's fit starts (a fit on all the conditions is a good start:
    a fold differs from it by one condition's data).  ``cache``: pass the first fit's, so the
    folds reuse its values and sensitivities at their common start.  ``model``/``mesh``: the
    model every fold's runs take (:func:`calibrate`).
    """
    model_entry(model)  # an unknown model fails before any run
    cache = cache if cache is not None else RunCache()
    if execution is None:
        execution = Execution(workers=workers) if workers > 1 else Execution()
    runs = run_names(loaded.system)
    conditions = [c for c in data.runs() if c in runs]
    out = []
    with kept_open(execution) as running:  # one cluster for every fold
        for i, left_out in enumerate(conditions):
            fit = [c for c in conditions if c != left_out]
            out.append((left_out, calibrate(loaded, data, fit, names, consistency=consistency,
                                            equilibrium=equilibrium, start=start, cache=cache, execution=running,
                                            model=model, mesh=mesh)))
            if progress is not None:
                progress((i + 1) / len(conditions))
    return out


__all__ = ["calibrate", "cross_validate", "RunCache", "resolve_parameters", "CalibrationResult", "Prediction", "ELONGATION_QUANTITY",
           "EQUILIBRIUM_QUANTITY"]
