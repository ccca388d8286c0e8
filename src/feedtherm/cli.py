"""Command-line interface: one small function per subcommand, calling the public API.

Every input error ends as one line on stderr, exit code 2, no traceback.
"""

from __future__ import annotations

import argparse
import math
import os
import signal
import sys
import threading
import time
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path

from . import __version__
from .errors import ArgumentError, FeedthermError, ModelError, Terminated, cli_message
from .models.options import MOTIONS


class _Parser(argparse.ArgumentParser):
    """argparse that reports a usage error as one line (and exit code 2)."""

    def error(self, message: str) -> None:  # noqa: D401 - argparse API
        self.exit(2, f"feedtherm: error: {message} (see feedtherm {self.prog.split()[-1]} --help)\n"
                  if " " in self.prog else f"feedtherm: error: {message} (see feedtherm --help)\n")


def _load(spec: str):
    from .system.load import load_system

    return load_system(spec)


def _load_in_mode(args: argparse.Namespace):
    """The description of ``args.system`` set to run in ``args.mode`` (:func:`feedtherm.plan.with_mode`)."""
    from .plan import with_mode

    return with_mode(_load(args.system), args.mode)


@contextmanager
def _naming(origin: str):
    """An error of the description that only its evaluation or its run finds (a heat, a
    coefficient, the model) names the description's file, as the loader's errors do."""
    try:
        yield
    except ModelError as exc:
        message = str(exc)
        if message.startswith(f"{origin}: "):
            raise
        raise ModelError(f"{origin}: {message}") from None


def _condition(loaded, name: str) -> str:
    conditions = loaded.system.conditions
    if name not in conditions:
        raise ArgumentError("condition", f"no condition {name!r} in {loaded.origin}; conditions: {', '.join(conditions)}")
    return name


def cmd_heat(args: argparse.Namespace) -> int:
    from .boundary import boundary_conditions
    from .outputs.heat_report import heat_json, print_heat

    from .plan import boundary_of
    from .system.overlay import available_overlay

    loaded = _load_in_mode(args)
    condition = _condition(loaded, args.condition)
    with _naming(loaded.origin):
        bc = boundary_of(loaded, condition)
    printed = available_overlay(loaded)
    if args.json:
        print(heat_json(bc, printed))
    else:
        print_heat(bc, loaded.system.meta.name, printed=printed)
    return 0


def cmd_modes(args: argparse.Namespace) -> int:
    from .analysis.thermal_modes import thermal_modes
    from .outputs.modes_report import modes_json, print_modes

    loaded = _load_in_mode(args)
    condition = _condition(loaded, args.condition)
    with _naming(loaded.origin):
        result = thermal_modes(loaded, condition, count=args.count)
    if args.json:
        print(modes_json(result))
    else:
        print_modes(result, loaded.system.meta.name)
    return 0


def cmd_check(args: argparse.Namespace) -> int:
    from .outputs.check_report import BASIS, area_lines, cost_lines, size_lines
    from .plan import model_sizes, plan_run, run_cost
    from .system.checks import check_system
    from .system.load import parse_toml, read_text, validate_data

    text, origin = read_text(args.system)
    loaded = validate_data(parse_toml(text, origin), origin)  # the schema; the checks below list every error
    findings = check_system(loaded.system)
    errors = [f for f in findings if f.severity == "error"]
    if errors:
        for finding in errors:
            print(f"feedtherm: error: {origin}: {finding}", file=sys.stderr)
        return 2
    system = loaded.system
    from .system.overlay import overlay_path, overlay_spec, read_overlay

    # The overlay of printed values `--mode` would lay over the physics, read and checked as `heat` reads it.
    overlay_file = overlay_path(loaded)
    overlay = None if overlay_file is None else read_overlay(overlay_file, system)
    # What `heat` and `run` would meet: every condition's and duty cycle's heats and
    # coefficients evaluated, and its step count planned (a model is not built).
    costs, sizes, first = [], model_sizes(system), None
    for kind, names in (("condition", system.conditions), ("cycle", system.duty_cycles), ("test", system.tests)):
        section = {"condition": "conditions", "cycle": "duty_cycles", "test": "tests"}[kind]
        for name in names:
            try:
                plan = plan_run(loaded, **{kind: name}, duration=args.duration)
            except FeedthermError as exc:
                raise FeedthermError(f"{loaded.origin}: {section}.{name}: {cli_message(exc)}") from None
            cost = run_cost(plan, sizes)
            first = first or cost
            costs.extend(cost_lines(f"{section}.{name}", plan.end - plan.segments[0].t0, cost))
    print(f"{loaded.origin}: valid description '{system.meta.name}' — {len(system.parts)} parts, "
          f"{len(system.joints)} joints, {len(system.sources)} heat sources, {len(system.surfaces)} surfaces, "
          f"{len(system.sensors)} sensors, {len(system.conditions)} conditions"
          + (f", {len(system.tests)} tests" if system.tests else "") + f"; sha256 {loaded.sha256[:12]}")
    if overlay is not None:
        print(f"overlay '{overlay.name}' ({overlay_spec(loaded)}, --mode {overlay.name}): {len(overlay.heat)} printed "
              f"heats and {len(overlay.chtc)} CHTCs at condition {overlay.reference_condition}")
    if not findings:
        print("no inconsistencies found")
    for finding in findings:
        print(f"warning: {finding}")
    for line in area_lines(loaded) + (size_lines(first) if first else []) + costs + ([BASIS] if costs else []):
        print(line)
    return 0


#: FE mesh densities `--mesh` offers.
MESHES = ("coarse", "medium", "fine")
#: A run shows a progress bar only once it has lasted this long [s]: short runs stay quiet.
PROGRESS_DELAY_S = 1.0


