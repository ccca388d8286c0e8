r"""Linear heat conduction on P1 tetrahedra: assembly, steady solve, theta time stepping.

The weak form, for a test function :math:`v`,

.. math::

    \int_\Omega \rho c\,\dot T v\,dV + \int_\Omega k \nabla T\cdot\nabla v\,dV
    + \sum_j \int_{\Gamma_j} h_j (T - T_{\infty,j}) v\,dA
    = \int_\Omega \dot q v\,dV + \int_{\Gamma_q} q'' v\,dA

gives :math:`C\dot T + G T = q`, with :math:`G` the conduction matrix plus the convection
(Robin) matrices and any interface couplings, and :math:`q` the sources plus
:math:`h T_\infty` terms. Material data are per element (``k``, ``ρc`` arrays, one value
per tetrahedron); convection data per facet. Everything is SI: W/(m·K), J/(m³·K), W/m³,
W/m², W/(m²·K), °C or K (the equations are linear, so either, consistently).

Time stepping is the theta method (``theta=1`` implicit Euler, ``theta=0.5`` Crank–Nicolson):

.. math::

    \left(\frac{C}{\Delta t} + \theta G^{n+1}\right) T^{n+1}
    = \left(\frac{C}{\Delta t} - (1-\theta) G^{n}\right) T^{n} + \theta q^{n+1} + (1-\theta) q^{n}

The left-hand matrix is factorised once (SuperLU, :class:`Direct`) per distinct operator
and step size and reused: a moving part visits a finite set of positions, each one
factorisation. For large meshes :class:`ConjugateGradient` solves each step iteratively
instead, in the matrix's own memory.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Hashable
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import cg, splu
from skfem import BilinearForm, CellBasis, ElementTetP1, FacetBasis, LinearForm, MeshTet
from skfem.helpers import dot, grad

__all__ = [
    "ELEMENT",
    "cell_basis",
    "facet_basis",
    "conduction_matrix",
    "capacity_matrix",
    "facet_mass_matrix",
    "facet_load",
    "volumetric_load",
    "HeatOperator",
    "convection",
    "Direct",
    "ConjugateGradient",
    "solve_steady",
    "ThetaStepper",
]

ELEMENT = ElementTetP1()


def cell_basis(mesh: MeshTet) -> CellBasis:
    """P1 basis on every tetrahedron (quadrature exact for the mass matrix)."""
    return CellBasis(mesh, ELEMENT, intorder=2)


def facet_basis(mesh: MeshTet, facets: np.ndarray) -> FacetBasis:
    """P1 trace basis on the given boundary facets (quadrature exact for the facet mass)."""
    return FacetBasis(mesh, ELEMENT, facets=np.asarray(facets, dtype=np.int64), intorder=2)


def _at_quadrature(values, count: int, basis, what: str) -> np.ndarray:
    """A scalar or one value per element/facet, spread over the quadrature points."""
    values = np.asarray(values, dtype=float)
    if values.ndim == 0:
        values = np.broadcast_to(values, (count,))
    if values.shape != (count,):
        raise ValueError(
            f"{what}: expected a scalar or {count} values (one per element or facet), got shape {values.shape}"
        )
    return np.repeat(values[:, None], basis.X.shape[-1], axis=1)


@BilinearForm
def _laplace(u, v, w):
    return w.k * dot(grad(u), grad(v))


@BilinearForm
def _mass(u, v, w):
    return w.c * u * v


@LinearForm
def _load(v, w):
    return w.s * v


def conduction_matrix(basis: CellBasis, conductivity) -> sp.csr_matrix:
    """:math:`\\int k \\nabla\\phi_i\\cdot\\nabla\\phi_j\\,dV`; ``conductivity`` [W/(m·K)] per element."""
    k = _at_quadrature(conductivity, basis.mesh.nelements, basis, "conductivity")
    return _laplace.assemble(basis, k=k).tocsr()


def capacity_matrix(basis: CellBasis, heat_capacity, lumped: bool = False) -> sp.csr_matrix:
    """:math:`\\int \\rho c\\,\\phi_i\\phi_j\\,dV`; ``heat_capacity`` ρc [J/(m³·K)] per element.

    ``lumped=True`` gives the row-sum diagonal (each node gets ρc·V/4 of each tetrahedron
    around it): no over- or undershoot after a sudden change, the same total capacity.
    """
    c = _at_quadrature(heat_capacity, basis.mesh.nelements, basis, "heat_capacity")
    m = _mass.assemble(basis, c=c).tocsr()
    return sp.diags(np.asarray(m.sum(axis=1)).ravel()).tocsr() if lumped else m


def facet_mass_matrix(mesh: MeshTet, facets: np.ndarray, weight=1.0, lumped: bool = False) -> sp.csr_matrix:
    """:math:`\\int_\\Gamma w\\,\\phi_i\\phi_j\\,dA` over ``facets``; ``weight`` per facet (N×N).

    ``lumped=True`` gives the row-sum diagonal (a third of each triangle's weighted area to
    each of its nodes).
    """
    facets = np.asarray(facets, dtype=np.int64)
    if facets.size == 0:
        return sp.csr_matrix((mesh.nvertices, mesh.nvertices))
    fb = facet_basis(mesh, facets)
    m = _mass.assemble(fb, c=_at_quadrature(weight, facets.size, fb, "weight")).tocsr()
    return sp.diags(np.asarray(m.sum(axis=1)).ravel()).tocsr() if lumped else m


def facet_load(mesh: MeshTet, facets: np.ndarray, flux) -> np.ndarray:
    """:math:`\\int_\\Gamma q''\\phi_i\\,dA`; ``flux`` q'' [W/m²] per facet (positive into the body)."""
    facets = np.asarray(facets, dtype=np.int64)
    if facets.size == 0:
        return np.zeros(mesh.nvertices)
    fb = facet_basis(mesh, facets)
    return _load.assemble(fb, s=_at_quadrature(flux, facets.size, fb, "flux"))


def volumetric_load(basis: CellBasis, power_density) -> np.ndarray:
    """:math:`\\int \\dot q\\,\\phi_i\\,dV`; ``power_density`` [W/m³] per element."""
    s = _at_quadrature(power_density, basis.mesh.nelements, basis, "power_density")
    return _load.assemble(basis, s=s)


@dataclass(frozen=True)
class HeatOperator:
    """The right-hand side of :math:`C\\dot T = q - G T`: conductances and heat loads.

    Parts add up: ``conduction + convection + contact``.
    """

    conductance: sp.csr_matrix  #: G [W/K], N×N
    load: np.ndarray  #: q [W], N

    def __add__(self, other: "HeatOperator") -> "HeatOperator":
        return HeatOperator((self.conductance + other.conductance).tocsr(), self.load + other.load)

    @classmethod
    def zero(cls, n: int) -> "HeatOperator":
        return cls(sp.csr_matrix((n, n)), np.zeros(n))

    @classmethod
    def conduction(cls, matrix: sp.spmatrix) -> "HeatOperator":
        return cls(sp.csr_matrix(matrix), np.zeros(matrix.shape[0]))

    @classmethod
    def source(cls, load: np.ndarray) -> "HeatOperator":
        n = load.size
        return cls(sp.csr_matrix((n, n)), np.asarray(load, dtype=float))


def convection(mesh: MeshTet, facets: np.ndarray, h, ambient: float, lumped: bool = False) -> HeatOperator:
    """Robin term :math:`\\int h (T - T_\\infty) v\\,dA` on ``facets``.

    ``h`` [W/(m²·K)] scalar or per facet, ``ambient`` T∞ [°C or K].
    """
    m = facet_mass_matrix(mesh, facets, h, lumped=lumped)
    return HeatOperator(m, ambient * np.asarray(m.sum(axis=1)).ravel())


class Direct:
    """Sparse LU factorisation (SuperLU): exact, reusable, but its fill-in grows fast in 3D.

    A 70,000-node block factorises in about 6 s and 2 GB, a 280,000-node one in about 3 min
    and 15–20 GB (this machine); keep it to coarse and medium meshes.
    """

    def prepare(self, A: sp.spmatrix):
        lu = splu(sp.csc_matrix(A))
        return lambda b, x0: lu.solve(b)


@dataclass(frozen=True)
class ConjugateGradient:
    """Conjugate gradients with a Jacobi preconditioner, warm-started from the last field.

    The matrices here are symmetric positive definite (conduction, capacity, convection and
    contact terms are). Memory stays at the matrix's; the iteration count grows with the
    step size and the mesh (80–130 iterations for dt = 10 s on 70,000–280,000 nodes).
    """

    rtol: float = 1e-10  #: relative residual
    maxiter: int = 20000

    def prepare(self, A: sp.spmatrix):
        A = sp.csr_matrix(A)
        jacobi = sp.diags(1.0 / A.diagonal())

        def solve(b, x0):
            x, info = cg(A, b, x0=x0, rtol=self.rtol, atol=0.0, M=jacobi, maxiter=self.maxiter)
            if info != 0:
                raise RuntimeError(f"conjugate gradients did not reach rtol={self.rtol} in {self.maxiter} iterations")
            return x

        return solve


def _split(n: int, fixed: np.ndarray | None) -> tuple[np.ndarray, np.ndarray]:
    """Free and fixed nodes; ``fixed`` keeps the caller's order (its values follow it)."""
    fixed = np.zeros(0, dtype=np.int64) if fixed is None else np.asarray(fixed, dtype=np.int64).ravel()
    if np.unique(fixed).size != fixed.size:
        raise ValueError("a node is fixed twice")
    free = np.setdiff1d(np.arange(n), fixed)
    return free, fixed


