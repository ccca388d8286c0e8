"""Benchmark of the commands a user types: wall time end to end, median of five (issue 13).

Run:  .venv/bin/python benchmarks/bench_cli.py [--repeat 5]

Each command runs in a child process (`python -m feedtherm ...`), so the figure includes
the interpreter's start, every import, loading the description and writing the outputs.
Printed and written as JSON to benchmarks/results/cli.json.
"""

from __future__ import annotations

import argparse
import json
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from datetime import date
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "results"


def commands(out: str) -> dict[str, list[str]]:
    return {
        "feedtherm --help": ["--help"],
        "feedtherm heat --condition I": ["heat", "paper", "--condition", "I"],
        "feedtherm run --condition I --no-plots": ["run", "paper", "--condition", "I", "--no-plots", "--out", out],
        "feedtherm run --condition I": ["run", "paper", "--condition", "I", "--out", out],
        # refused on bad input (exit 2): the start of a study's command, before any run
        "feedtherm compensate --sensors T9 (refused)": ["compensate", "paper", "--sensors", "T9", "--out", out + "/c"],
    }


#: Commands that end with another exit code than 0 by design.
EXIT_CODES = {"feedtherm compensate --sensors T9 (refused)": 2}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    figures = {"date": date.today().isoformat(),
               "machine": f"{platform.machine()}, {platform.python_implementation()} {platform.python_version()}",
               "repeat": args.repeat, "median_s": {}, "min_s": {}}
    with tempfile.TemporaryDirectory() as out:
        for name, arguments in commands(out).items():
            times = []
            for _ in range(args.repeat):
                started = time.perf_counter()
                done = subprocess.run([sys.executable, "-m", "feedtherm", *arguments], stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL)
                if done.returncode != EXIT_CODES.get(name, 0):
                    raise SystemExit(f"{name}: exit {done.returncode}")
                times.append(time.perf_counter() - started)
            figures["median_s"][name] = round(statistics.median(times), 3)
            figures["min_s"][name] = round(min(times), 3)
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "cli.json").write_text(json.dumps(figures, indent=2))
    print(json.dumps(figures, indent=2))


if __name__ == "__main__":
    main()
