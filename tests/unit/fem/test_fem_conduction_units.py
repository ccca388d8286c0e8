"""Unit tests of the conduction matrix the FE model assembles (models/fem/conduction.py)."""

import numpy as np
import pytest
from skfem import MeshTet

from feedtherm.models.fem.conduction import cell_basis, conduction_matrix


def _bar():
    """A 0.1 × 0.02 × 0.01 m block of tetrahedra (a tensor grid of 10 × 2 × 1 cells)."""
    return MeshTet.init_tensor(np.linspace(0, 0.1, 11), np.linspace(0, 0.02, 3), np.linspace(0, 0.01, 2))


def test_rows_sum_to_zero_and_a_linear_field_carries_fourier_flux():
    mesh = _bar()
    G = conduction_matrix(cell_basis(mesh), 45.0)
    np.testing.assert_allclose(G @ np.ones(mesh.nvertices), 0.0, atol=1e-9)
    # T = 100 K/m · x: the nodes at x = 0 give up k·A·dT/dx = 45 · (0.02 · 0.01) · 100 = 0.9 W
    T = 100.0 * mesh.p[0]
    assert -(G @ T)[mesh.p[0] < 1e-12].sum() == pytest.approx(0.9, rel=1e-12)


def test_conductivity_per_element():
    mesh = _bar()
    basis = cell_basis(mesh)
    k = np.where(mesh.p[0, mesh.t].mean(axis=0) < 0.05, 10.0, 40.0)  # two halves in series
    G = conduction_matrix(basis, k)
    # heat into x = 0 at unit flux leaves at x = 0.1: the linear solve of the series bar
    T = np.where(mesh.p[0] < 0.05, mesh.p[0] / 10.0, 0.05 / 10.0 + (mesh.p[0] - 0.05) / 40.0)
    residual = G @ T
    inner = (mesh.p[0] > 1e-12) & (mesh.p[0] < 0.1 - 1e-12)
    np.testing.assert_allclose(residual[inner], 0.0, atol=1e-12)  # piecewise linear: no heat inside
    assert -residual[mesh.p[0] < 1e-12].sum() == pytest.approx(0.02 * 0.01, rel=1e-12)  # q'' = 1 W/m² over A


def test_per_element_values_must_have_the_right_length():
    basis = cell_basis(_bar())
    with pytest.raises(ValueError, match="one per element"):
        conduction_matrix(basis, np.ones(5))
