"""Direct solvers of the step matrices: sparse LU per position (reusing a position's elimination
order when the coupling refactorises it) and dense Cholesky (or LU) for projected models."""

from __future__ import annotations

import hashlib

import numpy as np
import scipy.linalg
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from ..errors import ModelError


def factorize(A: sp.spmatrix, order: "EliminationOrder | None" = None):
    """Sparse LU of the symmetric positive definite ``A``.

    The minimum-degree ordering of ``A + Aᵀ`` with diagonal pivots keeps the symmetry;
    on the medium FE mesh it needs 40 % less fill than SuperLU's default column ordering,
    which is what bounds the memory of one cached factorisation per position.  ``order``
    (the :class:`EliminationOrder` of an earlier factorisation of a matrix with the same
    pattern) skips the ordering: the same fill, about 40 % less time on the fast model.
    """
    if order is not None:
        return _OrderedLU(A, order)
    return splu(A.tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})


class EliminationOrder:
    """The order in which a :func:`factorize` LU eliminated the unknowns, for matrices of one pattern.

    Kept from the first factorisation of the pattern; the first reuse builds the gather that
    permutes a matrix of the pattern by its values alone (a run that never refactorises, as a
    frozen FE run, keeps only the order).
    """

    def __init__(self, lu):
        self.order = np.argsort(lu.perm_c)
        self._gather = None

    def permute(self, A: sp.spmatrix) -> sp.csc_matrix:
        """``A[order][:, order]`` of a matrix with the pattern this order was built from."""
        A = A.tocsr()
        if self._gather is None:
            positions = sp.csr_matrix((np.arange(1.0, A.nnz + 1.0), A.indices, A.indptr), shape=A.shape)
            permuted = positions[self.order][:, self.order].tocsc()
            self._gather = (permuted.data.astype(np.int64) - 1, permuted.indices, permuted.indptr)
        take, indices, indptr = self._gather
        return sp.csc_matrix((A.data[take], indices, indptr), shape=A.shape)


class _OrderedLU:
    """SuperLU of ``A`` permuted symmetrically into a known elimination order (no ordering step)."""

    def __init__(self, A: sp.spmatrix, order: EliminationOrder):
        self.order = order.order
        self._lu = splu(order.permute(A), permc_spec="NATURAL", diag_pivot_thresh=0.0,
                        options={"SymmetricMode": True})

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        solution = np.empty_like(rhs)
        solution[self.order] = self._lu.solve(rhs[self.order])
        return solution


def _pattern(A: sp.spmatrix) -> str:
    """A fingerprint of a sparse matrix's pattern (what its elimination order depends on)."""
    A = A.tocsr()
    h = hashlib.blake2b(digest_size=16)
    h.update(np.ascontiguousarray(A.indptr).tobytes())
    h.update(np.ascontiguousarray(A.indices).tobytes())
    return h.hexdigest()


#: How far a dense step matrix may be from symmetric to be taken as symmetric, as a share of its
#: products' size: a Galerkin projection of a symmetric matrix is symmetric to rounding (about
#: 1e-16), a matrix with a non-symmetric term is so by far more.
SYMMETRY_TOLERANCE = 1e-10


def dense_factors(A: np.ndarray):
    """The factors of a dense step matrix: Cholesky where ``A`` is symmetric positive definite (a
    projected model's is: a Galerkin projection of one), LU otherwise.  ``.solve(rhs)``.

    Cholesky takes a third of LU's flops: at a reduced model's size (r ≈ 450) OpenBLAS's potrf
    takes 1.6 ms on one thread where its getrf takes 6 ms.
    """
    A = np.asarray(A, dtype=float)
    if symmetric(A):
        factors = _DenseCholesky.of(A)
        if factors is not None:
            return factors
    return _DenseLU(A)


def symmetric(A: np.ndarray) -> bool:
    """Whether the square ``A`` equals its transpose to rounding, judged by ``uᵀAv = vᵀAu`` for two
    fixed random vectors: a product's cost where comparing ``A`` with ``Aᵀ`` entry by entry walks
    one of them across memory, and a matrix that is not symmetric passes only for vectors chosen
    against it (the identity holds for all u, v exactly when A is symmetric)."""
    u, v = np.random.default_rng(0).standard_normal((2, A.shape[0]))
    Av, Au = A @ v, A @ u
    size = np.linalg.norm(u) * np.linalg.norm(Av) + np.linalg.norm(v) * np.linalg.norm(Au)
    return abs(float(u @ Av) - float(v @ Au)) <= SYMMETRY_TOLERANCE * size


class _DenseCholesky:
    """LAPACK's Cholesky (potrf/potrs) of a symmetric positive definite dense matrix, called directly."""

    def __init__(self, factor: np.ndarray, potrs):
        self._factor, self._potrs = factor, potrs

    @classmethod
    def of(cls, A: np.ndarray) -> "_DenseCholesky | None":
        """The factors of ``A`` (its lower triangle), None where ``A`` is not positive definite."""
        potrf, potrs = scipy.linalg.get_lapack_funcs(("potrf", "potrs"), (A,))
        # Aᵀ = A: LAPACK reads a C-ordered matrix's transpose without reordering it
        factor, info = potrf(A.T if A.flags.c_contiguous else A, lower=True, clean=False)
        return cls(factor, potrs) if info == 0 else None

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        return self._potrs(self._factor, rhs, lower=True)[0]


class _DenseLU:
    """LAPACK's LU (getrf/getrs) of a dense step matrix, called directly: ``scipy.linalg.lu_solve``
    copies the factors on every call, which costs more than the solve at a reduced model's size."""

    def __init__(self, A: np.ndarray):
        getrf, self._getrs = scipy.linalg.get_lapack_funcs(("getrf", "getrs"), (A,))
        self._lu, self._piv, info = getrf(np.asfortranarray(A, dtype=float))
        if info != 0:
            raise ModelError(f"a reduced model's step matrix is singular (LAPACK getrf info {info})")

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        return self._getrs(self._lu, self._piv, rhs)[0]
