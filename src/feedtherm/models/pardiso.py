"""Sparse Cholesky factorisations of large step matrices by Intel MKL PARDISO (through pypardiso).

A fine FE mesh's step matrix (171k unknowns, 2.5 M non-zeros) has 35 M non-zeros in its
Cholesky factor.  On this project's 2-core machine PARDISO factorises it in 1.3-1.6 s and
solves with it in 24 ms on two threads, against SuperLU's 22 s and 113 ms and 130-180 ms for
conjugate gradients (benchmarks/README.md), so one factorisation per position of the moving
group pays for itself within a stroke.  Each factor holds about 370 MB there, which is why the
integrator keeps them within a memory budget (:func:`memory_budget`).

pypardiso (and the MKL it needs) is installed where MKL has wheels (x86-64); elsewhere
:func:`available` is false and the integrator uses SuperLU or conjugate gradients.

PARDISO's parameters are set explicitly (``iparm(1) = 1``): left at zero it takes the
defaults of an unsymmetric matrix, which refine every solution twice (61 ms per solve instead
of 24 ms) for no gain on a symmetric positive definite matrix (relative residual 7e-15 on the
fine mesh without refinement).

Reference: O. Schenk, K. Gärtner, "Solving unsymmetric sparse systems of linear equations with
PARDISO", Future Generation Computer Systems 20 (2004) 475-487; Intel oneMKL Developer
Reference, "pardiso iparm parameter".
"""

from __future__ import annotations

import glob
import importlib.util
import os
import sys
import weakref
from functools import cache

import numpy as np
import scipy.sparse as sp

from ..errors import ModelError

#: Below this many unknowns SuperLU with a cached order is as fast (fast model, coarse FE mesh:
#: a PARDISO call's fixed cost, about 0.1 ms, is more than a small solve).
MIN_UNKNOWNS = 20_000

#: Share of the memory available when a run starts that its factorisations may hold: the rest is
#: the model's own (the fine mesh's FE model and state history need about 3 GB).
MEMORY_SHARE = 0.5

_SPD = 2  # PARDISO's matrix type: real symmetric positive definite
_PARAMETERS = {  # 1-based iparm indices, as pypardiso's set_iparm takes them
    1: 1,  # the values below are set, not defaulted
    2: 2,  # nested dissection ordering from METIS
    8: 0,  # iterative refinement only when pivots were perturbed (never, for an SPD matrix)
    10: 8,  # pivot perturbation 1e-8 (unused by a Cholesky factorisation; PARDISO's symmetric default)
}


def available() -> bool:
    """Whether pypardiso (and MKL) can be imported here."""
    return importlib.util.find_spec("pypardiso") is not None


@cache
def _locate_mkl() -> None:
    """Tell pypardiso where MKL's runtime library is, and MKL's threads not to spin; once per process.

    Without ``PYPARDISO_MKL_RT`` (pypardiso's documented setting) every solver object searches
    the whole environment's tree for it, 0.15-0.25 s each: more than a factorisation of the medium
    mesh.  pypardiso's import makes one such object (its scipy-like functions' solver), so this
    runs before pypardiso is imported.
    """
    # MKL's OpenMP threads spin 200 ms after each parallel region by default, taking the core the
    # time loop's own numpy work between two solves needs (the energy account doubled in time)
    os.environ.setdefault("KMP_BLOCKTIME", "0")
    if "PYPARDISO_MKL_RT" not in os.environ:
        found = sorted(glob.glob(os.path.join(sys.prefix, "lib*", "libmkl_rt.so*")), key=len)
        if found:
            os.environ["PYPARDISO_MKL_RT"] = found[0]


def openblas_on_one_thread():
    """A context in which OpenBLAS (numpy's and scipy's) runs on one thread.

    OpenBLAS's threads wait busily after each call, taking the cores PARDISO's next solve needs:
    with a few vector products between two solves, a fine-mesh solve took 46 ms instead of 26.
    The time loop's own BLAS work is vector-sized and loses nothing on one thread.
    """
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController().select(internal_api="openblas").limit(limits=1)


