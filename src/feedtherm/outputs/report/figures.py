"""The report's figures as PNG bytes.

Same conventions as :mod:`feedtherm.outputs.plots`: matplotlib is imported inside the
functions, figures are ``matplotlib.figure.Figure`` objects (no pyplot state, no backend
change).  Figures are 9 in wide at 120 dpi (1080 px) so that their text stays readable when
the page shows them 900 px wide.  They are embedded as palette PNGs (:func:`compact_png`):
a plot's flat colours and anti-aliased edges fit in 256 colours, at a third of the bytes of
the RGBA file matplotlib writes, which keeps a report of many figures light to mail.
"""

from __future__ import annotations

import io
from collections.abc import Sequence

import numpy as np

from ...analysis.validation_types import ELONGATION_QUANTITY, Comparison, Sensitivity
from ...constants import KELVIN_OFFSET
from ...solution import Solution
from ..plots import _thinned

_DPI = 120
_WIDTH = 9.0  # in
_HOURS = 3600.0
_MAX_HEATMAP_COLUMNS = 1200
_D_COLOUR = "C5"


def _colours(names: Sequence[str]) -> dict[str, str]:
    """One colour per sensor in its order, skipping D's."""
    palette = [f"C{i}" for i in range(10) if f"C{i}" != _D_COLOUR]
    return {name: palette[i % len(palette)] for i, name in enumerate(names)}


def sensor_curves(solution: Solution, condition: str, measured: dict[str, float],
                  stated_equilibrium_min: float | None) -> bytes:
    """The sensors [°C] over time [h] above D [µm]; the measured equilibrium values dashed.

    Each sensor has one legend entry showing its simulated (solid) and measured (dashed) line
    and the measured value.
    """
    from matplotlib.legend_handler import HandlerTuple

    figure = _figure(6.6)
    top, bottom = figure.subplots(2, 1, sharex=True, height_ratios=(3, 2))
    hours = solution.times / _HOURS
    celsius = solution.sensors_celsius()
    handles, labels = [], []
    ambient = solution.ambient_sensor
    colours = _colours([n for n in celsius if n != ambient])
    for name, colour in colours.items():
        (line,) = top.plot(hours, celsius[name], color=colour, linewidth=1.6)
        if name in measured:
            level = top.axhline(measured[name], color=colour, linestyle="--", linewidth=1.2, alpha=0.85)
            handles.append((line, level))
            labels.append(f"{name}, measured {measured[name]:.1f} °C")
        else:
            handles.append(line)
            labels.append(f"{name} (not measured)")
    if ambient in celsius:
        (line,) = top.plot(hours, celsius[ambient], color="0.5", linestyle=":", linewidth=1.2)
        handles.append(line)
        labels.append(f"{ambient} ambient")
    bottom.plot(hours, solution.elongation_um, color=_D_COLOUR, linewidth=1.6, label="D simulated")
    if ELONGATION_QUANTITY in measured:
        bottom.axhline(measured[ELONGATION_QUANTITY], color=_D_COLOUR, linestyle="--", linewidth=1.2,
                       label=f"D measured {measured[ELONGATION_QUANTITY]:.1f} µm")
    for ax in (top, bottom):
        _mark_times(ax, solution, stated_equilibrium_min, label=ax is bottom)
        ax.grid(True, alpha=0.3)
    top.legend(handles, labels, handler_map={tuple: HandlerTuple(ndivide=None, pad=0.6)}, handlelength=4.0,
               loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False, fontsize=9,
               title="simulated / measured", title_fontsize=9)
    bottom.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False, fontsize=9)
    top.set_ylabel("temperature [°C]")
    bottom.set_ylabel("elongation D [µm]")
    bottom.set_xlabel("time [h]")
    bottom.set_xlim(hours[0], hours[-1])
    top.set_title(f"Condition {condition}: simulated series (solid) and measured equilibrium values (dashed)")
    return _png(figure)


