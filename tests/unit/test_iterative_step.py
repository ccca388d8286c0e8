"""The iterative step solver (models/iterative.py): the increment's tolerance, the group-wise energy
correction, and the threaded product, each against a direct solve."""

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve

from feedtherm.errors import ModelError
from feedtherm.models import iterative
from feedtherm.models.iterative import StepCG, matrix_operator


def step_matrix(n: int, seed: int, capacity: float = 0.05) -> sp.csr_matrix:
    """``C/dt + G``: a conductance matrix (rows sum to zero) on a 2D grid's pattern with two parts joined by a
    weak contact, plus a small capacity on the diagonal (conduction-dominated, as a fine mesh's steps are)."""
    rng = np.random.default_rng(seed)
    side = int(np.sqrt(n))
    weights = sp.triu(sp.diags([1.0, 1.0], [1, side], shape=(n, n)), format="csr")
    weights.data = rng.uniform(0.5, 2.0, weights.nnz)
    rows, cols = weights.nonzero()
    across = (rows < n // 2) != (cols < n // 2)
    weights.data[across] *= 1e-3  # the contact between the two halves
    W = weights + weights.T
    G = sp.diags(np.asarray(W.sum(axis=1)).ravel()) - W
    return (G + sp.diags(np.full(n, capacity))).tocsr()


def halves(n: int) -> np.ndarray:
    return (np.arange(n) >= n // 2).astype(int)


def indicators(groups: np.ndarray) -> sp.csr_matrix:
    """The coarse space of each group's uniform field."""
    return sp.csr_matrix((np.ones(groups.size), (np.arange(groups.size), groups)))


def test_the_step_solution_matches_a_direct_solve_to_the_tolerance_of_the_increment():
    n = 900
    A = step_matrix(n, 1)
    start = np.full(n, 293.15)
    heat = np.zeros(n)
    heat[:30] = 1.0  # a source in one corner
    rhs = A @ start + heat  # C/dt·T + q, with G·T = 0 for the uniform start
    exact = spsolve(A.tocsc(), rhs)
    solved = StepCG(A, indicators(halves(n))).solve(rhs, start)
    change = np.abs(exact - start).max()
    # the error is a fraction of the step's change, not of the temperature (a 1e-3 tolerance of 293 K
    # would allow 0.3 K)
    assert np.abs(solved - exact).max() < 1e-2 * change
    assert np.abs(solved - exact).max() > 0.0  # an iterative answer, not a direct one in disguise


def test_the_correction_makes_every_group_conserve_the_steps_energy():
    n = 900
    A = step_matrix(n, 2)
    start = np.linspace(290.0, 300.0, n)
    rhs = A @ start + np.random.default_rng(3).uniform(0.0, 1.0, n)
    groups = halves(n)
    solver = StepCG(A, indicators(groups))
    solved = solver.solve(rhs, start, guess=start + 0.1)
    residual = rhs - A @ solved
    scale = np.abs(rhs - A @ start).sum()
    for g in (0, 1):  # each part's heat balance closes, whatever the iterations left
        assert abs(residual[groups == g].sum()) < 1e-12 * scale
    assert np.abs(residual).max() > 1e-9 * scale  # ...while the local residual is not zero
    assert solver.iterations > 0


def test_without_groups_the_total_energy_is_conserved():
    n = 400
    A = step_matrix(n, 4)
    start = np.full(n, 300.0)
    rhs = A @ start + np.random.default_rng(5).uniform(0.0, 1.0, n)
    residual = rhs - A @ StepCG(A).solve(rhs, start)
    assert abs(residual.sum()) < 1e-12 * np.abs(rhs - A @ start).sum()


def test_a_tighter_tolerance_comes_closer_to_the_exact_step(monkeypatch):
    n = 900
    A = step_matrix(n, 6)
    start = np.full(n, 293.15)
    rhs = A @ start + np.r_[np.ones(20), np.zeros(n - 20)]
    exact = spsolve(A.tocsc(), rhs)
    loose = np.abs(StepCG(A).solve(rhs, start) - exact).max()
    monkeypatch.setattr(iterative, "STEP_RTOL", 1e-9)
    tight = np.abs(StepCG(A).solve(rhs, start) - exact).max()
    assert tight < 1e-3 * loose


def test_a_step_that_does_not_converge_is_an_error_naming_the_remedy(monkeypatch):
    A = step_matrix(900, 7)
    monkeypatch.setattr(iterative, "STEP_MAXITER", 1)
    start = np.full(900, 293.15)
    heat = np.r_[np.ones(30), np.zeros(870)]  # not uniform: the coarse correction alone does not solve it
    with pytest.raises(ModelError, match="use --solver direct"):
        StepCG(A).solve(A @ start + heat, start)


def test_the_threaded_product_equals_the_plain_one(monkeypatch):
    monkeypatch.setattr(iterative, "THREADED_ROWS", 10)
    monkeypatch.setattr(iterative.os, "cpu_count", lambda: 2)
    A = step_matrix(401, 8)  # an odd size: halves of unequal length
    operator = matrix_operator(A)
    assert not sp.issparse(operator)
    v = np.random.default_rng(9).normal(size=401)
    np.testing.assert_array_equal(operator.matvec(v), A @ v)
    monkeypatch.setattr(iterative.os, "cpu_count", lambda: 1)
    assert matrix_operator(A) is A  # one core: the matrix itself


def test_a_steps_guess_extrapolates_the_last_two_increments_at_its_phase():
    history = iterative.IncrementHistory()
    start, fallback = np.full(3, 300.0), np.full(3, 301.0)
    assert history.guess("up 4", start, fallback) is fallback  # no step at this phase yet
    history.record("up 4", np.array([1.0, 2.0, 3.0]))
    np.testing.assert_array_equal(history.guess("up 4", start, fallback), [301.0, 302.0, 303.0])
    history.record("down 4", np.array([9.0, 9.0, 9.0]))  # another phase keeps its own
    history.record("up 4", np.array([1.5, 2.0, 2.0]))
    # 2 d₋₁ − d₋₂: the increment keeps changing as it changed between the last two cycles
    np.testing.assert_array_equal(history.guess("up 4", start, fallback), [302.0, 302.0, 301.0])
    history.record("up 4", np.array([2.0, 2.0, 1.0]))  # only the last two are kept
    np.testing.assert_array_equal(history.guess("up 4", start, fallback), [302.5, 302.0, 300.0])
    history.clear()
    assert history.guess("up 4", start, fallback) is fallback


def test_a_step_on_two_threads_is_the_step_on_one(monkeypatch):
    """A large step matrix is kept only as the two halves its threaded product uses: the solver's
    forcing, corrections and iterations all go through them, and give the one-thread answer."""
    n = 900
    A = step_matrix(n, 10)
    start = np.linspace(290.0, 300.0, n)
    rhs = A @ start + np.random.default_rng(11).uniform(0.0, 1.0, n)
    groups = indicators(halves(n))
    plain = StepCG(A, groups)
    assert sp.issparse(plain.operator)  # small: the matrix itself, once
    monkeypatch.setattr(iterative, "THREADED_ROWS", 10)
    monkeypatch.setattr(iterative.os, "cpu_count", lambda: 2)
    threaded = StepCG(A, groups)
    assert not sp.issparse(threaded.operator)
    assert not any(sp.issparse(value) and value.shape == A.shape for value in vars(threaded).values())
    np.testing.assert_allclose(threaded.solve(rhs, start), plain.solve(rhs, start), rtol=0.0, atol=1e-12)
    assert threaded.iterations == plain.iterations
