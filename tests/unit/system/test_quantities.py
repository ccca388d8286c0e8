import math

import pytest

from feedtherm.system.quantities import to_si


@pytest.mark.parametrize(
    "text, unit, expected",
    [
        ("32 mm", "m", 0.032),
        ("20 degC", "K", 293.15),
        ("293.15 K", "K", 293.15),
        ("396 rpm", "rad/s", 396 * 2 * math.pi / 60),
        ("-396 rpm", "rad/s", -396 * 2 * math.pi / 60),  # a negative speed is a direction
        ("0.18 m/min", "m/s", 0.003),
        ("1.25e-3 m^2*K/W", "m^2*K/W", 1.25e-3),
        ("100 mm^2/s", "m^2/s", 1e-4),
        ("15 deg", "rad", math.radians(15)),
        ("3 h", "s", 10800.0),
        (0.28, "", 0.28),
    ],
)
def test_quantities_convert_to_si(text, unit, expected):
    assert to_si(text, unit) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize(
    "value, unit, sign, fragment",
    [
        ("32", "m", "any", "has no unit"),
        (32, "m", "any", "has no unit"),
        ("32 furlongz", "m", "any", "unknown unit"),
        ("32 kg", "m", "any", "not convertible to m"),
        ("abc", "m", "any", "not a quantity"),
        ("-32 mm", "m", "positive", "must be positive"),
        ("0 mm", "m", "positive", "must be positive"),
        ("-1 mm", "m", "nonnegative", "must not be negative"),
        ("-300 degC", "K", "positive", "must be positive"),
        (True, "m", "any", "expected a quantity"),
    ],
)
def test_bad_quantities_say_why(value, unit, sign, fragment):
    with pytest.raises(ValueError, match=fragment):
        to_si(value, unit, sign=sign)
