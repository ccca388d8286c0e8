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
product (the method of snapshots, :func:`_compressed`): the basis size is the number of modes
whose singular values exceed ``tolerance`` times the largest one, not a constant.  Each
shift's snapshots are compressed first (:data:`SHIFT_TOLERANCE_FACTOR`), so that neither the
snapshots of every shift nor their Gram matrix are ever held at once, and the inputs are kept
sparse: a fine-mesh basis needs one sparse LU alive at a time and a few GB.  Those
factorisations are PARDISO's Cholesky wherever MKL is there, at every mesh size (not only
above :data:`~feedtherm.models.pardiso.MIN_UNKNOWNS`, as for a time step's one right-hand side):
each is solved for tens of inputs at once, and on the coarse mesh PARDISO solves 27 in 0.017 s
where SuperLU takes 0.048 s.  The POD and the final orthonormalisation work on the snapshots
scaled by the square roots of the (diagonal) capacities, where the capacity inner product is
the Euclidean one.

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
L. Sirovich, "Turbulence and the dynamics of coherent structures, part I: coherent structures",
Quart. Appl. Math. 45 (1987) 561–571.  R. Milk, S. Rave, F. Schindler, "pyMOR — generic
algorithms and interfaces for model order reduction", SIAM J. Sci. Comput. 38 (2016) S194–S216.
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
from ..interface import ThermalModel, affine_value, cycle_weights, film_coefficient, weighted_sum
from .disk import read_npz, write_npz

#: [W/(m²·K)] film coefficient on every surface while the snapshots are taken: still air with
#: radiation from a metal surface is 5-15; the runs' own coefficients enter the reduced operators.
REFERENCE_HTC = 10.0
#: [s] time constants of the shifted snapshots: a reciprocation step, a cycle, the nut's and
#: the screw's warm-up, the bed's (besides s = 0, the steady states).
TIME_CONSTANTS = (2.0, 60.0, 600.0, 6000.0)
#: [s] time constants at which only the inputs that do not move are answered (a surface's sink, a
#: fixed source): a held temperature reaches its value at once, and for its first seconds its answer
#: is a layer √(ατ) thick (3 mm of steel at 0.5 s) that the answers at 2 s cannot hold; without them a
#: pin fin held at its base read 1.0 K below the air 25 mm away at 3 s while being heated
#: (tests/verification/test_reduced_fin.py).  A source's heat grows from nothing: its early answer is
#: smooth, and the moving inputs' answers (most of a basis's cost) are not taken at these shifts.  They
#: are taken at the model's own numbers only, not at a parametric basis's other training points: a
#: held temperature's first seconds hardly depend on a film or a contact, and each shift is a
#: factorisation at each point.
EARLY_TIME_CONSTANTS = (0.2, 0.5, 1.0, 5.0, 20.0)
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
BASIS_VERSION = 5


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


def reference_coefficients(model: ThermalModel, coefficients: dict[str, float] | None = None) -> np.ndarray:
    """Each surface's film coefficient [W/(m²·K)] while the snapshots are taken (in series with the
    model's conduction to the face, :attr:`BoundaryBasis.film`, where it has one).

    A surface whose coefficient the description fixes (``convection.kind = "fixed"``: a
    foundation, a cooled face) takes that coefficient, which no operating point or
    temperature changes, or the one ``coefficients`` gives it (``"surfaces.<name>.coefficient"``,
    a training point of a parametric basis); every other surface :data:`REFERENCE_HTC`.
    """
    from ...system.surfaces import FixedConvection

    surfaces = model.system.surfaces
    coefficients = coefficients or {}
    basis = model.boundary_basis(0)
    out = []
    for name in basis.surfaces:
        surface = surfaces[name]
        if isinstance(surface.convection, FixedConvection):
            out.append(coefficients.get(f"surfaces.{name}.coefficient",
                                        surface.convection.coefficient * surface.chtc_factor))
        else:
            out.append(REFERENCE_HTC)
    out = np.array(out, dtype=float)
    # from the nodes to the air, as the model's links take them (a model with nodes inside its cells)
    return out if basis.film is None else film_coefficient(out, basis.film)


