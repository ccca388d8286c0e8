"""The files of `feedtherm run`, written from a small synthetic Solution (no model involved)."""

from __future__ import annotations

import csv
import dataclasses
import json
import math

import numpy as np
import pytest

from feedtherm.errors import FeedthermError
from feedtherm.outputs import run_files
from feedtherm.outputs.run_files import (
    default_out_dir,
    run_summary,
    sample_rows,
    summary_line,
    write_run,
    write_run_outputs,
)
from feedtherm.solution import EnergyBalance, Ledger, Solution

T_AMBIENT = 293.15  # K (20 °C)
EXPANSION = 11.5e-6  # 1/K, steel
TABLE_X = np.linspace(0.15, 0.45, 13)  # m: the nut's centre over a 300 mm stroke, 25 mm apart


def make_solution(*, sensor_names=("T1", "T2", "T3", "T4", "T5", "T6"), step=10.0, hours=2.0,
                  equilibrium_time=4500.0, info=None, fields=None) -> Solution:
    """A plausible warm-up: sensors rise exponentially to a few kelvin over ambient, the screw
    is warmest near its middle, D follows the mean screw rise, and the positioning error is the
    screw's displacement under the nut relative to the screw's front end (all SI, like a model's)."""
    times = np.arange(0.0, hours * 3600.0 + step / 2, step)
    warm = 1.0 - np.exp(-times / 1800.0)
    sensors = {}
    for index, name in enumerate(sensor_names):
        rise = 0.0 if name == "T6" else 2.0 + 1.5 * index
        sensors[name] = T_AMBIENT + rise * warm
    screw_x = np.linspace(0.0, 0.6, 25)  # m, cell centres
    profile = 1.0 + 3.0 * np.exp(-((screw_x - 0.3) / 0.15) ** 2)  # K at equilibrium
    screw_rise = np.outer(warm, profile)  # (times, positions)
    cell = screw_x[1] - screw_x[0]
    displacement = EXPANSION * np.cumsum(screw_rise, axis=1) * cell  # m, growing from the fixed end
    elongation = 2e-6 + displacement[:, -1]  # m; 2 µm at start: reference below the initial temperature
    table_x = TABLE_X
    positioning = np.array([np.interp(table_x, screw_x, row) for row in displacement]) - displacement[:, :1]
    last = slice(-36, None)  # the "last full cycle": 6 minutes
    final = {name: float(values[last].mean()) for name, values in sensors.items()}
    final["D"] = float(elongation[last].mean())
    steady = {name: T_AMBIENT + (0.0 if name == "T6" else 2.0 + 1.5 * i) for i, name in enumerate(sensor_names)}
    steady["D"] = 2e-6 + EXPANSION * float(np.sum(profile)) * cell
    # the ledger [J since the start]: a nut's heat of 30 W − 10 W·exp(−t/1800 s), a motor's 50 W, and
    # 20 W·(1 − exp(−t/1800 s)) lost, each integrated; their first step's at t = 0
    ledger = Ledger(capacities={"screw": 5000.0},
                    heat_in={"nut": 30.0 * times - 10.0 * 1800.0 * warm, "motor": 50.0 * times},
                    heat_lost=20.0 * (times - 1800.0 * warm), first_heat_in={"nut": 20.0, "motor": 50.0},
                    first_heat_lost=0.0)
    return Solution(
        times=times, sensors=sensors, elongation=elongation, screw_x=screw_x,
        screw_temperature=T_AMBIENT + screw_rise, screw_displacement=displacement,
        table_x=table_x, positioning_error=positioning, nut_offset=0.1 * np.sin(times / 60.0), part_temperatures={"screw": T_AMBIENT + screw_rise.mean(axis=1)},
        cycle_times=times[::6] + 30.0, cycle_sensors={k: v[::6] for k, v in sensors.items()},
        cycle_elongation=elongation[::6], final=final, steady=steady, equilibrium_time=equilibrium_time,
        energy=EnergyBalance(heat_in=1.0e5, heat_lost=6.0e4, heat_stored=3.99e4),
        info=info if info is not None else {
            "condition": "I", "model": "fast", "mode": "physics", "wall_time_s": np.float64(0.42), "ambient_sensor": "T6",
            "time_step_s": 10.0, "unknowns": np.int64(137),
            "provenance": {"feedtherm_version": "0.1.0", "description_sha256": "ab" * 32,
                           "description": "bundled:paper", "mode": "physics",
                           "assumptions": [{"paths": ["parts.screw"], "source": "feedtherm", "reason": "not printed"}]},
        },
        fields=fields,
        ledger=ledger,
    )


