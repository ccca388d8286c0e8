"""The windowed motion's rules (models/windows.py): how long a window is, which window a step
sweeps, and how a window weighs its positions."""

import numpy as np
import pytest
import scipy.sparse as sp

from feedtherm.models.interface import PositionWindow, cycle_weights, weighted_sum
from feedtherm.models.windows import swept_window, window_cells


def test_a_window_is_the_largest_divisor_of_the_grid_the_table_passes_within_the_window_step():
    # the paper bench's FE grid at condition I: K = 40 cells of 5 mm, the table at 6 mm/s, 10 s:
    # 60 mm = 12 cells; the divisors of 40 up to 12 are 1, 2, 4, 5, 8, 10 -> 10 cells (4 windows)
    assert window_cells(40, 2, 0.005, 0.006, 10.0) == 10
    # 5 s: 30 mm = 6 cells -> 5 (8 windows)
    assert window_cells(40, 2, 0.005, 0.006, 5.0) == 5
    # a fast table passes the whole stroke within the step: one window, the cycle average
    assert window_cells(40, 2, 0.005, 0.5, 10.0) == 40
    # a slow one passes less than a cell: never fewer cells than the exact motion's step advances
    assert window_cells(40, 2, 0.005, 1e-4, 10.0) == 2
    # a prime grid has no divisor between 1 and itself: 40 mm = 4 cells of 10 mm fall back to 1
    assert window_cells(7, 1, 0.01, 0.004, 10.0) == 1


@pytest.mark.parametrize("start, end, expected", [
    (0.0, 10.0, (0, 10)),      # out along the first window
    (30.0, 40.0, (30, 40)),    # up to the far end
    (40.0, 50.0, (30, 40)),    # and back over the same stretch: the same window, the same matrix
    (70.0, 80.0, (0, 10)),     # back home (positions 10 -> 0)
    (80.0, 90.0, (0, 10)),     # the next cycle starts where the first did
    (13.0, 23.0, (10, 20)),    # after a measuring stop off the windows' grid: the window of its middle
    (36.0, 44.0, (30, 40)),    # a sweep over the turning point
])
def test_a_step_sweeps_the_aligned_window_that_holds_its_middle(start, end, expected):
    window = swept_window(start, end, 40, 10)
    assert (window.first, window.last) == expected


def test_a_window_weighs_its_positions_by_the_time_spent_at_each():
    window = PositionWindow(10, 12)
    assert list(window.positions) == [10, 11, 12]
    # the trapezoid rule over the sweep: the ends are passed at half the time of the middle
    assert window.weights == pytest.approx([0.25, 0.5, 0.25])
    # the whole stroke as one window is the cycle average
    assert PositionWindow(0, 40).weights == pytest.approx(cycle_weights(41))
    assert hash(window) == hash(PositionWindow(10, 12))  # the caches key on it


def test_the_window_conductance_is_the_weighted_sum_of_its_positions():
    class Grid:
        """Three positions whose conductances are distinct diagonal matrices."""

        def conductance(self, k):
            return sp.diags([1.0 + k, 2.0 * k]).tocsr()

    from feedtherm.models.interface import ThermalModel

    summed = ThermalModel.window_conductance(Grid(), PositionWindow(0, 2))
    expected = weighted_sum([0.25, 0.5, 0.25], [Grid().conductance(k) for k in range(3)])
    # by hand: diagonal 0.25*1 + 0.5*2 + 0.25*3 = 2.0 and 0.25*0 + 0.5*2 + 0.25*4 = 2.0
    assert np.allclose(summed.toarray(), np.diag([2.0, 2.0]))
    assert np.allclose(summed.toarray(), expected.toarray())
