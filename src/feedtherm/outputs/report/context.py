"""Sensitivity ranking, inconsistencies in the data, calibrated values, provenance."""

from __future__ import annotations

import math

from ...analysis.validation_types import ELONGATION_QUANTITY, Sensitivity, Validation
from . import data, figures
from .html import (Cell, Raw, bullets, code, definition_table, esc, heading, number, paragraph, png_image, section,
                   table)

TOP_SENSITIVITIES = 15  # in the bar chart
TABLE_ROWS = 30  # in the open table; the rest folded below it

def sensitivity_section(validation: Validation) -> str:
    title = "Sensitivity ranking"
    rows = ranked(validation.sensitivities)
    if not rows:
        return ""
    intro = paragraph(
        f"Each declared assumption of the {data.runs_model(validation)} perturbed alone: its value multiplied by the "
        f"factor shown, everything else "
        f"unchanged, and the change of the steady state (cycle-averaged) of condition "
        f"{validation.sensitivity_condition}. One parameter at a time: the effects do not add up when several "
        f"values change together. Sorted by the largest temperature change over the sensors.")
    top = rows[:TOP_SENSITIVITIES]
    png = figures.sensitivity_bars(top, validation.sensitivity_condition)
    caption = f"Top {len(top)} of {len(rows)}" if len(rows) > len(top) else ""
    model = data.runs_model(validation)
    body = intro + png_image(png, "Sensitivity ranking", caption=caption) + sensitivity_table(rows[:TABLE_ROWS],
                                                                                              model=model)
    rest = rows[TABLE_ROWS:]
    if rest:  # complete but folded: <details> opens without JavaScript
        body += (f"<details><summary>The other {len(rest)} parameters</summary>"
                 f"{sensitivity_table(rest, first_rank=TABLE_ROWS + 1, model=model)}</details>")
    return section("sensitivity", title, body)


def sensitivity_table(rows: list[Sensitivity], first_rank: int = 1, model: str = data.UNCALIBRATED) -> str:
    body = [[str(rank), Cell(_parameter_cell(row), "text"), f"×{row.factor:g}", number(row.max_temperature_effect, 2),
             _largest_sensor(row), number(_abs_d(row), 2), Cell(row.assumption, "text small")]
            for rank, row in enumerate(rows, start=first_rank)]
    return table(["rank", "parameter", "factor", "max |ΔT| [K]", "at", "|ΔD| [µm]", "assumption source"], body,
                 model=model)


def _parameter_cell(row: Sensitivity) -> Raw:
    """The path as code, and under it the readable name where there is one."""
    if not row.name:
        return code(row.parameter)
    return Raw(f"{code(row.parameter).html}<br><span class=\"muted\">{esc(row.name)}</span>")


def ranked(rows: list[Sensitivity]) -> list[Sensitivity]:
    """By largest |ΔT| over the sensors, then |ΔD|, largest first."""
    return sorted(rows, key=lambda r: (r.max_temperature_effect, _abs_d(r) if math.isfinite(_abs_d(r)) else 0.0),
                  reverse=True)


def _abs_d(row: Sensitivity) -> float:
    return abs(row.effect.get(ELONGATION_QUANTITY, math.nan))


def _largest_sensor(row: Sensitivity) -> str:
    temperatures = [q for q in row.effect if q != ELONGATION_QUANTITY]
    return max(temperatures, key=lambda q: abs(row.effect[q])) if temperatures else "—"


def inconsistencies_section(validation: Validation) -> str:
    found = validation.inconsistencies
    body = heading("Found in this validation (feedtherm check and the data)")
    body += bullets(found) if found else paragraph("None reported.")
    if validation.notes.findings:
        body += heading("Known from the review of the source (the bench's report notes)")
        body += bullets(list(validation.notes.findings))
    return section("inconsistencies", "Inconsistencies in the data", body)


def calibrated_section(validation: Validation) -> str:
    title = "Calibrated values"
    entries = validation.calibrated
    if not entries:
        given = validation.calibration
        if given:
            fitted = ", ".join(given.get("parameters", {}))
            return section("calibrated", title, paragraph(
                f"The runs of this report are the {data.UNCALIBRATED}: every value of the description is from the "
                f"source or a declared assumption, nothing fitted. The calibration given with --calibration fitted "
                f"{fitted} to {', '.join(given.get('fit_conditions', []))}: the rows marked {data.CALIBRATED} show "
                "it (its fitted values in the headline's note; its calibrated.toml validates as the calibrated "
                "model)."))
        return section("calibrated", title, paragraph(
            "None: every value is from the source or a declared assumption; nothing was fitted to the "
            "measurements, so every comparison above is a prediction."))
    keys: list[str] = []
    for entry in entries:
        keys += [k for k in entry if k not in keys]
    rows = [[_plain(entry.get(k)) for k in keys] for entry in entries]
    intro = paragraph("Values fitted by feedtherm calibrate, with the conditions they were fitted on: comparisons "
                      "on those conditions are not independent of the measurements.")
    return section("calibrated", title, intro + table(keys, rows, css_class="text"))


def assumptions_section(validation: Validation) -> str:
    title = "Assumptions and provenance"
    parts = [heading("Assumptions in use")]
    if validation.assumptions:
        rows = [[_paths(entry.get("paths") or []), _plain(entry.get("source")), _plain(entry.get("reason"))]
                for entry in validation.assumptions]
        parts.append(table(["paths", "source", "reason"], rows, css_class="text"))
    else:
        parts.append(paragraph("No values are marked as assumptions."))
    parts.append(heading("Provenance"))
    pairs = [(key.replace("_", " "), _plain(value)) for key, value in validation.provenance.items()
             if key != "assumptions"]
    pairs.append(("measurement source", validation.measurement_source or "—"))
    pairs += [(key, value) for key, value in (("model", validation.model), ("mode", validation.mode))
              if key not in validation.provenance]
    if validation.wall_time_s:
        pairs.append(("wall time of the validation", f"{validation.wall_time_s:.1f} s"))
    parts.append(definition_table(pairs))
    return section("assumptions", title, "".join(parts))


def _paths(paths: list[str]) -> Raw | str:
    return Raw("<br>".join(code(p).html for p in paths)) if paths else "—"


def _plain(value) -> str:
    """A value as short text: lists joined, floats to 4 significant digits, None as a dash."""
    if value is None:
        return "—"
    if isinstance(value, (list, tuple)):
        return ", ".join(_plain(v) for v in value)
    if isinstance(value, dict):
        return "; ".join(f"{k}: {_plain(v)}" for k, v in value.items())
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)

