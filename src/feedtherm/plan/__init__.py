"""The first step of a run: a cheap, validated plan.

:func:`plan_run` checks every argument against the description, reads a duty-cycle CSV
once, and turns the condition or cycle into segments of constant operating point with their
boundary conditions.  The CLI plans before it loads a model, so bad input is reported at
once; :func:`feedtherm.simulate.execute` integrates a plan and packs its Solution.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

from ..boundary import PHYSICS, BoundaryConditions, EvaluationMemo, LocalTemperatures, boundary_conditions_at
from ..boundary.heat import motor_overloads
from ..boundary.operating import OperatingPoint, operating_point
from ..boundary.room import RoomAir
from ..constants import RPM_PER_RAD_S
from ..errors import ArgumentError, FeedthermError, ModelError
from ..models.coupling import Coupling
from ..models.integrator import Segment
from ..models.options import MOTIONS, ModelOptions
from ..models.registry import ModelEntry, model_entry
from ..system.load import LoadedSystem
from ..system.measurements import MeasurementSet
from ..system.overlay import Overlay, available_overlay, mode_of, with_overlay
from ..system.schema import DutySegment, FeedSystem
from ..system.thermal_tests import Soak, ThermalTest
from .cost import ModelSize, fast_size, fem_size, projection_time, run_work, wall_time
from .profiles import FromReadings, Initial, Soaked, Uniform, cycle_profile, soak_target, test_profile

MESHES = ("coarse", "medium", "fine")
SOLVERS = ("auto", "direct", "cg")
STARTS = ("initial", "steady")


@dataclass(frozen=True)
class RunPlan:
    """What a run will do, every input checked: the segments and their boundary conditions, the
    state it starts from and the room's air."""

    loaded: LoadedSystem
    label: str  # the test or condition, the duty cycle's name or the CSV file's stem
    model: ModelEntry
    options: ModelOptions
    segments: list[Segment]
    single_drive: bool
    sample_interval: float
    start: str  # "initial": from :attr:`initial`; "steady": the first segment's steady state
    initial: Initial | None = None
    air: RoomAir | None = None  # the room's measured air, None: each segment's ambient
    test: ThermalTest | None = None  # the test or condition run, None for a bare duty cycle

    @property
    def end(self) -> float:
        return self.segments[-1].t1

    @property
    def mode(self) -> str:
        """The overlay the run takes, by name, or ``"physics"``."""
        return mode_of(self.loaded)

    @property
    def coupling(self) -> Coupling | None:
        """How the boundary conditions follow the temperatures; None when they are frozen."""
        return coupling_of(self.loaded.system, self.loaded.overlay, self.options)


def with_mode(loaded: LoadedSystem, mode: str) -> LoadedSystem:
    """``loaded`` set to run in ``mode``: ``"physics"`` (every value from the correlations), or the
    name of the overlay of printed values its bench supplies (:mod:`feedtherm.system.overlay`).

    This is where a mode becomes an overlay, once: every run, study and report then reads it from
    the LoadedSystem.
    """
    if mode == PHYSICS:
        return with_overlay(loaded, None)
    overlay = available_overlay(loaded)
    if overlay is None:
        raise FeedthermError(f"--mode {mode}: {loaded.origin} has no overlay of printed values (a bench's "
                             f"overlay.toml, or meta.overlay); the only mode is {PHYSICS}")
    if overlay.name != mode:
        raise FeedthermError(f"--mode: must be {PHYSICS} or {overlay.name} (the overlay of {loaded.origin}), "
                             f"got {mode!r}")
    return with_overlay(loaded, overlay)


def boundary_of(loaded: LoadedSystem, condition: str) -> BoundaryConditions:
    """The boundary conditions of a declared condition, with the overlay ``loaded`` runs in."""
    system = loaded.system
    return boundary_at(loaded, operating_point(system, system.conditions[condition]), label=condition)


def boundary_at(loaded: LoadedSystem, point: OperatingPoint, *, label: str = "") -> BoundaryConditions:
    """The boundary conditions at any operating point, with the overlay ``loaded`` runs in."""
    return boundary_conditions_at(loaded.system, point, loaded.overlay, label=label)


def coupling_of(system: FeedSystem, overlay: Overlay | None, options: ModelOptions) -> Coupling | None:
    """The description's coupling: None for ``temperatures.coupling = "frozen"``."""
    if system.temperatures.coupling == "frozen":
        return None

    memo = EvaluationMemo()  # one run's surfaces and sources, each as last evaluated

    def evaluate(base: BoundaryConditions, temperatures: LocalTemperatures) -> BoundaryConditions:
        return boundary_conditions_at(system, base.point, overlay, label=base.condition, temperatures=temperatures,
                                      memo=memo)

    return Coupling(evaluate, options.coupling_tolerance)


