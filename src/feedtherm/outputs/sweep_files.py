"""The files of ``feedtherm sweep``: ``sweep.csv`` and PNG plots of the swept values.

Reads the row dicts of :func:`feedtherm.analysis.sweep.run_sweep` (already in °C, µm, rpm
and m/min).  Like a run's files, the set is staged and swapped in whole
(:func:`~feedtherm.outputs.files.staged_directory`): all files appear, or none, and no plot
of an earlier sweep is left beside the new CSV.  The layout is documented in
``docs/sweep.md``.

Plots are built with ``matplotlib.figure.Figure`` (no pyplot state), matplotlib imported
inside the functions, as in :mod:`feedtherm.outputs.plots`.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from ..analysis.sweep import OPTIONS, columns
from .files import staged_directory

SWEEP_CSV = "sweep.csv"
HEAT_MAP_PNG = "sweep_heat_map.png"
#: One plot per swept variable that has more than one value.
PLOT_NAMES = {"screw_rpm": "sweep_screw_rpm.png", "nut_rpm": "sweep_nut_rpm.png", "ambient_C": "sweep_ambient.png"}
#: Every file a sweep can write: the plots depend on which variables vary.
SWEEP_FILES = (SWEEP_CSV, HEAT_MAP_PNG, *PLOT_NAMES.values())

AXIS_LABELS = {"screw_rpm": r"screw speed $n_\mathrm{s}$ [rpm]", "nut_rpm": r"nut speed $n_\mathrm{n}$ [rpm]",
               "ambient_C": "ambient temperature [°C]"}
_SHORT = {"screw_rpm": ("screw", "rpm"), "nut_rpm": ("nut", "rpm"), "ambient_C": ("ambient", "°C")}

_DPI = 150
# Inputs are written as given (up to 10 significant digits); results with the 4 decimals of a run's files.
_INPUT_FORMAT = "{:.10g}"
_VALUE_FORMAT = "{:.4f}"
_ERROR_FORMAT = "{:.3e}"
# More curves than this get no legend entry each (the CSV has the numbers).
_MAX_LEGEND_CURVES = 12
# Up to this many swept values, the ticks sit at the values themselves.
_MAX_VALUE_TICKS = 10
# Heat-map cells are labelled with their value up to this many cells.
_MAX_LABELLED_CELLS = 120


def write_sweep(rows: list[dict], sensors: dict[str, str], out_dir: Path, *, title: str = "",
                drop: tuple[str, ...] = ()) -> list[Path]:
    """Write ``sweep.csv`` and the plots into ``out_dir``; return the written paths.

    Parameters
    ----------
    rows : list of dict
        One per grid point, keyed by :func:`~feedtherm.analysis.sweep.columns`.
    sensors : dict
        Sensor name -> short label (``{"<sensor>": "front bearing", …}``), in column order.
    out_dir : Path
        Created if missing; an earlier sweep's files (:data:`SWEEP_FILES`) are replaced as a
        whole, also plots this sweep does not draw; other files are kept.
    title : str
        What the sweep ran (description, mode, motion, duration), shown on every plot.
    drop : tuple of str
        Other entries of ``out_dir`` that go in the same swap (the kept rows of a finished
        sweep, :data:`~feedtherm.outputs.sweep_partial.PARTIAL_DIR`): gone exactly when the
        new files are in.
    """
    out_dir = Path(out_dir)
    with staged_directory(out_dir, replaces=SWEEP_FILES + tuple(drop)) as stage:
        write_sweep_csv(rows, list(sensors), stage / SWEEP_CSV)
        names = [SWEEP_CSV] + draw_sweep_plots(rows, sensors, stage, title=title)
    return [out_dir / name for name in names]


# --------------------------------------------------------------------------- CSV


def write_sweep_csv(rows: list[dict], sensors: list[str], path: Path) -> None:
    """One row per grid point; an equilibrium not reached is an empty cell."""
    header = columns(sensors)
    with open(path, "w", encoding="utf-8", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(header)
        for row in rows:
            writer.writerow([_cell(name, row.get(name)) for name in header])


def _cell(column: str, value) -> str:
    if value is None:
        return ""
    if column in OPTIONS or column == "table_speed_m_per_min" or column == "equilibrium_time_s":
        return _INPUT_FORMAT.format(value)
    if column == "energy_balance_error":
        return _ERROR_FORMAT.format(value)
    if column == "motor_duty":
        return f"{value:.3f}"
    return _VALUE_FORMAT.format(value)


# --------------------------------------------------------------------------- plots


def varied(rows: list[dict]) -> list[str]:
    """The swept variables with more than one value among ``rows``, in column order."""
    return [name for name in OPTIONS if len({row[name] for row in rows}) > 1]


def draw_sweep_plots(rows: list[dict], sensors: dict[str, str], directory: Path, *, title: str = "") -> list[str]:
    """One plot per varied variable, and the heat map when exactly two vary; return the names."""
    names = []
    swept = varied(rows)
    for variable in swept:
        plot_against(rows, sensors, variable, directory / PLOT_NAMES[variable], title=title)
        names.append(PLOT_NAMES[variable])
    if len(swept) == 2:
        plot_heat_map(rows, swept[0], swept[1], directory / HEAT_MAP_PNG, title=title)
        names.append(HEAT_MAP_PNG)
    return names


def plot_against(rows: list[dict], sensors: dict[str, str], variable: str, path: Path, *, title: str = "") -> None:
    """D and every sensor (one panel each) against ``variable``: steady solid, final dashed,
    one colour per combination of the other swept variables."""
    from matplotlib.lines import Line2D

    others = [name for name in OPTIONS if name != variable]
    others_varied = [name for name in others if len({row[name] for row in rows}) > 1]
    groups = _groups(rows, others_varied)
    colours = _colours(len(groups))
    quantities = [("D_um", "elongation D [µm]", "D — screw elongation")]
    quantities += [(name, f"{name} [°C]", f"{name} — {label}" if label else name) for name, label in sensors.items()]

    n_cols = 3 if len(quantities) > 4 else len(quantities)
    n_rows = math.ceil(len(quantities) / n_cols)
    figure = _figure(figsize=(4.0 * n_cols + 2.6, 3.1 * n_rows + 0.9))
    axes = np.atleast_1d(figure.subplots(n_rows, n_cols, sharex=True, squeeze=False)).ravel()
    for ax, (key, ylabel, panel_title) in zip(axes, quantities):
        for colour, (_, members) in zip(colours, groups):
            members = sorted(members, key=lambda row: row[variable])
            x = [row[variable] for row in members]
            ax.plot(x, [row[f"steady_{key}"] for row in members], color=colour, linewidth=1.5,
                    marker="o", markersize=3.5)
            ax.plot(x, [row[f"final_{key}"] for row in members], color=colour, linewidth=1.1,
                    linestyle="--", marker="o", markersize=2.5, markerfacecolor="white")
        ax.set_title(panel_title, fontsize=10)
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
    for index, ax in enumerate(axes):
        if index >= len(quantities):
            ax.set_visible(False)
        elif index + n_cols >= len(quantities):  # the lowest panel of its column
            ax.set_xlabel(AXIS_LABELS[variable])
            ax.xaxis.set_tick_params(labelbottom=True)
    xs = sorted({row[variable] for row in rows})
    if len(xs) <= _MAX_VALUE_TICKS:
        axes[0].set_xticks(xs)  # shared: every panel ticks at the swept values
    _table_speed_axis(axes[0], rows, variable)

    handles = [Line2D([], [], color="0.25", linewidth=1.5, marker="o", markersize=3.5, label="steady state"),
               Line2D([], [], color="0.25", linewidth=1.1, linestyle="--", marker="o", markersize=2.5,
                      markerfacecolor="white", label="final (end of run)")]
    if others_varied:
        shown = list(zip(colours, groups))
        if len(groups) > _MAX_LEGEND_CURVES:  # the colour runs in order: name its two ends
            shown = [shown[0], shown[-1]]
        handles += [Line2D([], [], color=colour, linewidth=2.0, label=_group_label(others_varied, key))
                    for colour, (key, _) in shown]
        if len(groups) > _MAX_LEGEND_CURVES:
            handles.insert(3, Line2D([], [], linestyle="none", label=f"… {len(groups) - 2} more, in order …"))
    figure.legend(handles=handles, loc="outside right upper", frameon=False, fontsize=9)
    fixed = [_value_label(name, rows[0][name]) for name in others if name not in others_varied]
    heading = f"Sweep of the {AXIS_LABELS[variable].split(' [')[0]}"
    if fixed:
        heading += f" at {', '.join(fixed)}"
    if others_varied and len(groups) > _MAX_LEGEND_CURVES:
        heading += f" — {len(groups)} curves, one per {' and '.join(_SHORT[n][0] for n in others_varied)} value"
    figure.suptitle(f"{heading}\n{title}" if title else heading, fontsize=11)
    _save(figure, path)


def plot_heat_map(rows: list[dict], x_name: str, y_name: str, path: Path, *, title: str = "") -> None:
    """Steady D [µm] over the grid of the two varied variables."""
    xs = sorted({row[x_name] for row in rows})
    ys = sorted({row[y_name] for row in rows})
    grid = np.full((len(ys), len(xs)), np.nan)
    for row in rows:
        grid[ys.index(row[y_name]), xs.index(row[x_name])] = row["steady_D_um"]

    figure = _figure(figsize=(8.5, 6.0))
    ax = figure.subplots()
    mesh = ax.pcolormesh(xs, ys, grid, shading="nearest", cmap="viridis")
    figure.colorbar(mesh, ax=ax, label="steady elongation D [µm]")
    if grid.size <= _MAX_LABELLED_CELLS:
        _label_cells(ax, mesh, xs, ys, grid)
    if len(xs) <= _MAX_VALUE_TICKS:
        ax.set_xticks(xs)
    if len(ys) <= _MAX_VALUE_TICKS:
        ax.set_yticks(ys)
    ax.set_xlabel(AXIS_LABELS[x_name])
    ax.set_ylabel(AXIS_LABELS[y_name])
    fixed = [name for name in OPTIONS if name not in (x_name, y_name)]
    heading = "Steady screw elongation D"
    if fixed:
        heading += f" at {_value_label(fixed[0], rows[0][fixed[0]])}"
    ax.set_title(f"{heading}\n{title}" if title else heading, fontsize=11)
    _save(figure, path)


# --------------------------------------------------------------------------- helpers


def _groups(rows: list[dict], keys: list[str]) -> list[tuple[tuple, list[dict]]]:
    """Rows grouped by their values of ``keys`` (sorted by those values)."""
    groups: dict[tuple, list[dict]] = {}
    for row in rows:
        groups.setdefault(tuple(row[k] for k in keys), []).append(row)
    return sorted(groups.items())


def _colours(count: int) -> list:
    from matplotlib import colormaps

    if count <= 10:
        return [f"C{i}" for i in range(count)]
    return list(colormaps["viridis"](np.linspace(0.0, 0.92, count)))


def _value_label(name: str, value: float) -> str:
    short, unit = _SHORT[name]
    return f"{short} {value:g} {unit}"


def _group_label(names: list[str], values: tuple) -> str:
    return ", ".join(_value_label(name, value) for name, value in zip(names, values))


def _table_speed_axis(ax, rows: list[dict], variable: str) -> None:
    """A table-speed scale on top when the other motor's speed is one value (speed = (n_s − n_n)·lead)."""
    if variable not in ("screw_rpm", "nut_rpm"):
        return
    other = "nut_rpm" if variable == "screw_rpm" else "screw_rpm"
    if len({row[other] for row in rows}) != 1:
        return
    leads = [row["table_speed_m_per_min"] / (row["screw_rpm"] - row["nut_rpm"])
             for row in rows if row["screw_rpm"] != row["nut_rpm"]]
    if not leads:
        return
    lead, fixed = leads[0], rows[0][other]
    sign = 1.0 if variable == "screw_rpm" else -1.0
    # speed = sign * (n - fixed) * lead  <=>  n = fixed + speed / (sign * lead)
    top = ax.secondary_xaxis("top", functions=(lambda n: sign * (n - fixed) * lead,
                                               lambda v: fixed + v / (sign * lead)))
    top.set_xlabel("table speed [m/min]", fontsize=9)
    xs = sorted({row[variable] for row in rows})
    if len(xs) <= _MAX_VALUE_TICKS:  # above the speeds' own ticks
        top.set_xticks([sign * (x - fixed) * lead for x in xs])
        top.xaxis.set_major_formatter("{x:g}")


