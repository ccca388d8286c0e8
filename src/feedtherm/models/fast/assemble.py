"""Conductance matrix, ambient links and heat vector of the fast model at one position.

The network is a graph: nodes (axial cells × rings of the screw and the rails, sub-volume
cells of every other part) joined by conductances [W/K]; some nodes also link to the ambient
air.  What depends on the moving group's position ``k`` — the sliding contacts, the part of
the screw the nut covers, the moving heat — is rebuilt per position; everything else is
built once.
"""

from __future__ import annotations

import hashlib
import json
import math
from collections import OrderedDict
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ...errors import ModelError
from ...system.geometry import surface_area
from .contacts import JointContact, fused_links, side, surface_samples
from .layout import AxialBody, Layout, contact_ranges, primitive_bounds

#: Faces normal to an axial body's axis: they sit at its ends, not along it.
END_FACES = ("-x", "+x", "ends")


def primitive_x_range(primitive) -> tuple[float, float]:
    """The x-extent [m] of a box or a cylinder."""
    lo, hi = primitive_bounds(primitive)
    return lo[0], hi[0]


@dataclass
class Edges:
    """Conductances between node pairs, and from nodes to the ambient."""

    a: list = field(default_factory=list)
    b: list = field(default_factory=list)
    g: list = field(default_factory=list)

    def add(self, a, b, g) -> None:
        self.a.extend(np.atleast_1d(a).tolist())
        self.b.extend(np.atleast_1d(b).tolist())
        self.g.extend(np.broadcast_to(np.atleast_1d(g), np.atleast_1d(a).shape).tolist())


#: The position-dependent geometry (where the contacts are, which faces are exposed) of the last
#: few descriptions, by the digest of what decides it.  Calibration, sweeps and sensitivity
#: studies rebuild the model for values that move no face (a contact resistance, a heat, a CHTC):
#: they find their contacts here instead of sampling the faces again.
_GEOMETRY: OrderedDict[str, dict] = OrderedDict()
_GEOMETRY_ENTRIES = 4
#: What a surface, a joint or a material has that does not decide what is kept here.  A joint's
#: resistance and area enter its links when they are formed (:meth:`JointContact.links`); a
#: material's capacity, expansion and stiffness enter the layout and the bars, built afresh with
#: each model; its conductivity divides the distances kept here when a model forms its links,
#: and keys the sums and film resistances kept under it.
_NOT_GEOMETRY = {"surfaces": ("convection", "emissivity", "chtc_factor", "sink_temperature", "description"),
                 "joints": ("tcr", "area", "description"),
                 "materials": ("density", "conductivity", "specific_heat", "expansion", "youngs_modulus",
                               "poisson_ratio", "name")}


def geometry_digest(layout: Layout) -> str:
    """sha256 of everything the contacts and exposed areas depend on: parts, materials, joints
    and surfaces without their thermal values, kinematics, and the layout's cells and positions."""
    data = layout.system.model_dump(mode="json", include={"parts", "materials", "joints", "surfaces", "kinematics"})
    for key, fields in _NOT_GEOMETRY.items():
        items = data[key].values() if isinstance(data[key], dict) else data[key]
        for item in items:
            for name in fields:
                item.pop(name, None)
    data["layout"] = {"n_nodes": layout.n_nodes, "positions": np.asarray(layout.positions).tolist(),
                      "cell_size": layout.cell_size}
    return hashlib.sha256(json.dumps(data, sort_keys=True).encode()).hexdigest()


def _geometry_cache(layout: Layout) -> dict:
    digest = geometry_digest(layout)
    if digest in _GEOMETRY:
        _GEOMETRY.move_to_end(digest)
    else:
        _GEOMETRY[digest] = {"sides": {}, "contacts": {}, "surfaces": {}, "bases": {}, "films": {}}
        while len(_GEOMETRY) > _GEOMETRY_ENTRIES:
            _GEOMETRY.popitem(last=False)
    return _GEOMETRY[digest]


def laplacian(n: int, edges: Edges) -> sp.csr_matrix:
    """Symmetric conductance matrix of the edge list (row sums zero)."""
    a, b, g = np.asarray(edges.a, int), np.asarray(edges.b, int), np.asarray(edges.g, float)
    rows = np.concatenate([a, b, a, b])
    cols = np.concatenate([a, b, b, a])
    vals = np.concatenate([g, g, -g, -g])
    return sp.csr_matrix((vals, (rows, cols)), shape=(n, n))


