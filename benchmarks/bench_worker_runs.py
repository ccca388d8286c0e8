"""Benchmark of one run's time in the command's own process and in a local Dask worker.

Run:  flock /tmp/feedtherm-bench.lock .venv/bin/python benchmarks/bench_worker_runs.py
          [--model reduced|fast] [--mesh medium] [--conditions I,II,IV] [--repeat 6]
          [--dask-environment]

The calibration's runs (cycle-averaged, 60 s steps, finals only: ``calibration._calibration_run``)
of the paper bench in physics mode, each condition ``--repeat`` times: first one after another in
this process, then on a local cluster of two workers (``--workers 2``), each run timed inside the
process that runs it.  A worker's runs should cost what this process's do; where they cost more,
the worker's environment is the suspect (docs/scale-out.md).  ``--dask-environment`` starts the
workers with Dask's whole pre-spawn environment, ``MALLOC_TRIM_THRESHOLD_`` included, as before
feedtherm dropped it (``execution.UNSET_WORKER_ENVIRONMENT``).  Run this script with
``MALLOC_TRIM_THRESHOLD_=65536`` in the environment to see that variable's cost in this process.

Prints the median run [s] in each place, the batches' wall times and writes them to
``benchmarks/results/worker_runs_<model>.json``.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import time
from pathlib import Path

from feedtherm.analysis import execution
from feedtherm.analysis.calibration import _CalibrationRun, _calibration_run
from feedtherm.analysis.execution import Execution, kept_open, run_ordered
from feedtherm.plan import with_mode
from feedtherm.system.load import load_system

RESULTS = Path(__file__).parent / "results"


def timed_run(run: _CalibrationRun) -> tuple[int, float]:
    """The process that ran it and the run's wall time [s], measured where it ran."""
    started = time.perf_counter()
    _calibration_run(run)
    return os.getpid(), time.perf_counter() - started


def batch(runs: list[_CalibrationRun], running: Execution) -> tuple[float, list[float], int]:
    """Wall time of the batch, each run's own time, and how many processes ran them."""
    list(run_ordered(timed_run, runs[:2], execution=running))  # each process reads the projection first
    started = time.perf_counter()
    results = [result for _, result in run_ordered(timed_run, runs, execution=running)]
    wall = time.perf_counter() - started
    return wall, [seconds for _, seconds in results], len({pid for pid, _ in results})


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--model", default="reduced")
    parser.add_argument("--mesh", default="medium", help="the FE mesh of a reduced or FE model")
    parser.add_argument("--conditions", default="I,II,IV")
    parser.add_argument("--repeat", type=int, default=6)
    parser.add_argument("--dask-environment", action="store_true",
                        help="start the workers with Dask's whole pre-spawn environment")
    args = parser.parse_args()
    if args.dask_environment:
        execution.UNSET_WORKER_ENVIRONMENT = ()
    loaded = with_mode(load_system("paper"), "physics")
    mesh = None if args.model == "fast" else args.mesh
    runs = [_CalibrationRun(loaded, c, model=args.model, mesh=mesh) for c in args.conditions.split(",")] * args.repeat

    with kept_open(Execution()) as running:
        serial_wall, serial_runs, _ = batch(runs, running)
    with kept_open(Execution(workers=2)) as running:
        workers_wall, worker_runs, processes = batch(runs, running)
    figures = {
        "machine": f"{platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, "
                   f"{platform.python_implementation()} {platform.python_version()}",
        "model": args.model, "mesh": mesh, "runs": len(runs),
        "this_process_MALLOC_TRIM_THRESHOLD_": os.environ.get("MALLOC_TRIM_THRESHOLD_"),
        "workers_with_dask_environment": args.dask_environment,
        "serial": {"wall_s": round(serial_wall, 2), "median_run_s": round(statistics.median(serial_runs), 3)},
        "two_workers": {"wall_s": round(workers_wall, 2), "median_run_s": round(statistics.median(worker_runs), 3),
                        "processes": processes},
    }
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / f"worker_runs_{args.model}.json").write_text(json.dumps(figures, indent=2) + "\n", encoding="utf-8")
    print(json.dumps(figures, indent=2))


if __name__ == "__main__":
    main()
