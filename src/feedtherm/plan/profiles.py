"""A run's profile: a test's or a duty cycle's segments, the state it starts from and its room's air.

:func:`test_profile` resolves a test (or a condition, the simplest test; system/thermal_tests.py)
into its duty segments, its start (:class:`Uniform`, a soak in another run, :class:`FromReadings`)
and its logged room air; :func:`cycle_profile` a bare duty cycle, declared or from a CSV file.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..boundary.room import RoomAir
from ..constants import ELONGATION_PROBE, KELVIN_OFFSET
from ..errors import ArgumentError, FeedthermError
from ..system.duty_cycle import read_duty_cycle_csv
from ..system.load import LoadedSystem
from ..system.measurement_series import ELONGATION_QUANTITY
from ..system.measurements import MeasurementSet, measurement_spec, read_description_measurements
from ..system.runs import as_test, run_duration
from ..system.schema import DEFAULT_DURATION_S, DutyCycle, DutySegment, FeedSystem
from ..system.thermal_tests import Soak, ThermalTest


@dataclass(frozen=True)
class Uniform:
    """A start with every part at one temperature [K]."""

    temperature: float


@dataclass(frozen=True)
class Soaked:
    """A start from the end state of another run, planned here (``name``: the test, condition or cycle)."""

    name: str
    plan: "RunPlan"


@dataclass(frozen=True)
class FromReadings:
    """A start that matches the readings at t = 0 (sensor → temperature [K], and ``D`` [m] where read),
    the air at ``air`` [K] (:func:`feedtherm.simulate.matched_state`)."""

    readings: dict[str, float]
    air: float


Initial = Uniform | Soaked | FromReadings


@dataclass(frozen=True)
class _Profile:
    label: str
    segments: list[DutySegment]
    end: float
    initial: "Initial | Soak"
    air: RoomAir | None = None
    test: ThermalTest | None = None


def test_profile(loaded: LoadedSystem, name: str, duration: float | None,
                  measured: MeasurementSet | None, argument: str = "condition") -> _Profile:
    """A test's (or a condition's) segments, its start and its room's air (``argument``: the
    caller's name for ``name``, which an unknown one's error names)."""
    system = loaded.system
    test = as_test(system, name)
    if test is None:
        tests = f"; tests: {', '.join(system.tests)}" if system.tests else ""
        raise ArgumentError(argument, f"no condition or test {name!r} in {loaded.origin}; "
                                      f"conditions: {', '.join(system.conditions)}{tests}")
    end = duration if duration is not None else run_duration(system, name)
    data = _measurements(loaded, name, test, measured) if test.needs_measurements else None
    air, room = None, None
    if test.room == "measured":
        series = data.air.get(name)
        if series is None:
            raise FeedthermError(f"tests.{name}.room: 'measured', but {data.source} logs no "
                                 f"{system.room.ambient_sensor} (the room's air) for {name}")
        air = RoomAir(series.times, series.values + KELVIN_OFFSET)
        room = air.mean(0.0, end)  # the surfaces' coefficients are taken there; the sinks follow the log
    elif not isinstance(test.room, str):
        room = float(test.room)
    if test.condition is not None:
        c = system.conditions[test.condition]
        duty = [DutySegment.model_construct(start=0.0, screw_speed=c.screw_speed, nut_speed=c.nut_speed,
                                            ambient=c.ambient if room is None else room, table_at=None)]
    else:
        duty = _timeline(system.duty_cycles[test.cycle], end, room)
    return _Profile(name, duty, end, _start_of(system, name, test, duty, air, data), air, test)


def _start_of(system: FeedSystem, name: str, test: ThermalTest, duty: list[DutySegment], air: RoomAir | None,
              data: MeasurementSet | None) -> "Initial | Soak":
    start = test.start
    if isinstance(start, Soak):
        return start
    air0 = air.at(0.0) if air is not None else duty[0].ambient
    if start == "ambient":
        return Uniform(air0)
    if start == "measured":
        at_zero = [row for row in data.rows if row.condition == name and row.series is not None
                   and row.series.times[0] == 0.0]
        readings = {row.quantity: float(row.series.values[0]) + KELVIN_OFFSET
                    for row in at_zero if row.quantity in system.sensors}
        # the elongation, where read at 0 s, is a reading of the field too (its mean along the loop)
        readings |= {ELONGATION_PROBE: float(row.series.values[0]) * 1e-6
                     for row in at_zero if row.quantity == ELONGATION_QUANTITY}
        if not readings:
            raise FeedthermError(f"tests.{name}.start: 'measured', but {data.source} has no sensor's reading at "
                                 f"0 s for {name}")
        return FromReadings(readings, air0)
    return Uniform(float(start))


def soak_target(loaded: LoadedSystem, name: str) -> dict:
    """The plan_run argument that names the soak: a test or condition, else a duty cycle."""
    return {"cycle": name} if name in loaded.system.duty_cycles else {"condition": name}


def _measurements(loaded: LoadedSystem, name: str, test: ThermalTest, measured: MeasurementSet | None) -> MeasurementSet:
    """The measurements a test's measured room or start reads: ``measured`` if given, else its own file,
    else the description's."""
    if measured is not None:
        return measured
    system = loaded.system
    spec = measurement_spec(test.measurements or None, system.meta.measurements, loaded.origin)
    return read_description_measurements(system, spec, loaded.origin)


def _timeline(cycle: DutyCycle, end: float, room: float | None) -> list[DutySegment]:
    """The cycle's whole profile up to ``end``, each segment's air the room's, its own or the cycle's."""
    out = []
    for seg in cycle.timeline():
        if seg.start >= end:
            break
        ambient = room if room is not None else seg.ambient if seg.ambient is not None else cycle.ambient
        out.append(seg.model_copy(update={"ambient": ambient}))
    return out


def cycle_profile(loaded: LoadedSystem, condition: str | None, cycle: str | None,
                   duration: float | None) -> _Profile:
    """A duty cycle's segments (a name in the description or a CSV file), from ``temperatures.initial``."""
    system = loaded.system
    if condition is not None:
        raise ArgumentError("cycle", "give exactly one of condition (or test) and cycle, not both")
    if cycle is None:
        raise ArgumentError("condition", "give exactly one of condition (a test or a condition), test and cycle")
    if cycle in system.duty_cycles:
        profile = system.duty_cycles[cycle]
        end = duration if duration is not None else profile.total_duration
        label, duty = cycle, _timeline(profile, end, None)
    elif not Path(cycle).is_file():
        names = ", ".join(system.duty_cycles) or "none"
        raise ArgumentError("cycle", f"{cycle!r} is neither a duty cycle of {loaded.origin} (declared: {names}) "
                                     "nor an existing CSV file")
    else:
        end = duration if duration is not None else DEFAULT_DURATION_S
        label, duty = Path(cycle).stem, read_duty_cycle_csv(cycle, end).segments
    initial = system.temperatures.initial
    return _Profile(label, duty, end, Uniform(duty[0].ambient if initial == "ambient" else float(initial)))


