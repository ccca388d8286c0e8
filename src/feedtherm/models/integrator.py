"""Time integration shared by the models (implicit Euler), with the moving group reciprocating.

Each step solves ``(C/dt + G(k) + A(k)) T⁺ = C/dt T + q(k) + a(k) T_amb`` (the operators of
:class:`~feedtherm.models.interface.ThermalModel`) with ``k`` the moving group's grid
position at the end of the step (the exact motion), or the window of positions the step
sweeps (the windowed motion of the models that take it, :mod:`.windows`), or the cycle
average (the averaged motion).  While the table moves, a step advances the group by a whole
number of grid positions, so each position's matrix can be factorised once and reused
(:mod:`.direct`: a symmetric fill-reducing ordering, dense Cholesky for a projected model); large FE
meshes use conjugate gradients on the step's increment instead (:mod:`.iterative`), started
from the increments of the last two steps at the same phase of the reciprocation
(:class:`~.iterative.IncrementHistory`; the linear extrapolation of the last two states where
there are none yet).  The energy account is kept apart from
the solver's matrices: heat in from the boundary conditions (not the model's heat vector),
heat lost from the ambient coupling, heat stored from the capacities.
"""

from __future__ import annotations

import contextlib
import hashlib
import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import cg

from ..boundary import BoundaryConditions, LocalTemperatures
from ..boundary.room import RoomAir, at_air
from ..system.geometry import nut_centre_x
from ..errors import ModelError
from ..system.quantities import TEMPERATURE_LIMIT
from .coupling import (
    LINK_REFACTOR,
    LINK_RATE_REFACTOR,
    MAX_ACCELERATION,
    MIN_RELAXATION,
    REFRESH_SHARE,
    RUNAWAY_ITERATIONS,
    SLOW_CONTRACTION,
    STEADY_ITERATIONS,
    STEADY_TOLERANCE,
    Coupling,
    TemperatureReadout,
)
from . import pardiso
from .direct import EliminationOrder, _pattern, dense_factors, factorize
from .iterative import IncrementHistory, StepCG, jacobi
from .interface import AmbientCoupling, Operator, PositionWindow, ThermalModel, source_powers
from .options import ModelOptions
from .windows import swept_window, window_cells

#: Above this many unknowns the "auto" solver uses conjugate gradients, not cached SuperLU factors
#: (PARDISO's Cholesky factors, where installed, are kept at any size within a memory budget).
DIRECT_SOLVER_LIMIT = 60_000
#: Relative tolerance of a steady solve by conjugate gradients (from zero: relative to the heat that drives it).
STEADY_CG_RTOL = 1e-10
#: Sample states kept before their readings are taken together (entries: 16 MB of states, any model's size).
SAMPLE_BLOCK_ENTRIES = 2_000_000


@dataclass(frozen=True)
class Segment:
    """A stretch of constant operating point, [t0, t1) in seconds.

    ``table_at``: a standstill with the table held at this position (the nut's centre along x in
    the machine frame [m]; a measuring stop), None: where the last segment left it.
    """

    t0: float
    t1: float
    bc: BoundaryConditions
    table_at: float | None = None

    @property
    def speed(self) -> float:
        return abs(self.bc.point.table_speed)


@dataclass
class Trace:
    """What the integrator hands back: step records, reduced samples and a few full snapshots."""

    step_end: list = field(default_factory=list)  # time at the end of each step [s]
    step_dt: list = field(default_factory=list)
    step_probe: list = field(default_factory=list)  # probe values at the end of each step
    sample_probe: list = field(default_factory=list)  # probe values at the sample times
    sample_screw: list = field(default_factory=list)  # screw profile at the sample times
    sample_displacement: list = field(default_factory=list)  # D and the screw's displacement at the sample times
    sample_parts: list = field(default_factory=list)  # part means at the sample times
    sample_offset: list = field(default_factory=list)  # moving-group offset at the sample times [m]
    snapshots: list = field(default_factory=list)  # (time, the model's state, offset) every snapshot_interval
    heat_in: float = 0.0
    heat_lost: float = 0.0
    # the energy ledger: each source's heat and the heat lost since the start [J], at the sample
    # times (within a step, its share of the step's); the first step's heats [W]
    sources: list = field(default_factory=list)  # the source names, in the order of the columns below
    sample_heat_in: list = field(default_factory=list)  # per sample: each source's heat since the start [J]
    sample_heat_lost: list = field(default_factory=list)  # per sample: the heat lost since the start [J]
    first_heat_in: np.ndarray | None = None  # each source's heat in the first step [W]
    first_heat_lost: float = 0.0  # the heat lost in the first step [W]
    time_step: float = 0.0  # the (first moving segment's) step [s]
    final_state: np.ndarray | None = None
    final_position: int = 0
    final_bc: BoundaryConditions | None = None  # the last step's (coupled: the last evaluation)
    coupling_updates: int = 0  # evaluations of the boundary conditions at the state (coupled runs)
    air: RoomAir | None = None  # the room's measured air the sinks followed, None: each segment's ambient


