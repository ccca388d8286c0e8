"""Points spread over the faces of a part's primitives, each standing for a patch of area.

The fast model finds with them what touches what: where a primitive's face lies against
another primitive of the same part (fused: conduction), against a part it is joined to
(the joint's contact, split over the cells on both sides), or against nothing (exposed:
convection). A point ``p`` with outward normal ``n`` is tested at ``p + ε n``, just outside
its own primitive. Faces are sampled on the grid of the cells under them, refined at every
feature line (a contact's edge that did not become a cell edge): :data:`PER_CELL` points
per interval and direction, so no point's patch straddles the edge of a contact and the
contact areas come out exact for faces that meet squarely. Around an axis the points are a
multiple of 16 (patches end on the 22.5° grid lines of a hole), polar on annuli.

Face labels follow the description's selectors (:mod:`feedtherm.system.geometry`): ``+x`` …
``-z`` on boxes, ``bore`` for the holes through a box, ``lateral``, ``bore`` and ``+<axis>``/
``-<axis>`` (the ends) on cylinders.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...system.geometry import BOX_FACES
from ...system.schema import Cylinder
from .cells import PartCells
from .grids import holes_of_box, in_holes

_AXES = {"x": 0, "y": 1, "z": 2}
PER_CELL = 3  #: sample points per grid interval along each face direction
MIN_AROUND = 32  #: at least this many points around a circle
EPSILON = 5e-4  #: [m] the test point's distance outside the face


@dataclass
class Samples:
    points: np.ndarray  # (n, 3) on the face [m]
    normals: np.ndarray  # (n, 3) outward unit normals
    areas: np.ndarray  # (n,) [m^2]
    primitive: np.ndarray  # (n,) index of the primitive (boxes, then cylinders)
    face: np.ndarray  # (n,) face label (str)
    extent: np.ndarray  # (n,) length [m] of each point's patch along x (0 on faces normal to x)

    def __len__(self) -> int:
        return len(self.areas)

    def outside(self, eps: float = EPSILON) -> np.ndarray:
        return self.points + eps * self.normals

    def inside(self, eps: float = EPSILON) -> np.ndarray:
        return self.points - eps * self.normals

    def select(self, mask: np.ndarray) -> "Samples":
        return Samples(self.points[mask], self.normals[mask], self.areas[mask], self.primitive[mask], self.face[mask],
                       self.extent[mask])


def _sub(edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """PER_CELL points per interval of ``edges``: their positions and widths."""
    w = np.diff(edges)
    offsets = (np.arange(PER_CELL) + 0.5) / PER_CELL
    return (edges[:-1, None] + w[:, None] * offsets[None, :]).ravel(), np.repeat(w / PER_CELL, PER_CELL)


def _around(radius: float, cell_size: float) -> int:
    """Points around a circle: a multiple of 16, so that patches end on the 22.5° grid lines of holes."""
    n = max(MIN_AROUND, int(math.ceil(PER_CELL * 2 * math.pi * radius / cell_size)))
    return 16 * int(math.ceil(n / 16))


def part_samples(cells: PartCells, cell_size: float) -> Samples:
    """Sample points on every face of a part's primitives (holes' walls included), on the
    grids of its cells: every cell face gets PER_CELL × PER_CELL points."""
    part = cells.part
    chunks = []
    for ib, (box, grid) in enumerate(zip(part.boxes, cells.grids)):
        lo = np.asarray(box.origin, dtype=float)
        size = np.asarray(box.size, dtype=float)
        for face in BOX_FACES:
            axis = _AXES[face[1]]
            sign = 1.0 if face[0] == "+" else -1.0
            u, v = [k for k in range(3) if k != axis]
            (cu, wu), (cv, wv) = _sub(grid.lines[u]), _sub(grid.lines[v])
            U, V = np.meshgrid(cu, cv, indexing="ij")
            pts = np.empty((U.size, 3))
            pts[:, u], pts[:, v] = U.ravel(), V.ravel()
            pts[:, axis] = lo[axis] + (size[axis] if sign > 0 else 0.0)
            normal = np.zeros(3)
            normal[axis] = sign
            area = np.outer(wu, wv).ravel()
            along_x = np.zeros(U.size) if axis == 0 else np.repeat(wu, len(wv))  # u is x unless the face is normal to x
            chunks.append((pts, np.tile(normal, (len(pts), 1)), area, ib, face, along_x))
        for hole in holes_of_box(box, part.holes):
            i = _AXES[hole.axis]
            start, end = hole.origin[i], hole.origin[i] + hole.length
            along = np.unique(np.clip(grid.lines[i], start, end)) - start
            pts, radial, area, along_x = _lateral(hole, hole.outer_diameter / 2.0, along, cell_size)
            chunks.append((pts, -radial, area, ib, "bore", along_x))
    offset = len(part.boxes)
    for ic, cyl in enumerate(part.cylinders):
        grid = cells.grids[offset + ic]
        pts, radial, area, along_x = _lateral(cyl, cyl.outer_diameter / 2.0, grid.axial_lines, cell_size)
        chunks.append((pts, radial, area, offset + ic, "lateral", along_x))
        if cyl.inner_diameter > 0.0:
            pts, radial, area, along_x = _lateral(cyl, cyl.inner_diameter / 2.0, grid.axial_lines, cell_size)
            chunks.append((pts, -radial, area, offset + ic, "bore", along_x))
        for sign in (1.0, -1.0):
            pts, normals, area = _annulus(cyl, sign, grid.radii, cell_size)
            chunks.append((pts, normals, area, offset + ic, f"{'+' if sign > 0 else '-'}{cyl.axis}", np.zeros(len(pts))))
    samples = Samples(
        np.concatenate([c[0] for c in chunks]),
        np.concatenate([c[1] for c in chunks]),
        np.concatenate([c[2] for c in chunks]).astype(float),
        np.concatenate([np.full(len(c[0]), c[3]) for c in chunks]),
        np.concatenate([np.full(len(c[0]), c[4], dtype=object) for c in chunks]),
        np.concatenate([c[5] for c in chunks]).astype(float),
    )
    # points of a box face that lie in a hole are not on the part
    keep = ~in_holes(part.holes, samples.inside())
    return samples.select(keep)


def _frame(cyl: Cylinder):
    axis = _AXES[cyl.axis]
    u, v = [k for k in range(3) if k != axis]
    return axis, u, v


def _lateral(cyl: Cylinder, radius: float, axial_edges: np.ndarray, cell_size: float):
    """Points on the cylinder of ``radius`` around ``cyl``'s axis (``axial_edges`` from its
    origin), the outward radial unit vectors, each point's area and its patch's length
    along x (0 unless the axis is x)."""
    axis, u, v = _frame(cyl)
    n_around = _around(radius, cell_size)
    theta = 2 * math.pi * (np.arange(n_around) + 0.5) / n_around
    along, width = _sub(np.asarray(axial_edges, dtype=float))
    T, A = np.meshgrid(theta, along, indexing="ij")
    radial = np.zeros((T.size, 3))
    radial[:, u], radial[:, v] = np.cos(T.ravel()), np.sin(T.ravel())
    pts = np.asarray(cyl.origin, dtype=float) + radius * radial
    pts[:, axis] += A.ravel()
    W = np.broadcast_to(width[None, :], T.shape).ravel()
    return pts, radial, 2 * math.pi * radius / n_around * W, (W.copy() if axis == 0 else np.zeros(T.size))


def _annulus(cyl: Cylinder, sign: float, radii: np.ndarray, cell_size: float):
    axis, u, v = _frame(cyl)
    r_sub = np.linspace(0.0, 1.0, PER_CELL + 1)
    edges = np.unique(np.concatenate([a + (b - a) * r_sub for a, b in zip(radii[:-1], radii[1:])]))
    radius = 0.5 * (edges[1:] + edges[:-1])
    n_around = _around(radii[-1], cell_size)
    band = math.pi * (edges[1:] ** 2 - edges[:-1] ** 2) / n_around
    theta = 2 * math.pi * (np.arange(n_around) + 0.5) / n_around
    T, R = np.meshgrid(theta, radius, indexing="ij")
    area = np.broadcast_to(band[None, :], T.shape).ravel()
    pts = np.tile(np.asarray(cyl.origin, dtype=float), (T.size, 1))
    pts[:, u] += R.ravel() * np.cos(T.ravel())
    pts[:, v] += R.ravel() * np.sin(T.ravel())
    pts[:, axis] += cyl.length if sign > 0 else 0.0
    normal = np.zeros(3)
    normal[axis] = sign
    return pts, np.tile(normal, (len(pts), 1)), area


__all__ = ["Samples", "part_samples", "EPSILON"]
