"""Physical quantities written with their units in a description, converted to SI.

A description states every dimensional value as a string ``"<number> <unit>"`` (for
example ``"32 mm"``, ``"396 rpm"``, ``"20 degC"``, ``"1.25e-3 m^2*K/W"``), parsed with
pint and stored as a float in SI units (K for temperatures, rad/s for speeds).  A bare
number is accepted only for dimensionless quantities, so a unit is never guessed.

Every value must be finite, and the quantities with a :class:`Limit` must lie inside it:
ranges no machine-tool feed drive leaves, stated with their reason, so that a typo (``20 K``
for ``20 degC``, ``1e30 rpm``) is an error at the description rather than a crash, a hang or
a nonsense result later.  A rotational speed written per unit time without an angle
(``1/min``, ``Hz``) counts revolutions, as datasheets mean it (pint alone would read it as
radians, 2 pi too slow); ``rev`` and ``r`` (``rev/min``, ``r/min``, the ISO symbol) are
revolutions, as pint's ``rpm``.
"""

from __future__ import annotations

import math
import re
import sys
import tokenize
from dataclasses import dataclass
from functools import lru_cache
from typing import Annotated

from pydantic import BeforeValidator

from ..constants import cache_root


def _import_pint():
    """pint, imported without its support for dask arrays where dask is not imported yet.

    ``pint.compat`` imports ``dask.base`` wherever dask is installed, and dask imports jinja2:
    85 ms of the 0.48 s every command spends importing (``python -X importtime``), for
    quantities of dask arrays, which feedtherm never forms.  So pint is imported with dask
    marked absent in ``sys.modules`` (an import of it fails, ``find_spec`` finds none), and
    the mark is taken away at once: a later ``import dask`` (a batch on a Dask cluster) imports
    it as usual.  Where dask is imported already (a Dask worker), pint finds it as it would.
    """
    if "pint" in sys.modules or "dask" in sys.modules:
        import pint

        return pint
    sys.modules["dask"] = None
    try:
        import pint
    finally:
        if sys.modules.get("dask", False) is None:
            del sys.modules["dask"]
    return pint


pint = _import_pint()

_NUMBER_AND_UNIT = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")
_KELVIN_AT_0C = 273.15


@dataclass(frozen=True)
class Limit:
    """The range ``low..high`` [``si``] a quantity must lie in, shown in ``unit`` with its reason.

    ``magnitude``: the limit applies to the absolute value (signed quantities such as a
    direction of rotation).
    """

    low: float
    high: float
    si: str
    unit: str
    reason: str
    magnitude: bool = False

    def violated_by(self, si_value: float) -> bool:
        v = abs(si_value) if self.magnitude else si_value
        return not self.low <= v <= self.high

    def describe(self) -> str:
        low, high = (float(registry().Quantity(x, self.si).to(self.unit).magnitude) for x in (self.low, self.high))
        span = f"|value| <= {high:g} {self.unit}" if self.magnitude else f"{low:g} to {high:g} {self.unit}"
        return f"{span.rstrip()} ({self.reason})"


#: The ranges of the limited quantities (docs/system-description.md, "Accepted ranges").
TEMPERATURE_LIMIT = Limit(_KELVIN_AT_0C - 150.0, _KELVIN_AT_0C + 1000.0, "K", "degC",
                          "the range of the air and lubricant properties feedtherm uses")
ROTATIONAL_SPEED_LIMIT = Limit(0.0, 100_000 * 2 * math.pi / 60, "rad/s", "rpm",
                               "faster than any machine-tool drive or spindle", magnitude=True)
LENGTH_LIMIT = Limit(0.0, 100.0, "m", "m", "larger than any machine tool", magnitude=True)
CONDUCTIVITY_LIMIT = Limit(0.0, 5000.0, "W/(m*K)", "W/(m*K)", "above every solid's, diamond's 2,200 included")
POWER_LIMIT = Limit(0.0, 1e6, "W", "W", "a megawatt is beyond any feed drive's heat")
DENSITY_LIMIT = Limit(0.0, 25_000.0, "kg/m^3", "kg/m^3", "denser than any material, osmium's 22,600 included")
SPECIFIC_HEAT_LIMIT = Limit(0.0, 20_000.0, "J/(kg*K)", "J/(kg*K)", "above every material's, hydrogen's 14,300 included")
EXPANSION_LIMIT = Limit(0.0, 1e-3, "1/K", "1/K", "ten times a polymer's")
MODULUS_LIMIT = Limit(0.0, 1e13, "Pa", "GPa", "ten times diamond's")
AREA_LIMIT = Limit(0.0, 1e4, "m^2", "m^2", "100 m square, larger than any machine tool")
FORCE_LIMIT = Limit(0.0, 1e7, "N", "N", "a thousand tonnes, beyond any feed drive's load or preload", magnitude=True)
TORQUE_LIMIT = Limit(0.0, 1e5, "N*m", "N*m", "beyond any feed drive's motor")
MASS_LIMIT = Limit(0.0, 1e6, "kg", "kg", "beyond any machine tool's moving mass")
HTC_LIMIT = Limit(0.0, 1e10, "W/(m^2*K)", "W/(m^2*K)",
                  "ten times the penalty coefficients that hold a face at a temperature")
