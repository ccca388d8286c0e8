import math

import pytest

from feedtherm.errors import DescriptionError
from feedtherm.system.duty_cycle import read_duty_cycle_csv
from feedtherm.system.load import load_system


def test_bundled_duty_cycle_has_a_standstill():
    cycle = load_system("paper").system.duty_cycles["I_then_standstill"]
    assert [s.start for s in cycle.segments] == [0.0, 7200.0]
    assert cycle.segments[1].screw_speed == 0.0 and cycle.segments[1].nut_speed == 0.0
    assert cycle.duration == 10800.0


def test_csv_cycle_reads_signed_speeds(tmp_path):
    path = tmp_path / "cycle.csv"
    path.write_text("time_s,screw_rpm,nut_rpm,ambient_C\n0,396,360,20\n600,-396,-360,21\n1200,0,0,21\n")
    cycle = read_duty_cycle_csv(path, duration=1800.0)
    assert len(cycle.segments) == 3
    assert cycle.segments[1].screw_speed == pytest.approx(-396 * 2 * math.pi / 60)
    assert cycle.segments[1].ambient == pytest.approx(294.15)


@pytest.mark.parametrize(
    "text, fragment",
    [
        ("", "empty"),
        ("time,screw,nut,amb\n0,1,1,20\n", "header must be time_s,screw_rpm,nut_rpm,ambient_C"),
        ("time_s,screw_rpm,nut_rpm,ambient_C\n", "no rows"),
        ("time_s,screw_rpm,nut_rpm,ambient_C\n0,396,360\n", "line 2: expected 4 values"),
        ("time_s,screw_rpm,nut_rpm,ambient_C\n0,fast,360,20\n", "line 2: values must be numbers"),
        ("time_s,screw_rpm,nut_rpm,ambient_C\n10,396,360,20\n", "first segment must start at 0 s"),
        ("time_s,screw_rpm,nut_rpm,ambient_C\n0,396,360,20\n0,1,1,20\n", "segment 1 starts at 0 s"),
        ("time_s,screw_rpm,nut_rpm,ambient_C\n0,396,360,20\n5000,1,1,20\n", "at or after the end"),
        ("time_s,screw_rpm,nut_rpm,ambient_C\n0,396,360,-300\n", "ambient: .-300.0 degC. lies outside the accepted range, -150 to 1000 degC"),
        ("time_s,screw_rpm,nut_rpm,ambient_C\n0,1e30,360,20\n", "screw_speed: .* lies outside the accepted range, \\|value\\| <= 100000 rpm"),
    ],
)
def test_bad_csv_cycles_name_the_line_and_reason(tmp_path, text, fragment):
    path = tmp_path / "cycle.csv"
    path.write_text(text)
    with pytest.raises(DescriptionError, match=fragment) as info:
        read_duty_cycle_csv(path, duration=3600.0)
    assert str(info.value).startswith(str(path))


def test_missing_csv(tmp_path):
    with pytest.raises(DescriptionError, match="no such file"):
        read_duty_cycle_csv(tmp_path / "none.csv", duration=10.0)
