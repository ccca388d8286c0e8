"""The fast model's displacements: every part an axial bar along x.

The fast model has no stiffness; it reads the axial displacements the way a 1-D analysis of
a feed drive does: each part stretches freely along x by its section-mean thermal strain,

.. math:: u(x) = u(x_a) + \\alpha \\int_{x_a}^{x} (\\bar T(\\xi) - T_{ref})\\, d\\xi

(:func:`~feedtherm.physics.thermal_expansion.displacement_weights_axial`), and the parts
carry each other along the structure's axial load path: a tree found breadth-first from the
part(s) a support holds along x (anchored at the support, u = 0 there) over the joints that
hold x (``release`` without ``x``).  A child fastened to its parent over an x-range (a housing
bolted along its foot, a bearing in its bore) is held at the middle of that range and expands
freely from there, as a bolted part expands about the centre of its joint; the drive holds the
nut to the screw at the nut's centre alone.  Loops of x-holding joints
(a nut, its bearing, its housing, its motor and belt) are cut where the search first
reaches a part: a bar model cannot share a load between two paths, and the parts of such a
loop are not what D or the positioning error read.

``T̄(ξ)`` is the capacity-weighted mean of the part's nodes whose x-extent covers ξ (one
material per part, so also the volume-weighted mean; for the screw the ring-area mean of
:meth:`FastDiscretization.screw_mean`); where no node covers ξ the part has no material and
no strain.  A cylinder along y or z has no x resolution: its whole x-extent is one bin.
Everything is linear in the node temperatures, so it is built once as rows over the state.
"""

from __future__ import annotations

from collections import deque

import numpy as np

from ...errors import ModelError
from ...physics.thermal_expansion import displacement_weights_axial
from ...system.geometry import bounds, drive_point
from ...system.mechanics import GROUND
from ...system.schema import FeedSystem
from .grids import BoxGrid
from .layout import Layout

_COVER = 1e-12  # [m] a node covers a bin when its extent reaches the bin's edges within this


