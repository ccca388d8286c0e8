"""Measured values to compare with (validation) or to fit to (calibration).

Two layouts, told apart by the header. Finals, one row per condition and quantity::

    condition,quantity,unit,measured[,reference_simulated]
    run1,front_bearing,C,27.1,28.1
    run1,D_um,um,29.9,32.8

``quantity`` is a sensor name (unit ``C``) or ``D_um`` (unit ``um``); the optional last
column holds another model's simulated value (for the paper's bench: its ANSYS results).
A description names its measurements in ``meta.measurements``: ``bundled:<bench>`` for the
measurements file of a bench (feedtherm.benches), or a path relative to the description file
(for a bench's description: relative to its folder). A description loaded from a bench that
names none is compared with the bench's own measurements file.

Time series, one row per sample (:mod:`~feedtherm.system.measurement_series`)::

    condition,time [min],quantity,value,unit[,uncertainty]
    v10,0,front_bearing,20.0,degC,0.2
    v10,10,D,41.5,um,1.0

A series becomes one :class:`Measurement` whose ``measured`` is its last sample (so every
reader of finals works on it unchanged) and whose ``series`` holds all of them. ``D`` is read
as ``D_um`` in µm, every temperature in °C. In either layout, blank lines and lines starting
with ``#`` (comments: where the data come from) are skipped.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Collection, Mapping

from ..benches import MEASUREMENTS, ORIGIN_PREFIX, bench, bench_name_of
from ..errors import DescriptionError
from .files import MAX_DATA_BYTES, read_text_file
from .measurement_series import (
    ELONGATION_QUANTITY,
    RUN_COLUMNS,
    SERIES_HEADER,
    Series,
    check_value_range,
    is_series_header,
    parse_series,
)

HEADER = ["condition", "quantity", "unit", "measured"]
OPTIONAL = "reference_simulated"
# ELONGATION_QUANTITY ("D_um"): the screw elongation; every other quantity is a temperature.
UNITS = {ELONGATION_QUANTITY: "um"}  # every other quantity is a temperature in C


@dataclass(frozen=True)
class Measurement:
    condition: str  # the run: a test or a condition
    quantity: str
    unit: str
    measured: float  # a series' last sample
    reference_simulated: float | None = None
    series: Series | None = None  # all samples, where the file is a time series
    target: float | None = None  # the positioning deviation's target position [m]
    since: float | None = None  # a drift's origin [s]: the series is the change since then (ISO 230-3)


@dataclass(frozen=True)
class MeasurementSet:
    """A measurement file's contents.

    ``rows``: the sensors' temperatures and D, finals or series, what every reader of finals
    takes; ``positioning``: the positioning deviations E at target positions (series, in µm, each
    ``target`` set); ``air``: the room's measured air temperature [°C] per run (series).
    """

    rows: list[Measurement]
    source: str
    equilibrium_min: dict[str, float]  # condition -> stated equilibrium time, where known
    positioning: list[Measurement] = field(default_factory=list)
    air: dict[str, Series] = field(default_factory=dict)

    def runs(self) -> list[str]:
        """Every run the file measures anything of, in the file's order."""
        return list(dict.fromkeys([*(r.condition for r in self.rows), *(r.condition for r in self.positioning),
                                   *self.air]))

    def positioning_of(self, run: str) -> list[Measurement]:
        """The positioning deviations measured in ``run``, by target."""
        return sorted((r for r in self.positioning if r.condition == run), key=lambda r: r.target)

    def conditions(self) -> list[str]:
        return list(dict.fromkeys(r.condition for r in self.rows))

    def for_condition(self, condition: str) -> list[Measurement]:
        return [r for r in self.rows if r.condition == condition]

    def has_series(self) -> bool:
        """True when the file gave time series (not only final values)."""
        return any(r.series is not None for r in self.rows)


def measurement_spec(measured: str | None, declared: str, origin: str) -> str:
    """Which measurements to read: the file given, else the description's ``meta.measurements``,
    else, for a description loaded from a bench, that bench's own measurements file."""
    if measured or declared:
        return measured or declared
    name = bench_name_of(origin)
    if name is None:
        raise DescriptionError(f"{origin} names no measurements (meta.measurements); pass --measured FILE")
    if bench(name).measurements is None:
        raise DescriptionError(f"{origin}: bench {name!r} has no measurements (no {MEASUREMENTS} in its folder, "
                               f"no meta.measurements); pass --measured FILE")
    return f"{ORIGIN_PREFIX}{name}"


def _from_bench(name: str) -> tuple[str, str, str | None]:
    found = bench(name)
    source = f"{ORIGIN_PREFIX}{name}"
    if found.measurements is None:
        raise DescriptionError(f"{source}: bench {name!r} has no {MEASUREMENTS} in {found.folder}")
    eq = found.equilibrium_times
    eq_text = read_text_file(eq, str(eq), MAX_DATA_BYTES, "measurement") if eq else None
    return read_text_file(found.measurements, source, MAX_DATA_BYTES, "measurement"), source, eq_text


