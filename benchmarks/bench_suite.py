"""Benchmark of the test suite: `make test`'s pytest command, wall time and its slowest tests (issue 36).

Run:  .venv/bin/python benchmarks/bench_suite.py [--hog N] [--workers 2] [--slowest 30]

The suite runs from this checkout exactly as `make test` runs it (``python -m pytest -n 2
--dist loadscope``), with an empty ``FEEDTHERM_CACHE`` (a temporary folder: every mesh, basis and
pint file is built as on a fresh clone).  ``--hog N`` starts N CPU-bound processes beside it for
the whole run (a compile, a browser's tab, another job on a 2-core laptop) and stops them after.

Prints the wall time, the tests passed and the slowest tests, and writes them as JSON to
benchmarks/results/suite.json (``suite_hog<N>.json`` with ``--hog``), pytest's whole output beside
it (``.log``: a failure's report).  Takes 10-25 minutes; run
nothing else beside it but its own hogs.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import os
import platform
import re
import subprocess
import sys
import tempfile
import time
from datetime import datetime, timezone
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "benchmarks" / "results"
DURATION = re.compile(r"^\s*([0-9.]+)s (setup|call|teardown)\s+(\S+)")
PASSED = re.compile(r"(\d+) passed")


def _hog(stop) -> None:
    """Busy arithmetic until ``stop`` is set: one core's worth of load."""
    x = 0
    while not stop.is_set():
        for _ in range(100_000):
            x = (x * 1103515245 + 12345) & 0xFFFFFFFF


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--hog", type=int, default=0, metavar="N", help="CPU-bound processes beside the suite")
    parser.add_argument("--workers", type=int, default=2, help="pytest-xdist processes (make test: 2)")
    parser.add_argument("--slowest", type=int, default=30, help="how many of the slowest tests to report")
    args = parser.parse_args()
    stop = multiprocessing.Event()
    hogs = [multiprocessing.Process(target=_hog, args=(stop,), daemon=True) for _ in range(args.hog)]
    for hog in hogs:
        hog.start()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                            text=True).stdout.strip()
    try:
        with tempfile.TemporaryDirectory(prefix="feedtherm-suite-cache-") as cache:
            env = {**os.environ, "FEEDTHERM_CACHE": cache}
            command = [sys.executable, "-m", "pytest", "-n", str(args.workers), "--dist", "loadscope",
                       f"--durations={args.slowest}", "-q", "-p", "no:cacheprovider"]
            start = time.perf_counter()
            result = subprocess.run(command, cwd=ROOT, env=env, capture_output=True, text=True)
            wall = time.perf_counter() - start
            load = os.getloadavg()
    finally:
        stop.set()
        for hog in hogs:
            hog.join(timeout=5)
    lines = result.stdout.splitlines()
    slowest = [{"seconds": float(m.group(1)), "phase": m.group(2), "test": m.group(3)}
               for m in map(DURATION.match, lines) if m]
    passed = PASSED.search(lines[-1] if lines else "")
    figures = {
        "date": datetime.now(timezone.utc).isoformat(timespec="minutes"),
        "commit": commit,
        "machine": f"{platform.machine()}, {os.cpu_count()} CPUs, {platform.python_implementation()} "
                   f"{platform.python_version()}",
        "command": " ".join(["python", *command[1:]]),
        "hogs": args.hog,
        "exit_code": result.returncode,
        "wall_s": round(wall, 1),
        "passed": int(passed.group(1)) if passed else None,
        "last_line": lines[-1] if lines else "",
        "load_average_at_end": [round(v, 2) for v in load],
        "slowest": slowest,
    }
    RESULTS.mkdir(parents=True, exist_ok=True)
    name = f"suite_hog{args.hog}" if args.hog else "suite"
    (RESULTS / f"{name}.json").write_text(json.dumps(figures, indent=2) + "\n", encoding="utf-8")
    (RESULTS / f"{name}.log").write_text(result.stdout + result.stderr, encoding="utf-8")
    print(f"test suite at {commit}, {args.workers} workers, {args.hog} CPU hog(s) beside it: "
          f"{figures['last_line']} ({wall:.1f} s wall)")
    for i, row in enumerate(slowest, 1):
        print(f"  {i:2d} {row['seconds']:7.2f} s {row['phase']:8s} {row['test']}")
    if result.returncode != 0:
        print(f"the suite failed: pytest's report in {RESULTS / name}.log", file=sys.stderr)
        sys.exit(result.returncode)


if __name__ == "__main__":
    main()
