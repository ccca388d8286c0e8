"""`feedtherm export --to c` (issue 58): the generated C, compiled with the system's cc, gives what
`feedtherm correct` gives, sample by sample, on the bench's logged series and on a 24 h random cycle,
for every law kind that exports; its guards behave as declared on fault series.

The laws are those of tests/law_documents.py (written by feedtherm's own writers) on T1-T3, the
sensors the ballscrew_example bench logs in its drift tests.
"""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from controller_harness import build_driver, random_day_log, run_driver, time_steps
from feedtherm.analysis.compensation.apply import correct, read_law
from feedtherm.analysis.compensation.evaluator import CompensationLaw
from feedtherm.cli import main
from law_documents import LAGS, POSITIONS, REFERENCE, every_document

pytestmark = pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler (cc) on this machine")

DOCUMENTS = every_document()
KINDS = ("law", "law_static", "law_adapted", "law_stroke")
BENCH_LOG = Path(__file__).resolve().parents[2] / "src" / "feedtherm" / "benches" / "ballscrew_example" / "drift_tests.csv"
#: The agreement asked of the generated code [m]: 1e-6 µm.
AGREEMENT_M = 1e-12
WIDE = "-50 degC,150 degC"


def export(tmp: Path, kind: str, *options: str) -> tuple[Path, str]:
    """`feedtherm export LAW --to c` in this process (the command's own exit code; one process saves
    the package's import per export)."""
    law = tmp / f"{kind}.json"
    law.write_text(json.dumps(DOCUMENTS[kind]))
    out = tmp / f"{kind}_c"
    assert main(["export", str(law), "--to", "c", "--name", f"ft_{kind}", "--out", str(out), *options]) == 0
    return out, f"ft_{kind}"


