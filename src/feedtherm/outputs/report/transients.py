"""Sensor curves, the screw field, the equilibrium time.

The equilibrium section's physics paragraphs appear where the runs hold what they speak of (an
ambient series, a speed series, a coupled description) and state the run's own figures.
"""

from __future__ import annotations

import numpy as np

from ...analysis.validation_types import ELONGATION_QUANTITY, Validation
from ...constants import KELVIN_OFFSET
from ...solution import Solution
from ...solution.equilibrium import FLUCTUATION_K, RISE_FRACTION, WINDOW_S
from . import data, figures
from .html import heading, number, paragraph, png_image, section, table

NOT_REACHED = "not reached in the run"
CRITERION = (f"every sensor within {100 * RISE_FRACTION:.0f} % of its steady rise and changing by less than "
             f"{FLUCTUATION_K:g} K over {WINDOW_S:.0f} s")
LINEAR_PHYSICS = (
    "Why the ambient temperature cannot change the equilibrium time when the coefficients are frozen. With the "
    "convection and radiation coefficients frozen for a run, the model is linear: C·dT/dt = "
    "−G·(T − T_amb) + q. Written for the rise θ = T − T_amb it reads C·dθ/dt = −G·θ + q with θ = 0 at the "
    "start, and the ambient temperature has disappeared: it shifts every temperature by the same amount and "
    "leaves every rise, and so the equilibrium time, unchanged: conditions at the same speeds that differ only "
    "in ambient must reach equilibrium at the same time. A warmer room does not make heat \"more difficult to "
    "dissipate\": the heat lost depends on T − T_amb, not on T_amb."
)
COUPLED_PHYSICS = (
    "This description couples them (temperatures.coupling = \"nonlinear\"): the convection and radiation "
    "coefficients, the lubricants' viscosities and the windings' resistances follow the simulated "
    "temperatures, so the equation above is linear only within a step. The ambient then also acts through the "
    "air's and the oils' properties (a cooler room: thicker oil, more bearing heat; warmer windings: more "
    "copper loss)."
)
TIME_CONSTANT_PHYSICS = (
    "The time constants are the eigenvalues of C⁻¹G: they follow from the heat capacities and the "
    "conductances (contacts, conduction, convection), not from the heat generated. Doubling every heat "
    f"doubles every rise and leaves the time to reach {100 * RISE_FRACTION:.0f} % of it unchanged."
)
SPEED_PHYSICS = (
    "What changes with speed: the heats grow (bearing and motor losses with the shaft speeds, the screw–nut "
    "friction with the relative speed), which raises the steady temperatures but not the time constants. "
    "The speed does shorten the time constants through the forced convection of the rotating screw and nut "
    "(h grows with the rotational Reynolds number; an overlay's printed CHTCs are scaled the same way). "
    "It also moves the heat between fast parts (screw, nut) and slow ones "
    "(housings, table, base), which changes which time constants dominate the sensors. The absolute part of "
    f"the equilibrium criterion (less than {FLUCTUATION_K:g} K change over {WINDOW_S:.0f} s) is met later by a "
    "larger rise, so a faster condition need not reach equilibrium sooner."
)


def sensor_curves_section(validation: Validation) -> str:
    if not validation.solutions:
        return ""
    rows = data.comparisons_by_key(validation)
    ambients = sorted({s.ambient_sensor for s in validation.solutions.values()})
    series = (" Where the measurements are time series, the final value is the series' last sample; the next "
              "section draws the series." if validation.transients else "")
    body = [paragraph(
        f"The {data.runs_model(validation)}'s sensor temperatures and the elongation D over time. The measured "
        f"final values are drawn as dashed lines in the colour of their sensor: the level a run should "
        f"approach.{series} {_ambient_words(ambients)}")]
    for condition, solution in validation.solutions.items():
        measured = {q: rows[(condition, q)].measured for q in validation.quantities if (condition, q) in rows}
        png = figures.sensor_curves(solution, condition, measured, validation.measured_equilibrium_min.get(condition))
        body.append(png_image(png, f"Sensor temperatures and elongation, condition {condition}",
                              caption=run_caption(validation, condition, solution)))
    return section("sensor-curves", "Sensor curves per condition", "".join(body))


