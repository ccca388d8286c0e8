"""Which boundary facets of a part make up a declared surface.

A surface of the description selects faces of a part's primitives (see
:func:`feedtherm.system.geometry.surface_area`): ``+x`` … ``-z`` of its boxes, ``bore`` of
the holes in its boxes, and ``lateral``, ``bore``, ``ends``, ``+x``/``-x`` (the ends at the
larger/smaller coordinate along the cylinder's axis) of its cylinders. A facet belongs to
a face when its three vertices lie on it (gmsh puts the vertices of a curved face on the
exact cylinder), its centroid lies within the face's extent, and its outward normal points
the face's way. The centroid, not every vertex, decides the extent: where two primitives of
a part meet in one plane (two boxes' tops), gmsh triangulates the fused face across their
common edge, and a facet straddling it belongs to the one that holds its centroid. Parts of
a primitive's face that are fused to another primitive, or cut away, have no boundary
facets: the mesh gives the true exposed area, where ``surface_area`` adds up whole faces.
"""

from __future__ import annotations

import numpy as np

from ...errors import ModelError
from ...system.geometry import BOX_FACES
from ...system.schema import Box, Cylinder, Part
from ...system.surfaces import Surface
from .facets import Triangles

__all__ = ["surface_facets", "curvature_sag"]

ON_FACE = 1e-6  # [m] a vertex this close to a face lies on it
_AXES = {"x": 0, "y": 1, "z": 2}


def surface_facets(surface: Surface, part: Part, points: np.ndarray, triangles: Triangles, path: str = "") -> np.ndarray:
    """Boolean mask over ``triangles`` (the part's boundary facets) of ``surface``'s facets."""
    boxes = part.boxes if surface.boxes is None else [part.boxes[i] for i in surface.boxes]
    cylinders = part.cylinders if surface.cylinders is None else [part.cylinders[i] for i in surface.cylinders]
    corners = triangles.corners(points)  # (3, 3, n)
    mask = np.zeros(triangles.size, dtype=bool)
    for face in surface.faces:
        for box in boxes:
            if face in BOX_FACES:
                mask |= _box_face(box, face, corners, triangles.normals)
            elif face == "bore":
                for hole in part.holes:
                    if _hole_in_box(hole, box):
                        mask |= _cylinder_face(hole, "hole", corners, triangles.normals)
            else:
                raise ModelError(f"{path or 'surface'}: face {face!r} does not exist on a box")
        for cyl in cylinders:
            mask |= _cylinder_face(cyl, face, corners, triangles.normals, path)
    return mask


def _box_face(box: Box, face: str, corners: np.ndarray, normals: np.ndarray) -> np.ndarray:
    i = _AXES[face[1]]
    sign = 1.0 if face[0] == "+" else -1.0
    lo = np.array(box.origin)
    hi = lo + np.array(box.size)
    plane = hi[i] if sign > 0 else lo[i]
    ok = (np.abs(corners[:, i] - plane) < ON_FACE).all(axis=0)
    centroid = corners.mean(axis=0)  # (3, n)
    for k in range(3):
        if k != i:
            ok &= (centroid[k] >= lo[k] - ON_FACE) & (centroid[k] <= hi[k] + ON_FACE)
    return ok & (sign * normals[i] > 0.9)


def _radial(cyl: Cylinder, corners: np.ndarray):
    """Axial coordinate from the cylinder's origin, radius, and the radial unit vectors."""
    i = _AXES[cyl.axis]
    o = np.array(cyl.origin)[None, :, None]
    d = corners - o  # (3, 3, n)
    along = d[:, i]
    radial = d.copy()
    radial[:, i] = 0.0
    r = np.linalg.norm(radial, axis=1)
    return i, along, r, radial


def _cylinder_face(cyl: Cylinder, face: str, corners: np.ndarray, normals: np.ndarray, path: str = "") -> np.ndarray:
    i, along, r, radial = _radial(cyl, corners)
    middle = along.mean(axis=0)  # the centroid's axial coordinate decides, as for boxes
    within = (middle >= -ON_FACE) & (middle <= cyl.length + ON_FACE)
    centre_dir = radial.mean(axis=0)
    centre_dir /= np.maximum(np.linalg.norm(centre_dir, axis=0), 1e-30)
    outward = np.einsum("ij,ij->j", centre_dir, normals)
    r_out, r_in = cyl.outer_diameter / 2.0, cyl.inner_diameter / 2.0
    if face == "lateral":
        return within & (np.abs(r - r_out) < ON_FACE).all(axis=0) & (outward > 0.5)
    if face == "bore":
        if r_in <= 0.0:
            return np.zeros(normals.shape[1], dtype=bool)
        return within & (np.abs(r - r_in) < ON_FACE).all(axis=0) & (outward < -0.5)
    if face == "hole":  # a hole's wall: the part's material is outside the cylinder
        return within & (np.abs(r - r_out) < ON_FACE).all(axis=0) & (outward < -0.5)
    ends = {"ends": (-1.0, 1.0), f"+{cyl.axis}": (1.0,), f"-{cyl.axis}": (-1.0,)}
    if face not in ends:
        raise ModelError(f"{path or 'surface'}: face {face!r} does not exist on a cylinder along {cyl.axis}")
    annulus = ((r >= r_in - ON_FACE) & (r <= r_out + ON_FACE)).all(axis=0)
    mask = np.zeros(normals.shape[1], dtype=bool)
    for sign in ends[face]:
        plane = cyl.length if sign > 0 else 0.0
        mask |= annulus & (np.abs(along - plane) < ON_FACE).all(axis=0) & (sign * normals[i] > 0.9)
    return mask


def _hole_in_box(hole: Cylinder, box: Box) -> bool:
    i = _AXES[hole.axis]
    lo, hi = box.origin, tuple(o + s for o, s in zip(box.origin, box.size))
    return all(lo[k] - 1e-9 <= hole.origin[k] <= hi[k] + 1e-9 for k in range(3) if k != i)


def curvature_sag(part: Part, points: np.ndarray, triangles: Triangles) -> float:
    """Largest chord height [m] of the part's facets on curved faces: ``L²/(8R)``.

    A facet on a cylinder lies inside it by up to this much; two meshes of one curved contact
    face can therefore be up to the sum of their sags apart.
    """
    corners = triangles.corners(points)
    edges = np.linalg.norm(corners - corners[[1, 2, 0]], axis=1).max(axis=0)  # (n,)
    sag = 0.0
    for cyl in [*part.cylinders, *part.holes]:
        _, _, r, _ = _radial(cyl, corners)
        for radius in (cyl.outer_diameter / 2.0, cyl.inner_diameter / 2.0):
            if radius <= 0.0:
                continue
            on = (np.abs(r - radius) < ON_FACE).all(axis=0)
            if on.any():
                sag = max(sag, float((edges[on] ** 2).max() / (8.0 * radius)))
    return sag
