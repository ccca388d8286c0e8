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
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from ..boundary import BoundaryConditions
from ..system.schema import FeedSystem

Operator = np.ndarray | sp.spmatrix  # a 1-D array is a diagonal


@dataclass(frozen=True)
class PositionWindow:
    """The grid positions ``first…last`` that the moving group sweeps in one step of the windowed
    motion, each weighted by the time the group spends at it (the trapezoid rule over the sweep: the
    two ends count half, as :func:`cycle_weights` counts the stroke's).

    A model's operators over a window are the weighted sums of its positions' operators, so that
    a step steps with the contacts and heats of the stretch it sweeps, not of its end position
    (:mod:`~feedtherm.models.windows`).  Hashable: the integrator's and the models' caches key
    on it as on a position.
    """

    first: int
    last: int

    @property
    def positions(self) -> range:
        return range(self.first, self.last + 1)

    @property
    def weights(self) -> np.ndarray:
        return cycle_weights(self.last - self.first + 1)


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
    #: What ``matrix`` is made of, where that is cheaper to fingerprint than the matrix (a projected
    #: model's surface coefficients); None: the integrator fingerprints the matrix itself
    key: bytes | None = None

    def heat_lost(self, state: np.ndarray) -> float:
        """Heat to the sinks [W] from ``state``."""
        return float(self.load @ state) - self.source_total

    @classmethod
    def diagonal(cls, links: np.ndarray, sink_heat: np.ndarray, key: bytes | None = None) -> "AmbientCoupling":
        """Node-to-sink conductances ``g`` [W/K] and ``g·T_s`` [W] of a full-state model."""
        return cls(links, links, sink_heat, float(sink_heat.sum()), key)


@dataclass(frozen=True)
class AffineParameter:
    """A number of the description that a model's operators are linear in.

    ``kind`` says which operator: ``"conductance"``, ``G_k = Σ_q θ_q ∂G_k/∂θ_q`` over the model's
    conductance parameters (:meth:`ThermalModel.conductance_term`); ``"expansion"``, the
    displacement rows and offsets are linear in it (:meth:`ThermalModel.displacement_term`).
    A parametric reduced model projects each term once and weighs it by another description's
    value (:func:`affine_value`), without building the full model again.
    """

    name: str  # :func:`affine_value`'s name: "materials.<m>.conductivity", "joints[<i>].conductance", ...
    kind: str  # "conductance" or "expansion"
    value: float  # at the model's own description [SI]
    moves: bool = False  # its term changes with the moving group's position


def affine_value(system: FeedSystem, name: str) -> float:
    """The value in ``system`` of the affine parameter ``name`` [SI].

    ``materials.<m>.conductivity`` [W/(m·K)] and ``materials.<m>.expansion`` [1/K] as declared;
    ``joints[<i>].conductance`` [W/(m²·K)] is the joint's ``1 / tcr``, what its interface matrix
    is linear in; ``surfaces.<s>.coefficient`` [W/(m²·K)] is a fixed-coefficient surface's
    coefficient times its ``chtc_factor`` (it enters the boundary conditions, not an operator:
    a reduced model's basis is trained over it).
    """
    head, _, field = name.rpartition(".")
    if head.startswith("materials."):
        return float(getattr(system.materials[head.removeprefix("materials.")], field))
    if head.startswith("joints[") and field == "conductance":
        return 1.0 / float(system.joints[int(head[len("joints["):-1])].tcr)
    if head.startswith("surfaces.") and field == "coefficient":
        surface = system.surfaces[head.removeprefix("surfaces.")]
        return float(surface.convection.coefficient) * float(surface.chtc_factor)
    raise KeyError(name)


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
    return [HeatInput(h.source, h.part, bc.heats[h.source].power * h.power, h.over_contact_with)
            for h in source_shares(system)]


def source_shares(system: FeedSystem) -> list[HeatInput]:
    """As :func:`heat_inputs`, with ``power`` the share of the source's heat (a source's shares add to 1)."""
    joined = {frozenset(j.between) for j in system.joints}
    out = []
    for name, source in system.sources.items():
        for part, share in source.into.items():
            if source.through is not None:  # made in `through`, entering each part over its contact with it
                out.append(HeatInput(name, part, share, source.through))
                continue
            partner = next((p for p in source.into if p != part and frozenset((p, part)) in joined), None)
            out.append(HeatInput(name, part, share, partner))
    return out


