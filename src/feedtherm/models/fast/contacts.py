"""Where the parts' cells touch: fused primitives, joints and exposed faces, from face samples.

Every face sample (:mod:`.samples`) of a part cut into cells belongs to the cell under it.
Tested just outside its face, it lies

* in another primitive of the same part: the two primitives are fused there — conduction
  from cell to cell, ``A / (d₁/k + d₂/k)``;
* in a part it is joined to: the joint's contact. Its conductance ``A_declared/R''`` (the
  description's area is authoritative, as in the FE model) is spread over the geometric
  contact ``A_geo`` found by the samples, ``R''_eff = R''·A_geo/A_declared``, in series with
  the distance from each side's node to the face (``d/k``);
* in nothing: exposed to the air (the convective areas).

A joint is sampled on one side: the part cut into cells (the other may be the screw or a
rail, resolved along x), the first of the two otherwise. A sliding joint's samples move with
the group: they are shifted by the group's offset into the fixed part's frame at every grid
position, and a sample's patch (of length ``extent`` along x) is spread over the axial cells
it overlaps, so that a contact covers a screw cell exactly in proportion to its overlap.
Parts joined in a description that do not touch in its geometry (``feedtherm check`` warns)
are joined at their nearest cells.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...system.geometry import bounds
from ...system.schema import Joint, Part
from .cells import PartCells
from .grids import in_holes
from .layout import AxialBody, Layout
from .samples import Samples, part_samples

_AXES = {"x": 0, "y": 1, "z": 2}


def part_contains(part: Part, points: np.ndarray) -> np.ndarray:
    """True where a point lies in one of the part's primitives (not in a hole)."""
    inside = np.zeros(len(points), dtype=bool)
    for box in part.boxes:
        lo = np.asarray(box.origin)
        hi = lo + np.asarray(box.size)
        inside |= np.all((points >= lo) & (points <= hi), axis=1)
    if part.holes:
        inside &= ~in_holes(part.holes, points)
    for cyl in part.cylinders:
        i = _AXES[cyl.axis]
        d = points - np.asarray(cyl.origin)
        r2 = np.einsum("ij,ij->i", np.delete(d, i, axis=1), np.delete(d, i, axis=1))
        inside |= (d[:, i] >= 0) & (d[:, i] <= cyl.length) \
            & (r2 >= (cyl.inner_diameter / 2.0) ** 2) & (r2 <= (cyl.outer_diameter / 2.0) ** 2)
    return inside


@dataclass
class Side:
    """A cell part's face samples, each with its own cell and the distance d [m] from the cell's
    node to the face (its specific resistance is d/k: the conductivity is the model's own, as
    the sides are kept with the geometry)."""

    cells: PartCells
    samples: Samples
    nodes: np.ndarray
    distance: np.ndarray
    fused_to: np.ndarray  # primitive of the same part just outside the sample (-1: none)

    @property
    def free(self) -> np.ndarray:
        return self.fused_to < 0


def side(cells: PartCells, cell_size: float) -> Side:
    s = part_samples(cells, cell_size)
    nodes = cells.locate(s.inside(), s.primitive)
    d = cells.distance(nodes, s.primitive, s.points, s.normals)
    fused = cells.primitive_of(s.outside())
    return Side(cells, s, nodes, d, fused)


