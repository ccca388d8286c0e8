"""Run a model on a described feed system: ``simulate(loaded, condition=name)``.

This is the public entry point the CLI and the analyses use, and ``feedtherm.simulate`` of the
public API (docs/python-api.md): this module is callable, ``ft.simulate(system, condition="v10")``
runs :func:`simulate` (its parameters: ``help(feedtherm.simulate.simulate)``).  A run has three steps:
:func:`~feedtherm.plan.plan_run` (validated segments and their boundary conditions),
integration by the shared :class:`~feedtherm.models.integrator.Integrator` with the model
from the registry, and :func:`~feedtherm.solution.pack.pack_solution`.
"""

from __future__ import annotations

import sys
import time
import types
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from . import __version__
from .constants import KELVIN_OFFSET
from .errors import ArgumentError, FeedthermError
from .models.integrator import Integrator, Segment
from .models.interface import ThermalModel
from .models.options import ModelOptions
from .models.registry import build_model
from .boundary.room import at_air
from .plan import FromReadings, RunPlan, Soaked, Uniform, plan_run
from .system.measurements import MeasurementSet
from .system.overlay import mode_of
from .solution import Solution
from .solution.health import check_health
from .solution.pack import pack_solution, sample_times
from .system.load import LoadedSystem, as_loaded
from .system.mechanics import loop_summary
from .system.schema import FeedSystem


def simulate(loaded: LoadedSystem | str, *, condition: str | None = None, cycle: str | None = None,
             test: str | None = None, model: str = "fast", duration: float | None = None,
             single_drive: bool = False, sample_interval: float = 10.0,
             progress: Callable[[float], None] | None = None, motion: str | None = None,
             mesh: str | None = None, start: str = "initial", options: ModelOptions | None = None,
             solver: str | None = None, allow_overload: bool = False,
             measured: MeasurementSet | None = None) -> Solution:
    """Simulate a test, a condition or a duty cycle of ``loaded`` and return its Solution.

    The boundary conditions take the overlay ``loaded`` carries, if any
    (:func:`feedtherm.plan.with_mode`).

    Parameters
    ----------
    loaded : LoadedSystem, str or path-like
        A description from :func:`feedtherm.load` (:func:`~feedtherm.system.load.load_system`),
        or a bench name or a description's path, loaded here in the physics mode.
    condition, test, cycle : str
        Exactly one: a test or a condition by name (``condition`` and ``test`` are the same
        argument: a condition is the simplest test; docs/tests.md), or a duty cycle (a name in the
        description or a CSV path, ``time_s,screw_rpm,nut_rpm,ambient_C``).
    model : str
        A model of the registry (:func:`feedtherm.models.registry.available_models`):
        ``"fast"`` or ``"fem"`` built in.
    duration : float, optional
        Length of the run [s]; default: the condition's duration (10,800 s) or the cycle's.
    single_drive : bool
        Run the dual drive as a conventional drive: nut motor off (nut speed 0) and the
        screw at the relative speed, so that the table speed is unchanged.
    sample_interval : float
        Interval of the output series [s].
    progress : callable, optional
        Called with the fraction of the run done, from 0 to 1.
    motion : {"resolved", "exact", "averaged"}, optional
        Position over time (default; the FE and reduced models step it window by window,
        :mod:`feedtherm.models.windows`), ``"exact"`` grid position by grid position in every model
        (the reference the windows are measured against), or the cycle-averaged contacts and heats.
    mesh : {"coarse", "medium", "fine"}, optional
        Mesh density of the FE model.
    start : {"initial", "steady"}
        Start from the initial temperature (default), or from the cycle-averaged steady state
        of the first operating point (to study the periodic steady state directly).
    options : ModelOptions, optional
        The models' discretisation and time stepping (:class:`feedtherm.models.options.ModelOptions`;
        default its defaults); ``motion``, ``mesh`` and ``solver``, where given, take precedence.
    solver : {"auto", "direct", "cg"}, optional
        Linear solver of the time steps (default: ``options.solver``, "auto").
    allow_overload : bool
        Run even where a motor needs more than its declared continuous torque (refused by default:
        :func:`feedtherm.plan.refuse_overloads`); studies that vary the preloads report such points.
    measured : MeasurementSet, optional
        The measurements a test with a measured room or start reads (default: its own file, else the
        description's).

    Returns
    -------
    Solution
        Sensor series, screw fields, D and E(x, t), final and steady values, the energy balance;
        :meth:`~feedtherm.solution.Solution.to_dataframe` tabulates them.

    Raises
    ------
    ArgumentError
        An argument the run cannot take, named as here: ``condition: no condition or test 'nope'
        in …``, ``model: no model …``, ``duration: must be positive …``.
    ModelError
        The description asks for something the model cannot do.

    Examples
    --------
    >>> import feedtherm as ft
    >>> run = ft.simulate(ft.load("ballscrew_example"), condition="v10", duration=600.0)  # doctest: +SKIP
    >>> run.to_dataframe().columns[0]  # doctest: +SKIP
    'time [s]'
    """
    loaded = as_loaded(loaded)
    plan = plan_run(loaded, condition=condition, cycle=cycle, test=test, model=model, duration=duration,
                    single_drive=single_drive, sample_interval=sample_interval, motion=motion, mesh=mesh,
                    solver=solver, start=start, options=options, allow_overload=allow_overload, measured=measured)
    return execute(plan, progress)


