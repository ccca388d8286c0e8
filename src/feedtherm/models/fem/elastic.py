r"""Linear thermoelasticity on the thermal model's mesh: the displacement of a temperature field.

Small strains, isotropic materials, quasi-static (inertia is nil on thermal time scales).
With vector elements :math:`\mathbf v` on the same tetrahedra and temperatures as the
thermal model (linear, or quadratic where the description's ``mechanics.elements`` asks:
:mod:`.elastic_space`), the displacement :math:`\mathbf u` solves

.. math::

    \int_\Omega \big(2\mu\,\varepsilon(\mathbf u):\varepsilon(\mathbf v)
        + \lambda\,\operatorname{tr}\varepsilon(\mathbf u)\,\operatorname{tr}\varepsilon(\mathbf v)\big)\,dV
    + \sum_{joints} k_p \int_{\Gamma} [\mathbf u]_h\cdot[\mathbf v]_h\,dA
    = \int_\Omega (3\lambda + 2\mu)\,\alpha\,(T - T_{ref})\,\nabla\cdot\mathbf v\,dV

(the thermal strain :math:`\alpha (T - T_{ref})\mathbf I` of each part's material; Timoshenko &
Goodier, Theory of Elasticity, 3rd ed., §150; Zienkiewicz, Taylor & Zhu, The Finite Element
Method, 7th ed., §6.2 for the initial-strain load), so :math:`\mathbf u = K^{-1} F (T - T_{ref})`.

**Joints.** The parts' meshes do not share nodes; a joint ties them with a penalty on the jump
:math:`[\mathbf u]` of its held components (the axes it does not release), integrated with the
thermal model's contact quadrature (:mod:`.coupling`; the moving group at the middle of the
stroke), both sides' fields read at the same points (:class:`Tie`: a uniform expansion strains
no joint, however the two meshes facet a curved face). The tie stiffness per area is :math:`k_p = \beta\,\max(E_a, E_b)/h_a` [N/m³], with
:math:`h_a` the element size of the integrating side and :math:`\beta` the description's
``mechanics.tie_penalty``: the joint then yields :math:`h_a/(\beta E)` per unit traction, a
:math:`1/\beta` part of one element's own compliance.

**The drive.** The thread holds the nut to the screw along the axis at the nut's centre: a
spring :math:`\beta E h` [N/m] between the two parts' displacements at that point of the bore,
along x (with a thread whose joint releases x, the nut's own expansion does not stretch the
screw: a split nut's halves are preloaded against each other by springs).

**Supports.** A support holds the node of its part nearest to its point along its axes
(eliminated from the system).

**The stiffness does not change in time**, so it is factorised once: every reading the
models take (D, the screw's displacement profile) is a row :math:`r^T K^{-1} F` found by one
solve per reading (:meth:`ThermoElastic.reading_rows`), so the time loop reads displacements
as it reads temperatures; full fields (for ParaView) cost one solve each.
"""

from __future__ import annotations

import time

import numpy as np
import scipy.sparse as sp

from ...errors import ModelError
from .. import pardiso
from ..direct import factorize
from .elastic_assembly import gradients, node_pairs, quadratic_matrices, stiffness_matrix, thermal_load_matrix
from .elastic_space import DisplacementSpace

#: Readings whose adjoint solves are made together (:meth:`ThermoElastic.reading_rows`): their dense
#: right-hand sides and solutions are what a block holds beside the factor.
READINGS_PER_SOLVE = 16

__all__ = ["ElasticPart", "PointTie", "Tie", "ThermoElastic", "lame", "stress"]

def lame(youngs_modulus: float, poisson_ratio: float) -> tuple[float, float]:
    """Lamé's :math:`\\lambda = E\\nu/((1+\\nu)(1-2\\nu))` and :math:`\\mu = E/(2(1+\\nu))` [Pa]."""
    E, nu = youngs_modulus, poisson_ratio
    return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))