def film_parameters(model: ThermalModel) -> dict[str, float]:
    """The fixed-coefficient surfaces' coefficients (``"surfaces.<name>.coefficient"``: :func:`affine_value`)."""
    from ...system.surfaces import FixedConvection

    return {f"surfaces.{name}.coefficient": affine_value(model.system, f"surfaces.{name}.coefficient")
            for name, surface in model.system.surfaces.items() if isinstance(surface.convection, FixedConvection)}


class TrainingOperators:
    """The full model's conductances and reference links at one point of its parameters.

    ``point`` gives some of the model's conductance parameters (:meth:`ThermalModel.affine_parameters`)
    and fixed surfaces' coefficients (:func:`film_parameters`) other values; ``G_k`` is the
    model's own plus ``Σ_q (θ_q − θ_q⁰) ∂G_k/∂θ_q`` (exact: the conductances are linear in them).
    """

    def __init__(self, model: ThermalModel, point: dict[str, float] | None = None):
        point = dict(point or {})
        own = {p.name: p for p in model.affine_parameters() if p.kind == "conductance"}
        films = film_parameters(model)
        unknown = sorted(set(point) - set(own) - set(films))
        if unknown:
            raise KeyError(f"not a conductance parameter or fixed coefficient of the model: {', '.join(unknown)}")
        self.model = model
        changes = {name: value - own[name].value for name, value in point.items() if name in own and value != own[name].value}
        self.moving = {name: change for name, change in changes.items() if own[name].moves}
        self.static_changes = {name: change for name, change in changes.items() if not own[name].moves}
        self.static = None  # Σ over the parameters whose terms do not move
        for name, change in self.static_changes.items():
            term = change * model.conductance_term(name, 0)
            self.static = term if self.static is None else self.static + term
        self.coefficients = reference_coefficients(model, {n: v for n, v in point.items() if n in films})

    def _plus(self, G, moving_term):
        for name, change in self.moving.items():
            G = G + change * moving_term(name)
        if self.static is not None:
            G = G + self.static
        return G.tocsr() if sp.issparse(G) else G

    def conductance(self, k: int):
        return self._plus(self.model.conductance(k), lambda name: self.model.conductance_term(name, k))

    def mean_conductance(self):
        """The cycle average of :meth:`conductance` (the model's own average and the moving terms' are kept on it)."""
        return self._plus(self._kept_means()[None], self.mean_term)

    def mean_term(self, name: str):
        """The cycle average of ``∂G_k/∂θ`` for the conductance parameter ``name`` (kept on the model)."""
        kept = self._kept_means()
        if name not in kept:
            model = self.model
            kept[name] = weighted_sum(cycle_weights(len(model.positions)),
                                      [model.conductance_term(name, k) for k in range(len(model.positions))])
        return kept[name]

    def _kept_means(self) -> dict:
        model = self.model
        kept = model.__dict__.setdefault("_cycle_averaged_terms", {})
        if None not in kept:
            weights = cycle_weights(len(model.positions))
            kept[None] = weighted_sum(weights, [model.conductance(k) for k in range(len(model.positions))])
        return kept

    def steady_operator(self) -> sp.csc_matrix:
        """The cycle-averaged steady operator: :meth:`mean_conductance` and the averaged links."""
        return (self.mean_conductance() + sp.diags(self.links(None))).tocsc()

    def links(self, k: int | None) -> np.ndarray:
        """Node-to-air conductances [W/K] at position k (None: the cycle average)."""
        return self.model.boundary_basis(k).exposure_by_node @ self.coefficients


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


