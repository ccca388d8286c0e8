"""`feedtherm calculix`: the FE model written as a CalculiX deck, and its input errors."""

import json

import pytest

from feedtherm.boundary import boundary_conditions
from feedtherm.cli import main


def test_the_deck_and_its_summary_are_written(tmp_path, paper, capsys):
    out = tmp_path / "deck"
    assert main(["calculix", "--condition", "II", "--step", "60", "--duration", "1200", "--out", str(out)]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["deck.json", "feedtherm.inp"]
    summary = json.loads((out / "deck.json").read_text())
    assert summary["condition"] == "II" and summary["position"] == summary["positions"] // 2
    assert summary["offset_m"] == pytest.approx(0.0, abs=1e-12)
    assert summary["heat_W"] == pytest.approx(boundary_conditions(paper.system, "II").total_heat, rel=1e-9)
    deck = (out / "feedtherm.inp").read_text()
    assert "*HEAT TRANSFER, DIRECT\n6.000000000e+01, 1.200000000e+03" in deck
    assert deck.count("*CONTACT PAIR") == len(summary["joints"]) == len(paper.system.joints)
    assert f"{summary['vertices']:,} nodes" in capsys.readouterr().out


def _exit_code(argv) -> int:
    """What the command exits with, whether argparse exits or the command returns."""
    try:
        return main(argv)
    except SystemExit as stop:
        return stop.code


@pytest.mark.parametrize("arguments, fragment", [
    (["--condition", "I", "--position", "999"], "--position: 999 is not a grid position"),
    (["--condition", "I", "--position", "-2"], "--position"),
    (["--condition", "I", "--step", "20000"], "--step: 20000 s is longer than the run"),
    (["--condition", "I", "--step", "0"], "--step"),
    (["--condition", "IX"], "--condition: no condition 'IX'"),
])
def test_bad_input_is_one_line_and_writes_nothing(tmp_path, capsys, arguments, fragment):
    out = tmp_path / "deck"
    assert _exit_code(["calculix", "--out", str(out), *arguments]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and fragment in err[0] and "Traceback" not in err[0]
    assert not out.exists()
