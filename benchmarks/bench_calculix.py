"""CalculiX side by side: the same FE model, mesh and 3 h transient in both solvers (issue 13).

Run:
    .venv/bin/python benchmarks/bench_calculix.py [--mesh coarse|medium|fine] [--condition I]
                                                   [--step 30] [--duration 10800]

CalculiX (``ccx``) comes from the Debian package ``calculix-ccx``; the script installs it with
apt-get where it is missing.

The configuration both can take: condition I's heats, film coefficients and joints, frozen
at the start (CalculiX takes them as constants), with the moving group held at the middle of
its stroke.  feedtherm's FE model is written to a CalculiX deck
(:func:`feedtherm.models.fem.calculix.calculix_deck`: nodes, C3D4 elements, materials, the
joints as tied contact pairs with their gap conductance, films on the exposed facets, nodal
heats); both solvers then march the same implicit Euler steps from the same uniform start.
feedtherm runs the full FE model and the reduced model (basis built here, timed apart).

Printed and written as JSON to benchmarks/results/calculix_<mesh>_<condition>.json: the
largest |ΔT| of T1–T5 and of D over every printed time (every 600 s), and the wall times of
CalculiX, of the full FE run and of the reduced model, with their ratios.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from datetime import date
from pathlib import Path

import numpy as np

from feedtherm.models.fem.calculix import calculix_deck, read_temperatures
from feedtherm.models.integrator import Integrator
from feedtherm.models.reduced import ProjectedModel, moment_basis
from feedtherm.simulate import plan_run
from feedtherm.system.load import load_system

RESULTS = Path(__file__).resolve().parent / "results"
SENSORS = ["T1", "T2", "T3", "T4", "T5"]


def ensure_calculix() -> str:
    """The path of ``ccx``, installed from Debian's ``calculix-ccx`` where missing."""
    found = shutil.which("ccx")
    if found:
        return found
    print("installing CalculiX (Debian package calculix-ccx) ...", flush=True)
    sudo = [] if os.geteuid() == 0 else ["sudo"]
    subprocess.run([*sudo, "apt-get", "update", "-qq"], check=True)
    subprocess.run([*sudo, "apt-get", "install", "-y", "-qq", "calculix-ccx"], check=True)
    found = shutil.which("ccx")
    if not found:
        sys.exit("calculix-ccx is installed but ccx is not on PATH")
    return found


