"""Sub-volumes of the parts the fast model does not resolve along the screw axis.

Every such part is cut, primitive by primitive, into grids of cells of about ``cell_size``
[m] (:mod:`.grids`); a small primitive at least into :data:`PART_CELLS` cells along its
longest side, so that a compact housing fused to a long bracket plate is cut as finely as a
housing alone (its bearing seat is where the heat enters and the sensor sits). Each cell is a
node. Primitives of one part touch over faces (a bracket plate fused to a housing, a riser on
a slab): those links are made from face samples (:mod:`.contacts`), like the joints between
parts.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...system.schema import Part
from .grids import BoxGrid, box_grid, cylinder_grid

PART_CELLS = 4  #: a primitive has at least this many cells along its longest side (small ones are finer)


@dataclass
class PartCells:
    """The cells of one part: its primitives' grids (boxes, then cylinders) and node indices."""

    name: str
    part: Part
    conductivity: float
    grids: list
    first: list[int]  # global index of each grid's first cell
    nodes: np.ndarray  # global indices of all cells

    @property
    def volumes(self) -> np.ndarray:
        return np.concatenate([g.volumes for g in self.grids])

    def node_points(self) -> np.ndarray:
        """Position [m] of every node (a cylinder's on its axis), shape (n, 3)."""
        pts = []
        for grid in self.grids:
            if isinstance(grid, BoxGrid):
                pts.append(grid.centroids)
            else:
                p = np.tile(np.asarray(grid.cyl.origin, dtype=float), (grid.size, 1))
                p[:, grid.axis] += grid.node_axial
                pts.append(p)
        return np.concatenate(pts)

    def primitive_of(self, points: np.ndarray, tol: float = 0.0) -> np.ndarray:
        """Index of the primitive (grid) containing each point, -1 where none does."""
        out = np.full(len(points), -1, dtype=int)
        for i, grid in enumerate(self.grids):
            free = out < 0
            if free.any():
                hit = grid.contains(points[free], tol)
                idx = np.nonzero(free)[0][hit]
                out[idx] = i
        return out

    def locate(self, points: np.ndarray, primitive: np.ndarray) -> np.ndarray:
        """Global node of each point, given the primitive containing it (all >= 0)."""
        nodes = np.empty(len(points), dtype=int)
        for i, grid in enumerate(self.grids):
            sel = primitive == i
            if sel.any():
                nodes[sel] = self.first[i] + grid.locate(points[sel])
        return nodes

    def distance(self, nodes: np.ndarray, primitive: np.ndarray, points: np.ndarray, normals: np.ndarray) -> np.ndarray:
        out = np.empty(len(points))
        for i, grid in enumerate(self.grids):
            sel = primitive == i
            if sel.any():
                out[sel] = grid.normal_distance(nodes[sel] - self.first[i], points[sel], normals[sel])
        return out

    def interpolation(self, point) -> tuple[np.ndarray, np.ndarray]:
        """Nodes and weights reading the field at ``point`` (on or within 1 mm of the part)."""
        p = np.asarray(point, dtype=float)[None, :]
        prim = self.primitive_of(p, tol=1e-3)[0]
        if prim < 0:  # outside (a sensor the checks warn about): the nearest primitive
            prim = int(np.argmin([_gap_to(grid, p[0]) for grid in self.grids]))
        cells, weights = self.grids[prim].interpolation(p[0])
        return self.first[prim] + cells, weights


def _gap_to(grid, point: np.ndarray) -> float:
    if isinstance(grid, BoxGrid):
        lo = np.asarray(grid.box.origin)
        hi = lo + np.asarray(grid.box.size)
        return float(np.linalg.norm(np.maximum(0.0, np.maximum(lo - point, point - hi))))
    along, r = grid._polar(point[None, :])
    da = max(0.0, -along[0], along[0] - grid.cyl.length)
    dr = max(0.0, grid.cyl.inner_diameter / 2.0 - r[0], r[0] - grid.cyl.outer_diameter / 2.0)
    return math.hypot(da, dr)


def part_cells(name: str, part: Part, conductivity: float, cell_size: float, first_node: int,
               breaks: list | None = None) -> PartCells:
    """The cells of a part; ``breaks[i]`` are the feature coordinates of its primitive ``i``
    (three lists for a box, one along the axis for a cylinder)."""
    n_box = len(part.boxes)
    breaks = breaks or [None] * (n_box + len(part.cylinders))
    grids = [box_grid(b, part.holes, min(cell_size, max(b.size) / PART_CELLS), breaks[i])
             for i, b in enumerate(part.boxes)]
    grids += [cylinder_grid(c, min(cell_size, max(c.length, c.outer_diameter) / PART_CELLS, c.outer_diameter),
                            breaks[n_box + i] or ())
              for i, c in enumerate(part.cylinders)]
    first, n = [], first_node
    for g in grids:
        first.append(n)
        n += g.size
    return PartCells(name, part, conductivity, grids, first, np.arange(first_node, n))


__all__ = ["PartCells", "part_cells", "PART_CELLS"]