def execute(plan: RunPlan, progress: Callable[[float], None] | None = None,
            model: ThermalModel | None = None) -> Solution:
    """Integrate a plan and pack its Solution (``model``: an already built discretisation to reuse)."""
    started = time.perf_counter()
    system = plan.loaded.system
    segments = plan.segments
    disc = model if model is not None else plan.model.build(system, plan.options)
    integrator = Integrator(disc, plan.options, plan.coupling)
    T0 = initial_state(plan, disc, integrator)
    times = sample_times(plan.end, plan.sample_interval)
    trace = integrator.run(segments, T0, times, progress, plan.air)
    last = segments[-1].bc.point
    stats = disc.stats
    kin = system.kinematics
    info = {
        "condition": plan.label,
        "model": plan.model.name,
        "mode": plan.mode,
        # Whether the axis ran as a single drive: declared so, or a dual drive run with --single-drive
        "single_drive": plan.single_drive or (kin is not None and kin.drive == "single"),
        "declared_drive": None if kin is None else kin.drive,  # None: the system has no feed drive
        "single_drive_option": plan.single_drive,
        "motion": plan.options.motion,
        # the resolved motion's windows (models/windows.py): cells a step swept, of the grid's K
        **({"motion_windows": {"cells": sorted(integrator.window_cells), "grid_cells": len(disc.positions) - 1,
                               "window_step_s": plan.options.window_step}} if integrator.window_cells else {}),
        **({"mesh": plan.options.mesh, "mesh_statistics": stats} if plan.model.uses_mesh
           else {k: v for k, v in stats.items() if k != "unknowns"}),
        "screw_rpm": last.screw_rpm,
        "nut_rpm": last.nut_rpm,
        "ambient_C": last.ambient - KELVIN_OFFSET,
        "warnings": sorted({w for seg in segments for w in seg.bc.warnings}),
        "coupling": system.temperatures.coupling,
        "screw_part": None if kin is None else kin.screw,  # which part of the field series the screw image shows
        "measuring_loop": loop_summary(system.mechanics),
        "provenance": provenance(plan.loaded),
    }
    solution = pack_solution(system, integrator, segments, trace, T0, times, info)
    solution.info["wall_time_s"] = time.perf_counter() - started
    check_health(solution)
    return solution


def initial_state(plan: RunPlan, model: ThermalModel, integrator: Integrator) -> np.ndarray:
    """The state ``plan`` starts from (:class:`~feedtherm.plan.Initial`), on ``model``."""
    first = plan.segments[0]
    if plan.start == "steady":
        return integrator.steady(0, first.bc, None if first.speed > 0 else 0)
    initial = plan.initial
    if isinstance(initial, Soaked):  # the other run first, on the same model, from its own start
        soak = initial.plan
        inner = Integrator(model, soak.options, soak.coupling)
        return inner.run(soak.segments, initial_state(soak, model, inner), np.array([soak.end]), air=soak.air).final_state
    if isinstance(initial, FromReadings):
        k = 0 if first.table_at is None else integrator.held_position(first.table_at)
        return matched_state(model, integrator, at_air(first.bc, model.system, initial.air), k, initial.readings)
    if isinstance(initial, Uniform):
        return model.uniform_state(initial.temperature)
    raise FeedthermError(f"a run plan without a start ({initial!r})")


def matched_state(model: ThermalModel, integrator: Integrator, bc, k: int, readings: dict[str, float]) -> np.ndarray:
    """The state that reads ``readings`` at position ``k`` (sensor → temperature [K], and ``D`` → [m] where
    read): the steady field of the surfaces at ``bc``'s air under a load along each reading's row (for a
    sensor, a heat [W] at its point), no other heat, the loads chosen so that every reading is met.

    Of the fields that match the readings it is the one conduction and the surfaces would hold if the
    readings were kept: smooth, at the air far from every sensor.  With ``R`` the readings' rows and
    ``A`` the steady operator, ``T = A⁻¹(s + Rᵀλ)`` with ``(R A⁻¹ Rᵀ) λ = y − R A⁻¹ s − offset``.
    """
    names = [n for n in model.probe_names if n in readings]
    given = model.probe_rows(k)
    if given is None:
        raise FeedthermError(f"the {type(model).__name__} cannot start from measured temperatures: it does not give "
                             "its sensors' rows")
    rows, offset = given
    index = [model.probe_names.index(n) for n in names]
    R = rows[index]
    R = R.toarray() if hasattr(R, "toarray") else np.asarray(R)
    loads = integrator.loads(-1, bc, k)
    base = integrator.steady(-1, bc, k, rhs=np.asarray(loads.ambient.source, dtype=float))
    columns = np.column_stack([integrator.steady(-1, bc, k, rhs=R[i].copy()) for i in range(len(names))])
    target = np.array([readings[n] for n in names]) - np.asarray(offset)[index] - R @ base
    heats, *_ = np.linalg.lstsq(R @ columns, target, rcond=None)
    return base + columns @ heats


