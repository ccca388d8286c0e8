"""Benchmark of the batch commands issue 36 sets aims for: `compensate` and `uncertainty`, end to end.

Run:  .venv/bin/python benchmarks/bench_batches.py [--repeat 1] [--only compensate|compensate_two_cores|uncertainty]

Each command runs in a child process (`python -m feedtherm ...`, output to a temporary folder),
as a user types it; the figure is the whole command's wall time, the median of --repeat runs:

- ``compensate paper --sensors 3`` (serial, the command's default) and with ``--workers 2``
  (both cores; aim <= 30 s);
- ``uncertainty paper --workers 2`` (the command's defaults on both cores: 128 points, Sobol'
  base 64; aim <= 3 min).

Printed and written as JSON to benchmarks/results/batches.json.  Takes 6 minutes per repeat;
run nothing else beside it.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from datetime import datetime, timezone
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "benchmarks" / "results"
COMMANDS = {
    "compensate": ["compensate", "paper", "--sensors", "3"],
    "compensate_two_cores": ["compensate", "paper", "--sensors", "3", "--workers", "2"],
    "uncertainty": ["uncertainty", "paper", "--workers", "2"],
}


def timed(arguments: list[str]) -> tuple[float, str]:
    """Wall time [s] of one run of ``feedtherm <arguments>`` in a child process, and its last line."""
    with tempfile.TemporaryDirectory(prefix="feedtherm-batch-") as folder:
        start = time.perf_counter()
        result = subprocess.run([sys.executable, "-m", "feedtherm", *arguments, "--out", str(Path(folder) / "out")],
                                capture_output=True, text=True, cwd=folder)
        wall = time.perf_counter() - start
    if result.returncode != 0:
        sys.exit(f"feedtherm {' '.join(arguments)} failed ({result.returncode}): {result.stderr[-2000:]}")
    lines = result.stdout.strip().splitlines()
    return wall, lines[-1] if lines else ""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--only", choices=sorted(COMMANDS), help="one command only")
    args = parser.parse_args()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                            text=True).stdout.strip()
    figures = {"date": datetime.now(timezone.utc).isoformat(timespec="minutes"), "commit": commit,
               "machine": f"{platform.machine()}, {os.cpu_count()} CPUs, {platform.python_implementation()} "
                          f"{platform.python_version()}", "commands": {}}
    for name, arguments in COMMANDS.items():
        if args.only and name != args.only:
            continue
        walls, last = [], ""
        for _ in range(args.repeat):
            wall, last = timed(arguments)
            walls.append(round(wall, 1))
        figures["commands"][name] = {"command": "feedtherm " + " ".join(arguments), "walls_s": walls,
                                     "median_s": round(statistics.median(walls), 1), "last_line": last}
        print(f"feedtherm {' '.join(arguments)}: median {statistics.median(walls):.1f} s of {walls}")
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / "batches.json").write_text(json.dumps(figures, indent=2) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
