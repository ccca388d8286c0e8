"""Tetrahedral meshes of a feed system's parts, built with gmsh, cached on disk.

Every part is meshed on its own (OCC kernel: its boxes and cylinders fused, its holes cut),
with linear tetrahedra of a size chosen per part:

.. math:: h_{part} = \\min(h_{max}, t / n_{across})

``t`` the part's thinnest dimension (a box's smallest side, a tube's wall, a solid
cylinder's radius), ``h_max`` and ``n_across`` set by the density (:data:`DENSITIES`). The
screw (a solid rod: ``t`` is its radius; the friction heat and the sliding contact are on it)
gets ``screw_factor`` times more elements across, and a part's ``mesh_refinement`` (the
description's) multiplies its ``n_across``. Curved faces also get at least ``per_circle`` elements around.

The parts' meshes are put side by side without merging nodes: a
joint between two parts is a non-conforming interface (:mod:`.coupling`). Moving parts are
meshed where the description declares them (the middle of the stroke).

Meshes are cached as ``<sha>-<density>.npz`` (points, tetrahedra, part id per tetrahedron)
under ``$FEEDTHERM_CACHE/meshes`` (default ``~/.cache/feedtherm/meshes``); the hash covers
the parts' geometry, the mesh sizes and :data:`MESH_VERSION`.
"""

from __future__ import annotations

import hashlib
import json
import os
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...constants import cache_root
from ...errors import ModelError
from ...system.schema import Cylinder, FeedSystem, Part

__all__ = ["DENSITIES", "Density", "PartMesh", "BenchMesh", "mesh_size", "mesh_system", "mesh_cache_path", "cache_dir"]

MESH_VERSION = 1  #: bump when the meshing changes, so old cache files are not reused
MM = 1e-3  # gmsh works in millimetres (its tolerances suit them); the result is in metres


@dataclass(frozen=True)
class Density:
    """Mesh size rule of one density (lengths in metres)."""

    h_max: float  #: largest element size anywhere [m]
    n_across: float  #: elements across a part's thinnest dimension
    screw_factor: float  #: the screw gets this many times more across
    per_circle: int  #: elements around a full circle of a curved face


DENSITIES: dict[str, Density] = {
    "coarse": Density(h_max=0.030, n_across=1.5, screw_factor=2.0, per_circle=12),
    "medium": Density(h_max=0.014, n_across=2.5, screw_factor=2.0, per_circle=20),
    "fine": Density(h_max=0.0072, n_across=4.0, screw_factor=2.0, per_circle=28),
}


def cache_dir() -> Path:
    """``$FEEDTHERM_CACHE/meshes``, default ``~/.cache/feedtherm/meshes``."""
    return cache_root() / "meshes"


def thickness(part: Part) -> float:
    """The part's thinnest dimension [m]: a box's smallest side, a tube's wall, a rod's radius."""
    values = [min(b.size) for b in part.boxes]
    for c in part.cylinders:
        wall = (c.outer_diameter - c.inner_diameter) / 2.0
        values.append(min(wall, c.length))
    return min(values)


def mesh_size(system: FeedSystem, name: str, density: str) -> float:
    """Target element size [m] of part ``name`` at ``density``."""
    rule = _density(density)
    across = rule.n_across * system.parts[name].mesh_refinement
    if system.kinematics is not None and name == system.kinematics.screw:
        across *= rule.screw_factor
    return min(rule.h_max, thickness(system.parts[name]) / across)


def _density(density: str) -> Density:
    if density not in DENSITIES:
        raise ModelError(f"mesh density must be one of {', '.join(DENSITIES)}, got {density!r}")
    return DENSITIES[density]


@dataclass(frozen=True)
class PartMesh:
    """One part's tetrahedral mesh [m]."""

    points: np.ndarray  #: (3, n)
    tets: np.ndarray  #: (4, m), indices into ``points``


@dataclass
class BenchMesh:
    """All parts' meshes side by side (nodes not merged) and how they were made."""

    points: np.ndarray  #: (3, N) [m]
    tets: np.ndarray  #: (4, M)
    part_of_tet: np.ndarray  #: (M,) index into ``parts``
    parts: list[str]
    sizes: dict[str, float]  #: element size used per part [m]
    density: str
    seconds: float = 0.0  #: meshing time (0 when read from the cache)
    cached: bool = False
    path: Path | None = None
    node_ranges: dict[str, tuple[int, int]] = field(default_factory=dict)  #: [start, stop) per part

    def part_nodes(self, name: str) -> np.ndarray:
        lo, hi = self.node_ranges[name]
        return np.arange(lo, hi)

    def part_tets(self, name: str) -> np.ndarray:
        return np.nonzero(self.part_of_tet == self.parts.index(name))[0]


def _geometry_key(system: FeedSystem, density: str, sizes: dict[str, float]) -> str:
    rule = _density(density)
    data = {
        "version": MESH_VERSION,
        "density": density,
        "rule": [rule.h_max, rule.n_across, rule.screw_factor, rule.per_circle],
        "parts": {
            name: {
                "boxes": [b.model_dump(mode="json") for b in p.boxes],
                "cylinders": [c.model_dump(mode="json") for c in p.cylinders],
                "holes": [h.model_dump(mode="json") for h in p.holes],
                "size": sizes[name],
            }
            for name, p in system.parts.items()
        },
    }
    return hashlib.sha256(json.dumps(data, sort_keys=True).encode()).hexdigest()[:16]


