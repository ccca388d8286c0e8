"""Benchmark of the batch execution layer: runs per second of `feedtherm sweep`, serial and on a
local Dask cluster of N worker processes, and whether the CSVs are byte-identical.

Run:  .venv/bin/python benchmarks/bench_batch.py [--workers 2] [--repeat 2] [--duration 3600] [--motion resolved]

Each figure is the command as a user types it, in a child process (interpreter, imports, the
cluster's start-up, the files): the wall time from start to exit, best of --repeat.  The grid is
12 fast-model points (screw 400-900 rpm x 2 ambients, nut 360 rpm); --duration and --motion set
the work per point (3,600 s position-resolved: about a second a point on the project's machine,
more at the higher speeds).  The in-process time of one point (650 rpm) is measured too.
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

GRID = ["--screw-rpm", "400:900:100", "--nut-rpm", "360", "--ambient", "20,25"]
POINTS = 12


def sweep(out: Path, duration: float, motion: str, extra: list[str]) -> float:
    env = {k: v for k, v in os.environ.items() if k != "DASK_SCHEDULER_ADDRESS"}
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "feedtherm", "sweep", *GRID, "--duration", f"{duration:g}", "--motion", motion,
                    "--out", str(out), *extra], check=True, capture_output=True, text=True, env=env)
    return time.perf_counter() - start


def one_point(duration: float, motion: str) -> float:
    from feedtherm.simulate import simulate
    from feedtherm.system.load import load_system
    from feedtherm.system.variants import with_condition

    variant = with_condition(load_system("paper"), "sweep", 650.0, 360.0, 20.0, duration)
    simulate(variant, condition="sweep", duration=duration, motion=motion)  # imports, caches
    start = time.perf_counter()
    simulate(variant, condition="sweep", duration=duration, motion=motion)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--duration", type=float, default=3600.0)
    parser.add_argument("--motion", choices=["resolved", "averaged"], default="resolved")
    args = parser.parse_args()
    point = one_point(args.duration, args.motion)
    with tempfile.TemporaryDirectory() as tmp:
        serial = min(sweep(Path(tmp) / "serial", args.duration, args.motion, []) for _ in range(args.repeat))
        parallel = min(sweep(Path(tmp) / "parallel", args.duration, args.motion, ["--workers", str(args.workers)])
                       for _ in range(args.repeat))
        identical = (Path(tmp) / "serial" / "sweep.csv").read_bytes() == \
            (Path(tmp) / "parallel" / "sweep.csv").read_bytes()
    result = {
        "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "machine": platform.machine(),
        "cpus": os.cpu_count(), "python": platform.python_version(), "points": POINTS,
        "duration_s": args.duration, "motion": args.motion, "one_point_s": round(point, 3), "workers": args.workers,
        "serial_wall_s": round(serial, 2), "parallel_wall_s": round(parallel, 2),
        "serial_runs_per_s": round(POINTS / serial, 3), "parallel_runs_per_s": round(POINTS / parallel, 3),
        "speed_up": round(serial / parallel, 2), "csv_identical": identical,
    }
    for key, value in result.items():
        print(f"{key:>20}: {value}")
    out = Path(__file__).parent / "results"
    out.mkdir(exist_ok=True)
    (out / "bench_batch.json").write_text(json.dumps(result, indent=2) + "\n")


if __name__ == "__main__":
    main()
