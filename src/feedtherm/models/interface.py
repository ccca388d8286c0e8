"""The one interface every model offers to the shared time integrator.

A model discretises a feed system into a state vector ``T`` and offers, for each grid
position ``k`` of the moving group (``positions[k]`` is its offset from the middle of the
stroke), the operators of

.. math:: C \\dot T + (G(k) + A(k))\\,T = q(k) + s(k)

with ``C`` the capacity, ``G`` conduction and contacts, ``A`` the coupling to the ambient
air (or a surface's own sink), ``s`` the heat those links bring at the sink temperatures,
and ``q`` the heat of the sources.  Any of ``C``, ``G`` and ``A``
may be a vector (a diagonal), a sparse or a dense matrix: full-state models (fast, FE) use
diagonal capacities and ambient links, a projected (reduced) model uses dense matrices.

What is the same for every model lives here once: where a source's heat enters
(:func:`heat_inputs`), the time share of the grid positions under reciprocation
(:func:`cycle_weights`), and the heat stored and lost for the energy account.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..boundary import BoundaryConditions
from ..physics.thermal_expansion import displacement_weights_axial
from ..system.schema import FeedSystem

Operator = np.ndarray | sp.spmatrix  # a 1-D array is a diagonal


@dataclass(frozen=True)
class AmbientCoupling:
    """How the state exchanges heat with the air (or a surface's sink) at one position.

    With node links ``g`` [W/K] to sinks at ``T_s`` [K], the heat lost is
    ``Σ g (T - T_s) = load @ T - source_total``; the step equations get ``matrix`` on the left
    and ``source`` on the right.  A projected model keeps the same quantities projected.
    """

    matrix: Operator  # [W/K] (1-D: diagonal)
    load: np.ndarray  # [W/K] per state entry: the heat lost per kelvin of each entry
    source: np.ndarray  # [W] per state entry: the links' heat at the sink temperatures
    source_total: float  # [W] Σ g T_s over every link

    def heat_lost(self, state: np.ndarray) -> float:
        """Heat to the sinks [W] from ``state``."""
        return float(self.load @ state) - self.source_total

    @classmethod
    def diagonal(cls, links: np.ndarray, sink_heat: np.ndarray) -> "AmbientCoupling":
        """Node-to-sink conductances ``g`` [W/K] and ``g·T_s`` [W] of a full-state model."""
        return cls(links, links, sink_heat, float(sink_heat.sum()))

    @classmethod
    def averaged(cls, weights: np.ndarray, couplings: list["AmbientCoupling"]) -> "AmbientCoupling":
        return cls(weighted_sum(weights, [c.matrix for c in couplings]),
                   weighted_sum(weights, [c.load for c in couplings]),
                   weighted_sum(weights, [c.source for c in couplings]),
                   float(sum(w * c.source_total for w, c in zip(weights, couplings))))


@dataclass(frozen=True)
class HeatInput:
    """A share of a source's heat into one part [W], and where it enters.

    ``over_contact_with`` names the other part that receives the same source and is joined to
    this one: the heat arises at their contact (friction) and enters over it; None means
    the heat is the part's own and enters by volume.
    """

    source: str
    part: str
    power: float
    over_contact_with: str | None


def heat_inputs(system: FeedSystem, bc: BoundaryConditions) -> list[HeatInput]:
    """Every (source, part) share of heat at ``bc``, with where it enters (see :class:`HeatInput`)."""
    joined = {frozenset(j.between) for j in system.joints}
    out = []
    for name, heat in bc.heats.items():
        for part, share in heat.into.items():
            partner = next((p for p in heat.into if p != part and frozenset((p, part)) in joined), None)
            out.append(HeatInput(name, part, heat.power * share, partner))
    return out


def cycle_weights(n_positions: int) -> np.ndarray:
    """Time share of each grid position under steady reciprocation (the ends count half)."""
    w = np.ones(n_positions)
    if n_positions > 1:
        w[0] = w[-1] = 0.5
    return w / w.sum()


def weighted_sum(weights, operators: list[Operator]) -> Operator:
    """Σ w_k O_k for operators of one kind (all vectors, all sparse or all dense)."""
    total = None
    for w, op in zip(weights, operators):
        term = w * op
        total = term if total is None else total + term
    return total.tocsr() if sp.issparse(total) else total


def elongation_row(edges: np.ndarray, fixed_at: float, read_at: float) -> np.ndarray:
    """Weights [m] of the screw's section means in D = α Σ w_j (T̄_j − T_ref)."""
    return displacement_weights_axial(edges, fixed_at, [read_at])[0]


class ThermalModel(ABC):
    """A discretisation of a feed system that the shared integrator can run.

    Attributes every model sets
    ---------------------------
    n_nodes : int
        Length of the state vector.
    capacity : Operator
        Heat capacity [J/K] (a vector: lumped per node).
    positions : ndarray
        Offsets [m] of the moving group at the grid positions k = 0…K.
    dx : float
        Grid step of the positions [m].
    probe_names : list[str]
        The sensors (without the ambient one), then ``"D"``.
    screw_edges, screw_centres : ndarray
        Axial sections of the screw [m] for its temperature profile.
    """

    system: FeedSystem
    n_nodes: int
    capacity: Operator
    positions: np.ndarray
    dx: float
    probe_names: list[str]
    screw_edges: np.ndarray
    screw_centres: np.ndarray

    # ------------------------------------------------------------------ operators
    @abstractmethod
    def conductance(self, k: int) -> Operator:
        """Conduction in the parts and across every joint, moving group at position k [W/K]."""

    @abstractmethod
    def surface_exposure(self, name: str, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Nodes of surface ``name`` and their exposed areas [m²] at position k.

        What a joined part covers is not exposed; a declared ``area`` of the surface is
        spread over the exposed nodes in proportion.
        """

    @abstractmethod
    def heat_distribution(self, heat: HeatInput, k: int) -> np.ndarray:
        """Fractions (summing to 1) of one :class:`HeatInput` over the state, at position k."""

    def ambient_links(self, bc: BoundaryConditions, k: int) -> np.ndarray:
        """Conductance [W/K] of every node to its surface's sink (convection + radiation)."""
        return self._links(bc, k)[0]

    def ambient_coupling(self, bc: BoundaryConditions, k: int) -> AmbientCoupling:
        """The ambient operator of the step equations (diagonal for full-state models)."""
        return AmbientCoupling.diagonal(*self._links(bc, k))

    def _links(self, bc: BoundaryConditions, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Node-to-sink conductances ``g`` [W/K] and their heat at the sink temperatures ``g·T_s`` [W]."""
        g = np.zeros(self.n_nodes)
        sink_heat = np.zeros(self.n_nodes)
        for name, transfer in bc.surfaces.items():
            nodes, areas = self.surface_exposure(name, k)
            links = transfer.total * areas
            np.add.at(g, nodes, links)
            np.add.at(sink_heat, nodes, links * transfer.sink)
        return g, sink_heat

    def heat_vector(self, bc: BoundaryConditions, k: int) -> np.ndarray:
        """Heat [W] into every state entry at position k, placed by :func:`heat_inputs`."""
        q = np.zeros(self.n_nodes)
        for heat in heat_inputs(self.system, bc):
            if heat.power != 0.0:
                q += heat.power * self.heat_distribution(heat, k)
        return q

    # ------------------------------------------------------------------ states
    def uniform_state(self, temperature: float) -> np.ndarray:
        """The state of a body at one temperature [K] throughout."""
        return np.full(self.n_nodes, float(temperature))

    def heat_stored(self, state: np.ndarray, start: np.ndarray) -> float:
        """Heat [J] stored between two states."""
        change = state - start
        if np.ndim(self.capacity) == 1:
            return float(self.capacity @ change)
        return float(np.asarray(self.capacity @ change).sum())

    # ------------------------------------------------------------------ readout
    @abstractmethod
    def probe(self, state: np.ndarray, k: int) -> np.ndarray:
        """Sensor temperatures [K] in ``probe_names`` order, then D [m], at position k."""

    @abstractmethod
    def screw_mean(self, states: np.ndarray) -> np.ndarray:
        """Section-mean screw temperature [K] per axial section, shape ``(..., sections)``."""

    @abstractmethod
    def part_means(self, states: np.ndarray) -> dict[str, np.ndarray]:
        """Mean temperature [K] of every part."""

    @property
    @abstractmethod
    def stats(self) -> dict:
        """Size of the discretisation (JSON-able), for the run's summary."""

    def field_mesh(self):
        """The mesh full states live on (a :class:`~feedtherm.models.fields.FieldMesh`), or None."""
        return None
