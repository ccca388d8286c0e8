"""ISO 230-3 figures of `feedtherm validate`: iso230_3.csv (per test and target) and iso230_3_drift.csv.

Written only where a test's measurements hold positioning deviations at targets, or an idle
test's displacements in a varying room (:mod:`feedtherm.analysis.drift_tests`).  Displacements in
µm, times in s.
"""

from __future__ import annotations

import csv
from pathlib import Path

from ..analysis.drift_tests import DriftTest

FIGURES_CSV = "iso230_3.csv"
DRIFT_CSV = "iso230_3_drift.csv"
FIGURES_HEADER = ["test", "figure", "quantity", "measured_um", "measured_at_s", "simulated_um", "simulated_at_s",
                  "rms_deviation_um", "max_abs_deviation_um", "samples"]
DRIFT_HEADER = ["test", "target_mm", "time_s", "measured_drift_um", "simulated_drift_um"]
_UM = 1e6


def figure_rows(test: DriftTest) -> list[dict]:
    """One row per figure: each target's largest drift, the outer targets' expansion and each ETVE."""
    rows = []
    for (measured, simulated), (rms, worst) in zip(zip(test.measured, test.simulated), test.residual):
        rows.append({"test": test.run, "figure": "largest drift", "quantity": f"E at {measured.target * 1e3:g} mm",
                     "measured_um": measured.largest * _UM, "measured_at_s": measured.time_of_largest,
                     "simulated_um": simulated.largest * _UM, "simulated_at_s": simulated.time_of_largest,
                     "rms_deviation_um": rms * _UM, "max_abs_deviation_um": worst * _UM,
                     "samples": len(measured.times)})
    m, s = test.expansion_measured, test.expansion_simulated
    if m is not None and s is not None:
        rows.append({"test": test.run, "figure": "expansion drift",
                     "quantity": f"E at {m.last_target * 1e3:g} mm less E at {m.first_target * 1e3:g} mm",
                     "measured_um": m.largest * _UM, "measured_at_s": m.time_of_largest,
                     "simulated_um": s.largest * _UM, "simulated_at_s": s.time_of_largest,
                     "rms_deviation_um": None, "max_abs_deviation_um": None, "samples": len(m.times)})
    for measured, simulated in test.etve:
        rows.append({"test": test.run, "figure": "ETVE (range)", "quantity": measured.quantity,
                     "measured_um": measured.range * _UM, "measured_at_s": None,
                     "simulated_um": simulated.range * _UM, "simulated_at_s": None,
                     "rms_deviation_um": None, "max_abs_deviation_um": None, "samples": None})
    return rows


def write_drift_test_files(tests: list[DriftTest], directory: Path) -> list[Path]:
    """Write iso230_3.csv and iso230_3_drift.csv into ``directory``; nothing without drift tests."""
    if not tests:
        return []
    figures, drifts = Path(directory) / FIGURES_CSV, Path(directory) / DRIFT_CSV
    with open(figures, "w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(FIGURES_HEADER)
        for test in tests:
            for row in figure_rows(test):
                writer.writerow([_cell(row[key]) for key in FIGURES_HEADER])
    with open(drifts, "w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(DRIFT_HEADER)
        for test in tests:
            for measured, simulated in zip(test.measured, test.simulated):
                for t, m, s in zip(measured.times, measured.drift, simulated.drift):
                    writer.writerow([test.run, f"{measured.target * 1e3:g}", f"{t:g}", f"{m * _UM:.3f}",
                                     f"{s * _UM:.3f}"])
    return [figures, drifts]


def drift_test_summary(tests: list[DriftTest]) -> list[dict]:
    """The figures for validation.json."""
    return [row for test in tests for row in figure_rows(test)]


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return f"{value:.4g}" if abs(value) >= 1e-3 or value == 0 else f"{value:.3e}"
    return str(value)
