r"""Stiffness and thermal-load matrices of linear tetrahedra for isotropic thermoelasticity.

For P1 basis functions :math:`\phi_a` with constant gradients :math:`g_a = \nabla\phi_a` in a
tetrahedron of volume :math:`V`, Lamé constants :math:`\lambda, \mu` and
:math:`\beta = (3\lambda + 2\mu)\alpha`, the element blocks are

.. math::

    K^e_{ai,bj} = V\,\big(\lambda\, g_{ai} g_{bj} + \mu\, g_{aj} g_{bi} + \mu\,\delta_{ij}\, g_a\cdot g_b\big),
    \qquad
    F^e_{ai,b} = \beta\,V\,g_{ai}\,/\,4

(:math:`\int 2\mu\,\varepsilon(u):\varepsilon(v) + \lambda\,\nabla\cdot u\,\nabla\cdot v` and
:math:`\int \beta\,T\,\nabla\cdot v` with :math:`\int \phi_b\,dV = V/4`; Zienkiewicz, Taylor &
Zhu, The Finite Element Method, 7th ed., §6.2-6.3).  Degrees of freedom are interleaved,
``3·node + axis`` (scikit-fem's ``ElementVector`` order).

They are the matrices scikit-fem assembles from the same weak form (the unit test compares
them to 1e-12), built here on the pattern of the nodes' adjacency: each tetrahedron's 16
node pairs are located in it once and every component block is summed with ``bincount``,
which on the fine mesh's 784,000 tetrahedra takes seconds where the general assembly took
40 s and 2.7 GB of coordinate lists.

Quadratic tetrahedra (:func:`quadratic_matrices`, for the models of modest meshes that
choose them) are assembled by scikit-fem from the same weak form, with the temperature in the
thermal model's P1 space and a rule exact for both integrands (degree 2).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from skfem import Basis, BilinearForm, ElementTetP1, ElementTetP2, ElementVector
from skfem.helpers import ddot, div, sym_grad, trace

__all__ = ["gradients", "node_pairs", "quadratic_matrices", "stiffness_matrix", "thermal_load_matrix"]


def gradients(points: np.ndarray, tets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Basis gradients (m, 4, 3) [1/m] and volumes (m,) [m³] of linear tetrahedra (``points`` (3, n), ``tets`` (4, m))."""
    p = points[:, tets].transpose(2, 1, 0)  # (m, 4 vertices, 3 coordinates)
    edges = p[:, 1:] - p[:, :1]  # (m, 3, 3): rows are the edges from vertex 0
    inverse = np.linalg.inv(edges)  # columns: gradients of the barycentric coordinates 1, 2, 3
    g = np.empty((tets.shape[1], 4, 3))
    g[:, 1:] = inverse.transpose(0, 2, 1)
    g[:, 0] = -g[:, 1:].sum(axis=1)
    volume = np.abs(np.linalg.det(edges)) / 6.0
    return g, volume


def node_pairs(tets: np.ndarray, n: int) -> tuple[sp.csr_matrix, np.ndarray]:
    """The pattern of every pair of the ``n`` nodes that share a tetrahedron (a CSR matrix of ones,
    sorted indices) and each tetrahedron's 16 ordered node pairs as indices into its data: (m, 4, 4)."""
    t = tets.T.astype(np.int64)  # (m, 4)
    wanted = (t[:, :, None] * n + t[:, None, :]).ravel()
    keys, pairs = np.unique(wanted, return_inverse=True)  # sorted: row by row, columns increasing
    rows, cols = np.divmod(keys, n)
    indptr = np.concatenate([[0], np.cumsum(np.bincount(rows, minlength=n))])
    pattern = sp.csr_matrix((np.ones(keys.size), cols, indptr), shape=(n, n))
    return pattern, pairs.reshape(t.shape[0], 4, 4)


def _blocks(pairs: np.ndarray, element: np.ndarray, pattern: sp.csr_matrix, block: tuple[int, int]) -> sp.csr_matrix:
    """Sum the element blocks ``element`` (m, 4, 4, r, c) over ``pairs`` into a BSR matrix on ``pattern``, as CSR."""
    r, c = block
    data = np.empty((pattern.nnz, r, c))
    flat = pairs.ravel()
    for i in range(r):
        for j in range(c):
            data[:, i, j] = np.bincount(flat, weights=element[..., i, j].ravel(), minlength=pattern.nnz)
    n = pattern.shape[0]
    return sp.bsr_matrix((data, pattern.indices, pattern.indptr), shape=(r * n, c * n)).tocsr()


def stiffness_matrix(g: np.ndarray, volume: np.ndarray, lam: np.ndarray, mu: np.ndarray, pairs: np.ndarray,
                     pattern: sp.csr_matrix) -> sp.csr_matrix:
    """The stiffness matrix (3n × 3n) [N/m] of Lamé constants ``lam``, ``mu`` [Pa] per tetrahedron."""
    dot = np.einsum("mai,mbi->mab", g, g)  # g_a · g_b
    outer = np.einsum("mai,mbj->mabij", g, g)  # g_ai g_bj
    element = (lam * volume)[:, None, None, None, None] * outer
    element += (mu * volume)[:, None, None, None, None] * outer.transpose(0, 1, 2, 4, 3)  # g_aj g_bi
    element += (mu * volume)[:, None, None, None, None] * dot[:, :, :, None, None] * np.eye(3)
    return _blocks(pairs, element, pattern, (3, 3))


def thermal_load_matrix(g: np.ndarray, volume: np.ndarray, beta: np.ndarray, pairs: np.ndarray,
                        pattern: sp.csr_matrix) -> sp.csr_matrix:
    """The thermal load matrix (3n × n) [N/K] of ``beta`` = (3λ + 2μ)α [Pa/K] per tetrahedron."""
    element = np.broadcast_to((beta * volume / 4.0)[:, None, None, None] * g[:, :, None, :], (*pairs.shape, 3))
    return _blocks(pairs, element[..., None], pattern, (3, 1))


@BilinearForm
def _elastic_form(u, v, w):
    eu, ev = sym_grad(u), sym_grad(v)
    return 2.0 * w.mu * ddot(eu, ev) + w.lam * trace(eu) * trace(ev)


@BilinearForm
def _thermal_load_form(t, v, w):
    return w.beta * t * div(v)


def quadratic_matrices(mesh, lam: np.ndarray, mu: np.ndarray, beta: np.ndarray) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """Stiffness (3s × 3s) [N/m] and thermal load (3s × n) [N/K] of quadratic tetrahedra on a
    scikit-fem ``MeshTet`` of n vertices and s = n + edges nodes, with Lamé's ``lam``, ``mu``
    and ``beta`` = (3λ + 2μ)α per tetrahedron; degrees of freedom interleaved, ``3·node + axis``."""
    displacement = Basis(mesh, ElementVector(ElementTetP2()), intorder=2)
    temperature = displacement.with_element(ElementTetP1())
    per_point = lambda values: np.repeat(np.asarray(values, dtype=float)[:, None], displacement.X.shape[-1], axis=1)  # noqa: E731
    K = _elastic_form.assemble(displacement, lam=per_point(lam), mu=per_point(mu))
    F = _thermal_load_form.assemble(temperature, displacement, beta=per_point(beta))
    return K.tocsr(), F.tocsr()
