"""The files of ``feedtherm run``: sensor series, screw fields and a JSON summary.

Everything is read from a :class:`~feedtherm.solution.Solution` (SI inside); the kelvin →
°C and metre → µm conversions happen here, at the output edge.  The layout of every file is
documented in ``docs/outputs.md``.

The files of one call are written into a temporary directory beside the output directory
and moved into place only once all of them are complete, so an error (or Ctrl-C) never
leaves a half-written file or a partial set behind.
"""

from __future__ import annotations

import json
import math
import os
import re
import shutil
import uuid
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from ..errors import FeedthermError
from ..solution import KELVIN_OFFSET, SENSOR_NAMES_AMBIENT, Solution

SENSORS_CSV = "sensors.csv"
SCREW_CSV = "screw.csv"
SCREW_DISPLACEMENT_CSV = "screw_displacement.csv"
SUMMARY_JSON = "summary.json"

# Fixed decimals keep the columns readable; 1e-4 °C and 1e-4 µm are far below any
# measurement or model accuracy.
_TIME_FORMAT = "%.10g"
_VALUE_FORMAT = "%.4f"


def write_run_outputs(solution: Solution, out_dir: Path, *, sample_interval: float) -> list[Path]:
    """Write ``sensors.csv``, ``screw.csv``, ``screw_displacement.csv`` and ``summary.json``.

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


def write_run(solution: Solution, out_dir: Path, *, sample_interval: float) -> list[Path]:
    """Tables and plots of a run in one step: all files appear in ``out_dir``, or none."""
    from .plots import draw_run_plots  # plots import from this module

    out_dir = Path(out_dir)
    with staged_directory(out_dir) as stage:
        names = write_tables(solution, stage, sample_interval=sample_interval) + draw_run_plots(solution, stage)
        names += write_field_outputs(solution, stage)
    if solution.snapshots:
        _remove_stale_fields(out_dir, set(names))
    return [out_dir / name for name in names]


def field_series(solution: Solution):
    """The FE run's snapshots as a :class:`~feedtherm.outputs.fields.FieldSeries` (None for the fast model)."""
    from .fields import FieldSeries

    if not solution.snapshots or solution.mesh is None:
        return None
    mesh = solution.mesh
    times = np.array([t for t, _, _ in solution.snapshots])
    rows = [int(np.argmin(np.abs(solution.times - t))) for t in times]
    info = solution.info
    title = f"condition {info.get('condition')}, {info.get('mode')} mode, fem model ({info.get('mesh', '')} mesh)"
    return FieldSeries(
        points=np.asarray(mesh.points).T, tets=np.asarray(mesh.tets).T, part_id=np.asarray(mesh.part_id),
        part_names=mesh.part_names, moving_part=mesh.moving_part, snapshot_times=times,
        temperatures=np.array([state for _, state, _ in solution.snapshots]),
        offsets=np.array([offset for _, _, offset in solution.snapshots]),
        screw_x=solution.screw_x, screw_displacement=solution.screw_displacement[rows], title=title,
    )


def write_field_outputs(solution: Solution, directory: Path) -> list[str]:
    """fields.pvd, its .vtu snapshots and the two field images of an FE run (nothing otherwise)."""
    series = field_series(solution)
    if series is None:
        return []
    from .field_images import write_field_images
    from .fields import write_pvd

    paths = write_pvd(series, directory) + write_field_images(series, directory)
    return [Path(p).name for p in paths]


def _remove_stale_fields(out_dir: Path, keep: set[str]) -> None:
    """Snapshots of an earlier, longer run in the same directory would join ParaView's file series."""
    for path in Path(out_dir).glob("fields_*.vtu"):
        if path.name not in keep:
            path.unlink()


