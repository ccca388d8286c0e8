"""Benchmark of the reduced model against the full FE model it projects (issue 13).

Run:
    .venv/bin/python benchmarks/bench_reduced.py --mesh coarse|medium|fine [--tolerance 1e-4] [--condition I]
    .venv/bin/python benchmarks/bench_reduced.py --mesh fine --cli [--repeat 5]

Builds the FE model once (the mesh from the cache), then times, on the same model and the
same plan (condition I, 10,800 s, position-resolved, >= 20 steps per stroke):

- the reduced model's basis (snapshots, POD), reading it back from the disk cache (as the next
  run of this model does), its projection, and its run;
- the full FE run (after the reduced model, so that the peak memory measured before it is the
  FE model's and the basis's).

It reports the largest deviation over the whole transient (every sample) of T1-T5 and D
between the two, the basis size, and the wall times.  The figures are printed and written as
JSON to benchmarks/results/reduced_<mesh>_<condition>.json; benchmarks/README.md keeps the
latest.  The fine mesh's full run takes 20-30 min on a 2-core machine.

``--cli`` times the command a user types instead, end to end in a child process (interpreter,
imports, the cached projected model read back, the run, the 19 VTU snapshots written):
``feedtherm run paper --condition <c> --model reduced --mesh <m> --no-plots``.  A first run
fills the caches where needed (its time and what it built are reported apart); then
``--repeat`` runs with the projected model's file in the page cache ("warm") and as many with
that file dropped from it first (``posix_fadvise(DONTNEED)``: "cold", read from the disk;
the libraries stay cached, as after any earlier Python run).  Median and minimum of each, to
benchmarks/results/reduced_cli_<mesh>_<condition>.json.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from datetime import date
from pathlib import Path

import numpy as np

from feedtherm.models import registry
from feedtherm.models.reduced import ProjectedModel, moment_basis
from feedtherm.models.reduced.basis import TIME_CONSTANTS, basis_cache_path, basis_key
from feedtherm.models.reduced.store import projection_cache_path, projection_key
from feedtherm.simulate import execute, plan_run
from feedtherm.system.load import load_system

SENSORS = ["T1", "T2", "T3", "T4", "T5"]
RESULTS = Path(__file__).resolve().parent / "results"


def peak_rss_mb() -> float:
    """The process's peak resident memory so far [MB]."""
    return round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0, 1)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh", default="coarse", choices=["coarse", "medium", "fine"])
    parser.add_argument("--condition", default="I")
    parser.add_argument("--tolerance", type=float, default=1e-4)
    parser.add_argument("--system", default="paper")
    parser.add_argument("--cli", action="store_true", help="time the cached command end to end instead")
    parser.add_argument("--repeat", type=int, default=5, help="--cli: runs of each kind")
    args = parser.parse_args()
    if args.cli:
        return cli(args)

    loaded = load_system(args.system)
    plan = plan_run(loaded, condition=args.condition, model="fem", mesh=args.mesh)
    started = time.perf_counter()
    full = plan.model.build(loaded.system, plan.options)
    build_s = time.perf_counter() - started
    started = time.perf_counter()  # the sliding contacts and exposures at every position (built lazily)
    for k in range(len(full.positions)):
        full.conductance(k)
        full.boundary_basis(k)
    positions_s = time.perf_counter() - started

    # the reduced model first, so that the peak memory after it is the FE model's and the basis's alone
    # (the full run's solver comes after); the first build caches the basis, the next run of this
    # model reads it back
    basis_cache_path(basis_key(full, args.tolerance, TIME_CONSTANTS)).unlink(missing_ok=True)
    started = time.perf_counter()
    basis = moment_basis(full, tolerance=args.tolerance)
    basis_s = time.perf_counter() - started
    basis_peak = peak_rss_mb()
    started = time.perf_counter()
    cached = moment_basis(full, tolerance=args.tolerance)
    cached_s = time.perf_counter() - started
    assert cached.cached and np.array_equal(cached.vectors, basis.vectors)
    started = time.perf_counter()
    reduced = ProjectedModel(full, basis)
    project_s = time.perf_counter() - started
    started = time.perf_counter()
    reduced_run = execute(plan, model=reduced)
    reduced_s = time.perf_counter() - started
    reduced_peak = peak_rss_mb()

    started = time.perf_counter()
    full_run = execute(plan, model=full)
    full_s = time.perf_counter() - started

    deviation = {name: float(np.max(np.abs(reduced_run.sensors[name] - full_run.sensors[name])))
                 for name in SENSORS}
    figures = {
        "date": date.today().isoformat(),
        "machine": f"{platform.machine()}, {platform.python_implementation()} {platform.python_version()}",
        "mesh": args.mesh, "condition": args.condition, "vertices": full.n_nodes,
        "positions": len(full.positions), "steps": full_run.info["steps"],
        "tolerance": args.tolerance, "basis_size": basis.size, "snapshots": basis.snapshots,
        "fe_build_s": round(build_s, 1),
        "fe_positions_s": round(positions_s, 1),
        "full_run_s": round(full_s, 1),
        "basis_s": round(basis_s, 1), "projection_s": round(project_s, 1), "reduced_run_s": round(reduced_s, 1),
        "reduced_total_s": round(basis_s + project_s + reduced_s, 1),
        "basis_cached_read_s": round(cached_s, 2),
        "reduced_total_cached_s": round(cached_s + project_s + reduced_s, 1),
        "speed_up_including_basis": round(full_s / (basis_s + project_s + reduced_s), 1),
        "max_abs_dT_K": {k: round(v, 4) for k, v in deviation.items()},
        "max_abs_dT_all_K": round(max(deviation.values()), 4),
        "max_abs_dD_um": round(float(np.max(np.abs(reduced_run.elongation - full_run.elongation))) * 1e6, 4),
        "energy_balance_error_reduced": reduced_run.energy.relative_error,
        "peak_rss_after_basis_MB": basis_peak,
        "peak_rss_after_reduced_run_MB": reduced_peak,
        "peak_rss_MB": peak_rss_mb(),
    }
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / f"reduced_{args.mesh}_{args.condition}.json").write_text(json.dumps(figures, indent=2))
    print(json.dumps(figures, indent=2))


