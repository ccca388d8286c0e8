"""The title and summary; the deviation tables (the measurements against the model)."""

from __future__ import annotations

from datetime import datetime, timezone

from ...analysis.validation_types import ELONGATION_QUANTITY, Comparison, Validation
from . import data
from .html import Cell, esc, grid, heading, number, paragraph, paragraph_html, section, table

def title_section(validation: Validation, generated: datetime | None = None) -> str:
    """``<header>``: title, run facts and the summary paragraph (the contents are the page's)."""
    when = (generated or datetime.now(timezone.utc)).strftime("%Y-%m-%d %H:%M UTC")
    version = validation.provenance.get("feedtherm_version", "")
    facts = [f"system {validation.system_name}", f"mode {validation.mode}", f"model {validation.model}",
             f"runs of the {data.runs_model(validation)}", f"generated {when}"]
    if version:
        facts.append(f"feedtherm {version}")
    return (f"<header><h1>Validation report — {esc(validation.system_name)}</h1>"
            f"{paragraph(' · '.join(facts), css_class='meta')}"
            f"{paragraph(summary_text(validation), css_class='summary')}</header>")


def summary_text(validation: Validation) -> str:
    """One paragraph: the largest deviations, the bias, and how the reference model did."""
    temperatures = [c for c in validation.comparisons if c.unit == "C"]
    elongations = [c for c in validation.comparisons if c.unit != "C"]
    source = validation.measurement_source or "the measurements"
    parts = [f"Compared with the measurements ({source}), the {data.runs_model(validation)}'s"]
    if temperatures:
        worst = validation.largest("temperature")
        parts.append(f"largest temperature deviation is {_signed(worst.deviation)} K at {worst.quantity} in "
                     f"condition {worst.condition} (simulated {worst.simulated:.1f} °C, measured "
                     f"{worst.measured:.1f} °C)")
    if elongations:
        worst = validation.largest("elongation")
        parts.append(f"{'its ' if temperatures else ''}largest elongation deviation is {_signed(worst.deviation)} µm "
                     f"in condition {worst.condition} (simulated {worst.simulated:.1f} µm, measured "
                     f"{worst.measured:.1f} µm)")
    if len(parts) == 1:
        return "No comparisons with measurements were made."
    text = parts[0] + " " + " and ".join(parts[1:]) + "."
    text += " " + headline(temperatures, elongations, reference_name(validation))
    return (text + " " + calibrated_summary(validation)).strip()


def calibrated_summary(validation: Validation) -> str:
    """The calibration given with ``--calibration``: its largest held-out deviations (flagged values left out)."""
    calibration = validation.calibration
    held = [r for r in (calibration or {}).get("held_out", []) if r.get("unit") in ("C", "um") and not r.get("flag")]
    if not held:
        return ""
    figures = []
    for unit, symbol in (("C", "K"), ("um", "µm")):
        worst = max((r for r in held if r["unit"] == unit), key=lambda r: abs(r["deviation"]), default=None)
        if worst is not None:
            figures.append(f"{abs(worst['deviation']):.1f} {symbol}")
    fit = ", ".join(data.fit_conditions(validation))
    predicted = ", ".join(dict.fromkeys(r["condition"] for r in held))
    return (f"The calibrated model (fitted to {fit}) predicts the held-out {predicted} within "
            f"{' and '.join(figures)}.")


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
    model = data.runs_model(validation)
    calibrated = data.calibrated_values(validation)
    fit = data.fit_conditions(validation)
    blocks = []
    for condition in data.conditions(validation):
        quantities = [q for q in validation.quantities if (condition, q) in rows]
        if quantities:
            blocks.append(condition_table(condition, [rows[(condition, q)] for q in quantities], bands, reference,
                                          model=model, calibrated=calibrated, fitted=condition in fit))
    if not blocks:
        return ""
    where = ", ".join(f"{q} {data.location(validation, q)}" for q in validation.temperature_quantities
                      if data.location(validation, q))
    legend = " ".join(f'<span class="dev-{band}">{esc(text)}</span>'
                      for band, text in enumerate(_band_texts(bands, reference, validation)))
    compared = [f"the {model}'s value (the runs of this report)", "the measurement"]
    if calibrated:
        runs = (validation.calibration or {}).get("model")
        compared.append(f"the calibrated model's value (the calibration given, fitted to {', '.join(fit)}"
                        + (f"; its runs: {runs}" if runs else "") + "), marked held out on the conditions it was "
                        "not fitted to")
    if any(c.paper_simulated is not None for c in validation.comparisons):
        compared.append(f"{reference}'s simulated value where the measurements carry it")
    body = (paragraph(f"Per condition: {', '.join(compared)}, and the deviations Δ = simulated − measured of each "
                      "model. Temperatures in °C, their deviations in K; the elongation D and its deviations in µm. "
                      "Deviations are coloured by magnitude:")
            + paragraph_html(legend)
            + grid(blocks)
            + (paragraph(f"Measuring points: {where}; D is the screw's axial elongation.", css_class="note")
               if where else "")
            + heading("Largest |deviation| per condition")
            + largest_table(validation, bands, calibrated))
    return section("deviations", "Deviation from the measurements", body)


