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
from .models.fast.assemble import Network, SolverTamper
from .models.fast.integrate import FastOptions, Integrator, Segment
from .models.fast.layout import Layout, build_layout
from .solution import EnergyBalance, Solution
from .system.duty_cycle import read_duty_cycle_csv
from .system.load import LoadedSystem
from .system.schema import DEFAULT_DURATION_S, DutyCycle, FeedSystem

MODELS = ("fast",)
AMBIENT_SENSOR = "T6"


def simulate(loaded: LoadedSystem, *, condition: str | None = None, cycle: str | None = None,
             mode: str = "physics", model: str = "fast", duration: float | None = None,
             single_drive: bool = False, sample_interval: float = 10.0,
             progress: Callable[[float], None] | None = None, motion: str | None = None,
             options: FastOptions | None = None, tamper: SolverTamper | None = None) -> Solution:
    """Simulate a condition or a duty cycle of ``loaded`` and return its Solution.

    Parameters
    ----------
    condition, cycle : str
        Exactly one: a condition name, or a duty cycle (a name in the description or a CSV
        path, ``time_s,screw_rpm,nut_rpm,ambient_C``).
    mode : {"physics", "paper"}
    model : {"fast"}
    duration : float, optional
        Length of the run [s]; default: the condition's duration (10,800 s) or the cycle's.
    single_drive : bool
        Run the dual drive as a conventional drive: nut motor off (nut speed 0) and the
        screw at the relative speed, so that the table speed is unchanged.
    sample_interval : float
        Interval of the output series [s].
    motion : {"resolved", "averaged"}, optional
        Position over time (default), or the cycle-averaged contacts and heats.
    """
    started = time.perf_counter()
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
    if not sample_interval > 0:
        raise FeedthermError(f"--sample-interval: must be positive, got {sample_interval!r} s")
    label, profile = _profile(loaded, condition, cycle, duration)
    opts = options or FastOptions()
    if motion is not None:
        opts = replace(opts, motion=motion)
    if system.temperatures.temperature_dependent_chtc:
        raise ModelError("temperatures.temperature_dependent_chtc = true: the fast model takes CHTCs frozen "
                         "at convection_delta_t (the paper's assumption 3); set it to false")
    layout = build_layout(system, axial_cells=opts.axial_cells, radial_rings=opts.radial_rings,
                          min_positions=opts.steps_per_stroke)
    segments = _segments(system, profile, mode, single_drive)
    network = Network(layout, tamper)
    integrator = Integrator(layout, network, opts)
    initial_temperature = segments[0].bc.point.ambient if system.temperatures.initial == "ambient" else system.temperatures.initial
    T0 = np.full(layout.n_nodes, initial_temperature)
    t_end = segments[-1].t1
    times = np.arange(0.0, t_end + 1e-9, sample_interval)
    if times[-1] < t_end - 1e-9:
        times = np.append(times, t_end)
    probes = _Probes(layout)
    trace = integrator.run(segments, T0, times, probes.values, progress)
    states = np.array(trace.samples)
    heat_stored = float(layout.capacity @ (trace.final_state - T0))
    energy = EnergyBalance(trace.heat_in, trace.heat_lost, heat_stored)

    step_end = np.array(trace.step_end)
    step_dt = np.array(trace.step_dt)
    step_values = np.array(trace.step_probe)  # (steps, sensors + D)
    window = _cycle_window(layout, segments, opts)
    cycle_values = _trailing_mean(step_end, step_dt, step_values, times, window)
    final_values = _trailing_mean(step_end, step_dt, step_values, np.array([t_end]), window)[0]
    last = segments[-1]
    steady_state = integrator.steady(len(segments) - 1, last.bc, None if last.speed > 0 else trace.final_position)
    steady_values = probes.values(steady_state)
    names = probes.names
    initial_values = dict(zip(names, probes.values(T0)))
    final = dict(zip(names, final_values))
    steady = dict(zip(names, steady_values))
    cycle_mask = times >= times[0] + window - 1e-9
    sensor_names = [n for n in names if n != "D"]
    t_eq = equilibrium_time(times[cycle_mask], {n: cycle_values[cycle_mask, i] for i, n in enumerate(names) if n != "D"},
                            initial_values, steady)
    ambient = np.array([_ambient_at(segments, t) for t in times])
    screw = layout.screw
    screw_T = probes.screw_mean(states)
    elong = system.elongation
    alpha = system.materials[system.parts[system.kinematics.screw].material].expansion
    t_ref = system.temperatures.reference
    sensors = {n: states[:, probes.nodes[n]] for n in sensor_names}
    sensors[AMBIENT_SENSOR] = ambient
    final[AMBIENT_SENSOR] = _window_ambient(segments, t_end - window, t_end)
    steady[AMBIENT_SENSOR] = last.bc.point.ambient
    cycle_sensors = {n: cycle_values[cycle_mask, i] for i, n in enumerate(names) if n != "D"}
    return Solution(
        times=times,
        sensors=sensors,
        elongation=probes.elongation(states),
        screw_x=screw.centres,
        screw_temperature=screw_T,
        screw_displacement=displacement(screw.edges, screw_T, alpha, t_ref, elong.fixed_at, screw.centres),
        nut_offset=np.array(trace.sample_offset),
        part_temperatures=probes.part_means(states),
        cycle_times=times[cycle_mask],
        cycle_sensors=cycle_sensors,
        cycle_elongation=cycle_values[cycle_mask, names.index("D")],
        final=final,
        steady=steady,
        equilibrium_time=t_eq,
        energy=energy,
        info={
            "condition": label,
            "model": model,
            "mode": mode,
            "single_drive": single_drive,
            "motion": opts.motion,
            "time_step_s": trace.time_step,
            "steps": len(step_end),
            "unknowns": layout.n_nodes,
            "screw_cells": len(screw.centres),
            "screw_rings": screw.n_rings,
            "cycle_window_s": window,
            "wall_time_s": time.perf_counter() - started,
            "warnings": sorted({w for seg in segments for w in seg.bc.warnings}),
            "provenance": provenance(loaded, mode),
        },
    )


