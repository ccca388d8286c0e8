"""The files of ``feedtherm run``: sensor series, screw fields, the positioning error, the energy
ledger (part temperatures, source heats) and a JSON summary.

Everything is read from a :class:`~feedtherm.solution.Solution` (SI inside); the kelvin →
°C and metre → µm conversions happen here, at the output edge.  The layout of every file is
documented in ``docs/outputs.md``.

The files of one call are staged and swapped in as one set
(:func:`~feedtherm.outputs.files.staged_directory`): an error, Ctrl-C or a killed process
never leaves a half-written file, or new files beside old ones, behind.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from ..constants import ELONGATION_PROBE, KELVIN_OFFSET
from ..solution import Solution
from .field_images import (
    SCREW_AXIAL_DEFORMATION_PNG,
    SCREW_DEFORMATION_PNG,
    TEMPERATURE_FIELD_PNG,
    write_field_images,
)
from .fields import PVD_NAME, write_pvd
from .files import staged_directory, to_json_ready, write_json
from .plots import PLOT_NAMES, draw_run_plots
from .sensor_order import ordered_sensor_names

SENSORS_CSV = "sensors.csv"
SCREW_CSV = "screw.csv"
SCREW_DISPLACEMENT_CSV = "screw_displacement.csv"
POSITIONING_ERROR_CSV = "positioning_error.csv"
PARTS_CSV = "parts.csv"
HEAT_CSV = "heat.csv"
SUMMARY_JSON = "summary.json"
TABLES = (SENSORS_CSV, SCREW_CSV, SCREW_DISPLACEMENT_CSV, POSITIONING_ERROR_CSV, PARTS_CSV, HEAT_CSV, SUMMARY_JSON)
#: heat.csv's last column: the heat lost to the air and the surfaces' sinks [W].
LOST_COLUMN = "lost"
#: Every file a run can write (glob patterns): an earlier run's files in its directory.
RUN_FILES = (*TABLES, *PLOT_NAMES, PVD_NAME, "fields_*.vtu", TEMPERATURE_FIELD_PNG, SCREW_DEFORMATION_PNG,
             SCREW_AXIAL_DEFORMATION_PNG)
#: ``solution.info`` key of the screw's part name (``kinematics.screw``): which part of a field
#: series the screw image shows.
SCREW_PART_KEY = "screw_part"

# Fixed decimals keep the columns readable; 1e-4 °C and 1e-4 µm are far below any
# measurement or model accuracy.
_TIME_FORMAT = "%.10g"
_VALUE_FORMAT = "%.4f"
# The energy ledger's files keep every digit (17 significant: a double read back is the same
# double), so that the stored heat recomputed from them is the run's to round-off.
_EXACT_FORMAT = "%.17g"


def write_run_outputs(solution: Solution, out_dir: Path, *, sample_interval: float) -> list[Path]:
    """Write ``sensors.csv``, ``screw.csv``, ``screw_displacement.csv``, ``positioning_error.csv``,
    ``parts.csv``, ``heat.csv`` and ``summary.json``.

    Parameters
    ----------
    solution : Solution
        The run to write.
    out_dir : Path
        Created if missing; files of the same names in it are replaced, others are left alone.
    sample_interval : float
        Spacing of the CSV rows [s]; see :func:`sample_rows`.

    Returns
    -------
    list of Path
        The written files, inside ``out_dir``.
    """
    out_dir = Path(out_dir)
    with staged_directory(out_dir) as stage:
        names = write_tables(solution, stage, sample_interval=sample_interval)
    return [out_dir / name for name in names]


def write_run(solution: Solution, out_dir: Path, *, sample_interval: float, figures: bool = True) -> list[Path]:
    """Tables, plots and (FE runs) fields of a run in one set: all files appear in ``out_dir``, or none.

    The set replaces every file of an earlier run in ``out_dir`` (:data:`RUN_FILES`), also
    those this run does not write, such as the fields of an earlier FE run or its extra
    snapshots; other files in ``out_dir`` are kept.  ``figures=False`` leaves out the plots
    and field images (about 2 s of drawing), for scripts that run many runs.
    """
    out_dir = Path(out_dir)
    with staged_directory(out_dir, replaces=RUN_FILES) as stage:
        names = write_tables(solution, stage, sample_interval=sample_interval)
        if figures:
            names += draw_run_plots(solution, stage)
        names += write_field_outputs(solution, stage, images=figures)
    return [out_dir / name for name in names]


def write_field_outputs(solution: Solution, directory: Path, *, images: bool = True) -> list[str]:
    """fields.pvd, its .vtu snapshots and (``images``) the field images of a run with fields (nothing otherwise).

    The screw's axial deformation image needs the series' displacements and the screw's part
    name, ``solution.info["screw_part"]`` (:data:`SCREW_PART_KEY`); without either it is left out.
    """
    series = solution.fields
    if series is None:
        return []
    paths = write_pvd(series, directory)
    if images:
        paths += write_field_images(series, directory, screw_part=solution.info.get(SCREW_PART_KEY))
    return [Path(p).name for p in paths]


def write_tables(solution: Solution, directory: Path, *, sample_interval: float) -> list[str]:
    """Write the CSV and JSON files straight into ``directory`` (no staging); return their names."""
    rows = sample_rows(solution.times, sample_interval)
    write_sensors_csv(solution, directory / SENSORS_CSV, rows)
    names = [SENSORS_CSV]
    if solution.screw_x.size:  # a system without a feed drive has no screw and no stroke
        write_screw_csv(solution.times[rows], solution.screw_x, solution.screw_temperature[rows] - KELVIN_OFFSET,
                        directory / SCREW_CSV)
        write_screw_csv(solution.times[rows], solution.screw_x, solution.screw_displacement[rows] * 1e6,
                        directory / SCREW_DISPLACEMENT_CSV)
        # the same wide layout: its columns are table positions, the nut's centre on the same x axis
        write_screw_csv(solution.times[rows], solution.table_x, solution.positioning_error[rows] * 1e6,
                        directory / POSITIONING_ERROR_CSV)
        names += [SCREW_CSV, SCREW_DISPLACEMENT_CSV, POSITIONING_ERROR_CSV]
    if solution.ledger is not None:
        write_parts_csv(solution, directory / PARTS_CSV, rows)
        write_heat_csv(solution, directory / HEAT_CSV, rows)
        names += [PARTS_CSV, HEAT_CSV]
    write_summary_json(solution, directory / SUMMARY_JSON)
    return [*names, SUMMARY_JSON]


# --------------------------------------------------------------------------- rows


def sample_rows(times: np.ndarray, interval: float) -> np.ndarray:
    """Indices of the samples to write, about ``interval`` [s] apart.

    The first sample at or after each multiple of ``interval`` (counted from the first
    sample) and the last sample.  Values are never interpolated: a solution sampled at
    ``interval`` is written whole, a finer one is thinned, a coarser one is written whole.
    """
    if not (interval > 0 and math.isfinite(interval)):
        raise ValueError(f"sample interval must be a positive number of seconds, got {interval!r}")
    times = np.asarray(times, dtype=float)
    if times.size == 0:
        return np.arange(0)
    # The small allowance keeps 9.999999999 s in the 10 s bin (times summed from steps).
    bins = np.floor((times - times[0]) / interval + 1e-6)
    keep = np.ones(times.size, dtype=bool)
    keep[1:] = bins[1:] > bins[:-1]
    keep[-1] = True
    return np.flatnonzero(keep)


# --------------------------------------------------------------------------- CSV


def write_sensors_csv(solution: Solution, path: Path, rows: np.ndarray) -> None:
    """``time_s,<sensors>,<ambient>,D_um``: sensor temperatures [°C] and the elongation D [µm]."""
    names = ordered_sensor_names(solution)
    celsius = solution.sensors_celsius()
    columns = [solution.times[rows]] + [celsius[name][rows] for name in names] + [solution.elongation_um[rows]]
    header = ",".join(["time_s", *names, "D_um"])
    _write_csv(path, header, np.column_stack(columns))


def write_screw_csv(times: np.ndarray, positions: np.ndarray, values: np.ndarray, path: Path) -> None:
    """A field along x in the wide layout: one row per time, one column per axial position.

    Header ``time_s,x_mm=<x0>,x_mm=<x1>,…`` with the positions in mm (the description's
    axial coordinate: the screw's cell centres, or for ``positioning_error.csv`` the table
    positions); ``values`` has shape (times, positions) and is already in output units (°C for
    ``screw.csv``, µm for ``screw_displacement.csv`` and ``positioning_error.csv``).
    """
    columns = ",".join(f"x_mm={x * 1e3:.6g}" for x in positions)
    header = f"time_s,{columns}" if columns else "time_s"
    _write_csv(path, header, np.column_stack([times, values]))


def write_parts_csv(solution: Solution, path: Path, rows: np.ndarray) -> None:
    """``time_s,<parts>``: each part's capacity-weighted mean temperature [°C], every digit."""
    names = list(solution.part_temperatures)
    columns = [solution.times[rows]] + [solution.part_temperatures[p][rows] - KELVIN_OFFSET for p in names]
    _write_csv(path, ",".join(["time_s", *names]), np.column_stack(columns), exact=True)