TEMPERATURE_DIFFERENCE_LIMIT = Limit(0.0, 1000.0, "K", "K", "the span of the accepted temperatures")
LINEAR_SPEED_LIMIT = Limit(0.0, 100.0, "m/s", "m/min", "a 6,000 m/min table, or a gale in the room", magnitude=True)
DURATION_LIMIT = Limit(0.0, 1e8, "s", "h", "three years")
KINEMATIC_VISCOSITY_LIMIT = Limit(0.0, 0.1, "m^2/s", "mm^2/s",
                                  "sixty-odd times the thickest ISO grade's, VG 1500 at 40 degC: an oil that thick "
                                  "no longer flows")
DYNAMIC_VISCOSITY_LIMIT = Limit(0.0, 1e4, "Pa*s", "Pa*s",
                                "ten times a stiff grease's apparent viscosity at low shear, 10^2-10^3 Pa s")
PRESSURE_VISCOSITY_LIMIT = Limit(0.0, 1e-6, "1/Pa", "1/GPa", "fifty times a mineral oil's, about 20 1/GPa")
#: A contact resistance from a soldered joint's to an insulating one's (Madhusudana, Thermal Contact
#: Conductance, 2nd ed. 2014, ch. 1: metal joints 1e-5 to 1e-2 m^2 K/W).
CONTACT_RESISTANCE_LIMIT = Limit(1e-7, 1e4, "m^2*K/W", "m^2*K/W",
                                 "from a fifth of a 25 um solder layer's 5e-7, below which two parts are one, to "
                                 "260 m of still air, beyond which a joint conducts nothing but holds its parts")
TORQUE_CONSTANT_LIMIT = Limit(1e-4, 1e3, "N*m/A", "N*m/A",
                              "a micromotor's 1e-3 N m/A to a large torque motor's 100 N m/A, a decade to spare")
RESISTANCE_LIMIT = Limit(1e-4, 1e4, "ohm", "ohm",
                         "a large torque motor's milliohms to a micromotor's hundreds of ohms, a decade to spare")
ROTATIONAL_DAMPING_LIMIT = Limit(0.0, 100.0, "N*m*s/rad", "N*m*s/rad",
                                 "100 N m of drag at 1 rad/s, beyond any motor's or bearing's viscous drag")
ANGLE_LIMIT = Limit(0.0, math.pi / 2.0, "rad", "deg",
                    "a flank or a contact normal lies within a quarter turn of the axis' normal plane")
#: The smallest size [m] a description may state (:data:`PosLength`), with its reason.
SIZE_MINIMUM = 1e-6
SIZE_MINIMUM_REASON = ("no part, bore or feature of a feed drive is made smaller and no mesh resolves it; two solids "
                       "closer than this touch for check (system/topology.py)")
#: A share of a whole (a source's heat into one of its parts).
FRACTION_LIMIT = Limit(0.0, 1.0, "", "", "a share of the whole")
#: Factors on a model's heat or coefficient (set by calibration and perturbation studies).
FACTOR_LIMIT = Limit(0.01, 100.0, "", "", "a model off by more than a hundred either way is another model, not a "
                     "correction of it")

#: What pint's parser may raise on a unit it cannot read: besides its own errors, the tokenizer's
#: (``"2 ("``), an assertion of its expression tree (``"1**"``), a bad exponent or operand.
_UNREADABLE = (pint.errors.PintError, AttributeError, TypeError, SyntaxError, AssertionError, tokenize.TokenError,
               ValueError, KeyError, IndexError, ZeroDivisionError, OverflowError)

#: The unit a bare number's hint suggests, where it is not the SI unit.
_HINT_UNITS = {"m": "mm", "rad/s": "rpm", "m^2": "mm^2"}