def _label_cells(ax, mesh, xs, ys, grid) -> None:
    norm, cmap = mesh.norm, mesh.cmap
    size = 9 if grid.size <= 40 else 7
    for i, y in enumerate(ys):
        for j, x in enumerate(xs):
            value = grid[i, j]
            if not np.isfinite(value):
                continue
            r, g, b, _ = cmap(norm(value))
            colour = "black" if 0.299 * r + 0.587 * g + 0.114 * b > 0.5 else "white"
            ax.text(x, y, f"{value:.1f}", ha="center", va="center", fontsize=size, color=colour)


def _figure(figsize: tuple[float, float]):
    from matplotlib.figure import Figure

    return Figure(figsize=figsize, layout="constrained")


def _save(figure, path: Path) -> None:
    figure.savefig(path, dpi=_DPI, format="png")


# --------------------------------------------------------------------------- the console line


def summary_line(out_dir: Path, points: int, wall_time_s: float, resumed: int | None = None) -> str:
    """One line: where the files are, how many points, how long it took (and, after ``--resume``,
    how many points were kept from the interrupted run rather than run again)."""
    line = f"{out_dir}: sweep of {points} point{'s' if points != 1 else ''} written in {wall_time_s:.1f} s"
    if resumed is not None:
        line += f"; resumed {resumed} of {points} points, ran {points - resumed}"
    return line


def sweep_title(system: str, mode_name: str, motion: str, duration_s: float) -> str:
    """``paper — physics mode, averaged motion, 1800 s (0.5 h) per point``: what every plot shows."""
    return f"{system} — {mode_name} mode, {motion} motion, {duration_s:g} s ({duration_s / 3600:.3g} h) per point"
