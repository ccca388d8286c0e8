r"""The projection basis of a reduced model: moments of the full model's transfer functions.

The full model's temperatures answer its inputs — each source's heat at each position of the
moving group, each surface's sink — through :math:`(G_k + A_k + sC)^{-1}` (Laplace variable
:math:`s`).  Rational Krylov (moment matching) spans those answers at a few shifts, from
:math:`s = 0` (the steady states) to :math:`s = 1/\tau` for time constants from a
reciprocation step to the parts' own (Grimme 1997; Antoulas 2005, ch. 11).  The snapshots
are taken with the cycle-averaged operator, one factorisation per shift, and corrected
toward each position's own operator by one block step
:math:`x_k \leftarrow x_k + \bar M^{-1}(b_k - M_k x_k)`, so that the sliding contact under
the nut at position k is in the span too.  The uniform state is the basis's first vector, so
the reduced model keeps the full model's energy balance exactly (its Galerkin equation for
that vector is the balance).

The snapshots are compressed by a proper orthogonal decomposition in the capacity inner
product (pyMOR's :func:`~pymor.algorithms.pod.pod`): the basis size is the number of modes
whose singular values exceed ``tolerance`` times the largest one, not a constant.  Each
shift's snapshots are compressed first (:data:`SHIFT_TOLERANCE_FACTOR`), so that neither the
snapshots of every shift nor their Gram matrix are ever held at once, and the inputs are kept
sparse: a fine-mesh basis needs one sparse LU alive at a time and a few GB.

A basis depends only on the full model's operators (capacity, conduction and contacts at
every position, where surfaces and sources act) and on the settings above, so it is kept on
disk under a digest of all of them (:func:`basis_key`, in ``cache_root()/bases``) and read
back by the next run of the same model: a description that changes no geometry, material or
joint (another condition, duty cycle or coefficient) reuses it.

The boundary conditions are not known when the model is built (they follow the operating
point and, coupled, the temperatures); the snapshots use a reference film coefficient
(:data:`REFERENCE_HTC`) on every surface whose coefficient follows them, and its own on a
surface whose coefficient the description fixes (:func:`reference_coefficients`: a foundation
at 800 W/(m²·K) taken at 10 left the base plate's state out of the span, 0.12 K at the front bearing).  The
reduced operators themselves take each run's coefficients exactly: they are sums of
per-surface projected matrices.

References
----------
E. J. Grimme, *Krylov projection methods for model reduction*, PhD thesis, University of
Illinois, 1997.  A. C. Antoulas, *Approximation of Large-Scale Dynamical Systems*, SIAM, 2005.
R. Milk, S. Rave, F. Schindler, "pyMOR — generic algorithms and interfaces for model order
reduction", SIAM J. Sci. Comput. 38 (2016) S194–S216.
"""

from __future__ import annotations

import hashlib
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from ...constants import cache_root
from .. import pardiso
from ..direct import EliminationOrder, factorize
from ..interface import ThermalModel, cycle_weights, film_coefficient, weighted_sum
from .disk import read_npz, write_npz

#: [W/(m²·K)] film coefficient on every surface while the snapshots are taken: still air with
#: radiation from a metal surface is 5-15; the runs' own coefficients enter the reduced operators.
REFERENCE_HTC = 10.0
#: [s] time constants of the shifted snapshots: a reciprocation step, a cycle, the nut's and
#: the screw's warm-up, the bed's (besides s = 0, the steady states).
TIME_CONSTANTS = (2.0, 60.0, 600.0, 6000.0)
#: Positions (spread over the stroke, the ends included) at which the answers to the inputs that
#: do not move are corrected toward the position's own operator.
CORRECTED_POSITIONS = 5
#: Each shift's snapshots are compressed by a POD of their own before the final one, keeping the
#: modes above this fraction of the tolerance (times the shift's largest singular value): the
#: dropped parts change the final singular values by at most 0.1 × tolerance × √shifts of the largest.
SHIFT_TOLERANCE_FACTOR = 0.1
#: Default relative POD tolerance (singular values below it times the largest are dropped).
TOLERANCE = 1e-5
#: Changes whenever the way a basis is built changes, so that older cached bases are not read.
BASIS_VERSION = 2


