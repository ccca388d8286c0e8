r"""Thermal contact between parts meshed on their own: a non-conforming interface conductance.

Two parts A and B of a joint each have their own mesh; their common face is triangulated
twice, differently. The heat flux across it is :math:`q'' = (T_A - T_B)/R''` at every point.
It is integrated over A's facets that touch B: at each quadrature point :math:`x` of A's
facets, :math:`T_A` is A's P1 field and :math:`T_B` is B's P1 field at the closest point of
B's facing facets. This gives

.. math::

    K = \frac{1}{R''_{eff}} \int_{\Gamma_A} (N_A - N_B)^T (N_A - N_B)\,dA

(``lumped=False``), with :math:`N_A`, :math:`N_B` the rows of basis values at the point and at
its closest point. Every row sums to zero (the basis values on each side sum to one), so the
heat leaving A is exactly the heat entering B, whatever the two triangulations.

``lumped=True`` (the default) replaces the A–A block by its row
sums :math:`\mathrm{diag}\int N_A` and the B–B block by :math:`\mathrm{diag}\int N_B`, keeping
the A–B block :math:`-\int N_A^T N_B`: rows still sum to zero, the matrix stays symmetric and
has no positive off-diagonal entries (an M-matrix: no overshoot when :math:`R''` is small
against the elements' own conductance), and for any nodal fields the total heat flow
:math:`\int (T_A - T_B)/R''` is the same as the consistent form's.

**Which points touch.** A quadrature point of A touches B when a facet of B faces it (normals
opposed), its gap along that facet's normal is within ``tol`` — 0.1 mm plus the chord heights
of both meshes on curved faces (a facet on a cylinder lies inside it by :math:`L^2/8R`) —
and its closest point on the facet is within 0.1 mm of its projection on the facet's plane
(so that contact stops within 0.1 mm of the edge of the other part's face).

**Area.** The description's joint ``area`` is authoritative: the mesh's contact area
:math:`A_{geo}` (the sum of the touching points' weights) may differ from it (a nut's bore is
longer than its engaged thread, a belt's wrap is not a face of the boxes), so
:math:`R''_{eff} = R''\,A_{geo}/A_{declared}` and the joint's total conductance is
:math:`A_{declared}/R''`, as in the fast model.

**Which side integrates.** The quadrature runs over the side with the smaller elements (its
points then follow the other side's coarser basis functions); a finer other side raises
the rule's level.

**Sliding.** The points of A are moved into B's frame: shifted along x by the moving group's
offset (plus when A moves with the group, minus when B does); a quadrature per position is
built on demand.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ...errors import ModelError
from .facets import NearestFacets, Triangles, rule

__all__ = ["CONTACT_TOLERANCE", "ContactQuadrature", "Contact", "interface_matrix", "side_load", "touching"]

CONTACT_TOLERANCE = 1e-4  #: [m] gap below which two faces touch (plus the meshes' chord heights)


@dataclass(frozen=True)
class ContactQuadrature:
    """Quadrature of a contact over A's touching facets, with each point's partner on B."""

    a_nodes: np.ndarray  #: (n, 3) A's facet nodes at each point
    a_bary: np.ndarray  #: (n, 3) A's basis values at the point
    b_nodes: np.ndarray  #: (n, 3) B's facet nodes at the closest point
    b_bary: np.ndarray  #: (n, 3) B's basis values at the closest point
    weights: np.ndarray  #: (n,) [m²]

    @property
    def area(self) -> float:
        """The contact area in the mesh [m²]."""
        return float(self.weights.sum())


def interface_matrix(n: int, cq: ContactQuadrature, conductance_per_area: float, lumped: bool = True) -> sp.csr_matrix:
    """The interface conductance matrix [W/K] of a contact quadrature, ``h_c = 1/R''_eff``."""
    w = cq.weights * conductance_per_area
    wa = w[:, None] * cq.a_bary  # (n, 3)
    wb = w[:, None] * cq.b_bary
    cross_rows = np.repeat(cq.a_nodes, 3, axis=1).ravel()
    cross_cols = np.tile(cq.b_nodes, (1, 3)).ravel()
    cross = -(np.repeat(wa, 3, axis=1) * np.tile(cq.b_bary, (1, 3))).ravel()  # -w N_A,i N_B,j
    if lumped:
        rows = [cq.a_nodes.ravel(), cq.b_nodes.ravel(), cross_rows, cross_cols]
        cols = [cq.a_nodes.ravel(), cq.b_nodes.ravel(), cross_cols, cross_rows]
        vals = [wa.ravel(), wb.ravel(), cross, cross]
    else:
        aa_rows = np.repeat(cq.a_nodes, 3, axis=1).ravel()
        aa_cols = np.tile(cq.a_nodes, (1, 3)).ravel()
        aa = (np.repeat(wa, 3, axis=1) * np.tile(cq.a_bary, (1, 3))).ravel()
        bb_rows = np.repeat(cq.b_nodes, 3, axis=1).ravel()
        bb_cols = np.tile(cq.b_nodes, (1, 3)).ravel()
        bb = (np.repeat(wb, 3, axis=1) * np.tile(cq.b_bary, (1, 3))).ravel()
        rows = [aa_rows, bb_rows, cross_rows, cross_cols]
        cols = [aa_cols, bb_cols, cross_cols, cross_rows]
        vals = [aa, bb, cross, cross]
    K = sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))
    return K.tocsr()


def side_load(n: int, cq: ContactQuadrature, side: str) -> np.ndarray:
    """Nodal shares (summing to 1) of a heat spread uniformly over the contact, into ``side``.

    ``side = "a"``: into A's nodes, :math:`\\int N_A\\,dA / A_{geo}`; ``"b"``: into B's nodes
    under the contact, :math:`\\int N_B\\,dA / A_{geo}`.
    """
    nodes, bary = (cq.a_nodes, cq.a_bary) if side == "a" else (cq.b_nodes, cq.b_bary)
    return np.bincount(nodes.ravel(), weights=(cq.weights[:, None] * bary).ravel(), minlength=n) / cq.area


def touching(x: np.ndarray, normals: np.ndarray, other: NearestFacets, tol: float) -> np.ndarray:
    """Mask of points ``x`` (3, n) whose surface (``normals``) touches ``other``'s facets."""
    facet, _, _ = other.query(x, normals, tol, CONTACT_TOLERANCE)
    return facet >= 0


