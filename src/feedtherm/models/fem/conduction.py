r"""The conduction matrix of linear tetrahedra, assembled with scikit-fem.

For P1 basis functions :math:`\phi_i` and a conductivity :math:`k` per tetrahedron,

.. math:: G_{ij} = \int_\Omega k\,\nabla\phi_i\cdot\nabla\phi_j\,dV \quad [W/K].

Every row sums to zero (a uniform field carries no heat), and a linear field's nodal
residuals are the boundary fluxes :math:`\int_{\partial\Omega} k\,\partial_n T\,\phi_i\,dA`
exactly.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from skfem import BilinearForm, CellBasis, ElementTetP1, MeshTet
from skfem.helpers import dot, grad

__all__ = ["cell_basis", "conduction_matrix"]

ELEMENT = ElementTetP1()


def cell_basis(mesh: MeshTet) -> CellBasis:
    """P1 basis on every tetrahedron (quadrature of order 2)."""
    return CellBasis(mesh, ELEMENT, intorder=2)


@BilinearForm
def _laplace(u, v, w):
    return w.k * dot(grad(u), grad(v))


def conduction_matrix(basis: CellBasis, conductivity) -> sp.csr_matrix:
    """:math:`\\int k \\nabla\\phi_i\\cdot\\nabla\\phi_j\\,dV` [W/K]; ``conductivity`` [W/(m·K)] scalar or per element."""
    count = basis.mesh.nelements
    k = np.asarray(conductivity, dtype=float)
    if k.ndim == 0:
        k = np.broadcast_to(k, (count,))
    if k.shape != (count,):
        raise ValueError(f"conductivity: expected a scalar or {count} values (one per element), got shape {k.shape}")
    return _laplace.assemble(basis, k=np.repeat(k[:, None], basis.X.shape[-1], axis=1)).tocsr()
