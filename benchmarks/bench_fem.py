"""Benchmarks and studies of the FE model (long runs: not part of the test suite).

Run:
    .venv/bin/python benchmarks/bench_fem.py run --mesh fine      # wall time + peak memory of a full run
    .venv/bin/python benchmarks/bench_fem.py timestep              # time-step study of the transient
    .venv/bin/python benchmarks/bench_fem.py mesh                  # mesh study: coarse, medium, fine
    .venv/bin/python benchmarks/bench_fem.py loop --mesh fine      # FE D and E beside the fast model's, I and V

``run`` times the position-resolved ``feedtherm run --model fem --mesh M --condition I``
over 10,800 s (>= 20 steps per stroke) as a whole command in a child process.  ``timestep``
runs condition I on the coarse mesh (10,800 s) with the time step doubled, as default and
halved, and reports the change of each sensor and the observed order.  ``mesh`` reports the
cycle-averaged steady state of conditions I and V on each mesh and the changes between
densities (the issue asks for less than 0.3 K from medium to fine).  Every figure is printed
and written as JSON to benchmarks/results/ (created on demand); benchmarks/README.md keeps
the latest figures.
"""

from __future__ import annotations

import argparse
import json
import math
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from feedtherm.models.options import ModelOptions
from feedtherm.simulate import simulate, steady_state
from feedtherm.system.load import load_system

SENSORS = ["T1", "T2", "T3", "T4", "T5"]
RESULTS = Path(__file__).resolve().parent / "results"


def peak_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def values(solution_or_dict, which="final") -> dict[str, float]:
    if isinstance(solution_or_dict, dict):
        out = {n: solution_or_dict[n] - 273.15 for n in SENSORS}
        out["D_um"] = solution_or_dict["D"] * 1e6
        return out
    return {k: float(v) for k, v in solution_or_dict.summary_values(which).items() if k != "T6"}


def save(name: str, figures: dict) -> None:
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / f"{name}.json").write_text(json.dumps(figures, indent=2))
    print(json.dumps(figures, indent=2))


def bench_run(mesh: str, condition: str, duration: float | None, solver: str) -> None:
    """Time the command a user runs, ``feedtherm run --model fem``, in a child process.

    Wall time and the child's peak resident memory cover everything: meshing (or the mesh
    cache), assembly, the transient, and writing every output (CSV, JSON, VTU, PNG).
    """
    with tempfile.TemporaryDirectory() as out:
        arguments = ["run", "--model", "fem", "--mesh", mesh, "--condition", condition, "--solver", solver]
        if duration is not None:
            arguments += ["--duration", str(duration)]
        started = time.perf_counter()
        subprocess.run([sys.executable, "-m", "feedtherm", *arguments, "--out", out], check=True,
                       stdout=subprocess.DEVNULL)
        wall = time.perf_counter() - started
        peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024.0
        summary = json.loads((Path(out) / "summary.json").read_text())
        written = sorted(p.name for p in Path(out).iterdir())
    mesh_stats = summary["mesh"]
    save(f"fem_run_{mesh}_{condition}", {
        "command": " ".join(["feedtherm", *arguments]), "solver": summary["solver"],
        "wall_time_s": round(wall, 1), "peak_rss_MB": round(peak, 1),
        "vertices": mesh_stats["vertices"], "tetrahedra": mesh_stats["tetrahedra"],
        "mesh_cached": mesh_stats["mesh_cached"], "simulate_seconds": round(summary["wall_time_s"], 1),
        "time_step_s": summary["time_step_s"], "steps": summary["steps"],
        "energy_balance_error": summary["energy_balance_error"],
        "final": summary["final"], "steady": summary["steady"], "files": written,
    })


