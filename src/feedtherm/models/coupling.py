"""Boundary conditions that follow the temperatures: the models' nonlinear coupling.

Under ``temperatures.coupling = "nonlinear"`` the CHTCs, radiative coefficients, lubricant
viscosities and winding resistances are evaluated at the simulated temperatures.  The
integrator reads them from the state with a :class:`TemperatureReadout` and re-evaluates the
boundary conditions (:class:`Coupling`) whenever a reading has moved by more than the
coupling tolerance since the last evaluation, so a step uses coefficients lagged by at most
that much.  A transient's re-evaluation moves only the readings that have moved by more
than :data:`REFRESH_SHARE` of the tolerance since their last evaluation; the others stay at
the temperature they were evaluated at
(:meth:`~feedtherm.boundary.temperatures.LocalTemperatures.lagging`), and a surface whose
temperature and operating point are those of its last evaluation keeps that evaluation's
coefficients without recomputing them; so does a source whose inputs are those of its last
evaluation (its temperature and, for a motor, its shaft's torque: a bearing warming by the
tolerance recomputes that bearing and its shaft's motor, not the other five of the paper
bench's sources).  Each reading's lag stays bounded by the tolerance;
one motor warming by the tolerance no longer recomputes the other twenty surfaces (in
`compensate`, one to five of the paper bench's 28 readings move by the tolerance between two
re-evaluations, and the surfaces were two thirds of the evaluation's cost).  Steady states
iterate to a fixed point: Picard on the readings, with halved steps when the change grows,
and steps scaled by 1/(1 − r) when successive steps keep a steady signed ratio r of
magnitude above :data:`SLOW_CONTRACTION` (longer for a slow one-way contraction, shorter for
a slowly fading oscillation, r < 0).  A change that keeps growing,
or a reading that leaves the accepted temperatures (−150 to 1000 °C, where the air's and the
oils' properties end), is reported as a divergence, the sign of a heat that grows with the
temperature faster than the surfaces shed it.  Each step's heat and losses are the ones its
equations used, so the energy account still closes.

What a surface's temperature is: the area-weighted mean of its exposed nodes; a source's:
the mean of the state weighted by where its heat enters (a bearing's seat, a motor's
volume, the thread's contact).  Both are averaged over the moving group's positions with
the cycle weights, so a reading does not jump as the nut travels.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
import scipy.sparse as sp

from ..boundary import BoundaryConditions
from ..boundary.temperatures import LocalTemperatures
from .interface import ThermalModel
from .options import ModelOptions

#: Default largest lag [K] of a coupled reading behind the state before re-evaluation.
COUPLING_TOLERANCE = ModelOptions.coupling_tolerance
#: A transient's re-evaluation moves the readings that have moved by more than this share of the
#: tolerance, not only the ones beyond it: the others then need at least half the tolerance more
#: to force the next one.  Measured on `compensate paper --sensors 3 --cycles 1`: refreshing only
#: the readings beyond the tolerance doubled the re-evaluations (6,425 → 12,098) for 3.6
#: surfaces recomputed each; at half, 6,432 re-evaluations and 8.5 surfaces each (21 before).
REFRESH_SHARE = 0.5
#: Relative change of a node's link to its sink above which a coupled run refactorises its steps.
LINK_REFACTOR = 0.2
#: [1/s] ... once that change is also this rate of the node's heat capacity, ``Δg > rate·C``.
#: Below it the right-hand side takes the change: stable for steps up to 2/rate = 200 s (the
#: steps are at most 30 s), and a step matrix hardly changes (a FE node's link is about 0.1 %
#: of its C/dt).  A rate, not a share of C/dt, so that runs with different steps refactorise
#: at the same moments (the observed order in time stays the scheme's).
LINK_RATE_REFACTOR = 0.01
#: A coupled steady state has converged when no node moves by more than this [K].
STEADY_TOLERANCE = 1e-4
STEADY_ITERATIONS = 100
#: Smallest fraction of a Picard step the steady iteration takes when the change grows.
MIN_RELAXATION = 1.0 / 16.0
#: Successive steps with a steady signed ratio |r| above this are rescaled by 1/(1 - r) ...
SLOW_CONTRACTION = 0.5
#: ... up to this many plain steps at once.
MAX_ACCELERATION = 4.0
#: Iterations of growing change, at the smallest fraction, after which the iteration has diverged.
RUNAWAY_ITERATIONS = 8


@dataclass(frozen=True)
class Coupling:
    """How boundary conditions follow the temperatures.

    ``evaluate(base, temperatures)`` gives the boundary conditions of ``base``'s operating
    point evaluated at ``temperatures``; ``tolerance`` [K] is the largest lag of a reading.
    """

    evaluate: Callable[[BoundaryConditions, LocalTemperatures], BoundaryConditions]
    tolerance: float = COUPLING_TOLERANCE

    def __post_init__(self):
        if not self.tolerance > 0.0:
            raise ValueError(f"coupling tolerance must be positive [K], got {self.tolerance!r}")


class TemperatureReadout:
    """The surfaces' and sources' temperatures [K] of a state (see the module notes)."""

    def __init__(self, model: ThermalModel):
        basis = model.boundary_basis(None)
        weights = sp.vstack([basis.exposure, basis.distribution]).tocsr()
        totals = np.asarray(weights.sum(axis=1)).ravel()
        # a surface never exposed, or a source with no place to enter, keeps the frozen value
        used = totals > 0.0
        self._weights = model.restrict(sp.diags(1.0 / totals[used]) @ weights[used])
        # the surfaces' rows come first, then the sources': one split of the values
        surfaces = len(basis.surfaces)
        self._surfaces = [n for n, keep in zip(basis.surfaces, used[:surfaces]) if keep]
        self._sources = [n for n, keep in zip(basis.sources, used[surfaces:]) if keep]

    def __call__(self, state: np.ndarray) -> LocalTemperatures:
        values = (self._weights @ state).tolist()
        split = len(self._surfaces)
        return LocalTemperatures(dict(zip(self._surfaces, values[:split])), dict(zip(self._sources, values[split:])))
