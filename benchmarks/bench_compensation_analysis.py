"""Benchmark of what `feedtherm compensate` does after its cycles are simulated: sensor selection,
the laws' fits and judgements, the Kalman filter, the files.

Run:  .venv/bin/python benchmarks/bench_compensation_analysis.py [--sets FILE] [--repeat 3] [--json]

With two workers the study's runs share both cores, but what follows them runs in the command's
own process while the workers stand idle.  This script times that part alone: the study's
simulated sets (`analysis.compensation.data.simulate_sets`, for ``compensate paper --sensors 3``)
are made once, serially, and kept in ``--sets`` (default: ``benchmarks/results/compensation_sets.pickle``);
each repeat then runs the whole command in this process with the sets read back instead of
simulated.  The figure is the best of ``--repeat`` [s].  Delete the file after a change to the
models: it holds their results.

Run it at another commit with ``PYTHONPATH=<worktree>/src`` (and the same ``--sets``) to compare.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import pickle
import platform
import tempfile
import time
from pathlib import Path

from feedtherm.analysis.compensation import data, study
from feedtherm.cli import main as feedtherm

ROOT = Path(__file__).resolve().parent
ARGUMENTS = ["compensate", "paper", "--sensors", "3"]


def command(folder: Path) -> float:
    """Wall time [s] of ``feedtherm compensate paper --sensors 3`` in this process, its output in ``folder``."""
    with contextlib.redirect_stdout(io.StringIO()):
        started = time.perf_counter()
        code = feedtherm([*ARGUMENTS, "--out", str(folder)])
        wall = time.perf_counter() - started
    if code:
        raise SystemExit(f"feedtherm {' '.join(ARGUMENTS)} failed ({code})")
    return wall


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sets", type=Path, default=ROOT / "results" / "compensation_sets.pickle")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")
    args = parser.parse_args()
    simulate = data.simulate_sets

    def kept(*arguments, **options):
        if not args.sets.exists():
            args.sets.parent.mkdir(parents=True, exist_ok=True)
            args.sets.write_bytes(pickle.dumps(simulate(*arguments, **options)))
        return pickle.loads(args.sets.read_bytes())

    study.simulate_sets = kept  # what run_study calls
    with tempfile.TemporaryDirectory(prefix="feedtherm-analysis-") as folder:
        first = command(Path(folder) / "first")  # simulates the sets if they are not kept yet
        walls = [command(Path(folder) / f"run{i}") for i in range(args.repeat)]
    figures = {
        "machine": f"{platform.processor() or platform.machine()}, {platform.python_implementation()} "
                   f"{platform.python_version()}",
        "command": " ".join(ARGUMENTS),
        "first_s": round(first, 2),
        "analysis_s": round(min(walls), 2),
        "walls_s": [round(w, 2) for w in walls],
    }
    if args.json:
        print(json.dumps(figures, indent=2))
        return
    print(f"feedtherm {figures['command']}, its simulated sets read back ({figures['machine']}): "
          f"{figures['analysis_s']} s, best of {args.repeat} ({', '.join(map(str, figures['walls_s']))} s)")


if __name__ == "__main__":
    main()
