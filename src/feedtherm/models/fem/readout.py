"""Reading the bench's field: sensors at points, the screw's section means, part means.

Everything is a fixed sparse matrix applied to the nodal field, built once:

- **sensors**: the P1 field at the sensor's coordinates, in the tetrahedron of the sensor's
  part that holds it (barycentric coordinates; a point just outside the faceted surface of
  a curved face takes the nearest tetrahedron's clamped coordinates). A sensor on a moving
  part stays at its material point: the moving group's mesh is in its own frame (the middle
  of the stroke), so the point does not depend on the group's position.
- **screw bins**: the volume mean of the screw's field over slabs ``edges[i] ≤ x <
  edges[i+1]``, integrated with the 64 points of a twice-refined tetrahedron (each
  tetrahedron cut into 8, twice; one point at each piece's centroid), so a tetrahedron that a
  slab plane cuts is shared between the two slabs in proportion, to within its 1/64th.
- **part means**: the volume mean over each part's nodes (lumped volumes).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["barycentric", "locate", "point_matrix", "slab_matrix", "refined_centroids", "tet_volumes"]


def tet_volumes(points: np.ndarray, tets: np.ndarray) -> np.ndarray:
    """Volume of each tetrahedron [m³]."""
    p = points[:, tets]
    e1, e2, e3 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]
    return np.abs(np.einsum("ij,ij->j", e1, np.cross(e2, e3, axis=0))) / 6.0


def barycentric(points: np.ndarray, tets: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Barycentric coordinates (4, m) of the point ``x`` (3,) in each of ``tets`` (4, m)."""
    p = points[:, tets]  # (3, 4, m)
    J = (p[:, 1:] - p[:, :1]).transpose(2, 0, 1)  # (m, 3, 3) columns: edges from vertex 0
    rhs = (x[:, None] - p[:, 0]).T[:, :, None]  # (m, 3, 1)
    lam = np.linalg.solve(J, rhs)[:, :, 0].T  # (3, m)
    return np.vstack([1.0 - lam.sum(axis=0), lam])


def locate(points: np.ndarray, tets: np.ndarray, x: np.ndarray) -> tuple[int, np.ndarray]:
    """The tetrahedron (index into ``tets`` (4, m)) that holds ``x`` (3,) [m] and its barycentric coordinates (4,).

    A point just outside the faceted surface of a curved face takes the nearest
    tetrahedron's coordinates clamped to it; a ValueError when it lies more than a quarter of
    an element outside.
    """
    lam = barycentric(points, tets, np.asarray(x, dtype=float))
    best = int(np.argmax(lam.min(axis=0)))
    if lam[:, best].min() < -0.25:  # more than a quarter of an element outside
        raise ValueError(f"the point {tuple(np.round(x, 6))} m lies outside the part's mesh")
    w = np.clip(lam[:, best], 0.0, None)
    return best, w / w.sum()


def point_matrix(points: np.ndarray, tets: np.ndarray, xs: list[np.ndarray], n: int) -> sp.csr_matrix:
    """Rows of P1 basis values at points ``xs``, each located among ``tets`` (its part's)."""
    rows, cols, vals = [], [], []
    for i, x in enumerate(xs):
        best, w = locate(points, tets, x)
        rows.extend([i] * 4)
        cols.extend(tets[:, best].tolist())
        vals.extend(w.tolist())
    return sp.csr_matrix((vals, (rows, cols)), shape=(len(xs), n))


def refined_centroids(levels: int = 2) -> np.ndarray:
    """Barycentric coordinates (q, 4) of the centroids of a tetrahedron cut into 8**levels."""
    tets = [np.eye(4)]
    for _ in range(levels):
        out = []
        for t in tets:
            v = list(t)
            m = {(i, j): 0.5 * (v[i] + v[j]) for i in range(4) for j in range(i + 1, 4)}
            e = lambda i, j: m[(min(i, j), max(i, j))]  # noqa: E731
            out += [np.array([v[0], e(0, 1), e(0, 2), e(0, 3)]), np.array([e(0, 1), v[1], e(1, 2), e(1, 3)]),
                    np.array([e(0, 2), e(1, 2), v[2], e(2, 3)]), np.array([e(0, 3), e(1, 3), e(2, 3), v[3]])]
            a, b, c, d, f, g = e(0, 1), e(0, 2), e(0, 3), e(1, 2), e(1, 3), e(2, 3)
            # the inner octahedron, cut along its diagonal e(0,2)–e(1,3) into four
            out += [np.array([b, f, a, c]), np.array([b, f, c, g]), np.array([b, f, g, d]), np.array([b, f, d, a])]
        tets = out
    return np.array([t.mean(axis=0) for t in tets])


def slab_matrix(points: np.ndarray, tets: np.ndarray, edges: np.ndarray, n: int, axis: int = 0,
                levels: int = 2) -> sp.csr_matrix:
    """(bins × n) matrix of volume means over slabs ``edges[i] ≤ x_axis < edges[i+1]``."""
    lam = refined_centroids(levels)  # (q, 4), equal volumes
    q = lam.shape[0]
    volume = tet_volumes(points, tets)
    xq = lam @ points[axis, tets]  # (q, m)
    bins = np.clip(np.searchsorted(edges, xq, side="right") - 1, 0, len(edges) - 2)  # (q, m)
    weight = (volume / q)[None, :, None] * lam[:, None, :]  # (q, m, 4)
    rows = np.broadcast_to(bins[:, :, None], weight.shape).ravel()
    cols = np.broadcast_to(tets.T[None, :, :], weight.shape).ravel()
    W = sp.csr_matrix((weight.ravel(), (rows, cols)), shape=(len(edges) - 1, n))
    slab_volume = np.asarray(W.sum(axis=1)).ravel()
    if (slab_volume <= 0).any():
        raise ValueError("a slab holds no part of the mesh")
    return sp.diags(1.0 / slab_volume) @ W
