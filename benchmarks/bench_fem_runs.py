"""Benchmark of the FE runs of one description in one process: what the registry's kept model saves.

Run:  .venv/bin/python benchmarks/bench_fem_runs.py [--mesh coarse] [--duration 600] [--conditions I,II,III,IV,V]
      .venv/bin/python benchmarks/bench_fem_runs.py --fresh      # each run builds its own FE model

The runs of a command on one description (``validate --model fem``'s five conditions, a
calibration point's conditions) build the FE model, its contacts at every position and its
elastic factor once: the registry keeps the last model built (models/registry.py,
``ModelEntry.build_options``).  ``--fresh`` drops it before each run, as every run built its
own before.  Prints each run's wall time [s], the total, the FE builds counted and the peak
memory, as JSON with ``--json``.
"""

from __future__ import annotations

import argparse
import json
import platform
import resource
import time

from feedtherm.models.fem import bench
from feedtherm.models.registry import forget_built_models
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh", default="coarse", choices=["coarse", "medium", "fine"])
    parser.add_argument("--duration", type=float, default=600.0, help="each run's length [s] (default 600)")
    parser.add_argument("--conditions", default="I,II,III,IV,V")
    parser.add_argument("--fresh", action="store_true", help="drop the kept FE model before each run")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    loaded = load_system("paper")
    builds = []
    original = bench.FemDiscretization.__init__

    def counted(self, *a, **k):
        builds.append(1)
        original(self, *a, **k)

    bench.FemDiscretization.__init__ = counted
    runs = {}
    started = time.perf_counter()
    for condition in args.conditions.split(","):
        if args.fresh:
            forget_built_models()
        t0 = time.perf_counter()
        simulate(loaded, condition=condition, model="fem", mesh=args.mesh, duration=args.duration)
        runs[condition] = round(time.perf_counter() - t0, 2)
    figures = {"machine": f"{platform.machine()}, {platform.python_implementation()} {platform.python_version()}",
               "mesh": args.mesh, "duration_s": args.duration, "fresh": args.fresh, "run_wall_s": runs,
               "total_wall_s": round(time.perf_counter() - started, 2), "fe_builds": len(builds),
               "peak_rss_MB": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1)}
    print(json.dumps(figures, indent=2) if args.json else "\n".join(f"{k:14s} {v}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
