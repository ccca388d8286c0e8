"""The files of ``feedtherm correct``: ``correction.csv`` and ``correction.json``, replaced as a set.

``correction.csv``: one row per log (condition), sample time and table position: ``condition``,
``time_s``, then ``D_um`` (a law of D) or ``x_mm`` and ``E_um`` (a stroke law); ``sd_um`` for an
adapted law (its predictive standard deviation); ``measured_D_um`` and ``residual_um`` (measured −
predicted) where the log holds D at that time; ``outside_envelope`` where the law carries its training
envelope: why a sample lies outside it, empty within.  ``correction.json``: the law and the log it
came from, and per condition the samples, the samples outside the envelope and, where D was logged,
the RMS and largest residual.
The axis is corrected by minus the predicted value.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from ..analysis.compensation.apply import Correction, rows
from .files import staged_directory, write_json


def _residuals(c: Correction) -> dict | None:
    if c.measured is None:
        return None
    logged = ~np.isnan(c.measured)
    e = c.measured[logged] - c.predicted[logged, 0]
    return {"samples": int(logged.sum()), "rms_um": float(np.sqrt(np.mean(e ** 2)) * 1e6),
            "max_um": float(np.abs(e).max() * 1e6)} if e.size else None


def write_correction(corrections: list[Correction], out_dir: Path, context: dict) -> None:
    """Write ``correction.csv`` and ``correction.json`` into ``out_dir`` (replaced as a set)."""
    header, table = rows(corrections)
    summary = {**context, "conditions": {c.condition: {"samples": len(c.times), "x_mm": [x * 1e3 for x in c.x],
                                                       "residual": _residuals(c),
                                                       "outside_envelope": None if c.flags is None else c.flagged}
                                         for c in corrections},
               "sign": "the axis is corrected by minus the predicted value"}
    with staged_directory(Path(out_dir), replaces=("correction.csv", "correction.json")) as stage:
        with open(stage / "correction.csv", "w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle)
            writer.writerow(header)
            writer.writerows(table)
        write_json(stage / "correction.json", summary)


def print_correction(corrections: list[Correction], out_dir: Path) -> None:
    """One line per log: its samples and, where D was logged, the residual."""
    for c in corrections:
        what = f"E at {len(c.x)} positions" if c.x else "D"
        line = f"{out_dir}: {c.condition}: {what} at {len(c.times)} samples"
        r = _residuals(c)
        if r is not None:
            line += f"; measured D - predicted: RMS {r['rms_um']:.2f} um, max {r['max_um']:.2f} um"
        if c.flags is not None:
            first = next((f"{t:g} s: {f}" for t, f in zip(c.times, c.flags) if f), None)
            line += (f"; {c.flagged} of {len(c.times)} samples outside the law's training envelope (first at {first})"
                     if first else "; every sample within the law's training envelope")
        print(line)
