"""Volumes, face areas and point location of the parts' primitives (boxes, cylinders).

Parts are unions of non-overlapping primitives, with optional holes (bores) cut from their
boxes.  These measures feed the heat capacities and convective areas of the models and the
consistency checks; the FE model meshes the same primitives.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .schema import Box, Cylinder, Part
from .surfaces import Surface

_AXES = {"x": 0, "y": 1, "z": 2}
BOX_FACES = ("+x", "-x", "+y", "-y", "+z", "-z")


def box_volume(box: Box) -> float:
    sx, sy, sz = box.size
    return sx * sy * sz


def cylinder_volume(cyl: Cylinder) -> float:
    return math.pi / 4.0 * (cyl.outer_diameter**2 - cyl.inner_diameter**2) * cyl.length


def part_volume(part: Part) -> float:
    """Volume [m^3]: boxes and cylinders, less the holes (which lie inside the boxes)."""
    solid = sum(box_volume(b) for b in part.boxes) + sum(cylinder_volume(c) for c in part.cylinders)
    return solid - sum(cylinder_volume(h) for h in part.holes)


def _box_face_area(box: Box, face: str, holes: list[Cylinder]) -> float:
    sx, sy, sz = box.size
    axis = face[1]
    area = {"x": sy * sz, "y": sx * sz, "z": sx * sy}[axis]
    for hole in holes:  # a through-hole along this axis removes its cross-section
        if hole.axis == axis and _hole_in_box(hole, box):
            area -= math.pi / 4.0 * hole.outer_diameter**2
    return area


def _hole_in_box(hole: Cylinder, box: Box) -> bool:
    i = _AXES[hole.axis]
    centre = hole.origin
    lo, hi = box.origin, tuple(o + s for o, s in zip(box.origin, box.size))
    return all(lo[k] - 1e-9 <= centre[k] <= hi[k] + 1e-9 for k in range(3) if k != i)


def _cylinder_face_area(cyl: Cylinder, face: str) -> float:
    ring = math.pi / 4.0 * (cyl.outer_diameter**2 - cyl.inner_diameter**2)
    if face == "lateral":
        return math.pi * cyl.outer_diameter * cyl.length
    if face == "bore":
        return math.pi * cyl.inner_diameter * cyl.length
    if face == "ends":
        return 2.0 * ring
    if face in (f"+{cyl.axis}", f"-{cyl.axis}"):
        return ring
    raise ValueError(f"face {face!r} does not exist on a cylinder along {cyl.axis}")


def surface_area(surface: Surface, part: Part) -> float:
    """Area [m^2] of a surface: its explicit ``area``, else the sum over selected faces.

    Raises ValueError when a selected face does not exist on a selected primitive.
    """
    if surface.area is not None:
        return surface.area
    boxes = part.boxes if surface.boxes is None else [part.boxes[i] for i in surface.boxes]
    cylinders = part.cylinders if surface.cylinders is None else [part.cylinders[i] for i in surface.cylinders]
    total = 0.0
    for face in surface.faces:
        for box in boxes:
            if face in BOX_FACES:
                total += _box_face_area(box, face, part.holes)
            elif face == "bore":
                total += sum(math.pi * h.outer_diameter * h.length for h in part.holes if _hole_in_box(h, box))
            else:
                raise ValueError(f"face {face!r} does not exist on a box (use {', '.join(BOX_FACES)})")
        for cyl in cylinders:
            total += _cylinder_face_area(cyl, face)
    return total


def bounds(part: Part) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    """Axis-aligned bounding box ``(lower, upper)`` of a part [m]."""
    lows, highs = [], []
    for box in part.boxes:
        lows.append(box.origin)
        highs.append(tuple(o + s for o, s in zip(box.origin, box.size)))
    for cyl in part.cylinders:
        lo, hi = _cylinder_bounds(cyl)
        lows.append(lo)
        highs.append(hi)
    return (tuple(min(p[k] for p in lows) for k in range(3)), tuple(max(p[k] for p in highs) for k in range(3)))


def _cylinder_bounds(cyl: Cylinder):
    i = _AXES[cyl.axis]
    r = cyl.outer_diameter / 2.0
    lo = [c - r for c in cyl.origin]
    hi = [c + r for c in cyl.origin]
    lo[i], hi[i] = cyl.origin[i], cyl.origin[i] + cyl.length
    return tuple(lo), tuple(hi)


def contains(part: Part, point, tol: float = 1e-3) -> bool:
    """True when ``point`` lies in (or within ``tol`` of) the part's material: in one of its
    primitives and not in a hole's empty bore (:func:`hole_at`)."""
    if any(_in_cylinder(cyl, point, tol) for cyl in part.cylinders):
        return True
    return any(_in_box(box, point, tol) for box in part.boxes) and hole_at(part, point, tol) is None