def write_heat_csv(solution: Solution, path: Path, rows: np.ndarray) -> None:
    """``time_s,<sources>,lost``: each source's heat and the heat lost [W], every digit.

    Row i > 0 holds the mean over (t_{i−1}, t_i], the heat between the two rows over their time
    apart, so that ``Σ_i Q_i (t_i − t_{i−1})`` is the heat since the start; row 0 (t = 0) holds the
    first time step's heats.
    """
    ledger = solution.ledger
    times = solution.times[rows]
    energies = np.column_stack([*(ledger.heat_in[s][rows] for s in ledger.heat_in), ledger.heat_lost[rows]])
    first = np.array([*ledger.first_heat_in.values(), ledger.first_heat_lost])
    powers = np.vstack([first, np.diff(energies, axis=0) / np.diff(times)[:, None]])
    header = ",".join(["time_s", *ledger.heat_in, LOST_COLUMN])
    _write_csv(path, header, np.column_stack([times, powers]), exact=True)


def _write_csv(path: Path, header: str, table: np.ndarray, *, exact: bool = False) -> None:
    formats = [_EXACT_FORMAT] * table.shape[1] if exact else [_TIME_FORMAT] + [_VALUE_FORMAT] * (table.shape[1] - 1)
    with open(path, "w", encoding="utf-8", newline="") as handle:
        np.savetxt(handle, table, fmt=formats, delimiter=",", header=header, comments="")