def plan_run(loaded: LoadedSystem, *, condition: str | None = None, cycle: str | None = None,
             test: str | None = None, model: str = "fast", duration: float | None = None,
             single_drive: bool = False, sample_interval: float = 10.0, motion: str | None = None,
             mesh: str | None = None, solver: str | None = None, start: str = "initial",
             options: ModelOptions | None = None, allow_overload: bool = False,
             factor_memory: float | None = None, measured: MeasurementSet | None = None) -> RunPlan:
    """Check a run's arguments and build its segments (see :func:`feedtherm.simulate.simulate`).

    ``condition`` and ``test`` are one argument: a test or a condition of the description by name
    (a condition is the simplest test).  ``measured``: the measurements a test whose room or start is
    measured reads (default: the test's own file, else the description's).

    A motor whose shaft needs more than its declared ``continuous_torque`` at a segment is
    refused (:func:`refuse_overloads`), unless ``allow_overload``: studies that vary the
    preloads (calibration, uncertainty) run such points and report them instead.  The boundary
    conditions take the overlay ``loaded`` carries (:func:`with_mode`).
    """
    entry = _check_arguments(model, duration, sample_interval, motion, mesh, solver, start)
    if factor_memory is not None and not (math.isfinite(factor_memory) and factor_memory > 0.0):
        raise ArgumentError("factor_memory", f"must be a positive number of GB, got {factor_memory / 1e9!r}")
    if condition is not None and test is not None:
        raise ArgumentError("test", "condition and test name the same thing; give one of them")
    name = condition if condition is not None else test
    opts = options or ModelOptions()
    opts = replace(opts, **{name: value for name, value in (("motion", motion), ("mesh", mesh), ("solver", solver),
                                                            ("factor_memory", factor_memory)) if value is not None})
    if name is not None and cycle is None:
        profile = test_profile(loaded, name, duration, measured, "condition" if condition is not None else "test")
        what = f"test {name}" if name in loaded.system.tests else f"condition {name}"
    else:
        profile = cycle_profile(loaded, name, cycle, duration)
        what = f"duty cycle {profile.label}"
    planned = _segments(loaded, profile.segments, profile.end, single_drive)
    _check_duration(loaded, planned, profile.end, opts, duration is not None)
    _check_step_count(loaded, planned, opts)
    _check_record_memory(loaded, planned, sample_interval, opts)
    if not allow_overload:
        refuse_overloads(planned, what)
    initial = profile.initial
    if isinstance(initial, Soak):
        soak = plan_run(loaded, **soak_target(loaded, initial.soaked), model=model, single_drive=single_drive,
                        sample_interval=max(sample_interval, 60.0), options=opts, allow_overload=allow_overload,
                        measured=measured if initial.soaked in loaded.system.tests else None)
        initial = Soaked(initial.soaked, soak)
    return RunPlan(loaded, profile.label, entry, opts, planned, single_drive, sample_interval, start, initial,
                   profile.air, profile.test)


def refuse_overloads(segments: list[Segment], what: str) -> None:
    """Raise if a motor needs more than its rated continuous torque in any segment of ``what`` (the
    condition or duty cycle; the physics alone: an overlay's printed heats carry no torques)."""
    for seg in segments:
        if seg.bc.overlay is not None:
            continue
        overloads = motor_overloads(seg.bc.heats)
        if overloads:
            where = what if len(segments) == 1 else f"{what}, from {seg.t0:g} s"
            raise ModelError(f"{where}: {overloads[0].describe()}")


#: Most time steps a run may plan: a minute or so of the fast model, many hours of the FE model
#: (the paper bench's 3 h runs take 6,480-9,721; a 24 h duty cycle at its fastest, 78,000).
#: A fast table with the resolved motion needs steps_per_stroke steps per stroke; beyond this
#: the run is refused before it starts rather than left to run for hours.
MAX_STEPS = 500_000


def estimated_steps(stroke: float, segments: list[Segment], options: ModelOptions) -> int:
    """About the time steps the shared integrator takes over ``segments``.

    Its rule (:meth:`~feedtherm.models.integrator.Integrator._step`) on a grid that splits the
    stroke evenly; the model's grid is not built yet when a run is planned.
    """
    return math.ceil(sum((seg.t1 - seg.t0) / _time_step(stroke, seg, options) for seg in segments))


