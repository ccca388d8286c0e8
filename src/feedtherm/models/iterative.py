"""Conjugate gradients for the time steps of large FE meshes, where one LU per position does not fit.

A step solves ``A T⁺ = b`` with ``A = C/dt + G(k) + A(k)`` symmetric positive definite.
:class:`StepCG` solves it for the step's *increment* ``d = T⁺ − T`` from the state ``T`` at
the step's start, ``A d = b − A T``, so that its relative tolerance :data:`STEP_RTOL` is
relative to what drives the step (its heat and its departure from equilibrium), not to
``C T/dt``, which is orders of magnitude larger and made the former tolerance (1e-10 of
``‖b‖``) an absolute one in disguise.

Before and after the iterations, a Galerkin correction in a coarse space (each part's uniform
field, :meth:`~feedtherm.models.interface.ThermalModel.coarse_space`) makes the residual sum
to zero over every part: each step then conserves energy part by part to round-off, whatever
the iterations stopped at.  This is the coarse correction of two-level methods with a
piecewise-constant coarse space (R. A. Nicolaides, "Deflation of conjugate gradients with
applications to boundary value problems", SIAM J. Numer. Anal. 24 (1987) 355–365), applied
around the iterations rather than inside them: measured as a preconditioner it cost more
per step than it saved in iterations (fine mesh, below).

Measured, the paper bench's first condition over 10,800 s on the coarse mesh against the direct solver: 1e-5 moves
the paper bench's sensors by at most 5e-6 K and D by 2e-6 µm in 23.5 iterations a step; 1e-4 by 5e-5 K in 18.8;
1e-3 by 6e-4 K in 14.7 (the former absolute tolerance: about 1e-6 K a step, 20.3 iterations).
Every run's energy balance closes to 1e-12.  :data:`STEP_RTOL` is 1e-5: the solver's error
stays below a millionth of a kelvin a step, as the verification cases ask of it.

Where the iterations start (:class:`IncrementHistory`): a reciprocating nut makes the increments
repeat from cycle to cycle at each phase of the stroke (position and direction), but for the slow
rise between cycles.  A step at a phase starts from its start state plus the linear extrapolation
of the increments of the last two steps taken at that phase, ``2 d₋₁ − d₋₂`` (``d₋₁`` where there
is one, the linear extrapolation of the last two states where there is none; at a standstill and
in cycle-averaged motion every step has the same phase, so the increments of the last two steps).
On the coarse mesh, the paper bench's first condition over 10,800 s: 23.7 → 8.6 iterations a
step (5.9 in the second half; ``d₋₁`` alone, 14.3) and 46 → 23 s, the final sensors within
4e-7 K of the run started from the extrapolated states (``benchmarks/study_cg_guess.py``; a
third increment, 8.4).

The matrix–vector product, most of an iteration, runs on two threads over halves of the rows
when the machine has two cores and the matrix is large (scipy's sparse kernels release the
interpreter lock): 2.0 → 1.2 ms a product on the fine mesh (171k unknowns).
"""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import LinearOperator, cg

from ..errors import ModelError

#: Relative tolerance of a step's conjugate gradients, on the increment's right-hand side (module notes).
STEP_RTOL = 1e-5
#: Most iterations of one step before the solver gives up.
STEP_MAXITER = 5000
#: Below this many unknowns the threads cost more than they save.
THREADED_ROWS = 20_000

_pool: ThreadPoolExecutor | None = None


def _worker() -> ThreadPoolExecutor:
    global _pool
    if _pool is None:
        _pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="feedtherm-matvec")
    return _pool


def jacobi(A: sp.spmatrix) -> LinearOperator:
    """The Jacobi (diagonal) preconditioner of ``A``.

    Measured on a step matrix of the fine mesh (171k unknowns), one solve to 1e-10 of ``‖b‖``:
    52 iterations of 2.6 ms (0.13 s), against 8 of 36 ms (0.29 s) with smoothed-aggregation
    multigrid (pyamg), 37 of 22 ms (0.82 s) with exact solves of the nut's and the screw's
    blocks, 18 of 10 ms (0.19 s) with a two-level preconditioner on 15 mm aggregates of each
    part: the diagonal alone costs least per step.
    """
    inverse_diagonal = 1.0 / A.diagonal()
    return LinearOperator(A.shape, matvec=lambda v: inverse_diagonal * v, dtype=float)


