"""Sections 1–2: title and summary; the deviation tables (the measurements against the model)."""

from __future__ import annotations

from datetime import datetime, timezone

from ...analysis.validation_types import ELONGATION_QUANTITY, Comparison, Validation
from . import data
from .html import Cell, esc, grid, heading, number, paragraph, paragraph_html, section, table

SECTIONS = (
    ("headline", "Headline: predictive accuracy"),
    ("deviations", "Deviation from the measurements"),
    ("sensor-curves", "Sensor curves per condition"),
    ("screw-field", "Screw temperature over time and position"),
    ("equilibrium", "Equilibrium time"),
    ("trends", "Final values against speed and ambient"),
    ("dual-single", "Dual drive against single drive"),
    ("heat-budget", "Heat budget per source"),
    ("inferred-heat", "Inferred heat per source"),
    ("consistency", "Measurement consistency"),
    ("sensitivity", "Sensitivity ranking"),
    ("inconsistencies", "Inconsistencies in the data"),
    ("calibrated", "Calibrated values"),
    ("assumptions", "Assumptions and provenance"),
)


def title_section(validation: Validation, generated: datetime | None = None) -> str:
    """``<header>``: title, run facts, the summary paragraph and the contents."""
    when = (generated or datetime.now(timezone.utc)).strftime("%Y-%m-%d %H:%M UTC")
    version = validation.provenance.get("feedtherm_version", "")
    facts = [f"system {validation.system_name}", f"mode {validation.mode}", f"model {validation.model}",
             f"generated {when}"]
    if version:
        facts.append(f"feedtherm {version}")
    sections = list(SECTIONS)
    if validation.transients:  # the measured time series' section follows the sensor curves
        sections.insert(3, ("measured-series", "Measured time series"))
    contents = "".join(f'<li><a href="#{anchor}">{esc(title)}</a></li>' for anchor, title in sections)
    return (f"<header><h1>Validation report — {esc(validation.system_name)}</h1>"
            f"{paragraph(' · '.join(facts), css_class='meta')}"
            f"{paragraph(summary_text(validation), css_class='summary')}"
            f"<nav><strong>Contents</strong><ol>{contents}</ol></nav></header>")


def summary_text(validation: Validation) -> str:
    """One paragraph: the largest deviations, the bias, and how the reference model did."""
    temperatures = [c for c in validation.comparisons if c.unit == "C"]
    elongations = [c for c in validation.comparisons if c.unit != "C"]
    source = validation.measurement_source or "the measurements"
    parts = [f"Compared with the measurements ({source})"]
    if temperatures:
        worst = validation.largest("temperature")
        parts.append(f"the largest temperature deviation is {_signed(worst.deviation)} K at {worst.quantity} in "
                     f"condition {worst.condition} (simulated {worst.simulated:.1f} °C, measured "
                     f"{worst.measured:.1f} °C)")
    if elongations:
        worst = validation.largest("elongation")
        parts.append(f"the largest elongation deviation is {_signed(worst.deviation)} µm in condition "
                     f"{worst.condition} (simulated {worst.simulated:.1f} µm, measured {worst.measured:.1f} µm)")
    if len(parts) == 1:
        return "No comparisons with measurements were made."
    text = parts[0] + ", " + " and ".join(parts[1:]) + "."
    return text + " " + headline(temperatures, elongations, reference_name(validation))


def reference_name(validation: Validation) -> str:
    """Who made the measurements' ``reference_simulated`` values (the bench's report notes)."""
    return validation.notes.reference_model or "the reference model"


def headline(temperatures: list[Comparison], elongations: list[Comparison],
             reference: str = "the reference model") -> str:
    """The finding: the model's bias and how many points are as close as the reference model's own."""
    sentences = []
    if temperatures:
        bias = sum(c.deviation for c in temperatures) / len(temperatures)
        below = sum(c.deviation < 0 for c in temperatures)
        direction = "below" if bias < 0 else "above"
        sentences.append(f"On average the model is {abs(bias):.1f} K {direction} the measured temperatures "
                         f"({below} of {len(temperatures)} points are below).")
    counts = []
    for rows, unit, name in ((temperatures, "C", "temperatures"), (elongations, "um", "elongations")):
        if rows:
            limit = reference_worst(rows)
            if limit is None:
                continue
            inside = sum(abs(c.deviation) <= limit + 1e-9 for c in rows)
            symbol = "K" if unit == "C" else "µm"
            counts.append(f"{inside} of {len(rows)} {name} within {limit:.1f} {symbol}")
    if counts:
        sentences.append(f"Measured against {reference}'s own worst deviation: " + ", ".join(counts) + ".")
    return " ".join(sentences)


