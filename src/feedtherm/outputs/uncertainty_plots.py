"""Figures of an uncertainty study (PNG bytes): bands over time, final values against the
measurements, Sobol indices.

Each figure is drawn from a plain description of what it shows (:func:`band_panels`,
:func:`finals_panels`, :func:`sobol_matrix`), so what a figure plots can be checked without
reading pixels.  Same conventions as :mod:`feedtherm.outputs.plots`: matplotlib is imported
inside the functions and figures are ``matplotlib.figure.Figure`` objects (no pyplot state).
"""

from __future__ import annotations

import io
from dataclasses import dataclass

import numpy as np

from ..analysis.uncertainty.types import BAND, FinalBand, UncertaintySet, UncertaintyStudy

_DPI = 110
_HOURS = 3600.0
#: Each state of knowledge keeps its colour in every figure.
SET_COLOURS = {"prior": "tab:blue", "calibrated": "tab:orange", "predictive": "tab:green"}
UNIT_LABELS = {"C": "°C", "um": "µm"}
#: The quantity the Sobol figure orders its parameters by, the first one present.
SOBOL_ORDER_BY = ("D_um",)


def quantity_order(quantities) -> list[str]:
    """Sensor temperatures by name, then D_um, each once."""
    names = list(dict.fromkeys(quantities))
    return sorted(names, key=lambda q: (q == "D_um", q))


def display_name(quantity: str) -> str:
    """``D`` for ``D_um`` (the unit is shown beside it), other names as they are."""
    return "D" if quantity == "D_um" else quantity


def band_label(label: str) -> str:
    low, high = (round(100 * b) for b in BAND)
    return f"{label} {low}–{high} %"


def colour(label: str, index: int) -> str:
    return SET_COLOURS.get(label, f"C{index + 2}")


# --------------------------------------------------------------------------- what the figures show


@dataclass(frozen=True)
class Layer:
    """One set's band of one quantity over time."""

    label: str
    p05: np.ndarray
    p50: np.ndarray
    p95: np.ndarray
    nominal: np.ndarray


@dataclass(frozen=True)
class BandPanel:
    """One quantity of one condition over time: the sets' bands, and its measured final value."""

    quantity: str
    unit: str
    hours: np.ndarray
    layers: list[Layer]  # the prior first, drawn underneath
    measured: float | None
    flag: str


def band_panels(study: UncertaintyStudy, condition: str) -> list[BandPanel]:
    """The panels of :func:`bands_over_time`: every quantity of ``condition``'s bands."""
    sets = [s for s in study.sets if condition in s.bands]
    if not sets:
        raise ValueError(f"no bands for condition {condition!r}")
    finals = {f.quantity: f for f in sets[0].finals if f.condition == condition}
    units = {f.quantity: f.unit for s in study.sets for f in s.finals}
    base = sets[0].bands[condition]
    panels = []
    for quantity in quantity_order(base.quantiles):
        layers = []
        for uset in sets:
            band = uset.bands[condition]
            if quantity in band.quantiles:
                q = np.asarray(band.quantiles[quantity], dtype=float)
                layers.append(Layer(uset.label, q[0], q[1], q[2], np.asarray(band.nominal[quantity], dtype=float)))
        final = finals.get(quantity)
        panels.append(BandPanel(quantity, units.get(quantity, "um" if quantity == "D_um" else "C"),
                                np.asarray(base.time_s, dtype=float) / _HOURS, layers,
                                None if final is None else final.measured, "" if final is None else final.flag))
    return panels


@dataclass(frozen=True)
class FinalsPanel:
    """One measured quantity's final values at every condition, per set."""

    quantity: str
    unit: str
    conditions: list[str]
    bands: dict[str, list[FinalBand | None]]  # set label -> per condition
    measured: list[float | None]
    flags: list[str]
    inside: dict[str, tuple[int, int]]  # set label -> (inside, measured)


def finals_panels(study: UncertaintyStudy) -> list[FinalsPanel]:
    """The panels of :func:`finals_against_measurements`: quantities with a measurement, in order."""
    finals = [f for s in study.sets for f in s.finals]
    measured_quantities = {f.quantity for f in finals if f.measured is not None}
    conditions = list(dict.fromkeys(f.condition for f in finals))
    panels = []
    for quantity in quantity_order(q for q in (f.quantity for f in finals) if q in measured_quantities):
        by_set, inside = {}, {}
        for uset in study.sets:
            lookup = {f.condition: f for f in uset.finals if f.quantity == quantity}
            by_set[uset.label] = [lookup.get(c) for c in conditions]
            judged = [f.inside for f in lookup.values() if f.inside is not None]
            inside[uset.label] = (sum(judged), len(judged))
        first = {f.condition: f for f in study.sets[0].finals if f.quantity == quantity}
        unit = next(f.unit for f in finals if f.quantity == quantity)
        panels.append(FinalsPanel(quantity, unit, conditions, by_set,
                                  [first[c].measured if c in first else None for c in conditions],
                                  [first[c].flag if c in first else "" for c in conditions], inside))
    return panels