def _ambient_words(sensors: list[str]) -> str:
    """The ambient sensors named ("<name> (dotted grey) is the ambient."), unless their name says it already."""
    named = [s for s in sensors if s.lower() != "ambient"]
    if not named:
        return "The ambient sensor is drawn dotted grey."
    return f"{', '.join(named)} (dotted grey) is the ambient."


def run_caption(validation: Validation, condition: str, solution: Solution) -> str:
    parts = [f"Condition {condition}"]
    screw, nut = data.screw_rpm(validation, condition), data.nut_rpm(validation, condition)
    if screw is not None:
        parts.append(f"screw {screw:.0f} rpm, nut {nut:.0f} rpm")
    ambient = data.ambient_c(solution)
    if ambient is not None:
        parts.append(f"ambient {ambient:.1f} °C")
    parts.append(f"run of {data.run_minutes(solution):.0f} min")
    parts.append(f"model equilibrium: {equilibrium_text(solution)}")
    return "; ".join(parts) + "."


def screw_field_section(validation: Validation) -> str:
    title = "Screw temperature over time and position"
    condition = data.reference_condition(validation)
    if condition is None:
        return ""
    solution = validation.solutions[condition]
    png = figures.screw_field(solution, condition)
    intro = paragraph(f"The {data.runs_model(validation)}'s cross-section mean temperature of the screw in condition "
                      f"{condition}, over time and axial position (x from the description's origin), and axial "
                      "profiles at a few times.")
    return section("screw-field", title, intro + png_image(png, f"Screw temperature field, condition {condition}",
                                                           caption=profile_facts(solution)))


def profile_facts(solution: Solution) -> str:
    """Where the screw is hottest at the end of the run, and how warm its ends are."""
    final = solution.screw_temperature[-1] - KELVIN_OFFSET
    x_mm = solution.screw_x * 1e3
    hottest = int(np.argmax(final))
    return (f"At the end of the run the screw is hottest at x = {number(x_mm[hottest], 0)} mm "
            f"({number(final[hottest])} °C); its ends are at {number(final[0])} °C (x = {number(x_mm[0], 0)} mm) "
            f"and {number(final[-1])} °C (x = {number(x_mm[-1], 0)} mm).")


def equilibrium_section(validation: Validation) -> str:
    if not validation.solutions:
        return ""
    stated = bool(validation.measured_equilibrium_min)
    body = [paragraph(
        f"When each run of the {data.runs_model(validation)} reached thermal equilibrium ({CRITERION}; "
        "docs/fast-model.md)" + (", beside the times the source states, where it does." if stated else "."))]
    shown: list[str] = []
    by_speed, by_ambient = data.speed_series(validation), data.ambient_series(validation)
    for series, what in ((by_speed, "Against speed"), (by_ambient, "Against ambient")):
        if series is not None:
            body.append(heading(f"{what} ({series.title})"))
            body.append(equilibrium_table(validation, series.conditions))
            shown += series.conditions
    others = [c for c in validation.solutions if c not in shown]
    if others:
        body.append(heading("Other conditions" if shown else "Per condition"))
        body.append(equilibrium_table(validation, others))
    if validation.start_variants:
        body.append(heading("Under another start"))
        body.append(paragraph(
            "Tests of a measured condition that start elsewhere (the description's [tests]), beside the condition's "
            "own start and against the same measurements: where the machine was before a test moves its "
            "equilibrium time and its whole transient, not its steady state."))
        body.append(start_variants_table(validation))
    if by_ambient is not None:
        body.append(paragraph(LINEAR_PHYSICS + " " + ambient_effect_text(validation, by_ambient)))
        if any(run.info.get("coupling") == "nonlinear" for run in validation.solutions.values()):
            body.append(paragraph(COUPLED_PHYSICS))
    body.append(paragraph(TIME_CONSTANT_PHYSICS))
    if by_speed is not None:
        body.append(paragraph(SPEED_PHYSICS))
    return section("equilibrium", "Equilibrium time", "".join(body))


