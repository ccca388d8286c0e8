"""Final values against speed and ambient, dual against single drive, heat budget.

Each section appears where the runs hold its content: a series of conditions that differ in speed
or in ambient alone, single-drive runs beside dual-drive ones, a heat budget.  The trends' prose
states the slopes of the runs it shows (:func:`ambient_trends`), not what a model ought to do.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...analysis.validation_types import ELONGATION_QUANTITY, Validation
from ...solution import Solution
from . import data, figures
from .html import grid, number, paragraph, png_image, section, table


@dataclass(frozen=True)
class AmbientTrends:
    """Slopes of the final values against the ambient over an ambient series (least squares).

    ``temperatures``: sensor -> K per K of ambient; ``elongation``: µm per K (None without D);
    ``measured_*`` the same of the measured values, a value the consistency check flags left out
    (``left_out`` names them).
    """

    conditions: list[str]
    temperatures: dict[str, float]
    elongation: float | None
    measured_temperatures: dict[str, float]
    measured_elongation: float | None
    left_out: list[str]


def ambient_trends(validation: Validation) -> AmbientTrends | None:
    """The ambient series' slopes, simulated and measured; None without an ambient series."""
    series = data.ambient_series(validation)
    if series is None:
        return None
    rows = data.comparisons_by_key(validation)
    flagged = validation.consistency.excluded() if validation.consistency else set()
    x = {c: validation.operating_points[c].ambient_c for c in series.conditions}  # as the figure draws them

    def fit(quantity: str, attribute: str) -> float | None:
        points = [(x[c], getattr(rows[(c, quantity)], attribute)) for c in series.conditions
                  if (c, quantity) in rows and not (attribute == "measured" and (c, quantity) in flagged)]
        return slope(points)

    def fits(attribute: str) -> dict[str, float]:
        found = {q: fit(q, attribute) for q in validation.temperature_quantities}
        return {q: v for q, v in found.items() if v is not None}

    left_out = [f"{c} {data.label(q)}" for c in series.conditions for q in validation.quantities
                if (c, q) in flagged and (c, q) in rows]
    return AmbientTrends(series.conditions, fits("simulated"), fit(ELONGATION_QUANTITY, "simulated"),
                         fits("measured"), fit(ELONGATION_QUANTITY, "measured"), left_out)


def slope(points: list[tuple[float, float]]) -> float | None:
    """Least-squares slope of (x, y) points; None with fewer than two distinct x."""
    if len({round(x, 6) for x, _ in points}) < 2:
        return None
    xs, ys = (np.array(v, dtype=float) for v in zip(*points))
    return float(np.polyfit(xs, ys, 1)[0])


def trend_text(trends: AmbientTrends) -> str:
    """The ambient series' slopes in words: how the model's finals and the measured ones follow the ambient."""
    sentences = []
    for who, temperatures, elongation in (("the model's", trends.temperatures, trends.elongation),
                                          ("the measured", trends.measured_temperatures, trends.measured_elongation)):
        parts = []
        if temperatures:
            low, high = min(temperatures.values()), max(temperatures.values())
            span = f"{_slope(low, 2)}" if round(low, 2) == round(high, 2) else f"{_slope(low, 2)} to {_slope(high, 2)}"
            parts.append(f"{who} temperatures change by {span} K per kelvin of ambient")
        if elongation is not None:
            parts.append(f"{who} D {_direction(elongation)} {abs(elongation):.2f} µm per kelvin")
        if parts:
            sentences.append(" and ".join(parts))
    if not sentences:
        return ""
    text = f"Over the ambient series ({', '.join(trends.conditions)}), " + "; ".join(sentences)
    if trends.left_out:
        text += f" (leaving out the flagged {', '.join(trends.left_out)})"
    return text + "."


def _direction(value: float) -> str:
    if round(value, 2) == 0:
        return "changes by"
    return "rises by" if value > 0 else "falls by"


def _slope(value: float, decimals: int) -> str:
    return number(value, decimals, signed=True)


