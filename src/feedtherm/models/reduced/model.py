"""The reduced model: a :class:`~.projection.Projection` as a :class:`~feedtherm.models.interface.ThermalModel`.

The shared integrator runs it as any model: dense operators of the basis's size per position,
the boundary conditions weighing the projected exposures and entries by their coefficients
and heats (:mod:`.projection`).  The full model is not needed to run: a model read from the
disk cache (:mod:`.store`) builds it only if a caller asks for something the projection does
not hold (a surface's nodes, a position's boundary basis), once.
"""

from __future__ import annotations

import weakref
from typing import Callable

import numpy as np

from ...boundary import BoundaryConditions
from ...system.schema import FeedSystem
from ...constants import ELONGATION_PROBE
from ..interface import (AmbientCoupling, HeatInput, PositionWindow, ThermalModel, affine_value, cycle_weights,
                         source_powers)
from .basis import Basis
from .projection import Projection, project

__all__ = ["ProjectedModel"]

#: What every model of a projection computes alike from it (the cycle averages of its per-position
#: arrays, the uniform state's row), kept once per projection: a batch makes a model of the one
#: projection it holds in memory for each of its runs.
_SHARED: "weakref.WeakKeyDictionary[Projection, dict[str, np.ndarray]]" = weakref.WeakKeyDictionary()


def _shared(projection: Projection, name: str, compute: Callable[[], np.ndarray]) -> np.ndarray:
    cache = _SHARED.setdefault(projection, {})
    if name not in cache:
        cache[name] = compute()
    return cache[name]


