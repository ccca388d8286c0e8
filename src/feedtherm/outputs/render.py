"""Software rendering of a tet mesh's outer surface: depth-buffered, interpolated colours.

numpy only, so images render on any headless machine (no OpenGL, no display): each boundary
triangle is rasterised with its depth, the nearest one wins per pixel, its temperature is
interpolated across it, and part edges are outlined.  Used by :mod:`.field_images`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .fields import FieldSeries, boundary_triangles

SUPERSAMPLE = 2
_FRAGMENTS_PER_CHUNK = 2_000_000  # bounds the rasteriser's temporary memory (~100 MB)
_EDGE_COLOUR = np.array([0.12, 0.12, 0.12])
_BACKGROUND = np.array([1.0, 1.0, 1.0])


@dataclass(frozen=True)
class View:
    """An orthographic camera: screen ``right`` and ``up`` and ``toward`` the viewer (unit)."""

    right: np.ndarray
    up: np.ndarray
    toward: np.ndarray

    @classmethod
    def from_angles(cls, azimuth: float, elevation: float) -> "View":
        if not -90.0 < elevation < 90.0:
            raise ValueError(f"elevation {elevation}° is outside (−90°, 90°)")
        az, el = np.radians(azimuth), np.radians(elevation)
        toward = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
        right = np.cross([0.0, 0.0, 1.0], toward)
        right /= np.linalg.norm(right)
        return cls(right=right, up=np.cross(toward, right), toward=toward)

    @property
    def light(self) -> np.ndarray:
        """A light from behind the viewer's left shoulder, a little above."""
        light = self.toward + 0.45 * self.up - 0.35 * self.right
        return light / np.linalg.norm(light)


@dataclass(frozen=True)
class Surface:
    """The outer surface of the mesh at one snapshot: triangles oriented outwards.

    Every boundary face of the tetrahedra (of all parts, or of the chosen ones), the moving
    parts displaced, less the faces that two parts share (a face with a coincident twin lies
    inside the assembly).
    """

    points: np.ndarray  #: (n, 3) displaced vertices [m]
    triangles: np.ndarray  #: (f, 3) vertex indices, counter-clockwise from outside
    part: np.ndarray  #: (f,) part id of each triangle
    normal: np.ndarray  #: (f, 3) unit outward normals

    @classmethod
    def of(cls, series: FieldSeries, snapshot: int, parts: Sequence[int] | None = None) -> "Surface":
        """The surface at ``snapshot``; ``parts`` (part ids): of those parts alone, default all."""
        points = series.displaced_points(snapshot)
        chosen = np.arange(len(series.tets)) if parts is None else np.flatnonzero(np.isin(series.part_id, parts))
        triangles, owner = boundary_triangles(points, series.tets[chosen])
        owner = chosen[owner]
        triangles, owner = _drop_shared_faces(points, triangles, owner)
        a, b, c = (points[triangles[:, j]] for j in range(3))
        normal = np.cross(b - a, c - a)
        length = np.linalg.norm(normal, axis=1)
        keep = length > 0
        return cls(points, triangles[keep], series.part_id[owner[keep]], normal[keep] / length[keep, None])

    def extent(self, view: View) -> np.ndarray:
        """Width and height of the surface's picture in that view [m]."""
        if len(self.points) == 0:
            return np.zeros(2)
        lo, hi, _ = self._window(view)
        return hi - lo

    def frame(self, view: View, scale: float) -> tuple[float, float, float, float]:
        """Where :func:`render_surface`'s image lies on the screen plane [m]: (left, right, bottom, top).

        The image's pixels tile this rectangle (``scale`` pixels per metre), so a figure can
        put a length axis under it: with a view whose ``right`` is +x, left and right are
        machine x.
        """
        lo, hi, margin = self._window(view)
        width, height = (int(np.ceil((hi[k] - lo[k] + 2 * margin) * scale)) for k in (0, 1))
        left, top = lo[0] - margin, hi[1] + margin
        return left, left + width / scale, top - height / scale, top

    def _window(self, view: View) -> tuple[np.ndarray, np.ndarray, float]:
        """Lowest and highest screen (right, up) coordinates of the drawn vertices, and the margin [m]."""
        used = np.unique(self.triangles) if len(self.triangles) else np.arange(len(self.points))
        screen = self.points[used] @ np.column_stack([view.right, view.up])
        lo, hi = screen.min(axis=0), screen.max(axis=0)
        return lo, hi, 0.03 * max(float((hi - lo).max()), 1e-12)