def condition_table(condition: str, rows: list[Comparison], bands: dict[str, tuple[float, float, float]],
                    reference: str = "the reference model", *, model: str = data.UNCALIBRATED,
                    calibrated: dict[tuple[str, str], data.CalibratedValue] | None = None,
                    fitted: bool = False) -> str:
    """One condition: quantities as columns; the runs' model, measured, the calibrated model's (where a
    calibration gives its values), the reference model's (where the measurements carry it), then the
    deviations of each, as rows."""
    headers = [""] + [f"{data.label(r.quantity)} [{_unit(r)}]" for r in rows]
    values = [(model, [r.simulated for r in rows])]
    own = [(calibrated or {}).get((condition, r.quantity)) for r in rows]
    if any(v is not None for v in own):
        where = "fitted to it" if fitted else "held out"
        values.append((f"{data.CALIBRATED} ({where})", [None if v is None else v.simulated for v in own]))
    if any(r.paper_simulated is not None for r in rows):
        values.append((reference, [r.paper_simulated for r in rows]))
    body = [[values[0][0]] + [number(v) for v in values[0][1]], ["measured"] + [number(r.measured) for r in rows]]
    body += [[name] + [number(v) for v in simulated] for name, simulated in values[1:]]
    body += [[f"Δ {name}"] + [deviation_cell(None if v is None else v - r.measured, bands[r.unit])
                              for v, r in zip(simulated, rows)] for name, simulated in values]
    tag = data.BOTH if len(values) > 1 and values[1][0].startswith(data.CALIBRATED) else model
    return table(headers, body, caption=f"Condition {condition}", model=tag)


def largest_table(validation: Validation, bands: dict[str, tuple[float, float, float]],
                  calibrated: dict[tuple[str, str], data.CalibratedValue] | None = None) -> str:
    """Per condition the largest |deviation| of a temperature and D's, of the runs' model (and the
    calibrated model's, where a calibration gives its values)."""
    per_condition = validation.largest_per_condition()
    model = data.runs_model(validation)
    calibrated = calibrated or {}
    body = []
    for condition in data.conditions(validation):
        slot = per_condition.get(condition, {})
        temp, elong = slot.get("temperature"), slot.get("elongation")
        body.append([condition, model,
                     "—" if temp is None else data.label(temp.quantity),
                     "—" if temp is None else deviation_cell(temp.deviation, bands["C"]),
                     "—" if elong is None else deviation_cell(elong.deviation, bands["um"])])
        mine = [(c, calibrated[(c.condition, c.quantity)].simulated - c.measured)
                for c in validation.comparisons if c.condition == condition and (c.condition, c.quantity) in calibrated]
        if mine:
            held = any(calibrated[(c.condition, c.quantity)].held_out for c, _ in mine)
            temps = [(c, d) for c, d in mine if c.unit == "C"]
            worst_t = max(temps, key=lambda p: abs(p[1]), default=None)
            worst_d = max(((c, d) for c, d in mine if c.unit != "C"), key=lambda p: abs(p[1]), default=None)
            body.append([condition, f"{data.CALIBRATED} ({'held out' if held else 'fitted to it'})",
                         "—" if worst_t is None else data.label(worst_t[0].quantity),
                         "—" if worst_t is None else deviation_cell(worst_t[1], bands["C"]),
                         "—" if worst_d is None else deviation_cell(worst_d[1], bands["um"])])
    tag = data.BOTH if calibrated else model
    return table(["condition", "model", "point", "largest temperature deviation [K]", "elongation deviation [µm]"],
                 body, model=tag)


def deviation_cell(value: float | None, limits: tuple[float, float, float]) -> Cell | str:
    """A signed deviation with the CSS class of its magnitude band (``dev-0`` … ``dev-3``) among ``limits``."""
    if value is None:
        return "—"
    return Cell(number(value, 1, signed=True), f"dev-{data.deviation_band(value, limits)}")


def _band_texts(bands: dict[str, tuple[float, float, float]], reference: str, validation: Validation) -> list[str]:
    t, u = bands["C"], bands["um"]
    known = [what for unit, what in (("C", "K"), ("um", "µm")) if data.reference_worst(validation, unit) is not None]
    middle = f"≤ {t[1]:g} K / {u[1]:g} µm"
    if known:
        middle += f" ({reference}'s worst{'' if len(known) == 2 else ' in ' + known[0]})"
    return [f"≤ {t[0]:g} K / {u[0]:g} µm", middle, f"≤ {t[2]:g} K / {u[2]:g} µm", f"> {t[2]:g} K / {u[2]:g} µm"]


def _unit(row: Comparison) -> str:
    return "µm" if row.unit == "um" or row.quantity == ELONGATION_QUANTITY else "°C"


def _signed(value: float) -> str:
    return number(value, 1, signed=True)

