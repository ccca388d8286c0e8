"""Benchmark of `feedtherm uncertainty` on the paper bench: wall time and runs per second, serial
and on a local Dask cluster of N worker processes, and whether the two give the same files.

Run:  .venv/bin/python benchmarks/bench_uncertainty.py [--workers 2] [--samples 128] [--sobol-base 64]
      [--update-with I,II,IV] [--only serial|parallel] [--model reduced --mesh medium]

Each execution is the command as a user types it, in a child process (interpreter, imports, the
cluster's start-up, the runs, the files): its wall time from start to exit.  The runs are the
study's (``settings.runs`` of uncertainty.json: every sampled point at every condition, the
nominal runs, the Sobol' points) plus, with --update-with, the update's (``model_runs``); the
in-process wall times of the study and of the update are read from uncertainty.json too.

Identical results: bands.csv, finals.csv and sobol.csv byte for byte, and uncertainty.json equal
once the wall times and the execution's description are left out.  The default settings are the
command's (128 points, Sobol' base 64: 2,186 runs; with --update-with I,II,IV another 591).
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

COMPARED_FILES = ("bands.csv", "finals.csv", "sobol.csv")
#: Keys of uncertainty.json that differ between executions by design.
VOLATILE = ("wall_time_s", "execution")


def uncertainty(out: Path, args: argparse.Namespace, extra: list[str]) -> float:
    """The wall time [s] of one `feedtherm uncertainty` into ``out``."""
    env = {k: v for k, v in os.environ.items() if k != "DASK_SCHEDULER_ADDRESS"}
    command = [sys.executable, "-m", "feedtherm", "uncertainty", "paper", "--samples", str(args.samples),
               "--sobol-base", str(args.sobol_base), "--out", str(out), *extra]
    if args.update_with:
        command += ["--update-with", args.update_with]
    if args.model != "fast":
        command += ["--model", args.model, "--mesh", args.mesh]
    start = time.perf_counter()
    process = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=env)
    wall = time.perf_counter() - start
    if process.returncode != 0:
        raise SystemExit(f"feedtherm uncertainty failed: {process.stderr.strip()}")
    return wall


def without_volatile(value):
    if isinstance(value, dict):
        return {k: without_volatile(v) for k, v in value.items() if k not in VOLATILE}
    if isinstance(value, list):
        return [without_volatile(v) for v in value]
    return value


def record(out: Path, wall: float) -> dict:
    document = json.loads((out / "uncertainty.json").read_text(encoding="utf-8"))
    update = next((s["calibration"] for s in document["sets"] if (s.get("calibration") or {}).get("model_runs")), None)
    runs = document["settings"]["runs"] + (update["model_runs"] if update else 0)
    return {"wall_s": round(wall, 1), "runs": runs, "runs_per_s": round(runs / wall, 2),
            "study_s": round(document["settings"]["wall_time_s"], 1),
            "update_s": round(update["wall_time_s"], 1) if update else None}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--samples", type=int, default=128)
    parser.add_argument("--sobol-base", type=int, default=64)
    parser.add_argument("--update-with", default=None, metavar="CONDITIONS")
    parser.add_argument("--model", default="fast", help="a model of `feedtherm models` (reduced: the parametric one)")
    parser.add_argument("--mesh", default="coarse", help="its FE mesh (with --model fem or reduced)")
    parser.add_argument("--only", choices=["serial", "parallel"], default=None,
                        help="time one execution only (no comparison of the files)")
    args = parser.parse_args()
    result = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "machine": platform.machine(),
              "cpus": os.cpu_count(), "python": platform.python_version(), "samples": args.samples,
              "sobol_base": args.sobol_base, "update_with": args.update_with, "workers": args.workers,
              "model": args.model, "mesh": args.mesh if args.model != "fast" else None}
    with tempfile.TemporaryDirectory() as tmp:
        folders = {}
        for name, extra in (("serial", ["--workers", "1"]), ("parallel", ["--workers", str(args.workers)])):
            if args.only in (None, name):
                folders[name] = Path(tmp) / name
                result[name] = record(folders[name], uncertainty(folders[name], args, extra))
        if len(folders) == 2:
            a, b = folders["serial"], folders["parallel"]
            result["speed_up"] = round(result["serial"]["wall_s"] / result["parallel"]["wall_s"], 2)
            result["files_identical"] = {name: (a / name).read_bytes() == (b / name).read_bytes()
                                         for name in COMPARED_FILES}
            result["json_equal_but_times"] = without_volatile(json.loads((a / "uncertainty.json").read_text())) == \
                without_volatile(json.loads((b / "uncertainty.json").read_text()))
    print(json.dumps(result, indent=2))
    out = Path(__file__).parent / "results"
    out.mkdir(exist_ok=True)
    tag = f"{args.samples}x{args.sobol_base}" + (f"_update_{args.update_with.replace(',', '-')}" if args.update_with else "")
    tag += f"_{args.model}_{args.mesh}" if args.model != "fast" else ""
    (out / f"bench_uncertainty_{tag}{'_' + args.only if args.only else ''}.json").write_text(
        json.dumps(result, indent=2) + "\n")


if __name__ == "__main__":
    main()
