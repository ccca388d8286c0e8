"""What a run will cost in wall time, estimated from its plan before any model is built.

A run of ``feedtherm run`` spends its time in a few places, each with its own driver::

    wall = start + set-up(N) + factorisations × factor(N) + steps × step(N) + outputs(N)

- ``start``: the process, its imports, the description's load and checks, the plan.
- ``set-up``: the fast model's network, or the FE model's mesh (when it is not cached), its
  assembly, its elastic readout and, at every grid position of the moving group, its sliding
  contacts and the coverage of its moving surfaces (a run with either motion forms them all:
  the averaged motion averages them, the steady state of the summary uses the average).
- ``factorisations``: one step matrix per (operating point, time step, grid position the run
  visits).  A coupled run refactorises only where a node's link to the air has moved by a fifth
  and faster than a hundredth of its capacity a second (models/coupling.py): the paper bench's
  first condition over 10,800 s, coupled, took 23 factorisations for its 21 positions visited,
  on the fast model and on the coarse FE mesh alike (2026-11-29), so none are counted for it.
- ``steps``: the integrator's time steps (its own rule, :func:`run_work`), one solve each.
- ``outputs``: the plots, and the FE model's fields (images, a VTU per snapshot).

``N`` is the model's unknowns, predicted from the description: the fast model's node count is its
layout's (cheap: geometry only, :func:`feedtherm.models.fast.layout.build_layout`); the FE
model's from each part's volume and faces and its target element size at the density
(:func:`fem_nodes`).  Each cost is a power law in ``N`` fitted to measurements on both bundled
benches (coarse, medium and, where measured, fine meshes); every constant below names its
measurement.  They were measured as CPU time of one thread (OpenBLAS and MKL on one thread) on
the project's 2-core x86-64 machine (AMD EPYC) while other sessions ran beside them: on a quiet
machine a single-threaded run's wall time is about its CPU time.  The figures and commands are in
benchmarks/README.md (*check's time estimates*) and ``benchmarks/study_check_estimates.py
--calibrate`` measures them again.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..models.fem.geometry import DENSITIES, mesh_cache_path, mesh_size
from ..models.integrator import Segment
from ..models.options import ModelOptions
from ..system.geometry import part_volume, surface_area
from ..system.schema import FeedSystem, Part

if TYPE_CHECKING:
    from . import RunPlan

# ----------------------------------------------------------------------------- every run
#: [s] The process's start: Python, feedtherm's imports, the description's load and checks, the
#: plan, the tables and summary.  `feedtherm run` of the paper bench's first condition over 1,800 s
#: and of ballscrew_example's v10 over 600 s, fast model: the whole process's CPU time
#: less the model's build, integration, packing and written files, 2.09 and 2.08 s.
START_S = 2.1
#: [s] The run's PNG plots (matplotlib's import and four figures): 2.39-2.71 s in every run measured.
PLOTS_S = 2.5

# ----------------------------------------------------------------------------- fast model
#: [s] The fast model's build, its operators at every grid position and the summary's steady
#: state: the fast runs' integration less their steps, 0.67-0.70 s, with the build, 0.19-0.22 s,
#: and the packing, 0.04-0.43 s (both benches, 180-21,750 steps).
FAST_SETUP_S = 1.1
#: [s] A fast-model time step per node: a solve with the position's cached factors (SuperLU,
#: 0.13-0.15 ms for 1,474-1,752 nodes) and the step's bookkeeping.  Two durations of the same
#: run, their difference over their steps: the paper bench (1,474 nodes, coupled) 0.30 ms a step,
#: ballscrew_example (1,752 nodes, frozen coefficients) 0.27 ms.
FAST_STEP_S_PER_NODE = 1.75e-7

# ----------------------------------------------------------------------------- FE model
#: Nodes of a part's tetrahedral mesh: ``a V/h³ + b S + c n`` with ``V`` its volume, ``h`` its
#: target element size (:func:`~feedtherm.models.fem.geometry.mesh_size`), ``S`` its faces in
#: elements (each face's area over its element size squared: curved faces' size is limited by
#: the density's elements around a circle, as gmsh's MeshSizeFromCurvature does) and ``n`` its
#: boxes, cylinders and holes.  Fitted (least squares, weights 1/√nodes) to every part of both
#: benches' meshes at the three densities (``mesh_system(load_system(bench).system, density)`` in
#: an empty cache, 2026-11-29): paper 13,069, 44,443, 171,510 nodes (coarse, medium, fine),
#: ballscrew_example 15,605, 53,346, 219,250; the totals within 1.1 %.
FEM_NODES_PER_VOLUME = 0.691
FEM_NODES_PER_FACE_ELEMENT = 0.770
FEM_NODES_PER_PRIMITIVE = 75.8
#: [s] Meshing with gmsh, ``a N^b``: the six meshes above, CPU time 2.44, 7.87, 43.6 s (paper)
#: and 2.81, 11.5, 63.8 s (ballscrew_example), each within 16 %.
FEM_MESH = (3.93e-5, 1.156)
#: [s] The FE model's build from a cached mesh (volumes, conduction, fixed joints, surfaces,
#: readout), ``a N^b``: 1.46, 5.20, 21.8 s (paper coarse, medium, fine), 2.02, 7.94 s
#: (ballscrew_example coarse, medium), within 17 %.
FEM_BUILD = (8.52e-5, 1.037)
#: [s] The elastic readout (D and the positioning error as rows over the temperatures: elastic
#: solves of 3N unknowns), ``a N^b``: 2.92, 13.9, 105 s and 4.01, 19.1 s, within 11 %.
FEM_READOUT = (7.05e-6, 1.364)
#: [s] A step matrix's factorisation, ``a N^b`` (SuperLU below 20,000 unknowns, PARDISO's
#: Cholesky above, where installed): 0.19, 0.81, 4.8 s and 0.31, 1.07 s, within 21 %.
FEM_FACTOR = (2.46e-6, 1.197)
#: [s] A solve with the factors, ``a N^b``: median and best of 30, 4.6-5.2, 12-14, 70-75 ms and
#: 6.0-9.0, 16-18 ms.
FEM_SOLVE = (5.0e-7, 0.98)
#: [s] A step's bookkeeping per node, beside its solve: the FE runs' time a step less the solve,
#: 1.4 ms (paper coarse, two durations) and 1.2 ms (ballscrew_example coarse).
FEM_STEP_S_PER_NODE = 8.5e-8
#: [s] A grid position's contacts and coverage per quadrature point matched (:func:`contact_work`):
#: three positions each, 0.158, 0.407, 1.06 s (paper; 30,900, 85,800, 219,700 points) and
#: 0.226, 0.551 s (ballscrew_example; 53,900, 149,700): 3.7-5.1 µs a point.
FEM_POSITION_S_PER_POINT = 4.5e-6
#: [s] The fields written (VTU files and images): ``a + b N`` and ``c N`` per snapshot: 5.3-5.8 s
#: (paper coarse, 2-7 snapshots), 5.7 s (paper medium), 5.6-6.0 s (ballscrew_example coarse and
#: medium).
FIELDS_S = 5.0
FIELDS_S_PER_NODE = 2.0e-5
FIELDS_S_PER_NODE_SNAPSHOT = 7.6e-6
#: Factorisations the summary's steady state costs (its solves, the coupled iteration's
#: re-evaluations): packing took 0.87-1.27 s on the paper bench's coarse mesh (coupled, 4.6-6.6
#: factorisations' time) and 0.94 s on ballscrew_example's (frozen, 3.0).
STEADY_FACTORS = {False: 3.0, True: 5.0}
# ----------------------------------------------------------------------------- reduced model
#: [s] The reduced model's basis and projection beside the FE build, per node and grid position:
#: the first run of the paper bench's coarse model 30.5 s (basis and projection 19.6 s, 13,069
#: nodes, 41 positions), ballscrew_example's 64.1 s (44.7 s; 15,605, 59): 3.7e-5 and 4.9e-5.
REDUCED_BASIS_S_PER_NODE_POSITION = 4.2e-5
#: [s] Reading a cached projection, per full-model node: 0.76 s for the paper bench's coarse one.
REDUCED_READ_S_PER_NODE = 5.8e-5
#: [s] A reduced step (dense, a few hundred unknowns) and a refactorisation of its step matrix:
#: the paper bench 1.3 ms a step with 171 factorisations over 1,080 steps, ballscrew_example
#: 0.44 ms a step.
REDUCED_STEP_S = 4.5e-4
REDUCED_FACTOR_S = 3.0e-3


@dataclass(frozen=True)
class ModelSize:
    """What a model's cost scales with, predicted from the description."""

    model: str
    mesh: str | None
    unknowns: int  # nodes: the fast model's network, the FE mesh (predicted)
    positions: int  # grid positions of the moving group
    contact_points: float = 0.0  # FE: quadrature points matched at each position (:func:`contact_work`)
    mesh_cached: bool = True  # FE: the mesh file exists, no meshing

    def describe(self) -> str:
        """``fast 1,474 nodes``, ``fem medium ~44,000 nodes`` (predicted, to two digits; followed by
        ``(not meshed yet)`` where its mesh is not cached), ``reduced (the coarse mesh projected)``."""
        if self.model == "fast":
            return f"fast {self.unknowns:,} nodes"
        if self.model == "reduced":
            return f"reduced (the {self.mesh} mesh projected)"
        cached = "" if self.mesh_cached else " (not meshed yet)"
        return f"{self.model} {self.mesh} ~{_round(self.unknowns):,} nodes{cached}"


