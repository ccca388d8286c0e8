r"""Thermal contact resistance between parts that do not share nodes, fixed or sliding.

**Contact.** Two parts touch along a face that each meshes on its own (coincident nodes with
different indices, see :mod:`.topology`). With a contact resistance :math:`R''` [m²·K/W],
the heat flux from side a to side b is :math:`q'' = (T_a - T_b)/R''` at every point of the
face. Its weak form, integrated over side b's facets with side a's temperature taken at the
coincident nodes, adds to the conduction matrix the block

.. math::

    \frac{1}{R''}\begin{bmatrix} M & -M \\ -M & M \end{bmatrix}

on the (a, b) node pairs, with :math:`M` the facet mass matrix
:math:`\int \phi_i\phi_j\,dA` of the face. Each row sums to zero, so whatever leaves one
side enters the other exactly. ``lumped=True`` (the default) uses the row-sum diagonal of
:math:`M`: each node pair is joined by a conductance ``A_i/R''`` (``A_i`` a third of the
area of the triangles around the node), which keeps the system an M-matrix (no
overshoot however small :math:`R''` is against the elements' own conductance). With
``lumped=False`` the consistent :math:`M` is used; both give the same total heat flow for
a given pair of nodal fields.

**Sliding contact.** A part (the nut, a carriage) slides along another (the screw, a rail)
whose contact surface is meshed in regular axial layers (:mod:`.layers`), the sliding
part's contact face being meshed on the same pattern. At position ``s`` the node in slot
``j`` of the sliding part's layer ``r`` touches the node in slot ``j`` of the track's layer
``r + s``. The block above is built once over the sliding part's face, and moving by ``k``
layers only changes which track nodes it is attached to: an index shift.
"""

from __future__ import annotations

from collections.abc import Hashable

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree
from skfem import Functional, MeshTet

from .heat import HeatOperator, facet_basis, facet_mass_matrix
from .layers import LayeredSurface

__all__ = ["pair_nodes", "coupling", "contact", "jump_heat_flow", "SlidingInterface"]


@Functional
def _flux(w):
    return w.jump / w.r


def pair_nodes(
    mesh: MeshTet, facets_a: np.ndarray, facets_b: np.ndarray, rtol: float = 1e-8
) -> tuple[np.ndarray, np.ndarray]:
    """Match the nodes of two facet sets by position.

    Returns ``(nodes_a, nodes_b)``, equal-length arrays with ``nodes_a[i]`` at the position of
    ``nodes_b[i]``. Raises ``ValueError`` if any node of one side has no partner on the other.
    """
    a = np.unique(mesh.facets[:, np.asarray(facets_a, dtype=np.int64)])
    b = np.unique(mesh.facets[:, np.asarray(facets_b, dtype=np.int64)])
    size = np.ptp(mesh.p[:, np.concatenate([a, b])], axis=1).max()
    dist, index = cKDTree(mesh.p[:, a].T).query(mesh.p[:, b].T)
    if a.size != b.size or (dist > rtol * size).any() or np.unique(index).size != b.size:
        raise ValueError(
            f"the two sides of the interface do not match node for node ({a.size} and {b.size} nodes, "
            f"largest gap {dist.max():.3g} m): mesh them with coincident nodes"
        )
    return a[index], b


def coupling(n: int, nodes_a: np.ndarray, nodes_b: np.ndarray, mass: sp.spmatrix, resistance: float) -> sp.csr_matrix:
    """The conductance matrix :math:`\\Pi^T M \\Pi / R''` of a contact between node pairs.

    ``mass`` is an N×N facet mass matrix living on ``nodes_b``; ``Π T`` is the jump
    ``T_b - T_a`` placed on ``nodes_b``.
    """
    if resistance <= 0:
        raise ValueError(f"contact resistance must be positive, got {resistance} m²·K/W")
    k = nodes_b.size
    rows = np.concatenate([nodes_b, nodes_b])
    cols = np.concatenate([nodes_b, nodes_a])
    vals = np.concatenate([np.ones(k), -np.ones(k)])
    jump = sp.csr_matrix((vals, (rows, cols)), shape=(n, n))
    return (jump.T @ sp.csr_matrix(mass) @ jump / resistance).tocsr()


def contact(
    mesh: MeshTet, facets_a: np.ndarray, facets_b: np.ndarray, resistance: float, lumped: bool = True
) -> HeatOperator:
    """Contact resistance ``resistance`` R'' [m²·K/W] between two coincident facet sets."""
    nodes_a, nodes_b = pair_nodes(mesh, facets_a, facets_b)
    mass = facet_mass_matrix(mesh, facets_b, lumped=lumped)
    return HeatOperator(coupling(mesh.nvertices, nodes_a, nodes_b, mass, resistance), np.zeros(mesh.nvertices))


