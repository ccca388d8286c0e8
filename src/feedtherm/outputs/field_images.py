"""PNG images of an FE field series: the whole system's temperature and the screw's deformation.

- ``temperature_field.png`` — the outer surface of every part, coloured by temperature, in two
  isometric-ish views (from either end), with a colour bar in °C (the paper's Figs. 5–9a);
- ``screw_deformation.png`` — the screw's axial thermal displacement [µm] along its length at
  the final time and a few earlier ones, and the screw drawn coloured by it (Figs. 5–9b).

Rendering needs no display and no OpenGL: the surface is rasterised here with numpy (a
z-buffer over the boundary triangles of the tetrahedral mesh, drawn at twice the output
resolution and averaged down for smooth edges), then framed by matplotlib (colour bar,
title) through the Agg canvas.  A z-buffer, unlike sorting polygons back to front, hides
every surface correctly whatever the triangle sizes, and its cost grows with the pixels
rather than the triangles: a 150,000-node mesh draws in a few seconds.  Colours are the
temperature interpolated linearly inside each triangle, as ParaView draws P1 data, dimmed
by a soft light so that faces of different orientation read as shapes; part boundaries,
silhouettes and sharp edges are outlined.  matplotlib is imported inside the functions.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .fields import FieldSeries, boundary_triangles

__all__ = [
    "write_field_images",
    "plot_temperature_field",
    "plot_screw_deformation",
    "render_surface",
    "Surface",
    "View",
    "DEFAULT_VIEWS",
    "TEMPERATURE_FIELD_PNG",
    "SCREW_DEFORMATION_PNG",
]

TEMPERATURE_FIELD_PNG = "temperature_field.png"
SCREW_DEFORMATION_PNG = "screw_deformation.png"

_DPI = 150
_HOURS = 3600.0
_SUPERSAMPLE = 2
_FRAGMENTS_PER_CHUNK = 2_000_000  # bounds the rasteriser's temporary memory (~100 MB)
_EDGE_COLOUR = np.array([0.12, 0.12, 0.12])
_BACKGROUND = np.array([1.0, 1.0, 1.0])
_COLOURMAP = "turbo"  # the blue-to-red scale engineers read in FE temperature plots
#: (azimuth, elevation) [degrees]: from the −x end and from the +x end, front (−y) side, above
DEFAULT_VIEWS: tuple[tuple[float, float], ...] = ((-145.0, 25.0), (-35.0, 25.0))


def write_field_images(series: FieldSeries, out_dir: Path, snapshot: int = -1, width_px: int = 900) -> list[Path]:
    """Write ``temperature_field.png`` (at ``snapshot``, default the last; ``width_px`` wide
    per view) and ``screw_deformation.png`` into ``out_dir``; return their paths."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    field, screw = out_dir / TEMPERATURE_FIELD_PNG, out_dir / SCREW_DEFORMATION_PNG
    plot_temperature_field(series, field, snapshot=snapshot, width_px=width_px)
    plot_screw_deformation(series, screw)
    return [field, screw]


# --------------------------------------------------------------------------- temperature field