def prepare(system: FeedSystem, model: str, mesh: str | None = None) -> None:
    """Build ``model`` once for ``system`` here when it keeps what a build makes for later runs
    (``ModelEntry.prepares``: the reduced model's projection, trained over the ranges ``system``
    declares), so that the runs of a batch, on Dask workers too, read it instead of each building
    one, and from a variant's description."""
    from .models.registry import model_entry

    if model_entry(model).prepares:
        options = ModelOptions(reduced_training="batch")
        build_model(model, system, options if mesh is None else replace(options, mesh=mesh))


def discretize(system: FeedSystem, model: str, options: ModelOptions | None = None) -> ThermalModel:
    """The registry's model ``model`` built for ``system`` (the operators the integrator uses)."""
    return build_model(model, system, options or ModelOptions())


@dataclass(frozen=True)
class SteadySolve:
    """The steady state of one condition, with the model and integrator that solved it.

    A moving table gives the cycle-averaged state (``k`` None) read with the moving group
    mid-stroke; a standstill gives the state at position 0.
    """

    model: ThermalModel
    integrator: Integrator
    segment: Segment
    state: np.ndarray

    @property
    def k(self) -> int | None:
        return None if self.segment.speed > 0 else 0

    @property
    def probe_position(self) -> int:
        return len(self.model.positions) // 2 if self.k is None else 0

    def values(self) -> dict[str, float]:
        """Sensors [K], ``D`` [m] and the ambient sensor."""
        values = dict(zip(self.model.probe_names, self.model.probe(self.state, self.probe_position)))
        values[self.model.system.room.ambient_sensor] = self.segment.bc.point.ambient
        return values


def steady_solve(loaded: LoadedSystem, condition: str, *, single_drive: bool = False,
                 model: str = "fast", mesh: str | None = None, options: ModelOptions | None = None) -> SteadySolve:
    """Plan ``condition``, build the model and solve its steady state (no transient)."""
    if condition not in loaded.system.conditions:
        raise ArgumentError("condition", f"no condition {condition!r} in {loaded.origin}; "
                                         f"conditions: {', '.join(loaded.system.conditions)}")
    plan = plan_run(loaded, condition=condition, model=model, single_drive=single_drive, mesh=mesh,
                    options=options)
    segment = plan.segments[0]
    disc = plan.model.build(loaded.system, plan.options)
    integrator = Integrator(disc, plan.options, plan.coupling)
    return SteadySolve(disc, integrator, segment, integrator.steady(0, segment.bc, None if segment.speed > 0 else 0))


def steady_state(loaded: LoadedSystem, condition: str, *, single_drive: bool = False,
                 model: str = "fast", options: ModelOptions | None = None) -> dict[str, float]:
    """Cycle-averaged steady state of a condition (no transient): sensors [K] and ``D`` [m].

    Cheap with the fast model (one sparse solve), for sensitivity studies and calibration.
    """
    return steady_solve(loaded, condition, single_drive=single_drive, model=model,
                        options=options).values()


def provenance(loaded: LoadedSystem) -> dict:
    """What a run relied on: version, description hash, mode (its overlay) and the assumptions in use."""
    return {
        "feedtherm_version": __version__,
        "description": loaded.origin,
        "description_sha256": loaded.sha256,
        "mode": mode_of(loaded),
        "assumptions": [
            {"paths": p.paths, "source": p.source, "reason": p.reason}
            for p in loaded.system.provenance if p.origin == "assumption"
        ],
    }


__all__ = ["simulate", "execute", "steady_state", "steady_solve", "SteadySolve", "discretize", "provenance", "ModelOptions"]


class _Verb(types.ModuleType):
    """This module, callable: ``feedtherm.simulate(...)`` runs :func:`simulate`.

    The public API's verb and this module share the name ``feedtherm.simulate``, and the import
    system sets a package's attribute to its submodule whenever the submodule is imported, over
    whatever the package had put there.  So the attribute is this module, and calling it is the
    verb; ``from feedtherm.simulate import simulate`` and patching the module's names work as before.
    """

    def __call__(self, *args, **kwargs) -> Solution:
        return simulate(*args, **kwargs)


_module = sys.modules[__name__]
_module.__class__ = _Verb
_module.__wrapped__ = simulate  # inspect.signature(feedtherm.simulate) is the function's
