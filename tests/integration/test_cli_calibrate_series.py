"""`feedtherm calibrate` on a measured time series, with the fast model.

tests/data/ballscrew_v10_series.csv is SYNTHETIC: the fast model's run of ballscrew_example's v10
over 20 min at its declared ball-nut drag torque (0.291 N m), plus seeded noise of 0.1 K and
0.5 µm, with declared uncertainties of 0.2 K and 1 µm (tests/data/make_ballscrew_series.py).  The
description here declares half that torque, so the fit has to find the factor 2 from the series.
"""

from __future__ import annotations

import json
from pathlib import Path

from feedtherm import cli
from feedtherm.benches import bench
from feedtherm.system.load import load_system

SERIES = Path(__file__).parents[1] / "data" / "ballscrew_v10_series.csv"
TRUE_FACTOR = 2.0  # the series' torque over the description's

CALIBRATION = """
[calibration.parameters.nut_drag]
kind = "scale"
paths = ["sources.ball_nut.torque"]
bounds = [0.5, 4.0]
description = "multiplier on the ball nut's preload drag torque"
"""


def halved_drag_description(tmp_path: Path) -> Path:
    """ballscrew_example with v10 lasting the series' 20 min, half the nut's drag and a calibration section."""
    text = (bench("ballscrew_example").folder / "description.toml").read_text(encoding="utf-8")
    for old, new in (('duration = "8 h"\ndescription = "10 m/min"\n', 'duration = "20 min"\ndescription = "10 m/min"\n'),
                     ('torque = "0.291 N*m"', 'torque = "0.1455 N*m"')):
        assert text.count(old) == 1
        text = text.replace(old, new)
    # the bench's declared prior of the drag excludes half of it: this machine is another one
    start = text.index("[uncertainty.parameters.ball_nut_torque]")
    text = text[:start] + text[text.index("[uncertainty.parameters.", start + 1):]
    path = tmp_path / "halved.toml"
    path.write_text(text + CALIBRATION, encoding="utf-8")
    return path


def test_calibrate_fits_the_series_and_recovers_the_drag_within_its_interval(tmp_path, capsys):
    system, out = halved_drag_description(tmp_path), tmp_path / "cal"
    assert cli.main(["calibrate", str(system), "--measured", str(SERIES), "--fit", "v10", "--params", "nut_drag",
                     "--workers", "1", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "fitted as series" in printed and "v10" in printed
    summary = json.loads((out / "calibration.json").read_text())
    fitted = summary["parameters"]["nut_drag"]
    # within its 95 % interval, although the fit's runs average the motion over a cycle and the
    # series came from a run that resolves it
    assert abs(fitted["fitted"] - TRUE_FACTOR) <= 1.96 * fitted["standard_error"], fitted
    assert fitted["standard_error"] < 0.05 * TRUE_FACTOR
    series = summary["series"]
    assert series["fitted_conditions"] == ["v10"] and series["held_out"] == []
    by_quantity = {s["quantity"]: s for s in series["fitted"]}
    assert set(by_quantity) == {"T1", "T3", "T4", "D_um"}
    for s in by_quantity.values():
        assert s["samples"] == 11 and s["end_s"] == 1200.0 and s["weights"] == "declared uncertainties"
        # the noise added was 0.1 K and 0.5 µm: a calibrated run follows the samples to about that
        assert s["rms_deviation"] < (0.2 if s["unit"] == "C" else 1.0), s
    calibrated = load_system(str(out / "calibrated.toml")).system
    assert abs(calibrated.sources["ball_nut"].torque - 0.1455 * fitted["fitted"]) < 1e-6