@dataclass(frozen=True)
class RunWork:
    """What a run does, counted from its plan: time steps, factorisations, field snapshots."""

    steps: int
    factorisations: int
    snapshots: int
    coupled: bool


def fast_size(system: FeedSystem, options: ModelOptions) -> ModelSize:
    """The fast model's nodes: its layout's (geometry only, no operator built)."""
    from ..models.fast.layout import build_layout

    layout = build_layout(system, axial_cells=options.axial_cells, radial_rings=options.radial_rings,
                          min_positions=options.steps_per_stroke, cell_size=options.cell_size)
    return ModelSize("fast", None, int(layout.n_nodes), len(layout.positions))


def fem_nodes(system: FeedSystem, density: str) -> int:
    """The FE mesh's nodes at ``density``, predicted from each part's geometry and target element
    size (:data:`FEM_NODES_PER_VOLUME` and the next two; no mesh is made)."""
    per_circle = DENSITIES[density].per_circle
    total = 0.0
    for name, part in system.parts.items():
        h = mesh_size(system, name, density)
        primitives = len(part.boxes) + len(part.cylinders) + len(part.holes)
        total += (FEM_NODES_PER_VOLUME * part_volume(part) / h**3
                  + FEM_NODES_PER_FACE_ELEMENT * _face_elements(part, h, per_circle)
                  + FEM_NODES_PER_PRIMITIVE * primitives)
    return int(round(total))


