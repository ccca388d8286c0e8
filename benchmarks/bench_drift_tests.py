"""Benchmark of a machine's thermal test through the commands (issue 56): wall time end to end.

Run:  .venv/bin/python benchmarks/bench_drift_tests.py [--repeat 3]

On ballscrew_example's ISO 230-3 drift tests (its drift_tests.csv, made by the FE model), each
command in a child process (`python -m feedtherm ...`: interpreter, imports, files), median of the
repeats: a test run as declared, the bench validated (its conditions and its three tests,
cycle-averaged motion), the fit on one test predicting the others, and the compensation study on
the sensors the machine has (defaults, two workers), with the estimate it prints before it starts
beside its wall time.  Printed and written as JSON to benchmarks/results/drift_tests.json.
"""

from __future__ import annotations

import argparse
import json
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time
from datetime import date
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "results"
ESTIMATE = re.compile(r"about ([0-9.]+) min on")


def commands(out: str) -> dict[str, list[str]]:
    return {
        "run --test drift (fast, averaged)": ["run", "ballscrew_example", "--test", "drift", "--motion", "averaged",
                                              "--no-plots", "--out", f"{out}/run"],
        "validate (averaged)": ["validate", "ballscrew_example", "--motion", "averaged", "--out", f"{out}/validate"],
        "calibrate --fit drift, 3 parameters": ["calibrate", "ballscrew_example", "--fit", "drift", "--params",
                                                "ball_nut_torque,front_bearing_preload,chtc_screw", "--out",
                                                f"{out}/calibrate"],
        "compensate --sensors declared --workers 2": ["compensate", "ballscrew_example", "--sensors", "declared",
                                                      "--workers", "2", "--out", f"{out}/compensate"],
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    figures = {"date": date.today().isoformat(),
               "machine": f"{platform.machine()}, {platform.python_implementation()} {platform.python_version()}",
               "repeat": args.repeat, "median_s": {}, "min_s": {}, "estimate_min": {}}
    with tempfile.TemporaryDirectory() as out:
        for name, arguments in commands(out).items():
            times = []
            for _ in range(args.repeat):
                started = time.perf_counter()
                done = subprocess.run([sys.executable, "-m", "feedtherm", *arguments], capture_output=True, text=True)
                if done.returncode != 0:
                    raise SystemExit(f"{name}: exit {done.returncode}: {done.stderr[-500:]}")
                times.append(time.perf_counter() - started)
                found = ESTIMATE.search(done.stdout)
                if found:
                    figures["estimate_min"][name] = float(found.group(1))
            figures["median_s"][name] = round(statistics.median(times), 2)
            figures["min_s"][name] = round(min(times), 2)
            print(f"{name:45s} median {figures['median_s'][name]:7.2f} s  min {figures['min_s'][name]:7.2f} s"
                  + (f"  (estimated {figures['estimate_min'][name] * 60:.0f} s)" if name in figures["estimate_min"] else ""),
                  flush=True)
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "drift_tests.json").write_text(json.dumps(figures, indent=2))


if __name__ == "__main__":
    main()