def suits(unknowns: int) -> bool:
    """Whether a sparse matrix of this many unknowns is factorised by PARDISO here."""
    return unknowns >= MIN_UNKNOWNS and available()


def memory_budget() -> float:
    """Bytes the factorisations of one run may hold: :data:`MEMORY_SHARE` of the available memory."""
    try:
        with open("/proc/meminfo") as meminfo:
            for line in meminfo:
                if line.startswith("MemAvailable:"):
                    return MEMORY_SHARE * float(line.split()[1]) * 1024.0
    except OSError:
        pass
    return MEMORY_SHARE * float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))


def _release(solver) -> None:
    solver.free_memory(everything=True)


class PardisoCholesky:
    """The Cholesky factorisation of a symmetric positive definite sparse ``A``: ``.solve(rhs)``.

    ``memory`` is what PARDISO reports its factorisation and solution need [bytes]; the memory
    is released when the object is collected.  :meth:`refactor` factorises another matrix of
    the same pattern in its place, reusing PARDISO's analysis.
    """

    def __init__(self, A: sp.spmatrix):
        _locate_mkl()  # before pypardiso's import, which makes a solver of its own (module notes of _locate_mkl)
        import pypardiso

        solver = pypardiso.PyPardisoSolver(mtype=_SPD)
        for index, value in _PARAMETERS.items():
            solver.set_iparm(index, value)
        self._solver = solver
        weakref.finalize(self, _release, solver)  # a factorisation that fails is released with the object too
        self._factorize(_upper_triangle(A), ANALYSE_AND_FACTORISE)

    def refactor(self, A: sp.spmatrix) -> None:
        """Factorise ``A`` in place of the matrix held (whose factor is gone).

        A matrix of the held one's pattern takes PARDISO's numerical factorisation alone: the
        analysis (the nested-dissection order and the factor's structure) depends on the
        pattern only.  On the coarse FE mesh that is 0.025 s against 0.11 s with the analysis,
        for the snapshots of a reduced model's basis, about forty matrices of one pattern
        (:mod:`~feedtherm.models.reduced.basis`).  Another pattern is analysed afresh.
        """
        upper = _upper_triangle(A)
        held = self._upper
        if (upper.shape == held.shape and np.array_equal(upper.indptr, held.indptr)
                and np.array_equal(upper.indices, held.indices)):
            self._factorize(upper, FACTORISE)
        else:
            _release(self._solver)
            self._factorize(upper, ANALYSE_AND_FACTORISE)

    def _factorize(self, upper: sp.csr_matrix, phase: int) -> None:
        import pypardiso

        self._upper = upper
        solver = self._solver
        try:
            # PARDISO by its phase numbers: pypardiso's factorize always analyses, and its solve
            # compares the matrix with the one it factorised, entry by entry, at every call
            solver.set_phase(phase)
            solver._call_pardiso(upper, np.zeros((upper.shape[0], 1)))
        except pypardiso.pardiso_wrapper.PyPardisoError as error:
            raise ModelError(f"the step matrix could not be factorised by PARDISO ({error}): it is not "
                             "symmetric positive definite") from None
        self.memory = 1024.0 * float(solver.get_iparm(16) + solver.get_iparm(17))  # iparm(16), (17): KB

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """``A⁻¹ rhs`` for one right-hand side (n,) or many (n, m)."""
        b = np.asarray(rhs, dtype=float)
        if not b.flags.f_contiguous:  # PARDISO reads the columns one after another, each contiguous
            b = np.asfortranarray(b)
        self._solver.set_phase(SOLVE)
        return self._solver._call_pardiso(self._upper, b)


#: PARDISO's phases (Intel oneMKL Developer Reference, "pardiso"): 12 analyses the pattern and
#: factorises, 22 factorises with the analysis held, 33 solves with the factor.
ANALYSE_AND_FACTORISE = 12
FACTORISE = 22
SOLVE = 33


def _upper_triangle(A: sp.spmatrix) -> sp.csr_matrix:
    """The upper triangle of ``A``, CSR with sorted indices: what PARDISO reads of a symmetric matrix."""
    upper = sp.triu(A, format="csr")
    upper.sort_indices()
    return upper
