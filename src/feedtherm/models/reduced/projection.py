r"""A full model projected onto a basis: the same interface, dense operators of the basis's size.

With a capacity-orthonormal basis :math:`V` (n × r) the state is :math:`T \approx V z` and the
Galerkin projection of :math:`C\dot T + (G_k + A_k)T = q_k + s_k` is

.. math:: \dot z + (V^T G_k V + V^T A_k V)\,z = V^T q_k + V^T s_k .

What depends on the moving group's position is projected once per position: the conduction
and contacts :math:`V^T G_k V`, each surface's exposure :math:`V^T \mathrm{diag}(e_{ik}) V`
and each source's entry :math:`V^T d_{jk}`; only what changes from position 0 is multiplied
out again, so a position costs the few nodes under the nut.  The boundary conditions weigh
these pieces by their coefficients and heats, so a coupled run re-evaluates them without
touching the full model.  The readouts (sensors, D, the screw's sections, the parts' means)
are the full model's rows times :math:`V`.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...boundary import BoundaryConditions
from ..interface import AmbientCoupling, HeatInput, ThermalModel, cycle_weights, source_powers, surface_coefficients
from .basis import Basis

__all__ = ["ProjectedModel"]


def _changed(current: sp.spmatrix, reference: sp.spmatrix) -> sp.csr_matrix:
    difference = (current - reference).tocsr()
    difference.eliminate_zeros()
    return difference


class ProjectedModel(ThermalModel):
    """``full`` projected onto ``basis`` (see the module notes)."""

    def __init__(self, full: ThermalModel, basis: Basis):
        self.full = full
        self.basis = basis
        V = np.ascontiguousarray(basis.vectors)  # sparse @ V copies a Fortran-ordered V on every product
        self.V = V
        self.system = full.system
        self.n_nodes = V.shape[1]
        self.positions = full.positions
        self.dx = full.dx
        self.probe_names = full.probe_names
        self.screw_edges = full.screw_edges
        self.screw_centres = full.screw_centres
        C = np.asarray(full.capacity)
        self.capacity = np.ones(self.n_nodes)  # Vᵀ C V = I: the basis is capacity-orthonormal
        self._stored = V.T @ C  # heat stored per unit of each reduced coordinate [J/K]
        self._screw = np.asarray(full.screw_mean(V.T))  # (r, sections)
        self._parts = {name: np.asarray(v) for name, v in full.part_means(V.T).items()}
        self._conductance: dict[int, np.ndarray] = {}
        self._boundary: dict[int | None, tuple] = {}
        self._probes: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        self._projected_probes: dict[int, tuple] = {}  # id(full rows) → (the rows, rows @ V)
        reference = full.boundary_basis(0)
        self._reference = reference
        self._reference_exposure = self._project_exposure(reference.exposure)
        self._G0 = full.conductance(0)
        self._G0_projected = self._project(self._G0)

    # ------------------------------------------------------------------ projection
    def _project(self, matrix: sp.spmatrix) -> np.ndarray:
        rows = np.unique(matrix.nonzero()[0])
        if rows.size == 0:
            return np.zeros((self.n_nodes, self.n_nodes))
        return self.V[rows].T @ (matrix[rows] @ self.V)

    def _project_exposure(self, exposure: sp.csr_matrix) -> np.ndarray:
        """``V^T diag(e_i) V`` for every surface row ``e_i`` of ``exposure``: shape (surfaces, r, r)."""
        out = np.zeros((exposure.shape[0], self.n_nodes, self.n_nodes))
        for i in range(exposure.shape[0]):
            row = exposure.getrow(i)
            nodes, areas = row.indices, row.data
            if nodes.size:
                Vn = self.V[nodes]
                out[i] = Vn.T @ (areas[:, None] * Vn)
        return out

    def conductance(self, k: int) -> np.ndarray:
        if k not in self._conductance:
            self._conductance[k] = self._G0_projected + self._project(_changed(self.full.conductance(k), self._G0))
        return self._conductance[k]

    def _boundary_pieces(self, k: int | None) -> tuple:
        """Per-surface projected exposures (s, r, r) and rows (s, r), areas (s,), source entries (sources, r)."""
        if k not in self._boundary:
            if k is None:
                w = cycle_weights(len(self.positions))
                pieces = [self._boundary_pieces(j) for j in range(len(w))]
                self._boundary[k] = tuple(sum(wj * p[i] for wj, p in zip(w, pieces)) for i in range(4))
            else:
                basis = self.full.boundary_basis(k)
                matrices = self._reference_exposure + self._project_exposure(
                    _changed(basis.exposure, self._reference.exposure))
                rows = np.asarray(basis.exposure @ self.V)
                areas = np.asarray(basis.exposure.sum(axis=1)).ravel()
                entries = np.asarray(basis.distribution @ self.V)
                self._boundary[k] = (matrices, rows, areas, entries)
        return self._boundary[k]

    # ------------------------------------------------------------------ the interface
    def surface_exposure(self, name: str, k: int):
        return self.full.surface_exposure(name, k)

    def heat_distribution(self, heat: HeatInput, k: int) -> np.ndarray:
        return self.V.T @ self.full.heat_distribution(heat, k)

    def boundary_basis(self, k):
        return self.full.boundary_basis(k)

    def ambient_links(self, bc: BoundaryConditions, k: int | None) -> np.ndarray:
        return self.full.ambient_links(bc, k)

    def ambient_coupling(self, bc: BoundaryConditions, k: int | None) -> AmbientCoupling:
        matrices, rows, areas, _ = self._boundary_pieces(k)
        h, sinks = surface_coefficients(bc, self._reference.surfaces)
        return AmbientCoupling(np.tensordot(h, matrices, axes=1), h @ rows, (h * sinks) @ rows,
                               float((h * sinks) @ areas))

    def heat_vector(self, bc: BoundaryConditions, k: int | None) -> np.ndarray:
        return source_powers(bc, self._reference.sources) @ self._boundary_pieces(k)[3]

    def restrict(self, rows):
        return np.asarray(rows @ self.V)

    def full_state(self, state: np.ndarray) -> np.ndarray:
        return self.V @ state

    def uniform_state(self, temperature: float) -> np.ndarray:
        # the uniform state is the basis's first vector, so this is exact
        return self.V.T @ (np.asarray(self.full.capacity) * np.full(self.full.n_nodes, float(temperature)))

    def heat_stored(self, state: np.ndarray, start: np.ndarray) -> float:
        return float(self._stored @ (state - start))

    # ------------------------------------------------------------------ readout
    def _probe_rows(self, k: int) -> tuple[np.ndarray, np.ndarray]:
        if k not in self._probes:
            given = self.full.probe_rows(k)
            if given is not None:  # rows @ V once per rows object (a model's rows are often the same at every k)
                rows, offset = given
                known = self._projected_probes.get(id(rows))
                if known is None or known[0] is not rows:
                    known = self._projected_probes[id(rows)] = (rows, np.asarray(rows @ self.V))
                self._probes[k] = (known[1], np.asarray(offset, dtype=float))
                return self._probes[k]
            offset = np.asarray(self.full.probe(np.zeros(self.full.n_nodes), k))
            columns = [np.asarray(self.full.probe(self.V[:, j], k)) - offset for j in range(self.n_nodes)]
            self._probes[k] = (np.column_stack(columns), offset)
        return self._probes[k]

    def probe(self, state: np.ndarray, k: int = 0) -> np.ndarray:
        rows, offset = self._probe_rows(k)
        return rows @ state + offset

    def screw_mean(self, states: np.ndarray) -> np.ndarray:
        return np.asarray(states) @ self._screw

    def part_means(self, states: np.ndarray) -> dict[str, np.ndarray]:
        states = np.asarray(states)
        return {name: states @ v for name, v in self._parts.items()}

    def field_mesh(self):
        return self.full.field_mesh()

    @property
    def stats(self) -> dict:
        b = self.basis
        return {**self.full.stats, "reduced_from": self.full.n_nodes, "basis_size": b.size,
                "basis_tolerance": b.tolerance, "basis_snapshots": b.snapshots,
                "basis_seconds": round(b.seconds, 2), "basis_cached": b.cached}