def read_measurements(spec: str, relative_to: str | None = None, sensors: list[str] | None = None, *,
                      conditions: Collection[str] | None = None,
                      run_end: Mapping[str, float] | None = None, air: str | None = None,
                      travel: tuple[float, float] | None = None,
                      visits: Mapping[str, Collection[float]] | None = None) -> MeasurementSet:
    """Read a measurement file (path or ``bundled:<bench>``); one-line errors naming the line.

    ``relative_to`` is the origin of the description that names ``spec``: a relative path is
    read beside that file, or in that bench's folder. ``sensors`` and ``conditions`` are the
    description's (its runs: tests and conditions): a row naming another is an error. ``run_end``
    (run → the end of its simulated run [s]) rejects samples of a series after it; ``air``,
    ``travel`` and ``visits`` are those of :func:`~.measurement_series.parse_series`.
    """
    if spec.startswith(ORIGIN_PREFIX):
        text, source, eq_text = _from_bench(spec[len(ORIGIN_PREFIX):])
    else:
        path = Path(spec)
        if relative_to and not path.is_absolute():
            name = bench_name_of(relative_to)
            path = (bench(name).folder if name else Path(relative_to).parent) / path
        if not path.exists():
            raise DescriptionError(f"{path}: no such measurement file")
        text, source, eq_text = read_text_file(path, str(path), MAX_DATA_BYTES, "measurement"), str(path), None
    key = (text, source, eq_text, _frozen(sensors), _frozen(conditions), _frozen(run_end), air, _frozen(travel),
           _frozen(visits))
    if key not in _PARSED:
        if len(_PARSED) >= PARSED_KEPT:
            del _PARSED[next(iter(_PARSED))]  # the oldest
        _PARSED[key] = _parse_text(text, source, eq_text, sensors, conditions, run_end, air, travel, visits)
    return _copy(_PARSED[key])


#: Files parsed, by their text and the description's names they were checked against: a batch's runs
#: of measured tests (a calibration's dozens, a compensation's drift tests) each read the file of
#: their room's air or start, and parsing a long series file again took 0.15 s a run.
_PARSED: dict[tuple, MeasurementSet] = {}
#: How many parsed files :data:`_PARSED` keeps (the oldest goes first).
PARSED_KEPT = 8


def _frozen(value):
    """``value`` as a hashable key: a mapping's items and a collection's members in their order."""
    if value is None or isinstance(value, (str, float, int)):
        return value
    if isinstance(value, Mapping):
        return tuple((k, _frozen(v)) for k, v in value.items())
    return tuple(_frozen(v) for v in value)


def _copy(data: MeasurementSet) -> MeasurementSet:
    """A set of its own for each reader: its lists, its dicts and its series' arrays copied."""
    def row(r: Measurement) -> Measurement:
        return r if r.series is None else replace(r, series=_series_copy(r.series))

    return MeasurementSet([row(r) for r in data.rows], data.source, dict(data.equilibrium_min),
                          [row(r) for r in data.positioning],
                          {name: _series_copy(s) for name, s in data.air.items()})


def _series_copy(series: Series) -> Series:
    return Series(series.times.copy(), series.values.copy(),
                  None if series.uncertainties is None else series.uncertainties.copy())


def _parse_text(text: str, source: str, eq_text: str | None, sensors, conditions, run_end, air, travel,
                visits) -> MeasurementSet:
    """The :class:`MeasurementSet` of a measurement file's ``text`` (see :func:`read_measurements`)."""
    lines = _lines(text)
    if not lines:
        raise DescriptionError(f"{source}: the file is empty; expected the header {','.join(HEADER)}")
    equilibrium = _parse_equilibrium(eq_text) if eq_text else {}
    if not is_series_header([c.strip() for c in lines[0][1]]):
        return MeasurementSet(_parse(lines, source, sensors, conditions), source, equilibrium)
    rows, positioning, air_series = [], [], {}
    for s in parse_series(lines, source, sensors=sensors, conditions=conditions, run_end=run_end, air=air,
                          travel=travel, visits=visits):
        row = Measurement(s.condition, s.quantity, s.unit, float(s.series.values[-1]), None, s.series, s.target)
        if s.target is not None:
            positioning.append(row)
        elif air is not None and s.quantity == air:
            air_series[s.condition] = s.series
        else:
            rows.append(row)
    return MeasurementSet(rows, source, equilibrium, positioning, air_series)


def _lines(text: str) -> list[tuple[int, list[str]]]:
    """The rows of a CSV text with their line numbers, without blank lines and ``#`` comment lines."""
    reader = csv.reader(text.splitlines())
    return [(reader.line_num, row) for row in reader
            if any(c.strip() for c in row) and not row[0].lstrip().startswith("#")]


