"""Benchmark of calibration: one fit and the leave-one-condition-out study, wall time and runs.

Run:  .venv/bin/python benchmarks/bench_calibration.py [--params a,b,c] [--fit I,II,IV] [--workers N]
          [--model fast|reduced] [--mesh coarse|medium|fine]

It times exactly what ``feedtherm calibrate <system> --fit ... --params ... --cross-validate``
computes (the consistency check, the fit, the prediction intervals, then one fit per left-out
condition started from the first fit), without writing files, and prints the held-out
accuracy beside the time so that a faster calibration cannot hide a worse one.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import time

from feedtherm.analysis.calibration import RunCache, calibrate, cross_validate
from feedtherm.analysis.execution import Execution, kept_open
from feedtherm.analysis.consistency import check_description_measurements
from feedtherm.analysis.validation import measurements_of
from feedtherm.outputs.calibration_files import worst
from feedtherm.system.load import load_system

DEFAULT_PARAMS = "screw_nut_preload,front_bearing_preload,foundation,chtc_screw,tcr"


def largest(rows) -> dict:
    out = {}
    for unit in ("C", "um", "min"):
        row = worst(rows, unit)
        if row is not None:
            out[unit] = f"{row.deviation:+.2f} ({row.condition} {row.quantity})"
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("system", nargs="?", default="paper")
    parser.add_argument("--params", default=DEFAULT_PARAMS)
    parser.add_argument("--fit", default="I,II,IV")
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--model", default="fast", help="a model of `feedtherm models` (reduced: the parametric one)")
    parser.add_argument("--mesh", default=None, help="its FE mesh (fem, reduced)")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")
    args = parser.parse_args()
    loaded = load_system(args.system)
    data = measurements_of(loaded, None)
    names = args.params.split(",")
    fit = args.fit.split(",")

    started = time.perf_counter()
    consistency = check_description_measurements(loaded.system, data)
    # As the command does: one local cluster (--workers > 1) for the fit and every fold.
    with kept_open(Execution(workers=args.workers) if args.workers > 1 else Execution()) as running:
        options = {"consistency": consistency, "execution": running, "cache": RunCache(), "model": args.model,
                   "mesh": args.mesh}
        result = calibrate(loaded, data, fit, names, **options)
        first = time.perf_counter() - started
        folds = cross_validate(loaded, data, names, start=result.fitted, **options)
    total = time.perf_counter() - started
    figures = {
        "machine": f"{platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, "
                   f"{platform.python_implementation()} {platform.python_version()}",
        "system": args.system,
        "params": names,
        "workers": args.workers,
        "model": args.model,
        "mesh": args.mesh,
        "fit_wall_s": round(first, 1),
        "fit_model_runs": result.model_runs,
        "leave_one_out_wall_s": round(total - first, 1),
        "leave_one_out_model_runs": sum(r.model_runs for _, r in folds),
        "fit_and_leave_one_out_wall_s": round(total, 1),
        "held_out_largest": largest(result.held_out),
        "leave_one_out_largest": largest([r for _, res in folds for r in res.held_out]),
        "flagged": [f"{f.condition} {f.quantity}" for f in consistency.flags],
        "peak_rss_MB": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1),
    }
    if args.json:
        print(json.dumps(figures, indent=2))
        return
    print(f"feedtherm calibrate --fit {args.fit} --params {args.params} --cross-validate (no files)")
    for key, value in figures.items():
        print(f"  {key:30s} {value}")


if __name__ == "__main__":
    main()
