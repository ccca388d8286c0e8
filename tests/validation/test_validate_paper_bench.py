"""`feedtherm validate` on the paper's bench: the 30 comparisons, in both modes.

These tests check the validation machinery and that the measured values are the paper's;
they do not assert agreement (the frozen assumptions are not tuned to Tables 6 and 7).
"""

import csv
import subprocess
import sys

import pytest

from feedtherm.analysis.validation import validate
from feedtherm.benches import bench
from feedtherm.plan import with_mode
from feedtherm.system.load import load_system


def measured_from_tables():
    out = {(r["condition"], r["point"]): float(r["measured_C"]) for r in bench("paper").table(6)}
    out.update({(r["condition"], "D_um"): float(r["measured_um"]) for r in bench("paper").table(7)})
    return out


def test_validate_command_writes_30_rows_and_a_report(tmp_path):
    out = tmp_path / "validation"
    result = subprocess.run([sys.executable, "-m", "feedtherm", "validate", "--out", str(out)],
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader(open(out / "validation.csv")))
    assert list(rows[0]) == ["condition", "quantity", "unit", "simulated", "measured", "paper_simulated", "deviation"]
    assert len(rows) == 30
    assert sum(r["unit"] == "C" for r in rows) == 25 and sum(r["quantity"] == "D_um" for r in rows) == 5
    measured = measured_from_tables()
    for r in rows:
        assert float(r["measured"]) == measured[(r["condition"], r["quantity"])]
        assert float(r["deviation"]) == pytest.approx(float(r["simulated"]) - float(r["measured"]), abs=1e-3)
    assert (out / "report.html").stat().st_size > 100_000
    assert "largest |deviation|" in result.stdout


def test_paper_mode_validation_uses_the_same_measurements():
    v = validate(with_mode(load_system("paper"), "paper"))
    assert len(v.comparisons) == 30 and v.mode == "paper"
    assert {c.condition for c in v.comparisons} == {"I", "II", "III", "IV", "V"}
    assert all(abs(s.energy.relative_error) < 1e-4 for s in v.solutions.values())
    assert v.sensitivity_condition == "I" and len(v.sensitivities) > 50
