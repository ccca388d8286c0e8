"""A Solution's series as pandas DataFrames, columns named with their units.

The tables hold what the run's CSV files hold (``sensors.csv``, ``parts.csv``, ``screw.csv``,
``screw_displacement.csv``, ``positioning_error.csv``; docs/outputs.md) in the same units: time
in s, temperatures in °C, D, displacements and E in µm, positions in mm.  Units are spelled in
ASCII (``degC``, ``um``) so that a column name is easy to type.  pandas is imported here only,
when a table is asked for: a run and the command line do without it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..constants import KELVIN_OFFSET
from ..errors import ArgumentError

if TYPE_CHECKING:  # the types only; pandas is imported where a table is built
    import pandas as pd

    from . import Solution

#: What :func:`to_dataframe` tabulates.
KINDS = ("sensors", "parts", "screw_temperature", "screw_displacement", "positioning_error")
#: Its layouts: one row per observation, or one row per time.
FORMS = ("long", "wide")

TIME = "time [s]"
X = "x [mm]"
#: Field kind -> (symbol in a wide column, quantity in a long column, unit).
_FIELDS = {
    "screw_temperature": ("T", "temperature", "degC"),
    "screw_displacement": ("u", "displacement", "um"),
    "positioning_error": ("E", "positioning error", "um"),
}


def to_dataframe(solution: "Solution", kind: str = "sensors", form: str = "wide") -> "pd.DataFrame":
    """One of ``solution``'s series as a table (see :meth:`feedtherm.solution.Solution.to_dataframe`)."""
    if kind not in KINDS:
        raise ArgumentError("kind", f"no table {kind!r}; tables: {', '.join(KINDS)}")
    if form not in FORMS:
        raise ArgumentError("form", f"must be long or wide, got {form!r}")
    if kind == "sensors":
        return _sensors(solution, form)
    if kind == "parts":
        return _parts(solution, form)
    return _field(solution, kind, form)


def sensor_order(solution: "Solution") -> list[str]:
    """The sensors as declared, the ambient one last (the order of ``sensors.csv``: the air is an
    input of the run, not a result)."""
    ambient = solution.ambient_sensor
    return [n for n in solution.sensors if n != ambient] + ([ambient] if ambient in solution.sensors else [])


def _sensors(solution: "Solution", form: str) -> "pd.DataFrame":
    import pandas as pd

    # D is what the displacement sensor reads: it belongs beside the temperatures it is compared with.
    series = {f"{name} [degC]": solution.sensors[name] - KELVIN_OFFSET for name in sensor_order(solution)}
    series["D [um]"] = solution.elongation_um
    if form == "wide":
        return pd.DataFrame({TIME: solution.times, **series})
    names = sensor_order(solution) + ["D"]
    units = ["degC"] * (len(names) - 1) + ["um"]
    n = solution.times.size
    return pd.DataFrame({
        TIME: np.tile(solution.times, len(names)),
        "sensor": np.repeat(names, n),
        "value": np.concatenate(list(series.values())) if n else np.zeros(0),
        "unit": np.repeat(units, n),
    })


def _parts(solution: "Solution", form: str) -> "pd.DataFrame":
    import pandas as pd

    names = list(solution.part_temperatures)
    if form == "wide":
        return pd.DataFrame({TIME: solution.times,
                             **{f"{p} [degC]": solution.part_temperatures[p] - KELVIN_OFFSET for p in names}})
    n = solution.times.size
    values = [solution.part_temperatures[p] - KELVIN_OFFSET for p in names]
    return pd.DataFrame({
        TIME: np.tile(solution.times, len(names)),
        "part": np.repeat(names, n),
        "temperature [degC]": np.concatenate(values) if values else np.zeros(0),
    })


def _field(solution: "Solution", kind: str, form: str) -> "pd.DataFrame":
    import pandas as pd

    symbol, quantity, unit = _FIELDS[kind]
    if kind == "positioning_error":
        x, values = solution.table_x, solution.positioning_error * 1e6
    elif kind == "screw_displacement":
        x, values = solution.screw_x, solution.screw_displacement * 1e6
    else:
        x, values = solution.screw_x, solution.screw_temperature - KELVIN_OFFSET
    values = np.asarray(values, dtype=float).reshape(solution.times.size, x.size)
    x_mm = np.asarray(x, dtype=float) * 1e3
    if form == "wide":
        columns = {f"{symbol}(x={xi:.6g} mm) [{unit}]": values[:, j] for j, xi in enumerate(x_mm)}
        return pd.DataFrame({TIME: solution.times, **columns})
    return pd.DataFrame({
        TIME: np.repeat(solution.times, x_mm.size),
        X: np.tile(x_mm, solution.times.size),
        f"{quantity} [{unit}]": values.ravel(),
    })
