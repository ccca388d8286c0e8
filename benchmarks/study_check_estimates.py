"""`feedtherm check`'s time estimates against the runs they estimate (issue 59, item 5).

Run:  .venv/bin/python benchmarks/study_check_estimates.py [--cache DIR] [--only NAME,...]
      .venv/bin/python benchmarks/study_check_estimates.py --calibrate [--fine]

The study: `feedtherm check BENCH [--duration S]` is run first, for every run below, and its
estimate for the run's model, mesh and motion is read from its output; then each run is made as
its own `feedtherm run` process, one at a time, and the whole process's wall time is measured
(and its CPU time, and the load average before it: figures from a busy machine are not a quiet
machine's).  The runs cover both bundled benches: the coarse and medium FE meshes and the fast
model's resolved and averaged motions on each.  By default the cache (FEEDTHERM_CACHE) is a new
empty folder, so that each FE run meshes first, as a first run does and as `check` then says;
``--cache DIR`` uses DIR instead.  Writes benchmarks/results/check_estimates.{csv,md}.  About
6 minutes on an idle 2-core machine.

On a busy machine the wall times are the other processes' as much as the run's: ``--one-thread``
keeps OpenBLAS and MKL on one thread, whose spinning threads otherwise take CPU time from the
run, so that the CPU time column is about what the run would take alone (a quiet machine's two
threads make the large meshes' PARDISO factorisations and solves quicker still).

``--calibrate`` measures what feedtherm.plan.cost's FE constants come from, in this process, one
thread (OpenBLAS and MKL), CPU time: the meshing of both benches at each density in an empty
cache (nodes and time), then the FE model's build, elastic readout, a grid position's contacts,
a step matrix's factorisation and a solve with it (coarse and medium; ``--fine`` adds the fine
meshes, several minutes and about 6 GB each); prints the power laws fitted to them beside the
constants in use, and writes benchmarks/results/run_cost_calibration.json.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "benchmarks" / "results"

#: name, bench, the run's selector, duration [s] (None: the test's or condition's own), model, mesh, motion
RUNS = [
    ("paper_fem_coarse", "paper", ["--condition", "I"], 1800.0, "fem", "coarse", "resolved"),
    ("paper_fem_medium", "paper", ["--condition", "I"], 600.0, "fem", "medium", "resolved"),
    ("paper_fast_resolved", "paper", ["--condition", "I"], None, "fast", None, "resolved"),
    ("paper_fast_averaged", "paper", ["--condition", "III"], None, "fast", None, "averaged"),
    ("ballscrew_fem_coarse", "ballscrew_example", ["--condition", "v10"], 180.0, "fem", "coarse", "resolved"),
    ("ballscrew_fem_medium", "ballscrew_example", ["--condition", "v10"], 30.0, "fem", "medium", "resolved"),
    ("ballscrew_fast_resolved", "ballscrew_example", ["--condition", "v10"], 1800.0, "fast", None, "resolved"),
    ("ballscrew_fast_averaged", "ballscrew_example", ["--test", "drift"], None, "fast", None, "averaged"),
]
UNITS = {"s": 1.0, "min": 60.0, "h": 3600.0}


def feedtherm(args: list[str]) -> list[str]:
    return [sys.executable, "-m", "feedtherm", *args]


def check_estimate(bench: str, selector: list[str], duration: float | None, model: str, mesh: str | None,
                   motion: str, env: dict, memo: dict) -> tuple[float, int]:
    """The estimate [s] and steps `feedtherm check` prints for the run."""
    key = (bench, duration)
    if key not in memo:
        args = ["check", bench] + ([] if duration is None else ["--duration", f"{duration:g}"])
        memo[key] = subprocess.run(feedtherm(args), env=env, capture_output=True, text=True, check=True).stdout
    section = {"--condition": "conditions", "--test": "tests", "--cycle": "duty_cycles"}[selector[0]]
    lines = memo[key].splitlines()
    head = next(i for i, line in enumerate(lines) if line.startswith(f"run cost of {section}.{selector[1]} ("))
    line = next(line for line in lines[head + 1:head + 4] if line.strip().startswith(f"--motion {motion}:"))
    steps = int(re.search(r": ([\d,]+) steps", line).group(1).replace(",", ""))
    windows = re.search(r"\(([\d,]+) in the FE and reduced models", line)
    if windows and model in ("fem", "reduced"):  # their resolved motion steps window by window
        steps = int(windows.group(1).replace(",", ""))
    name = model if mesh is None else f"{model} {mesh}"
    found = re.search(rf"(?:about |, ){re.escape(name)} ([\d.]+) (s|min|h)\b", line)
    return float(found.group(1)) * UNITS[found.group(2)], steps


def run_once(bench: str, selector: list[str], duration: float | None, model: str, mesh: str | None,
             motion: str, env: dict, out: Path) -> dict:
    args = ["run", bench, *selector, "--model", model, "--motion", motion]
    if duration is not None:
        args += ["--duration", f"{duration:g}"]
    if mesh is not None:
        args += ["--mesh", mesh]
    command = "feedtherm " + " ".join(args)
    args += ["--out", str(out)]
    load = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.perf_counter()
    subprocess.run(feedtherm(args), env=env, check=True, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - started
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    summary = json.loads((out / "summary.json").read_text())
    return {"command": command, "wall_s": wall, "cpu_s": cpu, "load_before": load, "steps_run": summary.get("steps")}


def study(args) -> None:
    cache = Path(args.cache) if args.cache else Path(tempfile.mkdtemp(prefix="feedtherm-estimates-"))
    env = {**os.environ, "FEEDTHERM_CACHE": str(cache)}
    if args.one_thread:  # CPU time then stands for a quiet machine's wall time (module notes)
        env.update(OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    chosen = [r for r in RUNS if not args.only or r[0] in args.only.split(",")]
    memo: dict = {}
    estimates = {r[0]: check_estimate(*r[1:], env=env, memo=memo) for r in chosen}  # all before any run
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, bench, selector, duration, model, mesh, motion in chosen:
            measured = run_once(bench, selector, duration, model, mesh, motion, env, Path(tmp) / name)
            estimate, steps = estimates[name]
            row = {"run": name, "bench": bench, "model": model if mesh is None else f"{model} {mesh}",
                   "motion": motion, "duration_s": duration, "steps_check": steps, "steps_run": measured["steps_run"],
                   "estimate_s": round(estimate, 1), "measured_wall_s": round(measured["wall_s"], 1),
                   "ratio": round(measured["wall_s"] / estimate, 2), "cpu_s": round(measured["cpu_s"], 1),
                   "cpu_ratio": round(measured["cpu_s"] / estimate, 2), "load_before": round(measured["load_before"], 2),
                   "command": measured["command"]}
            rows.append(row)
            print(f"{name:24s} estimate {row['estimate_s']:7.1f} s  measured {row['measured_wall_s']:7.1f} s "
                  f"(ratio {row['ratio']:.2f}; CPU {row['cpu_s']:.1f} s, {row['cpu_ratio']:.2f}; load {row['load_before']:.2f})",
                  flush=True)
    RESULTS.mkdir(parents=True, exist_ok=True)
    with open(RESULTS / "check_estimates.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    within = sum(0.5 <= r["ratio"] <= 2.0 for r in rows)
    lines = [f"`feedtherm check`'s estimates against the whole `feedtherm run` process, one run at a time "
             f"({'cache ' + str(cache) if args.cache else 'an empty cache: each FE run meshes first'}; "
             f"{'OpenBLAS and MKL on one thread; ' if args.one_thread else ''}"
             f"{os.uname().machine}, {os.cpu_count()} cores); ratio = measured / estimate", "",
             "| run | model | motion | steps | estimate [s] | measured wall [s] | ratio | CPU [s] | load before |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        lines.append(f"| `{r['command']}` | {r['model']} | {r['motion']} | {r['steps_run']:,} | {r['estimate_s']:g} | "
                     f"{r['measured_wall_s']:g} | {r['ratio']:.2f} | {r['cpu_s']:g} | {r['load_before']:.2f} |")
    lines += ["", f"{within} of {len(rows)} within a factor of 2."]
    busy = [r["run"] for r in rows if r["load_before"] > 1.0]
    if busy:
        lines += ["", f"The load average was above 1 before {len(busy)} of the runs ({', '.join(busy)}): other "
                      "processes shared the cores, and those wall times are not the quiet machine's the estimates are for."]
    (RESULTS / "check_estimates.md").write_text("\n".join(lines) + "\n")
    print(f"{within} of {len(rows)} within a factor of 2")
    print(f"written: {RESULTS / 'check_estimates.csv'}, {RESULTS / 'check_estimates.md'}")


# ----------------------------------------------------------------------------- calibration
def _fit(points: list[tuple[float, float]]) -> tuple[float, float]:
    """``a N^b`` by least squares in logs."""
    xs = [math.log(n) for n, _ in points]
    ys = [math.log(t) for _, t in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return math.exp(my - b * mx), b


def calibrate(args) -> None:
    # one thread before numpy, scipy and MKL load: their thread pools read these once
    os.environ.update(OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    import numpy as np
    from threadpoolctl import threadpool_limits

    from feedtherm.models.fem.geometry import mesh_system
    from feedtherm.models.integrator import Integrator
    from feedtherm.models.options import ModelOptions
    from feedtherm.models.registry import model_entry
    from feedtherm.plan import boundary_of, cost
    from feedtherm.system.load import load_system

    clock = time.process_time
    densities = ("coarse", "medium", "fine") if args.fine else ("coarse", "medium")
    benches = {"paper": "I", "ballscrew_example": "v10"}
    os.environ["FEEDTHERM_CACHE"] = tempfile.mkdtemp(prefix="feedtherm-calibrate-")
    records = []
    with threadpool_limits(1):
        for bench, condition in benches.items():
            loaded = load_system(bench)
            system = loaded.system
            for density in densities:
                started = clock()
                mesh = mesh_system(system, density)
                record = {"bench": bench, "mesh": density, "nodes": int(mesh.points.shape[1]), "mesh_s": clock() - started,
                          "predicted_nodes": cost.fem_nodes(system, density),
                          "contact_points": cost.contact_work(system, density)}
                options = ModelOptions(mesh=density)
                started = clock()
                model = model_entry("fem").build(system, options)
                record["build_s"] = clock() - started
                started = clock()
                model.displacement_rows()
                record["readout_s"] = clock() - started
                integrator = Integrator(model, options, None)
                bc = boundary_of(loaded, condition)
                positions = (2, 9, 17)
                started = clock()
                for k in positions:
                    integrator.loads(0, bc, k)
                record["position_s"] = (clock() - started) / len(positions)
                factors, solves = [], []
                rhs = np.random.default_rng(0).random(model.n_nodes)
                for k in positions:
                    started = clock()
                    lu = integrator.factors(0, bc, k, 1.0)
                    factors.append(clock() - started)
                    for _ in range(10):
                        started = clock()
                        lu.solve(rhs)
                        solves.append(clock() - started)
                record["factor_s"] = float(np.median(factors))
                record["solve_s"] = float(np.median(solves))
                records.append(record)
                print(json.dumps({k: round(v, 4) if isinstance(v, float) else v for k, v in record.items()}), flush=True)
                del model, integrator
    laws = {name: _fit([(r["nodes"], r[f"{name}_s"]) for r in records])
            for name in ("mesh", "build", "readout", "factor", "solve")}
    current = {"mesh": cost.FEM_MESH, "build": cost.FEM_BUILD, "readout": cost.FEM_READOUT, "factor": cost.FEM_FACTOR,
               "solve": cost.FEM_SOLVE}
    for name, (a, b) in laws.items():
        print(f"{name:8s} fitted {a:.3g} N^{b:.3f}; in use {current[name][0]:.3g} N^{current[name][1]:.3f}")
    per_point = [r["position_s"] / r["contact_points"] for r in records]
    print(f"position fitted {math.exp(sum(map(math.log, per_point)) / len(per_point)):.3g} s a point "
          f"(spread {min(per_point):.3g}-{max(per_point):.3g}); in use {cost.FEM_POSITION_S_PER_POINT:.3g}")
    print("nodes predicted / meshed: " + ", ".join(f"{r['bench']} {r['mesh']} {r['predicted_nodes'] / r['nodes']:.3f}"
                                                   for r in records))
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / "run_cost_calibration.json").write_text(json.dumps({"records": records, "laws": laws}, indent=2))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cache", help="FEEDTHERM_CACHE for the runs (default: a new empty folder)")
    parser.add_argument("--only", help="comma-separated run names: " + ", ".join(r[0] for r in RUNS))
    parser.add_argument("--one-thread", action="store_true",
                        help="run with OpenBLAS and MKL on one thread: on a busy machine, CPU time then stands "
                             "for a quiet machine's wall time")
    parser.add_argument("--calibrate", action="store_true", help="measure the FE cost constants instead")
    parser.add_argument("--fine", action="store_true", help="with --calibrate: the fine meshes too")
    args = parser.parse_args()
    calibrate(args) if args.calibrate else study(args)


if __name__ == "__main__":
    main()
