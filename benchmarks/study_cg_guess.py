"""How many conjugate-gradient iterations a step of the FE model needs from a better starting guess.

Run:  flock /tmp/feedtherm-bench.lock .venv/bin/python benchmarks/study_cg_guess.py [--mesh coarse] [--duration 10800]

Issue 36 asks the position-resolved fine run for at most 120 s and 4 GB.  Held factors cost the
memory (docs/fem-model.md, *Memory*), so such a run steps by conjugate gradients, whose cost is the
iterations a step.  A reciprocating nut makes a step's increment repeat the increments at the same
phase of the stroke (position and direction) in earlier cycles, but for the slow rise between them
(models/iterative.py, *Where the iterations start*).  This study runs condition I with
``--solver cg`` once for each starting guess of :data:`GUESSES`:

- ``extrapolated states``: the linear extrapolation of the last two states (the integrator's before);
- ``last increment``: the start state plus the increment of the last step at the same phase;
- ``two increments``: plus the linear extrapolation of the last two steps' at that phase (the integrator's);
- ``three increments``: their quadratic extrapolation.

It prints the iterations per step over the run and over its second half, the wall time (the model
built beforehand, so that every run uses it), and how far each run's final sensors and D lie from
the first's (every run stops at the integrator's tolerance, 1e-5 of a step's forcing).
Printed and written as JSON to benchmarks/results/cg_guess_<mesh>.json.
About 3 minutes on the coarse mesh over 10,800 s.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from feedtherm.models import integrator as integrator_module
from feedtherm.models.iterative import IncrementHistory
from feedtherm.plan import with_mode
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system

RESULTS = Path(__file__).resolve().parent / "results"


#: The starting guesses compared: the integrator's (two increments), and the alternatives it was chosen over.
GUESSES = {
    "extrapolated states": lambda kept, start, fallback: fallback,
    "last increment": lambda kept, start, fallback: start + kept[-1],
    "two increments (the integrator's)": None,
    "three increments": lambda kept, start, fallback: start + (
        3.0 * kept[-1] - 3.0 * kept[-2] + kept[-3] if len(kept) == 3 else
        2.0 * kept[-1] - kept[-2] if len(kept) == 2 else kept[-1]),
}


def run(loaded, condition: str, mesh: str, duration: float, guess: str) -> dict:
    """One cg run with the starting guess ``guess`` of :data:`GUESSES`."""
    plain_guess, plain_record = IncrementHistory.guess, IncrementHistory.record
    plain_solve = integrator_module.Integrator.solve
    iterations: list[int] = []

    def counted(self, *args):
        before = self.cg_iterations
        state = plain_solve(self, *args)
        iterations.append(self.cg_iterations - before)
        return state

    def guessed(self, phase, start, fallback):
        kept = self._kept.get(phase)
        return fallback if kept is None else GUESSES[guess](kept, start, fallback)

    def record_three(self, phase, increment):
        self._kept[phase] = (*self._kept.get(phase, ())[-2:], increment)

    integrator_module.Integrator.solve = counted
    if GUESSES[guess] is not None:
        IncrementHistory.guess = guessed
        IncrementHistory.record = record_three
    try:
        started = time.perf_counter()
        solution = simulate(loaded, condition=condition, model="fem", mesh=mesh, duration=duration, solver="cg")
        wall = time.perf_counter() - started
    finally:
        integrator_module.Integrator.solve = plain_solve
        IncrementHistory.guess, IncrementHistory.record = plain_guess, plain_record
    counts = np.array(iterations)
    return {"steps": int(counts.size), "iterations_per_step": round(float(counts.mean()), 2),
            "second_half_iterations_per_step": round(float(counts[counts.size // 2:].mean()), 2),
            "wall_s": round(wall, 1),
            "final": {name: float(values[-1]) for name, values in solution.sensors.items()},
            "final_D_um": float(solution.elongation[-1] * 1e6)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh", default="coarse", choices=["coarse", "medium", "fine"])
    parser.add_argument("--duration", type=float, default=10800.0, help="[s]")
    parser.add_argument("--condition", default="I")
    args = parser.parse_args()
    loaded = with_mode(load_system("paper"), "physics")
    # builds the FE model once (the registry keeps it), so that both walls are the runs' own
    simulate(loaded, condition=args.condition, model="fem", mesh=args.mesh, duration=10.0, solver="cg")
    runs = {guess: run(loaded, args.condition, args.mesh, args.duration, guess) for guess in GUESSES}
    a = runs["extrapolated states"]
    figures = {"mesh": args.mesh, "condition": args.condition, "duration_s": args.duration, "runs": runs,
               "largest_final_sensor_difference_K": {
                   guess: max(abs(a["final"][n] - b["final"][n]) for n in a["final"]) for guess, b in runs.items()},
               "final_D_difference_um": {guess: abs(a["final_D_um"] - b["final_D_um"]) for guess, b in runs.items()}}
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / f"cg_guess_{args.mesh}.json").write_text(json.dumps(figures, indent=2) + "\n")
    print(json.dumps(figures, indent=2))


if __name__ == "__main__":
    main()