def write_tables(solution: Solution, directory: Path, *, sample_interval: float) -> list[str]:
    """Write the CSV and JSON files straight into ``directory`` (no staging); return their names."""
    rows = sample_rows(solution.times, sample_interval)
    write_sensors_csv(solution, directory / SENSORS_CSV, rows)
    write_screw_csv(solution.times[rows], solution.screw_x, solution.screw_temperature[rows] - KELVIN_OFFSET,
                    directory / SCREW_CSV)
    write_screw_csv(solution.times[rows], solution.screw_x, solution.screw_displacement[rows] * 1e6,
                    directory / SCREW_DISPLACEMENT_CSV)
    write_summary_json(solution, directory / SUMMARY_JSON)
    return [SENSORS_CSV, SCREW_CSV, SCREW_DISPLACEMENT_CSV, SUMMARY_JSON]


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


def ordered_sensor_names(solution: Solution) -> list[str]:
    """The sensors as the description declares them, with the ambient sensor last."""
    names = [name for name in solution.sensors if name != SENSOR_NAMES_AMBIENT]
    if SENSOR_NAMES_AMBIENT in solution.sensors:
        names.append(SENSOR_NAMES_AMBIENT)
    return names


# --------------------------------------------------------------------------- CSV


def write_sensors_csv(solution: Solution, path: Path, rows: np.ndarray) -> None:
    """``time_s,T1,…,T6,D_um``: sensor temperatures [°C] and the elongation D [µm]."""
    names = ordered_sensor_names(solution)
    celsius = solution.sensors_celsius()
    columns = [solution.times[rows]] + [celsius[name][rows] for name in names] + [solution.elongation_um[rows]]
    header = ",".join(["time_s", *names, "D_um"])
    _write_csv(path, header, np.column_stack(columns))


def write_screw_csv(times: np.ndarray, screw_x: np.ndarray, values: np.ndarray, path: Path) -> None:
    """A screw field in the wide layout: one row per time, one column per axial position.

    Header ``time_s,x_mm=<x0>,x_mm=<x1>,…`` with the cell centres in mm (the description's
    axial coordinate); ``values`` has shape (times, positions) and is already in output units
    (°C for ``screw.csv``, µm for ``screw_displacement.csv``).
    """
    positions = ",".join(f"x_mm={x * 1e3:.6g}" for x in screw_x)
    header = f"time_s,{positions}" if positions else "time_s"
    _write_csv(path, header, np.column_stack([times, values]))


def _write_csv(path: Path, header: str, table: np.ndarray) -> None:
    formats = [_TIME_FORMAT] + [_VALUE_FORMAT] * (table.shape[1] - 1)
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
    return _jsonable({
        "condition": info.get("condition"),
        "model": info.get("model"),
        "mode": info.get("mode"),
        "single_drive": info.get("single_drive", False),
        "final": final,
        "steady": steady,
        "equilibrium_time_s": solution.equilibrium_time,
        "energy_balance_error": energy.relative_error,
        "energy_J": {"heat_in": energy.heat_in, "heat_lost": energy.heat_lost,
                     "heat_stored": energy.heat_stored, "residual": energy.residual},
        "wall_time_s": info.get("wall_time_s"),
        "time_step_s": info.get("time_step_s"),
        "steps": info.get("steps"),
        "solver": info.get("solver"),
        "unknowns": info.get("unknowns"),
        "elongation_change_um": {"final": final["D_um"] - start_um, "steady": steady["D_um"] - start_um},
        "warnings": info.get("warnings", []),  # e.g. correlations used outside their range
        "mesh": info.get("mesh_statistics"),  # FE runs: vertices, tetrahedra, per part, element size
        "provenance": info.get("provenance", {}),
    })


def write_summary_json(solution: Solution, path: Path) -> None:
    text = json.dumps(run_summary(solution), indent=2, ensure_ascii=False, allow_nan=False)
    path.write_text(text + "\n", encoding="utf-8")


def _ordered_values(solution: Solution, values: dict[str, float]) -> dict[str, float]:
    """Sensors in output order (ambient last), then D_um; anything else after them."""
    order = [name for name in ordered_sensor_names(solution) if name in values] + ["D_um"]
    rest = [name for name in values if name not in order]
    return {name: values[name] for name in order + rest}