def _time_step(stroke: float, seg: Segment, options: ModelOptions) -> float:
    """The integrator's step in ``seg`` [s] (the rule of :func:`estimated_steps`)."""
    if seg.speed == 0.0:
        return min(options.standstill_step, options.max_step)
    if options.motion == "averaged":
        return min(options.averaged_step, options.max_step)
    return min(stroke / (options.steps_per_stroke * seg.speed), options.max_step)  # steps_per_stroke per stroke


def _check_duration(loaded: LoadedSystem, segments: list[Segment], end: float, options: ModelOptions,
                    given: bool) -> None:
    """A run must last one time step at least: shorter, it has no step to report."""
    step = _time_step(_stroke(loaded.system), segments[0], options)
    if end < step:
        detail = f"{end:g} s is shorter than one time step of this run ({step:g} s); give {step:g} s or more"
        if given:
            raise ArgumentError("duration", detail)
        raise FeedthermError(f"the run's duration: {detail}")


#: Longest reciprocation cycle 2 stroke / |v| [s] for which `check` suggests --motion averaged.
#: The cycle-averaged motion's deviation from the resolved one grows with the cycle (the FE
#: verification's sliding contact: order 0.8-0.9 in the period, docs/fem-model.md).  Measured
#: over 3 h (final cycle means, the largest over its sensors): the paper bench at 396 rpm, cycle
#: 66.7 s, fast model: 0.06 K (D 0.13 µm); the paper bench at 1500 rpm, 67,000 steps planned (a
#: 6.4 s cycle), coarse FE model: 0.02 K (issue 33: 13 s against 4 min 44 s); ballscrew_example
#: v5, 9.6 s, fast model: under 0.005 K (D 0.02 µm) (2026-11-26).  Interpolated, a 30 s cycle
#: keeps the sensors' cycle means within about 0.04 K, a quarter of a class-A PT100's tolerance
#: at 20 degC (0.15 K + 0.002 |t|, IEC 60751).
AVERAGED_MOTION_MAX_CYCLE_S = 30.0


@dataclass(frozen=True)
class RunCost:
    """What a run of one condition or duty cycle will cost, planned, before any model is built
    (:mod:`feedtherm.plan.cost`)."""

    steps: dict[str, int]  # motion ("resolved", "averaged") -> the integrator's time steps
    seconds: dict[tuple[str, str | None], dict[str, float]]  # (model, mesh) -> motion -> estimated wall time [s]
    cycle_s: float | None  # the longest reciprocation cycle 2 stroke / |v| of a moving segment [s]; None at standstill
    sizes: dict[tuple[str, str | None], ModelSize] = field(default_factory=dict)  # what the times scale with
    #: (model, mesh) -> what its first run on a mesh adds [s] where it may be cached already (the
    #: reduced model's projection); the times above hold with it cached
    first_build: dict[tuple[str, str | None], float] = field(default_factory=dict)
    #: the resolved motion's steps in the models that step it window by window (FE, reduced;
    #: models/windows.py), where they differ from ``steps["resolved"]``
    window_steps: int | None = None

    @property
    def suggest_averaged(self) -> bool:
        return self.cycle_s is not None and self.cycle_s <= AVERAGED_MOTION_MAX_CYCLE_S


#: The built-in models whose resolved motion steps window by window (``ThermalModel.windowed_motion``).
WINDOWED_MODELS = ("fem", "reduced")
#: The models and FE meshes `check` estimates a run of (the reduced model on the coarse mesh).
COSTED_MODELS = (("fast", None), ("fem", "coarse"), ("fem", "medium"), ("fem", "fine"), ("reduced", None))


def model_sizes(system: FeedSystem, options: ModelOptions | None = None) -> dict[tuple[str, str | None], ModelSize]:
    """What each of :data:`COSTED_MODELS` would have for ``system``: nodes (the FE meshes' predicted),
    grid positions, and whether each mesh is cached."""
    opts = options or ModelOptions()
    sizes = {("fast", None): fast_size(system, opts)}
    for density in MESHES:
        sizes[("fem", density)] = fem_size(system, density, opts)
    sizes[("reduced", None)] = replace(sizes[("fem", opts.mesh)], model="reduced")
    return sizes