def trends_section(validation: Validation) -> str:
    title = "Final values against speed and ambient"
    by_speed, by_ambient = data.speed_series(validation), data.ambient_series(validation)
    speed = [(c, data.screw_rpm(validation, c)) for c in by_speed.conditions] if by_speed else []
    ambient = [(c, validation.operating_points[c].ambient_c) for c in by_ambient.conditions] if by_ambient else []
    rows = data.comparisons_by_key(validation)
    if not (speed or ambient) or not rows:
        return ""
    panels = [(kind, points, series.title) for kind, points, series in
              (("speed", speed, by_speed), ("ambient", ambient, by_ambient)) if points]
    png = figures.trends(panels, rows, validation.temperature_quantities)
    temperatures = ", ".join(validation.temperature_quantities)
    series = [f"{', '.join(s.conditions)} differ in {s.varies} at {s.title}" for s in (by_speed, by_ambient) if s]
    intro = (f"The {data.runs_model(validation)}'s final values of the deviation tables (filled circles, solid) and "
             f"the measured ones (open squares, dashed) of {temperatures} and D: conditions {'; '.join(series)}.")
    trends = ambient_trends(validation)
    if trends is not None:
        intro += " " + trend_text(trends)
    kinds = " and ".join(kind for kind, _, _ in panels)
    return section("trends", title, paragraph(intro) + png_image(
        png, f"Final temperatures and elongation against {kinds}"))


def dual_single_section(validation: Validation) -> str:
    title = "Dual drive against single drive"
    both = [c for c in validation.solutions if c in validation.single_drive]
    if not both:
        return ""
    dual = {c: drive_values(validation.solutions[c]) for c in both}
    single = {c: drive_values(validation.single_drive[c]) for c in both}
    intro = paragraph(
        f"The {data.runs_model(validation)} at the same table speed driven conventionally: the nut motor off (nut at "
        "rest) and the screw at the relative speed n_s − n_n. Final values at the end of the runs; the heat is the "
        "mean generated over the run.")
    tables = [drive_table(c, dual[c], single[c], data.runs_model(validation)) for c in both]
    png = figures.dual_single(both, dual, single)
    return section("dual-single", title,
                   intro + png_image(png, "Heat and elongation, dual against single drive") + grid(tables))


def drive_values(solution: Solution) -> dict[str, float]:
    """Final sensor temperatures [°C] (the ambient's left out), D [µm] and the mean heat generated [W] of one run."""
    values = {k: v for k, v in data.final_values(solution).items() if k != solution.ambient_sensor}
    heat = data.mean_heat_w(solution)
    if heat is not None:
        values["heat_W"] = heat
    return values


def drive_table(condition: str, dual: dict[str, float], single: dict[str, float],
                model: str = data.UNCALIBRATED) -> str:
    rows = []
    keys = [q for q in dual if q not in ("D_um", "heat_W")] + ["D_um", "heat_W"]
    labels = {"D_um": "D [µm]", "heat_W": "mean heat [W]"}
    for key in keys:
        if key not in dual or key not in single:
            continue
        rows.append([labels.get(key, f"{key} [°C]"), number(dual[key], 1), number(single[key], 1),
                     number(single[key] - dual[key], 1, signed=True)])
    return table(["quantity", "dual drive", "single drive", "single − dual"], rows,
                 caption=f"Condition {condition}", model=model)


def heat_budget_section(validation: Validation) -> str:
    title = "Heat budget per source"
    budget = validation.heat_budget
    if not budget:
        return ""
    conditions = list(budget)
    sources: list[str] = []
    for per_source in budget.values():
        sources += [s for s in per_source if s not in sources]
    rows = [[source.replace("_", " ")] + [number(budget[c].get(source), 2) for c in conditions] for source in sources]
    rows.append(["total"] + [number(sum(budget[c].values()), 2) for c in conditions])
    intro = paragraph(f"Heat generated by each source of the {data.runs_model(validation)} at the operating point of "
                      f"each condition, in {validation.mode} mode [W].")
    png = figures.heat_budget(budget)
    return section("heat-budget", title,
                   intro + png_image(png, "Heat per source and condition")
                   + table(["source"] + [f"{c} [W]" for c in conditions], rows, model=data.runs_model(validation)))