class PositionPath:
    """Reciprocation over grid positions 0..K along a triangle wave (in grid steps)."""

    def __init__(self, n_positions: int):
        self.K = n_positions - 1
        self.u = 0.0

    @property
    def k(self) -> int:
        if self.K == 0:  # one position: a system without a feed drive
            return 0
        period = 2 * self.K
        tri = math.fmod(self.u, period)
        pos = tri if tri <= self.K else period - tri
        return int(round(pos))

    def advance(self, cells: float) -> None:
        self.u += cells


def operator_sum(*operators: Operator) -> Operator:
    """Sum of operators given as vectors (diagonals), sparse or dense matrices."""
    n = next(len(op) if np.ndim(op) == 1 else op.shape[0] for op in operators)
    if any(isinstance(op, np.ndarray) and op.ndim == 2 for op in operators):
        total = np.zeros((n, n))
        for op in operators:
            if np.ndim(op) == 1:
                total[np.diag_indices(n)] += op
            else:
                total += op.toarray() if sp.issparse(op) else op
        return total
    diagonals = [op for op in operators if np.ndim(op) == 1]
    matrices = [op for op in operators if np.ndim(op) != 1]
    diagonal = sum(diagonals[1:], diagonals[0]) if diagonals else None
    if not matrices:
        return sp.diags(diagonal).tocsr()
    total = sum(matrices[1:], matrices[0]).tocsr()
    return total if diagonal is None else _plus_diagonal(total, diagonal)


def _plus_diagonal(A: sp.csr_matrix, diagonal: np.ndarray) -> sp.csr_matrix:
    """``A + diag(diagonal)``, added in place of a copy when ``A`` stores its whole diagonal (a step matrix's
    conduction does: a conductance matrix's diagonal is every node's total conductance)."""
    A = A.tocsr()
    rows = np.repeat(np.arange(A.shape[0]), np.diff(A.indptr))
    on_diagonal = A.indices == rows
    if np.count_nonzero(on_diagonal) != A.shape[0]:
        return (A + sp.diags(diagonal)).tocsr()
    data = A.data.copy()
    data[on_diagonal] += diagonal[A.indices[on_diagonal]]
    return sp.csr_matrix((data, A.indices.copy(), A.indptr.copy()), shape=A.shape)


@dataclass(frozen=True)
class _DiagonalLess:
    """``diag(diagonal) − matrix`` applied without forming it: a dense step's right-hand side
    operator is used for a few steps between two re-evaluations of a coupled run, fewer than
    the passes over the matrix that forming it takes."""

    diagonal: np.ndarray
    matrix: np.ndarray


def _apply(op: "Operator | _DiagonalLess", v: np.ndarray) -> np.ndarray:
    """``op v``, with a 1-D ``op`` a diagonal."""
    if isinstance(op, _DiagonalLess):
        return op.diagonal * v - op.matrix @ v
    return op * v if np.ndim(op) == 1 else op @ v


def _digest(op: Operator) -> str:
    """A fingerprint of an operator's values (vector, sparse or dense matrix)."""
    h = hashlib.blake2b(digest_size=16)
    if sp.issparse(op):
        op = op.tocsr()
        for array in (op.indptr, op.indices, op.data):
            h.update(np.ascontiguousarray(array).tobytes())
    else:
        h.update(np.ascontiguousarray(op).tobytes())
    return h.hexdigest()


@dataclass(frozen=True)
class Loads:
    """The operators at one position (or their cycle average)."""

    conductance: Operator
    ambient: AmbientCoupling
    heat: np.ndarray


@dataclass(frozen=True)
class _Step:
    """One kind of time step: ``T⁺ = lu⁻¹(rhs_operator T + load)``, and its energy account."""

    rhs_operator: "Operator | _DiagonalLess"  # C/dt, less the links' change a step takes explicitly
    load: np.ndarray  # heat and the links' heat at the sink temperatures [W]
    lu: object | None  # the step matrix's factors (direct solver), None: conjugate gradients
    heat_in: float  # [W]
    heats: np.ndarray  # each source's heat [W] in the description's order (their sum is heat_in)
    ambient: AmbientCoupling  # the links the step is evaluated with
    factorised: AmbientCoupling | None  # the links of the step matrix, when they are not ``ambient``'s

    def heat_lost(self, start: np.ndarray, end: np.ndarray) -> float:
        """Heat to the sinks [W] as the step's equations have it."""
        if self.factorised is None:
            return self.ambient.heat_lost(end)
        return self.ambient.heat_lost(start) + float(self.factorised.load @ (end - start))


