"""The section on ISO 230-3 tests: the drift at each target over time, measured beside simulated.

Empty (no section at all) when no test's measurements hold positioning deviations at targets or
an idle test's displacements in a varying room.
"""

from __future__ import annotations

import numpy as np

from ...analysis.drift_tests import DriftTest
from ...analysis.transient_scores import positioning_at
from ...analysis.validation_types import Validation
from ...solution import Solution
from ..drift_test_files import figure_rows
from .figures import _figure, _png
from .data import runs_model
from .html import number, paragraph, png_image, section, table

INTRO = (
    "ISO 230-3 judges a linear axis by the drift of its positioning deviation at target positions, measured at "
    "stops while the axis runs its duty: at each target the deviation less the deviation at the target's first "
    "measurement (the first reading holds the axis's geometric error, which is not thermal), the drift of largest "
    "magnitude and when it occurred, and the drift of the distance between the outer targets, the axis's thermal "
    "expansion. For a test with every motor at rest in a room whose air varies, the range of each displacement is "
    "its ETVE figure. The simulated drift is the run's positioning error E at the target, less its value at the "
    "same first instant. iso230_3.csv holds these figures, iso230_3_drift.csv every measured instant."
)


def drift_tests_section(validation: Validation) -> str:
    tests = validation.drift_tests
    if not tests:
        return ""
    rows = [[r["test"], r["figure"], r["quantity"], number(r["measured_um"], 1, signed=True),
             number(None if r["measured_at_s"] is None else r["measured_at_s"] / 60.0, 0),
             number(r["simulated_um"], 1, signed=True),
             number(None if r["simulated_at_s"] is None else r["simulated_at_s"] / 60.0, 0),
             number(r["rms_deviation_um"], 1), number(r["max_abs_deviation_um"], 1)]
            for test in tests for r in figure_rows(test)]
    body = [paragraph(INTRO),
            table(["test", "figure", "quantity", "measured [µm]", "at [min]", "simulated [µm]", "at [min]",
                   "RMS sim − meas [µm]", "max |sim − meas| [µm]"], rows, model=runs_model(validation))]
    for test in tests:
        if test.measured:
            png = drift_figure(validation.solutions[test.run], test)
            body.append(png_image(png, f"Drift at each target, {test.run}",
                                  caption=f"Test {test.run}: the drift at each target, measured (markers) and "
                                          "simulated (lines), and the outer targets' expansion drift."))
    return section("iso230-3", "ISO 230-3 drift tests", "".join(body))


def drift_figure(solution: Solution, test: DriftTest) -> bytes:
    """Drift at each target over time [µm] (upper) and the outer targets' expansion drift (lower)."""
    panels = 2 if test.expansion_measured is not None else 1
    figure = _figure(2.4 + 2.4 * panels)
    axes = figure.subplots(panels, 1, sharex=True, squeeze=False)[:, 0]
    hours = solution.times / 3600.0
    for index, measured in enumerate(test.measured):
        colour = f"C{index % 10}"
        series = positioning_at(solution, measured.target)
        origin = np.interp(measured.times[0], solution.times, series)
        axes[0].plot(hours, series - origin, color=colour, linewidth=1.4)
        axes[0].plot(measured.times / 3600.0, measured.drift * 1e6, "o", color=colour, markersize=4,
                     markerfacecolor="white", label=f"{measured.target * 1e3:g} mm")
    axes[0].set_ylabel("drift at the target [µm]")
    axes[0].legend(loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False, fontsize=9, title="target")
    if panels == 2:
        m, s = test.expansion_measured, test.expansion_simulated
        axes[1].plot(s.times / 3600.0, s.drift * 1e6, color="C7", linewidth=1.4, label="simulated")
        axes[1].plot(m.times / 3600.0, m.drift * 1e6, "o", color="C7", markersize=4, markerfacecolor="white",
                     label="measured")
        axes[1].set_ylabel(f"{m.last_target * 1e3:g} mm less {m.first_target * 1e3:g} mm [µm]")
        axes[1].legend(loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False, fontsize=9)
    for ax in axes:
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel("time [h]")
    axes[-1].set_xlim(hours[0], hours[-1])
    axes[0].set_title(f"Test {test.run}: ISO 230-3 drift, simulated (lines) and measured (markers)")
    return _png(figure)