@dataclass(frozen=True)
class Basis:
    """A capacity-orthonormal basis ``vectors`` (n, r), the uniform state first, and how it was made."""

    vectors: np.ndarray
    singular_values: np.ndarray
    tolerance: float
    snapshots: int
    seconds: float  # building it (or, read from the cache, reading it)
    cached: bool = False

    @property
    def size(self) -> int:
        return self.vectors.shape[1]


def reference_coefficients(model: ThermalModel) -> np.ndarray:
    """Each surface's film coefficient [W/(m²·K)] while the snapshots are taken (in series with the
    model's conduction to the face, :attr:`BoundaryBasis.film`, where it has one).

    A surface whose coefficient the description fixes (``convection.kind = "fixed"``: a
    foundation, a cooled face) takes that coefficient, which no operating point or
    temperature changes; every other surface :data:`REFERENCE_HTC`.
    """
    from ...system.surfaces import FixedConvection

    surfaces = model.system.surfaces
    basis = model.boundary_basis(0)
    out = []
    for name in basis.surfaces:
        surface = surfaces[name]
        fixed = isinstance(surface.convection, FixedConvection)
        out.append(surface.convection.coefficient * surface.chtc_factor if fixed else REFERENCE_HTC)
    out = np.array(out, dtype=float)
    # from the nodes to the air, as the model's links take them (a model with nodes inside its cells)
    return out if basis.film is None else film_coefficient(out, basis.film)


def reference_links(model: ThermalModel, k: int | None) -> np.ndarray:
    """Node-to-air conductances [W/K] with :func:`reference_coefficients` at position k."""
    return model.boundary_basis(k).exposure_by_node @ reference_coefficients(model)


def inputs(model: ThermalModel, k: int) -> sp.csc_matrix:
    """The full model's input vectors at position k: each source's heat shares, each surface's sink (n, m), sparse."""
    basis = model.boundary_basis(k)
    sinks = basis.exposure_by_node @ sp.diags(reference_coefficients(model))
    return sp.hstack([basis.distribution_by_node, sinks]).tocsc()


def split_inputs(model: ThermalModel) -> tuple[sp.csc_matrix, list[sp.csc_matrix]]:
    """The inputs that are the same at every position (n, m), and per position those that are not (sparse:
    dense, they would take n × inputs × positions numbers, 1.6 GB on the fine mesh)."""
    per_position = [inputs(model, k) for k in range(len(model.positions))]
    first = per_position[0]
    same = np.ones(first.shape[1], dtype=bool)
    for b in per_position[1:]:
        same &= np.asarray(abs(b - first).max(axis=0).todense()).ravel() == 0.0
    return first[:, np.flatnonzero(same)], [b[:, np.flatnonzero(~same)] for b in per_position]


def basis_key(model: ThermalModel, tolerance: float, time_constants: tuple[float, ...]) -> str:
    """A digest of everything :func:`moment_basis` reads: the operators at every position and its settings."""
    h = hashlib.blake2b(digest_size=20)
    settings = (BASIS_VERSION, tuple(reference_coefficients(model).tolist()), CORRECTED_POSITIONS,
                SHIFT_TOLERANCE_FACTOR, float(tolerance), tuple(map(float, time_constants)),
                model.n_nodes, len(model.positions))
    h.update(repr(settings).encode())

    def add(array: np.ndarray) -> None:
        h.update(np.ascontiguousarray(array).tobytes())

    add(np.asarray(model.capacity, dtype=float))
    for k in range(len(model.positions)):
        for matrix in (model.conductance(k), model.boundary_basis(k).exposure, model.boundary_basis(k).distribution):
            matrix = sp.csr_matrix(matrix)
            matrix.sort_indices()
            for array in (matrix.indptr, matrix.indices, matrix.data):
                add(array)
    return h.hexdigest()


def basis_cache_path(key: str) -> Path:
    """Where the basis of digest ``key`` (:func:`basis_key`) is kept."""
    return cache_root() / "bases" / f"{key}.npz"


def _read_cached(path: Path, started: float) -> Basis | None:
    return read_npz(path, lambda data: Basis(data["vectors"], data["singular_values"], float(data["tolerance"]),
                                             int(data["snapshots"]), time.perf_counter() - started, cached=True))


def _write_cached(path: Path, basis: Basis) -> None:
    write_npz(path, {"vectors": basis.vectors, "singular_values": basis.singular_values,
                     "tolerance": basis.tolerance, "snapshots": basis.snapshots})


