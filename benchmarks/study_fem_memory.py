"""What one factorisation per nut position costs on an FE mesh, and what sharing one factor would cost.

Run:  flock /tmp/feedtherm-bench.lock .venv/bin/python benchmarks/study_fem_memory.py [--mesh fine] [--repeat 10]

Issue 36 asks the position-resolved fine run (condition I, 10,800 s, 6,480 steps) for at most
4 GB and 120 s.  The run keeps one PARDISO Cholesky factor per visited position (21 at condition
I); this study measures, on the built model with condition I's boundary conditions and the
run's step (1.67 s):

- one position's factor: its memory (PARDISO's own report), the factorisation and one solve;
- the step count times one solve: the least time any scheme with one full solve a step needs;
- the rows of the step matrix that differ from the preconditioner's: the rank a Woodbury update
  of that factor would have to carry;
- conjugate gradients at position k0 + dk preconditioned by k0's factor (dk = 1, 2, 5, 10), and by
  the factor of the cycle-averaged matrix, on a developed step (30 direct steps from the
  ambient, then one step): iterations to the integrator's tolerance (1e-5 of the step's
  forcing), wall time, and the error against the direct answer; and Jacobi's at k0 + 10 beside them.

Printed and written as JSON to benchmarks/results/fem_memory_<mesh>.json.  Takes 4 minutes at
the fine mesh (14 s to build the model from the mesh cache, 8 factorisations); run nothing else
beside it.
"""

from __future__ import annotations

import argparse
import json
import resource
import time
from pathlib import Path

import numpy as np
from scipy.sparse.linalg import LinearOperator, cg

from feedtherm.boundary import boundary_conditions
from feedtherm.models import pardiso
from feedtherm.models.integrator import Integrator
from feedtherm.models.iterative import STEP_RTOL, jacobi
from feedtherm.models.options import ModelOptions
from feedtherm.simulate import discretize
from feedtherm.system.load import load_system

RESULTS = Path(__file__).resolve().parent / "results"
STEPS = 6480  # condition I over 10,800 s at 20 steps per stroke
DT = 10_800.0 / STEPS


def timed_solve(factor, rhs: np.ndarray, repeat: int) -> float:
    """The median of ``repeat`` solves [s], after one that is not counted (MKL's threads start on the first)."""
    factor.solve(rhs)
    times = []
    for _ in range(repeat):
        started = time.perf_counter()
        factor.solve(rhs)
        times.append(time.perf_counter() - started)
    return float(np.median(times))


def developed(model, factor, loads, start: np.ndarray, steps: int = 30) -> np.ndarray:
    state = start
    for _ in range(steps):
        state = factor.solve(model.capacity / DT * state + loads.heat + loads.ambient.source)
    return state


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh", default="fine", choices=["coarse", "medium", "fine"])
    parser.add_argument("--repeat", type=int, default=10, help="solves timed per figure")
    args = parser.parse_args()
    if not pardiso.available():
        raise SystemExit("this study measures PARDISO's factors: pypardiso is not installed here")
    system = load_system("paper").system
    options = ModelOptions(mesh=args.mesh)
    started = time.perf_counter()
    model = discretize(system, "fem", options)
    build = time.perf_counter() - started
    bc = boundary_conditions(system, "I")
    integrator = Integrator(model, options)
    k0 = len(model.positions) // 2
    ambient = np.full(model.n_nodes, bc.point.ambient)
    figures = {"mesh": args.mesh, "unknowns": int(model.n_nodes), "positions": len(model.positions),
               "build_s": round(build, 1), "time_step_s": DT, "steps": STEPS}
    with pardiso.openblas_on_one_thread():
        A0 = integrator._step_matrix(0, bc, k0, DT).tocsr()
        started = time.perf_counter()
        base = pardiso.PardisoCholesky(A0)
        figures["factor_s"] = round(time.perf_counter() - started, 2)
        figures["factor_MB"] = round(base.memory / 1e6, 1)
        state0 = developed(model, base, integrator.loads(0, bc, k0), ambient)
        solve = timed_solve(base, model.capacity / DT * state0, args.repeat)
        figures["solve_ms"] = round(solve * 1e3, 2)
        figures["solves_alone_s"] = round(STEPS * solve, 1)
        averaged = integrator._step_matrix(0, bc, None, DT).tocsr()
        mean = pardiso.PardisoCholesky(averaged)
        figures["averaged_factor_MB"] = round(mean.memory / 1e6, 1)
        figures["averaged_solve_ms"] = round(timed_solve(mean, model.capacity / DT * state0, args.repeat) * 1e3, 2)
        figures["preconditioned"] = []
        for dk, preconditioner, matrix in [(1, base, A0), (2, base, A0), (5, base, A0), (10, base, A0),
                                           (0, mean, averaged), (10, None, None)]:
            k = k0 + dk
            A = integrator._step_matrix(0, bc, k, DT).tocsr()
            loads = integrator.loads(0, bc, k)
            own = pardiso.PardisoCholesky(A)
            state = developed(model, own, loads, ambient)
            rhs = model.capacity / DT * state + loads.heat + loads.ambient.source
            exact = own.solve(rhs)
            del own
            forcing = rhs - A @ state
            count = [0]
            started = time.perf_counter()
            M = jacobi(A) if preconditioner is None else LinearOperator(A.shape, matvec=preconditioner.solve,
                                                                        dtype=float)
            increment, info = cg(A, forcing, x0=np.zeros_like(state), rtol=STEP_RTOL, M=M,
                                 callback=lambda _: count.__setitem__(0, count[0] + 1))
            seconds = time.perf_counter() - started
            if matrix is None:
                changed_rows, name = 0, "Jacobi (the diagonal)"
            else:  # the rows the preconditioner's matrix has wrong, beyond round-off
                changed = abs(A - matrix).tocoo()
                changed.data[changed.data <= 1e-12 * abs(matrix.diagonal()).max()] = 0.0
                changed_rows = int(np.unique(changed.row[changed.data > 0.0]).size)
                name = "cycle-averaged matrix" if preconditioner is mean else f"position {k0}"
            figures["preconditioned"].append({
                "position": k, "preconditioner": name, "changed_rows": changed_rows,
                "iterations": count[0], "converged": info == 0, "seconds": round(seconds, 3),
                "error_K": float(np.max(np.abs(state + increment - exact))),
                "run_estimate_s": round(STEPS * seconds, 0)})
    figures["peak_rss_MB"] = round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0, 1)
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / f"fem_memory_{args.mesh}.json").write_text(json.dumps(figures, indent=2))
    print(json.dumps(figures, indent=2))


if __name__ == "__main__":
    main()
