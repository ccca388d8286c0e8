"""Benchmark of the batch execution layer: runs per second of `feedtherm sweep`, serial and on a
local Dask cluster of N worker processes, and whether the CSVs are byte-identical.

Run:  .venv/bin/python benchmarks/bench_batch.py [--workers 2] [--repeat 2] [--points 12] [--duration 3600]
      [--motion resolved]

Two figures per execution, both from the command as a user types it, in a child process:

- **whole command**: the wall time from start to exit (interpreter, imports, the cluster's
  start-up, the files), best of --repeat, and the points divided by it;
- **steady state**: runs per second while every process is busy, without the fixed costs before
  the first run and after the last and without the ragged end where one process has no point
  left: ``(points - 2w) / (t[points - w] - t[w])``, where ``t[k]`` is when the k-th point
  finished and w the number of processes running points (1 serially, --workers on the
  cluster).  A point counts as finished when its record appears in ``<out>/.sweep-partial/``
  (the sweep keeps each point there at once, for --resume); the folder is polled every 10 ms.

The grid is --points fast-model points (--points / 2 screw speeds evenly from 400 to 900 rpm x
2 ambients, nut 360 rpm); --duration and --motion set the work per point (3,600 s
position-resolved: about 1.3 s a point on the project's machine, more at the higher speeds).
The in-process time of one point (650 rpm) is measured too.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

PARTIAL_DIR = ".sweep-partial"
POLL_S = 0.01


def grid(points: int) -> list[str]:
    speeds = points // 2
    values = [round(400 + 500 * i / (speeds - 1)) for i in range(speeds)] if speeds > 1 else [650]
    return ["--screw-rpm", ",".join(str(v) for v in values), "--nut-rpm", "360", "--ambient", "20,25"]


def sweep(out: Path, points: int, duration: float, motion: str, extra: list[str], processes: int = 1
          ) -> tuple[float, float]:
    """(wall time [s], steady runs per second) of one sweep into ``out``."""
    env = {k: v for k, v in os.environ.items() if k != "DASK_SCHEDULER_ADDRESS"}
    finished: dict[str, float] = {}
    start = time.perf_counter()
    process = subprocess.Popen([sys.executable, "-m", "feedtherm", "sweep", *grid(points), "--duration",
                                f"{duration:g}", "--motion", motion, "--out", str(out), *extra],
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=env)
    while process.poll() is None:
        try:
            names = os.listdir(out / PARTIAL_DIR)
        except OSError:
            names = []
        now = time.perf_counter()
        for name in names:
            if len(name) == 69 and name.endswith(".json"):  # a point's record, not sweep.json
                finished.setdefault(name, now)
        time.sleep(POLL_S)
    wall = time.perf_counter() - start
    if process.returncode != 0:
        raise SystemExit(f"the sweep failed: {process.stderr.read()}")
    if len(finished) != points:
        raise SystemExit(f"saw {len(finished)} of {points} points finish; is the run too short to poll?")
    times = sorted(finished.values())  # times[k - 1]: when the k-th point finished
    return wall, (points - 2 * processes) / (times[points - processes - 1] - times[processes - 1])


def one_point(duration: float, motion: str) -> float:
    from feedtherm.simulate import simulate
    from feedtherm.system.load import load_system
    from feedtherm.system.variants import with_condition

    variant = with_condition(load_system("paper"), "sweep", 650.0, 360.0, 20.0, duration)
    simulate(variant, condition="sweep", duration=duration, motion=motion)  # imports, caches
    start = time.perf_counter()
    simulate(variant, condition="sweep", duration=duration, motion=motion)
    return time.perf_counter() - start


def best(runs: list[tuple[float, float]]) -> tuple[float, float]:
    """The shortest wall time and the highest steady rate of the repeats."""
    return min(r[0] for r in runs), max(r[1] for r in runs)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--points", type=int, default=12, help="an even number of grid points (default 12)")
    parser.add_argument("--duration", type=float, default=3600.0)
    parser.add_argument("--motion", choices=["resolved", "averaged"], default="resolved")
    args = parser.parse_args()
    if args.points < 4 * args.workers or args.points % 2:
        parser.error("--points: an even number of at least 4 per worker")
    point = one_point(args.duration, args.motion)
    with tempfile.TemporaryDirectory() as tmp:
        serial = best([sweep(Path(tmp) / "serial", args.points, args.duration, args.motion, [])
                       for _ in range(args.repeat)])
        parallel = best([sweep(Path(tmp) / "parallel", args.points, args.duration, args.motion,
                               ["--workers", str(args.workers)], args.workers) for _ in range(args.repeat)])
        identical = (Path(tmp) / "serial" / "sweep.csv").read_bytes() == \
            (Path(tmp) / "parallel" / "sweep.csv").read_bytes()
    result = {
        "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "machine": platform.machine(),
        "cpus": os.cpu_count(), "python": platform.python_version(), "points": args.points,
        "duration_s": args.duration, "motion": args.motion, "one_point_s": round(point, 3), "workers": args.workers,
        "serial_wall_s": round(serial[0], 2), "parallel_wall_s": round(parallel[0], 2),
        "serial_runs_per_s": round(args.points / serial[0], 3),
        "parallel_runs_per_s": round(args.points / parallel[0], 3),
        "speed_up": round(serial[0] / parallel[0], 2),
        "serial_steady_runs_per_s": round(serial[1], 3), "parallel_steady_runs_per_s": round(parallel[1], 3),
        "steady_speed_up": round(parallel[1] / serial[1], 2), "csv_identical": identical,
    }
    for key, value in result.items():
        print(f"{key:>26}: {value}")
    out = Path(__file__).parent / "results"
    out.mkdir(exist_ok=True)
    (out / f"bench_batch_{args.points}x{args.duration:g}.json").write_text(json.dumps(result, indent=2) + "\n")


if __name__ == "__main__":
    main()
