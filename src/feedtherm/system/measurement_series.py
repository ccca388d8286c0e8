"""Measured time series: the long format of a measurement file.

One row per sample::

    test,time [min],quantity,value,unit[,uncertainty][,target [mm]]
    v10,0,front_bearing,20.0,degC,0.2,
    v10,10,front_bearing,21.8,degC,0.2,
    v10,10,D,0.0415,mm,0.001,
    drift,12,E,3.1,um,1.0,150

- the first column names the run: a test or a condition of the description (headed ``test`` or
  ``condition``, the same thing: a condition is the simplest test).
- ``time [<unit>]``: the header carries the time unit of the whole file, any time unit pint
  reads (``s``, ``min``, ``h``); times count from the start of the run (0).
- ``quantity``: a sensor of the description, the room's air (``room.ambient_sensor``), ``D``, the
  elongation probe, or ``E``, the positioning deviation at a target position: the target's axis
  coordinate in the ``target [<length unit>]`` column (the table's position, the nut's centre along
  x in the machine frame, as ``positioning_error.csv`` has it), empty on every other row.
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
import tokenize
from dataclasses import dataclass
from typing import Collection, Mapping

import numpy as np

from ..constants import ELONGATION_PROBE, KELVIN_OFFSET
from ..errors import DescriptionError
from .quantities import LENGTH_LIMIT, TEMPERATURE_LIMIT, pint, registry  # pint as system.quantities imports it

COLUMNS = ["test", "time [<unit>]", "quantity", "value", "unit"]
OPTIONAL = "uncertainty"
TARGET = "target"
SERIES_HEADER = ",".join(COLUMNS) + f"[,{OPTIONAL}][,{TARGET} [<unit>]]"
#: The first column's accepted names: a condition is the simplest test.
RUN_COLUMNS = ("test", "condition")
#: The positioning deviation at a target among the measured quantities.
POSITIONING_QUANTITY = "E"
#: Two targets closer than this are one [m] (a rounding of the written coordinate).
TARGET_TOLERANCE = 1e-6
#: The screw elongation among the measured quantities, as the finals name it [µm].
ELONGATION_QUANTITY, ELONGATION_UNIT = "D_um", "um"
TEMPERATURE_UNIT = "C"
# "C" is the finals format's degree Celsius; to pint it is a coulomb.
_ALIASES = {"C": "degC"}
#: What pint's parser raises for a unit it cannot read: besides its own errors, an unbalanced "(" ends
#: in tokenize's TokenError and a dangling operator ("1/", "m^", a NUL) in an AssertionError.
_UNREADABLE_UNIT = (pint.errors.PintError, AttributeError, TypeError, SyntaxError, ValueError, AssertionError,
                    tokenize.TokenError)


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

    condition: str  # the run: a test or a condition
    quantity: str  # a sensor name, "D_um" for the elongation (the finals' name), or E's :func:`target_key`
    unit: str  # "C" or "um"
    series: Series
    target: float | None = None  # E's target position [m]


def target_key(target: float) -> str:
    """The name of the positioning deviation at ``target`` [m] among the quantities: ``E@150mm``."""
    return f"{POSITIONING_QUANTITY}@{round(target * 1e3, 6):g}mm"


def target_of(quantity: str) -> float | None:
    """The target [m] of a positioning deviation's name (:func:`target_key`), None for another quantity."""
    head = f"{POSITIONING_QUANTITY}@"
    if not (quantity.startswith(head) and quantity.endswith("mm")):
        return None
    try:
        return float(quantity[len(head):-2]) * 1e-3
    except ValueError:
        return None


def is_series_header(header: list[str]) -> bool:
    """True for the long format's header: its second column is the time."""
    return len(header) > 1 and header[1].lower().startswith("time")


