"""Sweep grids as a user types them: values, ranges, strict errors, the full product."""

import pytest

from feedtherm.analysis.sweep import MAX_POINTS, SweepGrid, columns, parse_grid, parse_values
from feedtherm.errors import FeedthermError


@pytest.mark.parametrize(
    "text, expected",
    [
        ("20", (20.0,)),
        ("1116,2214", (1116.0, 2214.0)),
        (" 1116 , 2214 ", (1116.0, 2214.0)),  # spaces around items (a quoted list) are fine
        ("300:2400:300", (300.0, 600.0, 900.0, 1200.0, 1500.0, 1800.0, 2100.0, 2400.0)),
        ("0:1000:300", (0.0, 300.0, 600.0, 900.0)),  # 1000 is not on the grid: not included
        ("300:300:100", (300.0,)),  # a range of one value
        ("-600:600:300", (-600.0, -300.0, 0.0, 300.0, 600.0)),  # signed speeds
        ("0:1:0.1", (0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0)),  # decimal steps end exactly at 1
        ("15:25:2.5", (15.0, 17.5, 20.0, 22.5, 25.0)),
        ("100,300:500:100,1e3", (100.0, 300.0, 400.0, 500.0, 1000.0)),  # values and ranges mixed, order kept
        ("2214,1116", (2214.0, 1116.0)),  # values keep the order they are written in
        ("-360", (-360.0,)),
        ("+.5", (0.5,)),
    ],
)
def test_values_and_ranges(text, expected):
    assert parse_values(text, "--screw-rpm") == expected


def test_a_decimal_range_gives_the_exact_floats():
    # float arithmetic would give 0.30000000000000004 for 3 * 0.1
    assert parse_values("0:0.5:0.1", "--ambient")[3] == 0.3


@pytest.mark.parametrize(
    "text, fragments",
    [
        ("", ["empty list"]),
        ("   ", ["empty list"]),
        ("300,,600", ["empty item", "'300,,600'"]),
        ("300,", ["empty item"]),
        ("fast", ["'fast' is not a number"]),
        ("nan", ["'nan' is not a number"]),
        ("inf", ["'inf' is not a number"]),
        ("1_000", ["'1_000' is not a number"]),
        ("0x10", ["'0x10' is not a number"]),
        ("1e999", ["'1e999' is out of range"]),
        ("300:600", ["range '300:600' must be start:stop:step"]),
        ("300:600:100:1", ["must be start:stop:step"]),
        ("300::100", ["'' in '300::100' is not a number"]),
        ("300:600:x", ["'x' in '300:600:x' is not a number"]),
        ("300:600:0", ["step 0", "must be positive"]),
        ("300:600:-100", ["step -100", "must be positive"]),
        ("600:300:100", ["'600:300:100' is empty", "ranges run upwards"]),
        ("300,300", ["300 is listed twice"]),
        ("0:600:300,600", ["600 is listed twice"]),
        ("0,-0", ["0 is listed twice"]),
        ("0:600:1", ["gives 601 values", f"at most {MAX_POINTS} points"]),
        ("0:1e40:1", ["too many values"]),  # beyond decimal precision: still one clean line
        ("0:400:1,500:700:1", [f"more than {MAX_POINTS} values"]),
    ],
)
def test_strict_errors_name_the_option(text, fragments):
    with pytest.raises(FeedthermError) as info:
        parse_values(text, "--screw-rpm")
    message = str(info.value)
    assert message.startswith("--screw-rpm: ") and "\n" not in message
    for fragment in fragments:
        assert fragment in message, message


def test_the_grid_is_the_full_product_with_the_ambient_fastest():
    grid = parse_grid("396,1116", "360", "20,25")
    assert grid.shape == (2, 1, 2) and len(grid) == 4
    assert grid.points() == [(396.0, 360.0, 20.0), (396.0, 360.0, 25.0), (1116.0, 360.0, 20.0), (1116.0, 360.0, 25.0)]
    assert grid.varied == ["screw_rpm", "ambient_C"]


def test_a_grid_of_one_point_varies_nothing():
    grid = parse_grid("396", "360", "20")
    assert grid.points() == [(396.0, 360.0, 20.0)] and grid.varied == []


def test_a_hand_counted_grid_of_exactly_the_limit_is_accepted():
    # 10 screw speeds (300, 400, ..., 1200) x 5 nut speeds x 10 ambients = 500
    grid = parse_grid("300:1200:100", "-200:200:100", "10:19:1")
    assert grid.shape == (10, 5, 10) and len(grid) == MAX_POINTS


def test_one_point_over_the_limit_is_refused_before_running():
    with pytest.raises(FeedthermError, match=r"the grid has 510 points \(10 screw × 3 nut × 17 ambient\); "
                                             r".* at most 500"):
        parse_grid("300:1200:100", "-100:100:100", "10:26:1")


@pytest.mark.parametrize("ambient", ["-273.15", "-300", "20,-273.15"])
def test_ambients_must_be_above_absolute_zero(ambient):
    with pytest.raises(FeedthermError, match=r"^--ambient: -[0-9.]+ °C is not above absolute zero"):
        parse_grid("300", "0", ambient)


def test_a_cold_but_physical_ambient_is_accepted():
    assert parse_grid("300", "0", "-273.1").ambient_C == (-273.1,)


def test_a_single_drive_takes_only_a_resting_nut():
    assert parse_grid("500:1500:500", "0", "20", drive="single").nut_rpm == (0.0,)
    assert parse_grid("500", "-0", "20", drive="single").nut_rpm == (-0.0,)
    for nut in ("100", "0,100", "0:200:100"):
        with pytest.raises(FeedthermError, match=r'^--nut-rpm: a single drive \(kinematics.drive = "single"\) '
                                                 r'.* give --nut-rpm 0'):
            parse_grid("500", nut, "20", drive="single")


def test_each_list_is_checked_under_its_own_option():
    for args, option in [(("x", "0", "20"), "--screw-rpm"), (("300", "x", "20"), "--nut-rpm"),
                         (("300", "0", "x"), "--ambient")]:
        with pytest.raises(FeedthermError, match=f"^{option}: 'x' is not a number"):
            parse_grid(*args)


def test_the_columns_follow_the_sensors_in_order():
    assert columns(["T1", "T2"]) == [
        "screw_rpm", "nut_rpm", "ambient_C", "table_speed_m_per_min",
        "final_T1", "final_T2", "final_D_um", "steady_T1", "steady_T2", "steady_D_um",
        "equilibrium_time_s", "energy_balance_error", "motor_duty"]


def test_grid_axes_in_column_order():
    grid = SweepGrid((1.0, 2.0), (0.0,), (20.0,))
    assert list(grid.axes) == ["screw_rpm", "nut_rpm", "ambient_C"] and grid.varied == ["screw_rpm"]