# --------------------------------------------------------------------------- JSON


def run_summary(solution: Solution) -> dict:
    """The summary of a run in °C and µm, as plain JSON types (the content of ``summary.json``)."""
    info = solution.info
    final = _ordered_values(solution, solution.summary_values("final"))
    steady = _ordered_values(solution, solution.summary_values("steady"))
    start_um = float(solution.elongation_um[0])
    energy = solution.energy
    if not solution.info.get("constant_operating_point", True):
        # a cycle, its stops, a logged room: no steady state to approach, no equilibrium to reach
        return to_json_ready({**_common(solution, final, energy), "steady": None, "equilibrium_time_s": None,
                              "equilibrium_time_s_by_quantity": None, "profile": profile_summary(solution),
                              "elongation_change_um": {"final": final["D_um"] - start_um}})
    return to_json_ready({
        "condition": info.get("condition"),
        "model": info.get("model"),
        "mode": info.get("mode"),
        "single_drive": info.get("single_drive", False),  # ran as a single drive (declared, or the option)
        "declared_drive": info.get("declared_drive"),  # kinematics.drive of the description
        "single_drive_option": info.get("single_drive_option", False),  # --single-drive given
        "final": final,
        "steady": steady,
        "positioning_error": final_positioning_error(solution),
        "equilibrium_time_s": solution.equilibrium_time,
        "equilibrium_time_s_by_quantity": equilibrium_by_quantity(solution),
        "energy_balance_error": energy.relative_error,
        "energy_J": {"heat_in": energy.heat_in, "heat_lost": energy.heat_lost,
                     "heat_stored": energy.heat_stored, "residual": energy.residual},
        "ledger": ledger_summary(solution),
        "wall_time_s": info.get("wall_time_s"),
        "time_step_s": info.get("time_step_s"),
        "steps": info.get("steps"),
        "solver": info.get("solver"),
        "motion": info.get("motion"),
        "motion_windows": info.get("motion_windows"),  # the windowed motion's windows (models/windows.py)
        "unknowns": info.get("unknowns"),
        "elongation_change_um": {"final": final["D_um"] - start_um, "steady": steady["D_um"] - start_um},
        "warnings": info.get("warnings", []),  # e.g. correlations used outside their range
        "mesh": info.get("mesh_statistics"),  # FE runs: vertices, tetrahedra, per part, element size
        "provenance": info.get("provenance", {}),
    })