def plot_temperature_field(
    series: FieldSeries,
    path: Path,
    snapshot: int = -1,
    *,
    views: Sequence[tuple[float, float]] = DEFAULT_VIEWS,
    width_px: int = 900,
) -> None:
    """The whole system's surface coloured by temperature [°C], seen from one or more sides.

    Parameters
    ----------
    views : sequence of (azimuth, elevation) [degrees]
        Where the viewer stands, as in matplotlib's 3D axes: azimuth from +x towards +y,
        elevation above the x–y plane.  The default shows the system from its −x end and
        from its +x end, both from the −y side and above: together they show both bearing
        housings, the screw on either side of the nut housing, the table and the base.
    width_px : int
        Width [pixels] of the widest of the pictures; all are drawn at the same scale.
    """
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize
    from matplotlib.figure import Figure

    snapshot = range(series.n_snapshots)[snapshot]
    celsius = series.celsius(snapshot)
    used = np.unique(series.tets)
    low, high = (float(celsius[used].min()), float(celsius[used].max())) if used.size else (0.0, 0.0)
    spread = max(high - low, 1.0) - (high - low)  # a uniform field gets a 1 K wide scale
    norm, cmap = Normalize(low - spread / 2, high + spread / 2), colormaps[_COLOURMAP]
    surface = Surface.of(series, snapshot)
    cameras = [View.from_angles(azimuth, elevation) for azimuth, elevation in views]
    if not cameras:
        raise ValueError("no view to draw")
    scale = width_px / max(surface.extent(view)[0] for view in cameras)
    images = [render_surface(surface, celsius, view, norm, cmap, scale) for view in cameras]

    widths = [image.shape[1] for image in images]
    height = max(image.shape[0] for image in images)
    figure = Figure(figsize=(sum(widths) / _DPI + 1.6, height / _DPI + 1.1), layout="constrained")
    axes = np.atleast_1d(figure.subplots(1, len(images), width_ratios=widths))
    for ax, image, view in zip(axes, images, cameras):
        ax.imshow(image, interpolation="antialiased")
        ax.set_axis_off()
        _draw_triad(ax, view)
        if len(images) > 1:
            side = "−x" if view.toward[0] < 0 else "+x"
            ax.set_title(f"from the {side} end", fontsize=9, color="0.3")
    colourbar = figure.colorbar(ScalarMappable(norm, cmap), ax=list(axes), shrink=0.85, pad=0.01, aspect=30)
    colourbar.set_label("temperature [°C]")
    unit = _time_unit(series.snapshot_times)
    title = f"Temperature field at t = {_time_label(series.snapshot_times[snapshot], unit)}"
    figure.suptitle(f"{title} — {series.title}" if series.title else title)
    figure.text(0.01, 0.01, f"min {low:.1f} °C, max {high:.1f} °C", fontsize=9, color="0.3")
    figure.savefig(path, dpi=_DPI, format="png")


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

    Every boundary face of the tetrahedra, the moving parts displaced, less the faces that
    two parts share (a face with a coincident twin lies inside the assembly).
    """

    points: np.ndarray  #: (n, 3) displaced vertices [m]
    triangles: np.ndarray  #: (f, 3) vertex indices, counter-clockwise from outside
    part: np.ndarray  #: (f,) part id of each triangle
    normal: np.ndarray  #: (f, 3) unit outward normals

    @classmethod
    def of(cls, series: FieldSeries, snapshot: int) -> "Surface":
        points = series.displaced_points(snapshot)
        triangles, owner = boundary_triangles(points, series.tets)
        triangles, owner = _drop_shared_faces(points, triangles, owner)
        a, b, c = (points[triangles[:, j]] for j in range(3))
        normal = np.cross(b - a, c - a)
        length = np.linalg.norm(normal, axis=1)
        keep = length > 0
        return cls(points, triangles[keep], series.part_id[owner[keep]], normal[keep] / length[keep, None])

    def extent(self, view: View) -> np.ndarray:
        """Width and height of the surface's picture in that view [m]."""
        used = np.unique(self.triangles) if len(self.triangles) else np.arange(len(self.points))
        screen = self.points[used] @ np.column_stack([view.right, view.up])
        return np.ptp(screen, axis=0) if len(screen) else np.zeros(2)