class ProjectedModel(ThermalModel):
    """``full`` projected onto ``basis``; :meth:`from_projection` makes one of a projection alone."""

    #: stepped as its full model is, so that the two answer alike (the FE model's resolved motion is windowed)
    windowed_motion = True

    def __init__(self, full: ThermalModel, basis: Basis):
        self._setup(project(full, basis), full.system, full=full)

    @classmethod
    def from_projection(cls, projection: Projection, system: FeedSystem,
                        build_full: Callable[[], ThermalModel], **stats) -> "ProjectedModel":
        """A model of ``projection`` (of ``system``'s full model); ``build_full()`` builds that full model
        if a caller needs it; ``stats`` are added to :attr:`stats` (where the projection came from)."""
        model = cls.__new__(cls)
        model._setup(projection, system, build_full=build_full, extra_stats=stats)
        return model

    def _setup(self, projection: Projection, system: FeedSystem, *, full: ThermalModel | None = None,
               build_full: Callable[[], ThermalModel] | None = None, extra_stats: dict | None = None) -> None:
        self.projection = p = projection
        self._full, self._build_full = full, build_full
        self._extra_stats = dict(extra_stats or {})
        self.system = system
        self.basis = p.basis
        self.V = p.V
        self.n_nodes = p.V.shape[1]
        self.capacity = np.ones(self.n_nodes)  # Vᵀ C V = I: the basis is capacity-orthonormal
        self.positions = p.positions
        self.dx = p.dx
        self.probe_names = list(p.probe_names)
        self.screw_edges = p.screw_edges
        self.screw_centres = p.screw_centres
        self._surfaces, self._sources = list(p.surfaces), list(p.sources)
        self._weights = cycle_weights(len(p.positions))
        self._weighted = {}  # None (cycle average) or "positions" → (coefficients, Σ h_i Vᵀ diag(e_i) V), the latest
        self._take_values(system)

    def _take_values(self, system: FeedSystem) -> None:
        """The operators and displacement rows at ``system``'s values of the affine parameters: the
        projection's, plus each term times the change of its parameter (exact, as the full model's)."""
        p = self.projection
        self._conductance = p.conductance
        self._displacements = (p.displacement_rows, p.displacement_offsets)
        self._probes = (p.probe_rows, p.probe_offsets)
        self.expansion_changed = False
        dq = np.array([affine_value(system, name) for name in p.conductance_parameters]) - p.conductance_values
        # a position's operator is formed when a run asks for it (a cycle-averaged run asks for none)
        self._conductance_change = dq if np.any(dq != 0.0) else None
        self._at_position: dict[int, np.ndarray] = {}
        self._term_sum: np.ndarray | None = None
        da = np.array([affine_value(system, name) for name in p.expansion_parameters]) - p.expansion_values
        if np.any(da != 0.0):
            self.expansion_changed = True
            rows = p.displacement_rows + np.tensordot(da, p.displacement_terms, axes=1)
            offsets = p.displacement_offsets + da @ p.displacement_offset_terms
            self._displacements = (rows, offsets)
            if self.probe_names and self.probe_names[-1] == ELONGATION_PROBE:  # D is the last probe, row 0
                probe_rows, probe_offsets = p.probe_rows.copy(), p.probe_offsets.copy()
                probe_rows[:, -1] = rows[0]
                probe_offsets[:, -1] = offsets[0]
                self._probes = (probe_rows, probe_offsets)

    @property
    def full(self) -> ThermalModel:
        """The full model (built on first use when this model was read from the cache)."""
        if self._full is None:
            self._full = self._build_full()
        return self._full

    # ------------------------------------------------------------------ operators
    def _at(self, name: str, k: int | None) -> np.ndarray:
        """Array ``name`` of the projection (positions first) at position k, or its cycle average."""
        values = getattr(self.projection, name)
        if isinstance(k, PositionWindow):
            return np.tensordot(k.weights, values[k.first:k.last + 1], axes=1)
        if k is not None:
            return values[k]
        return _shared(self.projection, name, lambda: np.tensordot(self._weights, values, axes=1))

    def conductance(self, k: int) -> np.ndarray:
        dq = self._conductance_change
        if dq is None:
            return self._conductance[k]
        if k not in self._at_position:
            p = self.projection
            moved = np.tensordot(dq[p.conductance_moving], p.conductance_term_change[k], axes=1)
            self._at_position[k] = p.conductance[k] + self._terms() + moved
        return self._at_position[k]

    def _terms(self) -> np.ndarray:
        """Σ (q − q₀) Vᵀ G_q V over the terms, at every position alike (their sliding part apart)."""
        if self._term_sum is None:
            self._term_sum = np.tensordot(self._conductance_change, self.projection.conductance_terms, axes=1)
        return self._term_sum

    def averaged_conductance(self) -> np.ndarray:
        """The cycle average, from the projection's averages and the terms weighed by the description's
        values: r² per term, where averaging the positions' operators is r² per position and term."""
        dq = self._conductance_change
        if dq is None:
            return super().averaged_conductance()
        moving = self.projection.conductance_moving
        average = self._at("conductance", None) + self._terms()
        return average + np.tensordot(dq[moving], self._at("conductance_term_change", None), axes=1)

    def ambient_coupling(self, bc: BoundaryConditions, k: int | None) -> AmbientCoupling:
        h, sinks = self.projection.averaged.coefficients(bc)  # the full model's film in series, if it has one
        matrix = self._weighted_exposure(h, k)
        rows = self._at("exposure_rows", k)
        key = h.tobytes()  # with the position (the integrator's key holds it), the coefficients make the matrix
        return AmbientCoupling(matrix, h @ rows, (h * sinks) @ rows, float((h * sinks) @ self._at("exposure_areas", k)),
                               key)

    def _exposures(self, k: int | None) -> np.ndarray:
        """Each surface's Vᵀ diag(e_i) V at position k, or its cycle average (the moving surfaces' change
        added in once per projection: a cycle-averaged run weighs one array, not two)."""
        exposure = self.projection.exposure
        if k is not None:
            return exposure
        def averaged() -> np.ndarray:
            combined = exposure.copy()
            combined[self.projection.moving_surfaces] += self._at("exposure_change", None)
            return combined
        return _shared(self.projection, "exposure_averaged", averaged)

    def _weighted_exposure(self, h: np.ndarray, k: int | None) -> np.ndarray:
        """Σ h_i Vᵀ diag(e_i) V at position k, the latest kept for each position: a coupled run asks
        for every position with one evaluation's coefficients before the next.

        A re-evaluation of a coupled run changes some of the coefficients and keeps the others
        (:mod:`~feedtherm.models.coupling`): the sum is then the latest one plus the changed terms,
        each an r × r pass over memory where the whole sum is one pass per surface.
        """
        slot = None if k is None else "positions"
        latest, matrix = self._weighted.get(slot, (None, None))
        exposure = self._exposures(k)
        if latest is None or not np.array_equal(latest, h):
            changed = None if latest is None else np.flatnonzero(h != latest)
            if changed is None or 2 * len(changed) > len(h):
                matrix = np.tensordot(h, exposure, axes=1)
            else:
                matrix = matrix.copy()
                for i in changed:
                    matrix += (h[i] - latest[i]) * exposure[i]
            self._weighted[slot] = (h.copy(), matrix)
        if k is None:
            return matrix
        moving = self.projection.moving_surfaces
        return matrix + np.tensordot(h[moving], self._at("exposure_change", k), axes=1)

    def heat_vector(self, bc: BoundaryConditions, k: int | None) -> np.ndarray:
        return source_powers(bc, self._sources) @ self._at("entries", k)

    def boundary_basis(self, k: int | None):
        return self.projection.averaged if k is None else self.full.boundary_basis(k)

    def surface_exposure(self, name: str, k: int):
        return self.full.surface_exposure(name, k)

    def heat_distribution(self, heat: HeatInput, k: int) -> np.ndarray:
        return self.V.T @ self.full.heat_distribution(heat, k)

    # ------------------------------------------------------------------ states
    def restrict(self, rows):
        return np.asarray(rows @ self.V)

    def full_state(self, state: np.ndarray) -> np.ndarray:
        return self.V @ state

    def uniform_state(self, temperature: float) -> np.ndarray:
        # the uniform state is the basis's first vector, so this is exact
        return float(temperature) * _shared(self.projection, "capacity_row",
                                            lambda: self.V.T @ self.projection.full_capacity)

    def heat_stored(self, state: np.ndarray, start: np.ndarray) -> float:
        return float(self.projection.stored @ (state - start))

    # ------------------------------------------------------------------ readout
    def _probe_rows(self, k: int) -> tuple[np.ndarray, np.ndarray]:
        return self._probes[0][k], self._probes[1][k]

    def probe_rows(self, k: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """The full model's probe rows projected on the basis (this model's state)."""
        return self._probe_rows(k)

    def probe(self, state: np.ndarray, k: int = 0) -> np.ndarray:
        rows, offset = self._probe_rows(k)
        return rows @ state + offset

    def displacement_rows(self) -> tuple[np.ndarray, np.ndarray]:
        return self._displacements

    def displacement_field(self, state: np.ndarray) -> np.ndarray | None:
        p = self.projection
        if p.displacement_basis is None:
            return None
        if self.expansion_changed:  # the kept fields are of the projection's expansions: the full model's own
            return self.full.displacement_field(self.V @ np.asarray(state, dtype=float))
        return (p.displacement_basis @ np.asarray(state, dtype=np.float32) + p.displacement_origin).reshape(-1, 3)

    def screw_mean(self, states: np.ndarray) -> np.ndarray:
        return np.asarray(states) @ self.projection.screw

    def part_means(self, states: np.ndarray) -> dict[str, np.ndarray]:
        states = np.asarray(states)
        return {name: states @ v for name, v in self.projection.parts.items()}

    def part_capacities(self) -> dict[str, float] | None:
        """The full model's: the part means are its capacity-weighted means of the lifted state ``V z``,
        and ``Σ_p C_p T̄_p = Σ C (V z)``, the stored heat of :meth:`heat_stored`."""
        capacity = self.projection.part_capacity
        return None if capacity is None else dict(capacity)

    def field_mesh(self):
        return self.projection.field_mesh

    @property
    def stats(self) -> dict:
        b = self.basis
        return {**self.projection.full_stats, "reduced_from": int(self.projection.full_capacity.size),
                "basis_size": b.size, "basis_tolerance": b.tolerance, "basis_snapshots": b.snapshots,
                "basis_seconds": round(b.seconds, 2), "basis_cached": b.cached,
                "trained_over": self.projection.trained_over, **self._extra_stats}