def _parse(lines: list[tuple[int, list[str]]], source: str, sensors: list[str] | None,
           conditions: Collection[str] | None) -> list[Measurement]:
    header = [c.strip() for c in lines[0][1]]
    if header[:1] and header[0] in RUN_COLUMNS:
        header = ["condition", *header[1:]]
    if header not in (HEADER, [*HEADER, OPTIONAL]):
        raise DescriptionError(f"{source}: line {lines[0][0]}: header must be {','.join(HEADER)}[,{OPTIONAL}] "
                               f"(final values) or {SERIES_HEADER} (time series), got {','.join(header)}")
    rows, seen = [], set()
    for number, row in lines[1:]:
        if len(row) != len(header):
            raise DescriptionError(f"{source}: line {number}: expected {len(header)} values, got {len(row)}")
        condition, quantity, unit = (c.strip() for c in row[:3])
        if conditions is not None and condition not in conditions:
            raise DescriptionError(f"{source}: line {number}: unknown test {condition!r}; expected one of "
                                   f"{', '.join(conditions)}")
        expected_unit = UNITS.get(quantity, "C")
        if sensors is not None and quantity not in sensors and quantity not in UNITS:
            raise DescriptionError(f"{source}: line {number}: unknown quantity {quantity!r}; expected one of {', '.join([*sensors, *UNITS])}")
        if unit != expected_unit:
            raise DescriptionError(f"{source}: line {number}: {quantity} must be in {expected_unit}, got {unit!r}")
        try:
            values = [float(c) if c.strip() else None for c in row[3:]]
        except ValueError:
            raise DescriptionError(f"{source}: line {number}: values must be numbers, got {','.join(row[3:])}") from None
        if values[0] is None or not all(v is None or math.isfinite(v) for v in values):
            raise DescriptionError(f"{source}: line {number}: the measured value must be a finite number")
        for text, value in zip(row[3:], values):
            if value is not None:
                check_value_range("length" if quantity in UNITS else "temperature", value, f"{text.strip()} {unit}",
                                  f"{source}: line {number}")
        if (condition, quantity) in seen:
            raise DescriptionError(f"{source}: line {number}: {condition} {quantity} appears twice")
        seen.add((condition, quantity))
        rows.append(Measurement(condition, quantity, unit, values[0], values[1] if len(values) > 1 else None))
    if not rows:
        raise DescriptionError(f"{source}: no rows after the header")
    return rows


def _parse_equilibrium(text: str) -> dict[str, float]:
    return {row["condition"]: float(row["equilibrium_min"]) for row in csv.DictReader(text.splitlines())}


def read_description_measurements(system, spec: str, relative_to: str | None) -> MeasurementSet:
    """Read ``spec`` against the description ``system`` (a FeedSystem): its sensors, the room's air, its
    runs (tests and conditions) and their durations, the table's travel and each test's targets."""
    from .geometry import table_travel
    from .runs import run_durations, visited_targets

    durations = run_durations(system)
    return read_measurements(spec, relative_to=relative_to, sensors=list(system.sensors), conditions=list(durations),
                             run_end=durations, air=system.room.ambient_sensor,
                             travel=None if system.kinematics is None else table_travel(system),
                             visits={name: visited_targets(system, name) for name in durations})


def declared_measurements(system, origin: str) -> MeasurementSet:
    """Everything a description's measurements hold: its own file (``meta.measurements``, else its
    bench's, where either exists) and each test's own file (``tests.<name>.measurements``), one set.

    A run measured in two of them is an error: which to believe would be a guess.
    """
    specs: list[str] = []
    try:
        specs.append(measurement_spec(None, system.meta.measurements, origin))
    except DescriptionError:
        if not any(test.measurements for test in system.tests.values()):
            raise
    specs += [test.measurements for test in system.tests.values() if test.measurements]
    sets = [read_description_measurements(system, spec, origin) for spec in dict.fromkeys(specs)]
    return merged(sets)


def merged(sets: list[MeasurementSet]) -> MeasurementSet:
    """One set of several files' measurements; a run that two of them measure is an error."""
    if len(sets) == 1:
        return sets[0]
    seen: dict[str, str] = {}
    for data in sets:
        for run in data.runs():
            if run in seen:
                raise DescriptionError(f"{data.source}: {run} is measured here and in {seen[run]}; give each run's "
                                       "measurements in one file")
            seen[run] = data.source
    return MeasurementSet([r for d in sets for r in d.rows], " + ".join(d.source for d in sets),
                          {k: v for d in sets for k, v in d.equilibrium_min.items()},
                          [r for d in sets for r in d.positioning], {k: v for d in sets for k, v in d.air.items()})