class Integrator:
    """Implicit Euler over a plan's segments; with a :class:`~.coupling.Coupling`, the
    boundary conditions follow the temperatures (module notes of :mod:`.coupling`)."""

    def __init__(self, model: ThermalModel, options: ModelOptions, coupling: Coupling | None = None):
        self.model = model
        self.options = options
        self.coupling = coupling
        self._readout: TemperatureReadout | None = None
        self._lu = {}  # (step-matrix key, dt) → LU factors (direct solver)
        self._cg = {}  # (step-matrix key, dt) → StepCG (conjugate gradients)
        self._conductance = {}  # position (None: cycle average; or a PositionWindow) → conduction operator
        self._loads = {}  # (segment, boundary conditions' id, position) → (boundary conditions, Loads)
        self._matrix_keys = {}  # same keys → key of the step matrix (without C/dt)
        self._link_changes = {}  # (segment, evaluated bc's id, factorised bc's id, position) → link difference
        self._air_links = {}  # (segment, boundary conditions' id, position) → the air sinks' heat per kelvin
        self._orders = {}  # sparsity pattern → elimination order (direct solver; links and dt keep the pattern)
        solver = options.solver
        self.dense = isinstance(model.conductance(0), np.ndarray)
        self.uses_pardiso = not self.dense and solver != "cg" and pardiso.suits(model.n_nodes)
        self.direct = self.dense or solver == "direct" or (
            solver == "auto" and (model.n_nodes <= DIRECT_SOLVER_LIMIT or self.uses_pardiso))
        # "auto" keeps PARDISO's factors within a budget (options.factor_memory, or a share of the memory) and
        # steps the positions beyond it by cg
        if self.uses_pardiso and solver == "auto":
            self._budget = pardiso.memory_budget() if options.factor_memory is None else float(options.factor_memory)
        else:
            self._budget = None
        self._coarse_space = None
        self.over_budget = 0  # step matrices solved by cg because their factors would exceed the budget
        self.cg_iterations = 0  # conjugate-gradient iterations of every time step so far
        self.window_cells = set()  # the cells the windowed steps swept, per moving segment (none: no windows)
        self._samples = []  # sample states whose readings :meth:`_read_samples` has yet to take

    def release(self) -> None:
        """Drop every cached factorisation and iterative solver (a later step builds them again)."""
        self._lu.clear()
        self._cg.clear()

    @property
    def solver_name(self) -> str:
        if self.dense:
            return "dense Cholesky (LU where not symmetric positive definite)"
        if not self.direct:
            return "cg (Jacobi-preconditioned conjugate gradients)"
        if not self.uses_pardiso:
            return "direct (LU per position)"
        beyond = f"; cg for {self.over_budget} step matrices beyond the memory budget" if self.over_budget else ""
        return f"direct (PARDISO Cholesky per position{beyond})"

    @property
    def _coarse(self):
        if self._coarse_space is None:
            self._coarse_space = self.model.coarse_space()
        return self._coarse_space

    def _factorize(self, A: Operator):
        """The factors of ``A``, or None when PARDISO's would not fit in the memory budget (cg solves)."""
        if isinstance(A, np.ndarray):
            return dense_factors(A)
        if self.uses_pardiso:
            if self._budget is not None:
                held = [f.memory for f in self._lu.values() if isinstance(f, pardiso.PardisoCholesky)]
                if held and sum(held) + max(held) > self._budget:  # a position's factor is about as large
                    self.over_budget += 1
                    return None
            return pardiso.PardisoCholesky(A)
        pattern = _pattern(A)  # a position's matrices share their pattern whatever the links and dt
        lu = factorize(A, self._orders.get(pattern))
        if pattern not in self._orders:
            self._orders[pattern] = EliminationOrder(lu)
        return lu

    # -------------------------------------------------------------- cached pieces
    def conductance(self, k: int | None) -> Operator:
        """Conduction and contacts at position k (None: the cycle average); no boundary condition enters."""
        if k not in self._conductance:
            if k is None:
                self._conductance[k] = self.model.averaged_conductance()
            elif isinstance(k, PositionWindow):
                self._conductance[k] = self.model.window_conductance(k)
            else:
                self._conductance[k] = self.model.conductance(k)
        return self._conductance[k]

    def loads(self, seg_id: int, bc: BoundaryConditions, k: int | None) -> Loads:
        """The operators at position k; ``k = None`` gives the cycle average over all positions."""
        key = (seg_id, id(bc), k)
        if key not in self._loads:
            m = self.model
            loads = Loads(self.conductance(k), m.ambient_coupling(bc, k), m.heat_vector(bc, k))
            self._loads[key] = (bc, loads)  # holding bc keeps its id from being reused
        return self._loads[key][1]

    def _forget(self, seg_id: int, bc: BoundaryConditions) -> None:
        """Drop what was cached for boundary conditions a coupled run has left behind."""
        keys = [key for key in self._loads if key[:2] == (seg_id, id(bc))]
        stale = {self._matrix_keys.pop(key) for key in keys if key in self._matrix_keys}
        for key in keys:
            del self._loads[key]
        stale -= set(self._matrix_keys.values())
        self._link_changes.clear()
        for key in [key for key in self._air_links if key[:2] == (seg_id, id(bc))]:
            del self._air_links[key]
        for cache in (self._lu, self._cg):
            for key in [key for key in cache if key[0] in stale or key[1:3] == (seg_id, id(bc))]:
                del cache[key]

    def solve(self, seg_id: int, bc: BoundaryConditions, k: int | None, dt: float, rhs: np.ndarray,
              start: np.ndarray, guess: np.ndarray | None = None) -> np.ndarray:
        """The state after a step at position k: ``rhs`` its right-hand side, ``start`` the state it starts
        from, ``guess`` where the iterations of conjugate gradients start (default: ``start``)."""
        lu = self.factors(seg_id, bc, k, dt) if self.direct else None
        if lu is not None:
            return lu.solve(rhs)
        key = (self._matrix_key(seg_id, bc, k), round(dt, 12))
        if key not in self._cg:
            self._cg[key] = StepCG(self._step_matrix(seg_id, bc, k, dt), self._coarse)
        solver = self._cg[key]
        before = solver.iterations
        state = solver.solve(rhs, start, guess)
        self.cg_iterations += solver.iterations - before
        return state

    def factors(self, seg_id: int, bc: BoundaryConditions, k: int | None, dt: float):
        """The (cached) factors of the step matrix at position k (direct solver): ``.solve(rhs)``;
        None where they would exceed the memory budget."""
        key = (self._matrix_key(seg_id, bc, k), round(dt, 12))
        if key not in self._lu:
            self._lu[key] = self._factorize(self._step_matrix(seg_id, bc, k, dt))
        return self._lu[key]

    def _matrix_key(self, seg_id: int, bc: BoundaryConditions, k: int | None) -> tuple:
        """What the step matrix depends on: the position (conduction and contacts) and the sink links.

        Segments with the same links share one factorisation: a duty cycle that returns to an
        operating point, or one whose ambient changes but not its coefficients.
        """
        key = (seg_id, id(bc), k)
        if key not in self._matrix_keys:
            ambient = self.loads(seg_id, bc, k).ambient
            self._matrix_keys[key] = (k, ambient.key if ambient.key is not None else _digest(ambient.matrix))
        return self._matrix_keys[key]

    def _step_matrix(self, seg_id: int, bc: BoundaryConditions, k: int | None, dt: float) -> Operator:
        loads = self.loads(seg_id, bc, k)
        return operator_sum(loads.conductance, self.model.capacity / dt, loads.ambient.matrix)

    def steady(self, seg_id: int, bc: BoundaryConditions, k: int | None,
               rhs: np.ndarray | None = None) -> np.ndarray:
        """The steady state of segment ``seg_id`` at position k (None: the cycle average).

        ``rhs`` replaces the heat and sink terms: the steady response to any load (the inverse
        estimation's transfer matrix is made of such responses, one factorisation for all),
        at the boundary conditions ``bc`` as given.  Without ``rhs`` a coupled integrator
        iterates the boundary conditions with the state to a fixed point.
        """
        if rhs is not None or self.coupling is None:
            return self._steady_linear(seg_id, bc, k, rhs)
        state = self._steady_linear(seg_id, bc, k, None)
        current = factorised = bc
        reading, fraction, growing, last_step = None, 1.0, 0, None
        change = previous = ratio = math.inf
        for _ in range(STEADY_ITERATIONS):
            now = self.readout(state)
            # Picard on the readings; halved steps once the change grows (an oscillation)
            reading = now if reading is None else reading.toward(now, fraction)
            current, factorised = self._reevaluate(seg_id, bc, reading, current, factorised)
            loads = self.loads(seg_id, current, k)
            load = loads.heat + loads.ambient.source - self._link_change(seg_id, current, factorised, k, state)
            new = self._steady_linear(seg_id, factorised, k, load)
            step = new - state
            change = float(np.max(np.abs(step)))
            # the signed ratio of successive steps: an oscillation (r < 0) shrinking by |r| per
            # step is not the slow one-way contraction that longer steps would shorten
            contraction = _step_ratio(step, last_step)
            state, last_step = new, step
            if change <= STEADY_TOLERANCE:
                break
            growing = growing + 1 if change > previous else 0
            if growing and fraction > MIN_RELAXATION:
                fraction /= 2.0
            elif not growing and abs(contraction) > SLOW_CONTRACTION and abs(contraction - ratio) < 0.02:
                # a steady, slow contraction r (a heat that grows with the temperature) or a slowly
                # fading oscillation (r < 0): the step 1/(1 - r) of the last one lands where the
                # geometric series of plain steps would end (it shortens an oscillation's steps)
                fraction = min(fraction / (1.0 - contraction), MAX_ACCELERATION)
            elif growing >= RUNAWAY_ITERATIONS or not np.all(np.isfinite(state)):
                name, hottest = now.hottest()
                raise ModelError(f"temperatures.coupling = nonlinear: the steady iteration diverges ({name} at "
                                 f"{hottest - 273.15:.0f} degC and rising): the heat grows with the temperature "
                                 "faster than the surfaces shed it (a thermal runaway), or the coupling is too "
                                 "strong for this iteration; a transient run shows where the temperatures go")
            ratio = contraction
            previous = change
        else:
            raise ModelError(f"temperatures.coupling = nonlinear: the steady state did not converge in "
                             f"{STEADY_ITERATIONS} iterations (last change {change:.3g} K)")
        for stale in {id(current): current, id(factorised): factorised}.values():
            if stale is not bc:
                self._forget(seg_id, stale)
        return state

    def steady_boundary_conditions(self, seg_id: int, bc: BoundaryConditions, state: np.ndarray) -> BoundaryConditions:
        """The boundary conditions a (coupled) state was solved with: ``bc`` itself when frozen."""
        return bc if self.coupling is None else self.coupling.evaluate(bc, self.readout(state))

    def _reevaluate(self, seg_id: int, base: BoundaryConditions, now: LocalTemperatures,
                    bc: BoundaryConditions, factorised: BoundaryConditions,
                    transient: bool = False) -> tuple[BoundaryConditions, BoundaryConditions]:
        """Boundary conditions at the reading ``now``, and the ones to factorise the steps with.

        The step matrix is refactorised only once a node's link to its sink has moved by more
        than :data:`~.coupling.LINK_REFACTOR` of its factorised value and, in a transient, by
        more than :data:`~.coupling.LINK_RATE_REFACTOR` times its heat capacity; until then the
        steps take the difference on the right-hand side at the state of the step's start
        (stable, as the difference is a fraction of the implicit operator).
        """
        _within_accepted_temperatures(now)
        evaluated = self.coupling.evaluate(base, now)
        if bc is not factorised:
            self._forget(seg_id, bc)
        if self._links_moved(factorised, evaluated, transient):
            self._forget(seg_id, factorised)
            factorised = evaluated
        return evaluated, factorised

    def air_links(self, seg_id: int, bc: BoundaryConditions, k: int | None) -> tuple[np.ndarray, float]:
        """What one kelvin more of the room's air adds to the step's right-hand side [W per state entry],
        and to the links' heat at their sinks [W]: the air surfaces' links, their coefficients as in ``bc``."""
        key = (seg_id, id(bc), k)
        if key not in self._air_links:
            base = self.loads(seg_id, bc, k).ambient
            moved = self.model.ambient_coupling(at_air(bc, self.model.system, bc.point.ambient + 1.0), k)
            self._air_links[key] = (bc, np.asarray(moved.source - base.source), moved.source_total - base.source_total)
        return self._air_links[key][1:]

    def _link_change(self, seg_id: int, bc: BoundaryConditions, factorised: BoundaryConditions, k: int | None,
                     state: np.ndarray) -> np.ndarray:
        """Heat [W] the links of ``bc`` lose beyond those of the factorised step matrix, at ``state``:
        what the right-hand side takes while the matrix is not refactorised (0 when it is ``bc``'s)."""
        if factorised is bc:
            return np.zeros_like(state)
        return _apply(self._link_difference(seg_id, bc, factorised, k), state)

    def _link_difference(self, seg_id: int, bc: BoundaryConditions, factorised: BoundaryConditions,
                         k: int | None) -> Operator:
        """The links of ``bc`` less those of the factorised step matrix [W/K] at position k (cached)."""
        key = (seg_id, id(bc), id(factorised), k)
        if key not in self._link_changes:
            now, ref = self.loads(seg_id, bc, k).ambient, self.loads(seg_id, factorised, k).ambient
            self._link_changes[key] = now.matrix - ref.matrix
        return self._link_changes[key]

    def _links_moved(self, old: BoundaryConditions, new: BoundaryConditions, transient: bool = False) -> bool:
        g_old, g_new = self.model.ambient_links(old, None), self.model.ambient_links(new, None)
        change = np.abs(g_new - g_old)
        moved = change > LINK_REFACTOR * g_old
        if transient and not self.dense:  # a projected model's links are its full model's
            moved &= change > LINK_RATE_REFACTOR * np.asarray(self.model.capacity)
        return bool(np.any(moved))

    def readout(self, state: np.ndarray) -> LocalTemperatures:
        """The surfaces' and sources' temperatures of ``state`` (:class:`~.coupling.TemperatureReadout`)."""
        if self._readout is None:
            self._readout = TemperatureReadout(self.model)
        return self._readout(state)

    def _steady_linear(self, seg_id: int, bc: BoundaryConditions, k: int | None, rhs: np.ndarray | None) -> np.ndarray:
        loads = self.loads(seg_id, bc, k)
        A = operator_sum(loads.conductance, loads.ambient.matrix)
        if rhs is None:
            rhs = loads.heat + loads.ambient.source
        if self.direct:
            key = ("steady", seg_id, id(bc), k)
            if key not in self._lu:
                self._lu[key] = self._factorize(A)
            if self._lu[key] is not None:
                return self._lu[key].solve(rhs)
        solution, info = cg(A, rhs, x0=np.zeros_like(rhs), rtol=STEADY_CG_RTOL, maxiter=50000, M=jacobi(A))
        if info != 0:
            raise ModelError(f"--solver cg: conjugate gradients did not converge in {info} iterations of the steady "
                             "state; use --solver direct")
        return solution

    # -------------------------------------------------------------- time loop
    def run(self, segments: list[Segment], initial: np.ndarray, sample_times: np.ndarray,
            progress: Callable[[float], None] | None = None, air: RoomAir | None = None) -> Trace:
        """Step through ``segments`` from ``initial``, recording at ``sample_times``; ``air``: the room's
        measured air, which the air surfaces' sinks follow at the end of every step (None: each
        segment's ambient)."""
        # A projected model's factorisations are of the basis's size: a second OpenBLAS thread saves
        # little there and, busy-waiting between calls, slows the other process of a batch's pair
        one_thread = self.uses_pardiso or self.dense
        with pardiso.openblas_on_one_thread() if one_thread else contextlib.nullcontext():
            return self._run(segments, initial, sample_times, progress, air)

    def held_position(self, table_at: float) -> int:
        """The grid position nearest the table position ``table_at`` [m] (the nut's centre along x)."""
        offset = table_at - nut_centre_x(self.model.system)
        return int(np.argmin(np.abs(np.asarray(self.model.positions) - offset)))

    def _run(self, segments: list[Segment], initial: np.ndarray, sample_times: np.ndarray,
             progress: Callable[[float], None] | None, air: RoomAir | None = None) -> Trace:
        m = self.model
        trace = Trace(air=air)
        self._samples = []
        T = initial.copy()
        path = PositionPath(len(m.positions))
        if segments[0].table_at is not None:
            path.u = float(self.held_position(segments[0].table_at))
        t = segments[0].t0
        t_end = segments[-1].t1
        samples = iter(sample_times)
        next_sample = next(samples, None)
        next_snapshot = 0.0
        averaged = self.options.motion == "averaged"
        last_report = -1.0
        T_old, dt_old = None, None  # the previous state, for the solver's starting guess (cg)
        coupled = self.coupling is not None
        period = 2.0 * path.K  # grid cells of one reciprocation cycle
        mid = len(m.positions) // 2
        step_end, step_dt, step_probe = trace.step_end, trace.step_dt, trace.step_probe
        trace.sources = list(m.system.sources)
        heat_in = np.zeros(len(trace.sources))  # each source's heat since the start [J]
        heat_lost = 0.0  # [J]
        increments = IncrementHistory()  # conjugate gradients' starting guesses (:mod:`.iterative`)
        for seg_id, seg in enumerate(segments):
            increments.clear()  # another operating point: another pattern of increments
            moving = seg.speed > 0.0
            resolved = moving and not averaged
            dt_nominal, cells_per_step = self._step(seg)
            windowed = resolved and self._windowed(seg)
            window = self._window_cells(seg) if windowed else 0
            if windowed:
                self.window_cells.add(window)
            # whole grid cells a step (or none): the phases of the stroke recur, and so do their increments
            repeating = float(cells_per_step).is_integer()
            if moving and trace.time_step == 0.0:
                trace.time_step = dt_nominal
            if seg.table_at is not None:  # a measuring stop: the table moved there, held
                path.u = float(self.held_position(seg.table_at))
            bc = factorised = seg.bc  # latest evaluation; the one the step matrix was factorised with
            steps = {}  # (position, dt) → _Step at (bc, factorised): rebuilt whenever they change
            reading, checked = None, path.u
            while t < seg.t1 - 1e-9:
                # A coupled reading is checked every step, or once per cycle while the group
                # reciprocates (so its swing within a cycle does not count as a change).
                if coupled and (reading is None or not resolved or path.u - checked >= period):
                    checked, now = path.u, self.readout(T)
                    if reading is None or now.largest_change(reading) > self.coupling.tolerance:
                        if reading is not None:  # the readings that have hardly moved stay (:mod:`.coupling`)
                            now = now.lagging(reading, REFRESH_SHARE * self.coupling.tolerance)
                        bc, factorised = self._reevaluate(seg_id, seg.bc, now, bc, factorised, transient=True)
                        steps = {}
                        reading = now
                        trace.coupling_updates += 1
                dt = min(dt_nominal, seg.t1 - t)
                u_start = path.u
                if moving:
                    path.advance(cells_per_step * dt / dt_nominal)
                k = path.k
                if windowed:
                    k_step = swept_window(u_start, path.u, path.K, window)
                else:
                    k_step = None if (averaged and moving) else k
                step = steps.get((k_step, dt))
                if step is None:
                    step = steps[k_step, dt] = self._step_kernel(seg_id, bc, factorised, k_step, dt)
                rhs = _apply(step.rhs_operator, T)
                rhs += step.load
                shift = 0.0 if air is None else air.at(t + dt) - bc.point.ambient  # the sinks at the step's end
                if shift:
                    air_source, air_total = self.air_links(seg_id, bc, k_step)
                    rhs += shift * air_source
                if step.lu is not None:
                    T_new = step.lu.solve(rhs)
                else:
                    guess = T if T_old is None else T + (T - T_old) * (dt / dt_old)
                    phase = (round(math.fmod(path.u, period), 6) if period else 0.0, round(dt, 12)) if repeating else None
                    if phase is not None:
                        guess = increments.guess(phase, T, guess)
                    T_new = self.solve(seg_id, factorised, k_step, dt, rhs, T, guess)
                    if phase is not None:
                        increments.record(phase, T_new - T)
                t_new = t + dt
                # energy account: heat in from the boundary conditions, losses from the surfaces,
                # both as the step's equations had them
                lost = step.heat_lost(T, T_new)
                if shift:
                    lost -= shift * air_total
                trace.heat_in += step.heat_in * dt
                trace.heat_lost += lost * dt
                if trace.first_heat_in is None:
                    trace.first_heat_in, trace.first_heat_lost = step.heats.copy(), lost
                # the moving sensors sit where the group is; averaged motion smears it over the stroke
                k_probe = mid if (averaged and moving) else k
                while next_sample is not None and next_sample <= t_new + 1e-9:
                    w = (next_sample - t) / dt
                    state = (1 - w) * T + w * T_new
                    self._record_sample(trace, state, k_probe)
                    # the ledger's heats as the state: the step's share up to the sample
                    trace.sample_heat_in.append(heat_in + step.heats * (w * dt))
                    trace.sample_heat_lost.append(heat_lost + lost * (w * dt))
                    if self.options.fields and (next_sample >= next_snapshot - 1e-9 or next_sample >= t_end - 1e-9):
                        trace.snapshots.append((next_sample, state, m.positions[k_probe]))
                        next_snapshot = next_sample + self.options.snapshot_interval
                    next_sample = next(samples, None)
                heat_in = heat_in + step.heats * dt
                heat_lost += lost * dt
                step_end.append(t_new)
                step_dt.append(dt)
                step_probe.append(m.probe(T_new, k_probe))
                T_old, dt_old = T, dt
                T, t = T_new, t_new
                if progress is not None and t - last_report >= 0.01 * (t_end - segments[0].t0):
                    progress((t - segments[0].t0) / (t_end - segments[0].t0))
                    last_report = t
            trace.final_bc = bc
            if coupled:  # a coupled segment's evaluations are not met again: free their factorisations
                for stale in {id(bc): bc, id(factorised): factorised}.values():
                    if stale is not seg.bc:
                        self._forget(seg_id, stale)
        self._read_samples(trace)
        trace.final_state = T
        trace.final_position = path.k
        return trace

    def _step_kernel(self, seg_id: int, bc: BoundaryConditions, factorised: BoundaryConditions, k: int | None,
                     dt: float) -> "_Step":
        """What a step at position k takes from the caches, gathered once per (boundary conditions, k, dt)."""
        loads = self.loads(seg_id, bc, k)
        cap_dt = self.model.capacity / dt
        lu = self.factors(seg_id, factorised, k, dt) if self.direct else None
        heats = source_powers(bc, list(self.model.system.sources))
        if factorised is bc:
            return _Step(cap_dt, loads.heat + loads.ambient.source, lu, bc.total_heat, heats, loads.ambient, None)
        # the links' change since the factorisation, taken at the step's start state
        change = self._link_difference(seg_id, bc, factorised, k)
        if np.ndim(cap_dt) == 1 and np.ndim(change) == 1:
            rhs_operator = cap_dt - change
        elif np.ndim(cap_dt) == 1 and isinstance(change, np.ndarray):
            rhs_operator = _DiagonalLess(cap_dt, change)
        else:
            rhs_operator = operator_sum(cap_dt, -change)
        return _Step(rhs_operator, loads.heat + loads.ambient.source, lu, bc.total_heat, heats, loads.ambient,
                     self.loads(seg_id, factorised, k).ambient)

    def _record_sample(self, trace: Trace, state: np.ndarray, k: int) -> None:
        m = self.model
        trace.sample_probe.append(m.probe(state, k))
        trace.sample_offset.append(m.positions[k])
        self._samples.append(state)
        if len(self._samples) * m.n_nodes >= SAMPLE_BLOCK_ENTRIES:
            self._read_samples(trace)

    def _read_samples(self, trace: Trace) -> None:
        """The screw profile, the displacements and the part means of the samples kept since the last
        reading, read at once: one product with a block of states costs a fraction of one a state."""
        if not self._samples:
            return
        m = self.model
        states = np.array(self._samples)
        self._samples = []
        trace.sample_screw.extend(m.screw_mean(states))
        trace.sample_displacement.extend(m.displacements(states))
        parts = m.part_means(states)
        trace.sample_parts.extend({p: float(v[i]) for p, v in parts.items()} for i in range(len(states)))

    def _windowed(self, seg: Segment) -> bool:
        """Whether ``seg``'s resolved steps sweep windows (:mod:`.windows`): a moving segment of a model
        that takes the windowed motion, unless the run asks for the exact one."""
        return (seg.speed > 0.0 and self.options.motion == "resolved" and self.model.windowed_motion
                and len(self.model.positions) > 1)

    def _window_cells(self, seg: Segment) -> int:
        """Cells a windowed step of ``seg`` sweeps (:func:`.windows.window_cells`)."""
        K = len(self.model.positions) - 1
        return window_cells(K, max(1, K // self.options.steps_per_stroke), self.model.dx, seg.speed,
                            self.options.window_step)

    def _step(self, seg: Segment) -> tuple[float, float]:
        """Nominal time step [s] and grid positions advanced per step in ``seg``."""
        opts = self.options
        if opts.motion == "averaged" and seg.speed > 0.0:
            return min(opts.averaged_step, opts.max_step), 0.0
        if seg.speed == 0.0:
            return min(opts.standstill_step, opts.max_step), 0.0
        K = len(self.model.positions) - 1
        cells = self._window_cells(seg) if self._windowed(seg) else max(1, K // opts.steps_per_stroke)
        dt = cells * self.model.dx / seg.speed
        if dt > opts.max_step:  # slow table: smaller steps, fractional advance per step
            return opts.max_step, cells * opts.max_step / dt
        return dt, float(cells)


def _step_ratio(step: np.ndarray, last: np.ndarray | None) -> float:
    """The signed ratio r of two successive iteration steps, the projection of ``step`` on ``last``.

    Near a fixed point a Picard iteration's steps shrink as s_{k+1} ~ r s_k: r in (0, 1) is a
    one-way contraction, r < 0 an oscillation.  Infinite before there are two steps to compare.
    """
    if last is None:
        return math.inf
    norm = float(last @ last)
    return float(step @ last) / norm if norm > 0.0 else math.inf


def _within_accepted_temperatures(now: LocalTemperatures) -> None:
    """A coupled reading outside the temperatures the properties hold for is a runaway, not a state.

    The iterates of a steady state and the steps of a transient alike: evaluated there, a
    correlation would refuse an argument or a heat pass a megawatt, and the message would name
    a value and not the cause.
    """
    outside = now.outside(TEMPERATURE_LIMIT.low, TEMPERATURE_LIMIT.high)
    if outside is not None:
        name, value = outside
        raise ModelError(f"temperatures.coupling = nonlinear: {name} reaches {value - 273.15:.4g} degC, outside "
                         f"{TEMPERATURE_LIMIT.describe()}: the heat grows with the temperature faster than the "
                         "surfaces shed it (a thermal runaway), or a value of the description is far from its "
                         "machine's")
