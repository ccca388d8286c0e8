r"""Where the FE model's displacement lives: linear or quadratic tetrahedra on the thermal mesh.

- **linear** (4 nodes): one displacement per mesh node, the thermal model's own P1 space.
  Cheap, and exact for the axial stretch of bars; stiff in bending (a strip two elements
  thick bends about a tenth less than it should: docs/fem-model.md).
- **quadratic** (10 nodes, the Lagrange P2 tetrahedron, as ANSYS's SOLID187): a displacement
  at every mesh node and at the middle of every edge. Bending converges an order faster; the
  unknowns grow about sevenfold, so it is for parts and machines of modest meshes.

The space's *nodes* are numbered as scikit-fem numbers the P2 degrees of freedom: the mesh's
``N`` vertices first, then its edges (``N + edge``), so the displacement at the mesh's
nodes is the first ``N`` rows in either space. Its basis at a point of a tetrahedron with
barycentric coordinates :math:`\lambda`:

.. math::

    \phi_i = \lambda_i \;\text{(linear)}, \qquad
    \phi_i = \lambda_i (2\lambda_i - 1),\quad \phi_{ij} = 4\,\lambda_i \lambda_j \;\text{(quadratic)}

(Zienkiewicz, Taylor & Zhu, The Finite Element Method, 7th ed., §6.6, the 10-node
tetrahedron), with the edges in scikit-fem's local order of :data:`LOCAL_EDGES`.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from skfem import MeshTet

__all__ = ["DisplacementSpace", "LOCAL_EDGES", "ORDERS"]

#: The local edges of a tetrahedron, in scikit-fem's order (``MeshTet.t2e``, ``ElementTetP2``).
LOCAL_EDGES = ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))
ORDERS = {"linear": 1, "quadratic": 2}


class DisplacementSpace:
    """The displacement's nodes on a mesh (``points`` (3, N), ``tets`` (4, m)) for ``elements``
    "linear" or "quadratic"; :meth:`shape` evaluates its basis at points of tetrahedra."""

    def __init__(self, points: np.ndarray, tets: np.ndarray, elements: str = "linear"):
        if elements not in ORDERS:
            raise ValueError(f"elements: {elements!r} is not one of {sorted(ORDERS)}")
        self.elements, self.order = elements, ORDERS[elements]
        self.points, self.tets = np.asarray(points, dtype=float), np.asarray(tets)
        self.n_nodes = self.points.shape[1]
        self.mesh = None
        if self.order == 2:
            self.mesh = MeshTet(np.ascontiguousarray(self.points), np.ascontiguousarray(self.tets), validate=False)
            self.edges_of_tet = self.mesh.t2e  # (6, m), global edge indices in LOCAL_EDGES order
            self.size = self.n_nodes + self.mesh.edges.shape[1]
        else:
            self.size = self.n_nodes

    def shape(self, tet_ids: np.ndarray, bary: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The space's nodes (q, k) and basis values (q, k) at points of tetrahedra ``tet_ids`` (q,)
        with barycentric coordinates ``bary`` (q, 4); k = 4 (linear) or 10 (quadratic)."""
        tet_ids = np.asarray(tet_ids)
        lam = np.asarray(bary, dtype=float)
        vertices = self.tets[:, tet_ids].T
        if self.order == 1:
            return vertices, lam
        edges = self.n_nodes + self.edges_of_tet[:, tet_ids].T
        values = np.hstack([lam * (2.0 * lam - 1.0)] + [4.0 * lam[:, [i]] * lam[:, [j]] for i, j in LOCAL_EDGES])
        return np.hstack([vertices, edges]), values

    def rows(self, tet_ids: np.ndarray, bary: np.ndarray) -> sp.csr_matrix:
        """Rows (q, size) of the basis at the points: the displacement component there is ``rows @ u``."""
        nodes, values = self.shape(tet_ids, bary)
        q, k = nodes.shape
        return sp.csr_matrix((values.ravel(), (np.repeat(np.arange(q), k), nodes.ravel())), shape=(q, self.size))

    def on_nodes(self, rows: sp.spmatrix) -> sp.csr_matrix:
        """Rows (q, N) of the mesh's nodes widened to (q, size): what they read of a field at the nodes alone."""
        rows = sp.csr_matrix(rows)
        return sp.hstack([rows, sp.csr_matrix((rows.shape[0], self.size - self.n_nodes))], format="csr")
