"""Compensation judged as ISO 230-3 judges a machine: on the description's own drift tests.

For every declared test with measuring stops (system/thermal_tests.py) the nominal model runs
the test as declared (its duty, start and room), every candidate read through the study's noisy
sensors (:mod:`.noise`, a stream of its own).  At each stop the table stands at a target and the
interferometer would read the positioning error E there; each law asked for predicts it (a stroke
law at the target, a law of D its D at every x, the Kalman estimator its state along the stroke)
and the machine, corrected by minus the prediction, is left with the residual ``E − Ê``.  Its
drift since the target's first measurement (:mod:`..iso230_3`) is what an ISO 230-3 drift test
of the compensated axis would show, beside the uncompensated drift of E.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...models.options import ModelOptions
from ...simulate import simulate
from ...system.load import LoadedSystem
from ...system.runs import visited_targets
from ...system.schema import DutyCycle
from ..candidates import with_candidates
from ..iso230_3 import TargetDrift, target_drift
from ..transient_scores import positioning_at
from .data import CycleRecord, CycleSet, speeds_at
from .kalman import KalmanLaw
from .noise import noisy_set

#: The noise stream of the drift tests' readings (the study's sets use 0 to 3).
DRIFT_STREAM = 7
#: A stop's reading is taken this long before the table leaves the target [s] (an interferometer's
#: reading at the end of its hold).
READ_BEFORE_LEAVING_S = 1.0


@dataclass(frozen=True, eq=False)
class DriftJudgement:
    """One drift test: per target, the uncompensated drift of E and each law's residual drift [m]."""

    test: str
    uncompensated: list[TargetDrift]
    residual: dict[str, list[TargetDrift]]  # law kind -> per target

    def as_dict(self) -> dict:
        def figures(drifts: list[TargetDrift]) -> dict:
            return {f"{d.target * 1e3:g}": {"largest_um": d.largest * 1e6, "at_s": d.time_of_largest,
                                           "rms_um": float(np.sqrt(np.mean(d.drift[1:] ** 2)) * 1e6)
                                           if d.drift.size > 1 else 0.0} for d in drifts}

        return {"test": self.test, "uncompensated": figures(self.uncompensated),
                "residual": {kind: figures(drifts) for kind, drifts in self.residual.items()}}

    def worst(self, kind: str | None = None) -> float:
        """The largest |drift| [m] over the targets: of a law's residual, or uncompensated (None)."""
        drifts = self.uncompensated if kind is None else self.residual[kind]
        return max(abs(d.largest) for d in drifts)


def drift_tests(loaded: LoadedSystem) -> list[str]:
    """The description's tests that hold the table at target positions (measuring stops)."""
    return [name for name in loaded.system.tests if visited_targets(loaded.system, name)]


def judge_on_drift_tests(loaded: LoadedSystem, result, predictors: dict, noise, seed: int, model: str = "fast",
                         mesh: str | None = None) -> list[DriftJudgement]:
    """Every drift test of ``loaded`` (:func:`drift_tests`) with each law of ``predictors`` (law kind ->
    ``(law, record -> Ê at record.positions (n, p) [m] or D (n,))``); ``result`` the study's
    (:class:`~.study.StudyResult`, for its candidates), ``noise`` its :class:`~.noise.SensorNoise`."""
    described = with_candidates(loaded, result.candidates)
    names = list(result.candidates)
    out = []
    for index, test in enumerate(drift_tests(loaded)):
        run = simulate(described, test=test, model=model, mesh=mesh, motion="averaged", sample_interval=10.0,
                       options=ModelOptions(fields=False))
        record = _record(loaded, test, run, names)
        read = noisy_set(CycleSet(test, names, [record]), noise, seed, DRIFT_STREAM + index, one_machine=True).cycles[0]
        stops = _stop_times(loaded, test, run.times[-1])
        targets = record.positions
        uncompensated = [target_drift(x, stops[j], np.interp(stops[j], record.times, record.stroke_error[:, j]))
                         for j, x in enumerate(targets)]
        residual = {}
        for kind, (law, predict) in predictors.items():
            if isinstance(law, KalmanLaw):
                law.filter_records([read], names)
            predicted = np.asarray(predict(read), float)
            if predicted.ndim == 1:  # a law of D: the same correction at every x
                predicted = np.repeat(predicted[:, None], len(targets), axis=1)
            residual[kind] = [target_drift(x, stops[j], np.interp(stops[j], record.times,
                                                                  record.stroke_error[:, j] - predicted[:, j]))
                              for j, x in enumerate(targets)]
        out.append(DriftJudgement(test, uncompensated, residual))
    return out


def _record(loaded: LoadedSystem, test: str, run, names: list[str]) -> CycleRecord:
    """The test's run as a study's record, its positions the test's targets."""
    system = loaded.system
    targets = np.array(sorted(visited_targets(system, test)))
    cycle = system.duty_cycles[system.tests[test].cycle]
    timeline = DutyCycle.model_construct(segments=cycle.timeline(), duration=float(run.times[-1]))
    screw, nut = speeds_at(timeline, run.times)
    error = np.column_stack([positioning_at(run, x) * 1e-6 for x in targets])
    return CycleRecord(test, np.asarray(run.times, float), np.column_stack([run.sensors[n] for n in names]),
                       np.asarray(run.elongation, float), screw, nut, None, timeline, positions=targets,
                       stroke_error=error)


def _stop_times(loaded: LoadedSystem, test: str, end: float) -> list[np.ndarray]:
    """Per target (in increasing order), the instants [s] its readings are taken: the end of each hold."""
    system = loaded.system
    targets = sorted(visited_targets(system, test))
    timeline = system.duty_cycles[system.tests[test].cycle].timeline()
    ends = [s.start for s in timeline[1:]] + [end]
    times: dict[float, list[float]] = {x: [] for x in targets}
    for segment, stop in zip(timeline, ends):
        if segment.table_at is not None and segment.start < end:
            at = min(stop, end) - READ_BEFORE_LEAVING_S
            times[min(targets, key=lambda x: abs(x - segment.table_at))].append(at)
    return [np.array(times[x]) for x in targets]