def fused_links(sd: Side, conductivity: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Conduction between the cells of a part's fused primitives (each face counted once), the
    part's conductivity ``conductivity`` [W/(m·K)]."""
    s, cells = sd.samples, sd.cells
    sel = (sd.fused_to >= 0) & (s.primitive < sd.fused_to)
    if not sel.any():
        return np.zeros(0, int), np.zeros(0, int), np.zeros(0)
    q = s.outside()[sel]
    other = sd.fused_to[sel]
    nb = cells.locate(q, other)
    rb = cells.distance(nb, other, s.points[sel], s.normals[sel]) / conductivity
    return aggregate(sd.nodes[sel], nb, s.areas[sel], sd.distance[sel] / conductivity, rb, 0.0)


def aggregate(na, nb, area, ra, rb, r_contact: float):
    """Conductances [W/K] between node pairs from per-sample areas and specific resistances."""
    a, b, A, Ra, Rb = pair_sums(na, nb, area, ra, rb)
    return a, b, A / (r_contact + Ra + Rb)


def pair_sums(na, nb, area, ra, rb):
    """Per node pair: the nodes, the contact area [m²] and its area-weighted specific
    resistances [m²K/W] on either side (everything of :func:`aggregate` but the contact's own)."""
    return resistance_sums(pairing(na, nb, area), area, ra, rb)


def pairing(na, nb, area) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The node pairs of samples (``na[i]``, ``nb[i]``): each pair's nodes, each sample's pair and
    each pair's area [m²] — the geometry of :func:`pair_sums`."""
    na, nb = np.asarray(na, int), np.asarray(nb, int)
    if na.size == 0:
        return na, nb, np.zeros(0, int), np.zeros(0)
    pairs, inverse = np.unique(np.stack([na, nb], axis=1), axis=0, return_inverse=True)
    inverse = inverse.ravel()
    return pairs[:, 0], pairs[:, 1], inverse, np.bincount(inverse, weights=area)


def resistance_sums(pairs, area, ra, rb):
    """:func:`pair_sums` from the :func:`pairing` ``pairs`` of the samples and their specific resistances."""
    a, b, inverse, A = pairs
    if a.size == 0:
        return a, b, np.zeros(0), np.zeros(0), np.zeros(0)
    Ra = np.bincount(inverse, weights=area * ra) / A
    Rb = np.bincount(inverse, weights=area * rb) / A
    return a, b, A, Ra, Rb


def spread_along(edges: np.ndarray, x: np.ndarray, extent: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each patch [x − e/2, x + e/2] over the cells ``edges``: (patch, cell, fraction)."""
    n = len(edges) - 1
    lo, hi = x - extent / 2.0, x + extent / 2.0
    first = np.clip(np.searchsorted(edges, lo, side="right") - 1, 0, n - 1)
    last = np.clip(np.searchsorted(edges, hi, side="left") - 1, 0, n - 1)
    last = np.maximum(last, first)
    patches, cells, fractions = [], [], []
    for j in range(int((last - first).max(initial=0)) + 1):
        ok = first + j <= last
        cell = np.minimum(first + j, last)  # patches spanning fewer cells than the widest stay in range
        width = np.minimum(hi, edges[np.minimum(cell + 1, n)]) - np.maximum(lo, edges[cell])
        frac = np.where(extent > 0, width / np.where(extent > 0, extent, 1.0), 1.0)
        ok &= frac > 0
        patches.append(np.nonzero(ok)[0])
        cells.append(cell[ok])
        fractions.append(frac[ok])
    return np.concatenate(patches), np.concatenate(cells), np.concatenate(fractions)


#: How many pairs of conductivities a contact keeps its resistance sums for (the latest ones).
KEPT_CONDUCTIVITIES = 4


class JointContact:
    """The contact of one joint, sampled on one side; the other side a cell part or an axial body."""

    def __init__(self, layout: Layout, joint: Joint, sides: dict[str, Side], conductivity: dict[str, float],
                 surface_length: dict[str, float], cache: dict[int, dict] | None = None):
        self.layout = layout
        self.joint = joint
        a, b = joint.between
        self.sampled, self.other = (b, a) if (a in layout.bodies or (b in layout.cells and a not in layout.cells)) else (a, b)
        self.side = sides[self.sampled]
        self.k_sampled, self.k_other = conductivity[self.sampled], conductivity[self.other]
        self.surface_length = surface_length  # conduction length [m] from an axial body's node to its surface
        parts = layout.system.parts
        self.shift_sign = float(parts[self.sampled].moving) - float(parts[self.other].moving)
        # geometry, kept for every model of it: distances, not resistances (the conductivities are each model's)
        self._cache: dict[int, dict] = {} if cache is None else cache

    def key(self, k: int) -> int:
        return k if self.shift_sign != 0.0 else 0

    def contact(self, k: int) -> dict:
        """Samples in contact at position k: both sides' nodes, areas and specific resistances."""
        key = self.key(k)
        if key in self._cache:
            return self._cache[key]
        sd = self.side
        s = sd.samples
        free = np.nonzero(sd.free)[0]
        q = s.outside()[free]
        q[:, 0] += self.shift_sign * self.layout.positions[k]
        other_part = self.layout.system.parts[self.other]
        hit = part_contains(other_part, q)
        idx, q = free[hit], q[hit]
        out = {"sampled_nodes": sd.nodes[idx], "areas": s.areas[idx], "sampled_d": sd.distance[idx]}
        if self.other in self.layout.cells:
            cells = self.layout.cells[self.other]
            prim = cells.primitive_of(q)
            prim = np.where(prim < 0, cells.primitive_of(q, tol=1e-3), prim)
            ok = prim >= 0
            idx, q, prim = idx[ok], q[ok], prim[ok]
            for key_ in ("sampled_nodes", "areas", "sampled_d"):
                out[key_] = out[key_][ok]
            nodes = cells.locate(q, prim)
            out["other_nodes"] = nodes
            out["other_d"] = cells.distance(nodes, prim, s.points[idx], s.normals[idx])
        else:
            body = self.layout.bodies[self.other]
            patch, cell, frac = spread_along(body.edges, q[:, 0], s.extent[idx])
            ring = self._ring(body, q[patch])
            out["sampled_nodes"] = out["sampled_nodes"][patch]
            out["sampled_d"] = out["sampled_d"][patch]
            out["areas"] = out["areas"][patch] * frac
            out["other_nodes"] = body.nodes[cell, ring]
            out["other_d"] = self._body_distance(body, cell, ring, q[patch], s.normals[idx][patch])
            out["body_cells"] = cell
            out["body_faces"] = _face_labels(-s.normals[idx][patch])
        self._cache[key] = out
        return out

    def _radius(self, body: AxialBody, q: np.ndarray) -> np.ndarray:
        """Distance [m] of points from a cylindrical body's axis, within its section."""
        axis = self.layout.system.parts[body.part].cylinders[0].origin
        r = np.hypot(q[:, 1] - axis[1], q[:, 2] - axis[2])
        return np.clip(r, max(body.ring_radii[0], 1e-9), body.ring_radii[-1])

    def _ring(self, body: AxialBody, q: np.ndarray) -> np.ndarray:
        if not body.cylindrical:
            return np.zeros(len(q), dtype=int)
        return np.clip(np.searchsorted(body.ring_radii, self._radius(body, q), side="right") - 1, 0, body.n_rings - 1)

    def _body_distance(self, body: AxialBody, cell, ring, q, normals) -> np.ndarray:
        """Conduction length [m] from the body's node to the contact, its specific resistance over
        the conductivity: radial (``r ln(r/r_c)``) or axial (half the cell)."""
        if not body.cylindrical:
            return np.full(len(q), self.surface_length[body.part])
        rc = 0.5 * (body.ring_radii[1:] + body.ring_radii[:-1])[ring]
        r = self._radius(body, q)
        radial = r * np.abs(np.log(r / rc))
        axial = 0.5 * body.lengths[cell]
        return np.where(np.abs(normals[:, 0]) > 0.5, axial, radial)

    def covered_faces(self, k: int, faces: set[str]) -> tuple[np.ndarray, np.ndarray]:
        """Axial cells of the body side and the contact area [m²] on each sample, counting only
        the body's faces named in ``faces`` (``+x`` … ``-z``)."""
        c = self.contact(k)
        if "body_cells" not in c:
            return np.zeros(0, int), np.zeros(0)
        on = np.isin(c["body_faces"], list(faces))
        return c["body_cells"][on], c["areas"][on]

    def geometric_area(self, k: int) -> float:
        return float(self.contact(k)["areas"].sum())

    def links(self, k: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        c = self.contact(k)
        area = c["areas"].sum()
        if area <= 0.0:
            return self._nearest_link()
        r_eff = self.joint.tcr * area / self.joint.area
        a, b, A, Ra, Rb = self._pair_sums(c)
        return a, b, A / (r_eff + Ra + Rb)

    def _pair_sums(self, c: dict):
        """The contact's :func:`pair_sums` at this model's conductivities: the pairing is kept with
        the contact (geometry), the sums under the two conductivities they were taken at."""
        if "pairing" not in c:
            c["pairing"] = pairing(c["sampled_nodes"], c["other_nodes"], c["areas"])
            c["sums"] = {}
        sums, key = c["sums"], (self.k_sampled, self.k_other)
        if key not in sums:
            if len(sums) >= KEPT_CONDUCTIVITIES:  # an uncertainty study draws a conductivity per sample
                del sums[next(iter(sums))]
            sums[key] = resistance_sums(c["pairing"], c["areas"], c["sampled_d"] / self.k_sampled,
                                        c["other_d"] / self.k_other)
        return sums[key]

    def share(self, part: str, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Nodes of ``part`` (a side of this joint) at the contact and their shares of its area."""
        c = self.contact(k)
        if c["areas"].sum() <= 0.0:
            a, b, _ = self._nearest_link()
            return (a if part == self.sampled else b), np.ones(1)
        nodes = c["sampled_nodes"] if part == self.sampled else c["other_nodes"]
        return nodes, c["areas"] / c["areas"].sum()

    def covers(self, part: str, points: np.ndarray, k: int) -> np.ndarray:
        """True where the joint's other part lies just outside the (outside-shifted) ``points`` of ``part``."""
        other = self.other if part == self.sampled else self.sampled
        q = points.copy()
        sign = float(self.layout.system.parts[part].moving) - float(self.layout.system.parts[other].moving)
        q[:, 0] += sign * self.layout.positions[k]
        return part_contains(self.layout.system.parts[other], q)

    def _nearest_link(self):
        """Parts that do not touch: one link between their nearest nodes, conductance A/R''."""
        pa, pb = self._node_points(self.sampled), self._node_points(self.other)
        d = ((pa[0][:, None, :] - pb[0][None, :, :]) ** 2).sum(axis=2)
        i, j = np.unravel_index(np.argmin(d), d.shape)
        return np.array([pa[1][i]]), np.array([pb[1][j]]), np.array([self.joint.area / self.joint.tcr])

    def _node_points(self, part: str) -> tuple[np.ndarray, np.ndarray]:
        """Positions [m] and indices of a part's nodes (an axial body's on its axis)."""
        if part in self.layout.cells:
            cells = self.layout.cells[part]
            return cells.node_points(), cells.nodes
        body = self.layout.bodies[part]
        lo, hi = bounds(self.layout.system.parts[part])
        p = np.tile(0.5 * (np.asarray(lo) + np.asarray(hi)), (len(body.centres), 1))
        p[:, 0] = body.centres
        return p, body.nodes[:, -1]


def _face_labels(normals: np.ndarray) -> np.ndarray:
    """Box face selector (``+x`` … ``-z``) of outward normals along an axis."""
    axis = np.argmax(np.abs(normals), axis=1)
    sign = np.where(normals[np.arange(len(normals)), axis] > 0, "+", "-")
    return np.char.add(sign, np.array(list("xyz"))[axis])


def surface_samples(sd: Side, surface) -> np.ndarray:
    """Mask over a side's samples of the faces a declared surface selects."""
    part = sd.cells.part
    s = sd.samples
    boxes = range(len(part.boxes)) if surface.boxes is None else surface.boxes
    cylinders = range(len(part.cylinders)) if surface.cylinders is None else surface.cylinders
    prims = set(boxes) | {len(part.boxes) + i for i in cylinders}
    labels = set(surface.faces)
    if "ends" in labels:
        labels |= {f"{sign}{c.axis}" for c in part.cylinders for sign in "+-"}
    return np.isin(s.primitive, list(prims)) & np.isin(s.face.astype(str), list(labels))


__all__ = ["Side", "side", "fused_links", "aggregate", "JointContact", "surface_samples", "part_contains", "spread_along"]
