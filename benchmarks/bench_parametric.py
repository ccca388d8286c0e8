"""Benchmark of the parametric reduced model against the FE model at random points of the declared ranges (issue 36).

Run:
    flock /tmp/feedtherm-bench.lock .venv/bin/python benchmarks/bench_parametric.py [--mesh medium] [--points 10] [--seed 0]

In a cache directory of its own (the mesh file copied in from the user's cache when it is
there, so that the FE model is not meshed again), it builds the reduced model of the paper's
bench through the registry, as `feedtherm ... --model reduced` does: its basis trained over
the ranges the description declares (models/reduced/training.py).  Then, at ``--points``
points drawn from the declared distributions of ``[uncertainty.parameters]`` (every
uncertainty of the bench, the heats and CHTCs included: the reduced model's operators take
them all), it runs condition I over 10,800 s with the cycle-averaged motion in 60 s steps (the
runs of calibration and uncertainty) on the reduced model (read from the cache: the projection
of the nominal description) and on the FE model built for that point, and reports the largest
deviation over every 60 s sample of T1-T5 and of D.  Results go to
benchmarks/results/parametric_<mesh>.json.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import tempfile
import time
from datetime import date
from pathlib import Path

import numpy as np

RESULTS = Path(__file__).resolve().parent / "results"
SENSORS = ["T1", "T2", "T3", "T4", "T5"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh", default="medium", choices=("coarse", "medium", "fine"))
    parser.add_argument("--points", type=int, default=10)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()

    user_cache = Path(os.environ.get("FEEDTHERM_CACHE", Path.home() / ".cache" / "feedtherm"))
    cache = Path(tempfile.mkdtemp(prefix="feedtherm-parametric-"))
    os.environ["FEEDTHERM_CACHE"] = str(cache)
    from feedtherm.analysis.calibration import CALIBRATION_OPTIONS
    from feedtherm.analysis.uncertainty.declared import resolve_uncertainties, variant
    from feedtherm.analysis.uncertainty.sampling import to_values
    from feedtherm.models.fem.geometry import mesh_cache_path
    from feedtherm.models.options import ModelOptions
    from feedtherm.models.registry import build_model
    from feedtherm.simulate import execute, plan_run
    from feedtherm.system.load import load_system

    loaded = load_system("paper")
    mesh_file = mesh_cache_path(loaded.system, args.mesh)
    ours = user_cache / "meshes" / mesh_file.name
    if ours.exists():
        mesh_file.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(ours, mesh_file)
    started = time.perf_counter()
    model = build_model("reduced", loaded.system, ModelOptions(mesh=args.mesh))
    build_s = time.perf_counter() - started
    if not ours.exists() and mesh_file.exists():  # keep the mesh for the next benchmark
        ours.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(mesh_file, ours)
    stats = model.stats
    print(f"reduced model built in {build_s:.1f} s: basis {stats['basis_size']} vectors from "
          f"{stats['basis_snapshots']} snapshots ({stats['basis_seconds']} s), domain of "
          f"{sum(1 for lo, hi in model.projection.domain.values() if np.isfinite(hi) and hi > lo)} trained ranges",
          flush=True)

    prior = resolve_uncertainties(loaded)
    u = np.random.default_rng(args.seed).random((args.points, len(prior)))
    rows = []
    for i, x in enumerate(to_values(prior, u)):
        point = variant(loaded, prior, x, f"point {i}")
        options = CALIBRATION_OPTIONS
        t0 = time.perf_counter()
        reduced = execute(plan_run(point, condition="I", model="reduced", mesh=args.mesh, options=options,
                                   sample_interval=60.0, allow_overload=True))
        t1 = time.perf_counter()
        full = execute(plan_run(point, condition="I", model="fem", mesh=args.mesh, options=options,
                                sample_interval=60.0, allow_overload=True))
        t2 = time.perf_counter()
        dT = {s: float(np.max(np.abs(reduced.sensors[s] - full.sensors[s]))) for s in SENSORS}
        dD = float(np.max(np.abs(reduced.elongation_um - full.elongation_um)))
        row = {"point": i, "values": {p.name: float(v) for p, v in zip(prior, x)}, "dT_K": dT,
               "largest_dT_K": max(dT.values()), "dD_um": dD, "D_um_final": float(full.elongation_um[-1]),
               "reduced_s": round(t1 - t0, 2), "fe_s": round(t2 - t1, 2),
               "projection_cached": bool(reduced.info["mesh_statistics"]["projection_cached"])}
        rows.append(row)
        print(f"point {i}: largest |dT| {row['largest_dT_K']:.4f} K, |dD| {dD:.4f} um (D {row['D_um_final']:.2f} um); "
              f"reduced {row['reduced_s']} s, FE {row['fe_s']} s, cached {row['projection_cached']}", flush=True)
    summary = {"date": date.today().isoformat(), "machine": platform.machine(), "mesh": args.mesh,
               "build_s": round(build_s, 1), "basis_size": stats["basis_size"],
               "basis_snapshots": stats["basis_snapshots"], "basis_seconds": stats["basis_seconds"],
               "largest_dT_K": max(r["largest_dT_K"] for r in rows), "largest_dD_um": max(r["dD_um"] for r in rows),
               "median_reduced_s": float(np.median([r["reduced_s"] for r in rows])),
               "median_fe_s": float(np.median([r["fe_s"] for r in rows])), "points": rows}
    RESULTS.mkdir(exist_ok=True)
    out = RESULTS / f"parametric_{args.mesh}.json"
    out.write_text(json.dumps(summary, indent=1))
    print(f"largest |dT| {summary['largest_dT_K']:.4f} K, |dD| {summary['largest_dD_um']:.4f} um over {len(rows)} points "
          f"-> {out}")
    shutil.rmtree(cache, ignore_errors=True)


if __name__ == "__main__":
    main()
