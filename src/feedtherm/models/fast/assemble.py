"""Conductance matrix, ambient links and heat vector of the fast model at one position.

The network is a graph: nodes (axial cells × rings, lumped parts) joined by conductances
[W/K]; some nodes also link to the ambient air.  What depends on the moving group's position
``k`` — the sliding contacts, the part of the screw the nut covers, the moving heat — is
rebuilt per position; everything else is built once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ...boundary import BoundaryConditions
from ...errors import ModelError
from ...system.schema import Joint
from .layout import AxialBody, Layout, contact_ranges


@dataclass(frozen=True)
class SolverTamper:
    """Deliberate errors injected into the solver only, to prove the energy check works.

    Never used outside tests: ``drop_sources`` removes heat sources from the solver's heat
    vector, ``area_scale`` multiplies surfaces' convective areas in the solver.
    """

    drop_sources: tuple[str, ...] = ()
    area_scale: dict[str, float] = field(default_factory=dict)


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


def laplacian(n: int, edges: Edges) -> sp.csr_matrix:
    """Symmetric conductance matrix of the edge list (row sums zero)."""
    a, b, g = np.asarray(edges.a, int), np.asarray(edges.b, int), np.asarray(edges.g, float)
    rows = np.concatenate([a, b, a, b])
    cols = np.concatenate([a, b, b, a])
    vals = np.concatenate([g, g, -g, -g])
    return sp.csr_matrix((vals, (rows, cols)), shape=(n, n))


class Network:
    """Builds the position-dependent parts of the fast model's equations."""

    def __init__(self, layout: Layout, tamper: SolverTamper | None = None):
        self.layout = layout
        self.system = layout.system
        self.tamper = tamper or SolverTamper()
        self._check_joints()
        fixed = Edges()
        for body in layout.bodies.values():
            self._body_conduction(body, fixed)
        for joint in self.system.joints:
            if not joint.sliding:
                self._joint(joint, fixed, offset=0.0)
        self.fixed = laplacian(layout.n_nodes, fixed)

    # ------------------------------------------------------------------ structure
    def _check_joints(self) -> None:
        parts = self.system.parts
        for i, joint in enumerate(self.system.joints):
            a, b = joint.between
            moving = [parts[a].moving, parts[b].moving]
            if joint.sliding and moving.count(True) != 1:
                raise ModelError(f"joints[{i}]: a sliding joint needs one moving and one fixed part ({a}, {b})")
            if joint.sliding and not any(p in self.layout.bodies for p in (a, b)):
                raise ModelError(f"joints[{i}]: the fixed side of a sliding joint must be resolved along x")
            if not joint.sliding and moving.count(True) == 1:
                raise ModelError(f"joints[{i}]: {a} and {b}: a joint between a moving and a fixed part must be sliding")

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

    def _surface_resistance_length(self, body: AxialBody) -> float:
        """Conduction length [m] from the outer ring's node to the body's surface (per ln term)."""
        if body.cylindrical:
            r = body.ring_radii
            return math.log(r[-1] / (0.5 * (r[-1] + r[-2])))  # used as ln(r_o/r_c) / (2 pi k l)
        return body.cross_section / (2.0 * (math.sqrt(body.cross_section) * 2))  # area / perimeter

    def _lumped_resistance(self, part: str, area: float) -> float:
        return self.layout.surface_length[part] / (self._material(part).conductivity * area)

    def contact_weights(self, part: str, body: AxialBody, offset: float) -> np.ndarray:
        """Share of a contact per cell of ``body`` (sums to 1) where ``part`` touches it."""
        overlap = np.zeros(len(body.centres))
        for x0, x1 in contact_ranges(self.system, part, body, offset):
            overlap += body.overlap(x0, x1)
        total = overlap.sum()
        if total <= 0.0:
            raise ModelError(f"{part} does not touch {body.part} at offset {offset * 1e3:.1f} mm")
        return overlap / total

    def _joint(self, joint: Joint, edges: Edges, offset: float) -> None:
        a, b = joint.between
        bodies = self.layout.bodies
        if a in bodies and b in bodies:
            raise ModelError(f"joint {a}-{b}: two axially resolved parts cannot be joined")
        if a not in bodies and b not in bodies:
            g = 1.0 / (joint.tcr / joint.area + self._lumped_resistance(a, joint.area) + self._lumped_resistance(b, joint.area))
            edges.add(self.layout.lumped[a], self.layout.lumped[b], g)
            return
        body_name, other = (a, b) if a in bodies else (b, a)
        body = bodies[body_name]
        part_offset = offset if self.system.parts[other].moving else 0.0
        weights = self.contact_weights(other, body, part_offset)
        cells = np.nonzero(weights)[0]
        area = joint.area * weights[cells]
        k_body = self._material(body_name).conductivity
        if body.cylindrical:
            contact_length = np.maximum(weights[cells] * sum(x1 - x0 for x0, x1 in contact_ranges(self.system, other, body, part_offset)), 1e-12)
            r_surface = self._surface_resistance_length(body) / (2 * math.pi * k_body * contact_length)
        else:
            r_surface = self._surface_resistance_length(body) / (k_body * area)
        g = 1.0 / (joint.tcr / area + self._lumped_resistance(other, area) + r_surface)
        edges.add(np.full(len(cells), self.layout.lumped[other]), body.nodes[cells, -1], g)

    # ------------------------------------------------------------------ per position
    def sliding(self, k: int) -> sp.csr_matrix:
        """Conductance matrix of the sliding contacts with the moving group at position ``k``."""
        edges = Edges()
        for joint in self.system.joints:
            if joint.sliding:
                self._joint(joint, edges, offset=self.layout.positions[k])
        return laplacian(self.layout.n_nodes, edges)

    def ambient_links(self, bc: BoundaryConditions, k: int, *, for_solver: bool = True) -> np.ndarray:
        """Conductance [W/K] of every node to the ambient air (convection + radiation)."""
        g = np.zeros(self.layout.n_nodes)
        for name, area_by_node in self.surface_areas(bc, k).items():
            scale = self.tamper.area_scale.get(name, 1.0) if for_solver else 1.0
            nodes, areas = area_by_node
            np.add.at(g, nodes, bc.surfaces[name].total * areas * scale)
        return g

    def surface_areas(self, bc: BoundaryConditions, k: int) -> dict[str, tuple[np.ndarray, np.ndarray]]:
        """Per surface: the nodes it belongs to and their exposed areas [m²] at position ``k``."""
        out = {}
        offset = self.layout.positions[k]
        for name, transfer in bc.surfaces.items():
            surface = self.system.surfaces[name]
            if surface.part in self.layout.lumped:
                out[name] = (np.array([self.layout.lumped[surface.part]]), np.array([transfer.area]))
                continue
            body = self.layout.bodies[surface.part]
            share = body.lengths / body.lengths.sum()
            exposed = np.ones_like(share)
            if body.cylindrical and "lateral" in surface.faces:
                exposed = 1.0 - self._covered(body, offset) / body.lengths
            out[name] = (body.nodes[:, -1], transfer.area * share * np.clip(exposed, 0.0, 1.0))
        return out

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

    def heat_vector(self, bc: BoundaryConditions, k: int, *, for_solver: bool = True) -> np.ndarray:
        """Heat [W] into every node with the moving group at position ``k``."""
        q = np.zeros(self.layout.n_nodes)
        offset = self.layout.positions[k]
        for name, heat in bc.heats.items():
            if for_solver and name in self.tamper.drop_sources:
                continue
            for part, share in heat.into.items():
                power = heat.power * share
                if part in self.layout.lumped:
                    q[self.layout.lumped[part]] += power
                    continue
                body = self.layout.bodies[part]
                partner = next((p for p in heat.into if p != part and self._joined(p, part)), None)
                if partner is not None:  # heat that arises at a contact enters where the contact is
                    part_offset = offset if self.system.parts[partner].moving else 0.0
                    q[body.nodes[:, -1]] += power * self.contact_weights(partner, body, part_offset)
                else:  # heat of the body itself: by volume
                    volumes = np.outer(body.lengths, body.ring_areas()).ravel()
                    q[body.nodes.ravel()] += power * volumes / volumes.sum()
        return q

    def _joined(self, a: str, b: str) -> bool:
        return any(set(j.between) == {a, b} for j in self.system.joints)