def cmd_run(args: argparse.Namespace) -> int:
    from .outputs.files import check_output_dir
    from .outputs.run_files import default_out_dir, equilibrium_line, summary_line, write_run
    from .models.options import ModelOptions
    from .plan import plan_run

    loaded = _load_in_mode(args)
    # one description: a reduced model built for it is trained at its own numbers (models/reduced/store.py)
    options = ModelOptions(reduced_training="description")
    if args.max_step is not None:
        options = replace(options, max_step=args.max_step)
    if args.window_step is not None:
        options = replace(options, window_step=args.window_step)
    measured = None
    if args.measured:
        from .system.measurements import read_description_measurements

        measured = read_description_measurements(loaded.system, args.measured, None)
    with _naming(loaded.origin):
        plan = plan_run(loaded, condition=args.condition, cycle=args.cycle, model=args.model,
                        duration=args.duration, single_drive=args.single_drive, sample_interval=args.sample_interval,
                        motion=args.motion, mesh=args.mesh, solver=args.solver, factor_memory=args.factor_memory,
                        options=options, measured=measured)
    out_dir = Path(args.out) if args.out else default_out_dir(args.system, plan.label, plan.mode)
    check_output_dir(out_dir)
    # Imported only now: every input error above is reported without loading the model.
    from .simulate import execute

    with _LazyProgress(enabled=sys.stdout.isatty()) as progress, _naming(loaded.origin):
        solution = execute(plan, progress)
    write_run(solution, out_dir, sample_interval=args.sample_interval, figures=not args.no_plots)
    print(summary_line(solution, out_dir))
    equilibrium = equilibrium_line(solution)
    if equilibrium:
        print(equilibrium)
    return 0


def cmd_calculix(args: argparse.Namespace) -> int:
    from .outputs.calculix_files import write_calculix
    from .outputs.files import check_output_dir
    from .outputs.run_files import default_out_dir
    from .plan import plan_run

    loaded = _load_in_mode(args)
    condition = _condition(loaded, args.condition)
    with _naming(loaded.origin):
        plan = plan_run(loaded, condition=condition, model="fem", mesh=args.mesh)
    out_dir = Path(args.out) if args.out else default_out_dir(args.system, f"{condition}_calculix", plan.mode)
    check_output_dir(out_dir)
    duration = args.duration if args.duration is not None else plan.segments[-1].t1 - plan.segments[0].t0
    if args.step > duration:
        raise FeedthermError(f"--step: {args.step:g} s is longer than the run ({duration:g} s)")
    with _naming(loaded.origin):
        model = plan.model.build(loaded.system, plan.options)
    last = len(model.positions) - 1
    k = last // 2 if args.position is None else args.position
    if not 0 <= k <= last:
        raise FeedthermError(f"--position: {k} is not a grid position of the moving group (0 to {last}; "
                             f"{last // 2} is mid-stroke)")
    files = write_calculix(model, plan.segments[0].bc, k, out_dir, condition=condition, time_step=args.step,
                           duration=duration, output_interval=args.every)
    print(f"{files[0]}: {model.n_nodes:,} nodes, moving group at position {k} of 0..{last} "
          f"(offset {model.positions[k] * 1e3:+.1f} mm); run: cd {out_dir} && ccx -i feedtherm")
    return 0


def cmd_new(args: argparse.Namespace) -> int:
    from .benches.template import new_bench

    folder = new_bench(args.name, args.out)
    print(f"{folder}: a new bench (a single-drive ball-screw axis to adapt; {folder / 'README.md'} says how). "
          f"Next: feedtherm check {folder / 'description.toml'}")
    return 0


def cmd_benches(args: argparse.Namespace) -> int:
    from .benches import benches

    for bench in benches():
        measured = "measurements" if bench.measurements is not None else "no measurements"
        print(f"{bench.name:<20} {bench.title} ({measured}; from {bench.provider})")
    return 0


def cmd_models(args: argparse.Namespace) -> int:
    from .models.registry import available_models

    for entry in available_models().values():
        print(f"{entry.name:<10} {entry.summary}" + ("  [--mesh]" if entry.uses_mesh else ""))
    return 0