@pytest.fixture
def solution() -> Solution:
    return make_solution()


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    return rows[0], np.array(rows[1:], dtype=float)


# --------------------------------------------------------------------------- sensors.csv


def test_sensors_csv_header_and_units(solution, tmp_path):
    write_run_outputs(solution, tmp_path / "run", sample_interval=10.0)
    header, table = read_csv(tmp_path / "run" / "sensors.csv")
    assert header == ["time_s", "T1", "T2", "T3", "T4", "T5", "T6", "D_um"]
    assert table.shape == (solution.times.size, 8)
    np.testing.assert_allclose(table[:, 0], solution.times)
    np.testing.assert_allclose(table[:, 1], solution.sensors["T1"] - 273.15, atol=1e-4)
    np.testing.assert_allclose(table[:, 6], 20.0, atol=1e-4)  # T6: ambient in °C
    np.testing.assert_allclose(table[:, 7], solution.elongation * 1e6, atol=1e-4)
    assert table[0, 7] == pytest.approx(2.0, abs=1e-4)  # µm, not m


def test_sensors_csv_uses_the_descriptions_names_with_ambient_last(tmp_path):
    solution = make_solution(sensor_names=("T6", "front_bearing", "nut_flange"))
    write_run_outputs(solution, tmp_path, sample_interval=10.0)
    header, _ = read_csv(tmp_path / "sensors.csv")
    assert header == ["time_s", "front_bearing", "nut_flange", "T6", "D_um"]


def test_a_coarser_sample_interval_thins_the_rows_without_interpolating(solution, tmp_path):
    write_run_outputs(solution, tmp_path, sample_interval=600.0)
    _, table = read_csv(tmp_path / "sensors.csv")
    np.testing.assert_allclose(table[:, 0], np.arange(0.0, 7201.0, 600.0))
    every_60th = solution.sensors["T3"][::60] - 273.15
    np.testing.assert_allclose(table[:, 3], every_60th, atol=1e-4)


@pytest.mark.parametrize(
    "times, interval, expected",
    [
        ([0, 10, 20, 30], 10, [0, 1, 2, 3]),  # sampled at the interval: all rows
        ([0, 5, 10, 15, 20, 25], 10, [0, 2, 4, 5]),  # finer: thinned, last kept
        ([0, 30, 60], 10, [0, 1, 2]),  # coarser: all rows, nothing invented
        ([0, 9.999999999, 20.000000001, 30], 10, [0, 1, 2, 3]),  # times summed from steps
        ([0.0], 10, [0]),
    ],
)
def test_sample_rows(times, interval, expected):
    assert sample_rows(np.array(times, dtype=float), interval).tolist() == expected


@pytest.mark.parametrize("interval", [0.0, -1.0, math.nan, math.inf])
def test_sample_rows_rejects_a_non_positive_interval(interval):
    with pytest.raises(ValueError, match="sample interval"):
        sample_rows(np.arange(3.0), interval)


# --------------------------------------------------------------------------- screw CSVs


def test_screw_csv_is_time_by_position_in_celsius(solution, tmp_path):
    write_run_outputs(solution, tmp_path, sample_interval=10.0)
    header, table = read_csv(tmp_path / "screw.csv")
    assert header[0] == "time_s"
    assert header[1] == "x_mm=0" and header[-1] == "x_mm=600" and header[2] == "x_mm=25"
    assert len(header) == 1 + solution.screw_x.size
    assert table.shape == (solution.times.size, 1 + solution.screw_x.size)
    np.testing.assert_allclose(table[:, 1:], solution.screw_temperature - 273.15, atol=1e-4)
    assert table[-1, 13] == pytest.approx(20.0 + 4.0 * (1 - math.exp(-4)), abs=1e-3)  # mid-screw peak


