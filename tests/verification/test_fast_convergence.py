"""Convergence of the fast model on condition I, over the whole run (first 600 s included).

The cycle-averaged T1-T5 and D must change by less than 0.05 K / 0.2 µm when the time step
is halved, and by less than 0.1 K / 0.5 µm when the axial resolution is doubled or the size
of the other parts' sub-volumes is halved.  The observed order of accuracy in time is
computed from three step sizes.
"""

import math

import numpy as np
import pytest

from feedtherm.models.options import ModelOptions
from feedtherm.simulate import simulate

SENSORS = ["T1", "T2", "T3", "T4", "T5"]


def series(run):
    temps = np.column_stack([run.cycle_sensors[n] for n in SENSORS])
    return run.cycle_times, temps, run.cycle_elongation * 1e6


def difference(a, b):
    ta, Ta, Da = series(a)
    tb, Tb, Db = series(b)
    # compare on the coarser run's times (both series are trailing cycle means)
    Tb_at = np.column_stack([np.interp(ta, tb, Tb[:, i]) for i in range(len(SENSORS))])
    return np.abs(Ta - Tb_at).max(), np.abs(Da - np.interp(ta, tb, Db)).max()


@pytest.fixture(scope="module")
def base(paper):
    return simulate(paper, condition="I")


def test_halving_the_time_step(paper, base):
    fine = simulate(paper, condition="I", options=ModelOptions(steps_per_stroke=40))
    assert fine.info["time_step_s"] == pytest.approx(base.info["time_step_s"] / 2)
    assert fine.info["screw_cells"] == base.info["screw_cells"]
    dT, dD = difference(base, fine)
    assert dT < 0.05 and dD < 0.2


def test_doubling_the_axial_resolution(paper, base):
    fine = simulate(paper, condition="I", options=ModelOptions(axial_cells=200))
    assert fine.info["screw_cells"] >= 1.95 * base.info["screw_cells"]  # the cell size divides the stroke
    dT, dD = difference(base, fine)
    assert dT < 0.1 and dD < 0.5


def test_halving_the_cell_size_of_the_parts(paper, base):
    fine = simulate(paper, condition="I", options=ModelOptions(cell_size=ModelOptions().cell_size / 2))
    assert fine.info["screw_cells"] == base.info["screw_cells"]
    assert fine.info["part_cells"] > 3 * base.info["part_cells"]
    dT, dD = difference(base, fine)
    print(f"cell size {ModelOptions().cell_size * 1e3:g} -> {ModelOptions().cell_size * 500:g} mm: "
          f"{dT:.3f} K, {dD:.3f} µm ({base.info['unknowns']} -> {fine.info['unknowns']} unknowns)")
    assert dT < 0.1 and dD < 0.5


def test_observed_order_in_time(paper):
    # Measured on the cycle-averaged motion (with the resolved motion a different step also
    # visits different nut positions, mixing position sampling into the time error), on the
    # temperatures at the end of the first hour, with steps of 20, 10 and 5 s.
    runs = [simulate(paper, condition="I", duration=3600.0, options=ModelOptions(motion="averaged", averaged_step=s))
            for s in (20.0, 10.0, 5.0)]
    ends = [np.array([run.sensors[n][-1] for n in SENSORS]) for run in runs]
    e1 = np.abs(ends[0] - ends[1]).max()
    e2 = np.abs(ends[1] - ends[2]).max()
    order = math.log2(e1 / e2)
    print(f"observed order of accuracy in time (implicit Euler): {order:.2f}")
    assert 0.7 < order < 1.5