def mesh_cache_path(system: FeedSystem, density: str) -> Path:
    """Where the mesh of ``system`` at ``density`` is (or would be) cached: named by its geometry's digest."""
    sizes = {name: mesh_size(system, name, density) for name in system.parts}
    return cache_dir() / f"{_geometry_key(system, density, sizes)}-{density}.npz"


def mesh_system(system: FeedSystem, density: str, *, use_cache: bool = True) -> BenchMesh:
    """Mesh every part of ``system`` at ``density`` (from the cache when it holds it)."""
    sizes = {name: mesh_size(system, name, density) for name in system.parts}
    path = mesh_cache_path(system, density)
    names = list(system.parts)
    if use_cache and path.exists():
        data = np.load(path, allow_pickle=False)
        if [str(s) for s in data["parts"]] == names:
            mesh = BenchMesh(data["points"], data["tets"], data["part_of_tet"], names, sizes, density,
                             float(data["seconds"]), True, path)
            mesh.node_ranges = _node_ranges(mesh, data["node_counts"])
            return mesh
    started = time.perf_counter()
    meshes = [_mesh_part(system.parts[name], sizes[name], _density(density).per_circle, name) for name in names]
    seconds = time.perf_counter() - started
    points, tets, part_of_tet, offset = [], [], [], 0
    for i, m in enumerate(meshes):
        points.append(m.points)
        tets.append(m.tets + offset)
        part_of_tet.append(np.full(m.tets.shape[1], i, dtype=np.int32))
        offset += m.points.shape[1]
    counts = np.array([m.points.shape[1] for m in meshes])
    mesh = BenchMesh(np.hstack(points), np.hstack(tets).astype(np.int64), np.concatenate(part_of_tet), names, sizes,
                     density, seconds, False, path)
    mesh.node_ranges = _node_ranges(mesh, counts)
    if use_cache:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(".tmp.npz")
        np.savez_compressed(tmp, points=mesh.points, tets=mesh.tets, part_of_tet=mesh.part_of_tet,
                            parts=np.array(names), node_counts=counts, seconds=seconds)
        os.replace(tmp, path)
    return mesh


def _node_ranges(mesh: BenchMesh, counts) -> dict[str, tuple[int, int]]:
    edges = np.concatenate([[0], np.cumsum(counts)])
    return {name: (int(edges[i]), int(edges[i + 1])) for i, name in enumerate(mesh.parts)}


# ---------------------------------------------------------------------------- gmsh


def _mesh_part(part: Part, size: float, per_circle: int, name: str) -> PartMesh:
    """Mesh one part with gmsh (OCC): primitives fused, holes cut; linear tetrahedra."""
    import gmsh  # imported here: only the FE model needs it

    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add(name)
        occ = gmsh.model.occ
        solids = [(3, _box(occ, b)) for b in part.boxes]
        solids += [(3, t) for c in part.cylinders for t in [_cylinder(occ, c)]]
        if len(solids) > 1:
            solids, _ = occ.fuse(solids[:1], solids[1:])
        if part.holes:
            holes = [(3, _cylinder(occ, h)) for h in part.holes]
            solids, _ = occ.cut(solids, holes)
        occ.synchronize()
        h = size / MM
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        gmsh.option.setNumber("Mesh.MeshSizeMin", 0.2 * h)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", per_circle)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 1)
        gmsh.option.setNumber("Mesh.ElementOrder", 1)
        gmsh.option.setNumber("Mesh.Optimize", 1)
        gmsh.model.mesh.generate(3)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        _, node_tags = gmsh.model.mesh.getElementsByType(4)  # 4-node tetrahedra
    finally:
        gmsh.finalize()
    if node_tags.size == 0:
        raise ModelError(f"parts.{name}: gmsh made no tetrahedra")
    coords = coords.reshape(-1, 3).T * MM
    index = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(tags.size)
    tets = index[node_tags.astype(np.int64)].reshape(-1, 4).T
    used = np.unique(tets)  # drop nodes no tetrahedron uses (geometry points)
    compact = np.full(tags.size, -1, dtype=np.int64)
    compact[used] = np.arange(used.size)
    points = coords[:, used]
    tets = compact[tets]
    _orient(points, tets)
    return PartMesh(points, tets)


def _orient(points: np.ndarray, tets: np.ndarray) -> None:
    """Make every tetrahedron positively oriented (in place)."""
    p = points[:, tets]
    vol = np.einsum("ij,ij->j", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0], axis=0))
    neg = vol < 0
    tets[1, neg], tets[2, neg] = tets[2, neg].copy(), tets[1, neg].copy()


def _box(occ, box) -> int:
    o = [v / MM for v in box.origin]
    s = [v / MM for v in box.size]
    return occ.addBox(*o, *s)


def _cylinder(occ, cyl: Cylinder) -> int:
    o = [v / MM for v in cyl.origin]
    axis = [0.0, 0.0, 0.0]
    axis["xyz".index(cyl.axis)] = cyl.length / MM
    outer = occ.addCylinder(*o, *axis, cyl.outer_diameter / 2.0 / MM)
    if cyl.inner_diameter <= 0.0:
        return outer
    inner = occ.addCylinder(*o, *axis, cyl.inner_diameter / 2.0 / MM)
    out, _ = occ.cut([(3, outer)], [(3, inner)])
    return out[0][1]