def screw_field(solution: Solution, condition: str, profile_count: int = 5) -> bytes:
    """Screw temperature [°C] by time [h] and position [mm], above axial profiles."""
    import matplotlib

    figure = _figure(8.0)
    top, bottom = figure.subplots(2, 1, height_ratios=(1, 1))
    columns = _thinned(solution.times.size, _MAX_HEATMAP_COLUMNS)
    x_mm = solution.screw_x * 1e3
    celsius = solution.screw_temperature - KELVIN_OFFSET
    mesh = top.pcolormesh(solution.times[columns] / _HOURS, x_mm, celsius[columns].T, shading="nearest",
                          cmap="inferno", rasterized=True)
    figure.colorbar(mesh, ax=top, label="screw temperature [°C]")
    top.set_xlabel("time [h]")
    top.set_ylabel("axial position x [mm]")
    top.set_title(f"Condition {condition}: screw temperature (cross-section mean) over time and position")
    rows = profile_rows(solution.times, profile_count)
    colours = matplotlib.colormaps["viridis"](np.linspace(0.0, 0.9, len(rows)))
    for colour, row in zip(colours, rows):
        bottom.plot(x_mm, celsius[row], color=colour, linewidth=1.6,
                    label=f"t = {_duration_label(solution.times[row])}")
    bottom.set_xlabel("axial position x [mm]")
    bottom.set_ylabel("screw temperature [°C]")
    bottom.set_title("Axial profiles at selected times")
    bottom.set_xlim(x_mm[0], x_mm[-1])
    bottom.grid(True, alpha=0.3)
    bottom.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False, fontsize=9)
    return _png(figure)


def positioning_error(solutions: dict[str, Solution]) -> bytes:
    """E [µm] along the stroke at each run's end (solid) over the screw's displacement profile (dotted)."""
    figure = _figure(4.2)
    ax = figure.subplots()
    for index, (condition, solution) in enumerate(solutions.items()):
        colour = f"C{index}"
        ax.plot(solution.screw_x * 1e3, solution.screw_displacement[-1] * 1e6, color=colour, linestyle=":",
                linewidth=1.0)
        ax.plot(solution.table_x * 1e3, solution.positioning_error[-1] * 1e6, color=colour, linewidth=2.0,
                label=f"{condition}: E from {solution.positioning_error[-1, 0] * 1e6:.1f} to "
                      f"{solution.positioning_error[-1, -1] * 1e6:.1f} µm")
    ax.set_xlabel("position along the axis, x [mm] (solid: the table's positions over the stroke)")
    ax.set_ylabel("axial displacement [µm]")
    ax.axhline(0.0, color="0.6", linewidth=0.8)
    ax.legend(fontsize=8, ncol=2)
    ax.grid(alpha=0.3)
    return _png(figure)


#: Each kind of trend panel: its x-axis label and what its title says the series varies in.
TREND_AXES = {"speed": "screw speed n_s [rpm]", "ambient": "ambient temperature [°C]"}


def trends(panels: Sequence[tuple[str, Sequence[tuple[str, float | None]], str]],
           rows: dict[tuple[str, str], Comparison], temperatures: Sequence[str]) -> bytes:
    """Final ``temperatures`` [°C] and D [µm] against screw speed and/or against ambient, simulated
    and measured: one column per panel ``(kind, points, shared)``, ``kind`` "speed" or "ambient",
    ``points`` ``(condition, x)``, ``shared`` what the series holds fixed (the column's titles).

    A series with an unknown x is drawn at evenly spaced positions labelled by condition.
    """
    from matplotlib.lines import Line2D

    figure = _figure(7.4)
    axes = figure.subplots(2, len(panels), sharex="col", squeeze=False)
    colours = _colours(temperatures)
    for column, (kind, points, shared) in enumerate(panels):
        temps, elong = axes[0, column], axes[1, column]
        xs, ticks = _positions(points)
        names = [name for name, _ in points]
        for quantity in temperatures:
            _trend_lines(temps, xs, names, quantity, rows, colours[quantity])
        _trend_lines(elong, xs, names, ELONGATION_QUANTITY, rows, _D_COLOUR)
        title = f"against {kind}" + (f"\n({shared})" if shared else "")  # two lines: two columns fit 9 in
        temps.set_title(f"Final temperatures {title}", fontsize=10.5)
        elong.set_title(f"Elongation D {title}", fontsize=10.5)
        temps.set_ylabel("temperature [°C]")
        elong.set_ylabel("elongation D [µm]")
        elong.set_xlabel(TREND_AXES[kind])
        elong.set_xticks(xs, ticks)
        for ax in (temps, elong):
            ax.grid(True, alpha=0.3)
            if len(xs):
                pad = 0.08 * (max(xs) - min(xs) or 1.0)
                ax.set_xlim(min(xs) - pad, max(xs) + pad)
    handles = [Line2D([], [], color=colours[q], linewidth=1.6, label=q) for q in temperatures]
    handles += [Line2D([], [], color=_D_COLOUR, linewidth=1.6, label="D"),
                Line2D([], [], color="0.2", marker="o", linewidth=1.6, label="simulated"),
                Line2D([], [], color="0.2", marker="s", markerfacecolor="white", linestyle="--",
                       linewidth=1.2, label="measured")]
    figure.legend(handles=handles, loc="outside lower center", ncols=len(handles), frameon=False, fontsize=9)
    return _png(figure)