def test_screw_displacement_csv_is_in_micrometres(solution, tmp_path):
    write_run_outputs(solution, tmp_path, sample_interval=10.0)
    header, table = read_csv(tmp_path / "screw_displacement.csv")
    _, temperature = read_csv(tmp_path / "screw.csv")
    assert header == ["time_s"] + [f"x_mm={x * 1e3:.6g}" for x in solution.screw_x]
    np.testing.assert_allclose(table[:, 1:], solution.screw_displacement * 1e6, atol=1e-4)
    assert table[-1, -1] == pytest.approx(solution.screw_displacement[-1, -1] * 1e6, abs=1e-4)
    assert 10.0 < table[-1, -1] < 100.0  # tens of µm, as a 0.6 m screw a few K warmer
    np.testing.assert_allclose(table[:, 0], temperature[:, 0])


# --------------------------------------------------------------------------- positioning_error.csv


def test_positioning_error_csv_is_time_by_table_position_in_micrometres(solution, tmp_path):
    write_run_outputs(solution, tmp_path, sample_interval=10.0)
    header, table = read_csv(tmp_path / "positioning_error.csv")
    assert header == ["time_s"] + [f"x_mm={x:g}" for x in range(150, 451, 25)]  # table positions in mm
    assert table.shape == (solution.times.size, 1 + solution.table_x.size)
    np.testing.assert_allclose(table[:, 0], solution.times)
    np.testing.assert_allclose(table[:, 1:], solution.positioning_error * 1e6, atol=1e-4)
    assert 5.0 < table[-1, -1] < 100.0  # µm, not m: a few K warmer over a 0.45 m screw
    text = (tmp_path / "positioning_error.csv").read_text(encoding="utf-8").splitlines()
    assert text[1].split(",")[1] == "0.0000"  # 4 decimals, as every value column


def test_positioning_error_csv_has_the_rows_of_the_screw_csvs(solution, tmp_path):
    write_run_outputs(solution, tmp_path, sample_interval=600.0)
    _, error = read_csv(tmp_path / "positioning_error.csv")
    _, screw = read_csv(tmp_path / "screw_displacement.csv")
    np.testing.assert_array_equal(error[:, 0], screw[:, 0])
    np.testing.assert_allclose(error[:, 0], np.arange(0.0, 7201.0, 600.0))
    np.testing.assert_allclose(error[:, 1:], solution.positioning_error[::60] * 1e6, atol=1e-4)


# --------------------------------------------------------------------------- parts.csv and heat.csv


def test_parts_csv_keeps_every_digit_of_the_part_means(solution, tmp_path):
    write_run_outputs(solution, tmp_path, sample_interval=60.0)
    header, table = read_csv(tmp_path / "parts.csv")
    _, sensors = read_csv(tmp_path / "sensors.csv")
    assert header == ["time_s", "screw"]
    np.testing.assert_array_equal(table[:, 0], sensors[:, 0])  # the rows of sensors.csv
    rows = sample_rows(solution.times, 60.0)
    # read back as the very doubles written: °C = K − 273.15, no rounding to 4 decimals
    np.testing.assert_array_equal(table[:, 1], solution.part_temperatures["screw"][rows] - 273.15)


def test_heat_csv_rows_are_the_mean_heats_since_the_previous_row(solution, tmp_path):
    write_run_outputs(solution, tmp_path, sample_interval=60.0)
    header, table = read_csv(tmp_path / "heat.csv")
    assert header == ["time_s", "nut", "motor", "lost"]
    t = table[:, 0]
    assert t[0] == 0.0 and table[0, 1:].tolist() == [20.0, 50.0, 0.0]  # row 0: the first step's
    np.testing.assert_allclose(table[1:, 2], 50.0, rtol=1e-14)
    # the nut's mean over each interval: 30 W − 10 W · (1800 s / Δt) (e^(−t0/1800) − e^(−t1/1800))
    mean = 30.0 - 10.0 * 1800.0 * (np.exp(-t[:-1] / 1800.0) - np.exp(-t[1:] / 1800.0)) / np.diff(t)
    np.testing.assert_allclose(table[1:, 1], mean, rtol=1e-11)
    # the rectangle rule over the rows gives back the heats since the start
    ledger = solution.ledger
    assert np.sum(table[1:, 1] * np.diff(t)) == pytest.approx(ledger.heat_in["nut"][-1], rel=1e-13)
    assert np.sum(table[1:, 3] * np.diff(t)) == pytest.approx(ledger.heat_lost[-1], rel=1e-13)


