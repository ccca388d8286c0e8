"""The last step of a run: pack the integrator's trace into a :class:`~feedtherm.solution.Solution`.

Cycle means (over one reciprocation), the final and steady values, the equilibrium time,
the ambient series, the screw's displacement and the energy balance: what every model's run
reports in the same way.
"""

from __future__ import annotations

import time

import numpy as np

from ..constants import ELONGATION_PROBE
from ..models.integrator import Integrator, Segment, Trace
from ..models.interface import ThermalModel
from ..system.geometry import nut_centre_x
from ..system.schema import FeedSystem
from . import EnergyBalance, Ledger, Solution
from .equilibrium import equilibrium_time, equilibrium_times
from .fields import field_series


def sample_times(t_end: float, interval: float) -> np.ndarray:
    """0, interval, 2·interval, … and the end [s]."""
    times = np.arange(0.0, t_end + 1e-9, interval)
    if times[-1] < t_end - 1e-9:
        times = np.append(times, t_end)
    return times


def cycle_window(system: FeedSystem, segments: list[Segment], standstill_step: float) -> float:
    """Length [s] of one reciprocation cycle (the longest among moving segments)."""
    periods = [2.0 * system.kinematics.stroke / s.speed for s in segments if s.speed > 0]  # speed 0 without a drive
    return max(periods) if periods else standstill_step