def hold_position(model, plan, bc, k: int, step: float, duration: float, every: float) -> dict[float, np.ndarray]:
    """Implicit Euler at position k from the uniform initial state: probe values at every ``every`` s."""
    integrator = Integrator(model, plan.options, None)
    loads = integrator.loads(0, bc, k)
    state = model.uniform_state(bc.point.ambient)
    capacity = model.capacity
    apply_capacity = (lambda v: capacity * v) if np.ndim(capacity) == 1 else (lambda v: capacity @ v)
    probes = {}
    steps = int(round(duration / step))
    stride = max(1, int(round(every / step)))
    for i in range(1, steps + 1):
        rhs = apply_capacity(state) / step + loads.heat + loads.ambient.source
        state = integrator.solve(0, bc, k, step, rhs, state)
        if i % stride == 0 or i == steps:
            probes[round(i * step, 6)] = model.probe(state, k)
    return probes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh", default="coarse", choices=["coarse", "medium", "fine"])
    parser.add_argument("--condition", default="I")
    parser.add_argument("--step", type=float, default=30.0, help="time step of both solvers [s]")
    parser.add_argument("--duration", type=float, default=10_800.0, help="[s]")
    parser.add_argument("--every", type=float, default=600.0, help="interval of the compared values [s]")
    parser.add_argument("--tolerance", type=float, default=1e-4, help="the reduced model's basis tolerance")
    parser.add_argument("--threads", type=int, default=os.cpu_count() or 1, help="CalculiX's threads")
    args = parser.parse_args()
    ccx = ensure_calculix()

    loaded = load_system("paper")
    plan = plan_run(loaded, condition=args.condition, model="fem", mesh=args.mesh)
    bc = plan.segments[0].bc
    started = time.perf_counter()
    model = plan.model.build(loaded.system, plan.options)
    build_s = time.perf_counter() - started
    k = len(model.positions) // 2

    started = time.perf_counter()
    full = hold_position(model, plan, bc, k, args.step, args.duration, args.every)
    full_s = time.perf_counter() - started

    started = time.perf_counter()
    reduced_model = ProjectedModel(model, moment_basis(model, tolerance=args.tolerance))
    basis_s = time.perf_counter() - started
    started = time.perf_counter()
    reduced = hold_position(reduced_model, plan, bc, k, args.step, args.duration, args.every)
    reduced_s = time.perf_counter() - started

    with tempfile.TemporaryDirectory() as work:
        deck = calculix_deck(model, bc, k, time_step=args.step, duration=args.duration,
                             output_interval=args.every, initial=bc.point.ambient)
        (Path(work) / "feedtherm.inp").write_text(deck)
        env = dict(os.environ, OMP_NUM_THREADS=str(args.threads), CCX_NPROC_EQUATION_SOLVER=str(args.threads))
        started = time.perf_counter()
        done = subprocess.run([ccx, "-i", "feedtherm"], cwd=work, env=env, capture_output=True, text=True)
        ccx_s = time.perf_counter() - started
        if done.returncode != 0 or "*ERROR" in done.stdout:
            sys.exit("CalculiX failed:\n" + done.stdout[-3000:] + done.stderr[-2000:])
        times, states = read_temperatures((Path(work) / "feedtherm.dat").read_text(), model.n_nodes)
    if np.isnan(states).any():
        sys.exit("CalculiX's .dat file lacks some nodal temperatures")
    calculix = {round(float(t), 6): model.probe(s, k) for t, s in zip(times, states)}
    common = sorted(set(calculix) & set(full))
    if not common:
        sys.exit("no common output times between CalculiX and feedtherm")

    def largest(a: dict, b: dict) -> tuple[dict, float]:
        diff = np.array([a[t] - b[t] for t in common])
        return ({name: round(float(np.max(np.abs(diff[:, i]))), 4) for i, name in enumerate(SENSORS)},
                round(float(np.max(np.abs(diff[:, -1]))) * 1e6, 4))

    full_dT, full_dD = largest(full, calculix)
    reduced_dT, reduced_dD = largest(reduced, calculix)
    end = common[-1]
    figures = {
        "date": date.today().isoformat(),
        "machine": f"{platform.machine()}, {platform.python_implementation()} {platform.python_version()}",
        "mesh": args.mesh, "vertices": model.n_nodes, "condition": args.condition,
        "position_offset_mm": round(float(model.positions[k]) * 1e3, 3),
        "step_s": args.step, "duration_s": args.duration, "compared_times": len(common),
        "calculix": subprocess.run([ccx, "-v"], capture_output=True, text=True).stdout.strip().splitlines()[-1:],
        "end_temperatures_C": {name: round(float(calculix[end][i]) - 273.15, 3) for i, name in enumerate(SENSORS)},
        "end_D_um": round(float(calculix[end][-1]) * 1e6, 3),
        "full_vs_calculix_max_abs_dT_K": full_dT, "full_vs_calculix_max_abs_dD_um": full_dD,
        "full_vs_calculix_max_abs_dT_all_K": max(full_dT.values()),
        "reduced_vs_calculix_max_abs_dT_K": reduced_dT, "reduced_vs_calculix_max_abs_dD_um": reduced_dD,
        "reduced_vs_calculix_max_abs_dT_all_K": max(reduced_dT.values()),
        "reduced_basis_size": reduced_model.n_nodes,
        "calculix_s": round(ccx_s, 1), "calculix_threads": args.threads,
        "fe_build_s": round(build_s, 1), "full_run_s": round(full_s, 1),
        "reduced_basis_s": round(basis_s, 1), "reduced_run_s": round(reduced_s, 2),
        "calculix_over_full_run": round(ccx_s / full_s, 1),
        "calculix_over_reduced_including_basis": round(ccx_s / (basis_s + reduced_s), 1),
    }
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / f"calculix_{args.mesh}_{args.condition}.json").write_text(json.dumps(figures, indent=2))
    print(json.dumps(figures, indent=2))


if __name__ == "__main__":
    main()