def test_summary_json_gives_the_ledgers_capacities_and_columns(solution, tmp_path):
    write_run_outputs(solution, tmp_path, sample_interval=60.0)
    ledger = json.loads((tmp_path / "summary.json").read_text(encoding="utf-8"))["ledger"]
    assert ledger["part_capacity_J_per_K"] == {"screw": 5000.0}
    assert ledger["files"]["parts.csv"]["columns"] == ["time_s", "screw"]
    assert ledger["files"]["heat.csv"]["columns"] == ["time_s", "nut", "motor", "lost"]
    assert (ledger["files"]["parts.csv"]["unit"], ledger["files"]["heat.csv"]["unit"]) == ("degC", "W")


def test_a_solution_without_a_ledger_writes_neither_file(solution, tmp_path):
    written = write_run_outputs(dataclasses.replace(solution, ledger=None), tmp_path, sample_interval=60.0)
    assert "parts.csv" not in [p.name for p in written] and "heat.csv" not in [p.name for p in written]
    assert json.loads((tmp_path / "summary.json").read_text(encoding="utf-8"))["ledger"] is None


# --------------------------------------------------------------------------- summary.json


def test_summary_json_keys_and_units(solution, tmp_path):
    write_run_outputs(solution, tmp_path, sample_interval=10.0)
    summary = json.loads((tmp_path / "summary.json").read_text(encoding="utf-8"))
    for key in ("condition", "model", "mode", "final", "steady", "equilibrium_time_s", "energy_balance_error",
                "wall_time_s", "time_step_s", "unknowns", "elongation_change_um", "provenance",
                "single_drive", "warnings", "energy_J"):
        assert key in summary
    assert (summary["condition"], summary["model"], summary["mode"]) == ("I", "fast", "physics")
    assert list(summary["final"]) == ["T1", "T2", "T3", "T4", "T5", "T6", "D_um"]
    assert summary["final"]["T1"] == pytest.approx(solution.final["T1"] - 273.15)
    assert summary["final"]["D_um"] == pytest.approx(solution.final["D"] * 1e6)
    assert summary["steady"]["T5"] == pytest.approx(20.0 + 2.0 + 1.5 * 4)
    assert summary["equilibrium_time_s"] == 4500.0
    assert summary["energy_balance_error"] == pytest.approx(solution.energy.relative_error)
    assert summary["energy_balance_error"] == pytest.approx(100.0 / 1.0e5)
    assert summary["elongation_change_um"]["final"] == pytest.approx((solution.final["D"] - 2e-6) * 1e6)
    assert (summary["wall_time_s"], summary["time_step_s"], summary["unknowns"]) == (0.42, 10.0, 137)
    assert summary["provenance"] == solution.info["provenance"]


def test_summary_json_gives_the_final_positioning_error_and_where(solution, tmp_path):
    write_run_outputs(solution, tmp_path, sample_interval=10.0)
    summary = json.loads((tmp_path / "summary.json").read_text(encoding="utf-8"))
    final = solution.positioning_error[-1]
    peak = int(np.argmax(np.abs(final)))
    assert list(summary)[list(summary).index("steady") + 1] == "positioning_error"  # beside D
    error = summary["positioning_error"]
    assert error["time_s"] == solution.times[-1] == 7200.0
    assert error["max_abs_um"] == pytest.approx(abs(final[peak]) * 1e6)
    assert error["E_um"] == pytest.approx(final[peak] * 1e6)
    assert error["table_x_mm"] == pytest.approx(solution.table_x[peak] * 1e3)
    assert error["max_abs_um"] == pytest.approx(np.abs(final).max() * 1e6) and error["max_abs_um"] > 5.0


def test_the_final_positioning_error_of_a_negative_error_keeps_its_sign(solution):
    flipped = dataclasses.replace(solution, positioning_error=-solution.positioning_error)
    error = run_summary(flipped)["positioning_error"]
    assert error["E_um"] == pytest.approx(-error["max_abs_um"]) and error["E_um"] < 0


