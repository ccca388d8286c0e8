"""Boundary triangles of a tetrahedral part: quadrature points and closest points on them.

Surface integrals of the bench model (convection, contact, surface heat) are done here with
plain arrays, so that a quadrature point can be kept or dropped one by one (a facet half
under a nut) and evaluated against another part's mesh (a non-conforming contact):

- :func:`boundary_triangles` — a part's boundary facets, oriented with outward normals;
- :func:`rule` — composite rules on a triangle (the facet cut into four by its edge
  midpoints, once or more, three points in each piece): positive weights, exact for
  quadratics; :data:`RULE` is the 12-point one;
- :func:`closest_points` — the closest point on a set of triangles to each query point, with
  its barycentric coordinates (Ericson, *Real-Time Collision Detection*, §5.1.5), vectorised.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

__all__ = ["Triangles", "boundary_triangles", "RULE", "rule", "closest_points", "NearestFacets"]


def rule(level: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Barycentric points (n, 3) and weights (n,) summing to 1 of a composite rule.

    The triangle is cut ``level`` times into four by its edge midpoints, and each piece gets
    the three-point rule of degree 2: ``3·4**level`` points, positive weights, exact for
    quadratics. More levels follow another mesh's finer piecewise-linear functions better.
    """
    pieces = [np.eye(3)]
    for _ in range(level):
        out = []
        for c in pieces:
            m01, m12, m02 = 0.5 * (c[0] + c[1]), 0.5 * (c[1] + c[2]), 0.5 * (c[0] + c[2])
            out += [np.array([c[0], m01, m02]), np.array([m01, c[1], m12]), np.array([m02, m12, c[2]]),
                    np.array([m01, m12, m02])]
        pieces = out
    base = np.array([[2 / 3, 1 / 6, 1 / 6], [1 / 6, 2 / 3, 1 / 6], [1 / 6, 1 / 6, 2 / 3]])  # degree 2
    points = np.vstack([base @ c for c in pieces])
    return points, np.full(len(points), 1.0 / len(points))


RULE = rule(1)  #: the default: 12 points


@dataclass(frozen=True)
class Triangles:
    """Boundary facets of one part: node indices (global), outward normals, areas."""

    nodes: np.ndarray  #: (3, n) global node indices, counter-clockwise seen from outside
    normals: np.ndarray  #: (3, n) unit outward normals
    areas: np.ndarray  #: (n,) [m²]

    @property
    def size(self) -> int:
        return self.areas.size

    def corners(self, points: np.ndarray) -> np.ndarray:
        """(3 corners, 3 coordinates, n) vertex coordinates."""
        return points[:, self.nodes].transpose(1, 0, 2)

    def quadrature(self, points: np.ndarray, facets: np.ndarray | None = None, level: int = 1):
        """Quadrature points (3, n·q), weights [m²] (n·q,) and facet index (n·q,) of :func:`rule`.

        ``facets`` restricts to those facets (indices into this set).
        """
        facets = np.arange(self.size) if facets is None else np.asarray(facets)
        bary, w = rule(level)
        c = self.corners(points)[:, :, facets]  # (3, 3, n)
        x = np.einsum("qk,kin->inq", bary, c).reshape(3, -1)
        weights = (self.areas[facets][:, None] * w[None, :]).ravel()
        owner = np.repeat(facets, len(w))
        return x, weights, owner

    def subset(self, mask: np.ndarray) -> "Triangles":
        return Triangles(self.nodes[:, mask], self.normals[:, mask], self.areas[mask])


