"""Time integration of the fast model (implicit Euler) with the moving group reciprocating.

Each step solves ``(C/dt + G(k) + diag(g_amb(k))) T⁺ = C/dt T + q(k) + g_amb(k) T_amb``
with ``k`` the moving group's grid position at the end of the step.  While the table moves,
a step advances the moving group by a whole number of cells, so every position's matrix is
factorised once and reused.  The energy account is kept apart from the solver's matrices:
heat in from the boundary conditions, heat lost from the surface coefficients and areas,
heat stored from the capacities.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Literal

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from ...boundary import BoundaryConditions
from .assemble import Network
from .layout import Layout


@dataclass(frozen=True)
class FastOptions:
    """Discretisation of the fast model (defaults meet the issue's resolution)."""

    axial_cells: int = 100  # at least this many cells along the screw
    radial_rings: int = 2  # rings per screw cell
    steps_per_stroke: int = 20  # at least this many time steps per stroke
    standstill_step: float = 10.0  # [s] time step while the table stands still
    max_step: float = 30.0  # [s] upper bound of any step
    motion: Literal["resolved", "averaged"] = "resolved"  # position over time, or cycle-averaged
    averaged_step: float = 10.0  # [s] time step of the cycle-averaged model


@dataclass(frozen=True)
class Segment:
    """A stretch of constant operating point, [t0, t1) in seconds."""

    t0: float
    t1: float
    bc: BoundaryConditions

    @property
    def speed(self) -> float:
        return abs(self.bc.point.table_speed)


@dataclass
class Trace:
    """What the integrator hands back: step records and samples at the requested times."""

    step_end: list = field(default_factory=list)  # time at the end of each step [s]
    step_dt: list = field(default_factory=list)
    step_probe: list = field(default_factory=list)  # probe values at the end of each step
    samples: list = field(default_factory=list)  # full state vectors at sample times
    sample_offset: list = field(default_factory=list)  # moving-group offset at sample times [m]
    heat_in: float = 0.0
    heat_lost: float = 0.0
    time_step: float = 0.0  # the (first moving segment's) step [s]
    final_state: np.ndarray | None = None
    final_position: int = 0


class PositionPath:
    """Reciprocation over grid positions 0..K along a triangle wave (in cells)."""

    def __init__(self, n_positions: int):
        self.K = n_positions - 1
        self.u = 0.0

    @property
    def k(self) -> int:
        period = 2 * self.K
        tri = math.fmod(self.u, period)
        pos = tri if tri <= self.K else period - tri
        return int(round(pos))

    def advance(self, cells: float) -> None:
        self.u += cells


class Integrator:
    def __init__(self, layout: Layout, network: Network, options: FastOptions):
        self.layout = layout
        self.network = network
        self.options = options
        self._sliding = {}
        self._lu = {}
        self._loads = {}

    # -------------------------------------------------------------- cached pieces
    def sliding(self, k: int) -> sp.csr_matrix:
        if k not in self._sliding:
            self._sliding[k] = self.network.sliding(k)
        return self._sliding[k]

    def weights(self) -> np.ndarray:
        """Time share of each grid position under steady reciprocation (ends count half)."""
        K = len(self.layout.positions) - 1
        w = np.ones(K + 1)
        w[0] = w[-1] = 0.5
        return w / w.sum()

    def loads(self, seg_id: int, bc: BoundaryConditions, k: int | None):
        """(conductance matrix, ambient links, heat vector, loss coefficients) at position k.

        ``k = None`` gives the cycle average over all positions.
        """
        key = (seg_id, k)
        if key not in self._loads:
            if k is None:
                w = self.weights()
                parts = [self.loads(seg_id, bc, j) for j in range(len(w))]
                G = sum(wj * p[0] for wj, p in zip(w, parts))
                vectors = [sum(wj * p[i] for wj, p in zip(w, parts)) for i in (1, 2, 3)]
                self._loads[key] = (G.tocsr(), *vectors)
            else:
                G = self.network.fixed + self.sliding(k)
                g_amb = self.network.ambient_links(bc, k)
                q = self.network.heat_vector(bc, k)
                loss = self.network.ambient_links(bc, k, for_solver=False)
                self._loads[key] = (G, g_amb, q, loss)
        return self._loads[key]

    def factor(self, seg_id: int, bc: BoundaryConditions, k: int | None, dt: float):
        key = (seg_id, k, round(dt, 12))
        if key not in self._lu:
            G, g_amb, _, _ = self.loads(seg_id, bc, k)
            A = G + sp.diags(self.layout.capacity / dt + g_amb)
            self._lu[key] = splu(A.tocsc())
        return self._lu[key]

    def steady(self, seg_id: int, bc: BoundaryConditions, k: int | None) -> np.ndarray:
        G, g_amb, q, _ = self.loads(seg_id, bc, k)
        A = (G + sp.diags(g_amb)).tocsc()
        return splu(A).solve(q + g_amb * bc.point.ambient)

    # -------------------------------------------------------------- time loop
    def run(self, segments: list[Segment], initial: np.ndarray, sample_times: np.ndarray,
            probe: Callable[[np.ndarray], np.ndarray], progress: Callable[[float], None] | None = None) -> Trace:
        trace = Trace()
        T = initial.copy()
        path = PositionPath(len(self.layout.positions))
        t = segments[0].t0
        t_end = segments[-1].t1
        samples = iter(sample_times)
        next_sample = next(samples, None)
        averaged = self.options.motion == "averaged"
        C = self.layout.capacity
        last_report = -1.0
        for seg_id, seg in enumerate(segments):
            moving = seg.speed > 0.0
            dt_nominal, cells_per_step = self._step(seg)
            if moving and trace.time_step == 0.0:
                trace.time_step = dt_nominal
            while t < seg.t1 - 1e-9:
                dt = min(dt_nominal, seg.t1 - t)
                if moving:
                    path.advance(cells_per_step * dt / dt_nominal)
                k = None if (averaged and moving) else path.k
                lu = self.factor(seg_id, seg.bc, k, dt)
                _, g_amb, q, loss = self.loads(seg_id, seg.bc, k)
                T_new = lu.solve(C / dt * T + q + g_amb * seg.bc.point.ambient)
                t_new = t + dt
                # energy account: heat in from the boundary conditions, losses from the surfaces
                trace.heat_in += seg.bc.total_heat * dt
                trace.heat_lost += float(loss @ (T_new - seg.bc.point.ambient)) * dt
                while next_sample is not None and next_sample <= t_new + 1e-9:
                    w = (next_sample - t) / dt
                    trace.samples.append((1 - w) * T + w * T_new)
                    trace.sample_offset.append(self.layout.positions[path.k])
                    next_sample = next(samples, None)
                trace.step_end.append(t_new)
                trace.step_dt.append(dt)
                trace.step_probe.append(probe(T_new))
                T, t = T_new, t_new
                if progress is not None and t - last_report >= 0.01 * (t_end - segments[0].t0):
                    progress((t - segments[0].t0) / (t_end - segments[0].t0))
                    last_report = t
        trace.final_state = T
        trace.final_position = path.k
        return trace

    def _step(self, seg: Segment) -> tuple[float, float]:
        """Nominal time step [s] and cells advanced per step in ``seg``."""
        opts = self.options
        if opts.motion == "averaged" and seg.speed > 0.0:
            return min(opts.averaged_step, opts.max_step), 0.0
        if seg.speed == 0.0:
            return min(opts.standstill_step, opts.max_step), 0.0
        K = len(self.layout.positions) - 1
        cells = max(1, K // opts.steps_per_stroke)
        dt = cells * self.layout.dx / seg.speed
        if dt > opts.max_step:  # slow table: smaller steps, fractional advance per step
            return opts.max_step, cells * opts.max_step / dt
        return dt, float(cells)