def _jsonable(value):
    """Plain JSON types: numpy scalars and arrays unwrapped, NaN/inf as null, paths as text."""
    if isinstance(value, dict):
        return {str(key): _jsonable(item) for key, item in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_jsonable(item) for item in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None  # JSON has no NaN; null is what a reader can parse
    if isinstance(value, Path):
        return str(value)
    return value


# --------------------------------------------------------------------------- the console line


def summary_line(solution: Solution, out_dir: Path) -> str:
    """One line: where the files are and the final values (°C, µm, energy balance)."""
    final = solution.summary_values("final")
    temperatures = ", ".join(f"{name} {final[name]:.2f} °C" for name in ordered_sensor_names(solution)
                             if name != SENSOR_NAMES_AMBIENT and name in final)
    error_percent = 100.0 * solution.energy.relative_error
    return (f"{out_dir}: {temperatures}, D {final['D_um']:.2f} µm, "
            f"energy balance error {error_percent:.2g} %")


# --------------------------------------------------------------------------- where


def default_out_dir(system: str, run: str, mode: str) -> Path:
    """``out/<system>_<run>_<mode>`` with ``system`` a bundled name or a file's stem."""
    return Path("out") / "_".join(_safe_name(part) for part in (Path(system).stem, run, mode))


def _safe_name(text: str) -> str:
    # Duty-cycle names and CSV stems may hold spaces or separators; a directory name should not.
    return re.sub(r"[^A-Za-z0-9_.+-]+", "-", text).strip("-.") or "run"


# --------------------------------------------------------------------------- atomic writes


def check_output_dir(out_dir: Path) -> None:
    """Fail now, before a long run, if ``out_dir`` cannot become a directory we write into."""
    out_dir = Path(out_dir)
    target = Path(os.path.abspath(out_dir))
    if target.exists() and not target.is_dir():
        raise FeedthermError(f"{out_dir}: exists and is not a directory")
    existing = _nearest_existing(target)
    if not existing.is_dir():
        raise FeedthermError(f"{out_dir}: {existing} is a file, not a directory")
    # Files are staged beside out_dir and then moved into it: both places must be writable.
    must_write = [target.parent, target] if existing == target else [existing]
    for directory in must_write:
        if not os.access(directory, os.W_OK | os.X_OK):
            raise FeedthermError(f"{out_dir}: no permission to write in {directory}")


@contextmanager
def staged_directory(out_dir: Path) -> Iterator[Path]:
    """Yield an empty directory beside ``out_dir``; on success move its files into ``out_dir``.

    A missing ``out_dir`` is created by renaming the staging directory (one atomic step); in
    an existing one each file is replaced with ``os.replace`` (atomic per file).  On any error
    the staging directory, and any parent directories made for it, are removed again.
    """
    out_dir = Path(out_dir)
    check_output_dir(out_dir)
    made = _make_parents(out_dir.parent)
    stage = out_dir.parent / f".{out_dir.name}.partial-{uuid.uuid4().hex[:12]}"
    try:
        stage.mkdir()
        yield stage
        _move_into_place(stage, out_dir)
    except BaseException as exc:
        shutil.rmtree(stage, ignore_errors=True)
        _remove_if_empty(made)
        if isinstance(exc, OSError):
            raise FeedthermError(f"{out_dir}: cannot write the outputs ({exc.strerror or exc})") from None
        raise


def _move_into_place(stage: Path, out_dir: Path) -> None:
    if not out_dir.exists():
        try:
            stage.rename(out_dir)
            return
        except OSError:
            pass  # created meanwhile by someone else: move file by file below
    out_dir.mkdir(exist_ok=True)
    for path in sorted(stage.iterdir()):
        os.replace(path, out_dir / path.name)
    stage.rmdir()


def _nearest_existing(path: Path) -> Path:
    while not path.exists():
        path = path.parent
    return path


def _make_parents(directory: Path) -> list[Path]:
    """Create ``directory`` and its missing parents; return the ones made, deepest first."""
    missing = []
    current = Path(directory)
    while not current.exists():
        missing.append(current)
        current = current.parent
    for path in reversed(missing):
        path.mkdir()
    return missing


def _remove_if_empty(directories: list[Path]) -> None:
    for path in directories:  # deepest first
        try:
            path.rmdir()
        except OSError:
            return
