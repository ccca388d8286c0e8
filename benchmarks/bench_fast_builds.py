"""Benchmark of what a batch's fast-model runs cost besides their steps: model builds and
cycle-averaged runs over variants of one declared value.

Run:  .venv/bin/python benchmarks/bench_fast_builds.py [--path materials.q345b.conductivity]
      [--values 40:52] [--variants 40] [--repeat 3] [--json]

Two figures, each the best of ``--repeat`` passes over ``--variants`` variants of the paper's
bench (``--path`` set to values spread over ``--values``), in this process:

* a build: the fast model of a variant and its cycle-averaged conductance (what every
  cycle-averaged run of calibration, uncertainty, sweeps and sensitivity studies makes first);
* a run: conditions I, II and IV of a variant, cycle-averaged with calibration's options and
  60 s samples (a calibration's residual).

``--path joints[9].tcr --values 5e-4:2e-3`` varies a value that moves no face of the geometry
either way.  Run it at another commit with ``PYTHONPATH=<worktree>/src`` to compare.
"""

from __future__ import annotations

import argparse
import json
import platform
import time

import numpy as np

from feedtherm.analysis.calibration import CALIBRATION_OPTIONS
from feedtherm.models.options import ModelOptions
from feedtherm.simulate import discretize, execute, plan_run
from feedtherm.system.load import load_system
from feedtherm.system.variants import with_values

CONDITIONS = ("I", "II", "IV")


def best_of(repeat: int, passes) -> float:
    best = float("inf")
    for _ in range(repeat):
        started = time.perf_counter()
        passes()
        best = min(best, time.perf_counter() - started)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--path", default="materials.q345b.conductivity")
    parser.add_argument("--values", default="40:52", help="LOW:HIGH of the values, in SI units")
    parser.add_argument("--variants", type=int, default=40)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    low, high = (float(v) for v in args.values.split(":"))
    loaded = load_system("paper")
    variants = [with_values(loaded, {args.path: float(v)}) for v in np.linspace(low, high, args.variants)]
    execute(plan_run(loaded, condition="I", options=CALIBRATION_OPTIONS, sample_interval=60.0))  # warm-up

    def builds():
        for variant in variants:
            discretize(variant.system, "fast", ModelOptions()).averaged_conductance()

    def runs():
        for variant in variants:
            for condition in CONDITIONS:
                execute(plan_run(variant, condition=condition, options=CALIBRATION_OPTIONS, sample_interval=60.0))

    build = best_of(args.repeat, builds) / len(variants)
    run = best_of(args.repeat, runs) / (len(variants) * len(CONDITIONS))
    figures = {
        "machine": f"{platform.processor() or platform.machine()}, {platform.python_implementation()} "
                   f"{platform.python_version()}",
        "path": args.path, "values": [low, high], "variants": args.variants,
        "build_ms": round(1e3 * build, 1), "cycle_averaged_run_s": round(run, 4),
    }
    if args.json:
        print(json.dumps(figures, indent=2))
        return
    print(f"{args.variants} variants of {args.path} over {low:g}..{high:g}, best of {args.repeat}:")
    print(f"  a build (model and cycle-averaged conductance): {figures['build_ms']} ms")
    print(f"  a cycle-averaged run of I, II or IV:            {figures['cycle_averaged_run_s']} s")


if __name__ == "__main__":
    main()
