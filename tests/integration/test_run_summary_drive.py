"""summary.json says how the axis was driven, and gives each quantity's equilibrium time.

Short fast-model runs with the cycle-averaged motion (a few seconds each).
"""

import json

import pytest

from feedtherm.cli import main


def run_summary_of(tmp_path, *args) -> dict:
    out = tmp_path / "run"
    assert main(["run", *args, "--duration", "1200", "--motion", "averaged", "--no-plots", "--out", str(out)]) == 0
    return json.loads((out / "summary.json").read_text())


def test_a_declared_single_drive_is_reported_single(tmp_path):
    summary = run_summary_of(tmp_path, "ballscrew_example", "--condition", "v10")
    assert summary["single_drive"] is True  # kinematics.drive = "single": it was false before
    assert summary["declared_drive"] == "single"
    assert summary["single_drive_option"] is False


def test_a_dual_drive_is_single_only_with_the_option(tmp_path):
    summary = run_summary_of(tmp_path, "paper", "--condition", "I")
    keys = ("single_drive", "declared_drive", "single_drive_option")
    assert tuple(summary[key] for key in keys) == (False, "dual", False)
    summary = run_summary_of(tmp_path / "single", "paper", "--condition", "I", "--single-drive")
    assert tuple(summary[key] for key in keys) == (True, "dual", True)


def test_each_sensor_and_D_have_an_equilibrium_entry(tmp_path, capsys):
    summary = run_summary_of(tmp_path, "ballscrew_example", "--condition", "v10")
    each = summary["equilibrium_time_s_by_quantity"]
    assert list(each) == ["T1", "T2", "T3", "T4", "T5", "D"]
    # 20 minutes from a cold start: nothing has reached 95 % of its rise yet
    assert all(value is None for value in each.values())
    assert "equilibrium (95 % of the steady rise" in capsys.readouterr().out
