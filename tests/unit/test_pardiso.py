"""PARDISO's Cholesky factors of the step matrices, and the integrator's memory budget for them."""

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve

from feedtherm.errors import ModelError
from feedtherm.models import pardiso
from feedtherm.plan import plan_run
from feedtherm.simulate import execute

pytest.importorskip("pypardiso")


def spd(n: int, seed: int) -> sp.csr_matrix:
    """A symmetric, diagonally dominant conductance-like matrix with a 2D grid's pattern."""
    rng = np.random.default_rng(seed)
    side = int(np.sqrt(n))
    weights = sp.triu(sp.diags([1.0, 1.0], [1, side], shape=(n, n)), format="csr")
    weights.data = rng.uniform(0.5, 2.0, weights.nnz)
    W = weights + weights.T
    return (sp.diags(np.asarray(W.sum(axis=1)).ravel() + 0.1) - W).tocsr()


def test_the_cholesky_factors_solve_as_a_sparse_lu_does():
    A = spd(2500, 1)
    b = np.random.default_rng(2).normal(size=2500)
    factors = pardiso.PardisoCholesky(A)
    np.testing.assert_allclose(factors.solve(b), spsolve(A.tocsc(), b), rtol=1e-11, atol=1e-12)
    assert factors.memory > A.nnz * 8.0 / 2  # at least the upper triangle's values
    second = pardiso.PardisoCholesky(2.0 * A)  # a second factorisation alive beside the first
    np.testing.assert_allclose(second.solve(b), 0.5 * factors.solve(b), rtol=1e-11, atol=1e-12)


RELEASE = -1  # PARDISO's phase that releases all of its memory


def test_a_refactorisation_solves_as_a_fresh_factorisation_of_its_matrix(monkeypatch):
    """Another matrix of the held pattern skips the analysis (phase 22, not 12); one of another
    pattern, or a matrix that is not positive definite, is analysed or refused as a first one is."""
    A = spd(2500, 1)
    b = np.random.default_rng(2).normal(size=(2500, 3))
    factors = pardiso.PardisoCholesky(A)
    phases = []
    call = factors._solver._call_pardiso
    monkeypatch.setattr(factors._solver, "_call_pardiso", lambda *args: (phases.append(factors._solver.phase),
                                                                        call(*args))[1])
    same_pattern = A + sp.diags(np.linspace(0.5, 3.0, 2500))
    factors.refactor(same_pattern)
    np.testing.assert_allclose(factors.solve(b), spsolve(same_pattern.tocsc(), b), rtol=1e-11, atol=1e-12)
    links = sp.diags([np.ones(2498), np.ones(2498)], [2, -2])  # more neighbours: another pattern
    other = spd(2500, 4) + sp.diags(np.asarray(links.sum(axis=1)).ravel()) - links
    factors.refactor(other)
    np.testing.assert_allclose(factors.solve(b[:, 0]), spsolve(other.tocsc(), b[:, 0]), rtol=1e-11, atol=1e-12)
    assert phases == [pardiso.FACTORISE, pardiso.SOLVE, RELEASE, pardiso.ANALYSE_AND_FACTORISE, pardiso.SOLVE]
    with pytest.raises(ModelError, match="not symmetric positive definite"):
        factors.refactor(A - sp.identity(2500) * 50.0)


def test_a_matrix_that_is_not_positive_definite_is_refused():
    A = spd(400, 3) - sp.identity(400) * 50.0
    with pytest.raises(ModelError, match="not symmetric positive definite"):
        pardiso.PardisoCholesky(A)


def test_the_budget_is_a_share_of_the_memory_available():
    budget = pardiso.memory_budget()
    with open("/proc/meminfo") as meminfo:
        total = next(float(line.split()[1]) * 1024.0 for line in meminfo if line.startswith("MemTotal:"))
    assert 0.0 < budget <= pardiso.MEMORY_SHARE * total


def superlu_and_pardiso(paper, monkeypatch, **plan):
    """Condition I's first half hour by the fast model, solved by SuperLU and by PARDISO."""
    monkeypatch.setattr(pardiso, "MIN_UNKNOWNS", 10**9)
    reference = execute(plan_run(paper, condition="I", duration=1800.0))
    monkeypatch.setattr(pardiso, "MIN_UNKNOWNS", 0)  # the fast model's matrices by PARDISO, as a fine mesh's are
    return reference, execute(plan_run(paper, condition="I", duration=1800.0, **plan))


def test_a_run_with_pardiso_equals_the_run_with_superlu(paper, monkeypatch):
    reference, solution = superlu_and_pardiso(paper, monkeypatch)
    assert reference.info["solver"] == "direct (LU per position)"
    assert solution.info["solver"] == "direct (PARDISO Cholesky per position)"
    for name in ("T1", "T2", "T3", "T4", "T5", "D_um"):
        assert solution.summary_values("final")[name] == pytest.approx(reference.summary_values("final")[name],
                                                                         abs=1e-9)


def test_positions_beyond_the_memory_budget_are_stepped_by_conjugate_gradients(paper, monkeypatch):
    monkeypatch.setattr(pardiso, "memory_budget", lambda: 1.0)  # room for the first factorisation only
    reference, budgeted = superlu_and_pardiso(paper, monkeypatch)
    assert "cg for" in budgeted.info["solver"] and "beyond the memory budget" in budgeted.info["solver"]
    for name in ("T1", "T2", "T3", "T4", "T5"):
        assert budgeted.summary_values("final")[name] == pytest.approx(reference.summary_values("final")[name],
                                                                         abs=1e-3)


def test_mkl_is_located_before_pypardisos_import_makes_its_own_solver():
    """pypardiso's import makes a solver, which searches the environment's whole tree for MKL
    (0.25 s) unless ``PYPARDISO_MKL_RT`` names it: a fresh interpreter's first factorisation sets
    it first, and no search walks a tree."""
    import os
    import subprocess
    import sys

    script = (
        "import glob, sys\n"
        "searches = []\n"
        "original = glob.glob\n"
        "def recorded(pattern, *args, **kwargs):\n"
        "    if kwargs.get('recursive'):\n"
        "        searches.append(pattern)\n"
        "    return original(pattern, *args, **kwargs)\n"
        "glob.glob = recorded\n"
        "import numpy as np, scipy.sparse as sp\n"
        "from feedtherm.models import pardiso\n"
        "A = sp.diags([np.full(99, -1.0), np.full(100, 2.5), np.full(99, -1.0)], [-1, 0, 1], format='csr')\n"
        "x = pardiso.PardisoCholesky(A).solve(np.ones(100))\n"
        "assert np.allclose(A @ x, 1.0)\n"
        "assert 'pypardiso' in sys.modules and not searches, searches\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "PYPARDISO_MKL_RT"}
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120, env=env)
    assert result.returncode == 0, result.stderr[-2000:]
