"""A reduced linear state-space model of the feed drive, for the model-based estimator.

The fast model's cycle-averaged operators (the table's motion averaged over a stroke, as the
study's runs, :mod:`.data`) at frozen coefficients give

.. math:: C \\dot T = -\\Big(G + \\sum_s h_s\\,\\mathrm{diag}(e_s)\\Big) T + \\sum_j q_j\\,b_j
          + \\sum_s h_s T_{\\infty}\\, e_s ,

with ``C`` the capacities, ``G`` conduction and contacts, ``e_s`` the exposed area of surface
``s`` per node and ``h_s`` its coefficient (convection + radiation) at the operating point,
``b_j`` where source ``j``'s heat ``q_j`` enters, and ``T_∞`` the ambient.  The operating point
enters only through the numbers ``h_s`` and ``q_j``, so the model is *affine in them*: reduced
once, it is evaluated at any speed and ambient by a few small matrix sums.

Reduction.  In the symmetric coordinates ``z = C^{1/2} T`` the state matrix
``-C^{-1/2}(G + Σ h_s diag e_s)C^{-1/2}`` is symmetric negative definite.  The basis is found by
balanced truncation [1]_ at a reference operating point (gramians solved exactly in the
eigenbasis of that matrix: ``P_ij = (B̃B̃ᵀ)_ij / (λ_i + λ_j)``), then orthonormalised together with
the uniform field ``C^{1/2}·1``; the model is projected onto it by Galerkin projection.  A
Galerkin projection of a symmetric negative-definite matrix on an orthonormal basis stays
symmetric negative definite, so the reduced model is stable at *every* operating point, not only
at the reference one; and with the uniform field in the basis a machine at the ambient is
represented exactly (an ambient drift alone causes no reduction error at rest).

References
----------
.. [1] B. C. Moore, "Principal component analysis in linear systems: controllability,
   observability, and model reduction", IEEE Trans. Automatic Control 26(1), 17-32 (1981);
   the square-root form: A. C. Antoulas, Approximation of Large-Scale Dynamical Systems,
   SIAM (2005), §7.1.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ...boundary import BoundaryConditions, boundary_conditions_at
from ...boundary.operating import OperatingPoint
from ...system.overlay import Overlay
from ...constants import ELONGATION_PROBE
from ...errors import FeedthermError
from ...models.interface import cycle_weights, film_coefficient, source_powers, surface_coefficients, weighted_sum
from ...simulate import discretize
from ...system.load import LoadedSystem

#: States of the reduced model (besides the uniform field): "a few dozen" (issue 16); the
#: Hankel singular values of the paper bench fall by 1e-4 of the largest at about 20 states.
DEFAULT_ORDER = 30


@dataclass(frozen=True)
class ReducedModel:
    """``ζ̇ = (A0 + Σ h_s A_s) ζ + Bq q + T_∞ Σ h_s f_s``; outputs ``y = Cy ζ + dy``.

    Units: ``ζ`` in √(J/K)·K (the symmetric coordinates), ``h`` [W/(m²·K)], ``q`` [W], ``T_∞`` [K];
    outputs are temperatures [K] and D [m] in the order of :attr:`outputs`.
    """

    surfaces: list[str]
    sources: list[str]
    outputs: list[str]
    A0: np.ndarray  # (r, r)
    A_surface: np.ndarray  # (surfaces, r, r)
    f_surface: np.ndarray  # (surfaces, r)
    Bq: np.ndarray  # (r, sources)
    Cy: np.ndarray  # (outputs, r)
    dy: np.ndarray  # (outputs,)
    uniform: np.ndarray  # (r,): ζ of the machine at 1 K throughout
    hankel: np.ndarray  # the Hankel singular values at the reference point (all kept and dropped)
    ambient: str = "ambient"  # the name of the ambient reading, the model's input (room.ambient_sensor)
    #: each surface's conduction from its nodes to its face [m²·K/W], in series with h_s (BoundaryBasis.film)
    film: np.ndarray | None = None
    #: the positioning error E along the stroke, ``E = C_stroke ζ + d_stroke`` [m] at the table positions
    #: ``stroke_x`` [m] (:func:`.data.stroke_positions`); read through the same basis, not weighed in its
    #: choice (None: a model without a table, or a law document written before them)
    stroke_x: np.ndarray | None = None
    C_stroke: np.ndarray | None = None
    d_stroke: np.ndarray | None = None

    @property
    def order(self) -> int:
        return self.A0.shape[0]

    def matrices(self, h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``A`` and the ambient's input column at coefficients ``h`` (one per surface)."""
        return self.A0 + np.tensordot(h, self.A_surface, axes=1), h @ self.f_surface

    def operating(self, system, point: OperatingPoint, overlay: Overlay | None = None) -> tuple[np.ndarray, np.ndarray]:
        """``h`` per surface and ``q`` per source at ``point`` (frozen coefficients, nominal loss models;
        ``overlay``: printed values laid over them)."""
        bc = boundary_conditions_at(system, point, overlay)
        return coefficients(bc, self.surfaces, self.sources, self.film)


