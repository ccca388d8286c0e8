"""Nodes of the fast model: axially resolved bodies and the other parts' sub-volumes.

* The screw is cut into axial cells (at least ``axial_cells``) and, in each cell, into
  ``radial_rings`` concentric rings of equal thickness, because the nut's contact
  conductance (~6000 W/(m² K)) makes the screw's Biot number under the nut about 2.
* Every other fixed part that a moving part slides on (the guideways) is cut into axial
  cells (one ring), so the moving contact has a place to be.
* Every other part is cut into cells of about ``cell_size`` along its primitives
  (:mod:`.cells`): heat enters such parts at small patches (a motor's flange, a bearing
  seat, a housing's top) and spreads over them, so one node per part misses both the
  spreading resistance and the local temperature a sensor reads.

The cell size divides the stroke exactly, so that the moving group's positions fall on the
cell grid and each position's system matrix can be factorised once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...system.geometry import BOX_FACES, bounds, part_volume
from ...system.schema import Cylinder, FeedSystem, Part
from .cells import PartCells, part_cells

CONTACT_TOLERANCE = 1e-3  # [m] primitives closer than this touch
END_CONTACT = 1e-6  # [m] axial extent given to an end-to-end contact (it lands in the end cell)


@dataclass
class AxialBody:
    """A fixed part resolved along x: cells (edges) × rings, with global node indices."""

    part: str
    edges: np.ndarray  # (m+1,) cell edges along x [m]
    ring_radii: np.ndarray  # (n_rings+1,) ring edges [m] for a cylinder; [0, r_eq] otherwise
    cross_section: float  # [m^2]
    nodes: np.ndarray  # (m, n_rings) global indices; last ring is the outer surface
    cylindrical: bool

    @property
    def centres(self) -> np.ndarray:
        return 0.5 * (self.edges[1:] + self.edges[:-1])

    @property
    def lengths(self) -> np.ndarray:
        return np.diff(self.edges)

    @property
    def n_rings(self) -> int:
        return self.nodes.shape[1]

    def ring_areas(self) -> np.ndarray:
        r = self.ring_radii
        if not self.cylindrical:
            return np.array([self.cross_section])
        return math.pi * (r[1:] ** 2 - r[:-1] ** 2)

    def overlap(self, x0: float, x1: float) -> np.ndarray:
        """Length [m] of each cell inside [x0, x1]."""
        lo = np.maximum(self.edges[:-1], x0)
        hi = np.minimum(self.edges[1:], x1)
        return np.clip(hi - lo, 0.0, None)

    def cell_at(self, x: float) -> int:
        return int(np.clip(np.searchsorted(self.edges, x, side="right") - 1, 0, len(self.edges) - 2))


@dataclass
class Layout:
    system: FeedSystem
    bodies: dict[str, AxialBody]
    cells: dict[str, PartCells]  # the other parts, cut into sub-volumes
    capacity: np.ndarray  # [J/K] per node
    n_nodes: int
    dx: float  # axial cell size of the screw [m]
    positions: np.ndarray  # offsets [m] of the moving group at grid positions k = 0..K
    cell_size: float = 0.0  # [m] target size of the sub-volumes

    @property
    def screw(self) -> AxialBody | None:
        """The screw's body; None for a system without a feed drive."""
        kin = self.system.kinematics
        return None if kin is None else self.bodies[kin.screw]

    def part_nodes(self, part: str) -> np.ndarray:
        if part in self.cells:
            return self.cells[part].nodes
        return self.bodies[part].nodes.ravel()

    def part_capacity(self, part: str) -> np.ndarray:
        return self.capacity[self.part_nodes(part)]


def axial_parts(system: FeedSystem) -> list[str]:
    """The screw, then every fixed part that a sliding joint connects to a moving part."""
    names = [] if system.kinematics is None else [system.kinematics.screw]
    for joint in system.joints:
        if joint.sliding:
            for name in joint.between:
                if not system.parts[name].moving and name not in names:
                    names.append(name)
    return names


def build_layout(system: FeedSystem, *, axial_cells: int = 100, radial_rings: int = 2,
                 min_positions: int = 20, cell_size: float = 0.04) -> Layout:
    """Node layout: axial bodies on a grid whose cell size divides the stroke, then the
    other parts' sub-volumes of about ``cell_size`` [m].  Without a feed drive nothing moves:
    one position, no axial body."""
    if system.kinematics is None:
        positions_count, dx, stroke = 0, cell_size, 0.0
    else:
        lo, hi = bounds(system.parts[system.kinematics.screw])
        length = hi[0] - lo[0]
        stroke = system.kinematics.stroke
        positions_count = max(min_positions, math.ceil(stroke / (length / axial_cells)))
        dx = stroke / positions_count
    capacity: list[float] = []
    bodies: dict[str, AxialBody] = {}
    next_node = 0
    for name in axial_parts(system):
        part = system.parts[name]
        material = system.materials[part.material]
        rings = radial_rings if system.kinematics is not None and name == system.kinematics.screw else 1
        body = _axial_body(name, part, dx, rings, next_node)
        bodies[name] = body
        next_node += body.nodes.size
        volumes = np.outer(body.lengths, body.ring_areas())
        capacity.extend((material.density * material.specific_heat * volumes).ravel())
    cells: dict[str, PartCells] = {}
    for name, part in system.parts.items():
        if name in bodies:
            continue
        material = system.materials[part.material]
        cells[name] = part_cells(name, part, material.conductivity, cell_size, next_node, feature_breaks(system, name))
        next_node += cells[name].nodes.size
        capacity.extend(material.density * material.specific_heat * cells[name].volumes)
    offsets = -stroke / 2.0 + dx * np.arange(positions_count + 1)
    return Layout(system, bodies, cells, np.array(capacity), next_node, dx, offsets, cell_size)


