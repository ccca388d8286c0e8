"""Which declared uncertainty costs a compensation law most: one at a time, at its 5 % and 95 % points.

A law trained on the nominal machine (``law.json`` of a ``feedtherm compensate`` folder) is run on
the study's first test cycles (seed 0, stream 2), on machines that differ from the nominal one in
one declared uncertainty only, set to its 5 % or 95 % quantile; the readings are the model's (no
sensor noise), so the residual is the law's mismatch with that machine alone.  Prints the RMS and
max residual of D per parameter, largest first.

    PYTHONPATH=src python benchmarks/study_compensation_sensitivity.py out/paper_compensation_physics [CYCLES]
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from feedtherm.analysis.candidates import candidate_sensors, with_candidates
from feedtherm.analysis.compensation.data import CYCLE_NAME, STREAMS, StudySettings
from feedtherm.analysis.compensation.evaluator import CompensationLaw
from feedtherm.analysis.random_cycles import cycle_seed, random_cycle
from feedtherm.analysis.sweep import SweepRun, run_batch
from feedtherm.analysis.uncertainty.declared import resolve_uncertainties, variant
from feedtherm.analysis.uncertainty.sampling import ppf
from feedtherm.system.load import load_system
from feedtherm.system.variants import with_values


def main(folder: str, cycles: int = 2) -> None:
    loaded = load_system("paper")
    law = CompensationLaw.from_file(Path(folder) / "law.json")
    candidates = candidate_sensors(loaded.system)
    base = with_candidates(loaded, candidates)
    settings = StudySettings()
    drawn = [random_cycle(loaded.system, cycle_seed(0, STREAMS["test"], i), settings.ranges) for i in range(cycles)]
    machines = {"nominal": base}
    for p in resolve_uncertainties(loaded):
        for q in (0.05, 0.95):
            machines[f"{p.name}@{q:.2f}"] = variant(base, [p], [float(ppf(p, q))], f"{p.name} at {q}")
    runs, keys = [], []
    for name, machine in machines.items():
        for i, cycle in enumerate(drawn):
            described = with_values(machine, {"duty_cycles": {**machine.system.duty_cycles, CYCLE_NAME: cycle}})
            runs.append(SweepRun(described, {"cycle": CYCLE_NAME, "model": "fast", "motion": "averaged",
                                             "sample_interval": settings.sample_interval}, label=f"{name} {i}"))
            keys.append(name)
    errors: dict[str, list[np.ndarray]] = {}
    for key, solution in zip(keys, run_batch(runs)):
        law.reset()
        predicted = [law.update(t, {n: solution.sensors[n][j] for n in law.inputs})
                     for j, t in enumerate(solution.times)]
        errors.setdefault(key, []).append(np.asarray(solution.elongation) - np.asarray(predicted))
    rows = []
    for key, parts in errors.items():
        e = np.concatenate(parts)
        rows.append((key, float(np.sqrt(np.mean(e ** 2))) * 1e6, float(np.abs(e).max()) * 1e6))
    print(f"law on {', '.join(law.inputs)}; {cycles} test cycles, no sensor noise; residual of D [um]")
    for key, rms, mx in sorted(rows, key=lambda r: -r[1]):
        print(f"{key:32s} RMS {rms:6.2f}  max {mx:6.2f}")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 2)
