"""A surface cut into regular axial layers, so that whatever moves along it moves by index.

A screw's or a rail's surface, meshed in layers of equal thickness ``spacing`` along an axis,
is described by:

- ``facets[l]``: the facets of layer ``l`` (between planes ``l`` and ``l+1``);
- ``grid[r, j]``: the node in *slot* ``j`` of layer ``r``. A slot is a place in the layer
  pattern: the node's offset from the layer's start plane and its two transverse
  coordinates. Every layer has the same slots (the surface mesh repeats with the layer), and
  the end plane ``r = n_layers`` holds only the slots at offset 0 (``grid = -1`` elsewhere).

Shifting something by ``k`` layers then maps node ``grid[r, j]`` to ``grid[r + k, j]``: no
search, no re-assembly. Per-layer heat loads and convection matrices are assembled once;
a heat band or a covered strip at position ``k`` is the sum over its layers.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree
from skfem import MeshTet

from .heat import HeatOperator, facet_load, facet_mass_matrix
from .topology import facet_areas

__all__ = ["LayeredSurface", "layered_surface"]


@dataclass(frozen=True)
class LayeredSurface:
    """Facets in regular axial layers; see the module docstring."""

    mesh: MeshTet
    axis: int  #: 0, 1 or 2 (x, y, z)
    origin: float  #: axial coordinate of plane 0 [m]
    spacing: float  #: layer thickness [m]
    facets: tuple  #: facets of each layer (tuple of int arrays)
    grid: np.ndarray  #: (n_layers + 1, n_slots) node index, -1 where a slot is absent
    slots: np.ndarray  #: (3, n_slots) offset along the axis and the two transverse coordinates [m]
    _unit_loads: sp.csc_matrix = field(repr=False, compare=False, default=None)
    _triplets: dict = field(repr=False, compare=False, default_factory=dict)

    @property
    def n_layers(self) -> int:
        return len(self.facets)

    @property
    def nodes(self) -> np.ndarray:
        return self.grid[self.grid >= 0]

    def layer_facets(self, layers) -> np.ndarray:
        """The facets of the given layers (an iterable of layer indices or a range)."""
        chosen = [self.facets[i] for i in self._check(layers)]
        return np.concatenate(chosen) if chosen else np.zeros(0, dtype=np.int64)

    def layer_areas(self) -> np.ndarray:
        """Area of each layer [m²]."""
        return np.array([facet_areas(self.mesh, f).sum() for f in self.facets])

    def load(self, layers, flux) -> np.ndarray:
        """Nodal heat loads [W] of a flux [W/m²] (scalar or one per listed layer) on ``layers``."""
        layers = self._check(layers)
        flux = np.broadcast_to(np.asarray(flux, dtype=float), (len(layers),))
        return self._unit_loads[:, layers] @ flux

    def mass(self, layers, lumped: bool = False) -> sp.csr_matrix:
        """Facet mass matrix :math:`\\int \\phi_i\\phi_j\\,dA` over ``layers`` (N×N).

        Assembled once per layer (on first use); a call only selects the layers' entries.
        """
        layers = self._check(layers)
        if lumped not in self._triplets:
            parts = []
            for i, f in enumerate(self.facets):
                m = facet_mass_matrix(self.mesh, f, lumped=lumped).tocoo()
                parts.append((m.row, m.col, m.data, np.full(m.nnz, i)))
            self._triplets[lumped] = tuple(np.concatenate(c) for c in zip(*parts))
        rows, cols, vals, layer = self._triplets[lumped]
        chosen = np.zeros(self.n_layers, dtype=bool)
        chosen[layers] = True
        keep = chosen[layer]
        n = self.mesh.nvertices
        return sp.csr_matrix((vals[keep], (rows[keep], cols[keep])), shape=(n, n))

    def convection(self, layers, h: float, ambient: float, lumped: bool = False) -> HeatOperator:
        """Convection ``h`` [W/(m²·K)] to ``ambient`` on ``layers`` (uniform ``h``)."""
        m = h * self.mass(layers, lumped=lumped)
        return HeatOperator(m, ambient * np.asarray(m.sum(axis=1)).ravel())

    def _check(self, layers) -> list[int]:
        layers = [int(i) for i in layers]
        if layers and (min(layers) < 0 or max(layers) >= self.n_layers):
            raise IndexError(f"layers {min(layers)}…{max(layers)} outside 0…{self.n_layers - 1}")
        return layers


def layered_surface(
    mesh: MeshTet, facets: np.ndarray, axis: int, spacing: float, origin: float | None = None, rtol: float = 1e-6
) -> LayeredSurface:
    """Sort ``facets`` into axial layers of thickness ``spacing`` and check that they repeat.

    Parameters
    ----------
    mesh : MeshTet
    facets : ndarray of int
        Boundary facets of one part (e.g. a screw's outer surface).
    axis : int
        0, 1 or 2.
    spacing : float
        Layer thickness [m].
    origin : float, optional
        Axial coordinate of plane 0 [m]; the facets' smallest coordinate by default.
    rtol : float
        Position tolerance, relative to ``spacing``.

    Raises
    ------
    ValueError
        If a facet crosses a layer plane, or a layer's node pattern differs from layer 0's.
    """
    facets = np.asarray(facets, dtype=np.int64)
    if facets.size == 0:
        raise ValueError("no facets given")
    tol = rtol * spacing
    nodes = np.unique(mesh.facets[:, facets])
    x = mesh.p[axis, nodes]
    if origin is None:
        origin = float(x.min())
    row = np.floor((x - origin) / spacing + rtol).astype(np.int64)
    offset = x - origin - row * spacing
    offset[np.abs(offset) < tol] = 0.0
    if row.min() < 0:
        raise ValueError(f"nodes before the origin {origin} m")
    n_layers = int(row.max())
    if n_layers < 1:
        raise ValueError(f"the facets span less than one layer of {spacing} m")
    other = [a for a in range(3) if a != axis]
    key = np.vstack([offset, mesh.p[other][:, nodes]])  # (3, n)

    # facets per layer: a facet lies in the layer of its midpoint, and must not cross a plane
    node_row = np.full(mesh.nvertices, -1)
    node_row[nodes] = row
    node_offset = np.zeros(mesh.nvertices)
    node_offset[nodes] = offset
    fr = node_row[mesh.facets[:, facets]]
    fo = node_offset[mesh.facets[:, facets]]
    layer = fr.min(axis=0)
    beyond = (fr > layer[None] + 1) | ((fr == layer[None] + 1) & (fo > 0))
    crosses = beyond.any(axis=0) | (layer >= n_layers)
    if crosses.any():
        raise ValueError(
            f"{int(crosses.sum())} facets cross a layer plane or lie in the end plane: "
            f"the surface is not layered with spacing {spacing} m"
        )
    layer_facets = tuple(facets[layer == i] for i in range(n_layers))

    # the slots of layer 0 are the reference; every layer must show the same ones
    first = row == 0
    slots = key[:, first]
    order = np.lexsort(slots[::-1])
    slots = slots[:, order]
    tree = cKDTree(slots.T)
    grid = np.full((n_layers + 1, slots.shape[1]), -1, dtype=np.int64)
    for r in range(n_layers + 1):
        in_row = row == r
        dist, slot = tree.query(key[:, in_row].T)
        expected = slots.shape[1] if r < n_layers else int((slots[0] == 0).sum())
        if (dist > tol).any() or np.unique(slot).size != slot.size or slot.size != expected:
            raise ValueError(f"layer {r} does not repeat the node pattern of layer 0 (spacing {spacing} m)")
        grid[r, slot] = nodes[in_row]
    if (grid[n_layers, slots[0] > 0] != -1).any():
        raise ValueError("the end plane holds nodes inside a layer")

    unit = sp.hstack([sp.csc_matrix(facet_load(mesh, f, 1.0)[:, None]) for f in layer_facets]).tocsc()
    return LayeredSurface(mesh, axis, float(origin), float(spacing), layer_facets, grid, slots, unit)