@lru_cache(maxsize=1)
def registry() -> pint.UnitRegistry:
    """The one unit registry of feedtherm, built lazily.

    Parsing pint's definitions takes about 0.5 s, reading them back from pint's disk cache
    (under :func:`~feedtherm.constants.cache_root`) 0.02 s; a cache that cannot be written or
    read (a read-only home, a file cut short) costs only that time.
    """
    try:
        return pint.UnitRegistry(cache_folder=cache_root() / "pint")
    except Exception:  # noqa: BLE001 - a cache must never stop a command
        return pint.UnitRegistry()


#: ``rev`` and ``r`` as whole words of a unit: data sheets' revolutions (``rev/min``, ``r/min``), which
#: pint does not define.  Rewritten in the text rather than defined in the registry: ``r`` there would
#: also parse ``hr`` and ``yr`` as hecto- and yocto-revolutions.
_REVOLUTION = re.compile(r"(?<![A-Za-z0-9_])(?:revs?|r)(?![A-Za-z0-9_])")


def _pint_unit(unit: str) -> str:
    """``unit`` as pint reads it: ``rev`` and ``r`` spelt ``revolution``."""
    return _REVOLUTION.sub("revolution", unit)


def _counts_revolutions(quantity) -> bool:
    """True for a speed written per unit time without an angle (``1/min``, ``Hz``)."""
    return "radian" not in quantity.to_root_units()._units


def to_si(value: object, si_unit: str, *, sign: str = "any", limit: Limit | None = None,
          hint: str | None = None) -> float:
    """Convert ``"<number> <unit>"`` to a float in ``si_unit``.

    Parameters
    ----------
    value : str or float
        The written quantity; a bare number only where ``si_unit`` is dimensionless.
    si_unit : str
        Target unit, e.g. ``"m"``, ``"K"``, ``"rad/s"``, ``""`` for dimensionless.
    sign : {"any", "positive", "nonnegative"}
        Constraint on the converted value (temperatures are checked in kelvin).
    limit : Limit, optional
        The range the converted value must lie in.
    hint : str, optional
        The unit a bare number's message suggests (default: a usual one for ``si_unit``).

    Raises
    ------
    ValueError
        With a one-line reason: no unit, unknown unit, wrong dimension, wrong sign, not
        finite, outside ``limit``.
    """
    if isinstance(value, bool):
        raise ValueError(f"expected a quantity, got {value!r}")
    suggestion = hint or _HINT_UNITS.get(si_unit, si_unit)
    if isinstance(value, (int, float)):
        if si_unit:
            raise ValueError(f"{value!r} has no unit; write it with one, e.g. \"{value} {suggestion}\"")
        number, unit = float(value), ""
    elif isinstance(value, str):
        match = _NUMBER_AND_UNIT.match(value)
        if not match:
            raise ValueError(_not_a_quantity(value))
        number, unit = float(match.group(1)), match.group(2)
        if si_unit and not unit:
            raise ValueError(f"{value!r} has no unit; write it with one, e.g. \"{value.strip()} {suggestion}\"")
    else:
        raise ValueError(f"expected a quantity such as \"1 {si_unit or '1'}\", got {value!r}")
    if not math.isfinite(number):
        raise ValueError(f"must be a finite number, got {value!r}")
    try:
        converted = _converted(number, unit, si_unit)
    except pint.errors.UndefinedUnitError:
        raise ValueError(f"unknown unit {unit!r} in {value!r}") from None
    except pint.errors.DimensionalityError:
        raise ValueError(f"{value!r} is not convertible to {si_unit or 'a dimensionless number'}") from None
    except _UNREADABLE:
        raise ValueError(f"cannot read the unit of {value!r}") from None
    if not math.isfinite(converted):
        raise ValueError(f"must be a finite number, got {value!r} ({converted:g} {si_unit or ''})".replace(" )", ")"))
    out_of_range = limit is not None and limit.violated_by(converted)
    # an absolute temperature below its range is out of range, not "negative"; a contact
    # resistance of 1e-300 is out of range, one of -1 is not positive
    if out_of_range and limit.low > 0 and (converted > 0 or limit is TEMPERATURE_LIMIT):
        raise ValueError(f"{value!r} lies outside the accepted range, {limit.describe()}{_typo(number, unit, limit)}")
    if sign == "positive" and not converted > 0:
        raise ValueError(f"must be positive, got {value!r}")
    if sign == "nonnegative" and not converted >= 0:
        raise ValueError(f"must not be negative, got {value!r}")
    if out_of_range:
        raise ValueError(f"{value!r} lies outside the accepted range, {limit.describe()}")
    return converted


