"""Measured time series against their runs: transients.csv (the scores) and transient_samples.csv.

Written by `feedtherm validate` only when the measurements hold time series.
"""

from __future__ import annotations

import csv
from pathlib import Path

from ..analysis.transient_scores import TransientComparison
from ..system.measurement_series import target_of

TRANSIENTS_CSV = "transients.csv"
SAMPLES_CSV = "transient_samples.csv"
#: Deviations are differences: kelvin for temperatures, µm for the elongation.
SCORE_HEADER = ["condition", "quantity", "unit", "samples", "start_s", "end_s", "rms_deviation",
                "max_abs_deviation", "time_of_max_s", "mean_deviation", "inside_two_sigma"]
SAMPLE_HEADER = ["condition", "quantity", "unit", "time_s", "measured", "simulated", "deviation", "uncertainty"]


def deviation_unit(comparison: TransientComparison) -> str:
    """The unit of a deviation: ``K`` for a temperature (°C values), else the values' own."""
    return "K" if comparison.unit == "C" else comparison.unit


def write_transient_files(comparisons: list[TransientComparison], directory: Path) -> list[Path]:
    """Write transients.csv and transient_samples.csv into ``directory``; nothing without series."""
    if not comparisons:
        return []
    scores, samples = Path(directory) / TRANSIENTS_CSV, Path(directory) / SAMPLES_CSV
    with open(scores, "w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(SCORE_HEADER)
        for c in comparisons:
            writer.writerow([c.condition, c.quantity, deviation_unit(c), len(c.times), f"{c.times[0]:g}",
                             f"{c.times[-1]:g}", f"{c.rms:.4f}", f"{c.max_abs:.4f}", f"{c.time_of_max:g}",
                             f"{c.mean:.4f}", "" if c.inside_two_sigma is None else f"{c.inside_two_sigma:.3f}"])
    with open(samples, "w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(SAMPLE_HEADER)
        for c in comparisons:
            for i, time in enumerate(c.times):
                uncertainty = "" if c.uncertainty is None else f"{c.uncertainty[i]:.4g}"
                writer.writerow([c.condition, c.quantity, c.unit, f"{time:g}", f"{c.measured[i]:.4f}",
                                 f"{c.simulated[i]:.4f}", f"{c.deviation[i]:.4f}", uncertainty])
    return [scores, samples]


def transient_summary(comparisons: list[TransientComparison]) -> list[dict]:
    """The scores for validation.json."""
    return [{"condition": c.condition, "quantity": c.quantity, "unit": deviation_unit(c), "samples": len(c.times),
             "rms_deviation": c.rms, "max_abs_deviation": c.max_abs, "time_of_max_s": c.time_of_max,
             "mean_deviation": c.mean, "inside_two_sigma": c.inside_two_sigma} for c in comparisons]


def transient_lines(comparisons: list[TransientComparison]) -> list[str]:
    """Console lines: per condition, the temperature series and the elongation with the largest RMS."""
    lines = []
    for condition in dict.fromkeys(c.condition for c in comparisons):
        own = [c for c in comparisons if c.condition == condition]
        parts = []
        positioning = [c for c in own if target_of(c.quantity) is not None]
        for label, rows in (("temperature", [c for c in own if c.unit == "C"]),
                            ("elongation", [c for c in own if c.unit != "C" and c not in positioning]),
                            ("drift at a target", positioning)):
            if rows:
                worst = max(rows, key=lambda c: c.rms)
                unit = "K" if label == "temperature" else "µm"
                name = "D" if label == "elongation" else worst.quantity
                parts.append(f"{label} RMS {worst.rms:.1f} {unit} ({name}), "
                             f"max |Δ| {worst.max_abs:.1f} {unit} at {worst.time_of_max / 60.0:.0f} min")
        lines.append(f"measured series, condition {condition}: " + "; ".join(parts))
    return lines