def node_extents(layout: Layout, part: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The part's nodes and each node's x-extent ``(nodes, lo, hi)`` [m]."""
    if part in layout.bodies:
        body = layout.bodies[part]
        cell = np.repeat(np.arange(len(body.edges) - 1), body.n_rings)  # nodes are (cell, ring), row-major
        return body.nodes.ravel(), body.edges[cell], body.edges[cell + 1]
    cells = layout.cells[part]
    lo, hi = [], []
    for grid in cells.grids:
        if isinstance(grid, BoxGrid):
            ix = np.nonzero(grid.local >= 0)[0]  # kept cells in the grid's (C) order of its nodes
            lo.append(grid.edges[0][ix])
            hi.append(grid.edges[0][ix + 1])
        elif grid.axis == 0:
            axial = grid.cyl.origin[0] + grid.axial_edges
            slab = np.arange(grid.size) // grid.shape[1]  # nodes are (slice, ring), row-major
            lo.append(axial[slab])
            hi.append(axial[slab + 1])
        else:  # across x: the whole section is one bin
            r = grid.cyl.outer_diameter / 2.0
            lo.append(np.full(grid.size, grid.cyl.origin[0] - r))
            hi.append(np.full(grid.size, grid.cyl.origin[0] + r))
    return cells.nodes, np.concatenate(lo), np.concatenate(hi)


class Bar:
    """One part as an axial bar: bins along x and its section-mean weights in each."""

    def __init__(self, layout: Layout, part: str, alpha: float):
        self.alpha = alpha
        self.nodes, lo, hi = node_extents(layout, part)
        self.edges = np.unique(np.concatenate([lo, hi]))
        density = layout.capacity[self.nodes] / (hi - lo)  # [J/(K·m)]: capacity per unit length
        covers = (lo[None, :] <= self.edges[:-1, None] + _COVER) & (hi[None, :] >= self.edges[1:, None] - _COVER)
        weight = covers * density[None, :]
        total = weight.sum(axis=1, keepdims=True)
        # rows sum to 1 where material covers the bin, 0 in a gap between primitives (no strain)
        self.mean = np.divide(weight, total, out=np.zeros_like(weight), where=total > 0)

    def stretch(self, x_from: float, x, n_nodes: int) -> np.ndarray:
        """Rows (len(x), n_nodes) [m/K]: α ∫ T̄ dξ from ``x_from`` to each ``x``, over the nodes."""
        rows = np.zeros((len(np.atleast_1d(x)), n_nodes))
        rows[:, self.nodes] = self.alpha * displacement_weights_axial(self.edges, x_from, x) @ self.mean
        return rows


def load_path(system: FeedSystem) -> dict[str, tuple[str | None, float, float]]:
    """Each part the structure holds along x: its parent on the axial load path (None for a part
    a support holds) and the x-range [m] over which it moves with its parent."""
    tree: dict[str, tuple[str | None, float, float]] = {}
    for support in system.mechanics.supports:
        if "x" in support.fix and support.part not in tree:  # a second x support would restrain expansion
            tree[support.part] = (None, support.point[0], support.point[0])
    kin = system.kinematics
    # the links that hold x: the joints that do not release it, and the drive (the thread holds
    # the nut to the screw at the nut's centre)
    links = [(*joint.between, None) for joint in system.joints if "x" not in joint.release]
    if (drive := drive_point(system)) is not None:
        links.append((kin.screw, kin.nut, drive[0]))
    queue = deque(tree)
    while queue:
        parent = queue.popleft()
        for a, b, at in links:
            if parent not in (a, b):
                continue
            child = b if a == parent else a
            if child in tree:
                continue
            if at is None:  # where they meet along x (the middle of the gap, if they are apart)
                (p_lo, p_hi), (c_lo, c_hi) = _x_extent(system, parent), _x_extent(system, child)
                lo, hi = max(p_lo, c_lo), min(p_hi, c_hi)
                tree[child] = (parent, lo, hi) if lo <= hi else (parent, 0.5 * (lo + hi), 0.5 * (lo + hi))
            else:
                tree[child] = (parent, at, at)
            queue.append(child)
    return tree


def anchors(system: FeedSystem) -> dict[str, tuple[str | None, float]]:
    """Each part the structure holds along x: its parent on the axial load path (None for a part
    a support holds) and the x [m] where it is held, from which it expands freely: the middle of
    the range over which it meets its parent (a part fastened over a range expands about the
    middle of its joint), the support's point, or the nut's centre for the drive."""
    return {part: (parent, 0.5 * (lo + hi)) for part, (parent, lo, hi) in load_path(system).items()}


def _x_extent(system: FeedSystem, part: str) -> tuple[float, float]:
    lo, hi = bounds(system.parts[part])
    return lo[0], hi[0]


class Bars:
    """The axial displacement of the parts on the load path, as rows over the state [m/K]."""

    def __init__(self, layout: Layout):
        self.system = system = layout.system
        self.layout = layout
        self.anchors = anchors(system)
        self._bars: dict[str, Bar] = {}  # built when read: only the parts on a chain to a read point

    def _bar(self, part: str) -> Bar:
        if part not in self._bars:
            self._bars[part] = Bar(self.layout, part, self.system.materials[self.system.parts[part].material].expansion)
        return self._bars[part]

    def at(self, part: str, x, field: str) -> np.ndarray:
        """Rows (len(x), n_nodes): ``rows @ T`` is α ∫ T̄ along the path to ``part`` at each ``x``
        (the displacement plus a constant that a state at T_ref cancels)."""
        if part not in self.anchors:
            raise ModelError(f"{field}: part {part!r} is on no chain of joints holding x from a support "
                             "fixing x, so the fast model's bars cannot say how it moves along x")
        parent, anchor = self.anchors[part]  # held there (the middle of its joint), expanding from there
        rows = self._bar(part).stretch(anchor, np.atleast_1d(np.asarray(x, dtype=float)), self.layout.n_nodes)
        if parent is not None:
            rows += self.at(parent, [anchor], field)
        return rows


def displacement_rows(layout: Layout) -> tuple[np.ndarray, np.ndarray]:
    """``(rows, offset)``: ``rows @ T + offset`` is D, then the screw's axial displacement at its
    cell centres relative to the positioning reference [m] (the model interface's rows)."""
    system = layout.system
    mech = system.mechanics
    sensor = mech.elongation
    if sensor.axis != 0:
        raise ModelError("mechanics.elongation.direction: the fast model reads displacements along x only; "
                         "use --model fem")
    bars = Bars(layout)
    d = bars.at(sensor.target.part, [sensor.target.point[0]], "mechanics.elongation.target")
    if sensor.mount != GROUND:
        d = d - bars.at(sensor.mount.part, [sensor.mount.point[0]], "mechanics.elongation.mount")
    d = d * sensor.direction[0]  # ±1: the sensor's sense along x
    if mech.positioning is None:  # no feed drive: D alone
        profile = np.zeros((0, layout.n_nodes))
    else:
        reference = mech.positioning.reference
        profile = (bars.at(system.kinematics.screw, layout.screw.centres, "kinematics.screw")
                   - bars.at(reference.part, [reference.point[0]], "mechanics.positioning.reference"))
    rows = np.vstack([d, profile])
    # every displacement is zero with every node at the reference temperature
    return rows, -system.temperatures.reference * rows.sum(axis=1)


__all__ = ["Bar", "Bars", "anchors", "displacement_rows", "load_path", "node_extents"]
