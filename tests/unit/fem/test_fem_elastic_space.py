"""The displacement's spaces: the quadratic tetrahedron's basis against scikit-fem's, and its
matrices against what linear elasticity says of rigid motions, a uniform expansion and a
quadratic field (which linear tetrahedra cannot represent)."""

import numpy as np
import pytest
from skfem import Basis, ElementTetP2, MeshTet

from feedtherm.models.fem.elastic import lame
from feedtherm.models.fem.elastic_assembly import quadratic_matrices
from feedtherm.models.fem.elastic_space import DisplacementSpace


@pytest.fixture(scope="module")
def space():
    rng = np.random.default_rng(7)
    m = MeshTet.init_tensor(np.linspace(0, 0.2, 4), np.linspace(0, 0.1, 3), np.linspace(0, 0.05, 3))
    return DisplacementSpace(m.p + rng.uniform(-0.004, 0.004, m.p.shape), m.t, "quadratic")


def node_positions(space) -> np.ndarray:
    """(size, 3): the mesh's nodes, then the middle of each edge [m]."""
    edges = space.mesh.edges
    return np.vstack([space.points.T, 0.5 * (space.points[:, edges[0]] + space.points[:, edges[1]]).T])


def test_the_basis_is_scikit_fems_at_random_points(space):
    rng = np.random.default_rng(11)
    tets = rng.integers(0, space.tets.shape[1], 20)
    bary = rng.dirichlet(np.ones(4), 20)
    x = np.einsum("qk,ikq->iq", bary, space.points[:, space.tets[:, tets]])  # (3, q)
    scalar = Basis(space.mesh, ElementTetP2())
    field = np.random.default_rng(13).normal(size=scalar.N)
    ours = space.rows(tets, bary) @ field
    assert ours == pytest.approx(scalar.probes(x) @ field, rel=1e-10, abs=1e-12)


def test_the_linear_space_is_the_mesh_nodes(space):
    linear = DisplacementSpace(space.points, space.tets)
    nodes, values = linear.shape(np.array([0, 3]), np.array([[0.1, 0.2, 0.3, 0.4], [1.0, 0.0, 0.0, 0.0]]))
    assert linear.size == space.n_nodes
    assert (nodes == space.tets[:, [0, 3]].T).all()
    assert values[1].tolist() == [1.0, 0.0, 0.0, 0.0]


def test_an_unknown_element_is_refused(space):
    with pytest.raises(ValueError, match="elements"):
        DisplacementSpace(space.points, space.tets, "cubic")


@pytest.fixture(scope="module")
def matrices(space):
    E, nu, alpha = 200e9, 0.3, 1.2e-5
    lam, mu = lame(E, nu)
    m = space.tets.shape[1]
    K, F = quadratic_matrices(space.mesh, np.full(m, lam), np.full(m, mu), np.full(m, (3 * lam + 2 * mu) * alpha))
    return K, F, alpha


def test_rigid_motions_cost_nothing(space, matrices):
    K = matrices[0]
    x = node_positions(space)
    rotation = np.cross([0.3, -0.2, 1.0], x)  # a small rotation about an axis through the origin
    for u in (np.tile([1.0, 0.0, 0.0], (space.size, 1)), rotation):
        assert np.abs(K @ u.ravel()).max() < 1e-9 * np.abs(K).max()


def test_a_uniform_rise_expands_freely(space, matrices):
    # u = α ΔT x balances the thermal load of a uniform ΔT at every node: K u = F ΔT
    K, F, alpha = matrices
    u = alpha * 30.0 * node_positions(space)
    residual = K @ u.ravel() - F @ np.full(space.n_nodes, 30.0)
    assert np.abs(residual).max() < 1e-9 * np.abs(F @ np.full(space.n_nodes, 30.0)).max()


def test_a_quadratic_displacement_is_held_exactly(space, matrices):
    # K is symmetric positive semi-definite, and a quadratic field's energy is the integral
    # of its strain energy density: u = (c x², 0, 0) has ε_xx = 2 c x, the rest nil, so
    # W = ½ ∫ (λ + 2μ) (2 c x)² dV, a polynomial of degree 2 integrated exactly.
    K = matrices[0]
    lam, mu = lame(200e9, 0.3)
    x = node_positions(space)
    c = 1e-3
    u = np.zeros_like(x)
    u[:, 0] = c * x[:, 0] ** 2
    energy = 0.5 * u.ravel() @ (K @ u.ravel())
    points, tets = space.points, space.tets
    # the exact integral of x² over each tetrahedron: V/20 (Σ x_i² + (Σ x_i)²)
    corners = points[:, tets]
    volume = np.abs(np.einsum("ij,ij->j", corners[:, 1] - corners[:, 0],
                              np.cross(corners[:, 2] - corners[:, 0], corners[:, 3] - corners[:, 0], axis=0))) / 6
    xs = corners[0]
    x2 = (volume / 20 * ((xs**2).sum(axis=0) + xs.sum(axis=0) ** 2)).sum()
    assert energy == pytest.approx(0.5 * (lam + 2 * mu) * 4 * c**2 * x2, rel=1e-10)
