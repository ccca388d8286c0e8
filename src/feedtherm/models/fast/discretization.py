"""The fast model (a thermal network) as a :class:`~feedtherm.models.interface.ThermalModel`."""

from __future__ import annotations

from dataclasses import replace
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from ...constants import ELONGATION_PROBE
from ...system.schema import FeedSystem
from ..interface import BoundaryBasis, HeatInput, ThermalModel, cycle_weights, source_shares
from ..options import ModelOptions
from .assemble import Network
from .bars import displacement_rows
from .layout import build_layout


class FastDiscretization(ThermalModel):
    def __init__(self, system: FeedSystem, options: ModelOptions):
        self.system = system
        self.layout = build_layout(system, axial_cells=options.axial_cells, radial_rings=options.radial_rings,
                                   min_positions=options.steps_per_stroke, cell_size=options.cell_size)
        self.network = Network(self.layout)
        self.n_nodes = self.layout.n_nodes
        self.capacity = self.layout.capacity
        self.positions = self.layout.positions
        self.dx = self.layout.dx
        self._sliding: dict[int, sp.csr_matrix] = {}
        # where the sources' heat goes: with the geometry, what the boundary bases depend on
        self._source_shares = tuple((h.source, h.part, h.power, h.over_contact_with) for h in source_shares(system))
        self._probes()

    # -------------------------------------------------------------- operators
    def conductance(self, k: int) -> sp.csr_matrix:
        if k not in self._sliding:
            self._sliding[k] = (self.network.fixed + self.network.sliding(k)).tocsr()
        return self._sliding[k]

    def averaged_conductance(self) -> sp.csr_matrix:
        """The cycle average of :meth:`conductance`: the fixed links and the sliding contacts' links
        of every position weighted by its time share, assembled as one matrix."""
        weights = cycle_weights(len(self.positions))
        return (self.network.fixed + self.network.averaged_sliding(dict(enumerate(weights)))).tocsr()

    def surface_exposure(self, name: str, k: int) -> tuple[np.ndarray, np.ndarray]:
        return self.network.surface_exposure(name, k)

    def surface_film_resistance(self, name: str) -> float:
        return self.network.film_resistance(name)

    def heat_distribution(self, heat: HeatInput, k: int) -> np.ndarray:
        return self.network.heat_distribution(heat.part, heat.over_contact_with, k)

    def boundary_basis(self, k: int | None) -> BoundaryBasis:
        """As :meth:`ThermalModel.boundary_basis`, shared by the models of one geometry.

        Calibration and sweeps build a model per run for values that move no face; the bases'
        exposures and heat distributions depend on the geometry (the network's digest) and on
        where the sources' heat goes (their shares, which the digest leaves out), so they are
        kept under both.  Their film resistances go with the conductivities: a model whose
        differ takes the kept basis with its own.
        """
        own = self.__dict__.setdefault("_own_bases", {})
        if k not in own:
            bases = self.network.geometry["bases"]
            key = (k, self._source_shares)
            if key not in bases:
                bases[key] = super().boundary_basis(k)
            kept, film = bases[key], self._film
            same = film is None if kept.film is None else film is not None and np.array_equal(kept.film, film)
            own[k] = kept if same else replace(kept, film=film)
        return own[k]

    @cached_property
    def _film(self) -> np.ndarray | None:
        """Each surface's film resistance (:meth:`surface_film_resistance`), None where all are 0."""
        film = np.array([self.surface_film_resistance(name) for name in self.system.surfaces], dtype=float)
        return film if film.any() else None

    # -------------------------------------------------------------- probes
    def _probes(self) -> None:
        layout, system = self.layout, self.system
        rows = []  # each sensor reads a weighted mean of nodes
        names = []
        for name, sensor in system.sensors.items():
            if name == system.room.ambient_sensor:  # reported from the boundary conditions
                continue
            if sensor.part in layout.cells:  # between the centres of the cells around it
                nodes, weights = layout.cells[sensor.part].interpolation(sensor.position)
            else:
                body = layout.bodies[sensor.part]
                radius = float(np.hypot(sensor.position[1], sensor.position[2]))
                ring = int(np.clip(np.searchsorted(body.ring_radii, radius) - 1, 0, body.n_rings - 1))
                nodes, weights = np.array([body.nodes[body.cell_at(sensor.position[0]), ring]]), np.ones(1)
            names.append(name)
            row = np.zeros(layout.n_nodes)
            np.add.at(row, nodes, weights)
            rows.append(row)
        self.probe_names = [*names, ELONGATION_PROBE]
        screw = layout.screw
        if screw is None:  # no feed drive: no screw field
            self.screw_edges, self.screw_centres = np.zeros(0), np.zeros(0)
            self._screw_nodes, self._ring_share = np.zeros((0, 1), dtype=np.intp), np.zeros(1)
        else:
            self.screw_edges = screw.edges
            self.screw_centres = screw.centres
            self._screw_nodes = screw.nodes
            self._ring_share = screw.ring_areas() / screw.ring_areas().sum()
        self._displacement = displacement_rows(layout)
        # one dense matrix reads every sensor and D (a probe is taken at every time step);
        # D is the displacements' first row, so the two readings cannot differ
        d_rows, d_offset = self._displacement
        self._probe = np.vstack([*rows, d_rows[0]])
        self._probe_offset = np.zeros(len(self.probe_names))
        self._probe_offset[-1] = d_offset[0]
        self._part_names = list(system.parts)
        means = np.zeros((len(self._part_names), layout.n_nodes))
        for i, part in enumerate(self._part_names):
            nodes = layout.part_nodes(part)
            means[i, nodes] = self.capacity[nodes] / self.capacity[nodes].sum()
        self._means = means

    def screw_mean(self, states: np.ndarray) -> np.ndarray:
        return states[..., self._screw_nodes] @ self._ring_share

    def probe(self, T: np.ndarray, k: int = 0) -> np.ndarray:
        return self._probe @ T + self._probe_offset

    def probe_rows(self, k: int = 0):
        return self._probe, self._probe_offset

    def displacement_rows(self) -> tuple[np.ndarray, np.ndarray]:
        """D, then the screw's displacement at its cell centres: axial bars (:mod:`.bars`)."""
        return self._displacement

    def part_means(self, states: np.ndarray) -> dict[str, np.ndarray]:
        """Capacity-weighted mean temperature of every part."""
        values = np.asarray(states) @ self._means.T
        return {part: values[..., i] for i, part in enumerate(self._part_names)}

    def part_capacities(self) -> dict[str, float]:
        """ρcV [J/K] of every part: its nodes' capacities summed."""
        return {part: float(self.layout.part_capacity(part).sum()) for part in self._part_names}

    @property
    def stats(self) -> dict:
        screw = self.layout.screw
        return {"unknowns": self.n_nodes, "screw_cells": len(self.screw_centres),
                "screw_rings": 0 if screw is None else screw.n_rings,
                "part_cells": sum(c.nodes.size for c in self.layout.cells.values()),
                "cell_size_mm": round(self.layout.cell_size * 1e3, 3)}
