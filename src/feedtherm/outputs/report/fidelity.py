"""Sections on predictive accuracy: the headline, the inferred heats, the measurements' consistency.

The headline puts side by side what a user needs to judge the model: the model as described
(nothing fitted), the model calibrated on some conditions and judged on the others (held out,
and leave-one-condition-out), and the reference model's own in-sample deviations.  A measured value the
consistency check flags is reported apart, with its reason, never dropped.
"""

from __future__ import annotations

from ...analysis.consistency import COVERAGE
from ...analysis.validation_types import Comparison, Validation
from ..calibration_files import UNIT_SYMBOLS
from . import data
from .html import Cell, bullets, heading, number, paragraph, section, table


def _flagged(validation: Validation) -> set[tuple[str, str]]:
    return validation.consistency.excluded() if validation.consistency else set()


def _worst_comparison(rows: list[Comparison], unit: str, flagged: set) -> Comparison | None:
    rows = [r for r in rows if r.unit == unit and (r.condition, r.quantity) not in flagged]
    return max(rows, key=lambda r: abs(r.deviation), default=None)


def _worst_entry(rows: list[dict], unit: str) -> dict | None:
    rows = [r for r in rows if r["unit"] == unit and not r.get("flag")]
    return max(rows, key=lambda r: abs(r["deviation"]), default=None)


def _cell(value: float | None, where: str) -> Cell | str:
    if value is None:
        return "—"
    return Cell(f"{abs(value):.1f} ({where})" if where else f"{abs(value):.1f}", "num")


def _physics_row(validation: Validation, flagged: set) -> list:
    if validation.calibrated:  # a calibrated description validated: its fit conditions are in sample
        cells = [f"{data.CALIBRATED}, {validation.mode} mode: the description's fitted values, the conditions it "
                 "was fitted to included"]
    else:
        cells = [f"{data.UNCALIBRATED}, {validation.mode} mode, nothing fitted"]
    for unit in ("C", "um"):
        row = _worst_comparison(validation.comparisons, unit, flagged)
        cells.append(_cell(None if row is None else row.deviation,
                           "" if row is None else f"{row.condition} {row.quantity if unit == 'C' else 'D'}"))
    cells.append(_equilibrium_cell(validation))
    return cells


def _equilibrium_cell(validation: Validation) -> Cell | str:
    worst, where = None, ""
    for condition, minutes in validation.measured_equilibrium_min.items():
        run = validation.solutions.get(condition)
        if run is None:
            continue
        simulated = run.equilibrium_time
        deviation = float("inf") if simulated is None else simulated / 60.0 - minutes
        if worst is None or abs(deviation) > abs(worst):
            worst, where = deviation, condition
    if worst is None:
        return "—"
    if worst == float("inf"):
        return Cell(f"not reached in the run ({where})", "text")
    return _cell(worst, where)


def _calibration_rows(calibration: dict) -> list[list]:
    rows = []
    fit = ", ".join(calibration.get("fit_conditions", []))
    held = calibration.get("held_out", [])
    if held:
        predicted = ", ".join(dict.fromkeys(r["condition"] for r in held))
        rows.append([f"{data.CALIBRATED}, fitted to {fit}, predicting {predicted} (held out)"]
                    + [_entry_cell(_worst_entry(held, unit)) for unit in ("C", "um", "min")])
    series = (calibration.get("series") or {}).get("held_out") or []
    if series:  # a held-out test's whole transient, its drifts at the targets among it: the RMS of each series
        predicted = ", ".join(dict.fromkeys(r["condition"] for r in series))
        cells = [f"{data.CALIBRATED}, fitted to {fit}, predicting {predicted} over the whole transient "
                 "(RMS of each series)"]
        for unit in ("C", "um"):
            own = [r for r in series if r["unit"] == unit]
            worst = max(own, key=lambda r: r["rms_deviation"]) if own else None
            quantity = None if worst is None else ("D" if worst["quantity"] == "D_um" else worst["quantity"])
            cells.append("—" if worst is None else _cell(worst["rms_deviation"], f"{worst['condition']} {quantity}"))
        rows.append(cells + ["—"])
    cross = calibration.get("cross_validation")
    if cross:
        cells = [f"{data.CALIBRATED}, leave-one-condition-out (each condition predicted by a fit to the others)"]
        for key in ("largest_temperature_deviation_C", "largest_elongation_deviation_um",
                    "largest_equilibrium_deviation_min"):
            entry = cross.get(key)
            cells.append(_entry_cell(entry))
        rows.append(cells)
    return rows


def _entry_cell(entry: dict | None) -> Cell | str:
    if entry is None:
        return "—"
    quantity = "D" if entry["quantity"] == "D_um" else entry["quantity"]
    return _cell(entry["deviation"], f"{entry['condition']} {quantity}")