def _face_elements(part: Part, h: float, per_circle: int) -> float:
    """The part's faces in elements: each face's area over its element size squared."""
    def around(diameter: float) -> float:  # a curved face's size: per_circle elements around, at least h/5
        return min(h, max(0.2 * h, math.pi * diameter / per_circle))

    count = 0.0
    for box in part.boxes:
        sx, sy, sz = box.size
        count += 2.0 * (sx * sy + sy * sz + sx * sz) / h**2
    for cyl in part.cylinders:
        count += math.pi * cyl.outer_diameter * cyl.length / around(cyl.outer_diameter) ** 2
        if cyl.inner_diameter > 0.0:
            count += math.pi * cyl.inner_diameter * cyl.length / around(cyl.inner_diameter) ** 2
        count += 2.0 * math.pi / 4.0 * (cyl.outer_diameter**2 - cyl.inner_diameter**2) / h**2
    for hole in part.holes:
        count += math.pi * hole.outer_diameter * hole.length / around(hole.outer_diameter) ** 2
    return count


def contact_work(system: FeedSystem, density: str) -> float:
    """Quadrature points the FE model matches at each grid position of the moving group.

    A sliding joint's contact integrates over the whole boundary of its finer side, at a rule of
    more points where the other side is finer still (models/fem/bench.py); a surface whose part
    slides past a joined part has its points tested against that part's facets.
    """
    from ..models.fem.facets import rule  # here: its KD-trees' scipy.spatial would slow every command's start

    per_circle = DENSITIES[density].per_circle
    sizes = {name: mesh_size(system, name, density) for name in system.parts}
    points = 0.0
    for joint in system.joints:
        if not joint.sliding:
            continue
        a, b = joint.between
        if sizes[b] < sizes[a]:
            a, b = b, a
        level = 1 + max(0, math.ceil(math.log2(sizes[a] / sizes[b]) - 1e-9))
        points += rule(level)[0].shape[0] * _face_elements(system.parts[a], sizes[a], per_circle)
    for surface in system.surfaces.values():
        part = surface.part
        moving = system.parts[part].moving
        passing = sum(1 for joint in system.joints if part in joint.between
                      for other in joint.between if other != part and system.parts[other].moving != moving)
        if passing:
            points += passing * surface_area(surface, system.parts[part]) / sizes[part] ** 2
    return points


