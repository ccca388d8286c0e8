"""The long (time-series) format of a measurement file, and the checks both formats share."""

import numpy as np
import pytest

from feedtherm.system.measurements import read_measurements
from feedtherm.errors import DescriptionError

SENSORS = ["A", "B"]
CONDITIONS = ["run1", "run2"]
HEADER = "condition,time [min],quantity,value,unit,uncertainty\n"


def _read(tmp_path, text, **kwargs):
    path = tmp_path / "m.csv"
    path.write_text(text)
    kwargs = {"sensors": SENSORS, "conditions": CONDITIONS, **kwargs}
    return read_measurements(str(path), **kwargs)


def test_series_convert_units_and_keep_the_last_sample_as_final(tmp_path):
    text = (HEADER
            + "run1,0,A,68,degF,0.9\n"      # 20 °C; 0.9 °F is a difference of 0.5 K
            + "run1,0,D,0,mm,0.001\n"
            + "run1,30,A,294.15,K,0.5\n"    # 21 °C
            + "\n"                           # a blank line is skipped, line numbers stay the file's
            + "run1,30,D,41.5,um,1\n"
            + "run1,90,A,22.5,C,0.5\n")     # C is degree Celsius, as in the finals format
    data = _read(tmp_path, text)
    assert data.has_series()
    a, d = data.rows
    assert (a.condition, a.quantity, a.unit) == ("run1", "A", "C")
    np.testing.assert_allclose(a.series.times, [0.0, 1800.0, 5400.0])
    np.testing.assert_allclose(a.series.values, [20.0, 21.0, 22.5], atol=1e-12)
    np.testing.assert_allclose(a.series.uncertainties, [0.5, 0.5, 0.5])
    assert a.measured == pytest.approx(22.5)
    # the elongation probe D is the finals' D_um, in µm
    assert (d.quantity, d.unit, d.measured) == ("D_um", "um", 41.5)
    np.testing.assert_allclose(d.series.values, [0.0, 41.5])
    np.testing.assert_allclose(d.series.uncertainties, [1.0, 1.0])


def test_time_unit_from_the_header_and_no_uncertainty_column(tmp_path):
    text = "condition, time [h] ,quantity,value,unit\nrun2,0.5,B,25,degC\nrun2, 1.5 ,B,26, °C \n"
    data = _read(tmp_path, text)
    (b,) = data.rows
    np.testing.assert_allclose(b.series.times, [1800.0, 5400.0])
    assert b.series.uncertainties is None
    assert b.reference_simulated is None


def test_interleaved_series_read_each_in_its_own_order(tmp_path):
    text = HEADER + "".join(f"run1,{t},{q},{20 + t},degC,\n" for t in (0, 5, 10) for q in ("A", "B"))
    data = _read(tmp_path, text)
    assert [r.quantity for r in data.rows] == ["A", "B"]
    for row in data.rows:
        np.testing.assert_allclose(row.series.times, [0.0, 300.0, 600.0])
        assert row.series.uncertainties is None


def test_finals_only_files_have_no_series(tmp_path):
    data = _read(tmp_path, "condition,quantity,unit,measured\nrun1,A,C,27.1\n")
    assert not data.has_series()
    assert data.rows[0].series is None


@pytest.mark.parametrize(
    "text, fragment",
    [
        # the header
        ("condition,time,quantity,value,unit\nrun1,0,A,20,degC\n", "line 1: the time column names its unit"),
        ("condition,time [furlong],quantity,value,unit\nrun1,0,A,20,degC\n", "line 1: 'furlong' is not a unit of time"),
        ("condition,time [zz],quantity,value,unit\nrun1,0,A,20,degC\n", "line 1: unknown time unit 'zz'"),
        ("condition,time [s],quantity,value\nrun1,0,A,20\n", "line 1: header must be"),
        # names
        (HEADER + "run1,0,T9,20,degC,\n", "line 2: unknown quantity 'T9'"),
        (HEADER + "run1,0,D_um,20,um,\n", "line 2: the long format names the elongation D"),
        (HEADER + "run9,0,A,20,degC,\n", "line 2: unknown test 'run9'"),
        # numbers
        (HEADER + "run1,0,A,20,degC,\nrun1,1,A,nan,degC,\n", "line 3: the value must be a finite number"),
        (HEADER + "run1,0,A,inf,degC,\n", "line 2: the value must be a finite number"),
        (HEADER + "run1,nan,A,20,degC,\n", "line 2: the time must be a finite number"),
        (HEADER + "run1,0,A,warm,degC,\n", "line 2: the value must be a number"),
        (HEADER + "run1,0,A,20,degC,\nrun1,1,A,,degC,\n", "line 3: the value is missing"),
        (HEADER + "run1,,A,20,degC,\n", "line 2: the time is missing"),
        (HEADER + "run1,-1,A,20,degC,\n", "line 2: time -1 lies before the start of the run"),
        (HEADER + "run1,0,A,20,degC,-0.1\n", "line 2: the uncertainty must not be negative"),
        (HEADER + "run1,0,A,20,degC,inf\n", "line 2: the uncertainty must be a finite number"),
        (HEADER + "run1,0,A,20,K,\n", "line 2: 20 K lies outside the accepted range"),
        # units
        (HEADER + "run1,0,A,20,mm,\n", "line 2: 'mm' is not a temperature's unit"),
        (HEADER + "run1,0,D,20,degC,\n", "line 2: 'degC' is not a length's unit"),
        (HEADER + "run1,0,A,20,delta_degC,\n", "line 2: 'delta_degC' is not a temperature's unit"),
        (HEADER + "run1,0,A,20,blorp,\n", "line 2: unknown unit 'blorp'"),
        (HEADER + "run1,0,A,20,,\n", "line 2: the unit is missing"),
        # order within a series
        (HEADER + "run1,0,A,20,degC,\nrun1,0,B,20,degC,\nrun1,0,A,21,degC,\n", "line 4: run1 A has time 0 s twice"),
        (HEADER + "run1,5,A,20,degC,\nrun1,1,A,21,degC,\n", "line 3: run1 A is out of order"),
        (HEADER + "run1,0,A,20,degC,0.1\nrun1,1,A,21,degC,\n", "line 3: run1 A has uncertainties on some samples"),
        (HEADER + "run1,0,A,20,degC,\nrun1,1,A,21,degC,0.1\n", "line 3: run1 A has uncertainties on some samples"),
        (HEADER + "run1,0,A,20,degC\n", "line 2: expected 6 values, got 5"),
        (HEADER, "no rows after the header"),
    ],
)
def test_bad_series_files_name_the_line(tmp_path, text, fragment):
    with pytest.raises(DescriptionError, match=fragment) as raised:
        _read(tmp_path, text)
    assert "\n" not in str(raised.value)
    assert str(raised.value).startswith(str(tmp_path / "m.csv"))


def test_a_sample_after_the_end_of_the_run_is_an_error(tmp_path):
    text = HEADER + "run1,0,A,20,degC,\nrun1,61,A,21,degC,\n"
    with pytest.raises(DescriptionError, match="line 3: time 3660 s lies after the end of run1's run"):
        _read(tmp_path, text, run_end={"run1": 3600.0})
    assert _read(tmp_path, text, run_end={"run1": 3660.0}).rows[0].measured == 21.0


def test_finals_with_an_unknown_condition_name_the_line(tmp_path):
    with pytest.raises(DescriptionError, match="line 3: unknown test 'run9'"):
        _read(tmp_path, "condition,quantity,unit,measured\nrun1,A,C,27.1\nrun9,A,C,27.1\n")