class Contact:
    """A joint between parts ``a`` (integration side) and ``b`` (its facets matched).

    Parameters
    ----------
    points : ndarray (3, N)
        All nodes [m].
    tri_a, tri_b : Triangles
        The boundary facets of the two parts.
    tol : float
        Contact tolerance [m].
    name : str
        For messages.
    level : int
        Quadrature level on A's facets (:func:`.facets.rule`): raise it when B's facets are
        smaller than A's, so that B's basis functions are followed.
    """

    def __init__(self, points: np.ndarray, tri_a: Triangles, tri_b: Triangles, tol: float, name: str = "",
                 level: int = 1):
        self.points = points
        self.tri_a, self.tri_b = tri_a, tri_b
        self.tol = float(tol)
        self.name = name
        self.level = level
        self.nearest_b = NearestFacets(points, tri_b)
        self._x, self._w, self._owner = tri_a.quadrature(points, level=level)
        self._normals = tri_a.normals[:, self._owner]
        self._bary = rule(level)[0]

    def quadrature(self, shift: float = 0.0) -> ContactQuadrature:
        """The contact with A shifted by ``shift`` [m] along x."""
        x = self._x.copy()
        x[0] += shift
        facet, bary, _ = self.nearest_b.query(x, self._normals, self.tol, CONTACT_TOLERANCE)
        hit = facet >= 0
        if not hit.any():
            raise ModelError(f"joint {self.name}: the two parts do not touch in the mesh (shift {shift * 1e3:.1f} mm)")
        q = self._bary.shape[0]
        local = np.tile(np.arange(q), self.tri_a.size)[hit]
        return ContactQuadrature(
            a_nodes=self.tri_a.nodes[:, self._owner[hit]].T,
            a_bary=self._bary[local],
            b_nodes=self.tri_b.nodes[:, facet[hit]].T,
            b_bary=bary[hit],
            weights=self._w[hit],
        )

