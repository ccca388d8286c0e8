"""Checks on a run's results before anyone reads them: finite, above absolute zero, energy kept.

A valid description can still give a run no one should use: an iteration that diverged, a
state of NaN, a balance that does not close.  :func:`check_health` finds these before the
results are written or compared, and says what failed in one line.
"""

from __future__ import annotations

import numpy as np

from ..constants import ELONGATION_PROBE
from ..errors import ModelError
from . import Solution

#: Largest |relative energy balance error| of a healthy run (issue 12's bound; the models'
#: own runs stay below 1e-6: benchmarks/README.md).
ENERGY_TOLERANCE = 1e-4


def problems(solution: Solution, energy_tolerance: float = ENERGY_TOLERANCE) -> list[str]:
    """What is wrong with ``solution`` (an empty list for a healthy run)."""
    found = []
    series = {f"sensor {name}": values for name, values in solution.sensors.items()}
    series.update({f"part {name}": values for name, values in solution.part_temperatures.items()})
    series["screw temperature"] = solution.screw_temperature
    for what, values in series.items():
        values = np.asarray(values, dtype=float)
        if not np.all(np.isfinite(values)):
            found.append(f"{what}: the temperatures are not finite (NaN or infinite)")
        elif values.size and values.min() <= 0.0:
            found.append(f"{what}: a temperature of {values.min():.4g} K, at or below absolute zero")
    for what, values in (("elongation D", solution.elongation), ("screw displacement", solution.screw_displacement)):
        if not np.all(np.isfinite(values)):
            found.append(f"{what}: not finite (NaN or infinite)")
    error = solution.energy.relative_error
    if not np.isfinite(error) or abs(error) > energy_tolerance:
        found.append(f"energy balance: heat in, lost and stored differ by {error:.3g} of the heat, "
                     f"more than {energy_tolerance:g}")
    for which, values in (("final", solution.final), ("steady", solution.steady)):
        missing = [name for name in (*solution.sensors, ELONGATION_PROBE) if name not in values]
        if missing:
            found.append(f"summary: no {which} value of {', '.join(missing)}, which the series have")
        bad = [name for name, value in values.items() if not np.isfinite(value)]
        if bad:
            found.append(f"summary: the {which} value of {', '.join(bad)} is not finite")
    return found


def check_health(solution: Solution, energy_tolerance: float = ENERGY_TOLERANCE) -> None:
    """Raise :class:`~feedtherm.errors.ModelError` (one line) where ``solution`` is unhealthy."""
    found = problems(solution, energy_tolerance)
    if found:
        more = f" (and {len(found) - 1} more)" if len(found) > 1 else ""
        label = solution.info.get("condition", "the run")
        raise ModelError(f"results of {label} failed their check, nothing written: {found[0]}{more}")