def test_the_final_positioning_error_ignores_non_finite_positions_and_is_null_without_any(solution):
    error = solution.positioning_error.copy()
    error[-1, 3] = math.nan
    summary = run_summary(dataclasses.replace(solution, positioning_error=error))["positioning_error"]
    assert summary["max_abs_um"] == pytest.approx(np.nanmax(np.abs(error[-1])) * 1e6)
    empty = dataclasses.replace(solution, table_x=np.empty(0), positioning_error=np.empty((solution.times.size, 0)))
    assert run_summary(empty)["positioning_error"] == {"time_s": 7200.0, "max_abs_um": None, "E_um": None,
                                                        "table_x_mm": None}


def test_summary_json_writes_null_for_a_run_without_equilibrium(tmp_path):
    write_run_outputs(make_solution(equilibrium_time=None), tmp_path, sample_interval=10.0)
    assert json.loads((tmp_path / "summary.json").read_text())["equilibrium_time_s"] is None


def test_summary_never_writes_nan(tmp_path):
    info = {"condition": "I", "model": "fast", "mode": "physics", "wall_time_s": math.nan, "time_step_s": 10.0,
            "unknowns": 3, "provenance": {}, "ambient_sensor": "T6"}
    write_run_outputs(make_solution(info=info), tmp_path, sample_interval=10.0)
    text = (tmp_path / "summary.json").read_text()
    assert "NaN" not in text and json.loads(text)["wall_time_s"] is None


def test_run_summary_is_plain_json(solution):
    json.dumps(run_summary(solution), allow_nan=False)  # would raise on numpy scalars


# --------------------------------------------------------------------------- atomic writing


def fail_on_second_csv(monkeypatch):
    """Let sensors.csv be written completely, then fail while writing screw.csv."""
    real_write = run_files._write_csv
    calls = []

    def flaky(path, header, table, **options):
        calls.append(path.name)
        if len(calls) == 2:
            path.write_text("time_s,x_mm=0\n0,")  # half a file
            raise RuntimeError("disk on fire")
        real_write(path, header, table, **options)

    monkeypatch.setattr(run_files, "_write_csv", flaky)
    return calls


def test_a_failure_midway_leaves_no_output_directory(solution, tmp_path, monkeypatch):
    calls = fail_on_second_csv(monkeypatch)
    out_dir = tmp_path / "new" / "nested" / "run"
    with pytest.raises(RuntimeError, match="disk on fire"):
        write_run_outputs(solution, out_dir, sample_interval=10.0)
    assert calls == ["sensors.csv", "screw.csv"]  # it did fail midway
    assert not out_dir.exists()
    assert list(tmp_path.iterdir()) == []  # no staging directory, no parents made for it


def test_a_failure_midway_keeps_the_previous_files(solution, tmp_path, monkeypatch):
    out_dir = tmp_path / "run"
    out_dir.mkdir()
    (out_dir / "sensors.csv").write_text("previous run\n")
    (out_dir / "notes.txt").write_text("mine\n")
    fail_on_second_csv(monkeypatch)
    with pytest.raises(RuntimeError):
        write_run_outputs(solution, out_dir, sample_interval=10.0)
    assert sorted(p.name for p in out_dir.iterdir()) == ["notes.txt", "sensors.csv"]
    assert (out_dir / "sensors.csv").read_text() == "previous run\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]


def test_rewriting_replaces_our_files_and_keeps_others(solution, tmp_path):
    out_dir = tmp_path / "run"
    out_dir.mkdir()
    (out_dir / "sensors.csv").write_text("previous run\n")
    (out_dir / "notes.txt").write_text("mine\n")
    written = write_run_outputs(solution, out_dir, sample_interval=10.0)
    assert [p.name for p in written] == ["sensors.csv", "screw.csv", "screw_displacement.csv",
                                         "positioning_error.csv", "parts.csv", "heat.csv", "summary.json"]
    assert all(p.parent == out_dir and p.is_file() for p in written)
    assert (out_dir / "sensors.csv").read_text().startswith("time_s,T1")
    assert (out_dir / "notes.txt").read_text() == "mine\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]


