"""Small structured tetrahedral meshes for tests and examples.

Every mesh is a tensor grid of hexahedra, each cut into six tetrahedra along its main
diagonal (``skfem.MeshTet.init_tensor``). That cut is the same in every hexahedron, so a
plane of the grid is triangulated the same way from both sides and along any translation by
whole cells: two parts built on the same grid lines meet facet to facet, and a regular axial
layer of facets looks like every other.

Boundary facets are named by position: ``x0``/``x1`` (the faces at the smallest/largest x),
``y0``/``y1``, ``z0``/``z1``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import MeshTet

from .topology import join, part_facets, split_nodes

__all__ = ["box", "bar", "TwoBlocks", "two_blocks", "RodAndSlider", "rod_and_slider"]


def _faces(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> dict:
    tol = 1e-9 * max(x[-1] - x[0], y[-1] - y[0], z[-1] - z[0])
    return {
        "x0": lambda m: np.abs(m[0] - x[0]) < tol,
        "x1": lambda m: np.abs(m[0] - x[-1]) < tol,
        "y0": lambda m: np.abs(m[1] - y[0]) < tol,
        "y1": lambda m: np.abs(m[1] - y[-1]) < tol,
        "z0": lambda m: np.abs(m[2] - z[0]) < tol,
        "z1": lambda m: np.abs(m[2] - z[-1]) < tol,
    }


def box(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> MeshTet:
    """A box on the grid lines ``x``, ``y``, ``z`` [m] with faces named ``x0`` … ``z1``."""
    x, y, z = (np.sort(np.asarray(c, dtype=float)) for c in (x, y, z))
    return MeshTet.init_tensor(x, y, z).with_boundaries(_faces(x, y, z))


def bar(length: float, width: float, height: float, nx: int, ny: int = 1, nz: int = 1) -> MeshTet:
    """A bar along x from 0 to ``length`` [m], ``nx`` × ``ny`` × ``nz`` hexahedra."""
    return box(
        np.linspace(0.0, length, nx + 1), np.linspace(0.0, width, ny + 1), np.linspace(0.0, height, nz + 1)
    )


@dataclass(frozen=True)
class TwoBlocks:
    """Two blocks side by side along x that touch at ``x = length_a`` without sharing nodes."""

    mesh: MeshTet
    elements_a: np.ndarray  #: block a, 0 ≤ x ≤ length_a
    elements_b: np.ndarray  #: block b, length_a ≤ x ≤ length_a + length_b
    interface_a: np.ndarray  #: facets of a on the common face
    interface_b: np.ndarray  #: facets of b on the common face
    outer_a: np.ndarray  #: facets at x = 0
    outer_b: np.ndarray  #: facets at x = length_a + length_b
    lateral: np.ndarray  #: facets on the four sides


def two_blocks(
    length_a: float, length_b: float, width: float, height: float, na: int, nb: int, ny: int = 1, nz: int = 1
) -> TwoBlocks:
    """Two blocks meshed as one conforming box, then split at ``x = length_a``."""
    x = np.concatenate([np.linspace(0.0, length_a, na + 1), np.linspace(length_a, length_a + length_b, nb + 1)[1:]])
    whole = box(x, np.linspace(0.0, width, ny + 1), np.linspace(0.0, height, nz + 1))
    centre_x = whole.p[0, whole.t].mean(axis=0)
    elements_b = np.nonzero(centre_x > length_a)[0]
    elements_a = np.nonzero(centre_x < length_a)[0]
    mesh, _ = split_nodes(whole, elements_b)
    tol = 1e-9 * (length_a + length_b)

    def at(x0):
        return lambda m: np.abs(m[0] - x0) < tol

    def on_sides(m):
        return (np.abs(m[1]) < tol) | (np.abs(m[1] - width) < tol) | (np.abs(m[2]) < tol) | (np.abs(m[2] - height) < tol)

    lateral = part_facets(mesh, np.arange(mesh.nelements), on_sides)
    return TwoBlocks(
        mesh=mesh,
        elements_a=elements_a,
        elements_b=elements_b,
        interface_a=part_facets(mesh, elements_a, at(length_a)),
        interface_b=part_facets(mesh, elements_b, at(length_a)),
        outer_a=part_facets(mesh, elements_a, at(0.0)),
        outer_b=part_facets(mesh, elements_b, at(length_a + length_b)),
        lateral=lateral,
    )


@dataclass(frozen=True)
class RodAndSlider:
    """A square rod along x with a block (the slider) resting on its top face.

    The rod is cut into axial layers of thickness ``layer``; the slider spans
    ``slider_layers`` of them and is meshed over rod layers ``slider_start …
    slider_start + slider_layers - 1``. The two touch without sharing nodes: the slider's
    position is set by the sliding interface, not by moving its mesh.
    """

    mesh: MeshTet
    layer: float  #: axial layer thickness [m]
    rod_layers: int
    slider_layers: int
    rod_elements: np.ndarray
    slider_elements: np.ndarray
    rod_top: np.ndarray  #: rod facets at z = width (the track the slider runs on)
    rod_sides: np.ndarray  #: rod facets at y = 0, y = width, z = 0 (not the ends)
    rod_ends: np.ndarray  #: rod facets at x = 0 and x = length
    slider_bottom: np.ndarray  #: slider facets on its contact face
    slider_free: np.ndarray  #: the slider's other boundary facets


def rod_and_slider(
    layer: float,
    rod_layers: int,
    slider_layers: int,
    width: float,
    slider_height: float,
    n_cross: int = 2,
    n_height: int = 2,
    slider_start: int = 0,
) -> RodAndSlider:
    """A rod of ``rod_layers`` layers and a slider of ``slider_layers`` layers on its top."""
    if not 0 <= slider_start <= rod_layers - slider_layers:
        raise ValueError(
            f"a slider of {slider_layers} layers from layer {slider_start} does not fit on a rod of {rod_layers} layers"
        )
    y = np.linspace(0.0, width, n_cross + 1)
    rod = box(np.arange(rod_layers + 1) * layer, y, y)
    z_slider = width + np.linspace(0.0, slider_height, n_height + 1)
    slider = box((slider_start + np.arange(slider_layers + 1)) * layer, y, z_slider)
    mesh, (rod_elements, slider_elements) = join([rod, slider])
    tol = 1e-9 * width
    length = rod_layers * layer
    top = lambda m: np.abs(m[2] - width) < tol  # noqa: E731
    sides = lambda m: (np.abs(m[1]) < tol) | (np.abs(m[1] - width) < tol) | (np.abs(m[2]) < tol)  # noqa: E731
    ends = lambda m: (np.abs(m[0]) < tol) | (np.abs(m[0] - length) < tol)  # noqa: E731
    slider_bottom = part_facets(mesh, slider_elements, top)
    return RodAndSlider(
        mesh=mesh,
        layer=layer,
        rod_layers=rod_layers,
        slider_layers=slider_layers,
        rod_elements=rod_elements,
        slider_elements=slider_elements,
        rod_top=part_facets(mesh, rod_elements, top),
        rod_sides=part_facets(mesh, rod_elements, sides),
        rod_ends=part_facets(mesh, rod_elements, ends),
        slider_bottom=slider_bottom,
        slider_free=np.setdiff1d(part_facets(mesh, slider_elements), slider_bottom),
    )