def stress(points: np.ndarray, tets: np.ndarray, displacement: np.ndarray, temperature_rise: np.ndarray,
           constants: list["ElasticPart"], part_of_tet: np.ndarray) -> np.ndarray:
    r"""Cauchy stress of each tetrahedron [Pa] from a P1 displacement field and the temperatures.

    .. math::

        \sigma = \lambda\,\operatorname{tr}(\varepsilon - \alpha\,\Delta T\,\mathbf I)\,\mathbf I
                 + 2\mu\,(\varepsilon - \alpha\,\Delta T\,\mathbf I)

    with :math:`\varepsilon = \tfrac12(\nabla\mathbf u + \nabla\mathbf u^T)` constant in each
    tetrahedron (linear elements) and :math:`\Delta T` the rise at its centroid, the mean of its
    four nodes' (the one-point rule of the thermal load in :class:`ThermoElastic`), so that the
    stresses are the ones the solve balances. Of a quadratic model's run (``mechanics.elements``)
    the displacements are its mesh nodes', and the stress is that of their linear interpolant: a
    mean over each element, not the quadratic field's varying stress.

    Parameters
    ----------
    points : ndarray, shape (3, N)
        Vertices [m].
    tets : ndarray of int, shape (4, M)
        Tetrahedra (vertex indices).
    displacement : ndarray, shape (N, 3)
        Nodal displacements [m], e.g. :meth:`ThermoElastic.displacement` or a snapshot of a
        run's ``fields.displacements``.
    temperature_rise : ndarray, shape (N,)
        Nodal temperatures less the reference temperature, ``T − T_ref`` [K].
    constants : list of ElasticPart
        Each part's Young's modulus, Poisson's ratio and expansion, indexed by ``part_of_tet``.
    part_of_tet : ndarray of int, shape (M,)

    Returns
    -------
    ndarray, shape (M, 3, 3)
        The symmetric stress tensor of each tetrahedron [Pa], tension positive.
    """
    points = np.asarray(points, dtype=float)
    tets = np.asarray(tets)
    u = np.asarray(displacement, dtype=float)
    corners = points[:, tets].transpose(2, 1, 0)  # (M, 4, 3)
    edges = corners[:, 1:] - corners[:, :1]  # (M, 3, 3): rows x_i − x_0
    du = u[tets[1:].T] - u[tets[0]][:, None, :]  # (M, 3, 3): rows u_i − u_0
    grad = np.linalg.solve(edges, du).transpose(0, 2, 1)  # (M, 3, 3): ∂u_i/∂x_j, from edges @ G^T = du
    strain = 0.5 * (grad + grad.transpose(0, 2, 1))
    part = np.asarray(part_of_tet)
    lam_mu = np.array([lame(c.youngs_modulus, c.poisson_ratio) for c in constants])
    alpha = np.array([c.expansion for c in constants])
    rise = np.asarray(temperature_rise, dtype=float)[tets].mean(axis=0)  # (M,) at the centroids
    elastic = strain - (alpha[part] * rise)[:, None, None] * np.eye(3)
    trace_ = np.trace(elastic, axis1=1, axis2=2)
    return (lam_mu[part, 0] * trace_)[:, None, None] * np.eye(3) + 2.0 * lam_mu[part, 1][:, None, None] * elastic


class ElasticPart:
    """A part's elastic constants: Young's modulus [Pa], Poisson's ratio [-], expansion [1/K]."""

    def __init__(self, youngs_modulus: float, poisson_ratio: float, expansion: float):
        self.youngs_modulus, self.poisson_ratio, self.expansion = youngs_modulus, poisson_ratio, expansion


class Tie:
    r"""A joint's mechanical tie: :math:`k_p \int (N_A - N_B)^T (N_A - N_B)\,dA` along the held axes.

    At each quadrature point of A's facets, ``a_nodes``/``a_values`` are A's nodes and basis
    values there (of the tetrahedron the facet bounds) and ``b_nodes``/``b_values`` B's, both
    evaluated at the *same* point: B's field in the tetrahedron under its facet, extended the
    chord's height to the point.
    A field linear over both parts (a uniform expansion) then has no jump and the tie no
    force, whatever the two triangulations of a curved face (the patch test).
    """

    def __init__(self, a_nodes: np.ndarray, a_values: np.ndarray, b_nodes: np.ndarray, b_values: np.ndarray,
                 weights: np.ndarray, axes: list[int], stiffness: float, name: str = ""):
        self.nodes = np.hstack([a_nodes, b_nodes])  # (q, na + nb)
        self.values = np.hstack([a_values, -b_values])
        self.weights = np.asarray(weights, dtype=float)
        self.axes, self.stiffness, self.name = axes, stiffness, name

    def matrix(self, n: int) -> sp.csr_matrix:
        """The scalar penalty matrix (n × n) [N/m]."""
        k = self.nodes.shape[1]
        values = (self.stiffness * self.weights)[:, None, None] * self.values[:, :, None] * self.values[:, None, :]
        rows = np.repeat(self.nodes[:, :, None], k, axis=2)
        cols = np.repeat(self.nodes[:, None, :], k, axis=1)
        return sp.coo_matrix((values.ravel(), (rows.ravel(), cols.ravel())), shape=(n, n)).tocsr()


class PointTie:
    """Two parts held together at one point along the given axes: a spring of ``stiffness`` [N/m]
    between the displacements of the two parts at the point (``rows``: each part's (1, size) row of the space)."""

    def __init__(self, row_a: sp.spmatrix, row_b: sp.spmatrix, axes: list[int], stiffness: float, name: str = ""):
        self.jump = sp.csr_matrix(row_a - row_b)
        self.axes, self.stiffness, self.name = axes, stiffness, name

    def matrix(self, n: int) -> sp.csr_matrix:
        return (self.stiffness * (self.jump.T @ self.jump)).tocsr()