def boundary_triangles(points: np.ndarray, tets: np.ndarray) -> Triangles:
    """The faces of ``tets`` that belong to one tetrahedron only, with outward normals."""
    faces = np.hstack([tets[[1, 2, 3]], tets[[0, 3, 2]], tets[[0, 1, 3]], tets[[0, 2, 1]]])  # (3, 4m)
    opposite = np.concatenate([tets[0], tets[1], tets[2], tets[3]])
    key = np.sort(faces, axis=0).astype(np.int64)
    n = int(key.max()) + 1
    code = (key[0] * n + key[1]) * n + key[2] if n < 2**21 else None
    if code is None:
        _, inverse, counts = np.unique(key.T, axis=0, return_inverse=True, return_counts=True)
    else:
        _, inverse, counts = np.unique(code, return_inverse=True, return_counts=True)
    single = counts[inverse.ravel()] == 1
    tri, opp = faces[:, single], opposite[single]
    p0, p1, p2 = (points[:, tri[i]] for i in range(3))
    cross = np.cross(p1 - p0, p2 - p0, axis=0)
    outward = np.einsum("ij,ij->j", cross, p0 - points[:, opp]) > 0
    tri[[1, 2]] = np.where(outward, tri[[1, 2]], tri[[2, 1]])
    cross = np.where(outward, cross, -cross)
    norm = np.linalg.norm(cross, axis=0)
    return Triangles(tri, cross / norm, 0.5 * norm)


