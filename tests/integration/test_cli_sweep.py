"""`feedtherm sweep` as a user runs it: a small real sweep, its CSV and plots, and bad input."""

import csv
import struct
import subprocess
import sys

import pytest

from feedtherm import cli
from feedtherm.outputs import sweep_files

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
LEAD_M = 0.010  # the paper bench's Tr32x10 screw
HEADER = ("screw_rpm,nut_rpm,ambient_C,table_speed_m_per_min,final_T1,final_T2,final_T3,final_T4,final_T5,final_D_um,"
          "steady_T1,steady_T2,steady_T3,steady_T4,steady_T5,steady_D_um,equilibrium_time_s,energy_balance_error,motor_duty")


def run(cwd, *args):
    return subprocess.run([sys.executable, "-m", "feedtherm", "sweep", *args], capture_output=True, text=True,
                          timeout=120, cwd=cwd)


def read_rows(path):
    with open(path, newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def png_size(path):
    data = path.read_bytes()
    assert data[:8] == PNG_MAGIC, f"{path.name} is not a PNG"
    return struct.unpack(">II", data[16:24])


# --------------------------------------------------------------------------- a real sweep


@pytest.fixture(scope="module")
def sweep(tmp_path_factory):
    """2 screw speeds × 1 nut speed × 2 ambients, 30 min each; (396, 360, 20) is the paper's condition I."""
    cwd = tmp_path_factory.mktemp("sweep")
    result = run(cwd, "--screw-rpm", "396,1116", "--nut-rpm", "360", "--ambient", "20:25:5",
                 "--duration", "1800", "--motion", "averaged")
    return cwd, result


def test_the_sweep_writes_its_files_and_one_line(sweep):
    cwd, result = sweep
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
    lines = result.stdout.splitlines()
    assert len(lines) == 1 and lines[0].startswith("out/paper_sweep_physics: sweep of 4 points written in "), lines
    assert lines[0].endswith(" s")
    out = cwd / "out" / "paper_sweep_physics"
    # Screw speed and ambient vary, the nut speed does not: no nut plot, a heat map of the two.
    assert sorted(p.name for p in out.iterdir()) == ["sweep.csv", "sweep_ambient.png", "sweep_heat_map.png",
                                                     "sweep_screw_rpm.png"]
    assert [p.name for p in (cwd / "out").iterdir()] == ["paper_sweep_physics"]  # no staging directory left
    for name in ("sweep_ambient.png", "sweep_screw_rpm.png", "sweep_heat_map.png"):
        width, height = png_size(out / name)
        assert width >= 1200 and height >= 800, name


def test_the_csv_has_one_row_per_point_in_grid_order(sweep):
    cwd, _ = sweep
    path = cwd / "out" / "paper_sweep_physics" / "sweep.csv"
    assert path.read_text(encoding="utf-8").splitlines()[0] == HEADER
    rows = read_rows(path)
    assert [(r["screw_rpm"], r["nut_rpm"], r["ambient_C"]) for r in rows] == [
        ("396", "360", "20"), ("396", "360", "25"), ("1116", "360", "20"), ("1116", "360", "25")]
    for row in rows:
        # table speed = (n_screw − n_nut) · lead: (396 − 360) · 0.01 m = 0.36 m/min, (1116 − 360) · 0.01 = 7.56
        assert float(row["table_speed_m_per_min"]) == pytest.approx(
            (float(row["screw_rpm"]) - float(row["nut_rpm"])) * LEAD_M, abs=1e-12)
        assert abs(float(row["energy_balance_error"])) < 1e-4
        assert row["equilibrium_time_s"] == ""  # 30 min is far from equilibrium: an empty cell
        for name in ("T1", "T2", "T3", "T4", "T5"):  # heated above the ambient, more so at the steady state
            ambient = float(row["ambient_C"])
            assert ambient < float(row[f"final_{name}"]) < float(row[f"steady_{name}"])
    assert [float(r["table_speed_m_per_min"]) for r in rows] == pytest.approx([0.36, 0.36, 7.56, 7.56])
    # the screw motor's torque over its 1.17 N m rating: at condition I's speeds what `feedtherm heat` gives
    from feedtherm.boundary import boundary_conditions
    from feedtherm.system.load import load_system

    torque = boundary_conditions(load_system("paper").system, "I").heats["screw_motor"].details["torque_Nm"]
    assert float(rows[0]["motor_duty"]) == pytest.approx(abs(torque) / 1.17, abs=1e-3)
    assert all(0.5 < float(r["motor_duty"]) < 1.0 for r in rows)


def test_points_the_motors_cannot_run_are_computed_and_named(tmp_path):
    """Single drive at 11 m/min: the thread's grease drag takes the screw motor past its rating."""
    result = run(tmp_path, "--screw-rpm", "1116", "--nut-rpm", "0,1080", "--ambient", "20", "--duration", "600",
                 "--motion", "averaged", "--out", "out")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert len(lines) == 2 and lines[1].startswith("warning: 1 of 2 points need more than a motor's continuous torque")
    assert "at screw 1116 rpm, nut 0 rpm" in lines[1]
    rows = read_rows(tmp_path / "out" / "sweep.csv")
    assert float(rows[0]["motor_duty"]) > 1.0 > float(rows[1]["motor_duty"])


def test_d_grows_with_the_speed_and_the_laser_follows_the_ambient(sweep):
    cwd, _ = sweep
    rows = read_rows(cwd / "out" / "paper_sweep_physics" / "sweep.csv")
    d = {(float(r["screw_rpm"]), float(r["ambient_C"])): (float(r["final_D_um"]), float(r["steady_D_um"]))
         for r in rows}
    for screw in (396.0, 1116.0):
        # the laser stands on the base: 5 K warmer everywhere adds only the loop's own free expansion,
        # alpha · 5 K · (450 - 480 mm) = -1.8 µm (and the thinner warm oils make a little less heat),
        # not the 27 µm a screw measured against a fixed frame would gain over its 450 mm
        assert abs(d[(screw, 25.0)][1] - d[(screw, 20.0)][1] + 1.8) < 5.0
    for ambient in (20.0, 25.0):
        assert d[(1116.0, ambient)][1] > d[(396.0, ambient)][1]


def test_a_sweep_point_is_the_run_of_the_same_condition(sweep):
    """(396, 360, 20 °C) is condition I: the sweep's row equals simulate() of condition I."""
    from feedtherm.simulate import simulate
    from feedtherm.system.load import load_system

    cwd, _ = sweep
    row = read_rows(cwd / "out" / "paper_sweep_physics" / "sweep.csv")[0]
    solution = simulate(load_system("paper"), condition="I", duration=1800, motion="averaged")
    for which in ("final", "steady"):
        values = solution.summary_values(which)
        for name in ("T1", "T2", "T3", "T4", "T5", "D_um"):
            assert float(row[f"{which}_{name}"]) == pytest.approx(values[name], abs=1e-4), (which, name)


# --------------------------------------------------------------------------- bad input


def assert_one_line_error_and_nothing_written(result, cwd, *fragments, inputs=()):
    assert result.returncode == 2, result.stderr
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("feedtherm: error: ") and "Traceback" not in result.stderr
    for fragment in fragments:
        assert fragment in lines[0], lines[0]
    assert sorted(p.name for p in cwd.iterdir()) == sorted(inputs)  # no out/, no staging directory


GOOD = {"--screw-rpm": "396", "--nut-rpm": "360", "--ambient": "20"}


def args_with(**changes):
    values = dict(GOOD, **{f"--{key.replace('_', '-')}": value for key, value in changes.items()})
    return [item for option, value in values.items() for item in (option, value)]


@pytest.mark.parametrize(
    "args, fragments",
    [
        (args_with(screw_rpm="300:600"), ["--screw-rpm: range '300:600' must be start:stop:step"]),
        (args_with(screw_rpm="300,,600"), ["--screw-rpm: empty item"]),
        (args_with(nut_rpm="-300:300:0"), ["--nut-rpm: range '-300:300:0' has step 0"]),
        (args_with(nut_rpm="-300:300:-100"), ["--nut-rpm: range '-300:300:-100' has step -100"]),
        (args_with(ambient="25:20:1"), ["--ambient: range '25:20:1' is empty"]),
        (args_with(ambient="twenty"), ["--ambient: 'twenty' is not a number"]),
        (args_with(ambient="-280"), ["--ambient: -280 °C is not above absolute zero"]),
        (args_with(screw_rpm="100:3000:10", ambient="18,20"), ["the grid has 582 points", "at most 500"]),
        (args_with(screw_rpm="0:600:1"), ["--screw-rpm: range '0:600:1' gives 601 values", "at most 500"]),
        (["ballscrew_example", *args_with(nut_rpm="0,100")], ["--nut-rpm: a single drive", "give --nut-rpm 0"]),
        (["ballscrew_example", *args_with(nut_rpm="0"), "--mode", "paper"], ["--mode paper", "no overlay of printed values"]),
        (args_with(duration="0"), ["--duration", "positive", "'0'"]),
        (args_with(motion="fast"), ["--motion", "invalid choice: 'fast'"]),
        (["--screw-rpm", "396", "--nut-rpm", "360"], ["the following arguments are required: --ambient"]),
        (["no_such_bench.toml", *args_with()], ["no_such_bench.toml: no such file"]),
    ],
)
def test_bad_arguments(tmp_path, args, fragments):
    assert_one_line_error_and_nothing_written(run(tmp_path, *args), tmp_path, *fragments)


def test_an_out_path_that_is_a_file(tmp_path):
    (tmp_path / "results").write_text("not a directory")
    result = run(tmp_path, *args_with(out="results"))
    assert_one_line_error_and_nothing_written(result, tmp_path, "results", "not a directory", inputs=["results"])


def test_signed_lists_are_values_not_options():
    """`--nut-rpm -600:600:300` and `--nut-rpm -300,300` (argparse would take them for options)."""
    parser = cli.build_parser()
    args = parser.parse_args(["sweep", "--screw-rpm", "-300,300", "--nut-rpm", "-600:600:300", "--ambient", "-5"])
    assert (args.screw_rpm, args.nut_rpm, args.ambient) == ("-300,300", "-600:600:300", "-5")
    assert args.motion == "averaged" and args.mode == "physics" and args.duration is None and args.system == "paper"


# --------------------------------------------------------------------------- the files, from made-up rows


def made_up_rows(screws, nuts, ambients):
    """Rows shaped like run_sweep's, with values that vary smoothly (no model involved)."""
    rows = []
    for s in screws:
        for n in nuts:
            for a in ambients:
                row = {"screw_rpm": s, "nut_rpm": n, "ambient_C": a, "table_speed_m_per_min": (s - n) * LEAD_M}
                for which, scale in (("final", 0.6), ("steady", 1.0)):
                    for i, name in enumerate(("T1", "T2")):
                        row[f"{which}_{name}"] = a + scale * (i + 1) * abs(s - n) / 100
                    row[f"{which}_D_um"] = 11.5 * (a - 20) + scale * abs(s - n) / 5
                row["equilibrium_time_s"] = 3600.0 if s < 500 else None
                row["energy_balance_error"] = 1.5e-12
                row["motor_duty"] = 0.6 + abs(s - n) / 1000 if s < 500 else None
                rows.append(row)
    return rows


SENSORS = {"T1": "front bearing", "T2": "rear bearing"}


def test_csv_cells_of_made_up_rows(tmp_path):
    rows = made_up_rows([396.0, 1116.0], [360.0], [20.0])
    written = sweep_files.write_sweep(rows, SENSORS, tmp_path / "out", title="test")
    assert [p.name for p in written] == ["sweep.csv", "sweep_screw_rpm.png"]  # one varied variable: no heat map
    lines = (tmp_path / "out" / "sweep.csv").read_text().splitlines()
    assert lines[0] == ("screw_rpm,nut_rpm,ambient_C,table_speed_m_per_min,final_T1,final_T2,final_D_um,"
                        "steady_T1,steady_T2,steady_D_um,equilibrium_time_s,energy_balance_error,motor_duty")
    assert lines[1] == "396,360,20,0.36,20.2160,20.4320,4.3200,20.3600,20.7200,7.2000,3600,1.500e-12,0.636"
    assert lines[2].endswith(",,1.500e-12,")  # no equilibrium, no motor rating: empty cells


def test_a_single_point_writes_only_the_csv(tmp_path):
    written = sweep_files.write_sweep(made_up_rows([396.0], [360.0], [20.0]), SENSORS, tmp_path / "one")
    assert [p.name for p in written] == ["sweep.csv"]


def test_many_curves_and_three_varied_variables(tmp_path):
    """4 × 4 × 4: three plots with 16 curves each (legend names the two ends), no heat map."""
    rows = made_up_rows([300.0, 600.0, 900.0, 1200.0], [-300.0, 0.0, 300.0, 600.0], [15.0, 18.0, 21.0, 24.0])
    written = sweep_files.write_sweep(rows, SENSORS, tmp_path / "many", title="test")
    assert [p.name for p in written] == ["sweep.csv", "sweep_screw_rpm.png", "sweep_nut_rpm.png", "sweep_ambient.png"]
    assert all(png_size(p) for p in written[1:])


def test_a_failing_plot_leaves_no_files(tmp_path, monkeypatch):
    def broken(*args, **kwargs):
        raise RuntimeError("no ink")

    monkeypatch.setattr(sweep_files, "plot_heat_map", broken)
    with pytest.raises(RuntimeError, match="no ink"):
        sweep_files.write_sweep(made_up_rows([396.0, 1116.0], [360.0], [20.0, 25.0]), SENSORS, tmp_path / "out")
    assert list(tmp_path.iterdir()) == []
