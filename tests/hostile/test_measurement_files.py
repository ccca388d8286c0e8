"""Measurement files with careless values: the consistency of the measurements (analysis/consistency.py,
shown by ``validate``, ``calibrate`` and ``uncertainty``, and left out of a fit) blames the condition whose
values are off, not the conditions that agree with one another."""

from __future__ import annotations

import csv
import io

import pytest

from feedtherm.analysis.consistency import check_description_measurements
from feedtherm.benches import bench
from feedtherm.constants import KELVIN_OFFSET
from feedtherm.system.measurements import read_description_measurements

MEASURED = (bench("paper").folder / "measurements.csv").read_text(encoding="utf-8")


def shifted(tmp_path, condition: str, offset: float, quantities=("T1", "T2", "T3", "T4", "T5")) -> str:
    """The paper bench's measurements with ``condition``'s ``quantities`` moved by ``offset``."""
    rows = list(csv.reader(io.StringIO(MEASURED)))
    for row in rows[1:]:
        if row[0] == condition and row[1] in quantities:
            row[3] = f"{float(row[3]) + offset:.2f}"
    out = io.StringIO()
    csv.writer(out, lineterminator="\n").writerows(rows)
    path = tmp_path / "measured.csv"
    path.write_text(out.getvalue(), encoding="utf-8")
    return str(path)


def flags_of(paper, path: str):
    return check_description_measurements(paper.system, read_description_measurements(paper.system, path, None)).flags


def test_condition_one_in_kelvin_is_blamed_on_condition_one(tmp_path, paper):
    # I's temperatures + 273.15: I is 270 K hotter than II and III, which run faster and agree
    flags = [f for f in flags_of(paper, shifted(tmp_path, "I", KELVIN_OFFSET)) if f.check == "speed_monotone"]
    assert [(f.condition, f.quantity) for f in flags] == [("I", q) for q in ("T1", "T2", "T3", "T4", "T5")]
    first = flags[0].reason
    assert "above conditions II, III" in first and "those conditions agree with one another" in first
    assert "300.25 °C is 27.1 °C if read as kelvin" in first and "in K where °C are expected" in first


def test_a_faster_condition_in_kelvin_is_blamed_on_itself(tmp_path, paper):
    # III in kelvin: hotter than I and II is what a faster drive may be, so nothing is flagged by speed...
    assert not [f for f in flags_of(paper, shifted(tmp_path, "III", KELVIN_OFFSET)) if f.check == "speed_monotone"]
    # ...but III 40 K below I and II, which run slower and agree, is III's
    flags = [f for f in flags_of(paper, shifted(tmp_path, "III", -40.0)) if f.check == "speed_monotone"]
    assert {f.condition for f in flags} == {"III"}
    assert "below conditions I, II" in flags[0].reason and "if read as kelvin" not in flags[0].reason


@pytest.mark.parametrize("quantities", [("T3",), ("T1", "T4")])
def test_only_the_columns_that_are_off_are_flagged(tmp_path, paper, quantities):
    flags = [f for f in flags_of(paper, shifted(tmp_path, "I", KELVIN_OFFSET, quantities))
             if f.check == "speed_monotone"]
    assert [(f.condition, f.quantity) for f in flags] == [("I", q) for q in quantities]


def test_the_bundled_measurements_raise_no_speed_flag(paper):
    path = str(bench("paper").folder / "measurements.csv")
    assert not [f for f in flags_of(paper, path) if f.check == "speed_monotone"]