def dual_single(conditions: Sequence[str], dual: dict[str, dict[str, float]],
                single: dict[str, dict[str, float]]) -> bytes:
    """Mean heat [W] and final D [µm], dual beside single drive, per condition."""
    figure = _figure(3.8)
    heat_ax, d_ax = figure.subplots(1, 2)
    x = np.arange(len(conditions))
    width = 0.38
    for ax, key, label in ((heat_ax, "heat_W", "mean heat generated [W]"), (d_ax, "D_um", "final elongation D [µm]")):
        for offset, (values, name, colour) in zip((-width / 2, width / 2),
                                                  ((dual, "dual drive", "C0"), (single, "single drive", "C1"))):
            heights = [values.get(c, {}).get(key, np.nan) for c in conditions]
            ax.bar(x + offset, heights, width, color=colour, label=name)
        ax.set_xticks(x, conditions)
        ax.set_xlabel("condition")
        ax.set_ylabel(label)
        ax.grid(True, axis="y", alpha=0.3)
    heat_ax.set_title("Heat generated, same table speed", fontsize=10.5)
    d_ax.set_title("Screw elongation at the end of the run", fontsize=10.5)
    heat_ax.legend(frameon=False, fontsize=9)
    return _png(figure)


def heat_budget(budget: dict[str, dict[str, float]]) -> bytes:
    """Heat [W] per source, grouped by condition; sources ordered by their total."""
    conditions = list(budget)
    totals: dict[str, float] = {}
    for sources in budget.values():
        for source, watts in sources.items():
            totals[source] = totals.get(source, 0.0) + abs(watts)
    sources = sorted(totals, key=totals.get, reverse=True)
    figure = _figure(4.6)
    ax = figure.subplots()
    x = np.arange(len(conditions))
    width = 0.84 / max(1, len(sources))
    for index, source in enumerate(sources):
        heights = [budget[c].get(source, 0.0) for c in conditions]
        ax.bar(x - 0.42 + (index + 0.5) * width, heights, width, label=source.replace("_", " "),
               color=f"C{index % 10}")
    ax.set_xticks(x, conditions)
    ax.set_xlabel("condition")
    ax.set_ylabel("heat [W]")
    ax.set_title("Heat per source and condition")
    ax.grid(True, axis="y", alpha=0.3)
    ax.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False, fontsize=9)
    return _png(figure)


def sensitivity_bars(rows: Sequence[Sensitivity], condition: str) -> bytes:
    """Horizontal bars: largest |ΔT| [K] and |ΔD| [µm] of each perturbed parameter, largest on top."""
    figure = _figure(1.6 + 0.34 * max(1, len(rows)))
    t_ax, d_ax = figure.subplots(1, 2, sharey=True, width_ratios=(3, 2))
    y = np.arange(len(rows))[::-1]
    labels = [f"{_shorten(row.label)} ×{row.factor:g}" for row in rows]
    t_ax.barh(y, [row.max_temperature_effect for row in rows], color="C3")
    d_ax.barh(y, [abs(row.effect.get(ELONGATION_QUANTITY, np.nan)) for row in rows], color=_D_COLOUR)
    t_ax.set_yticks(y, labels, fontsize=8.5)
    t_ax.set_xlabel("largest |ΔT| over the sensors [K]")
    d_ax.set_xlabel("|ΔD| [µm]")
    t_ax.set_title(f"Steady-state effect, condition {condition}", fontsize=10.5)
    d_ax.set_title("Elongation", fontsize=10.5)
    for ax in (t_ax, d_ax):
        ax.grid(True, axis="x", alpha=0.3)
    return _png(figure)