def ambient_effect_text(validation: Validation, series: data.Series) -> str:
    """What the ambient series' own figures say: the radiation coefficient's change over its span, and
    how far apart the model's and the stated equilibrium times of its conditions are."""
    ambients = [validation.operating_points[c].ambient_c for c in series.conditions]  # what the series varies
    parts = []
    if max(ambients) > min(ambients):
        low, high = min(ambients) + KELVIN_OFFSET, max(ambients) + KELVIN_OFFSET
        parts.append(f"The only ambient effect left comes through the temperature the coefficients are taken "
                     f"at: over the {high - low:.0f} K of the ambient series the air's properties change the "
                     f"convection coefficients by a few per cent, and the linearised radiation coefficient (∝ T³) "
                     f"by {100 * ((high / low) ** 3 - 1):.0f} %.")
    names = ", ".join(series.conditions)
    model = [data.equilibrium_minutes(validation.solutions[c]) for c in series.conditions]
    times = ", ".join(NOT_REACHED if m is None else f"{m:.0f}" for m in model)
    sentence = f"The model's equilibrium times of {names}: {times} min"
    if all(m is not None for m in model):
        sentence += f" ({max(model) - min(model):.0f} min apart)"
    given = [validation.measured_equilibrium_min.get(c) for c in series.conditions]
    known = [g for g in given if g is not None]
    if len(known) >= 2:
        sentence += (f"; the stated ones: {', '.join('—' if g is None else f'{g:.0f}' for g in given)} min "
                     f"({max(known) - min(known):.0f} min apart)")
    parts.append(sentence + ".")
    return " ".join(parts)


def equilibrium_table(validation: Validation, conditions: list[str]) -> str:
    stated = bool(validation.measured_equilibrium_min)
    rows = []
    for condition in conditions:
        solution = validation.solutions[condition]
        rows.append([
            condition,
            number(data.screw_rpm(validation, condition), 0),
            number(data.ambient_c(solution), 1),
            number(data.run_minutes(solution), 0),
            number(data.equilibrium_minutes(solution), 0, missing=NOT_REACHED),
        ] + ([number(validation.measured_equilibrium_min.get(condition), 0)] if stated else []))
    return table(["condition", "screw speed [rpm]", "ambient [°C]", "run length [min]",
                  "model equilibrium [min]"] + (["stated [min]"] if stated else []), rows,
                 model=data.runs_model(validation))


def start_variants_table(validation: Validation) -> str:
    """Each condition with another start: both runs' start, equilibrium time and final deviations."""
    rows = []
    conditions = dict.fromkeys(condition for condition, _ in validation.start_variants.values())
    for condition in conditions:
        runs = [(condition, validation.solutions[condition])] + [
            (name, run) for name, (c, run) in validation.start_variants.items() if c == condition]
        measured = {c.quantity: c.measured for c in validation.comparisons if c.condition == condition}
        for name, run in runs:
            final = run.summary_values("final")
            start = run.sensors_celsius()
            first = [float(start[q][0]) for q in measured if q in start]
            temperature = [abs(final[q] - v) for q, v in measured.items() if q in final and q != ELONGATION_QUANTITY]
            d = measured.get(ELONGATION_QUANTITY)
            rows.append([condition, name, number(sum(first) / len(first) if first else None, 1),
                         number(data.equilibrium_minutes(run), 0, missing=NOT_REACHED),
                         number(validation.measured_equilibrium_min.get(condition), 0),
                         number(max(temperature) if temperature else None, 1),
                         number(None if d is None else final[ELONGATION_QUANTITY] - d, 1, signed=True)])
    return table(["condition", "run", "start: sensors at 0 s [°C]", "model equilibrium [min]", "stated [min]",
                  "largest |ΔT| final [K]", "ΔD final [µm]"], rows, model=data.runs_model(validation))


def equilibrium_text(solution: Solution) -> str:
    minutes = data.equilibrium_minutes(solution)
    return NOT_REACHED if minutes is None else f"{minutes:.0f} min"
