"""What one time step's solve costs the fast model, by ordering and by solver.

Run:  flock /tmp/feedtherm-bench.lock .venv/bin/python benchmarks/study_fast_solve.py [--repeat 3000]

Issue 36 asks the fast model's 3 h run of condition I (6,480 steps) for at most 0.2 s in process,
30.9 µs a step for everything.  Each step solves with the factors of its position's step matrix
(1,474 unknowns).  This study takes the step matrices a run of condition I factorises, and times
one solve of one of them, warm in the cache, for:

- SuperLU with each column ordering it offers (the integrator's: minimum degree on Aᵀ + A with
  diagonal pivots), and after a reverse Cuthill–McKee ordering, with the factors' entries;
- LAPACK's banded Cholesky (``pbtrs``) after reverse Cuthill–McKee;
- MKL PARDISO's Cholesky (``models/pardiso.py``), where installed;
- SuperLU on a 10-unknown diagonal system: the call's own cost, apart from the work.

It also times a whole run and its solves as the run makes them (the positions' factors in turn).
Printed and written as JSON to benchmarks/results/fast_solve.json.  About 30 s.
"""

from __future__ import annotations

import argparse
import json
import platform
import time
from pathlib import Path

import numpy as np
import scipy.sparse as sp
from scipy.linalg.lapack import dpbtrf, dpbtrs
from scipy.sparse.csgraph import reverse_cuthill_mckee
from scipy.sparse.linalg import splu

from feedtherm.models import direct
from feedtherm.models import integrator as integrator_module
from feedtherm.plan import with_mode
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system

RESULTS = Path(__file__).resolve().parent / "results"


def per_call_us(fn, repeat: int) -> float:
    fn()
    started = time.perf_counter()
    for _ in range(repeat):
        fn()
    return round((time.perf_counter() - started) / repeat * 1e6, 1)


def step_matrices(loaded) -> tuple[list[sp.csc_matrix], dict]:
    """The step matrices a run of condition I factorises, and the run's wall time and solves."""
    matrices, solves = [], []
    plain_factorize = integrator_module.factorize

    def factorize(A, order=None):
        matrices.append(A.tocsc().copy())
        return _Timed(plain_factorize(A, order), solves)

    simulate(loaded, condition="I", duration=60.0)  # imports and caches
    integrator_module.factorize = factorize
    try:
        started = time.perf_counter()
        simulate(loaded, condition="I")
        wall = time.perf_counter() - started
    finally:
        integrator_module.factorize = plain_factorize
    return matrices, {"run_wall_s": round(wall, 3), "solves": len(solves),
                      "solves_s": round(sum(solves), 3), "solve_in_run_us": round(sum(solves) / len(solves) * 1e6, 1)}


class _Timed:
    """Factors whose solves are timed (the run's own solves, factors in turn as the positions go)."""

    def __init__(self, factors, times: list):
        self._factors, self._times = factors, times

    def __getattr__(self, name):  # perm_c, L, U: what the integrator reads of SuperLU's factors
        return getattr(self._factors, name)

    def solve(self, rhs):
        started = time.perf_counter()
        x = self._factors.solve(rhs)
        self._times.append(time.perf_counter() - started)
        return x


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3000)
    args = parser.parse_args()
    loaded = with_mode(load_system("paper"), "physics")
    matrices, run = step_matrices(loaded)
    A = matrices[len(matrices) // 4]
    n = A.shape[0]
    b = np.random.default_rng(0).normal(size=n)
    figures = {"machine": f"{platform.processor() or platform.machine()}, {platform.python_implementation()} "
                          f"{platform.python_version()}",
               "unknowns": n, "matrix_entries": int(A.nnz), "factorisations_in_run": len(matrices), **run,
               "superlu": {}}
    for spec in ("MMD_AT_PLUS_A", "MMD_ATA", "COLAMD"):
        lu = splu(A, permc_spec=spec, diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        figures["superlu"][spec] = {"factor_entries": int(lu.L.nnz + lu.U.nnz),
                                    "solve_us": per_call_us(lambda: lu.solve(b), args.repeat)}
    order = reverse_cuthill_mckee(A.tocsr(), symmetric_mode=True)
    P = A[order][:, order].tocsc()
    lu = splu(P, permc_spec="NATURAL", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
    figures["superlu"]["RCM, then natural"] = {"factor_entries": int(lu.L.nnz + lu.U.nnz),
                                               "solve_us": per_call_us(lambda: lu.solve(b), args.repeat)}
    rows, cols = P.nonzero()
    band = int(np.max(np.abs(rows - cols)))
    lower = sp.tril(P).tocoo()
    banded = np.zeros((band + 1, n))
    banded[lower.row - lower.col, lower.col] = lower.data
    factor, info = dpbtrf(banded, lower=1)
    assert info == 0
    figures["banded_cholesky_after_rcm"] = {"bandwidth": band,
                                            "solve_us": per_call_us(lambda: dpbtrs(factor, b, lower=1), args.repeat)}
    tiny = splu(sp.eye(10, format="csc") * 2.0)
    figures["superlu_10_unknowns_us"] = per_call_us(lambda: tiny.solve(np.ones(10)), args.repeat)
    from feedtherm.models import pardiso
    if pardiso.available():
        P_factor = pardiso.PardisoCholesky(A.tocsr())
        with pardiso.openblas_on_one_thread():
            figures["pardiso_solve_us"] = per_call_us(lambda: P_factor.solve(b), args.repeat)
    assert isinstance(direct.factorize(A), type(splu(A)))  # the integrator's first factorisation is SuperLU's
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "fast_solve.json").write_text(json.dumps(figures, indent=2) + "\n")
    print(json.dumps(figures, indent=2))


if __name__ == "__main__":
    main()