def solve_steady(
    operator: HeatOperator,
    fixed: np.ndarray | None = None,
    fixed_values=None,
    solver: Direct | ConjugateGradient | None = None,
) -> np.ndarray:
    """Solve :math:`G T = q`, with ``T[fixed] = fixed_values`` if given.

    Without fixed nodes, G must be non-singular: some convection or contact to a fixed
    temperature somewhere. ``solver`` is :class:`Direct` (default) or :class:`ConjugateGradient`.
    """
    solver = Direct() if solver is None else solver
    G, q = operator.conductance, operator.load
    free, fixed = _split(q.size, fixed)
    T = np.zeros(q.size)
    if fixed.size:
        T[fixed] = np.broadcast_to(np.asarray(fixed_values, dtype=float), fixed.shape)
    rhs = q[free] - G[free][:, fixed] @ T[fixed]
    T[free] = solver.prepare(G[free][:, free])(rhs, np.zeros(free.size))
    return T


class ThetaStepper:
    """Theta-method steps of :math:`C\\dot T + G(t) T = q(t)` with cached factorisations.

    Parameters
    ----------
    capacity : sparse matrix
        C [J/K], consistent or lumped.
    theta : float
        1 implicit Euler (default), 0.5 Crank–Nicolson.
    fixed : ndarray of int, optional
        Nodes with prescribed temperatures (Dirichlet).
    cache_size : int
        How many prepared matrices (factorisations) to keep, least recently used dropped first.
    solver : Direct or ConjugateGradient
        :class:`Direct` by default.
    """

    def __init__(
        self,
        capacity: sp.spmatrix,
        theta: float = 1.0,
        fixed: np.ndarray | None = None,
        cache_size: int = 64,
        solver: Direct | ConjugateGradient | None = None,
    ):
        if not 0.5 <= theta <= 1.0:
            raise ValueError(f"theta must lie in [0.5, 1] (0.5 Crank–Nicolson, 1 implicit Euler), got {theta}")
        self.capacity = sp.csr_matrix(capacity)
        self.theta = float(theta)
        self.free, self.fixed = _split(capacity.shape[0], fixed)
        self.cache_size = int(cache_size)
        self._cache: OrderedDict = OrderedDict()
        self.solver = Direct() if solver is None else solver
        self.factorisations = 0  #: how many matrices were prepared (factorised) so far

    def _factor(self, G: sp.spmatrix, dt: float, key: Hashable | None):
        cache_key = None if key is None else (key, dt)
        if cache_key is not None and cache_key in self._cache:
            self._cache.move_to_end(cache_key)
            return self._cache[cache_key]
        A = (self.capacity / dt + self.theta * G).tocsr()
        solve = self.solver.prepare(A[self.free][:, self.free])
        coupling = A[self.free][:, self.fixed]
        self.factorisations += 1
        if cache_key is not None:
            self._cache[cache_key] = (solve, coupling)
            while len(self._cache) > self.cache_size:
                self._cache.popitem(last=False)
        return solve, coupling

    def step(
        self,
        T: np.ndarray,
        dt: float,
        old: HeatOperator,
        new: HeatOperator,
        key: Hashable | None = None,
        fixed_values=None,
    ) -> np.ndarray:
        """One step of ``dt`` [s] from ``T`` (operator ``old``) to the end (operator ``new``).

        ``key`` names ``new``'s conductance matrix (e.g. a position index): steps with the same
        key and ``dt`` reuse one factorisation. Without a key every step factorises.
        ``fixed_values`` are the Dirichlet temperatures at the end of the step.
        """
        th = self.theta
        rhs = self.capacity @ T / dt + th * new.load + (1.0 - th) * old.load
        if th < 1.0:
            rhs -= (1.0 - th) * (old.conductance @ T)
        solve, coupling = self._factor(new.conductance, dt, key)
        T_new = np.empty_like(T)
        if self.fixed.size:
            T_new[self.fixed] = np.broadcast_to(np.asarray(fixed_values, dtype=float), self.fixed.shape)
            T_new[self.free] = solve(rhs[self.free] - coupling @ T_new[self.fixed], T[self.free])
        else:
            T_new[:] = solve(rhs, T)
        return T_new
