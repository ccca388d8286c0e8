"""Benchmark of the fast model: wall time and peak memory of full 10,800 s runs.

Run:  .venv/bin/python benchmarks/bench_fast.py   (or: make bench)

Reports, for the position-resolved model (>= 20 steps per stroke) on the paper's bench:
one run of condition I, then all five conditions in sequence, with the time step, the
number of steps and the number of unknowns.  Each figure is the best of --repeat runs.
"""

from __future__ import annotations

import argparse
import json
import platform
import resource
import time

from feedtherm.plan import with_mode
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system


def timed(fn, repeat: int):
    best, result = float("inf"), None
    for _ in range(repeat):
        start = time.perf_counter()
        result = fn()
        best = min(best, time.perf_counter() - start)
    return best, result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--mode", default="physics", choices=["physics", "paper"])
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")
    args = parser.parse_args()
    loaded = load_system("paper")
    simulate(loaded, condition="I", duration=60.0)  # warm caches (imports, CoolProp)

    loaded = with_mode(loaded, args.mode)
    one, run = timed(lambda: simulate(loaded, condition="I"), args.repeat)
    all_five, runs = timed(lambda: [simulate(loaded, condition=c) for c in loaded.system.conditions],
                           args.repeat)
    figures = {
        "machine": f"{platform.processor() or platform.machine()}, {platform.python_implementation()} {platform.python_version()}",
        "mode": args.mode,
        "condition_I_wall_s": round(one, 3),
        "all_five_wall_s": round(all_five, 3),
        "time_step_s": {c: round(r.info["time_step_s"], 4) for c, r in zip(loaded.system.conditions, runs)},
        "steps": {c: r.info["steps"] for c, r in zip(loaded.system.conditions, runs)},
        "unknowns": run.info["unknowns"],
        "screw_cells_x_rings": f'{run.info["screw_cells"]} x {run.info["screw_rings"]}',
        "energy_balance_error_I": run.energy.relative_error,
        "peak_rss_MB": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1),
    }
    if args.json:
        print(json.dumps(figures, indent=2))
        return
    print("feedtherm fast model, paper bench, 10,800 s per run, position-resolved")
    for key, value in figures.items():
        print(f"  {key:24s} {value}")


if __name__ == "__main__":
    main()
