"""The elasticity matrices of linear tetrahedra against scikit-fem's assembly of the same weak form,
and against what linear elasticity says of rigid motions and of a uniform expansion."""

import numpy as np
import pytest
from skfem import Basis, BilinearForm, ElementTetP1, ElementVector, MeshTet
from skfem.helpers import ddot, div, sym_grad, trace

from feedtherm.models.fem.elastic import lame
from feedtherm.models.fem.elastic_assembly import gradients, node_pairs, stiffness_matrix, thermal_load_matrix


@BilinearForm
def stiffness_form(u, v, w):
    eu, ev = sym_grad(u), sym_grad(v)
    return 2.0 * w.mu * ddot(eu, ev) + w.lam * trace(eu) * trace(ev)


@BilinearForm
def thermal_form(t, v, w):
    return w.beta * t * div(v)


@pytest.fixture(scope="module")
def mesh():
    rng = np.random.default_rng(3)
    m = MeshTet.init_tensor(np.linspace(0, 0.2, 4), np.linspace(0, 0.1, 3), np.linspace(0, 0.05, 3))
    # distorted, so that no entry vanishes by symmetry
    return MeshTet(m.p + rng.uniform(-0.004, 0.004, m.p.shape), m.t)


@pytest.fixture(scope="module")
def constants(mesh):
    rng = np.random.default_rng(5)
    E, nu, alpha = rng.uniform(100e9, 210e9, mesh.nelements), rng.uniform(0.25, 0.34, mesh.nelements), 1.2e-5
    lam, mu = lame(E, nu)
    return lam, mu, (3 * lam + 2 * mu) * alpha


def test_the_matrices_are_scikit_fems(mesh, constants):
    lam, mu, beta = constants
    vector, scalar = Basis(mesh, ElementVector(ElementTetP1()), intorder=1), Basis(mesh, ElementTetP1(), intorder=1)
    per_point = lambda a: np.repeat(a[:, None], vector.X.shape[-1], axis=1)  # noqa: E731
    K_ref = stiffness_form.assemble(vector, lam=per_point(lam), mu=per_point(mu))
    F_ref = thermal_form.assemble(scalar, vector, beta=per_point(beta))
    g, volume = gradients(mesh.p, mesh.t)
    pattern, pairs = node_pairs(mesh.t, mesh.p.shape[1])
    K = stiffness_matrix(g, volume, lam, mu, pairs, pattern)
    F = thermal_load_matrix(g, volume, beta, pairs, pattern)
    assert abs(K - K_ref).max() <= 1e-12 * abs(K_ref).max()
    assert abs(F - F_ref).max() <= 1e-12 * abs(F_ref).max()


def test_the_gradients_and_volume_of_the_unit_tetrahedron():
    # vertices 0, e_x, e_y, e_z: the barycentric coordinates are 1 - x - y - z, x, y, z
    g, volume = gradients(np.array([[0.0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]), np.array([[0], [1], [2], [3]]))
    np.testing.assert_allclose(g[0], [[-1, -1, -1], [1, 0, 0], [0, 1, 0], [0, 0, 1]], atol=1e-15)
    assert volume[0] == pytest.approx(1 / 6, rel=1e-15)


def test_a_rigid_motion_is_free_of_force_and_a_uniform_expansion_balances_its_load(mesh, constants):
    lam, mu, _ = constants
    g, volume = gradients(mesh.p, mesh.t)
    pattern, pairs = node_pairs(mesh.t, mesh.p.shape[1])
    K = stiffness_matrix(g, volume, lam, mu, pairs, pattern)
    x, y, z = mesh.p
    rotation = np.column_stack([-y, x, np.zeros_like(x)]).ravel()  # about z, interleaved x, y, z per node
    assert np.abs(K @ rotation).max() <= 1e-9 * abs(K).max() * 0.2
    # u = αΔT x is stress-free for one α: K u = F ΔT, node by node (the patch test)
    alpha_dt = 1e-3
    expansion = (alpha_dt * mesh.p.T).ravel()
    F_alpha = thermal_load_matrix(g, volume, 1.2e-5 * (3 * lam + 2 * mu), pairs, pattern)
    np.testing.assert_allclose(K @ expansion, F_alpha @ np.full(mesh.p.shape[1], alpha_dt / 1.2e-5),
                               atol=1e-9 * abs(K @ expansion).max())
