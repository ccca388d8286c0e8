"""The runs a description declares, by name: its tests and its conditions (the simplest tests).

Every command that takes a condition takes a test (system/thermal_tests.py); these functions
answer for either without the caller telling them apart.
"""

from __future__ import annotations

from .schema import FeedSystem
from .thermal_tests import ThermalTest


def run_names(system: FeedSystem) -> list[str]:
    """The conditions, then the tests, in declared order."""
    return [*system.conditions, *system.tests]


def as_test(system: FeedSystem, name: str) -> ThermalTest | None:
    """The test ``name``, or the condition ``name`` as the test it is (from ``temperatures.initial``, in a
    room at its own ambient); None for neither."""
    if name in system.tests:
        return system.tests[name]
    if name in system.conditions:
        return ThermalTest.model_construct(condition=name, cycle=None, duration=None,
                                           start=system.temperatures.initial, room="declared", measurements="",
                                           description=system.conditions[name].description)
    return None


def run_duration(system: FeedSystem, name: str) -> float:
    """How long the run ``name`` lasts [s]: its own duration, else its condition's or its cycle's whole profile."""
    test = as_test(system, name)
    if test is None:
        raise KeyError(name)
    if test.duration is not None:
        return test.duration
    if test.condition is not None:
        return system.conditions[test.condition].duration
    return system.duty_cycles[test.cycle].total_duration


def run_durations(system: FeedSystem) -> dict[str, float]:
    """Every run's duration [s] by name (:func:`run_duration`)."""
    return {name: run_duration(system, name) for name in run_names(system)}


def visited_targets(system: FeedSystem, name: str) -> list[float]:
    """The table positions [m] the run ``name`` holds the table at: its cycle's measuring targets and
    held standstills, in order of first visit (none for a condition)."""
    test = as_test(system, name)
    if test is None or test.cycle is None:
        return []
    cycle = system.duty_cycles[test.cycle]
    held = [*(cycle.measuring.targets if cycle.measuring is not None else []),
            *(s.table_at for s in cycle.segments if s.table_at is not None)]
    return list(dict.fromkeys(held))


def is_idle(system: FeedSystem, name: str) -> bool:
    """Whether no motor turns in the run ``name`` (its measuring stops aside): ISO 230-3's ETVE test."""
    test = as_test(system, name)
    if test is None:
        return False
    if test.condition is not None:
        c = system.conditions[test.condition]
        return c.screw_speed == 0.0 and c.nut_speed == 0.0
    return all(s.screw_speed == 0.0 and s.nut_speed == 0.0 for s in system.duty_cycles[test.cycle].segments)