def reference_worst(rows: list[Comparison]) -> float | None:
    """Largest |reference simulated − measured| among ``rows``; None if they carry no reference values."""
    values = [abs(c.paper_simulated - c.measured) for c in rows if c.paper_simulated is not None]
    return max(values) if values else None


def deviations_section(validation: Validation) -> str:
    rows = data.comparisons_by_key(validation)
    bands = {unit: data.deviation_bands(validation, unit) for unit in ("C", "um")}
    reference = reference_name(validation)
    blocks = []
    for condition in data.conditions(validation):
        quantities = [q for q in validation.quantities if (condition, q) in rows]
        if quantities:
            blocks.append(condition_table(condition, [rows[(condition, q)] for q in quantities], bands, reference))
    if not blocks:
        return section("deviations", "Deviation from the measurements",
                       paragraph("No measurements were compared."))
    where = ", ".join(f"{q} {data.location(validation, q)}" for q in validation.temperature_quantities
                      if data.location(validation, q))
    legend = " ".join(f'<span class="dev-{band}">{esc(text)}</span>'
                      for band, text in enumerate(_band_texts(bands, reference)))
    body = (paragraph(f"Per condition: this model's value, the measurement, {reference}'s simulated value where "
                      "the measurements carry it, and the deviations Δ = simulated − measured of both models. Temperatures in °C, their "
                      "deviations in K; the elongation D and its deviations in µm. Deviations are coloured by "
                      "magnitude:")
            + paragraph_html(legend)
            + grid(blocks)
            + paragraph(f"Measuring points: {where}; D is the screw's axial elongation.", css_class="note")
            + heading("Largest |deviation| per condition")
            + largest_table(validation, bands))
    return section("deviations", "Deviation from the measurements", body)


def condition_table(condition: str, rows: list[Comparison], bands: dict[str, tuple[float, float, float]],
                    reference: str = "the reference model") -> str:
    """One condition: quantities as columns; simulated, measured, reference, deviations as rows."""
    headers = [""] + [f"{data.label(r.quantity)} [{_unit(r)}]" for r in rows]
    body = [
        ["this model"] + [number(r.simulated) for r in rows],
        ["measured"] + [number(r.measured) for r in rows],
        [reference] + [number(r.paper_simulated) for r in rows],
        ["Δ this model"] + [deviation_cell(r.deviation, bands[r.unit]) for r in rows],
        [f"Δ {reference}"] + [deviation_cell(None if r.paper_simulated is None
                                             else r.paper_simulated - r.measured, bands[r.unit]) for r in rows],
    ]
    return table(headers, body, caption=f"Condition {condition}")


def largest_table(validation: Validation, bands: dict[str, tuple[float, float, float]]) -> str:
    per_condition = validation.largest_per_condition()
    body = []
    for condition in data.conditions(validation):
        slot = per_condition.get(condition, {})
        temp, elong = slot.get("temperature"), slot.get("elongation")
        body.append([
            condition,
            "—" if temp is None else data.label(temp.quantity),
            "—" if temp is None else deviation_cell(temp.deviation, bands["C"]),
            "—" if elong is None else deviation_cell(elong.deviation, bands["um"]),
        ])
    return table(["condition", "point", "largest temperature deviation [K]", "elongation deviation [µm]"], body)


def deviation_cell(value: float | None, limits: tuple[float, float, float]) -> Cell | str:
    """A signed deviation with the CSS class of its magnitude band (``dev-0`` … ``dev-3``) among ``limits``."""
    if value is None:
        return "—"
    return Cell(number(value, 1, signed=True), f"dev-{data.deviation_band(value, limits)}")


def _band_texts(bands: dict[str, tuple[float, float, float]], reference: str) -> list[str]:
    t, u = bands["C"], bands["um"]
    return [f"≤ {t[0]:g} K / {u[0]:g} µm", f"≤ {t[1]:g} K / {u[1]:g} µm ({reference}'s worst, where known)",
            f"≤ {t[2]:g} K / {u[2]:g} µm", f"> {t[2]:g} K / {u[2]:g} µm"]


def _unit(row: Comparison) -> str:
    return "µm" if row.unit == "um" or row.quantity == ELONGATION_QUANTITY else "°C"


def _signed(value: float) -> str:
    return number(value, 1, signed=True)