def _not_a_quantity(text: str) -> str:
    """Why ``text`` is no ``"<number> <unit>"``: an infinite number (``"inf N"``) is not finite."""
    if re.match(r"^\s*[-+]?(inf|nan)", text, re.IGNORECASE):
        return f"must be a finite number, got {text!r}"
    return f"{text!r} is not a quantity of the form \"<number> <unit>\""


@lru_cache(maxsize=8192)
def _converted(number: float, unit: str, si_unit: str) -> float:
    """``number`` ``unit`` in ``si_unit``; a description is validated many times over in a study (each
    machine, each worker), and pint takes about 0.3 ms a conversion, so the conversions are kept."""
    quantity = registry().Quantity(number, _pint_unit(unit) or "dimensionless")
    converted = float(quantity.to(si_unit or "dimensionless").magnitude)
    if si_unit == "rad/s" and _counts_revolutions(quantity):
        converted *= 2.0 * math.pi
    return converted


def _typo(number: float, unit: str, limit: Limit) -> str:
    """A hint where a temperature written in K would be plausible in degC (``20 K``)."""
    if limit is TEMPERATURE_LIMIT and unit in ("K", "kelvin") and not limit.violated_by(number + _KELVIN_AT_0C):
        return f"; did you mean \"{number:g} degC\"?"
    return ""


@dataclass(frozen=True)
class SIUnit:
    """Marks a quantity field with the SI unit its value is stored in (see :func:`same_dimension`),
    and the rules its validator applies: ``sign``, ``limit`` and, for sizes, the smallest nonzero
    ``minimum`` [``unit``] (the reference of the description's keys shows them)."""

    unit: str
    sign: str = "any"
    limit: Limit | None = None
    minimum: float | None = None


def _quantity(si_unit: str, sign: str = "any", limit: Limit | None = None, hint: str | None = None):
    return Annotated[float, BeforeValidator(lambda v: to_si(v, si_unit, sign=sign, limit=limit, hint=hint)),
                     SIUnit(si_unit, sign, limit)]


# Annotated float types: SI value after validation.  "Pos" = strictly positive.
Length = _quantity("m", limit=LENGTH_LIMIT)
#: A size (a box's edge, a cylinder's length or diameter, a hole's, a convection length, a lead, a
#: bearing's bore): positive, and at least :data:`SIZE_MINIMUM`.
PosLength = Annotated[float, BeforeValidator(lambda v: _size(v, "positive")),
                      SIUnit("m", "positive", LENGTH_LIMIT, SIZE_MINIMUM)]
#: A size that may be 0 for "none" (a solid cylinder's inner diameter), else at least SIZE_MINIMUM.
NonNegLength = Annotated[float, BeforeValidator(lambda v: _size(v, "nonnegative")),
                         SIUnit("m", "nonnegative", LENGTH_LIMIT, SIZE_MINIMUM)]