def parse_series(rows: list[tuple[int, list[str]]], source: str, *, sensors: Collection[str] | None = None,
                 conditions: Collection[str] | None = None,
                 run_end: Mapping[str, float] | None = None, air: str | None = None,
                 travel: tuple[float, float] | None = None,
                 visits: Mapping[str, Collection[float]] | None = None) -> list[SeriesRow]:
    """Parse the long format: ``rows`` are (line number, cells), the header first.

    Parameters
    ----------
    rows : list of (int, list of str)
        The file's non-blank lines with their numbers, the header first.
    source : str
        The file's name in error messages.
    sensors, conditions : collection of str, optional
        The description's sensors and runs (its tests and conditions); a row naming another is an error.
    run_end : mapping of str to float, optional
        Run → the end of its simulated run [s]; a later sample cannot be compared.
    air : str, optional
        The room's air among the quantities (``room.ambient_sensor``); None: no air series.
    travel : (float, float), optional
        The table positions the stroke reaches [m]; a target outside them is an error.
    visits : mapping of str to collection of float, optional
        Run → the target positions [m] its measuring stops hold the table at; a deviation at a
        target the run never visits is an error (a run left out visits none).

    Raises
    ------
    DescriptionError
        One line naming the file, the line and the reason.
    """
    number, header = rows[0][0], [c.strip() for c in rows[0][1]]
    time_unit, extra = _header(header, source, number)
    width = len(header)
    samples: dict[tuple[str, str], list[tuple[int, float, float, float | None]]] = {}
    units: dict[tuple[str, str], str] = {}
    targets: dict[tuple[str, str], float] = {}
    for number, row in rows[1:]:
        where = f"{source}: line {number}"
        if len(row) != width:
            raise DescriptionError(f"{where}: expected {width} values, got {len(row)}")
        condition, time_text, quantity, value_text, unit = (c.strip() for c in row[:5])
        if conditions is not None and condition not in conditions:
            raise DescriptionError(f"{where}: unknown test {condition!r}; expected one of {', '.join(conditions)}")
        kind = _kind(quantity, sensors, air, where)
        time = _number(time_text, "time", where) * time_unit
        if time < 0:
            raise DescriptionError(f"{where}: time {time_text} lies before the start of the run (0)")
        end = run_end.get(condition) if run_end is not None else None
        if end is not None and time > end * (1 + 1e-9):
            raise DescriptionError(f"{where}: time {time:g} s lies after the end of {condition}'s run "
                                   f"({end:g} s), so no simulated value can be compared with it")
        scale, offset = _conversion(unit, "temperature" if kind == "temperature" else "length", where)
        value = _number(value_text, "value", where) * scale + offset
        check_value_range(kind, value, f"{value_text} {unit}", where)
        uncertainty = None
        if OPTIONAL in extra and row[extra[OPTIONAL][0]].strip():
            uncertainty = _number(row[extra[OPTIONAL][0]].strip(), "uncertainty", where) * scale
            if uncertainty < 0:
                raise DescriptionError(f"{where}: the uncertainty must not be negative, got {row[extra[OPTIONAL][0]].strip()}")
        target = _target(row, extra, kind, quantity, where)
        if target is not None:
            _check_target(target, condition, travel, visits, where)
            key = (condition, target_key(target))
            targets[key] = target
        else:
            key = (condition, ELONGATION_QUANTITY if kind == "length" else quantity)
        _check_order(samples.get(key), number, time, condition, key[1], where)
        samples.setdefault(key, []).append((number, time, value, uncertainty))
        units[key] = ELONGATION_UNIT if kind != "temperature" else TEMPERATURE_UNIT
    if not samples:
        raise DescriptionError(f"{source}: no rows after the header")
    return [SeriesRow(c, q, units[(c, q)], _series(points, source, c, q), targets.get((c, q)))
            for (c, q), points in samples.items()]


def _target(row: list[str], extra: dict, kind: str, quantity: str, where: str) -> float | None:
    """E's target [m] from the ``target`` column; every other quantity leaves the cell empty."""
    text = row[extra[TARGET][0]].strip() if TARGET in extra else ""
    if kind != "positioning":
        if text:
            raise DescriptionError(f"{where}: only {POSITIONING_QUANTITY} is measured at a target; leave the target "
                                   f"empty for {quantity}")
        return None
    if TARGET not in extra:
        raise DescriptionError(f"{where}: {POSITIONING_QUANTITY} is the deviation at a target position: add a column "
                               f"'{TARGET} [mm]' with the target's axis coordinate")
    if not text:
        raise DescriptionError(f"{where}: the target is missing (an empty cell); {POSITIONING_QUANTITY} is measured at "
                               "a target position")
    return _number(text, "target", where) * extra[TARGET][1]


