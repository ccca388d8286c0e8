"""How the FE run's moving nut is stepped: time, peak memory and difference from the exact motion.

Each option is the whole command ``feedtherm run paper --condition I --model fem --mesh M
--no-plots`` with its own flags, in a fresh child process under ``/usr/bin/time -v`` (wall time and
peak resident memory of the process), one after another.  The exact motion (grid position by grid
position, one factor per position: the package's path before the windows) is the reference: each
other option's final T1-T5 and D, and their largest difference over every 10 s sample, against it.

    .venv/bin/python benchmarks/study_fem_motion_windows.py --mesh medium
    .venv/bin/python benchmarks/study_fem_motion_windows.py --mesh fine --options exact,windows,windows_5s,averaged

Writes ``benchmarks/results/fem_motion_windows_<mesh>.json`` and ``.md``.  The mesh is meshed
before the first option (a throwaway averaged run) so that no option pays for the meshing.
Run it alone: two heavy runs at once make both figures worthless.
"""

from __future__ import annotations

import argparse
import json
import platform
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results"
SENSORS = ["T1", "T2", "T3", "T4", "T5"]

#: option name -> (what it is, the flags it adds to the command)
OPTIONS = {
    "exact": ("exact motion, one PARDISO factor per grid position visited (the reference)", ["--motion", "exact"]),
    "windows": ("windowed motion, windows the table passes in 10 s (the default)", []),
    "windows_5s": ("windowed motion, windows the table passes in 5 s", ["--window-step", "5"]),
    "exact_2GB": ("exact motion, factors within 2 GB, Jacobi-preconditioned CG beyond",
                  ["--motion", "exact", "--factor-memory", "2"]),
    "exact_cg": ("exact motion, Jacobi-preconditioned CG at every step", ["--motion", "exact", "--solver", "cg"]),
    "averaged": ("cycle-averaged motion, one factor, 10 s steps", ["--motion", "averaged"]),
}


def timed_run(mesh: str, flags: list[str], out: Path) -> dict:
    """The command under /usr/bin/time -v: wall time [s], peak memory [GB], its summary.json and sensors."""
    command = ["/usr/bin/time", "-v", sys.executable, "-m", "feedtherm", "run", "paper", "--condition", "I",
               "--model", "fem", "--mesh", mesh, "--no-plots", "--out", str(out), *flags]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed:\n{result.stderr[-3000:]}")
    wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)", result.stderr).group(1)
    seconds = sum(float(part) * 60 ** i for i, part in enumerate(reversed(wall.split(":"))))
    peak_kb = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", result.stderr).group(1))
    summary = json.loads((out / "summary.json").read_text())
    sensors = pd.read_csv(out / "sensors.csv", comment="#")
    return {"wall_s": seconds, "peak_GB": peak_kb * 1024 / 1e9, "steps": summary["steps"],
            "solver": summary["solver"], "motion_windows": summary.get("motion_windows"),
            "final": {name: summary["final"][name] for name in [*SENSORS, "D_um"]}, "sensors": sensors}


def compare(run: dict, reference: dict) -> dict:
    """Final and largest-over-the-samples differences from the reference run [K, µm]."""
    a, b = run["sensors"], reference["sensors"]
    columns = [*SENSORS, "D_um"]
    over_run = (a[columns] - b[columns]).abs().max()
    return {"final": {c: run["final"][c] - reference["final"][c] for c in columns},
            "largest": {c: float(over_run[c]) for c in columns}}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh", choices=["coarse", "medium", "fine"], default="medium")
    parser.add_argument("--options", default="exact,windows,windows_5s,exact_2GB,averaged",
                        help=f"comma-separated, the first the reference; of {', '.join(OPTIONS)}")
    args = parser.parse_args()
    names = [n.strip() for n in args.options.split(",") if n.strip()]
    unknown = [n for n in names if n not in OPTIONS]
    if unknown:
        raise SystemExit(f"--options: unknown {', '.join(unknown)}; choose from {', '.join(OPTIONS)}")
    runs = {}
    with tempfile.TemporaryDirectory() as tmp:
        # mesh once, so that every option reads the mesh from the cache
        subprocess.run([sys.executable, "-m", "feedtherm", "run", "paper", "--condition", "I", "--model", "fem",
                        "--mesh", args.mesh, "--motion", "averaged", "--duration", "60", "--no-plots", "--out",
                        str(Path(tmp) / "warm")], check=True, capture_output=True)
        for name in names:
            print(f"{name}: {OPTIONS[name][0]} ...", flush=True)
            runs[name] = timed_run(args.mesh, OPTIONS[name][1], Path(tmp) / name)
            print(f"  {runs[name]['wall_s']:.1f} s, {runs[name]['peak_GB']:.2f} GB, {runs[name]['steps']} steps",
                  flush=True)
    reference = runs[names[0]]
    rows = []
    for name in names:
        run = runs[name]
        difference = compare(run, reference)
        rows.append({"option": name, "what": OPTIONS[name][0], "wall_s": round(run["wall_s"], 1),
                     "peak_GB": round(run["peak_GB"], 2), "steps": run["steps"], "solver": run["solver"],
                     "motion_windows": run["motion_windows"], "final": run["final"], "difference": difference})
    machine = f"{platform.machine()}, {platform.python_implementation()} {platform.python_version()}"
    RESULTS.mkdir(parents=True, exist_ok=True)
    stem = RESULTS / f"fem_motion_windows_{args.mesh}"
    stem.with_suffix(".json").write_text(json.dumps({"mesh": args.mesh, "machine": machine, "reference": names[0],
                                                     "runs": rows}, indent=2) + "\n")
    lines = [f"# The FE run's motion on the {args.mesh} mesh: condition I, 10,800 s ({machine})", "",
             f"Differences from `{names[0]}`: the final value, and the largest over every 10 s sample.", "",
             "| option | wall time | peak memory | steps | largest \\|ΔT\\| final / over the run (K) | "
             "\\|ΔD\\| final / over the run (µm) |", "|---|---|---|---|---|---|"]
    for row in rows:
        d = row["difference"]
        final_t = max(abs(d["final"][s]) for s in SENSORS)
        over_t = max(d["largest"][s] for s in SENSORS)
        lines.append(f"| {row['option']}: {row['what']} | {row['wall_s']:.0f} s | {row['peak_GB']:.2f} GB | "
                     f"{row['steps']} | {final_t:.4f} / {over_t:.4f} | {abs(d['final']['D_um']):.4f} / "
                     f"{d['largest']['D_um']:.4f} |")
    stem.with_suffix(".md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
