"""The report's figure of measured time series against their runs, as PNG bytes.

Conventions of :mod:`.figures`: matplotlib imported inside, ``Figure`` objects, 9 in wide at
120 dpi. The quantities drawn are those the file measured, in its order: no bench's sensor
names are assumed.
"""

from __future__ import annotations

from ...analysis.transient_scores import TransientComparison, simulated_series
from ...solution import Solution
from ...system.measurement_series import target_of
from .figures import _figure, _png

_HOURS = 3600.0
_D_COLOUR = "C5"
_MAX_MARKERS = 400  # per series: beyond this, markers merge into a band and hide the curve


def measured_series(solution: Solution, condition: str, comparisons: list[TransientComparison]) -> bytes:
    """Simulated curves (lines) and measured samples (markers, with ±1 uncertainty bars where given).

    Temperatures [°C] above the elongation D [µm]; the lower panel only where D was measured.
    """
    temperatures = [c for c in comparisons if c.unit == "C"]
    # E at targets has its own figure, as drifts (report/drift_tests.py)
    elongation = [c for c in comparisons if c.unit != "C" and target_of(c.quantity) is None]
    panels = [p for p in (temperatures, elongation) if p]
    figure = _figure(2.2 + 2.4 * len(panels))
    axes = figure.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    hours = solution.times / _HOURS
    # D keeps its colour of the report's other figures; the temperatures take the others in turn
    palette = [f"C{i}" for i in range(10) if f"C{i}" != _D_COLOUR]
    for ax, panel in zip(axes, panels):
        for index, c in enumerate(panel):
            colour = _D_COLOUR if c.unit != "C" else palette[index % len(palette)]
            name = "D" if c.unit != "C" else c.quantity
            ax.plot(hours, simulated_series(solution, c.quantity), color=colour, linewidth=1.5,
                    label=f"{name} simulated")
            step = max(1, -(-len(c.times) // _MAX_MARKERS))
            shown = slice(None, None, step)
            errors = None if c.uncertainty is None else c.uncertainty[shown]
            ax.errorbar(c.times[shown] / _HOURS, c.measured[shown], yerr=errors, color=colour, linestyle="none",
                        marker="o", markersize=3.5, markerfacecolor="white", elinewidth=0.8, capsize=1.5,
                        label=f"{name} measured (RMS {c.rms:.2g} {'K' if c.unit == 'C' else 'µm'})")
        ax.grid(True, alpha=0.3)
        ax.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False, fontsize=9)
        ax.set_ylabel("temperature [°C]" if panel is temperatures else "elongation D [µm]")
    axes[-1].set_xlabel("time [h]")
    axes[-1].set_xlim(hours[0], hours[-1])
    axes[0].set_title(f"Condition {condition}: simulated (lines) and measured series (markers)")
    return _png(figure)
