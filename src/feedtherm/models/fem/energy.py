r"""The energy balance of a run, from integrals kept apart from the solver's matrices.

Over a run, the heat put in by the sources must equal the heat stored plus the heat lost:

.. math::

    E_{in} = \int_0^t \Big(\sum_s P_s\Big)\,dt, \qquad
    E_{lost} = \int_0^t \sum_j \int_{\Gamma_j} h_j (T - T_{\infty,j})\,dA\,dt, \qquad
    E_{stored} = \int_\Omega \rho c\,(T - T_0)\,dV

Source powers come from their definitions (power density × element volume, flux × facet
area), the loss and the stored heat from surface and volume integrals of the field
(:func:`convective_loss`, :func:`stored_heat`). The time integrals use the same weights as
the time scheme (the end of each step for implicit Euler, the trapezoidal rule for
Crank–Nicolson), so that for a correct assembly and solve the balance closes to round-off;
a wrong matrix shows up at once. Contacts and sliding interfaces exchange heat inside the
body and do not appear. Nodes with a prescribed temperature exchange heat with the
outside that no integral here sees: keep them out of balanced runs.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import CellBasis, Functional, MeshTet

from .heat import facet_basis
from .topology import element_volumes, facet_areas

__all__ = ["stored_heat", "ConvectiveLoss", "convective_loss", "volumetric_power", "surface_power", "EnergyLedger"]


@Functional
def _excess(w):
    return w.c * (w.T - w.ref)


def _per_item(values, count: int, nqp: int) -> np.ndarray:
    values = np.broadcast_to(np.asarray(values, dtype=float), (count,))
    return np.repeat(values[:, None], nqp, axis=1)


def stored_heat(basis: CellBasis, heat_capacity, T: np.ndarray, T0) -> float:
    """:math:`\\int \\rho c (T - T_0)\\,dV` [J]; ``heat_capacity`` ρc per element, ``T0`` scalar or nodal."""
    ref = np.broadcast_to(np.asarray(T0, dtype=float), T.shape)
    c = _per_item(heat_capacity, basis.mesh.nelements, basis.X.shape[-1])
    return float(_excess.assemble(basis, c=c, T=basis.interpolate(T), ref=basis.interpolate(ref)))


class ConvectiveLoss:
    """:math:`\\int h (T - T_\\infty)\\,dA` over fixed ``facets`` [W], the facet basis built once.

    ``h`` [W/(m²·K)] scalar or per facet, ``ambient`` [°C or K]. Call with a nodal field.
    """

    def __init__(self, mesh: MeshTet, facets: np.ndarray, h, ambient: float):
        self.facets = np.asarray(facets, dtype=np.int64)
        self.ambient = float(ambient)
        self._basis = facet_basis(mesh, self.facets) if self.facets.size else None
        if self._basis is not None:
            self._h = _per_item(h, self.facets.size, self._basis.X.shape[-1])

    def __call__(self, T: np.ndarray) -> float:
        if self._basis is None:
            return 0.0
        return float(_excess.assemble(self._basis, c=self._h, T=self._basis.interpolate(T), ref=self.ambient))


def convective_loss(mesh: MeshTet, facets: np.ndarray, h, ambient: float, T: np.ndarray) -> float:
    """:math:`\\int h (T - T_\\infty)\\,dA` over ``facets`` [W]; ``h`` scalar or per facet."""
    return ConvectiveLoss(mesh, facets, h, ambient)(T)


def volumetric_power(mesh: MeshTet, power_density) -> float:
    """:math:`\\sum_e \\dot q_e V_e` [W]; ``power_density`` per element [W/m³]."""
    return float(np.sum(np.broadcast_to(power_density, (mesh.nelements,)) * element_volumes(mesh)))


def surface_power(mesh: MeshTet, facets: np.ndarray, flux) -> float:
    """:math:`\\sum_f q''_f A_f` [W]; ``flux`` scalar or per facet [W/m²]."""
    facets = np.asarray(facets, dtype=np.int64)
    return float(np.sum(np.broadcast_to(flux, (facets.size,)) * facet_areas(mesh, facets)))


@dataclass
class EnergyLedger:
    """Heat in and heat lost, accumulated step by step with the time scheme's weights.

    ``theta`` is the scheme's (1 implicit Euler, 0.5 Crank–Nicolson): a step's heat is
    ``dt·(θ·rate_end + (1-θ)·rate_start)``. Give the rates at the start of the run
    (``power``, ``loss`` [W]), then each step's end rates to :meth:`add_step`.
    """

    power: float  #: heat input rate at the current time [W]
    loss: float  #: loss rate at the current time [W]
    theta: float = 1.0
    heat_in: float = 0.0  #: [J]
    heat_lost: float = 0.0  #: [J]

    def add_step(self, dt: float, power: float, loss: float) -> None:
        """Account one step of ``dt`` [s] whose end rates are ``power`` and ``loss`` [W]."""
        th = self.theta
        self.heat_in += dt * (th * power + (1.0 - th) * self.power)
        self.heat_lost += dt * (th * loss + (1.0 - th) * self.loss)
        self.power, self.loss = power, loss

    def error(self, stored: float) -> float:
        """Relative imbalance ``|E_in - E_lost - E_stored| / max(|E_in|, |E_lost| + |E_stored|)``."""
        scale = max(abs(self.heat_in), abs(self.heat_lost) + abs(stored), 1e-300)
        return abs(self.heat_in - self.heat_lost - stored) / scale
