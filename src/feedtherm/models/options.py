"""Options of the models and of their shared time integration."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

#: The moving group's motions a run may take (:attr:`ModelOptions.motion`).
MOTIONS = ("resolved", "exact", "averaged")


@dataclass(frozen=True)
class ModelOptions:
    """Discretisation and time stepping (defaults meet the issues' resolution requirements)."""

    # fast model
    axial_cells: int = 100  # at least this many cells along the screw
    radial_rings: int = 2  # rings per screw cell
    cell_size: float = 0.04  # [m] size of the sub-volumes of the parts not resolved along the screw axis
    # FE model
    mesh: Literal["coarse", "medium", "fine"] = "coarse"
    # reduced model: relative POD tolerance of its basis (models/reduced/basis.py)
    reduction_tolerance: float = 1e-4
    # reduced model: what a projection built for a run is trained over (models/reduced/store.py):
    # "declared", the ranges the description declares; "description", its own numbers only (a
    # single run's, 2.5 times quicker to build on the paper bench); "batch", the declared ranges, and
    # only a projection trained over them is taken from the cache (a batch's preparation, so that
    # its runs at other numbers find it).  A cached projection that holds the description serves
    # the first two whatever it was trained over.
    reduced_training: Literal["declared", "description", "batch"] = "declared"
    # time stepping (every model)
    steps_per_stroke: int = 20  # at least this many time steps per stroke
    standstill_step: float = 10.0  # [s] time step while the table stands still
    max_step: float = 30.0  # [s] upper bound of any step
    # position over time ("resolved": window by window where the model takes windows, models/windows.py;
    # "exact": grid position by grid position in every model), or cycle-averaged
    motion: Literal["resolved", "exact", "averaged"] = "resolved"
    window_step: float = 10.0  # [s] the longest a windowed step may take to sweep its window (models/windows.py)
    averaged_step: float = 10.0  # [s] time step of the cycle-averaged motion
    solver: Literal["auto", "direct", "cg"] = "auto"  # cached factors per position, or conjugate gradients
    # [bytes] what "auto"'s PARDISO factors of one run may hold; None: half the memory available
    # when the run starts (models/pardiso.py); the positions beyond step by conjugate gradients
    factor_memory: float | None = None
    snapshot_interval: float = 600.0  # [s] full-field snapshots kept for field output (FE)
    # full-field snapshots and their displacement fields at all: the runs of a batch, which read
    # sensors and D only, leave them out (a reduced model's fields can cost its full model)
    fields: bool = True
    # nonlinear coupling (temperatures.coupling = "nonlinear")
    # [K] largest lag of a surface's or source's temperature before re-evaluation: at 0.5 K the
    # lagging heats moved the paper bench's time to 95 % of the rise at 396 rpm by 2.3 min,
    # at 0.2 K by 0.4 min, for 30 % more re-evaluations
    coupling_tolerance: float = 0.2