@dataclass(frozen=True)
class SobolMatrix:
    """A set's Sobol indices as parameter × quantity arrays, parameters by total index, largest first."""

    condition: str
    parameters: list[str]
    quantities: list[str]
    S1: np.ndarray  # (n_parameters, n_quantities); NaN where an index is missing
    ST: np.ndarray
    ordered_by: str


def sobol_matrix(uset: UncertaintySet) -> SobolMatrix:
    """The indices of ``uset`` (which must have some), ordered by ST on D (or the first quantity)."""
    if not uset.sobol:
        raise ValueError(f"the {uset.label} set has no Sobol indices")
    quantities = quantity_order(i.quantity for i in uset.sobol)
    parameters = list(dict.fromkeys(i.parameter for i in uset.sobol))
    s1 = np.full((len(parameters), len(quantities)), np.nan)
    st = np.full_like(s1, np.nan)
    for index in uset.sobol:
        row, column = parameters.index(index.parameter), quantities.index(index.quantity)
        s1[row, column], st[row, column] = index.S1, index.ST
    key = next((q for q in SOBOL_ORDER_BY if q in quantities), quantities[0])
    order = sorted(range(len(parameters)), key=lambda r: -np.nan_to_num(st[r, quantities.index(key)], nan=-1.0))
    return SobolMatrix(uset.sobol_condition or "", [parameters[r] for r in order], quantities, s1[order], st[order], key)


# --------------------------------------------------------------------------- the figures


def bands_over_time(study: UncertaintyStudy, condition: str) -> bytes:
    """One panel per quantity of ``condition``: each set's 5–95 % band shaded (the calibrated one on
    top), its median dashed and its nominal run solid, and the measured final value at the end."""
    return _png(bands_figure(study, condition))