def _in_box(box: Box, point, tol: float) -> bool:
    return all(box.origin[k] - tol <= point[k] <= box.origin[k] + box.size[k] + tol for k in range(3))


def _in_cylinder(cyl: Cylinder, point, tol: float) -> bool:
    i = _AXES[cyl.axis]
    radial = math.dist([point[k] for k in range(3) if k != i], [cyl.origin[k] for k in range(3) if k != i])
    along = point[i] - cyl.origin[i]
    inside_r = cyl.inner_diameter / 2.0 - tol <= radial <= cyl.outer_diameter / 2.0 + tol
    return -tol <= along <= cyl.length + tol and inside_r


def hole_at(part: Part, point, tol: float = 1e-3) -> int | None:
    """Index of the hole in whose empty bore ``point`` lies more than ``tol`` from the material
    around it (None where it lies in none, or in one of the part's cylinders).

    The bore's wall is material within ``tol``, and so is its bottom where the hole ends in a box
    (a blind hole's floor, where a thermocouple may sit); where the hole opens out of the part,
    its mouth is empty for ``tol`` beyond the face.
    """
    if any(_in_cylinder(cyl, point, tol) for cyl in part.cylinders):
        return None
    for j, hole in enumerate(part.holes):
        k = _AXES[hole.axis]
        radial = math.dist([point[m] for m in range(3) if m != k], [hole.origin[m] for m in range(3) if m != k])
        if radial >= hole.outer_diameter / 2.0 - tol:
            continue
        start, end = hole.origin[k], hole.origin[k] + hole.length
        low = start + tol if _floored(part, hole, start, -1.0) else start - tol
        high = end - tol if _floored(part, hole, end, 1.0) else end + tol
        if low < point[k] < high:
            return j
    return None


def _floored(part: Part, hole: Cylinder, level: float, outward: float) -> bool:
    """True when a box of the part closes the hole's end at ``level`` (its axis meets material
    just beyond it)."""
    k = _AXES[hole.axis]
    probe = list(hole.origin)
    probe[k] = level + outward * 1e-9
    return any(_in_box(box, probe, 0.0) for box in part.boxes) and not any(
        _in_hole(other, probe) for other in part.holes)


def _in_hole(hole: Cylinder, point) -> bool:
    k = _AXES[hole.axis]
    radial = math.dist([point[m] for m in range(3) if m != k], [hole.origin[m] for m in range(3) if m != k])
    return radial < hole.outer_diameter / 2.0 and hole.origin[k] <= point[k] <= hole.origin[k] + hole.length


def part_surface_area(part: Part) -> float:
    """An upper bound of the surface [m^2] of a part as drawn: every face of its boxes and
    cylinders whole and every hole's wall, counted primitive by primitive (the faces where its
    own primitives meet and the holes' mouths are counted too, a blind hole's floor is not: no
    larger than a mouth)."""
    boxes = sum(2.0 * (sx * sy + sy * sz + sx * sz) for sx, sy, sz in (box.size for box in part.boxes))
    walls = sum(math.pi * h.outer_diameter * h.length for h in part.holes)
    cylinders = sum(_cylinder_face_area(c, f) for c in part.cylinders for f in ("lateral", "bore", "ends"))
    return boxes + walls + cylinders


def nut_centre_x(system) -> float:
    """The nut's centre along x [m] at the middle of the stroke: where the table is."""
    lo, hi = bounds(system.parts[system.kinematics.nut])
    return 0.5 * (lo[0] + hi[0])


def table_travel(system) -> tuple[float, float]:
    """The table positions [m] the stroke reaches: the nut's centre along x, ends included."""
    centre = nut_centre_x(system)
    return centre - 0.5 * system.kinematics.stroke, centre + 0.5 * system.kinematics.stroke


def drive_point(system) -> tuple[float, float, float] | None:
    """Where the thread holds the nut to the screw along the axis [m]: on the screw's surface
    (its top), at the nut's centre along x (the moving group at the middle of the stroke); None
    when the nut does not sit on the screw there (a description without a thread), or without a
    feed drive."""
    if system.kinematics is None:
        return None
    screw = system.parts[system.kinematics.screw].cylinders[0]
    point = (nut_centre_x(system), screw.origin[1], screw.origin[2] + screw.outer_diameter / 2.0)
    if not contains(system.parts[system.kinematics.nut], point, tol=1e-6):
        return None
    return point


@dataclass(frozen=True)
class ScrewAxis:
    """The screw's extent along x [m] and its diameter [m]."""

    start: float
    end: float
    diameter: float


def screw_axis(part: Part) -> ScrewAxis:
    cyl = part.cylinders[0]
    return ScrewAxis(cyl.origin[0], cyl.origin[0] + cyl.length, cyl.outer_diameter)