def pack_solution(system: FeedSystem, integrator: Integrator, segments: list[Segment], trace: Trace,
                  initial_state: np.ndarray, times: np.ndarray, info: dict) -> Solution:
    """The Solution of a run: ``info`` is completed with the run's own figures."""
    model = integrator.model
    energy = EnergyBalance(trace.heat_in, trace.heat_lost, model.heat_stored(trace.final_state, initial_state))
    names = model.probe_names
    d_index = names.index(ELONGATION_PROBE)
    sensor_names = [n for n in names if n != ELONGATION_PROBE]
    t_end = segments[-1].t1
    step_end, step_dt = np.array(trace.step_end), np.array(trace.step_dt)
    step_values = np.array(trace.step_probe)
    samples = np.array(trace.sample_probe)
    window = cycle_window(system, segments, integrator.options.standstill_step)
    cycle_values = trailing_mean(step_end, step_dt, step_values, times, window)
    final_values = trailing_mean(step_end, step_dt, step_values, np.array([t_end]), window)[0]
    last = segments[-1]
    k_steady = None if last.speed > 0 else trace.final_position
    steady_state = integrator.steady(len(segments) - 1, last.bc, k_steady)
    if integrator.coupling is not None:
        info = {**info, "coupling_updates": trace.coupling_updates}
    final_bc = trace.final_bc or last.bc
    info = {**info, "heat_W": {name: heat.power for name, heat in final_bc.heats.items()}}
    steady_values = model.probe(steady_state, len(model.positions) // 2 if k_steady is None else k_steady)
    initial = dict(zip(names, model.probe(initial_state, 0)))
    final = dict(zip(names, final_values))
    steady = dict(zip(names, steady_values))
    in_cycle = times >= times[0] + window - 1e-9
    cycle_sensors = {n: cycle_values[in_cycle, names.index(n)] for n in sensor_names}
    t_eq = equilibrium_time(times[in_cycle], cycle_sensors, initial, steady)
    t_eq_each = equilibrium_times(times[in_cycle], cycle_sensors, cycle_values[in_cycle, d_index], initial, steady,
                                  ELONGATION_PROBE)
    sensors = {n: samples[:, names.index(n)] for n in sensor_names}
    ambient = system.room.ambient_sensor
    if trace.air is not None:  # the room's measured air, which the sinks followed
        sensors[ambient] = np.asarray(trace.air.at(times), dtype=float)
        final[ambient] = trace.air.mean(max(t_end - window, segments[0].t0), t_end)
    else:
        sensors[ambient] = np.array([ambient_at(segments, t) for t in times])
        final[ambient] = window_ambient(segments, t_end - window, t_end)
    steady[ambient] = last.bc.point.ambient
    screw_T = np.array(trace.sample_screw)
    displacement = np.array(trace.sample_displacement)[:, 1:]
    if system.kinematics is None:  # no table: no positions along a stroke, no positioning error
        table_x = np.zeros(0)
        positioning = np.zeros((len(times), 0))
    else:
        table_x = nut_centre_x(system) + model.positions
        positioning = along_stroke(model.screw_centres, displacement, table_x)
    # one operating point in a room of constant air: a run with a steady state to approach (a cycle, its
    # stops or a logged room has none: its summary gives what the run did, not a steady state)
    constant = len({seg.bc.point for seg in segments}) == 1 and trace.air is None
    info = {**info, "constant_operating_point": constant, "ambient_sensor": ambient, "time_step_s": trace.time_step,
            "steps": len(step_end), "solver": integrator.solver_name,
            **({"cg_iterations": integrator.cg_iterations} if integrator.cg_iterations else {}),
            "unknowns": model.n_nodes, "cycle_window_s": window}
    mesh = model.field_mesh()
    fields = None
    if mesh is not None and trace.snapshots:
        rows = [int(np.argmin(np.abs(times - t))) for t, _, _ in trace.snapshots]
        title = (f"condition {info.get('condition')}, {info.get('mode')} mode, {info.get('model')} model"
                 + (f" ({info['mesh']} mesh)" if info.get("mesh") else ""))
        integrator.release()  # the time loop is over: its factors make room for the displacement fields'
        snapshots = [(t, model.full_state(state), offset) for t, state, offset in trace.snapshots]
        started = time.perf_counter()
        vectors = [model.displacement_field(state) for _, state, _ in trace.snapshots]
        info = {**info, "displacement_fields_seconds": round(time.perf_counter() - started, 2)}
        fields = field_series(mesh, snapshots, model.screw_centres, displacement[rows], title,
                              displacements=None if any(v is None for v in vectors) else np.array(vectors))
    return Solution(
        times=times,
        sensors=sensors,
        elongation=samples[:, d_index],
        screw_x=model.screw_centres,
        screw_temperature=screw_T,
        screw_displacement=displacement,
        table_x=table_x,
        positioning_error=positioning,
        nut_offset=np.array(trace.sample_offset),
        part_temperatures={p: np.array([s[p] for s in trace.sample_parts]) for p in system.parts},
        cycle_times=times[in_cycle],
        cycle_sensors=cycle_sensors,
        cycle_elongation=cycle_values[in_cycle, d_index],
        final=final,
        steady=steady,
        equilibrium_time=t_eq,
        energy=energy,
        info=info,
        fields=fields,
        equilibrium_times=t_eq_each,
        ledger=ledger(model, trace),
    )


def ledger(model: ThermalModel, trace: Trace) -> Ledger:
    """The parts' capacities and the sources' heats of a run (:class:`~feedtherm.solution.Ledger`)."""
    heat_in = np.array(trace.sample_heat_in).reshape(len(trace.sample_heat_in), len(trace.sources))
    first = trace.first_heat_in if trace.first_heat_in is not None else np.zeros(len(trace.sources))
    capacities = model.part_capacities()
    return Ledger(
        capacities=None if capacities is None else {p: float(c) for p, c in capacities.items()},
        heat_in={name: heat_in[:, i] for i, name in enumerate(trace.sources)},
        heat_lost=np.array(trace.sample_heat_lost, dtype=float),
        first_heat_in={name: float(q) for name, q in zip(trace.sources, first)},
        first_heat_lost=float(trace.first_heat_lost),
    )


def along_stroke(screw_x: np.ndarray, profile: np.ndarray, table_x: np.ndarray) -> np.ndarray:
    """The screw's displacement ``profile`` (n, m) at ``screw_x``, read at the table positions (n, p)
    by linear interpolation between section centres (the end sections' values beyond them)."""
    profile = np.atleast_2d(profile)
    return np.array([np.interp(table_x, screw_x, row) for row in profile])


def ambient_at(segments: list[Segment], t: float) -> float:
    """Ambient temperature [K] at time t."""
    for seg in segments:
        if seg.t0 <= t < seg.t1:
            return seg.bc.point.ambient
    return segments[-1].bc.point.ambient


def window_ambient(segments: list[Segment], t0: float, t1: float) -> float:
    """Time-mean ambient temperature [K] over [t0, t1] (exact for piecewise-constant ambients)."""
    t0 = max(t0, segments[0].t0)
    total = sum(max(0.0, min(s.t1, t1) - max(s.t0, t0)) * s.bc.point.ambient for s in segments)
    return total / (t1 - t0) if t1 > t0 else segments[-1].bc.point.ambient


def trailing_mean(step_end, step_dt, values, at, window) -> np.ndarray:
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
