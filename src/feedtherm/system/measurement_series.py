"""Measured time series: the long format of a measurement file.

One row per sample::

    condition,time [min],quantity,value,unit[,uncertainty]
    v10,0,front_bearing,20.0,degC,0.2
    v10,10,front_bearing,21.8,degC,0.2
    v10,10,D,0.0415,mm,0.001

- ``time [<unit>]``: the header carries the time unit of the whole file, any time unit pint
  reads (``s``, ``min``, ``h``); times count from the start of the condition's run (0).
- ``quantity``: a sensor of the description, or ``D``, the elongation probe.
- ``unit``: the value's unit, per row. A sensor reads a temperature in any unit pint reads
  (``degC``, ``K``, ``degF``; ``C`` means degree Celsius, as in the finals format, never
  coulomb); ``D`` reads a length (``um``, ``mm``, ``m``).
- ``uncertainty`` (optional column): the standard uncertainty of the value, in the value's
  unit, a difference (20 degF → 11.1 K, not an absolute temperature); empty on every sample of
  a series, or given on every one.

The rows of one series (condition and quantity) come in the order of strictly increasing
time; the rows of different series may interleave (a logger's time-major output reads as is).
Values are converted to the units the finals use (°C and µm), times to seconds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Collection, Mapping

import numpy as np

from ..constants import ELONGATION_PROBE, KELVIN_OFFSET
from ..errors import DescriptionError
from .quantities import TEMPERATURE_LIMIT, pint, registry  # pint as system.quantities imports it

COLUMNS = ["condition", "time [<unit>]", "quantity", "value", "unit"]
OPTIONAL = "uncertainty"
SERIES_HEADER = ",".join(COLUMNS) + f"[,{OPTIONAL}]"
#: The screw elongation among the measured quantities, as the finals name it [µm].
ELONGATION_QUANTITY, ELONGATION_UNIT = "D_um", "um"
TEMPERATURE_UNIT = "C"
# "C" is the finals format's degree Celsius; to pint it is a coulomb.
_ALIASES = {"C": "degC"}


@dataclass(frozen=True, eq=False)
class Series:
    """One measured series of a condition and quantity.

    Attributes
    ----------
    times : ndarray, shape (n,)
        Sample times [s] from the start of the run, strictly increasing.
    values : ndarray, shape (n,)
        Measured values [°C] for a temperature, [µm] for the elongation.
    uncertainties : ndarray, shape (n,), or None
        Standard uncertainties of ``values`` [K] or [µm], None where the file gives none.
    """

    times: np.ndarray
    values: np.ndarray
    uncertainties: np.ndarray | None = None

    def zero_uncertainty_at(self) -> float | None:
        """The first time [s] whose stated uncertainty is not positive (a weight a fit cannot use), else None."""
        u = self.uncertainties
        if u is None or not np.any(u <= 0):
            return None
        return float(self.times[int(np.argmax(u <= 0))])


@dataclass(frozen=True)
class SeriesRow:
    """What one measured series becomes among the finals: its last sample stands for the final value."""

    condition: str
    quantity: str  # a sensor name, or "D_um" for the elongation (the finals' name)
    unit: str  # "C" or "um"
    series: Series


def is_series_header(header: list[str]) -> bool:
    """True for the long format's header: its second column is the time."""
    return len(header) > 1 and header[1].lower().startswith("time")


def parse_series(rows: list[tuple[int, list[str]]], source: str, *, sensors: Collection[str] | None = None,
                 conditions: Collection[str] | None = None,
                 run_end: Mapping[str, float] | None = None) -> list[SeriesRow]:
    """Parse the long format: ``rows`` are (line number, cells), the header first.

    Parameters
    ----------
    rows : list of (int, list of str)
        The file's non-blank lines with their numbers, the header first.
    source : str
        The file's name in error messages.
    sensors, conditions : collection of str, optional
        The description's sensors and conditions; a row naming another is an error.
    run_end : mapping of str to float, optional
        Condition → the end of its simulated run [s]; a later sample cannot be compared.

    Raises
    ------
    DescriptionError
        One line naming the file, the line and the reason.
    """
    number, header = rows[0][0], [c.strip() for c in rows[0][1]]
    time_unit = _time_unit(header, source, number)
    width = len(header)
    samples: dict[tuple[str, str], list[tuple[int, float, float, float | None]]] = {}
    units: dict[tuple[str, str], str] = {}
    for number, row in rows[1:]:
        where = f"{source}: line {number}"
        if len(row) != width:
            raise DescriptionError(f"{where}: expected {width} values, got {len(row)}")
        condition, time_text, quantity, value_text, unit = (c.strip() for c in row[:5])
        if conditions is not None and condition not in conditions:
            raise DescriptionError(f"{where}: unknown condition {condition!r}; expected one of {', '.join(conditions)}")
        kind = _kind(quantity, sensors, where)
        time = _number(time_text, "time", where) * time_unit
        if time < 0:
            raise DescriptionError(f"{where}: time {time_text} lies before the start of the run (0)")
        end = run_end.get(condition) if run_end is not None else None
        if end is not None and time > end * (1 + 1e-9):
            raise DescriptionError(f"{where}: time {time:g} s lies after the end of condition {condition}'s run "
                                   f"({end:g} s), so no simulated value can be compared with it")
        scale, offset = _conversion(unit, kind, where)
        value = _number(value_text, "value", where) * scale + offset
        if kind == "temperature" and TEMPERATURE_LIMIT.violated_by(value + KELVIN_OFFSET):
            raise DescriptionError(f"{where}: {value_text} {unit} lies outside the accepted range, "
                                   f"{TEMPERATURE_LIMIT.describe()}")
        uncertainty = None
        if width > 5 and row[5].strip():
            uncertainty = _number(row[5].strip(), "uncertainty", where) * scale
            if uncertainty < 0:
                raise DescriptionError(f"{where}: the uncertainty must not be negative, got {row[5].strip()}")
        key = (condition, ELONGATION_QUANTITY if kind == "length" else quantity)
        _check_order(samples.get(key), number, time, condition, quantity, where)
        samples.setdefault(key, []).append((number, time, value, uncertainty))
        units[key] = ELONGATION_UNIT if kind == "length" else TEMPERATURE_UNIT
    if not samples:
        raise DescriptionError(f"{source}: no rows after the header")
    return [SeriesRow(c, q, units[(c, q)], _series(points, source, c, q)) for (c, q), points in samples.items()]