def _common(solution: Solution, final: dict, energy) -> dict:
    """What every summary holds (a run of a varying profile adds its ``profile`` block)."""
    info = solution.info
    return {
        "condition": info.get("condition"), "model": info.get("model"), "mode": info.get("mode"),
        "single_drive": info.get("single_drive", False), "declared_drive": info.get("declared_drive"),
        "single_drive_option": info.get("single_drive_option", False), "final": final,
        "positioning_error": final_positioning_error(solution),
        "energy_balance_error": energy.relative_error,
        "energy_J": {"heat_in": energy.heat_in, "heat_lost": energy.heat_lost,
                     "heat_stored": energy.heat_stored, "residual": energy.residual},
        "ledger": ledger_summary(solution), "wall_time_s": info.get("wall_time_s"),
        "time_step_s": info.get("time_step_s"), "steps": info.get("steps"), "solver": info.get("solver"),
        "motion": info.get("motion"), "motion_windows": info.get("motion_windows"),
        "unknowns": info.get("unknowns"), "warnings": info.get("warnings", []),
        "mesh": info.get("mesh_statistics"), "provenance": info.get("provenance", {}),
    }


def profile_summary(solution: Solution) -> dict:
    """What a run of a varying profile did, per sensor [°C] and D [µm]: its start, its end (the last
    sample), its range, and its largest and smallest value with when [s]."""
    series = {name: values for name, values in solution.sensors_celsius().items()}
    series["D_um"] = solution.elongation_um
    out = {}
    for name in [*ordered_sensor_names(solution), "D_um"]:
        if name not in series:
            continue
        values = np.asarray(series[name], dtype=float)
        hi, lo = int(np.argmax(values)), int(np.argmin(values))
        out[name] = {"start": float(values[0]), "end": float(values[-1]), "range": float(values[hi] - values[lo]),
                     "max": float(values[hi]), "max_at_s": float(solution.times[hi]),
                     "min": float(values[lo]), "min_at_s": float(solution.times[lo])}
    return out


def ledger_summary(solution: Solution) -> dict | None:
    """The ``ledger`` block of summary.json: the parts' heat capacities, and what parts.csv and heat.csv hold.

    None for a Solution without a :class:`~feedtherm.solution.Ledger`.
    """
    ledger = solution.ledger
    if ledger is None:
        return None
    return {
        "part_capacity_J_per_K": ledger.capacities,
        "files": {
            PARTS_CSV: {"columns": ["time_s", *solution.part_temperatures], "unit": "degC",
                        "rows": "the rows of sensors.csv",
                        "values": "each part's mean temperature, its nodes weighted by their heat capacity"},
            HEAT_CSV: {"columns": ["time_s", *ledger.heat_in, LOST_COLUMN], "unit": "W",
                       "rows": "the rows of sensors.csv",
                       "values": f"each source's heat, then {LOST_COLUMN}: the heat lost to the air and the surfaces' "
                                 "sinks; row i > 0 the mean over (t[i-1], t[i]], row 0 the first time step's"},
        },
        "heat_stored_J": "sum over parts of part_capacity_J_per_K * (T(t) - T(0)), T from parts.csv",
        "heat_in_J": "sum over rows i > 0 and sources of Q[i] * (t[i] - t[i-1]), Q from heat.csv",
        "heat_lost_J": f"sum over rows i > 0 of {LOST_COLUMN}[i] * (t[i] - t[i-1]), from heat.csv",
    }