def feature_breaks(system: FeedSystem, name: str) -> list:
    """Coordinates each primitive's grid of cells should pass through: the faces of the
    primitives it touches (of its own part, or of a part joined to it), so that a footprint,
    a fused face or a seat falls on whole cells. A primitive sliding past (a moving part on a
    fixed one) gives only its position across the motion (y, z)."""
    part = system.parts[name]
    partners = [(name, True)]
    for joint in system.joints:
        if name in joint.between:
            other = joint.between[1] if joint.between[0] == name else joint.between[0]
            partners.append((other, system.parts[other].moving == part.moving))
    out = []
    for prim in [*part.boxes, *part.cylinders]:
        lo, hi = primitive_bounds(prim)
        axes = range(3) if not isinstance(prim, Cylinder) else ["xyz".index(prim.axis)]
        found = {a: [] for a in axes}
        for other, same_frame in partners:
            for q in [*system.parts[other].boxes, *system.parts[other].cylinders]:
                if q is prim:
                    continue
                qlo, qhi = primitive_bounds(q)
                if any(max(qlo[a] - hi[a], lo[a] - qhi[a]) > CONTACT_TOLERANCE for a in range(3)):
                    continue  # apart
                for a in axes:
                    if a == 0 and not same_frame:
                        continue
                    found[a].extend([qlo[a], qhi[a]])
        out.append([found[a] for a in range(3)] if not isinstance(prim, Cylinder) else found[axes[0]])
    return out


def _axial_body(name: str, part: Part, dx: float, rings: int, first_node: int) -> AxialBody:
    lo, hi = bounds(part)
    n = max(1, int(round((hi[0] - lo[0]) / dx)))
    edges = lo[0] + dx * np.arange(n + 1)
    edges[-1] = hi[0]  # the last cell absorbs the remainder (within half a cell)
    cylindrical = len(part.cylinders) == 1 and not part.boxes and part.cylinders[0].axis == "x"
    if cylindrical:
        cyl = part.cylinders[0]
        r_in, r_out = cyl.inner_diameter / 2.0, cyl.outer_diameter / 2.0
        radii = np.linspace(r_in, r_out, rings + 1)
        area = math.pi * (r_out**2 - r_in**2)
    else:
        area = part_volume(part) / (hi[0] - lo[0])
        radii = np.array([0.0, math.sqrt(area / math.pi)])
        rings = 1
    nodes = first_node + np.arange(n * rings).reshape(n, rings)
    return AxialBody(name, edges, radii, area, nodes, cylindrical)


def contact_ranges(system: FeedSystem, part: str, body: AxialBody, offset: float = 0.0) -> list[tuple[float, float]]:
    """x-ranges [m] where ``part`` (shifted by ``offset``) touches the axial ``body``.

    A cylinder coaxial with a cylindrical body touches it only when its bore sits on the
    body's surface (a nut sleeve does, its flange does not); other primitives touch when
    their bounding boxes meet.
    """
    target = system.parts[body.part]
    t_lo, t_hi = bounds(target)
    ranges = []
    p = system.parts[part]
    for prim in [*p.boxes, *p.cylinders]:
        lo, hi = primitive_bounds(prim)
        x0, x1 = lo[0] + offset, hi[0] + offset
        if any(max(lo[k] - t_hi[k], t_lo[k] - hi[k]) > CONTACT_TOLERANCE for k in (1, 2)):
            continue  # apart across the axis
        if x1 < t_lo[0] - CONTACT_TOLERANCE or x0 > t_hi[0] + CONTACT_TOLERANCE:
            continue  # apart along the axis
        if isinstance(prim, Cylinder) and body.cylindrical and prim.axis == "x" and _coaxial(prim, target.cylinders[0]):
            if prim.inner_diameter > target.cylinders[0].outer_diameter + 2 * CONTACT_TOLERANCE:
                continue  # a coaxial ring clear of the surface (e.g. a nut flange)
        if x1 <= t_lo[0] + CONTACT_TOLERANCE:  # end to end: contact on the body's first face
            ranges.append((t_lo[0], t_lo[0] + END_CONTACT))
        elif x0 >= t_hi[0] - CONTACT_TOLERANCE:  # on its last face
            ranges.append((t_hi[0] - END_CONTACT, t_hi[0]))
        else:
            ranges.append((x0, x1))
    return ranges


def _coaxial(a: Cylinder, b: Cylinder) -> bool:
    return abs(a.origin[1] - b.origin[1]) < CONTACT_TOLERANCE and abs(a.origin[2] - b.origin[2]) < CONTACT_TOLERANCE


def primitive_bounds(prim):
    """The axis-aligned bounds ``(lower, upper)`` [m] of a box or a cylinder, as lists."""
    if isinstance(prim, Cylinder):
        i = "xyz".index(prim.axis)
        r = prim.outer_diameter / 2.0
        lo = [c - r for c in prim.origin]
        hi = [c + r for c in prim.origin]
        lo[i], hi[i] = prim.origin[i], prim.origin[i] + prim.length
        return lo, hi
    return list(prim.origin), [o + s for o, s in zip(prim.origin, prim.size)]


__all__ = ["AxialBody", "Layout", "build_layout", "contact_ranges", "axial_parts", "BOX_FACES"]
