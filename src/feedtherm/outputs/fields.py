"""Fields of the FE and reduced models as files: ``fields.pvd`` and one ``.vtu`` per snapshot.

A run of a mesh-based model carries its fields as a
:class:`~feedtherm.solution.fields.FieldSeries`: the mesh at rest,
which parts move with the worktable, and per snapshot the nodal temperatures, the moving
group's offset along x, the screw's axial displacement and (when the model solves the
thermoelastic problem) the 3-D displacement of every vertex.  :func:`write_pvd` writes it as a
ParaView time series (:mod:`.vtu` writes the ``.vtu`` files, the mesh's arrays encoded once for
all of them; the ``.pvd`` collection is plain XML);
:mod:`feedtherm.outputs.field_images` draws it as PNG images.

:func:`boundary_triangles` (the outer faces of a tetrahedral mesh) serves the images.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from ..solution.fields import FieldSeries
from .vtu import TetSeriesWriter

__all__ = [
    "FieldSeries",
    "write_pvd",
    "snapshot_mesh",
    "boundary_triangles",
    "PVD_NAME",
    "TEMPERATURE_FIELD",
    "DISPLACEMENT_FIELD",
    "PART_FIELD",
]

PVD_NAME = "fields.pvd"
TEMPERATURE_FIELD = "temperature_C"  #: point data [°C]
#: point data, 3 components [m]: the thermal displacement, in the points' unit (ParaView's Warp By Vector)
DISPLACEMENT_FIELD = "displacement"
PART_FIELD = "part_id"  #: cell data: index into ``FieldSeries.part_names``
_VTU_STEM = "fields_"
_VTU_PATTERN = re.compile(r"fields_(\d{4,})\.vtu")


def snapshot_mesh(series: FieldSeries, snapshot: int):
    """One snapshot as a ``meshio.Mesh``: displaced vertices, ``temperature_C``, ``displacement``
    (when the series has displacements) and ``part_id``."""
    import meshio

    tets = series.tets
    if len(series.points) < np.iinfo(np.int32).max:
        tets = tets.astype(np.int32)  # half the size of int64; ParaView reads either
    # contiguous arrays: meshio would otherwise copy them and say so on stdout
    return meshio.Mesh(
        np.ascontiguousarray(series.displaced_points(snapshot)),
        [("tetra", np.ascontiguousarray(tets))],
        point_data=_point_data(series, snapshot),
        cell_data={PART_FIELD: [series.part_id.astype(np.int32)]},
    )


def vtu_names(count: int) -> list[str]:
    """``fields_0000.vtu`` …: zero-padded to at least 4 digits so that they sort by time."""
    width = max(4, len(str(count - 1)))
    return [f"{_VTU_STEM}{i:0{width}d}.vtu" for i in range(count)]


def write_pvd(series: FieldSeries, out_dir: Path) -> list[Path]:
    """Write ``fields_0000.vtu`` … (one per snapshot) and ``fields.pvd`` into ``out_dir``.

    Each ``.vtu`` holds the mesh with the moving parts displaced by that snapshot's offset
    (points in metres), point data ``temperature_C`` [°C], point data ``displacement``
    (3 components, metres like the points; only when ``series.displacements`` is not None)
    and cell data ``part_id``.  ``fields.pvd`` is a ParaView collection of them, with
    ``timestep`` in seconds and file paths relative to itself; it is written last, so it
    never names a missing file.  Older ``fields_NNNN.vtu`` files in
    ``out_dir`` that the new collection does not contain are removed (ParaView would
    otherwise group them with the new ones when the directory is opened as a file series).

    Returns the paths written: the ``.pvd`` first, then the ``.vtu`` files in time order.
    """
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    names = vtu_names(series.n_snapshots)
    writer = TetSeriesWriter(len(series.points), series.tets, {PART_FIELD: series.part_id.astype(np.int32)})
    for snapshot, name in enumerate(names):
        writer.write(out_dir / name, series.displaced_points(snapshot), _point_data(series, snapshot))
    pvd = out_dir / PVD_NAME
    _write_collection(pvd, series, names)
    _remove_stale_snapshots(out_dir, set(names))
    return [pvd] + [out_dir / name for name in names]


def _point_data(series: FieldSeries, snapshot: int) -> dict[str, np.ndarray]:
    """The point arrays of one snapshot: temperature [°C] and, if known, the thermal displacement [m].

    The displacement is the thermal one alone: the moving parts' offset is already in the
    points, so that Warp By Vector on top of it does not move them a second time.  It stays in
    metres, the points' unit, so that a warp scale factor of 1 is the true deformation.
    """
    data = {TEMPERATURE_FIELD: series.celsius(snapshot)}
    if series.displacements is not None:
        data[DISPLACEMENT_FIELD] = series.displacements[snapshot]
    return data


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