def test_an_existing_file_as_output_directory_is_an_error(solution, tmp_path):
    target = tmp_path / "run"
    target.write_text("not a directory")
    with pytest.raises(FeedthermError, match="not a directory"):
        write_run_outputs(solution, target, sample_interval=10.0)
    with pytest.raises(FeedthermError, match="is a file"):
        write_run_outputs(solution, target / "inside", sample_interval=10.0)


def test_an_os_error_becomes_one_feedtherm_error(solution, tmp_path, monkeypatch):
    def full_disk(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(run_files, "write_summary_json", full_disk)
    with pytest.raises(FeedthermError, match="No space left on device"):
        write_run_outputs(solution, tmp_path / "run", sample_interval=10.0)
    assert list(tmp_path.iterdir()) == []


def test_write_run_writes_tables_and_plots_together(solution, tmp_path):
    written = write_run(solution, tmp_path / "run", sample_interval=60.0)
    assert sorted(p.name for p in (tmp_path / "run").iterdir()) == sorted(p.name for p in written) == [
        "elongation.png", "heat.csv", "parts.csv", "positioning_error.csv", "positioning_error.png", "screw.csv",
        "screw_displacement.csv", "screw_heatmap.png", "sensors.csv", "sensors.png", "summary.json"]


def test_without_figures_a_run_writes_the_tables_and_removes_an_earlier_runs_plots(solution, tmp_path):
    out_dir = tmp_path / "run"
    write_run(solution, out_dir, sample_interval=60.0)
    written = write_run(solution, out_dir, sample_interval=60.0, figures=False)
    assert sorted(p.name for p in out_dir.iterdir()) == sorted(p.name for p in written) == [
        "heat.csv", "parts.csv", "positioning_error.csv", "screw.csv", "screw_displacement.csv", "sensors.csv",
        "summary.json"]


def test_a_run_replaces_every_file_of_an_earlier_run_and_keeps_others(solution, tmp_path):
    """A fast run over an FE run's directory: no fields of the other run beside the new summary."""
    out_dir = tmp_path / "run"
    out_dir.mkdir()
    for name in ("summary.json", "fields.pvd", "fields_0000.vtu", "fields_0012.vtu", "temperature_field.png",
                 "screw_deformation.png", "screw_axial_deformation.png"):
        (out_dir / name).write_text("earlier FE run\n")
    (out_dir / "notes.txt").write_text("mine\n")
    written = write_run(solution, out_dir, sample_interval=600.0)
    assert sorted(p.name for p in out_dir.iterdir()) == sorted([p.name for p in written] + ["notes.txt"])
    assert len(written) == 11 and (out_dir / "notes.txt").read_text() == "mine\n"
    assert json.loads((out_dir / "summary.json").read_text())["model"] == "fast"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]


# --------------------------------------------------------------------------- names and the console line


def test_default_out_dir():
    assert str(default_out_dir("paper", "I", "physics")) == "out/paper_I_physics"
    assert str(default_out_dir("machines/my bench.toml", "warm up", "paper")) == "out/my-bench_warm-up_paper"


def test_summary_line_names_the_directory_and_final_values(solution, tmp_path):
    line = summary_line(solution, tmp_path / "run")
    assert "\n" not in line
    assert line.startswith(f"{tmp_path / 'run'}: T1 ")
    assert f"T5 {solution.final['T5'] - 273.15:.2f} °C" in line
    assert "T6" not in line  # the ambient is an input, not a result
    assert f"D {solution.final['D'] * 1e6:.2f} µm" in line
    assert "energy balance error 0.1 %" in line


def test_summary_and_line_give_each_quantitys_equilibrium_time(tmp_path):
    each = {"T2": 3000.0, "T1": None, "T6": None, "D": 4080.0}  # T6, the ambient, is left out
    solution = dataclasses.replace(make_solution(), equilibrium_times=each)
    assert run_summary(solution)["equilibrium_time_s_by_quantity"] == {"T1": None, "T2": 3000.0, "D": 4080.0}
    line = run_files.equilibrium_line(solution)
    assert "T1 not reached, T2 50 min, D 68 min" in line and "\n" not in line