def _check_target(target: float, condition: str, travel, visits, where: str) -> None:
    if travel is not None and not travel[0] - TARGET_TOLERANCE <= target <= travel[1] + TARGET_TOLERANCE:
        raise DescriptionError(f"{where}: target {target * 1e3:g} mm lies outside the table's travel, "
                               f"{travel[0] * 1e3:g}..{travel[1] * 1e3:g} mm")
    if visits is not None:
        held = visits.get(condition, ())
        if not any(abs(target - x) <= TARGET_TOLERANCE for x in held):
            where_held = (f"its measuring stops hold the table at {', '.join(f'{x * 1e3:g}' for x in held)} mm"
                          if held else "it has no measuring stops")
            raise DescriptionError(f"{where}: {condition} never visits target {target * 1e3:g} mm ({where_held})")


def _header(header: list[str], source: str, number: int) -> tuple[float, dict[str, tuple[int, float]]]:
    """Seconds per unit of the header's ``time [<unit>]``, and the optional columns: name → (index,
    metres per unit of the target column, 1 for the uncertainty); the rest of the header checked."""
    wrong = DescriptionError(f"{source}: line {number}: header must be {SERIES_HEADER}, got {','.join(header)}")
    if len(header) < 5 or header[0] not in RUN_COLUMNS or header[2:5] != ["quantity", "value", "unit"]:
        raise wrong
    seconds = _unit_in(header[1], "time", "s", "a unit of time", source, number)
    extra: dict[str, tuple[int, float]] = {}
    for index, name in enumerate(header[5:], start=5):
        if name == OPTIONAL and OPTIONAL not in extra:
            extra[OPTIONAL] = (index, 1.0)
        elif name.lower().startswith(TARGET) and TARGET not in extra:
            extra[TARGET] = (index, _unit_in(name, TARGET, "m", "a length unit", source, number))
        else:
            raise wrong
    return seconds, extra


def _unit_in(name: str, column: str, si: str, what: str, source: str, number: int) -> float:
    """SI units per unit of a header cell ``<column> [<unit>]``."""
    text = name[len(column):].strip()
    if not (text.startswith("[") and text.endswith("]") and text[1:-1].strip()):
        raise DescriptionError(f"{source}: line {number}: the {column} column names its unit, e.g. "
                               f"'{column} [{'min' if si == 's' else 'mm'}]', got {name!r}")
    unit = text[1:-1].strip()
    try:
        return float(registry().Quantity(1.0, unit).to(si).magnitude)
    except pint.errors.DimensionalityError:
        raise DescriptionError(f"{source}: line {number}: {unit!r} is not {what}") from None
    except _UNREADABLE_UNIT:
        raise DescriptionError(f"{source}: line {number}: unknown {column} unit {unit!r}") from None


def _kind(quantity: str, sensors: Collection[str] | None, air: str | None, where: str) -> str:
    """"temperature", "length" (D) or "positioning" (E)."""
    if quantity == ELONGATION_PROBE:
        return "length"
    if quantity == POSITIONING_QUANTITY:
        return "positioning"
    if quantity == ELONGATION_QUANTITY:
        raise DescriptionError(f"{where}: the long format names the elongation {ELONGATION_PROBE} with a length "
                               f"unit (e.g. {ELONGATION_PROBE},12.5,um), not {ELONGATION_QUANTITY}")
    if sensors is not None and quantity not in sensors and quantity != air:
        known = [*sensors, *([air] if air else []), ELONGATION_PROBE, POSITIONING_QUANTITY]
        raise DescriptionError(f"{where}: unknown quantity {quantity!r}; expected one of {', '.join(known)}")
    return "temperature"


def check_value_range(kind: str, value: float, written: str, where: str) -> None:
    """A temperature [°C] within TEMPERATURE_LIMIT, a length (D, E) [µm] within LENGTH_LIMIT (a
    reading of 1e308 µm is finite, but no elongation, and overflows whatever squares it).

    Raises
    ------
    DescriptionError
        One line: ``where``, the value as ``written`` and the accepted range.
    """
    limit, si = (TEMPERATURE_LIMIT, value + KELVIN_OFFSET) if kind == "temperature" else (LENGTH_LIMIT, value * 1e-6)
    if limit.violated_by(si):
        raise DescriptionError(f"{where}: {written} lies outside the accepted range, {limit.describe()}")


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
        except _UNREADABLE_UNIT:
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
