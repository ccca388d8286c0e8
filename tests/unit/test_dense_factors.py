"""The dense factorisations of a projected model's step matrices (models/direct.py)."""

import numpy as np

from feedtherm.models.direct import _DenseCholesky, _DenseLU, dense_factors, symmetric


def spd(n, seed=1):
    rng = np.random.default_rng(seed)
    B = rng.standard_normal((n, n))
    return B @ B.T + n * np.eye(n)


def test_a_symmetric_positive_definite_matrix_is_solved_by_cholesky():
    A = spd(40)
    b = np.arange(40.0)
    factors = dense_factors(A)
    assert isinstance(factors, _DenseCholesky)
    np.testing.assert_allclose(A @ factors.solve(b), b, rtol=1e-12, atol=1e-12)
    # the C-ordered matrix and its Fortran-ordered copy give the same factors
    np.testing.assert_array_equal(factors.solve(b), dense_factors(np.asfortranarray(A)).solve(b))


def test_a_matrix_that_is_not_symmetric_or_not_definite_falls_back_to_lu():
    A = spd(40)
    A[3, 7] += 1.0  # one entry off: not symmetric
    assert not symmetric(A)
    factors = dense_factors(A)
    assert isinstance(factors, _DenseLU)
    b = np.ones(40)
    np.testing.assert_allclose(A @ factors.solve(b), b, rtol=1e-12, atol=1e-12)
    indefinite = np.diag([1.0, -1.0, 2.0])  # symmetric, not definite
    assert symmetric(indefinite) and isinstance(dense_factors(indefinite), _DenseLU)
    np.testing.assert_allclose(dense_factors(indefinite).solve(np.ones(3)), [1.0, -1.0, 0.5])


def test_rounding_is_not_taken_for_asymmetry():
    A = spd(30)
    A = A + 1e-15 * np.abs(A).max() * np.triu(np.ones_like(A), 1)  # below the projection's rounding
    assert symmetric(A)
    assert not symmetric(A + 1e-6 * np.abs(A).max() * np.triu(np.ones_like(A), 1))