def equilibrium_by_quantity(solution: Solution) -> dict[str, float | None]:
    """Each sensor's and D's own equilibrium time [s] (None: not within the run), sensors in
    output order, then ``D``; the ambient has none."""
    each = solution.equilibrium_times
    names = [name for name in ordered_sensor_names(solution) if name in each and name != solution.ambient_sensor]
    names.append(ELONGATION_PROBE)
    return {name: each.get(name) for name in names if name in each}


def final_positioning_error(solution: Solution) -> dict:
    """The positioning error at the end of the run: its largest magnitude over the stroke, and where.

    ``time_s`` the last sample, ``max_abs_um`` the largest |E| [µm] over the table positions,
    ``E_um`` the signed E there [µm] and ``table_x_mm`` that table position [mm].  The values
    of the last sample, not a cycle mean like ``final``: E is already resolved along the
    stroke.  All but ``time_s`` None for a run without table positions, or one whose E is
    not finite anywhere.
    """
    times = np.asarray(solution.times, dtype=float)
    x = np.asarray(solution.table_x, dtype=float)
    error = np.asarray(solution.positioning_error, dtype=float)
    empty = {"time_s": float(times[-1]) if times.size else None, "max_abs_um": None, "E_um": None,
             "table_x_mm": None}
    if x.size == 0 or error.size == 0 or not np.isfinite(error[-1]).any():
        return empty
    last = error[-1]
    peak = int(np.nanargmax(np.where(np.isfinite(last), np.abs(last), np.nan)))
    return {**empty, "max_abs_um": abs(float(last[peak])) * 1e6, "E_um": float(last[peak]) * 1e6,
            "table_x_mm": float(x[peak]) * 1e3}


def write_summary_json(solution: Solution, path: Path) -> None:
    write_json(path, run_summary(solution))


def _ordered_values(solution: Solution, values: dict[str, float]) -> dict[str, float]:
    """Sensors in output order (ambient last), then D_um; anything else after them."""
    order = [name for name in ordered_sensor_names(solution) if name in values] + ["D_um"]
    rest = [name for name in values if name not in order]
    return {name: values[name] for name in order + rest}


# --------------------------------------------------------------------------- the console line


def summary_line(solution: Solution, out_dir: Path) -> str:
    """One line: where the files are and the final values (°C, µm, energy balance)."""
    final = solution.summary_values("final")
    temperatures = ", ".join(f"{name} {final[name]:.2f} °C" for name in ordered_sensor_names(solution)
                             if name != solution.ambient_sensor and name in final)
    error_percent = 100.0 * solution.energy.relative_error
    return (f"{out_dir}: {temperatures}, D {final['D_um']:.2f} µm, "
            f"energy balance error {error_percent:.2g} %")


def equilibrium_line(solution: Solution) -> str | None:
    """One line: each sensor's and D's own equilibrium time, or that the run ended first (None
    for a Solution without them); for a run of a varying profile, the largest value of each and when."""
    if not solution.info.get("constant_operating_point", True):
        profile = profile_summary(solution)
        parts = [f"{name.removesuffix('_um')} {p['max']:.2f} {'µm' if name == 'D_um' else '°C'} at "
                 f"{p['max_at_s'] / 60.0:.0f} min" for name, p in profile.items() if name != solution.ambient_sensor]
        return "largest (a varying profile has no steady state): " + ", ".join(parts)
    each = equilibrium_by_quantity(solution)
    if not each:
        return None
    times = ", ".join(f"{name} {'not reached' if t is None else f'{t / 60.0:.0f} min'}" for name, t in each.items())
    return f"equilibrium (95 % of the steady rise, then steady; solution/equilibrium.py): {times}"


# --------------------------------------------------------------------------- where


def default_out_dir(system: str, run: str, mode_name: str) -> Path:
    """``out/<system>_<run>_<mode_name>`` with ``system`` a bundled name or a file's stem."""
    return Path("out") / "_".join(_safe_name(part) for part in (Path(system).stem, run, mode_name))


def _safe_name(text: str) -> str:
    # Duty-cycle names and CSV stems may hold spaces or separators; a directory name should not.
    return re.sub(r"[^A-Za-z0-9_.+-]+", "-", text).strip("-.") or "run"