def jump_heat_flow(
    mesh: MeshTet, facets: np.ndarray, nodes: np.ndarray, partners: np.ndarray, T: np.ndarray, resistance: float
) -> float:
    """:math:`\\int (T - T_{partner})/R''\\,dA` over ``facets`` [W]: the heat leaving that side.

    ``nodes`` are the facets' nodes and ``partners`` the coincident nodes on the other side.
    A separate surface integral, not taken from the assembled matrices.
    """
    jump = np.zeros(mesh.nvertices)
    jump[nodes] = T[nodes] - T[partners]
    fb = facet_basis(mesh, facets)
    return float(_flux.assemble(fb, jump=fb.interpolate(jump), r=float(resistance)))


class SlidingInterface:
    """A contact resistance between a track and a part sliding on it layer by layer.

    Parameters
    ----------
    track : LayeredSurface
        The fixed surface (screw, rail), e.g. ``n`` layers.
    slider : LayeredSurface
        The sliding part's contact face, ``m ≤ n`` layers, same spacing and axis, and the
        same slots as the track (its node pattern repeats the track's).
    resistance : float
        R'' [m²·K/W].
    lumped : bool
        Lumped (default) or consistent facet mass matrix, see the module docstring.

    Positions are ``s = 0 … n - m``: the slider's layer ``r`` on the track's layer ``r + s``.
    """

    def __init__(
        self,
        track: LayeredSurface,
        slider: LayeredSurface,
        resistance: float,
        lumped: bool = True,
        cache_size: int = 256,
    ):
        if track.mesh is not slider.mesh:
            raise ValueError("track and slider must live in the same mesh")
        if track.axis != slider.axis or not np.isclose(track.spacing, slider.spacing):
            raise ValueError(f"track and slider need the same axis and spacing ({track.spacing} m vs {slider.spacing} m)")
        if slider.n_layers > track.n_layers:
            raise ValueError(f"the slider ({slider.n_layers} layers) is longer than the track ({track.n_layers})")
        tol = 1e-6 * track.spacing
        dist, slot = cKDTree(track.slots.T).query(slider.slots.T)
        if (dist > tol).any():
            raise ValueError("the slider's contact face does not repeat the track's node pattern")
        self.track, self.slider = track, slider
        self.resistance = float(resistance)
        self.lumped = lumped
        self.n_positions = track.n_layers - slider.n_layers + 1
        rest = (slider.origin - track.origin) / track.spacing
        #: the position at which the slider's mesh coordinates touch the track (or None if
        #: they sit off the layer planes); a field plot shifts the slider by
        #: ``(s - rest_position)·spacing`` along the axis
        self.rest_position = int(round(rest)) if abs(rest - round(rest)) < 1e-6 else None
        present = slider.grid >= 0
        self._rows, self._cols = np.nonzero(present)  # the slider's (layer, slot) entries
        self._track_slot = slot[self._cols]
        self.slider_nodes = slider.grid[self._rows, self._cols]
        self.slider_facets = slider.layer_facets(range(slider.n_layers))
        self._mass = facet_mass_matrix(slider.mesh, self.slider_facets, lumped=lumped)
        self._cache: dict[Hashable, HeatOperator] = {}
        self._cache_size = cache_size

    def partners(self, s: int) -> np.ndarray:
        """Track nodes touching ``self.slider_nodes`` at position ``s``."""
        if not 0 <= s < self.n_positions:
            raise IndexError(f"position {s} outside 0…{self.n_positions - 1}")
        nodes = self.track.grid[self._rows + s, self._track_slot]
        if (nodes < 0).any():
            raise ValueError("the slider's face runs past the track's end plane")
        return nodes

    def operator(self, s: int) -> HeatOperator:
        """The contact's conductance matrix at position ``s`` (assembled once per position)."""
        if s not in self._cache:
            n = self.track.mesh.nvertices
            G = coupling(n, self.partners(s), self.slider_nodes, self._mass, self.resistance)
            if len(self._cache) >= self._cache_size:
                self._cache.pop(next(iter(self._cache)))
            self._cache[s] = HeatOperator(G, np.zeros(n))
        return self._cache[s]

    def track_facets(self, s: int) -> np.ndarray:
        """The track's facets under the slider at position ``s`` (all their nodes touch it)."""
        facets = self.track.layer_facets(range(s, s + self.slider.n_layers))
        covered = np.isin(self.track.mesh.facets[:, facets], self.partners(s)).all(axis=0)
        return facets[covered]

    def heat_flow(self, T: np.ndarray, s: int) -> tuple[float, float]:
        """Heat [W] leaving the slider and heat entering the track, as two separate integrals.

        The first is :math:`\\int (T_{slider} - T_{track})/R''\\,dA` over the slider's facets,
        the second the same jump integrated over the track's facets under it. They agree
        when the two faces match facet for facet.
        """
        mesh = self.track.mesh
        partners = self.partners(s)
        out_of_slider = jump_heat_flow(mesh, self.slider_facets, self.slider_nodes, partners, T, self.resistance)
        into_track = -jump_heat_flow(mesh, self.track_facets(s), partners, self.slider_nodes, T, self.resistance)
        return out_of_slider, into_track
