"""The thermal modes of a condition: which masses set the time to equilibrium.

Around a steady state the model is linear, :math:`C\\dot T + (G + A)T = q + s`, with ``C`` the
(lumped, diagonal) capacity, ``G`` conduction and contacts averaged over the stroke and ``A`` the
links to the air at the steady state's coefficients.  The generalised eigenproblem

.. math:: (G + A)\\,v_i = \\lambda_i C v_i, \\qquad v_i^T C v_j = \\delta_{ij}

gives the modes: a start ``T_0`` approaches the steady state ``T_∞`` as
:math:`T(t) - T_∞ = \\sum_i c_i e^{-\\lambda_i t} v_i` with :math:`c_i = v_i^T C (T_0 - T_∞)`,
so mode ``i`` has the time constant :math:`τ_i = 1/λ_i` [s] and shows at a sensor read by the
row ``p`` with the amplitude :math:`p\\,v_i c_i` [K].  Its heat is stored in the parts in the
shares :math:`\\sum_{n∈\\text{part}} C_n v_{i,n}^2` (they add to 1): those are the masses that set it.

The paper's bench reaches equilibrium when the rise is at 95 % of its final value; for one
mode that is :math:`3τ` (:func:`settling_time`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp

from ..errors import FeedthermError
from ..simulate import steady_solve
from ..system.load import LoadedSystem

#: Largest state a dense eigen-analysis is run on (the fast model has about 1,500 nodes).
MAX_NODES = 6000


@dataclass(frozen=True)
class Mode:
    """One thermal mode: its time constant, where its heat is stored and how each sensor sees it."""

    time_constant: float  # [s]
    part_shares: dict[str, float]  # share of the mode's stored heat per part (adds to 1)
    sensor_amplitudes: dict[str, float]  # [K] this mode's part of (start − steady state) at each sensor


@dataclass(frozen=True)
class ThermalModes:
    """The slowest modes of one condition (``modes`` slowest first) and the parts' capacities [J/K]."""

    condition: str
    modes: list[Mode]
    capacities: dict[str, float]

    def dominant(self, sensor: str) -> Mode:
        """The mode with the largest amplitude at ``sensor``, among the slowest ``len(modes)``."""
        return max(self.modes, key=lambda m: abs(m.sensor_amplitudes[sensor]))


def settling_time(time_constant: float, fraction: float = 0.95) -> float:
    """Time [s] for one mode's rise to reach ``fraction`` of its final value: :math:`-τ\\ln(1 - f)`.

    ``fraction = 0.95`` (the paper's §4.2 criterion) gives :math:`3.0τ`.
    """
    if not 0.0 < fraction < 1.0:
        raise ValueError(f"fraction must lie in (0, 1), got {fraction}")
    return -time_constant * math.log(1.0 - fraction)


def slow_modes(capacity: np.ndarray, matrix, count: int) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues λ [1/s] (ascending) and C-orthonormal modes (columns) of ``matrix v = λ C v``.

    ``capacity`` (n,) [J/K] is the diagonal of C, ``matrix`` (n, n) [W/K] is G + A (symmetric).
    """
    dense = matrix.toarray() if sp.issparse(matrix) else np.asarray(matrix, dtype=float)
    count = min(count, len(capacity))
    return sl.eigh(dense, np.diag(capacity), subset_by_index=[0, count - 1])


def mode_table(capacity: np.ndarray, matrix, start_deviation: np.ndarray, readout: dict[str, np.ndarray],
               groups: dict[str, np.ndarray], count: int) -> list[Mode]:
    """The ``count`` slowest modes, with the parts' shares and the sensors' amplitudes.

    ``start_deviation`` (n,) is ``T_0 − T_∞`` [K]; ``readout`` maps a sensor to its row (n,);
    ``groups`` maps a part to the indices of its nodes.
    """
    lam, vectors = slow_modes(capacity, matrix, count)
    weights = vectors.T @ (capacity * start_deviation)  # c_i
    modes = []
    for i, rate in enumerate(lam):
        v = vectors[:, i]
        energy = capacity * v * v
        modes.append(Mode(
            time_constant=float(1.0 / rate),
            part_shares={part: float(energy[nodes].sum()) for part, nodes in groups.items()},
            sensor_amplitudes={name: float(row @ v * weights[i]) for name, row in readout.items()},
        ))
    return modes


def thermal_modes(loaded: LoadedSystem, condition: str, *, model: str = "fast",
                  count: int = 6) -> ThermalModes:
    """The ``count`` slowest thermal modes of ``condition`` around its steady state (module notes)."""
    solve = steady_solve(loaded, condition, model=model)
    disc, integrator = solve.model, solve.integrator
    if np.ndim(disc.capacity) != 1 or disc.n_nodes > MAX_NODES:
        raise FeedthermError(f"--model {model}: the eigen-analysis needs a lumped capacity and at most "
                             f"{MAX_NODES} unknowns (the fast model); this model has {disc.n_nodes}")
    bc = integrator.steady_boundary_conditions(0, solve.segment.bc, solve.state)
    k = solve.k
    matrix = integrator.conductance(k) + sp.diags(disc.ambient_coupling(bc, k).matrix)
    capacity = np.asarray(disc.capacity, dtype=float)
    initial = loaded.system.temperatures.initial
    start = disc.uniform_state(bc.point.ambient if initial == "ambient" else initial)
    rows, _ = disc.probe_rows(solve.probe_position)
    readout = {name: np.asarray(rows[i]).ravel() for i, name in enumerate(disc.probe_names[:-1])}
    identity = np.eye(disc.n_nodes)
    means = disc.part_means(identity)
    groups = {part: np.flatnonzero(weights) for part, weights in means.items()}
    modes = mode_table(capacity, matrix, start - solve.state, readout, groups, count)
    capacities = {part: float(capacity[nodes].sum()) for part, nodes in groups.items()}
    return ThermalModes(condition, modes, capacities)
