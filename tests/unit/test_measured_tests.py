"""A test's measurements: positioning deviations at targets, the room's air, a test column; and
each way such a file can be wrong, refused in one line naming the file and the line."""

import numpy as np
import pytest

from feedtherm.errors import DescriptionError
from feedtherm.system.measurement_series import target_key, target_of
from feedtherm.system.measurements import read_measurements

HEADER = "test,time [s],quantity,value,unit,uncertainty,target [mm]\n"
TRAVEL = (0.100, 0.500)  # the table's positions [m]
VISITS = {"drift": [0.110, 0.300, 0.490], "idle": []}


def _read(tmp_path, text):
    path = tmp_path / "m.csv"
    path.write_text(text)
    return read_measurements(str(path), sensors=["T1"], conditions=["drift", "idle"], air="ambient",
                             travel=TRAVEL, visits=VISITS, run_end={"drift": 3600.0, "idle": 3600.0})


def test_targets_air_and_sensors_each_go_their_own_way(tmp_path):
    text = (HEADER
            + "drift,0,ambient,20.1,degC,0.05,\n"
            + "drift,0,T1,21.0,degC,0.1,\n"
            + "drift,19,E,0.0080,mm,0.001,110\n"     # 8 µm at 110 mm
            + "drift,39,E,11,um,1,0.49 m\n".replace("0.49 m", "490")
            + "drift,600,ambient,20.3,degC,0.05,\n"
            + "drift,619,E,12.5,um,1,110\n"
            + "drift,639,E,13,um,1,490\n")
    data = _read(tmp_path, text)
    assert [r.quantity for r in data.rows] == ["T1"]  # what the readers of finals take, as before
    np.testing.assert_allclose(data.air["drift"].values, [20.1, 20.3])
    e110, e490 = data.positioning_of("drift")
    assert (e110.quantity, e110.target, e110.unit) == ("E@110mm", pytest.approx(0.110), "um")
    np.testing.assert_allclose(e110.series.values, [8.0, 12.5])
    np.testing.assert_allclose(e110.series.uncertainties, [1.0, 1.0])  # 0.001 mm
    np.testing.assert_allclose(e490.series.times, [39.0, 639.0])
    assert data.runs() == ["drift"]


def test_target_names_round_trip():
    assert target_key(0.110) == "E@110mm"
    assert target_key(0.1105) == "E@110.5mm"
    assert target_of("E@110.5mm") == pytest.approx(0.1105)
    assert target_of("T1") is None and target_of("E@abcmm") is None


def test_a_target_column_in_metres(tmp_path):
    text = "condition,time [min],quantity,value,unit,target [m]\ndrift,1,E,3,um,0.3\n"
    (e,) = _read(tmp_path, text).positioning
    assert e.target == pytest.approx(0.300) and e.series.times[0] == 60.0


@pytest.mark.parametrize("text, fragment", [
    # a target outside the table's travel
    (HEADER + "drift,19,E,8,um,1,90\n", "line 2: target 90 mm lies outside the table's travel, 100..500 mm"),
    # a target the test never visits
    (HEADER + "drift,19,E,8,um,1,200\n", "line 2: drift never visits target 200 mm (its measuring stops hold the "
                                         "table at 110, 300, 490 mm)"),
    (HEADER + "idle,19,E,8,um,1,110\n", "line 2: idle never visits target 110 mm (it has no measuring stops)"),
    # a time that goes back within one target's series
    (HEADER + "drift,619,E,8,um,1,110\ndrift,19,E,9,um,1,110\n", "line 3: drift E@110mm is out of order"),
    # a NaN
    (HEADER + "drift,19,E,nan,um,1,110\n", "line 2: the value must be a finite number, got 'nan'"),
    (HEADER + "drift,19,E,8,um,1,nan\n", "line 2: the target must be a finite number, got 'nan'"),
    # a header without units
    ("test,time [s],quantity,value,unit,uncertainty,target\ndrift,19,E,8,um,1,110\n",
     "line 1: the target column names its unit, e.g. 'target [mm]', got 'target'"),
    ("test,time [s],quantity,value,unit,target [K]\ndrift,19,E,8,um,110\n", "line 1: 'K' is not a length unit"),
    ("test,time,quantity,value,unit\ndrift,19,T1,20,degC\n", "line 1: the time column names its unit"),
    # E without a target, a target on another quantity, E in a temperature unit
    (HEADER + "drift,19,E,8,um,1,\n", "line 2: the target is missing"),
    ("test,time [s],quantity,value,unit\ndrift,19,E,8,um\n", "line 2: E is the deviation at a target position: add "
                                                            "a column 'target [mm]'"),
    (HEADER + "drift,19,T1,20,degC,0.1,110\n", "line 2: only E is measured at a target; leave the target empty for T1"),
    (HEADER + "drift,19,E,8,degC,1,110\n", "line 2: 'degC' is not a length's unit"),
    # a test the description does not declare; the air's sensor misnamed
    (HEADER + "drift2,19,E,8,um,1,110\n", "line 2: unknown test 'drift2'"),
    (HEADER + "drift,0,air,20,degC,0.05,\n", "line 2: unknown quantity 'air'; expected one of T1, ambient, D, E"),
])
def test_bad_test_measurements_name_the_line(tmp_path, text, fragment):
    with pytest.raises(DescriptionError) as raised:
        _read(tmp_path, text)
    message = str(raised.value)
    assert fragment in message, message
    assert message.startswith(str(tmp_path / "m.csv")) and "\n" not in message