def matrix_operator(A: sp.csr_matrix) -> sp.csr_matrix | LinearOperator:
    """``A`` itself, or, for a large matrix on a machine with two cores or more, a product on two threads."""
    if A.shape[0] < THREADED_ROWS or (os.cpu_count() or 1) < 2:
        return A
    half = A.shape[0] // 2
    top, bottom = A[:half].tocsr(), A[half:].tocsr()

    def matvec(v: np.ndarray) -> np.ndarray:
        v = np.ravel(v)
        out = np.empty(A.shape[0])
        lower = _worker().submit(bottom.dot, v)
        out[:half] = top @ v
        out[half:] = lower.result()
        return out

    return LinearOperator(A.shape, matvec=matvec, dtype=float)


class IncrementHistory:
    """Starting guesses of a step's conjugate gradients from the increments of the last two steps at
    the same phase of the reciprocation (module notes).

    ``phase`` is any hashable that names a step's place in the cycle and its length; a phase never
    met before gets the caller's ``fallback``.  Two states' worth of entries are kept per phase (40
    phases at 20 steps a stroke: 110 MB on the fine mesh), so the caller keeps the phases finite:
    the integrator uses it only where a step advances the nut by whole grid cells.
    """

    def __init__(self):
        self._kept: dict = {}  # phase → the last one or two increments there, oldest first

    def guess(self, phase, start: np.ndarray, fallback: np.ndarray) -> np.ndarray:
        """Where a step from ``start`` at ``phase`` starts its iterations."""
        kept = self._kept.get(phase)
        if kept is None:
            return fallback
        if len(kept) == 1:
            return start + kept[0]
        return start + (2.0 * kept[1] - kept[0])

    def record(self, phase, increment: np.ndarray) -> None:
        """The increment a step at ``phase`` took."""
        self._kept[phase] = (*self._kept.get(phase, ())[-1:], increment)

    def clear(self) -> None:
        self._kept.clear()


class StepCG:
    """Jacobi-preconditioned conjugate gradients on a step's increment, corrected in a coarse space (module notes).

    Parameters
    ----------
    A : sparse matrix
        The step matrix (symmetric positive definite).
    coarse : sparse matrix, optional
        Columns of the fields each step is corrected in (each part's uniform field,
        :meth:`~feedtherm.models.interface.ThermalModel.coarse_space`); None: the uniform field.
    """

    def __init__(self, A: sp.spmatrix, coarse: sp.spmatrix | None = None):
        A = A.tocsr()
        n = A.shape[0]
        self.Z = sp.csr_matrix(np.ones((n, 1))) if coarse is None else sp.csr_matrix(coarse)
        self._ZT = self.Z.T.tocsr()
        # the matrix is kept once, as the product uses it (a large one in two halves of its rows, which
        # the forcing and the corrections use too): an integrator keeps a solver for every position
        self.operator = matrix_operator(A)
        self.preconditioner = jacobi(A)
        self._coarse = np.linalg.inv((self._ZT @ A @ self.Z).toarray())  # one column per part
        self.iterations = 0  # over every solve, for the run's statistics

    def correct(self, increment: np.ndarray, forcing: np.ndarray) -> np.ndarray:
        """``increment`` plus its Galerkin correction in the coarse space: the residual left is orthogonal to it."""
        residual = forcing - self.operator @ increment
        return increment + self.Z @ (self._coarse @ (self._ZT @ residual))

    def solve(self, rhs: np.ndarray, start: np.ndarray, guess: np.ndarray | None = None) -> np.ndarray:
        """``T⁺`` with ``A T⁺ = rhs``, from the step's start state and a starting guess (default: the start)."""
        forcing = rhs - self.operator @ start
        first = self.correct(np.zeros_like(start) if guess is None else guess - start, forcing)
        count = [0]

        def counted(_):
            count[0] += 1

        increment, info = cg(self.operator, forcing, x0=first, rtol=STEP_RTOL, maxiter=STEP_MAXITER,
                             M=self.preconditioner, callback=counted)
        self.iterations += count[0]
        if info != 0:
            raise ModelError(f"--solver cg: conjugate gradients did not converge in {STEP_MAXITER} iterations of "
                             "a time step; use --solver direct")
        return start + self.correct(increment, forcing)
