"""Parameter sweeps: the full grid of screw speeds × nut speeds × ambient temperatures.

Two steps, both without printing:

- :func:`parse_grid` reads the three lists as a user types them (``300:2400:300``,
  ``1116,2214``, ``20``) and checks them strictly, before anything is simulated;
- :func:`run_sweep` makes every grid point a constant condition of the description
  (:func:`~feedtherm.system.variants.with_condition`), simulates it and returns one row
  per point: the inputs, the table speed, the final and steady sensor temperatures [°C]
  and elongation D [µm], the equilibrium time and the energy-balance error.

The CSV and the plots of a sweep are written by :mod:`feedtherm.outputs.sweep_files`.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import re
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from decimal import Decimal, InvalidOperation

from ..boundary import boundary_conditions
from ..boundary.heat import motor_duties
from ..errors import FeedthermError
from ..constants import KELVIN_OFFSET
from ..system.load import LoadedSystem
from ..system.overlay import mode_of
from ..system.variants import with_condition
from .execution import Execution, TaskFailure, run_ordered

#: A sweep runs at most this many grid points (a typo such as ``0:3000:1`` should not start 3000 runs).
MAX_POINTS = 500
#: The swept variables: CSV column -> command-line option.
OPTIONS = {"screw_rpm": "--screw-rpm", "nut_rpm": "--nut-rpm", "ambient_C": "--ambient"}
#: The name under which each grid point is added to the description's conditions.
CONDITION_NAME = "sweep"

# A plain decimal number: no nan/inf, no underscores, no hex (float() would take all three).
_NUMBER = re.compile(r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?")


@dataclass(frozen=True)
class SweepGrid:
    """The values of each swept variable, in the order given; the grid is their full product."""

    screw_rpm: tuple[float, ...]
    nut_rpm: tuple[float, ...]
    ambient_C: tuple[float, ...]

    @property
    def axes(self) -> dict[str, tuple[float, ...]]:
        """CSV column -> values, in the order of the CSV columns."""
        return {"screw_rpm": self.screw_rpm, "nut_rpm": self.nut_rpm, "ambient_C": self.ambient_C}

    @property
    def varied(self) -> list[str]:
        """The variables with more than one value."""
        return [name for name, values in self.axes.items() if len(values) > 1]

    @property
    def shape(self) -> tuple[int, int, int]:
        return len(self.screw_rpm), len(self.nut_rpm), len(self.ambient_C)

    def __len__(self) -> int:
        return math.prod(self.shape)

    def points(self) -> list[tuple[float, float, float]]:
        """``(screw_rpm, nut_rpm, ambient_C)`` of every point; the ambient varies fastest."""
        return list(itertools.product(self.screw_rpm, self.nut_rpm, self.ambient_C))


# --------------------------------------------------------------------------- parsing


def parse_values(text: str, option: str) -> tuple[float, ...]:
    """The numbers of one list: comma-separated values and/or ranges ``start:stop:step``.

    A range runs from ``start`` up to ``stop`` in steps of ``step`` (> 0), and includes
    ``stop`` when it falls on the grid: ``300:1200:300`` is 300, 600, 900, 1200 and
    ``0:1000:300`` is 0, 300, 600, 900.  The arithmetic is decimal, so ``0:1:0.1`` gives
    exactly 0, 0.1, …, 1.  Values keep the order they are written in; a value listed twice
    is an error.

    Raises
    ------
    FeedthermError
        One line naming ``option``: bad syntax, a step that is not positive, a range or a
        list without values, a repeated value, or more than :data:`MAX_POINTS` values.
    """
    if not text.strip():
        raise FeedthermError(f"{option}: empty list; give values such as 300,600 or a range such as 300:2400:300")
    values: list[float] = []
    for item in text.split(","):
        item = item.strip()
        if not item:
            raise FeedthermError(f"{option}: empty item in {text!r} (two commas, or a comma at an end)")
        if ":" in item:
            values.extend(_range(item, option))
        else:
            values.append(float(_decimal(item, item, option)))
        if len(values) > MAX_POINTS:
            raise FeedthermError(f"{option}: more than {MAX_POINTS} values in {text!r}; "
                                 f"a sweep runs at most {MAX_POINTS} points")
    seen: set[float] = set()
    for value in values:
        if value in seen:
            raise FeedthermError(f"{option}: {_fmt(value)} is listed twice in {text!r}")
        seen.add(value)
    return tuple(values)


def _range(item: str, option: str) -> list[float]:
    parts = item.split(":")
    if len(parts) != 3:
        raise FeedthermError(f"{option}: range {item!r} must be start:stop:step, e.g. 300:2400:300")
    start, stop, step = (_decimal(part.strip(), item, option) for part in parts)
    if step <= 0:
        raise FeedthermError(f"{option}: range {item!r} has step {_fmt(float(step))}; the step must be positive")
    if stop < start:
        raise FeedthermError(f"{option}: range {item!r} is empty (stop {_fmt(float(stop))} is below start "
                             f"{_fmt(float(start))}; ranges run upwards)")
    try:
        count = int((stop - start) // step) + 1
    except InvalidOperation:  # a quotient beyond decimal precision: far too many values anyway
        count = None
    if count is None or count > MAX_POINTS:
        many = f"{count}" if count is not None else "too many"
        raise FeedthermError(f"{option}: range {item!r} gives {many} values; a sweep runs at most {MAX_POINTS} points")
    return [float(start + i * step) for i in range(count)]


def _decimal(text: str, item: str, option: str) -> Decimal:
    if not _NUMBER.fullmatch(text):
        where = "" if text == item else f" in {item!r}"
        raise FeedthermError(f"{option}: {text!r}{where} is not a number")
    try:
        value = Decimal(text)
    except InvalidOperation:  # pragma: no cover - the pattern admits only valid decimals
        raise FeedthermError(f"{option}: {text!r} is not a number") from None
    if not math.isfinite(float(value)):
        raise FeedthermError(f"{option}: {text!r} is out of range")
    return value


def parse_grid(screw_rpm: str, nut_rpm: str, ambient_c: str, *, drive: str = "dual") -> SweepGrid:
    """The grid of the three lists, checked: temperatures above absolute zero, a single
    drive's nut at rest, and at most :data:`MAX_POINTS` points in all.

    ``drive`` is the description's ``kinematics.drive``.
    """
    grid = SweepGrid(parse_values(screw_rpm, OPTIONS["screw_rpm"]), parse_values(nut_rpm, OPTIONS["nut_rpm"]),
                     parse_values(ambient_c, OPTIONS["ambient_C"]))
    too_cold = [value for value in grid.ambient_C if not value > -KELVIN_OFFSET]
    if too_cold:
        raise FeedthermError(f"--ambient: {_fmt(too_cold[0])} °C is not above absolute zero (-273.15 °C)")
    if drive == "single" and grid.nut_rpm != (0.0,):
        raise FeedthermError(f"--nut-rpm: a single drive (kinematics.drive = \"single\") has no nut motor; "
                             f"give --nut-rpm 0, got {','.join(_fmt(v) for v in grid.nut_rpm)}")
    if len(grid) > MAX_POINTS:
        a, b, c = grid.shape
        raise FeedthermError(f"the grid has {len(grid)} points ({a} screw × {b} nut × {c} ambient); "
                             f"a sweep runs at most {MAX_POINTS}")
    return grid


def _fmt(value: float) -> str:
    return f"{value:g}"


# --------------------------------------------------------------------------- running


def sensor_labels(loaded: LoadedSystem) -> dict[str, str]:
    """The description's sensors in order (without the ambient) -> a short label.

    The label is the part of the sensor's description before its first colon
    (``"front bearing"``), or the sensor's part name.
    """
    out = {}
    for name, sensor in loaded.system.sensors.items():
        if name == loaded.system.room.ambient_sensor:
            continue
        out[name] = sensor.description.split(":")[0].strip() or sensor.part
    return out


def columns(sensors: list[str]) -> list[str]:
    """The columns of a sweep row, in CSV order."""
    return [*OPTIONS, "table_speed_m_per_min",
            *(f"final_{name}" for name in sensors), "final_D_um",
            *(f"steady_{name}" for name in sensors), "steady_D_um",
            "equilibrium_time_s", "energy_balance_error", "motor_duty"]


def run_sweep(loaded: LoadedSystem, grid: SweepGrid, *, duration: float | None = None,
              motion: str = "averaged", progress: Callable[[float], None] | None = None,
              execution: Execution = Execution(), known: Mapping[int, dict] | None = None,
              on_row: Callable[[int, dict], None] | None = None) -> list[dict]:
    """Simulate every point of ``grid`` as a constant condition; one row dict per point.

    Parameters
    ----------
    loaded : LoadedSystem
        With the overlay its runs take (:func:`feedtherm.plan.with_mode`).
    grid : SweepGrid
        From :func:`parse_grid`.
    duration : float, optional
        Length of every run [s]; default: a condition's default duration.
    motion : {"resolved", "averaged"}
        See :func:`~feedtherm.simulate.simulate`; averaged is much faster for long sweeps.
    progress : callable, optional
        Called with the fraction of the whole sweep done (0–1), the known points counted as done.
    execution : Execution, optional
        Where the runs go (:mod:`.execution`); serial by default.  The rows are the same.
    known : mapping, optional
        Rows already computed (an interrupted sweep's, see :func:`point_key`), by the point's
        index in :meth:`SweepGrid.points`: those points are not run again.
    on_row : callable, optional
        ``on_row(index, row)`` as soon as each point that runs has finished (in the order they
        finish): where a caller keeps it on disk.  Not called for failed points.

    Returns
    -------
    list of dict
        Keyed by :func:`columns`, in the order of :meth:`SweepGrid.points`: speeds [rpm],
        ambient [°C], table speed [m/min] (signed, ``(n_screw − n_nut) · lead``), final and
        steady temperatures [°C] and D [µm], equilibrium time [s] (None if not reached), the
        relative energy-balance error and the motor duty: the largest torque over continuous
        torque of the motors that declare one (None if none does; above 1 the point is a machine
        its motors cannot run, computed as declared all the same).

    Raises
    ------
    SweepFailed
        When some points failed: it carries the rows of the others (in grid order) and one
        :class:`~feedtherm.analysis.execution.TaskFailure` per failed point.
    """
    sensors = list(sensor_labels(loaded))
    lead = loaded.system.kinematics.lead
    points = grid.points()
    known = dict(known or {})
    # Every condition is built (and so validated) before the first run.
    variants = [with_condition(loaded, CONDITION_NAME, screw, nut, ambient, duration) for screw, nut, ambient in points]
    todo = [index for index in range(len(points)) if index not in known]
    duties = {index: largest_motor_duty(variants[index]) for index in todo}  # known rows carry theirs
    runs = [SweepRun(variants[index], {"condition": CONDITION_NAME, "duration": duration,
                                       "motion": motion}, label=point_label(*points[index]))
            for index in todo]

    def done(position: int, solution) -> None:
        if on_row is not None and not isinstance(solution, TaskFailure):
            on_row(todo[position], _row(points[todo[position]], solution, sensors, lead, duties[todo[position]]))

    results = dict(known)
    failures = []
    share = None if progress is None else _remaining_share(progress, len(known), len(points))
    for index, solution in zip(todo, run_batch(runs, share, execution, on_done=done)):
        if isinstance(solution, TaskFailure):
            failures.append(solution)
        else:
            results[index] = _row(points[index], solution, sensors, lead, duties[index])
    rows = [results[index] for index in range(len(points)) if index in results]
    if failures:
        raise SweepFailed(rows, failures, len(points))
    return rows


def _remaining_share(progress: Callable[[float], None], known: int, total: int) -> Callable[[float], None]:
    """The progress of the points still to run as a fraction of the whole sweep."""
    progress(known / total)
    return lambda fraction: progress((known + fraction * (total - known)) / total)


def largest_motor_duty(loaded: LoadedSystem) -> float | None:
    """The largest torque over continuous torque of the motors of the sweep's condition (None: no
    motor declares a continuous torque, or an overlay, whose printed heats carry no torques)."""
    if loaded.overlay is not None:
        return None
    ratios = motor_duties(boundary_conditions(loaded.system, CONDITION_NAME).heats)
    return max(ratios.values()) if ratios else None


def _row(point: tuple[float, float, float], solution, sensors: list[str], lead: float,
         duty: float | None = None) -> dict:
    """One point's row (see :func:`run_sweep`) from its solution."""
    screw, nut, ambient = point
    final, steady = solution.summary_values("final"), solution.summary_values("steady")
    row = {"screw_rpm": screw, "nut_rpm": nut, "ambient_C": ambient, "table_speed_m_per_min": (screw - nut) * lead}
    row.update({f"final_{name}": float(final[name]) for name in sensors})
    row["final_D_um"] = float(final["D_um"])
    row.update({f"steady_{name}": float(steady[name]) for name in sensors})
    row["steady_D_um"] = float(steady["D_um"])
    row["equilibrium_time_s"] = None if solution.equilibrium_time is None else float(solution.equilibrium_time)
    row["energy_balance_error"] = float(solution.energy.relative_error)
    row["motor_duty"] = duty
    return row


