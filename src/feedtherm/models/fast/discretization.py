"""The fast model seen through the interface the shared integrator uses.

Any model offers: ``n_nodes``, ``capacity``, ``positions``, ``dx``, ``conductance(k)``,
``ambient_links(bc, k, for_solver)``, ``heat_vector(bc, k)``, ``probe_names``,
``probe(T, k)``, ``screw_edges``, ``screw_centres``, ``screw_mean(states)``,
``part_means(states)`` and ``stats``.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...system.schema import FeedSystem
from ..options import ModelOptions
from .assemble import Network, SolverTamper
from .layout import build_layout


class FastDiscretization:
    def __init__(self, system: FeedSystem, options: ModelOptions, tamper: SolverTamper | None = None):
        self.system = system
        self.layout = build_layout(system, axial_cells=options.axial_cells, radial_rings=options.radial_rings,
                                   min_positions=options.steps_per_stroke)
        self.network = Network(self.layout, tamper)
        self.n_nodes = self.layout.n_nodes
        self.capacity = self.layout.capacity
        self.positions = self.layout.positions
        self.dx = self.layout.dx
        self._sliding: dict[int, sp.csr_matrix] = {}
        self._probes()

    # -------------------------------------------------------------- operators
    def conductance(self, k: int) -> sp.csr_matrix:
        if k not in self._sliding:
            self._sliding[k] = (self.network.fixed + self.network.sliding(k)).tocsr()
        return self._sliding[k]

    def ambient_links(self, bc, k: int, for_solver: bool = True) -> np.ndarray:
        return self.network.ambient_links(bc, k, for_solver=for_solver)

    def heat_vector(self, bc, k: int) -> np.ndarray:
        return self.network.heat_vector(bc, k)

    # -------------------------------------------------------------- probes
    def _probes(self) -> None:
        layout, system = self.layout, self.system
        self.sensor_nodes: dict[str, int] = {}
        for name, sensor in system.sensors.items():
            if name == "T6":
                continue
            if sensor.part in layout.lumped:
                self.sensor_nodes[name] = layout.lumped[sensor.part]
            else:
                body = layout.bodies[sensor.part]
                radius = float(np.hypot(sensor.position[1], sensor.position[2]))
                ring = int(np.clip(np.searchsorted(body.ring_radii, radius) - 1, 0, body.n_rings - 1))
                self.sensor_nodes[name] = int(body.nodes[body.cell_at(sensor.position[0]), ring])
        self.probe_names = [*self.sensor_nodes, "D"]
        self._node_index = np.array(list(self.sensor_nodes.values()), dtype=int)
        screw = layout.screw
        self.screw_edges = screw.edges
        self.screw_centres = screw.centres
        self._ring_share = screw.ring_areas() / screw.ring_areas().sum()
        part = system.parts[system.kinematics.screw]
        self._alpha = system.materials[part.material].expansion
        e = system.elongation
        lo, hi = min(e.fixed_at, e.read_at), max(e.fixed_at, e.read_at)
        sign = 1.0 if e.read_at >= e.fixed_at else -1.0
        self._d_weights = sign * screw.overlap(lo, hi)  # D = alpha sum_i overlap_i (T_i - T_ref)
        self._t_ref = system.temperatures.reference

    def screw_mean(self, states: np.ndarray) -> np.ndarray:
        return states[..., self.layout.screw.nodes] @ self._ring_share

    def elongation(self, states: np.ndarray) -> np.ndarray:
        return self._alpha * ((self.screw_mean(states) - self._t_ref) @ self._d_weights)

    def probe(self, T: np.ndarray, k: int = 0) -> np.ndarray:
        return np.append(T[self._node_index], self.elongation(T))

    def part_means(self, states: np.ndarray) -> dict[str, np.ndarray]:
        out = {}
        for part in self.system.parts:
            nodes = self.layout.part_nodes(part)
            c = self.capacity[nodes]
            out[part] = states[..., nodes] @ (c / c.sum())
        return out

    @property
    def stats(self) -> dict:
        screw = self.layout.screw
        return {"unknowns": self.n_nodes, "screw_cells": len(screw.centres), "screw_rings": screw.n_rings}