def bands_figure(study: UncertaintyStudy, condition: str):
    panels = band_panels(study, condition)
    columns = 2
    rows = -(-len(panels) // columns)
    figure = _figure((9.0, 2.1 * rows + 0.6))
    axes = figure.subplots(rows, columns, sharex=True, squeeze=False).ravel()
    for ax, panel in zip(axes, panels):
        for index, layer in enumerate(panel.layers):
            c = colour(layer.label, index)
            ax.fill_between(panel.hours, layer.p05, layer.p95, color=c, alpha=0.25 if index == 0 else 0.45, lw=0,
                            label=band_label(layer.label))
            ax.plot(panel.hours, layer.p50, color=c, ls="--", lw=1.0, label=f"{layer.label} median")
            ax.plot(panel.hours, layer.nominal, color=c, lw=1.4, label=f"{layer.label} nominal run")
        if panel.measured is not None:
            flagged = bool(panel.flag)
            ax.plot(panel.hours[-1], panel.measured, "X" if flagged else "D", color="tab:red" if flagged else "k",
                    ms=7, zorder=5, label="measured (flagged)" if flagged else "measured final value")
            ax.annotate(f"{panel.measured:.1f}", (panel.hours[-1], panel.measured), xytext=(-6, 6),
                        textcoords="offset points", ha="right", fontsize=7)
        ax.set_title(f"{display_name(panel.quantity)} [{UNIT_LABELS.get(panel.unit, panel.unit)}]", fontsize=9)
        ax.grid(alpha=0.3)
    for ax in axes[max(0, len(panels) - columns):len(panels)]:
        ax.set_xlabel("time [h]")
        ax.xaxis.set_tick_params(labelbottom=True)
    handles, labels = _legend_entries(axes[:len(panels)])
    for ax in axes[len(panels):]:
        ax.set_axis_off()
    if len(panels) < len(axes):  # the empty cell holds the legend
        axes[-1].legend(handles, labels, loc="center", fontsize=8, frameon=False)
    else:
        figure.legend(handles, labels, loc="outside lower center", ncols=min(4, len(labels)), fontsize=7,
                      frameon=False)
    figure.suptitle(f"condition {condition}: {band_label('')[1:]} bands of {_runs_text(study)}", fontsize=10)
    return figure


def finals_against_measurements(study: UncertaintyStudy) -> bytes:
    """Per measured quantity, each set's 5–95 % interval of the final value at every condition side by
    side, the median marked, and the measured value; flagged measurements as a red cross."""
    return _png(finals_figure(study))


def finals_figure(study: UncertaintyStudy):
    panels = finals_panels(study)
    columns = 3 if len(panels) > 4 else 2
    rows = max(1, -(-len(panels) // columns))
    figure = _figure((9.0, 2.7 * rows + 0.9))
    axes = figure.subplots(rows, columns, squeeze=False).ravel()
    labels = [s.label for s in study.sets]
    width = 0.5 / max(1, len(labels))
    for ax, panel in zip(axes, panels):
        x = np.arange(len(panel.conditions), dtype=float)
        for index, label in enumerate(labels):
            offset = (index - (len(labels) - 1) / 2) * width
            for position, band in zip(x + offset, panel.bands[label]):
                if band is None:
                    continue
                ax.errorbar(position, band.p50, yerr=[[band.p50 - band.p05], [band.p95 - band.p50]], fmt="o",
                            ms=3, capsize=3, lw=1.6, color=colour(label, index))
        for position, value, flag in zip(x, panel.measured, panel.flags):
            if value is not None:
                ax.plot(position, value, "X" if flag else "D", color="tab:red" if flag else "k", ms=6, zorder=5,
                        mfc="none" if flag else "k")
        ax.set_xticks(x, panel.conditions)
        ax.set_xlim(-0.6, len(panel.conditions) - 0.4)
        ax.set_ylabel(UNIT_LABELS.get(panel.unit, panel.unit))
        counts = ", ".join(f"{label} {k}/{n}" for label, (k, n) in panel.inside.items())
        ax.set_title(f"{display_name(panel.quantity)}: measured inside the band\n{counts}", fontsize=8)
        ax.grid(alpha=0.3, axis="y")
    for ax in axes[len(panels):]:
        ax.set_axis_off()
    _finals_legend(figure, labels)
    totals = "; ".join(f"{s.label}: {s.coverage[0]} of {s.coverage[1]}" for s in study.sets)
    figure.suptitle(f"final values: measured values inside the {band_label('')[1:]} band — {totals}", fontsize=10)
    return figure


def sobol_indices(uset: UncertaintySet) -> bytes:
    """First-order (S1) and total (ST) Sobol indices as two heat maps, parameters × quantities."""
    return _png(sobol_figure(uset))


def sobol_figure(uset: UncertaintySet):
    matrix = sobol_matrix(uset)
    height = 0.32 * len(matrix.parameters) + 1.6
    figure = _figure((9.0, max(3.0, height)))
    axes = figure.subplots(1, 2, sharey=True)
    image = None
    for ax, values, name in ((axes[0], matrix.S1, "first order S1"), (axes[1], matrix.ST, "total ST")):
        image = ax.imshow(np.clip(np.nan_to_num(values, nan=0.0), 0, 1), vmin=0, vmax=1, cmap="viridis",
                          aspect="auto")
        for (row, column), value in np.ndenumerate(values):
            if np.isfinite(value):
                ax.text(column, row, f"{value:.2f}", ha="center", va="center", fontsize=6,
                        color="white" if value < 0.5 else "black")
        ax.set_xticks(range(len(matrix.quantities)), [display_name(q) for q in matrix.quantities], fontsize=8)
        ax.set_title(name, fontsize=9)
    axes[0].set_yticks(range(len(matrix.parameters)), matrix.parameters, fontsize=7)
    figure.colorbar(image, ax=axes, shrink=0.8, label="share of the variance of the final value")
    figure.suptitle(f"Sobol indices at condition {matrix.condition} ({uset.label}, {uset.runs} runs); "
                    f"parameters ordered by ST on {display_name(matrix.ordered_by)}", fontsize=9)
    return figure


# --------------------------------------------------------------------------- helpers


def _runs_text(study: UncertaintyStudy) -> str:
    return ", ".join(f"{s.runs} {s.label} runs" for s in study.sets if s.runs)


def _legend_entries(axes):
    """Each label once, in the order first drawn."""
    entries = {}
    for ax in axes:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            entries.setdefault(label, handle)
    return list(entries.values()), list(entries)


def _finals_legend(figure, labels: list[str]) -> None:
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], color=colour(label, i), marker="o", ms=3, lw=1.6) for i, label in enumerate(labels)]
    names = [band_label(label) + " (median marked)" for label in labels]
    handles += [Line2D([], [], color="k", marker="D", ls="none", ms=6),
                Line2D([], [], color="tab:red", marker="X", mfc="none", ls="none", ms=6)]
    names += ["measured", "measured, flagged by the consistency check"]
    # three entries a row: the figure's width holds them whatever the number of sets
    figure.legend(handles, names, loc="outside lower center", ncols=min(3, len(names)), fontsize=7, frameon=False)


def _figure(figsize):
    from matplotlib.figure import Figure

    return Figure(figsize=figsize, layout="constrained")


def _png(figure) -> bytes:
    buffer = io.BytesIO()
    figure.savefig(buffer, dpi=_DPI, format="png")
    return buffer.getvalue()
