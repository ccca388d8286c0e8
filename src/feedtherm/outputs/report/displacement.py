"""The thermal error as a displacement: what the laser reads, the model's gain, the error along the stroke.

D is what the description's displacement sensor reads (``mechanics.elongation``: its target
relative to its mount), computed from the temperatures by each model's mechanics; no fitted
read point stands in for it.  The section puts beside each other: the declared loop, the
simulated and measured D per condition, the model's gain against the measured one (the slope
of D over the mean measured temperature, across the conditions the measurements' own
elongation law holds for), the positioning error along the stroke, and, with a calibration,
the held-out elongation error with this loop beside the earlier read-point figures.
"""

from __future__ import annotations

import numpy as np

from ...analysis.validation_types import ELONGATION_QUANTITY, Validation
from . import data
from .html import Cell, number, paragraph, png_image, section, table

def gains(validation: Validation, conditions: list[str] | None = None) -> tuple[float | None, float | None, list[str]]:
    """Slopes [µm/K] of simulated and of measured D against the mean measured temperature T̄.

    Over ``conditions`` (default: those the measurements' elongation law holds for, or every
    measured one), leaving out an elongation the consistency check flags; the same T̄ for both:
    the model's gain and the bench's (with the default conditions, the bench's is the law's slope).
    """
    rows = data.comparisons_by_key(validation)
    law = validation.consistency.law if validation.consistency else None
    flagged = validation.consistency.excluded() if validation.consistency else set()
    names = conditions if conditions is not None else (
        law.conditions if law is not None else data.conditions(validation))
    points, used = [], []
    sensors = validation.temperature_quantities
    for c in names:
        temps = [rows[(c, q)].measured for q in sensors if (c, q) in rows]
        if ((c, ELONGATION_QUANTITY) in rows and (c, ELONGATION_QUANTITY) not in flagged
                and len(temps) == len(sensors)):
            d = rows[(c, ELONGATION_QUANTITY)]
            points.append((float(np.mean(temps)), d.simulated, d.measured))
            used.append(c)
    if len(points) < 2:
        return None, None, []
    t, simulated, measured = (np.array(v) for v in zip(*points))
    if np.ptp(t) < 1e-6:  # one mean temperature: no slope to tell
        return None, None, []
    model = float(np.polyfit(t, simulated, 1)[0])
    if conditions is None and law is not None:
        return model, law.slope_um_per_k, used
    return model, float(np.polyfit(t, measured, 1)[0]), used


def _gain_table(validation: Validation) -> str:
    rows = []
    series = [s for s in (data.speed_series(validation), data.ambient_series(validation)) if s is not None]
    for label, names in (("the conditions the elongation law holds for", None),
                         *((f"against {s.varies} ({s.title})", s.conditions) for s in series)):
        model, bench, used = gains(validation, names)
        if model is not None:
            rows.append([label, ", ".join(used), number(model, 2), number(bench, 2)])
    if not rows:
        return ""
    sensors = validation.temperature_quantities
    return table(["series", "conditions", "the model's gain [µm/K]", "the bench's gain [µm/K]"], rows,
                 model=data.runs_model(validation)) + paragraph(
        f"The gain is the slope of D against the mean measured temperature of {', '.join(sensors)} (both models' "
        "D against the same "
        "measured temperatures). A gain above the bench's says the loop expands too much per kelvin of what the "
        "sensors read: too long a warm length in the loop, or a screw warmer than its sensors say; a gain that "
        "agrees over all conditions while the series disagree hides opposite errors against speed and against "
        "ambient.")


def _loop_text(validation: Validation) -> str:
    run = next(iter(validation.solutions.values()), None)
    loop = run.info.get("measuring_loop") if run is not None else None
    if not loop:
        return "The description's measuring loop is not recorded in these runs."
    laser = loop["elongation"]
    direction = ", ".join(f"{c:g}" for c in laser["direction"])
    described = f" ({laser['description']})" if laser.get("description") else ""
    return (f"D is what the declared displacement sensor reads: the displacement of its target, {laser['target']}, "
            f"relative to its mount, {laser['mount']}, along ({direction}), zero with every part at the reference "
            f"temperature{described}. The positioning error E(x, t) is the "
            f"screw's axial displacement under the nut at each table position x, relative to "
            f"{loop['positioning_reference']}. Both come from the temperatures through the model's mechanics "
            "(3-D thermoelasticity in the FE model, axial bars along the load path in the fast model).")


def _calibration_text(validation: Validation) -> str:
    calibration = validation.calibration
    if not calibration:
        return ""
    held = [r for r in calibration.get("held_out", []) if r["unit"] == "um" and not r.get("flag")]
    worst = max(held, key=lambda r: abs(r["deviation"]), default=None)
    cross = (calibration.get("cross_validation") or {}).get("largest_elongation_deviation_um")
    parts = []
    if worst is not None:
        parts.append(f"held out, {abs(worst['deviation']):.1f} µm ({worst['condition']})")
    if cross:
        parts.append(f"leave-one-condition-out, {abs(cross['deviation']):.1f} µm ({cross['condition']})")
    if not parts:
        return ""
    earlier = " and ".join(f"{v:.1f} µm {k}" for k, v in validation.notes.earlier_held_out_elongation_um.items())
    before = f" Before the loop was declared, the held-out error was {earlier}." if earlier else ""
    return (f"Calibrated with this loop (nothing fitted about where or how the laser reads), the largest "
            f"elongation error is {' and '.join(parts)}, leaving out the values the consistency check flags."
            + before)


def displacement_section(validation: Validation) -> str:
    title = "The thermal error as a displacement"
    if not validation.solutions:
        return ""
    body = [paragraph(_loop_text(validation))]
    rows = data.comparisons_by_key(validation)
    flagged = validation.consistency.excluded() if validation.consistency else set()
    elongations = [rows[(c, ELONGATION_QUANTITY)] for c in data.conditions(validation)
                   if (c, ELONGATION_QUANTITY) in rows]
    with_reference = any(d.paper_simulated is not None for d in elongations)
    table_rows = []
    for d in elongations:
        c = d.condition
        temps = [rows[(c, q)].measured for q in validation.temperature_quantities if (c, q) in rows]
        mark = " (flagged)" if (c, ELONGATION_QUANTITY) in flagged else ""
        table_rows.append([c, number(float(np.mean(temps)) if temps else None, 2), number(d.simulated),
                           Cell(f"{number(d.measured)}{mark}", "num"), number(d.deviation, signed=True)]
                          + ([number(d.paper_simulated)] if with_reference else []))
    if table_rows:
        reference = validation.notes.reference_model or "the reference model"
        sensors = ", ".join(validation.temperature_quantities)
        body.append(table(["condition", f"mean measured {sensors} [°C]", "simulated D [µm]", "measured D [µm]",
                           "deviation [µm]"] + ([f"{reference}'s simulated D [µm]"] if with_reference else []),
                          table_rows, model=data.runs_model(validation)))
    body.append(_gain_table(validation))
    text = _calibration_text(validation)
    if text:
        body.append(paragraph(text))
    from .figures import positioning_error

    body.append(png_image(positioning_error(validation.solutions), "Positioning error along the stroke",
                          caption=f"The {data.runs_model(validation)}: the positioning error E along the stroke "
                                  "at the end of each run (solid) and the screw's axial displacement relative to "
                                  "the positioning reference (dotted), per condition."))
    return section("displacement", title, "".join(body))


__all__ = ["displacement_section", "gains"]
