"""Leave one condition out on the measured bench with laws fitted on the measurements alone.

Issue 34 asks the adapted law to predict each held-out condition of the paper's bench within
8 µm RMS over the five (``feedtherm compensate`` gives 15.7 µm, docs/compensation.md §5).  How far
can *any* simple law of the measured temperatures carry from four conditions to the fifth?  This
fits, on the four others, D = a + b·f for one summary f of the measured values at a time (the
form of the review's elongation model, docs/paper-audit.md §4, and its neighbours), and predicts
the fifth:

- ``mean T1 T2 T4``: the review's δ = α L (T̄ − T_ref), with T̄ the bearing and screw mean;
- ``mean T1-T5``, ``T4`` (the screw), ``T3`` (the nut flange);
- ``ambient``: the condition's stated ambient alone;
- ``mean T1 T2 T4 + ambient``: two summaries.

Each is a least-squares fit of 2 or 3 coefficients on 4 points, so none is underdetermined.
Prints the held-out residuals and their RMS; no simulation runs (under a second).

    PYTHONPATH=src python benchmarks/study_measured_loo.py
"""

from __future__ import annotations

import numpy as np

from feedtherm.system.measurements import ELONGATION_QUANTITY, read_measurements
from feedtherm.system.load import load_system


def main() -> None:
    loaded = load_system("paper")
    data = read_measurements("bundled:paper")
    conditions = data.conditions()
    table = {c: {r.quantity: r.measured for r in data.for_condition(c)} for c in conditions}
    ambient = np.array([loaded.system.conditions[c].ambient - 273.15 for c in conditions])
    T = {name: np.array([table[c][name] for c in conditions]) for name in ("T1", "T2", "T3", "T4", "T5")}
    D = np.array([table[c][ELONGATION_QUANTITY] for c in conditions])
    mean124 = (T["T1"] + T["T2"] + T["T4"]) / 3
    summaries = {"mean T1 T2 T4": [mean124], "mean T1-T5": [sum(T.values()) / 5], "T4": [T["T4"]], "T3": [T["T3"]],
                 "ambient": [ambient], "mean T1 T2 T4 + ambient": [mean124, ambient]}
    print(f"measured D [um]: {', '.join(f'{c} {d:.1f}' for c, d in zip(conditions, D))}")
    print(f"{'law fitted on the other four':28s} " + " ".join(f"{c:>6s}" for c in conditions) + "    RMS    max")
    for name, columns in summaries.items():
        X = np.column_stack([np.ones(len(D)), *columns])
        held = []
        for i in range(len(D)):
            keep = np.arange(len(D)) != i
            coefficients, *_ = np.linalg.lstsq(X[keep], D[keep], rcond=None)
            held.append(X[i] @ coefficients - D[i])
        held = np.array(held)
        print(f"{name:28s} " + " ".join(f"{h:+6.1f}" for h in held)
              + f" {np.sqrt(np.mean(held ** 2)):6.1f} {np.abs(held).max():6.1f}")


if __name__ == "__main__":
    main()
