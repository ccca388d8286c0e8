"""The windowed motion: the moving group resolved stretch by stretch, not grid position by position.

The exact resolved motion steps the group from grid position to grid position, a few cells a
step, and factorises one step matrix per position it stops at: an FE run of the paper's bench
on its fine mesh holds 21 factors of 370 MB (docs/fem-model.md, *Memory of the exact motion*).  The windowed motion
cuts the stroke into ``K / W`` windows of ``W`` cells; a step sweeps one window, with the
operators averaged over the positions it sweeps (:class:`~.interface.PositionWindow`: the
contacts, the exposed surfaces and the heat under the nut spread over the stretch, weighted
by the time spent at each position).  The step matrices are then as many as the windows,
whatever the grid, and the steps ``W / cells`` times fewer.

Between the two limits: one cell a window steps like the exact motion (with the contact of the
cell swept, not of its end), one window over the stroke like the cycle-averaged motion (with
the group going there and back in two steps).  The window's length is set by time, not by
space: a step may sweep at most what the group passes in :attr:`ModelOptions.window_step`
(10 s, the cycle-averaged motion's step and the standstill's), rounded down to a divisor of
``K`` so that windows tile the stroke and recur.  Within 10 s the heat the nut leaves on the
screw spreads over sqrt(alpha t) = 11 mm of steel (alpha = 1.2e-5 m²/s): the stretch a
slow table sweeps (6 mm/s, 60 mm) is longer, so a window does move the heat's footprint; what
that does to the sensors and the elongation is measured against the exact motion in
``benchmarks/study_fem_motion_windows.py`` (docs/fem-model.md, *The windowed motion*), not
assumed.
"""

from __future__ import annotations

import math

from .interface import PositionWindow


def window_cells(n_cells: int, exact_cells: int, dx: float, speed: float, window_step: float) -> int:
    """Grid cells a step of the windowed motion sweeps.

    Parameters
    ----------
    n_cells : int
        ``K``, the cells of the stroke (the grid has ``K + 1`` positions).
    exact_cells : int
        The cells a step of the exact motion advances: a window is never shorter.
    dx : float
        The grid step [m].
    speed : float
        The table's speed relative to the screw [m/s], > 0.
    window_step : float
        The longest a step may take to sweep its window [s].

    Returns
    -------
    int
        The largest divisor ``W`` of ``K`` with ``W dx / speed <= window_step``, and at least
        ``exact_cells`` (at least 1).
    """
    most = max(int(math.floor(window_step * speed / dx + 1e-9)), 1)
    divisors = [w for w in range(1, n_cells + 1) if n_cells % w == 0 and w <= most]
    return max(max(divisors, default=1), exact_cells, 1)


def swept_window(u_start: float, u_end: float, n_cells: int, cells: int) -> PositionWindow:
    """The window of ``cells`` cells a step sweeping the path from ``u_start`` to ``u_end`` steps with.

    ``u`` is the reciprocation's unfolded path in cells (:class:`~.integrator.PositionPath`);
    the window is the aligned one (positions ``j cells … (j + 1) cells``) that holds the
    sweep's middle, so that a sweep after a measuring stop, which starts off the windows' grid,
    steps with one of the same ``K / cells`` matrices.
    """
    period = 2 * n_cells
    middle = math.fmod(0.5 * (u_start + u_end), period)
    if middle < 0.0:
        middle += period
    position = middle if middle <= n_cells else period - middle
    count = n_cells // cells
    j = min(int(position // cells), count - 1)
    return PositionWindow(j * cells, (j + 1) * cells)
