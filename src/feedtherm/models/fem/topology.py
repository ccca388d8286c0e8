"""Mesh topology for parts that touch without sharing nodes.

Two parts in thermal contact are meshed so that the nodes of their common face coincide in
position but not in index: each part owns its own copy of the face. Two ways to get there:

- :func:`join` puts separately built meshes side by side (no node merging, unlike
  ``skfem.Mesh.__add__``);
- :func:`split_nodes` takes a conforming mesh of several parts (e.g. from gmsh with shared
  faces) and gives one side of a face its own copies of the face's nodes.

Either way the face appears as two sets of boundary facets, one per side, told apart by the
element that owns them (:func:`part_facets`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
from skfem import MeshTet

__all__ = ["join", "split_nodes", "part_facets", "element_volumes", "facet_areas"]


def join(meshes: Sequence[MeshTet]) -> tuple[MeshTet, list[np.ndarray]]:
    """Put tetrahedral meshes into one mesh without merging coincident nodes.

    Parameters
    ----------
    meshes : sequence of MeshTet
        The parts, in order.

    Returns
    -------
    mesh : MeshTet
        One mesh holding every part; part ``i``'s nodes follow part ``i-1``'s.
    elements : list of ndarray
        The element indices of each part in the joined mesh.
    """
    p, t, elements = [], [], []
    node_offset = element_offset = 0
    for m in meshes:
        p.append(m.p)
        t.append(m.t + node_offset)
        elements.append(np.arange(element_offset, element_offset + m.nelements))
        node_offset += m.nvertices
        element_offset += m.nelements
    return MeshTet(np.hstack(p), np.hstack(t)), elements


def split_nodes(mesh: MeshTet, elements: np.ndarray) -> tuple[MeshTet, np.ndarray]:
    """Give ``elements`` their own copies of the nodes they share with the other elements.

    The result has the same elements (same indices) and the same geometry; the nodes on the
    boundary between ``elements`` and the rest are duplicated, the copies being used by
    ``elements``. The two sides then meet along two coincident sets of boundary facets.

    Parameters
    ----------
    mesh : MeshTet
        A conforming mesh.
    elements : ndarray of int
        The elements of one side.

    Returns
    -------
    mesh : MeshTet
        The split mesh.
    copies : ndarray of int, shape (2, n)
        Row 0 the original node indices that were duplicated (kept by the other side), row 1
        their copies (used by ``elements``).
    """
    elements = np.asarray(elements, dtype=np.int64)
    inside = np.zeros(mesh.nelements, dtype=bool)
    inside[elements] = True
    nodes_in = np.unique(mesh.t[:, inside])
    nodes_out = np.unique(mesh.t[:, ~inside])
    shared = np.intersect1d(nodes_in, nodes_out)
    new_index = np.arange(mesh.nvertices)
    new_index[shared] = mesh.nvertices + np.arange(shared.size)
    t = mesh.t.copy()
    t[:, inside] = new_index[mesh.t[:, inside]]
    p = np.hstack([mesh.p, mesh.p[:, shared]])
    return MeshTet(p, t), np.vstack([shared, new_index[shared]])


def part_facets(
    mesh: MeshTet,
    elements: np.ndarray,
    where: Callable[[np.ndarray], np.ndarray] | None = None,
) -> np.ndarray:
    """Boundary facets owned by ``elements`` whose midpoints satisfy ``where``.

    On a split interface both sides have a boundary facet at the same place; the owner
    element tells them apart.

    Parameters
    ----------
    mesh : MeshTet
    elements : ndarray of int
        The part's elements.
    where : callable, optional
        ``where(x) -> bool array`` on facet midpoints ``x`` of shape (3, n); all boundary
        facets of the part if omitted.
    """
    facets = mesh.boundary_facets()
    owned = np.isin(mesh.f2t[0, facets], elements)
    facets = facets[owned]
    if where is not None:
        mid = mesh.p[:, mesh.facets[:, facets]].mean(axis=1)
        facets = facets[np.asarray(where(mid), dtype=bool)]
    return facets


def element_volumes(mesh: MeshTet) -> np.ndarray:
    """Volume of each tetrahedron [m³]."""
    p = mesh.p[:, mesh.t]  # (3, 4, nelements)
    e1, e2, e3 = (p[:, i] - p[:, 0] for i in (1, 2, 3))
    return np.abs(np.einsum("ij,ij->j", e1, np.cross(e2, e3, axis=0))) / 6.0


def facet_areas(mesh: MeshTet, facets: np.ndarray) -> np.ndarray:
    """Area of each triangle ``facets`` [m²]."""
    p = mesh.p[:, mesh.facets[:, facets]]  # (3, 3, n)
    return 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0], axis=0), axis=0)
