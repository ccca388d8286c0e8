"""The order in which every output shows a run's sensors: as declared, the ambient one last."""

from __future__ import annotations

from ..constants import AMBIENT_SENSOR
from ..solution import Solution


def ordered_sensor_names(solution: Solution) -> list[str]:
    """The sensors as the description declares them, with the ambient sensor last.

    The ambient air temperature is an input of the run, not a result: columns, legends and
    summaries list it after the sensors on the machine.
    """
    names = [name for name in solution.sensors if name != AMBIENT_SENSOR]
    if AMBIENT_SENSOR in solution.sensors:
        names.append(AMBIENT_SENSOR)
    return names