def headline_section(validation: Validation) -> str:
    title = "Headline: predictive accuracy"
    flagged = _flagged(validation)
    if not validation.comparisons and not validation.calibration:
        return ""
    rows = [_physics_row(validation, flagged)]
    calibration_rows = _calibration_rows(validation.calibration) if validation.calibration else []
    rows += calibration_rows
    worst = {unit: data.reference_worst(validation, unit) for unit in ("C", "um")}
    if any(value is not None for value in worst.values()):
        reference = validation.notes.reference_model or "the reference model"
        rows.append([f"{reference}, in sample (the measurements' reference values)",
                     "—" if worst["C"] is None else _cell(worst["C"], ""),
                     "—" if worst["um"] is None else _cell(worst["um"], ""), "—"])
    body = paragraph(
        "Largest |simulated − measured| over the conditions and points of each row. Held-out rows judge a "
        "calibration on conditions it was not fitted to: the only figures that say how the model will do on "
        "a new operating point. Measured values the consistency check flags are left out of these maxima and "
        "listed below with their deviation.")
    body += table(["", "temperature [K]", "elongation [µm]", "equilibrium time [min]"], rows,
                  model=data.BOTH if calibration_rows else data.runs_model(validation))
    if validation.calibration:
        parameters = validation.calibration.get("parameters", {})
        listed = ", ".join(f"{name} = {p['fitted']:.4g} ± {p['standard_error']:.2g}" + (" (at a bound)" if p.get("at_bound") else "")
                           for name, p in parameters.items())
        body += paragraph(f"Calibrated parameters (fit on {', '.join(validation.calibration.get('fit_conditions', []))}): "
                          f"{listed}.", css_class="note")
    else:
        body += paragraph("No calibration was given: run `feedtherm calibrate <system> --fit <conditions> --params … "
                          "--cross-validate`, then `feedtherm validate <system> --calibration <its output folder>` "
                          "(`make validate` does both).", css_class="note")
    body += _flag_lines(validation)
    return section("headline", title, body)


def _flag_lines(validation: Validation) -> str:
    if not validation.consistency or not validation.consistency.flags:
        return ""
    by_key = {(c.condition, c.quantity): c for c in validation.comparisons}
    items = []
    for flag in validation.consistency.flags:
        row = by_key.get((flag.condition, flag.quantity))
        deviation = (f"; the {data.runs_model(validation)} deviates by {row.deviation:+.1f} {UNIT_SYMBOLS[row.unit]}"
                     if row else "")
        items.append(f"{flag.condition} {flag.quantity} (flagged): {flag.reason}{deviation}.")
    return heading("Flagged measurements") + bullets(items)


def consistency_section(validation: Validation) -> str:
    title = "Measurement consistency"
    report = validation.consistency
    if report is None:
        return ""
    body = paragraph(
        "From the measurements alone, no model: (1) across conditions the elongation must follow the measured "
        "temperatures along one affine law D = a + s·T̄ (linear thermoelasticity, a fixed reference "
        "temperature, one screw); a condition off the line through the others is flagged; (2) a faster drive at "
        "the same ambient is not cooler; (3) an ambient shift at the same speeds moves the rises above ambient "
        f"only a little. Tolerances: {COVERAGE:g} standard uncertainties of the declared measurement uncertainties.")
    if report.law is not None:
        law = report.law
        body += paragraph(
            f"Elongation law through {', '.join(law.conditions)}: D = {law.intercept_um:.1f} µm + "
            f"{law.slope_um_per_k:.2f} µm/K · T̄ (T̄ the mean of {', '.join(law.proxy)}), largest residual "
            f"{law.max_residual_um:.1f} µm.")
    if report.flags:
        body += table(["condition", "quantity", "check", "reason"],
                      [[f.condition, f.quantity, f.check, Cell(f.reason, "text small")] for f in report.flags])
    else:
        body += paragraph("Nothing flagged.")
    if report.notes:
        body += bullets(report.notes)
    return section("consistency", title, body)


def inferred_heat_section(validation: Validation) -> str:
    title = "Inferred heat per source"
    if not validation.inferred:
        return ""
    body = paragraph(
        "Which heats explain each condition's measured temperatures and elongation: non-negative least squares "
        "with the model's own steady transfer matrix and the loss models' heats as a prior (docs/inverse.md; "
        "`feedtherm infer`). \"From data\" is the share of the estimate the measurements determine (the rest "
        "comes from the prior). A loss model far outside the interval of a well-resolved source is the loss "
        "model to doubt.")
    blocks = []
    for inference in validation.inferred:
        rows = [[e.group, number(e.loss_model), number(e.inferred) + (" (at 0)" if e.at_bound else ""),
                 f"{e.low:.1f} – {e.high:.1f}", f"{100 * e.resolution:.0f} %"] for e in inference.estimates]
        blocks.append(heading(f"Condition {inference.condition}: χ² {inference.chi2:.1f} over "
                              f"{len(inference.observations)} measurements", 4)
                      + table(["source", "loss models [W]", "inferred [W]", "95 % interval [W]", "from data"], rows,
                              model=data.runs_model(validation)))
        if inference.not_told_apart:
            pairs = "; ".join(f"{a} and {b} ({r:+.2f})" for a, b, r in inference.not_told_apart)
            blocks.append(paragraph(f"Not told apart by these sensors: {pairs}.", css_class="note"))
    return section("inferred-heat", title, body + "".join(blocks))


__all__ = ["headline_section", "consistency_section", "inferred_heat_section"]
