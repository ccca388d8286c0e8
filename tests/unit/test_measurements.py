import pytest

from feedtherm.system.measurements import read_measurements
from feedtherm.benches import bench
from feedtherm.errors import DescriptionError

SENSORS = ["T1", "T2", "T3", "T4", "T5"]


def test_bundled_measurements_equal_tables_6_and_7():
    data = read_measurements("bundled:paper", sensors=SENSORS)
    assert len(data.rows) == 30
    measured = {(r.condition, r.quantity): r.measured for r in data.rows}
    for row in bench("paper").table(6):
        assert measured[(row["condition"], row["point"])] == float(row["measured_C"])
    for row in bench("paper").table(7):
        assert measured[(row["condition"], "D_um")] == float(row["measured_um"])
    assert data.equilibrium_min == {"I": 120.0, "II": 100.0, "III": 90.0, "IV": 70.0, "V": 110.0}


@pytest.mark.parametrize(
    "text, fragment",
    [
        ("", "empty"),
        ("cond,quantity,unit,measured\nI,T1,C,27\n", "line 1: header must be"),
        ("condition,quantity,unit,measured\nI,T9,C,27\n", "line 2: unknown quantity 'T9'"),
        ("condition,quantity,unit,measured\nI,T1,K,27\n", "line 2: T1 must be in C"),
        ("condition,quantity,unit,measured\nI,D_um,mm,27\n", "line 2: D_um must be in um"),
        ("condition,quantity,unit,measured\nI,T1,C,warm\n", "line 2: values must be numbers"),
        ("condition,quantity,unit,measured\nI,T1,C,27\nI,T1,C,28\n", "line 3: I T1 appears twice"),
        ("condition,quantity,unit,measured\nI,T1,C\n", "line 2: expected 4 values"),
        ("condition,quantity,unit,measured\n", "no rows"),
    ],
)
def test_bad_measurement_files_name_the_line(tmp_path, text, fragment):
    path = tmp_path / "m.csv"
    path.write_text(text)
    with pytest.raises(DescriptionError, match=fragment):
        read_measurements(str(path), sensors=SENSORS)


def test_missing_file(tmp_path):
    with pytest.raises(DescriptionError, match="no such measurement file"):
        read_measurements(str(tmp_path / "none.csv"))
