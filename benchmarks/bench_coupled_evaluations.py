"""Benchmark of a coupled run's boundary-condition evaluations: their cost one by one, and their
share of a `compensate` study.

Run:  .venv/bin/python benchmarks/bench_coupled_evaluations.py [--bench paper] [--evaluations 600]
      [--repeat 5] [--study] [--json]

A run under ``temperatures.coupling = "nonlinear"`` evaluates its boundary conditions again
whenever a reading of the state has moved by the coupling tolerance, with one memo for the run
(surfaces and sources at the inputs of their last evaluation are not recomputed).  Two figures:

* per evaluation [µs]: ``boundary_conditions_at`` at condition I's operating point (the
  bench's first condition) with one memo, over a seeded random walk of readings in which each
  evaluation moves 40 % of the surfaces' and 55 % of the sources' temperatures by up to 0.3 K,
  about what `compensate paper` meets (one to five of the 28 readings move by the tolerance
  between two re-evaluations, more by less); the best of ``--repeat`` passes;
* ``--study``: `feedtherm compensate paper --sensors 3` run serially in this process, its wall
  time and the time spent inside the boundary conditions' evaluations (the study takes about
  40 s on two cores).

Run it at another commit with ``PYTHONPATH=<worktree>/src`` to compare (a commit before the
sources' memo passes a plain dict as the memo).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import platform
import random
import sys
import tempfile
import time
import warnings
from pathlib import Path

from feedtherm import boundary, plan
from feedtherm.boundary import LocalTemperatures, boundary_conditions_at
from feedtherm.plan import boundary_of
from feedtherm.system.load import load_system


def fresh_memo():
    """A run's memo, as this commit's ``plan.coupling_of`` makes it."""
    memo_type = getattr(boundary, "EvaluationMemo", None)
    return memo_type() if memo_type is not None else {}


def readings(system, count: int, seed: int = 1) -> list[LocalTemperatures]:
    """A random walk of ``count`` readings from 300 K (see the module notes)."""
    rng = random.Random(seed)
    surfaces = {name: 300.0 for name in system.surfaces}
    sources = {name: 300.0 for name in system.sources}
    walk = []
    for _ in range(count):
        surfaces = {k: v + 0.3 * rng.random() if rng.random() < 0.4 else v for k, v in surfaces.items()}
        sources = {k: v + 0.3 * rng.random() if rng.random() < 0.55 else v for k, v in sources.items()}
        walk.append(LocalTemperatures(dict(surfaces), dict(sources)))
    return walk


def per_evaluation(bench: str, count: int, repeat: int) -> float:
    """Best, over ``repeat`` passes, of the mean time [µs] of one evaluation along the walk."""
    loaded = load_system(bench)
    system = loaded.system
    point = boundary_of(loaded, next(iter(system.conditions))).point
    walk = readings(system, count)
    best = float("inf")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the range warnings go into each evaluation's list
        for _ in range(repeat):
            memo = fresh_memo()
            started = time.perf_counter()
            for reading in walk:
                boundary_conditions_at(system, point, loaded.overlay, temperatures=reading, memo=memo)
            best = min(best, time.perf_counter() - started)
    return best / count * 1e6


def study_share() -> dict[str, float]:
    """Wall time [s] of a serial `compensate paper --sensors 3`, and the time inside its evaluations."""
    from feedtherm.cli import main

    inside = [0.0, 0]
    evaluate = plan.boundary_conditions_at

    def timed(*args, **kwargs):
        started = time.perf_counter()
        try:
            return evaluate(*args, **kwargs)
        finally:
            inside[0] += time.perf_counter() - started
            inside[1] += 1

    plan.boundary_conditions_at = timed  # what a coupled run's evaluations call (plan.coupling_of)
    try:
        with tempfile.TemporaryDirectory(prefix="feedtherm-coupled-") as folder, \
                contextlib.redirect_stdout(io.StringIO()):  # the command's own line, not this script's figures
            started = time.perf_counter()
            code = main(["compensate", "paper", "--sensors", "3", "--out", str(Path(folder) / "out")])
            wall = time.perf_counter() - started
    finally:
        plan.boundary_conditions_at = evaluate
    if code:
        sys.exit(f"compensate failed ({code})")
    return {"wall_s": round(wall, 2), "evaluations_s": round(inside[0], 2), "evaluations": inside[1],
            "share": round(inside[0] / wall, 3)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bench", action="append", help="bench name (repeatable; default: paper and ballscrew_example)")
    parser.add_argument("--evaluations", type=int, default=600)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--study", action="store_true", help="also time a serial compensate study (about 40 s)")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")
    args = parser.parse_args()
    figures = {
        "machine": f"{platform.processor() or platform.machine()}, {platform.python_implementation()} "
                   f"{platform.python_version()}",
        "per_evaluation_us": {bench: round(per_evaluation(bench, args.evaluations, args.repeat), 1)
                              for bench in args.bench or ["paper", "ballscrew_example"]},
    }
    if args.study:
        figures["compensate_serial"] = study_share()
    if args.json:
        print(json.dumps(figures, indent=2))
        return
    print(f"coupled boundary-condition evaluations ({figures['machine']})")
    for bench, micro in figures["per_evaluation_us"].items():
        print(f"  {bench}: {micro:.1f} us per evaluation ({args.evaluations} along a random walk, best of {args.repeat})")
    if args.study:
        study = figures["compensate_serial"]
        print(f"  compensate paper --sensors 3, serial: {study['wall_s']} s, of which {study['evaluations_s']} s in "
              f"{study['evaluations']} evaluations ({100 * study['share']:.0f} %)")


if __name__ == "__main__":
    main()