def steady_state(loaded: LoadedSystem, condition: str, *, mode: str = "physics", single_drive: bool = False,
                 options: FastOptions | None = None) -> dict[str, float]:
    """Cycle-averaged steady state of a condition (no transient): sensors [K] and ``D`` [m].

    Cheap (one sparse solve), for sensitivity studies and calibration.
    """
    system = loaded.system
    if condition not in system.conditions:
        raise FeedthermError(f"no condition {condition!r} in {loaded.origin}")
    opts = options or FastOptions()
    layout = build_layout(system, axial_cells=opts.axial_cells, radial_rings=opts.radial_rings,
                          min_positions=opts.steps_per_stroke)
    label, profile = _profile(loaded, condition, None, None)
    segment = _segments(system, profile, mode, single_drive)[0]
    integrator = Integrator(layout, Network(layout), opts)
    probes = _Probes(layout)
    state = integrator.steady(0, segment.bc, None if segment.speed > 0 else 0)
    values = dict(zip(probes.names, probes.values(state)))
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


def _cycle_window(layout: Layout, segments: list[Segment], opts: FastOptions) -> float:
    """Length [s] of one reciprocation cycle (the longest among moving segments)."""
    periods = [2.0 * layout.system.kinematics.stroke / s.speed for s in segments if s.speed > 0]
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


class _Probes:
    """Sensor temperatures and the elongation read from a state vector."""

    def __init__(self, layout: Layout):
        system = layout.system
        self.layout = layout
        self.nodes: dict[str, int] = {}
        for name, sensor in system.sensors.items():
            if name == AMBIENT_SENSOR:
                continue
            if sensor.part in layout.lumped:
                self.nodes[name] = layout.lumped[sensor.part]
            else:
                body = layout.bodies[sensor.part]
                radius = float(np.hypot(sensor.position[1], sensor.position[2]))
                ring = int(np.clip(np.searchsorted(body.ring_radii, radius) - 1, 0, body.n_rings - 1))
                self.nodes[name] = int(body.nodes[body.cell_at(sensor.position[0]), ring])
        self.names = [*self.nodes, "D"]
        self._node_index = np.array(list(self.nodes.values()), dtype=int)
        screw = layout.screw
        self._ring_share = screw.ring_areas() / screw.ring_areas().sum()
        part = system.parts[system.kinematics.screw]
        self._alpha = system.materials[part.material].expansion
        e = system.elongation
        # D = alpha * sum_i overlap_i (T_i - T_ref) between the fixed and the read point
        lo, hi = min(e.fixed_at, e.read_at), max(e.fixed_at, e.read_at)
        sign = 1.0 if e.read_at >= e.fixed_at else -1.0
        self._d_weights = sign * screw.overlap(lo, hi)
        self._t_ref = system.temperatures.reference

    def screw_mean(self, states: np.ndarray) -> np.ndarray:
        screw = self.layout.screw
        return states[..., screw.nodes] @ self._ring_share

    def elongation(self, states: np.ndarray) -> np.ndarray:
        return self._alpha * ((self.screw_mean(states) - self._t_ref) @ self._d_weights)

    def values(self, T: np.ndarray) -> np.ndarray:
        return np.append(T[self._node_index], self.elongation(T))

    def part_means(self, states: np.ndarray) -> dict[str, np.ndarray]:
        out = {}
        for part in self.layout.system.parts:
            nodes = self.layout.part_nodes(part)
            c = self.layout.capacity[nodes]
            out[part] = states[:, nodes] @ (c / c.sum())
        return out


__all__ = ["simulate", "steady_state", "provenance", "FastOptions", "MODELS"]
_ = ModelError  # re-exported for callers that catch model errors from here