def sweep_settings(loaded: LoadedSystem, *, duration: float | None, motion: str) -> dict:
    """What every point of a sweep shares: the description (by its digest), mode, duration, motion
    and the feedtherm version that computes it (plain JSON types)."""
    from .. import __version__

    return {"feedtherm": __version__, "description": loaded.origin, "description_sha256": loaded.sha256,
            "mode": mode_of(loaded), "duration_s": duration, "motion": motion}


def point_key(settings: dict, point: tuple[float, float, float]) -> str:
    """A digest of one point's full inputs: :func:`sweep_settings` and its speeds and ambient.

    A row kept under this key is the row the same point of the same sweep would give; a point of
    a sweep with another description, mode, duration, motion or feedtherm version has another
    key.  The description's origin (its path) is left out: the same description moved is the
    same description.
    """
    inputs = {key: value for key, value in settings.items() if key != "description"}
    inputs["point"] = [float(value) for value in point]
    text = json.dumps(inputs, sort_keys=True, allow_nan=False)
    return hashlib.sha256(text.encode()).hexdigest()


def point_label(screw: float, nut: float, ambient: float) -> str:
    """A grid point in words, as a failure names it."""
    return f"point screw {_fmt(screw)} rpm, nut {_fmt(nut)} rpm, ambient {_fmt(ambient)} °C"