def study_timestep(duration: float) -> None:
    """Condition I on the coarse mesh with 10, 20 (the default) and 40 steps per stroke.

    Reports the change of every sensor when the default step is halved, and the observed
    order ``log2(|v10 − v20| / |v20 − v40|)`` (implicit Euler: 1).
    """
    loaded = load_system("paper")
    runs = {}
    for steps in (10, 20, 40):
        started = time.perf_counter()
        run = simulate(loaded, condition="I", model="fem", mesh="coarse", duration=duration,
                       options=ModelOptions(mesh="coarse", steps_per_stroke=steps))
        runs[steps] = {"time_step_s": run.info["time_step_s"], "steps": run.info["steps"],
                       "seconds": round(time.perf_counter() - started, 1),
                       "energy_balance_error": run.energy.relative_error, "final": values(run)}
    a, b, c = (runs[n]["final"] for n in (10, 20, 40))
    order = {k: round(math.log2(abs(a[k] - b[k]) / abs(b[k] - c[k])), 2) if abs(b[k] - c[k]) > 1e-9 else None
             for k in a}
    save("fem_timestep_study", {
        "mesh": "coarse", "condition": "I", "duration_s": duration, "runs": runs,
        "change_default_to_half_step": {k: round(c[k] - b[k], 4) for k in a},
        "change_double_to_default_step": {k: round(b[k] - a[k], 4) for k in a},
        "observed_order": order, "peak_rss_MB": round(peak_rss_mb(), 1),
    })


def study_mesh() -> None:
    loaded = load_system("paper")
    figures = {}
    for condition in ("I", "V"):
        per_mesh = {}
        for mesh in ("coarse", "medium", "fine"):
            started = time.perf_counter()
            per_mesh[mesh] = values(steady_state(loaded, condition, model="fem", options=ModelOptions(mesh=mesh)))
            per_mesh[mesh]["seconds"] = round(time.perf_counter() - started, 1)
        fast = values(steady_state(loaded, condition))
        figures[condition] = {
            "steady": per_mesh, "fast": fast,
            "medium_to_fine": {k: round(per_mesh["fine"][k] - per_mesh["medium"][k], 3) for k in fast},
            "coarse_to_medium": {k: round(per_mesh["medium"][k] - per_mesh["coarse"][k], 3) for k in fast},
            "fem_medium_minus_fast": {k: round(per_mesh["medium"][k] - fast[k], 3) for k in fast},
        }
    figures["peak_rss_MB"] = round(peak_rss_mb(), 1)
    save("fem_mesh_study", figures)


def study_loop(mesh: str) -> None:
    """D and the positioning error of the 3-D thermoelastic solution beside the fast model's bars.

    Conditions I and V of the paper's bench over their 10,800 s, position-resolved: the final D
    (the mean over the last cycle) and E at the stroke's start, middle and end, each model from
    its own temperatures, and T4 (the screw mid-span), to tell a thermal difference between
    the models from a mechanical one.
    """
    loaded = load_system("paper")
    figures: dict = {"mesh": mesh}
    for condition in ("I", "V"):
        per_model = {}
        for model in ("fast", "fem"):
            started = time.perf_counter()
            run = simulate(loaded, condition=condition, model=model, **({"mesh": mesh} if model == "fem" else {}))
            ends = run.positioning_error[-1][[0, len(run.table_x) // 2, -1]]  # stroke's start, middle, end
            per_model[model] = {"D_um": round(run.final["D"] * 1e6, 3),
                                "E_end_um": [round(v * 1e6, 3) for v in ends],
                                "T4_C": round(run.final["T4"] - 273.15, 3),
                                "seconds": round(time.perf_counter() - started, 1)}
        figures[condition] = {**per_model, "D_fem_minus_fast_um": round(per_model["fem"]["D_um"]
                                                                        - per_model["fast"]["D_um"], 3)}
    figures["peak_rss_MB"] = round(peak_rss_mb(), 1)
    save(f"fem_loop_{mesh}", figures)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="what", required=True)
    run = sub.add_parser("run")
    run.add_argument("--mesh", default="fine", choices=["coarse", "medium", "fine"])
    run.add_argument("--condition", default="I")
    run.add_argument("--duration", type=float, default=None)
    run.add_argument("--solver", default="auto", choices=["auto", "direct", "cg"])
    step = sub.add_parser("timestep")
    step.add_argument("--duration", type=float, default=10_800.0)
    sub.add_parser("mesh")
    loop = sub.add_parser("loop")
    loop.add_argument("--mesh", default="fine", choices=["coarse", "medium", "fine"])
    args = parser.parse_args()
    if args.what == "run":
        bench_run(args.mesh, args.condition, args.duration, args.solver)
    elif args.what == "timestep":
        study_timestep(args.duration)
    elif args.what == "loop":
        study_loop(args.mesh)
    else:
        study_mesh()


if __name__ == "__main__":
    main()