@dataclass(frozen=True)
class BoundaryBasis:
    """Geometry of the boundary conditions at one position (see :meth:`ThermalModel.boundary_basis`).

    ``exposure[i, n]``: exposed area [m²] of surface ``surfaces[i]`` at node n;
    ``distribution[j, n]``: fraction of source ``sources[j]``'s heat entering node n.
    """

    surfaces: list[str]
    sources: list[str]
    exposure: sp.csr_matrix
    distribution: sp.csr_matrix
    #: each surface's specific resistance [m²·K/W] from its nodes to its faces (None: nodes on the faces)
    film: np.ndarray | None = None

    def coefficients(self, bc: BoundaryConditions) -> tuple[np.ndarray, np.ndarray]:
        """Each surface's coefficient [W/(m²·K)] from its nodes to its sink, and the sink [K]:
        :func:`surface_coefficients` in series with :attr:`film` (:func:`film_coefficient`)."""
        h, sinks = surface_coefficients(bc, self.surfaces)
        return (h if self.film is None else film_coefficient(h, self.film)), sinks

    def links(self, h: np.ndarray, sinks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Node-to-sink conductances ``g`` [W/K] and ``g·T_s`` [W] of the surfaces' coefficients and sinks."""
        return self.exposure_by_node @ h, self.exposure_by_node @ (h * sinks)

    @cached_property
    def exposure_by_node(self) -> sp.csr_matrix:
        """``exposure.T`` as CSR, kept: links are ``exposure_by_node @ h`` at every evaluation of a coupled run."""
        return self.exposure.T.tocsr()

    @cached_property
    def distribution_by_node(self) -> sp.csr_matrix:
        """``distribution.T`` as CSR, kept (see :attr:`exposure_by_node`)."""
        return self.distribution.T.tocsr()


def surface_coefficients(bc: BoundaryConditions, surfaces: list[str]) -> tuple[np.ndarray, np.ndarray]:
    """Each surface's total coefficient [W/(m²·K)] and sink temperature [K] (a surface left out exchanges nothing)."""
    transfer = [bc.surfaces.get(name) for name in surfaces]
    return (np.array([0.0 if t is None else t.total for t in transfer]),
            np.array([0.0 if t is None else t.sink for t in transfer]))


def film_coefficient(h, resistance):
    """A surface coefficient in series with conduction from a node inside the solid to the face.

    .. math:: h_\\mathrm{n} = \\frac{h}{1 + h\\,r}, \\qquad r = d/k

    Parameters
    ----------
    h : float or array_like
        The film coefficient at the face (convection + radiation) [W/(m²·K)], >= 0.
    resistance : float or array_like
        Specific conduction resistance ``r`` from the node to the face [m²·K/W], >= 0: the
        node's distance ``d`` [m] from the face over the conductivity ``k`` [W/(m·K)].

    Returns
    -------
    numpy.ndarray
        The coefficient [W/(m²·K)] from the node to the sink, per unit face area.

    Notes
    -----
    Two resistances per unit area in series, ``1/h`` and ``d/k`` (Incropera, *Fundamentals of
    Heat and Mass Transfer*, 6th ed., §3.1.3, eq. 3.19).  Exact for one node behind a uniform
    face; ``h r`` is the cell's Biot number, so the correction grows with ``h·d/k``.
    """
    h = np.asarray(h, dtype=float)
    return h / (1.0 + h * np.asarray(resistance, dtype=float))


def source_powers(bc: BoundaryConditions, sources: list[str]) -> np.ndarray:
    """Each source's heat [W] (a source left out gives nothing)."""
    heats = [bc.heats.get(name) for name in sources]
    return np.array([0.0 if q is None else q.power for q in heats])


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
        Axial sections of the screw [m] for its temperature and displacement profiles.

    Displacements are linear in the temperatures (linear thermoelasticity from the reference
    temperature): :meth:`displacement_rows` reads them, the first row D (``mechanics.elongation``),
    then the screw's axial displacement at ``screw_centres`` relative to the positioning
    reference (``mechanics.positioning``), from which the positioning error along the stroke is
    taken.  D is also the last probe.

    A model whose step matrices are costly to hold (one factorisation per grid position of a
    large mesh) sets ``windowed_motion``: its resolved motion then steps window by window
    (:mod:`~feedtherm.models.windows`), with the operators weighted over each window's positions
    (:class:`PositionWindow`, which :meth:`boundary_basis` and :meth:`window_conductance` take).
    """

    #: Whether the resolved motion steps this model window by window (:mod:`~feedtherm.models.windows`).
    windowed_motion: bool = False
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

    def window_conductance(self, window: PositionWindow) -> Operator:
        """:meth:`conductance` weighted over the positions of ``window``: what a windowed step steps with."""
        return weighted_sum(window.weights, [self.conductance(k) for k in window.positions])

    def averaged_conductance(self) -> Operator:
        """The cycle average of :meth:`conductance` over the positions (:func:`cycle_weights`): what a
        cycle-averaged run steps with.  A model may form it more cheaply than from every position."""
        w = cycle_weights(len(self.positions))
        return weighted_sum(w, [self.conductance(k) for k in range(len(w))])

    @abstractmethod
    def surface_exposure(self, name: str, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Nodes of surface ``name`` and their exposed areas [m²] at position k.

        What a joined part covers is not exposed; a declared ``area`` of the surface is
        spread over the exposed nodes in proportion.
        """

    def surface_film_resistance(self, name: str) -> float:
        """Specific resistance [m²·K/W] of conduction from the nodes of surface ``name`` to its
        faces, in series with its coefficient (:func:`film_coefficient`): 0 for a model with
        nodes on its faces (the FE model); a model whose nodes stand for cell centres says."""
        return 0.0

    @abstractmethod
    def heat_distribution(self, heat: HeatInput, k: int) -> np.ndarray:
        """Fractions (summing to 1) of one :class:`HeatInput` over the state, at position k."""

    def ambient_links(self, bc: BoundaryConditions, k: int | None) -> np.ndarray:
        """Conductance [W/K] of every node to its surface's sink (convection + radiation)."""
        basis = self.boundary_basis(k)  # the links alone: a coupled run compares them at every evaluation
        return basis.exposure_by_node @ basis.coefficients(bc)[0]

    def ambient_coupling(self, bc: BoundaryConditions, k: int | None) -> AmbientCoupling:
        """The ambient operator of the step equations at position k (None: the cycle average)."""
        basis = self.boundary_basis(k)
        h, sinks = basis.coefficients(bc)
        # with the position (the integrator's key holds it), the coefficients make the links: a
        # fingerprint of a few numbers where the links' own is one of every node's
        return AmbientCoupling.diagonal(*basis.links(h, sinks), h.tobytes())

    def _links(self, bc: BoundaryConditions, k: int | None) -> tuple[np.ndarray, np.ndarray]:
        """Node-to-sink conductances ``g`` [W/K] and their heat at the sink temperatures ``g·T_s`` [W]."""
        basis = self.boundary_basis(k)
        return basis.links(*basis.coefficients(bc))

    def heat_vector(self, bc: BoundaryConditions, k: int | None) -> np.ndarray:
        """Heat [W] into every state entry at position k (None: the cycle average), placed by :func:`heat_inputs`."""
        basis = self.boundary_basis(k)
        return basis.distribution_by_node @ source_powers(bc, basis.sources)

    def boundary_basis(self, k: int | None) -> "BoundaryBasis":
        """Where each surface exchanges heat and each source's heat enters, at position k.

        ``k = None`` gives the cycle average, a :class:`PositionWindow` its positions' weighted
        sum.  These depend on the geometry alone, so they are built once per position; boundary
        conditions then weigh them by their coefficients and heats, which keeps re-evaluating
        coefficients (the nonlinear coupling) cheap.
        """
        cache = self.__dict__.setdefault("_boundary_bases", {})
        if k not in cache:
            system = self.system
            if k is None or isinstance(k, PositionWindow):
                w = cycle_weights(len(self.positions)) if k is None else k.weights
                bases = [self.boundary_basis(j) for j in (range(len(w)) if k is None else k.positions)]
                cache[k] = BoundaryBasis(bases[0].surfaces, bases[0].sources,
                                         weighted_sum(w, [b.exposure for b in bases]),
                                         weighted_sum(w, [b.distribution for b in bases]), bases[0].film)
            else:
                rows, cols, vals = [], [], []
                for i, name in enumerate(system.surfaces):
                    nodes, areas = self.surface_exposure(name, k)
                    rows.append(np.full(len(nodes), i))
                    cols.append(np.asarray(nodes))
                    vals.append(np.asarray(areas, dtype=float))
                exposure = sp.csr_matrix((np.concatenate(vals) if vals else np.zeros(0),
                                          (np.concatenate(rows) if rows else np.zeros(0, int),
                                           np.concatenate(cols) if cols else np.zeros(0, int))),
                                         shape=(len(system.surfaces), self.n_nodes))
                names = list(system.sources)
                dense = np.zeros((len(names), self.n_nodes))
                for share in source_shares(system):
                    dense[names.index(share.source)] += share.power * self.heat_distribution(share, k)
                film = np.array([self.surface_film_resistance(name) for name in system.surfaces], dtype=float)
                cache[k] = BoundaryBasis(list(system.surfaces), names, exposure, sp.csr_matrix(dense),
                                         film if film.any() else None)
        return cache[k]

    # ------------------------------------------------------------------ states
    def restrict(self, rows: Operator) -> Operator:
        """Rows that read a full state (one per row, over the nodes), as rows that read this model's state.

        A full-state model reads its own nodes; a projected model multiplies by its basis.
        """
        return rows

    def full_state(self, state: np.ndarray) -> np.ndarray:
        """The nodal temperatures [K] of ``state`` (a projected model lifts its coordinates)."""
        return state

    def uniform_state(self, temperature: float) -> np.ndarray:
        """The state of a body at one temperature [K] throughout."""
        return np.full(self.n_nodes, float(temperature))

    def coarse_space(self) -> sp.csr_matrix | None:
        """Columns (one row per state entry) of fields an iterative step solver corrects each step in
        (:mod:`.iterative`), or None for the uniform field alone.

        The step then conserves energy over every group of entries whose indicator the columns
        span: a model whose parts are joined by contacts gives each part's uniform field.
        """
        return None

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

    def probe_rows(self, k: int) -> tuple[Operator, np.ndarray] | None:
        """``(rows, offset)`` with ``probe(T, k) == rows @ T + offset``, or None if the model does not say.

        A projected model multiplies them by its basis once; without them it probes the basis's
        columns one by one.  A model whose readings do not depend on k returns the same ``rows``
        object at every position.
        """
        return None

    @abstractmethod
    def displacement_rows(self) -> tuple[Operator, np.ndarray]:
        """``(rows, offset)``: ``rows @ state + offset`` is D, then the screw's axial displacement at
        ``screw_centres`` relative to the positioning reference [m] (see the class notes)."""

    # ------------------------------------------------------------------ affine parameters
    def affine_parameters(self) -> list[AffineParameter]:
        """The description's numbers this model's operators are linear in (:class:`AffineParameter`);
        none by default: a model whose conductances are not linear in its materials' and joints'
        numbers (the fast model's cells in series) is reduced for its own description only."""
        return []

    def conductance_term(self, name: str, k: int) -> Operator:
        """``∂G_k/∂θ`` of the conductance parameter ``name`` [W/K per unit of θ]."""
        raise NotImplementedError(f"{type(self).__name__} has no affine parameter {name!r}")

    def displacement_term(self, name: str) -> tuple[Operator, np.ndarray]:
        """``∂(rows, offset)/∂θ`` of :meth:`displacement_rows` for the expansion parameter ``name``."""
        raise NotImplementedError(f"{type(self).__name__} has no affine parameter {name!r}")

    def displacements(self, states: np.ndarray) -> np.ndarray:
        """D, then the screw's axial displacement profile [m], of ``states`` (:meth:`displacement_rows`),
        shape ``(..., 1 + sections)``: one state, or several stacked along the first axis."""
        rows, offset = self.displacement_rows()
        states = np.asarray(states)
        if states.ndim == 1:
            return rows @ states + offset
        return np.asarray(rows @ states.reshape(-1, states.shape[-1]).T).T.reshape(*states.shape[:-1], -1) + offset

    def displacement_field(self, state: np.ndarray) -> np.ndarray | None:
        """The displacement [m] of every vertex of :meth:`field_mesh`, shape (n, 3), or None if the
        model has no such field."""
        return None

    @abstractmethod
    def screw_mean(self, states: np.ndarray) -> np.ndarray:
        """Section-mean screw temperature [K] per axial section, shape ``(..., sections)``."""

    @abstractmethod
    def part_means(self, states: np.ndarray) -> dict[str, np.ndarray]:
        """Mean temperature [K] of every part.

        A model that gives :meth:`part_capacities` weighs each part's nodes by their capacity,
        so that ``Σ_p C_p ΔT̄_p`` is :meth:`heat_stored` (the energy ledger of ``run``'s files).
        """

    def part_capacities(self) -> dict[str, float] | None:
        """Heat capacity ρcV [J/K] of every part, or None if the model does not say.

        The capacities of each part's nodes summed (a projected model: its full model's), every
        node in one part: with the capacity-weighted :meth:`part_means`, the heat stored
        between two states is ``Σ_p C_p (T̄_p − T̄_p,start)``, the same as :meth:`heat_stored`
        up to round-off.
        """
        return None

    @property
    @abstractmethod
    def stats(self) -> dict:
        """Size of the discretisation (JSON-able), for the run's summary."""

    def field_mesh(self):
        """The mesh full states live on (a :class:`~feedtherm.models.fields.FieldMesh`), or None."""
        return None
