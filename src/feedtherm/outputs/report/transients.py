"""Sections 3–5: sensor curves, the screw field, the equilibrium time."""

from __future__ import annotations

import numpy as np

from ...analysis.validation_types import ELONGATION_QUANTITY, Validation
from ...constants import KELVIN_OFFSET
from ...solution import Solution
from . import data, figures
from .html import heading, number, paragraph, png_image, section, table

NOT_REACHED = "not reached in the run"
EQUILIBRIUM_PHYSICS = (
    "Why the ambient temperature cannot change the equilibrium time when the coefficients are frozen. With the "
    "convection and radiation coefficients frozen for a run, the model is linear: C·dT/dt = "
    "−G·(T − T_amb) + q. Written for the rise θ = T − T_amb it reads C·dθ/dt = −G·θ + q with θ = 0 at the "
    "start, and the ambient temperature has disappeared: it shifts every temperature by the same amount and "
    "leaves every rise, and so the equilibrium time, unchanged: conditions at the same speeds that differ only "
    "in ambient must reach equilibrium at the same time. The only ambient effect left "
    "in physics mode comes through the temperature at which the coefficients are frozen: the air's properties "
    "change the convection coefficients by a few per cent over 10 K, and the linearised radiation coefficient "
    "(∝ T³) by about 10 %, far too little to move the equilibrium time by 40 min. A warmer room does not make "
    "heat \"more difficult to dissipate\": the heat lost depends on T − T_amb, not on T_amb."
)
COUPLED_PHYSICS = (
    "This description couples them (temperatures.coupling = \"nonlinear\"): the convection and radiation "
    "coefficients, the lubricants' viscosities and the windings' resistances follow the simulated "
    "temperatures, so the equation above is linear only within a step. The ambient then also acts through the "
    "air's and the oils' properties (a cooler room: thicker oil, more bearing heat; warmer windings: more "
    "copper loss), by a few per cent per 10 K; the model's times of the ambient series above show how much."
)
TIME_CONSTANT_PHYSICS = (
    "The time constants are the eigenvalues of C⁻¹G: they follow from the heat capacities and the "
    "conductances (contacts, conduction, convection), not from the heat generated. Doubling every heat "
    "doubles every rise and leaves the time to reach 95 % of it unchanged."
)
SPEED_PHYSICS = (
    "What changes with speed: the heats grow (bearing and motor losses with the shaft speeds, the screw–nut "
    "friction with the relative speed), which raises the steady temperatures but not the time constants. "
    "The speed does shorten the time constants through the forced convection of the rotating screw and nut "
    "(h grows with the rotational Reynolds number; an overlay's printed CHTCs are scaled the same way). "
    "It also moves the heat between fast parts (screw, nut) and slow ones "
    "(housings, table, base), which changes which time constants dominate the sensors. The absolute part of "
    "the equilibrium criterion (less than 0.5 K change over 600 s) is met later by a larger rise, so a "
    "faster condition need not reach equilibrium sooner."
)


def sensor_curves_section(validation: Validation) -> str:
    rows = data.comparisons_by_key(validation)
    ambients = sorted({s.ambient_sensor for s in validation.solutions.values()})
    body = [paragraph(
        f"Simulated sensor temperatures and the elongation D over time. The measured values at thermal "
        f"equilibrium are drawn as dashed lines in the colour of their sensor: the level a run should "
        f"approach. {', '.join(ambients) or 'The ambient'} (dotted grey) is the ambient.")]
    for condition, solution in validation.solutions.items():
        measured = {q: rows[(condition, q)].measured for q in validation.quantities if (condition, q) in rows}
        png = figures.sensor_curves(solution, condition, measured, validation.measured_equilibrium_min.get(condition))
        body.append(png_image(png, f"Sensor temperatures and elongation, condition {condition}",
                              caption=run_caption(validation, condition, solution)))
    if not validation.solutions:
        body.append(paragraph("No runs to show."))
    return section("sensor-curves", "Sensor curves per condition", "".join(body))


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
        return section("screw-field", title, paragraph("No runs to show."))
    solution = validation.solutions[condition]
    png = figures.screw_field(solution, condition)
    intro = paragraph(f"Cross-section mean temperature of the screw in condition {condition}, over time and "
                      "axial position (x from the description's origin), and axial profiles at a few times.")
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
    body = [paragraph(
        "When each run reached thermal equilibrium (every sensor within 95 % of its steady rise and changing by "
        "less than 0.5 K over 600 s; docs/fast-model.md), beside the times the source states, where it does.")]
    shown: list[str] = []
    for series, what in ((data.speed_series(validation), "Against speed"),
                         (data.ambient_series(validation), "Against ambient")):
        if series is not None:
            body.append(heading(f"{what} ({series.title})"))
            body.append(equilibrium_table(validation, series.conditions))
            shown += series.conditions
    others = [c for c in validation.solutions if c not in shown]
    if others:
        body.append(heading("Other conditions"))
        body.append(equilibrium_table(validation, others))
    if not validation.solutions:
        body.append(paragraph("No runs to show."))
    if validation.start_variants:
        body.append(heading("Under another start"))
        body.append(paragraph(
            "Tests of a measured condition that start elsewhere (the description's [tests]), beside the condition's "
            "own start and against the same measurements: where the machine was before a test moves its "
            "equilibrium time and its whole transient, not its steady state."))
        body.append(start_variants_table(validation))
    body.append(paragraph(EQUILIBRIUM_PHYSICS))
    if any(run.info.get("coupling") == "nonlinear" for run in validation.solutions.values()):
        body.append(paragraph(COUPLED_PHYSICS))
    body += [paragraph(TIME_CONSTANT_PHYSICS), paragraph(SPEED_PHYSICS)]
    return section("equilibrium", "Equilibrium time", "".join(body))


def equilibrium_table(validation: Validation, conditions: list[str]) -> str:
    rows = []
    for condition in conditions:
        solution = validation.solutions[condition]
        rows.append([
            condition,
            number(data.screw_rpm(validation, condition), 0),
            number(data.ambient_c(solution), 1),
            number(data.run_minutes(solution), 0),
            number(data.equilibrium_minutes(solution), 0, missing=NOT_REACHED),
            number(validation.measured_equilibrium_min.get(condition), 0),
        ])
    return table(["condition", "screw speed [rpm]", "ambient [°C]", "run length [min]",
                  "model equilibrium [min]", "stated [min]"], rows)


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
                  "largest |ΔT| final [K]", "ΔD final [µm]"], rows)


def equilibrium_text(solution: Solution) -> str:
    minutes = data.equilibrium_minutes(solution)
    return NOT_REACHED if minutes is None else f"{minutes:.0f} min"