def render_surface(surface: Surface, values: np.ndarray, view: View, norm, cmap, scale: float) -> np.ndarray:
    """RGB image (h, w, 3) of the surface seen from ``view``, ``scale`` pixels per metre.

    ``values`` (one per vertex) are interpolated inside each triangle and mapped through
    ``norm`` and ``cmap``; the background is white, outlines dark grey.
    """
    facing = surface.normal @ view.toward > 1e-9
    triangles, normal, part = surface.triangles[facing], surface.normal[facing], surface.part[facing]
    points = surface.points
    screen = np.column_stack([points @ view.right, points @ view.up, points @ view.toward])
    used = np.unique(surface.triangles) if len(surface.triangles) else np.arange(len(points))
    lo, hi = screen[used, :2].min(axis=0), screen[used, :2].max(axis=0)
    margin = 0.03 * max(float((hi - lo).max()), 1e-12)
    pixels = scale * _SUPERSAMPLE  # per metre, while rendering
    width, height = (int(np.ceil((hi[k] - lo[k] + 2 * margin) * scale)) * _SUPERSAMPLE for k in (0, 1))
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
    shape = (height // _SUPERSAMPLE, _SUPERSAMPLE, width // _SUPERSAMPLE, _SUPERSAMPLE, 3)
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


def _draw_triad(ax, view: View) -> None:
    """Small x/y/z arrows in the lower left corner, pointing as the model's axes do."""
    corner = (0.05, 0.07)
    for k, (label, colour) in enumerate((("x", "#c0392b"), ("y", "#1e8449"), ("z", "#2c3e9e"))):
        u, v = np.eye(3)[k] @ view.right, np.eye(3)[k] @ view.up
        ax.annotate("", xy=corner, xycoords="axes fraction", xytext=(22 * u, 22 * v),
                    textcoords="offset points", arrowprops=dict(arrowstyle="<|-", color=colour, lw=1.3))
        if np.hypot(u, v) > 0.2:  # an axis pointing at the viewer has no readable arrow
            ax.annotate(label, xy=corner, xycoords="axes fraction", xytext=(30 * u, 30 * v),
                        textcoords="offset points", ha="center", va="center", color=colour,
                        fontsize=9, fontweight="bold")


def _time_unit(times: np.ndarray) -> str:
    """``h`` when the series reaches an hour, else ``s``: one unit for every label of a figure."""
    return "h" if times[-1] >= _HOURS else "s"


def _time_label(seconds: float, unit: str) -> str:
    return f"{seconds / _HOURS:.2f} h" if unit == "h" else f"{seconds:.0f} s"


# --------------------------------------------------------------------------- screw deformation


def plot_screw_deformation(series: FieldSeries, path: Path, n_curves: int = 5) -> None:
    """The screw's axial displacement [µm] along it [mm]: the screw coloured by the final
    displacement (top) and profiles at up to ``n_curves`` times (bottom, the last in black)."""
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize
    from matplotlib.figure import Figure

    if len(series.screw_x) == 0:
        raise ValueError("the field series holds no screw displacement (screw_x is empty)")
    x_mm = series.screw_x * 1e3
    um = series.screw_displacement * 1e6
    final = um[-1]
    unit = _time_unit(series.snapshot_times)
    figure = Figure(figsize=(9, 6), layout="constrained")
    top, bottom = figure.subplots(2, 1, sharex=True, height_ratios=[1, 4.5])

    # the screw as a bar coloured by its displacement at the final time
    edges = _cell_edges(x_mm)
    low, high = float(final.min()), float(final.max())
    if high - low < 1e-9:
        low, high = low - 0.5, high + 0.5
    norm = Normalize(low, high)
    across = np.linspace(-1.0, 1.0, 33)
    roundness = 0.62 + 0.38 * np.sqrt(1.0 - across**2)  # shaded like a lit shaft
    shaft = colormaps[_COLOURMAP](norm(final))[None, :, :3] * roundness[:, None, None]
    top.imshow(shaft, extent=(edges[0], edges[-1], -1.0, 1.0), aspect="auto", interpolation="nearest")
    mesh = ScalarMappable(norm, colormaps[_COLOURMAP])
    top.set_yticks([])
    top.set_ylim(-1.5, 1.5)
    top.set_ylabel("screw", rotation=0, ha="right", va="center")
    top.tick_params(axis="x", length=0)
    for side in ("left", "right", "top", "bottom"):
        top.spines[side].set_visible(False)
    bar = figure.colorbar(mesh, ax=top, pad=0.01, aspect=6)
    bar.set_label("µm")
    last = _time_label(series.snapshot_times[-1], unit)
    title = f"Axial deformation of the screw at t = {last}"
    figure.suptitle(f"{title} — {series.title}" if series.title else title)

    # profiles at a few times, the last one emphasised
    picks = _profile_snapshots(series.snapshot_times, n_curves)
    shades = colormaps["Blues"](np.linspace(0.35, 0.8, max(len(picks) - 1, 1)))
    for colour, k in zip(shades, picks[:-1]):
        bottom.plot(x_mm, um[k], color=colour, linewidth=1.3,
                    label=f"t = {_time_label(series.snapshot_times[k], unit)}")
    bottom.plot(x_mm, final, color="black", linewidth=2.0, label=f"t = {last}")
    peak = int(np.argmax(np.abs(final)))
    bottom.plot(x_mm[peak], final[peak], "o", color="black", markersize=4)
    right_half = x_mm[peak] > 0.5 * (x_mm[0] + x_mm[-1])
    bottom.annotate(f"{final[peak]:.1f} µm at x = {x_mm[peak]:.0f} mm", xy=(x_mm[peak], final[peak]),
                    xytext=(-8 if right_half else 8, 8 if final[peak] >= 0 else -14),
                    textcoords="offset points", ha="right" if right_half else "left", fontsize=9)
    bottom.axhline(0.0, color="0.5", linewidth=0.8)
    bottom.set_xlabel("axial position x [mm]")
    bottom.set_ylabel("axial displacement [µm]")
    bottom.set_xlim(edges[0], edges[-1])
    bottom.margins(y=0.12)
    bottom.grid(True, alpha=0.3)
    bottom.legend(loc="best", fontsize=9, frameon=False)
    figure.savefig(path, dpi=_DPI, format="png")


def _cell_edges(x: np.ndarray) -> np.ndarray:
    """Edges around the positions ``x``: midpoints between them, half a spacing beyond the ends."""
    if len(x) == 1:
        return np.array([x[0] - 0.5, x[0] + 0.5])
    mid = 0.5 * (x[1:] + x[:-1])
    return np.concatenate([[x[0] - (mid[0] - x[0])], mid, [x[-1] + (x[-1] - mid[-1])]])


def _profile_snapshots(times: np.ndarray, n_curves: int) -> list[int]:
    """Up to ``n_curves`` snapshots nearest to evenly spaced times after the first; the last always."""
    last = len(times) - 1
    if n_curves <= 1 or last == 0:
        return [last]
    targets = times[0] + (times[-1] - times[0]) * np.arange(1, n_curves + 1) / n_curves
    picks = sorted({int(np.argmin(np.abs(times - target))) for target in targets} | {last})
    return picks