def closest_points(p: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Closest points on triangles (a, b, c) to points ``p`` (all (n, 3)).

    Returns the distances (n,) and the barycentric coordinates (n, 3) of the closest points.
    """
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = _dot(ab, ap), _dot(ac, ap)
    bp = p - b
    d3, d4 = _dot(ab, bp), _dot(ac, bp)
    cp = p - c
    d5, d6 = _dot(ab, cp), _dot(ac, cp)
    vc = d1 * d4 - d3 * d2
    vb = d5 * d2 - d1 * d6
    va = d3 * d6 - d5 * d4
    with np.errstate(divide="ignore", invalid="ignore"):
        v_ab = d1 / (d1 - d3)
        w_ac = d2 / (d2 - d6)
        w_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        denom = 1.0 / (va + vb + vc)
        v_in, w_in = vb * denom, vc * denom
    one, zero = np.ones_like(d1), np.zeros_like(d1)
    conditions = [
        (d1 <= 0) & (d2 <= 0),
        (d3 >= 0) & (d4 <= d3),
        (vc <= 0) & (d1 >= 0) & (d3 <= 0),
        (d6 >= 0) & (d5 <= d6),
        (vb <= 0) & (d2 >= 0) & (d6 <= 0),
        (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0),
    ]
    v = np.select(conditions, [zero, one, v_ab, zero, zero, 1 - w_bc], v_in)
    w = np.select(conditions, [zero, zero, zero, one, w_ac, w_bc], w_in)
    bary = np.stack([1.0 - v - w, v, w], axis=1)
    q = bary[:, :1] * a + bary[:, 1:2] * b + bary[:, 2:] * c
    return np.linalg.norm(p - q, axis=1), bary


def _dot(x, y):
    return np.einsum("ij,ij->i", x, y)


class NearestFacets:
    """Closest facing facet of a triangle set to query points, within a distance.

    ``query(x, normals, tol, tangential)`` returns for every point the facet (or -1), the
    barycentric coordinates of the closest point on it, and the distance; only facets that
    face the point's own surface (normals opposed, ``n·n' ≤ -0.5``), lie within ``tol`` along
    their normal and whose closest point is within ``tangential`` of the point's projection
    on their plane count.
    """

    #: facets whose centroids are nearest to a point are tried (gmsh meshes are graded
    #: smoothly: the facet holding a point's projection is among its nearest few)
    candidates = 16
    #: [m] how far past its bounds a candidate is still taken to the closest-point test: far above
    #: the rounding of the test's distances (1e-10 m where they are centimetres), far below an element
    slack = 1e-7

    def __init__(self, points: np.ndarray, triangles: Triangles):
        self.triangles = triangles
        self.corners = triangles.corners(points)  # (3, 3, n)
        centroids = self.corners.mean(axis=0)
        #: each facet's radius about its centroid [m] (its farthest corner)
        self.radii = np.linalg.norm(self.corners - centroids[None], axis=1).max(axis=0)
        self.reach = float(self.radii.max()) if triangles.size else 0.0
        self.tree = cKDTree(centroids.T) if triangles.size else None
        self.centroids = centroids
        if triangles.size:
            self._box = (self.corners.min(axis=(0, 2)), self.corners.max(axis=(0, 2)))

    def near_box(self, x: np.ndarray, tol: float) -> np.ndarray:
        """Points (3, n) within the facets' bounding box grown by ``tol``."""
        if self.triangles.size == 0:
            return np.zeros(x.shape[1], dtype=bool)
        lo, hi = self._box
        return ((x >= lo[:, None] - tol) & (x <= hi[:, None] + tol)).all(axis=0)

    def query(self, x: np.ndarray, normals: np.ndarray, tol: float, tangential: float | None = None,
              chunk: int = 20000):
        tangential = tol if tangential is None else tangential
        n = x.shape[1]
        facet = np.full(n, -1, dtype=np.int64)
        bary = np.zeros((n, 3))
        dist = np.full(n, np.inf)
        if self.tree is None or n == 0:
            return facet, bary, dist
        inside = self.near_box(x, tol)
        if not inside.all():  # points far from every facet: skip them
            sub = np.nonzero(inside)[0]
            f, b, d = self.query(x[:, sub], normals[:, sub], tol, tangential, chunk)
            facet[sub], bary[sub], dist[sub] = f, b, d
            return facet, bary, dist
        for start in range(0, n, chunk):
            sl = slice(start, min(n, start + chunk))
            kk = min(self.candidates, self.triangles.size)
            _, idx = self.tree.query(x[:, sl].T, k=kk, distance_upper_bound=self.reach + tol)
            idx = idx.reshape(-1, kk)
            valid = idx < self.triangles.size
            if not valid.any():
                continue
            cand = idx[valid]
            point = np.repeat(np.arange(sl.start, sl.stop), kk)[valid.ravel()]
            facet_normals = self.triangles.normals[:, cand]
            facing = np.einsum("ij,ij->j", facet_normals, normals[:, point]) <= -0.5
            cand, point, facet_normals = cand[facing], point[facing], facet_normals[:, facing]
            cand, point, facet_normals = self._within_bounds(x, cand, point, facet_normals, tol, tangential)
            a, b, c = (self.corners[i][:, cand].T for i in range(3))
            at = x[:, point].T
            d, bc = closest_points(at, a, b, c)
            # the gap along the facet's normal may be up to ``tol`` (chord heights of curved
            # faces); the closest point must lie on the facet within ``tangential`` of the
            # point's projection, so that a face's rim does not reach past the facet's edge
            gap = at - (bc[:, :1] * a + bc[:, 1:2] * b + bc[:, 2:] * c)
            normal_gap = np.abs(np.einsum("ij,ji->i", gap, facet_normals))
            side = np.sqrt(np.maximum(d**2 - normal_gap**2, 0.0))
            d = np.where((side <= tangential) & (normal_gap <= tol), d, np.inf)
            order = np.lexsort((d, point))  # per point, the nearest candidate first
            first = np.ones(order.size, dtype=bool)
            first[1:] = point[order][1:] != point[order][:-1]
            best = order[first]
            facet[point[best]] = cand[best]
            bary[point[best]] = bc[best]
            dist[point[best]] = d[best]
        far = dist > tol
        facet[far] = -1
        bary[far] = 0.0
        return facet, bary, dist

    def _within_bounds(self, x, cand, point, facet_normals, tol, tangential):
        """The candidate pairs (facet ``cand``, point ``point``) that the closest-point test could accept.

        The closest point ``q`` lies in the facet's plane, within its radius ``R`` of its centroid
        ``c``: the point's gap along the normal is ``(x − c)·n``, and its projection lies at
        most ``R`` beyond ``q``, so a pair with a gap over ``tol`` or a projection farther than
        ``tangential + R`` from ``c`` fails the test (by :attr:`slack`, beyond rounding).  Dropping
        them first leaves every kept pair's result, and each point's nearest, as they were: of the
        16 candidates of a point in a contact, about one passes.
        """
        offset = x[:, point] - self.centroids[:, cand]
        along = np.einsum("ij,ij->j", offset, facet_normals)
        across = np.einsum("ij,ij->j", offset, offset) - along * along
        reach = tangential + self.radii[cand] + self.slack
        kept = (np.abs(along) <= tol + self.slack) & (across <= reach * reach)
        return cand[kept], point[kept], facet_normals[:, kept]
