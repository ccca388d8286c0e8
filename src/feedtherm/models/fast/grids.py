"""Grids of cells in one primitive (a box or a cylinder) of a part.

A box is cut along each axis through its *feature lines* — the edges of its holes and the
faces of the primitives it touches (:func:`feedtherm.models.fast.layout.feature_breaks`) —
and every interval between them into ``round(length/h)`` cells (at least one), so that a
footprint, a seat or a fused face falls on whole cells whatever the cell size ``h``. A
cylinder is cut into axial slices the same way and into rings (at least :data:`MIN_RINGS`),
axisymmetric: these parts are rings and sleeves, several of them rotate.

Holes (bores cut from boxes) are subtracted approximately: besides its edges, a hole puts
grid lines across itself at ``r·sin(22.5°·j)``, each cell keeps the fraction of its volume
that is solid and each face between two cells the fraction of it that is open, both counted
on sub-samples; cells less than :data:`MIN_FRACTION` solid are dropped and the box's exact
solid volume is shared among the rest. Each cell is one node at the centroid of its solid;
neighbours conduct ``k·A_open/Δ`` (boxes), ``k·A/Δx`` and ``2πkl/ln(r₂/r₁)`` (cylinders).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from ...system.schema import Box, Cylinder

_AXES = {"x": 0, "y": 1, "z": 2}
SUB = 4  #: sub-samples per cell side for solid fractions and open face fractions
MIN_FRACTION = 0.1  #: cells less solid than this are dropped (their volume goes to the rest)
#: grid lines across a hole, in radii from its axis: at the sines of every 22.5°
HOLE_LINES = np.sin(np.linspace(-0.5, 0.5, 9) * math.pi)
MIN_RINGS = 2  #: a cylinder has at least this many rings
MIN_GAP = 2e-3  #: [m] a hole's grid lines closer than this to each other make one
FEATURE_GAP = 0.5  #: other feature lines closer than this many cell sizes to a grid line are dropped


def divisions(length: float, cell_size: float) -> int:
    return max(1, int(round(length / cell_size)))


def in_holes(holes: list[Cylinder], points: np.ndarray) -> np.ndarray:
    """True where a point (n, 3) lies strictly inside one of ``holes``."""
    out = np.zeros(len(points), dtype=bool)
    for hole in holes:
        i = _AXES[hole.axis]
        d = points - np.asarray(hole.origin)
        radial = np.delete(d, i, axis=1)
        out |= (np.einsum("ij,ij->i", radial, radial) < (hole.outer_diameter / 2.0) ** 2) \
            & (d[:, i] > 0.0) & (d[:, i] < hole.length)
    return out


def holes_of_box(box: Box, holes: list[Cylinder]) -> list[Cylinder]:
    """The holes whose axis runs through ``box`` (they lie inside the boxes)."""
    out = []
    lo, hi = np.asarray(box.origin), np.asarray(box.origin) + np.asarray(box.size)
    for hole in holes:
        i = _AXES[hole.axis]
        if all(lo[k] - 1e-9 <= hole.origin[k] <= hi[k] + 1e-9 for k in range(3) if k != i):
            out.append(hole)
    return out


@dataclass
class BoxGrid:
    """A box cut into cells along ``edges``; ``local`` maps grid cells to the grid's node list (-1: none)."""

    box: Box
    holes: list[Cylinder]
    edges: list[np.ndarray]  # cell edges along x, y, z [m]
    local: np.ndarray  # (nx, ny, nz) -> index among this grid's cells, -1 if dropped
    volumes: np.ndarray  # (n,) solid volume [m^3]
    centroids: np.ndarray  # (n, 3) [m]
    links: tuple[np.ndarray, np.ndarray, np.ndarray] = field(default=None)  # (i, j, A_open/Δ [m])
    lines: list[np.ndarray] = field(default=None)  # the cell edges and every feature coordinate, per axis

    @property
    def shape(self) -> tuple[int, int, int]:
        return tuple(len(e) - 1 for e in self.edges)

    @property
    def size(self) -> int:
        return len(self.volumes)

    def contains(self, points: np.ndarray, tol: float = 0.0) -> np.ndarray:
        lo = np.asarray(self.box.origin)
        hi = lo + np.asarray(self.box.size)
        inside = np.all((points >= lo - tol) & (points <= hi + tol), axis=1)
        return inside & ~in_holes(self.holes, points)

    def index(self, points: np.ndarray) -> np.ndarray:
        """Grid index (n, 3) of the cell containing each point (clamped to the grid)."""
        return np.stack([np.clip(np.searchsorted(e, points[:, a], side="right") - 1, 0, len(e) - 2)
                         for a, e in enumerate(self.edges)], axis=1)

    def locate(self, points: np.ndarray) -> np.ndarray:
        """This grid's cell of each point; in a dropped sliver, the nearest kept cell."""
        ijk = self.index(points)
        local = self.local[ijk[:, 0], ijk[:, 1], ijk[:, 2]]
        missing = local < 0
        if missing.any():
            d = ((points[missing, None, :] - self.centroids[None, :, :]) ** 2).sum(axis=2)
            local[missing] = np.argmin(d, axis=1)
        return local

    def interpolation(self, point: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Cells and weights of the trilinear interpolation between cell centres at ``point``."""
        corners = [list(zip(*_linear(0.5 * (e[1:] + e[:-1]), float(point[a])))) for a, e in enumerate(self.edges)]
        cells, weights = [], []
        for i, wi in corners[0]:
            for j, wj in corners[1]:
                for k, wk in corners[2]:
                    if self.local[i, j, k] >= 0 and wi * wj * wk > 0.0:
                        cells.append(self.local[i, j, k])
                        weights.append(wi * wj * wk)
        if not cells:
            return self.locate(np.asarray(point)[None, :]), np.ones(1)
        w = np.asarray(weights)
        return np.asarray(cells), w / w.sum()

    def normal_distance(self, local: np.ndarray, points: np.ndarray, normals: np.ndarray) -> np.ndarray:
        """Distance [m] from each cell's node to a face point, along the face normal."""
        return np.abs(np.einsum("ij,ij->i", points - self.centroids[local], normals))


@dataclass
class CylinderGrid:
    """A cylinder cut into ``n_axial`` slices × ``n_radial`` rings (axisymmetric)."""

    cyl: Cylinder
    shape: tuple[int, int]
    radii: np.ndarray  # (n_radial+1,) ring edges [m]
    volumes: np.ndarray
    node_radius: np.ndarray  # (n,) radius of each ring's node [m]
    node_axial: np.ndarray  # (n,) position of each slice's node along the axis, from the origin [m]
    axial_edges: np.ndarray  # (n_axial+1,) slice edges along the axis, from the origin [m]
    links: tuple[np.ndarray, np.ndarray, np.ndarray] = field(default=None)
    axial_lines: np.ndarray = field(default=None)  # the slice edges and every feature coordinate [m]

    @property
    def axis(self) -> int:
        return _AXES[self.cyl.axis]

    @property
    def size(self) -> int:
        return len(self.volumes)

    def _polar(self, points: np.ndarray):
        d = points - np.asarray(self.cyl.origin)
        along = d[:, self.axis]
        radial = np.delete(d, self.axis, axis=1)
        return along, np.sqrt(np.einsum("ij,ij->i", radial, radial))

    def contains(self, points: np.ndarray, tol: float = 0.0) -> np.ndarray:
        along, r = self._polar(points)
        return (along >= -tol) & (along <= self.cyl.length + tol) \
            & (r >= self.cyl.inner_diameter / 2.0 - tol) & (r <= self.cyl.outer_diameter / 2.0 + tol)

    def locate(self, points: np.ndarray) -> np.ndarray:
        along, r = self._polar(points)
        na, nr = self.shape
        i = np.clip(np.searchsorted(self.axial_edges, along, side="right") - 1, 0, na - 1)
        j = np.clip(np.searchsorted(self.radii, r, side="right") - 1, 0, nr - 1)
        return i * nr + j

    def interpolation(self, point: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        along, r = self._polar(np.asarray(point, dtype=float)[None, :])
        na, nr = self.shape
        axial = self.node_axial.reshape(na, nr)[:, 0]
        rings = self.node_radius.reshape(na, nr)[0]
        ia, wa = _linear(axial, along[0])
        ir, wr = _linear(rings, r[0])
        cells = np.array([a * nr + b for a in ia for b in ir])
        weights = np.array([x * y for x in wa for y in wr])
        keep = weights > 0
        return cells[keep], weights[keep] / weights[keep].sum()

    def normal_distance(self, local: np.ndarray, points: np.ndarray, normals: np.ndarray) -> np.ndarray:
        along, r = self._polar(points)
        axial_normal = np.abs(normals[:, self.axis]) > 0.5
        return np.where(axial_normal, np.abs(along - self.node_axial[local]), np.abs(r - self.node_radius[local]))


def _linear(nodes: np.ndarray, x: float) -> tuple[list[int], list[float]]:
    if len(nodes) == 1:
        return [0], [1.0]
    i0 = int(np.clip(np.searchsorted(nodes, x) - 1, 0, len(nodes) - 2))
    t = float(np.clip((x - nodes[i0]) / (nodes[i0 + 1] - nodes[i0]), 0.0, 1.0))
    return [i0, i0 + 1], [1.0 - t, t]


# ---------------------------------------------------------------------------------- grids
def graded_edges(lo: float, hi: float, tiers, cell_size: float) -> np.ndarray:
    """Cell edges from ``lo`` to ``hi`` through feature coordinates, each interval then cut
    into cells of about ``cell_size``.

    ``tiers`` is a list of ``(coordinates, gap)`` in order of precedence: a coordinate
    becomes a grid line unless it lies within ``gap`` of a line already kept (the box's own
    faces come first, then a hole's edges, its other lines, the faces of touching primitives).
    """
    kept = [lo, hi]
    for coordinates, gap in tiers:
        for b in sorted(coordinates):
            if lo < b < hi and min(abs(b - k) for k in kept) >= gap:
                kept.append(b)
    kept.sort()
    edges = [lo]
    for a, b in zip(kept[:-1], kept[1:]):
        n = divisions(b - a, cell_size)
        edges.extend(a + (b - a) * np.arange(1, n + 1) / n)
    return np.asarray(edges)


#: Grids kept by their primitive, holes, cell size and feature lines: a batch builds a model per run
#: (calibration, sensitivities, uncertainty), and a value that moves no face leaves every grid as it
#: was; cutting the paper bench's boxes took three quarters of a fast model's build.  A kept grid's
#: arrays are read-only: every model that has it shares them.
GRIDS_KEPT = 512


def _frozen(grid):
    for value in vars(grid).values():
        for array in (value if isinstance(value, (list, tuple)) else (value,)):
            if isinstance(array, np.ndarray):
                array.flags.writeable = False
    return grid


def box_grid(box: Box, holes: list[Cylinder], cell_size: float, breaks=None) -> BoxGrid:
    """The cells of ``box``; ``breaks`` (three lists) are feature coordinates the grid passes through
    (kept: :data:`GRIDS_KEPT`)."""
    key = None if breaks is None else tuple(tuple(float(x) for x in axis) for axis in breaks)
    return _kept_box_grid(box, tuple(holes), float(cell_size), key)


@lru_cache(maxsize=GRIDS_KEPT)
def _kept_box_grid(box: Box, holes: tuple[Cylinder, ...], cell_size: float, breaks) -> BoxGrid:
    return _frozen(_box_grid(box, holes, cell_size, breaks))


def _box_grid(box: Box, holes, cell_size: float, breaks=None) -> BoxGrid:
    holes = holes_of_box(box, holes)
    lo = np.asarray(box.origin, dtype=float)
    hi = lo + np.asarray(box.size, dtype=float)
    breaks = breaks or ([], [], [])
    rims, lines = [[], [], []], [[], [], []]
    for hole in holes:  # the grid follows the hole: its ends and edges, and across it more lines
        i = _AXES[hole.axis]
        r = hole.outer_diameter / 2.0
        for a in range(3):
            if a == i:
                rims[a].extend([hole.origin[i], hole.origin[i] + hole.length])
            else:
                rims[a].extend([hole.origin[a] - r, hole.origin[a] + r])
                lines[a].extend(hole.origin[a] + r * HOLE_LINES)
    feature_gap = max(MIN_GAP, FEATURE_GAP * cell_size)
    edges = [graded_edges(lo[a], hi[a], [(rims[a], MIN_GAP), (lines[a], MIN_GAP), (breaks[a], feature_gap)], cell_size)
             for a in range(3)]
    shape = tuple(len(e) - 1 for e in edges)
    widths = [np.diff(e) for e in edges]
    cell_volume = widths[0][:, None, None] * widths[1][None, :, None] * widths[2][None, None, :]
    if holes:
        fraction, centroids = _solid_fractions(edges, holes)
    else:
        fraction = np.ones(shape)
        centres = [0.5 * (e[1:] + e[:-1]) for e in edges]
        centroids = np.stack(np.meshgrid(*centres, indexing="ij"), axis=-1)
    keep = fraction >= MIN_FRACTION
    local = np.full(shape, -1, dtype=int)
    local[keep] = np.arange(int(keep.sum()))
    volumes = (fraction * cell_volume)[keep]
    solid = float(np.prod(box.size)) - sum(_hole_volume_in_box(h, box) for h in holes)
    volumes *= solid / volumes.sum()  # the box's exact solid volume
    grid = BoxGrid(box, holes, edges, local, volumes, centroids[keep].reshape(-1, 3))
    grid.links = _box_links(grid, fraction)
    grid.lines = [_lines(edges[a], [*rims[a], *breaks[a]]) for a in range(3)]
    return grid


def _lines(edges: np.ndarray, features) -> np.ndarray:
    """The cell edges and the features between them (face samples never straddle a feature)."""
    inside = [f for f in features if edges[0] + 1e-9 < f < edges[-1] - 1e-9]
    lines = np.unique(np.concatenate([edges, inside]))
    return lines[np.concatenate([[True], np.diff(lines) > 1e-9])]


def _subsamples(edges: np.ndarray) -> np.ndarray:
    """SUB points per cell, at the middles of equal sub-intervals: shape (cells * SUB,)."""
    offsets = (np.arange(SUB) + 0.5) / SUB
    return (edges[:-1, None] + np.diff(edges)[:, None] * offsets[None, :]).ravel()


def _solid_fractions(edges, holes):
    """Solid fraction and solid centroid of every cell, from SUB³ sub-samples each."""
    shape = tuple(len(e) - 1 for e in edges)
    X, Y, Z = np.meshgrid(*[_subsamples(e) for e in edges], indexing="ij")
    pts = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
    solid = ~in_holes(holes, pts)
    blocks = (shape[0], SUB, shape[1], SUB, shape[2], SUB)
    count = solid.reshape(blocks).sum(axis=(1, 3, 5)).astype(float)
    fraction = count / SUB**3
    centroids = np.empty((*shape, 3))
    for a, coords in enumerate((X, Y, Z)):
        c = (coords * solid.reshape(X.shape)).reshape(blocks).sum(axis=(1, 3, 5))
        centre = 0.5 * (edges[a][1:] + edges[a][:-1])
        default = np.broadcast_to(centre.reshape([-1 if k == a else 1 for k in range(3)]), shape)
        centroids[..., a] = np.where(count > 0, c / np.maximum(count, 1), default)
    return fraction, centroids


def _hole_volume_in_box(hole: Cylinder, box: Box) -> float:
    i = _AXES[hole.axis]
    lo, hi = box.origin[i], box.origin[i] + box.size[i]
    overlap = max(0.0, min(hi, hole.origin[i] + hole.length) - max(lo, hole.origin[i]))
    return math.pi / 4.0 * hole.outer_diameter**2 * overlap


def _box_links(grid: BoxGrid, fraction: np.ndarray):
    """Neighbour pairs in the grid and their geometric factor A_open/Δ [m]."""
    shape = grid.shape
    widths = [np.diff(e) for e in grid.edges]
    a_list, b_list, g_list = [], [], []
    for axis in range(3):
        if shape[axis] < 2:
            continue
        u, v = [k for k in range(3) if k != axis]
        face_area = np.expand_dims(widths[u][:, None] * widths[v][None, :], axis)  # broadcast over the axis
        open_fraction = _open_fractions(grid, axis) if grid.holes else np.ones(
            [shape[k] - 1 if k == axis else shape[k] for k in range(3)])
        sl_a = [slice(None)] * 3
        sl_b = [slice(None)] * 3
        sl_a[axis] = slice(0, shape[axis] - 1)
        sl_b[axis] = slice(1, shape[axis])
        la, lb = grid.local[tuple(sl_a)], grid.local[tuple(sl_b)]
        both = (la >= 0) & (lb >= 0)
        fa, fb = fraction[tuple(sl_a)], fraction[tuple(sl_b)]
        opened = np.maximum(open_fraction, 0.05 * np.minimum(fa, fb))  # solid cells always conduct a little
        area = np.broadcast_to(face_area, opened.shape)
        ca, cb = grid.centroids[la[both]], grid.centroids[lb[both]]
        step = np.broadcast_to(np.expand_dims(0.5 * (widths[axis][:-1] + widths[axis][1:]),
                                              tuple(k for k in range(3) if k != axis)), opened.shape)
        distance = np.maximum(np.abs(cb[:, axis] - ca[:, axis]), 0.25 * step[both])
        a_list.append(la[both])
        b_list.append(lb[both])
        g_list.append(area[both] * opened[both] / distance)
    if not a_list:
        return np.zeros(0, int), np.zeros(0, int), np.zeros(0)
    return np.concatenate(a_list), np.concatenate(b_list), np.concatenate(g_list)


def _open_fractions(grid: BoxGrid, axis: int) -> np.ndarray:
    """Open (solid) fraction of every internal face normal to ``axis``, from SUB² sub-samples."""
    shape = grid.shape
    axes = [grid.edges[a][1:-1] if a == axis else _subsamples(grid.edges[a]) for a in range(3)]
    X, Y, Z = np.meshgrid(*axes, indexing="ij")
    solid = ~in_holes(grid.holes, np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1))
    dims, sub_axes = [], []
    for a in range(3):
        if a == axis:
            dims.append(shape[a] - 1)
        else:
            dims.extend([shape[a], SUB])
            sub_axes.append(len(dims) - 1)
    return solid.reshape(dims).astype(float).mean(axis=tuple(sub_axes))


def cylinder_grid(cyl: Cylinder, cell_size: float, breaks=()) -> CylinderGrid:
    """The cells of ``cyl``; ``breaks`` are feature coordinates along its axis (machine frame; kept:
    :data:`GRIDS_KEPT`)."""
    return _kept_cylinder_grid(cyl, float(cell_size), tuple(float(b) for b in breaks))


@lru_cache(maxsize=GRIDS_KEPT)
def _kept_cylinder_grid(cyl: Cylinder, cell_size: float, breaks: tuple[float, ...]) -> CylinderGrid:
    return _frozen(_cylinder_grid(cyl, cell_size, breaks))


def _cylinder_grid(cyl: Cylinder, cell_size: float, breaks=()) -> CylinderGrid:
    r_in, r_out = cyl.inner_diameter / 2.0, cyl.outer_diameter / 2.0
    start = cyl.origin[_AXES[cyl.axis]]
    axial_edges = graded_edges(0.0, cyl.length, [([b - start for b in breaks], max(MIN_GAP, FEATURE_GAP * cell_size))],
                               cell_size)
    na = len(axial_edges) - 1
    nr = max(MIN_RINGS, divisions(r_out - r_in, cell_size))
    radii = np.linspace(r_in, r_out, nr + 1)
    ring_area = math.pi * (radii[1:] ** 2 - radii[:-1] ** 2)
    slice_length = np.diff(axial_edges)
    volumes = (slice_length[:, None] * ring_area[None, :]).ravel()
    # node of a ring at its area-mean radius (the centroid of the ring's section)
    r_node = np.sqrt(0.5 * (radii[1:] ** 2 + radii[:-1] ** 2))
    axial = 0.5 * (axial_edges[1:] + axial_edges[:-1])
    grid = CylinderGrid(cyl, (na, nr), radii, volumes, np.tile(r_node, na), np.repeat(axial, nr), axial_edges)
    index = np.arange(na * nr).reshape(na, nr)
    a_list = [index[:-1, :].ravel(), index[:, :-1].ravel()]
    b_list = [index[1:, :].ravel(), index[:, 1:].ravel()]
    g_list = [(ring_area[None, :] / np.diff(axial)[:, None]).ravel(),  # axial neighbours: A / Δ
              (2.0 * math.pi * slice_length[:, None] / np.log(r_node[1:] / r_node[:-1])[None, :]).ravel()]  # radial
    grid.links = (np.concatenate(a_list), np.concatenate(b_list), np.concatenate(g_list))
    grid.axial_lines = _lines(axial_edges, [b - start for b in breaks])
    return grid


__all__ = ["BoxGrid", "CylinderGrid", "box_grid", "cylinder_grid", "graded_edges", "in_holes", "holes_of_box",
           "divisions"]