class Network:
    """Builds the position-dependent parts of the fast model's equations."""

    def __init__(self, layout: Layout):
        self.layout = layout
        self.system = layout.system
        self._check_joints()
        cache = _geometry_cache(layout)
        #: this geometry's cache, shared with every model built on the same geometry
        self.geometry = cache
        sides = cache["sides"]
        for name, cells in layout.cells.items():
            if name not in sides:
                sides[name] = side(cells, layout.cell_size)
        self.sides = {name: sides[name] for name in layout.cells}
        conductivity = {name: self._material(name).conductivity for name in self.system.parts}
        surface_length = {name: self._surface_resistance_length(body) for name, body in layout.bodies.items()}
        self.contacts = [JointContact(layout, joint, self.sides, conductivity, surface_length,
                                      cache["contacts"].setdefault(i, {}))
                         for i, joint in enumerate(self.system.joints)]
        fixed = Edges()
        for body in layout.bodies.values():
            self._body_conduction(body, fixed)
        for name, cells in layout.cells.items():
            k = conductivity[name]
            for grid, first in zip(cells.grids, cells.first):
                a, b, g = grid.links
                fixed.add(first + a, first + b, k * g)
            fixed.add(*fused_links(self.sides[name], k))
        for contact in self.contacts:
            if not contact.joint.sliding:
                fixed.add(*contact.links(0))
        self.fixed = laplacian(layout.n_nodes, fixed)
        self._surface_cache: dict[tuple[str, int], tuple[np.ndarray, np.ndarray]] = cache["surfaces"]
        # a film resistance goes with its part's conductivity: kept under both
        self._film_cache: dict[tuple[str, float], float] = cache["films"]

    # ------------------------------------------------------------------ structure
    def _check_joints(self) -> None:
        parts = self.system.parts
        bodies = self.layout.bodies
        for i, joint in enumerate(self.system.joints):
            a, b = joint.between
            moving = [parts[a].moving, parts[b].moving]
            if joint.sliding and moving.count(True) != 1:
                raise ModelError(f"joints[{i}]: a sliding joint needs one moving and one fixed part ({a}, {b})")
            if joint.sliding and not any(p in bodies for p in (a, b)):
                raise ModelError(f"joints[{i}]: the fixed side of a sliding joint must be resolved along x")
            if not joint.sliding and moving.count(True) == 1:
                raise ModelError(f"joints[{i}]: {a} and {b}: a joint between a moving and a fixed part must be sliding")
            if a in bodies and b in bodies:
                raise ModelError(f"joint {a}-{b}: two axially resolved parts cannot be joined")

    def _material(self, part: str):
        return self.system.materials[self.system.parts[part].material]

    def _body_conduction(self, body: AxialBody, edges: Edges) -> None:
        k = self._material(body.part).conductivity
        areas = body.ring_areas()
        centres = body.centres
        for j in range(body.n_rings):
            g = k * areas[j] / np.diff(centres)
            edges.add(body.nodes[:-1, j], body.nodes[1:, j], g)
        if body.cylindrical:
            r = body.ring_radii
            rc = 0.5 * (r[1:] + r[:-1])
            for j in range(body.n_rings - 1):
                g = 2 * math.pi * k * body.lengths / math.log(rc[j + 1] / rc[j])
                edges.add(body.nodes[:, j], body.nodes[:, j + 1], g)

    @staticmethod
    def _surface_resistance_length(body: AxialBody) -> float:
        """Conduction length [m] from a non-cylindrical body's node to its surface (area / perimeter)."""
        return body.cross_section / (2.0 * (math.sqrt(body.cross_section) * 2))

    def contact_weights(self, part: str, body: AxialBody, offset: float) -> np.ndarray:
        """Share of a contact per cell of ``body`` (sums to 1) where ``part`` touches it."""
        overlap = np.zeros(len(body.centres))
        for x0, x1 in contact_ranges(self.system, part, body, offset):
            overlap += body.overlap(x0, x1)
        total = overlap.sum()
        if total <= 0.0:
            raise ModelError(f"{part} does not touch {body.part} at offset {offset * 1e3:.1f} mm")
        return overlap / total

    def _contact(self, a: str, b: str) -> JointContact | None:
        return next((c for c in self.contacts if set(c.joint.between) == {a, b}), None)

    # ------------------------------------------------------------------ per position
    def sliding(self, k: int) -> sp.csr_matrix:
        """Conductance matrix of the sliding contacts with the moving group at position ``k``."""
        return self.averaged_sliding({k: 1.0})

    def averaged_sliding(self, weights: dict[int, float]) -> sp.csr_matrix:
        """``Σ_k w_k`` :meth:`sliding` ``(k)`` as one matrix of the positions' links weighted (a
        cycle average assembled once, where summing the positions' matrices assembles each)."""
        edges = Edges()
        for k, w in weights.items():
            for contact in self.contacts:
                if contact.joint.sliding:
                    a, b, g = contact.links(k)
                    edges.add(a, b, w * g)
        return laplacian(self.layout.n_nodes, edges)

    def surface_exposure(self, name: str, k: int) -> tuple[np.ndarray, np.ndarray]:
        """The nodes of surface ``name`` and their exposed areas [m²] at position ``k``."""
        if self.system.surfaces[name].part in self.layout.cells:
            return self._cell_surface(name, k)
        return self._body_surface(name, k, self.layout.positions[k])

    def _body_surface(self, name: str, k: int, offset: float) -> tuple[np.ndarray, np.ndarray]:
        """Exposed area [m²] per node of a surface on the screw or a rail.

        The faces along the body (a cylinder's ``lateral``, a rail's ``±y``, ``±z``) by cell
        length on the outer ring, less what the parts seated on the body cover: on the screw's
        lateral face the bearings and the nut (by their length), on a rail's faces the contacts
        of the parts joined to it (the carriages).  An end face (``-x``, ``+x``, a cylinder's
        ``ends``) is on the cell at its end, over the rings by their areas.  A declared ``area``
        is spread over the exposed nodes the same way.
        """
        surface = self.system.surfaces[name]
        body = self.layout.bodies[surface.part]
        nodes, values, _ = self._body_patches(surface, body, self._body_along(surface, body, k, offset))
        nodes, areas = np.concatenate(nodes), np.concatenate(values)
        if surface.area is not None and areas.sum() > 0.0:
            areas = areas * surface.area / areas.sum()
        return nodes, areas

    def _body_along(self, surface, body: AxialBody, k: int, offset: float) -> np.ndarray:
        """Exposed area [m²] per cell of the surface's faces along the body at position k."""
        along = [face for face in surface.faces if face not in END_FACES]
        along_area = surface_area(surface.model_copy(update={"area": None, "faces": along}),
                                  self.system.parts[surface.part]) if along else 0.0
        areas = along_area * body.lengths / body.lengths.sum()
        if body.cylindrical:
            if "lateral" in surface.faces:
                areas = areas * np.clip(1.0 - self._covered(body, offset) / body.lengths, 0.0, 1.0)
        else:
            for contact in self.contacts:
                if body.part in contact.joint.between:
                    cells, covered = contact.covered_faces(k, set(along))
                    np.subtract.at(areas, cells, covered)
            areas = np.clip(areas, 0.0, None)
        return areas

    def _body_patches(self, surface, body: AxialBody, along: np.ndarray):
        """The surface's nodes, exposed areas [m²] and specific resistances [m²·K/W] from each
        node to its face, in patches: the faces along the body on the outer ring (``along`` per
        cell), then each end face on its end cell over the rings."""
        k = self._material(body.part).conductivity
        if body.cylindrical:
            radius = body.ring_radii[-1]
            centre = 0.5 * (body.ring_radii[-1] + body.ring_radii[-2])
            r_along = radius * math.log(radius / centre) / k
        else:
            r_along = self._surface_resistance_length(body) / k
        nodes, values, resistances = [body.nodes[:, -1]], [along], [np.full(len(along), r_along)]
        for x, area in self._end_faces(surface, body):
            cell = body.cell_at(x)
            nodes.append(body.nodes[cell])
            values.append(area * body.ring_areas() / body.ring_areas().sum())
            resistances.append(np.full(body.n_rings, 0.5 * body.lengths[cell] / k))
        return nodes, values, resistances

    def _end_faces(self, surface, body: AxialBody) -> list[tuple[float, float]]:
        """``(x [m], area [m²])`` of each selected end face of the body's primitives, x a little
        inside the primitive (so that its cell is the primitive's own end cell)."""
        part = self.system.parts[surface.part]
        primitives = [*(part.boxes if surface.boxes is None else [part.boxes[i] for i in surface.boxes]),
                      *(part.cylinders if surface.cylinders is None else [part.cylinders[i] for i in surface.cylinders])]
        out = []
        for face in surface.faces:
            if face not in END_FACES:
                continue
            for primitive in primitives:
                lo, hi = primitive_x_range(primitive)
                inset = 1e-6 * (hi - lo)
                one = surface.model_copy(update={"area": None, "faces": ["-x" if face == "ends" else face],
                                                 "boxes": None, "cylinders": None})
                alone = part.model_copy(update={"boxes": [primitive] if primitive in part.boxes else [],
                                                "cylinders": [primitive] if primitive in part.cylinders else []})
                try:
                    area = surface_area(one, alone)
                except ValueError:
                    continue  # a face of another axis's cylinder: not an end face of this body
                if face in ("-x", "ends"):
                    out.append((lo + inset, area))
                if face in ("+x", "ends"):
                    out.append((hi - inset, area))
        return out

    def _cell_surface(self, name: str, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Exposed area [m²] per cell of a surface on a part cut into cells.

        The selected faces less what is fused to another primitive of the part and what a
        joined part covers; a declared ``area`` is spread over the exposed faces the same way.
        """
        surface = self.system.surfaces[name]
        part = surface.part
        partners = [c for c in self.contacts if part in c.joint.between]
        moves = any(self.system.parts[p].moving != self.system.parts[part].moving
                    for c in partners for p in c.joint.between)
        key = (name, k if moves else 0)
        if key not in self._surface_cache:
            sd = self.sides[part]
            weights = self._cell_samples(name, k)
            areas = np.bincount(sd.nodes, weights=weights, minlength=self.layout.n_nodes)
            if surface.area is not None:
                areas *= surface.area / areas.sum()
            nodes = np.nonzero(areas)[0]
            self._surface_cache[key] = (nodes, areas[nodes])
        return self._surface_cache[key]

    def _cell_samples(self, name: str, k: int) -> np.ndarray:
        """Exposed area [m²] of each face sample of surface ``name``'s part at position k (0 off
        the surface); with a declared ``area`` and nothing exposed, the selected faces' areas."""
        surface = self.system.surfaces[name]
        part = surface.part
        sd = self.sides[part]
        selected = surface_samples(sd, surface)
        exposed = selected & sd.free
        outside = sd.samples.outside()
        for contact in (c for c in self.contacts if part in c.joint.between):
            idx = np.nonzero(exposed)[0]
            exposed[idx[contact.covers(part, outside[idx], k)]] = False
        if surface.area is not None and not (sd.samples.areas * exposed).sum() > 0.0:
            return sd.samples.areas * selected  # nothing exposed: the declared area over the faces
        return sd.samples.areas * exposed

    def film_resistance(self, name: str) -> float:
        """Specific resistance [m²·K/W] of conduction from the nodes of surface ``name`` to its
        faces, the exposed-area mean at position 0.

        A node stands for its cell's centre, half a cell (``d``) from the face the film is on:
        ``d/k`` of a box's cell (from :func:`.contacts.side`), ``R ln(R/r_c)/k`` from an axial
        body's outer ring at ``r_c`` to its lateral face at ``R``, half the end cell's length
        over ``k`` to an end face.  :func:`~feedtherm.models.interface.film_coefficient` puts it
        in series with the surface's coefficient.
        """
        key = (name, self._material(self.system.surfaces[name].part).conductivity)
        if key not in self._film_cache:
            self._film_cache[key] = self._film_resistance(name)
        return self._film_cache[key]

    def _film_resistance(self, name: str) -> float:
        surface = self.system.surfaces[name]
        if surface.part in self.layout.cells:
            weights = self._cell_samples(name, 0)
            total = weights.sum()
            # numpy's own sum, not a BLAS dot product: the same digits whatever the threads (a study's
            # workers run single-threaded, its serial run may not)
            resistance = self.sides[surface.part].distance / self._material(surface.part).conductivity
            return float(np.sum(weights * resistance) / total) if total > 0.0 else 0.0
        body = self.layout.bodies[surface.part]
        _, areas, resistances = self._body_patches(surface, body, self._body_along(surface, body, 0,
                                                                                   self.layout.positions[0]))
        areas, resistances = np.concatenate(areas), np.concatenate(resistances)
        return float(np.sum(areas * resistances) / areas.sum()) if areas.sum() > 0.0 else 0.0

    def _covered(self, body: AxialBody, offset: float) -> np.ndarray:
        """Length of each cell covered by parts seated on the body's surface (bearings, nut)."""
        covered = np.zeros(len(body.centres))
        for joint in self.system.joints:
            if body.part not in joint.between:
                continue
            other = joint.between[1] if joint.between[0] == body.part else joint.between[0]
            part_offset = offset if self.system.parts[other].moving else 0.0
            for x0, x1 in contact_ranges(self.system, other, body, part_offset):
                covered += body.overlap(x0, x1)
        return np.minimum(covered, body.lengths)

    def heat_distribution(self, part: str, partner: str | None, k: int) -> np.ndarray:
        """Fractions (summing to 1) over the nodes of heat into ``part`` at position ``k``.

        Heat of the part itself goes in by volume; heat that arises at the contact with
        ``partner`` (the screw–nut friction) enters where that contact is: the screw under
        the nut, the nut's bore.
        """
        q = np.zeros(self.layout.n_nodes)
        if part in self.layout.cells:
            if partner is not None:
                nodes, weights = self._contact(part, partner).share(part, k)
                np.add.at(q, nodes, weights)
            else:
                cells = self.layout.cells[part]
                q[cells.nodes] += cells.volumes / cells.volumes.sum()
            return q
        body = self.layout.bodies[part]
        if partner is not None:
            offset = self.layout.positions[k] if self.system.parts[partner].moving else 0.0
            q[body.nodes[:, -1]] += self.contact_weights(partner, body, offset)
        else:
            volumes = np.outer(body.lengths, body.ring_areas()).ravel()
            q[body.nodes.ravel()] += volumes / volumes.sum()
        return q
