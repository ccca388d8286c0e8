"""Training and held-out data of a compensation study: random cycles run through a model.

Four sets of cycles, each drawn from its own stream of the study's seed
(:func:`~feedtherm.analysis.random_cycles.cycle_seed`):

- ``train`` (stream 0): cycles on the nominal description — what a law is fitted on;
- ``validation`` (stream 1): cycles on machine variants (another machine of the same design,
  :mod:`~feedtherm.analysis.machine_variants`, one draw per cycle) — what the sensor selection
  compares candidate sets on;
- ``test`` (stream 2): further cycles on further variants — what the reported figures come from,
  never seen while fitting or choosing;
- ``out_of_range`` (stream 3): cycles outside what the training cycles contain, on further
  variants (:data:`OUT_OF_RANGE`), reported beside the test figures, never mixed into them.

A variant draws every declared uncertainty and the heat and CHTC factors
(:func:`~feedtherm.analysis.machine_variants.draw_variant`); the training set stays on the
nominal machine.

Every cycle runs with every candidate sensor (:mod:`~feedtherm.analysis.candidates`) through
:func:`~feedtherm.analysis.sweep.run_batch`, the loop of ``feedtherm sweep``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ...constants import RPM_PER_RAD_S
from ...errors import ArgumentError, FeedthermError
from ...models.options import ModelOptions
from ...simulate import prepare
from ...system.load import LoadedSystem
from ...system.schema import DutyCycle
from ...system.variants import with_values
from ..candidates import Candidate, with_candidates
from ..machine_variants import DEFAULT_SPREAD, draw_variant
from ..random_cycles import CycleRanges, cycle_seed, random_cycle
from ..execution import Execution, TaskFailure
from ..sweep import SweepRun, run_batch

#: The sets of a study and their seed streams.
STREAMS = {"train": 0, "validation": 1, "test": 2, "out_of_range": 3}
#: The out-of-range cases, each an assumption about what a machine meets that its training did
#: not hold; every case changes one thing of a random cycle drawn as the training's are:
#:
#: - ``ambient_ramp``: the room warms by 8 K over the 8 h, from the cycle's first ambient (a
#:   workshop whose air conditioning fails; the training drifts by at most 3 K);
#: - ``ambient_step``: the room jumps by +5 K at a quarter of the cycle (2 h of 8) and stays (a
#:   door to a hot hall opened; the training's ambient moves by under 0.4 K per 10 min);
#: - ``fast``: every run 1.5 times faster, screw and relative speed alike (above every condition
#:   the description states, where the training's speeds end);
#: - ``warm_start``: the machine starts 8 K above its room, uniformly (stopped after work in a
#:   warmer hall; the training starts at the ambient).
OUT_OF_RANGE = ("ambient_ramp", "ambient_step", "fast", "warm_start")
#: Cycles per out-of-range case (fewer when a study runs fewer cycles per set).
OUT_OF_RANGE_CYCLES = 2
#: The size of the cases' changes (see :data:`OUT_OF_RANGE`): K, K, share of the cycle, factor, K.
RAMP_K, STEP_K, STEP_AT, SPEED_FACTOR, WARM_K = 8.0, 5.0, 0.25, 1.5, 8.0


def out_of_range_cases() -> dict[str, str]:
    """Each out-of-range case and what it changes, in words (for the files and the report)."""
    return {"ambient_ramp": f"the room warms by {RAMP_K:g} K over the cycle",
            "ambient_step": f"the room jumps by +{STEP_K:g} K at {100 * STEP_AT:g} % of the cycle",
            "fast": f"every run {SPEED_FACTOR:g} times faster than the training's",
            "warm_start": f"the machine starts {WARM_K:g} K above its room"}
#: Offset of the streams the machine variants are drawn from (independent of the cycles' draws).
VARIANT_STREAM = 100
#: The name under which a cycle is added to the description's duty cycles.
CYCLE_NAME = "compensation_cycle"
#: The table positions along the stroke where a study records the positioning error E(x, t):
#: 9, evenly spaced, both ends included (a quarter of a 250 mm stroke every 31 mm; E varies smoothly
#: along the screw, a quadratic or cubic in x, so 9 points over-determine any basis of order ≤ 4).
STROKE_POSITIONS = 9


@dataclass(frozen=True)
class StudySettings:
    """How a study's cycles are made and run.

    ``sample_interval`` 60 s: what a controller's thermal compensation reads (temperatures every
    few seconds to a minute, against time constants of 10-60 min); ``motion = "averaged"``: the
    cycle-averaged contacts and heats, as ``feedtherm sweep`` (the final values differ from the
    resolved motion by well under 1 % of D on the paper bench, docs/sweep.md), and a law corrects
    the slow thermal drift, not the ripple within one stroke.
    """

    cycles: int = 8
    seed: int = 0
    ranges: CycleRanges = CycleRanges()
    spread: float = DEFAULT_SPREAD
    sample_interval: float = 60.0
    model: str = "fast"
    motion: str = "averaged"
    mesh: str | None = None
    #: Read the cycles through noisy sensors (:mod:`.noise`); False: the model's temperatures.
    noise: bool = True

    def __post_init__(self) -> None:
        if isinstance(self.seed, bool) or not isinstance(self.seed, (int, np.integer)):
            raise ArgumentError("seed", f"{self.seed!r} is not an integer")
        if isinstance(self.cycles, bool) or not isinstance(self.cycles, (int, np.integer)) or self.cycles < 1:
            raise ArgumentError("cycles", f"{self.cycles!r} is not a positive integer")
        if not self.sample_interval > 0:
            raise FeedthermError("the sample interval must be positive")


@dataclass(frozen=True)
class CycleRecord:
    """One simulated cycle: series at the sample times, SI units.

    ``sensors[:, j]`` is candidate ``j``'s reading [K] (with its sensor's noise and offset once
    :func:`.noise.noisy_set` has run; ``truth`` then holds the model's temperatures, else None);
    ``elongation`` D [m]; the motor speeds [rpm] are those commanded over the sample's preceding
    interval (what a controller knows); ``positions`` [m] the table positions x_j
    (:func:`stroke_positions`) and ``stroke_error`` ``(n, len(positions))`` [m] the positioning error
    E(x_j, t) there (the run's ``positioning_error``, relative to ``[mechanics] positioning``), or
    None for a record without a table.
    """

    label: str
    times: np.ndarray
    sensors: np.ndarray
    elongation: np.ndarray
    screw_rpm: np.ndarray
    nut_rpm: np.ndarray
    variant: dict | None = None
    cycle: DutyCycle | None = field(default=None, repr=False)
    truth: np.ndarray | None = field(default=None, repr=False)
    positions: np.ndarray | None = field(default=None, repr=False)
    stroke_error: np.ndarray | None = field(default=None, repr=False)


def stroke_positions(table_x: np.ndarray, count: int = STROKE_POSITIONS) -> np.ndarray:
    """``count`` table positions [m] evenly spaced from the first to the last of a run's ``table_x``
    (its ends included): where a study records E(x, t)."""
    table_x = np.asarray(table_x, dtype=float)
    return np.linspace(table_x[0], table_x[-1], count) if table_x.size else np.zeros(0)


def stroke_error_at(solution, positions: np.ndarray) -> np.ndarray:
    """The run's E(x, t) [m] ``(n, len(positions))`` at ``positions`` [m], linear between its table positions."""
    table_x = np.asarray(solution.table_x, dtype=float)
    error = np.asarray(solution.positioning_error, dtype=float)
    return np.array([np.interp(positions, table_x, row) for row in error]).reshape(len(error), len(positions))


@dataclass(frozen=True)
class CycleSet:
    """The cycles of one set, with the candidates' names (the columns of every ``sensors``)."""

    name: str
    names: list[str]
    cycles: list[CycleRecord]
    #: The description's reference temperature [K], where every displacement is zero: a law fitted on
    #: the set passes through it (its regressors taken from it, no free intercept; :mod:`.regression`).
    #: None: a free intercept.
    reference: float | None = None

    def stacked(self) -> tuple[np.ndarray, np.ndarray]:
        """All samples of all cycles: sensors ``(n, candidates)`` [K] and D ``(n,)`` [m]."""
        return (np.vstack([c.sensors for c in self.cycles]), np.concatenate([c.elongation for c in self.cycles]))

    def clean(self) -> "CycleSet":
        """The same cycles with the model's (noise-free) temperatures as readings."""
        from dataclasses import replace

        return replace(self, cycles=[c if c.truth is None else replace(c, sensors=c.truth, truth=None)
                                     for c in self.cycles])


def speeds_at(cycle: DutyCycle, times: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Screw and nut speed [rpm] holding over the interval that ends at each time (the first: at 0)."""
    starts = np.array([s.start for s in cycle.segments])
    index = np.clip(np.searchsorted(starts, np.asarray(times), side="left") - 1, 0, len(starts) - 1)
    screw = np.array([s.screw_speed for s in cycle.segments]) * RPM_PER_RAD_S
    nut = np.array([s.nut_speed for s in cycle.segments]) * RPM_PER_RAD_S
    return screw[index], nut[index]


def out_of_range_cycle(case: str, cycle: DutyCycle) -> DutyCycle:
    """``cycle`` changed as out-of-range ``case`` says (:data:`OUT_OF_RANGE`; ``warm_start`` changes
    the machine's start, not the cycle)."""
    rows = []
    first = cycle.segments[0].ambient
    step_at = float(round(STEP_AT * cycle.duration))
    for segment in cycle.segments:
        ambient, screw, nut = segment.ambient, segment.screw_speed, segment.nut_speed
        if case == "ambient_ramp":
            ambient = first + RAMP_K * segment.start / cycle.duration
        elif case == "ambient_step":
            ambient = first + (STEP_K if segment.start >= step_at else 0.0)
        elif case == "fast":
            screw, nut = SPEED_FACTOR * screw, SPEED_FACTOR * nut
        rows.append({"start": f"{segment.start!r} s", "screw_speed": f"{screw!r} rad/s", "nut_speed": f"{nut!r} rad/s",
                     "ambient": f"{ambient!r} K"})
    if case == "ambient_step" and step_at not in {s.start for s in cycle.segments}:
        held = next(s for s in reversed(cycle.segments) if s.start < step_at)
        rows.append({"start": f"{step_at!r} s", "screw_speed": f"{held.screw_speed!r} rad/s",
                     "nut_speed": f"{held.nut_speed!r} rad/s", "ambient": f"{first + STEP_K!r} K"})
        rows.sort(key=lambda row: float(row["start"].split()[0]))
    return DutyCycle.model_validate({"segments": rows, "duration": f"{cycle.duration!r} s",
                                     "description": f"{cycle.description}, out of range: {case}"})


def _planned(loaded: LoadedSystem, settings: StudySettings, name: str) -> list[tuple[str, DutyCycle, int, str | None]]:
    """``(label, cycle, index, out-of-range case)`` of every cycle of set ``name``."""
    stream = STREAMS[name]
    if name != "out_of_range":
        return [(f"{name}-{index:03d}", random_cycle(loaded.system, cycle_seed(settings.seed, stream, index),
                                                     settings.ranges,
                                                     description=f"{name} cycle {index} of seed {settings.seed}"),
                 index, None) for index in range(settings.cycles)]
    out = []
    for c, case in enumerate(OUT_OF_RANGE):
        for k in range(min(OUT_OF_RANGE_CYCLES, settings.cycles)):
            index = c * OUT_OF_RANGE_CYCLES + k
            cycle = random_cycle(loaded.system, cycle_seed(settings.seed, stream, index), settings.ranges,
                                 description=f"{name} cycle {index} of seed {settings.seed}")
            out.append((f"{case}-{k:03d}", out_of_range_cycle(case, cycle), index, case))
    return out


def simulate_set(loaded: LoadedSystem, candidates: dict[str, Candidate], settings: StudySettings, name: str,
                 progress: Callable[[float], None] | None = None, execution: Execution = Execution()) -> CycleSet:
    """Draw and simulate the cycles of set ``name`` (a key of :data:`STREAMS`; see :func:`simulate_sets`)."""
    return simulate_sets(loaded, candidates, settings, (name,), progress, execution)[name]


def simulate_sets(loaded: LoadedSystem, candidates: dict[str, Candidate], settings: StudySettings,
                  names: tuple[str, ...], progress: Callable[[float], None] | None = None,
                  execution: Execution = Execution()) -> dict[str, CycleSet]:
    """Draw and simulate the cycles of the sets ``names`` (keys of :data:`STREAMS`) as one batch.

    The training set runs the nominal description; the others run one machine variant per cycle,
    drawn from every declared uncertainty (:func:`~feedtherm.analysis.machine_variants.draw_variant`).
    One batch for all sets: on a cluster the workers start once and stay busy to the last run
    (each set's runs are independent of the others', so the results are the same as set by set).
    """
    base = with_candidates(loaded, candidates)
    plans = {name: _plan_set(loaded, base, settings, name) for name in names}
    runs = [run for plan in plans.values() for run in plan[0]]
    prepare(base.system, settings.model, settings.mesh)
    solutions = iter(run_batch(runs, progress, execution))
    reference = float(loaded.system.temperatures.reference)
    return {name: CycleSet(name, list(candidates), [_record(next(solutions), cycle, variant, label, list(candidates))
                                                    for _, cycle, variant, label in zip(*plan)], reference)
            for name, plan in plans.items()}


def _plan_set(loaded: LoadedSystem, base: LoadedSystem, settings: StudySettings, name: str):
    """``(runs, cycles, variants, labels)`` of set ``name``: each cycle added to its machine as a duty cycle."""
    stream = STREAMS[name]
    runs, cycles, variants, labels = [], [], [], []
    for label, cycle, index, case in _planned(loaded, settings, name):
        variant = None
        described = base
        if name != "train":
            variant = draw_variant(loaded, cycle_seed(settings.seed, VARIANT_STREAM + stream, index), settings.spread)
            described = variant.apply(base, label=f"{name} machine {index}")
        changes = {"duty_cycles": {**described.system.duty_cycles, CYCLE_NAME: cycle}}
        if case == "warm_start":
            changes["temperatures.initial"] = cycle.segments[0].ambient + WARM_K
        described = with_values(described, changes, origin_suffix=f"{name} cycle {index}")
        runs.append(SweepRun(described, {"cycle": CYCLE_NAME, "model": settings.model,
                                         "motion": settings.motion, "mesh": settings.mesh,
                                         "sample_interval": settings.sample_interval,
                                         "options": ModelOptions(fields=False)},  # sensors and D only
                             label=f"{name} cycle {index} of seed {settings.seed}"))
        cycles.append(cycle)
        variants.append(variant)
        labels.append(label)
    return runs, cycles, variants, labels


def _record(solution, cycle: DutyCycle, variant, label: str, names: list[str]) -> CycleRecord:
    """One simulated cycle's record (:class:`CycleRecord`); a failed run ends the study."""
    if isinstance(solution, TaskFailure):  # a study needs every cycle: the first failure ends it
        raise FeedthermError(str(solution))
    missing = [n for n in names if n not in solution.sensors]
    if missing:  # pragma: no cover - every candidate is a sensor of the run
        raise FeedthermError(f"the run did not report {', '.join(missing)}")
    screw, nut = speeds_at(cycle, solution.times)
    positions = stroke_positions(solution.table_x)
    return CycleRecord(
        label, np.asarray(solution.times, float),
        np.column_stack([solution.sensors[n] for n in names]), np.asarray(solution.elongation, float),
        screw, nut, None if variant is None else variant.as_dict(), cycle,
        positions=positions if positions.size else None,
        stroke_error=stroke_error_at(solution, positions) if positions.size else None)


#: A study's run probes every candidate at every sample: its step costs this many times a plain run's
#: (ballscrew_example, 103 candidates, 8 cycles a set: 52.9 s of runs for 92,160 steps serial, where
#: the plain fast model steps at 2.8e-4 s on the same machine; 2026-11-29, benchmarks/README.md;
#: feedtherm.plan.cost gives its 1,752 nodes 3.1e-4 s).
STUDY_STEP_FACTOR = 2.0
#: The selection, fits, filters and judgements per run of the study, on the same machine [s] (12.5 s for 32 runs).
FIT_SECONDS_PER_RUN = 0.4


@dataclass(frozen=True)
class StudyCost:
    """What a study's cycles will cost, planned before any run: runs per set, time steps, wall time [s]."""

    runs: dict[str, int]  # set name -> cycles
    steps: int
    seconds: float

    def describe(self, workers: int = 1) -> str:
        sets = ", ".join(f"{n} {name.replace('_', '-')}" for name, n in self.runs.items())
        total = sum(self.runs.values())
        minutes = self.seconds / max(workers, 1) / 60.0
        fits = FIT_SECONDS_PER_RUN * total / 60.0
        return (f"{total} runs ({sets}), {self.steps:,} time steps: about {minutes + fits:.1f} min on "
                f"{max(workers, 1)} worker{'s' if workers > 1 else ''} (runs {minutes:.1f} min, fits {fits:.1f} min; "
                "estimated as check does, for a 2-core x86-64 machine)")


def study_cost(loaded: LoadedSystem, settings: StudySettings) -> StudyCost:
    """The runs a study will make and their time steps (the integrator's rule on each cycle,
    :func:`feedtherm.plan.estimated_steps`), with the wall time a step of the model takes at its
    size on the project's machine (:func:`feedtherm.plan.cost.seconds_per_step`)."""
    from ...plan import model_sizes, estimated_steps
    from ...plan.cost import seconds_per_step
    from ...models.integrator import Segment

    options = ModelOptions(motion=settings.motion)
    stroke = loaded.system.kinematics.stroke
    runs, steps = {}, 0
    for name in STREAMS:
        planned = _planned(loaded, settings, name)
        runs[name] = len(planned)
        for _, cycle, _, _ in planned:
            ends = [s.start for s in cycle.segments[1:]] + [cycle.duration]
            segments = [Segment(s.start, end, _Moving(s, loaded.system)) for s, end in zip(cycle.segments, ends)]
            steps += estimated_steps(stroke, segments, options)
    sizes = model_sizes(loaded.system, ModelOptions(mesh=settings.mesh or "coarse"))
    key = {"fast": ("fast", None), "reduced": ("reduced", None)}.get(settings.model, ("fem", settings.mesh or "coarse"))
    per_step = seconds_per_step(sizes.get(key, sizes[("fast", None)]))
    return StudyCost(runs, steps, steps * per_step * STUDY_STEP_FACTOR)


class _Moving:
    """The little of boundary conditions :func:`~feedtherm.plan.estimated_steps` reads: the table speed."""

    def __init__(self, segment, system):
        from ...boundary.operating import OperatingPoint

        self.point = OperatingPoint(segment.screw_speed * RPM_PER_RAD_S, segment.nut_speed * RPM_PER_RAD_S,
                                    segment.ambient or 293.15, system.kinematics.lead)