def run_cost(plan: RunPlan, sizes: dict[tuple[str, str | None], ModelSize] | None = None) -> RunCost:
    """The integrator's time steps of ``plan`` by each motion, and the wall time each model would take
    (``sizes``: :func:`model_sizes` of the plan's description, computed here when not given)."""
    system = plan.loaded.system
    sizes = sizes or model_sizes(system, plan.options)
    stroke = _stroke(system)
    positions = sizes[("fast", None)].positions
    works = {motion: run_work(plan, motion, positions) for motion in MOTIONS}
    windowed = run_work(plan, "resolved", positions, windowed=True)
    seconds, first = {}, {}
    for key, size in sizes.items():
        own = {**works, "resolved": windowed} if size.model in WINDOWED_MODELS else works
        seconds[key] = {motion: wall_time(size, work) for motion, work in own.items()}
        if size.model == "reduced":
            once = projection_time(size)
            if size.mesh_cached:  # its projection may be on disk already
                first[key] = once
            else:  # no mesh, no projection: the run builds both
                seconds[key] = {motion: s + once for motion, s in seconds[key].items()}
    moving = [seg.speed for seg in plan.segments if seg.speed > 0.0]
    cycle = 2.0 * stroke / min(moving) if moving else None  # the slowest cycle decides
    return RunCost({motion: work.steps for motion, work in works.items()}, seconds, cycle, sizes, first,
                   windowed.steps if windowed.steps != works["resolved"].steps else None)


def _stroke(system) -> float:
    """The table's stroke [m]; 0 for a system without a feed drive (nothing moves)."""
    return 0.0 if system.kinematics is None else system.kinematics.stroke


def _check_step_count(loaded: LoadedSystem, segments: list[Segment], options: ModelOptions) -> None:
    steps = estimated_steps(_stroke(loaded.system), segments, options)
    if steps > MAX_STEPS:
        fastest = max(seg.speed for seg in segments) * 60.0
        raise FeedthermError(f"the run would take about {steps:,} time steps, more than the {MAX_STEPS:,} a run may "
                             f"plan (the table moves at up to {fastest:.4g} m/min, {options.steps_per_stroke} steps "
                             "per stroke): shorten --duration, or use --motion averaged")


#: The most a run's records may hold [bytes]: its samples (every series the run writes, at each
#: sample time) and its step records.  1 GB, an eighth of an 8 GB workstation's memory: the rest is
#: the model's (an FE run's factors take gigabytes) and the system's.
RECORD_MEMORY_BYTES = 1e9
#: Bytes of one recorded value (float64).
BYTES_PER_VALUE = 8
#: How many times a recorded value is held at a run's peak: the integrator's trace (lists of small
#: arrays and of the parts' means), the Solution's arrays, the stacked columns of the CSV files
#: written.  The paper bench at 0.25-1 s samples over 3 h (43,201 and 10,801 samples of 277 values,
#: tracemalloc, 2026-11-29): 5.7 kB a sample at the peak of simulate and write_tables, 2.6 times
#: its 2.2 kB of values.
RECORD_COPIES = 3


