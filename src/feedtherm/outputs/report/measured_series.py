"""The section on measured time series: the whole transient scored, per condition a figure.

Empty (no section at all) when the measurements are final values only.
"""

from __future__ import annotations

import numpy as np

from ...analysis.validation_types import Validation
from ...system.measurement_series import target_of
from ..transient_files import deviation_unit
from . import data, series_figures
from .html import number, paragraph, png_image, section, table

INTRO = (
    "The measurements hold time series, so the runs are compared over the whole transient, not only at its end: "
    "each run is interpolated linearly to the measured times ({sampling}) and the deviations "
    "simulated − measured are summarised per series by their root mean square, their largest magnitude (and "
    "when it occurred) and their mean, the bias. The final value of a series in the deviation tables is its last "
    "sample. Where the file gives standard uncertainties u, \"within 2 u\" is the share of samples whose "
    "deviation the measurement's scatter alone could explain (about 95 % if it did; the model's own "
    "uncertainty not counted). transients.csv holds these scores, transient_samples.csv every sample."
)


def sampling_text(validation: Validation, comparisons) -> str:
    """How often the compared runs sample, from their own times: "it samples every 10 s"."""
    steps = sorted({round(float(np.median(np.diff(run.times))), 1)
                    for run in (validation.solutions[c] for c in dict.fromkeys(x.condition for x in comparisons))
                    if run.times.size > 1})
    if not steps:
        return "one sample per run"
    if len(steps) == 1:
        return f"it samples every {steps[0]:g} s"
    return f"the runs sample every {steps[0]:g}–{steps[-1]:g} s"


def measured_series_section(validation: Validation) -> str:
    comparisons = validation.transients
    if not comparisons:
        return ""
    rows = [[c.condition, "D" if c.quantity == "D_um" else c.quantity, len(c.times), number(c.rms, 2),
             number(c.max_abs, 2), number(c.time_of_max / 60.0, 0), number(c.mean, 2, signed=True),
             deviation_unit(c),
             "—" if c.inside_two_sigma is None else f"{100 * c.inside_two_sigma:.0f} %"] for c in comparisons]
    body = [paragraph(INTRO.format(sampling=sampling_text(validation, comparisons))),
            table(["condition", "quantity", "samples", "RMS deviation", "max |deviation|", "at [min]",
                   "mean deviation", "unit", "within 2 u"], rows, model=data.runs_model(validation))]
    for condition in dict.fromkeys(c.condition for c in comparisons):
        solution = validation.solutions[condition]
        own = [c for c in comparisons if c.condition == condition and target_of(c.quantity) is None]
        if not own:  # E at targets alone: the ISO 230-3 section draws it
            continue
        png = series_figures.measured_series(solution, condition, own)
        with_bars = any(c.uncertainty is not None for c in own)
        caption = (f"Condition {condition}: {len(own)} measured series"
                   + (", bars ±1 standard uncertainty" if with_bars else "") + ".")
        body.append(png_image(png, f"Measured and simulated series, condition {condition}", caption=caption))
    return section("measured-series", "Measured time series", "".join(body))
