"""PNG images of an FE field series: the whole system's temperature and the screw's deformation.

- ``temperature_field.png`` — the outer surface of every part, coloured by temperature, in two
  isometric-ish views (from either end), with a colour bar in °C (the paper's Figs. 5–9a);
- ``screw_deformation.png`` — the screw's axial thermal displacement [µm] along its length at
  the final time and a few earlier ones, and the screw drawn coloured by it (Figs. 5–9b);
- ``screw_axial_deformation.png`` — the screw part of the mesh alone, its surface coloured by
  the axial component u_x [µm] of the 3-D displacement field at the last snapshot (Figs. 5–9b
  as the FE program draws them); only for series that carry displacements.

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
from pathlib import Path

import numpy as np

from .fields import FieldSeries
from .instants import spread_instants, time_label, time_unit
from .render import Surface, View, render_surface

__all__ = [
    "write_field_images",
    "plot_temperature_field",
    "plot_screw_deformation",
    "plot_screw_axial_deformation",
    "render_surface",
    "Surface",
    "View",
    "DEFAULT_VIEWS",
    "TEMPERATURE_FIELD_PNG",
    "SCREW_DEFORMATION_PNG",
    "SCREW_AXIAL_DEFORMATION_PNG",
]

TEMPERATURE_FIELD_PNG = "temperature_field.png"
SCREW_DEFORMATION_PNG = "screw_deformation.png"
SCREW_AXIAL_DEFORMATION_PNG = "screw_axial_deformation.png"

_DPI = 150
_COLOURMAP = "turbo"  # the blue-to-red scale engineers read in FE temperature plots
#: (azimuth, elevation) [degrees]: from the −x end and from the +x end, front (−y) side, above
DEFAULT_VIEWS: tuple[tuple[float, float], ...] = ((-145.0, 25.0), (-35.0, 25.0))
#: (azimuth, elevation) [degrees] of the screw alone: from the front (−y), a little above, so
#: that the picture's width is the screw's axis (+x to the right)
SCREW_VIEW: tuple[float, float] = (-90.0, 20.0)


def write_field_images(series: FieldSeries, out_dir: Path, snapshot: int = -1, width_px: int = 900,
                       screw_part: str | None = None) -> list[Path]:
    """Write the field images into ``out_dir``; return their paths.

    Parameters
    ----------
    series : FieldSeries
    out_dir : Path
        Created if missing.
    snapshot : int
        The snapshot of ``temperature_field.png``, default the last.
    width_px : int
        Width of each view of ``temperature_field.png`` [pixels].
    screw_part : str, optional
        The screw's part name (the description's ``kinematics.screw``).  With it, and when the
        series carries displacements, ``screw_axial_deformation.png`` is drawn too.

    Returns
    -------
    list of Path
        ``temperature_field.png``, ``screw_deformation.png`` (not for a system without a feed
        drive, whose series has no screw) and, if drawn, ``screw_axial_deformation.png``.
    """
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    field, screw = out_dir / TEMPERATURE_FIELD_PNG, out_dir / SCREW_DEFORMATION_PNG
    plot_temperature_field(series, field, snapshot=snapshot, width_px=width_px)
    paths = [field]
    if np.size(series.screw_x):
        plot_screw_deformation(series, screw)
        paths.append(screw)
    if series.displacements is not None and screw_part is not None:
        paths.append(out_dir / SCREW_AXIAL_DEFORMATION_PNG)
        plot_screw_axial_deformation(series, paths[-1], screw_part)
    return paths


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
    unit = time_unit(series.snapshot_times)
    title = f"Temperature field at t = {time_label(series.snapshot_times[snapshot], unit)}"
    figure.suptitle(f"{title} — {series.title}" if series.title else title)
    figure.text(0.01, 0.01, f"min {low:.1f} °C, max {high:.1f} °C", fontsize=9, color="0.3")
    figure.savefig(path, dpi=_DPI, format="png")


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
    unit = time_unit(series.snapshot_times)
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
    last = time_label(series.snapshot_times[-1], unit)
    title = f"Axial deformation of the screw at t = {last}"
    figure.suptitle(f"{title} — {series.title}" if series.title else title)

    # profiles at a few times, the last one emphasised
    picks = spread_instants(series.snapshot_times, n_curves)
    shades = colormaps["Blues"](np.linspace(0.35, 0.8, max(len(picks) - 1, 1)))
    for colour, k in zip(shades, picks[:-1]):
        bottom.plot(x_mm, um[k], color=colour, linewidth=1.3,
                    label=f"t = {time_label(series.snapshot_times[k], unit)}")
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


def plot_screw_axial_deformation(series: FieldSeries, path: Path, screw_part: str, snapshot: int = -1, *,
                                 view: tuple[float, float] = SCREW_VIEW, width_px: int = 1200) -> None:
    """The screw part alone, its surface coloured by the axial displacement u_x [µm], with a colour bar.

    Parameters
    ----------
    series : FieldSeries
        Must carry ``displacements``; u_x is their x component as the ``.vtu`` files hold it
        (relative to the supports, not to the positioning reference).
    path : Path
        The PNG to write.
    screw_part : str
        The screw's part name (``kinematics.screw``), one of ``series.part_names``.
    snapshot : int
        Which snapshot, default the last.
    view : (azimuth, elevation) [degrees]
        Where the viewer stands (as in :func:`plot_temperature_field`); the default's picture
        has the screw's axis across, so that the axis below it reads as x [mm].
    width_px : int
        Width of the screw's picture [pixels]; drawn to scale, so a slender screw is a band.

    Raises
    ------
    ValueError
        No displacements in the series, or no part named ``screw_part`` (or it has no tetrahedra).
    """
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize
    from matplotlib.figure import Figure

    if series.displacements is None:
        raise ValueError("the field series holds no displacement field (displacements is None)")
    if screw_part not in series.part_names:
        raise ValueError(f"no part {screw_part!r} in the field series (parts: {', '.join(series.part_names)})")
    snapshot = range(series.n_snapshots)[snapshot]
    part = series.part_names.index(screw_part)
    surface = Surface.of(series, snapshot, parts=[part])
    if len(surface.triangles) == 0:
        raise ValueError(f"part {screw_part!r} has no tetrahedra in the field series")
    u_x = series.displacements[snapshot, :, 0] * 1e6
    own = np.unique(series.tets[series.part_id == part])
    low, high = float(u_x[own].min()), float(u_x[own].max())
    if high - low < 1e-9:  # a uniform field still gets a readable scale
        low, high = low - 0.5, high + 0.5
    norm, cmap = Normalize(low, high), colormaps[_COLOURMAP]
    camera = View.from_angles(*view)
    scale = width_px / max(float(surface.extent(camera)[0]), 1e-12)
    image = render_surface(surface, u_x, camera, norm, cmap, scale)
    left, right, bottom, top = (1e3 * edge for edge in surface.frame(camera, scale))

    height, width = image.shape[:2]
    figure = Figure(figsize=(width / _DPI + 0.8, height / _DPI + 1.5), layout="constrained")
    ax = figure.subplots()
    ax.imshow(image, extent=(left, right, bottom, top), interpolation="antialiased")
    ax.set_yticks([])
    for side in ("left", "right", "top"):
        ax.spines[side].set_visible(False)
    if camera.right[0] > 0.999:  # the picture's width is the machine's +x axis: label it
        ax.set_xlabel("axial position x [mm]")
    else:
        ax.set_xticks([])
    colourbar = figure.colorbar(ScalarMappable(norm, cmap), ax=ax, location="bottom", shrink=0.6, aspect=40)
    colourbar.set_label("axial displacement u_x [µm]")
    unit = time_unit(series.snapshot_times)
    title = f"Axial deformation of the screw at t = {time_label(series.snapshot_times[snapshot], unit)}"
    figure.suptitle(f"{title} — {series.title}" if series.title else title)
    figure.text(0.01, 0.01, f"min {float(u_x[own].min()):.1f} µm, max {float(u_x[own].max()):.1f} µm",
                fontsize=9, color="0.3")
    figure.savefig(path, dpi=_DPI, format="png")


def _cell_edges(x: np.ndarray) -> np.ndarray:
    """Edges around the positions ``x``: midpoints between them, half a spacing beyond the ends."""
    if len(x) == 1:
        return np.array([x[0] - 0.5, x[0] + 0.5])
    mid = 0.5 * (x[1:] + x[:-1])
    return np.concatenate([[x[0] - (mid[0] - x[0])], mid, [x[-1] + (x[-1] - mid[-1])]])
