"""PNG plots of a run, drawn from the synthetic Solution of test_run_files (no model involved)."""

from __future__ import annotations

import dataclasses
import struct

import matplotlib
import numpy as np
import pytest

from feedtherm.outputs import plots
from feedtherm.outputs.plots import run_label, write_run_plots

# The synthetic warm-up lives beside this file (pytest puts the directory on sys.path).
from test_run_files import make_solution

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
NAMES = ["sensors.png", "elongation.png", "screw_heatmap.png", "positioning_error.png"]


@pytest.fixture
def solution():
    return make_solution()


def png_size(path) -> tuple[int, int]:
    """Width and height from the IHDR chunk that follows the signature."""
    data = path.read_bytes()
    assert data[:8] == PNG_MAGIC, f"{path.name} is not a PNG"
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def test_four_valid_pngs_of_a_useful_size(solution, tmp_path):
    written = write_run_plots(solution, tmp_path / "run")
    assert [p.name for p in written] == NAMES
    for path in written:
        width, height = png_size(path)
        assert width >= 900 and height >= 600, path.name  # 150 dpi, 9 in wide
        assert path.stat().st_size > 20_000, path.name  # lines, labels and legend, not a blank canvas


def test_plots_without_equilibrium_or_with_other_sensors(tmp_path):
    solution = make_solution(sensor_names=("front_bearing", "T6"), equilibrium_time=None, hours=0.5)
    written = write_run_plots(solution, tmp_path)
    assert all(png_size(path) for path in written)


def test_a_long_run_is_thinned_for_the_heat_map(tmp_path):
    solution = make_solution(step=1.0, hours=3.0)  # 10 801 samples
    indices = plots._thinned(solution.times.size, plots._MAX_HEATMAP_COLUMNS)
    assert indices.size <= plots._MAX_HEATMAP_COLUMNS + 1 and indices[-1] == solution.times.size - 1
    write_run_plots(solution, tmp_path)
    assert png_size(tmp_path / "screw_heatmap.png")


def test_a_failing_plot_leaves_no_files(solution, tmp_path, monkeypatch):
    def broken(solution, path):
        raise RuntimeError("no ink")

    monkeypatch.setattr(plots, "plot_screw_heatmap", broken)
    with pytest.raises(RuntimeError, match="no ink"):
        write_run_plots(solution, tmp_path / "run")
    assert list(tmp_path.iterdir()) == []


def test_plotting_leaves_the_callers_backend_alone(solution, tmp_path):
    before = matplotlib.get_backend()
    write_run_plots(solution, tmp_path)
    assert matplotlib.get_backend() == before


def test_positioning_error_plot_shows_a_few_instants_the_last_in_black_in_um_and_mm(solution, tmp_path,
                                                                                    monkeypatch):
    from matplotlib.axes import Axes

    drawn = []
    original = Axes.plot

    def spy(self, *args, **kwargs):
        drawn.append((self, args, kwargs))
        return original(self, *args, **kwargs)

    monkeypatch.setattr(Axes, "plot", spy)
    plots.plot_positioning_error(solution, tmp_path / "e.png")
    assert png_size(tmp_path / "e.png")
    curves = [(args, kwargs) for _, args, kwargs in drawn if "label" in kwargs]
    assert [kwargs["label"] for _, kwargs in curves] == ["t = 0.40 h", "t = 0.80 h", "t = 1.20 h", "t = 1.60 h",
                                                         "t = 2.00 h"]
    (x_mm, last_um), style = curves[-1]
    assert style["color"] == "black"
    np.testing.assert_allclose(x_mm, solution.table_x * 1e3)
    np.testing.assert_allclose(last_um, solution.positioning_error[-1] * 1e6)
    ax = drawn[0][0]
    assert ax.get_xlabel() == "table position x [mm]" and ax.get_ylabel() == "positioning error E [µm]"
    assert ax.get_title().endswith("— I, physics mode, fast model")


def test_positioning_error_plot_of_a_single_table_position(solution, tmp_path):
    standstill = dataclasses.replace(solution, table_x=solution.table_x[:1],
                                     positioning_error=solution.positioning_error[:, :1])
    plots.plot_positioning_error(standstill, tmp_path / "e.png")
    assert png_size(tmp_path / "e.png")


def test_run_label(solution):
    assert run_label(solution) == "I, physics mode, fast model"
