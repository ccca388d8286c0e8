"""The verification cases: descriptions in ``cases/``, run by the ordinary entry points.

Each case is a description file with a ``# requirement:`` line and its reference (MOOSE's
way: what is verified is what users run).  Transient cases go through
:func:`feedtherm.simulate.simulate`; steady cases through
:func:`feedtherm.simulate.steady_solve` (what ``steady_state()`` runs), which keeps the model so
that a test can read heat flows from it.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from pathlib import Path

import numpy as np

from feedtherm.boundary import BoundaryConditions
from feedtherm.models.fem.readout import slab_matrix
from feedtherm.models.interface import ThermalModel, cycle_weights
from feedtherm.models.options import ModelOptions
from feedtherm.simulate import steady_solve
from feedtherm.system.load import LoadedSystem, load_system

CASES = Path(__file__).parent / "cases"


@cache
def load_case(name: str) -> LoadedSystem:
    """The description ``cases/<name>.toml``, loaded and validated as any other."""
    return load_system(str(CASES / f"{name}.toml"))


@dataclass(frozen=True)
class SteadyState:
    """The FE model's steady state of one condition (cycle-averaged when the table moves)."""

    model: ThermalModel
    bc: BoundaryConditions
    state: np.ndarray  # [K]
    k: int | None  # the position, or None for the cycle average

    def surface_heat(self, name: str) -> float:
        """Heat [W] surface ``name`` gives to its sink, ``∑ h·a·(T − T_sink)`` over its exposed nodes."""
        transfer = self.bc.surfaces[name]
        positions = [self.k] if self.k is not None else range(len(self.model.positions))
        weights = [1.0] if self.k is not None else cycle_weights(len(self.model.positions))
        total = 0.0
        for w, k in zip(weights, positions):
            nodes, areas = self.model.surface_exposure(name, k)
            total += w * transfer.total * float(areas @ (self.state[nodes] - transfer.sink))
        return total


def section_means(mesh, temperatures: np.ndarray, part: str, edges: np.ndarray) -> np.ndarray:
    """Volume means [K] of nodal ``temperatures`` over ``part``'s slabs ``edges[i] ≤ x < edges[i+1]``.

    ``mesh`` is a field mesh or field series (points (n, 3), tets (m, 4), part_id, part_names);
    the means are the FE model's own section readout (``models/fem/readout.py::slab_matrix``),
    what its screw profile is read with.
    """
    tets = mesh.tets[np.asarray(mesh.part_id) == list(mesh.part_names).index(part)].T
    return slab_matrix(np.asarray(mesh.points).T, tets, np.asarray(edges, dtype=float), len(mesh.points)) @ temperatures


def solve_steady(loaded: LoadedSystem, condition: str, mesh: str, options: ModelOptions | None = None) -> SteadyState:
    """The steady state of ``condition`` with the FE model at ``mesh`` density (as ``steady_state()`` solves it)."""
    steady = steady_solve(loaded, condition, model="fem", mesh=mesh, options=options)
    return SteadyState(steady.model, steady.segment.bc, steady.state, steady.k)


def observed_order(errors, sizes) -> list[float]:
    """Orders ``ln(e_i/e_{i+1}) / ln(h_i/h_{i+1})`` of successive (size, error) pairs."""
    e, h = np.abs(np.asarray(errors, float)), np.asarray(sizes, float)
    return list(np.log(e[:-1] / e[1:]) / np.log(h[:-1] / h[1:]))



def element_size(mesh, part: str) -> float:
    """Mean edge length [m] of ``part``'s tetrahedra: the element size the mesh actually has.

    ``mesh`` is a model's ``field_mesh()`` or a Solution's ``fields`` (points (n, 3), tets
    (m, 4), part_id, part_names). The density's target size is an upper bound; gmsh may mesh
    a part finer.
    """
    tets = np.asarray(mesh.tets)[np.asarray(mesh.part_id) == list(mesh.part_names).index(part)]
    corners = np.asarray(mesh.points)[tets]  # (m, 4, 3)
    edges = [np.linalg.norm(corners[:, i] - corners[:, j], axis=1) for i in range(4) for j in range(i + 1, 4)]
    return float(np.mean(edges))