def moment_basis(model: ThermalModel, tolerance: float = TOLERANCE,
                 time_constants: tuple[float, ...] = TIME_CONSTANTS, *, use_cache: bool = True) -> Basis:
    """The basis of :mod:`this module <.basis>` for ``model`` (module notes), from the disk cache when it holds it."""
    started = time.perf_counter()
    if not use_cache:
        return _build(model, tolerance, time_constants)
    path = basis_cache_path(basis_key(model, tolerance, time_constants))
    cached = _read_cached(path, started)
    if cached is not None:
        return cached
    basis = _build(model, tolerance, time_constants)
    _write_cached(path, basis)
    return basis


def _build(model: ThermalModel, tolerance: float, time_constants: tuple[float, ...]) -> Basis:
    from pymor.algorithms.gram_schmidt import gram_schmidt
    from pymor.algorithms.pod import pod
    from pymor.core.logger import set_log_levels
    from pymor.operators.numpy import NumpyMatrixOperator
    from pymor.vectorarrays.numpy import NumpyVectorSpace

    set_log_levels({"pymor": "WARN"})  # its progress lines are not a run's output

    started = time.perf_counter()
    C = np.asarray(model.capacity, dtype=float)
    n_positions = len(model.positions)
    averaged_links = reference_links(model, None)
    links = [reference_links(model, k) for k in range(n_positions)]
    G_mean = weighted_sum(cycle_weights(n_positions), [model.conductance(k) for k in range(n_positions)])
    fixed, moving = split_inputs(model)
    # the fixed inputs' answers are corrected at a few positions, the moving inputs' at every one
    corrected_at = sorted({round(i * (n_positions - 1) / (CORRECTED_POSITIONS - 1)) for i in range(CORRECTED_POSITIONS)})
    space = NumpyVectorSpace(model.n_nodes)
    product = NumpyMatrixOperator(sp.diags(C).tocsr())
    ones = np.ones(model.n_nodes) / np.sqrt(C.sum())
    order = None  # every shift's matrix has one pattern: its elimination order is computed once
    blocks, count = [], 0
    fixed = fixed.toarray()  # (n, fixed inputs): a few, dense
    for tau in (None, *time_constants):
        shift = 0.0 if tau is None else 1.0 / tau
        A = (G_mean + sp.diags(averaged_links + shift * C)).tocsc()
        if pardiso.suits(model.n_nodes):  # 1.5 s, not SuperLU's 22 s, at the fine mesh
            mean = pardiso.PardisoCholesky(A)
        else:
            mean = factorize(A, order)
            if order is None:
                order = EliminationOrder(mean)
        x_fixed = mean.solve(fixed)
        snapshots = [x_fixed]
        for k in range(n_positions):
            # one block step toward position k's own operator (its sliding contact and exposure)
            M_k = model.conductance(k) + sp.diags(links[k] + shift * C)
            if k in corrected_at:
                snapshots.append(x_fixed + mean.solve(fixed - M_k @ x_fixed))
            if moving[k].shape[1]:
                b = moving[k].toarray()
                x = mean.solve(b)
                snapshots.append(x + mean.solve(b - M_k @ x))
        del mean, x_fixed
        X = np.hstack(snapshots)
        del snapshots
        # the uniform part is the first basis vector: take it out of the snapshots, then scale
        # each snapshot to unit capacity norm so that every input counts alike
        X -= np.outer(ones, ones @ (C[:, None] * X))
        norms = np.sqrt(np.einsum("ij,ij->j", X, C[:, None] * X))
        kept = norms > 1e-12 * norms.max()  # an input with no response beyond the uniform one
        X = X[:, kept] / norms[kept]
        count += X.shape[1]
        # compressed per shift, far below the tolerance (module notes): only its modes are kept
        modes, values = pod(space.from_numpy(X), product=product, rtol=SHIFT_TOLERANCE_FACTOR * tolerance)
        del X
        blocks.append(modes.to_numpy() * values)
    Y = np.hstack(blocks)
    del blocks
    modes, singular_values = pod(space.from_numpy(Y), product=product, rtol=tolerance)
    del Y
    vectors = gram_schmidt(space.from_numpy(np.column_stack([ones, modes.to_numpy()])), product=product)
    return Basis(vectors.to_numpy(), np.asarray(singular_values), tolerance, count,
                 time.perf_counter() - started)
