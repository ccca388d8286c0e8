"""Reading a temperature field: section means along an axis and values at points."""

from __future__ import annotations

import numpy as np
from skfem import MeshTet

from .heat import cell_basis
from .topology import element_volumes

__all__ = ["section_means", "probe"]


def section_means(
    mesh: MeshTet, T: np.ndarray, axis: int, edges: np.ndarray, elements: np.ndarray | None = None
) -> np.ndarray:
    """Volume means of ``T`` over slabs ``edges[i] ≤ x_axis ≤ edges[i+1]`` [same unit as T].

    An element belongs to the slab holding its centroid, so the means are exact integrals
    when the slab planes are element planes (a layered mesh). ``elements`` restricts the
    means to one part (e.g. the screw).
    """
    elements = np.arange(mesh.nelements) if elements is None else np.asarray(elements)
    centre = mesh.p[axis][mesh.t[:, elements]].mean(axis=0)
    mean_T = T[mesh.t[:, elements]].mean(axis=0)  # exact element mean of a P1 field
    volume = element_volumes(mesh)[elements]
    slab = np.searchsorted(edges, centre) - 1
    inside = (slab >= 0) & (slab < len(edges) - 1)
    n = len(edges) - 1
    total = np.bincount(slab[inside], weights=(volume * mean_T)[inside], minlength=n)
    vol = np.bincount(slab[inside], weights=volume[inside], minlength=n)
    if (vol == 0).any():
        raise ValueError("a slab holds no element centroid")
    return total / vol


def probe(mesh: MeshTet, T: np.ndarray, points: np.ndarray) -> np.ndarray:
    """``T`` interpolated at ``points`` (shape (3, n)) [same unit as T]."""
    return cell_basis(mesh).probes(np.asarray(points, dtype=float)) @ T