class ThermoElastic:
    """Stiffness, thermal load and supports of a mesh; solves and reading rows.

    Parameters
    ----------
    space : DisplacementSpace
        The mesh and its displacement's nodes (linear or quadratic tetrahedra).
    constants : list of (E [Pa], ν [-], α [1/K]) per tetrahedron's part, as ``part_of_tet`` indexes
    part_of_tet : ndarray (M,)
    ties : list of Tie or PointTie
        On the space's nodes.
    supports : list of (node, axis index)
        Held components of mesh nodes.
    """

    def __init__(self, space: DisplacementSpace, constants: list[ElasticPart], part_of_tet: np.ndarray,
                 ties: list[Tie], supports: list[tuple[int, int]]):
        started = time.perf_counter()
        self.n_nodes = space.n_nodes
        n = 3 * space.size
        lam_mu = np.array([lame(c.youngs_modulus, c.poisson_ratio) for c in constants])
        beta_part = np.array([c.youngs_modulus / (1.0 - 2.0 * c.poisson_ratio) * c.expansion for c in constants])
        lam, mu, beta = lam_mu[part_of_tet, 0], lam_mu[part_of_tet, 1], beta_part[part_of_tet]
        if space.order == 1:
            g, volume = gradients(space.points, space.tets)
            pattern, pairs = node_pairs(space.tets, self.n_nodes)
            K = stiffness_matrix(g, volume, lam, mu, pairs, pattern)
            F = thermal_load_matrix(g, volume, beta, pairs, pattern)
            del g, pairs
        else:
            K, F = quadratic_matrices(space.mesh, lam, mu, beta)
        tied = [None, None, None]  # per axis: the sum of the scalar tie matrices that hold it
        for tie in ties:
            scalar_tie = tie.matrix(space.size)
            for axis in tie.axes:
                tied[axis] = scalar_tie if tied[axis] is None else tied[axis] + scalar_tie
        for axis, scalar_tie in enumerate(tied):
            if scalar_tie is not None:
                pick = sp.csr_matrix(([1.0], ([axis], [axis])), shape=(3, 3))
                K = K + sp.kron(scalar_tie, pick, format="csr")
        held = np.array(sorted({3 * node + axis for node, axis in supports}), dtype=np.intp)
        free = np.ones(n, dtype=bool)
        free[held] = False
        self.free = np.flatnonzero(free)
        self._K_free = K.tocsr()[self.free][:, self.free].tocsr()
        self._F_free = F.tocsr()[self.free]
        self._factor = None
        self.assembly_seconds = time.perf_counter() - started
        self.factor_seconds = 0.0
        self.factor_memory = 0.0

    @property
    def unknowns(self) -> int:
        return self.free.size

    def _solver(self):
        if self._factor is None:
            started = time.perf_counter()
            A = self._K_free
            if pardiso.suits(A.shape[0]):
                with pardiso.openblas_on_one_thread():
                    self._factor = pardiso.PardisoCholesky(A)
                self.factor_memory = self._factor.memory
            else:
                self._factor = factorize(A)
            self.factor_seconds += time.perf_counter() - started
        return self._factor

    def release(self) -> None:
        """Drop the factorisation (a later solve factorises again)."""
        self._factor = None

    def _solve(self, rhs: np.ndarray) -> np.ndarray:
        solution = self._solver().solve(rhs)
        if not np.all(np.isfinite(solution)):
            raise ModelError("mechanics: the thermoelastic system is singular; the supports and joints must hold "
                             "every part (feedtherm check names a free motion)")
        return solution

    def displacement(self, temperature_rise: np.ndarray) -> np.ndarray:
        """Displacements (N, 3) [m] of the mesh's nodes for nodal temperatures ``T − T_ref`` (N,) [K], or (k, N, 3) of (k, N)."""
        rise = np.atleast_2d(temperature_rise)
        rhs = np.asarray(self._F_free @ rise.T)
        free = self._solve(rhs if rhs.shape[1] > 1 else rhs[:, 0])
        out = np.zeros((3 * self.n_nodes, rise.shape[0]))
        mesh_nodes = self.free < out.shape[0]  # the mesh's nodes come first; a quadratic space's edges after
        out[self.free[mesh_nodes]] = free.reshape(self.free.size, -1)[mesh_nodes]
        u = out.T.reshape(rise.shape[0], self.n_nodes, 3)
        return u if np.ndim(temperature_rise) == 2 else u[0]

    def reading_rows(self, readings: sp.spmatrix) -> np.ndarray:
        """Rows ``R`` (q, N) with ``readings @ u = R @ (T − T_ref)`` for readings (q, 3 size) of the
        displacements (interleaved x, y, z per node of the space): one solve per reading (the adjoint)."""
        C = sp.csr_matrix(readings)[:, self.free].tocsc()  # (q, free): a row per reading
        rows = []
        # a few readings at a time: each block's right-hand sides and solutions are dense (free, block),
        # 66 MB at the fine mesh for 16, where all 103 at once held 424 MB twice beside the factor
        for start in range(0, C.shape[0], READINGS_PER_SOLVE):
            block = C[start:start + READINGS_PER_SOLVE].toarray().T
            Y = self._solve(block if block.shape[1] > 1 else block[:, 0]).reshape(self.free.size, -1)
            rows.append(np.asarray((self._F_free.T @ Y).T))
        return np.vstack(rows)