def _evict(path: Path) -> None:
    """Drop one file's pages from the page cache (only this file: others' timings keep theirs)."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.posix_fadvise(fd, 0, 0, os.POSIX_FADV_DONTNEED)
    finally:
        os.close(fd)


def cli(args) -> None:
    """The module notes' ``--cli``."""
    loaded = load_system(args.system)
    plan = plan_run(loaded, condition=args.condition, model="reduced", mesh=args.mesh)
    options = plan.options
    if args.tolerance != options.reduction_tolerance:
        raise SystemExit("--cli runs the command as a user types it: the default tolerance only")
    command = [sys.executable, "-m", "feedtherm", "run", args.system, "--condition", args.condition,
               "--model", "reduced", "--mesh", args.mesh, "--no-plots"]

    with tempfile.TemporaryDirectory() as out:
        def run() -> tuple[float, dict]:
            started = time.perf_counter()
            subprocess.run([*command, "--out", out], check=True, stdout=subprocess.DEVNULL)
            seconds = time.perf_counter() - started
            return seconds, json.loads((Path(out) / "summary.json").read_text())

        first_s, first = run()
        stats = first["mesh"]  # the model's statistics (summary.json)
        inputs = registry._reduced_inputs(loaded.system, options)
        path = projection_cache_path(projection_key(inputs, options.reduction_tolerance))
        warm, cold = [], []
        for _ in range(args.repeat):
            warm.append(run())
        for _ in range(args.repeat):
            _evict(path)
            cold.append(run())
        written = sum(p.stat().st_size for p in Path(out).iterdir())

    def summary(runs):
        times = [t for t, _ in runs]
        own = [s["wall_time_s"] for _, s in runs]  # the run's own: the model read back, integration, packing
        return {"median_s": round(statistics.median(times), 2), "min_s": round(min(times), 2),
                "run_wall_time_s_median": round(statistics.median(own), 2)}

    figures = {
        "date": date.today().isoformat(),
        "machine": f"{platform.machine()}, {os.cpu_count()} CPUs, {platform.python_implementation()} "
                   f"{platform.python_version()}",
        "command": " ".join(["feedtherm", *command[3:]]),
        "mesh": args.mesh, "condition": args.condition, "repeat": args.repeat,
        "first_run_s": round(first_s, 2),
        "first_run_built": {"projection": not stats.get("projection_cached", False),
                            "basis": not stats.get("basis_cached", False)},
        "basis_size": stats.get("basis_size"),
        "projection_file_MB": round(path.stat().st_size / 1e6, 1),
        "warm": summary(warm),
        "cold_projection_file": summary(cold),
        "files_written_MB": round(written / 1e6, 1),
    }
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / f"reduced_cli_{args.mesh}_{args.condition}.json").write_text(json.dumps(figures, indent=2))
    print(json.dumps(figures, indent=2))


if __name__ == "__main__":
    main()
