"""Physical quantities written with their units in a description, converted to SI.

A description states every dimensional value as a string ``"<number> <unit>"`` (for
example ``"32 mm"``, ``"396 rpm"``, ``"20 degC"``, ``"1.25e-3 m^2*K/W"``), parsed with
pint and stored as a float in SI units (K for temperatures, rad/s for speeds).  A bare
number is accepted only for dimensionless quantities, so a unit is never guessed.
"""

from __future__ import annotations

import re
from functools import lru_cache
from typing import Annotated

import pint
from pydantic import BeforeValidator

_NUMBER_AND_UNIT = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


@lru_cache(maxsize=1)
def registry() -> pint.UnitRegistry:
    """The one unit registry of feedtherm (built lazily: pint takes ~0.1 s to load)."""
    return pint.UnitRegistry()


def to_si(value: object, si_unit: str, *, sign: str = "any") -> float:
    """Convert ``"<number> <unit>"`` to a float in ``si_unit``.

    Parameters
    ----------
    value : str or float
        The written quantity; a bare number only where ``si_unit`` is dimensionless.
    si_unit : str
        Target unit, e.g. ``"m"``, ``"K"``, ``"rad/s"``, ``""`` for dimensionless.
    sign : {"any", "positive", "nonnegative"}
        Constraint on the converted value (temperatures are checked in kelvin).

    Raises
    ------
    ValueError
        With a one-line reason: no unit, unknown unit, wrong dimension, wrong sign.
    """
    if isinstance(value, bool):
        raise ValueError(f"expected a quantity, got {value!r}")
    ureg = registry()
    if isinstance(value, (int, float)):
        if si_unit:
            raise ValueError(f"{value!r} has no unit; write it as \"{value} {si_unit}\"")
        number, unit = float(value), ""
    elif isinstance(value, str):
        match = _NUMBER_AND_UNIT.match(value)
        if not match:
            raise ValueError(f"{value!r} is not a quantity of the form \"<number> <unit>\"")
        number, unit = float(match.group(1)), match.group(2)
        if si_unit and not unit:
            raise ValueError(f"{value!r} has no unit; write it as \"{value} {si_unit}\"")
    else:
        raise ValueError(f"expected a quantity such as \"1 {si_unit or '1'}\", got {value!r}")
    try:
        quantity = ureg.Quantity(number, unit or "dimensionless")
        converted = float(quantity.to(si_unit or "dimensionless").magnitude)
    except pint.errors.UndefinedUnitError:
        raise ValueError(f"unknown unit {unit!r} in {value!r}") from None
    except pint.errors.DimensionalityError:
        raise ValueError(f"{value!r} is not convertible to {si_unit or 'a dimensionless number'}") from None
    except (pint.errors.PintError, AttributeError, TypeError, SyntaxError):
        raise ValueError(f"cannot read the unit of {value!r}") from None
    if sign == "positive" and not converted > 0:
        raise ValueError(f"must be positive, got {value!r}")
    if sign == "nonnegative" and not converted >= 0:
        raise ValueError(f"must not be negative, got {value!r}")
    return converted


def _quantity(si_unit: str, sign: str = "any"):
    return Annotated[float, BeforeValidator(lambda v: to_si(v, si_unit, sign=sign))]


# Annotated float types: SI value after validation.  "Pos" = strictly positive.
Length = _quantity("m")
PosLength = _quantity("m", "positive")
NonNegLength = _quantity("m", "nonnegative")
PosArea = _quantity("m^2", "positive")
PosDensity = _quantity("kg/m^3", "positive")
PosConductivity = _quantity("W/(m*K)", "positive")
PosSpecificHeat = _quantity("J/(kg*K)", "positive")
PosExpansion = _quantity("1/K", "positive")
PosModulus = _quantity("Pa", "positive")
PosContactResistance = _quantity("m^2*K/W", "positive")
PosHeatTransferCoefficient = _quantity("W/(m^2*K)", "positive")
Power = _quantity("W", "nonnegative")
Temperature = _quantity("K", "positive")  # absolute: must be above 0 K
PosTemperatureDifference = _quantity("K", "positive")
AngularSpeed = _quantity("rad/s")  # signed: the sign is the direction of rotation
Speed = _quantity("m/s")
NonNegSpeed = _quantity("m/s", "nonnegative")
PosDuration = _quantity("s", "positive")
NonNegDuration = _quantity("s", "nonnegative")
PosForce = _quantity("N", "positive")
NonNegForce = _quantity("N", "nonnegative")
NonNegTorque = _quantity("N*m", "nonnegative")
PosTorque = _quantity("N*m", "positive")
PosTorqueConstant = _quantity("N*m/A", "positive")  # a motor's torque per A r.m.s.
PosResistance = _quantity("ohm", "positive")
NonNegRotationalDamping = _quantity("N*m*s/rad", "nonnegative")  # drag torque per angular speed
PosKinematicViscosity = _quantity("m^2/s", "positive")
PosDynamicViscosity = _quantity("Pa*s", "positive")
PosPressureViscosityCoefficient = _quantity("1/Pa", "positive")  # Barus alpha of a lubricant
PosMass = _quantity("kg", "positive")
Fraction = Annotated[float, BeforeValidator(lambda v: _fraction(v))]
PosDimensionless = _quantity("", "positive")
NonNegAngle = _quantity("rad", "nonnegative")


def _fraction(value: object) -> float:
    number = to_si(value, "")
    if not 0.0 <= number <= 1.0:
        raise ValueError(f"must lie between 0 and 1, got {value!r}")
    return number


def to_base_si(value: object) -> float:
    """A bound such as ``"500 N"``, ``"1e-4 m^2*K/W"`` or ``0.1`` in coherent SI base units.

    Used where the target unit is that of another value (calibration bounds): the value is
    converted to SI base units (N, m, K, ...), the units every description value is stored in.
    """
    if isinstance(value, bool):
        raise ValueError(f"expected a number or a quantity, got {value!r}")
    if isinstance(value, (int, float)):
        return float(value)
    if not isinstance(value, str):
        raise ValueError(f"expected a number or a quantity, got {value!r}")
    match = _NUMBER_AND_UNIT.match(value)
    if not match:
        raise ValueError(f"{value!r} is not a quantity of the form \"<number> <unit>\"")
    number, unit = float(match.group(1)), match.group(2)
    try:
        quantity = registry().Quantity(number, unit or "dimensionless")
        return float(quantity.to_base_units().magnitude)
    except (pint.errors.PintError, AttributeError, TypeError, SyntaxError):
        raise ValueError(f"cannot read the unit of {value!r}") from None
