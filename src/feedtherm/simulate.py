"""Run a model on a described feed system: ``simulate(loaded, condition="I")``.

This is the public entry point the CLI and the analyses use.  It turns a condition or a
duty cycle into segments of constant operating point, computes their boundary conditions,
runs the chosen model and packs a :class:`~feedtherm.solution.Solution`.
"""

from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path
from typing import Callable

import numpy as np

from . import __version__
from .analysis.elongation import displacement
from .analysis.equilibrium import equilibrium_time
from .boundary import MODES, boundary_conditions_at
from .boundary.operating import OperatingPoint, operating_point
from .errors import FeedthermError, ModelError
from .models.fast.assemble import SolverTamper
from .models.fast.discretization import FastDiscretization
from .models.integrator import Integrator, Segment
from .models.options import FastOptions, ModelOptions
from .solution import EnergyBalance, Solution
from .system.duty_cycle import read_duty_cycle_csv
from .system.load import LoadedSystem
from .system.schema import DEFAULT_DURATION_S, DutyCycle, FeedSystem

MODELS = ("fast", "fem")
MESHES = ("coarse", "medium", "fine")
SOLVERS = ("auto", "direct", "cg")
AMBIENT_SENSOR = "T6"


def simulate(loaded: LoadedSystem, *, condition: str | None = None, cycle: str | None = None,
             mode: str = "physics", model: str = "fast", duration: float | None = None,
             single_drive: bool = False, sample_interval: float = 10.0,
             progress: Callable[[float], None] | None = None, motion: str | None = None,
             mesh: str | None = None, start: str = "initial", options: ModelOptions | None = None,
             tamper: SolverTamper | None = None, solver: str | None = None) -> Solution:
    """Simulate a condition or a duty cycle of ``loaded`` and return its Solution.

    Parameters
    ----------
    condition, cycle : str
        Exactly one: a condition name, or a duty cycle (a name in the description or a CSV
        path, ``time_s,screw_rpm,nut_rpm,ambient_C``).
    mode : {"physics", "paper"}
    model : {"fast", "fem"}
    duration : float, optional
        Length of the run [s]; default: the condition's duration (10,800 s) or the cycle's.
    single_drive : bool
        Run the dual drive as a conventional drive: nut motor off (nut speed 0) and the
        screw at the relative speed, so that the table speed is unchanged.
    sample_interval : float
        Interval of the output series [s].
    motion : {"resolved", "averaged"}, optional
        Position over time (default), or the cycle-averaged contacts and heats.
    mesh : {"coarse", "medium", "fine"}, optional
        Mesh density of the FE model.
    start : {"initial", "steady"}
        Start from the initial temperature (default), or from the cycle-averaged steady state
        of the first operating point (to study the periodic steady state directly).
    solver : {"auto", "direct", "cg"}, optional
        Linear solver of the time steps (default: ``options.solver``, "auto").
    """
    started = time.perf_counter()
    system = loaded.system
    _check_arguments(loaded, mode, model, duration, sample_interval, motion, mesh, solver)
    label, profile = _profile(loaded, condition, cycle, duration)
    opts = _options(options, motion, mesh, solver)
    segments = _segments(system, profile, mode, single_drive)
    disc = discretize(system, model, opts, tamper)
    integrator = Integrator(disc, opts)
    if start not in ("initial", "steady"):
        raise FeedthermError(f"start must be 'initial' or 'steady', got {start!r}")
    if start == "steady":
        first = segments[0]
        T0 = integrator.steady(0, first.bc, None if first.speed > 0 else 0)
    else:
        initial_temperature = (segments[0].bc.point.ambient if system.temperatures.initial == "ambient"
                               else system.temperatures.initial)
        T0 = np.full(disc.n_nodes, initial_temperature)
    t_end = segments[-1].t1
    times = np.arange(0.0, t_end + 1e-9, sample_interval)
    if times[-1] < t_end - 1e-9:
        times = np.append(times, t_end)
    trace = integrator.run(segments, T0, times, progress)
    heat_stored = float(disc.capacity @ (trace.final_state - T0))
    energy = EnergyBalance(trace.heat_in, trace.heat_lost, heat_stored)

    names = disc.probe_names
    sensor_names = [n for n in names if n != "D"]
    step_end, step_dt = np.array(trace.step_end), np.array(trace.step_dt)
    step_values = np.array(trace.step_probe)
    samples = np.array(trace.sample_probe)
    window = _cycle_window(system, segments, opts)
    cycle_values = _trailing_mean(step_end, step_dt, step_values, times, window)
    final_values = _trailing_mean(step_end, step_dt, step_values, np.array([t_end]), window)[0]
    last = segments[-1]
    k_steady = None if last.speed > 0 else trace.final_position
    steady_state_vector = integrator.steady(len(segments) - 1, last.bc, k_steady)
    steady_values = disc.probe(steady_state_vector, len(disc.positions) // 2 if k_steady is None else k_steady)
    initial_values = dict(zip(names, disc.probe(T0, 0)))
    final = dict(zip(names, final_values))
    steady = dict(zip(names, steady_values))
    cycle_mask = times >= times[0] + window - 1e-9
    t_eq = equilibrium_time(times[cycle_mask], {n: cycle_values[cycle_mask, i] for i, n in enumerate(names) if n != "D"},
                            initial_values, steady)
    sensors = {n: samples[:, i] for i, n in enumerate(names) if n != "D"}
    sensors[AMBIENT_SENSOR] = np.array([_ambient_at(segments, t) for t in times])
    final[AMBIENT_SENSOR] = _window_ambient(segments, t_end - window, t_end)
    steady[AMBIENT_SENSOR] = last.bc.point.ambient
    screw_T = np.array(trace.sample_screw)
    elong = system.elongation
    alpha = system.materials[system.parts[system.kinematics.screw].material].expansion
    parts = {p: np.array([s[p] for s in trace.sample_parts]) for p in system.parts}
    info = {
        "condition": label,
        "model": model,
        "mode": mode,
        "single_drive": single_drive,
        "motion": opts.motion,
        "time_step_s": trace.time_step,
        "steps": len(step_end),
        "solver": integrator.solver_name,
        "unknowns": disc.n_nodes,
        **({"mesh": opts.mesh, "mesh_statistics": disc.stats} if model == "fem"
           else {k: v for k, v in disc.stats.items() if k != "unknowns"}),
        "cycle_window_s": window,
        "screw_rpm": last.bc.point.screw_rpm,
        "nut_rpm": last.bc.point.nut_rpm,
        "ambient_C": last.bc.point.ambient - 273.15,
        "wall_time_s": time.perf_counter() - started,
        "warnings": sorted({w for seg in segments for w in seg.bc.warnings}),
        "provenance": provenance(loaded, mode),
    }
    return Solution(
        times=times,
        sensors=sensors,
        elongation=samples[:, names.index("D")],
        screw_x=disc.screw_centres,
        screw_temperature=screw_T,
        screw_displacement=displacement(disc.screw_edges, screw_T, alpha, system.temperatures.reference,
                                        elong.fixed_at, disc.screw_centres),
        nut_offset=np.array(trace.sample_offset),
        part_temperatures=parts,
        cycle_times=times[cycle_mask],
        cycle_sensors={n: cycle_values[cycle_mask, i] for i, n in enumerate(names) if n != "D"},
        cycle_elongation=cycle_values[cycle_mask, names.index("D")],
        final=final,
        steady=steady,
        equilibrium_time=t_eq,
        energy=energy,
        info=info,
        snapshots=trace.snapshots if model == "fem" else [],
        mesh=disc if model == "fem" else None,
    )


def discretize(system: FeedSystem, model: str, options: ModelOptions, tamper: SolverTamper | None = None):
    """The chosen model's discretisation of ``system`` (the interface the integrator uses)."""
    if model == "fem":
        if tamper is not None:
            raise ModelError("solver tampering is a test hook of the fast model only")
        from .models.fem.bench import FemDiscretization  # gmsh and scikit-fem load only here

        return FemDiscretization(system, options.mesh)
    return FastDiscretization(system, options, tamper)


def _options(options: ModelOptions | None, motion: str | None, mesh: str | None,
             solver: str | None = None) -> ModelOptions:
    opts = options or ModelOptions()
    if solver is not None:
        opts = replace(opts, solver=solver)
    if motion is not None:
        opts = replace(opts, motion=motion)
    if mesh is not None:
        opts = replace(opts, mesh=mesh)
    return opts


def _check_arguments(loaded, mode, model, duration, sample_interval, motion, mesh, solver=None) -> None:
    system = loaded.system
    if mode not in MODES:
        raise FeedthermError(f"--mode: must be one of {', '.join(MODES)}, got {mode!r}")
    if model not in MODELS:
        raise FeedthermError(f"--model: must be one of {', '.join(MODELS)}, got {model!r}")
    if mode == "paper" and system.paper is None:
        raise FeedthermError(f"--mode paper: {loaded.origin} has no [paper] table of printed values")
    if duration is not None and not duration > 0:
        raise FeedthermError(f"--duration: must be positive, got {duration!r} s")
    if motion not in (None, "resolved", "averaged"):
        raise FeedthermError(f"--motion: must be resolved or averaged, got {motion!r}")
    if mesh not in (None, *MESHES):
        raise FeedthermError(f"--mesh: must be one of {', '.join(MESHES)}, got {mesh!r}")
    if solver not in (None, *SOLVERS):
        raise FeedthermError(f"--solver: must be one of {', '.join(SOLVERS)}, got {solver!r}")
    if not sample_interval > 0:
        raise FeedthermError(f"--sample-interval: must be positive, got {sample_interval!r} s")
    if system.temperatures.temperature_dependent_chtc:
        raise ModelError("temperatures.temperature_dependent_chtc = true: the models take CHTCs frozen "
                         "at convection_delta_t (the paper's assumption 3); set it to false")


def steady_state(loaded: LoadedSystem, condition: str, *, mode: str = "physics", single_drive: bool = False,
                 model: str = "fast", options: ModelOptions | None = None) -> dict[str, float]:
    """Cycle-averaged steady state of a condition (no transient): sensors [K] and ``D`` [m].

    Cheap with the fast model (one sparse solve), for sensitivity studies and calibration.
    """
    system = loaded.system
    if condition not in system.conditions:
        raise FeedthermError(f"no condition {condition!r} in {loaded.origin}")
    opts = options or ModelOptions()
    label, profile = _profile(loaded, condition, None, None)
    segment = _segments(system, profile, mode, single_drive)[0]
    disc = discretize(system, model, opts)
    integrator = Integrator(disc, opts)
    k = None if segment.speed > 0 else 0
    state = integrator.steady(0, segment.bc, k)
    values = dict(zip(disc.probe_names, disc.probe(state, len(disc.positions) // 2 if k is None else k)))
    values[AMBIENT_SENSOR] = segment.bc.point.ambient
    return values


def provenance(loaded: LoadedSystem, mode: str) -> dict:
    """What a run relied on: version, description hash, mode and the assumptions in use."""
    return {
        "feedtherm_version": __version__,
        "description": loaded.origin,
        "description_sha256": loaded.sha256,
        "mode": mode,
        "assumptions": [
            {"paths": p.paths, "source": p.source, "reason": p.reason}
            for p in loaded.system.provenance if p.origin == "assumption"
        ],
    }


# ---------------------------------------------------------------------------- profile


def _profile(loaded: LoadedSystem, condition: str | None, cycle: str | None, duration: float | None):
    system = loaded.system
    if (condition is None) == (cycle is None):
        raise FeedthermError("give exactly one of --condition and --cycle")
    if condition is not None:
        if condition not in system.conditions:
            raise FeedthermError(f"--condition: no condition {condition!r} in {loaded.origin}; conditions: {', '.join(system.conditions)}")
        c = system.conditions[condition]
        end = duration if duration is not None else c.duration
        profile = DutyCycle.model_validate({"segments": [{"start": "0 s", "screw_speed": f"{c.screw_speed} rad/s",
                                                          "nut_speed": f"{c.nut_speed} rad/s", "ambient": f"{c.ambient} K"}],
                                            "duration": f"{end} s"})
        return condition, profile
    if cycle in system.duty_cycles:
        profile = system.duty_cycles[cycle]
        if duration is not None:
            profile = _cut(profile, duration)
        return cycle, profile
    if not (cycle.endswith(".csv") or Path(cycle).exists()):
        names = ", ".join(system.duty_cycles) or "none"
        raise FeedthermError(f"--cycle: {cycle!r} is neither a duty cycle of {loaded.origin} ({names}) nor a CSV file")
    profile = read_duty_cycle_csv(cycle, duration if duration is not None else DEFAULT_DURATION_S)
    return Path(cycle).stem, profile


def _cut(profile: DutyCycle, duration: float) -> DutyCycle:
    segments = [s for s in profile.segments if s.start < duration]
    return profile.model_copy(update={"segments": segments, "duration": duration})


def _segments(system: FeedSystem, profile: DutyCycle, mode: str, single_drive: bool) -> list[Segment]:
    rpm = 60.0 / (2.0 * np.pi)
    cache: dict[OperatingPoint, object] = {}
    out = []
    starts = [s.start for s in profile.segments] + [profile.duration]
    for seg, t1 in zip(profile.segments, starts[1:]):
        point = OperatingPoint(seg.screw_speed * rpm, seg.nut_speed * rpm, seg.ambient, system.kinematics.lead)
        if single_drive:
            point = replace(point, screw_rpm=point.relative_rpm, nut_rpm=0.0)
        if point not in cache:
            cache[point] = boundary_conditions_at(system, point, mode)
        out.append(Segment(seg.start, t1, cache[point]))
    return out


def _ambient_at(segments: list[Segment], t: float) -> float:
    for seg in segments:
        if seg.t0 <= t < seg.t1:
            return seg.bc.point.ambient
    return segments[-1].bc.point.ambient


def _window_ambient(segments: list[Segment], t0: float, t1: float) -> float:
    """Time-mean ambient temperature [K] over [t0, t1] (exact for piecewise-constant ambients)."""
    t0 = max(t0, segments[0].t0)
    total = sum(max(0.0, min(s.t1, t1) - max(s.t0, t0)) * s.bc.point.ambient for s in segments)
    return total / (t1 - t0) if t1 > t0 else segments[-1].bc.point.ambient


def _cycle_window(system: FeedSystem, segments: list[Segment], opts: ModelOptions) -> float:
    """Length [s] of one reciprocation cycle (the longest among moving segments)."""
    periods = [2.0 * system.kinematics.stroke / s.speed for s in segments if s.speed > 0]
    return max(periods) if periods else opts.standstill_step


def _trailing_mean(step_end, step_dt, values, at, window) -> np.ndarray:
    """Time-mean of step-wise constant ``values`` over [t - window, t] for every t in ``at``.

    Implicit Euler holds each step's end value over the step, so the values are piecewise
    constant on (t_end - dt, t_end].
    """
    cumulative = np.vstack([np.zeros(values.shape[1]), np.cumsum(values * step_dt[:, None], axis=0)])
    edges = np.concatenate([[step_end[0] - step_dt[0]], step_end])

    def integral(t):
        t = np.clip(t, edges[0], edges[-1])
        i = np.clip(np.searchsorted(edges, t, side="right") - 1, 0, len(step_dt) - 1)
        return cumulative[i] + values[i] * (t - edges[i])[:, None]

    at = np.asarray(at, dtype=float)
    lo = np.maximum(at - window, edges[0])
    span = np.maximum(at - lo, 1e-12)
    return (integral(at) - integral(lo)) / span[:, None]


__all__ = ["simulate", "steady_state", "discretize", "provenance", "FastOptions", "ModelOptions", "MODELS", "MESHES"]