def render_surface(surface: Surface, values: np.ndarray, view: View, norm, cmap, scale: float) -> np.ndarray:
    """RGB image (h, w, 3) of the surface seen from ``view``, ``scale`` pixels per metre.

    ``values`` (one per vertex) are interpolated inside each triangle and mapped through
    ``norm`` and ``cmap``; the background is white, outlines dark grey.
    """
    facing = surface.normal @ view.toward > 1e-9
    triangles, normal, part = surface.triangles[facing], surface.normal[facing], surface.part[facing]
    points = surface.points
    screen = np.column_stack([points @ view.right, points @ view.up, points @ view.toward])
    lo, hi, margin = surface._window(view)
    pixels = scale * SUPERSAMPLE  # per metre, while rendering
    width, height = (int(np.ceil((hi[k] - lo[k] + 2 * margin) * scale)) * SUPERSAMPLE for k in (0, 1))
    x = (screen[:, 0] - lo[0] + margin) * pixels
    y = (hi[1] + margin - screen[:, 1]) * pixels  # image rows grow downwards
    frame = _rasterise(np.column_stack([x, y]), screen[:, 2], triangles, width, height)

    hit = frame.triangle >= 0
    won = frame.triangle[hit]
    tri = triangles[won]
    l0, l1 = frame.l0[hit], frame.l1[hit]
    value = l0 * values[tri[:, 0]] + l1 * values[tri[:, 1]] + (1 - l0 - l1) * values[tri[:, 2]]
    shade = 0.62 + 0.38 * np.clip(normal[won] @ view.light, 0.0, 1.0)
    rgb = np.tile(_BACKGROUND, (height, width, 1))
    rgb[hit] = cmap(norm(value))[:, :3] * shade[:, None]
    pixel_part = np.full((height, width), -1)
    pixel_part[hit] = part[won]
    pixel_normal = np.zeros((height, width, 3))
    pixel_normal[hit] = normal[won]
    rgb[_outlines(pixel_part, pixel_normal, frame.depth, depth_jump=25.0 / pixels)] = _EDGE_COLOUR
    shape = (height // SUPERSAMPLE, SUPERSAMPLE, width // SUPERSAMPLE, SUPERSAMPLE, 3)
    return rgb.reshape(shape).mean(axis=(1, 3))


def _drop_shared_faces(points, triangles, owner):
    """Remove boundary faces that have a coincident twin (the two sides of a part joint)."""
    if len(triangles) == 0:
        return triangles, owner
    extent = float(np.ptp(points, axis=0).max()) or 1.0
    grid = np.round(points / (1e-7 * extent)).astype(np.int64)
    _, position = np.unique(grid, axis=0, return_inverse=True)
    key = np.sort(position.ravel()[triangles], axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    alone = counts[inverse.ravel()] == 1
    return triangles[alone], owner[alone]


@dataclass
class _Frame:
    triangle: np.ndarray  #: index of the visible triangle per pixel, -1 for background
    depth: np.ndarray  #: its depth towards the viewer (−inf for background)
    l0: np.ndarray  #: barycentric weight of its vertex 0 at the pixel centre
    l1: np.ndarray  #: … of its vertex 1


def _rasterise(xy: np.ndarray, depth: np.ndarray, triangles: np.ndarray, width: int, height: int) -> _Frame:
    """Z-buffer the triangles: per pixel the nearest triangle covering the pixel centre.

    Triangles are grouped by the size of their pixel bounding box (powers of two), so that
    each group is one vectorised pass over (triangle × box pixel) candidates.
    """
    n_pixels = width * height
    best = np.full(n_pixels, -np.inf)
    winner = np.full(n_pixels, -1)
    w0 = np.zeros(n_pixels)
    w1 = np.zeros(n_pixels)
    frame = _Frame(winner, best, w0, w1)
    if len(triangles) == 0:
        return _reshaped(frame, width, height)
    px, py, pz = xy[triangles, 0], xy[triangles, 1], depth[triangles]
    # pixel (i, j) has its centre at (i + 0.5, j + 0.5); the columns/rows whose centre is inside the box
    i0 = np.clip(np.ceil(px.min(axis=1) - 0.5), 0, width).astype(np.int64)
    i1 = np.clip(np.floor(px.max(axis=1) - 0.5), -1, width - 1).astype(np.int64)
    j0 = np.clip(np.ceil(py.min(axis=1) - 0.5), 0, height).astype(np.int64)
    j1 = np.clip(np.floor(py.max(axis=1) - 0.5), -1, height - 1).astype(np.int64)
    nx, ny = i1 - i0 + 1, j1 - j0 + 1
    det = (py[:, 1] - py[:, 2]) * (px[:, 0] - px[:, 2]) + (px[:, 2] - px[:, 1]) * (py[:, 0] - py[:, 2])
    keep = (nx > 0) & (ny > 0) & (np.abs(det) > 1e-12)
    bx = _next_power_of_two(nx)
    by = _next_power_of_two(ny)
    groups = np.flatnonzero(keep)
    order = groups[np.lexsort((by[groups], bx[groups]))]
    boundaries = np.flatnonzero(np.diff(bx[order]) | np.diff(by[order])) + 1
    for group in np.split(order, boundaries):
        if group.size == 0:
            continue
        kx, ky = int(bx[group[0]]), int(by[group[0]])
        step = max(1, _FRAGMENTS_PER_CHUNK // (kx * ky))
        dx, dy = np.meshgrid(np.arange(kx), np.arange(ky), indexing="xy")
        dx, dy = dx.ravel(), dy.ravel()
        for start in range(0, group.size, step):
            t = group[start:start + step]
            cx = i0[t, None] + dx
            cy = j0[t, None] + dy
            valid = (cx <= i1[t, None]) & (cy <= j1[t, None])
            sx, sy = cx + 0.5, cy + 0.5
            x2, y2 = px[t, 2, None], py[t, 2, None]
            d = det[t, None]
            l0 = ((py[t, 1, None] - y2) * (sx - x2) + (x2 - px[t, 1, None]) * (sy - y2)) / d
            l1 = ((y2 - py[t, 0, None]) * (sx - x2) + (px[t, 0, None] - x2) * (sy - y2)) / d
            l2 = 1.0 - l0 - l1
            tol = -1e-9
            valid &= (l0 >= tol) & (l1 >= tol) & (l2 >= tol)
            rows, cols = np.nonzero(valid)
            if rows.size == 0:
                continue
            pixel = cy[rows, cols] * width + cx[rows, cols]
            a0, a1 = l0[rows, cols], l1[rows, cols]
            z = a0 * pz[t[rows], 0] + a1 * pz[t[rows], 1] + (1 - a0 - a1) * pz[t[rows], 2]
            # the nearest fragment per pixel in this chunk, then against the buffer
            nearest = np.lexsort((-z, pixel))
            first = np.ones(nearest.size, dtype=bool)
            first[1:] = pixel[nearest[1:]] != pixel[nearest[:-1]]
            pick = nearest[first]
            closer = z[pick] > best[pixel[pick]]
            pick = pick[closer]
            target = pixel[pick]
            best[target] = z[pick]
            winner[target] = t[rows[pick]]
            w0[target] = a0[pick]
            w1[target] = a1[pick]
    return _reshaped(frame, width, height)


def _reshaped(frame: _Frame, width: int, height: int) -> _Frame:
    return _Frame(*(getattr(frame, name).reshape(height, width) for name in ("triangle", "depth", "l0", "l1")))


def _next_power_of_two(n: np.ndarray) -> np.ndarray:
    n = np.maximum(n, 1)
    return (1 << np.ceil(np.log2(n)).astype(np.int64)).astype(np.int64)


def _outlines(part: np.ndarray, normal: np.ndarray, depth: np.ndarray, depth_jump: float) -> np.ndarray:
    """Pixels on a silhouette, a part boundary, a depth jump or a sharp edge (> 30°)."""
    edge = np.zeros(part.shape, dtype=bool)
    for axis in (0, 1):
        sl_a = [slice(None)] * 2
        sl_b = [slice(None)] * 2
        sl_a[axis], sl_b[axis] = slice(None, -1), slice(1, None)
        pa, pb = part[tuple(sl_a)], part[tuple(sl_b)]
        na, nb = normal[tuple(sl_a)], normal[tuple(sl_b)]
        za, zb = depth[tuple(sl_a)], depth[tuple(sl_b)]
        both = (pa >= 0) & (pb >= 0)
        za, zb = np.where(both, za, 0.0), np.where(both, zb, 0.0)  # background depth is −inf
        differs = (pa != pb) | (both & (np.abs(za - zb) > depth_jump)) | (
            both & (np.einsum("...k,...k->...", na, nb) < np.cos(np.radians(30.0)))
        )
        # mark the nearer pixel of the pair, so that a line sits on the front part
        front_a = za >= zb
        edge[tuple(sl_a)] |= differs & front_a & (pa >= 0)
        edge[tuple(sl_b)] |= differs & ~front_a & (pb >= 0)
    return edge
