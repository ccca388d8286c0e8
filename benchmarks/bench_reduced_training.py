"""Benchmark of a reduced model's first build by what its basis is trained over.

Run:  .venv/bin/python benchmarks/bench_reduced_training.py [--system paper] [--mesh coarse] [--threads 1]

``ModelOptions.reduced_training`` (models/reduced/store.py): a single run (``feedtherm run``)
trains its basis at its description's own numbers ("description"); a batch prepares one over the
ranges the description declares ("batch", as "declared" builds).  Each is built in a child
process of its own, in an empty cache holding only the mesh (copied from the user's, made first
where missing), with ``--threads`` BLAS/PARDISO threads (1: as the tests run it): the build's
wall time, the basis's size and snapshots, the projection file's size, and a 600 s run of
condition I on each with its T1–T5 and D at the end, then their largest difference.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

CHILD = """
import json, sys, time
from feedtherm.models.options import ModelOptions
from feedtherm.models.registry import build_model
from feedtherm.simulate import execute
from feedtherm.plan import plan_run
from feedtherm.system.load import load_system
system, mesh, training = sys.argv[1:4]
loaded = load_system(system)
options = ModelOptions(mesh=mesh, reduced_training=training)
started = time.perf_counter()
model = build_model("reduced", loaded.system, options)
build = time.perf_counter() - started
condition = next(iter(loaded.system.conditions))
run = execute(plan_run(loaded, condition=condition, model="reduced", duration=600.0, options=options))
finals = {name: float(values[-1]) for name, values in run.sensors.items()}
finals["D_um"] = float(run.elongation[-1]) * 1e6
print(json.dumps({"build_s": round(build, 2), "trained_over": model.stats["trained_over"],
                  "basis_size": model.stats["basis_size"], "basis_snapshots": model.stats["basis_snapshots"],
                  "condition": condition, "finals": finals}))
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--system", default="paper")
    parser.add_argument("--mesh", default="coarse", choices=["coarse", "medium", "fine"])
    parser.add_argument("--threads", type=int, default=1, help="BLAS and PARDISO threads of the builds (default 1)")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    from feedtherm.constants import cache_root
    from feedtherm.models.fem.geometry import mesh_cache_path, mesh_system
    from feedtherm.system.load import load_system

    system = load_system(args.system).system
    mesh = mesh_cache_path(system, args.mesh)
    if not mesh.exists():
        mesh_system(system, args.mesh)
    threads = str(args.threads)
    results = {}
    for training in ("description", "batch"):
        with tempfile.TemporaryDirectory() as cache:
            target = Path(cache) / mesh.relative_to(cache_root())
            target.parent.mkdir(parents=True)
            shutil.copy2(mesh, target)
            env = {**os.environ, "FEEDTHERM_CACHE": cache, "OPENBLAS_NUM_THREADS": threads, "MKL_NUM_THREADS": threads,
                   "OMP_NUM_THREADS": threads}
            done = subprocess.run([sys.executable, "-c", CHILD, args.system, args.mesh, training], env=env,
                                  capture_output=True, text=True, check=True)
            result = json.loads(done.stdout.strip().splitlines()[-1])
            files = list((Path(cache) / "projections").glob("*.npz"))
            result["projection_MB"] = round(sum(f.stat().st_size for f in files) / 1e6, 1)
            results[training] = result
    a, b = results["description"]["finals"], results["batch"]["finals"]
    figures = {"machine": f"{platform.machine()}, {platform.python_implementation()} {platform.python_version()}",
               "system": args.system, "mesh": args.mesh, "threads": args.threads, **results,
               "largest_difference_K": round(max(abs(a[n] - b[n]) for n in a if n.startswith("T")), 5),
               "difference_D_um": round(abs(a["D_um"] - b["D_um"]), 5)}
    print(json.dumps(figures, indent=2) if args.json else "\n".join(f"{k:22s} {v}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