def _positive_number(text: str, what: str = "number") -> float:
    """argparse type: a finite number > 0."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"must be a positive {what}, got {text!r}")
    return value


def _positive_int(text: str) -> int:
    """argparse type: a whole number > 0."""
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value <= 0:
        raise argparse.ArgumentTypeError(f"must be a positive whole number, got {text!r}")
    return value


def _grid_position(text: str) -> int:
    """argparse type: a whole number >= 0."""
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value < 0:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 0, got {text!r}")
    return value


def _positive_seconds(text: str) -> float:
    """argparse type: a finite number of seconds > 0."""
    return _positive_number(text, "number of seconds")


def _gigabytes(text: str) -> float:
    """argparse type: a finite number of gigabytes > 0, as bytes."""
    return _positive_number(text, "number of GB") * 1e9


def cmd_sweep(args: argparse.Namespace) -> int:
    from .analysis.execution import resolve_execution
    from .analysis.sweep import SweepFailed, columns, parse_grid, point_key, run_sweep, sensor_labels, sweep_settings
    from .outputs.files import check_output_dir
    from .outputs.run_files import default_out_dir
    from .outputs.sweep_partial import PARTIAL_DIR, PartialSweep
    from .plan import with_mode
    from .system.schema import DEFAULT_DURATION_S, feed_drive

    started = time.perf_counter()
    execution = resolve_execution(args.workers, args.scheduler)
    loaded = _load(args.system)
    grid = parse_grid(args.screw_rpm, args.nut_rpm, args.ambient,
                      drive=feed_drive(loaded.system, "feedtherm sweep").drive)
    loaded = with_mode(loaded, args.mode)
    out_dir = Path(args.out) if args.out else default_out_dir(args.system, "sweep", args.mode)
    check_output_dir(out_dir)
    # Every finished point is kept in out_dir/.sweep-partial at once, so that an interrupted
    # sweep loses at most the runs under way; --resume reads them back.
    settings = sweep_settings(loaded, duration=args.duration, motion=args.motion)
    keys = [point_key(settings, point) for point in grid.points()]
    sensors = sensor_labels(loaded)
    partial = PartialSweep(out_dir, settings, columns(list(sensors)))
    partial.open(resume=args.resume)
    known = partial.load(keys) if args.resume else {}
    from .outputs.sweep_files import summary_line, sweep_title, write_sweep

    # The model is imported only inside run_sweep: every input error above comes first.
    failures = []
    duration = args.duration if args.duration is not None else DEFAULT_DURATION_S
    try:
        with _LazyProgress(enabled=sys.stdout.isatty()) as progress:
            try:
                rows = run_sweep(loaded, grid, duration=args.duration, motion=args.motion,
                                 progress=progress, execution=execution, known=known,
                                 on_row=lambda index, row: partial.save(keys[index], row))
            except SweepFailed as failed:  # the points that ran are written; each failed one is a line
                rows, failures = failed.rows, failed.failures
        if rows:
            # On success the kept points go in the same swap as the new files; with failed points
            # they stay, so that --resume runs only the failed ones.
            write_sweep(rows, sensors, out_dir, drop=() if failures else (PARTIAL_DIR,),
                        title=sweep_title(loaded.system.meta.name, args.mode, args.motion, duration))
    except KeyboardInterrupt as stop:
        kept = partial.count()
        if not kept or not partial.folder.is_dir():  # nothing kept, or already swapped out with the files in
            raise
        raise type(stop)(f"{kept} of {len(keys)} points kept in {partial.folder}; the same command with "
                         f"--resume runs only the others") from None
    if rows:
        print(summary_line(out_dir, len(rows), time.perf_counter() - started,
                           resumed=len(known) if args.resume else None))
        overloaded = [row for row in rows if (row.get("motor_duty") or 0.0) > 1.0]
        if overloaded:
            worst = max(overloaded, key=lambda row: row["motor_duty"])
            print(f"warning: {len(overloaded)} of {len(rows)} points need more than a motor's continuous torque "
                  f"(motor_duty > 1 in sweep.csv; the most, {100 * worst['motor_duty']:.0f} %, at screw "
                  f"{worst['screw_rpm']:g} rpm, nut {worst['nut_rpm']:g} rpm): computed as declared, but no machine "
                  "with these motors runs there")
    for failure in failures:
        print(f"feedtherm: error: {failure}", file=sys.stderr)
    # 1, not 2: the input was valid and the points that ran are written (2 means nothing was).
    return 1 if failures else 0


class _LazyProgress:
    """A progress callback that shows a rich bar only once the run has lasted a while.

    Runs shorter than ``PROGRESS_DELAY_S`` print nothing; a bar appears on the first call
    after that.  It is transient (gone when the run ends), so only the final line remains.
    """

    def __init__(self, *, enabled: bool, delay: float = PROGRESS_DELAY_S, clock=time.monotonic):
        self._enabled = enabled
        self._delay = delay
        self._clock = clock
        self._started = clock()
        self._bar = None
        self._task = None

    def __enter__(self) -> "_LazyProgress":
        return self

    def __exit__(self, *exc_info) -> None:
        if self._bar is not None:
            self._bar.stop()

    def __call__(self, fraction: float) -> None:
        if not self._enabled:
            return
        completed = min(max(float(fraction), 0.0), 1.0)
        if self._bar is None:
            if self._clock() - self._started < self._delay:
                return
            self._start_bar(completed)
        else:
            self._bar.update(self._task, completed=completed)

    def _start_bar(self, completed: float) -> None:
        from rich.progress import BarColumn, Progress, TaskProgressColumn, TextColumn, TimeRemainingColumn

        self._bar = Progress(TextColumn("simulating"), BarColumn(), TaskProgressColumn(), TimeRemainingColumn(),
                             transient=True)
        self._task = self._bar.add_task("simulating", total=1.0, completed=completed)
        self._bar.start()  # after the task has its fraction, so the first frame is not 0 %


def cmd_validate(args: argparse.Namespace) -> int:
    from .outputs.files import check_output_dir
    from .outputs.run_files import default_out_dir

    from .models.registry import model_entry

    loaded = _load_in_mode(args)
    model_entry(args.model)  # an unknown model fails before any run
    out_dir = Path(args.out) if args.out else default_out_dir(args.system, "validation", args.mode)
    check_output_dir(out_dir)
    from .analysis.validation import measurements_of, validate
    from .outputs.validation_files import print_validation, write_validation

    measurements_of(loaded, args.measured)  # bad measurement files fail before any run
    from .outputs.calibration_files import read_calibration_summary

    calibration = read_calibration_summary(Path(args.calibration)) if args.calibration else None
    from .outputs.compensation_files import read_compensation_summary

    compensation = read_compensation_summary(Path(args.compensation)) if args.compensation else None
    from .outputs.uncertainty_files import read_uncertainty_summary

    uncertainty = read_uncertainty_summary(Path(args.uncertainty)) if args.uncertainty else None
    with _LazyProgress(enabled=sys.stdout.isatty()) as progress:
        validation = validate(loaded, model=args.model, mesh=args.mesh, motion=args.motion, measured=args.measured,
                              progress=progress, calibration=calibration, compensation=compensation,
                              uncertainty=uncertainty)
    write_validation(validation, out_dir)
    print_validation(validation, out_dir)
    return 0


def _model_and_mesh(args: argparse.Namespace) -> dict:
    """``--model`` checked against the registry (an unknown name: one line naming ``--model``) and
    ``--mesh`` where that model takes one: the ``model``/``mesh`` keywords of a study."""
    from .models.registry import model_entry

    entry = model_entry(args.model)
    return {"model": entry.name, "mesh": args.mesh if entry.uses_mesh else None}


def cmd_calibrate(args: argparse.Namespace) -> int:
    from .outputs.files import check_output_dir
    from .outputs.run_files import default_out_dir

    from .analysis.execution import Execution, kept_open, resolve_execution

    execution = resolve_execution(args.workers, args.scheduler)
    if execution.serial and args.workers is None:
        # Hundreds of runs in batches of a few: a local cluster of one worker per core, kept for
        # the whole calibration, gains 1.2-1.5x on 2 cores (benchmarks/README.md); --workers 1 is serial.
        cores = os.cpu_count() or 1
        execution = Execution(workers=cores) if cores > 1 else execution
    loaded = _load_in_mode(args)
    model = _model_and_mesh(args)  # an unknown model fails before any run
    out_dir = Path(args.out) if args.out else default_out_dir(args.system, "calibration", args.mode)
    check_output_dir(out_dir)
    from .analysis.calibration import RunCache, calibrate, cross_validate, resolve_parameters
    from .analysis.consistency import check_description_measurements
    from .analysis.validation import measurements_of
    from .outputs.calibration_files import print_calibration, write_calibration

    data = measurements_of(loaded, args.measured)
    names = [n.strip() for n in args.params.split(",") if n.strip()]
    fit = [c.strip() for c in args.fit.split(",") if c.strip()]
    resolve_parameters(loaded, names)  # unknown names and missing bounds fail before any run
    consistency = check_description_measurements(loaded.system, data)
    # One cluster (or one connection to the scheduler) for the fit and every leave-one-out fold:
    # a calibration is hundreds of short runs in small batches.
    with kept_open(execution) as running:
        options = {"consistency": consistency, "equilibrium": not args.no_equilibrium,
                   "execution": running, "cache": RunCache(), **model}
        with _LazyProgress(enabled=sys.stdout.isatty()) as progress:
            result = calibrate(loaded, data, fit, names, progress=progress, **options)
        cross = None
        if args.cross_validate:
            with _LazyProgress(enabled=sys.stdout.isatty()) as progress:
                cross = cross_validate(loaded, data, names, progress=progress, start=result.fitted, **options)
    write_calibration(loaded, result, out_dir, cross)
    print_calibration(result, out_dir, cross)
    return 0


def cmd_infer(args: argparse.Namespace) -> int:
    from .models.registry import model_entry
    from .outputs.files import check_output_dir
    from .outputs.run_files import default_out_dir

    loaded = _load_in_mode(args)
    model_entry(args.model)
    out_dir = Path(args.out) if args.out else default_out_dir(args.system, "inference", args.mode)
    check_output_dir(out_dir)
    from .analysis.inverse import Noise, infer_conditions
    from .analysis.validation import measurements_of
    from .outputs.inference_files import print_inference, write_inference

    data = measurements_of(loaded, args.measured)
    conditions = [c.strip() for c in args.conditions.split(",") if c.strip()] if args.conditions else data.conditions()
    noise = Noise(args.sigma_temperature, args.sigma_elongation * 1e-6)
    results = infer_conditions(loaded, data, conditions, groups=args.groups, noise=noise,
                               prior_width=args.prior_width, model=args.model)
    context = {"system": loaded.origin, "mode": args.mode, "model": args.model, "measurements": data.source,
               "sigma_temperature_K": args.sigma_temperature, "sigma_elongation_um": args.sigma_elongation,
               "prior_width": args.prior_width}
    write_inference(results, out_dir, context)
    print_inference(results, out_dir)
    return 0


def _integer(text: str) -> int:
    """argparse type: a whole number (any sign)."""
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a whole number, got {text!r}") from None


def cmd_compensate(args: argparse.Namespace) -> int:
    from .analysis.candidates import candidate_sensors
    from .analysis.compensation.data import StudySettings
    from .analysis.compensation.study import parse_sensors
    from .analysis.random_cycles import CycleRanges
    from .models.registry import model_entry
    from .outputs.files import check_output_dir
    from .outputs.run_files import default_out_dir
    from .system.schema import feed_drive

    from .analysis.execution import resolve_execution

    started = time.perf_counter()
    execution = resolve_execution(args.workers, args.scheduler)
    loaded = _load_in_mode(args)
    feed_drive(loaded.system, "feedtherm compensate")
    model_entry(args.model)
    request = parse_sensors(args.sensors, candidate_sensors(loaded.system))
    ranges = CycleRanges() if args.duration is None else CycleRanges(duration=args.duration)
    settings = StudySettings(cycles=args.cycles, seed=args.seed, ranges=ranges, model=args.model,
                             mesh=args.mesh if args.model != "fast" else None)
    out_dir = Path(args.out) if args.out else default_out_dir(args.system, "compensation", args.mode)
    check_output_dir(out_dir)
    from .analysis.compensation.measured import predict_measured
    from .analysis.compensation.study import run_study
    from .analysis.validation import measurements_of
    from .outputs.compensation_files import summary_line, write_compensation

    from .analysis.compensation.adaptation import adapt_study, check_adaptation_file, loco_study
    from .system.measurements import read_measurements

    adapt_data = None
    if args.adapt:  # read and checked before the long run; sensors chosen by the study are checked after it
        adapt_data = read_measurements(args.adapt)
        check_adaptation_file(loaded, adapt_data, None if isinstance(request, int) else request)
    try:  # the measured bench, where the description has measurements (read before the long run)
        data = measurements_of(loaded, None)
    except FeedthermError:
        data = None
    from .analysis.compensation.data import study_cost

    print(f"compensate: {study_cost(loaded, settings).describe(execution.workers or 1)}", flush=True)
    with _LazyProgress(enabled=sys.stdout.isatty()) as progress:
        result = run_study(loaded, settings, request, progress, execution)
    measured = {} if data is None else {kind: predict_measured(r.law, loaded, data)
                                         for kind, r in result.declared.items()}
    adapted = None if adapt_data is None else adapt_study(result, loaded, adapt_data)
    write_compensation(result, loaded, out_dir, measured=measured, adapted=adapted, adapt_data=adapt_data,
                       loco=loco_study(result, loaded, data))
    print(summary_line(out_dir, result, time.perf_counter() - started))
    return 0


def _positions(text: str) -> tuple[float, ...]:
    """argparse type: table positions with their unit, separated by commas ("150 mm,200 mm") [m]."""
    from .system.quantities import to_si

    out = []
    for item in text.split(","):
        try:
            out.append(to_si(item.strip(), "m"))
        except ValueError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None
    return tuple(out)


def cmd_correct(args: argparse.Namespace) -> int:
    from .analysis.compensation.apply import correct, read_law
    from .outputs.correction_files import print_correction, write_correction
    from .outputs.files import check_output_dir

    law = read_law(args.law)
    out_dir = Path(args.out) if args.out else Path("out") / f"{Path(args.law).stem}_correction"
    check_output_dir(out_dir)
    corrections = correct(law, args.readings, args.x or ())
    write_correction(corrections, out_dir, {"law": str(args.law), "readings": str(args.readings)})
    for warning in law.warnings:
        print(f"warning: {warning}")
    print_correction(corrections, out_dir)
    return 0


def _quantity_of(si_unit: str):
    """argparse type: one quantity with its unit, in ``si_unit``."""
    def parse(text: str) -> float:
        from .system.quantities import to_si

        try:
            return to_si(text.strip(), si_unit)
        except ValueError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None
    return parse


def _temperature_range(text: str) -> tuple[float, float]:
    """argparse type: "LOW,HIGH" temperatures with their unit ("5 degC,45 degC") [K]."""
    parts = text.split(",")
    if len(parts) != 2:
        raise argparse.ArgumentTypeError(f"must be two temperatures, low and high, as \"5 degC,45 degC\"; got {text!r}")
    low, high = (_quantity_of("K")(part) for part in parts)
    return low, high


def cmd_export(args: argparse.Namespace) -> int:
    from .outputs.controller.export import ExportOptions, export_law
    from .outputs.files import check_output_dir

    out_dir = Path(args.out) if args.out else Path("out") / f"{Path(args.law).stem}_{args.to}"
    check_output_dir(out_dir)
    options = ExportOptions(args.to, args.name, args.valid_range, args.margin, args.max_rate, args.start, args.x_ref,
                            args.axis, args.units)
    summary = export_law(args.law, options, out_dir)
    for warning in summary["warnings"]:
        print(f"warning: {warning}")
    guards = summary["guards"]
    print(f"{out_dir}: {', '.join(summary['files'])}")
    print(f"  {summary['kind']} on {', '.join(i['name'] for i in summary['inputs'])}; rate limit "
          f"{guards['max_rate_m_per_s'] * 1e6:g} um/s; valid range from {guards['valid_range_from']}; start "
          f"{guards['start']}")
    if "offset_slope" in summary:
        form = summary["offset_slope"]
        print(f"  offset and slope about x = {form['x_ref_m'] * 1e3:g} mm: error at most "
              f"{form['reduction_error_bound_m'] * 1e6:.3g} um over the stroke for inputs within {form['ranges_from']}")
    return 0


def _power_of_two(text: str) -> int:
    """argparse type: a power of 2 (Sobol' points are balanced only in such sets)."""
    value = _positive_int(text)
    if value & (value - 1):
        raise argparse.ArgumentTypeError(f"must be a power of 2 (Sobol' points are balanced only in such sets), "
                                         f"got {text!r}")
    return value


def cmd_uncertainty(args: argparse.Namespace) -> int:
    from .analysis.execution import resolve_execution
    from .outputs.files import check_output_dir
    from .outputs.run_files import default_out_dir

    execution = resolve_execution(args.workers, args.scheduler)
    loaded = _load_in_mode(args)
    from .analysis.uncertainty.declared import resolve_uncertainties

    resolve_uncertainties(loaded)  # a system without declared uncertainties fails before anything else
    if args.condition is None:
        args.condition = next(iter(loaded.system.conditions))
    if not args.no_sobol:
        _condition(loaded, args.condition)
    model = _model_and_mesh(args)  # an unknown model fails before any run
    out_dir = Path(args.out) if args.out else default_out_dir(args.system, "uncertainty", args.mode)
    check_output_dir(out_dir)
    from .analysis.consistency import check_description_measurements
    from .analysis.uncertainty.posterior import read_posterior
    from .analysis.uncertainty.study import run_uncertainty
    from .analysis.validation import measurements_of
    from .outputs.calibration_files import read_calibration_summary

    try:  # the measurements the final values are judged against, where the description has them
        data = measurements_of(loaded, args.measured)
    except FeedthermError:
        if args.measured:
            raise
        data = None
    consistency = check_description_measurements(loaded.system, data) if data is not None else None
    posterior = None
    if args.calibration and args.update_with:
        raise FeedthermError("--update-with and --calibration: give one (the priors updated with measurements, or "
                             "a calibration folder's posterior)")
    update_with = _update_conditions(loaded, args.update_with, data) if args.update_with else None
    if args.calibration:
        folder = Path(args.calibration)
        posterior = read_posterior(folder, loaded, read_calibration_summary(folder))
    if update_with:
        from .analysis.uncertainty.update import bayesian_update

        posterior = bayesian_update(loaded, data, update_with, consistency=consistency,
                                    execution=execution, **model)
    from .outputs.uncertainty_files import print_uncertainty, write_uncertainty

    with _LazyProgress(enabled=sys.stdout.isatty()) as progress:
        study = run_uncertainty(loaded, samples=args.samples, sobol_base=None if args.no_sobol else args.sobol_base,
                                seed=args.seed, sobol_condition=args.condition, data=data,
                                consistency=consistency, posterior=posterior, execution=execution, progress=progress,
                                **model)
    write_uncertainty(study, out_dir)
    print_uncertainty(study, out_dir)
    return 0


def _update_conditions(loaded, text: str, data) -> list[str]:
    """The conditions of ``--update-with A,B,C``, each once, with measurements to update with
    (:func:`~feedtherm.analysis.uncertainty.update.bayesian_update` checks that each is known
    and measured, before any run)."""
    conditions = [c.strip() for c in text.split(",")]
    if any(not c for c in conditions) or len(set(conditions)) != len(conditions):
        raise FeedthermError(f"--update-with: {text!r} is not a comma-separated list of distinct conditions, "
                             f"such as A,B,C")
    if data is None:
        raise FeedthermError(f"--update-with: {loaded.origin} has no measurements to update with; give --measured CSV")
    return conditions


def _system_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("system", nargs="?", default="paper",
                        help="a TOML description or a bench name of `feedtherm benches` (default: paper)")


def _mode_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--mode", default="physics", metavar="MODE",
                        help="physics (default): every value from the correlations; or the name of the printed "
                             "values the bench lays over them (its overlay.toml: paper for the paper bench)")


