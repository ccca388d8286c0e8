"""Projected models kept on disk, so that a run of a cached reduced model never builds the full one.

On the fine mesh the FE model takes about 29 s to build with its 41 positions, and its basis
read back and projected another 3 s; the run itself takes a few.  A :class:`~.projection.Projection`
holds everything the reduced model runs and reads with (operators per position, readouts,
the cycle-averaged boundary basis, the field mesh, the basis itself for the fields), so it is
saved under ``cache_root()/projections/<key>.npz`` and read back instead.

The key must name everything the projection depends on without building the full model (a
key made of its operators, as :func:`~.basis.basis_key` is, would cost the build it saves):

- ``inputs``, given by whoever knows how the full model is built (the registry): the
  description's whole content, the mesh file's digest, the full model's name and arguments;
- the tolerance of the basis;
- the digest of every file of the feedtherm package (:func:`package_digest`: code, shipped
  data), so that any change of how operators, bases or projections are made is another key;
- the versions of Python and of the libraries that build them (:data:`LIBRARIES`).

Files are written atomically, a damaged one is rebuilt, and the directory keeps the most
recently used within the basis cache's budget (:mod:`.disk`).
"""

from __future__ import annotations

import hashlib
import json
import platform
import time
from functools import lru_cache
from importlib import metadata
from pathlib import Path
from typing import Callable

import numpy as np
import scipy.sparse as sp

from ...constants import cache_root
from ...system.schema import FeedSystem
from ..fields import FieldMesh
from ..interface import BoundaryBasis, ThermalModel
from .basis import Basis, moment_basis
from .disk import read_npz, write_npz
from .model import ProjectedModel
from .projection import Projection, project

__all__ = ["cached_projected_model", "file_digest", "package_digest", "projection_key", "projection_cache_path"]

#: Changes whenever the file layout below changes (the package digest covers it too; this names it).
STORE_VERSION = 4
#: The distributions whose code builds a full model, its basis or its projection.
LIBRARIES = ("numpy", "scipy", "scikit-fem", "gmsh", "meshio", "pymor")
_PACKAGE = Path(__file__).resolve().parents[2]  # src/feedtherm


@lru_cache(maxsize=1)
def package_digest() -> str:
    """Digest of every file of the feedtherm package (its code and its data), by relative path."""
    h = hashlib.blake2b(digest_size=20)
    for path in sorted(p for p in _PACKAGE.rglob("*") if p.is_file() and "__pycache__" not in p.parts):
        h.update(str(path.relative_to(_PACKAGE)).encode() + b"\0")
        h.update(path.read_bytes())
        h.update(b"\0")
    return h.hexdigest()


def library_versions() -> dict[str, str]:
    """The installed versions of :data:`LIBRARIES` and of Python ("absent" for one not installed)."""
    versions = {"python": platform.python_version(), "machine": platform.machine()}
    for name in LIBRARIES:
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            versions[name] = "absent"
    return versions


def file_digest(path: Path) -> str | None:
    """Digest of a file's bytes, or None when it does not exist."""
    try:
        with open(path, "rb") as f:
            return hashlib.file_digest(f, "blake2b").hexdigest()
    except FileNotFoundError:
        return None


def projection_key(inputs: dict, tolerance: float) -> str:
    """Digest of the module notes' key: ``inputs`` (JSON-able), the tolerance, the package and the libraries."""
    data = {"store_version": STORE_VERSION, "inputs": inputs, "tolerance": float(tolerance),
            "package": package_digest(), "libraries": library_versions()}
    return hashlib.blake2b(json.dumps(data, sort_keys=True).encode(), digest_size=20).hexdigest()


def projection_cache_path(key: str) -> Path:
    return cache_root() / "projections" / f"{key}.npz"


def cached_projected_model(system: FeedSystem, tolerance: float, build_full: Callable[[], ThermalModel],
                           inputs: Callable[[], dict | None]) -> ProjectedModel:
    """The reduced model of ``build_full()``'s full model, from the disk cache when it holds it.

    ``inputs()`` gives what the full model is built from (module notes), or None when it cannot
    be said before building it (its mesh file does not exist yet): the model is then built and
    saved under the inputs the build leaves.
    """
    started = time.perf_counter()
    known = inputs()
    if known is not None:
        path = projection_cache_path(projection_key(known, tolerance))
        projection = read_npz(path, lambda data: _from_arrays(data, path.stem))
        if projection is not None:
            return ProjectedModel.from_projection(projection, system, build_full, projection_cached=True,
                                                  projection_seconds=round(time.perf_counter() - started, 2))
    full = build_full()
    projection = project(full, moment_basis(full, tolerance=tolerance))
    known = inputs()  # the full model's build has written its mesh file
    if known is not None:
        key = projection_key(known, tolerance)
        write_npz(projection_cache_path(key), _to_arrays(projection, key))
    return ProjectedModel.from_projection(projection, system, lambda: full, projection_cached=False,
                                          projection_seconds=round(time.perf_counter() - started, 2))