@pytest.fixture(scope="module")
def logs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("logs")
    return {"bench": BENCH_LOG, "day": random_day_log(folder / "day.csv")}


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("log", ("bench", "day"))
def test_the_compiled_law_gives_what_correct_gives(tmp_path, logs, kind, log):
    out, name = export(tmp_path, kind, "--valid-range", WIDE)
    exe = build_driver(out, name)
    law = read_law(tmp_path / f"{kind}.json")
    stroke = kind == "law_stroke"
    corrections = correct(law, str(logs[log]), tuple(POSITIONS) if stroke else ())
    assert sum(len(c.times) for c in corrections) >= (300 if log == "bench" else 1000)
    for c in corrections:
        readings = np.column_stack([c.readings[n] for n in law.inputs])
        rows = run_driver(exe, time_steps(c.times), readings, x=POSITIONS[0], positions=POSITIONS)
        assert not np.any(rows[:, 3].astype(int) & 1), "no sample is refused inside a wide valid range"
        if stroke:
            np.testing.assert_allclose(rows[:, 5:5 + len(POSITIONS)], c.predicted, rtol=0, atol=AGREEMENT_M)
        else:
            np.testing.assert_allclose(rows[:, 0], c.predicted[:, 0], rtol=0, atol=AGREEMENT_M)
            if kind == "law_adapted":
                np.testing.assert_allclose(rows[:, 2], c.sd, rtol=0, atol=AGREEMENT_M)
        # where the rate limit does not act, the guarded output is the law's value
        free = ~(rows[:, 3].astype(int) & 2).astype(bool)
        assert free[len(free) // 2:].all(), "a thermal drift is never rate limited at 1 um/s"
        np.testing.assert_array_equal(rows[free, 1], rows[free, 0])


def test_the_code_compiles_without_a_warning_under_pedantic_c99(tmp_path):
    """build_driver compiles with -std=c99 -Wall -Wextra -pedantic -Werror; this is each kind's once more
    with the plain `--to c` defaults (envelope-derived ranges)."""
    for kind in KINDS:
        out, name = export(tmp_path, kind)
        build_driver(out, name)
        header = (out / f"{name}.h").read_text()
        assert "#include" not in header, "the header needs nothing"
        assert "#include <math.h>" in (out / f"{name}.c").read_text()


# --------------------------------------------------------------------------- guards on fault series


def _series(n: int = 400, seed: int = 5):
    rng = np.random.default_rng(seed)
    times = np.arange(n) * 60.0
    readings = REFERENCE + 2.0 + np.cumsum(rng.normal(0, 0.05, (n, 2)), axis=0)
    return times, readings


def _evaluate(document: dict, times, readings) -> np.ndarray:
    law = CompensationLaw(document)
    return np.array([law.update(t, {"T1": r[0], "T2": r[1]}) for t, r in zip(times, readings)])


def test_a_sensor_dropping_out_holds_the_output_and_the_lags_resume_as_without_the_lost_samples(tmp_path):
    out, name = export(tmp_path, "law", "--valid-range", "0 degC,60 degC")
    exe = build_driver(out, name)
    times, readings = _series()
    faulty = readings.copy()
    faulty[100:120, 1] = np.nan   # T2 drops out for 20 minutes
    faulty[150, 0] = 400.0        # T1 reads 127 degC once: out of range
    rows = run_driver(exe, time_steps(times), faulty)
    flags, bad = rows[:, 3].astype(int), rows[:, 4].astype(int)
    held = list(range(100, 120)) + [150]
    assert all(flags[j] & 1 for j in held) and not any(flags[j] & 1 for j in range(len(times)) if j not in held)
    assert list(bad[100:120]) == [1] * 20 and bad[150] == 0 and bad[99] == -1
    np.testing.assert_array_equal(rows[100:120, 1], rows[99, 1])  # the output held
    assert rows[150, 1] == rows[149, 1]
    kept = [j for j in range(len(times)) if j not in held]
    expected = _evaluate(DOCUMENTS["law"], times[kept], readings[kept])
    np.testing.assert_allclose(rows[kept, 0], expected, rtol=0, atol=AGREEMENT_M)


def test_a_step_becomes_a_ramp_at_the_declared_rate(tmp_path):
    rate = 0.01e-6  # 0.01 um/s
    out, name = export(tmp_path, "law", "--valid-range", "0 degC,60 degC", "--max-rate", "0.01 um/s")
    exe = build_driver(out, name)
    times, readings = _series()
    readings[200:, 0] += 5.0  # T1 steps by 5 K
    rows = run_driver(exe, time_steps(times), readings)
    law, output, flags = rows[:, 0], rows[:, 1], rows[:, 3].astype(int)
    jump = law[200] - law[199]
    assert abs(jump) > 10e-6, "the step moves the law by more than 10 um"
    steps = np.abs(np.diff(output))
    assert np.all(steps <= rate * 60.0 * (1 + 1e-12)), "the output never moves faster than declared"
    ramping = np.flatnonzero(flags & 2)
    assert ramping.size and ramping.min() <= 2 and any(200 <= j < 240 for j in ramping)
    caught = ramping.max() + 1
    assert caught < len(times)
    np.testing.assert_array_equal(output[caught:], law[caught:])
    assert caught - 200 >= math.floor(abs(jump) / (rate * 60.0)) - 2


def test_a_cold_start_at_the_reference_follows_the_lags_from_the_reference(tmp_path):
    """--start reference: the lags start at the law's reference temperature; a machine held at 25 degC
    from power-up: each lag L(t) = T + (T_ref - T) exp(-t/tau), the law its weighted sum (hand formula)."""
    out, name = export(tmp_path, "law", "--start", "reference", "--valid-range", "0 degC,60 degC")
    exe = build_driver(out, name)
    document = DOCUMENTS["law"]
    times = np.arange(600) * 60.0
    hot = 298.15
    rows = run_driver(exe, time_steps(times), np.full((len(times), 2), hot))
    bias, weights = document["bias_m"], np.asarray(document["weights_m_per_K"])
    expected = bias + sum(w[0] * hot + sum(wl * (hot + (REFERENCE - hot) * np.exp(-times / tau))
                                           for wl, tau in zip(w[1:], LAGS)) for w in weights)
    np.testing.assert_allclose(rows[:, 0], expected, rtol=0, atol=1e-11)
    assert rows[0, 1] == 0.0, "the output starts at 0: nothing is applied at power-up"
    assert not rows[0, 3].astype(int) & 4


def test_before_the_first_valid_sample_the_output_is_zero_and_flagged(tmp_path):
    out, name = export(tmp_path, "law", "--valid-range", "0 degC,60 degC")
    exe = build_driver(out, name)
    times, readings = _series(40)
    readings[:5, 0] = np.nan
    dts = time_steps(times)
    dts[10] = -1.0  # a clock that goes back
    rows = run_driver(exe, dts, readings)
    flags = rows[:, 3].astype(int)
    assert all(flags[:5] & 4) and all(flags[:5] & 1) and not flags[5] & 4
    np.testing.assert_array_equal(rows[:5, 1], 0.0)
    assert flags[10] & 8 and rows[10, 1] == rows[9, 1] and rows[10, 0] == rows[9, 0]
    # the lags settle at the first valid sample (sample 5), as correct settles them at a log's first
    expected = _evaluate(DOCUMENTS["law"], times[5:10], readings[5:10])
    np.testing.assert_allclose(rows[5:10, 0], expected, rtol=0, atol=AGREEMENT_M)


def test_a_stroke_law_holds_outside_the_stroke_and_its_line_is_within_the_stated_bound(tmp_path):
    out, name = export(tmp_path, "law_stroke", "--valid-range", WIDE, "--x-ref", "150 mm")
    summary = json.loads((out / "export.json").read_text())
    bound = summary["offset_slope"]["reduction_error_bound_m"]
    exe = build_driver(out, name)
    rng = np.random.default_rng(2)
    times = np.arange(300) * 60.0
    envelope = DOCUMENTS["law_stroke"]["envelope"]["inputs"]
    low = np.array([envelope[n]["min_K"] for n in ("T1", "T2", "T3")])
    high = np.array([envelope[n]["max_K"] for n in ("T1", "T2", "T3")])
    readings = low + (high - low) * np.clip(0.5 + np.cumsum(rng.normal(0, 0.03, (300, 3)), axis=0), 0, 1)
    x = np.full(300, 0.2)
    x[50] = 0.35      # beyond the stroke's end (0.3 m)
    x[51] = np.nan
    grid = np.linspace(0.1, 0.3, 9)
    rows = run_driver(exe, time_steps(times), readings, x=x, positions=grid)
    flags = rows[:, 3].astype(int)
    assert flags[50] & 16 and flags[51] & 16 and not flags[49] & 16
    assert rows[50, 1] == rows[49, 1] == rows[51, 1]
    offset, slope, reduction = rows[:, -3], rows[:, -2], rows[:, -1]
    line = offset[:, None] + slope[:, None] * (grid[None, :] - 0.15)
    settled = ~(flags & 2).astype(bool)  # not ramping: the guarded coefficients are the law's
    assert settled.sum() > 250
    gap = np.abs(line - rows[:, 5:5 + len(grid)])[settled]
    assert np.all(gap <= reduction[settled, None] + 1e-15) and np.all(reduction <= bound + 1e-15)
    assert gap.max() > 1e-9, "the law is curved along the stroke: the line leaves something out"
    assert summary["offset_slope"]["x_ref_m"] == pytest.approx(0.15)


# --------------------------------------------------------------------------- refusals


def _export(tmp_path, law: Path, *options):
    out = tmp_path / "out"
    done = subprocess.run([sys.executable, "-m", "feedtherm", "export", str(law), "--to", "c", "--out", str(out),
                           *options], capture_output=True, text=True, timeout=120)
    return done, out


def _export_here(capsys, tmp_path, law: Path, *options):
    """The same in this process: (exit code, stderr, the output folder)."""
    out = tmp_path / "out"
    code = main(["export", str(law), "--to", "c", "--out", str(out), *options])
    return code, capsys.readouterr().err, out


@pytest.mark.parametrize("case", ["kalman", "nan", "x_ref_on_d", "range", "name", "reference_missing", "x_ref_out"])
def test_what_cannot_export_is_refused_in_one_line_and_nothing_is_written(tmp_path, capsys, case):
    document = dict(DOCUMENTS["law_kalman" if case == "kalman" else "law_stroke" if case == "x_ref_out" else "law"])
    options, expect = [], ""
    if case == "kalman":
        expect = "a Kalman estimator does not export"
    elif case == "nan":
        law = tmp_path / "law.json"
        law.write_text(json.dumps(document).replace('"bias_m": ', '"bias_m": NaN, "x": ', 1))
        expect = "NaN"
    elif case == "x_ref_on_d":
        options, expect = ["--x-ref", "100 mm"], "--x-ref: this law predicts D"
    elif case == "range":
        options, expect = ["--valid-range", "40 degC,10 degC"], "--valid-range"
    elif case == "name":
        options, expect = ["--name", "Bad-Name"], "--name"
    elif case == "reference_missing":
        document.pop("reference")
        options, expect = ["--start", "reference"], "--start: reference: the law has no reference block"
    elif case == "x_ref_out":
        options, expect = ["--x-ref", "500 mm"], "--x-ref: 500 mm is outside the law's stroke"
    law = tmp_path / "law.json"
    if case != "nan":
        law.write_text(json.dumps(document))
    code, err, out = _export_here(capsys, tmp_path, law, *options)
    assert code == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and expect in lines[0] and "Traceback" not in err
    assert not out.exists()


def test_a_bad_law_file_is_refused_as_correct_refuses_it(tmp_path):
    law = tmp_path / "law.json"
    law.write_text(json.dumps(DOCUMENTS["law"]).replace('"lags_s": [', '"lags_s": [-1, ', 1))
    exported, _ = _export(tmp_path, law)
    readings = tmp_path / "log.csv"
    readings.write_text("condition,quantity,unit,measured\na,T1,degC,20\na,T2,degC,21\n")
    corrected = subprocess.run([sys.executable, "-m", "feedtherm", "correct", str(law), str(readings), "--out",
                                str(tmp_path / "c")], capture_output=True, text=True, timeout=120)
    assert exported.returncode == corrected.returncode == 2
    assert exported.stderr == corrected.stderr


def test_a_name_too_long_for_hal_is_refused_before_anything_is_written(tmp_path, capsys):
    """HAL names are at most 47 characters (HAL_NAME_LEN): the component's longest pin must fit."""
    law = tmp_path / "law.json"
    law.write_text(json.dumps(DOCUMENTS["law_stroke"]))
    out = tmp_path / "out"
    code = main(["export", str(law), "--to", "linuxcnc", "--name", "a" * 27, "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "--name" in err and "use at most 26 characters" in err
    assert not out.exists()
    assert main(["export", str(law), "--to", "linuxcnc", "--name", "a" * 26, "--out", str(out)]) == 0