@dataclass(frozen=True)
class RecordPlan:
    """What a run's records will hold: samples and steps, the values of each, and their memory."""

    samples: int
    values_per_sample: int
    steps: int
    values_per_step: int

    @property
    def bytes(self) -> float:
        return RECORD_COPIES * BYTES_PER_VALUE * (self.samples * self.values_per_sample
                                                  + self.steps * self.values_per_step)

    def most_samples(self) -> int:
        """The most samples the run may record beside its steps, within :data:`RECORD_MEMORY_BYTES`."""
        spare = RECORD_MEMORY_BYTES / (RECORD_COPIES * BYTES_PER_VALUE) - self.steps * self.values_per_step
        return max(0, int(spare // self.values_per_sample))


def record_plan(loaded: LoadedSystem, segments: list[Segment], sample_interval: float,
                options: ModelOptions) -> RecordPlan:
    """The records of a run over ``segments`` sampled every ``sample_interval`` [s] (:class:`RecordPlan`).

    A sample holds the time, every sensor's and the ambient's reading and D, each part's mean, each
    source's heat and the heat lost since the start, the moving group's offset, the screw's temperature
    and displacement in each of its cells and the positioning error at each grid position (the grid of
    the built-in models, :func:`screw_grid`); a step its end, its length and the probes' readings.
    """
    system = loaded.system
    end = segments[-1].t1
    samples = math.floor(end / sample_interval + 1e-9) + 2  # 0, interval, ... and the end (sample_times)
    cells, positions = screw_grid(system, options)
    probes = len(system.sensors) + 2  # the sensors, the ambient and D
    per_sample = 1 + probes + len(system.parts) + len(system.sources) + 2 + 2 * cells + positions
    steps = estimated_steps(_stroke(system), segments, options)
    return RecordPlan(samples, per_sample, steps, 2 + probes)


def screw_grid(system: FeedSystem, options: ModelOptions) -> tuple[int, int]:
    """The screw's axial cells and the moving group's grid positions of the built-in models: at least
    ``axial_cells`` cells along the screw and ``steps_per_stroke`` positions over the stroke, the cell
    dividing the stroke (models/fast/layout.py, models/fem/bench.py); (0, 1) without a feed drive."""
    if system.kinematics is None:
        return 0, 1
    from ..system.geometry import bounds

    lo, hi = bounds(system.parts[system.kinematics.screw])
    length, stroke = hi[0] - lo[0], system.kinematics.stroke
    count = max(options.steps_per_stroke, math.ceil(stroke / (length / options.axial_cells)))
    return max(1, round(length / (stroke / count))), count + 1


def _check_record_memory(loaded: LoadedSystem, segments: list[Segment], sample_interval: float,
                         options: ModelOptions) -> None:
    """Refuse, before anything is allocated, a run whose records would not fit :data:`RECORD_MEMORY_BYTES`."""
    plan = record_plan(loaded, segments, sample_interval, options)
    if plan.bytes <= RECORD_MEMORY_BYTES:
        return
    end = segments[-1].t1
    most = plan.most_samples()
    # the smallest interval whose samples fit, rounded up to two significant digits
    smallest = _rounded_up(end / max(most - 2, 1))
    raise FeedthermError(
        f"--sample-interval: {sample_interval:g} s over the run's {end:g} s gives {plan.samples:,} samples of "
        f"{plan.values_per_sample:,} values, about {_size(plan.bytes)} held ({RECORD_COPIES} copies of "
        f"{BYTES_PER_VALUE}-byte values) against the {_size(RECORD_MEMORY_BYTES)} a run's records may hold: "
        f"{most:,} samples at most; give --sample-interval {smallest:g} or more, or a shorter --duration")


def _rounded_up(value: float) -> float:
    """``value`` rounded up to two significant digits (a number a user types, never below ``value``)."""
    scale = 10.0 ** (math.floor(math.log10(value)) - 1)
    return math.ceil(value / scale - 1e-9) * scale


def _size(n_bytes: float) -> str:
    for unit, size in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6)):
        if n_bytes >= size:
            return f"{n_bytes / size:.3g} {unit}"
    return f"{n_bytes / 1e3:.3g} kB"


def _check_arguments(model, duration, sample_interval, motion, mesh, solver, start) -> ModelEntry:
    entry = model_entry(model)
    if duration is not None and not duration > 0:
        raise ArgumentError("duration", f"must be positive, got {duration!r} s")
    if motion not in (None, *MOTIONS):
        raise ArgumentError("motion", f"must be resolved, exact or averaged, got {motion!r}")
    if mesh not in (None, *MESHES):
        raise ArgumentError("mesh", f"must be one of {', '.join(MESHES)}, got {mesh!r}")
    if solver not in (None, *SOLVERS):
        raise ArgumentError("solver", f"must be one of {', '.join(SOLVERS)}, got {solver!r}")
    if not sample_interval > 0:
        raise ArgumentError("sample_interval", f"must be positive, got {sample_interval!r} s")
    if start not in STARTS:
        raise ArgumentError("start", f"must be 'initial' or 'steady', got {start!r}")
    return entry


def _segments(loaded: LoadedSystem, duty: list[DutySegment], end: float, single_drive: bool) -> list[Segment]:
    system = loaded.system
    cache: dict[OperatingPoint, object] = {}
    out = []
    starts = [s.start for s in duty] + [end]
    for seg, t1 in zip(duty, starts[1:]):
        if system.kinematics is None and (seg.screw_speed != 0.0 or seg.nut_speed != 0.0):
            raise FeedthermError(f"--cycle: a segment from {seg.start:g} s turns a motor, but {loaded.origin} has no "
                                 "feed drive ([kinematics] is left out); give its speeds as 0 rpm")
        point = OperatingPoint(seg.screw_speed * RPM_PER_RAD_S, seg.nut_speed * RPM_PER_RAD_S, seg.ambient,
                               0.0 if system.kinematics is None else system.kinematics.lead)
        if single_drive:
            point = replace(point, screw_rpm=point.relative_rpm, nut_rpm=0.0, nut_motor_off=True)
        if point not in cache:
            cache[point] = boundary_at(loaded, point)
        out.append(Segment(seg.start, t1, cache[point], getattr(seg, "table_at", None)))
    return out
