"""`feedtherm correct`: an exported law run over logged readings, checked by hand; bad input."""

import csv
import json
import math
import subprocess
import sys

import pytest

FORMAT = "feedtherm-compensation-law"


def run(cwd, *args):
    return subprocess.run([sys.executable, "-m", "feedtherm", "correct", *args], capture_output=True, text=True,
                          timeout=120, cwd=cwd)


def stroke_law(path):
    """E(x) = (b0 + w0 T) + (b1 + w1 T) ξ on one input T [K], no lags, x from 100 to 300 mm."""
    path.write_text(json.dumps({
        "format": FORMAT, "version": 2, "kind": "linear_regression_stroke",
        "inputs": [{"name": "T1"}], "lags_s": [],
        "position": {"x_min_m": 0.1, "x_max_m": 0.3}, "basis": {"kind": "legendre", "order": 1},
        "bias_m": [-3.0e-3, -1.0e-3], "weights_m_per_K": [[[1.0e-5, 4.0e-6]]]}))
    return path


def d_law(path):
    """D = b + w T1 + v L(T1), one lag of 600 s."""
    path.write_text(json.dumps({
        "format": FORMAT, "version": 1, "kind": "linear_regression", "inputs": [{"name": "T1"}],
        "lags_s": [600.0], "bias_m": -6.0e-3, "weights_m_per_K": [[1.0e-5, 1.0e-5]]}))
    return path


#: T1 logged at 0 and 10 min (20 °C, 30 °C), D at 10 min only.
SERIES = ("condition,time [min],quantity,value,unit\n"
          "run1,0,T1,20,degC\nrun1,10,T1,30,degC\nrun1,10,D,40,um\n")


def read_rows(path):
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def test_a_stroke_law_at_two_positions_by_hand(tmp_path):
    stroke_law(tmp_path / "law_stroke.json")
    (tmp_path / "log.csv").write_text(SERIES)
    result = run(tmp_path, "law_stroke.json", "log.csv", "--x", "100 mm,250 mm", "--out", "out")
    assert result.returncode == 0, result.stderr
    rows = read_rows(tmp_path / "out" / "correction.csv")
    assert list(rows[0]) == ["condition", "time_s", "x_mm", "E_um"]
    assert [(r["time_s"], r["x_mm"]) for r in rows] == [("0.0", "100.0"), ("0.0", "250.0"),
                                                       ("600.0", "100.0"), ("600.0", "250.0")]
    # T = 293.15 K: c0 = -3e-3 + 1e-5·293.15 = -68.5 µm, c1 = -1e-3 + 4e-6·293.15 = 172.6 µm;
    # x = 100 mm: ξ = -1, E = c0 - c1 = -241.1 µm; x = 250 mm: ξ = 0.5, E = c0 + c1/2 = 17.8 µm.
    # T = 303.15 K: c0 = 31.5 µm, c1 = 212.6 µm: E = -181.1 µm and 137.8 µm.
    expected = [-241.1, 17.8, -181.1, 137.8]
    assert [float(r["E_um"]) for r in rows] == pytest.approx(expected, abs=1e-6)
    summary = json.loads((tmp_path / "out" / "correction.json").read_text())
    assert summary["conditions"]["run1"]["x_mm"] == [100.0, 250.0]


def test_a_law_of_d_with_a_lag_and_the_logged_d_by_hand(tmp_path):
    d_law(tmp_path / "law.json")
    (tmp_path / "log.csv").write_text(SERIES)
    result = run(tmp_path, "law.json", "log.csv", "--out", "out")
    assert result.returncode == 0, result.stderr
    rows = read_rows(tmp_path / "out" / "correction.csv")
    assert list(rows[0]) == ["condition", "time_s", "D_um", "measured_D_um", "residual_um"]
    # t = 0: the lag starts at the reading, D = -6e-3 + 2e-5·293.15 = -137 µm.
    # t = 600 s: a = exp(-1), L = 293.15 a + 303.15 (1 - a) = 303.15 - 10 a;
    # D = -6e-3 + 1e-5 (303.15 + 303.15 - 10 a) = 63 - 100 a µm = 26.212 µm; measured 40, residual 13.788.
    a = math.exp(-1.0)
    assert float(rows[0]["D_um"]) == pytest.approx(-137.0, abs=1e-6)
    assert rows[0]["measured_D_um"] == ""
    assert float(rows[1]["D_um"]) == pytest.approx(63 - 100 * a, abs=1e-6)
    assert float(rows[1]["residual_um"]) == pytest.approx(40 - 63 + 100 * a, abs=1e-6)
    assert "measured D - predicted: RMS 13.79 um" in result.stdout


@pytest.mark.parametrize("law, args, message", [
    ("stroke", ["--x", "350 mm"], "--x: 350 mm is outside the law's stroke, [100, 300] mm"),
    ("stroke", [], "--x: a stroke law needs the table positions, between 100 and 300 mm"),
    ("stroke", ["--x", "250"], "'250' has no unit"),
    ("d", ["--x", "200 mm"], "--x: this law predicts D, the same at every table position"),
    ("missing", [], "law.json: no such law file"),
    ("kalman", [], "law.json: a Kalman estimator needs the motor speeds"),
    ("foreign", [], "law.json: not a law feedtherm can evaluate: not a feedtherm-compensation-law document"),
    ("d_other_input", [], "log.csv: condition run1 does not log T2, an input of the law on T2"),
    ("no_log", [], "log.csv: no such measurement file"),
])
def test_bad_input_is_one_line_exit_2_and_nothing_written(tmp_path, law, args, message):
    if law != "no_log":
        (tmp_path / "log.csv").write_text(SERIES)
    if law == "stroke":
        stroke_law(tmp_path / "law.json")
    elif law in ("d", "no_log"):
        d_law(tmp_path / "law.json")
    elif law == "kalman":
        (tmp_path / "law.json").write_text(json.dumps({"format": FORMAT, "version": 1, "kind": "kalman"}))
    elif law == "foreign":
        (tmp_path / "law.json").write_text(json.dumps({"format": "other"}))
    elif law == "d_other_input":
        d_law(tmp_path / "law.json")
        text = (tmp_path / "law.json").read_text().replace('"T1"', '"T2"')
        (tmp_path / "law.json").write_text(text)
    before = sorted(p.name for p in tmp_path.iterdir())
    result = run(tmp_path, "law.json", "log.csv", *args, "--out", "out")
    assert result.returncode == 2 and result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and message in lines[0], result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == before
