"""The Cauchy stress of P1 tetrahedra from displacements and temperatures (models/fem/elastic.py)."""

import numpy as np
import pytest

from feedtherm.models.fem.elastic import ElasticPart, stress

E, NU, ALPHA = 200e9, 0.3, 1.2e-5
# two tetrahedra of a unit cube's corner, one of them given in the other orientation
POINTS = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], dtype=float).T * 0.01  # (3, 5) [m]
TETS = np.array([[0, 1, 2, 3], [1, 2, 3, 4]]).T  # (4, 2)
STEEL = [ElasticPart(E, NU, ALPHA)]


def field(gradient: np.ndarray) -> np.ndarray:
    """Nodal displacements (5, 3) of u = G p."""
    return (gradient @ POINTS).T


def test_a_bar_clamped_along_x_and_free_across_carries_minus_e_alpha_dt():
    # ε_xx = 0, ε_yy = ε_zz = (1 + ν) α ΔT: σ_yy = λ (tr ε − 3αΔT) + 2μ(ε_yy − αΔT)
    # = λ (2(1+ν) − 3) αΔT + 2μ ν αΔT = αΔT [Eν(2ν − 1)/((1+ν)(1−2ν)) + Eν/(1+ν)] = 0, and
    # σ_xx = λ (2ν − 1) αΔT − 2μ αΔT = −αΔT [Eν/(1+ν) + E/(1+ν)] = −E α ΔT = −120 MPa at 50 K
    dT = 50.0
    lateral = (1 + NU) * ALPHA * dT
    sigma = stress(POINTS, TETS, field(np.diag([0.0, lateral, lateral])), np.full(5, dT), STEEL, np.zeros(2, int))
    expected = np.diag([-E * ALPHA * dT, 0.0, 0.0])
    assert -E * ALPHA * dT == pytest.approx(-120e6)
    np.testing.assert_allclose(sigma, np.broadcast_to(expected, (2, 3, 3)), atol=1e-6 * E * ALPHA * dT)


def test_free_expansion_and_a_small_rotation_carry_no_stress():
    dT = 30.0
    spin = np.array([[0.0, -2e-4, 1e-4], [2e-4, 0.0, -3e-4], [-1e-4, 3e-4, 0.0]])  # antisymmetric: no strain
    u = field(ALPHA * dT * np.eye(3) + spin)
    sigma = stress(POINTS, TETS, u, np.full(5, dT), STEEL, np.zeros(2, int))
    np.testing.assert_allclose(sigma, 0.0, atol=1e-9 * E * ALPHA * dT)


def test_a_general_strain_at_the_centroid_temperature():
    # ε from a general gradient; ΔT is the mean of the tetrahedron's four nodes
    G = np.array([[1.0, 2.0, -1.0], [0.5, -2.0, 1.5], [3.0, 0.0, 1.0]]) * 1e-4
    eps = 0.5 * (G + G.T)
    rise = np.array([10.0, 20.0, 30.0, 40.0, 50.0])
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    sigma = stress(POINTS, TETS, field(G), rise, STEEL, np.zeros(2, int))
    for k, centroid_rise in enumerate([25.0, 35.0]):  # (10+20+30+40)/4, (20+30+40+50)/4
        elastic = eps - ALPHA * centroid_rise * np.eye(3)
        expected = lam * np.trace(elastic) * np.eye(3) + 2 * mu * elastic
        np.testing.assert_allclose(sigma[k], expected, rtol=1e-10, atol=1e-6)
        np.testing.assert_allclose(sigma[k], sigma[k].T)
