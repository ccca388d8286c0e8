import math

import pytest
from pydantic import TypeAdapter, ValidationError

from feedtherm.system.quantities import (
    AngularSpeed,
    PosConductivity,
    PosDuration,
    PosForce,
    PosHeatTransferCoefficient,
    PosLength,
    PosTemperatureDifference,
    Power,
    Speed,
    Temperature,
    same_dimension,
    to_base_si,
    to_si,
)


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


# The same shaft speed in every spelling a datasheet uses: 396 rev/min = 396 * 2 pi / 60 rad/s
# = 41.4690 rad/s.  "1/min", "min^-1" and "Hz" carry no angle; an engineer means revolutions.
# "rev" and "r" (the ISO symbol, "r/min") are revolutions too.
@pytest.mark.parametrize("text", ["396 rpm", "396 1/min", "396 min^-1", "6.6 Hz", "6.6 1/s",
                                  "6.6 revolution/second", "41.469023027385 rad/s", "2376 deg/s",
                                  "396 rev/min", "396 r/min", "396 revs/min", "396 rev / min", "6.6 r/s",
                                  "23760 r/h"])
def test_every_spelling_of_a_rotational_speed_gives_the_same_shaft_speed(text):
    assert to_si(text, "rad/s") == pytest.approx(396 * 2 * math.pi / 60, rel=1e-9)


def test_revolutions_spelt_r_leave_other_units_alone():
    # "r" is rewritten as a whole word only: hours and years keep their meaning
    assert to_si("2 hr", "s") == 7200.0
    assert to_si("1 yr", "s") == pytest.approx(365.25 * 86400)
    with pytest.raises(ValueError, match="unknown unit"):
        to_si("396 rr/min", "rad/s")


@pytest.mark.parametrize("value", ["1e400 mm", "inf mm", float("inf"), float("nan")])
def test_values_must_be_finite(value):
    with pytest.raises(ValueError, match="finite|not a quantity"):
        to_si(value, "m" if isinstance(value, str) else "")


@pytest.mark.parametrize(
    "annotation, value, fragment",
    [
        # the typos: 20 K for 20 degC; an absolute zero crossed; a speed beyond any spindle
        (Temperature, "20 K", 'lies outside the accepted range, -150 to 1000 degC (the range of the air and '
                              'lubricant properties feedtherm uses); did you mean "20 degC"?'),
        (Temperature, "-300 degC", "lies outside the accepted range, -150 to 1000 degC"),
        (Temperature, 20, 'has no unit; write it with one, e.g. "20 degC"'),
        (AngularSpeed, "1e30 rpm", "lies outside the accepted range, |value| <= 100000 rpm"),
        (AngularSpeed, "-200000 rpm", "|value| <= 100000 rpm"),
        (PosLength, 10, 'has no unit; write it with one, e.g. "10 mm"'),
        (PosLength, "1e400 mm", "must be a finite number, got '1e400 mm'"),
        (PosLength, "200 m", "|value| <= 100 m"),
        (PosLength, "-5 mm", "must be positive"),  # the sign before the range
        (PosConductivity, "1e30 W/(m*K)", "0 to 5000 W/(m*K)"),
        (Power, "1e30 W", "0 to 1e+06 W"),
        (PosTemperatureDifference, 1, 'e.g. "1 K"'),
        (PosForce, "1e30 N", "|value| <= 1e+07 N"),
        (PosDuration, "1e12 s", "0 to 27777.8 h (three years)"),
        (Speed, "-200 m/s", "|value| <= 6000 m/min"),
        (PosHeatTransferCoefficient, "1e12 W/(m^2*K)", "0 to 1e+10 W/(m^2*K)"),
    ],
)
def test_limits_name_the_range_and_reason(annotation, value, fragment):
    with pytest.raises(ValidationError) as info:
        TypeAdapter(annotation).validate_python(value)
    assert fragment in str(info.value)


def test_limits_accept_the_ends_of_their_ranges():
    assert TypeAdapter(Temperature).validate_python("-150 degC") == pytest.approx(123.15)
    assert TypeAdapter(AngularSpeed).validate_python("-100000 rpm") == pytest.approx(-100000 * 2 * math.pi / 60)
    assert TypeAdapter(PosConductivity).validate_python("5000 W/(m*K)") == 5000.0


def test_loading_a_description_imports_pint_without_dask_and_dask_still_imports_after_it():
    """pint imports dask (and jinja2) wherever dask is installed, 85 ms of every command's start;
    feedtherm imports it without (system/quantities.py).  In a fresh interpreter: a description
    loads and its units convert without dask imported, and dask then imports and works."""
    import subprocess
    import sys

    script = (
        "import sys\n"
        "from feedtherm.system.load import load_system\n"
        "from feedtherm.system.quantities import to_si\n"
        "loaded = load_system('paper')\n"
        "assert to_si('396 rpm', 'rad/s') > 41.4 and to_si('20 degC', 'K') == 293.15\n"
        "assert 'dask' not in sys.modules and 'jinja2' not in sys.modules, 'dask imported'\n"
        "import dask, dask.array\n"
        "assert float(dask.array.ones(4).sum().compute()) == 4.0\n"
    )
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr[-2000:]


@pytest.mark.parametrize("value", ["1**", "2 (", "1 m^", "1 1/", "3 )(", "1 m**"])
def test_a_unit_pints_parser_cannot_read_is_one_valueerror(value):
    # pint's tokenizer raises TokenError ("2 ("), its expression tree an AssertionError ("1**"):
    # both reached `feedtherm correct --x` as tracebacks
    for convert in (lambda v: to_si(v, "m"), to_base_si):
        with pytest.raises(ValueError, match="cannot read the unit"):
            convert(value)
    assert not same_dimension(value, "m")