class SweepFailed(FeedthermError):
    """Some points of a sweep failed; ``rows`` holds the others' rows, ``failures`` one entry per failed point."""

    def __init__(self, rows: list[dict], failures: list[TaskFailure], total: int):
        super().__init__(f"{len(failures)} of {total} sweep points failed; the first: {failures[0]}")
        self.rows, self.failures, self.total = rows, failures, total


@dataclass(frozen=True)
class SweepRun:
    """One run of a batch: a description, the keyword arguments of :func:`~feedtherm.simulate.simulate`
    and what the run is, in words (named when the run fails)."""

    loaded: LoadedSystem
    arguments: dict
    label: str = ""

    def describe(self) -> str:
        return self.label or self.loaded.origin


def run_batch(runs: list[SweepRun], progress: Callable[[float], None] | None = None,
              execution: Execution = Execution(), *,
              on_done: Callable[[int, object], None] | None = None) -> Iterator:
    """Simulate every run; yield its :class:`~feedtherm.solution.Solution`, in the order of ``runs``.

    The one loop of every batch of runs (the sweep's grid, the training and held-out cycles of a
    compensation study).  ``execution`` says where the runs go (:mod:`.execution`: serial by
    default, or on a Dask cluster); the results and their order are the same either way.  A run
    that fails yields a :class:`~feedtherm.analysis.execution.TaskFailure` naming the run in its
    place, and the other runs go on.  ``progress`` gets the fraction of the whole batch done (0-1).
    ``on_done(index, result)`` as soon as each run finishes (see
    :func:`~feedtherm.analysis.execution.run_ordered`).
    """
    for _, result in run_ordered(_simulate, runs, execution=execution, describe=SweepRun.describe,
                                 progress=progress, passes_progress=True, on_done=on_done):
        yield result


def _simulate(run: SweepRun, progress: Callable[[float], None] | None = None):
    """One run of a batch, wherever it executes (a worker imports this by name)."""
    from ..simulate import simulate  # the model is loaded only when a batch really runs

    # A grid or a random cycle may reach speeds where a motor needs more than its continuous torque;
    # a batch runs every point as declared (sweep.csv's motor_duty names such points).
    return simulate(run.loaded, progress=progress, allow_overload=True, **run.arguments)