def _time_unit(header: list[str], source: str, number: int) -> float:
    """Seconds per unit of the header's ``time [<unit>]``; the rest of the header checked."""
    names = [header[0], "time", *header[2:]]
    if names not in (["condition", "time", "quantity", "value", "unit"],
                     ["condition", "time", "quantity", "value", "unit", OPTIONAL]):
        raise DescriptionError(f"{source}: line {number}: header must be {SERIES_HEADER}, got {','.join(header)}")
    text = header[1][len("time"):].strip()
    if not (text.startswith("[") and text.endswith("]") and text[1:-1].strip()):
        raise DescriptionError(f"{source}: line {number}: the time column names its unit, e.g. 'time [min]', "
                               f"got {header[1]!r}")
    unit = text[1:-1].strip()
    try:
        seconds = float(registry().Quantity(1.0, unit).to("s").magnitude)
    except pint.errors.DimensionalityError:
        raise DescriptionError(f"{source}: line {number}: {unit!r} is not a unit of time") from None
    except (pint.errors.PintError, AttributeError, TypeError, SyntaxError, ValueError):
        raise DescriptionError(f"{source}: line {number}: unknown time unit {unit!r}") from None
    return seconds


def _kind(quantity: str, sensors: Collection[str] | None, where: str) -> str:
    if quantity == ELONGATION_PROBE:
        return "length"
    if quantity == ELONGATION_QUANTITY:
        raise DescriptionError(f"{where}: the long format names the elongation {ELONGATION_PROBE} with a length "
                               f"unit (e.g. {ELONGATION_PROBE},12.5,um), not {ELONGATION_QUANTITY}")
    if sensors is not None and quantity not in sensors:
        raise DescriptionError(f"{where}: unknown quantity {quantity!r}; expected one of "
                               f"{', '.join([*sensors, ELONGATION_PROBE])}")
    return "temperature"


def _number(text: str, what: str, where: str) -> float:
    if not text:
        raise DescriptionError(f"{where}: the {what} is missing (an empty cell); leave out a sample that was not taken")
    try:
        number = float(text)
    except ValueError:
        raise DescriptionError(f"{where}: the {what} must be a number, got {text!r}") from None
    if not math.isfinite(number):
        raise DescriptionError(f"{where}: the {what} must be a finite number, got {text!r}")
    return number


_CONVERSIONS: dict[tuple[str, str], tuple[float, float]] = {}


def _conversion(unit: str, kind: str, where: str) -> tuple[float, float]:
    """(scale, offset) taking a value in ``unit`` to °C (temperature) or µm (length).

    A temperature scale may be affine (degF): the offset applies to values only, the scale
    to values and to their uncertainties, which are differences.
    """
    key = (unit, kind)
    if key not in _CONVERSIONS:
        target = "degC" if kind == "temperature" else "um"
        name = "a temperature" if kind == "temperature" else "a length"
        if not unit:
            raise DescriptionError(f"{where}: the unit is missing; give {name}'s unit")
        ureg = registry()
        try:
            parsed = ureg.Unit(_ALIASES.get(unit, unit))
            if "delta" in str(parsed):  # a difference unit cannot place an absolute value
                raise pint.errors.DimensionalityError(parsed, target)
            offset = float(ureg.Quantity(0.0, parsed).to(target).magnitude)
            scale = float(ureg.Quantity(1.0, parsed).to(target).magnitude) - offset
        except pint.errors.DimensionalityError:
            raise DescriptionError(f"{where}: {unit!r} is not {name}'s unit") from None
        except (pint.errors.PintError, AttributeError, TypeError, SyntaxError, ValueError):
            raise DescriptionError(f"{where}: unknown unit {unit!r}") from None
        _CONVERSIONS[key] = (scale, offset)
    return _CONVERSIONS[key]


def _check_order(previous: list | None, number: int, time: float, condition: str, quantity: str, where: str) -> None:
    if not previous:
        return
    last_line, last_time = previous[-1][0], previous[-1][1]
    if time == last_time:
        raise DescriptionError(f"{where}: {condition} {quantity} has time {time:g} s twice (line {last_line} too)")
    if time < last_time:
        raise DescriptionError(f"{where}: {condition} {quantity} is out of order: time {time:g} s after "
                               f"{last_time:g} s on line {last_line}; sort each series by time")


def _series(points: list[tuple[int, float, float, float | None]], source: str, condition: str,
            quantity: str) -> Series:
    given = [u is not None for *_, u in points]
    if any(given) and not all(given):
        line = points[given.index(False) if given[0] else given.index(True)][0]
        raise DescriptionError(f"{source}: line {line}: {condition} {quantity} has uncertainties on some samples "
                               "only; give one on every sample of a series or on none")
    times = np.array([t for _, t, _, _ in points])
    values = np.array([v for _, _, v, _ in points])
    uncertainties = np.array([u for *_, u in points]) if all(given) else None
    return Series(times, values, uncertainties)