def fem_size(system: FeedSystem, density: str, options: ModelOptions) -> ModelSize:
    """The FE model's predicted nodes and positions at ``density``, and whether its mesh is cached."""
    from . import screw_grid

    _, positions = screw_grid(system, options)
    return ModelSize("fem", density, fem_nodes(system, density), positions, contact_work(system, density),
                     mesh_cache_path(system, density).exists())


def _power(law: tuple[float, float], n: float) -> float:
    return law[0] * n ** law[1]


def _round(n: int) -> int:
    """``n`` to two significant digits (a prediction's precision)."""
    if n < 100:
        return n
    scale = 10 ** (len(str(n)) - 2)
    return int(round(n / scale) * scale)


def run_work(plan: "RunPlan", motion: str, positions: int, windowed: bool = False) -> RunWork:
    """The time steps, factorisations and field snapshots of ``plan`` run with ``motion`` on a
    model of ``positions`` grid positions (with a soak run before it, where its test has one);
    ``windowed``: a model whose resolved motion steps window by window (models/windows.py)."""
    from .profiles import FromReadings, Soaked

    options = _with_motion(plan.options, motion)
    work = _segments_work(plan.loaded.system, plan.segments, options, positions, windowed)
    coupled = plan.coupling is not None
    if plan.start == "steady" or isinstance(plan.initial, FromReadings):  # a steady solve: one factorisation
        soak = RunWork(0, 1, 0, coupled)
    elif isinstance(plan.initial, Soaked):  # the soak's run first, on the same model
        soak = run_work(plan.initial.plan, motion, positions, windowed)
    else:
        soak = RunWork(0, 0, 0, coupled)
    snapshots = math.floor((plan.end - plan.segments[0].t0) / options.snapshot_interval) + 2 if options.fields else 0
    return RunWork(work.steps + soak.steps, work.factorisations + soak.factorisations, snapshots, coupled)


def _with_motion(options: ModelOptions, motion: str) -> ModelOptions:
    from dataclasses import replace

    return replace(options, motion=motion)


def _segments_work(system: FeedSystem, segments: list[Segment], options: ModelOptions, positions: int,
                   windowed: bool = False) -> RunWork:
    """Steps and factorisations by the integrator's rules (models/integrator.py): its time step, the
    grid positions (or windows) a reciprocating table visits, a factorisation per (operating point,
    step, position or window)."""
    K = positions - 1
    stroke = 0.0 if system.kinematics is None else system.kinematics.stroke
    dx = stroke / K if K > 0 else 0.0
    steps = 0
    matrices: set[tuple] = set()
    u = 0.0  # the table's place on the triangle wave of positions, in grid cells
    for seg in segments:
        windows = windowed and options.motion == "resolved" and seg.speed > 0.0 and K > 0
        dt, cells = _step(seg, options, K, dx, windows)
        length = seg.t1 - seg.t0
        count = max(1, math.ceil(length / dt - 1e-6))
        steps += count
        # the segment's last step is shorter where dt does not divide it: a matrix of its own
        partial = length - (count - 1) * dt < dt * (1.0 - 1e-9)
        if cells == 0.0:  # standing, or the averaged motion: one position
            where = None if seg.speed > 0.0 else (seg.table_at, round(u))
            matrices.add((id(seg.bc), dt, where))
            if partial:
                matrices.add((id(seg.bc), "last", where))
            continue
        width = _window_width(seg, options, K, dx) if windows else 0
        for _ in range(min(count, 4 * K + 4)):  # a cycle or two visit every position they will
            u += cells
            matrices.add((id(seg.bc), dt, _where(u - cells, u, K, width)))
        u += cells * max(0, count - (4 * K + 4))
        if partial:
            matrices.add((id(seg.bc), "last", _where(u - cells, u, K, width)))
    return RunWork(steps, len(matrices), 0, False)


