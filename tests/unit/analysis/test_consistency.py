"""Measurement consistency from the measurements alone: hand-made sets with known answers, and
the paper's Tables 6-7, where one elongation cannot hold with the others."""

import numpy as np
import pytest

from feedtherm.analysis.consistency import OperatingPoint, check_consistency, operating_points
from feedtherm.system.measurements import Measurement, MeasurementSet, read_measurements

SENSORS = ("T1", "T2")


def measured(values: dict[str, dict[str, float]]) -> MeasurementSet:
    rows = [Measurement(c, q, "um" if q == "D_um" else "C", v) for c, row in values.items() for q, v in row.items()]
    return MeasurementSet(rows, "test", {})


def linear_set(slope=3.0, intercept=-60.0):
    """Four speeds at 20 °C and one at 25 °C; D exactly affine in the mean temperature."""
    temps = {"A": (25.0, 23.0), "B": (27.0, 24.0), "C": (29.0, 26.0), "D": (30.0, 27.5), "E": (33.0, 31.0)}
    return {c: {"T1": t1, "T2": t2, "D_um": intercept + slope * (t1 + t2) / 2} for c, (t1, t2) in temps.items()}


POINTS = {"A": OperatingPoint(400, 360, 20), "B": OperatingPoint(1100, 1080, 20), "C": OperatingPoint(2200, 2160, 20),
          "D": OperatingPoint(3000, 2900, 20), "E": OperatingPoint(1100, 1080, 25)}


def test_a_consistent_set_has_no_flags_and_gives_its_law():
    report = check_consistency(measured(linear_set()), POINTS)
    assert report.flags == []
    assert report.law.slope_um_per_k == pytest.approx(3.0)
    assert report.law.intercept_um == pytest.approx(-60.0)


def test_one_elongation_off_the_line_is_flagged_with_its_deviation():
    values = linear_set()
    values["E"]["D_um"] += 20.0  # 20 µm where the others put it
    report = check_consistency(measured(values), POINTS)
    assert [(f.condition, f.quantity, f.check) for f in report.flags] == [("E", "D_um", "elongation_law")]
    assert "+20.0 µm" in report.flags[0].reason
    assert report.law.conditions == ["A", "B", "C", "D"]
    assert report.excluded() == {("E", "D_um")}


def test_a_scattered_set_is_reported_not_pruned():
    values = linear_set()
    values["B"]["D_um"] += 8.0
    values["E"]["D_um"] -= 15.0
    report = check_consistency(measured(values), POINTS)
    assert report.flags == []
    assert "no single condition explains it" in report.notes[0]


def test_a_faster_drive_that_is_cooler_is_flagged():
    values = linear_set()
    values["C"]["T2"] = values["B"]["T2"] - 3.0  # faster than B, same ambient, 3 K cooler
    report = check_consistency(measured(values), POINTS, sigma_t=0.5)
    flags = [f for f in report.flags if f.check == "speed_monotone"]
    assert [(f.condition, f.quantity) for f in flags] == [("C", "T2")]
    # tolerance 3 * sqrt(2) * 0.5 K = 2.121 K, drop 3 K: excess 0.879 K
    assert flags[0].excess == pytest.approx(3.0 - 3 * np.sqrt(2) * 0.5)


def test_an_ambient_shift_that_changes_a_rise_is_flagged():
    values = linear_set()
    # B and E: same speeds, ambient 20 and 25 °C.  Rises of T1: 7 K at B; E's T1 = 33 -> 8 K.
    values["E"]["T1"] = 25.0 + 7.0 + 2.5  # rise 9.5 K against 7 K
    report = check_consistency(measured(values), POINTS, sigma_t=0.5)
    flags = [f for f in report.flags if f.check == "ambient_shift"]
    assert [(f.condition, f.quantity) for f in flags] == [("E", "T1")]
    assert flags[0].excess == pytest.approx(2.5 - 3 * np.sqrt(2) * 0.5)


def test_fewer_than_four_elongations_are_not_judged():
    values = {c: v for c, v in linear_set().items() if c in ("A", "B", "C")}
    report = check_consistency(measured(values), POINTS)
    assert report.flags == [] and report.law is None
    assert "four or more" in report.notes[0]


def test_the_papers_condition_V_elongation_is_flagged(paper):
    """Tables 6-7.  Mean of T1..T5 [°C] and D [µm]:
    I 30.24, 29.9; II 32.58, 35.5; III 34.46, 42.5; IV 26.86, 20.3; V 36.24, 71.5.
    Least squares through I-IV: x̄ = 31.035, ȳ = 32.05, Sxx = 32.18, Sxy = 91.9, slope 2.856 µm/K;
    at V it gives 32.05 + 2.856 * (36.24 - 31.035) = 46.9 µm against 71.5 measured (+24.6 µm),
    while I-IV lie within 1 µm of the line.  Under linear thermoelasticity a warmer field at
    II than halfway between IV and V cannot give a 10 µm smaller elongation than halfway: the
    IV->II->V steps (same speeds, ambient +5 K each) add 15.2 and 36.0 µm."""
    report = check_consistency(read_measurements("bundled:paper"), operating_points(paper.system))
    assert [(f.condition, f.quantity) for f in report.flags] == [("V", "D_um")]
    assert report.law.slope_um_per_k == pytest.approx(2.856, abs=0.01)
    assert report.law.max_residual_um < 1.0
    assert "+24.6 µm" in report.flags[0].reason
