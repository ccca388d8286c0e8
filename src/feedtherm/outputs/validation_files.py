"""`feedtherm validate` outputs: validation.csv, validation.json, report.html, a console table, and
transients.csv with transient_samples.csv where the measurements are time series."""

from __future__ import annotations

import csv
import sys
from pathlib import Path

from rich.console import Console
from rich.table import Table

from ..analysis.validation_types import Validation
from .files import staged_directory, write_json
from .drift_test_files import drift_test_summary, write_drift_test_files
from .transient_files import SAMPLES_CSV, TRANSIENTS_CSV, transient_lines, transient_summary, write_transient_files

VALIDATION_HEADER = ["condition", "quantity", "unit", "simulated", "measured", "paper_simulated", "deviation"]


def write_validation(validation: Validation, out_dir: Path) -> list[Path]:
    """Write validation.csv, validation.json and report.html into ``out_dir``, all or none."""
    from .report import write_report  # matplotlib and the HTML builder load only here

    with staged_directory(out_dir) as stage:
        write_validation_csv(validation, stage / "validation.csv")
        write_json(stage / "validation.json", validation_summary(validation))
        write_report(validation, stage / "report.html")
        write_transient_files(validation.transients, stage)  # only with measured time series
        write_drift_test_files(validation.drift_tests, stage)  # only with tests measured at targets
        names = sorted(p.name for p in stage.iterdir())
    return [Path(out_dir) / name for name in names]


def write_validation_csv(validation: Validation, path: Path) -> None:
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(VALIDATION_HEADER)
        for c in validation.comparisons:
            paper = "" if c.paper_simulated is None else f"{c.paper_simulated:.4g}"
            writer.writerow([c.condition, c.quantity, c.unit, f"{c.simulated:.4f}", f"{c.measured:.4g}", paper,
                             f"{c.deviation:.4f}"])


def validation_summary(validation: Validation) -> dict:
    per_condition = {
        condition: {kind: {"quantity": c.quantity, "deviation": c.deviation} for kind, c in kinds.items()}
        for condition, kinds in validation.largest_per_condition().items()
    }
    t, d = validation.largest("temperature"), validation.largest("elongation")
    return {
        "system": validation.system_name,
        "mode": validation.mode,
        "model": validation.model,
        "largest_temperature_deviation_C": None if t is None else {"condition": t.condition, "quantity": t.quantity,
                                                                   "deviation": t.deviation},
        "largest_elongation_deviation_um": None if d is None else {"condition": d.condition, "deviation": d.deviation},
        "largest_per_condition": per_condition,
        "equilibrium_time_min": {c: (None if s.equilibrium_time is None else s.equilibrium_time / 60.0)
                                 for c, s in validation.solutions.items()},
        "stated_equilibrium_time_min": validation.measured_equilibrium_min,
        "energy_balance_error": {c: s.energy.relative_error for c, s in validation.solutions.items()},
        "measurements": validation.measurement_source,
        "flagged_measurements": [{"condition": f.condition, "quantity": f.quantity, "check": f.check, "reason": f.reason}
                                 for f in (validation.consistency.flags if validation.consistency else [])],
        "inferred_heat_W": {i.condition: {e.group: {"loss_models": e.loss_model, "inferred": e.inferred,
                                                    "interval95": [e.low, e.high], "from_data": e.resolution}
                                          for e in i.estimates} for i in validation.inferred},
        "calibration": None if validation.calibration is None else {
            "fit_conditions": validation.calibration.get("fit_conditions"),
            "held_out": validation.calibration.get("held_out"),
            "cross_validation": validation.calibration.get("cross_validation")},
        "wall_time_s": validation.wall_time_s,
        "provenance": validation.provenance,
    } | ({"transients": transient_summary(validation.transients)} if validation.transients else {}) \
      | ({"iso230_3": drift_test_summary(validation.drift_tests)} if validation.drift_tests else {})


def print_validation(validation: Validation, out_dir: Path, console: Console | None = None) -> None:
    console = console or Console(width=None if sys.stdout.isatty() else 120)
    table = Table(title=f"{validation.system_name}: simulated − measured ({validation.mode} mode, {validation.model} model)",
                  title_justify="left")
    quantities = validation.quantities
    for column in ("condition", *quantities[:-1], "D [µm]", "largest |ΔT| [K]", "|ΔD| [µm]"):
        table.add_column(column, justify="left" if column == "condition" else "right")
    largest = validation.largest_per_condition()
    for condition in validation.solutions:
        rows = {c.quantity: c for c in validation.comparisons if c.condition == condition}
        cells = [f"{rows[q].deviation:+.1f}" if q in rows else "—" for q in quantities]
        t, d = largest[condition].get("temperature"), largest[condition].get("elongation")
        table.add_row(condition, *cells, f"{abs(t.deviation):.1f} ({t.quantity})" if t else "—",
                      f"{abs(d.deviation):.1f}" if d else "—")
    console.print(table)
    t, d = validation.largest("temperature"), validation.largest("elongation")
    reference = [(validation.reference_worst(unit), symbol) for unit, symbol in (("C", "K"), ("um", "µm"))]
    said = (f"; {validation.notes.reference_model or 'the reference model'} is off by up to "
            + " and ".join(f"{value:.1f} {symbol}" for value, symbol in reference if value is not None)
            if any(value is not None for value, _ in reference) else "")
    largest = ([f"temperature {abs(t.deviation):.1f} K ({t.condition} {t.quantity})"] if t else []) \
        + ([f"elongation {abs(d.deviation):.1f} µm ({d.condition})"] if d else [])
    console.print("largest |deviation|: " + (", ".join(largest) or "none compared") + said)
    for flag in (validation.consistency.flags if validation.consistency else []):
        console.print(f"flagged measurement {flag.condition} {flag.quantity}: {flag.reason}")
    if validation.calibration and validation.calibration.get("cross_validation"):
        cross = validation.calibration["cross_validation"]
        t, d = cross.get("largest_temperature_deviation_C"), cross.get("largest_elongation_deviation_um")
        if t and d:
            console.print(f"calibrated, leave-one-condition-out: temperature {abs(t['deviation']):.1f} K "
                          f"({t['condition']} {t['quantity']}), elongation {abs(d['deviation']):.1f} µm ({d['condition']})")
    if validation.uncertainty is not None:
        low, high = (round(100 * b) for b in validation.uncertainty["summary"].get("band", (0.05, 0.95)))
        console.print("measured values inside the " + f"{low}–{high} % band: " + ", ".join(
            f"{s['label']} {s['coverage']['inside']} of {s['coverage']['total']}"
            for s in validation.uncertainty["summary"]["sets"]))
    for line in transient_lines(validation.transients):
        console.print(line)
    series = f", {TRANSIENTS_CSV}, {SAMPLES_CSV}" if validation.transients else ""
    console.print(f"wrote {out_dir}/validation.csv, validation.json, report.html{series} ({validation.wall_time_s:.1f} s)")
