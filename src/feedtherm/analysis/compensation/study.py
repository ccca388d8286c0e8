"""A compensation study: cycles, sensor selection for K = 1 … 6, laws judged on held-out machines.

:func:`parse_sensors` checks ``--sensors`` (a count K, or names of candidates) before anything
runs; :func:`run_study` simulates the three sets of cycles (:mod:`.data`), reads them through
noisy sensors (:mod:`.noise`: every set, each candidate with its kind's noise and offset),
chooses sensors greedily for the static and the lagged regression with the ridge chosen on the
validation cycles (:mod:`.selection`), fits the law asked for, the law on the description's own
sensors for comparison, judges each on the test cycles (:mod:`.metrics`) and states each law's
conditioning (:mod:`.conditioning`).  Along the stroke (:mod:`.stroke`): for the two regression
laws asked for, a law of E(x, t) on the same sensors, its basis order and ridge chosen on the
validation cycles, judged on the test cycles over positions and time beside every law of D applied
at every x (the Kalman estimator's included: it stays a law of D).  On the description's drift
tests (:mod:`.drift_judge`): each law asked for, the residual drift at each target.  Out of range
(:data:`~.data.OUT_OF_RANGE`): each law asked for, and the best with at most 3 sensors, judged on
each case's cycles apart, as a law of D and along the stroke (:func:`out_of_range`).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field, replace

from ...boundary.operating import OperatingPoint
from ...constants import ELONGATION_PROBE, KELVIN_OFFSET
from ...errors import ArgumentError, FeedthermError
from ...system.load import LoadedSystem
from ..candidates import Candidate, candidate_sensors, carriable, with_candidates
from ..execution import Execution
from ..random_cycles import SpeedEnvelope
from .conditioning import kalman_conditioning, regression_conditioning
from .data import OUT_OF_RANGE, STREAMS, CycleSet, StudySettings, simulate_sets
from .drift_judge import DriftJudgement, judge_on_drift_tests
from .kalman import KalmanLaw, KalmanNoise, model_errors, sensor_sigma
from .metrics import Residuals, residuals
from .noise import SensorNoise, noisy_set
from .operating_table import build_table
from .regression import DEFAULT_LAGS, RegressionLaw
from .selection import fit_validated, greedy_selection
from .state_space import DEFAULT_ORDER, reduce_model
from .stroke import StrokeChoice, fit_stroke_validated, stroke_residuals

#: The error against K is shown for K = 1 … this (issue 16), or up to the K asked for.
CURVE_SENSORS = 6
#: The regression laws of a study: name -> lag time constants [s] (:mod:`.regression`).
LAWS = {"regression": (), "regression_lags": DEFAULT_LAGS}
#: The model-based estimator (:mod:`.kalman`); it reads the sensor sets the lagged regression chose.
KALMAN = "kalman"

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


@dataclass(frozen=True)
class LawResult:
    """One law: its kind, its sensors, the fitted law and its errors on the held-out cycles."""

    kind: str  # a key of LAWS, or KALMAN
    sensors: tuple[str, ...]
    law: RegressionLaw | KalmanLaw
    validation: Residuals
    test: Residuals
    conditioning: dict = field(default_factory=dict)  # :mod:`.conditioning`

    @property
    def k(self) -> int:
        return len(self.sensors)


@dataclass(frozen=True)
class StrokeResult:
    """Along the stroke, for one law asked for: the law of D applied at every x (``d_only``, test
    cycles) and, for a regression law, the stroke law on its sensors (``choice``, its ``validation``
    and ``test`` residuals over positions and time); the Kalman estimator: no ``choice``, its state
    read along the stroke (``validation``, ``test``), or None where its model has no such rows."""

    kind: str
    sensors: tuple[str, ...]
    d_only: Residuals
    choice: StrokeChoice | None = None
    validation: Residuals | None = None
    test: Residuals | None = None


@dataclass(frozen=True)
class StudyResult:
    """A compensation study's laws, each judged on cycles and machines it was not fitted on.

    Attributes
    ----------
    settings : StudySettings
        How the study's cycles were made and run.
    candidates : dict
        The candidate sensors by name: where a machine can carry one.
    sets : dict
        The cycles of each set (``"train"``, ``"validation"``, ``"test"``, ``"out_of_range"``) read
        through the sensors.
    curves : dict
        Law kind -> the laws on the greedy sensor sets for K = 1, 2, …: the error against the
        number of sensors.
    chosen : dict
        Law kind -> the law asked for (K greedy sensors, or the sensors named).
    declared : dict
        Law kind -> the law on the description's own sensors.
    request : int or tuple of str
        The sensors asked for: a count K, or candidate names.
    noise : SensorNoise or None
        The sensors' noise the sets were read with.
    stroke : dict
        Law kind -> the laws along the stroke, E(x, t).
    out_of_range : dict
        Law kind (or ``"best"``) -> ``"d"`` or ``"stroke"`` -> out-of-range case -> residuals.
    drift_tests : list of DriftJudgement
        Each law asked for on the description's drift tests, as ISO 230-3 judges it.
    offsets : dict
        Each candidate's declared offset [K]: what the laws' conditioning prices it at.
    """

    settings: StudySettings
    candidates: dict[str, Candidate]
    sets: dict[str, CycleSet]
    curves: dict[str, list[LawResult]]  # law kind -> the greedy sets for K = 1 … n
    chosen: dict[str, LawResult]  # law kind -> the law asked for (K greedy sensors, or the named ones)
    declared: dict[str, LawResult]  # law kind -> the law on the description's own sensors
    request: int | tuple[str, ...]
    noise: SensorNoise | None = None  # the sensors' noise the sets were read with
    stroke: dict[str, StrokeResult] = field(default_factory=dict)  # law kind -> along the stroke (:mod:`.stroke`)
    #: law kind (or "best") -> "d" / "stroke" -> out-of-range case -> residuals (:func:`out_of_range`)
    out_of_range: dict[str, dict[str, dict[str, Residuals]]] = field(default_factory=dict)
    #: each law asked for on the description's drift tests, as ISO 230-3 would judge it (:mod:`.drift_judge`)
    drift_tests: list[DriftJudgement] = field(default_factory=list)
    #: each candidate's declared offset [K] (its kind's, also in a noise-free study): what the laws'
    #: conditioning prices it at (:mod:`.conditioning`)
    offsets: dict[str, float] = field(default_factory=dict)

    def best(self, max_sensors: int = 3) -> LawResult:
        """The law with the smallest validation RMS among the curves' laws of at most ``max_sensors`` sensors.

        Parameters
        ----------
        max_sensors : int
            The most sensors the law may read.

        Returns
        -------
        LawResult
            That law, with its sensors and its errors on the held-out cycles.
        """
        pool = [r for curve in self.curves.values() for r in curve if r.k <= max_sensors]
        return min(pool, key=lambda r: r.validation.rms)


#: ``--sensors declared``: the description's own sensors, the ones the machine has.
DECLARED = "declared"


def parse_sensors(text: str, candidates: dict[str, Candidate]) -> int | tuple[str, ...]:
    """``--sensors``: a count K (1 … the candidates a machine can carry), ``declared`` (the
    description's own sensors) or comma-separated candidate names.

    Raises
    ------
    ArgumentError
        Naming ``sensors``: K not a positive whole number or larger than the carriable candidates, an
        unknown name (with the closest ones), a name listed twice.
    FeedthermError
        ``declared`` without declared sensors (the description is what is missing).
    """
    text = text.strip()
    if text == DECLARED:
        own = tuple(name for name, c in candidates.items() if c.where == "declared")
        if not own:
            raise FeedthermError("--sensors declared: the description declares no sensor ([sensors])")
        return own
    if re.fullmatch(r"[+-]?\d+", text):
        k = int(text)
        pool = carriable(candidates)
        if k < 1:
            raise ArgumentError("sensors", f"K must be at least 1, got {k}")
        if k > len(pool):
            raise ArgumentError("sensors", f"K = {k} but there are {len(pool)} candidate positions a machine can "
                                           f"carry (of {len(candidates)}; docs/compensation.md, *Candidates*)")
        return k
    names = tuple(item.strip() for item in text.split(","))
    for name in names:
        if not name or not _NAME.fullmatch(name):
            raise ArgumentError("sensors", f"{text!r} is neither a count nor a list of sensor names")
        if name not in candidates:
            raise ArgumentError("sensors", f"no candidate sensor {name!r}{_closest(name, candidates)}")
    if len(set(names)) != len(names):
        raise ArgumentError("sensors", f"a sensor is listed twice in {text!r}")
    return names


def _closest(name: str, candidates: dict[str, Candidate]) -> str:
    import difflib

    close = difflib.get_close_matches(name, list(candidates), n=3)
    return f"; did you mean {', '.join(close)}?" if close else ""


def run_study(loaded: LoadedSystem, settings: StudySettings, request: int | tuple[str, ...],
              progress: Callable[[float], None] | None = None, execution: Execution = Execution()) -> StudyResult:
    """Simulate the cycles, choose sensors, fit and judge the laws (see the module's notes); the
    cycles run where ``execution`` says (:mod:`~feedtherm.analysis.execution`: the same results)."""
    candidates = candidate_sensors(loaded.system)
    pool = carriable(candidates)  # what the greedy choice chooses among (named sensors may be any candidate)
    if isinstance(request, int) and request > len(pool):
        raise ArgumentError("sensors", f"K = {request} but there are {len(pool)} candidate positions a machine can carry")
    kinds = {name: c.kind for name, c in candidates.items()}
    declared_noise = SensorNoise.of(loaded.system, kinds)
    noise = declared_noise if settings.noise else SensorNoise.none(kinds)
    offsets = declared_noise.offsets()  # a noise-free study's laws are priced at the declared offsets too
    clean = simulate_sets(loaded, candidates, settings, tuple(STREAMS), progress, execution)
    sets = {name: noisy_set(cycles, noise, settings.seed, STREAMS[name], one_machine=name == "train")
            for name, cycles in clean.items()}
    n_curve = max(CURVE_SENSORS, request if isinstance(request, int) else 0)
    n_curve = min(n_curve, len(pool))
    curves, chosen, declared = {}, {}, {}
    own = tuple(n for n in loaded.system.sensors if n != loaded.system.room.ambient_sensor)
    for kind, lags in LAWS.items():
        steps = greedy_selection(sets["train"], sets["validation"], n_curve, lags, allowed=pool)
        curves[kind] = [_judge(kind, step.law, sets, offsets) for step in steps]
        if isinstance(request, int):
            chosen[kind] = curves[kind][request - 1]
        else:
            chosen[kind] = _judge(kind, fit_validated(sets["train"], sets["validation"], request, lags), sets, offsets)
        if own:
            declared[kind] = _judge(kind, fit_validated(sets["train"], sets["validation"], own, lags), sets, offsets)
    kalman = kalman_factory(loaded, candidates, sets["train"].clean(), settings, kalman_noise(noise))
    curves[KALMAN] = [_with_kalman_conditioning(_judge(KALMAN, kalman(r.sensors), sets), sets, offsets)
                      for r in curves["regression_lags"]]
    chosen[KALMAN] = _with_kalman_conditioning(_judge(KALMAN, kalman(chosen["regression_lags"].sensors), sets), sets,
                                               offsets)
    if own:
        declared[KALMAN] = _with_kalman_conditioning(_judge(KALMAN, kalman(own), sets), sets, offsets)
    has_stroke = all(c.stroke_error is not None for name in ("test", "out_of_range") for c in sets[name].cycles)
    stroke = along_stroke(chosen, sets) if has_stroke else {}
    result = StudyResult(settings, candidates, sets, curves, chosen, declared, request, noise, stroke, offsets=offsets)
    result = replace(result, out_of_range=out_of_range(result))
    predictors = {kind: (r.law, _stroke_predictor(kind, r.law, result)) for kind, r in result.chosen.items()}
    return replace(result, drift_tests=judge_on_drift_tests(loaded, result, predictors, noise, settings.seed,
                                                            settings.model, settings.mesh))


def out_of_range(result: StudyResult) -> dict[str, dict[str, dict[str, Residuals]]]:
    """Each law asked for, and the best with at most 3 sensors (``best``), on each out-of-range case
    apart: ``d``, its residuals of D; ``stroke``, over positions and time, with the stroke law where
    there is one (a regression's, the filter's state along the stroke) and else its D at every x."""
    cycles = result.sets["out_of_range"]
    names = cycles.names
    cases = {case: replace(cycles, name=case, cycles=[c for c in cycles.cycles if c.label.startswith(f"{case}-")])
             for case in OUT_OF_RANGE}
    laws = {kind: r.law for kind, r in result.chosen.items()}
    best = result.best(3)
    if all(best.law is not law for law in laws.values()):
        laws["best"] = best.law
    out = {}
    for kind, law in laws.items():
        if isinstance(law, KalmanLaw):  # every case's cycles through the filter side by side
            law.filter_records(cycles.cycles, names)
        d = {case: residuals(lambda record, law=law: law.predict_record(record, names), subset)
             for case, subset in cases.items() if subset.cycles}
        entry = {"d": d}
        if result.stroke:
            along = _stroke_predictor(kind, law, result)
            entry["stroke"] = {case: stroke_residuals(along, subset) for case, subset in cases.items() if subset.cycles}
        out[kind] = entry
    return out


def _stroke_predictor(kind: str, law, result: StudyResult):
    """record -> E(x_j, t) [m] as law ``kind`` predicts it along the stroke (see :func:`out_of_range`)."""
    names = result.sets["test"].names
    stroke = result.stroke.get(kind)
    if stroke is not None and stroke.choice is not None:
        return lambda record: stroke.choice.law.predict_record(record, names)
    if stroke is not None and stroke.test is not None:
        return lambda record: law.predict_stroke_record(record, names)
    return lambda record: law.predict_record(record, names)


def along_stroke(chosen: dict[str, LawResult], sets: dict[str, CycleSet]) -> dict[str, StrokeResult]:
    """Per law asked for, its error along the stroke (:class:`StrokeResult`): every law's D applied
    at every x; for the regressions, the stroke law on the same sensors and lags."""
    names = sets["test"].names
    out = {}
    for kind, result in chosen.items():
        d_only = stroke_residuals(lambda record, law=result.law: law.predict_record(record, names), sets["test"])
        if kind not in LAWS:  # the Kalman estimator: its state read along the stroke, where its model can
            law = result.law
            stroke = getattr(law, "predict_stroke_record", None)
            if stroke is None or stroke(sets["test"].cycles[0], names) is None:
                out[kind] = StrokeResult(kind, result.sensors, d_only)
            else:
                out[kind] = StrokeResult(kind, result.sensors, d_only, None,
                                         stroke_residuals(lambda record: stroke(record, names), sets["validation"]),
                                         stroke_residuals(lambda record: stroke(record, names), sets["test"]))
            continue
        choice = fit_stroke_validated(sets["train"], sets["validation"], result.sensors, LAWS[kind])
        law = choice.law
        out[kind] = StrokeResult(kind, result.sensors, d_only, choice,
                                 stroke_residuals(lambda record: law.predict_record(record, names), sets["validation"]),
                                 stroke_residuals(lambda record: law.predict_record(record, names), sets["test"]))
    return out


def kalman_noise(noise: SensorNoise, base: KalmanNoise = KalmanNoise()) -> KalmanNoise:
    """The filter's noise model with the study's declared sensor noise and offsets (:mod:`.noise`)."""
    c, i = noise.levels["contact"], noise.levels["infrared"]
    return replace(base, contact=c.noise, infrared=i.noise, contact_offset=c.offset, infrared_offset=i.offset)


def kalman_factory(loaded: LoadedSystem, candidates: dict[str, Candidate], train: CycleSet, settings: StudySettings,
                   noise: KalmanNoise = KalmanNoise(), order: int = DEFAULT_ORDER):
    """``sensors -> KalmanLaw``: the reduced model of every candidate and D, reduced once at the
    middle of the speed envelope and the middle of the cycles' ambient range, its table, and each
    output's open-loop error over the training cycles (:class:`~.kalman.KalmanLaw`; ``train``
    with the model's noise-free temperatures, so that the error is the model's)."""
    described = with_candidates(loaded, candidates)
    system = described.system
    envelope = SpeedEnvelope.of(system)
    screw = sum(envelope.screw) / 2
    nut = screw - sum(envelope.relative) / 2 if envelope.dual else 0.0
    ambient = sum(settings.ranges.ambient_mean) / 2 + KELVIN_OFFSET
    reference = OperatingPoint(screw, nut, ambient, system.kinematics.lead)
    outputs = [n for n in candidates if n != system.room.ambient_sensor] + [ELONGATION_PROBE]
    model = reduce_model(described, outputs, reference, order=order)
    table = build_table(system, model.surfaces, model.sources, ambient, overlay=described.overlay, film=model.film)
    errors = model_errors(model, table, train.cycles, train.names)
    methods = {name: candidate.kind for name, candidate in candidates.items()}
    steps: dict = {}  # one model, table and noise: every law shares its discrete steps
    made: dict[tuple[str, ...], KalmanLaw] = {}  # one law per sensor set: its filtered records are kept

    def law(sensors: tuple[str, ...]) -> KalmanLaw:
        sensors = tuple(sensors)
        if sensors not in made:
            own = sensor_sigma(sensors, methods, noise)
            sigma = tuple(float((o ** 2 + errors.get(s, 0.0) ** 2) ** 0.5) for s, o in zip(sensors, own))
            made[sensors] = KalmanLaw(model, table, sensors, sigma, noise, steps)
        return made[sensors]

    return law


def _judge(kind: str, law: RegressionLaw | KalmanLaw, sets: dict[str, CycleSet],
           offsets: dict[str, float] | None = None) -> LawResult:
    names = sets["test"].names
    if isinstance(law, KalmanLaw):  # every cycle of both sets through the filter side by side
        law.filter_records([*sets["validation"].cycles, *sets["test"].cycles], names)
    return LawResult(kind, tuple(law.sensors), law,
                     residuals(lambda record: law.predict_record(record, names), sets["validation"]),
                     residuals(lambda record: law.predict_record(record, names), sets["test"]),
                     regression_conditioning(law, offsets) if isinstance(law, RegressionLaw) else {})


def _with_kalman_conditioning(result: LawResult, sets: dict[str, CycleSet], offsets: dict[str, float]) -> LawResult:
    """``result`` with the Kalman law's conditioning on the first test cycle (:mod:`.conditioning`)."""
    test = sets["test"]
    return replace(result, conditioning=kalman_conditioning(result.law, test.cycles[0], test.names, offsets))