def basis_key(model: ThermalModel, tolerance: float, time_constants: tuple[float, ...],
              points: tuple[dict[str, float], ...] = ()) -> str:
    """A digest of everything :func:`moment_basis` reads: the operators at every position, the terms
    its training ``points`` change, and its settings."""
    h = hashlib.blake2b(digest_size=20)
    settings = (BASIS_VERSION, tuple(reference_coefficients(model).tolist()), CORRECTED_POSITIONS,
                SHIFT_TOLERANCE_FACTOR, float(tolerance), tuple(map(float, time_constants)), EARLY_TIME_CONSTANTS,
                model.n_nodes, len(model.positions), tuple(tuple(sorted(p.items())) for p in points))
    h.update(repr(settings).encode())

    def add(array: np.ndarray) -> None:
        h.update(np.ascontiguousarray(array).tobytes())

    def add_matrix(matrix) -> None:
        matrix = sp.csr_matrix(matrix)
        matrix.sort_indices()
        for array in (matrix.indptr, matrix.indices, matrix.data):
            add(array)

    add(np.asarray(model.capacity, dtype=float))
    for k in range(len(model.positions)):
        for matrix in (model.conductance(k), model.boundary_basis(k).exposure, model.boundary_basis(k).distribution):
            add_matrix(matrix)
    changed = sorted({name for p in points for name in p if not name.startswith("surfaces.")})
    moving = {p.name: p.moves for p in model.affine_parameters()}
    for name in changed:
        for k in (range(len(model.positions)) if moving[name] else (0,)):
            add_matrix(model.conductance_term(name, k))
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
                 time_constants: tuple[float, ...] = TIME_CONSTANTS, *,
                 points: tuple[dict[str, float], ...] = (), use_cache: bool = True) -> Basis:
    """The basis of :mod:`this module <.basis>` for ``model`` (module notes), from the disk cache when it holds it.

    ``points``: training points beyond the model's own description, each giving some of its
    conductance parameters and fixed coefficients other values (:class:`TrainingOperators`): the
    basis then spans the answers at those too (a parametric reduced model, :mod:`.training`).
    """
    started = time.perf_counter()
    points = tuple(dict(p) for p in points)
    if not use_cache:
        return _build(model, tolerance, time_constants, points)
    path = basis_cache_path(basis_key(model, tolerance, time_constants, points))
    cached = _read_cached(path, started)
    if cached is not None:
        return cached
    basis = _build(model, tolerance, time_constants, points)
    _write_cached(path, basis)
    return basis


def _build(model: ThermalModel, tolerance: float, time_constants: tuple[float, ...],
           points: tuple[dict[str, float], ...]) -> Basis:
    started = time.perf_counter()
    C = np.asarray(model.capacity, dtype=float)
    scale = np.sqrt(C)  # the capacity inner product of x is the Euclidean one of scale ⊙ x (C is diagonal)
    n_positions = len(model.positions)
    fixed, moving = split_inputs(model)
    fixed = fixed.toarray()  # (n, fixed inputs): a few, dense
    # the fixed inputs' answers are corrected at a few positions, the moving inputs' at every one
    corrected_at = sorted({round(i * (n_positions - 1) / (CORRECTED_POSITIONS - 1)) for i in range(CORRECTED_POSITIONS)})
    ones = np.ones(model.n_nodes) / np.sqrt(C.sum())
    factors = _OnePattern()
    # kept: the modes so far, scaled and weighted; once compressed, orthogonal with norms kept_values
    kept, kept_values, count = None, None, 0
    for index, point in enumerate(({}, *points)):
        # another training point than the model's own: the moving inputs at the corrected positions
        # only (their shapes at the others are the first point's, moved)
        moving_at = range(n_positions) if index == 0 else corrected_at
        blocks, snapshots = _point_snapshots(TrainingOperators(model, point), C, fixed, moving, corrected_at,
                                             moving_at, time_constants, tolerance, scale, ones, factors,
                                             EARLY_TIME_CONSTANTS if index == 0 else ())
        count += snapshots
        if kept is None:
            kept = np.hstack(blocks)
        else:  # another point's modes with those so far, compressed far below the tolerance (module notes)
            kept, kept_values = _compressed(np.hstack([kept, *blocks]), SHIFT_TOLERANCE_FACTOR * tolerance,
                                            kept_values)
        del blocks
    weighted, singular_values = _compressed(kept, tolerance, kept_values)
    modes = weighted / singular_values / scale[:, None]
    vectors = orthonormalise(np.column_stack([ones, modes]), scale)
    return Basis(vectors, np.asarray(singular_values), tolerance, count, time.perf_counter() - started)