def _measured_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--measured", metavar="FILE",
                        help="measurements: final values (condition,quantity,unit,measured) or time series "
                             "(condition,time [min],quantity,value,unit[,uncertainty]; docs/measurements.md); "
                             "default: the description's own")


def _directory(text: str) -> str:
    """argparse type: a directory's path, not empty (an empty one would write into the current directory)."""
    if not text.strip():
        raise argparse.ArgumentTypeError("an empty path; name a directory")
    return text


def _out_argument(parser: argparse.ArgumentParser, default: str) -> None:
    parser.add_argument("--out", type=_directory, metavar="DIR", help=f"output directory (default: {default})")


def _execution_arguments(parser: argparse.ArgumentParser, default: str = "one after another in this process") -> None:
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--workers", type=_positive_int, metavar="N",
                       help=f"run the batch's runs on a local Dask cluster of N worker processes (default: "
                            f"{default}; the results are the same)")
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="run the batch's runs on the running Dask scheduler at ADDRESS, e.g. tcp://10.0.0.5:8786 "
                            "(default: $DASK_SCHEDULER_ADDRESS when set); its workers need feedtherm installed")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="feedtherm", description="Thermal model of machine-tool feed drives.")
    parser.add_argument("--version", action="version", version=f"feedtherm {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    heat = sub.add_parser("heat", help="heat per source and CHTC per surface at a condition")
    _system_argument(heat)
    heat.add_argument("--condition", required=True, help="a condition of the description")
    _mode_argument(heat)
    heat.add_argument("--json", action="store_true", help="print one JSON object")
    heat.set_defaults(func=cmd_heat)

    modes = sub.add_parser("modes", help="the slowest thermal modes of a condition (fast model): time constants, "
                                         "the parts that store their heat, and how each sensor sees them")
    _system_argument(modes)
    modes.add_argument("--condition", required=True, help="a condition of the description")
    _mode_argument(modes)
    modes.add_argument("--count", type=_positive_int, default=6, help="how many modes (default 6)")
    modes.add_argument("--json", action="store_true", help="print one JSON object")
    modes.set_defaults(func=cmd_modes)

    check = sub.add_parser("check", help="validate a description and list its inconsistencies")
    _system_argument(check)
    check.add_argument("--duration", type=_positive_seconds, metavar="S",
                       help="estimate the runs' cost over S seconds each (default: each condition's, cycle's or "
                            "test's own length), as `run --duration S` would run them")
    check.set_defaults(func=cmd_check)

    run = sub.add_parser("run", help="simulate a condition or a duty cycle and write CSV, JSON and PNG files")
    _system_argument(run)
    operation = run.add_mutually_exclusive_group(required=True)
    operation.add_argument("--condition", help="a condition or a test of the description")
    operation.add_argument("--test", dest="condition", help="a test of the description (docs/tests.md), or a condition")
    operation.add_argument("--cycle", help="a duty cycle declared in the description, or a CSV file "
                                           "(time_s,screw_rpm,nut_rpm,ambient_C)")
    run.add_argument("--measured", metavar="FILE",
                     help="the measurements a test whose room or start is measured reads (default: the test's own "
                          "file, else the description's)")
    run.add_argument("--model", default="fast",
                     help="a model of `feedtherm models`: fast (thermal network, seconds), fem (3D finite "
                          "elements, minutes), ... (default fast)")
    run.add_argument("--mesh", choices=MESHES, default="coarse", help="FE mesh density (with --model fem)")
    _mode_argument(run)
    run.add_argument("--duration", type=_positive_seconds, metavar="S",
                     help="length of the run [s] (default: the condition's or the cycle's)")
    run.add_argument("--motion", choices=MOTIONS, default="resolved",
                     help="the moving nut's position over time (default; the FE and reduced models step it window "
                          "by window, docs/fem-model.md), exact (grid position by grid position in every model: "
                          "the reference), or averaged (cycle-averaged contacts and heats)")
    run.add_argument("--window-step", type=_positive_seconds, metavar="S",
                     help="with the resolved motion of the FE and reduced models: the longest a step may take to "
                          "sweep its window of the stroke [s] (default 10; shorter: more, narrower windows, "
                          "nearer the exact motion)")
    run.add_argument("--single-drive", action="store_true", help="operate a dual drive as a single (screw-only) drive")
    run.add_argument("--solver", choices=["auto", "direct", "cg"], default="auto",
                     help="linear solver of the time steps: cached factors per position (direct: PARDISO's "
                          "Cholesky where installed, SuperLU otherwise), Jacobi-preconditioned conjugate gradients "
                          "(cg), or auto: direct within half the free memory (without PARDISO: up to 60,000 "
                          "unknowns), cg beyond")
    run.add_argument("--factor-memory", type=_gigabytes, metavar="GB",
                     help="with --solver auto: the most the FE steps' factors may hold [GB] (default: half the "
                          "memory free when the run starts); the positions beyond step by conjugate gradients")
    run.add_argument("--sample-interval", type=_positive_seconds, default=10.0, metavar="S",
                     help="spacing of the written samples [s] (default: 10)")
    run.add_argument("--max-step", type=_positive_seconds, metavar="S",
                     help="the longest time step [s] (default: 10 s at a standstill and with the averaged "
                          "motion, 30 s for a slow table): shorter to resolve the first seconds after a step "
                          "change, as a held temperature's")
    run.add_argument("--no-plots", action="store_true",
                     help="write the tables (and an FE run's fields) without plots and images: faster, "
                          "for scripts that run many runs")
    _out_argument(run, "out/<system>_<condition>_<mode>")
    run.set_defaults(func=cmd_run)

    sweep = sub.add_parser("sweep", help="simulate the full grid of screw speeds × nut speeds × ambients; "
                                         "write sweep.csv and plots")
    # Lists such as -600:600:300 or -300,300 are values, not options (Python 3.11's argparse
    # takes only plain negative numbers as values; 3.13 uses this same pattern).
    import re

    sweep._negative_number_matcher = re.compile(r"^-\.?\d")
    _system_argument(sweep)
    list_help = "comma-separated values and/or ranges start:stop:step (stop included when on the grid)"
    sweep.add_argument("--screw-rpm", required=True, metavar="LIST", help=f"screw speeds [rpm], signed: {list_help}")
    sweep.add_argument("--nut-rpm", required=True, metavar="LIST",
                       help="nut speeds [rpm], signed (0 for a single drive), same syntax")
    sweep.add_argument("--ambient", required=True, metavar="LIST", help="ambient temperatures [°C], same syntax")
    _mode_argument(sweep)
    sweep.add_argument("--duration", type=_positive_seconds, metavar="S",
                       help="length of every run [s] (default: a condition's, 10800)")
    sweep.add_argument("--motion", choices=MOTIONS, default="averaged",
                       help="cycle-averaged contacts and heats (default, fast), or the nut's position over time")
    _execution_arguments(sweep)
    sweep.add_argument("--resume", action="store_true",
                       help="finish an interrupted sweep into the same --out: the points it kept are read back, "
                            "only the others run (same grid options, mode, duration and motion)")
    _out_argument(sweep, "out/<system>_sweep_<mode>")
    sweep.set_defaults(func=cmd_sweep)

    validate = sub.add_parser("validate", help="run every measured condition and compare with the measurements")
    _system_argument(validate)
    validate.add_argument("--model", default="fast", help="a model of `feedtherm models` (default fast)")
    validate.add_argument("--mesh", choices=MESHES, default="coarse", help="FE mesh density (with --model fem)")
    validate.add_argument("--motion", choices=MOTIONS, default="resolved",
                          help="the table's motion in the runs: resolved stroke by stroke (default; window by "
                               "window in the FE and reduced models), exact (grid position by grid position), or averaged "
                               "over a stroke, for fast axes whose strokes are short against the thermal time "
                               "constants (docs/fast-model.md)")
    _mode_argument(validate)
    _measured_argument(validate)
    validate.add_argument("--calibration", metavar="DIR",
                          help="output folder of `feedtherm calibrate --cross-validate`: its held-out figures "
                               "go into the report's headline")
    validate.add_argument("--compensation", metavar="DIR",
                          help="output folder of `feedtherm compensate`: its laws and figures become the report's "
                               "compensation section")
    validate.add_argument("--uncertainty", metavar="DIR",
                          help="output folder of `feedtherm uncertainty`: its bands, coverage and Sobol indices "
                               "become the report's uncertainty section")
    _out_argument(validate, "out/<system>_validation_<mode>")
    validate.set_defaults(func=cmd_validate)

    calculix = sub.add_parser("calculix", help="write the FE model at a condition, the moving group held at one "
                                               "position, as a CalculiX input deck")
    _system_argument(calculix)
    calculix.add_argument("--condition", required=True, help="a condition of the description (its first operating point)")
    calculix.add_argument("--mesh", choices=MESHES, default="coarse", help="FE mesh density (default coarse)")
    _mode_argument(calculix)
    calculix.add_argument("--position", type=_grid_position, metavar="K",
                          help="grid position of the moving group (default: mid-stroke)")
    calculix.add_argument("--step", type=_positive_seconds, default=30.0, metavar="S",
                          help="fixed time increment [s] (default 30)")
    calculix.add_argument("--duration", type=_positive_seconds, metavar="S",
                          help="length of the transient [s] (default: the condition's)")
    calculix.add_argument("--every", type=_positive_seconds, default=600.0, metavar="S",
                          help="interval of the printed nodal temperatures [s] (default 600)")
    _out_argument(calculix, "out/<system>_<condition>_calculix_<mode>")
    calculix.set_defaults(func=cmd_calculix)

    new = sub.add_parser("new", help="write a commented bench folder to adapt to your machine (a single-drive "
                                     "ball-screw axis that checks and runs as written)")
    new.add_argument("name", metavar="NAME", help="the bench's name: the folder's and meta.name")
    new.add_argument("--out", type=_directory, default=".", metavar="DIR",
                     help="the existing folder to write the folder NAME in (default: here)")
    new.set_defaults(func=cmd_new)

    bench_list = sub.add_parser("benches", help="list the bundled and plugged-in benches SYSTEM may name")
    bench_list.set_defaults(func=cmd_benches)

    infer = sub.add_parser("infer", help="infer the heat of each source (group) from measured temperatures and "
                                         "elongation, beside the loss models' heat")
    _system_argument(infer)
    _measured_argument(infer)
    infer.add_argument("--conditions", metavar="C,C,...", help="measured conditions to infer (default: all)")
    infer.add_argument("--groups", metavar="NAME=SRC,SRC;...",
                       help="sources estimated together (e.g. motors=screw_motor,nut_motor); others one by one")
    infer.add_argument("--sigma-temperature", type=_positive_number, default=0.5, metavar="K",
                       help="standard uncertainty of a measured temperature [K] (default 0.5)")
    infer.add_argument("--sigma-elongation", type=_positive_number, default=2.0, metavar="UM",
                       help="standard uncertainty of the measured elongation [µm] (default 2)")
    infer.add_argument("--prior-width", type=_positive_number, default=1.0, metavar="F",
                       help="prior standard deviation of each heat, relative to the loss models' heat (floor 1 W; "
                            "default 1.0)")
    infer.add_argument("--model", default="fast", help="a model of `feedtherm models` (default fast)")
    _mode_argument(infer)
    _out_argument(infer, "out/<system>_inference_<mode>")
    infer.set_defaults(func=cmd_infer)

    models = sub.add_parser("models", help="list the models --model accepts")
    models.set_defaults(func=cmd_models)

    calibrate = sub.add_parser("calibrate", help="fit declared parameters to measured conditions; predict the others")
    _system_argument(calibrate)
    _measured_argument(calibrate)
    calibrate.add_argument("--fit", required=True, metavar="C,C,...", help="conditions to fit, separated by commas")
    calibrate.add_argument("--params", required=True, metavar="NAME,...",
                           help="parameters declared under [calibration.parameters]")
    calibrate.add_argument("--cross-validate", action="store_true",
                           help="also leave each measured condition out in turn and predict it")
    calibrate.add_argument("--no-equilibrium", action="store_true",
                           help="fit the final values only, not the measured equilibrium times")
    calibrate.add_argument("--model", default="fast", help="a model of `feedtherm models` (default fast)")
    calibrate.add_argument("--mesh", choices=MESHES, default="coarse", help="FE mesh density (with --model fem)")
    _mode_argument(calibrate)
    _execution_arguments(calibrate, default="one worker per CPU, kept for the whole calibration; 1: serial")
    _out_argument(calibrate, "out/<system>_calibration_<mode>")
    calibrate.set_defaults(func=cmd_calibrate)

    compensate = sub.add_parser("compensate", help="fit thermal-error compensation laws on random simulated cycles, "
                                                   "choose sensor positions, judge them on other machines of the design")
    _system_argument(compensate)
    compensate.add_argument("--sensors", default="3", metavar="K|declared|NAME,...",
                            help="K sensors chosen greedily among the candidates a machine can carry, 'declared' (the "
                                 "description's own sensors), or candidate names separated by commas (default 3)")
    compensate.add_argument("--cycles", type=_positive_int, default=8, metavar="N",
                            help="cycles in each of the training, validation and test sets (default 8)")
    compensate.add_argument("--seed", type=_integer, default=0, metavar="S", help="seed of every random draw (default 0)")
    compensate.add_argument("--duration", type=_positive_seconds, metavar="S",
                            help="length of every cycle [s] (default 28800, one shift)")
    compensate.add_argument("--model", default="fast", help="a model of `feedtherm models` (default fast)")
    compensate.add_argument("--mesh", choices=MESHES, default="coarse", help="FE mesh density (with --model fem)")
    compensate.add_argument("--adapt", metavar="MEASURED.csv",
                            help="measurements of the machine (final values or time series, docs/measurements.md; "
                                 "bundled:<bench>): update the regression laws on them (law_adapted*.json)")
    _mode_argument(compensate)
    _execution_arguments(compensate)
    _out_argument(compensate, "out/<system>_compensation_<mode>")
    compensate.set_defaults(func=cmd_compensate)

    correct = sub.add_parser("correct", help="run an exported law (law*.json of `feedtherm compensate`) over logged "
                                             "readings: D, or E at table positions, at every sample")
    correct.add_argument("law", metavar="LAW.json", help="a law file of `feedtherm compensate`")
    correct.add_argument("readings", metavar="READINGS.csv",
                         help="the law's inputs logged on the machine (final values or time series, docs/measurements.md)")
    correct.add_argument("--x", type=_positions, metavar="X,...",
                         help="table positions with their unit, for a stroke law (law_stroke*.json): \"150 mm,250 mm\"")
    _out_argument(correct, "out/<law>_correction")
    correct.set_defaults(func=cmd_correct)

    export = sub.add_parser("export", help="write an exported law (law*.json) as C99 or as a LinuxCNC HAL component, "
                                           "with guards: valid input ranges, a rate limit, the power-up")
    export.add_argument("law", metavar="LAW.json", help="a law file of `feedtherm compensate` (not a Kalman estimator)")
    export.add_argument("--to", required=True, choices=("c", "linuxcnc"),
                        help="c: a header and a source; linuxcnc: those, a halcompile component and a HAL file")
    export.add_argument("--name", help="the prefix of the C names and the component's name (default "
                                       "ft_<law file's name>)")
    export.add_argument("--valid-range", type=_temperature_range, metavar="LOW,HIGH",
                        help="every input's valid range, e.g. \"5 degC,45 degC\" (default: the law's training "
                             "envelope widened by --margin); outside it the output holds")
    export.add_argument("--margin", type=_quantity_of("K"), metavar="DT",
                        help="the widening of the training envelope, e.g. \"10 K\" (default 10 K)")
    export.add_argument("--max-rate", type=_quantity_of("m/s"), metavar="RATE",
                        help="the output's largest change, e.g. \"1 um/s\" (default 1 um/s)")
    export.add_argument("--start", choices=("first-sample", "reference"), default="first-sample",
                        help="power-up: the lags settle at the first valid sample (as `correct`), or start at the "
                             "law's reference temperature; the output starts at 0 and ramps (default first-sample)")
    export.add_argument("--x-ref", type=_quantity_of("m"), metavar="X",
                        help="a stroke law: the reference position of the offset-and-slope form, e.g. \"300 mm\" "
                             "(default: the stroke's middle)")
    export.add_argument("--axis", default="x", help="linuxcnc: the axis letter the HAL file wires (default x)")
    export.add_argument("--units", choices=("mm", "inch"), default="mm",
                        help="linuxcnc: the machine's linear units (default mm)")
    _out_argument(export, "out/<law>_<to>")
    export.set_defaults(func=cmd_export)

    uncertainty = sub.add_parser("uncertainty", help="prediction bands (5-95 %%) of the sensors and D over time and Sobol' "
                                                     "indices from the description's declared uncertainties")
    _system_argument(uncertainty)
    uncertainty.add_argument("--samples", type=_power_of_two, default=128, metavar="N",
                             help="scrambled Sobol' points of the bands, a power of 2 (default 128; each runs every "
                                  "condition)")
    uncertainty.add_argument("--sobol-base", type=_power_of_two, default=64, metavar="N",
                             help="base of Saltelli's scheme for the Sobol' indices, a power of 2: N (d + 2) runs "
                                  "for d parameters (default 64)")
    uncertainty.add_argument("--no-sobol", action="store_true", help="bands only, no Sobol' indices")
    uncertainty.add_argument("--condition", help="the condition of the Sobol' indices (default: the description's first)")
    uncertainty.add_argument("--seed", type=_integer, default=0, metavar="S",
                             help="seed of the scrambled Sobol' points (default 0)")
    uncertainty.add_argument("--calibration", metavar="DIR",
                             help="output folder of `feedtherm calibrate`: also the bands after calibration (the "
                                  "fitted parameters' posterior, the other priors kept)")
    uncertainty.add_argument("--update-with", metavar="CONDITIONS",
                             help="comma-separated measured conditions: also the bands after a "
                                  "Bayesian update of every declared prior with their measured final values "
                                  "(docs/uncertainty.md); not with --calibration")
    uncertainty.add_argument("--model", default="fast", help="a model of `feedtherm models` (default fast)")
    uncertainty.add_argument("--mesh", choices=MESHES, default="coarse", help="FE mesh density (with --model fem)")
    _measured_argument(uncertainty)
    _mode_argument(uncertainty)
    _execution_arguments(uncertainty)
    _out_argument(uncertainty, "out/<system>_uncertainty_<mode>")
    uncertainty.set_defaults(func=cmd_uncertainty)
    return parser


def _raise_terminated(signum, frame) -> None:
    raise Terminated()


def _what_was_kept(stop: KeyboardInterrupt) -> str:
    """``; <message>`` where the command said what an interruption left (a sweep's kept points)."""
    return f"; {stop.args[0]}" if stop.args and isinstance(stop.args[0], str) else ""


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    # A terminated run unwinds like an interrupted one: staged outputs are removed, worker
    # pools shut down, nothing half-written is left (only in the main thread, where Python
    # may install handlers).
    previous = None
    if threading.current_thread() is threading.main_thread():
        previous = signal.signal(signal.SIGTERM, _raise_terminated)
    try:
        return args.func(args)
    except FeedthermError as exc:
        print(f"feedtherm: error: {cli_message(exc)}", file=sys.stderr)
        return 2
    except Terminated as stop:
        print(f"feedtherm: terminated{_what_was_kept(stop)}", file=sys.stderr)
        return 128 + signal.SIGTERM
    except KeyboardInterrupt as stop:
        print(f"feedtherm: interrupted{_what_was_kept(stop)}", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # The reader went away (`feedtherm check | head`): nothing more to say, and Python's
        # final flush of stdout must not fail again (the recipe of the signal module's docs).
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