def coefficients(bc: BoundaryConditions, surfaces: list[str], sources: list[str],
                 film: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Each surface's coefficient [W/(m²·K)] from its nodes to the air (its total coefficient in
    series with ``film``, :func:`~feedtherm.models.interface.film_coefficient`) and each source's
    heat [W] at ``bc``."""
    h, sinks = surface_coefficients(bc, surfaces)
    if film is not None:
        h = film_coefficient(h, film)
    ambient = bc.point.ambient
    if np.any((h > 0) & (np.abs(sinks - ambient) > 1e-9)):
        raise FeedthermError("the state-space model takes every surface's sink at the ambient; a surface of this "
                             "description exchanges heat with another sink")
    return h, source_powers(bc, sources)


def reduce_model(loaded: LoadedSystem, outputs: list[str], reference: OperatingPoint, *,
                 order: int = DEFAULT_ORDER) -> ReducedModel:
    """Balanced-truncation basis at ``reference``, Galerkin projection (see the module's notes).

    Parameters
    ----------
    loaded : LoadedSystem
        The description with the sensors to be read (candidates included).
    outputs : list of str
        Sensor names and ``"D"``: the rows of ``Cy``.  The observability gramian weighs them
        alike, D scaled to kelvin by ``α L`` (its elongation per kelvin of the whole span).
    reference : OperatingPoint
        Where the gramians are taken.
    order : int
        States kept besides the uniform field.
    """
    system = loaded.system
    model = discretize(system, "fast")
    weights = cycle_weights(len(model.positions))
    G = weighted_sum(weights, [model.conductance(k) for k in range(len(model.positions))])
    basis = model.boundary_basis(None)
    capacity = np.asarray(model.capacity, dtype=float)
    s = 1.0 / np.sqrt(capacity)
    exposure = basis.exposure.toarray()  # (surfaces, nodes)
    distribution = basis.distribution.toarray()  # (sources, nodes)
    rows, offset = model.probe_rows(len(model.positions) // 2)
    rows = rows.toarray() if sp.issparse(rows) else np.asarray(rows)
    names = list(model.probe_names)
    unknown = [o for o in outputs if o not in names]
    if unknown:
        raise FeedthermError(f"the model reports no {', '.join(unknown)}")
    out_rows = rows[[names.index(o) for o in outputs]]
    out_offset = np.asarray(offset)[[names.index(o) for o in outputs]]

    bc = boundary_conditions_at(system, reference, loaded.overlay)
    h_ref, q_ref = coefficients(bc, list(basis.surfaces), list(basis.sources), basis.film)
    K = (G.toarray() if sp.issparse(G) else np.asarray(G)) + np.diag(exposure.T @ h_ref)
    Ks = s[:, None] * K * s[None, :]
    lam, V = np.linalg.eigh((Ks + Ks.T) / 2)  # Ks = V diag(lam) V^T, lam > 0
    if lam[0] <= 0:
        raise FeedthermError("the fast model has a node without a path to the ambient; it has no steady state")
    # inputs scaled by their size at the reference point (1 W for a source without heat there); the ambient by 1 K
    B = np.column_stack([*(s * distribution[j] * max(q_ref[j], 1.0) for j in range(len(q_ref))),
                         s * (exposure.T @ h_ref)])
    part = system.parts[system.kinematics.screw]
    # D's scale [m/K]: the screw's expansion per kelvin from the positioning reference to the laser's target
    span = abs(system.mechanics.elongation.target.point[0] - system.mechanics.positioning.reference.point[0])
    per_kelvin = system.materials[part.material].expansion * max(span, 1e-3)
    scale = np.array([1.0 / per_kelvin if o == ELONGATION_PROBE else 1.0 for o in outputs])
    Cm = (scale[:, None] * out_rows * s[None, :]) @ V  # outputs in the eigenbasis
    Bm = V.T @ B
    denominator = lam[:, None] + lam[None, :]
    P = (Bm @ Bm.T) / denominator
    O = (Cm.T @ Cm) / denominator
    Lp, Lo = _psd_root(P), _psd_root(O)
    U, hankel, Wt = np.linalg.svd(Lo.T @ Lp, full_matrices=False)
    r = min(order, int(np.sum(hankel > hankel[0] * 1e-14)))
    right = Lp @ Wt[:r].T / np.sqrt(hankel[:r])  # the balanced basis's columns, eigenbasis coordinates
    uniform = np.sqrt(capacity)  # C^{1/2}·1
    Q, _ = np.linalg.qr(np.column_stack([uniform / np.linalg.norm(uniform), V @ right]))
    A0 = -Q.T @ (s[:, None] * np.asarray(G @ (s[:, None] * Q)))
    A_surface = np.stack([-(Q.T * (s * s * exposure[i])) @ Q for i in range(exposure.shape[0])])
    f_surface = np.stack([Q.T @ (s * exposure[i]) for i in range(exposure.shape[0])])
    Bq = Q.T @ (s[:, None] * distribution.T)
    Cy = (out_rows * s[None, :]) @ Q
    A0 = (A0 + A0.T) / 2
    stroke_x, C_stroke, d_stroke = _stroke_rows(system, model, s, Q)
    return ReducedModel(list(basis.surfaces), list(basis.sources), list(outputs), A0, A_surface, f_surface, Bq, Cy,
                        out_offset, Q.T @ uniform, hankel, system.room.ambient_sensor, basis.film,
                        stroke_x, C_stroke, d_stroke)


def _stroke_rows(system, model, s: np.ndarray, Q: np.ndarray):
    """``(x [m], C (p, r), d (p,))``: E(x_j) of the reduced state ζ at the study's table positions, the
    full model's displacement rows read under the nut (linear between the screw's section centres,
    as :func:`~feedtherm.solution.pack.along_stroke`); ``(None, None, None)`` without a table."""
    if system.kinematics is None:
        return None, None, None
    from ...system.geometry import nut_centre_x
    from .data import stroke_positions

    rows, offset = model.displacement_rows()
    rows = rows.toarray() if sp.issparse(rows) else np.asarray(rows, dtype=float)
    offset = np.asarray(offset, dtype=float)
    x = stroke_positions(nut_centre_x(system) + np.asarray(model.positions, dtype=float))
    centres = np.asarray(model.screw_centres, dtype=float)
    W = np.column_stack([np.interp(x, centres, e) for e in np.eye(len(centres))])  # (p, sections)
    return x, (W @ rows[1:] * s[None, :]) @ Q, W @ offset[1:]


def _psd_root(M: np.ndarray) -> np.ndarray:
    """``L`` with ``L Lᵀ = M`` for a symmetric positive semi-definite ``M``, of the columns whose
    eigenvalue lies above ``eigh``'s rounding (``n ε`` of the largest): a gramian's eigenvalues fall
    fast, so ``L`` has a few dozen columns rather than one per node, and the SVD of ``Loᵀ Lp`` is small."""
    w, U = np.linalg.eigh((M + M.T) / 2)
    keep = w > max(w[-1], 0.0) * len(w) * np.finfo(float).eps
    return U[:, keep] * np.sqrt(w[keep])