#: A positive length that is no size: a displacement's spread (a displacement sensor resolves far
#: below SIZE_MINIMUM).
PosDisplacement = _quantity("m", "positive", LENGTH_LIMIT)
PosArea = _quantity("m^2", "positive", AREA_LIMIT)
PosDensity = _quantity("kg/m^3", "positive", DENSITY_LIMIT)
PosConductivity = _quantity("W/(m*K)", "positive", CONDUCTIVITY_LIMIT)
PosSpecificHeat = _quantity("J/(kg*K)", "positive", SPECIFIC_HEAT_LIMIT)
PosExpansion = _quantity("1/K", "positive", EXPANSION_LIMIT)
PosModulus = _quantity("Pa", "positive", MODULUS_LIMIT)
PosContactResistance = _quantity("m^2*K/W", "positive", CONTACT_RESISTANCE_LIMIT)
PosHeatTransferCoefficient = _quantity("W/(m^2*K)", "positive", HTC_LIMIT)
Power = _quantity("W", "nonnegative", POWER_LIMIT)
Temperature = _quantity("K", "positive", TEMPERATURE_LIMIT, hint="degC")  # absolute
PosTemperatureDifference = _quantity("K", "positive", TEMPERATURE_DIFFERENCE_LIMIT, hint="K")
NonNegTemperatureDifference = _quantity("K", "nonnegative", TEMPERATURE_DIFFERENCE_LIMIT, hint="K")
AngularSpeed = _quantity("rad/s", limit=ROTATIONAL_SPEED_LIMIT)  # signed: the sign is the direction of rotation
Speed = _quantity("m/s", limit=LINEAR_SPEED_LIMIT)
NonNegSpeed = _quantity("m/s", "nonnegative", LINEAR_SPEED_LIMIT)
PosDuration = _quantity("s", "positive", DURATION_LIMIT)
NonNegDuration = _quantity("s", "nonnegative", DURATION_LIMIT)
PosForce = _quantity("N", "positive", FORCE_LIMIT)
NonNegForce = _quantity("N", "nonnegative", FORCE_LIMIT)
NonNegTorque = _quantity("N*m", "nonnegative", TORQUE_LIMIT)
PosTorque = _quantity("N*m", "positive", TORQUE_LIMIT)
PosTorqueConstant = _quantity("N*m/A", "positive", TORQUE_CONSTANT_LIMIT)  # a motor's torque per A r.m.s.
PosResistance = _quantity("ohm", "positive", RESISTANCE_LIMIT)
NonNegRotationalDamping = _quantity("N*m*s/rad", "nonnegative", ROTATIONAL_DAMPING_LIMIT)  # drag torque per angular speed
PosKinematicViscosity = _quantity("m^2/s", "positive", KINEMATIC_VISCOSITY_LIMIT)
PosDynamicViscosity = _quantity("Pa*s", "positive", DYNAMIC_VISCOSITY_LIMIT)
PosPressureViscosityCoefficient = _quantity("1/Pa", "positive", PRESSURE_VISCOSITY_LIMIT)  # Barus alpha of a lubricant
PosMass = _quantity("kg", "positive", MASS_LIMIT)
Fraction = Annotated[float, BeforeValidator(lambda v: _fraction(v)), SIUnit("", "nonnegative", FRACTION_LIMIT)]
PosDimensionless = _quantity("", "positive")
NonNegAngle = _quantity("rad", "nonnegative", ANGLE_LIMIT)
#: A factor on a model's heat or coefficient (``heat_factor``, ``chtc_factor``).
PosFactor = _quantity("", "positive", FACTOR_LIMIT)


def _size(value: object, sign: str) -> float:
    """A size in metres: ``sign`` and :data:`LENGTH_LIMIT` as any length, and not below
    :data:`SIZE_MINIMUM` (0 stays 0 where ``sign`` is ``"nonnegative"``: none)."""
    metres = to_si(value, "m", sign=sign, limit=LENGTH_LIMIT)
    if metres != 0.0 and metres < SIZE_MINIMUM:
        raise ValueError(f"{value!r} is below the smallest accepted size, 1 µm ({SIZE_MINIMUM_REASON})")
    return metres


def _fraction(value: object) -> float:
    number = to_si(value, "")
    if FRACTION_LIMIT.violated_by(number):
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
        if not math.isfinite(value):
            raise ValueError(f"must be a finite number, got {value!r}")
        return float(value)
    if not isinstance(value, str):
        raise ValueError(f"expected a number or a quantity, got {value!r}")
    match = _NUMBER_AND_UNIT.match(value)
    if not match:
        raise ValueError(_not_a_quantity(value))
    number, unit = float(match.group(1)), match.group(2)
    try:
        quantity = registry().Quantity(number, _pint_unit(unit) or "dimensionless")
        converted = float(quantity.to_base_units().magnitude)
    except _UNREADABLE:
        raise ValueError(f"cannot read the unit of {value!r}") from None
    if not math.isfinite(converted):
        raise ValueError(f"must be a finite number, got {value!r}")
    return converted


def same_dimension(value: object, si_unit: str) -> bool:
    """True when ``value`` (a bare number or ``"<number> <unit>"``) has the dimension of ``si_unit``.

    A bare number is dimensionless.  Angles are dimensionless to pint, so ``"1000 rpm"`` has
    the dimension of ``"rad/s"`` (and of ``"1/s"``).
    """
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        unit = ""
    elif isinstance(value, str) and (match := _NUMBER_AND_UNIT.match(value)):
        unit = match.group(2)
    else:
        return False
    ureg = registry()
    try:
        return ureg.Quantity(1, _pint_unit(unit) or "dimensionless").dimensionality == \
            ureg.Quantity(1, si_unit or "dimensionless").dimensionality
    except _UNREADABLE:
        return False
