"""`feedtherm run`'s file set for a run with fields: the .vtu series and the field images beside the tables.

The Solution is test_run_files' synthetic warm-up carrying test_fields' synthetic field series
(no model involved).
"""

from __future__ import annotations

import dataclasses

import pytest

from feedtherm.outputs import field_images
from feedtherm.outputs.run_files import write_run

# The synthetic solution and fields live beside this file (pytest puts the directory on sys.path).
from test_fields import PNG_MAGIC, make_screw_series, make_series
from test_run_files import make_solution

TABLES = ["heat.csv", "parts.csv", "positioning_error.csv", "screw.csv", "screw_displacement.csv", "sensors.csv",
          "summary.json"]
PLOTS = ["elongation.png", "positioning_error.png", "screw_heatmap.png", "sensors.png"]
FIELDS = ["fields.pvd", "fields_0000.vtu", "fields_0001.vtu", "fields_0002.vtu"]


@pytest.fixture(autouse=True)
def small_images(monkeypatch):
    monkeypatch.setattr(field_images, "_DPI", 60)  # the test is about which files appear


def fe_solution(series, screw_part="screw"):
    solution = make_solution(hours=0.5, fields=series)
    info = {**solution.info, "model": "fem"}
    if screw_part is not None:
        info["screw_part"] = screw_part
    return dataclasses.replace(solution, info=info)


def test_a_run_with_displacements_writes_the_screw_axial_deformation_image(tmp_path):
    written = write_run(fe_solution(make_screw_series()), tmp_path / "run", sample_interval=60.0)
    names = sorted(p.name for p in written)
    assert names == sorted(TABLES + PLOTS + FIELDS + ["screw_axial_deformation.png", "screw_deformation.png",
                                                      "temperature_field.png"])
    assert sorted(p.name for p in (tmp_path / "run").iterdir()) == names
    for name in ("screw_axial_deformation.png", "positioning_error.png"):
        assert (tmp_path / "run" / name).read_bytes()[:8] == PNG_MAGIC


def test_without_figures_a_run_writes_tables_and_fields_and_no_image(tmp_path):
    out_dir = tmp_path / "run"
    write_run(fe_solution(make_screw_series()), out_dir, sample_interval=60.0)
    written = write_run(fe_solution(make_screw_series()), out_dir, sample_interval=60.0, figures=False)
    assert sorted(p.name for p in out_dir.iterdir()) == sorted(p.name for p in written) == sorted(TABLES + FIELDS)


def test_the_screw_image_is_skipped_without_displacements_or_the_screw_part(tmp_path):
    without_displacements = write_run(fe_solution(make_series()), tmp_path / "a", sample_interval=60.0)
    without_name = write_run(fe_solution(make_screw_series(), screw_part=None), tmp_path / "b", sample_interval=60.0)
    for written in (without_displacements, without_name):
        names = [p.name for p in written]
        assert "screw_axial_deformation.png" not in names
        assert "temperature_field.png" in names and "screw_deformation.png" in names
