"""PNG plots of a run: sensor temperatures, the elongation, the screw temperature map, the positioning error.

matplotlib is imported inside the functions (importing it costs ~0.3 s, which commands
that draw nothing should not pay).  Figures are built with ``matplotlib.figure.Figure``
and saved through the Agg canvas: no pyplot state, no GUI backend, and no change to the
backend of a caller who has one (``matplotlib.use`` would switch it for the whole process).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..constants import KELVIN_OFFSET
from ..solution import Solution
from .files import staged_directory
from .instants import spread_instants, time_label, time_unit
from .sensor_order import ordered_sensor_names

SENSORS_PNG = "sensors.png"
ELONGATION_PNG = "elongation.png"
SCREW_HEATMAP_PNG = "screw_heatmap.png"
POSITIONING_ERROR_PNG = "positioning_error.png"
PLOT_NAMES = (SENSORS_PNG, ELONGATION_PNG, SCREW_HEATMAP_PNG, POSITIONING_ERROR_PNG)

_DPI = 150
_HOURS = 3600.0
# More time columns than this adds nothing a 150-dpi heat map can show, only drawing time.
_MAX_HEATMAP_COLUMNS = 1500


def write_run_plots(solution: Solution, out_dir: Path) -> list[Path]:
    """Write ``sensors.png``, ``elongation.png``, ``screw_heatmap.png`` and ``positioning_error.png``
    into ``out_dir``.

    Staged and swapped in as one set (:func:`~feedtherm.outputs.files.staged_directory`):
    all four appear, or none; other files in ``out_dir`` are kept.
    """
    out_dir = Path(out_dir)
    with staged_directory(out_dir) as stage:
        names = draw_run_plots(solution, stage)
    return [out_dir / name for name in names]


def draw_run_plots(solution: Solution, directory: Path) -> list[str]:
    """Draw the four plots straight into ``directory`` (no staging); return their names.  A system
    without a feed drive has no screw map and no positioning error: two plots."""
    plot_sensors(solution, directory / SENSORS_PNG)
    plot_elongation(solution, directory / ELONGATION_PNG)
    if not solution.screw_x.size:
        return [SENSORS_PNG, ELONGATION_PNG]
    plot_screw_heatmap(solution, directory / SCREW_HEATMAP_PNG)
    plot_positioning_error(solution, directory / POSITIONING_ERROR_PNG)
    return list(PLOT_NAMES)


def run_label(solution: Solution) -> str:
    """``I, physics mode, fast model``: which run a figure shows."""
    info = solution.info
    parts = [str(info["condition"])] if info.get("condition") else []
    parts += [f"{info[key]} {key}" for key in ("mode", "model") if info.get(key)]
    return ", ".join(parts)


# --------------------------------------------------------------------------- the plots


def plot_sensors(solution: Solution, path: Path) -> None:
    """Every sensor [°C] over time [h]; the ambient sensor dashed grey, equilibrium marked."""
    figure = _figure(figsize=(9, 5))
    ax = figure.subplots()
    hours = solution.times / _HOURS
    celsius = solution.sensors_celsius()
    for name in ordered_sensor_names(solution):
        if name == solution.ambient_sensor:
            ax.plot(hours, celsius[name], color="0.45", linestyle="--", linewidth=1.2, label=f"{name} (ambient)")
        else:
            ax.plot(hours, celsius[name], linewidth=1.4, label=name)
    _mark_equilibrium(ax, solution)
    ax.set_xlabel("time [h]")
    ax.set_ylabel("temperature [°C]")
    ax.set_title(f"Sensor temperatures — {run_label(solution)}")
    ax.set_xlim(hours[0], hours[-1])
    ax.grid(True, alpha=0.3)
    ax.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False)
    _save(figure, path)


def plot_elongation(solution: Solution, path: Path) -> None:
    """D [µm] (against the reference temperature) above its change since the start [µm]."""
    figure = _figure(figsize=(9, 6))
    top, bottom = figure.subplots(2, 1, sharex=True)
    hours = solution.times / _HOURS
    steady_um = solution.summary_values("steady")["D_um"]
    top.plot(hours, solution.elongation_um, color="C0", linewidth=1.4, label="D (from the reference temperature)")
    top.axhline(steady_um, color="C0", linestyle="--", linewidth=1.0, alpha=0.6,
                label=f"steady state of the final operating point ({steady_um:.1f} µm)")
    top.set_ylabel("elongation D [µm]")
    top.set_title(f"Screw elongation — {run_label(solution)}")
    bottom.plot(hours, solution.elongation_change_um, color="C1", linewidth=1.4)
    bottom.set_ylabel("change since start ΔD [µm]")
    bottom.set_xlabel("time [h]")
    bottom.set_xlim(hours[0], hours[-1])
    for ax in (top, bottom):
        _mark_equilibrium(ax, solution, label=ax is top)
        ax.grid(True, alpha=0.3)
    top.legend(loc="lower right", frameon=False)
    _save(figure, path)


def plot_screw_heatmap(solution: Solution, path: Path) -> None:
    """Screw temperature [°C] by time [h] (x) and axial position [mm] (y)."""
    figure = _figure(figsize=(9, 5))
    ax = figure.subplots()
    columns = _thinned(solution.times.size, _MAX_HEATMAP_COLUMNS)
    hours = solution.times[columns] / _HOURS
    x_mm = solution.screw_x * 1e3
    celsius = solution.screw_temperature[columns] - KELVIN_OFFSET
    mesh = ax.pcolormesh(hours, x_mm, celsius.T, shading="nearest", cmap="inferno", rasterized=True)
    figure.colorbar(mesh, ax=ax, label="screw temperature [°C]")
    ax.set_xlabel("time [h]")
    ax.set_ylabel("axial position x [mm]")
    ax.set_title(f"Screw temperature (cross-section mean) — {run_label(solution)}")
    _save(figure, path)


def plot_positioning_error(solution: Solution, path: Path, n_curves: int = 5) -> None:
    """The thermal positioning error E [µm] against the table position [mm] at a few times.

    Up to ``n_curves`` instants evenly spread over the run, the last one in black with its
    largest |E| marked: how the error along the stroke grows as the drive warms up.
    """
    x_mm = np.asarray(solution.table_x, dtype=float) * 1e3
    error_um = np.asarray(solution.positioning_error, dtype=float) * 1e6
    figure = _figure(figsize=(9, 5))
    ax = figure.subplots()
    unit = time_unit(solution.times)
    picks = spread_instants(solution.times, n_curves)
    # a single table position is a point, not a line: draw it as a marker
    style = {"marker": "o"} if x_mm.size == 1 else {}
    shades = _colormap("Blues")(np.linspace(0.35, 0.8, max(len(picks) - 1, 1)))
    for colour, k in zip(shades, picks[:-1]):
        ax.plot(x_mm, error_um[k], color=colour, linewidth=1.3,
                label=f"t = {time_label(solution.times[k], unit)}", **style)
    final = error_um[picks[-1]]
    ax.plot(x_mm, final, color="black", linewidth=2.0, label=f"t = {time_label(solution.times[-1], unit)}",
            **style)
    if x_mm.size:
        peak = int(np.nanargmax(np.abs(final))) if np.isfinite(final).any() else 0
        right_half = x_mm[peak] > 0.5 * (x_mm[0] + x_mm[-1])
        ax.plot(x_mm[peak], final[peak], "o", color="black", markersize=4)
        ax.annotate(f"{final[peak]:.1f} µm at x = {x_mm[peak]:.0f} mm", xy=(x_mm[peak], final[peak]),
                    xytext=(-8 if right_half else 8, 8 if final[peak] >= 0 else -14),
                    textcoords="offset points", ha="right" if right_half else "left", fontsize=9)
    ax.axhline(0.0, color="0.5", linewidth=0.8)
    ax.set_xlabel("table position x [mm]")
    ax.set_ylabel("positioning error E [µm]")
    ax.set_title(f"Thermal positioning error along the stroke — {run_label(solution)}")
    ax.margins(y=0.12)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=9, frameon=False)
    _save(figure, path)


# --------------------------------------------------------------------------- helpers


def _colormap(name: str):
    from matplotlib import colormaps

    return colormaps[name]


def _figure(figsize: tuple[float, float]):
    from matplotlib.figure import Figure

    return Figure(figsize=figsize, layout="constrained")


def _save(figure, path: Path) -> None:
    figure.savefig(path, dpi=_DPI, format="png")


def _mark_equilibrium(ax, solution: Solution, *, label: bool = True) -> None:
    """A dotted vertical line where the run reached thermal equilibrium (if it did)."""
    if solution.equilibrium_time is None:
        return
    hours = solution.equilibrium_time / _HOURS
    ax.axvline(hours, color="0.3", linestyle=":", linewidth=1.0,
               label=f"equilibrium ({hours:.2f} h)" if label else None)


def _thinned(count: int, limit: int) -> np.ndarray:
    """Indices of every k-th of ``count`` samples so that at most ``limit`` remain, last kept."""
    step = max(1, -(-count // limit))
    indices = np.arange(0, count, step)
    if count and indices[-1] != count - 1:
        indices = np.append(indices, count - 1)
    return indices