def _compressed(Y: np.ndarray, rtol: float, orthogonal: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The POD of the scaled snapshots ``Y`` (n, m): its modes above ``rtol`` of the largest
    singular value, each weighted by its singular value (n, r), and the singular values (r,).

    The method of snapshots (Sirovich 1987), as pyMOR's
    :func:`~pymor.algorithms.svd_va.method_of_snapshots`, which computes every block of the Gram
    matrix: the eigenvectors ``W`` of ``YᵀY`` give the weighted modes ``Y W``.  ``orthogonal``:
    the norms of ``Y``'s first columns where those are orthogonal, as a compression's own output
    is; their block of the Gram matrix is then ``diag(orthogonal²)``, not computed (a POD's modes
    are orthogonal to the rounding of the Gram matrix itself, ε times the largest squared
    singular value).  When the modes kept so far (about 750 on the coarse mesh) meet the next
    training point's (about 450), that saves two fifths of the Gram matrix's products.  In the
    scaled coordinates (module notes) the Euclidean product is the capacity one; the modes are
    not re-orthonormalised (pyMOR's ``orth_tol=inf``): what is kept of them is their span, and
    the basis is orthonormalised once at the end.
    """
    import scipy.linalg

    k = 0 if orthogonal is None else len(orthogonal)
    new = Y[:, k:]
    gram = np.empty((Y.shape[1], Y.shape[1]))
    gram[k:, k:] = new.T @ new
    if k:
        gram[:k, :k] = np.diag(np.asarray(orthogonal) ** 2)
        gram[:k, k:] = Y[:, :k].T @ new
        gram[k:, :k] = gram[:k, k:].T
    eigenvalues, W = scipy.linalg.eigh(gram, overwrite_a=True)
    values = np.sqrt(np.clip(eigenvalues[::-1], 0.0, None))
    r = int(np.count_nonzero(values >= rtol * values[0])) if values.size and values[0] > 0.0 else 0
    return Y @ W[:, ::-1][:, :r], values[:r]


#: A column whose part beyond the columns before it is at most this share of its own size depends
#: on them (the relative tolerance of pyMOR's :func:`~pymor.algorithms.gram_schmidt.gram_schmidt`).
DEPENDENT_SHARE = 1e-13


def orthonormalise(X: np.ndarray, scale: np.ndarray) -> np.ndarray:
    """The columns of ``X`` made orthonormal in the capacity inner product (``scale``: the square
    roots of the diagonal capacities), in order: each column keeps its direction beyond those
    before it, and one that depends on them is dropped.

    A Householder QR of ``scale ⊙ X`` (LAPACK, blocked): orthonormal to rounding in one pass, where
    pyMOR's Gram–Schmidt, pair of vectors by pair with the capacity applied to each, took 8 s of a
    coarse basis's 46 s.  A dependent column is rare (the POD modes are orthogonal already); where
    there is one, pyMOR's Gram–Schmidt, which drops it, does the whole.
    """
    scaled = X * scale[:, None]
    Q, R = np.linalg.qr(scaled)
    diagonal = np.diag(R)
    if np.any(np.abs(diagonal) <= DEPENDENT_SHARE * np.linalg.norm(scaled, axis=0)):
        from pymor.algorithms.gram_schmidt import gram_schmidt
        from pymor.core.logger import set_log_levels
        from pymor.vectorarrays.numpy import NumpyVectorSpace

        set_log_levels({"pymor": "WARN"})  # its progress lines are not a run's output
        Q = gram_schmidt(NumpyVectorSpace(X.shape[0]).from_numpy(scaled), copy=False).to_numpy()
    else:
        Q *= np.where(diagonal < 0.0, -1.0, 1.0)  # R's diagonal positive, as Gram–Schmidt's
    return Q / scale[:, None]


def _point_snapshots(ops: TrainingOperators, C, fixed, moving, corrected_at, moving_at, time_constants,
                     tolerance, scale, ones, factors: "_OnePattern",
                     early_time_constants: tuple[float, ...] = ()) -> tuple[list[np.ndarray], int]:
    """One training point's snapshots, compressed per shift: (blocks, snapshots taken)."""
    model = ops.model
    n_positions = len(model.positions)
    averaged_links = ops.links(None)
    conductances = {k: ops.conductance(k) for k in sorted({*corrected_at, *moving_at})}
    G_mean = ops.mean_conductance()
    links = {k: ops.links(k) for k in conductances}
    blocks, count = [], 0
    for tau in (None, *time_constants, *(t for t in early_time_constants if t not in time_constants)):
        shift = 0.0 if tau is None else 1.0 / tau
        mean = factors((G_mean + sp.diags(averaged_links + shift * C)).tocsc())
        x_fixed = mean.solve(fixed)
        if tau is not None and tau not in time_constants:  # an early shift: the fixed inputs alone
            count += _append_block(blocks, x_fixed, C, ones, scale, tolerance)
            del mean, x_fixed
            continue
        # one block step toward each position's own operator (its sliding contact and exposure),
        # x + M̄⁻¹(b − M_k x): the positions' solves as one solve of many right-hand sides
        moved = [k for k in conductances if k in moving_at and moving[k].shape[1]]
        b_moving = {k: moving[k].toarray() for k in moved}
        x_moving = dict(zip(moved, _solve_blocks(mean, [b_moving[k] for k in moved])))
        starts, residuals = [], []
        for k in conductances:
            M_k = conductances[k] + sp.diags(links[k] + shift * C)
            if k in corrected_at:
                starts.append(x_fixed)
                residuals.append(fixed - M_k @ x_fixed)
            if k in x_moving:
                starts.append(x_moving[k])
                residuals.append(b_moving[k] - M_k @ x_moving[k])
        del b_moving, x_moving
        snapshots = [x_fixed] + [x + dx for x, dx in zip(starts, _solve_blocks(mean, residuals))]
        del mean, x_fixed, starts, residuals
        X = np.hstack(snapshots)
        del snapshots
        count += _append_block(blocks, X, C, ones, scale, tolerance)
        del X
    return blocks, count


def _append_block(blocks: list, X: np.ndarray, C, ones, scale, tolerance) -> int:
    """One shift's snapshots ``X`` compressed onto ``blocks``; returns how many were taken.

    The uniform part is the first basis vector: it is taken out of the snapshots, and each is scaled
    to unit capacity norm so that every input counts alike."""
    X = X - np.outer(ones, ones @ (C[:, None] * X))
    norms = np.sqrt(np.einsum("ij,ij->j", X, C[:, None] * X))
    if not norms.size or norms.max() == 0.0:
        return 0
    kept = norms > 1e-12 * norms.max()  # an input with no response beyond the uniform one
    X = X[:, kept] * (scale[:, None] / norms[kept])
    blocks.append(_compressed(X, SHIFT_TOLERANCE_FACTOR * tolerance)[0])
    return X.shape[1]


class _OnePattern:
    """Factorisations of the snapshots' matrices, every one of one pattern and one alive at a time.

    PARDISO's Cholesky wherever it is installed (many right-hand sides: 1.5 s, not SuperLU's 22 s,
    at the fine mesh; module notes), its analysis made for the first matrix and reused
    (:meth:`~feedtherm.models.pardiso.PardisoCholesky.refactor`); elsewhere SuperLU, its
    elimination order computed once.
    """

    def __init__(self):
        self._held = None
        self._order = None

    def __call__(self, A: sp.spmatrix):
        if pardiso.available():
            if self._held is None:
                self._held = pardiso.PardisoCholesky(A)
            else:
                self._held.refactor(A)
            return self._held
        lu = factorize(A, self._order)
        if self._order is None:
            self._order = EliminationOrder(lu)
        return lu


def _solve_blocks(factor, blocks: list[np.ndarray]) -> list[np.ndarray]:
    """``factor.solve`` of each block of right-hand sides, as one call: PARDISO's cost per column
    falls fourfold from 5 columns to 100 (coarse mesh)."""
    if not blocks:
        return []
    solution = factor.solve(np.hstack(blocks))
    return np.split(solution, np.cumsum([b.shape[1] for b in blocks])[:-1], axis=1)


#: Candidate points of a parametric basis's domain (a Latin hypercube of another seed than the
#: training points') whose residual indicator :func:`steady_check` ranks.
CHECK_CANDIDATES = 16
#: How many of the candidates, those of the largest indicator, :func:`steady_check` compares with
#: the full model.
CHECK_POINTS = 2


def _steady_inputs(model: ThermalModel) -> np.ndarray:
    """The inputs whose steady answers the check compares (dense, nodes × inputs): the fixed ones
    and the moving ones averaged over the cycle."""
    fixed, moving = split_inputs(model)
    weights = cycle_weights(len(model.positions))
    if moving and moving[0].shape[1]:
        return sp.hstack([fixed, weighted_sum(weights, moving)]).toarray()
    return fixed.toarray()


def _steady_operator(model: ThermalModel, point: dict[str, float]) -> sp.csc_matrix:
    return TrainingOperators(model, point).steady_operator()


def _galerkin(A: sp.spmatrix, V: np.ndarray, inputs_: np.ndarray,
              reduced: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The reduced steady answers ``V z`` of ``A x = b`` for every input, and the residuals ``b − A V z``
    (``reduced``: ``VᵀAV`` where it is known)."""
    if reduced is None:
        reduced = V.T @ np.asarray(A @ V)
    answers = V @ np.linalg.solve(reduced, V.T @ inputs_)
    return answers, inputs_ - A @ answers


def _indicator(inputs_: np.ndarray, residual: np.ndarray) -> float:
    """:func:`residual_indicator`'s value: the largest residual as a share of its input's size."""
    sizes = np.linalg.norm(inputs_, axis=0)
    return float(np.max(np.linalg.norm(residual, axis=0) / np.where(sizes > 0.0, sizes, 1.0)))


def _galerkin_at(model: ThermalModel, V: np.ndarray, point: dict[str, float],
                 inputs_: np.ndarray) -> tuple[sp.csc_matrix, np.ndarray, float]:
    """At ``point``: the steady operator, the Galerkin answers and :func:`residual_indicator`'s value."""
    A = _steady_operator(model, point)
    reduced, residual = _galerkin(A, V, inputs_)
    return A, reduced, _indicator(inputs_, residual)


class _ProjectedSteadyOperator:
    """``VᵀA(θ)V`` of the steady operator at any point θ, as the sum of projected terms.

    ``A(θ)`` is affine in the conductance parameters and the fixed coefficients
    (:class:`TrainingOperators`): the nominal operator, each parameter's change times its
    cycle-averaged term, each fixed surface's change of coefficient times its exposure.  Each
    term is projected once, on the rows it has; a point then costs sums of r × r matrices, where
    projecting its operator afresh costs a product of the basis's size with the whole mesh.
    """

    def __init__(self, model: ThermalModel, V: np.ndarray):
        self.model, self.V = model, V
        self.nominal = TrainingOperators(model, {})
        self._reference = self._project(self.nominal.steady_operator())
        self._terms: dict[str, np.ndarray] = {}
        self._exposures: dict[int, np.ndarray] = {}

    def _project(self, M: sp.spmatrix) -> np.ndarray:
        M = sp.csr_matrix(M)
        rows = np.flatnonzero(np.diff(M.indptr))  # VᵀMV = V[rows]ᵀ (M V)[rows]
        return self.V[rows].T @ np.asarray(M[rows] @ self.V)

    def at(self, ops: TrainingOperators) -> np.ndarray:
        """``VᵀA(θ)V`` at the point of ``ops``."""
        reduced = self._reference.copy()
        for name, change in {**ops.moving, **ops.static_changes}.items():
            if name not in self._terms:
                self._terms[name] = self._project(ops.mean_term(name) if name in ops.moving
                                                  else self.model.conductance_term(name, 0))
            reduced += change * self._terms[name]
        exposure = self.model.boundary_basis(None).exposure_by_node
        for s in np.flatnonzero(ops.coefficients != self.nominal.coefficients):
            if s not in self._exposures:
                self._exposures[s] = self._project(sp.diags(exposure[:, s].toarray().ravel()))
            reduced += (ops.coefficients[s] - self.nominal.coefficients[s]) * self._exposures[s]
        return reduced


def residual_indicator(model: ThermalModel, basis: Basis, point: dict[str, float]) -> float:
    """The largest relative residual ``‖b − A V z‖ / ‖b‖`` of the inputs' Galerkin steady answers at
    ``point`` (cycle-averaged operator, reference coefficients).

    It needs no solve of the full model (a sparse product with the basis and a solve of its size),
    so it can rank many points of the domain; it is not the error, whose size it indicates only
    up to the operator's conditioning.
    """
    return _galerkin_at(model, basis.vectors, point, _steady_inputs(model))[2]


def steady_check(model: ThermalModel, basis: Basis, candidates: tuple[dict[str, float], ...],
                 checked: int = CHECK_POINTS) -> dict:
    """The basis against the full model at the ``checked`` candidates of the largest
    :func:`residual_indicator`: each input's steady answer (cycle-averaged operator, reference
    coefficients), the full model's ``x = A⁻¹b`` and the reduced model's Galerkin answer
    ``V (VᵀAV)⁻¹ Vᵀb``.

    Returns the largest nodal difference of the two as a share of the full answer's range
    ``max|x − V z| / (max x − min x)`` over the inputs and the points checked, with the input and
    the candidate where it is largest, and the largest indicator: a check against the full model
    where the basis was not trained and where the indicator says it is weakest among the
    candidates, not a bound elsewhere.
    """
    inputs_ = _steady_inputs(model)
    projected = _ProjectedSteadyOperator(model, basis.vectors)
    indicators, largest = [], []  # largest: (indicator, candidate, operator, Galerkin answers) of the top ones
    for index, point in enumerate(candidates):
        ops = TrainingOperators(model, point)
        A = ops.steady_operator()
        reduced, residual = _galerkin(A, basis.vectors, inputs_, projected.at(ops))
        indicator = _indicator(inputs_, residual)
        indicators.append(indicator)
        largest = sorted([*largest, (indicator, index, A, reduced)], key=lambda c: -c[0])[:checked]
    worst = {"steady_check_share": 0.0, "steady_check_point": None, "steady_check_input": None}
    for _, index, A, reduced in largest:
        exact = (pardiso.PardisoCholesky(A) if pardiso.available() else factorize(A)).solve(inputs_)
        spans = exact.max(axis=0) - exact.min(axis=0)
        shares = np.abs(exact - reduced).max(axis=0) / np.where(spans > 0.0, spans, 1.0)
        j = int(np.argmax(shares))
        if shares[j] >= worst["steady_check_share"]:
            worst = {"steady_check_share": float(shares[j]), "steady_check_point": index, "steady_check_input": j}
    worst["steady_check_points"] = len(largest)
    worst["steady_check_candidates"] = len(candidates)
    worst["steady_check_indicator"] = float(max(indicators)) if indicators else 0.0
    return worst