# --------------------------------------------------------------------------- helpers


def profile_rows(times: np.ndarray, count: int) -> list[int]:
    """Sample indices at about 1/16, 1/8, 1/4, 1/2 and all of the run (distinct, ascending)."""
    end = float(times[-1])
    fractions = [2.0 ** -k for k in range(count - 1, -1, -1)]
    rows = sorted({int(np.argmin(np.abs(times - f * end))) for f in fractions})
    return [row for row in rows if times[row] > times[0]] or [times.size - 1]


def _trend_lines(ax, xs, names, quantity, rows, colour) -> None:
    simulated = [_value(rows, name, quantity, "simulated") for name in names]
    measured = [_value(rows, name, quantity, "measured") for name in names]
    ax.plot(xs, simulated, color=colour, marker="o", linewidth=1.6)
    ax.plot(xs, measured, color=colour, marker="s", markerfacecolor="white", linestyle="--", linewidth=1.2)


def _value(rows, condition, quantity, attribute) -> float:
    row = rows.get((condition, quantity))
    return np.nan if row is None else getattr(row, attribute)


def _positions(points) -> tuple[list[float], list[str]]:
    if points and all(x is not None for _, x in points):
        return [float(x) for _, x in points], [f"{x:g}\n({name})" for name, x in points]
    return [float(i) for i in range(len(points))], [name for name, _ in points]


def _mark_times(ax, solution: Solution, stated_equilibrium_min: float | None, *, label: bool) -> None:
    if solution.equilibrium_time is not None:
        hours = solution.equilibrium_time / _HOURS
        ax.axvline(hours, color="0.25", linestyle=":", linewidth=1.2,
                   label=f"model equilibrium ({hours * 60:.0f} min)" if label else None)
    end_h = solution.times[-1] / _HOURS
    if stated_equilibrium_min is not None and stated_equilibrium_min / 60.0 <= end_h:
        ax.axvline(stated_equilibrium_min / 60.0, color="0.55", linestyle="-.", linewidth=1.2,
                   label=f"stated equilibrium ({stated_equilibrium_min:.0f} min)" if label else None)


def _duration_label(seconds: float) -> str:
    minutes = seconds / 60.0
    return f"{minutes:.0f} min" if minutes < 120 else f"{minutes / 60.0:.1f} h"


def _shorten(path: str, limit: int = 44) -> str:
    return path if len(path) <= limit else "…" + path[-(limit - 1):]


def _figure(height: float):
    from matplotlib.figure import Figure

    return Figure(figsize=(_WIDTH, height), layout="constrained")


#: Colours of the report's palette PNGs: a figure's lines, bars and colour map fit in 256 without banding.
PNG_COLOURS = 256


def _png(figure) -> bytes:
    buffer = io.BytesIO()
    figure.savefig(buffer, dpi=_DPI, format="png")
    return compact_png(buffer.getvalue())


def compact_png(png: bytes, colours: int = PNG_COLOURS) -> bytes:
    """``png`` as an optimised palette PNG of at most ``colours`` colours, same size in pixels.

    The figures are drawn on an opaque white face, so the alpha channel is dropped; the median-cut
    palette without dithering keeps lines and text crisp.  Pillow comes with matplotlib.
    """
    from PIL import Image

    with Image.open(io.BytesIO(png)) as image:
        palette = image.convert("RGB").quantize(colors=colours, method=Image.Quantize.MEDIANCUT,
                                                dither=Image.Dither.NONE)
    buffer = io.BytesIO()
    palette.save(buffer, format="PNG", optimize=True)
    return buffer.getvalue()
