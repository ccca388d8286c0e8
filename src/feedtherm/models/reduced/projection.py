r"""A full model projected onto a basis: the dense operators of the basis's size, at every position.

With a capacity-orthonormal basis :math:`V` (n × r) the state is :math:`T \approx V z` and the
Galerkin projection of :math:`C\dot T + (G_k + A_k)T = q_k + s_k` is

.. math:: \dot z + (V^T G_k V + V^T A_k V)\,z = V^T q_k + V^T s_k .

What depends on the moving group's position is projected once per position: the conduction
and contacts :math:`V^T G_k V`, each surface's exposure :math:`V^T \mathrm{diag}(e_{ik}) V`
and each source's entry :math:`V^T d_{jk}`; only what changes from position 0 is multiplied
out again, so a position costs the few nodes under the nut.  Only the surfaces the moving
group covers and uncovers change with the position (two of 21 on the paper's bench): their
change from position 0 is kept per position, the others' exposure once, so that a coupled run
weighs 21 matrices by their coefficients once per evaluation, not once per position.  The
readouts (sensors, D, the screw's sections and displacement profile, the parts' means) are
the full model's rows times :math:`V`, and the displacement field of each basis vector (the
thermoelastic solution of the full model, :math:`K^{-1} F V`) is kept in single precision, for
the fields a run writes.

A :class:`Projection` is arrays and names only: everything
:class:`~feedtherm.models.reduced.model.ProjectedModel` runs and reads with, so that it can be
kept on disk (:mod:`.store`) and a run of a cached model never builds the full one.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ..fields import FieldMesh
from ..interface import BoundaryBasis, ThermalModel
from .basis import Basis

__all__ = ["Projection", "project"]


@dataclass(frozen=True, eq=False)
class Projection:
    """A full model's operators and readouts projected onto ``basis`` (module notes); K positions,
    r basis vectors, s surfaces, c of them moving, p probes."""

    basis: Basis
    full_capacity: np.ndarray  # (n,) [J/K]: the full model's, for the uniform state
    stored: np.ndarray  # (r,) Vᵀ C [J/K]: heat stored per unit of each reduced coordinate
    conductance: np.ndarray  # (K, r, r) Vᵀ G_k V [W/K]
    surfaces: tuple[str, ...]
    sources: tuple[str, ...]
    exposure: np.ndarray  # (s, r, r) Vᵀ diag(e_i0) V [m²]: every surface at position 0
    moving_surfaces: np.ndarray  # (c,) indices of the surfaces whose exposure changes with the position
    exposure_change: np.ndarray  # (K, c, r, r) their Vᵀ diag(e_ik − e_i0) V [m²]
    exposure_rows: np.ndarray  # (K, s, r) e_ik V [m²]
    exposure_areas: np.ndarray  # (K, s) [m²]
    entries: np.ndarray  # (K, sources, r) d_jk V
    probe_rows: np.ndarray  # (K, p, r): probe(z, k) = probe_rows[k] @ z + probe_offsets[k]
    probe_offsets: np.ndarray  # (K, p)
    screw: np.ndarray  # (r, sections): screw_mean(z) = z @ screw
    displacement_rows: np.ndarray  # (1 + sections, r): displacements(z) = rows @ z + offsets (D, the screw's profile)
    displacement_offsets: np.ndarray  # (1 + sections,)
    displacement_basis: np.ndarray | None  # (3n, r) float32: the field of z is basis @ z + displacement_origin
    displacement_origin: np.ndarray | None  # (3n,) [m]: the field of z = 0
    parts: dict[str, np.ndarray]  # part → (r,): its mean is z @ parts[part]
    part_capacity: dict[str, float] | None  # part → ρcV [J/K] of the full model (None: it does not say)
    averaged: BoundaryBasis  # the full model's cycle-averaged one: coupled readings and links
    positions: np.ndarray
    dx: float
    probe_names: tuple[str, ...]
    screw_edges: np.ndarray
    screw_centres: np.ndarray
    field_mesh: FieldMesh | None
    full_stats: dict
    # the full model's affine parameters (ThermalModel.affine_parameters): Q conductance ones, Qm of
    # them moving, E expansions; the arrays above are at ``*_values``
    conductance_parameters: tuple[str, ...] = ()
    conductance_values: np.ndarray = field(default_factory=lambda: np.zeros(0))  # (Q,) θ⁰ [SI]
    conductance_terms: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 0)))  # (Q, r, r) Vᵀ ∂G_0/∂θ_q V
    conductance_moving: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.intp))  # (Qm,) indices of the moving ones
    conductance_term_change: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 0, 0)))  # (K, Qm, r, r) Vᵀ (∂G_k/∂θ − ∂G_0/∂θ) V
    expansion_parameters: tuple[str, ...] = ()
    expansion_values: np.ndarray = field(default_factory=lambda: np.zeros(0))  # (E,) [1/K]
    displacement_terms: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 0)))  # (E, 1 + sections, r) ∂rows/∂α V
    displacement_offset_terms: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))  # (E, 1 + sections)
    #: [SI] the parameters' ranges the basis was trained over (name → (low, high)); a description
    #: outside them is another model (models/reduced/store.py)
    domain: dict | None = None
    #: what the basis was trained over: "declared", the ranges the description declares (every point
    #: of a batch's runs inside them), or "description", its own numbers only (a single run's)
    trained_over: str = "declared"

    @property
    def V(self) -> np.ndarray:
        return self.basis.vectors


def _changed(current: sp.spmatrix, reference: sp.spmatrix) -> sp.csr_matrix:
    difference = (current - reference).tocsr()
    difference.eliminate_zeros()
    return difference


def _project(V: np.ndarray, matrix: sp.spmatrix) -> np.ndarray:
    """``Vᵀ M V`` from the rows of ``M`` that hold anything."""
    rows = np.unique(matrix.nonzero()[0])
    if rows.size == 0:
        return np.zeros((V.shape[1], V.shape[1]))
    return V[rows].T @ (matrix[rows] @ V)


def _project_exposure(V: np.ndarray, exposure: sp.csr_matrix, surfaces) -> np.ndarray:
    """``Vᵀ diag(e_i) V`` for the surface rows ``e_i`` of ``exposure`` listed in ``surfaces``: (len, r, r)."""
    out = np.zeros((len(surfaces), V.shape[1], V.shape[1]))
    for j, i in enumerate(surfaces):
        row = exposure.getrow(i)
        if row.indices.size:
            Vn = V[row.indices]
            out[j] = Vn.T @ (row.data[:, None] * Vn)
    return out


def _probes(full: ThermalModel, V: np.ndarray, n_positions: int) -> tuple[np.ndarray, np.ndarray]:
    """Each position's probe rows times V, and offsets: from the full model's rows (once per rows
    object: a model's rows are often the same at every position), or probing V's columns."""
    rows_out, offsets = [], []
    projected: dict[int, tuple] = {}  # id(full rows) → (the rows, rows @ V)
    for k in range(n_positions):
        given = full.probe_rows(k)
        if given is not None:
            rows, offset = given
            known = projected.get(id(rows))
            if known is None or known[0] is not rows:
                known = projected[id(rows)] = (rows, np.asarray(rows @ V))
            rows_out.append(known[1])
            offsets.append(np.asarray(offset, dtype=float))
        else:
            offset = np.asarray(full.probe(np.zeros(full.n_nodes), k))
            rows_out.append(np.column_stack([np.asarray(full.probe(V[:, j], k)) - offset for j in range(V.shape[1])]))
            offsets.append(offset)
    return np.array(rows_out), np.array(offsets)


def _displacement_fields(full: ThermalModel, V: np.ndarray) -> tuple[np.ndarray | None, np.ndarray | None]:
    """The full model's displacement field of each basis vector, and of the zero state (None without fields).

    The field is affine in the state, ``u(T) = K⁻¹F (T − T_ref)``: the field of ``V z`` is
    ``Σ z_j (u(V_j) − u(0)) + u(0)``.
    """
    origin = full.displacement_field(np.zeros(full.n_nodes))
    if origin is None:
        return None, None
    origin = np.asarray(origin, dtype=float).ravel()
    columns = np.asarray(full.displacement_field(V.T))  # (r, n, 3): one solve with r right-hand sides
    return (columns.reshape(V.shape[1], -1).T - origin[:, None]).astype(np.float32), origin


def project(full: ThermalModel, basis: Basis) -> Projection:
    """``full`` projected onto ``basis`` at every position (module notes)."""
    V = np.ascontiguousarray(basis.vectors)  # sparse @ V copies a Fortran-ordered V on every product
    if V is not basis.vectors:
        basis = Basis(V, basis.singular_values, basis.tolerance, basis.snapshots, basis.seconds, basis.cached)
    K = len(full.positions)
    C = np.asarray(full.capacity, dtype=float)
    G0 = full.conductance(0)
    G0_projected = _project(V, G0)
    conductance = np.array([G0_projected + _project(V, _changed(full.conductance(k), G0)) for k in range(K)])
    reference = full.boundary_basis(0)
    bases = [full.boundary_basis(k) for k in range(K)]
    changes = [_changed(b.exposure, reference.exposure) for b in bases]
    moving = np.unique(np.concatenate([np.unique(c.nonzero()[0]) for c in changes])).astype(np.intp)
    rows, offsets = _probes(full, V, K)
    d_rows, d_offsets = full.displacement_rows()
    field_basis, field_origin = _displacement_fields(full, V)
    terms = _affine_terms(full, V)
    return Projection(
        basis=basis,
        full_capacity=C,
        stored=V.T @ C,
        conductance=conductance,
        surfaces=tuple(reference.surfaces),
        sources=tuple(reference.sources),
        exposure=_project_exposure(V, reference.exposure, range(reference.exposure.shape[0])),
        moving_surfaces=moving,
        exposure_change=np.array([_project_exposure(V, c, moving) for c in changes]),
        exposure_rows=np.array([np.asarray(b.exposure @ V) for b in bases]),
        exposure_areas=np.array([np.asarray(b.exposure.sum(axis=1)).ravel() for b in bases]),
        entries=np.array([np.asarray(b.distribution @ V) for b in bases]),
        probe_rows=rows,
        probe_offsets=offsets,
        screw=np.asarray(full.screw_mean(V.T)),
        displacement_rows=np.asarray(d_rows @ V),
        displacement_offsets=np.asarray(d_offsets, dtype=float),
        displacement_basis=field_basis,
        displacement_origin=field_origin,
        parts={name: np.asarray(v) for name, v in full.part_means(V.T).items()},
        part_capacity=full.part_capacities(),
        averaged=full.boundary_basis(None),
        positions=np.asarray(full.positions, dtype=float),
        dx=float(full.dx),
        probe_names=tuple(full.probe_names),
        screw_edges=np.asarray(full.screw_edges, dtype=float),
        screw_centres=np.asarray(full.screw_centres, dtype=float),
        field_mesh=full.field_mesh(),
        full_stats=dict(full.stats),
        **terms,
    )


def _affine_terms(full: ThermalModel, V: np.ndarray) -> dict:
    """The projected terms of ``full``'s affine parameters (:meth:`ThermalModel.affine_parameters`):
    the conductance terms at position 0 and the moving ones' change per position, the
    displacement rows' and offsets' terms per unit expansion."""
    parameters = full.affine_parameters()
    conduction = [p for p in parameters if p.kind == "conductance"]
    expansion = [p for p in parameters if p.kind == "expansion"]
    r, K = V.shape[1], len(full.positions)
    first = {p.name: full.conductance_term(p.name, 0) for p in conduction}
    moving = np.array([i for i, p in enumerate(conduction) if p.moves], dtype=np.intp)
    change = np.zeros((K, moving.size, r, r))
    for k in range(1, K):
        for j, i in enumerate(moving):
            name = conduction[i].name
            change[k, j] = _project(V, _changed(full.conductance_term(name, k), first[name]))
    displacement = [full.displacement_term(p.name) for p in expansion]
    n_rows = np.shape(full.displacement_rows()[0])[0]
    return {
        "conductance_parameters": tuple(p.name for p in conduction),
        "conductance_values": np.array([p.value for p in conduction], dtype=float),
        "conductance_terms": np.array([_project(V, first[p.name]) for p in conduction]).reshape(len(conduction), r, r),
        "conductance_moving": moving,
        "conductance_term_change": change,
        "expansion_parameters": tuple(p.name for p in expansion),
        "expansion_values": np.array([p.value for p in expansion], dtype=float),
        "displacement_terms": np.array([np.asarray(rows @ V) for rows, _ in displacement]).reshape(len(expansion), n_rows, r),
        "displacement_offset_terms": np.array([np.asarray(offset, dtype=float) for _, offset in displacement]
                                              ).reshape(len(expansion), n_rows),
    }
