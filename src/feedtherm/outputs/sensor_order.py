"""The order in which every output shows a run's sensors: as declared, the ambient one last."""

from __future__ import annotations

from ..solution import Solution


def ordered_sensor_names(solution: Solution) -> list[str]:
    """The sensors as the description declares them, with the ambient sensor last.

    The ambient air temperature is an input of the run, not a result: columns, legends and
    summaries list it after the sensors on the machine.
    """
    ambient = solution.ambient_sensor
    names = [name for name in solution.sensors if name != ambient]
    if ambient in solution.sensors:
        names.append(ambient)
    return names
