"""Temperature fields of the FE model as files: ``fields.pvd`` and one ``.vtu`` per snapshot.

The finite element model hands its results over as a :class:`FieldSeries`: the mesh at rest,
which parts move with the worktable, and per snapshot the nodal temperatures, the moving
group's offset along x and the screw's axial displacement.  :func:`write_pvd` writes it as a
ParaView time series (meshio writes the ``.vtu`` files, the ``.pvd`` collection is plain XML);
:mod:`feedtherm.outputs.field_images` draws it as PNG images.

:func:`boundary_triangles` (the outer faces of a tetrahedral mesh) serves the images.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np

from ..solution import KELVIN_OFFSET

__all__ = [
    "FieldSeries",
    "write_pvd",
    "snapshot_mesh",
    "boundary_triangles",
    "PVD_NAME",
    "TEMPERATURE_FIELD",
    "PART_FIELD",
]

PVD_NAME = "fields.pvd"
TEMPERATURE_FIELD = "temperature_C"  #: point data [°C]
PART_FIELD = "part_id"  #: cell data: index into ``FieldSeries.part_names``
_VTU_STEM = "fields_"
_VTU_PATTERN = re.compile(r"fields_(\d{4,})\.vtu")


@dataclass(frozen=True, eq=False)
class FieldSeries:
    """The FE temperature field at a few instants, with the moving parts where they were.

    Parameters
    ----------
    points : ndarray, shape (n, 3)
        Mesh vertices with every part at rest [m].
    tets : ndarray of int, shape (m, 4)
        Linear tetrahedra (vertex indices).
    part_id : ndarray of int, shape (m,)
        The part of each tetrahedron, an index into ``part_names``.
    part_names : sequence of str
        Part names, e.g. ``["base", "screw", "worktable", ...]``.
    moving_part : sequence of bool
        Per part: does it move with the worktable group?  A node of a moving part is drawn
        at ``points + [offset, 0, 0]``; a node may not belong to a moving and a fixed part.
    snapshot_times : ndarray, shape (k,)
        Time of each snapshot [s], increasing.
    temperatures : ndarray, shape (k, n)
        Nodal temperatures [K].
    offsets : ndarray, shape (k,)
        Displacement of the moving group along x at each snapshot [m].
    screw_x : ndarray, shape (b,)
        Axial positions along the screw at which its displacement is given [m], increasing.
    screw_displacement : ndarray, shape (k, b)
        The screw's axial thermal displacement at ``screw_x`` [m].
    title : str
        What the run was, e.g. ``"condition I, physics mode, fem model (medium mesh)"``.
    """

    points: np.ndarray
    tets: np.ndarray
    part_id: np.ndarray
    part_names: Sequence[str]
    moving_part: Sequence[bool]
    snapshot_times: np.ndarray
    temperatures: np.ndarray
    offsets: np.ndarray
    screw_x: np.ndarray
    screw_displacement: np.ndarray
    title: str = ""

    def __post_init__(self) -> None:
        fix = lambda name, value: object.__setattr__(self, name, value)  # noqa: E731
        fix("points", np.asarray(self.points, dtype=float))
        fix("tets", np.asarray(self.tets))
        fix("part_id", np.asarray(self.part_id))
        fix("part_names", tuple(str(name) for name in self.part_names))
        fix("moving_part", tuple(bool(flag) for flag in self.moving_part))
        for name in ("snapshot_times", "temperatures", "offsets", "screw_x", "screw_displacement"):
            fix(name, np.asarray(getattr(self, name), dtype=float))
        self._check()

    def _check(self) -> None:
        n = len(self.points)
        k = len(self.snapshot_times)
        b = len(self.screw_x)
        problems = []

        def expect(name: str, shape: tuple[int, ...]) -> None:
            actual = getattr(self, name).shape
            if actual != shape:
                problems.append(f"{name} has shape {actual}, expected {shape}")

        expect("points", (n, 3))
        if self.tets.ndim != 2 or self.tets.shape[1] != 4:
            problems.append(f"tets has shape {self.tets.shape}, expected (m, 4)")
        elif not np.issubdtype(self.tets.dtype, np.integer):
            problems.append("tets must hold integers")
        elif self.tets.size and (self.tets.min() < 0 or self.tets.max() >= n):
            problems.append(f"tets refer to vertices outside 0…{n - 1}")
        expect("part_id", (len(self.tets),))
        if not np.issubdtype(self.part_id.dtype, np.integer):
            problems.append("part_id must hold integers")
        elif self.part_id.size and (self.part_id.min() < 0 or self.part_id.max() >= len(self.part_names)):
            problems.append(f"part_id outside 0…{len(self.part_names) - 1} (one per part name)")
        if len(self.moving_part) != len(self.part_names):
            problems.append(f"{len(self.moving_part)} moving_part flags for {len(self.part_names)} parts")
        expect("snapshot_times", (k,))
        if k == 0:
            problems.append("no snapshot")
        elif np.any(np.diff(self.snapshot_times) <= 0):
            problems.append("snapshot_times must increase")
        expect("temperatures", (k, n))
        expect("offsets", (k,))
        expect("screw_x", (b,))
        if b and np.any(np.diff(self.screw_x) <= 0):
            problems.append("screw_x must increase")
        expect("screw_displacement", (k, b))
        for name in ("points", "snapshot_times", "temperatures", "offsets", "screw_x", "screw_displacement"):
            if not np.all(np.isfinite(getattr(self, name))):
                problems.append(f"{name} holds NaN or infinite values")
        if problems:
            raise ValueError("invalid FieldSeries: " + "; ".join(problems))
        self.moving_nodes  # noqa: B018 (raises if a node is shared by a moving and a fixed part)

    @cached_property
    def moving_nodes(self) -> np.ndarray:
        """Per node: does it belong to a moving part (bool)?"""
        return _moving_nodes(self)

    @property
    def n_snapshots(self) -> int:
        return len(self.snapshot_times)

    def celsius(self, snapshot: int) -> np.ndarray:
        """Nodal temperatures of one snapshot [°C]."""
        return self.temperatures[snapshot] - KELVIN_OFFSET

    def displaced_points(self, snapshot: int) -> np.ndarray:
        """Vertices with the moving parts at their position of that snapshot [m]."""
        moved = self.points.copy()
        moved[self.moving_nodes, 0] += self.offsets[snapshot]
        return moved


def _moving_nodes(series: FieldSeries) -> np.ndarray:
    moving = np.asarray(series.moving_part, dtype=bool)[series.part_id]
    n = len(series.points)
    in_moving = np.zeros(n, dtype=bool)
    in_fixed = np.zeros(n, dtype=bool)
    in_moving[series.tets[moving].ravel()] = True
    in_fixed[series.tets[~moving].ravel()] = True
    shared = np.flatnonzero(in_moving & in_fixed)
    if shared.size:
        raise ValueError(
            f"invalid FieldSeries: {shared.size} mesh nodes belong to both a moving and a fixed part "
            f"(e.g. node {shared[0]}); moving parts must own their nodes "
            "(see feedtherm.models.fem.topology.split_nodes)"
        )
    return in_moving


# --------------------------------------------------------------------------- ParaView files


def snapshot_mesh(series: FieldSeries, snapshot: int):
    """One snapshot as a ``meshio.Mesh``: displaced vertices, ``temperature_C``, ``part_id``."""
    import meshio

    tets = series.tets
    if len(series.points) < np.iinfo(np.int32).max:
        tets = tets.astype(np.int32)  # half the size of int64; ParaView reads either
    # contiguous arrays: meshio would otherwise copy them and say so on stdout
    return meshio.Mesh(
        np.ascontiguousarray(series.displaced_points(snapshot)),
        [("tetra", np.ascontiguousarray(tets))],
        point_data={TEMPERATURE_FIELD: series.celsius(snapshot)},
        cell_data={PART_FIELD: [series.part_id.astype(np.int32)]},
    )


def vtu_names(count: int) -> list[str]:
    """``fields_0000.vtu`` …: zero-padded to at least 4 digits so that they sort by time."""
    width = max(4, len(str(count - 1)))
    return [f"{_VTU_STEM}{i:0{width}d}.vtu" for i in range(count)]


def write_pvd(series: FieldSeries, out_dir: Path) -> list[Path]:
    """Write ``fields_0000.vtu`` … (one per snapshot) and ``fields.pvd`` into ``out_dir``.

    Each ``.vtu`` holds the mesh with the moving parts displaced by that snapshot's offset,
    point data ``temperature_C`` [°C] and cell data ``part_id``.  ``fields.pvd`` is a ParaView
    collection of them, with ``timestep`` in seconds and file paths relative to itself; it
    is written last, so it never names a missing file.  Older ``fields_NNNN.vtu`` files in
    ``out_dir`` that the new collection does not contain are removed (ParaView would
    otherwise group them with the new ones when the directory is opened as a file series).

    Returns the paths written: the ``.pvd`` first, then the ``.vtu`` files in time order.
    """
    import meshio

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    names = vtu_names(series.n_snapshots)
    for snapshot, name in enumerate(names):
        meshio.write(out_dir / name, snapshot_mesh(series, snapshot), file_format="vtu")
    pvd = out_dir / PVD_NAME
    _write_collection(pvd, series, names)
    _remove_stale_snapshots(out_dir, set(names))
    return [pvd] + [out_dir / name for name in names]


def _write_collection(path: Path, series: FieldSeries, names: list[str]) -> None:
    root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
    parts = ", ".join(f"{i} = {name}{' (moving)' if moving else ''}"
                      for i, (name, moving) in enumerate(zip(series.part_names, series.moving_part)))
    root.append(ET.Comment(f" {series.title} | part_id: {parts} ".replace("--", "–")))
    collection = ET.SubElement(root, "Collection")
    for time, name in zip(series.snapshot_times, names):
        ET.SubElement(collection, "DataSet", timestep=repr(float(time)), group="", part="0", file=name)
    ET.indent(root)
    tmp = path.with_name(f".{path.name}.tmp")
    ET.ElementTree(root).write(tmp, encoding="utf-8", xml_declaration=True)
    tmp.replace(path)


def _remove_stale_snapshots(out_dir: Path, keep: set[str]) -> None:
    for path in out_dir.iterdir():
        if _VTU_PATTERN.fullmatch(path.name) and path.name not in keep and path.is_file():
            path.unlink()


# --------------------------------------------------------------------------- geometry


def boundary_triangles(points: np.ndarray, tets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The faces that belong to exactly one tetrahedron, oriented outwards.

    Parts that touch without sharing nodes each keep their own copy of the common face, so
    both copies are returned (one per part).

    Returns
    -------
    triangles : ndarray of int, shape (f, 3)
        Vertex indices, counter-clockwise seen from outside (right-hand normal points out).
    owner : ndarray of int, shape (f,)
        The tetrahedron each face belongs to.
    """
    points = np.asarray(points, dtype=float)
    tets = np.asarray(tets)
    m = len(tets)
    if m == 0:
        return np.empty((0, 3), dtype=np.intp), np.empty(0, dtype=np.intp)
    # face i of a tetrahedron is the one opposite its vertex i
    local = np.array([[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]])
    faces = tets[:, local].reshape(-1, 3)
    key = np.sort(faces, axis=1).astype(np.int64)
    n = int(tets.max()) + 1
    if n < 2**21:  # one int64 per face: much faster than unique over rows
        key = (key[:, 0] * n + key[:, 1]) * n + key[:, 2]
        _, first, counts = np.unique(key, return_index=True, return_counts=True)
    else:
        _, first, counts = np.unique(key, axis=0, return_index=True, return_counts=True)
    single = np.sort(first[counts == 1])
    triangles = faces[single]
    owner = single // 4
    opposite = tets.ravel()[single]  # the vertex not on the face
    a, b, c = (points[triangles[:, j]] for j in range(3))
    normal = np.cross(b - a, c - a)
    inward = np.einsum("ij,ij->i", normal, points[opposite] - a) > 0
    triangles[inward] = triangles[inward][:, [0, 2, 1]]
    return triangles, owner
