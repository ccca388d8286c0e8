"""A sweep's files are one set: a new sweep leaves no plot of an earlier one behind."""

from __future__ import annotations

from feedtherm.analysis.sweep import columns
from feedtherm.outputs.sweep_files import write_sweep

SENSORS = {"T1": "front bearing"}


def one_point() -> list[dict]:
    row = dict.fromkeys(columns(list(SENSORS)), 1.0)
    row.update(screw_rpm=396.0, nut_rpm=360.0, ambient_C=20.0, equilibrium_time_s=None)
    return [row]


def test_a_sweep_replaces_the_plots_of_an_earlier_sweep_and_keeps_other_files(tmp_path):
    out_dir = tmp_path / "sweep"
    out_dir.mkdir()
    for name in ("sweep.csv", "sweep_ambient.png", "sweep_heat_map.png", "sweep_screw_rpm.png"):
        (out_dir / name).write_text("earlier sweep\n")  # a sweep of screw speed and ambient
    (out_dir / "notes.txt").write_text("mine\n")
    written = write_sweep(one_point(), SENSORS, out_dir)  # one point: no variable varies, no plot
    assert [p.name for p in written] == ["sweep.csv"]
    assert sorted(p.name for p in out_dir.iterdir()) == ["notes.txt", "sweep.csv"]
    assert (out_dir / "sweep.csv").read_text().startswith("screw_rpm,nut_rpm,ambient_C,")