# ---------------------------------------------------------------------------- file layout
_ARRAYS = ("full_capacity", "stored", "conductance", "exposure", "moving_surfaces", "exposure_change",
           "exposure_rows", "exposure_areas", "entries", "probe_rows", "probe_offsets", "screw", "positions",
           "screw_edges", "screw_centres", "displacement_rows", "displacement_offsets")


def _sparse(prefix: str, matrix: sp.csr_matrix) -> dict[str, np.ndarray]:
    matrix = sp.csr_matrix(matrix)
    return {f"{prefix}_data": matrix.data, f"{prefix}_indices": matrix.indices, f"{prefix}_indptr": matrix.indptr,
            f"{prefix}_shape": np.array(matrix.shape)}


def _read_sparse(data, prefix: str) -> sp.csr_matrix:
    return sp.csr_matrix((data[f"{prefix}_data"], data[f"{prefix}_indices"], data[f"{prefix}_indptr"]),
                         shape=tuple(data[f"{prefix}_shape"]))


def _to_arrays(p: Projection, key: str) -> dict[str, np.ndarray]:
    b = p.basis
    arrays = {name: getattr(p, name) for name in _ARRAYS}
    arrays |= {"store_version": STORE_VERSION, "key": key, "dx": p.dx,
               "surfaces": np.array(p.surfaces), "sources": np.array(p.sources),
               "probe_names": np.array(p.probe_names), "full_stats": json.dumps(p.full_stats),
               "part_names": np.array(list(p.parts)), "part_rows": np.array(list(p.parts.values())),
               "has_part_capacity": p.part_capacity is not None,
               "part_capacity": np.array([(p.part_capacity or {}).get(name, np.nan) for name in p.parts]),
               "basis_vectors": b.vectors, "basis_singular_values": b.singular_values,
               "basis_tolerance": b.tolerance, "basis_snapshots": b.snapshots, "basis_seconds": b.seconds,
               "basis_cached": b.cached}
    arrays |= _sparse("averaged_exposure", p.averaged.exposure) | _sparse("averaged_distribution", p.averaged.distribution)
    arrays["has_film"] = p.averaged.film is not None
    arrays["averaged_film"] = np.zeros(0) if p.averaged.film is None else np.asarray(p.averaged.film, dtype=float)
    arrays["has_displacement_fields"] = p.displacement_basis is not None
    if p.displacement_basis is not None:
        arrays |= {"displacement_basis": p.displacement_basis, "displacement_origin": p.displacement_origin}
    mesh = p.field_mesh
    arrays["has_field_mesh"] = mesh is not None
    if mesh is not None:
        arrays |= {"mesh_points": mesh.points, "mesh_tets": mesh.tets, "mesh_part_id": mesh.part_id,
                   "mesh_part_names": np.array(mesh.part_names), "mesh_moving_part": np.array(mesh.moving_part)}
    return arrays


def _from_arrays(data, key: str) -> Projection | None:
    if int(data["store_version"]) != STORE_VERSION or str(data["key"]) != key:
        return None  # another layout, or a file copied under another name: not this model's
    names = lambda name: tuple(str(s) for s in data[name])  # noqa: E731
    surfaces, sources = names("surfaces"), names("sources")
    mesh = None
    if bool(data["has_field_mesh"]):
        mesh = FieldMesh(points=data["mesh_points"], tets=data["mesh_tets"], part_id=data["mesh_part_id"],
                         part_names=names("mesh_part_names"),
                         moving_part=tuple(bool(m) for m in data["mesh_moving_part"]))
    basis = Basis(data["basis_vectors"], data["basis_singular_values"], float(data["basis_tolerance"]),
                  int(data["basis_snapshots"]), float(data["basis_seconds"]), bool(data["basis_cached"]))
    return Projection(
        basis=basis, surfaces=surfaces, sources=sources, dx=float(data["dx"]), probe_names=names("probe_names"),
        parts=dict(zip(names("part_names"), data["part_rows"])),
        part_capacity=(dict(zip(names("part_names"), (float(c) for c in data["part_capacity"])))
                       if bool(data["has_part_capacity"]) else None),
        averaged=BoundaryBasis(list(surfaces), list(sources), _read_sparse(data, "averaged_exposure"),
                               _read_sparse(data, "averaged_distribution"),
                               np.array(data["averaged_film"], dtype=float) if bool(data["has_film"]) else None),
        field_mesh=mesh, full_stats=json.loads(str(data["full_stats"])),
        displacement_basis=data["displacement_basis"] if bool(data["has_displacement_fields"]) else None,
        displacement_origin=data["displacement_origin"] if bool(data["has_displacement_fields"]) else None,
        **{name: data[name] for name in _ARRAYS},
    )
