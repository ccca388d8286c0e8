"""What the thermoelastic part costs the FE model's run: wall time and peak memory, paired A/B.

Run (the machine otherwise idle; every run is a whole `feedtherm run` in a child process):

    flock /tmp/feedtherm-bench.lock .venv/bin/python benchmarks/bench_thermoelastic.py --mesh fine \\
        --baseline f14b9ba --pairs 2

``--baseline`` is a commit before the FE model solved displacements (f14b9ba: D was the 1-D
integral of the screw's temperatures): it is checked out into a temporary git worktree and run
with this venv (``PYTHONPATH`` at its ``src``).  The two commands run in turn, A B A B …, so a
drift of the machine's speed falls on both; each pair gives a ratio.  Reported per command: the
median wall time and peak resident memory (the child's ``ru_maxrss``), and from the new run's
``summary.json`` the thermoelastic part's own timers (assembly, factorisation, reading rows,
fields) and the size of its factorisation.  Written to benchmarks/results/thermoelastic_<mesh>.json.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = Path(__file__).resolve().parent / "results"


def child_peak_mb(command: list[str], env: dict, cwd: Path) -> tuple[float, float]:
    """Wall time and peak memory of one run, measured in a fresh grandchild (so every run's peak is its own)."""
    probe = ("import json, resource, subprocess, sys, time\n"
             "t = time.perf_counter(); subprocess.run(sys.argv[1:], check=True, stdout=subprocess.DEVNULL)\n"
             "print(json.dumps([time.perf_counter() - t, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024]))")
    out = subprocess.run([sys.executable, "-c", probe, *command], check=True, env=env, cwd=cwd,
                         capture_output=True, text=True).stdout
    wall, peak = json.loads(out.strip().splitlines()[-1])
    return wall, peak


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--mesh", default="fine", choices=["coarse", "medium", "fine"])
    parser.add_argument("--condition", default="I")
    parser.add_argument("--baseline", default="f14b9ba", help="a commit before the thermoelastic part")
    parser.add_argument("--pairs", type=int, default=2)
    args = parser.parse_args()
    run = ["-m", "feedtherm", "run", "--model", "fem", "--mesh", args.mesh, "--condition", args.condition,
           "--no-plots"]
    with tempfile.TemporaryDirectory() as scratch:
        scratch = Path(scratch)
        base = scratch / "baseline"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(base), args.baseline],
                       check=True, capture_output=True)
        try:
            commands = {
                "with thermoelasticity": ([sys.executable, *run, "--out", str(scratch / "new")],
                                          {**os.environ, "PYTHONPATH": str(ROOT / "src")}),
                f"baseline {args.baseline}": ([sys.executable, *run, "--out", str(scratch / "old")],
                                              {**os.environ, "PYTHONPATH": str(base / "src")}),
            }
            figures = {name: {"wall_s": [], "peak_MB": []} for name in commands}
            for _ in range(args.pairs):
                for name, (command, env) in commands.items():
                    wall, peak = child_peak_mb(command, env, scratch)
                    figures[name]["wall_s"].append(round(wall, 1))
                    figures[name]["peak_MB"].append(round(peak, 1))
                    print(name, figures[name], flush=True)
            summary = json.loads((scratch / "new" / "summary.json").read_text())
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(base)], check=False,
                           capture_output=True)
    new, old = (figures[name] for name in commands)
    result = {
        "command": "feedtherm " + " ".join(run[2:]), "pairs": args.pairs, "baseline": args.baseline,
        "runs": figures,
        "median_wall_s": {name: statistics.median(f["wall_s"]) for name, f in figures.items()},
        "median_peak_MB": {name: statistics.median(f["peak_MB"]) for name, f in figures.items()},
        "wall_ratio_per_pair": [round(a / b, 3) for a, b in zip(new["wall_s"], old["wall_s"])],
        "peak_increase_MB_per_pair": [round(a - b, 1) for a, b in zip(new["peak_MB"], old["peak_MB"])],
        "thermoelastic_stats": {k: v for k, v in summary.get("mesh", {}).items() if k.startswith("elastic")},
    }
    RESULTS.mkdir(exist_ok=True)
    path = RESULTS / f"thermoelastic_{args.mesh}.json"
    path.write_text(json.dumps(result, indent=2))
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