def _window_width(seg: Segment, options: ModelOptions, K: int, dx: float) -> int:
    """The cells a windowed step of ``seg`` sweeps (:func:`~feedtherm.models.windows.window_cells`)."""
    from ..models.windows import window_cells

    return window_cells(K, max(1, K // options.steps_per_stroke), dx, seg.speed, options.window_step)


def _where(u_start: float, u_end: float, K: int, width: int):
    """The grid position a step ends at, or the window it sweeps (``width`` cells; 0: no windows)."""
    if width:
        from ..models.windows import swept_window

        return swept_window(u_start, u_end, K, width)
    return _position(u_end, K)


def _step(seg: Segment, options: ModelOptions, K: int, dx: float, windowed: bool = False) -> tuple[float, float]:
    """The integrator's nominal step [s] in ``seg`` and grid cells advanced a step
    (:meth:`~feedtherm.models.integrator.Integrator._step`); ``windowed``: a step sweeps a window."""
    if options.motion == "averaged" and seg.speed > 0.0:
        return min(options.averaged_step, options.max_step), 0.0
    if seg.speed == 0.0 or K == 0:
        return min(options.standstill_step, options.max_step), 0.0
    cells = _window_width(seg, options, K, dx) if windowed else max(1, K // options.steps_per_stroke)
    dt = cells * dx / seg.speed
    if dt > options.max_step:
        return options.max_step, cells * options.max_step / dt
    return dt, float(cells)


def _position(u: float, K: int) -> int:
    """The grid position at ``u`` cells along the triangle wave (the integrator's PositionPath)."""
    period = 2 * K
    tri = math.fmod(u, period)
    return int(round(tri if tri <= K else period - tri))


def wall_time(size: ModelSize, work: RunWork) -> float:
    """Estimated wall time [s] of ``feedtherm run`` of ``work`` on a model of ``size``, with its files
    and plots written; the reduced model with its projection cached (:func:`projection_time`)."""
    return sum(wall_time_parts(size, work).values())


def wall_time_parts(size: ModelSize, work: RunWork) -> dict[str, float]:
    """:func:`wall_time` by where it goes [s]: start, set-up, factorisations, steps, outputs."""
    n = size.unknowns
    start = START_S + PLOTS_S
    if size.model == "fast":
        return {"start": start, "set-up": FAST_SETUP_S, "factorisations": 0.0,
                "steps": work.steps * seconds_per_step(size), "outputs": 0.0}
    fields = FIELDS_S + FIELDS_S_PER_NODE * n + FIELDS_S_PER_NODE_SNAPSHOT * n * work.snapshots
    if size.model == "reduced":
        return {"start": start, "set-up": REDUCED_READ_S_PER_NODE * n,
                "factorisations": work.factorisations * REDUCED_FACTOR_S, "steps": work.steps * seconds_per_step(size),
                "outputs": fields}
    meshing = 0.0 if size.mesh_cached else _power(FEM_MESH, n)
    setup = (meshing + _power(FEM_BUILD, n) + _power(FEM_READOUT, n)
             + size.positions * FEM_POSITION_S_PER_POINT * size.contact_points)
    factor = _power(FEM_FACTOR, n)
    return {"start": start, "set-up": setup,
            "factorisations": (work.factorisations + STEADY_FACTORS[work.coupled]) * factor,
            "steps": work.steps * seconds_per_step(size), "outputs": fields}


def seconds_per_step(size: ModelSize) -> float:
    """[s] A time step of a model of ``size``, its solve and bookkeeping (no set-up, no outputs)."""
    if size.model == "fast":
        return FAST_STEP_S_PER_NODE * size.unknowns
    if size.model == "reduced":
        return REDUCED_STEP_S
    return _power(FEM_SOLVE, size.unknowns) + FEM_STEP_S_PER_NODE * size.unknowns


def projection_time(size: ModelSize) -> float:
    """[s] What the reduced model's first run on a mesh adds: the FE model's build (and its mesh where
    not cached), its contacts at every position, the basis and the projection, kept on disk after."""
    n = size.unknowns
    meshing = 0.0 if size.mesh_cached else _power(FEM_MESH, n)
    return (meshing + _power(FEM_BUILD, n) + _power(FEM_READOUT, n)
            + size.positions * FEM_POSITION_S_PER_POINT * size.contact_points
            + REDUCED_BASIS_S_PER_NODE_POSITION * n * size.positions)
